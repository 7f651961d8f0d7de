/* The adversarial MOVE_COMMITs over which target_bench measures frame_worst, each from rest:
 * first the (a move of metres at micrometres a second, and at the longest duration), then
 * what scripts/frame_search.sh found costliest (docs/validation.md, "What one frame costs"). */
#include "frame_cases.h"

#define HOME {0.0f, 0.0f, 1.115202f, 0.0f, 0.0f, 0.0f}

const bench_commit bench_frame_cases[] = {
    /* 1 um/s to x = 4 m, y = -2 m: 4.47e9 segments, refused too_long before they are counted */
    {HOME, {4.0f, -2.0f, 1.115202f, 0.0f, 0.0f, 0.0f}, 1, 1},
    /* out of reach along x, an hour long; and at the slowest speed a move may last */
    {HOME, {0.6f, 0.0f, 1.115202f, 0.0f, 0.0f, 0.0f}, 0, 3600000},
    {HOME, {0.6f, 0.0f, 1.115202f, 0.0f, 0.0f, 0.0f}, 1, 167},
    /* scripts/frame_search.sh (its fixed seed) at issue 24's first bound (FW_VALIDATE_WORK 8192,
     * FW_VALIDATE_WALK 4096): the two costliest of each kind, with what they cost there */
    {{0.000000f, 0.000000f, 1.115202f, 0.000000f, 0.000000f, 0.000000f}, {-0.299525f, -0.269886f, 0.496935f, -0.010794f, -0.432330f, -0.336775f}, 0, 1}, /* 16204848 instructions, edge (mutated), accepted */
    {{0.000000f, 0.000000f, 1.115202f, 0.000000f, 0.000000f, 0.000000f}, {-0.298296f, -0.279689f, 0.496973f, -0.010708f, -0.440819f, -0.344161f}, 0, 1}, /* 14268615 instructions, edge (mutated), accepted */
    {{0.000000f, 0.000000f, 1.115202f, 0.000000f, 0.000000f, 0.000000f}, {1.123131f, -1.194128f, -0.100272f, 2.799575f, 1.209549f, 1.486784f}, 0, 3139144}, /* 455497 instructions, far (mutated), kinematics */
    {{0.000000f, 0.000000f, 1.115202f, 0.000000f, 0.000000f, 0.000000f}, {1.127069f, -1.184374f, -0.100479f, 2.802667f, 1.219818f, 1.491114f}, 0, 2572323}, /* 455192 instructions, far (mutated), kinematics */
    {{0.092206f, 0.053201f, 0.335806f, -0.191791f, 0.049616f, -0.490039f}, {-0.011626f, 0.070208f, 0.349569f, -0.054584f, -0.039512f, -0.091385f}, 1, 199659}, /* 18452439 instructions, chord (mutated), accepted */
    {{0.092206f, 0.053201f, 0.335806f, -0.191791f, 0.049616f, -0.490039f}, {-0.011684f, 0.070275f, 0.349737f, -0.056209f, -0.039751f, -0.094601f}, 1, 409256}, /* 18429046 instructions, chord (mutated), accepted */
    {{0.000000f, 0.000000f, 1.115202f, 0.000000f, 0.000000f, 0.000000f}, {0.000000f, 0.000000f, 1.115202f, 0.658518f, 0.733708f, -1.226324f}, 0, 11388}, /* 2324587 instructions, turn (mutated), kinematics */
    {{0.000000f, 0.000000f, 1.115202f, 0.000000f, 0.000000f, 0.000000f}, {0.000000f, 0.000000f, 1.115202f, 0.654340f, 0.745017f, -1.213675f}, 0, 255314}, /* 2253117 instructions, turn (mutated), kinematics */
};

const unsigned bench_frame_case_count = sizeof bench_frame_cases / sizeof bench_frame_cases[0];

/* What the kin target makes of its bytes: a design, a pose, seeds and the slides for the forward
 * kinematics.  Most bytes map onto plausible values (a pose near the workspace of the design, a
 * parameter near the prototype's), so that reachable poses are common; a tag byte per value also
 * lets any double through, or one of a table of awkward ones (NaN, infinities, huge, tiny, just
 * beyond float's range).  Missing bytes read as zero, so every input decodes. */
#ifndef FUZZ_KIN_INPUT_H
#define FUZZ_KIN_INPUT_H

#include <stddef.h>
#include <stdint.h>

#include "kin_side.h"

/* How the forward kinematics' slides are made from the inverse kinematics' answer. */
typedef enum {
    FK_SLIDES_SAME = 0,  /* the IK's slides as they are (NaN where it found none) */
    FK_SLIDES_NUDGED,    /* each moved by up to +-12.7 um */
    FK_SLIDES_ANY,       /* decoded values of their own */
    FK_SLIDES_MOVED      /* each moved by up to +-12.7 mm */
} fk_slides;

typedef struct {
    int run_double, run_float;
    double params[SIDE_NPARAMS]; /* the prototype's unless fuzz_params */
    int fuzz_params;
    int plausible_params;        /* every parameter the prototype's or near it */
    double pose[6];
    int ik_seeded;
    double ik_seed[6];
    int warm_ik_seed;            /* ik_seed is a nudge of the pose's own double IK solution */
    int run_fk;
    fk_slides fk_mode;
    double fk_slides[6];         /* the deltas, or the slides for FK_SLIDES_ANY */
    int fk_seeded;
    int fk_seed_at_pose;         /* the seed is the pose itself (the answer, when the IK took it) */
    double fk_seed[6];
} kin_case;

void kin_decode(const uint8_t *data, size_t size, kin_case *c);

#endif

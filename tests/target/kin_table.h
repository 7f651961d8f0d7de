/* The table of poses the `kinematics` target image checks the float kinematics against.
 *
 * Written at build time by gen_kin_table.c, a host program built from the same kinematics
 * sources in double precision (TSE_REAL_FLOAT=0): kin_table.c in the build tree.  Plain types
 * only, so that the table means the same to the generator and to the board. */
#ifndef TSE_TARGET_KIN_TABLE_H
#define TSE_TARGET_KIN_TABLE_H

#include <stdint.h>

/* A design: the kinematic parameters of tse_params, as the float values both sides use (the
 * generator widens these very floats to double). */
typedef struct {
    float L, k1, eta, k3, k4, alpha_min, alpha_max, s_min, s_max, mu_min, nu_min;
} kin_design;

typedef struct {
    uint8_t design;     /* index into kin_designs */
    uint8_t path_start; /* 1: first pose of a path (the warm pass starts from no seed) */
    uint8_t status;     /* tse_status of the double IK, cold and warm alike */
    uint8_t scissor;    /* its failing scissor, 0 when ok */
    uint8_t fk;         /* 1: the double FK from the home pose returns this pose: check FK */
    float pose[6];      /* the input, exactly as both precisions see it */
    double q[6];        /* double slides (NaN where a scissor has no solution) */
    float mu[3];        /* double type-1 margins (NaN where no solution) */
    float fk_sens[6];   /* row sums of |(dq/dp)^-1|: pose error per metre of slide error */
} kin_case;

#define KIN_DESIGNS 2
extern const kin_design kin_designs[KIN_DESIGNS];
extern const kin_case kin_cases[];
extern const unsigned kin_case_count;

/* Reference poses of the planner and controller images (design 0), in whole micrometres and
 * microradians as the CAN protocol carries them, with their double slides: each is accepted with
 * every mu >= 0.1. */
typedef struct {
    const char *name;
    int32_t pose_u[6];  /* um, urad */
    double q[6];        /* double IK of pose_u * 1e-6, from no seed */
} kin_ref;

enum { REF_START, REF_NEAR, REF_FAR, REF_TURN, REF_CTL_A, REF_CTL_B, KIN_REFS };
extern const kin_ref kin_refs[KIN_REFS];

/* Straight paths at a fixed orientation between two accepted poses, through a region where the
 * IK fails (design 0): pose(u) = from + u (to - from) in position, the orientation of both.  In
 * double, u = u_first - 1e-4 and the path before it (warm, every 5e-4) are accepted, and every u
 * in [u_first, u_first + KIN_PATH_AFTER] fails with the same status on the same scissor (40
 * samples).  One path per status found. */
#define KIN_PATH_AFTER 0.004
typedef struct {
    float from[6], to[6];
    double u_first;     /* where the path first fails (bisected to 1e-12) */
    uint8_t status, scissor;
} kin_path;

extern const kin_path kin_paths[];
extern const unsigned kin_path_count;

#endif

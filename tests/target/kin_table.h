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

#endif

/* The reference side of the kin target: kinematics.md's geometry in long double, through the
 * independent oracle of the kinematics tests (tests/kinematics/oracle.h) and a few checks of its
 * own, fed exactly the values the library held. */
#ifndef FUZZ_KIN_REF_H
#define FUZZ_KIN_REF_H

#include "kin_side.h"
#include "oracle.h"

typedef struct {
    orc_geom g;
    int is_float;
    long double acc; /* kinematics.md: |q - q_exact| where mu >= 0.1: 1e-9 m (double), 2e-6 m (float) */
    orc_tol tol;     /* how near a threshold the reference's verdict is too close to call */
    int plausible;   /* a design near the prototype: the accuracy and the verdicts are compared */
} ref_design;

/* The design as the library held it (side_init's held values). */
void ref_design_init(ref_design *d, const double held[SIDE_NPARAMS], int is_float, int plausible);

/* The checks of an accepted pose with its slides (IK's answer, or FK's pose with the slides it
 * was given): every slide on the det M > 0 branch, within the accuracy (plus slack[k], when slack
 * is not NULL) of the exact solution where mu >= 0.1 and nu >= nu_strict, the apex of each scissor
 * from its slides at the plate's ball joint there, and every check of the contract (stroke, stops,
 * above the base, mu, nu) passed up to the band of tol. */
void ref_check_accepted(const ref_design *d, const double pose[6], const double q[6], double nu_strict,
                        const double *slack);

/* |q - q_exact| per slide at this pose, the exact solution found from q (0 where none is). */
void ref_slide_errors(const ref_design *d, const double pose[6], const double q[6], double err[6]);

/* Whether scissor i (0-based) cannot reach its ball joint at this pose with any slides: a joint
 * further from the slide origin than the scissor can stretch (kin_ref.c derives the bound). */
/* Whether every scissor's M, at the exact slides near q, has a condition number of at most the
 * bound under which ref_check_accepted holds the accuracy (0 when a slide does not settle). */
int ref_well_conditioned(const ref_design *d, const double pose[6], const double q[6]);

int ref_out_of_reach(const ref_design *d, const double pose[6], int i);

/* Whether the reference's verdict on this pose is to be compared: a plausible design and a pose
 * within a hundred scissor lengths and ten thousand radians. */
int ref_comparable(const ref_design *d, const double pose[6]);

/* The reference's verdict (orc_ik with no preference). */
void ref_classify(const ref_design *d, const double pose[6], orc_result *o);

/* What a broken check prints before it aborts (the case being run). */
void ref_context(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void ref_print_context(void);

#define KIN_CHECK(cond)                                                                             \
    do {                                                                                            \
        if (!(cond)) {                                                                              \
            ref_print_context();                                                                    \
            FUZZ_CHECK(cond);                                                                       \
        }                                                                                           \
    } while (0)

#endif

/* The table of poses the Cortex-M3 image test_kinematics_fixed checks the fixed-point inverse
 * kinematics against: written at build time by gen_kin_table_fixed.c, a host program built from
 * the double kinematics and the kinematics tests' independent oracle (tests/kinematics/oracle.c),
 * never from the fixed code.  Integers only: the image has no floating point. */
#ifndef TSE_TARGET_M3_KIN_TABLE_FIXED_H
#define TSE_TARGET_M3_KIN_TABLE_FIXED_H

#include <stdint.h>

typedef struct {
    int32_t pose[6];    /* Q24 m, Q28 rad: the input, exactly as the double build saw it */
    int32_t q[6];       /* the double slides rounded to Q24 (INT32_MIN where none) */
    uint8_t path_start; /* 1: first pose of a path (the warm pass starts from no seed) */
    uint8_t status;     /* tse_status of the double IK from no seed */
    uint8_t scissor;    /* its failing scissor, 0 when ok */
    uint8_t clear;      /* the oracle finds it clear of every "too close to call" band */
    uint8_t accurate;   /* ok with every mu >= 0.1 (the oracle's): slides within 1 um */
} kin_fx_case;

extern const kin_fx_case kin_fx_cases[];
extern const unsigned kin_fx_case_count;

#endif

/* One scalar type for the whole kinematics library.
 *
 * The same sources build twice: as float for the Cortex-M4F (its FPU is single precision only) and
 * as double on the host.  Defining TSE_REAL_FLOAT=1 selects float.  Every public symbol carries a
 * suffix (_f or _d) through TSE_NS so that one host program can link both builds side by side
 * (tse-kin --precision, the float-versus-double tests).
 *
 * Literals in library code are written TSE_R(0.5): a bare 0.5 is a double and would silently
 * promote float arithmetic to software double on the board (-Wdouble-promotion catches it). */
#ifndef TSE_REAL_H
#define TSE_REAL_H

#include <float.h>
#include <math.h>
#include <stddef.h>

#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
typedef float tse_real;
#define TSE_R(x) x##f
#define TSE_NS(name) name##_f
#define TSE_REAL_EPS FLT_EPSILON
#define TSE_REAL_NAME "float"
#define tse_sqrt sqrtf
#define tse_sin sinf
#define tse_cos cosf
#define tse_acos acosf
#define tse_asin asinf
#define tse_atan2 atan2f
#define tse_fabs fabsf
#define tse_cbrt cbrtf
#define tse_ceil ceilf
#else
typedef double tse_real;
#define TSE_R(x) x
#define TSE_NS(name) name##_d
#define TSE_REAL_EPS DBL_EPSILON
#define TSE_REAL_NAME "double"
#define tse_sqrt sqrt
#define tse_sin sin
#define tse_cos cos
#define tse_acos acos
#define tse_asin asin
#define tse_atan2 atan2
#define tse_fabs fabs
#define tse_cbrt cbrt
#define tse_ceil ceil
#endif

#define TSE_PI TSE_R(3.14159265358979323846)

#endif

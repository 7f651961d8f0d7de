/* The paper's prototype (section VI), the one place its figures are written: the kinematics'
 * defaults (tse_params_default, in SI) and the controller's parameter table (fw_param_table's
 * defaults, in its integer units) are made from these; the host tools and Python take them from
 * those two (tse-kin params, the generated tse/_protocol.py).  Plain double constants, so that both
 * a constant initializer and either precision of the library can use them. */
#ifndef TSE_PROTOTYPE_H
#define TSE_PROTOTYPE_H

#define TSE_PROTO_L 1.727                /* total scissor length [m] */
#define TSE_PROTO_K1 0.2647              /* l0 / L */
#define TSE_PROTO_ETA 0.5235987755982988 /* slide angle: 30 deg [rad] */
#define TSE_PROTO_K3 0.0186              /* r_act / L */
#define TSE_PROTO_K4 0.11765             /* r_top / L */
/* The angle stops: retracted height 0.324 m and extended 1.619 m, alpha = asin(height / L), to
 * double precision (tests/kinematics/test_params.c holds every value here to docs/kinematics.md). */
#define TSE_PROTO_ALPHA_MIN 0.18872691741051098 /* [rad] */
#define TSE_PROTO_ALPHA_MAX 1.2152711412317807  /* [rad] */
/* docs/kinematics.md: a stroke wide enough that the alpha stops bound the workspace. */
#define TSE_PROTO_S_MIN 0.0  /* [m] */
#define TSE_PROTO_S_MAX 0.90 /* [m] */
#define TSE_PROTO_MU_MIN 0.05
#define TSE_PROTO_NU_MIN 1e-3

#endif

/* The C side of tse.kin (python/tse/kin.py): what libtse_kin.so exports, nothing else.
 *
 * Promise: every entry point works on the caller's arrays (C order, doubles in, doubles and ints
 * out), keeps no state between calls and allocates nothing (tse_py_ik and tse_py_fk may start
 * threads for a large batch, and have joined them when they return; tse_py_plan takes the
 * planner's memory for the call and gives it back).  A design is passed as
 * v[TSE_PY_NPARAMS], the parameters in the order of tse_param_id (v[0] = L, v[1] = k1, ...,
 * v[10] = nu_min) in SI units and radians; each batch call validates it with the build's own
 * tse_geometry_init (after rounding to that build's precision, as tse-kin does) and returns the
 * first parameter it rejects (a tse_param_id), or TSE_PARAM_OK (0) when the set is valid and the
 * arrays are filled.  Inputs are rounded to the build's precision on the way in and results
 * widened on the way out, exactly as tse-kin's bridge (host_tools/tse_kin/kin_ops.c) does, so a
 * row's answer is tse-kin's answer to the same row, bit for bit.
 *
 * The batch entry points exist once per precision, suffixed _d (double) and _f (float). */
#ifndef TSE_PY_H
#define TSE_PY_H

#include <stddef.h>

#include "tse/params.h"

#define TSE_PY_API __attribute__((visibility("default")))
#define TSE_PY_NPARAMS (TSE_PARAM_COUNT - 1)

/* Names and tables, precision independent (tse_py_params.c). */
TSE_PY_API int tse_py_status_count(void);
TSE_PY_API const char *tse_py_status_name(int status);
TSE_PY_API int tse_py_param_count(void);
TSE_PY_API const char *tse_py_param_name(int id);
/* The spellings a parameter file accepts (tse-kin's table): key i of n, its parameter id, whether
 * its value is in degrees, and its rule (kinematics.md, "Valid parameter sets") in its unit.
 * NULL past the end. */
TSE_PY_API const char *tse_py_param_key(int i, int *id, int *degrees, const char **rule);
/* The prototype's values (tse_params_default, double build). */
TSE_PY_API void tse_py_params_default(double v[TSE_PY_NPARAMS]);
/* A parameter file, read and judged as tse-kin reads it (kin_params_file.h): as a controller's set
 * (design 0, tse-kin --params: exactly the files tse-sim takes) or as a design (design 1, tse-kin
 * --design): 0 with the values in v, -1 (not a valid file) or -2 (unreadable) with tse-kin's
 * message in err. */
TSE_PY_API int tse_py_params_load(const char *path, int design, double v[TSE_PY_NPARAMS], char *err, size_t errlen);

/* A controller's rates (INFO's step_hz and segment_hz): the built-in ones (fw/limits.h), which a
 * controller whose firmware is older than INFO ran at, into rates[2]; and whether a controller runs
 * at step_hz and segment_hz (fw_rates_run): 1 or 0. */
TSE_PY_API void tse_py_rates_built_in(unsigned rates[2]);
TSE_PY_API int tse_py_rates_run(unsigned step_hz, unsigned segment_hz);

/* The controller's whole-path check of a trajectory, tsectl's (host_tools/traj_check): from rest at
 * pose0[6] (m, rad) with slides q0[6] (m), under the controller's parameter set params[n_params]
 * (its raw wire integers in parameter-id order, as PARAM_GET reads them) at its rates step_hz and
 * segment_hz (INFO's), n rows dt_us[n] apart (the first from the start) at poses[n][6] (m, rad;
 * rounded as the wire rounds them), the last flagged last.  Returns 0 when every row passes, 1 when
 * row *row (0-based) would be refused, with the REJECT's fields the controller would send in
 * reject[7] (function, seq 0, reason, scissor, kin_status, field, where), -1 when the controller
 * would refuse the set itself, -2 when n_params is not this library's parameter count, -3 when no
 * controller runs at those rates.  *v_peak, *a_peak: the worst slide speed and acceleration
 * checked, against their limits (1 = at the limit). */
TSE_PY_API int tse_py_traj_check(const int *params, int n_params, unsigned step_hz, unsigned segment_hz,
                                 const double pose0[6], const double q0[6], long n, const unsigned *dt_us,
                                 const double *poses, long *row, int reject[7], double *v_peak, double *a_peak);

/* A REJECT's seven fields (function, seq, reason, scissor, kin_status, field, where: raw, as the
 * frame carries them) in tsectl's words, "rejected: REASON: explanation", into buf (cap bytes, 512
 * hold any); returns buf. */
TSE_PY_API const char *tse_py_reject_text(const int fields[7], char *buf, size_t cap);

/* tsectl's wait for rest (rest_wait.h), a STATUS at a time: the longest a wait for a motion planned
 * to take expected_s (0: unknown) may take [s]; and the judgement of a STATUS (state, fault: raw)
 * elapsed_s into that wait, *seen_motion carried from one call to the next (0 at first), settled as
 * rest_wait_begin takes it.  Returns 0: wait on; 1: at rest (done, or already); -1: it ended
 * badly (disabled, fault, e-stop); -2: no rest within the limit; with the words for any but 0 in
 * words (cap bytes, 160 hold any). */
TSE_PY_API double tse_py_rest_limit(double expected_s);
/* Whether a controller in state (raw) is at rest: 1 or 0. */
TSE_PY_API int tse_py_rest_state(int state);
TSE_PY_API int tse_py_rest_judge(double expected_s, int settled, int *seen_motion, double elapsed_s, int state,
                                 int fault, const char *what, char *words, size_t cap);

/* tse-kin plan's planner (planner/): waypoints poses[n][6] (m, rad), each with a time t[n] and a
 * plate speed cap v[n] (NaN where free; t and v may be NULL), under the controller's parameter set
 * params[n_params] at its rates step_hz and segment_hz (as for tse_py_traj_check; rates no
 * controller runs at are refused, -1 with why), rows `period` s apart, corners cut by at most
 * `blend` m (0: a spline through every waypoint), the slides' jerk held to jmax m/s^3 (0: no limit;
 * below 0: the controller's own, PLAN_JMAX_CONTROLLER).  Returns the number of rows of the plan, and when
 * it is at most cap fills rows[][7] (t, x, y, z, roll, pitch, yaw); -1 with the reason in err (the
 * planner's words: the waypoint, counted from 1, and why); -2 when n_params is not this library's
 * parameter count.  stats: duration [s], the peak speed and acceleration over their limits, the
 * limits [m/s, m/s^2], the rows outside the first and last 5 % of the time, of those the rows with
 * some slide at 90 % or more of a limit, and the validator's refusals on the way. */
TSE_PY_API long tse_py_plan(const int *params, int n_params, unsigned step_hz, unsigned segment_hz, long n,
                            const double *poses, const double *t, const double *v, double period, double blend,
                            double jmax, long cap, double *rows, double stats[8], char *err, size_t errlen);

#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
#define TSE_PY(name) name##_f
#else
#define TSE_PY(name) name##_d
#endif

#define tse_py_check TSE_PY(tse_py_check)
#define tse_py_ik TSE_PY(tse_py_ik)
#define tse_py_fk TSE_PY(tse_py_fk)
#define tse_py_jacobian TSE_PY(tse_py_jacobian)
#define tse_py_haf TSE_PY(tse_py_haf)
#define tse_py_sigma_z TSE_PY(tse_py_sigma_z)
#define tse_py_workspace TSE_PY(tse_py_workspace)
#define tse_py_workspace_points TSE_PY(tse_py_workspace_points)

#ifdef TSE_PY_BATCH
/* The set as this build sees it: TSE_PARAM_OK or the first parameter it rejects. */
TSE_PY_API int tse_py_check(const double v[TSE_PY_NPARAMS]);

/* Inverse kinematics of poses[n][6].  seed: NULL (home), one seed q (seed_stride 0) or one per row
 * (seed_stride 6).  warm: a row after one that came back ok is seeded with that row's slides (in
 * the build's precision), as a controller stepping along a path; the others with their seed.
 * threads: at most that many threads, the calling thread one of them (1 or less: the calling
 * thread only); a warm batch, or one of fewer than 4096 rows, runs on the calling thread.  The
 * answers do not depend on it.
 * Out: status[n], scissor[n] (0 when ok), q[n][6] (the library's slides, NaN where none). */
TSE_PY_API int tse_py_ik(const double v[TSE_PY_NPARAMS], long n, const double *poses, const double *seed,
                         long seed_stride, int warm, int threads, int *status, int *scissor, double *q);

/* Forward kinematics of q[n][6], seeds and threads as tse_py_ik's (poses; warm: the last ok
 * pose).  Out: status[n], scissor[n], pose[n][6] (NaN unless ok, as tse-kin prints it). */
TSE_PY_API int tse_py_fk(const double v[TSE_PY_NPARAMS], long n, const double *q, const double *seed,
                         long seed_stride, int warm, int threads, int *status, int *scissor, double *pose);

/* tse-kin jacobian: the slides from home, then dq/dp (J[n][6][6], rows s_a1..s_b3, columns
 * x..yaw) and the singular values of dp/dq, descending (sv[n][6]); NaN unless ok. */
TSE_PY_API int tse_py_jacobian(const double v[TSE_PY_NPARAMS], long n, const double *poses, int *status,
                               int *scissor, double *J, double *sv);

/* HAF and sigma_z at heights z[n] (NaN unless ok). */
TSE_PY_API int tse_py_haf(const double v[TSE_PY_NPARAMS], long n, const double *z, int *status, double *haf);
TSE_PY_API int tse_py_sigma_z(const double v[TSE_PY_NPARAMS], long n, const double *z, int *status,
                              double *sigma);

/* The workspace count of the paper's grid (tse_workspace_count: tse_workspace's numbers). */
TSE_PY_API int tse_py_workspace(const double v[TSE_PY_NPARAMS], int n_r, int n_phi, int n_z,
                                const double orientation[3], int *status, long *reachable, long *total);

/* Every point of that grid: pose[n_r * n_phi * n_z][6] in the order (i, j, k), k fastest, and its
 * status and scissor from tse_ik without a seed (what the count counts). */
TSE_PY_API int tse_py_workspace_points(const double v[TSE_PY_NPARAMS], int n_r, int n_phi, int n_z,
                                       const double orientation[3], double *pose, int *status, int *scissor);
#endif

#endif

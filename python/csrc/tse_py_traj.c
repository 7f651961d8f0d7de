/* tse.can's trajectory check: the shared checker (traj_checker.h) over the caller's arrays.  See
 * tse_py.h. */
#include <stdint.h>

#include "traj_checker.h"
#include "tse_py.h"

_Static_assert(sizeof(int) == sizeof(int32_t) && sizeof(unsigned) == sizeof(uint32_t), "ctypes int is 32 bits");

int tse_py_traj_check(const int *params, int n_params, const double pose0[6], const double q0[6], long n,
                      const unsigned *dt_us, const double *poses, long *row, int reject[7], double *v_peak,
                      double *a_peak)
{
    *row = -1;
    *v_peak = *a_peak = 0.0;
    if (n_params != FP_COUNT)
        return -2;
    fw_param_set s;
    for (int i = 0; i < FP_COUNT; ++i)
        s.v[i] = params[i];
    traj_checker c; /* on the caller's stack: nothing kept between calls */
    if (traj_checker_start(&c, &s, pose0, q0) != 0)
        return -1;
    int rc = 0;
    int32_t v[PROTO_MAX_FIELDS];
    for (long i = 0; i < n && rc == 0; ++i) {
        if (traj_checker_push(&c, dt_us[i], &poses[6 * i], i == n - 1, v) != 0) {
            *row = i;
            for (int k = 0; k < 7; ++k)
                reject[k] = v[k];
            rc = 1;
        }
    }
    traj_checker_peaks(&c, v_peak, a_peak);
    return rc;
}

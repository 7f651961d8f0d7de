/* tse.can's trajectory check: the shared checker (traj_checker.h) over the caller's arrays, and the
 * rates it takes.  See tse_py.h. */
#include <stdint.h>

#include "traj_checker.h"
#include "tse_py.h"

_Static_assert(sizeof(int) == sizeof(int32_t) && sizeof(unsigned) == sizeof(uint32_t), "ctypes int is 32 bits");

void tse_py_rates_built_in(unsigned rates[2])
{
    rates[0] = FW_STEP_HZ;
    rates[1] = FW_SEGMENT_HZ;
}

int tse_py_rates_run(unsigned step_hz, unsigned segment_hz)
{
    return fw_rates_run((fw_rates){step_hz, segment_hz});
}

int tse_py_traj_check(const int *params, int n_params, unsigned step_hz, unsigned segment_hz, const double pose0[6],
                      const double q0[6], long n, const unsigned *dt_us, const double *poses, long *row, int reject[7],
                      double *v_peak, double *a_peak)
{
    *row = -1;
    *v_peak = *a_peak = 0.0;
    if (n_params != FP_COUNT)
        return -2;
    const fw_rates rates = {step_hz, segment_hz};
    if (!fw_rates_run(rates))
        return -3;
    fw_param_set s;
    for (int i = 0; i < FP_COUNT; ++i)
        s.v[i] = params[i];
    traj_checker c; /* on the caller's stack: nothing kept between calls */
    if (traj_checker_start(&c, &s, rates, pose0, q0) != 0)
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

/* tse.can's wait for rest: tsectl's own judgement of each STATUS (host_tools/traj_check/rest_wait.c),
 * so that the two wait alike.  See tse_py.h. */
#include "rest_wait.h"
#include "tse_py.h"

int tse_py_rest_state(int state)
{
    return rest_state(state);
}

double tse_py_rest_limit(double expected_s)
{
    rest_wait w;
    rest_wait_begin(&w, expected_s, false);
    return w.limit_s;
}

int tse_py_rest_judge(double expected_s, int settled, int *seen_motion, double elapsed_s, int state, int fault,
                      const char *what, char *words, size_t cap)
{
    rest_wait w;
    rest_wait_begin(&w, expected_s, settled != 0);
    w.seen_motion = *seen_motion != 0;
    const rest_verdict v = rest_wait_status(&w, elapsed_s, state, fault, what, words, cap);
    *seen_motion = w.seen_motion;
    return v == REST_WAIT_ON ? 0 : v > 0 ? 1 : v == REST_WAIT_TIMEOUT ? -2 : -1;
}

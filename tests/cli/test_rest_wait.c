/* The wait for rest that tsectl and tse.can share (host_tools/traj_check/rest_wait.h), STATUS by
 * STATUS: each case a sequence of (time, state, fault) and the verdict and words expected after
 * each, worked from the promise in the header, not from the code. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fw/types.h"
#include "rest_wait.h"

typedef struct {
    double t;
    int state, fault;
    rest_verdict want;
    const char *words; /* NULL: not looked at (ON) */
} step;

static void run(double expected, bool settled, const step *s, int n)
{
    rest_wait w;
    rest_wait_begin(&w, expected, settled);
    char words[160];
    for (int i = 0; i < n; ++i) {
        words[0] = '\0';
        const rest_verdict v = rest_wait_status(&w, s[i].t, s[i].state, s[i].fault, "moving", words, sizeof words);
        if (v != s[i].want)
            fail_msg("step %d (t %.2f, state %d): verdict %d, expected %d", i, s[i].t, s[i].state, v, s[i].want);
        if (s[i].words)
            assert_string_equal(words, s[i].words);
    }
}

static void test_limit(void **state)
{
    (void)state;
    rest_wait w;
    rest_wait_begin(&w, 2.0, false);
    assert_true(w.limit_s == 3.0 * 2.0 + 60.0);
    rest_wait_begin(&w, 0.0, false);
    assert_true(w.limit_s == 3.0 * 60.0 + 60.0); /* unplanned (homing): a minute's worth */
}

static void test_rest_counts_after_motion(void **state)
{
    (void)state;
    const step s[] = {
        {0.05, FW_STATE_IDLE, FW_FAULT_NONE, REST_WAIT_ON, NULL},  /* a STATUS from before the command */
        {0.10, FW_STATE_MOVING, FW_FAULT_NONE, REST_WAIT_ON, NULL},
        {1.50, FW_STATE_STOPPING, FW_FAULT_NONE, REST_WAIT_ON, NULL},
        {1.75, FW_STATE_IDLE, FW_FAULT_NONE, REST_WAIT_DONE, "moving: at rest after 1.75 s"},
    };
    run(1.5, false, s, 4);
}

static void test_ended_badly(void **state)
{
    (void)state;
    const step fault[] = {
        {0.10, FW_STATE_MOVING, FW_FAULT_NONE, REST_WAIT_ON, NULL},
        {0.60, FW_STATE_FAULT, FW_FAULT_UNDERRUN, REST_WAIT_ENDED, "moving ended fault after 0.60 s, fault underrun"},
    };
    run(1.0, false, fault, 2);
    const step disabled[] = {
        {0.10, FW_STATE_HOMING, FW_FAULT_NONE, REST_WAIT_ON, NULL},
        {3.00, FW_STATE_DISABLED, FW_FAULT_NONE, REST_WAIT_ENDED, "moving ended disabled after 3.00 s, fault none"},
    };
    run(0.0, false, disabled, 2);
}

static void test_already_at_rest(void **state)
{
    (void)state;
    const step idle[] = {
        {0.5, FW_STATE_IDLE, FW_FAULT_NONE, REST_WAIT_ON, NULL},
        {2.0, FW_STATE_IDLE, FW_FAULT_NONE, REST_WAIT_ON, NULL}, /* 2 s is not more than 2 s */
        {2.1, FW_STATE_IDLE, FW_FAULT_NONE, REST_WAIT_ALREADY, "moving: already at rest"},
    };
    run(0.0, false, idle, 3);
    const step estop[] = {
        {2.5, FW_STATE_ESTOP, FW_FAULT_ESTOP, REST_WAIT_ENDED, "moving: the controller is estop, fault estop"},
    };
    run(0.0, false, estop, 1);
}

static void test_settled_counts_at_once(void **state)
{
    (void)state;
    const step s[] = {{0.01, FW_STATE_IDLE, FW_FAULT_NONE, REST_WAIT_DONE, "moving: at rest after 0.01 s"}};
    run(0.0, true, s, 1);
}

static void test_timeout(void **state)
{
    (void)state;
    const step s[] = {
        {10.0, FW_STATE_MOVING, FW_FAULT_NONE, REST_WAIT_ON, NULL},
        {40.0, -1, 0, REST_WAIT_ON, NULL}, /* no STATUS: only the time */
        {66.5, FW_STATE_MOVING, FW_FAULT_NONE, REST_WAIT_TIMEOUT, "moving did not come to rest within 66 s"},
    };
    run(2.0, false, s, 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_limit),
        cmocka_unit_test(test_rest_counts_after_motion),
        cmocka_unit_test(test_ended_badly),
        cmocka_unit_test(test_already_at_rest),
        cmocka_unit_test(test_settled_counts_at_once),
        cmocka_unit_test(test_timeout),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The controller on the board's timing (tests/board_time: every solve charged its cost on the
 * Cortex-M4F at 168 MHz, the control and step ticks preempting the thread where they come due),
 * with the real plant checking the slides (sim_rig.h).
 *
 * Issue 24's case: a trajectory of one-second rows streamed while it runs.  Validating a row costs
 * about 1,800 instructions per millisecond of its dt (10.8 ms for 1 s), while only a few
 * milliseconds of setpoints are queued ahead of the step generator.  With the control tick in an
 * interrupt of its own (fw/runtime.h) no tick is lost and the plant sees the slides within their
 * limits; with the control tick where the board once had it, in the main loop after the frames
 * (board_time's control_in_thread), the same rows lose control ticks at every row and the plant
 * sees the slides jerk past slide_amax: the rig catches a starvation of the tick if it ever comes
 * back. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fw/traj.h"
#include "sim_rig.h"

static sim_rig R;

#define ROWS 9
#define DT_MS 1000

/* The plate's x offset at row i (1..ROWS): the speed steps 0, 7, 14, ... 35, ... 7 mm/s row by row
 * (changes of 7 mm/s at a point, inside the rows' share of slide_amax x 10 ms), 0.175 m in all, at
 * rest at the end. */
static double row_x(int i)
{
    static const double v[ROWS] = {0.007, 0.014, 0.021, 0.028, 0.035, 0.028, 0.021, 0.014, 0.007};
    double x = 0.0;
    for (int k = 0; k < i && k < ROWS; ++k)
        x += v[k] * DT_MS * 1e-3;
    return x;
}

/* Streams the rows as the queue has room, waits for rest; returns the rows taken. */
static int run_rows(void)
{
    const tse_real *home = fw_geometry_of(R.fw)->home_pose;
    const unsigned from = R.nlog;
    int sent = 0;
    uint8_t id = 0;
    for (uint32_t ms = 0; ms < 30000 && (sent < ROWS || fw_state_of(R.fw) != FW_STATE_IDLE); ++ms) {
        /* As a host streams a path it computes as it goes: a row or two ahead, so that each
         * row is validated while the plate moves. */
        if (sent < ROWS && FW_TRAJ_CAPACITY - rig_now(&R).traj_free < 2u) {
            double pose[6];
            for (int k = 0; k < 6; ++k)
                pose[k] = (double)home[k];
            pose[0] -= 0.1;
            pose[0] += row_x(sent + 1);
            const uint8_t q = R.seq++;
            if (sent == 0)
                id = q;
            rig_stage(&R, q, pose);
            const int32_t v[4] = {q, DT_MS * 1000,
                                  (sent == 0 ? (int32_t)PROTO_TRAJ_FIRST : 0) |
                                      (sent == ROWS - 1 ? (int32_t)PROTO_TRAJ_LAST : 0),
                                  id};
            rig_send(&R, PM_TRAJ_COMMIT, v);
            ++sent;
        }
        rig_run(&R, 1);
    }
    int taken = 0;
    for (unsigned n = from; n < R.nlog; ++n) {
        const hal_can_frame *f = &R.log[n % RIG_LOG].f;
        if ((f->id >> PROTO_NODE_BITS) == proto_table[PM_ACK].function &&
            f->data[0] == proto_table[PM_TRAJ_COMMIT].function)
            ++taken;
    }
    return taken;
}

/* Home, then to the trajectory's start (x 10 cm back from home). */
static void setup_rig(void)
{
    rig_boot(&R, 0.2);
    rig_home(&R);
    double start[6];
    for (int k = 0; k < 6; ++k)
        start[k] = (double)fw_geometry_of(R.fw)->home_pose[k];
    start[0] -= 0.1;
    rig_move(&R, start, 1000);
    assert_true(rig_until(&R, FW_STATE_MOVING, 100));
    assert_true(rig_until(&R, FW_STATE_IDLE, 5000));
}

static void report(const char *what, int taken)
{
    const double us = 1e6 / BT_HZ;
    printf("%s: %d of %d rows taken; the thread's longest work %.2f ms; control ticks lost %llu, the latest "
           "began %.1f us behind its time; plant breaches 0x%x%s%s\n",
           what, taken, ROWS, (double)R.bt.thread_run_max * us * 1e-3, (unsigned long long)R.bt.control_lost,
           (double)R.bt.control_late_max * us, R.plant.breaches, R.plant.breaches ? ": " : "",
           R.plant.breaches ? R.plant.first_breach : "");
}

static void test_rows_of_a_second_while_running(void **state)
{
    (void)state;
    setup_rig();
    const int taken = run_rows();
    report("control tick in its interrupt", taken);
    assert_int_equal(taken, ROWS);
    assert_int_equal(R.bt.control_lost, 0);
    assert_int_equal(R.plant.breaches, 0);
    /* A row's validation runs for milliseconds (the rig measured the 10.8 ms): the case
     * is the one the issue met, not a cheap one. */
    assert_true(R.bt.thread_run_max > 5u * (BT_HZ / 1000u));
}

static void test_the_tick_in_the_main_loop_starves(void **state)
{
    (void)state;
    setup_rig();
    R.bt.control_in_thread = true;
    R.allowed_lost_ticks = UINT64_MAX;
    R.allowed_breaches = ~0u;
    const int taken = run_rows();
    report("control tick in the main loop (before issue 23)", taken);
    assert_true(R.bt.control_lost > 0);
    assert_true(R.plant.breaches != 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rows_of_a_second_while_running),
        cmocka_unit_test(test_the_tick_in_the_main_loop_starves),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

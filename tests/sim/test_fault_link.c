/* The link to the host failing, with the controller, the real plant and the rig's checks after
 * every period (sim_rig.h): a host gone silent, and the CAN controller bus-off.
 * docs/controller.md ("Faults", "The host watchdog"): host silence past the watchdog timeout and
 * a bus-off each lead to a controlled stop and a fault that must be cleared; docs/protocol.md:
 * the watchdog only while enabled. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "sim_rig.h"

#define FN(m) (proto_table[m].function)

static sim_rig R;

static const double TARGET[6] = {0.05, 0.0, 1.0, 0.0, 0.0, 0.0};
static const double OTHER[6] = {-0.05, 0.03, 1.1, 0.0, 0.0, 0.1};

static void ready(void)
{
    rig_boot(&R, 0.205);
    rig_home(&R);
}

static uint64_t now(void)
{
    return fault_clock_us(&R.can.clock);
}

/* Until the period whose heartbeat has just been taken: the next heartbeat is 10 ms away. */
static void after_heartbeat(void)
{
    while (R.ticks % 10 != 1)
        rig_run(&R, 1);
}

static void lands_on(const double p[6])
{
    rig_run(&R, 10);
    assert_true(rig_until(&R, FW_STATE_IDLE, 30000));
    assert_true(rig_plate_at(&R, p));
}

/* Silent for less than the watchdog (the heartbeat period included): nothing happens. */
static void test_short_silence(void **state)
{
    (void)state;
    ready();
    const uint32_t wd = (uint32_t)fw_params_of(R.fw)->v[FP_WATCHDOG_MS];
    rig_move(&R, TARGET, 2000);
    rig_run(&R, 300);
    after_heartbeat();
    /* The last heartbeat came a period ago; the first after the silence comes within 10 ms. */
    R.can.cfg.silence = (fault_window){now(), now() + (wd - 10 - 2) * 1000u};
    rig_run(&R, wd);
    assert_true(R.can.stats.silenced > 0);
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_NONE);
    lands_on(TARGET);
}

/* Silent past the watchdog while moving: a controlled stop in the very period the timeout
 * passes, then the watchdog fault latched with the drives off.  A controlled stop loses no step:
 * cleared, enabled again, the robot is still homed and lands on its next target. */
static void test_silence_past_watchdog(void **state)
{
    (void)state;
    ready();
    const uint32_t wd = (uint32_t)fw_params_of(R.fw)->v[FP_WATCHDOG_MS];
    rig_move(&R, OTHER, 3000);
    rig_run(&R, 500);
    after_heartbeat();
    const uint64_t last_heartbeat = now() - 1000; /* taken by the previous period's poll */
    R.can.cfg.silence = (fault_window){now(), now() + 2000000};
    /* The timeout is passed once more than wd ms have gone since that heartbeat: not in the
     * period that begins wd ms after it, in the next. */
    while (now() <= last_heartbeat + (uint64_t)wd * 1000u) {
        rig_run(&R, 1);
        assert_int_equal(fw_state_of(R.fw), FW_STATE_MOVING);
    }
    rig_run(&R, 1); /* the period at wd + 1 ms */
    assert_int_equal(fw_state_of(R.fw), FW_STATE_STOPPING);
    assert_true(rig_until(&R, FW_STATE_FAULT, 3000));
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_WATCHDOG);
    assert_false(R.plant.enabled);
    /* The host hears of it (STATUS goes out; only what comes in is lost). */
    const unsigned from = R.nlog;
    rig_run(&R, 200);
    const proto_message st = rig_status(&R, from);
    assert_int_equal(st.v[0], FW_STATE_FAULT);
    assert_int_equal(st.v[1], FW_FAULT_WATCHDOG);
    /* Back: the fault must be cleared; the zero survived the controlled stop. */
    while (now() < R.can.cfg.silence.until_us)
        rig_run(&R, 1);
    const unsigned back = R.nlog;
    const uint8_t m = rig_move(&R, TARGET, 1500);
    rig_run(&R, 10);
    uint8_t reason = 0;
    assert_int_equal(rig_answer(&R, back, FN(PM_MOVE_COMMIT), m, &reason), 'r');
    assert_int_equal(reason, FW_REASON_STATE);
    rig_cmd(&R, PM_CLEAR_FAULT);
    rig_run(&R, 10);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_DISABLED);
    rig_cmd(&R, PM_ENABLE);
    rig_run(&R, 10);
    assert_true(fw_homed_of(R.fw));
    rig_move(&R, TARGET, 1500);
    lands_on(TARGET);
}

/* Silent while disabled: no watchdog (it guards motion only). */
static void test_silence_while_disabled(void **state)
{
    (void)state;
    rig_boot(&R, 0.205);
    R.can.cfg.silence = (fault_window){now(), now() + 3000000};
    rig_run(&R, 3000);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_DISABLED);
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_NONE);
}

/* Bus-off while moving: a controlled stop from the period that sees it, the fault latched at rest;
 * while it lasts nothing reaches the host and what the host sends is lost, unanswered even
 * afterwards.  After the recovery the host reads the fault in STATUS and clears it. */
static void test_bus_off(void **state)
{
    (void)state;
    ready();
    rig_move(&R, OTHER, 3000);
    rig_run(&R, 500);
    const unsigned before = R.nlog;
    R.can.cfg.bus_off = (fault_window){now(), now() + 150000};
    rig_run(&R, 1);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_STOPPING);
    const uint8_t lost = rig_cmd(&R, PM_STOP);
    while (now() < R.can.cfg.bus_off.until_us)
        rig_run(&R, 1);
    assert_int_equal(R.nlog, before); /* not a frame out */
    assert_true(R.can.stats.send_refused > 0); /* STATUS, at least, was due */
    assert_true(R.can.stats.bus_off_lost > 0);
    assert_true(rig_until(&R, FW_STATE_FAULT, 3000));
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_BUS_OFF);
    assert_false(R.plant.enabled);
    rig_run(&R, 300);
    assert_int_equal(rig_answer(&R, before, FN(PM_STOP), lost, NULL), 0);
    const proto_message st = rig_status(&R, before);
    assert_int_equal(st.v[0], FW_STATE_FAULT);
    assert_int_equal(st.v[1], FW_FAULT_BUS_OFF);
    const unsigned from = R.nlog;
    const uint8_t c = rig_cmd(&R, PM_CLEAR_FAULT);
    rig_run(&R, 10);
    assert_int_equal(rig_answer(&R, from, FN(PM_CLEAR_FAULT), c, NULL), 'a');
    assert_int_equal(fw_state_of(R.fw), FW_STATE_DISABLED);
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_NONE);
}

/* A bus-off that began and ended between two control ticks' looks still latches the fault. */
static void test_bus_off_between_looks(void **state)
{
    (void)state;
    ready();
    R.can.cfg.bus_off = (fault_window){now() + 200, now() + 700};
    rig_run(&R, 1); /* its look is at the start of the period: before the window */
    assert_int_equal(fw_state_of(R.fw), FW_STATE_IDLE);
    rig_run(&R, 1); /* after it */
    assert_int_equal(fw_state_of(R.fw), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_BUS_OFF);
    assert_false(R.plant.enabled);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_short_silence),
        cmocka_unit_test(test_silence_past_watchdog),
        cmocka_unit_test(test_silence_while_disabled),
        cmocka_unit_test(test_bus_off),
        cmocka_unit_test(test_bus_off_between_looks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The machine failing, with the controller, the real plant and the rig's checks after every
 * period (sim_rig.h): a limit switch tripped mid-move, the e-stop opened at random instants, a
 * slide that stalls.  docs/controller.md ("Faults", "E-stop"): a limit switch hit outside homing
 * leads to a controlled stop and a fault that must be cleared; e-stop cuts stepping at once.  And
 * what the controller cannot do: it has no position feedback, so a stalled slide goes unnoticed
 * unless its homing switch comes to disagree with the count by more than 0.5 mm (docs/protocol.md,
 * HOME). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "sim_rig.h"

#define FN(m) (proto_table[m].function)

static sim_rig R;

static const double TARGET[6] = {0.05, 0.0, 1.0, 0.0, 0.0, 0.0};
static const double OTHER[6] = {-0.05, 0.03, 1.1, 0.0, 0.0, 0.1};
/* Every slide at 0.3796 m (tse-kin ik), well above the 0.2 m homing switches. */
static const double HIGH[6] = {0.0, 0.0, 1.2, 0.0, 0.0, 0.0};
/* Slide B1 at 0.0137 m, far below its switch (tse-kin ik). */
static const double LOW[6] = {0.2, 0.15, 0.9, 0.0, 0.1, 0.5};
/* Every slide at 0.2866 m: a long way down from home. */
static const double TALL[6] = {0.0, 0.0, 1.45, 0.0, 0.0, 0.0};

static void ready(void)
{
    rig_boot(&R, 0.205);
    rig_home(&R);
}

static uint64_t now(void)
{
    return fault_clock_us(&R.can.clock);
}

static void lands_on(const double p[6])
{
    rig_run(&R, 10);
    assert_true(rig_until(&R, FW_STATE_IDLE, 30000));
    assert_true(rig_plate_at(&R, p));
}

static char answer_to(proto_msg m, uint8_t *reason)
{
    const unsigned from = R.nlog;
    const uint8_t s = rig_cmd(&R, m);
    rig_run(&R, 10);
    return rig_answer(&R, from, FN(m), s, reason);
}

/* After a fault that dropped the zero: the fault must be cleared, and moves wait for homing. */
static void clear_and_need_homing(void)
{
    uint8_t reason = 0;
    const unsigned from = R.nlog;
    const uint8_t m = rig_move(&R, TARGET, 1500);
    rig_run(&R, 10);
    assert_int_equal(rig_answer(&R, from, FN(PM_MOVE_COMMIT), m, &reason), 'r');
    assert_int_equal(reason, FW_REASON_STATE);
    assert_int_equal(answer_to(PM_CLEAR_FAULT, NULL), 'a');
    assert_int_equal(fw_state_of(R.fw), FW_STATE_DISABLED);
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_NONE);
    assert_false(R.plant.enabled);
    assert_int_equal(answer_to(PM_ENABLE, NULL), 'a');
    const unsigned again = R.nlog;
    const uint8_t m2 = rig_move(&R, TARGET, 1500);
    rig_run(&R, 10);
    assert_int_equal(rig_answer(&R, again, FN(PM_MOVE_COMMIT), m2, &reason), 'r');
    assert_int_equal(reason, FW_REASON_NOT_HOMED);
}

/* A high-end switch pressed mid-move: a controlled stop from that period (the plant checks its
 * acceleration), the zero dropped, the limit fault latched at rest with the drives off.  Cleared
 * and homed again, the robot lands on its targets. */
static void test_limit_mid_move(void **state)
{
    (void)state;
    ready();
    rig_move(&R, OTHER, 3000);
    rig_run(&R, 600);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_MOVING);
    R.inputs.cfg.limit = (fault_window){now(), now() + 600000};
    R.inputs.cfg.limit_mask = 1u << (8 + 2); /* slide 3's high end */
    rig_run(&R, 1);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_STOPPING);
    assert_false(fw_homed_of(R.fw));
    assert_true(R.plant.enabled); /* braking under control, not cut */
    assert_true(rig_until(&R, FW_STATE_FAULT, 3000));
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_LIMIT);
    assert_false(R.plant.enabled);
    const unsigned from = R.nlog;
    rig_run(&R, 200);
    const proto_message st = rig_status(&R, from);
    assert_int_equal(st.v[1], FW_FAULT_LIMIT);
    assert_true(st.v[2] & 8); /* the switch pressed */
    while (now() < R.inputs.cfg.limit.until_us)
        rig_run(&R, 1);
    clear_and_need_homing();
    rig_cmd(&R, PM_HOME);
    rig_run(&R, 10);
    assert_true(rig_until(&R, FW_STATE_IDLE, 120000));
    assert_true(fw_homed_of(R.fw));
    rig_move(&R, TARGET, 1500);
    lands_on(TARGET);
}

/* A homing switch pressed while its slide is far above it (a broken switch, or the slide is not
 * where the count says): at rest, the limit fault latches at once. */
static void test_switch_disagrees_at_rest(void **state)
{
    (void)state;
    ready();
    const uint64_t pulses = R.plant.pulses;
    R.inputs.cfg.limit = (fault_window){now(), FAULT_FOREVER};
    R.inputs.cfg.limit_mask = 1u << 0;
    rig_run(&R, 1);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_FAULT);
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_LIMIT);
    assert_false(fw_homed_of(R.fw));
    assert_false(R.plant.enabled);
    rig_run(&R, 100);
    assert_true(R.plant.pulses == pulses);
}

/* The e-stop input opened at random instants (seeded) while homing, moving and stopping: in the
 * first control period that reads it the state is ESTOP and no step is made (the rig checks this
 * every period), the drives are off and the zero dropped; CLEAR_FAULT is refused while the input
 * is open; once closed, cleared, the robot must home again, and then lands on its target. */
static void test_estop_at_random_instants(void **state)
{
    (void)state;
    fault_rng rng;
    fault_rng_seed(&rng, 9);
    for (int i = 0; i < 9; ++i) {
        const int phase = i % 3;
        if (phase == 0) {
            rig_boot(&R, 0.205);
            assert_int_equal(answer_to(PM_ENABLE, NULL), 'a');
            assert_int_equal(answer_to(PM_HOME, NULL), 'a');
            rig_run(&R, fault_rng_below(&rng, 4000)); /* homing takes about 6 s from here */
            assert_int_equal(fw_state_of(R.fw), FW_STATE_HOMING);
        } else {
            ready();
            rig_move(&R, OTHER, 2000);
            rig_run(&R, 10 + fault_rng_below(&rng, 1500));
            assert_int_equal(fw_state_of(R.fw), FW_STATE_MOVING);
            if (phase == 2) {
                rig_cmd(&R, PM_STOP);
                rig_run(&R, 1);
                assert_int_equal(fw_state_of(R.fw), FW_STATE_STOPPING);
            }
        }
        const fw_state was = fw_state_of(R.fw);
        /* Anywhere within the next period, for 50 to 500 ms. */
        const uint64_t at = now() + fault_rng_below(&rng, 1000);
        R.inputs.cfg.estop = (fault_window){at, at + 50000 + 1000u * fault_rng_below(&rng, 450)};
        rig_run(&R, 1);
        if (at > now() - 1000) /* the period's look came before the input opened */
            rig_run(&R, 1);
        assert_int_equal(fw_state_of(R.fw), FW_STATE_ESTOP);
        assert_int_equal(fw_fault_of(R.fw), FW_FAULT_ESTOP);
        assert_false(fw_homed_of(R.fw));
        assert_false(R.plant.enabled);
        const uint64_t pulses = R.plant.pulses;
        uint8_t reason = 0;
        assert_int_equal(answer_to(PM_CLEAR_FAULT, &reason), 'r');
        assert_int_equal(reason, FW_REASON_STATE);
        while (now() < R.inputs.cfg.estop.until_us)
            rig_run(&R, 1);
        assert_true(R.plant.pulses == pulses);
        print_message("e-stop %d in state %d, %.3f ms into a period: no step after it\n", i, was,
                      (double)(at % 1000) / 1000.0);
        clear_and_need_homing();
    }
    rig_cmd(&R, PM_HOME);
    rig_run(&R, 10);
    assert_true(rig_until(&R, FW_STATE_IDLE, 120000));
    rig_move(&R, TARGET, 1500);
    lands_on(TARGET);
}

/* A slide stalled from rest takes none of its steps.  The controller cannot know: the move
 * completes, no fault, STATUS all well, the count (and SLIDES, FK) at the target while the slide
 * is where it was and the plate is not at the target.  It is caught only when the count goes
 * more than 0.5 mm below the homing switch while the stalled slide keeps it released: in that
 * very period, a controlled stop and the limit fault. */
static void test_stall_not_detected(void **state)
{
    (void)state;
    ready();
    const int k = 1; /* B1 */
    const double spm = (double)fw_params_of(R.fw)->v[FP_STEPS_PER_M];
    const int64_t at = R.plant.steps[k];
    R.stepper.cfg.stall = (fault_window){now(), FAULT_FOREVER};
    R.stepper.cfg.stall_mask = 1u << k;
    const unsigned from = R.nlog;
    const uint8_t m = rig_move(&R, HIGH, 1500);
    rig_run(&R, 10);
    assert_int_equal(rig_answer(&R, from, FN(PM_MOVE_COMMIT), m, NULL), 'a');
    assert_true(rig_until(&R, FW_STATE_IDLE, 30000));
    rig_run(&R, 200);
    /* Not detected. */
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_NONE);
    assert_true(fw_homed_of(R.fw));
    const proto_message st = rig_status(&R, from);
    assert_int_equal(st.v[0], FW_STATE_IDLE);
    assert_int_equal(st.v[1], FW_FAULT_NONE);
    assert_int_equal(st.v[2] & 8, 0);
    /* The truth: the slide never moved, the count says it did, the plate is elsewhere. */
    assert_true(R.plant.steps[k] == at);
    assert_true(llabs((long long)(R.stepper.lost[k] - (llround(0.37956889321410042 * spm) - at))) <= 1);
    assert_true(rig_count_error(&R, k) == R.stepper.lost[k]);
    for (int j = 0; j < 6; ++j)
        if (j != k)
            assert_true(llabs((long long)rig_count_error(&R, j)) <= 1);
    assert_false(rig_plate_at(&R, HIGH));
    /* Down towards LOW: caught where the count passes 0.5 mm below the switch. */
    const int32_t sw = (int32_t)((int64_t)fw_params_of(R.fw)->v[FP_HOME_SW_1 + k] * fw_params_of(R.fw)->v[FP_STEPS_PER_M] / 1000000);
    const int32_t tol = (int32_t)llround(500e-6 * spm);
    rig_move(&R, LOW, 2000);
    rig_run(&R, 10);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_MOVING);
    int32_t pos[6];
    for (int t = 0; t < 30000 && fw_state_of(R.fw) == FW_STATE_MOVING; ++t) {
        stepgen_positions(fw_stepgen_of(R.fw), pos); /* what this period's control tick reads */
        rig_run(&R, 1);
        if (fw_state_of(R.fw) == FW_STATE_MOVING)
            assert_true(pos[k] >= sw - tol);
    }
    const int32_t prev = pos[k];
    assert_int_equal(fw_state_of(R.fw), FW_STATE_STOPPING);
    assert_true(prev < sw - tol);
    assert_true(prev >= sw - tol - 192); /* the first period past it: at most 1 ms at 0.15 m/s */
    assert_true(rig_until(&R, FW_STATE_FAULT, 3000));
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_LIMIT);
    assert_false(fw_homed_of(R.fw));
}

/* A slide stalled at speed stops dead and restarts dead: the plant sees an acceleration no
 * controller could have commanded; the controller still notices nothing. */
static void test_stall_at_speed(void **state)
{
    (void)state;
    ready();
    const int k = 0;
    rig_move(&R, TALL, 1500);
    rig_run(&R, 700);
    assert_int_equal(fw_state_of(R.fw), FW_STATE_MOVING);
    R.allowed_breaches = PLANT_OVERACCEL;
    R.stepper.cfg.stall = (fault_window){now(), now() + 100000};
    R.stepper.cfg.stall_mask = 1u << k;
    assert_true(rig_until(&R, FW_STATE_IDLE, 30000));
    rig_run(&R, 200);
    assert_int_equal(R.plant.breaches, PLANT_OVERACCEL);
    assert_int_equal(fw_fault_of(R.fw), FW_FAULT_NONE);
    assert_true(fw_homed_of(R.fw));
    /* 100 ms at over 2 cm/s: thousands of steps the slide never took. */
    assert_true(R.stepper.lost[k] < -2560);
    assert_true(rig_count_error(&R, k) == R.stepper.lost[k]);
    assert_false(rig_plate_at(&R, TALL));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_limit_mid_move),
        cmocka_unit_test(test_switch_disagrees_at_rest),
        cmocka_unit_test(test_estop_at_random_instants),
        cmocka_unit_test(test_stall_not_detected),
        cmocka_unit_test(test_stall_at_speed),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

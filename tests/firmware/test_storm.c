/* The controller under a storm: a long random mix of well-formed commands, corrupted frames,
 * random identifiers and lengths, e-stop and limit events, on the fake HAL.  Whatever arrives:
 * no crash (and nothing for the sanitizers), the state and fault always valid, no step pulse
 * unless the drives are on and the state moves the robot, every refused frame answered. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fake_hal.h"
#include "fw/controller.h"
#include "fw/runtime.h"

static fake_hal F;
static fw_controller_mem C_mem;
static fw_controller *C;

static uint32_t rnd(void)
{
    static uint32_t x = 2463534242u;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return x;
}

static void random_frame(void)
{
    hal_can_frame f;
    memset(&f, 0, sizeof f);
    const uint32_t kind = rnd() % 4;
    if (kind < 2) {
        /* A well-formed command with random in-range fields, mostly to our node. */
        proto_msg m;
        do
            m = (proto_msg)(rnd() % PM_COUNT);
        while (proto_table[m].dir != PROTO_TO_CONTROLLER);
        proto_message pm = {m, (uint8_t)(rnd() % 8 ? 1 : rnd() % 16), {0}};
        for (int k = 0; k < proto_table[m].nfields; ++k) {
            const proto_field *fd = &proto_table[m].fields[k];
            const int64_t span = (int64_t)fd->max - fd->min + 1;
            int64_t v = fd->min + (int64_t)(rnd() % (uint32_t)(span > 0xFFFFFFFFLL ? 0xFFFFFFFFLL : span));
            if (fd->type == PF_I24) /* poses mostly near the workspace, to get moves accepted */
                v = (int64_t)(rnd() % 600000) - 300000 + (k == 1 && m == PM_POSE_B ? 1000000 : 0);
            pm.v[k] = (int32_t)v;
        }
        if (proto_encode(&pm, &f) != 0)
            return;
        if (kind == 1 && f.len > 0)
            f.data[rnd() % f.len] ^= (uint8_t)(1u << (rnd() % 8)); /* one flipped bit */
    } else if (kind == 2) {
        f.id = (uint16_t)(rnd() & 0x7FF);
        f.len = (uint8_t)(rnd() % 9);
        for (int b = 0; b < 8; ++b)
            f.data[b] = (uint8_t)rnd();
    } else {
        f.id = (uint16_t)((rnd() % 0x12) << 4 | 1); /* our node, any command, a wrong length */
        f.len = (uint8_t)(rnd() % 9);
        for (int b = 0; b < 8; ++b)
            f.data[b] = (uint8_t)rnd();
    }
    fake_send(&F, f.id, f.len, f.data);
}

static void send(proto_msg m, const int32_t *v)
{
    fake_send_msg(&F, 1, m, v);
}

/* A quiet spell of a well-behaved host: recover, home, start a move, so that the next burst of
 * the storm also finds the robot moving. */
static void recover(uint8_t *seq)
{
    F.estop_open = false;
    const int32_t s1[1] = {(*seq)++}, s2[1] = {(*seq)++}, s3[1] = {(*seq)++}, hb[1] = {0};
    send(PM_CLEAR_FAULT, s1);
    send(PM_ENABLE, s2);
    fake_run(&F, C, 5);
    send(PM_HOME, s3);
    for (int t = 0; t < 60000 && !(fw_state_of(C) == FW_STATE_IDLE && fw_homed_of(C)); t += 10) {
        send(PM_HOST_HEARTBEAT, hb);
        F.tx_count = 0;
        fake_run(&F, C, 10);
    }
    if (!(fw_state_of(C) == FW_STATE_IDLE && fw_homed_of(C)))
        return;
    const uint8_t s = (*seq)++;
    const int32_t a[3] = {s, 50000, 0}, b[3] = {s, 1050000, 0}, c[3] = {s, 0, 0}, m[3] = {s, 0, 2000};
    send(PM_POSE_A, a);
    send(PM_POSE_B, b);
    send(PM_POSE_C, c);
    send(PM_MOVE_COMMIT, m);
}

static void test_storm(void **state)
{
    (void)state;
    fw_hal hal;
    fake_hal_init(&F, &hal);
    for (int k = 0; k < 6; ++k)
        F.steps[k] = FAKE_SWITCH_AT + 3000; /* just above the homing switches */
    const fw_config cfg = {1, 1000, 100000, NULL, NULL, NULL};
    C = fw_init(&C_mem, &hal, &cfg);
    assert_non_null(C);
    unsigned states_seen = 0, restarts = 0;
    uint8_t seq = 100;
    for (int ms = 0; ms < 60000; ++ms) {
        if (ms % 3000 == 0)
            recover(&seq);
        const uint32_t n = rnd() % 3;
        for (uint32_t i = 0; i < n; ++i)
            random_frame();
        if (rnd() % 20000 == 0)
            F.estop_open = !F.estop_open;
        F.forced_limits = rnd() % 30000 == 0 ? (uint16_t)(1u << (rnd() % 6)) : 0;
        F.tx_count = 0; /* the fake bus keeps the last millisecond only */
        const uint64_t before = F.pulses;
        const fw_state s0 = fw_state_of(C);
        fake_run(&F, C, 1);
        assert_true((unsigned)fw_state_of(C) < FW_STATE_COUNT);
        assert_true((unsigned)fw_fault_of(C) < FW_FAULT_COUNT);
        states_seen |= 1u << fw_state_of(C);
        if (F.pulses != before) {
            /* Steps only from a state that moves the robot, and only with the drives on. */
            assert_true(F.enabled || s0 == FW_STATE_MOVING || s0 == FW_STATE_STOPPING || s0 == FW_STATE_HOMING);
            assert_true(s0 == FW_STATE_MOVING || s0 == FW_STATE_STOPPING || s0 == FW_STATE_HOMING ||
                        fw_state_of(C) == FW_STATE_MOVING || fw_state_of(C) == FW_STATE_STOPPING || fw_state_of(C) == FW_STATE_HOMING);
        }
        if (fw_state_of(C) == FW_STATE_ESTOP || fw_state_of(C) == FW_STATE_DISABLED || fw_state_of(C) == FW_STATE_FAULT)
            assert_false(F.enabled);
        if (fw_boot_requested(C)) {
            /* A BOOT_ENTER taken: only with the drives off; the board restarts (here: its
             * bootloader starts the application again). */
            assert_false(F.enabled);
            ++restarts;
            C = fw_init(&C_mem, &hal, &cfg);
            assert_non_null(C);
        }
    }
    print_message("restarts into the bootloader: %u\n", restarts);
    print_message("states visited: 0x%02x\n", states_seen);
    /* The storm reached the interesting states, not only refusals. */
    assert_true(states_seen & (1u << FW_STATE_IDLE));
    assert_true(states_seen & (1u << FW_STATE_ESTOP));
    assert_true(states_seen & (1u << FW_STATE_HOMING));
    assert_true(states_seen & (1u << FW_STATE_MOVING));
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_storm)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}

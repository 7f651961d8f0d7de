/* The controller-level tests' shared helpers (harness.h). */
#include "harness.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

fake_hal F;
fw_controller *C;
static fw_controller_mem C_mem;
uint8_t seq;
uint8_t traj_id;

void start(void)
{
    fw_hal hal;
    fake_hal_init(&F, &hal);
    for (int k = 0; k < 6; ++k)
        F.steps[k] = FAKE_SWITCH_AT + 3000 + 100 * k; /* just above the switches: homing is short */
    restart(&hal);
    seq = 1;
}

void restart(const fw_hal *hal)
{
    const fw_config cfg = {1, 1000, 100000, NULL, NULL, NULL};
    C = fw_init(&C_mem, hal, &cfg);
    assert_non_null(C);
}

fw_inspection now(void)
{
    fw_inspection i;
    fw_inspect(C, &i);
    return i;
}

void send(proto_msg m, const int32_t *v)
{
    fake_send_msg(&F, 1, m, v);
}

void cmd(proto_msg m)
{
    const int32_t v[1] = {seq++};
    send(m, v);
}

void heartbeat(void)
{
    const int32_t v[1] = {0};
    send(PM_HOST_HEARTBEAT, v);
}

/* Runs ms milliseconds with the host alive. */
void run(uint32_t ms)
{
    for (uint32_t t = 0; t < ms; t += 10) {
        heartbeat();
        fake_run(&F, C, 10);
    }
}

void stage(uint8_t s, const double p[6])
{
    const int32_t a[3] = {s, (int32_t)lround(p[0] * 1e6), (int32_t)lround(p[1] * 1e6)};
    const int32_t b[3] = {s, (int32_t)lround(p[2] * 1e6), (int32_t)lround(p[3] * 1e6)};
    const int32_t c[3] = {s, (int32_t)lround(p[4] * 1e6), (int32_t)lround(p[5] * 1e6)};
    send(PM_POSE_A, a);
    send(PM_POSE_B, b);
    send(PM_POSE_C, c);
}

void move_to(const double p[6], int32_t ms)
{
    const uint8_t s = seq++;
    stage(s, p);
    const int32_t m[3] = {s, 0, ms};
    send(PM_MOVE_COMMIT, m);
}

void traj_row(const double p[6], uint32_t dt_us, bool first, bool last)
{
    const uint8_t s = seq++;
    if (first)
        traj_id = s;
    stage(s, p);
    const int32_t v[4] = {s, (int32_t)dt_us, (first ? (int32_t)PROTO_TRAJ_FIRST : 0) | (last ? (int32_t)PROTO_TRAJ_LAST : 0),
                          traj_id};
    send(PM_TRAJ_COMMIT, v);
}

/* What the controller answered since tx index `from`: 'a' ack, 'r' reject, 0 nothing. */
char answer(unsigned from, uint8_t function, uint8_t *reason)
{
    for (unsigned i = from; i < F.tx_count; ++i) {
        const hal_can_frame *f = &F.tx[i];
        if ((f->id >> 4) == 0x04 && f->data[0] == function)
            return 'a';
        if ((f->id >> 4) == 0x03 && f->data[0] == function) {
            if (reason)
                *reason = f->data[2];
            return 'r';
        }
    }
    return 0;
}

char set_param(uint16_t id, int32_t value, uint8_t *reason, uint8_t *field)
{
    const unsigned from = F.tx_count;
    const int32_t v[2] = {id, value};
    send(PM_PARAM_SET, v);
    fw_poll(C);
    const char got = answer(from, proto_table[PM_PARAM_SET].function, reason);
    const hal_can_frame *r = fake_last(&F, 0x03, from);
    if (got == 'r' && field)
        *field = r->data[5];
    return got;
}

void home(void)
{
    cmd(PM_ENABLE);
    run(20);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    cmd(PM_HOME);
    run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_HOMING);
    for (int i = 0; i < 200 && fw_state_of(C) == FW_STATE_HOMING; ++i)
        run(100);
    assert_int_equal(fw_state_of(C), FW_STATE_IDLE);
    assert_true(fw_homed_of(C));
}

const double NEAR[6] = {0.05, 0.0, 1.0, 0, 0, 0};

void reach(fw_state s)
{
    start();
    switch (s) {
    case FW_STATE_DISABLED:
        break;
    case FW_STATE_HOMING:
        cmd(PM_ENABLE);
        run(20);
        cmd(PM_HOME);
        run(50);
        break;
    case FW_STATE_IDLE:
        home();
        break;
    case FW_STATE_MOVING:
        home();
        move_to(NEAR, 3000);
        run(100);
        break;
    case FW_STATE_STOPPING:
        home();
        move_to(NEAR, 3000);
        run(1000);
        cmd(PM_STOP);
        fw_poll(C);
        break;
    case FW_STATE_FAULT:
        cmd(PM_ENABLE);
        run(20);
        fake_run(&F, C, 700); /* no heartbeat past the 500 ms watchdog */
        break;
    case FW_STATE_ESTOP:
        cmd(PM_ESTOP);
        run(20);
        break;
    default:
        fail();
    }
    assert_int_equal(fw_state_of(C), s);
}

static proto_message decode_from(const hal_can_frame *f)
{
    proto_message m;
    assert_non_null(f);
    const proto_error e = proto_decode(f, PROTO_TO_HOST, &m);
    assert_int_equal(e.reason, FW_REASON_NONE);
    return m;
}

proto_message reject_of(unsigned from, uint8_t function)
{
    for (unsigned i = from; i < F.tx_count; ++i)
        if ((F.tx[i].id >> 4) == proto_table[PM_REJECT].function && F.tx[i].data[0] == function)
            return decode_from(&F.tx[i]);
    fail_msg("no REJECT of function 0x%02x", function);
    return decode_from(NULL);
}

proto_message status_since(unsigned from)
{
    return decode_from(fake_last(&F, proto_table[PM_STATUS].function, from));
}

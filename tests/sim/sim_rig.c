/* The simulator's parts composed for fault tests (sim_rig.h). */
#include "sim_rig.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#if SIM_RIG_BOARD_TIME
static void board_step(void *arg);
static void board_control(void *arg);
#endif

void rig_boot(sim_rig *r, double start_m)
{
    memset(r, 0, sizeof *r);
    fw_hal hal;
    fake_hal_init(&r->bus, &hal);
    const fault_can_config no_can = {.delay_us = 20000}; /* tse-sim's default, for tests that delay */
    const fault_inputs_config no_inputs = {0};
    const fault_stepper_config no_stepper = {0};
    fault_can_init(&r->can, &no_can, hal.can, hal.clock);
    fault_inputs_init(&r->inputs, &no_inputs, plant_inputs(&r->plant), hal.clock);
    fault_stepper_init(&r->stepper, &no_stepper, plant_stepper(&r->plant), hal.clock);
    hal.can = fault_can_hal(&r->can);
    hal.inputs = r->in = fault_inputs_hal(&r->inputs);
    hal.stepper = fault_stepper_hal(&r->stepper);
#if SIM_RIG_BOARD_TIME
    /* The thread waits for the tick as the board's does: time runs to the next interrupt. */
    bt_stop(); /* fw_init's solves are before the board's time starts */
    const fw_config cfg = {1, RIG_CONTROL_HZ, RIG_STEP_HZ, bt_await, &r->bt, NULL};
#else
    const fw_config cfg = {1, RIG_CONTROL_HZ, RIG_STEP_HZ, NULL, NULL, NULL};
#endif
    r->fw = fw_init(&r->fw_mem, &hal, &cfg);
    assert_non_null(r->fw);
    /* The plant is the machine the default parameters describe (as tse-sim builds it). */
    const fw_param_set *fp = fw_params_of(r->fw);
    plant_config pc = {(double)fp->v[FP_STEPS_PER_M], fp->v[FP_SLIDE_VMAX] * 1e-6, fp->v[FP_SLIDE_AMAX] * 1e-6, 0.05,
                       RIG_STEP_HZ, fw_stepgen_of(r->fw)->cfg.min_step_interval, (uint32_t)fp->v[FP_STEP_PULSE_NS],
                       (uint32_t)fp->v[FP_DIR_SETUP_NS], {0}};
    for (int k = 0; k < 6; ++k)
        pc.home_sw[k] = fp->v[FP_HOME_SW_1 + k] * 1e-6;
    const double s0[6] = {start_m, start_m, start_m, start_m, start_m, start_m};
    const plant_kinematics pk = plant_kinematics_of(&fw_geometry_of(r->fw)->p);
    assert_int_equal(plant_init(&r->plant, &pc, &pk, s0), 0);
    r->host_alive = true;
    r->seq = 1;
#if SIM_RIG_BOARD_TIME
    const bt_hooks hooks = {board_step, board_control, NULL, r, &r->bus.now_us};
    bt_init(&r->bt, RIG_STEP_HZ, RIG_CONTROL_HZ, &hooks);
#endif
}

static bool moves_robot(fw_state s)
{
    return s == FW_STATE_HOMING || s == FW_STATE_MOVING || s == FW_STATE_STOPPING;
}

static void check(sim_rig *r, fw_state s0, bool estop_open, uint64_t emitted0)
{
    const fw_inspection in = rig_now(r), *c = &in;
    const double t = (double)r->bus.now_us * 1e-6;
    if (r->plant.breaches & ~r->allowed_breaches)
        fail_msg("t = %.3f s: plant: %s (breaches 0x%x; state %d, fault %d)", t, r->plant.first_breach,
                 r->plant.breaches, c->state, c->fault);
    if ((unsigned)c->state >= FW_STATE_COUNT || (unsigned)c->fault >= FW_FAULT_COUNT)
        fail_msg("t = %.3f s: state %d, fault %d", t, c->state, c->fault);
    if (c->drives_on != r->plant.enabled)
        fail_msg("t = %.3f s: the controller believes the drives %s, they are %s", t, c->drives_on ? "on" : "off",
                 r->plant.enabled ? "on" : "off");
    if ((c->state == FW_STATE_DISABLED || c->state == FW_STATE_FAULT || c->state == FW_STATE_ESTOP) &&
        r->plant.enabled)
        fail_msg("t = %.3f s: drives on in state %d", t, c->state);
    const uint64_t emitted = r->plant.pulses + r->stepper.lost_total - emitted0;
    if (emitted && !moves_robot(s0) && !moves_robot(c->state))
        fail_msg("t = %.3f s: %llu steps from state %d to %d", t, (unsigned long long)emitted, s0, c->state);
    if (estop_open && (emitted || c->state != FW_STATE_ESTOP))
        fail_msg("t = %.3f s: e-stop input open: %llu steps, state %d", t, (unsigned long long)emitted, c->state);
    if (s0 == FW_STATE_HOMING || c->state == FW_STATE_HOMING) {
        r->offset_known = false; /* homing sets the zero */
        r->lost_at_zero = r->stepper.lost_total;
        return;
    }
    /* Homed and moving, no step lost since the zero: the true slides are at a pose inside every
     * limit (the double-precision FK finds one and its IK check passes), whatever precision the
     * controller computes in (this rig runs it in float too, as the board does). */
    if (c->homed && moves_robot(c->state) && !estop_open && r->stepper.lost_total == r->lost_at_zero) {
        if (!plant_update_pose(&r->plant)) {
            double q[6];
            plant_slides(&r->plant, q);
            fail_msg("t = %.3f s: state %d: the slides (%.6f %.6f %.6f %.6f %.6f %.6f m) are at no valid pose", t,
                     c->state, q[0], q[1], q[2], q[3], q[4], q[5]);
        }
        ++r->poses_checked;
    }
    for (int k = 0; k < 6; ++k) {
        const int64_t d = (int64_t)c->sg_pos[k] - (r->plant.steps[k] + r->stepper.lost[k]);
        if (r->offset_known && d != r->offset[k])
            fail_msg("t = %.3f s: slide %d: the controller's count moved %lld steps away from the pulses it gave", t,
                     k + 1, (long long)(d - r->offset[k]));
        r->offset[k] = d;
    }
    r->offset_known = true;
}

static void collect(sim_rig *r)
{
    for (unsigned i = 0; i < r->bus.tx_count; ++i) {
        const uint8_t fn = (uint8_t)(r->bus.tx[i].id >> PROTO_NODE_BITS);
        if (fn != proto_table[PM_ACK].function && fn != proto_table[PM_REJECT].function &&
            fn != proto_table[PM_STATUS].function)
            continue;
        rig_frame *l = &r->log[r->nlog++ % RIG_LOG];
        l->t_us = r->bus.now_us;
        l->f = r->bus.tx[i];
    }
    r->bus.tx_count = 0;
}

#if SIM_RIG_BOARD_TIME
static void board_step(void *arg)
{
    sim_rig *r = arg;
    fw_step_tick(r->fw);
    plant_tick(&r->plant);
}

/* A control tick where it falls; then the period before it is checked, up to this tick's end (the
 * tick completes what the thread may have begun meanwhile: an e-stop frame read during a
 * validation halts the drives at once, and the tick then makes the state ESTOP). */
static void board_control(void *arg)
{
    sim_rig *r = arg;
    const bool estop_open = r->in.estop(r->in.ctx);
    const fw_state s0 = fw_state_of(r->fw);
    const uint64_t emitted0 = r->plant.pulses + r->stepper.lost_total;
    fw_control_tick(r->fw);
    if (r->bt.control_lost > r->allowed_lost_ticks)
        fail_msg("t = %.3f s: a control tick was lost: the one before it was still pending (the thread's work "
                 "kept it out for a whole period)", (double)r->bus.now_us * 1e-6);
    if (r->period_open)
        check(r, r->p_s0, r->p_estop_open, r->p_emitted0);
    r->p_estop_open = estop_open;
    r->p_s0 = s0;
    r->p_emitted0 = emitted0;
    r->period_open = true;
}

static void board_poll(void *arg)
{
    sim_rig *r = arg;
    fw_poll(r->fw);
    if (r->after_poll)
        r->after_poll(r->after_poll_arg);
}

void rig_tick(sim_rig *r)
{
    const uint64_t period = r->bt.control_period;
    bt_thread(&r->bt, board_poll, r);
    bt_idle_until(&r->bt, (r->bt.now / period + 1u) * period);
    const uint64_t ticks = r->bt.now / period;
    for (; r->ticks < ticks; ++r->ticks) {
        const fw_state s = fw_state_of(r->fw);
        ++r->state_ms[s < FW_STATE_COUNT ? s : 0];
    }
    collect(r);
}
#else
/* The rig's part of each call of a period: the test's hook after the poll, the plant's step. */
static void ran(void *ctx, fw_ran what)
{
    sim_rig *r = ctx;
    if (what == FW_RAN_POLL && r->after_poll)
        r->after_poll(r->after_poll_arg);
    else if (what == FW_RAN_STEP)
        plant_tick(&r->plant);
}

void rig_tick(sim_rig *r)
{
    const bool estop_open = r->in.estop(r->in.ctx); /* as this period's control tick reads it */
    const fw_state s0 = fw_state_of(r->fw);
    const uint64_t emitted0 = r->plant.pulses + r->stepper.lost_total;
    fw_run_period(r->fw, ran, r);
    r->bus.now_us += 1000000u / RIG_CONTROL_HZ;
    ++r->ticks;
    const fw_state s = fw_state_of(r->fw);
    ++r->state_ms[s < FW_STATE_COUNT ? s : 0];
    collect(r);
    check(r, s0, estop_open, emitted0);
}
#endif

void rig_run(sim_rig *r, uint32_t ms)
{
    const uint64_t end = r->ticks + ms;
    while (r->ticks < end) {
#if SIM_RIG_BOARD_TIME
        const bool due = r->ticks >= r->next_heartbeat; /* a long work may pass a multiple of 10 */
#else
        const bool due = r->ticks % 10 == 0;
#endif
        if (r->host_alive && due) {
            const int32_t hb[1] = {(int32_t)(r->ticks / 10 % 256)};
            rig_send(r, PM_HOST_HEARTBEAT, hb);
            r->next_heartbeat = r->ticks + 10u;
        }
        rig_tick(r);
    }
}

bool rig_until(sim_rig *r, fw_state s, uint32_t max_ms)
{
    for (uint32_t m = 0; m < max_ms && fw_state_of(r->fw) != s; ++m)
        rig_run(r, 1);
    return fw_state_of(r->fw) == s;
}

void rig_send(sim_rig *r, proto_msg m, const int32_t *v)
{
    fake_send_msg(&r->bus, 1, m, v);
}

uint8_t rig_cmd(sim_rig *r, proto_msg m)
{
    const uint8_t s = r->seq++;
    const int32_t v[1] = {s};
    rig_send(r, m, v);
    return s;
}

void rig_stage(sim_rig *r, uint8_t s, const double p[6])
{
    const int32_t a[3] = {s, (int32_t)lround(p[0] * 1e6), (int32_t)lround(p[1] * 1e6)};
    const int32_t b[3] = {s, (int32_t)lround(p[2] * 1e6), (int32_t)lround(p[3] * 1e6)};
    const int32_t c[3] = {s, (int32_t)lround(p[4] * 1e6), (int32_t)lround(p[5] * 1e6)};
    rig_send(r, PM_POSE_A, a);
    rig_send(r, PM_POSE_B, b);
    rig_send(r, PM_POSE_C, c);
}

uint8_t rig_move(sim_rig *r, const double p[6], int32_t ms)
{
    const uint8_t s = r->seq++;
    rig_stage(r, s, p);
    const int32_t m[3] = {s, 0, ms};
    rig_send(r, PM_MOVE_COMMIT, m);
    return s;
}

void rig_home(sim_rig *r)
{
    const unsigned from = r->nlog;
    const uint8_t e = rig_cmd(r, PM_ENABLE);
    rig_run(r, 10);
    assert_int_equal(rig_answer(r, from, proto_table[PM_ENABLE].function, e, NULL), 'a');
    const uint8_t h = rig_cmd(r, PM_HOME);
    rig_run(r, 10);
    assert_int_equal(rig_answer(r, from, proto_table[PM_HOME].function, h, NULL), 'a');
    assert_int_equal(fw_state_of(r->fw), FW_STATE_HOMING);
    assert_true(rig_until(r, FW_STATE_IDLE, 120000));
    assert_true(fw_homed_of(r->fw));
    for (int k = 0; k < 6; ++k)
        if (llabs((long long)rig_count_error(r, k)) > 1)
            fail_msg("slide %d: after homing the controller counts %lld steps from the truth", k + 1,
                     (long long)rig_count_error(r, k));
}

static const rig_frame *logged(const sim_rig *r, unsigned i)
{
    return &r->log[i % RIG_LOG];
}

static void in_log(const sim_rig *r, unsigned from)
{
    if (from + RIG_LOG < r->nlog)
        fail_msg("log index %u is no longer kept (%u received)", from, r->nlog);
}

char rig_answer(const sim_rig *r, unsigned from, uint8_t function, int seq, uint8_t *reason)
{
    in_log(r, from);
    for (unsigned i = from; i < r->nlog; ++i) {
        const hal_can_frame *f = &logged(r, i)->f;
        const uint8_t fn = (uint8_t)(f->id >> PROTO_NODE_BITS);
        if (f->data[0] != function || (seq >= 0 && f->data[1] != (uint8_t)seq))
            continue;
        if (fn == proto_table[PM_ACK].function)
            return 'a';
        if (fn == proto_table[PM_REJECT].function) {
            if (reason)
                *reason = f->data[2];
            return 'r';
        }
    }
    return 0;
}

unsigned rig_answers(const sim_rig *r, unsigned from, uint8_t function)
{
    in_log(r, from);
    unsigned n = 0;
    for (unsigned i = from; i < r->nlog; ++i) {
        const hal_can_frame *f = &logged(r, i)->f;
        const uint8_t fn = (uint8_t)(f->id >> PROTO_NODE_BITS);
        if ((fn == proto_table[PM_ACK].function || fn == proto_table[PM_REJECT].function) && f->data[0] == function)
            ++n;
    }
    return n;
}

proto_message rig_status(const sim_rig *r, unsigned from)
{
    in_log(r, from);
    for (unsigned i = r->nlog; i-- > from;) {
        const hal_can_frame *f = &logged(r, i)->f;
        if ((f->id >> PROTO_NODE_BITS) != proto_table[PM_STATUS].function)
            continue;
        proto_message m;
        assert_int_equal(proto_decode(f, PROTO_TO_HOST, &m).reason, FW_REASON_NONE);
        return m;
    }
    fail_msg("no STATUS since log index %u", from);
    proto_message none = {0};
    return none;
}

bool rig_plate_at(sim_rig *r, const double want[6])
{
    if (!plant_update_pose(&r->plant))
        return false;
    for (int k = 0; k < 6; ++k)
        if (fabs(r->plant.pose[k] - want[k]) > (k < 3 ? 10e-6 : 1e-5))
            return false;
    return true;
}

int64_t rig_count_error(const sim_rig *r, int k)
{
    int32_t pos[6];
    stepgen_positions(fw_stepgen_of(r->fw), pos);
    return (int64_t)pos[k] - r->plant.steps[k];
}

fw_inspection rig_now(const sim_rig *r)
{
    fw_inspection i;
    fw_inspect(r->fw, &i);
    return i;
}

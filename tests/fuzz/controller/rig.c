#include "rig.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "fuzz_target.h"
#include "oracle.h"

/* The e-stop interrupt: the input opens and its interrupt runs. */
static void fire_estop_isr(rig *r, bool inside)
{
    r->f.estop_open = true;
    oracle_estop_isr(r, inside);
    fw_estop_isr(r->c);
    if (inside && r->in_feed)
        r->hook_fired_in_feed = true;
}

static void hook(void *arg, fake_hook_point at)
{
    rig *r = arg;
    if (r->hook_point == (int)at && r->hook_countdown > 0 && --r->hook_countdown == 0) {
        r->hook_point = RIG_HOOK_NONE;
        fire_estop_isr(r, true);
    }
}

/* The stepper outputs pass the oracle on their way to the fake. */
static void w_set_dir(void *ctx, uint8_t mask)
{
    rig *r = ctx;
    oracle_dir(r, mask);
    r->inner.set_dir(r->inner.ctx, mask);
}

static void w_pulse(void *ctx, uint8_t mask)
{
    rig *r = ctx;
    oracle_pulse(r, mask);
    r->inner.pulse(r->inner.ctx, mask);
}

static void w_enable(void *ctx, bool on)
{
    rig *r = ctx;
    r->inner.enable(r->inner.ctx, on);
}

static void w_timing(void *ctx, uint32_t pulse_ns, uint32_t dir_setup_ns)
{
    rig *r = ctx;
    r->inner.timing(r->inner.ctx, pulse_ns, dir_setup_ns);
}

/* The bus: what the controller sends passes the oracle as it is sent. */
static int w_can_send(void *ctx, const hal_can_frame *f)
{
    rig *r = ctx;
    oracle_sent(r, f);
    return r->inner_can.send(r->inner_can.ctx, f);
}

static int w_can_receive(void *ctx, hal_can_frame *f)
{
    rig *r = ctx;
    return r->inner_can.receive(r->inner_can.ctx, f);
}

static void w_can_state(void *ctx, hal_can_state *st)
{
    rig *r = ctx;
    r->inner_can.state(r->inner_can.ctx, st);
}

void rig_plant_follow(rig *r, const fw_param_set *params)
{
    const int64_t was = r->plant_params.v[FP_STEPS_PER_M], spm = params->v[FP_STEPS_PER_M];
    for (int k = 0; k < 6; ++k) {
        if (spm != was)
            r->f.steps[k] = (int32_t)llround((double)r->f.steps[k] * (double)spm / (double)was);
        r->f.switch_at[k] = (int32_t)((int64_t)params->v[FP_HOME_SW_1 + k] * spm / 1000000);
    }
    r->plant_params = *params;
}

static void fixture_params(rig_fixture fx, fw_param_set *p)
{
    fw_params_default(p);
    if (fx == RIG_HARNESS)
        return;
    for (int k = 0; k < 6; ++k)
        p->v[FP_HOME_SW_1 + k] = 395000;
    p->v[FP_STEPS_PER_M] = 64000;
    p->v[FP_HOMING_SPEED] = 10000;
    p->v[FP_SLIDE_AMAX] = 4000000;
}

#if FUZZ_BOARD_TIME
/* The step interrupt, as the tick it was due at (the plant's checks count in ticks). */
static void bt_step(void *arg)
{
    rig *r = arg;
    r->tick = r->bt.next_step / (BT_HZ / r->cfg.step_hz) - 1u;
    if (r->in_feed)
        r->steps_in_feed = true;
    fw_step_tick(r->c);
}

static bool bt_step_idle(void *arg)
{
    rig *r = arg;
    return stepgen_idle(fw_stepgen_of(r->c));
}

/* The control interrupt: the segment's checks, the tick, the oracle's look after it. */
static void bt_control(void *arg)
{
    rig *r = arg;
    if (r->in_feed)
        r->ticks_in_feed = true;
    r->tick = r->bt.control_due / (BT_HZ / r->cfg.step_hz);
    oracle_segment(r);
    fw_control_tick(r->c);
    oracle_after_control(r);
}

static void bt_poll(void *arg)
{
    rig *r = arg;
    fw_poll(r->c);
}

/* Where the board's time stands, in the rig's step ticks. */
static void follow_board(rig *r)
{
    r->tick = r->bt.now / (BT_HZ / r->cfg.step_hz);
}

/* The controller (re)started: fw_init's solves are not the board's time. */
static void boot(rig *r)
{
    bt_stop();
    r->c = fw_init(&r->mem, &r->hal, &r->cfg);
    FUZZ_CHECK(r->c != NULL);
    bt_resume(&r->bt);
}
#endif

void rig_start(rig *r, rig_fixture fixture)
{
    /* The fake (most of the rig) is cleared by its own init. */
    memset(&r->mem, 0, sizeof *r - offsetof(rig, mem));
    fake_hal_init(&r->f, &r->hal);
    r->inner = r->hal.stepper;
    r->hal.stepper = (hal_stepper){r, w_set_dir, w_pulse, w_enable, w_timing};
    r->inner_can = r->hal.can;
    r->hal.can = (hal_can){r, w_can_send, w_can_receive, w_can_state};
    r->f.hook = hook;
    r->f.hook_arg = r;
    r->hook_point = RIG_HOOK_NONE;
    r->fixture = fixture;

    fw_param_set p;
    fixture_params(fixture, &p);
    const bool fast = fixture != RIG_HARNESS;
    if (fast)
        r->f.storage_len = (int)fw_params_serialize(&p, r->f.storage, sizeof r->f.storage);
#if FUZZ_BOARD_TIME
    r->cfg = (fw_config){fixture == RIG_FAST_BOARD ? 15 : 1, 1000, fast ? 10000 : 100000, bt_await, &r->bt, RIG_BOARD_NAME};
#else
    r->cfg = (fw_config){fixture == RIG_FAST_BOARD ? 15 : 1, 1000, fast ? 10000 : 100000, NULL, NULL, RIG_BOARD_NAME};
#endif
    /* The plant's coordinates are the parameters' from the start (the fake's default switches are
     * the default set's). */
    r->plant_params = p;
    r->plant_params.v[FP_STEPS_PER_M] = fw_param_table[FP_STEPS_PER_M].def;
    rig_plant_follow(r, &p);
    /* Just above the switches, as tests/firmware/harness.c starts them, or just below. */
    for (int k = 0; k < 6; ++k) {
        const int32_t off = fast ? 40 + 5 * k : 3000 + 100 * k;
        r->f.steps[k] = r->f.switch_at[k] + (fixture == RIG_FAST_ON_SWITCH ? -off : off);
    }

#if FUZZ_BOARD_TIME
    const bt_hooks hooks = {bt_step, bt_control, bt_step_idle, r, &r->f.now_us};
    bt_init(&r->bt, r->cfg.step_hz, r->cfg.segment_hz, &hooks);
    boot(r);
#else
    r->c = fw_init(&r->mem, &r->hal, &r->cfg);
    FUZZ_CHECK(r->c != NULL);
#endif
    r->ticks_per_segment = r->cfg.step_hz / r->cfg.segment_hz;
    r->us_per_tick = 1000000u / r->cfg.step_hz;
    r->cap_ticks = (uint64_t)(fast ? RIG_CAP_S_FAST : RIG_CAP_S_HARNESS) * r->cfg.step_hz;
    r->host_alive = true;
    r->seq = 1;
    for (int k = 0; k < 6; ++k)
        r->home_um[k] = (int32_t)llround(fw_geometry_of(r->c)->home_pose[k] * 1e6);
    oracle_start(r, fast ? &p : NULL);
}

bool rig_over(const rig *r)
{
    /* A BOOT_ENTER taken: the board restarts into its bootloader, and the input ends there (the
     * controller takes no frame meanwhile, and what restarts is another program). */
    return r->tick >= r->cap_ticks || fw_boot_requested(r->c);
}

/* The thread's poll: in place, or on the board's time. */
static void thread_poll(rig *r)
{
#if FUZZ_BOARD_TIME
    bt_thread(&r->bt, bt_poll, r);
    follow_board(r);
#else
    fw_poll(r->c);
#endif
}

void rig_feed(rig *r, const hal_can_frame *fr)
{
    /* Flush what is due (STATUS, telemetry) first, so that the frame's poll sends only what the
     * frame causes. */
    thread_poll(r);
    oracle_after_poll(r);
    oracle_before_frame(r, fr);
    fake_send(&r->f, fr->id, fr->len, fr->data);
    r->in_feed = true;
    r->hook_fired_in_feed = false;
    r->ticks_in_feed = r->steps_in_feed = false;
    thread_poll(r);
    r->in_feed = false;
    oracle_after_frame(r);
}

void rig_feed_msg(rig *r, uint8_t node, proto_msg m, const int32_t *values)
{
    hal_can_frame fr;
    if (fake_encode(node, m, values, &fr) == 0)
        rig_feed(r, &fr);
}

#if !FUZZ_BOARD_TIME
/* The oracle looks after the period's poll and after its control tick (fw/runtime.h: the order). */
static void after_call(void *arg, fw_ran what)
{
    rig *r = arg;
    if (what == FW_RAN_POLL)
        oracle_after_poll(r);
    else if (what == FW_RAN_CONTROL)
        oracle_after_control(r);
}

static void segment_boundary(rig *r)
{
    oracle_segment(r);
    if (r->host_alive && r->tick >= r->next_heartbeat_tick) {
        const int32_t v[1] = {(int32_t)(r->tick & 0xFF)};
        rig_feed_msg(r, r->cfg.node, PM_HOST_HEARTBEAT, v);
        r->next_heartbeat_tick = r->tick + 10u * r->cfg.step_hz / 1000u;
    }
    fw_period_start(r->c, after_call, r);
}

#endif

#if FUZZ_BOARD_TIME
/* Board time: the interrupts as they come due; after the control tick at each segment boundary
 * the thread's turn (a heartbeat fed, or a poll), however long it takes. */
void rig_advance(rig *r, uint64_t n)
{
    const uint64_t end = r->tick + n < r->cap_ticks ? r->tick + n : r->cap_ticks;
    const uint64_t cycles = BT_HZ / r->cfg.step_hz;
    while (r->tick < end) {
        /* The control tick at a boundary runs on past it (its own cost): the thread's turn comes
         * once per segment whose tick has run. */
        const uint64_t segment = r->bt.next_control / r->bt.control_period - 1u;
        if (segment > r->thread_segment && !r->bt.control_pending) {
            r->thread_segment = segment;
            if (r->host_alive && r->tick >= r->next_heartbeat_tick) {
                const int32_t v[1] = {(int32_t)(r->tick & 0xFF)};
                r->next_heartbeat_tick = r->tick + 10u * r->cfg.step_hz / 1000u;
                rig_feed_msg(r, r->cfg.node, PM_HOST_HEARTBEAT, v);
            } else {
                thread_poll(r);
                oracle_after_poll(r);
            }
            continue;
        }
        uint64_t until = (r->tick / r->ticks_per_segment + 1u) * r->ticks_per_segment;
        if (until > end)
            until = end;
        bt_idle_until(&r->bt, until * cycles);
        follow_board(r);
    }
}
#else
void rig_advance(rig *r, uint64_t n)
{
    const uint64_t end = r->tick + n < r->cap_ticks ? r->tick + n : r->cap_ticks;
    while (r->tick < end) {
        r->f.now_us = r->tick * r->us_per_tick;
        const uint64_t phase = r->tick % r->ticks_per_segment;
        uint64_t until = r->tick + (r->ticks_per_segment - phase);
        if (until > end)
            until = end;
        if (phase == 0)
            segment_boundary(r);
        /* A step generator with nothing running or queued emits nothing until the next control
         * tick queues a segment (stepgen.h): after one tick that shows it, the rest of the
         * segment's ticks are skipped, which makes the long waits of an input at rest cheap. */
        fw_step_tick(r->c);
        ++r->tick;
        if (stepgen_idle(fw_stepgen_of(r->c)))
            r->tick = until;
        else
            for (; r->tick < until; ++r->tick)
                fw_step_tick(r->c);
    }
    r->f.now_us = r->tick * r->us_per_tick;
}
#endif

void rig_run_ms(rig *r, uint32_t ms)
{
    rig_advance(r, (uint64_t)ms * r->cfg.step_hz / 1000u);
}

void rig_run_until_rest(rig *r, uint32_t max_ms)
{
    for (uint32_t ms = 0; ms < max_ms && !rig_over(r); ++ms) {
        const fw_state s = fw_state_of(r->c);
        if (s != FW_STATE_HOMING && s != FW_STATE_MOVING && s != FW_STATE_STOPPING)
            return;
        rig_run_ms(r, 1);
    }
}

void rig_estop_input(rig *r, bool open, bool isr)
{
    if (open && isr) {
        fire_estop_isr(r, false);
    } else {
        r->f.estop_open = open;
    }
    rig_input_changed(r);
}

void rig_arm_estop_hook(rig *r, fake_hook_point at, unsigned n)
{
    r->hook_point = (int)at;
    r->hook_countdown = n;
}

void rig_reboot(rig *r)
{
    r->hook_point = RIG_HOOK_NONE;
    r->f.tx_count = 0;
#if FUZZ_BOARD_TIME
    boot(r);
#else
    r->c = fw_init(&r->mem, &r->hal, &r->cfg);
    FUZZ_CHECK(r->c != NULL);
#endif
    oracle_reboot(r);
}

void rig_report_fault(rig *r, fw_fault f)
{
    fw_report_fault(r->c, f);
    rig_input_changed(r);
    oracle_published(r);
}

void rig_input_changed(rig *r)
{
    oracle_event(r);
}

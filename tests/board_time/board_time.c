#include "board_time.h"

#include <stddef.h>

static board_time *cur;

void bt_init(board_time *b, uint32_t step_hz, uint32_t control_hz, const bt_hooks *hooks)
{
    *b = (board_time){0};
    b->h = *hooks;
    b->step_period = BT_HZ / step_hz;
    b->control_period = BT_HZ / control_hz;
    b->next_step = b->step_period;
    b->next_control = b->control_period;
    cur = b;
}

void bt_stop(void)
{
    cur = NULL;
}

void bt_resume(board_time *b)
{
    cur = b;
}

static void clock_follow(board_time *b)
{
    if (b->h.clock_us)
        *b->h.clock_us = b->now / (BT_HZ / 1000000u);
}

static void run_step(board_time *b)
{
    const bt_context was = b->ctx;
    b->ctx = BT_STEP;
    b->next_step += b->step_period;
    clock_follow(b);
    b->h.step(b->h.arg);
    b->now += BT_STEP_TICK;
    b->charged[BT_STEP] += BT_STEP_TICK;
    b->ctx = was;
    if (b->h.step_idle && b->next_step < b->next_control && b->h.step_idle(b->h.arg))
        b->next_step = b->next_control; /* (a control period is a whole number of step periods) */
}

static void run_control(board_time *b)
{
    const bt_context was = b->ctx;
    b->ctx = BT_CONTROL;
    b->control_pending = false;
    if (b->now - b->control_due > b->control_late_max)
        b->control_late_max = b->now - b->control_due;
    clock_follow(b);
    b->h.control(b->h.arg);
    bt_charge(BT_CONTROL_BASE);
    b->ctx = was;
}

/* Whatever has come due and outranks the context running now. */
static void dispatch(board_time *b)
{
    for (;;) {
        if (b->ctx < BT_STEP && b->now >= b->next_step) {
            run_step(b);
            continue;
        }
        /* The control timer's event: it pends the interrupt, once. */
        while (b->now >= b->next_control) {
            if (b->control_pending)
                ++b->control_lost;
            b->control_pending = true;
            b->control_due = b->next_control;
            b->next_control += b->control_period;
        }
        const bool may = b->ctx < BT_CONTROL && !(b->control_in_thread && b->ctx == BT_THREAD && !b->idle);
        if (may && b->control_pending) {
            run_control(b);
            continue;
        }
        break;
    }
    clock_follow(b);
}

void bt_charge(uint32_t n)
{
    board_time *b = cur;
    if (!b)
        return;
    /* The charge runs in steps no longer than a step period, so that the interrupts preempting
     * it come at their times and their lateness is what a real preemption would give. */
    while (n > 0) {
        const uint32_t piece = n < b->step_period ? n : b->step_period;
        b->now += piece;
        b->charged[b->ctx] += piece;
        n -= piece;
        dispatch(b);
    }
}

static void thread_ran(board_time *b)
{
    const uint64_t run = b->now - b->thread_run_start;
    if (run > b->thread_run_max)
        b->thread_run_max = run;
}

void bt_thread(board_time *b, void (*fn)(void *), void *arg)
{
    b->ctx = BT_THREAD;
    b->thread_run_start = b->now;
    fn(arg);
    bt_charge(BT_POLL);
    thread_ran(b);
}

/* When the next step or control interrupt comes due. */
static uint64_t next_due(const board_time *b)
{
    return b->next_step < b->next_control ? b->next_step : b->next_control;
}

static void to_next_interrupt(board_time *b)
{
    const uint64_t t = b->control_pending ? b->now : next_due(b);
    if (t > b->now)
        b->now = t;
    dispatch(b);
}

void bt_await(void *arg)
{
    board_time *b = arg;
    thread_ran(b);
    b->idle = true;
    to_next_interrupt(b);
    b->idle = false;
    b->thread_run_start = b->now;
}

void bt_idle_until(board_time *b, uint64_t t)
{
    b->idle = true;
    dispatch(b);
    while (b->now < t) {
        const uint64_t next = next_due(b);
        b->now = next < t ? next : t;
        dispatch(b);
    }
    b->idle = false;
}

/* ---- the firmware's solves, charged (--wrap) ---- */

#include "tse/enclose.h"
#include "tse/fk.h"
#include "tse/ik.h"

tse_status __real_tse_ik_f(const tse_geometry *g, const tse_real pose[6], const tse_real seed[6], tse_ik_result *out);
tse_status __wrap_tse_ik_f(const tse_geometry *g, const tse_real pose[6], const tse_real seed[6], tse_ik_result *out);
tse_status __real_tse_fk_f(const tse_geometry *g, const tse_real q[6], const tse_real seed[6], tse_fk_result *out);
tse_status __wrap_tse_fk_f(const tse_geometry *g, const tse_real q[6], const tse_real seed[6], tse_fk_result *out);
int __real_tse_ik_enclose_f(const tse_geometry *g, const tse_piece *piece, const tse_real pose[6],
                            const tse_ik_result *centre, tse_enclosure *out);
int __wrap_tse_ik_enclose_f(const tse_geometry *g, const tse_piece *piece, const tse_real pose[6],
                            const tse_ik_result *centre, tse_enclosure *out);

static unsigned depth; /* a solve inside a solve is part of the outer one's figure */

static void charged(uint32_t n)
{
    if (--depth == 0)
        bt_charge(n);
}

tse_status __wrap_tse_ik_f(const tse_geometry *g, const tse_real pose[6], const tse_real seed[6], tse_ik_result *out)
{
    ++depth;
    const tse_status r = __real_tse_ik_f(g, pose, seed, out);
    charged(BT_IK);
    return r;
}

tse_status __wrap_tse_fk_f(const tse_geometry *g, const tse_real q[6], const tse_real seed[6], tse_fk_result *out)
{
    ++depth;
    const tse_status r = __real_tse_fk_f(g, q, seed, out);
    charged(BT_FK);
    return r;
}

int __wrap_tse_ik_enclose_f(const tse_geometry *g, const tse_piece *piece, const tse_real pose[6],
                            const tse_ik_result *centre, tse_enclosure *out)
{
    ++depth;
    const int r = __real_tse_ik_enclose_f(g, piece, pose, centre, out);
    charged(BT_ENCLOSE);
    return r;
}

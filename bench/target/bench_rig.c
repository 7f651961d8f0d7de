#include "bench_rig.h"

#include <string.h>

#include "fw/inspect.h"
#include "fw/runtime.h"
#include "fw/testing.h"
#include "hal_stm32f4/regs_rcc.h"
#include "hal_stm32f4/regs_tim.h"
#include "tse/ik.h"

static fw_controller_mem bench_mem;
fw_controller *bench_ctl;
uint64_t bench_now_us;
uint32_t bench_overhead;

/* The last ACK or REJECT the controller sent: what a commit was answered. */
static hal_can_frame answer_frame;
static bool answered;

uint32_t bench_counter_start(void)
{
    TSE_RCC->APB1ENR |= RCC_APB1ENR_TIM2;
    TSE_TIM2->CR1 = 0;
    TSE_TIM2->PSC = 0;
    TSE_TIM2->ARR = 0xFFFFFFFFu;
    TSE_TIM2->EGR = TIM_EGR_UG;
    TSE_TIM2->CR1 = TIM_CR1_CEN;
    /* Two reads back to back: what a measurement of nothing reads. */
    uint32_t lo = UINT32_MAX;
    for (int i = 0; i < 16; ++i) {
        const uint32_t a = bench_count();
        const uint32_t b = bench_count();
        if (b - a < lo)
            lo = b - a;
    }
    bench_overhead = lo;
    return lo;
}

void bench_wrap_clear(void)
{
    TSE_TIM2->SR = 0;
}

bool bench_wrapped(void)
{
    return (TSE_TIM2->SR & TIM_SR_UIF) != 0;
}

static int can_send(void *c, const hal_can_frame *f)
{
    (void)c;
    const uint8_t fn = (uint8_t)(f->id >> PROTO_NODE_BITS);
    if (fn == proto_wire[PM_ACK].function || fn == proto_wire[PM_REJECT].function) {
        answer_frame = *f;
        answered = true;
    }
    return 0;
}
/* The thread's longest stretch between two reads of the bus while a hold is measured, and the
 * clock then running with the instructions (168 per microsecond, the board's core clock), so that
 * what falls due during a long validation (STATUS, telemetry) is sent, and counted, as on the
 * board. */
#define BENCH_CORE_MHZ 168u
static bool holding;
static uint32_t hold_t0, hold_last, hold_worst;

static void hold_mark(void)
{
    if (!holding)
        return;
    const uint32_t t = bench_count();
    if (t - hold_last > hold_worst)
        hold_worst = t - hold_last;
    hold_last = t;
}

void bench_hold_begin(void)
{
    hold_worst = 0;
    hold_t0 = hold_last = bench_count();
    holding = true;
}

uint32_t bench_hold_end(void)
{
    hold_mark();
    holding = false;
    bench_now_us += (hold_last - hold_t0) / BENCH_CORE_MHZ;
    return hold_worst;
}

/* Frames for the next poll: a small ring the rig fills and the controller's poll empties. */
#define RX_RING 8u
static hal_can_frame rx[RX_RING];
static unsigned rx_head, rx_count;
static int can_receive(void *c, hal_can_frame *f)
{
    (void)c;
    hold_mark();
    if (rx_count == 0)
        return 0;
    *f = rx[rx_head];
    rx_head = (rx_head + 1u) % RX_RING;
    --rx_count;
    return 1;
}
static void can_state(void *c, hal_can_state *s) { (void)c; memset(s, 0, sizeof *s); }
static void st_dir(void *c, uint8_t m) { (void)c; (void)m; }
static void st_pulse(void *c, uint8_t m) { (void)c; (void)m; }
static void st_enable(void *c, bool on) { (void)c; (void)on; }
static uint16_t in_limits(void *c) { (void)c; return 0; }
static bool in_estop(void *c) { (void)c; return false; }
static uint64_t clk_now(void *c)
{
    (void)c;
    return holding ? bench_now_us + (bench_count() - hold_t0) / BENCH_CORE_MHZ : bench_now_us;
}
static int st_load(void *c, void *b, size_t n) { (void)c; (void)b; (void)n; return 0; }
static int st_save(void *c, const void *b, size_t n) { (void)c; (void)b; (void)n; return -1; }

void bench_queue(proto_msg msg, const int32_t *v)
{
    hal_can_frame f;
    proto_encode_values(msg, 1, v, &f);
    if (rx_count == RX_RING)
        fw_poll(bench_ctl); /* room first: the rig never drops a frame */
    rx[(rx_head + rx_count) % RX_RING] = f;
    ++rx_count;
}

void bench_frame(proto_msg msg, const int32_t *v)
{
    bench_queue(msg, v);
    fw_poll(bench_ctl);
}

void bench_stage(uint8_t seq, const tse_real pose[6])
{
    for (int part = 0; part < 3; ++part) {
        const int32_t v[3] = {seq, (int32_t)(pose[2 * part] * TSE_R(1e6)), (int32_t)(pose[2 * part + 1] * TSE_R(1e6))};
        bench_queue((proto_msg)(PM_POSE_A + part), v);
    }
    fw_poll(bench_ctl);
}

void bench_period(uint32_t *c)
{
    bench_now_us += 1000;
    bench_frame(PM_HOST_HEARTBEAT, (const int32_t[]){0});
    if (c) {
        const uint32_t t0 = bench_count();
        fw_control_tick(bench_ctl);
        *c = bench_count() - t0 - bench_overhead;
    } else {
        fw_control_tick(bench_ctl);
    }
    const fw_config *cfg = fw_config_of(bench_ctl);
    for (uint32_t t = 0; t < cfg->step_hz / cfg->segment_hz; ++t)
        fw_step_tick(bench_ctl);
}

int bench_rig_place(const tse_real p[6])
{
    return fw_testing_homed_at(bench_ctl, p);
}

int bench_rig_start(void)
{
    fw_hal hal;
    memset(&hal, 0, sizeof hal);
    hal.can = (hal_can){0, can_send, can_receive, can_state};
    hal.stepper = (hal_stepper){.set_dir = st_dir, .pulse = st_pulse, .enable = st_enable};
    hal.inputs = (hal_inputs){0, in_limits, in_estop};
    hal.clock = (hal_clock){0, clk_now};
    hal.storage = (hal_storage){0, st_load, st_save};
    const fw_config cfg = {1, 1000, 200000, NULL, NULL, NULL}; /* one context: no await */
    rx_head = rx_count = 0;
    bench_ctl = fw_init(&bench_mem, &hal, &cfg);
    if (!bench_ctl || fw_testing_homed_at_home(bench_ctl) != 0)
        return -1;
    bench_frame(PM_ENABLE, (const int32_t[]){0});
    fw_control_tick(bench_ctl); /* takes the ENABLE the poll handed over */
    return fw_state_of(bench_ctl) == FW_STATE_IDLE ? 0 : -1;
}

uint32_t bench_commit_cost(const bench_commit *bc, char *answer, int *reason, uint32_t *hold)
{
    /* A copy to come back to, restored where it was taken: the controller's pointers (to the HAL's
     * functions, and into its own memory) stay valid. */
    static fw_controller_mem rest;
    rest = bench_mem;
    *answer = 0;
    *reason = 0;
    if (bench_rig_place(bc->from) != 0) {
        bench_mem = rest;
        return 0;
    }
    static fw_inspection in;
    fw_inspect(bench_ctl, &in);
    const uint8_t seq = (uint8_t)(in.last_seq + 1u); /* newer than the last, whatever it was */
    bench_stage(seq, bc->to);
    answered = false;
    bench_queue(PM_MOVE_COMMIT, ((const int32_t[]){seq, bc->kind, bc->value}));
    bench_wrap_clear();
    const uint32_t t0 = bench_count();
    bench_hold_begin();
    fw_poll(bench_ctl);
    const uint32_t longest = bench_hold_end();
    const uint32_t t1 = bench_count();
    if (hold)
        *hold = longest;
    const bool wrapped = bench_wrapped();
    if (answered) {
        const uint8_t fn = (uint8_t)(answer_frame.id >> PROTO_NODE_BITS);
        *answer = fn == proto_wire[PM_ACK].function ? 'a' : 'r';
        *reason = *answer == 'r' ? answer_frame.data[2] : 0;
    }
    bench_mem = rest;
    return wrapped ? UINT32_MAX : t1 - t0 - bench_overhead;
}

/* The step generator (fw/stepgen.h) on the emulated Cortex-M4F, at the board's rates: 1 kHz
 * control segments, 200 kHz step interrupts (200 ticks a segment).
 *
 * Every tick goes to a fake driver exactly as fw_step_tick hands it over (set_dir when the
 * generator says the direction changed, then pulse), and the driver records what a real one
 * would see: its DIR pins, the steps counted with them, the tick of every STEP and DIR edge.
 * The checks are on that record, against expectations written from the header's promises:
 * - exactness: after every segment, whatever the sequence of setpoints (reversals, segments at
 *   the capacity, queued ahead), the driver's count is the setpoint;
 * - within a segment the count stays within half a step of the straight line to the setpoint;
 * - spacing: two steps of one axis at least min_step_interval ticks apart, across segments;
 * - direction set-up: no step of an axis until dir_setup_ticks ticks after its DIR changed (a
 *   step exactly dir_setup_ticks ticks later has DIR stable for dir_setup_ticks periods);
 * - the direction mask reported on every tick is the driver's DIR pins;
 * - a segment asking more than its capacity is an overrun, emits the capacity, and what is left
 *   is caught up in the next segments until the driver is on the setpoint;
 * - a halt (the e-stop interrupt's half) stops the pulses from the next tick on.
 * The capacity is computed here from its definition (ticks, less the set-up on a reversal,
 * divided by the interval).  The board's own configuration comes from the parameter defaults
 * (dir_setup_ns, step_rate_max) rounded up to whole ticks (docs/controller.md, "Step timing in
 * ticks"; the firmware's own configuration has one tick of DIR set-up more, fw_dir_setup_ticks). */
#include <stdint.h>
#include <string.h>

#include "fw/params.h"
#include "fw/stepgen.h"
#include "target_test.h"

#define STEP_HZ 200000u
#define SEGMENT_HZ 1000u
#define TICKS (STEP_HZ / SEGMENT_HZ)

typedef struct {
    uint8_t dir;          /* DIR pins: bit set, forward */
    int32_t pos[6];       /* counted from the STEP pulses with the DIR pins */
    long tick;            /* ticks so far (1-based) */
    long last_step[6];
    long last_dir[6];
    long min_spacing;     /* smallest gap between two steps of one axis */
    long min_setup;       /* smallest gap from a DIR change to the next step of that axis */
    unsigned long pulses;
    unsigned mask_mismatch; /* ticks whose reported mask differs from the pins */
    uint32_t interval, setup;
} driver;

static stepgen sg;
static driver drv;
static uint32_t rng = 0x2545F491u;

static uint32_t rnd(uint32_t n)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng % n;
}

static void set_dir(uint8_t mask)
{
    for (int i = 0; i < 6; ++i)
        if (((mask ^ drv.dir) >> i) & 1u)
            drv.last_dir[i] = drv.tick;
    drv.dir = mask;
}

static void pulse(uint8_t mask)
{
    for (int i = 0; i < 6; ++i) {
        if (!((mask >> i) & 1u))
            continue;
        const long gap = drv.tick - drv.last_step[i], setup = drv.tick - drv.last_dir[i];
        if (gap < drv.min_spacing)
            drv.min_spacing = gap;
        if (setup < drv.min_setup)
            drv.min_setup = setup;
        TT_CHECKF(gap >= (long)drv.interval, "axis %d: steps %ld ticks apart at tick %ld\n", i, gap, drv.tick);
        TT_CHECKF(setup >= (long)drv.setup, "axis %d: step %ld ticks after its DIR change at tick %ld\n", i,
                  setup, drv.tick);
        drv.pos[i] += ((drv.dir >> i) & 1u) ? 1 : -1;
        drv.last_step[i] = drv.tick;
        ++drv.pulses;
    }
}

/* One step interrupt, as fw_step_tick runs it. */
static uint8_t tick(void)
{
    ++drv.tick;
    const stepgen_output o = stepgen_tick(&sg);
    if (o.dir_changed)
        set_dir(o.forward_mask);
    if (o.forward_mask != drv.dir)
        ++drv.mask_mismatch;
    if (o.step_mask)
        pulse(o.step_mask);
    return o.step_mask;
}

static void start(uint32_t setup, uint32_t interval)
{
    const stepgen_config cfg = {TICKS, setup, interval};
    const int32_t zero[6] = {0};
    TT_CHECK(stepgen_init(&sg, &cfg, zero) == 0);
    memset(&drv, 0, sizeof drv);
    drv.dir = sg.forward_mask; /* the controller sets the pins to a fresh generator's mask */
    drv.min_spacing = drv.min_setup = 1L << 30;
    for (int i = 0; i < 6; ++i)
        drv.last_step[i] = drv.last_dir[i] = -(1L << 20);
    drv.interval = interval;
    drv.setup = setup;
}

/* The capacity by its definition. */
static int32_t capacity(bool reversal)
{
    return (int32_t)((TICKS - (reversal ? drv.setup : 0u)) / drv.interval);
}

/* The board's configuration from the parameter defaults. */
static void board_config(uint32_t *setup, uint32_t *interval)
{
    const uint64_t dir_ns = (uint64_t)fw_param_specs[FP_DIR_SETUP_NS].def;
    const uint32_t rate = (uint32_t)fw_param_specs[FP_STEP_RATE_MAX].def;
    *setup = (uint32_t)((dir_ns * STEP_HZ + 999999999u) / 1000000000u);
    if (*setup == 0)
        *setup = 1;
    *interval = (STEP_HZ + rate - 1u) / rate;
}

static const uint32_t configs[][2] = {{0, 0} /* the board's */, {3, 2}, {7, 3}, {20, 1}};
#define NCONFIG (sizeof configs / sizeof configs[0])

static void config_of(unsigned c, uint32_t *setup, uint32_t *interval)
{
    if (c == 0) {
        board_config(setup, interval);
    } else {
        *setup = configs[c][0];
        *interval = configs[c][1];
    }
}

static void capacity_definition(void)
{
    uint32_t setup, interval;
    board_config(&setup, &interval);
    sh_printf("  board: %u ticks a segment, dir set-up %lu tick(s), step interval %lu tick(s)\n", TICKS,
              (unsigned long)setup, (unsigned long)interval);
    for (unsigned c = 0; c < NCONFIG; ++c) {
        config_of(c, &setup, &interval);
        start(setup, interval);
        TT_CHECK(stepgen_capacity(&sg.cfg, false) == (uint32_t)capacity(false));
        TT_CHECK(stepgen_capacity(&sg.cfg, true) == (uint32_t)capacity(true));
    }
}

/* Random setpoints within capacity, two queued ahead of the running segment: a third of the axis
 * moves exactly at the capacity, a fifth at rest, directions reversing at random. */
#define SEGMENTS 2000
static int32_t targets[SEGMENTS][6];

static void exact_random(void)
{
    for (unsigned c = 0; c < NCONFIG; ++c) {
        uint32_t setup, interval;
        config_of(c, &setup, &interval);
        start(setup, interval);
        bool forward[6] = {true, true, true, true, true, true}; /* the generator's view, modelled */
        int32_t at[6] = {0};
        unsigned at_cap = 0, reversals = 0, line_bad = 0;
        for (int s = 0; s < SEGMENTS; ++s) {
            for (int i = 0; i < 6; ++i) {
                const bool fwd = rnd(2) == 0;
                const bool rev = fwd != forward[i];
                const int32_t cap = capacity(rev);
                const uint32_t kind = rnd(10);
                int32_t d = kind < 2 ? 0 : kind < 5 ? cap : (int32_t)rnd((uint32_t)cap + 1u);
                if (d != 0) {
                    forward[i] = fwd;
                    reversals += rev;
                    at_cap += d == cap;
                }
                at[i] += fwd ? d : -d;
                targets[s][i] = at[i];
            }
        }
        TT_CHECK(stepgen_push(&sg, targets[0]) == 0);
        TT_CHECK(stepgen_push(&sg, targets[1]) == 0);
        int32_t from[6] = {0};
        bool exact = true;
        for (int s = 0; s < SEGMENTS; ++s) {
            if (s + 2 < SEGMENTS)
                TT_CHECK(stepgen_push(&sg, targets[s + 2]) == 0);
            const uint8_t dir_before = drv.dir;
            for (uint32_t t = 1; t <= TICKS; ++t) {
                tick();
                /* Half a step of the straight line: from the segment's start, over the ticks
                 * after the set-up on a reversal. */
                for (int i = 0; i < 6; ++i) {
                    const bool rev = ((drv.dir ^ dir_before) >> i) & 1u;
                    const int32_t d = targets[s][i] - from[i];
                    const int32_t lead = rev ? (int32_t)setup : 0;
                    const int32_t span = (int32_t)TICKS - lead;
                    const int32_t el = (int32_t)t - lead < 0 ? 0 : (int32_t)t - lead;
                    /* |pos - (from + d el / span)| <= 1/2, in integers */
                    const int64_t dev = 2 * ((int64_t)(drv.pos[i] - from[i]) * span - (int64_t)d * el);
                    if (dev > span || dev < -span)
                        ++line_bad;
                }
            }
            for (int i = 0; i < 6; ++i) {
                if (drv.pos[i] != targets[s][i])
                    exact = false;
                from[i] = drv.pos[i];
            }
        }
        TT_CHECKF(exact, "config %u: a segment ended off its setpoint\n", c);
        TT_CHECK(line_bad == 0);
        TT_CHECK(sg.overruns == 0);
        TT_CHECK(drv.mask_mismatch == 0);
        TT_CHECK(stepgen_idle(&sg));
        int32_t pos[6];
        stepgen_positions(&sg, pos);
        TT_CHECK(memcmp(pos, drv.pos, sizeof pos) == 0);
        /* The sequence did what it is meant to: reversals and full-capacity segments. */
        TT_CHECK(reversals > 1000 && at_cap > 1000);
        TT_CHECK(drv.min_spacing == (long)interval); /* the capacity is reached: spacing tight */
        TT_CHECK(drv.min_setup >= (long)setup);
        sh_printf("  set-up %2lu, interval %lu: %d segments, %lu steps (%u at capacity, %u reversals); "
                  "closest steps %ld ticks, DIR to step %ld ticks\n",
                  (unsigned long)setup, (unsigned long)interval, SEGMENTS, drv.pulses, at_cap, reversals,
                  drv.min_spacing, drv.min_setup);
    }
}

/* More than the capacity: an overrun, the capacity emitted, the rest caught up. */
static void overrun_caught_up(void)
{
    for (unsigned c = 0; c < NCONFIG; ++c) {
        uint32_t setup, interval;
        config_of(c, &setup, &interval);
        start(setup, interval);
        /* First a segment backwards on axes 2 and 5, so that the big ask reverses them. */
        const int32_t back[6] = {0, 0, -10, 0, 0, -10};
        TT_CHECK(stepgen_push(&sg, back) == 0);
        for (uint32_t t = 0; t < TICKS; ++t)
            tick();
        const int32_t cf = capacity(false), cr = capacity(true);
        /* axis 0: one over; 1: backwards (a reversal) what three segments hold, the first with the
         * set-up taken off; 2: a reversal, one over; 3: exactly the capacity; 4: within; 5: 2.5
         * segments' worth, same direction.  So: overruns in segments 1 and 2, on the setpoint
         * after the third (which axis 1 fills exactly). */
        const int32_t want[6] = {cf + 1, -(cr + 2 * cf), -10 + cr + 1, cf, cf / 3, -10 - (5 * cf) / 2};
        unsigned expected_overruns = 0, segments = 0;
        bool first = true;
        while (segments < 10) {
            /* The model: an overrun when some axis still needs more than its capacity. */
            bool over = false;
            for (int i = 0; i < 6; ++i) {
                const int32_t need = want[i] - drv.pos[i];
                const bool fwd_pin = (drv.dir >> i) & 1u;
                const bool rev = need != 0 && (need > 0) != fwd_pin;
                const int32_t n = need < 0 ? -need : need;
                if (n > capacity(rev))
                    over = true;
            }
            expected_overruns += over;
            int32_t before[6];
            memcpy(before, drv.pos, sizeof before);
            const uint8_t dir_before = drv.dir;
            TT_CHECK(stepgen_push(&sg, want) == 0);
            for (uint32_t t = 0; t < TICKS; ++t)
                tick();
            ++segments;
            TT_CHECK(sg.overruns == expected_overruns);
            for (int i = 0; i < 6; ++i) {
                const int32_t need = want[i] - before[i];
                const int32_t n = need < 0 ? -need : need;
                const bool rev = ((drv.dir ^ dir_before) >> i) & 1u;
                const int32_t cap = capacity(rev);
                const int32_t moved = drv.pos[i] - before[i];
                /* the capacity when more is asked (the maximum rate), else exactly the rest */
                const int32_t expect = n > cap ? (need > 0 ? cap : -cap) : need;
                TT_CHECKF(moved == expect, "config %u segment %u axis %d: moved %ld, expected %ld\n", c, segments,
                          i, (long)moved, (long)expect);
            }
            if (first) {
                TT_CHECK(sg.overruns == 1);
                first = false;
            }
            if (memcmp(drv.pos, want, sizeof want) == 0)
                break;
        }
        TT_CHECK(memcmp(drv.pos, want, sizeof want) == 0);
        TT_CHECK(segments == 3);
        TT_CHECK(expected_overruns == 2);
        /* On the setpoint it stays: the same setpoint again moves nothing. */
        const unsigned long pulses = drv.pulses;
        TT_CHECK(stepgen_push(&sg, want) == 0);
        for (uint32_t t = 0; t < 3 * TICKS; ++t)
            tick();
        TT_CHECK(drv.pulses == pulses && sg.overruns == expected_overruns);
        TT_CHECK(drv.mask_mismatch == 0);
        sh_printf("  set-up %2lu, interval %lu: capacity %ld (%ld on a reversal), %u overruns, on the "
                  "setpoint after %u segments\n",
                  (unsigned long)setup, (unsigned long)interval, (long)cf, (long)cr, expected_overruns, segments);
    }
}

/* The e-stop interrupt's half: no pulse from the next tick on, setpoints pushed meanwhile only
 * wait; the abort drops them and the count is what the driver saw. */
static void halt_stops_pulses(void)
{
    uint32_t setup, interval;
    board_config(&setup, &interval);
    start(setup, interval);
    const int32_t t1[6] = {150, -150, 150, -150, 150, -150};
    TT_CHECK(stepgen_push(&sg, t1) == 0);
    TT_CHECK(stepgen_push(&sg, t1) == 0);
    for (uint32_t t = 0; t < TICKS / 2; ++t)
        tick();
    TT_CHECK(drv.pulses > 0);
    stepgen_halt(&sg);
    const unsigned long pulses = drv.pulses;
    const int32_t t2[6] = {300, -300, 300, -300, 300, -300};
    TT_CHECK(stepgen_push(&sg, t2) == 0);
    for (uint32_t t = 0; t < 5 * TICKS; ++t)
        tick();
    TT_CHECK(drv.pulses == pulses);
    stepgen_abort(&sg);
    TT_CHECK(stepgen_idle(&sg));
    int32_t pos[6];
    stepgen_positions(&sg, pos);
    TT_CHECK(memcmp(pos, drv.pos, sizeof pos) == 0);
    for (uint32_t t = 0; t < 2 * TICKS; ++t)
        tick();
    TT_CHECK(drv.pulses == pulses);
    /* Stepping resumes from where the driver is. */
    TT_CHECK(stepgen_push(&sg, t1) == 0);
    for (uint32_t t = 0; t < TICKS; ++t)
        tick();
    TT_CHECK(memcmp(drv.pos, t1, sizeof t1) == 0);
}

int main(void)
{
    tt_begin("stepgen");
    tt_case("capacity by its definition", capacity_definition);
    tt_case("exact counts, straight line, spacing, DIR set-up over random setpoints", exact_random);
    tt_case("overrun counted, capacity emitted, the rest caught up", overrun_caught_up);
    tt_case("halt: no pulse from the next tick", halt_stops_pulses);
    tt_finish();
}

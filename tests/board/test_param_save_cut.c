/* Issue 9, "power cut during a parameter save", end to end: a controller (fw_controller) whose
 * hal_storage is the board's parameter log (param_log_hal) over the simulated F4 flash
 * (sim_flash.h).  A host changes a dozen parameters with PARAM_SET and sends PARAM_SAVE, all as
 * CAN frames; the power goes at every flash write operation of that save in turn (k = 1..N, N the
 * operations of the same save uncut); then a fresh controller boots with fw_init on the same
 * flash and the host reads every parameter back with PARAM_GET.  The set in force must be exactly
 * the previous saved set or exactly the new one, and a further save must work and survive
 * another boot.
 *
 * Independent of the code under test: the sets are known from what the host sent (and, for the
 * parameters it never sends, from what the first controller on blank flash reported); the frames
 * are decoded by hand from the layouts of docs/protocol.md; the operations a save costs come
 * from the record format of param_log.h and the parameter record of params.h, worked out below.
 *
 * The scenarios put the save where the log does different things: the first save on blank
 * flash, appends in the middle and at the very end of a sector, and saves that must start the
 * other sector (its erase and header are cut too), into a never-used sector and into one full of
 * older records, after a reboot and within one run. */
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "hal_stm32f4/param_log.h"
#include "harness.h"
#include "sim_flash.h"

/* The parameter record of params.h: magic (4), count and a spare byte (2), the values (4 each),
 * CRC (4).  In the log (param_log.h): a length word, a sequence word, the payload in whole
 * words, a CRC word. */
#define RECORD_BYTES (4u + 2u + 4u * FP_COUNT + 4u)
#define RECORD_WORDS (3u + (RECORD_BYTES + 3u) / 4u)
#define HEADER_WORDS 4u
#define SECTOR_WORDS (PARAM_LOG_SECTOR_BYTES / 4u)
/* Records of one run fit one after another after the header. */
#define PER_SECTOR ((SECTOR_WORDS - HEADER_WORDS) / RECORD_WORDS)
/* An append programs the record's words; starting a sector also erases it and writes its
 * header. */
#define OPS_APPEND RECORD_WORDS
#define OPS_START (1u + HEADER_WORDS + RECORD_WORDS)

/* Torn words and half-done erases come out differently per seed; an erase, the first operation
 * of a save that starts a sector, leaves more kinds of wreckage. */
#define SEEDS_PER_CUT 3u
#define SEEDS_PER_ERASE_CUT 16u

static const uint8_t FN_PARAM_SET = 0x10, FN_PARAM_SAVE = 0x11, FN_PARAM_VALUE = 0x27;
static const int32_t SAVE_MAGIC = 0x45564153; /* "SAVE" */

static sim_flash flash;  /* two 128 KiB sectors: static, not on the stack */
static sim_flash before; /* the flash a scenario starts every cut from */
static param_log plog;

/* ---- the parameter sets the host sends ---- */

/* The parameters the host changes, and how: set n gives parameter p the value
 * lo + (n % span) * step.  Spans above 2 make consecutive sets (and sets two apart) differ in
 * every one of them, so any mix of two of them is neither. */
static const struct {
    int id;
    int32_t lo, span, step;
} varied[] = {
    {FP_SLIDE_VMAX, 100000, 997, 50},      /* 0.100 .. 0.150 m/s */
    {FP_SLIDE_AMAX, 500000, 991, 1000},    /* 0.5 .. 1.49 m/s^2 */
    {FP_PLATE_VMAX, 200000, 983, 100},
    {FP_PLATE_AMAX, 500000, 977, 1000},
    {FP_PLATE_JMAX, 5000000, 971, 10000},
    {FP_PLATE_WMAX, 300000, 967, 300},
    {FP_PLATE_DWMAX, 1000000, 953, 1000},
    {FP_STEP_RATE_MAX, 150000, 947, 50},   /* 150 .. 197 kHz */
    {FP_WATCHDOG_MS, 100, 941, 10},
    {FP_TELEMETRY_MS, 20, 937, 1},
    {FP_HOMING_SPEED, 10000, 929, 10},
    {FP_MU_MIN, 30000, 919, 20},
    {FP_CAN_KBPS, 0, 3, 0},                /* 125, 250, 1000 in turn: see value_of */
};
#define NVARIED (sizeof varied / sizeof varied[0])

static fw_param_set baseline; /* what a controller on blank flash reports: set 0 */
static bool have_baseline;

static int32_t value_of(size_t i, uint32_t n)
{
    if (varied[i].id == FP_CAN_KBPS) {
        static const int32_t rates[3] = {125, 250, 1000};
        return rates[n % 3u];
    }
    return varied[i].lo + (int32_t)(n % (uint32_t)varied[i].span) * varied[i].step;
}

static fw_param_set set_of(uint32_t n)
{
    fw_param_set s = baseline;
    if (n > 0)
        for (size_t i = 0; i < NVARIED; ++i)
            s.v[varied[i].id] = value_of(i, n);
    return s;
}

/* ---- the host's side of the bus ---- */

static int32_t le32(const uint8_t *p)
{
    return (int32_t)((uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                     (uint32_t)p[3] << 24);
}

/* ACKs and REJECTs of `function` among the controller's frames, and the last reject's reason. */
static void answers(uint8_t function, unsigned *acks, unsigned *rejects, uint8_t *reason)
{
    *acks = *rejects = 0;
    for (unsigned i = 0; i < F.tx_count; ++i) {
        const hal_can_frame *f = &F.tx[i];
        if ((f->id >> 4) == 0x04 && f->data[0] == function)
            ++*acks;
        if ((f->id >> 4) == 0x03 && f->data[0] == function) {
            ++*rejects;
            *reason = f->data[2];
        }
    }
}

/* Every parameter, read with PARAM_GET. */
static fw_param_set read_all(void)
{
    F.tx_count = 0;
    for (int id = 0; id < FP_COUNT; ++id) {
        const int32_t v[1] = {id};
        send(PM_PARAM_GET, v);
    }
    fw_poll(C);
    fw_param_set s;
    bool seen[FP_COUNT] = {false};
    for (unsigned i = 0; i < F.tx_count; ++i) {
        const hal_can_frame *f = &F.tx[i];
        if ((f->id >> 4) != FN_PARAM_VALUE || (f->id & 0xFu) != 1u)
            continue;
        assert_int_equal(f->len, 6);
        const unsigned id = f->data[0] | f->data[1] << 8;
        assert_true(id < FP_COUNT);
        assert_false(seen[id]);
        seen[id] = true;
        s.v[id] = le32(&f->data[2]);
    }
    for (int id = 0; id < FP_COUNT; ++id)
        assert_true(seen[id]);
    return s;
}

/* PARAM_SET of every varied parameter to its value in set n; each must be taken. */
static void send_set(uint32_t n)
{
    F.tx_count = 0;
    for (size_t i = 0; i < NVARIED; ++i) {
        const int32_t v[2] = {varied[i].id, value_of(i, n)};
        send(PM_PARAM_SET, v);
    }
    fw_poll(C);
    unsigned acks, rejects;
    uint8_t reason = 0;
    answers(FN_PARAM_SET, &acks, &rejects, &reason);
    if (acks != NVARIED || rejects != 0)
        fail_msg("set %u: %u of %u PARAM_SETs taken, %u refused (reason %u)", n, acks,
                 (unsigned)NVARIED, rejects, reason);
}

/* PARAM_SAVE: 'a' acknowledged, 'r' refused for storage. */
static char save(void)
{
    F.tx_count = 0;
    const int32_t v[1] = {SAVE_MAGIC};
    send(PM_PARAM_SAVE, v);
    fw_poll(C);
    unsigned acks, rejects;
    uint8_t reason = 0;
    answers(FN_PARAM_SAVE, &acks, &rejects, &reason);
    assert_int_equal(acks + rejects, 1);
    if (rejects)
        assert_int_equal(reason, FW_REASON_STORAGE);
    return acks ? 'a' : 'r';
}

/* Power on (again): the flash works, and a fresh controller with a fresh log boots from it. */
static void boot(void)
{
    sim_flash_reboot(&flash);
    assert_int_equal(param_log_init(&plog, sim_flash_ops(&flash)), 0);
    fw_hal hal;
    fake_hal_init(&F, &hal);
    hal.storage = param_log_hal(&plog);
    restart(&hal);
    assert_int_equal(fw_state_of(C), FW_STATE_DISABLED);
}

/* Which of sets a and b s is: 'a', 'b', or a failure naming the parameters that are neither. */
static char which(const fw_param_set *s, uint32_t a, uint32_t b, const char *what)
{
    const fw_param_set sa = set_of(a), sb = set_of(b);
    if (memcmp(s, &sa, sizeof *s) == 0)
        return 'a';
    if (memcmp(s, &sb, sizeof *s) == 0)
        return 'b';
    char msg[1024];
    size_t len = 0;
    for (int id = 0; id < FP_COUNT && len < sizeof msg - 80; ++id)
        if (s->v[id] != sa.v[id] || s->v[id] != sb.v[id])
            len += (size_t)snprintf(msg + len, sizeof msg - len, " %s=%d (set %u: %d, set %u: %d)",
                                    fw_param_table[id].name, s->v[id], a, sa.v[id], b, sb.v[id]);
    fail_msg("%s: neither set %u nor set %u:%s", what, a, b, msg);
    return 0;
}

/* ---- the scenarios ---- */

typedef struct {
    const char *what;
    uint32_t prefill;   /* saves of sets 1..prefill in one run from blank flash */
    bool one_more;      /* after the boot, one more save in the same run before the cut one */
    uint32_t ops;       /* write operations of the save under test */
    int erased;         /* the sector that save erases, -1 if it only appends */
} scenario;

typedef struct {
    uint32_t cut_points, runs, in_erase, old_kept, new_taken, refused;
} tally;

static tally total;

static void run_scenario(const scenario *sc, uint32_t index)
{
    sim_flash_init(&flash, PARAM_LOG_SECTOR_BYTES, 1u + index);
    boot();
    if (!have_baseline) {
        baseline = read_all();
        have_baseline = true;
    } else {
        const fw_param_set b = read_all();
        assert_memory_equal(&b, &baseline, sizeof b);
    }
    for (uint32_t n = 1; n <= sc->prefill; ++n) {
        send_set(n);
        assert_int_equal(save(), 'a');
    }
    before = flash;

    const uint32_t prev = sc->prefill + (sc->one_more ? 1u : 0u), next = prev + 1u;
    /* The save under test, uncut: its cost, and where it goes. */
    boot();
    if (sc->one_more) {
        send_set(prev);
        assert_int_equal(save(), 'a');
    }
    send_set(next);
    const uint64_t ops0 = flash.ops;
    const uint32_t erases0[2] = {flash.erases[0], flash.erases[1]};
    assert_int_equal(save(), 'a');
    const uint32_t n_ops = (uint32_t)(flash.ops - ops0);
    assert_int_equal(n_ops, sc->ops);
    for (int s = 0; s < 2; ++s)
        assert_int_equal(flash.erases[s] - erases0[s], s == sc->erased ? 1u : 0u);
    boot();
    fw_param_set got = read_all();
    assert_int_equal(which(&got, next, next, "uncut save"), 'a');

    tally t = {0};
    for (uint32_t k = 1; k <= n_ops; ++k) {
        ++t.cut_points;
        const uint32_t seeds = sc->erased >= 0 && k == 1 ? SEEDS_PER_ERASE_CUT : SEEDS_PER_CUT;
        for (uint32_t seed = 0; seed < seeds; ++seed) {
            ++t.runs;
            flash = before;
            flash.rng = 0x9E3779B9u ^ (index << 24 | k << 4 | seed);
            boot();
            got = read_all();
            assert_int_equal(which(&got, sc->prefill, sc->prefill, "before the save"), 'a');
            if (sc->one_more) {
                send_set(prev);
                assert_int_equal(save(), 'a');
            }
            send_set(next);
            const uint32_t illegal0 = flash.illegal;
            sim_flash_cut_after(&flash, k);
            /* The cut operation fails, and nothing after it works: the host is told. */
            assert_int_equal(save(), 'r');
            assert_true(flash.cut_happened);
            t.in_erase += flash.cut_in_erase;

            boot();
            got = read_all();
            const char w = which(&got, prev, next, "after the cut");
            /* The record's CRC word is its last: before that is written nothing of the new
             * record can be taken. */
            if (w == 'b')
                assert_int_equal(k, n_ops);
            t.old_kept += w == 'a';
            t.new_taken += w == 'b';

            /* The controller goes on: a further save is taken and is what the next boot
             * finds. */
            send_set(next + 1u);
            assert_int_equal(save(), 'a');
            boot();
            got = read_all();
            assert_int_equal(which(&got, next + 1u, next + 1u, "the save after"), 'a');
            t.refused += flash.illegal - illegal0;
        }
    }
    assert_true(t.old_kept > 0);
    assert_true(t.in_erase == (sc->erased >= 0 ? SEEDS_PER_ERASE_CUT : 0u));
    print_message("%-58s %2u cut points (%u runs): previous set %3u, new set %u, cuts in an "
                  "erase %u, refused re-programs %u\n",
                  sc->what, t.cut_points, t.runs, t.old_kept, t.new_taken, t.in_erase, t.refused);
    total.cut_points += t.cut_points;
    total.runs += t.runs;
    total.in_erase += t.in_erase;
    total.old_kept += t.old_kept;
    total.new_taken += t.new_taken;
    total.refused += t.refused;
}

/* Record positions in one run from blank flash, from the format: record n (from 1) of the
 * first sector starts at word 4 + (n - 1) * RECORD_WORDS, and PER_SECTOR of them fit; the
 * next run appends one blank word after the last written one. */
static void test_power_cut_at_every_write_of_a_save(void **state)
{
    (void)state;
    print_message("a %u-byte parameter record: %u words in the log, %u records in a 128 KiB "
                  "sector\n",
                  (unsigned)RECORD_BYTES, (unsigned)RECORD_WORDS, (unsigned)PER_SECTOR);
    /* The third scenario needs room for the blank word a reboot leaves. */
    assert_true((SECTOR_WORDS - HEADER_WORDS) % RECORD_WORDS >= 1);
    const scenario scenarios[] = {
        {"first save on blank flash (erase sector 0)", 0, false, OPS_START, 0},
        {"append, middle of sector 0, after a reboot", 5, false, OPS_APPEND, -1},
        /* with 40-word records: 818 end at word 32724; after the blank word 32725 + 40 fits */
        {"append, last that fits in sector 0, after a reboot", PER_SECTOR - 1u, false, OPS_APPEND,
         -1},
        /* 819 end at 32764: no room, sector 1 (never used) is erased */
        {"sector 0 full, after a reboot (erase blank sector 1)", PER_SECTOR, false, OPS_START, 1},
        /* the 819th written after a reboot at 32725..32764, the 820th in the same run */
        {"sector 0 full, in the same run (erase blank sector 1)", PER_SECTOR - 1u, true, OPS_START,
         1},
        {"append in sector 1, sector 0 holding older records", PER_SECTOR + 1u, false, OPS_APPEND,
         -1},
        /* 819 in each sector: back to sector 0, erasing records 1..819 */
        {"sector 1 full (erase sector 0 of older records)", 2u * PER_SECTOR, false, OPS_START, 0},
    };
    for (uint32_t i = 0; i < sizeof scenarios / sizeof scenarios[0]; ++i)
        run_scenario(&scenarios[i], i);
    print_message("power cut at every write of a PARAM_SAVE: %u cut points, %u runs: previous "
                  "set %u times, new set %u times, never a mix or a corrupt set; %u cuts in an "
                  "erase; %u refused re-programs\n",
                  total.cut_points, total.runs, total.old_kept, total.new_taken, total.in_erase,
                  total.refused);
    assert_true(total.new_taken > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_power_cut_at_every_write_of_a_save),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

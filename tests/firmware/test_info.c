/* INFO_GET, INFO and BOARD (docs/protocol.md): in every state the controller acknowledges INFO_GET
 * page 0 and sends INFO right after, with the project's version and the rates it was configured
 * with, and nothing else changes; page 1 is answered by BOARD, the board's name in ASCII, NUL
 * padded; a page it does not have is refused `range` naming the page; a
 * configuration whose rates INFO cannot carry does not start.  The frames are written and read
 * here byte by byte, as docs/protocol.md lays them out, not through the codec; the version expected
 * is the project's as CMake gives this test (TSE_EXPECT_VERSION), the rates the harness's (1 kHz
 * segments, 100 kHz steps: harness.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fw/limits.h"
#include "harness.h"

#define NODE 1u
#define INFO_GET_ID (0x12u << 4 | NODE)
#define INFO_ID (0x29u << 4 | NODE)
#define ACK_ID (0x04u << 4 | NODE)
#define REJECT_ID (0x03u << 4 | NODE)
#define BOARD_ID (0x2Bu << 4 | NODE)

/* The eight bytes INFO must carry: the version's three parts, step_hz (u24), segment_hz (u16),
 * little-endian. */
static void expected_info(uint32_t step_hz, uint32_t segment_hz, uint8_t out[8])
{
    unsigned major, minor, patch;
    assert_int_equal(sscanf(TSE_EXPECT_VERSION, "%u.%u.%u", &major, &minor, &patch), 3);
    const uint8_t b[8] = {(uint8_t)major,         (uint8_t)minor,        (uint8_t)patch,
                          (uint8_t)step_hz,       (uint8_t)(step_hz >> 8), (uint8_t)(step_hz >> 16),
                          (uint8_t)segment_hz,    (uint8_t)(segment_hz >> 8)};
    memcpy(out, b, sizeof b);
}

/* The frames sent since `from` that are not periodic (STATUS 0x20, SLIDES and FK 0x21..0x26). */
static unsigned answers_since(const fake_hal *f, unsigned from, const hal_can_frame *out[], unsigned cap)
{
    unsigned n = 0;
    for (unsigned i = from; i < f->tx_count; ++i) {
        const unsigned fn = f->tx[i].id >> 4;
        if ((fn < 0x20 || fn > 0x26) && n < cap)
            out[n++] = &f->tx[i];
    }
    return n;
}

/* INFO_GET of page `page` fed to the harness's controller and polled once; its answers in out. */
static unsigned ask(uint8_t page, const hal_can_frame *out[4])
{
    const unsigned from = F.tx_count;
    fake_send(&F, INFO_GET_ID, 1, &page);
    fw_poll(C);
    return answers_since(&F, from, out, 4);
}

/* A controller of its own configured with cfg, asked INFO_GET of `page`: its answers in out. */
static unsigned ask_configured(const fw_config *cfg, uint8_t page, const hal_can_frame *out[4])
{
    static fake_hal f;
    static fw_controller_mem mem;
    fw_hal hal;
    fake_hal_init(&f, &hal);
    fw_controller *c = fw_init(&mem, &hal, cfg);
    assert_non_null(c);
    fake_send(&f, INFO_GET_ID, 1, &page);
    fw_poll(c);
    return answers_since(&f, 0, out, 4);
}

static void assert_ack_then_info(const hal_can_frame *const got[2], const uint8_t want[8])
{
    assert_int_equal(got[0]->id, ACK_ID);
    assert_int_equal(got[0]->data[0], 0x12); /* function */
    assert_int_equal(got[0]->data[1], 0);    /* seq: INFO_GET has none */
    assert_int_equal(got[1]->id, INFO_ID);
    assert_int_equal(got[1]->len, 8);
    assert_memory_equal(got[1]->data, want, 8);
}

/* What INFO_GET must leave as it was. */
static bool same(const fw_inspection *a, const fw_inspection *b)
{
    return a->state == b->state && a->fault == b->fault && a->pending_fault == b->pending_fault &&
           a->homed == b->homed && a->drives_on == b->drives_on && a->traj_depth == b->traj_depth &&
           a->last_seq == b->last_seq && a->any_commit == b->any_commit && a->stage_have == b->stage_have &&
           a->src == b->src && a->stopping == b->stopping && a->segments_run == b->segments_run &&
           a->heartbeat_us == b->heartbeat_us && memcmp(&a->params, &b->params, sizeof a->params) == 0;
}

static void answered_in_every_state_changing_nothing(void **state)
{
    (void)state;
    const fw_state states[] = {FW_STATE_DISABLED, FW_STATE_HOMING, FW_STATE_IDLE,  FW_STATE_MOVING,
                               FW_STATE_STOPPING, FW_STATE_FAULT,  FW_STATE_ESTOP};
    uint8_t want[8];
    expected_info(100000, 1000, want);
    for (size_t k = 0; k < sizeof states / sizeof states[0]; ++k) {
        reach(states[k]);
        const fw_inspection before = now();
        const hal_can_frame *got[4];
        const unsigned n = ask(0, got);
        if (n != 2)
            fail_msg("state %d: %u answers to INFO_GET, expected ACK and INFO", (int)states[k], n);
        assert_ack_then_info(got, want);
        const fw_inspection after = now();
        if (!same(&before, &after))
            fail_msg("INFO_GET changed the controller in state %d", (int)states[k]);
    }
}

static void a_page_it_does_not_have_is_refused_naming_the_page(void **state)
{
    (void)state;
    reach(FW_STATE_IDLE);
    for (unsigned page = 2; page <= 255; page += 253 / 2) { /* 2, 128, 254 */
        const hal_can_frame *got[4];
        assert_int_equal(ask((uint8_t)page, got), 1);
        assert_int_equal(got[0]->id, REJECT_ID);
        const uint8_t *r = got[0]->data;
        assert_int_equal(r[0], 0x12);             /* function */
        assert_int_equal(r[1], 0);                /* seq */
        assert_int_equal(r[2], FW_REASON_RANGE);  /* reason */
        assert_int_equal(r[5], 0);                /* field: the page */
    }
    /* Of another length: bad_length, no INFO. */
    const unsigned from = F.tx_count;
    const uint8_t two[2] = {0, 0};
    fake_send(&F, INFO_GET_ID, 2, two);
    fw_poll(C);
    const hal_can_frame *got[4];
    assert_int_equal(answers_since(&F, from, got, 4), 1);
    assert_int_equal(got[0]->id, REJECT_ID);
    assert_int_equal(got[0]->data[2], FW_REASON_BAD_LENGTH);
    /* Broadcast: nothing answers. */
    const unsigned from_b = F.tx_count;
    const uint8_t zero = 0;
    fake_send(&F, 0x12u << 4, 1, &zero);
    fw_poll(C);
    assert_int_equal(answers_since(&F, from_b, got, 4), 0);
}

/* A controller built with board name `name` (fw_config.board), asked INFO_GET page 1: ACK, then
 * BOARD with the eight bytes `want` (written here as docs/protocol.md lays BOARD out: one ASCII
 * character a byte, NUL after the name). */
static void assert_board_page(const char *name, const char want[8])
{
    const fw_config cfg = {NODE, 1000, 100000, NULL, NULL, name};
    const hal_can_frame *got[4];
    assert_int_equal(ask_configured(&cfg, 1, got), 2);
    assert_int_equal(got[0]->id, ACK_ID);
    assert_int_equal(got[0]->data[0], 0x12);
    assert_int_equal(got[1]->id, BOARD_ID);
    assert_int_equal(got[1]->len, 8);
    assert_memory_equal(got[1]->data, want, 8);
}

static void page_1_names_the_board(void **state)
{
    (void)state;
    assert_board_page("gen_f405", "gen_f405");             /* eight characters: no NUL */
    assert_board_page("tse-sim", "tse-sim\0");              /* seven, then one NUL */
    assert_board_page("ab", "ab\0\0\0\0\0\0");
    assert_board_page(NULL, "\0\0\0\0\0\0\0\0");          /* none given: an empty name */
    assert_board_page("stm32f4discovery", "stm32f4d"); /* longer: its first eight */
    assert_board_page("a\xC3\xA9" "b", "a\0\0\0\0\0\0\0");      /* not ASCII: the name ends there */
}

/* Page 1 is answered in every state too, and changes nothing. */
static void page_1_in_every_state_changing_nothing(void **state)
{
    (void)state;
    const fw_state states[] = {FW_STATE_DISABLED, FW_STATE_IDLE, FW_STATE_MOVING, FW_STATE_FAULT, FW_STATE_ESTOP};
    for (size_t k = 0; k < sizeof states / sizeof states[0]; ++k) {
        reach(states[k]);
        const fw_inspection before = now();
        const hal_can_frame *got[4];
        if (ask(1, got) != 2 || got[0]->id != ACK_ID || got[1]->id != BOARD_ID)
            fail_msg("state %d: INFO_GET page 1 not answered ACK then BOARD", (int)states[k]);
        const fw_inspection after = now();
        if (!same(&before, &after))
            fail_msg("INFO_GET page 1 changed the controller in state %d", (int)states[k]);
    }
}

/* A controller configured at other rates reports those. */
static void reports_the_rates_it_was_configured_with(void **state)
{
    (void)state;
    static const struct {
        uint32_t segment_hz, step_hz;
    } rates[] = {{2000, 200000}, {500, 100000}, {1000, 300000}};
    for (size_t i = 0; i < sizeof rates / sizeof rates[0]; ++i) {
        const fw_config cfg = {NODE, rates[i].segment_hz, rates[i].step_hz, NULL, NULL, NULL};
        const hal_can_frame *got[4];
        assert_int_equal(ask_configured(&cfg, 0, got), 2);
        uint8_t want[8];
        expected_info(rates[i].step_hz, rates[i].segment_hz, want);
        assert_ack_then_info(got, want);
    }
}

/* The rates a controller runs at: a control segment of whole microseconds and whole step
 * interrupts, each rate within INFO's field (step_hz up to 2^24 - 1, segment_hz up to 2^16 - 1); a
 * configuration outside them does not start. */
static void rates_info_cannot_carry_do_not_start(void **state)
{
    (void)state;
    static const struct {
        uint32_t step_hz, segment_hz;
        bool runs;
    } cases[] = {
        {16777215, 1, true},      {16777216, 1, false},   /* u24 */
        {62500, 62500, true},     {200000, 100000, false}, /* u16; 100 kHz would keep time */
        {200000, 1000, true},     {200000, 0, false},     {300000, 3000, false}, /* 333.3 us */
        {200500, 1000, false}, /* 200.5 step interrupts a segment */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        if (fw_rates_run((fw_rates){cases[i].step_hz, cases[i].segment_hz}) != cases[i].runs)
            fail_msg("%u Hz steps, %u Hz segments: expected %s", (unsigned)cases[i].step_hz,
                     (unsigned)cases[i].segment_hz, cases[i].runs ? "to run" : "refused");
    static fake_hal f;
    static fw_controller_mem mem;
    fw_hal hal;
    fake_hal_init(&f, &hal);
    const fw_config cfg = {NODE, 0, 200000, NULL, NULL, NULL};
    assert_null(fw_init(&mem, &hal, &cfg));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(answered_in_every_state_changing_nothing),
        cmocka_unit_test(a_page_it_does_not_have_is_refused_naming_the_page),
        cmocka_unit_test(reports_the_rates_it_was_configured_with),
        cmocka_unit_test(page_1_names_the_board),
        cmocka_unit_test(page_1_in_every_state_changing_nothing),
        cmocka_unit_test(rates_info_cannot_carry_do_not_start),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

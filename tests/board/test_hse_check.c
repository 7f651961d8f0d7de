/* The crystal's check (hal_stm32f4/hse_check.h) against a model of the two clocks: a 16-bit
 * timer counting a (possibly mistrimmed) HSI, capturing every HSE_CHECK_EDGES periods of a
 * crystal of a given frequency, each capture's edge displaced by jitter, looked at by polls a
 * given time apart with the board driver's rules (CC1IF, the read of CCR1 clearing it, CC1OF
 * when a capture comes before the last was read).  Frequencies are judged as the issue states
 * them: 8 MHz expected is kept with 8 and 7.9 MHz (1.25 % off), refused with 8.2 (2.5 %), 12 and
 * 25 MHz; no crystal is silent, within the time bound. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "hal_stm32f4/hse_check.h"

#define HSI_HZ 16000000.0

typedef struct {
    /* the clocks */
    double hse_hz;    /* the crystal; 0: none */
    double hsi_hz;    /* what the timer really counts */
    double jitter_s;  /* each capture's edge displaced by up to +- this */
    double poll_s;    /* between two polls */
    uint16_t cnt0;    /* the counter at time 0 */
    bool stuck;       /* the counter never moves, no capture comes (a timer not clocked) */
    /* the timer */
    double t;         /* now */
    uint64_t next;    /* the next capture's index */
    double next_t;    /* and its time, jitter included (drawn once) */
    bool cc1if, cc1of;
    uint16_t ccr1;
    uint32_t rng;
    uint32_t polls;
} model;

static double uniform(model *m) /* -1..1 */
{
    m->rng ^= m->rng << 13;
    m->rng ^= m->rng >> 17;
    m->rng ^= m->rng << 5;
    return (double)m->rng / 2147483647.5 - 1.0;
}

static uint16_t count_at(const model *m, double t)
{
    if (m->stuck)
        return 0;
    return (uint16_t)(m->cnt0 + (uint64_t)floor(t * m->hsi_hz));
}

/* The k-th capture: HSE_CHECK_EDGES crystal periods each, the first a quarter period in. */
static double capture_time(model *m, uint64_t k)
{
    const double period = HSE_CHECK_EDGES / m->hse_hz;
    return ((double)k + 0.25) * period + m->jitter_s * uniform(m);
}

static hse_poll poll(void *ctx, uint16_t *value)
{
    model *m = ctx;
    m->t += m->poll_s;
    ++m->polls;
    if (m->hse_hz > 0 && !m->stuck)
        for (; m->next_t <= m->t; m->next_t = capture_time(m, ++m->next)) {
            if (m->cc1if)
                m->cc1of = true;
            m->cc1if = true;
            m->ccr1 = count_at(m, m->next_t);
        }
    if (!m->cc1if) {
        *value = count_at(m, m->t);
        return HSE_POLL_NONE;
    }
    *value = m->ccr1;
    m->cc1if = false;
    if (m->cc1of) {
        m->cc1of = false;
        return HSE_POLL_MISSED;
    }
    return HSE_POLL_CAPTURE;
}

static model clocks(double hse_hz)
{
    model m;
    memset(&m, 0, sizeof m);
    m.hse_hz = hse_hz;
    m.hsi_hz = HSI_HZ;
    m.poll_s = 1e-6; /* 16 cycles at 16 MHz, as a poll of TIM11 takes on the board */
    m.cnt0 = 65000;  /* the counter wraps during the measurement */
    m.rng = 12345;
    return m;
}

static hse_check measure(model *m, uint32_t expected_hz)
{
    if (m->hse_hz > 0 && m->t == 0)
        m->next_t = capture_time(m, m->next);
    const hse_check_timer t = {poll, m};
    return hse_check_measure(&t, (uint32_t)HSI_HZ, expected_hz);
}

/* What hse_check_say says, collected. */
static char said[256];
static size_t said_len;

static void collect(const char *s)
{
    const size_t n = strlen(s);
    assert_true(said_len + n < sizeof said);
    memcpy(said + said_len, s, n + 1);
    said_len += n;
}

static const char *say(const hse_check *c)
{
    said_len = 0;
    said[0] = '\0';
    hse_check_say(c, collect);
    return said;
}

static void text_is(const hse_check *c, const char *want)
{
    assert_string_equal(say(c), want);
}

/* measured within `ticks` ticks of quantisation of what the HSI-based timer could say */
static void assert_measured(const hse_check *c, double want_hz, double ticks)
{
    const double rel = ticks / c->ticks;
    if (fabs(c->measured_hz - want_hz) > want_hz * rel)
        fail_msg("measured %u Hz, want %.0f Hz within %.1f ppm", (unsigned)c->measured_hz, want_hz, rel * 1e6);
}

/* ---- the arithmetic, by hand ---- */

static void counts_to_hz(void **state)
{
    (void)state;
    /* 248 x 32 periods of 8 MHz are 992 us: 15,872 ticks of 16 MHz. */
    assert_int_equal(hse_check_hz(16000000u, 32, 15872), 8000000u);
    assert_int_equal(hse_check_hz(16000000u, 32, 10581), 12000378u); /* 12 MHz: 10,581.33 ticks */
    assert_int_equal(hse_check_hz(16000000u, 32, 10582), 11999244u);
    assert_int_equal(hse_check_hz(16000000u, 32, 5079), 25000197u);  /* 25 MHz: 5,079.04 */
    assert_int_equal(hse_check_hz(16000000u, 1, 496), 8000000u);
    assert_int_equal(hse_check_hz(16000000u, 32, 0), 0u);
    assert_int_equal(hse_check_hz(16000000u, 32, 1), UINT32_MAX); /* saturates */
}

static void tolerance(void **state)
{
    (void)state;
    assert_int_equal(hse_check_judge(8000000u, 8000000u), HSE_CHECK_OK);
    assert_int_equal(hse_check_judge(8160000u, 8000000u), HSE_CHECK_OK); /* 2 % exactly */
    assert_int_equal(hse_check_judge(8160001u, 8000000u), HSE_CHECK_OFF);
    assert_int_equal(hse_check_judge(7840000u, 8000000u), HSE_CHECK_OK);
    assert_int_equal(hse_check_judge(7839999u, 8000000u), HSE_CHECK_OFF);
    assert_int_equal(hse_check_judge(7900000u, 8000000u), HSE_CHECK_OK);  /* 1.25 % */
    assert_int_equal(hse_check_judge(8200000u, 8000000u), HSE_CHECK_OFF); /* 2.5 % */
    assert_int_equal(hse_check_judge(12000000u, 8000000u), HSE_CHECK_OFF);
    assert_int_equal(hse_check_judge(0u, 8000000u), HSE_CHECK_OFF);
    assert_int_equal(hse_check_judge(UINT32_MAX, 26000000u), HSE_CHECK_OFF);
    assert_int_equal(hse_check_judge(25500000u, 25000000u), HSE_CHECK_OK);
    assert_int_equal(hse_check_judge(25500001u, 25000000u), HSE_CHECK_OFF);
}

/* ---- against the model ---- */

/* "crystal F MHz, expected 8.000 MHz" and the suffix: F to the kHz, within a kHz of want_hz
 * (a tick of quantisation is 63 ppm at 8 MHz, 94 at 12: 12 MHz may read 11.999). */
static void text_names(const hse_check *c, double want_hz, const char *expected, const char *suffix)
{
    const char *buf = say(c);
    char tail[64] = "";
    unsigned mhz = 0, khz = 0;
    char exp[16] = "";
    if (sscanf(buf, "crystal %u.%3u MHz, expected %15[0-9.] MHz%63[^\n]", &mhz, &khz, exp, tail) < 3)
        fail_msg("unexpected text '%s'", buf);
    assert_true(fabs((mhz * 1000.0 + khz) * 1e3 - want_hz) <= 1e3);
    assert_string_equal(exp, expected);
    assert_string_equal(tail, suffix);
}

/* 8 MHz expected: the cases. */
static void expected_8mhz(void **state)
{
    (void)state;
    static const char refused[] = ": on the internal oscillator";
    static const struct {
        double hse;
        hse_check_verdict v;
        const char *suffix;
    } cases[] = {
        {8.0e6, HSE_CHECK_OK, ""},          {7.9e6, HSE_CHECK_OK, ""},
        {8.2e6, HSE_CHECK_OFF, refused},    {12.0e6, HSE_CHECK_OFF, refused},
        {25.0e6, HSE_CHECK_OFF, refused},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        model m = clocks(cases[i].hse);
        const hse_check c = measure(&m, 8000000u);
        assert_int_equal(c.verdict, cases[i].v);
        assert_int_equal(c.expected_hz, 8000000u);
        assert_measured(&c, cases[i].hse, 1.0);
        text_names(&c, cases[i].hse, "8.000", cases[i].suffix);
        /* 33 captures of 248 periods: from the first look to the last capture */
        assert_true(m.t <= 34.0 * HSE_CHECK_EDGES / cases[i].hse + 2 * m.poll_s);
    }
}

/* The boards the descriptions will name: each crystal kept at its own frequency. */
static void other_crystals(void **state)
{
    (void)state;
    static const double f[] = {4e6, 8e6, 12e6, 16e6, 25e6, 26e6};
    for (size_t i = 0; i < sizeof f / sizeof f[0]; ++i) {
        model m = clocks(f[i]);
        const hse_check c = measure(&m, (uint32_t)f[i]);
        assert_int_equal(c.verdict, HSE_CHECK_OK);
        assert_measured(&c, f[i], 1.0);
    }
    /* 12 MHz expected: 8 MHz (an image for the E407 on an 8 MHz board) is refused too. */
    model m = clocks(8e6);
    const hse_check c = measure(&m, 12000000u);
    assert_int_equal(c.verdict, HSE_CHECK_OFF);
    text_names(&c, 8e6, "12.000", ": on the internal oscillator");
}

/* Every crystal from 4 to 26 MHz in steps of 10 kHz against 8 MHz: the verdict is the
 * frequency's own, but within a tick of quantisation of the 2 % edges. */
static void sweep(void **state)
{
    (void)state;
    for (double f = 4e6; f <= 26e6; f += 10e3) {
        model m = clocks(f);
        const hse_check c = measure(&m, 8000000u);
        assert_measured(&c, f, 1.0);
        const double off = fabs(f - 8e6) / 8e6;
        if (fabs(off - 0.02) > 1.0 / c.ticks)
            assert_int_equal(c.verdict, off > 0.02 ? HSE_CHECK_OFF : HSE_CHECK_OK);
    }
}

/* The HSI is the reference: 1 % off (its factory trim), it moves the measurement by 1 % the
 * other way, and an exact crystal is kept still. */
static void hsi_mistrimmed(void **state)
{
    (void)state;
    for (int sign = -1; sign <= 1; sign += 2) {
        model m = clocks(8e6);
        m.hsi_hz = HSI_HZ * (1.0 + sign * 0.01);
        const hse_check c = measure(&m, 8000000u);
        assert_int_equal(c.verdict, HSE_CHECK_OK);
        assert_measured(&c, 8e6 * HSI_HZ / m.hsi_hz, 1.0);
    }
    /* 1.25 % low and the HSI 1 % high: 2.2 % low as measured, refused. */
    model m = clocks(7.9e6);
    m.hsi_hz = HSI_HZ * 1.01;
    assert_int_equal(measure(&m, 8000000u).verdict, HSE_CHECK_OFF);
}

/* Jitter on every capture (up to +- 100 ns, 1.6 ticks): only the first and last captures count
 * in the sum, so the error stays within their jitter over the whole measurement. */
static void jitter(void **state)
{
    (void)state;
    static const double f[] = {8e6, 12e6, 25e6};
    for (size_t i = 0; i < sizeof f / sizeof f[0]; ++i)
        for (uint32_t seed = 1; seed <= 50; ++seed) {
            model m = clocks(f[i]);
            m.jitter_s = 100e-9;
            m.rng = seed * 2654435761u;
            m.poll_s = 0.3e-6 + 0.01e-6 * seed; /* polls not in step with the captures */
            const hse_check c = measure(&m, (uint32_t)f[i]);
            assert_int_equal(c.verdict, HSE_CHECK_OK);
            assert_measured(&c, f[i], 1.0 + 2.0 * 100e-9 * HSI_HZ);
        }
}

/* No crystal: silent once the limit has passed since the first look, 2 ms. */
static void no_signal(void **state)
{
    (void)state;
    model m = clocks(0);
    const hse_check c = measure(&m, 8000000u);
    assert_int_equal(c.verdict, HSE_CHECK_SILENT);
    assert_int_equal(c.measured_hz, 0u);
    assert_true(m.t > HSE_CHECK_LIMIT_TICKS / HSI_HZ);
    assert_true(m.t <= (HSE_CHECK_LIMIT_TICKS + 1) / HSI_HZ + 2 * m.poll_s); /* the first look, a poll late */
    text_is(&c, "crystal: no signal, expected 8.000 MHz: on the internal oscillator");
}

/* A crystal slower than the limit (100 kHz: 39,680 ticks a capture) is no signal either; one
 * just faster (125 kHz: 31,744) is measured, within the 68 ms bound. */
static void slowest_signal(void **state)
{
    (void)state;
    model m = clocks(100e3);
    assert_int_equal(measure(&m, 8000000u).verdict, HSE_CHECK_SILENT);
    assert_true(m.t < 2 * 39680 / HSI_HZ);

    m = clocks(125e3);
    const hse_check c = measure(&m, 8000000u);
    assert_int_equal(c.verdict, HSE_CHECK_OFF);
    assert_measured(&c, 125e3, 1.0);
    assert_true(m.t < 33.0 * (HSE_CHECK_LIMIT_TICKS + 1) / HSI_HZ);
    text_is(&c, "crystal 0.125 MHz, expected 8.000 MHz: on the internal oscillator");
}

/* A counter that never moves (TIM11 not clocked, reading 0): silent after the polls' bound. */
static void counter_stuck(void **state)
{
    (void)state;
    model m = clocks(8e6);
    m.stuck = true;
    assert_int_equal(measure(&m, 8000000u).verdict, HSE_CHECK_SILENT);
    assert_int_equal(m.polls, HSE_CHECK_POLLS_MAX);
}

/* Polls slower than the captures (a debugger's pause, an interrupt): a capture overwritten is
 * not taken for one interval. */
static void captures_missed(void **state)
{
    (void)state;
    model m = clocks(8e6);
    m.poll_s = 40e-6; /* a capture every 31 us */
    const hse_check c = measure(&m, 8000000u);
    assert_int_equal(c.verdict, HSE_CHECK_MISSED);
    text_is(&c, "crystal: captures missed, expected 8.000 MHz: on the internal oscillator");
    /* The first capture only needs to be the latest: an overcapture there is harmless. */
    m = clocks(8e6);
    m.poll_s = 40e-6;
    m.next_t = capture_time(&m, 0);
    uint16_t v;
    assert_int_equal(poll(&m, &v), HSE_POLL_MISSED); /* 40 us in: two captures came */
    m.poll_s = 1e-6;
    const hse_check again = measure(&m, 8000000u);
    assert_int_equal(again.verdict, HSE_CHECK_OK);
}

static void words(void **state)
{
    (void)state;
    const hse_check none = {HSE_CHECK_NOT_RUN, 0, 8000000u, 0};
    text_is(&none, "crystal not measured");
    const hse_check odd = {HSE_CHECK_OFF, 12345678u, 7999500u, 1};
    text_is(&odd, "crystal 12.346 MHz, expected 8.000 MHz: on the internal oscillator"); /* kHz, rounded */
    const hse_check ok = {HSE_CHECK_OK, 8000499u, 8000000u, 15872};
    text_is(&ok, "crystal 8.000 MHz, expected 8.000 MHz");
    const hse_check round_up = {HSE_CHECK_OFF, 9999500u, 8000000u, 12698};
    text_is(&round_up, "crystal 10.000 MHz, expected 8.000 MHz: on the internal oscillator");
    const hse_check silent = {HSE_CHECK_SILENT, 0, 25000000u, 0};
    text_is(&silent, "crystal: no signal, expected 25.000 MHz: on the internal oscillator");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(counts_to_hz),    cmocka_unit_test(tolerance),     cmocka_unit_test(expected_8mhz),
        cmocka_unit_test(other_crystals),  cmocka_unit_test(sweep),         cmocka_unit_test(hsi_mistrimmed),
        cmocka_unit_test(jitter),          cmocka_unit_test(no_signal),     cmocka_unit_test(slowest_signal),
        cmocka_unit_test(counter_stuck),   cmocka_unit_test(captures_missed), cmocka_unit_test(words),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The crystal's measurement and judgement (hal_stm32f4/hse_check.h): plain code, no register
 * access (the board's TIM11 side is hse_check_tim11.c). */
#include "hal_stm32f4/hse_check.h"

uint32_t hse_check_hz(uint32_t timer_hz, uint32_t intervals, uint32_t ticks)
{
    if (ticks == 0)
        return 0;
    /* 16 MHz x 248 x 32 = 1.3e11: 64 bits; the quotient fits 32 for any interval of a tick. */
    const uint64_t periods_x_hz = (uint64_t)timer_hz * HSE_CHECK_EDGES * intervals;
    const uint64_t hz = (periods_x_hz + ticks / 2u) / ticks;
    return hz > UINT32_MAX ? UINT32_MAX : (uint32_t)hz;
}

hse_check_verdict hse_check_judge(uint32_t measured_hz, uint32_t expected_hz)
{
    const uint64_t off = measured_hz > expected_hz ? measured_hz - expected_hz : expected_hz - measured_hz;
    return off * 100u > (uint64_t)expected_hz * HSE_CHECK_TOLERANCE_PCT ? HSE_CHECK_OFF : HSE_CHECK_OK;
}

static hse_check ended(hse_check_verdict v, uint32_t expected_hz, uint32_t ticks)
{
    const hse_check c = {v, 0, expected_hz, ticks};
    return c;
}

hse_check hse_check_measure(const hse_check_timer *t, uint32_t timer_hz, uint32_t expected_hz)
{
    uint16_t v = 0;
    hse_poll p = t->poll(t->ctx, &v);
    uint16_t mark = v;     /* the count the wait is timed from: the first look, then each capture */
    uint32_t captures = 0; /* taken; the first is the reference */
    uint32_t ticks = 0;
    for (uint32_t polls = 1;; ++polls) {
        const uint16_t since = (uint16_t)(v - mark);
        if (p == HSE_POLL_NONE) {
            if (since > HSE_CHECK_LIMIT_TICKS)
                return ended(HSE_CHECK_SILENT, expected_hz, ticks);
        } else {
            if (captures > 0) {
                /* A capture overwritten before it was read makes this interval two or more. */
                if (p == HSE_POLL_MISSED)
                    return ended(HSE_CHECK_MISSED, expected_hz, ticks);
                if (since > HSE_CHECK_LIMIT_TICKS)
                    return ended(HSE_CHECK_SILENT, expected_hz, ticks);
                ticks += since;
            }
            mark = v;
            if (++captures > HSE_CHECK_INTERVALS)
                break;
        }
        if (polls >= HSE_CHECK_POLLS_MAX)
            return ended(HSE_CHECK_SILENT, expected_hz, ticks);
        p = t->poll(t->ctx, &v);
    }
    const uint32_t hz = hse_check_hz(timer_hz, HSE_CHECK_INTERVALS, ticks);
    const hse_check c = {hse_check_judge(hz, expected_hz), hz, expected_hz, ticks};
    return c;
}

/* ---- the words ---- */

static void put_uint(void (*put)(const char *), uint32_t v, unsigned min_digits)
{
    char s[11];
    unsigned n = sizeof s - 1u;
    s[n] = '\0';
    do {
        s[--n] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v || sizeof s - 1u - n < min_digits);
    put(s + n);
}

/* "12.000 MHz": to the nearest kHz. */
static void put_mhz(void (*put)(const char *), uint32_t hz)
{
    const uint32_t khz = hz / 1000u + (hz % 1000u >= 500u);
    put_uint(put, khz / 1000u, 1);
    put(".");
    put_uint(put, khz % 1000u, 3);
    put(" MHz");
}

void hse_check_say(const hse_check *c, void (*put)(const char *s))
{
    static const char *const found[] = {
        [HSE_CHECK_NOT_RUN] = "crystal not measured", [HSE_CHECK_OK] = "crystal ",
        [HSE_CHECK_OFF] = "crystal ",                 [HSE_CHECK_SILENT] = "crystal: no signal",
        [HSE_CHECK_MISSED] = "crystal: captures missed",
    };
    put(found[c->verdict]);
    if (c->verdict == HSE_CHECK_NOT_RUN)
        return;
    if (c->verdict == HSE_CHECK_OK || c->verdict == HSE_CHECK_OFF)
        put_mhz(put, c->measured_hz);
    put(", expected ");
    put_mhz(put, c->expected_hz);
    if (c->verdict != HSE_CHECK_OK)
        put(": on the internal oscillator");
}

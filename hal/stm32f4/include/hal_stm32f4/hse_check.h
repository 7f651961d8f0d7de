/* The crystal checked at start-up: its frequency measured against the internal RC oscillator
 * (HSI, 16 MHz, factory-trimmed to 1 %) before the PLL is switched in, and judged against the
 * frequency the image was built for.  An image built for an 8 MHz crystal on a board with a
 * 12 MHz one would otherwise run its PLL 1.5 times too fast, and CAN at the wrong bit rate, with
 * no fault.
 *
 * The method (RM0090 section 7.2, "Internal/external clock measurement using TIM5/TIM11"):
 * TIM11 counts the HSI (SYSCLK, AHB and APB2 undivided, as after reset) and captures on channel
 * 1, whose input TI1 is remapped to HSE_RTC (TIM11_OR's TI1_RMP = 2, RM0090 section 19), the
 * crystal divided by RCC_CFGR's RTCPRE (RM0090 7.3.3).  With RTCPRE 31 (the largest: HSE_RTC
 * stays below 1 MHz for any crystal up to 31 MHz, the oscillator's 4..26 MHz included) and the
 * input-capture prescaler at 8, a capture comes every 248 crystal periods: 496 HSI ticks from
 * 8 MHz, 159 from 25 MHz.  The timer ticks between the first capture and the 33rd,
 * HSE_CHECK_INTERVALS of them, count 248 x 32 crystal periods: 15,872 ticks (1 ms) from 8 MHz,
 * so one tick of quantisation is 63 ppm (200 ppm from 25 MHz), far below the HSI's own 1 % and
 * the 2 % judged.
 *
 * Bounded: a capture interval longer than HSE_CHECK_LIMIT_TICKS (2 ms: a crystal below 121 kHz,
 * or none) ends the measurement as silent, and so does a counter that never moves (the polls are
 * counted too); the longest measurement a signal can keep going is 33 such limits, 68 ms.
 *
 * The arithmetic and the judgement (hse_check_measure and below) are plain code over a timer
 * reached through hse_check_timer, tested on the host against a model of the two clocks
 * (tests/board/test_hse_check.c); board_hse_check drives TIM11 on the board. */
#ifndef TSE_BOARD_HSE_CHECK_H
#define TSE_BOARD_HSE_CHECK_H

#include <stdint.h>

#define HSE_CHECK_RTCPRE 31u     /* HSE_RTC = HSE / 31 */
#define HSE_CHECK_IC_PSC 8u      /* a capture every 8 edges of HSE_RTC */
#define HSE_CHECK_EDGES (HSE_CHECK_RTCPRE * HSE_CHECK_IC_PSC) /* crystal periods a capture */
#define HSE_CHECK_INTERVALS 32u  /* capture intervals summed */
#define HSE_CHECK_LIMIT_TICKS 32768u /* the longest interval taken for a signal (< 65536) */
#define HSE_CHECK_POLLS_MAX 1000000u /* polls at most: over a second at 16 MHz */
#define HSE_CHECK_TOLERANCE_PCT 2u

typedef enum {
    HSE_CHECK_NOT_RUN = 0, /* not measured (the crystal never started) */
    HSE_CHECK_OK,          /* within HSE_CHECK_TOLERANCE_PCT of the expected frequency */
    HSE_CHECK_OFF,         /* measured more than HSE_CHECK_TOLERANCE_PCT off it */
    HSE_CHECK_SILENT,      /* no capture within the limit: no signal reaches the timer */
    HSE_CHECK_MISSED,      /* a capture came before the last was read: not measured */
} hse_check_verdict;

typedef struct {
    hse_check_verdict verdict;
    uint32_t measured_hz; /* with HSE_CHECK_OK and HSE_CHECK_OFF; 0 otherwise */
    uint32_t expected_hz;
    uint32_t ticks;       /* timer ticks over the intervals summed (for a debugger) */
} hse_check;

/* What one look at the capture timer found. */
typedef enum {
    HSE_POLL_NONE,    /* no capture since the last look: *value is the counter */
    HSE_POLL_CAPTURE, /* a capture: *value is the count it latched */
    HSE_POLL_MISSED,  /* a capture, and at least one before it that was never read */
} hse_poll;

typedef struct {
    hse_poll (*poll)(void *ctx, uint16_t *value);
    void *ctx;
} hse_check_timer;

/* The crystal's frequency from HSE_CHECK_EDGES x intervals crystal periods counted as `ticks`
 * ticks of a timer at timer_hz, rounded to the nearest Hz; 0 when ticks is 0. */
uint32_t hse_check_hz(uint32_t timer_hz, uint32_t intervals, uint32_t ticks);

/* HSE_CHECK_OFF when measured_hz is more than HSE_CHECK_TOLERANCE_PCT from expected_hz
 * (exactly 2 % is within), else HSE_CHECK_OK. */
hse_check_verdict hse_check_judge(uint32_t measured_hz, uint32_t expected_hz);

/* Measures the crystal through t, a 16-bit timer counting at timer_hz that captures every
 * HSE_CHECK_EDGES crystal periods, and judges it against expected_hz: the first capture is the
 * reference, the next HSE_CHECK_INTERVALS are summed (their counts differences modulo 2^16).
 * The counter is watched between captures: an interval beyond HSE_CHECK_LIMIT_TICKS, or
 * HSE_CHECK_POLLS_MAX polls in all, is HSE_CHECK_SILENT.  The polls must come less than
 * 65536 - HSE_CHECK_LIMIT_TICKS ticks apart (on the board: a few cycles). */
hse_check hse_check_measure(const hse_check_timer *t, uint32_t timer_hz, uint32_t expected_hz);

/* The check in words, handed to put piece by piece (board_bootline_puts on the board).  A fault
 * says what was found, what was expected and where the board stays:
 * "crystal 12.000 MHz, expected 8.000 MHz: on the internal oscillator",
 * "crystal: no signal, expected 8.000 MHz: on the internal oscillator"; frequencies to the
 * nearest kHz. */
void hse_check_say(const hse_check *c, void (*put)(const char *s));

/* On the board: measures the crystal (which must be running: HSERDY) with TIM11 against the
 * HSI, which must be the system clock with AHB and APB2 undivided (the reset clocks), and
 * judges it against expected_hz.  Leaves TIM11 off and RTCPRE as it found them. */
hse_check board_hse_check(uint32_t expected_hz);

#endif

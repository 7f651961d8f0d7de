#include "fault_spec.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "text.h"

const char fault_spec_help[] =
    "  --fault SPEC         inject faults between the firmware and the bus and plant, as\n"
    "                       comma-separated items, e.g. --fault drop=0.01,dup=0.01,seed=7:\n"
    "                         drop|dup|reorder|delay|corrupt=P  each frame to the controller\n"
    "                                  suffers at most one fault, this one with probability P\n"
    "                                  (0..1; together at most 1)\n"
    "                         delay_ms=N  how long delay holds a frame, and reorder at most\n"
    "                                  (1..60000, default 20)\n"
    "                         seed=N   seeds the random draws (default 1)\n"
    "                         silence=T[+D]  every host frame lost: from T s after the start,\n"
    "                                  for D s (no D: to the end)\n"
    "                         busoff=T[+D]   the CAN controller bus-off\n"
    "                         estop=T[+D]    the e-stop input open\n"
    "                         limit=K@T[+D]  slide K's (1..6) high-end limit switch pressed\n"
    "                         stall=K@T[+D]  slide K takes no step: the controller has no\n"
    "                                  position feedback and does not notice\n";

#define MAX_SECONDS 1e6
#define SPEC_MAX 512

static int fail(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return -1;
}

/* A whole number lo..hi written in decimal digits only. */
static int whole(const char *s, unsigned long long lo, unsigned long long hi, unsigned long long *out)
{
    if (*s < '0' || *s > '9')
        return -1;
    for (const char *p = s; *p; ++p)
        if (*p < '0' || *p > '9')
            return -1;
    errno = 0;
    const unsigned long long v = strtoull(s, NULL, 10);
    if (errno == ERANGE || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

/* "T" or "T+D" in seconds (the + of an exponent, as in 1e+3, is the number's). */
static int window(const char *s, fault_window *w)
{
    char buf[SPEC_MAX];
    snprintf(buf, sizeof buf, "%s", s);
    char *plus = NULL;
    for (char *p = buf + 1; *buf && *p; ++p)
        if (*p == '+' && p[-1] != 'e' && p[-1] != 'E') {
            plus = p;
            break;
        }
    double t, d = 0.0;
    if (plus)
        *plus = '\0';
    if (text_number(buf, &t) != 0 || t < 0.0 || t > MAX_SECONDS)
        return -1;
    if (plus && (text_number(plus + 1, &d) != 0 || !(d > 0.0) || t + d > MAX_SECONDS))
        return -1;
    w->from_us = (uint64_t)llround(t * 1e6);
    w->until_us = plus ? (uint64_t)llround((t + d) * 1e6) : FAULT_FOREVER;
    if (w->until_us <= w->from_us)
        return -1; /* shorter than a microsecond */
    return 0;
}

/* "K@T[+D]": slide K (1..6) and its window. */
static int slide_window(const char *s, int *slide, fault_window *w, const char **why)
{
    const char *at = strchr(s, '@');
    unsigned long long k;
    char num[8];
    *why = "expected K@T[+D]: a slide 1..6, then when";
    if (!at || at == s || (size_t)(at - s) >= sizeof num)
        return -1;
    memcpy(num, s, (size_t)(at - s));
    num[at - s] = '\0';
    if (whole(num, 1, 6, &k) != 0) {
        *why = "the slide is 1..6";
        return -1;
    }
    if (window(at + 1, w) != 0) {
        *why = "after @: T or T+D, seconds after the start (T >= 0, D > 0)";
        return -1;
    }
    *slide = (int)k - 1;
    return 0;
}

static const char *const prob_keys[FAULT_CAN_KINDS] = {"drop", "dup", "reorder", "delay", "corrupt"};

static const char *const keys[] = {"drop",  "dup",     "reorder", "delay",  "corrupt", "delay_ms",
                                   "seed",  "silence", "busoff",  "estop",  "limit",   "stall"};
#define NKEYS (sizeof keys / sizeof keys[0])

static int item(const char *key, const char *val, fault_plan *plan, char *err, size_t errlen)
{
    for (int k = 0; k < FAULT_CAN_KINDS; ++k) {
        if (strcmp(key, prob_keys[k]) != 0)
            continue;
        double p;
        if (text_number(val, &p) != 0 || p < 0.0 || p > 1.0)
            return fail(err, errlen, "'%s=%s': %s is a probability, 0..1", key, val, key);
        plan->can.p[k] = p;
        return 0;
    }
    unsigned long long n;
    if (!strcmp(key, "delay_ms")) {
        if (whole(val, 1, 60000, &n) != 0)
            return fail(err, errlen, "'%s=%s': delay_ms is a whole number of milliseconds, 1..60000", key, val);
        plan->can.delay_us = (uint32_t)n * 1000u;
        return 0;
    }
    if (!strcmp(key, "seed")) {
        if (whole(val, 0, UINT64_MAX, &n) != 0)
            return fail(err, errlen, "'%s=%s': seed is a whole number, 0..18446744073709551615", key, val);
        plan->can.seed = n;
        return 0;
    }
    fault_window *w = !strcmp(key, "silence") ? &plan->can.silence
                    : !strcmp(key, "busoff")  ? &plan->can.bus_off
                    : !strcmp(key, "estop")   ? &plan->inputs.estop
                                              : NULL;
    if (w) {
        if (window(val, w) != 0)
            return fail(err, errlen, "'%s=%s': expected T or T+D, seconds after the start (T >= 0, D > 0)", key, val);
        return 0;
    }
    int slide;
    const char *why;
    if (!strcmp(key, "limit")) {
        if (slide_window(val, &slide, &plan->inputs.limit, &why) != 0)
            return fail(err, errlen, "'%s=%s': %s", key, val, why);
        plan->inputs.limit_mask = (uint16_t)(1u << (8 + slide));
        return 0;
    }
    if (slide_window(val, &slide, &plan->stepper.stall, &why) != 0) /* stall: the last key */
        return fail(err, errlen, "'%s=%s': %s", key, val, why);
    plan->stepper.stall_mask = (uint8_t)(1u << slide);
    return 0;
}

int fault_spec_parse(const char *spec, fault_plan *plan, char *err, size_t errlen)
{
    memset(plan, 0, sizeof *plan);
    plan->can.seed = 1;
    plan->can.delay_us = 20000;
    if (strlen(spec) >= SPEC_MAX)
        return fail(err, errlen, "longer than %d characters", SPEC_MAX - 1);
    if (!*spec)
        return fail(err, errlen, "empty: give items such as drop=0.01,seed=7");
    char buf[SPEC_MAX];
    memcpy(buf, spec, strlen(spec) + 1);
    bool seen[NKEYS] = {false};
    char *rest = buf;
    for (;;) {
        char *comma = strchr(rest, ',');
        if (comma)
            *comma = '\0';
        if (!*rest)
            return fail(err, errlen, "an empty item (two commas, or one at an end)");
        char *eq = strchr(rest, '=');
        if (!eq)
            return fail(err, errlen, "'%s': expected KEY=VALUE", rest);
        *eq = '\0';
        size_t k = 0;
        while (k < NKEYS && strcmp(rest, keys[k]) != 0)
            ++k;
        if (k == NKEYS)
            return fail(err, errlen,
                        "unknown item '%s' (known: drop, dup, reorder, delay, corrupt, delay_ms, seed, silence, "
                        "busoff, estop, limit, stall)",
                        rest);
        if (seen[k])
            return fail(err, errlen, "'%s' given twice", rest);
        seen[k] = true;
        if (item(rest, eq + 1, plan, err, errlen) != 0)
            return -1;
        if (!comma)
            break;
        rest = comma + 1;
    }
    double sum = 0.0;
    for (int k = 0; k < FAULT_CAN_KINDS; ++k)
        sum += plan->can.p[k];
    if (sum > 1.0 + 1e-12)
        return fail(err, errlen, "drop, dup, reorder, delay and corrupt add up to %g: at most 1 (a frame suffers one fault at most)",
                    sum);
    return 0;
}

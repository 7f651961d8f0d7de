/* One value between text in a spelling's unit and the wire integer (param_text.h). */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "param_text_internal.h"
#include "text.h"

/* The power of ten that per_unit is (0 for 1, 6 for 1e6), or -1. */
static int decimal_places(double per_unit)
{
    double p = 1.0; /* exact: powers of ten up to 1e22 are doubles */
    for (int d = 0; d <= 9; ++d) {
        if (p == per_unit)
            return d;
        p *= 10.0;
    }
    return -1;
}

/* The wire integer nearest x units of k, if it is one that int32 holds. */
static int nearest_raw(const param_key *k, double x, double *r)
{
    *r = round(x * k->per_unit);
    return *r >= (double)INT32_MIN && *r <= (double)INT32_MAX;
}

const char *param_to_text(const param_key *k, int32_t raw, char *buf, size_t cap)
{
    const int places = decimal_places(k->per_unit);
    if (places >= 0) {
        /* Exact: the integer's digits with the point moved. */
        int64_t scale = 1;
        for (int i = 0; i < places; ++i)
            scale *= 10;
        const int64_t m = raw < 0 ? -(int64_t)raw : (int64_t)raw;
        char frac[12] = ""; /* '.', at most 9 digits, NUL */
        if (m % scale) {
            int64_t r = m % scale;
            frac[0] = '.';
            for (int i = places; i >= 1; --i, r /= 10)
                frac[i] = (char)('0' + r % 10);
            frac[places + 1] = '\0';
            for (char *e = frac + places; *e == '0'; --e)
                *e = '\0';
        }
        snprintf(buf, cap, "%s%lld%s", raw < 0 ? "-" : "", (long long)(m / scale), frac);
        return buf;
    }
    /* Fixed notation, as few decimals as turn back into raw. */
    const double x = (double)raw / k->per_unit;
    for (int d = 0; d <= 17; ++d) {
        char t[64];
        snprintf(t, sizeof t, "%.*f", d, x);
        double back, r;
        if (text_value(t, &back) == 0 && nearest_raw(k, back, &r) && r == (double)raw) {
            snprintf(buf, cap, "%s", t);
            return buf;
        }
    }
    snprintf(buf, cap, "%.17g", x);
    return buf;
}

const char *param_value_words(const param_key *k, int32_t raw, char *buf, size_t cap)
{
    char v[64];
    snprintf(buf, cap, "%s%s%s", param_to_text(k, raw, v, sizeof v), *k->unit ? " " : "", k->unit);
    return buf;
}

/* A range's end in k's unit, in as few digits as stay inside the range (side -1: the low end, 1:
 * the high one): in degrees, "90" would round to the high end of eta's range yet lie outside it. */
static const char *bound_text(const param_key *k, int32_t raw, int side, char *buf, size_t cap)
{
    param_to_text(k, raw, buf, cap);
    double x;
    for (int d = 1; d <= 17 && text_value(buf, &x) == 0 && side * (x * k->per_unit - raw) > 0; ++d)
        snprintf(buf, cap, "%.*g", d, (double)raw / k->per_unit);
    return buf;
}

void param_range_error(const param_key *k, double raw, const char *shown, char *err, size_t errlen)
{
    const fw_param_def *d = &fw_param_table[k->id];
    const char *sp = *k->unit ? " " : "";
    if (k->id == FP_CAN_KBPS && raw >= d->min && raw <= d->max) {
        snprintf(err, errlen, "%s = %s%s%s is not one of the rates 125, 250, 500, 1000 kbit/s", d->name, shown, sp,
                 k->unit);
        return;
    }
    char lo[64], hi[64];
    bound_text(k, d->min, -1, lo, sizeof lo);
    bound_text(k, d->max, 1, hi, sizeof hi);
    snprintf(err, errlen, "%s = %s%s%s is outside %s..%s%s%s", d->name, shown, sp, k->unit, lo, hi, sp, k->unit);
}

int param_number_from_text(const param_key *k, const char *text, char *err, size_t errlen)
{
    double x;
    /* The number rule of every host reader (text.h): 1e-400 is no more a 0 here than 1e400 is big. */
    if (text_value(text, &x) != 0) {
        snprintf(err, errlen, "%s: '%.40s' is not one finite number%s%s%s", fw_param_table[k->id].name, text,
                 *k->unit ? " (in " : "", k->unit, *k->unit ? ")" : "");
        return -1;
    }
    return 0;
}

int param_from_text(const param_key *k, const char *text, int32_t *raw, char *err, size_t errlen)
{
    const fw_param_def *d = &fw_param_table[k->id];
    double x, r;
    if (param_number_from_text(k, text, err, errlen) != 0 || text_value(text, &x) != 0)
        return -1;
    /* Shown as given (blanks aside): the writer recognises their own number. */
    while (isspace((unsigned char)*text))
        ++text;
    size_t n = strlen(text);
    while (n && isspace((unsigned char)text[n - 1]))
        --n;
    char shown[48];
    snprintf(shown, sizeof shown, "%.*s", (int)(n < 40 ? n : 40), text);
    /* The range holds for the value as written, before rounding to the wire's unit: what the
     * message says, and what lets tse-kin compute with the written value (kin_params_file.h). */
    const double exact = x * k->per_unit;
    if (!(exact >= (double)d->min && exact <= (double)d->max) || !nearest_raw(k, x, &r) ||
        !fw_param_value_ok((uint16_t)k->id, (int32_t)r)) {
        param_range_error(k, exact, shown, err, errlen);
        return -1;
    }
    *raw = (int32_t)r;
    return 0;
}

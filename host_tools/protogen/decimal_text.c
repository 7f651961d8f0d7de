/* Exact decimal text for the DBC and the docs.  See decimal_text.h. */
#include "decimal_text.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define MAX_SIG 17 /* a double needs at most 17 significant digits to read back exactly */

/* The shortest "%.*e" text of x: its digits (most significant first) and the power of ten of
 * the last one, so that |x| reads as digits x 10^exp10. */
static int shortest_digits(double x, int *negative, int digits[MAX_SIG], int *ndigits, int *exp10)
{
    char buf[40];
    int p = 1;
    for (;; ++p) {
        snprintf(buf, sizeof buf, "%.*e", p - 1, x);
        if (strtod(buf, NULL) == x || p == MAX_SIG)
            break;
    }
    const char *s = buf;
    *negative = *s == '-';
    if (*negative)
        ++s;
    int n = 0;
    for (; *s && *s != 'e'; ++s)
        if (*s >= '0' && *s <= '9')
            digits[n++] = *s - '0';
    if (*s != 'e' || n == 0)
        return -1;
    *ndigits = n;
    *exp10 = (int)strtol(s + 1, NULL, 10) - (n - 1);
    return 0;
}

int dec_shortest(double x, char *out, size_t n)
{
    if (!isfinite(x))
        return -1;
    char buf[40];
    for (int p = 1; p <= MAX_SIG; ++p) {
        snprintf(buf, sizeof buf, "%.*g", p, x);
        if (strtod(buf, NULL) == x)
            break;
    }
    const int len = snprintf(out, n, "%s", buf);
    return len < 0 || (size_t)len >= n ? -1 : 0;
}

typedef struct {
    char *p;
    size_t left;
} sink;

static int put(sink *s, char c)
{
    if (s->left < 2)
        return -1;
    *s->p++ = c;
    *s->p = '\0';
    --s->left;
    return 0;
}

int dec_scaled(int64_t raw, double scale, char *out, size_t n)
{
    if (n == 0 || !isfinite(scale))
        return -1;
    out[0] = '\0';
    int neg_scale, sd[MAX_SIG], nsd, exp10;
    if (shortest_digits(scale, &neg_scale, sd, &nsd, &exp10) != 0)
        return -1;

    /* |raw| as decimal digits, least significant first (INT64_MIN has no positive int64). */
    uint64_t mag = raw < 0 ? (uint64_t)0 - (uint64_t)raw : (uint64_t)raw;
    int rd[20], nrd = 0;
    do {
        rd[nrd++] = (int)(mag % 10u);
        mag /= 10u;
    } while (mag);

    /* Schoolbook product, least significant digit first. */
    int prod[20 + MAX_SIG] = {0};
    const int nprod = nrd + nsd;
    for (int i = 0; i < nrd; ++i)
        for (int j = 0; j < nsd; ++j)
            prod[i + j] += rd[i] * sd[nsd - 1 - j];
    for (int k = 0; k + 1 < nprod; ++k) {
        prod[k + 1] += prod[k] / 10;
        prod[k] %= 10;
    }
    int top = nprod - 1;
    while (top > 0 && prod[top] == 0)
        --top;
    const int zero = top == 0 && prod[0] == 0;

    sink s = {out, n};
    if (!zero && (raw < 0) != neg_scale && put(&s, '-') != 0)
        return -1;
    if (zero)
        return put(&s, '0');
    if (exp10 >= 0) {
        for (int k = top; k >= 0; --k)
            if (put(&s, (char)('0' + prod[k])) != 0)
                return -1;
        for (int k = 0; k < exp10; ++k)
            if (put(&s, '0') != 0)
                return -1;
        return 0;
    }
    /* exp10 < 0: the lowest -exp10 digits are the fraction; drop its trailing zeros. */
    const int frac = -exp10;
    int low = 0;
    while (low < frac && low <= top && prod[low] == 0)
        ++low;
    if (top < frac && put(&s, '0') != 0)
        return -1;
    for (int k = top; k >= frac; --k)
        if (put(&s, (char)('0' + prod[k])) != 0)
            return -1;
    if (low < frac) {
        if (put(&s, '.') != 0)
            return -1;
        for (int k = frac - 1; k >= low; --k)
            if (put(&s, (char)(k <= top ? '0' + prod[k] : '0')) != 0)
                return -1;
    }
    return 0;
}

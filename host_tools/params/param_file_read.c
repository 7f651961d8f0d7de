/* Reading a parameter text file (param_text.h): every line is judged before anything is adopted. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "param_text_internal.h"
#include "text.h"

/* Far beyond any parameter file (every parameter with its comments is a few kilobytes): a
 * bigger file is something else. */
#define MAX_BYTES (256 * 1024)

typedef struct {
    const char *path;
    int judged; /* the values by the controller's ranges and rules, not only as numbers */
    param_reading next;
    const char *key[FP_COUNT]; /* how each parameter was spelled where it was set */
    char *err;
    size_t errlen;
} reading;


/* The text of path, or NULL with the message; *unreadable says whether it could not be read at
 * all (rather than read and found not to be a parameter text file). */
static char *file_text(const char *path, int *unreadable, char *err, size_t errlen)
{
    *unreadable = 1;
    FILE *f = fopen(path, "rb");
    if (!f) {
        snprintf(err, errlen, "%s: cannot open: %s", path, strerror(errno));
        return NULL;
    }
    char *text = malloc(MAX_BYTES + 1);
    const size_t n = text ? fread(text, 1, MAX_BYTES + 1, f) : 0;
    const int read_errno = errno;
    const int failed = ferror(f);
    (void)fclose(f); /* read only: the read's error is the one that counts */
    *unreadable = !text || failed;
    const char *why = !text ? "out of memory"
                      : failed ? strerror(read_errno)
                      : n > MAX_BYTES ? "larger than 256 KiB: not a parameter text file"
                      : memchr(text, '\0', n) ? "contains a NUL byte: not a parameter text file (an old binary record?)"
                                              : NULL;
    if (why) {
        snprintf(err, errlen, "%s: %s", path, why);
        free(text);
        return NULL;
    }
    text[n] = '\0';
    return text;
}

char *param_file_text(const char *path, char *err, size_t errlen)
{
    int unreadable;
    return file_text(path, &unreadable, err, errlen);
}

/* One line, comment and blanks included; 0, or -1 with "PATH:LINE: ..." in err. */
static int take_line(reading *r, char *line, int lineno)
{
    char *hash = strchr(line, '#');
    if (hash)
        *hash = '\0';
    line = text_trim(line);
    if (!*line)
        return 0;
    char *eq = strchr(line, '=');
    if (!eq) {
        snprintf(r->err, r->errlen, "%s:%d: expected 'name = value', got '%.40s'", r->path, lineno, line);
        return -1;
    }
    *eq = '\0';
    const char *name = text_trim(line), *value = text_trim(eq + 1);
    param_key k;
    if (!*name) {
        snprintf(r->err, r->errlen, "%s:%d: no parameter name before '='", r->path, lineno);
        return -1;
    }
    if (param_lookup(name, &k) != 0) {
        snprintf(r->err, r->errlen, "%s:%d: unknown parameter '%.40s'", r->path, lineno, name);
        return -1;
    }
    if (r->next.line[k.id]) {
        snprintf(r->err, r->errlen, "%s:%d: %s given twice (first on line %d as %s)", r->path, lineno, name,
                 r->next.line[k.id], r->key[k.id]);
        return -1;
    }
    char why[200];
    double written;
    if (r->judged ? param_from_text(&k, value, &r->next.set.v[k.id], why, sizeof why) != 0
                  : param_number_from_text(&k, value, why, sizeof why) != 0) {
        snprintf(r->err, r->errlen, "%s:%d: %s", r->path, lineno, why);
        return -1;
    }
    (void)text_value(value, &written); /* a number: just checked */
    const int degrees = !strcmp(k.unit, "deg");
    r->next.si[k.id] = degrees ? written * (PARAM_PI / 180.0) : written;
    r->next.line[k.id] = lineno;
    r->next.degrees[k.id] = degrees;
    r->key[k.id] = name;
    return 0;
}

/* The whole set, judged as the controller judges it (at its rates). */
static int take_set(reading *r, const fw_param_set *before)
{
    const fw_param_fault f = fw_params_judge_config(&r->next.set, r->next.rates.step_hz, r->next.rates.segment_hz);
    if (f.rule == FW_RULE_NONE)
        return 0;
    char why[400];
    param_explain_fault(&r->next.set, f, r->next.rates, why, sizeof why);
    const int bad = f.id;
    if (bad < 0)
        snprintf(r->err, r->errlen, "%s: %s", r->path, why);
    else if (r->next.line[bad])
        snprintf(r->err, r->errlen, "%s:%d: %s", r->path, r->next.line[bad], why);
    else
        snprintf(r->err, r->errlen, "%s: %s (%s is not set in the file: its %s is what is in conflict)", r->path,
                 why, fw_param_table[bad].name,
                 before->v[bad] == fw_param_table[bad].def ? "default" : "value before reading");
    return -1;
}

void param_reading_start(param_reading *r, const fw_param_set *base)
{
    memset(r, 0, sizeof *r);
    r->set = *base;
    r->rates = FW_RATES_BUILT_IN;
    for (int id = 0; id < FP_COUNT; ++id) {
        param_key k;
        param_si_key(id, &k);
        r->si[id] = (double)base->v[id] / k.per_unit;
    }
}

static int read_text(char *text, const char *name, int judged, param_reading *out, char *err, size_t errlen)
{
    reading r;
    memset(&r, 0, sizeof r);
    r.path = name;
    r.judged = judged;
    param_reading_start(&r.next, &out->set);
    r.next.rates = out->rates;
    r.err = err;
    r.errlen = errlen;
    char *cur = text;
    if (!strncmp(cur, "\xEF\xBB\xBF", 3))
        cur += 3;
    int rc = 0;
    for (int lineno = 1; rc == 0 && *cur; ++lineno) {
        char *nl = strchr(cur, '\n');
        if (nl)
            *nl = '\0';
        rc = take_line(&r, cur, lineno);
        cur = nl ? nl + 1 : cur + strlen(cur);
    }
    if (rc == 0 && judged)
        rc = take_set(&r, &out->set);
    if (rc == 0)
        *out = r.next;
    return rc;
}

int param_text_read(char *text, const char *name, param_reading *r, char *err, size_t errlen)
{
    return read_text(text, name, 1, r, err, errlen);
}

int param_text_scan(char *text, const char *name, param_reading *r, char *err, size_t errlen)
{
    return read_text(text, name, 0, r, err, errlen);
}

/* The file at path through one of the two. */
static int read_file(const char *path, int judged, param_reading *r, char *err, size_t errlen)
{
    int unreadable;
    char *text = file_text(path, &unreadable, err, errlen);
    if (!text)
        return unreadable ? -2 : -1;
    const int rc = read_text(text, path, judged, r, err, errlen);
    free(text);
    return rc;
}

int param_file_read_full(const char *path, param_reading *r, char *err, size_t errlen)
{
    return read_file(path, 1, r, err, errlen);
}

int param_file_scan(const char *path, param_reading *r, char *err, size_t errlen)
{
    return read_file(path, 0, r, err, errlen);
}

int param_file_read(const char *path, fw_param_set *s, fw_rates rates, char *err, size_t errlen)
{
    param_reading r;
    param_reading_start(&r, s);
    r.rates = rates;
    if (param_file_read_full(path, &r, err, errlen) != 0)
        return -1;
    *s = r.set;
    return 0;
}

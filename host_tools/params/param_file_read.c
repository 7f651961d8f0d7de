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
    fw_param_set next;
    int line[FP_COUNT];        /* where each parameter was set (0: not in the file) */
    const char *key[FP_COUNT]; /* and how it was spelled there */
    char *err;
    size_t errlen;
} reading;


char *param_file_text(const char *path, char *err, size_t errlen)
{
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
    if (r->line[k.id]) {
        snprintf(r->err, r->errlen, "%s:%d: %s given twice (first on line %d as %s)", r->path, lineno, name,
                 r->line[k.id], r->key[k.id]);
        return -1;
    }
    char why[200];
    if (param_from_text(&k, value, &r->next.v[k.id], why, sizeof why) != 0) {
        snprintf(r->err, r->errlen, "%s:%d: %s", r->path, lineno, why);
        return -1;
    }
    r->line[k.id] = lineno;
    r->key[k.id] = name;
    return 0;
}

/* The whole set, judged as the controller judges it (at its rates). */
static int take_set(reading *r, const fw_param_set *before)
{
    const fw_param_fault f = fw_params_judge_config(&r->next, FW_STEP_HZ, FW_SEGMENT_HZ);
    if (f.rule == FW_RULE_NONE)
        return 0;
    char why[400];
    param_explain_fault(&r->next, f, why, sizeof why);
    const int bad = f.id;
    if (bad < 0)
        snprintf(r->err, r->errlen, "%s: %s", r->path, why);
    else if (r->line[bad])
        snprintf(r->err, r->errlen, "%s:%d: %s", r->path, r->line[bad], why);
    else
        snprintf(r->err, r->errlen, "%s: %s (%s is not set in the file: its %s is what is in conflict)", r->path,
                 why, fw_param_table[bad].name,
                 before->v[bad] == fw_param_table[bad].def ? "default" : "value before reading");
    return -1;
}

int param_file_read(const char *path, fw_param_set *s, char *err, size_t errlen)
{
    reading r;
    memset(&r, 0, sizeof r);
    r.path = path;
    r.next = *s;
    r.err = err;
    r.errlen = errlen;
    char *text = param_file_text(path, err, errlen);
    if (!text)
        return -1;
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
    if (rc == 0)
        rc = take_set(&r, s);
    if (rc == 0)
        *s = r.next;
    free(text);
    return rc;
}

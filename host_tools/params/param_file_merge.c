/* A user's parameter file with a set's values written into it (param_text_internal.h): every
 * byte the user wrote stays but the values that change, and what the file does not set is
 * appended. */
#define _POSIX_C_SOURCE 200809L /* strndup */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "param_text_internal.h"
#include "line_reader.h"

typedef struct {
    char *p;
    size_t n, cap;
    int failed;
} out_text;

static void put(out_text *o, const char *s, size_t n)
{
    if (o->failed)
        return;
    if (o->n + n + 1 > o->cap) {
        size_t cap = o->cap ? o->cap : 4096;
        while (o->n + n + 1 > cap)
            cap *= 2;
        char *p = realloc(o->p, cap);
        if (!p) {
            o->failed = 1;
            return;
        }
        o->p = p;
        o->cap = cap;
    }
    if (!o->p) { /* (not reached: the first put allocates) */
        o->failed = 1;
        return;
    }
    memcpy(o->p + o->n, s, n);
    o->n += n;
    o->p[o->n] = '\0';
}

static void puts_text(out_text *o, const char *s)
{
    put(o, s, strlen(s));
}

/* As text_trim (param_file_read) sees blanks. */
static int is_blank(char c)
{
    return isspace((unsigned char)c);
}

/* One line (line[0..len), its end excluded): copied as it is, or with its value replaced by s's
 * when it reads back to another.  Marks the parameter it sets in `set`. */
static void merge_line(out_text *o, const char *line, size_t len, const fw_param_set *s, int set[FP_COUNT])
{
    const char *hash = memchr(line, '#', len);
    const size_t code = hash ? (size_t)(hash - line) : len;
    const char *eq = memchr(line, '=', code);
    if (!eq) {
        put(o, line, len);
        return;
    }
    /* The key and the value without the blanks around them, as param_file_read takes them. */
    size_t k0 = 0, k1 = (size_t)(eq - line), v0 = k1 + 1, v1 = code;
    while (k0 < k1 && is_blank(line[k0]))
        ++k0;
    while (k1 > k0 && is_blank(line[k1 - 1]))
        --k1;
    while (v0 < v1 && is_blank(line[v0]))
        ++v0;
    while (v1 > v0 && is_blank(line[v1 - 1]))
        --v1;
    /* The line copied once, key and value cut in place: as long as the reader takes them (a
     * value may be any length: leading zeros, long digits). */
    char *copy = strndup(line, len);
    param_key k;
    int32_t raw;
    char err[256];
    int known = 0;
    if (copy) {
        copy[k1] = '\0'; /* k1 <= the '=' < v0: the value is untouched */
        copy[v1] = '\0';
        known = param_lookup(copy + k0, &k) == 0 && param_from_text(&k, copy + v0, &raw, err, sizeof err) == 0;
        free(copy);
    } else {
        o->failed = 1;
    }
    if (!known) {
        put(o, line, len); /* not reached for a file that reads */
        return;
    }
    set[k.id] = 1;
    if (raw == s->v[k.id]) {
        put(o, line, len);
        return;
    }
    char v[64];
    put(o, line, v0);
    puts_text(o, param_to_text(&k, s->v[k.id], v, sizeof v));
    put(o, line + v1, len - v1);
}

char *param_file_merged(const char *text, const fw_param_set *s)
{
    out_text o = {0};
    int set[FP_COUNT] = {0};
    const size_t bom = utf8_bom_length(text, strlen(text));
    put(&o, text, bom);
    const char *eol = "\n";
    const char *cur = text + bom;
    while (*cur) {
        const char *nl = strchr(cur, '\n');
        const size_t len = nl ? (size_t)(nl - cur) : strlen(cur);
        /* A CRLF line keeps its CR outside what is merged, and says how the file ends lines. */
        const size_t body = len > 0 && cur[len - 1] == '\r' ? len - 1 : len;
        if (body < len)
            eol = "\r\n";
        merge_line(&o, cur, body, s, set);
        put(&o, cur + body, len - body);
        if (!nl)
            break;
        puts_text(&o, "\n");
        cur = nl + 1;
    }
    int missing = 0;
    for (int id = 0; id < FP_COUNT; ++id)
        missing += !set[id] && s->v[id] != fw_param_table[id].def;
    if (missing) {
        if (o.n > bom && o.p[o.n - 1] != '\n')
            puts_text(&o, eol);
        if (o.n > bom)
            puts_text(&o, eol);
        puts_text(&o, "# Saved by the controller (PARAM_SAVE): values this file did not set");
        puts_text(&o, eol);
        for (int id = 0; id < FP_COUNT; ++id) {
            if (set[id] || s->v[id] == fw_param_table[id].def)
                continue;
            char line[160];
            param_line_text(s, id, line, sizeof line);
            puts_text(&o, line);
            puts_text(&o, eol);
        }
    }
    if (!o.p)
        puts_text(&o, "");
    if (o.failed) {
        free(o.p);
        return NULL;
    }
    return o.p;
}

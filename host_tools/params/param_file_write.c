/* Writing a parameter text file (param_text.h): a temporary file, synced, renamed over the old
 * one, so that a crash leaves either the old file or the new one; a dump of a set. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "param_text_internal.h"

#define WIDTH 100

static const char header[] =
    "# Parameters of a TSE controller (tse-sim --params FILE; tse-sim --write-params FILE writes\n"
    "# the defaults).\n"
    "# One 'name = value' per line; '#' starts a comment; a name left out keeps its default.\n"
    "# Values are SI (m, rad, m/s, m/s^2, m/s^3, rad/s, rad/s^2, 1/m, 1/s; ratios plain) unless the\n"
    "# name carries its unit (_ms, _ns, _kbps).  eta, alpha_min and alpha_max may instead be given in\n"
    "# degrees as eta_deg, alpha_min_deg, alpha_max_deg.\n";

/* "# " and text, broken at blanks so that no line passes WIDTH where a word allows. */
static void comment(FILE *f, const char *text)
{
    const size_t room = WIDTH - 2;
    while (*text) {
        size_t n = strlen(text);
        if (n > room) {
            n = room;
            while (n > 0 && text[n] != ' ')
                --n;
            if (n == 0)
                n = strcspn(text, " ");
        }
        fprintf(f, "# %.*s\n", (int)n, text);
        text += n;
        while (*text == ' ')
            ++text;
    }
}

static void entry(FILE *f, const fw_param_set *s, int id)
{
    const fw_param_def *d = &fw_param_table[id];
    param_key k;
    param_si_key(id, &k);
    char lo[32], hi[32], def[32], v[32], deg[64] = "";
    if (!strcmp(d->unit, "urad"))
        snprintf(deg, sizeof deg, " (or %s_deg in degrees)", d->name);
    fputc('\n', f);
    comment(f, d->doc);
    fprintf(f, "# %s%s%s, %s..%s, default %s\n", *k.unit ? "in " : "a ratio", k.unit, deg,
            param_to_text(&k, d->min, lo, sizeof lo),
            param_to_text(&k, d->max, hi, sizeof hi), param_to_text(&k, d->def, def, sizeof def));
    fprintf(f, "%s = %s\n", d->name, param_to_text(&k, s->v[id], v, sizeof v));
}

void param_line_text(const fw_param_set *s, int id, char *buf, size_t cap)
{
    param_key k;
    param_si_key(id, &k);
    char v[64];
    snprintf(buf, cap, "%s = %s   # %s", fw_param_table[id].name, param_to_text(&k, s->v[id], v, sizeof v),
             *k.unit ? k.unit : "ratio");
}

void param_file_line(FILE *f, const fw_param_set *s, int id)
{
    char line[160];
    param_line_text(s, id, line, sizeof line);
    fprintf(f, "%s\n", line);
}

void param_file_dump(FILE *f, const fw_param_set *s, fw_rates rates, const char *title)
{
    if (title)
        comment(f, title);
    char speed[512];
    comment(f, param_speed_limit_words(s, rates, speed, sizeof speed));
    for (int id = 0; id < FP_COUNT; ++id)
        param_file_line(f, s, id);
}

/* The directory entry of the rename survives a crash too (best effort: not every file system
 * lets a directory be synced). */
static void sync_dir(const char *path)
{
    char *copy = strdup(path);
    if (!copy)
        return;
    const int fd = open(dirname(copy), O_RDONLY);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
    free(copy);
}

/* What goes to PATH: the template for a new file, the user's file merged; NULL with err when
 * neither can be made. */
static char *new_text(const char *path, const fw_param_set *s, fw_rates rates, const struct stat *old, char *err,
                      size_t errlen)
{
    if (old) {
        fw_param_set check;
        fw_params_default(&check);
        char why[400];
        if (param_file_read(path, &check, rates, why, sizeof why) != 0) {
            snprintf(err, errlen, "not written over %s, which does not read as a parameter file now: %s", path, why);
            return NULL;
        }
        char *text = param_file_text(path, err, errlen);
        char *merged = text ? param_file_merged(text, s) : NULL;
        if (text && !merged)
            snprintf(err, errlen, "%s: out of memory", path);
        free(text);
        return merged;
    }
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    if (!m) {
        snprintf(err, errlen, "%s: out of memory", path);
        return NULL;
    }
    fputs(header, m);
    for (int id = 0; id < FP_COUNT; ++id)
        entry(m, s, id);
    if (fclose(m) != 0) {
        free(buf);
        snprintf(err, errlen, "%s: out of memory", path);
        return NULL;
    }
    return buf;
}

int param_file_write(const char *path, const fw_param_set *s, fw_rates rates, char *err, size_t errlen)
{
    if (fw_params_judge_config(s, rates.step_hz, rates.segment_hz).rule != FW_RULE_NONE) {
        char why[400];
        param_explain_invalid(s, rates, why, sizeof why);
        snprintf(err, errlen, "%s: not written: %s", path, why);
        return -1;
    }
    struct stat st;
    const int merge = stat(path, &st) == 0 && S_ISREG(st.st_mode);
    char *text = new_text(path, s, rates, merge ? &st : NULL, err, errlen);
    if (!text)
        return -1;
    const size_t n = strlen(path) + sizeof ".tmp";
    char *tmp = malloc(n);
    if (!tmp) {
        snprintf(err, errlen, "%s: out of memory", path);
        free(text);
        return -1;
    }
    snprintf(tmp, n, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        snprintf(err, errlen, "%s: cannot create: %s", tmp, strerror(errno));
        free(tmp);
        free(text);
        return -1;
    }
    const size_t len = strlen(text);
    /* The user's file keeps its permissions. */
    int ok = (!merge || fchmod(fileno(f), st.st_mode & 07777) == 0) && fwrite(text, 1, len, f) == len;
    free(text);
    ok = ok && !ferror(f) && fflush(f) == 0 && fsync(fileno(f)) == 0;
    int e = errno;
    if (fclose(f) != 0 && ok) {
        ok = 0;
        e = errno;
    }
    if (ok && rename(tmp, path) != 0) {
        snprintf(err, errlen, "%s: cannot replace it with %s: %s", path, tmp, strerror(errno));
        (void)remove(tmp); /* tidying up after the failure reported */
        free(tmp);
        return -1;
    }
    if (!ok) {
        snprintf(err, errlen, "%s: cannot write: %s", tmp, strerror(e));
        (void)remove(tmp); /* tidying up after the failure reported */
        free(tmp);
        return -1;
    }
    free(tmp);
    sync_dir(path);
    return 0;
}

/* Writing a parameter text file (param_text.h): a temporary file, synced, renamed over the old
 * one, so that a crash leaves either the old file or the new one. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

int param_file_write(const char *path, const fw_param_set *s, char *err, size_t errlen)
{
    if (fw_params_check(s) >= 0) {
        char why[400];
        param_explain_invalid(s, why, sizeof why);
        snprintf(err, errlen, "%s: not written: %s", path, why);
        return -1;
    }
    const size_t n = strlen(path) + sizeof ".tmp";
    char *tmp = malloc(n);
    if (!tmp) {
        snprintf(err, errlen, "%s: out of memory", path);
        return -1;
    }
    snprintf(tmp, n, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        snprintf(err, errlen, "%s: cannot create: %s", tmp, strerror(errno));
        free(tmp);
        return -1;
    }
    fputs(header, f);
    for (int id = 0; id < FP_COUNT; ++id)
        entry(f, s, id);
    int ok = !ferror(f) && fflush(f) == 0 && fsync(fileno(f)) == 0;
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

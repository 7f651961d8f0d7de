/* tse-sim's parameter storage (param_store.h). */
#define _POSIX_C_SOURCE 200809L
#include "param_store.h"

#include <errno.h>
#include <string.h>
#include <sys/stat.h>

#include "param_text.h"

int sim_param_store_open(sim_param_store *st, const char *path, fw_rates rates, FILE *log, char *err, size_t errlen)
{
    memset(st, 0, sizeof *st);
    st->path = path;
    st->rates = rates;
    st->log = log;
    fw_params_default(&st->set);
    struct stat sb;
    if (!path || (stat(path, &sb) != 0 && errno == ENOENT))
        return 0;
    if (param_file_read(path, &st->set, rates, err, errlen) != 0)
        return -1;
    st->stored = true;
    return 0;
}

static int load(void *ctx, void *buf, size_t cap)
{
    const sim_param_store *st = ctx;
    if (!st->stored)
        return 0;
    const size_t n = fw_params_serialize(&st->set, buf, cap);
    return n ? (int)n : -1;
}

static int save(void *ctx, const void *buf, size_t len)
{
    sim_param_store *st = ctx;
    fw_param_set s;
    if (!st->path)
        snprintf(st->err, sizeof st->err, "no parameter file (tse-sim --params FILE)");
    else if (fw_params_deserialize(&s, buf, len) != 0)
        snprintf(st->err, sizeof st->err, "%s: not written: the controller's record is not a valid set", st->path);
    else if (param_file_write(st->path, &s, st->rates, st->err, sizeof st->err) == 0) {
        st->set = s;
        st->stored = true;
        st->err[0] = '\0';
        return 0;
    }
    if (st->log)
        fprintf(st->log, "tse-sim: parameters not saved: %s\n", st->err);
    return -1;
}

hal_storage sim_param_store_hal(sim_param_store *st)
{
    return (hal_storage){st, load, save};
}

/* tse-sim's parameter storage: the text file of host_tools/params (param_text.h) behind the
 * firmware's hal_storage, which speaks the firmware's binary record (fw_params_serialize).
 *
 * The file is read once, when the store is opened: a file that exists must be a parameter text
 * file whose set the controller takes at the simulator's rates, or the store does not open (and
 * the file is never written).  A missing file means the defaults, and the first PARAM_SAVE creates it.  load hands
 * fw_init the record of the set read; save turns the record back into a set and writes the file
 * whole (param_file_write). */
#ifndef TSE_SIM_PARAM_STORE_H
#define TSE_SIM_PARAM_STORE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "fw/limits.h"
#include "fw/params.h"
#include "hal/storage.h"

typedef struct {
    const char *path;  /* NULL: nothing is kept, and a save fails */
    bool stored;       /* the file held a set when opened, or one has been saved since */
    fw_param_set set;  /* what the file holds (the defaults while it holds nothing) */
    fw_rates rates;    /* the controller's, which every set read or written is judged at */
    FILE *log;         /* where a failed save is explained (NULL: nowhere) */
    char err[512];     /* why the latest save failed */
} sim_param_store;

/* Opens the store of a controller running at `rates`.  Returns 0, or -1 with "PATH:LINE: ..." (or
 * "PATH: ...") in err. */
int sim_param_store_open(sim_param_store *st, const char *path, fw_rates rates, FILE *log, char *err, size_t errlen);

hal_storage sim_param_store_hal(sim_param_store *st);

#endif

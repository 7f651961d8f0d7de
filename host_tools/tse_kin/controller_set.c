#include "controller_set.h"

#include <stdio.h>
#include <string.h>

#include "param_text.h"

int kin_controller_set(const kin_run *run, fw_param_set *s)
{
    fw_params_default(s);
    if (!run->opt->params_path)
        return KIN_EXIT_OK;
    char err[512];
    if (param_file_read(run->opt->params_path, s, FW_RATES_BUILT_IN, err, sizeof err) != 0) {
        fprintf(stderr, "tse-kin: %s\n", err);
        return KIN_EXIT_FILE;
    }
    return KIN_EXIT_OK;
}

int cmd_one_file_check(const kin_options *o, char *err, size_t errlen)
{
    if (o->n_args != 1) {
        snprintf(err, errlen, o->n_args ? "takes one FILE, not %d" : "needs a CSV FILE", o->n_args);
        return -1;
    }
    return 0;
}

int cmd_bench_check(const kin_options *o, char *err, size_t errlen)
{
    if (o->n_args > 1 || (o->n_args == 1 && (strcmp(o->args[0], "plan") != 0 || o->n_set))) {
        snprintf(err, errlen, o->n_args == 1 && o->n_set ? "bench plan does not take --n"
                              : "bench takes no argument but 'plan'; got '%s'", o->args[o->n_args - 1]);
        return -1;
    }
    return 0;
}

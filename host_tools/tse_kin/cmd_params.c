/* `tse-kin params`: the default parameters as a file to edit.
 *
 * Promise: writes params_template.h's text to stdout, so that
 * `tse-kin params > p.txt && tse-kin ik --params p.txt` answers as the defaults do. */
#include "commands.h"
#include "params_template.h"

const char cmd_params_help[] =
    "usage: tse-kin params\n"
    "\n"
    "Writes a parameter file with every key tse-kin takes, set to the prototype's values, each with\n"
    "its unit, meaning and rule as a comment (angles also in degrees): edit it and pass it with\n"
    "--params. The controller's other parameters follow, in SI, with their defaults and ranges;\n"
    "tse-kin checks that they are numbers and ignores them, so one file serves tse-kin and the\n"
    "simulator.\n"
    "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

int cmd_params(const kin_run *run)
{
    (void)run;
    kin_params_write_template(stdout);
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "tse-kin: error writing the output\n");
        return KIN_EXIT_FILE;
    }
    return KIN_EXIT_OK;
}

/* `tsectl params dump`'s text for the set a parameter file gives (host_tools/params: the same
 * param_file_dump), so that test_kin.py can read a dump back with tse.kin.Params.from_file.
 * Usage: tse_py_param_dump FILE.  Exit 0, or 2 with the reader's message. */
#include <stdio.h>

#include "param_text.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: tse_py_param_dump FILE\n");
        return 2;
    }
    fw_param_set s;
    fw_params_default(&s);
    char err[512];
    if (param_file_read(argv[1], &s, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    param_file_dump(stdout, &s, "parameters of a test set");
    return 0;
}

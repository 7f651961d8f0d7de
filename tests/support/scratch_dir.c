#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "scratch_dir.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char dir[64];

int scratch_dir_make(void **state)
{
    (void)state;
    strcpy(dir, "/tmp/tse_test.XXXXXX");
    return mkdtemp(dir) ? 0 : -1;
}

int scratch_dir_remove(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

const char *scratch_path(const char *name)
{
    static char p[128];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return p;
}

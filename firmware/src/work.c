#include "fw/work.h"

#include <stddef.h>

/* Set and read by the controller's thread only; a tool that never begins work reads NULL. */
static fw_work_watch watcher;
static void *watcher_ctx;
static unsigned points;

void fw_work_begin(fw_work_watch watch, void *ctx)
{
    watcher = watch;
    watcher_ctx = ctx;
    points = 0;
}

void fw_work_end(void)
{
    watcher = NULL;
    watcher_ctx = NULL;
}

bool fw_work_point(void)
{
    if (!watcher || ++points % FW_WORK_STRIDE != 0u)
        return false;
    return watcher(watcher_ctx);
}

#define _POSIX_C_SOURCE 200809L /* clock_gettime, fileno */
/* Progress bar on stderr: see progress.h for the promise. */
#include "progress.h"

#include <stdio.h>
#include <time.h>
#include <unistd.h>

/* A run shorter than this is over before a bar would help; redraws closer than the interval only
 * cost terminal bandwidth. */
#define SHOW_AFTER_S 1.0
#define REDRAW_S 0.1
enum { BAR_WIDTH = 30, LINE_WIDTH = 79 };

double kin_progress_now(void)
{
    struct timespec t;
    (void)clock_gettime(CLOCK_MONOTONIC, &t); /* CLOCK_MONOTONIC always exists on Linux */
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void kin_progress_start(kin_progress *p, const char *what, long total)
{
    p->what = what;
    p->total = total > 0 ? total : 1;
    p->tty = isatty(fileno(stderr));
    p->start = kin_progress_now();
    p->last_draw = -1.0;
}

int kin_progress_visible(const kin_progress *p)
{
    return p->tty;
}

void kin_progress_update(kin_progress *p, long done)
{
    if (!p->tty)
        return;
    const double now = kin_progress_now();
    if (now - p->start < SHOW_AFTER_S || (p->last_draw >= 0 && now - p->last_draw < REDRAW_S))
        return;
    p->last_draw = now;
    const double frac = done <= 0 ? 0.0 : done >= p->total ? 1.0 : (double)done / (double)p->total;
    const int n = (int)(frac * BAR_WIDTH);
    char bar[BAR_WIDTH + 1];
    for (int i = 0; i < BAR_WIDTH; ++i)
        bar[i] = i < n ? '#' : '.';
    bar[BAR_WIDTH] = '\0';
    fprintf(stderr, "\r%.24s [%s] %3d%% (%ld of %ld) %.0f s ", p->what, bar, (int)(frac * 100.0), done, p->total,
            now - p->start);
    (void)fflush(stderr); /* a bar that is not drawn is no error of the command's */
}

void kin_progress_end(kin_progress *p)
{
    if (p->tty && p->last_draw >= 0) {
        fprintf(stderr, "\r%*s\r", LINE_WIDTH, "");
        (void)fflush(stderr);
    }
    p->last_draw = -1.0;
}

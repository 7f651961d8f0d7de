#define _POSIX_C_SOURCE 200809L
#include "progress.h"

#include <stdio.h>
#include <unistd.h>

static int bar_open; /* a bar is drawn and its line not ended */

void progress_start(progress *p, const char *what, int tty)
{
    p->what = what;
    p->tty = tty < 0 ? isatty(fileno(stdout)) : tty;
    p->shown = -1;
}

void progress_update(progress *p, double frac, const char *detail)
{
    if (frac < 0.0)
        frac = 0.0;
    if (frac > 1.0)
        frac = 1.0;
    const int pct = (int)(frac * 100.0 + 0.5);
    if (p->tty) {
        if (pct == p->shown)
            return;
        const int width = 40, n = (int)(frac * width + 0.5);
        printf("\r%-10s [", p->what);
        for (int i = 0; i < width; ++i)
            putchar(i < n ? '#' : '.');
        printf("] %3d%%", pct);
        bar_open = 1;
    } else {
        const int quarter = pct / 25;
        if (quarter <= p->shown)
            return;
        printf("%s: %d%%%s%s\n", p->what, quarter * 25, detail ? " " : "", detail ? detail : "");
    }
    p->shown = p->tty ? pct : pct / 25;
    fflush(stdout);
}

void progress_break(void)
{
    if (bar_open) {
        putchar('\n');
        fflush(stdout);
        bar_open = 0;
    }
}

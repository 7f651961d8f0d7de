/* A progress bar on stderr for tse-kin's long commands (sweep, workspace --points).
 *
 * Promise: nothing is written unless stderr is a terminal and the work has run for more than a
 * second, so that a short run, a pipe or a log never sees a bar; stdout is never touched.  The bar
 * is redrawn in place at most ten times a second and erased by kin_progress_end, leaving the
 * terminal as it was.  Not thread-safe: one thread (the one that started it) updates it. */
#ifndef TSE_KIN_PROGRESS_H
#define TSE_KIN_PROGRESS_H

typedef struct {
    const char *what;  /* shown before the bar, e.g. "sweep k1" */
    long total;        /* units of work */
    int tty;           /* stderr is a terminal */
    double start;      /* monotonic seconds at kin_progress_start */
    double last_draw;  /* when the bar was last drawn; < 0 before the first */
} kin_progress;

void kin_progress_start(kin_progress *p, const char *what, long total);

/* done units of total are finished. */
void kin_progress_update(kin_progress *p, long done);

/* Erases the bar, if one was drawn. */
void kin_progress_end(kin_progress *p);

/* Whether drawing is possible at all (stderr is a terminal): a caller that would have to wake up
 * just to draw can skip that when it is not. */
int kin_progress_visible(const kin_progress *p);

/* Monotonic seconds, for callers timing their own work. */
double kin_progress_now(void);

#endif

/* Progress of a long operation on stdout: a bar redrawn in place on a terminal; elsewhere (a log, a
 * pipe) a plain line at each quarter, so that logs hold a few lines, not thousands of frames.
 * Errors end the bar's line first (ctl_error calls progress_break), so nothing is glued to it. */
#ifndef TSECTL_PROGRESS_H
#define TSECTL_PROGRESS_H

typedef struct {
    const char *what;
    int tty;
    int shown;     /* last percentage drawn on a terminal, or last quarter printed elsewhere */
} progress;

/* tty < 0: ask isatty(stdout). */
void progress_start(progress *p, const char *what, int tty);
/* frac in [0, 1]; detail (may be NULL) follows the percentage on the plain lines. */
void progress_update(progress *p, double frac, const char *detail);
/* Ends the bar's line (a terminal), if one is open. */
void progress_break(void);

#endif

/* Waiting for the controller to come to rest after a command: how each STATUS is judged, one
 * judgement for tsectl (answer.c) and tse.can (python/tse/can.py, through libtse_kin.so).
 *
 * A STATUS sent before the command took effect may still show rest, so rest counts once motion
 * has been seen, or at once when the caller is `settled` (every STATUS from now on reflects what it
 * asked: a STOP already acknowledged; frames keep their order on the bus).  Rest without motion
 * for 2 s is "already at rest".  At rest in idle with no fault the wait succeeded; at rest in
 * disabled, fault or e-stop it ended badly.  The wait is bounded: three times what was planned
 * plus a minute (a minute's worth for an unplanned one, such as homing). */
#ifndef TSE_REST_WAIT_H
#define TSE_REST_WAIT_H

#include <stdbool.h>
#include <stddef.h>

typedef struct {
    double limit_s;   /* the longest the wait may take [s] */
    bool settled;
    bool seen_motion; /* a STATUS in motion has been seen */
} rest_wait;

typedef enum {
    REST_WAIT_ON = 0,        /* not yet: wait for the next STATUS */
    REST_WAIT_DONE = 1,      /* at rest, idle, no fault */
    REST_WAIT_ALREADY = 2,   /* never seen moving, at rest for 2 s (idle or disabled) */
    REST_WAIT_ENDED = -1,    /* came to rest in disabled, fault or e-stop */
    REST_WAIT_TIMEOUT = -2   /* no rest within limit_s */
} rest_verdict;

/* expected_s: how long the motion was planned to take (0: unknown). */
void rest_wait_begin(rest_wait *w, double expected_s, bool settled);

/* Whether the controller in `state` (fw_state) is at rest. */
bool rest_state(int state);

/* A STATUS with `state` and `fault` (fw_fault), elapsed_s after the wait began; state < 0: no STATUS
 * came (only the time is judged).  words: what the verdict says, "WHAT at rest after 1.23 s" or why
 * not (names from the message table), for a verdict other than ON. */
rest_verdict rest_wait_status(rest_wait *w, double elapsed_s, int state, int fault, const char *what, char *words,
                              size_t cap);

#endif

/* Independent pieces of work spread over threads, with the progress bar drawn meanwhile.
 *
 * Promise: work(ctx, i) is called exactly once for every i in [0, n), from up to `jobs` threads at
 * a time, in no particular order; kin_parallel_for returns when every call has returned.  The
 * calls must not share mutable state except through ctx in ways the caller makes safe (sweep:
 * each call writes only its own row).  If threads cannot be started, the work runs in the calling
 * thread: slower, never different. */
#ifndef TSE_KIN_PARALLEL_H
#define TSE_KIN_PARALLEL_H

#include "progress.h"

typedef void (*kin_work_fn)(void *ctx, long i);

/* progress (may be NULL) is started by the caller and updated here with the count of finished
 * calls; the caller ends it. */
void kin_parallel_for(long n, int jobs, kin_work_fn work, void *ctx, kin_progress *progress);

/* The number of online cores, at least 1, at most KIN_MAX_JOBS: --jobs' default. */
int kin_default_jobs(void);

#endif

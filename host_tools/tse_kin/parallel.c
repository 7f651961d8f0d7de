#define _POSIX_C_SOURCE 200809L /* sysconf, nanosleep */
/* Threads for independent work: see parallel.h for the promise. */
#include "parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <time.h>
#include <unistd.h>

#include "options.h"

typedef struct {
    atomic_long next; /* the next index nobody has taken */
    atomic_long done; /* calls that have returned */
    long n;
    kin_work_fn work;
    void *ctx;
} shared_work;

/* Takes indices until none is left: the designs of a sweep differ in cost (an unreachable point
 * costs ten reachable ones), so fixed slices would leave a thread idle while another still works. */
static void *worker(void *arg)
{
    shared_work *w = arg;
    for (;;) {
        const long i = atomic_fetch_add(&w->next, 1);
        if (i >= w->n)
            break;
        w->work(w->ctx, i);
        atomic_fetch_add(&w->done, 1);
    }
    return NULL;
}

int kin_default_jobs(void)
{
    const long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > KIN_MAX_JOBS ? KIN_MAX_JOBS : (int)n;
}

void kin_parallel_for(long n, int jobs, kin_work_fn work, void *ctx, kin_progress *progress)
{
    shared_work w;
    atomic_init(&w.next, 0);
    atomic_init(&w.done, 0);
    w.n = n;
    w.work = work;
    w.ctx = ctx;
    if (jobs > KIN_MAX_JOBS)
        jobs = KIN_MAX_JOBS;
    if ((long)jobs > n)
        jobs = (int)n;
    pthread_t threads[KIN_MAX_JOBS];
    int started = 0;
    if (jobs > 1)
        while (started < jobs && pthread_create(&threads[started], NULL, worker, &w) == 0)
            ++started;
    if (started == 0) {
        /* One job, or no thread to be had: this thread does it all, drawing between calls. */
        for (long i = 0; i < n; ++i) {
            work(ctx, i);
            if (progress)
                kin_progress_update(progress, i + 1);
        }
        return;
    }
    if (progress && kin_progress_visible(progress)) {
        const struct timespec tick = {0, 50 * 1000 * 1000};
        while (atomic_load(&w.done) < n) {
            (void)nanosleep(&tick, NULL); /* an interrupted sleep only draws sooner */
            kin_progress_update(progress, atomic_load(&w.done));
        }
    }
    for (int t = 0; t < started; ++t)
        (void)pthread_join(threads[t], NULL); /* joinable threads of ours: cannot fail */
}

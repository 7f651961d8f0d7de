/* hal/ on Linux: SocketCAN, the monotonic clock, and the tick thread.  (Parameter storage is the
 * simulator's own: host_tools/tse_sim/param_store.h keeps the parameters as a text file.) */
#ifndef HAL_POSIX_H
#define HAL_POSIX_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

#include "hal/can.h"
#include "hal/clock.h"

/* The socket is read by the controller's thread (receive, which also takes the error frames) and
 * its state by the control tick: the state is kept in atomics. */
typedef struct {
    int fd;
    atomic_bool bus_off, error_passive;
    atomic_uint bus_off_events, rx_overruns;
} posix_can;

/* Opens a raw CAN socket on iface, receiving only frames addressed to `node` or to node 0
 * (kernel filters on the low 4 bits of the identifier), with error frames for bus-off.
 * Returns 0, or -1 with errno set (for example when the kernel has no CAN). */
int posix_can_open(posix_can *c, const char *iface, uint8_t node);
void posix_can_close(posix_can *c);
hal_can posix_can_hal(posix_can *c);

hal_clock posix_clock_hal(void);

/* The control tick and the step interrupts in a thread of their own (fw/runtime.h: the control
 * context, and the step context inside it): every control period one control call, then the
 * period's step calls back to back.  The plant's clock is the step count, so simulated physics
 * stays exact whatever the scheduler does.  The thread blocks every signal: they go to the
 * controller's thread. */
typedef struct {
    atomic_int stop;
    uint64_t periods;    /* control periods run */
    uint64_t overruns;   /* of them, periods the process was too late for (run late, back to back) */
    uint64_t max_behind; /* the most periods it was ever behind at once */
    /* The tick thread's */
    pthread_t thread;
    int fd;
    int efd;             /* an eventfd the tick thread signals after every control call */
    uint32_t control_hz, steps;
    void (*control)(void *arg);
    void (*step)(void *arg);
    void *arg;
} posix_ticker;

/* Starts the tick thread: control(arg) control_hz times a second, each followed by
 * step_hz / control_hz calls of step(arg).  Returns 0, or -1 for rates it cannot keep or a thread
 * or timer it cannot have. */
int posix_ticker_start(posix_ticker *t, uint32_t control_hz, void (*control)(void *arg), uint32_t step_hz,
                       void (*step)(void *arg), void *arg);

/* Waits until the tick thread has made a control call since the wait began, or one that came
 * just before it (the caller checks what it waits for and waits again): for the controller's
 * thread handing a command over (fw_config.await).  Never makes the tick thread wait. */
void posix_ticker_await(posix_ticker *t);

/* Stops the tick thread and waits for it; the counts are then final. */
void posix_ticker_stop(posix_ticker *t);

#endif

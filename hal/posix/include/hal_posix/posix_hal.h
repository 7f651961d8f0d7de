/* hal/ on Linux: SocketCAN, the monotonic clock, and a timerfd ticker.  (Parameter storage is the
 * simulator's own: host_tools/tse_sim/param_store.h keeps the parameters as a text file.) */
#ifndef HAL_POSIX_H
#define HAL_POSIX_H

#include <stdint.h>

#include "hal/can.h"
#include "hal/clock.h"
#include "hal/ticker.h"

typedef struct {
    int fd;
    uint32_t rx_overruns;
    hal_can_state state;
} posix_can;

/* Opens a raw CAN socket on iface, receiving only frames addressed to `node` or to node 0
 * (kernel filters on the low 4 bits of the identifier), with error frames for bus-off.
 * Returns 0, or -1 with errno set (for example when the kernel has no CAN). */
int posix_can_open(posix_can *c, const char *iface, uint8_t node);
void posix_can_close(posix_can *c);
hal_can posix_can_hal(posix_can *c);

hal_clock posix_clock_hal(void);

typedef struct {
    volatile int stop;
    uint64_t periods;    /* control periods run */
    uint64_t overruns;   /* of them, periods the process was too late for (run late, back to back) */
    uint64_t max_behind; /* the most periods it was ever behind at once */
} posix_ticker;
/* start() runs the loop in the calling thread until stop() (or a signal sets ->stop): every
 * control period one control call, then the period's step calls back to back.  The plant's
 * clock is the step count, so simulated physics stays exact whatever the scheduler does. */
hal_ticker posix_ticker_hal(posix_ticker *t);

#endif

/* hal/ on Linux: SocketCAN and the monotonic clock.  (The tick thread: hal_posix/ticker.h.
 * Parameter storage is the simulator's own: host_tools/tse_sim/param_store.h keeps the parameters
 * as a text file.) */
#ifndef HAL_POSIX_H
#define HAL_POSIX_H

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

#endif

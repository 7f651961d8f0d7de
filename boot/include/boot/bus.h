/* The bootloader on the bus: CAN frames in, the update's commands (boot/update.h) run, ACK,
 * REJECT and the BOOT_QUERY answers out, all through the protocol's codec (fw/proto.h), so that the
 * bootloader speaks exactly the message table (docs/protocol.md, Updating the firmware).
 *
 * It answers as one node, frames to others and broadcasts unanswered.  Every frame is answered as
 * the table says: a malformed one with REJECT bad_length, unknown or range; a controller's command
 * that is not the bootloader's with REJECT state (field 0: boot); HOST_HEARTBEAT and BOOT_DATA
 * not at all (BOOT_DATA's block answers them). */
#ifndef BOOT_BUS_H
#define BOOT_BUS_H

#include <stdbool.h>
#include <stdint.h>

#include "boot/update.h"
#include "hal/can.h"

#define BOOT_VERSION_MAJOR 1
#define BOOT_VERSION_MINOR 0

typedef struct {
    boot_update up;
    hal_can can;
    uint8_t node;
    bool start;         /* BOOT_START was acknowledged: the platform starts the application */
    uint32_t sent_lost; /* answers the transmit queue refused */
} boot_bus;

/* The bootloader as node over can, updating flash in layout for board. */
void boot_bus_init(boot_bus *b, const boot_layout *layout, const flash_ops *flash, uint32_t board, uint8_t node,
                   hal_can can);

/* One received frame. */
void boot_bus_frame(boot_bus *b, const hal_can_frame *f);

#endif

/* One bank (bank 0), two 16-bit mask filters, FIFO 0; every other CAN1 bank inactive. */
#include "hal_stm32f4/bxcan_filter.h"

#include <string.h>

#include "hal_stm32f4/regs_can.h"

/* A 16-bit mask filter (identifier in bits 15:0, mask in 31:16) accepting the standard data
 * frames whose node bits equal `node`: the mask covers the node bits, RTR and IDE; the function
 * bits and EXID[17:15] are free. */
static uint32_t node_filter16(uint8_t node)
{
    const uint32_t mask = BXCAN_NODE_MASK << CAN_F16_STID_SHIFT | CAN_F16_RTR | CAN_F16_IDE;
    const uint32_t id = (uint32_t)node << CAN_F16_STID_SHIFT; /* RTR = 0, IDE = 0 */
    return mask << 16 | id;
}

int bxcan_filter_for_node(uint8_t node, bxcan_filter_regs *out)
{
    if (node == BXCAN_BROADCAST || node > BXCAN_NODE_MASK)
        return -1;
    memset(out, 0, sizeof *out); /* mask mode, 16-bit scale, FIFO 0, inactive */
    out->fr1[0] = node_filter16(node);
    out->fr2[0] = node_filter16(BXCAN_BROADCAST);
    out->fa1r = 1u << 0;
    return 0;
}

/* Two controllers answering under one node id, told from the STATUS counters a host reads.
 *
 * A controller's STATUS counter goes up by one each status period; a frame lost on the bus makes
 * it skip ahead, and only a restart makes it go back.  Two controllers under one node id
 * interleave two counters, which then repeat or go back again and again. */
#ifndef TSECTL_STATUS_ORDER_H
#define TSECTL_STATUS_ORDER_H

#include <stdbool.h>
#include <stdint.h>

typedef struct {
    bool seen;          /* a counter has been noted */
    uint16_t last;      /* the last one */
    unsigned disorder;  /* counters that repeated or went back, since the last long orderly run */
    unsigned in_order;  /* counters that followed on since the last disorder */
} status_order;

/* Notes the counter of the node's next STATUS.  Returns true when the counters seen show two
 * sources: three disorders within a run shorter than 20 orderly counters (a controller that
 * restarts now and then stays one source). */
bool status_order_note(status_order *o, uint16_t counter);

#endif

/* The controller's telemetry: commanded slide positions (SLIDES_A..C, every telemetry period) and
 * the plate pose from their forward kinematics (FK_A..C, only once homed). */
#ifndef TSECTL_TELEMETRY_H
#define TSECTL_TELEMETRY_H

#include "fw/proto.h"

typedef struct {
    double slides[6];   /* m */
    double pose[6];     /* m, rad */
    unsigned have;      /* bit k: SLIDES_A + k arrived; bit 3 + k: FK_A + k (of the present period) */
} telemetry;

/* Takes a frame in; returns 1 when it completed a period's pose.  One period at a time, in the
 * controller's order (SLIDES_A..C, then FK_A..C once homed): the slides and the pose are always
 * of one period, and a period with a frame missing is dropped. */
int telemetry_take(telemetry *t, const proto_message *m);

static inline int telemetry_has_slides(const telemetry *t) { return (t->have & 7u) == 7u; }
static inline int telemetry_has_pose(const telemetry *t) { return (t->have & 070u) == 070u; }

#endif

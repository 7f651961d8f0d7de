/* The controller's telemetry: commanded slide positions (SLIDES_A..C, every telemetry period) and
 * the plate pose from their forward kinematics (FK_A..C, only once homed). */
#ifndef TSECTL_TELEMETRY_H
#define TSECTL_TELEMETRY_H

#include "fw/proto.h"

typedef struct {
    double slides[6];   /* m */
    double pose[6];     /* m, rad */
    unsigned have;      /* bit k: SLIDES_A + k arrived; bit 3 + k: FK_A + k */
} telemetry;

/* Takes a frame in; returns 1 when it completed the pose (FK_C after FK_A and FK_B). */
int telemetry_take(telemetry *t, const proto_message *m);

static inline int telemetry_has_slides(const telemetry *t) { return (t->have & 7u) == 7u; }
static inline int telemetry_has_pose(const telemetry *t) { return (t->have & 070u) == 070u; }

#endif

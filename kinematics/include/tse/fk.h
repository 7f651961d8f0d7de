/* Forward kinematics: the pose whose solution is q (kinematics.md, "Forward kinematics").
 *
 * Newton on the six constraints F(p, q) = 0 from a seed pose.  The answer is then checked by the
 * inverse kinematics, seeded with q: unless it reproduces q, the result is a failure, never a pose.
 * Before any of that: a non-finite q or seed is TSE_INVALID, and a slide outside [s_min, s_max]
 * is TSE_STROKE with its scissor (the first such), as the inverse kinematics would say of any
 * pose that needs it. */
#ifndef TSE_FK_H
#define TSE_FK_H

#include "tse/geometry.h"
#include "tse/status.h"

typedef struct {
    tse_status status; /* TSE_OK, TSE_INVALID, TSE_STROKE, TSE_NOCONVERGE, or the IK check's status */
    int scissor;       /* scissor of a slide outside the stroke, or failing scissor of the IK check, else 0 */
    tse_real pose[6];  /* meaningful only when status == TSE_OK */
    int iterations;
    tse_real q_error;  /* max |IK(pose) - q| [m] */
} tse_fk_result;

#define tse_fk TSE_NS(tse_fk)

/* seed_pose: the last pose, or NULL for the geometry's home pose.  A seed angle beyond a full turn
 * is taken as the same angle in [-pi, pi], so that the pose found is as fine as the precision. */
tse_status tse_fk(const tse_geometry *g, const tse_real q[6], const tse_real seed_pose[6],
                  tse_fk_result *out);

#endif

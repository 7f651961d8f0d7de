#include "telemetry.h"

int telemetry_take(telemetry *t, const proto_message *m)
{
    if (m->msg >= PM_SLIDES_A && m->msg <= PM_SLIDES_C) {
        const int k = (int)m->msg - PM_SLIDES_A;
        t->slides[2 * k] = (double)m->v[0] / PROTO_NM_PER_M;
        t->slides[2 * k + 1] = (double)m->v[1] / PROTO_NM_PER_M;
        t->have |= 1u << k;
    } else if (m->msg >= PM_FK_A && m->msg <= PM_FK_C) {
        const int k = (int)m->msg - PM_FK_A;
        if (k == 0)
            t->have &= ~070u; /* a new pose begins: never mix two */
        t->pose[2 * k] = (double)m->v[0] / proto_pose_units(2 * k);
        t->pose[2 * k + 1] = (double)m->v[1] / proto_pose_units(2 * k + 1);
        t->have |= 1u << (3 + k);
        return k == 2 && telemetry_has_pose(t);
    }
    return 0;
}

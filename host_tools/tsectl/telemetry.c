#include "telemetry.h"

int telemetry_take(telemetry *t, const proto_message *m)
{
    if (m->msg >= PM_SLIDES_A && m->msg <= PM_SLIDES_C) {
        const int k = (int)m->msg - PM_SLIDES_A;
        t->slides[2 * k] = m->v[0] * 1e-9;
        t->slides[2 * k + 1] = m->v[1] * 1e-9;
        t->have |= 1u << k;
    } else if (m->msg >= PM_FK_A && m->msg <= PM_FK_C) {
        const int k = (int)m->msg - PM_FK_A;
        if (k == 0)
            t->have &= ~070u; /* a new pose begins: never mix two */
        t->pose[2 * k] = m->v[0] * 1e-6;
        t->pose[2 * k + 1] = m->v[1] * 1e-6;
        t->have |= 1u << (3 + k);
        return k == 2 && telemetry_has_pose(t);
    }
    return 0;
}

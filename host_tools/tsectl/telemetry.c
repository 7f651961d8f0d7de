#include "telemetry.h"

/* A period's frames, as the controller sends them (firmware/src/telemetry.c), are the table's
 * six in a row: the slides, then, once homed, the pose of those slides. */
_Static_assert(PM_SLIDES_B == PM_SLIDES_A + 1 && PM_SLIDES_C == PM_SLIDES_A + 2 && PM_FK_A == PM_SLIDES_A + 3 &&
                   PM_FK_B == PM_SLIDES_A + 4 && PM_FK_C == PM_SLIDES_A + 5,
               "a telemetry period's frames follow each other in the table");

int telemetry_take(telemetry *t, const proto_message *m)
{
    if (m->msg < PM_SLIDES_A || m->msg > PM_FK_C)
        return 0;
    const int k = (int)m->msg - PM_SLIDES_A;
    /* SLIDES_A begins a period; any other frame counts only right after its predecessor of the
     * same period: a frame lost or a period begun before this reader started leaves nothing half
     * of one period and half of the next (a pose beside the slides it was not solved from). */
    if (k == 0)
        t->have = 0;
    else if (t->have != (1u << k) - 1u) {
        t->have = 0;
        return 0;
    }
    if (k < 3) {
        t->slides[2 * k] = (double)m->v[0] / PROTO_NM_PER_M;
        t->slides[2 * k + 1] = (double)m->v[1] / PROTO_NM_PER_M;
    } else {
        const int j = 2 * (k - 3);
        t->pose[j] = (double)m->v[0] / proto_pose_units(j);
        t->pose[j + 1] = (double)m->v[1] / proto_pose_units(j + 1);
    }
    t->have |= 1u << k;
    return k == 5;
}

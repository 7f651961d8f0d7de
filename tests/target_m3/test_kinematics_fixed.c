/* On the Cortex-M3 (QEMU mps2-an385, no FPU): the fixed-point inverse kinematics against the
 * table the host computed with the double build and the oracle (kin_table_fixed.h): from no seed
 * every pose the oracle finds clear gets the double build's status and failing scissor, and an
 * accepted one with every mu >= 0.1 slides within 1 um (17 units of 2^-24 m) of the double's; warm
 * along each path (seeded with the previous answer) the same.  Prints "N passed, M failed". */
#include <stdint.h>

#include "hal_mps2/m3.h"
#include "kin_table_fixed.h"
#include "tse/ik_fixed.h"

#define ONE_UM 17 /* 1 um is 16.8 units of 2^-24 m */

static unsigned passed, failed, reported;

static void fail(unsigned i, const char *what, long long got, long long want)
{
    ++failed;
    if (++reported > 12)
        return;
    m3_puts("FAIL case ");
    m3_put_int(i);
    m3_puts(": ");
    m3_puts(what);
    m3_puts(" ");
    m3_put_int(got);
    m3_puts(", expected ");
    m3_put_int(want);
    m3_puts("\n");
}

static void check(unsigned i, const kin_fx_case *c, const tse_fx_ik_result *r)
{
    if (c->clear) {
        if ((int)r->status != c->status) {
            fail(i, "status", r->status, c->status);
            return;
        }
        if (c->status != TSE_OK && c->status != TSE_DEGENERATE && r->scissor != c->scissor) {
            fail(i, "scissor", r->scissor, c->scissor);
            return;
        }
    }
    if (c->accurate)
        for (int k = 0; k < 6; ++k) {
            const int32_t d = r->q[k] - c->q[k];
            if (d > ONE_UM || d < -ONE_UM) {
                fail(i, "slide (units of 2^-24 m)", r->q[k], c->q[k]);
                return;
            }
        }
    ++passed;
}

int main(void)
{
    tse_fx_params p;
    tse_fx_params_default(&p);
    static tse_fx_geometry g;
    if (tse_fx_geometry_init(&g, &p) != TSE_PARAM_OK) {
        m3_puts("the prototype's fixed geometry was refused\n");
        return 1;
    }
    unsigned compared = 0;
    tse_fx_ik_result prev;
    for (unsigned i = 0; i < kin_fx_case_count; ++i) {
        const kin_fx_case *c = &kin_fx_cases[i];
        tse_fx_ik_result r;
        tse_fx_ik(&g, c->pose, 0, &r);
        check(i, c, &r);
        compared += c->accurate;
        /* warm: seeded with the answer to the previous pose of the path, where it had one */
        if (!c->path_start && prev.status == TSE_OK) {
            tse_fx_ik(&g, c->pose, prev.q, &r);
            check(i, c, &r);
        }
        prev = r;
    }
    m3_puts("kinematics_fixed on the Cortex-M3: ");
    m3_put_int(kin_fx_case_count);
    m3_puts(" poses, ");
    m3_put_int(compared);
    m3_puts(" compared to 1 um\nkinematics_fixed: ");
    m3_put_int(passed);
    m3_puts(" passed, ");
    m3_put_int(failed);
    m3_puts(" failed\n");
    return failed != 0;
}

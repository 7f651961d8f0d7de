#include "plan_text.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "reject_text.h"
#include "text.h"

void plan_waypoints_from_rows(const waypoint_row *rows, int n, plan_waypoint *wp)
{
    for (int i = 0; i < n; ++i) {
        memcpy(wp[i].pose, rows[i].pose, sizeof wp[i].pose);
        wp[i].t = rows[i].t;
        wp[i].v = rows[i].v;
        wp[i].line = rows[i].line;
        wp[i].number = i + 1;
    }
}

int plan_text_make(const fw_param_set *s, const plan_waypoint *wp, int n, const plan_options *o, const char *path,
                   plan_made *m, char *err, size_t errlen)
{
    m->p = NULL;
    m->mem = NULL;
    const size_t bytes = plan_bytes(s, wp, n, o);
    if (bytes > 0 && !(m->mem = malloc(bytes))) {
        snprintf(err, errlen, "%s: out of memory (%zu bytes to plan)", path, bytes);
        return -1;
    }
    plan_result r;
    m->p = plan_make(m->mem, bytes, s, wp, n, o, &r);
    if (m->p)
        return 0;
    char why[512], words[512];
    plan_explain(&r, wp, why, sizeof why);
    if (r.status == PLAN_REFUSED) {
        proto_message rej = {.msg = PM_REJECT};
        memcpy(rej.v, r.reject, sizeof rej.v);
        snprintf(err, errlen, "%s: %s: %s", path, why, reject_text(&rej, words, sizeof words));
    } else {
        snprintf(err, errlen, "%s: %s", path, why);
    }
    return -1;
}

int plan_jerk_from_text(const char *text, double *jmax)
{
    double j;
    if (!strcmp(text, "controller"))
        j = PLAN_JMAX_CONTROLLER;
    else if (text_number(text, &j) != 0 || !(j > 0.0 && j <= PLAN_JERK_MAX))
        return -1;
    *jmax = j;
    return 0;
}

void plan_print_stats(FILE *f, const char *prefix, const plan_stats *st)
{
    fprintf(f,
            "%sslide speed up to %.1f%% of %.4g m/s, acceleration up to %.1f%% of %.4g m/s^2 (as the controller "
            "measures rows)",
            prefix, 100.0 * st->v_peak, st->v_limit, 100.0 * st->a_peak, st->a_limit);
    if (st->j_limit > 0.0)
        fprintf(f, ", jerk up to %.1f%% of %.4g m/s^3 (over rows evenly apart)", 100.0 * st->j_peak, st->j_limit);
    fprintf(f,
            "; rows with some slide at >= 90%% of a limit: %.1f%% (%ld of %ld, leaving out the first and last 5%% "
            "of the time)\n",
            st->rows_mid ? 100.0 * (double)st->rows_near / (double)st->rows_mid : 0.0, st->rows_near, st->rows_mid);
}

void plan_write_rows(FILE *f, const plan *p)
{
    fputs("t,x,y,z,roll,pitch,yaw\n", f);
    plan_cursor c;
    plan_row row;
    for (plan_rows_begin(p, &c); plan_rows_next(p, &c, &row);) {
        fprintf(f, "%.6f", row.t);
        for (int k = 0; k < 6; ++k)
            fprintf(f, ",%.6f", (double)lround(row.pose[k] * 1e6) * 1e-6);
        fputc('\n', f);
    }
}

/* Template parameter file: see params_template.h for the promise. */
#include "params_template.h"

#include <stdlib.h>
#include <string.h>

#include "fw/params.h"
#include "kin_params_file.h"

#define KIN_PI 3.14159265358979323846

/* The fewest significant digits that read back to x: "1.727", not "1.7270000000000001". */
static void put_exact(FILE *f, double x)
{
    char buf[40];
    for (int digits = 6; digits <= 17; ++digits) {
        snprintf(buf, sizeof buf, "%.*g", digits, x);
        if (strtod(buf, NULL) == x)
            break;
    }
    fputs(buf, f);
}

/* SI form of a table unit: the micro-units scale by 1e-6 ("um/s" is "m/s", "ppm" a plain ratio);
 * the others ("1/m", "ms", "kbit/s") are already what the name says. */
static double si_scale(const char *unit, const char **si_unit)
{
    if (!strcmp(unit, "1")) { /* a plain number (node, enable_level) */
        *si_unit = "";
        return 1.0;
    }
    if (!strcmp(unit, "ppm")) {
        *si_unit = "";
        return 1e-6;
    }
    if (unit[0] == 'u') {
        *si_unit = unit + 1;
        return 1e-6;
    }
    *si_unit = unit;
    return 1.0;
}

static void put_unit(FILE *f, const char *unit)
{
    fputs(unit[0] ? unit : "ratio", f);
}

static int is_kinematic(const char *name)
{
    for (int id = 1; id < TSE_PARAM_COUNT; ++id)
        if (!strcmp(kin_param_key((tse_param_id)id), name))
            return 1;
    return 0;
}

void kin_params_write_template(FILE *f)
{
    kin_param_values d;
    kin_params_default(&d);
    const kin_param_key_def *keys;
    const int n = kin_param_keys(&keys);
    fputs("# TSE parameter file (tse-kin params): the prototype's values, docs/kinematics.md.\n"
          "# 'key = value' lines, keys in any case; '#' starts a comment; a key left out keeps the value\n"
          "# shown here.\n"
          "# Names without a unit suffix are SI (m, rad, m/s, ratios); a suffix names the unit\n"
          "# (watchdog_ms). Angles may be given in degrees instead, as eta_deg, alpha_min_deg and\n"
          "# alpha_max_deg (one spelling per parameter).\n"
          "\n"
          "# Kinematics: tse-kin uses these.\n",
          f);
    for (int i = 0; i < n; ++i) {
        const kin_param_key_def *k = &keys[i];
        if (k->degrees)
            continue;
        fprintf(f, "%s = ", k->key);
        put_exact(f, d.v[k->id]);
        fputs("   # ", f);
        put_unit(f, k->unit);
        if (!strcmp(k->unit, "rad"))
            fprintf(f, " (%.6g deg)", d.v[k->id] * (180.0 / KIN_PI));
        const fw_param_def *w = &fw_param_table[fw_param_of_kin(k->id)];
        const char *unit;
        const double sc = si_scale(w->unit, &unit);
        fprintf(f, "; %s; valid: %s; a controller's range %.7g..%.7g\n", k->doc, k->rule, w->min * sc, w->max * sc);
    }
    fputs("\n"
          "# The controller's other parameters: the simulator and the controller use them; tse-kin\n"
          "# --params holds them to their ranges and the set to the controller's rules, as tse-sim\n"
          "# does (--design: only numbers). Ranges as the controller takes them.\n",
          f);
    for (int i = 0; i < FP_COUNT; ++i) {
        const fw_param_def *p = &fw_param_table[i];
        if (is_kinematic(p->name))
            continue;
        const char *unit;
        const double s = si_scale(p->unit, &unit);
        fprintf(f, "%s = %.15g   # ", p->name, p->def * s);
        put_unit(f, unit);
        fprintf(f, "; %s; range %.15g..%.15g\n", p->doc, p->min * s, p->max * s);
    }
}

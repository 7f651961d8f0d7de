/* Names and units of the parameters' spellings (param_text.h). */
#include <math.h>
#include <string.h>
#include <strings.h>

#include "param_text.h"


/* Micro-units on the wire and their SI unit; any other wire unit (ms, ns, kbit/s, 1/m, 1/s) is
 * already the unit people write, one raw unit apiece, and "1" (a plain number) is written bare. */
static const struct {
    const char *wire, *si;
} micro_units[] = {
    {"um", "m"},         {"urad", "rad"},       {"ppm", ""},
    {"um/s", "m/s"},     {"um/s^2", "m/s^2"},   {"um/s^3", "m/s^3"},
    {"urad/s", "rad/s"}, {"urad/s^2", "rad/s^2"}, {"us", "s"},
};

void param_si_key(int id, param_key *k)
{
    const char *wire = fw_param_table[id].unit;
    k->id = id;
    k->per_unit = 1.0;
    k->unit = wire;
    if (!strcmp(wire, "1")) /* a plain number (node, enable_level): no unit to write */
        k->unit = "";
    for (size_t i = 0; i < sizeof micro_units / sizeof micro_units[0]; ++i)
        if (!strcmp(wire, micro_units[i].wire)) {
            k->per_unit = 1e6;
            k->unit = micro_units[i].si;
        }
}

/* Only plain angles take degrees: an angular speed in "deg" would read as an angle. */
static int is_angle(int id)
{
    return !strcmp(fw_param_table[id].unit, "urad");
}

int param_lookup(const char *name, param_key *k)
{
    const size_t n = strlen(name), ns = strlen(PARAM_DEG_SUFFIX);
    for (int id = 0; id < FP_COUNT; ++id) {
        const char *t = fw_param_table[id].name;
        if (!strcasecmp(name, t)) {
            param_si_key(id, k);
            return 0;
        }
        if (is_angle(id) && n == strlen(t) + ns && !strncasecmp(name, t, strlen(t)) &&
            !strcasecmp(name + strlen(t), PARAM_DEG_SUFFIX)) {
            k->id = id;
            k->per_unit = 1e6 * PARAM_PI / 180.0;
            k->unit = "deg";
            return 0;
        }
    }
    return -1;
}

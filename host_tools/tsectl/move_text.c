#include "move_text.h"

#include <stdio.h>

#include "reject_text.h"

static const char *plate_limit(int bound)
{
    switch (bound) {
    case FW_BOUND_PLATE_VMAX:
        return "the plate's speed limit (plate_vmax)";
    case FW_BOUND_PLATE_AMAX:
        return "the plate's acceleration limit (plate_amax)";
    case FW_BOUND_PLATE_JMAX:
        return "the plate's jerk limit (plate_jmax)";
    case FW_BOUND_PLATE_WMAX:
        return "the plate's turning speed limit (plate_wmax)";
    case FW_BOUND_PLATE_DWMAX:
        return "the plate's angular acceleration limit (plate_dwmax)";
    case FW_BOUND_PLATE_JMAX_ANGULAR:
        return "the plate's angular jerk limit (plate_dwmax x plate_jmax / plate_amax)";
    default:
        return NULL;
    }
}

const char *move_info_text(const proto_message *info, char *buf, size_t cap)
{
    const int start = info->v[1], bound = info->v[2], slide = info->v[3], demand = info->v[4];
    const char *how = start == FW_START_BLENDED ? ", blended into the running move"
                      : start == FW_START_AFTER ? ", after the running move (blending the two would break a limit)"
                                                : "";
    const char *plate = plate_limit(bound);
    if (plate)
        snprintf(buf, cap, "%s, paced by %s", how, plate);
    else if (bound == FW_BOUND_SLIDE_VMAX || bound == FW_BOUND_SLIDE_AMAX || bound == FW_BOUND_STEP_GENERATOR)
        snprintf(buf, cap,
                 "%s, slower than asked: the slides set the pace (unstretched, slide %s (scissor %d) would need "
                 "%.2f times its %s)",
                 how, reject_slide_name(slide), (slide + 1) / 2, demand / (double)PROTO_PER_MILLE,
                 bound == FW_BOUND_SLIDE_AMAX   ? "acceleration limit, slide_amax"
                 : bound == FW_BOUND_SLIDE_VMAX ? "speed limit, slide_vmax"
                                                : "speed limit in effect, the step generator's, lower than slide_vmax "
                                                  "('tsectl params get slide_vmax' shows it)");
    else
        snprintf(buf, cap, "%s", how);
    return buf;
}

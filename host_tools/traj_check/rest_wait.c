#include "rest_wait.h"

#include <stdio.h>

#include "fw/proto.h"
#include "fw/proto_table.h"
#include "fw/types.h"

/* Rest without motion this long after the command: it had nothing to do (already at rest). */
#define REST_WAIT_ALREADY_S 2.0

void rest_wait_begin(rest_wait *w, double expected_s, bool settled)
{
    w->limit_s = 3.0 * (expected_s > 0.0 ? expected_s : 60.0) + 60.0;
    w->settled = settled;
    w->seen_motion = false;
}

bool rest_state(int state)
{
    return state == FW_STATE_IDLE || state == FW_STATE_DISABLED || state == FW_STATE_FAULT || state == FW_STATE_ESTOP;
}

rest_verdict rest_wait_status(rest_wait *w, double elapsed_s, int state, int fault, const char *what, char *words,
                              size_t cap)
{
    if (elapsed_s > w->limit_s) {
        snprintf(words, cap, "%s did not come to rest within %.0f s", what, w->limit_s);
        return REST_WAIT_TIMEOUT;
    }
    if (state < 0)
        return REST_WAIT_ON;
    const char *st = proto_enum_name(proto_state_names, state), *ft = proto_enum_name(proto_fault_names, fault);
    if (!rest_state(state)) {
        w->seen_motion = true;
        return REST_WAIT_ON;
    }
    if (w->seen_motion || w->settled) {
        if (state == FW_STATE_IDLE && fault == FW_FAULT_NONE) {
            snprintf(words, cap, "%s: at rest after %.2f s", what, elapsed_s);
            return REST_WAIT_DONE;
        }
        snprintf(words, cap, "%s ended %s after %.2f s, fault %s", what, st, elapsed_s, ft);
        return REST_WAIT_ENDED;
    }
    if (elapsed_s <= REST_WAIT_ALREADY_S)
        return REST_WAIT_ON;
    if (state == FW_STATE_FAULT || state == FW_STATE_ESTOP) {
        snprintf(words, cap, "%s: the controller is %s, fault %s", what, st, ft);
        return REST_WAIT_ENDED;
    }
    snprintf(words, cap, "%s: already at rest", what);
    return REST_WAIT_ALREADY;
}

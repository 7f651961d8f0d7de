/* A controller's REJECT in words: what was refused, why, and what to do about it.
 *
 * The frame carries the reason and, per reason, the first failing scissor and kinematic status
 * and path position (kinematics), the slide, the limit and how far over it (timing), the state the
 * controller was in (state), the field or parameter (range, param_*) and the rule a refused set
 * breaks (param_set); the limits' and rules' words are the message table's (proto_table.h).  The text begins with the
 * reason's wire name, so scripts can match "rejected: timing". */
#ifndef TSECTL_REJECT_TEXT_H
#define TSECTL_REJECT_TEXT_H

#include <stddef.h>

#include "fw/proto.h"

/* Writes "rejected: REASON: explanation" into buf.  Returns buf. */
const char *reject_text(const proto_message *reject, char *buf, size_t cap);

/* Name of slide 1..6 ("A1", "B1", ... "B3"), or "?". */
const char *reject_slide_name(int slide);

#endif

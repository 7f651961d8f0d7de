/* A controller's MOVE_INFO in words: how an accepted move starts and what set its pace, so that a
 * move that takes longer than asked says why. */
#ifndef TSECTL_MOVE_TEXT_H
#define TSECTL_MOVE_TEXT_H

#include <stddef.h>

#include "fw/proto.h"

/* Writes the words after "move accepted: T s planned" (empty when the move starts from rest at
 * the pace asked), each part starting with ", ".  Returns buf. */
const char *move_info_text(const proto_message *info, char *buf, size_t cap);

#endif

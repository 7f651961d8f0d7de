#include "wire.h"

#include <string.h>

#include "fuzz_target.h"
#include "wire_ref.h"

void wire_classify(const hal_can_frame *f, uint8_t node, wire_frame *out)
{
    memset(out, 0, sizeof *out);
    const uint8_t to = (uint8_t)(f->id & PROTO_NODE_MASK);
    out->function = (uint8_t)(f->id >> PROTO_NODE_BITS);
    const proto_def *cmd = wire_ref_entry(out->function, PROTO_TO_CONTROLLER);
    if (to != node && to != PROTO_BROADCAST) {
        out->kind = WIRE_OTHER_NODE;
        return;
    }
    if (!cmd && wire_ref_entry(out->function, PROTO_TO_HOST)) {
        out->kind = WIRE_OWN_TRAFFIC;
        return;
    }
    if (cmd) {
        out->msg = cmd->msg;
        out->has_seq = cmd->nfields > 0 && strcmp(cmd->fields[0].name, "seq") == 0;
        if (f->len == cmd->dlc) {
            for (int i = 0; i < cmd->nfields; ++i) {
                const proto_field *fd = &cmd->fields[i];
                out->v[i] = wire_ref_field(f->data, fd);
                if (out->v[i] < fd->min || out->v[i] > fd->max)
                    out->bad_fields |= (uint8_t)(1u << i);
            }
            out->well_formed = out->bad_fields == 0;
            /* The sequence number is the frame's whenever its length is right: a bad field
             * elsewhere does not make it another message's. */
            if (out->has_seq && !(out->bad_fields & 1u))
                out->seq = (uint8_t)out->v[0];
        }
    }
    if (to == PROTO_BROADCAST)
        out->kind = WIRE_BROADCAST;
    else if (!cmd)
        out->kind = WIRE_UNKNOWN;
    else if (f->len != cmd->dlc)
        out->kind = WIRE_BAD_LENGTH;
    else if (out->bad_fields)
        out->kind = WIRE_RANGE;
    else
        out->kind = WIRE_COMMAND;
}

proto_msg wire_read_sent(const hal_can_frame *f, uint8_t node, int64_t v[PROTO_MAX_FIELDS])
{
    FUZZ_CHECK(f->id <= HAL_CAN_MAX_ID);
    FUZZ_CHECK((f->id & PROTO_NODE_MASK) == node);
    const proto_def *d = wire_ref_entry((uint8_t)(f->id >> PROTO_NODE_BITS), PROTO_TO_HOST);
    FUZZ_CHECK(d != NULL);
    FUZZ_CHECK(f->len == d->dlc);
    for (int i = 0; i < d->nfields; ++i) {
        const proto_field *fd = &d->fields[i];
        v[i] = wire_ref_field(f->data, fd);
        FUZZ_CHECK(v[i] >= fd->min && v[i] <= fd->max);
    }
    return d->msg;
}

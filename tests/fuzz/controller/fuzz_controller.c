/* The controller (firmware/) on the fake HAL, fed any sequence of frames, time and events decoded
 * from the fuzzer's bytes; after every frame, poll, control tick and step pulse the oracle
 * (oracle.h) holds it to docs/controller.md (the controller's behaviour) and docs/protocol.md.
 *
 * Encoding (make_seeds.py writes seeds in it; change both together).  Byte 0 picks the fixture
 * (rig.h, modulo RIG_FIXTURES); then operations, each an opcode byte (modulo OP_COUNT) and its
 * operands, until the input or the simulated time (rig.h's cap) ends.  Multi-byte operands are
 * little-endian.  SEQ is a 2-bit sequence mode: 0 the host's next number, 1 its current one (a
 * commit of the pose just staged), 2 a raw byte that follows, 3 the current one minus 1.
 *   WAIT_MS b          1 + b % 16 ms
 *   WAIT_TICKS b       1 + b step ticks (a frame then lands inside a segment)
 *   WAIT_LONG b        25 (1 + b % 40) ms
 *   WAIT_REST b        until the controller is at rest, at most 100 (1 + b % 32) ms
 *   CMD b              ESTOP, STOP, ENABLE, DISABLE, HOME or CLEAR_FAULT (b % 8 % 6); bit 3 to node
 *                      0; bits 4-5 SEQ
 *   MSG i v f...       the i-th (modulo) host-to-controller message of the table; v: bits 0-1 the
 *                      node (0, 1 ours, 2 broadcast, 3 another), bit 2 flip one bit (a byte
 *                      follows the fields: its position), bit 3 the sequence number from SEQ in
 *                      bits 4-5 instead of field bytes; fields: their width in bytes each, folded
 *                      onto the field's range (MOVE_COMMIT's value and TRAJ_COMMIT's dt onto
 *                      bounded ranges, see fold())
 *   POSE m x y z r p w the pose home + offsets (int16 each; 4 um or 4 urad a count, 128 times that
 *                      with m bit 5); m bits 0-2 the parts to send (0: all), bits 3-4 SEQ, bit 6
 *                      send C, B, A
 *   MOVE m v16         MOVE_COMMIT: m bits 0-1 SEQ, bit 2 by speed (50 mm/s + 8 v um/s) else
 *                      duration (1 + v % 2000 ms): moves the simulated time can see through
 *   TRAJ m v16         TRAJ_COMMIT: m bits 0-1 SEQ, bit 2 last row, bit 3 first row (its number
 *                      becomes the host's trajectory identity), bit 4 an identity one off the
 *                      host's; dt = 1 ms + 10 v us
 *   PARAM id m v32     id % 40 (or 16-bit id with m bit 4: two id bytes); m % 8: 0 set v folded
 *                      onto the range, 1 default + int16(v), 2 min + v % 256, 3 max - v % 256,
 *                      4 set v raw, 5 get, 6 save, 7 save with v as the magic
 *   RAW id16 len d8    any frame: id & 0x7FF, len % 9, 8 data bytes
 *   HOST b             bit 0 the host sends heartbeats every 10 ms; bit 1 one heartbeat now
 *   ESTOP_IN b         bit 0 open; bit 1 its interrupt fires as it opens
 *   LIMITS v16         switches forced pressed: v & 0x3F3F (bits 8..13 the high-end ones)
 *   BUS b              b % 4: bus-off, bus on, a bus-off recovered since, error passive toggled
 *   STORAGE b          bit 0 the flash fails
 *   HOOK b             the e-stop interrupt inside the controller: at fake hook point b % 4,
 *                      its 1 + (b / 4) % 8-th call
 *   REBOOT             power cycle
 *   PLANT_FAULT b      the platform reports a fault: plant (b even) or hardware */
#include <string.h>

#include "fuzz_target.h"
#include "rig.h"
#include "summary.h"

enum {
    OP_WAIT_MS, OP_WAIT_TICKS, OP_WAIT_LONG, OP_WAIT_REST, OP_CMD, OP_MSG, OP_POSE, OP_MOVE,
    OP_TRAJ, OP_PARAM, OP_RAW, OP_HOST, OP_ESTOP_IN, OP_LIMITS, OP_BUS, OP_STORAGE, OP_HOOK,
    OP_REBOOT, OP_PLANT_FAULT, OP_COUNT
};

const char *const fuzz_op_names[] = {
    "wait_ms", "wait_ticks", "wait_long", "wait_rest", "cmd", "msg", "pose", "move", "traj", "param",
    "raw", "host", "estop_in", "limits", "bus", "storage", "hook", "reboot", "plant_fault",
};
const unsigned fuzz_op_count = OP_COUNT;

typedef struct {
    const uint8_t *p;
    size_t n;
} input;

static bool take(input *in, uint8_t *out, size_t k)
{
    if (in->n < k)
        return false;
    memcpy(out, in->p, k);
    in->p += k;
    in->n -= k;
    return true;
}

static bool take8(input *in, uint8_t *b)
{
    return take(in, b, 1);
}

static bool take16(input *in, uint16_t *v)
{
    uint8_t b[2];
    if (!take(in, b, 2))
        return false;
    *v = (uint16_t)(b[0] | b[1] << 8);
    return true;
}

static bool take32(input *in, uint32_t *v)
{
    uint8_t b[4];
    if (!take(in, b, 4))
        return false;
    *v = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
    return true;
}

static rig R;

/* A sequence number by mode (SEQ). */
static bool seq_of(input *in, unsigned mode, int32_t *seq)
{
    uint8_t b = 0;
    switch (mode & 3u) {
    case 0:
        *seq = ++R.seq;
        return true;
    case 1:
        *seq = R.seq;
        return true;
    case 2:
        if (!take8(in, &b))
            return false;
        *seq = b;
        return true;
    default:
        *seq = (uint8_t)(R.seq - 1u);
        return true;
    }
}

static const proto_msg commands[] = {PM_ESTOP, PM_STOP, PM_ENABLE, PM_DISABLE, PM_HOME, PM_CLEAR_FAULT};

static uint8_t other_node(void)
{
    return (uint8_t)(R.cfg.node % 15u + 1u);
}

static bool op_cmd(input *in)
{
    uint8_t b;
    int32_t seq;
    if (!take8(in, &b) || !seq_of(in, b >> 4, &seq))
        return false;
    const int32_t v[1] = {seq};
    rig_feed_msg(&R, (b & 8u) ? PROTO_BROADCAST : R.cfg.node, commands[b % 8u % 6u], v);
    return true;
}

static const unsigned width[] = {[PF_U8] = 1, [PF_I8] = 1, [PF_U16] = 2, [PF_I16] = 2,
                                 [PF_U24] = 3, [PF_I24] = 3, [PF_U32] = 4, [PF_I32] = 4};

/* A field's raw bytes folded onto its range.  Two are folded tighter: a move is validated over its
 * whole path before it starts (a segment per millisecond), so MOVE_COMMIT's value becomes at most
 * 4 s, or at least 20 mm/s by speed; a trajectory point over its piece, so TRAJ_COMMIT's dt at
 * most 1 s.  Their full ranges are the codec fuzzer's and the unit tests' business (validating a
 * move of the longest duration, an hour, walks 3.6 million segments). */
static int32_t fold(proto_msg m, int field, const proto_field *fd, uint32_t raw, int32_t kind)
{
    int64_t lo = fd->min, hi = fd->max;
    if (m == PM_MOVE_COMMIT && field == 2) {
        lo = kind == 0 ? 1 : 20000;
        hi = kind == 0 ? 4000 : 2000000;
    } else if (m == PM_TRAJ_COMMIT && field == 1) {
        hi = 1000000;
    }
    const uint64_t span = (uint64_t)(hi - lo) + 1u;
    return (int32_t)(lo + (int64_t)(raw % span));
}

static bool op_msg(input *in)
{
    static proto_msg cmds[PM_COUNT];
    static unsigned ncmds;
    if (ncmds == 0)
        for (int i = 0; i < PM_COUNT; ++i)
            if (proto_table[i].dir == PROTO_TO_CONTROLLER)
                cmds[ncmds++] = (proto_msg)i;
    uint8_t idx, var;
    if (!take8(in, &idx) || !take8(in, &var))
        return false;
    const proto_def *d = &proto_table[cmds[idx % ncmds]];
    proto_message pm;
    memset(&pm, 0, sizeof pm);
    pm.msg = d->msg;
    const unsigned node_sel = var & 3u;
    pm.node = node_sel < 2 ? R.cfg.node : node_sel == 2 ? PROTO_BROADCAST : other_node();
    for (int i = 0; i < d->nfields; ++i) {
        const proto_field *fd = &d->fields[i];
        if (i == 0 && (var & 8u) && strcmp(fd->name, "seq") == 0) {
            if (!seq_of(in, var >> 4, &pm.v[0]))
                return false;
            continue;
        }
        uint8_t b[4] = {0};
        if (!take(in, b, width[fd->type]))
            return false;
        const uint32_t raw = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
        pm.v[i] = fold(d->msg, i, fd, raw, i > 1 ? pm.v[1] : 0);
    }
    hal_can_frame fr;
    FUZZ_CHECK(proto_encode(&pm, &fr) == 0);
    if (var & 4u) {
        uint8_t pos;
        if (!take8(in, &pos))
            return false;
        const unsigned bit = pos % 76u;
        if (bit < 11)
            fr.id ^= (uint16_t)(1u << bit);
        else if (bit == 11)
            fr.len = (uint8_t)((fr.len + 1u) % 9u);
        else
            fr.data[(bit - 12) / 8] ^= (uint8_t)(1u << ((bit - 12) % 8));
    }
    rig_feed(&R, &fr);
    return true;
}

static int32_t clamp(int64_t v, int32_t lo, int32_t hi)
{
    return (int32_t)(v < lo ? lo : v > hi ? hi : v);
}

static bool op_pose(input *in)
{
    uint8_t m, b[12];
    int32_t seq;
    if (!take8(in, &m) || !take(in, b, sizeof b) || !seq_of(in, m >> 3, &seq))
        return false;
    const int64_t scale = (m & 32u) ? 512 : 4;
    int32_t v[6];
    for (int k = 0; k < 6; ++k) {
        const int16_t off = (int16_t)(b[2 * k] | b[2 * k + 1] << 8);
        const proto_field *fd = &proto_table[PM_POSE_A + k / 2].fields[1 + k % 2];
        v[k] = clamp(R.home_um[k] + off * scale, fd->min, fd->max);
    }
    const unsigned parts = (m & 7u) ? (m & 7u) : 7u;
    for (int i = 0; i < 3; ++i) {
        const int part = (m & 64u) ? 2 - i : i;
        if ((parts >> part) & 1u) {
            const int32_t f[3] = {seq, v[2 * part], v[2 * part + 1]};
            rig_feed_msg(&R, R.cfg.node, (proto_msg)(PM_POSE_A + part), f);
        }
    }
    return true;
}

static bool op_move(input *in)
{
    uint8_t m;
    uint16_t v;
    int32_t seq;
    if (!take8(in, &m) || !take16(in, &v) || !seq_of(in, m, &seq))
        return false;
    const int32_t kind = (m & 4u) ? 1 : 0;
    const int32_t f[3] = {seq, kind, kind ? 50000 + 8 * (int32_t)v : 1 + v % 2000};
    rig_feed_msg(&R, R.cfg.node, PM_MOVE_COMMIT, f);
    return true;
}

static bool op_traj(input *in)
{
    uint8_t m;
    uint16_t v;
    int32_t seq;
    if (!take8(in, &m) || !take16(in, &v) || !seq_of(in, m, &seq))
        return false;
    static uint8_t traj_id; /* the host's trajectory: its first row's number */
    if (m & 8u)
        traj_id = (uint8_t)seq;
    const int32_t flags = ((m & 4u) ? (int32_t)PROTO_TRAJ_LAST : 0) | ((m & 8u) ? (int32_t)PROTO_TRAJ_FIRST : 0);
    const int32_t f[4] = {seq, 1000 + 10 * (int32_t)v, flags, (uint8_t)(traj_id + ((m & 16u) ? 1u : 0u))};
    rig_feed_msg(&R, R.cfg.node, PM_TRAJ_COMMIT, f);
    return true;
}

static bool op_param(input *in)
{
    uint8_t idb, m;
    uint16_t id16 = 0;
    uint32_t raw;
    if (!take8(in, &idb) || !take8(in, &m))
        return false;
    if ((m & 16u) && !take16(in, &id16))
        return false;
    if (!take32(in, &raw))
        return false;
    const unsigned id = (m & 16u) ? id16 : idb % 40u;
    const fw_param_def *d = id < FP_COUNT ? &fw_param_table[id] : NULL;
    int64_t value = (int32_t)raw;
    switch (m % 8u) {
    case 0:
        if (d)
            value = d->min + (int64_t)(raw % ((uint64_t)((int64_t)d->max - d->min) + 1u));
        break;
    case 1:
        value = (d ? d->def : 0) + (int16_t)raw;
        break;
    case 2:
        value = (d ? d->min : 0) + raw % 256u;
        break;
    case 3:
        value = (d ? d->max : 0) - raw % 256u;
        break;
    case 5: {
        const int32_t f[1] = {(int32_t)id};
        rig_feed_msg(&R, R.cfg.node, PM_PARAM_GET, f);
        return true;
    }
    case 6: {
        const int32_t f[1] = {proto_table[PM_PARAM_SAVE].fields[0].min};
        rig_feed_msg(&R, R.cfg.node, PM_PARAM_SAVE, f);
        return true;
    }
    case 7: { /* any magic: refused for its range unless it happens to be the one */
        hal_can_frame fr = {(uint16_t)(proto_table[PM_PARAM_SAVE].function << 4 | R.cfg.node), 4, {0}};
        memcpy(fr.data, &raw, 4);
        rig_feed(&R, &fr);
        return true;
    }
    default:
        break;
    }
    const int32_t f[2] = {(int32_t)id, (int32_t)value};
    rig_feed_msg(&R, R.cfg.node, PM_PARAM_SET, f);
    return true;
}

static bool op_raw(input *in)
{
    uint16_t id;
    uint8_t len;
    hal_can_frame fr;
    if (!take16(in, &id) || !take8(in, &len) || !take(in, fr.data, 8))
        return false;
    fr.id = id & HAL_CAN_MAX_ID;
    fr.len = len % 9u;
    rig_feed(&R, &fr);
    return true;
}

static bool op_event(input *in, unsigned op)
{
    uint8_t b = 0;
    uint16_t v = 0;
    if (op == OP_LIMITS) {
        if (!take16(in, &v))
            return false;
        R.f.forced_limits = v & 0x3F3Fu;
        rig_input_changed(&R);
        return true;
    }
    if (op == OP_REBOOT) {
        rig_reboot(&R);
        return true;
    }
    if (!take8(in, &b))
        return false;
    switch (op) {
    case OP_HOST:
        R.host_alive = b & 1u;
        if (b & 2u) {
            const int32_t f[1] = {b};
            rig_feed_msg(&R, R.cfg.node, PM_HOST_HEARTBEAT, f);
        }
        break;
    case OP_ESTOP_IN:
        rig_estop_input(&R, b & 1u, b & 2u);
        break;
    case OP_BUS:
        switch (b % 4u) {
        case 0:
            R.f.can_state.bus_off = true;
            ++R.f.can_state.bus_off_events;
            break;
        case 1:
            R.f.can_state.bus_off = false;
            break;
        case 2:
            ++R.f.can_state.bus_off_events;
            break;
        default:
            R.f.can_state.error_passive = !R.f.can_state.error_passive;
            break;
        }
        rig_input_changed(&R);
        break;
    case OP_STORAGE:
        R.f.storage_fails = b & 1u;
        break;
    case OP_HOOK:
        rig_arm_estop_hook(&R, (fake_hook_point)(b % 4u), 1u + (b / 4u) % 8u);
        break;
    case OP_PLANT_FAULT:
        rig_report_fault(&R, (b & 1u) ? FW_FAULT_HARDWARE : FW_FAULT_PLANT);
        break;
    default:
        break;
    }
    return true;
}

static bool step(input *in)
{
    uint8_t op, b;
    if (!take8(in, &op))
        return false;
    op %= OP_COUNT;
    summary_op(op);
    switch (op) {
    case OP_WAIT_MS:
        if (!take8(in, &b))
            return false;
        rig_run_ms(&R, 1u + b % 16u);
        return true;
    case OP_WAIT_TICKS:
        if (!take8(in, &b))
            return false;
        rig_advance(&R, 1u + b);
        return true;
    case OP_WAIT_LONG:
        if (!take8(in, &b))
            return false;
        rig_run_ms(&R, 25u * (1u + b % 40u));
        return true;
    case OP_WAIT_REST:
        if (!take8(in, &b))
            return false;
        rig_run_until_rest(&R, 100u * (1u + b % 32u));
        return true;
    case OP_CMD:
        return op_cmd(in);
    case OP_MSG:
        return op_msg(in);
    case OP_POSE:
        return op_pose(in);
    case OP_MOVE:
        return op_move(in);
    case OP_TRAJ:
        return op_traj(in);
    case OP_PARAM:
        return op_param(in);
    case OP_RAW:
        return op_raw(in);
    default:
        return op_event(in, op);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    summary_input();
    rig_start(&R, (rig_fixture)(data[0] % RIG_FIXTURES));
    input in = {data + 1, size - 1};
    while (!rig_over(&R) && step(&in)) {
    }
    /* Whatever the input left running goes on a little: what it set in motion is judged too. */
    rig_run_ms(&R, 50);
    return 0;
}

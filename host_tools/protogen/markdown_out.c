/* docs/protocol.md: the messages, enumerations, the state/command matrix and the parameters.
 * See outputs.h. */
#include <stdio.h>

#include "boot/image.h"
#include "boot/update.h"
#include "decimal_text.h"
#include "field_type.h"
#include "flags_text.h"
#include "fw/command_table.h"
#include "fw/params.h"
#include "fw/proto.h"
#include "outputs.h"

static const char *const state_col[] = {"boot", "disabled", "homing", "idle", "moving", "stopping", "fault", "estop"};

static void print_enum(FILE *out, const char *title, const proto_enum_entry *e)
{
    fprintf(out, "\n### %s\n\n| value | name |\n|---|---|\n", title);
    for (; e->name; ++e)
        fprintf(out, "| %d | `%s` |\n", (int)e->value, e->name);
}

static void print_codes(FILE *out, const char *title, const proto_code *c)
{
    fprintf(out, "\n### %s\n\n| value | name | meaning |\n|---|---|---|\n", title);
    for (; c->name; ++c)
        fprintf(out, "| %d | `%s` | %s |\n", (int)c->value, c->name, c->words);
}

/* The bootloader's protocol (boot/update.h), with the bus's limit it is measured against. */
static void updating(FILE *out)
{
    const unsigned frames = BOOT_BLOCK_BYTES / 8u;
    fprintf(out, "### Updating the firmware\n\n"
                 "A board's bootloader (its own image in the first flash sector) starts the application when the\n"
                 "application area holds a whole image for this board and no update was asked for; otherwise it\n"
                 "stays on the bus, as the same node, and takes one. `BOOT_ENTER` asks the application to restart\n"
                 "into it (refused `state` while the drives may be on); the bootloader's own commands are refused\n"
                 "`state` by an application, which is how a host tells the two apart. An update: `BOOT_QUERY`\n"
                 "(answered `BOOT_ID`: the bootloader's version, the board's identity, the block size;\n"
                 "`BOOT_LAYOUT`: the application area; `BOOT_APP`: the image in it, its version and CRC), then\n"
                 "`BOOT_ERASE` with the image's length (acknowledged once the sectors it needs are erased: seconds,\n"
                 "timed apart from the transfer), then the blocks in order from 0, then `BOOT_VERIFY`, then\n"
                 "`BOOT_START`. A host refuses an image whose header names another board before it erases\n"
                 "anything; the bootloader refuses it too (`board`, at block 0).\n\n"
                 "An image is the application's flash from its first byte, with a %u-byte header at offset 0x%X\n"
                 "(after the vector table): magic `TSEI`, header version %u, the board's identity (the CRC-32 of\n"
                 "its board name), the application's version, its length and the CRC-32 (IEEE 802.3, as zlib's\n"
                 "crc32) of bytes 0 .. length - 1 without the crc word itself (offset 0x%X). The build writes it\n"
                 "after linking. The bootloader holds block 0's header back while it writes the rest, and only\n"
                 "`BOOT_VERIFY`, once the CRC read back from flash matches, programs it, its magic word last: a\n"
                 "power cut at any moment leaves the old image whole (before the first erase took it), no image\n"
                 "(the bootloader stays), or the new one whole, and the bootloader never starts anything less.\n\n"
                 "A block is %u bytes: `BOOT_WRITE` (its number, its frames, its CRC-32), then %u `BOOT_DATA`\n"
                 "frames of 8 bytes at implicit offsets (fewer for the image's last block, its last frame padded),\n"
                 "answered by one `ACK` (detail: the block's number) once programmed, or a `REJECT`: `order` (not\n"
                 "the next block: `where` is the one expected), `address`, `length`, `crc`, `header`, `board`,\n"
                 "`flash`. A refused block writes nothing; the host sends again from it. The host keeps %u blocks\n"
                 "in flight: it sends block k + 1 while block k is programmed and acknowledged, so that neither\n"
                 "the round trip nor the programming stands in the bus's way.\n\n"
                 "**The bus's limit.** At 500 kbit/s an image's bits alone take `8 x length / 500000` s: 62,500\n"
                 "B/s, 1.39 s for 85 KiB. That is the limit an update is measured against (issue 28: at least\n"
                 "half of it, 31,250 B/s, 2.79 s for 85 KiB). No CAN transfer reaches it: a classic data frame\n"
                 "with 8 bytes (11-bit identifier) is 108 bits plus 3 of intermission, 111 bits for 64 bits of\n"
                 "payload, before stuff bits (one after five equal bits, up to 24 more in the 98 bits from the\n"
                 "start of frame to the CRC). So 8-byte frames back to back carry at most 64 / 111 of the bit\n"
                 "rate, 36,036 B/s (57.7 %% of the limit) without stuffing, 29,630 B/s (47.4 %%) with the most\n"
                 "stuffing data can cause. An update adds a `BOOT_WRITE` and an `ACK` to every %u `BOOT_DATA`\n"
                 "frames (98.5 %% of the frames carry the image): 35,481 B/s, 56.8 %% of the limit, before\n"
                 "stuffing; `BOOT_DATA`'s identifier (0x7E0 + node) costs one stuff bit a frame, and the image's\n"
                 "own bits some more. `tsectl flash` prints the rate it reached against the limit.\n\n",
            (unsigned)sizeof(boot_image_header), BOOT_IMAGE_HEADER_OFFSET, BOOT_IMAGE_HEADER_VERSION,
            BOOT_IMAGE_CRC_OFFSET, BOOT_BLOCK_BYTES, frames, BOOT_WINDOW_BLOCKS, frames);
}

static void intro(FILE *out)
{
    fprintf(out, "# TSE controller CAN protocol\n\n");
    fprintf(out, "Generated by `host_tools/protogen` from the message table in `firmware/include/fw/proto_messages.def`;\n"
                 "do not edit by hand (a test fails when this file differs from the table).\n\n");
    fprintf(out, "Classic CAN 2.0A frames, 11-bit identifiers `id = function << 4 | node`: controllers are nodes\n"
                 "1..15, node 0 addresses every controller (only `ESTOP` and `STOP` honour it, and nothing answers\n"
                 "a broadcast). A lower function code wins arbitration, so `ESTOP` goes first. Integers only,\n"
                 "little-endian; every message has one fixed length. A frame of the wrong length, an unknown\n"
                 "function, a field outside its range or a command the state does not accept is answered with\n"
                 "`REJECT` naming the reason, and changes nothing. The states, what moves the controller from\n"
                 "one to another and what each command does in each are in [controller.md](controller.md).\n"
                 "A controller's node id is its parameter `node`, taken at start-up (below). A host finds the\n"
                 "controllers on a bus by sending `INFO_GET` pages 0 and 1 to each node 1..15 and reading who\n"
                 "answers with `INFO` and `BOARD` (`tsectl scan`, `tse.can.scan`).\n\n");
    fprintf(out, "A pose is staged in `POSE_A`, `POSE_B`, `POSE_C` under one sequence number and applied by a\n"
                 "commit (`MOVE_COMMIT` or `TRAJ_COMMIT`) carrying the same number: only when all three parts of\n"
                 "that number arrived (in any order), and only when the number is newer than the last accepted\n"
                 "commit (modulo 256, ahead by 1..127). A part under another number than the one being staged\n"
                 "starts the staging afresh (so a late part of an abandoned pose makes the next commit\n"
                 "`incomplete`, and a stray part can never lock the host out); a part whose number is not\n"
                 "newer than the last accepted commit is refused `stale` and changes nothing.\n"
                 "A commit refused for its content spends its number.\n\n");
    fprintf(out, "### Streaming a trajectory\n\n"
                 "A trajectory is a run of `TRAJ_COMMIT` rows. Its first row carries flag bit 1 (first) and an\n"
                 "identity the host chooses (`traj`; tsectl and tse.can use the first row's sequence number), and\n"
                 "is taken only while idle; every later row carries the same identity and the sequence number\n"
                 "after its previous row's, else it is refused `order` (nothing taken) or, once the trajectory\n"
                 "has ended, `ended` in any state (saying how it ended and how long before the row came), so a\n"
                 "row of a stopped trajectory never starts or joins another. The controller starts the\n"
                 "trajectory's clock (`t = 0` of its first row's `dt`) once its queue holds `traj_lead` of path,\n"
                 "or the last row (flag bit 0), or the queue is full; until then the plate is at rest. Once\n"
                 "running, a queue that holds less path than a stop needs is an underrun: the controller stops\n"
                 "along what it holds and latches `underrun`. `TRAJ_END` says once how each trajectory ended.\n\n"
                 "A host keeps the queue ahead by sending rows as `ACK` and `STATUS` report free slots, with up\n"
                 "to %d rows in flight (sent, not yet answered): %d rows are %d frames, at most half the board's\n"
                 "receive ring. A row refused `queue_full` is sent again, in order, with the rows after it\n"
                 "(refused `order` meanwhile), once there is room.\n\n",
            PROTO_TRAJ_WINDOW, PROTO_TRAJ_WINDOW, 4 * PROTO_TRAJ_WINDOW);
    updating(out);
    fprintf(out, "In the message tables, a field's physical value is its raw value times its \"one raw count\";\n"
                 "`-` marks a plain number or code.\n");
}

/* The "one raw count" cell: the scale with its unit, or "-" for a plain number. */
static int count_cell(const proto_field *f, char *cell, size_t n)
{
    if (!f->unit[0]) {
        snprintf(cell, n, "-");
        return 0;
    }
    char scale[64];
    if (dec_shortest(f->scale, scale, sizeof scale) != 0)
        return -1;
    const int len = snprintf(cell, n, "%s %s", scale, f->unit);
    return len < 0 || (size_t)len >= n ? -1 : 0;
}

static int messages(FILE *out)
{
    fprintf(out, "\n## Messages\n");
    for (int i = 0; i < PM_COUNT; ++i) {
        const proto_def *d = &proto_table[i];
        fprintf(out, "\n### `%s`: function 0x%02X, id 0x%03X + node, %u byte%s, %s\n\n%s\n", d->name, d->function,
                d->function << PROTO_NODE_BITS, d->dlc, d->dlc == 1 ? "" : "s",
                d->dir == PROTO_TO_CONTROLLER ? "host to controller" : "controller to host", d->doc);
        if (d->nfields == 0)
            continue;
        fprintf(out, "\n| byte | field | type | range (raw) | one raw count | meaning |\n|---|---|---|---|---|---|\n");
        for (int k = 0; k < d->nfields; ++k) {
            const proto_field *f = &d->fields[k];
            char cell[160];
            if (count_cell(f, cell, sizeof cell) != 0) {
                fprintf(stderr, "protogen: %s.%s: scale %g and unit '%s' do not print in %zu characters\n", d->name,
                        f->name, f->scale, f->unit, sizeof cell - 1);
                return -1;
            }
            char meaning[4096];
            if (field_meaning((proto_msg)i, k, meaning, sizeof meaning) != 0)
                return -1;
            fprintf(out, "| %u | `%s` | %s | %ld .. %ld | %s | %s%s |\n", f->offset, f->name, ft_name(f->type),
                    (long)f->min, (long)f->max, cell, meaning, f->values ? " (values below)" : "");
        }
    }
    return 0;
}

static void state_matrix(FILE *out)
{
    fprintf(out, "\n## Which command each state accepts\n\n`A` accepted (acknowledged, except heartbeats and pose "
                 "parts), `-` refused with `state`. Motion commands also need homing (`not_homed`), and a trajectory "
                 "point is accepted while moving only in trajectory mode. What an accepted command does in each state: "
                 "[controller.md](controller.md), \"Commands in each state\".\n\n| command |");
    for (int s = 0; s < FW_STATE_COUNT; ++s)
        fprintf(out, " %s |", state_col[s]);
    fprintf(out, "\n|---|");
    for (int s = 0; s < FW_STATE_COUNT; ++s)
        fprintf(out, "---|");
    fprintf(out, "\n");
    for (int i = 0; i < PM_COUNT; ++i) {
        if (proto_table[i].dir != PROTO_TO_CONTROLLER)
            continue;
        fprintf(out, "| `%s` |", proto_table[i].name);
        for (int s = 0; s < FW_STATE_COUNT; ++s)
            fprintf(out, " %s |", fw_command_allowed((proto_msg)i, (fw_state)s) == FW_REASON_NONE ? "A" : "-");
        fprintf(out, "\n");
    }
}

static void parameters(FILE *out)
{
    fprintf(out, "\n## Parameters (`PARAM_GET`, `PARAM_SET`, `PARAM_SAVE`)\n\n"
                 "Set only while disabled or in a fault; each value is range-checked, then the whole set is\n"
                 "checked (kinematics.md's valid parameter sets; the homing switches inside the stroke and\n"
                 "reachable all at once; the STEP pulse and DIR set-up against the controller's step interrupt\n"
                 "rate) before it replaces the old one, and the drivers' timing is programmed at once. A set\n"
                 "refused as a whole is answered `param_set` with the parameter set in `field` and the rule it\n"
                 "breaks in `where` (\"param_set rule\" above).\n"
                 "`can_kbps`, `node` and `enable_level` are only stored: the board applies them at start-up\n"
                 "(tse-sim takes `node` unless `--node` overrides it), so they take effect after `PARAM_SAVE`\n"
                 "and a restart. Until then `PARAM_GET` shows the value stored, and a controller whose `node` was\n"
                 "set keeps answering on the id it started with (its `PARAM_VALUE` too); `tsectl node set`\n"
                 "does the set and the save. A unit of 1 is a plain number (an id, a code).\n\n"
                 "| id | name | unit | min | max | default | meaning |\n|---|---|---|---|---|---|---|\n");
    for (int i = 0; i < FP_COUNT; ++i) {
        const fw_param_def *p = &fw_param_table[i];
        fprintf(out, "| %d | `%s` | %s | %ld | %ld | %ld | %s |\n", i, p->name, p->unit, (long)p->min, (long)p->max,
                (long)p->def, p->doc);
    }
}

int gen_markdown(FILE *out)
{
    intro(out);
    if (messages(out) != 0)
        return -1;
    fprintf(out, "\n## Enumerations\n");
    for (const proto_enum_def *d = proto_enums; d->table; ++d)
        print_enum(out, d->title, d->table);
    for (const proto_code_def *d = proto_code_tables; d->table; ++d)
        print_codes(out, d->title, d->table);
    state_matrix(out);
    parameters(out);
    return 0;
}

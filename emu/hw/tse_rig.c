/*
 * tse-rig: the six slides, their homing switches and the e-stop chain of the TSE, wired to the
 * board as docs/board.md says, and a text interface to read and drive them (the "chardev"
 * property; docs/emulator.md describes the protocol).
 *
 * The drivers: a slide moves one step on each STEP pulse while ENABLE is high (low with the property "enable-active-low"), towards +s when
 * DIR is high.  Like a real driver it misses a pulse high for less than step-pulse-ns (default
 * 2500: the DM542's minimum, docs/board.md), and takes a step whose rising edge comes less than
 * dir-setup-ns (5000) after a change of DIR in the direction DIR had before (property "miss-violations", on by default; off, such
 * steps count as the firmware meant them).  Either way each such event is logged with its
 * virtual time, slide and the time measured (`log`).  Positions: initial + steps / steps-per-m.
 *
 * The switches: normally-closed contacts to GND; a slide's switch is pressed (open: the pin's
 * pull-up reads 1) at and below its switch position, released (closed: 0) above, unless forced
 * (`switch K open|closed|auto`).  The e-stop chain: closed (0) until `estop open`.
 *
 * The slides keep their positions over resets and power cycles (`reset`): they are mechanics.
 *
 * What the rig also observes, for the figures a test reports: the frames the controller takes
 * from the bus (bxCAN's rx line) and the watchdog's reloads (the IWDG's reload line).
 * `firststep` gives the virtual time the controller took the last frame with identifier mark-id
 * (default 0x0D1: a MOVE_COMMIT to node 1, docs/protocol.md) and of the first STEP edge a driver
 * took after it: a command's latency to motion.  `feedgap` gives the longest time between two
 * reloads since the last `feedgap` (the image feeds the watchdog from its main loop's idle hook,
 * so this is the longest pause of its main loop), and how many reloads there were.
 *
 * SPDX-License-Identifier: GPL-2.0-or-later
 */
#include "qemu/osdep.h"
#include <math.h>
#include "qemu/cutils.h"
#include "qemu/error-report.h"
#include "qemu/timer.h"
#include "qapi/error.h"
#include "hw/sysbus.h"
#include "hw/irq.h"
#include "hw/qdev-properties.h"
#include "hw/qdev-properties-system.h"
#include "chardev/char-fe.h"
#include "tse_f407.h"

OBJECT_DECLARE_SIMPLE_TYPE(TseRigState, TSE_RIG)

#define SLIDES 6
/* Where the slides stand when the emulator starts, and where their switches trip (the
 * firmware's home_sw_k default), in metres. */
#define RIG_DEFAULT_INITIAL_M "0.25"
#define RIG_DEFAULT_SWITCH_M "0.2"
#define LOG_MAX 1000
#define REQUEST_MAX 256

enum { SW_AUTO, SW_OPEN, SW_CLOSED };

typedef struct {
    int64_t t;
    int slide;
    int64_t ns;
    bool pulse; /* else a DIR set-up violation */
} RigEvent;

typedef struct {
    int64_t steps;
    bool step_level, dir_level;
    int64_t step_rise;     /* time of the STEP rising edge */
    int64_t dir_change;    /* time of the last DIR change */
    bool dir_before;       /* DIR's level before that change */
    int step_dir;          /* the direction the pulse in progress steps (+1/-1), 0: none */
    int force;             /* SW_* */
    int sw_sent;           /* what the switch output last drove (-2: nothing yet) */
} Slide;

struct TseRigState {
    SysBusDevice parent_obj;
    CharBackend chr;
    Slide slide[SLIDES];
    bool enable;
    bool estop_open;
    int estop_sent;
    qemu_irq sw_out[SLIDES], estop_out, power_out, canerr_out;
    double initial[SLIDES], switch_at[SLIDES];
    RigEvent log[LOG_MAX];
    unsigned log_len;
    uint64_t log_dropped;
    char line[REQUEST_MAX];
    unsigned line_len;
    bool line_overflow;

    /* observations */
    int64_t mark_t;       /* when the controller took the last marked frame (-1: none) */
    int64_t mark_step_t;  /* the first STEP edge taken after it (-1: none yet) */
    int64_t feed_t;       /* the last watchdog reload (-1: none) */
    int64_t feed_gap;     /* the longest time between two reloads since the last `feedgap` */
    uint64_t feeds;
    uint64_t flash_ops;   /* flash erase and program operations started, since the emulator started */
    uint64_t cut_at;      /* power-cycle as operation number cut_at starts (0: not armed) */

    /* properties */
    uint32_t mark_id;
    uint32_t steps_per_m;
    char *initial_m, *switch_m;
    uint32_t step_pulse_ns, dir_setup_ns;
    bool miss_violations;
    bool enable_active_low;
};

static int64_t now_ns(void)
{
    return qemu_clock_get_ns(QEMU_CLOCK_VIRTUAL);
}

static double position(TseRigState *s, int k)
{
    return s->initial[k] + (double)s->slide[k].steps / s->steps_per_m;
}

/* Drives the switch pins and the e-stop pin: a closed contact pulls to 0, an open one lets go. */
static void update_outputs(TseRigState *s)
{
    for (int k = 0; k < SLIDES; ++k) {
        Slide *sl = &s->slide[k];
        const bool open = sl->force == SW_AUTO ? position(s, k) <= s->switch_at[k] + 1e-12
                                               : sl->force == SW_OPEN;
        const int drive = open ? -1 : 0;
        if (drive != sl->sw_sent) {
            sl->sw_sent = drive;
            qemu_set_irq(s->sw_out[k], drive);
        }
    }
    if (s->estop_sent != (s->estop_open ? -1 : 0)) {
        s->estop_sent = s->estop_open ? -1 : 0;
        qemu_set_irq(s->estop_out, s->estop_sent);
    }
}

static void note(TseRigState *s, int k, int64_t ns, bool pulse)
{
    if (s->log_len == LOG_MAX) {
        ++s->log_dropped;
        return;
    }
    s->log[s->log_len++] = (RigEvent){ now_ns(), k, ns, pulse };
}

static void step_in(void *opaque, int k, int level)
{
    TseRigState *s = opaque;
    Slide *sl = &s->slide[k];
    const int64_t t = now_ns();
    level = level != 0;
    if (level == sl->step_level) {
        return;
    }
    sl->step_level = level;
    if (level) {
        sl->step_rise = t;
        sl->step_dir = 0;
        if (!s->enable) {
            return; /* a disabled driver ignores its STEP input */
        }
        bool dir = sl->dir_level;
        if (t - sl->dir_change < s->dir_setup_ns) {
            note(s, k, t - sl->dir_change, false);
            if (s->miss_violations) {
                dir = sl->dir_before;
            }
        }
        sl->step_dir = dir ? 1 : -1;
        if (s->mark_t >= 0 && s->mark_step_t < 0) {
            s->mark_step_t = t;
        }
        return;
    }
    /* Falling edge: the pulse is complete; a short one is missed. */
    if (sl->step_dir == 0) {
        return;
    }
    const int64_t width = t - sl->step_rise;
    if (width < s->step_pulse_ns) {
        note(s, k, width, true);
        if (s->miss_violations) {
            sl->step_dir = 0;
            return;
        }
    }
    sl->steps += sl->step_dir;
    sl->step_dir = 0;
    update_outputs(s);
}

static void dir_in(void *opaque, int k, int level)
{
    TseRigState *s = opaque;
    Slide *sl = &s->slide[k];
    level = level != 0;
    if (level != sl->dir_level) {
        sl->dir_before = sl->dir_level;
        sl->dir_level = level;
        sl->dir_change = now_ns();
    }
}

/* The drivers' enable: high enables them, or low with enable-active-low (a stepstick's EN, as on
 * the monster8 board). */
static void enable_in(void *opaque, int n, int level)
{
    TseRigState *s = TSE_RIG(opaque);
    s->enable = s->enable_active_low ? level == 0 : level != 0;
}

/* bxCAN took a frame: level 1 + its identifier (then 0). */
static void can_rx_in(void *opaque, int n, int level)
{
    TseRigState *s = opaque;
    if (level > 0 && (uint32_t)(level - 1) == s->mark_id) {
        s->mark_t = now_ns();
        s->mark_step_t = -1;
    }
}

static void feed_in(void *opaque, int n, int level)
{
    TseRigState *s = opaque;
    if (!level) {
        return;
    }
    const int64_t t = now_ns();
    if (s->feed_t >= 0 && t - s->feed_t > s->feed_gap) {
        s->feed_gap = t - s->feed_t;
    }
    s->feed_t = t;
    ++s->feeds;
}

/* A flash operation starts: counted; the one `cutflash` named starts and the power goes (the
 * flash model leaves what it had not done of it undone: a program not applied, an erase partial). */
static void flash_op_in(void *opaque, int n, int level)
{
    TseRigState *s = opaque;
    if (!level) {
        return;
    }
    ++s->flash_ops;
    if (s->cut_at && s->flash_ops == s->cut_at) {
        s->cut_at = 0;
        qemu_irq_pulse(s->power_out);
    }
}

/* ---- the text interface ---- */

static void say(TseRigState *s, const char *fmt, ...) G_GNUC_PRINTF(2, 3);
static void say(TseRigState *s, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    g_autofree char *text = g_strdup_vprintf(fmt, ap);
    va_end(ap);
    qemu_chr_fe_write_all(&s->chr, (const uint8_t *)text, strlen(text));
}

static void answer_log(TseRigState *s)
{
    for (unsigned i = 0; i < s->log_len; ++i) {
        const RigEvent *e = &s->log[i];
        say(s, "%s %" PRId64 " %d %" PRId64 "\n", e->pulse ? "pulse" : "dir", e->t, e->slide + 1, e->ns);
    }
    if (s->log_dropped) {
        say(s, "dropped %" PRIu64 "\n", s->log_dropped);
    }
    s->log_len = 0;
    s->log_dropped = 0;
    say(s, "end\nok\n");
}

static void request(TseRigState *s, char *line)
{
    char *argv[4];
    int argc = 0;
    for (char *p = strtok(line, " \t"); p && argc < 4; p = strtok(NULL, " \t")) {
        argv[argc++] = p;
    }
    if (argc == 0) {
        return;
    }
    const char *cmd = argv[0];
    if (!strcmp(cmd, "slides") && argc == 1) {
        say(s, "slides");
        for (int k = 0; k < SLIDES; ++k) {
            say(s, " %.9f", position(s, k));
        }
        say(s, "\nok\n");
    } else if (!strcmp(cmd, "steps") && argc == 1) {
        say(s, "steps");
        for (int k = 0; k < SLIDES; ++k) {
            say(s, " %" PRId64, s->slide[k].steps);
        }
        say(s, "\nok\n");
    } else if (!strcmp(cmd, "time") && argc == 1) {
        say(s, "time %" PRId64 "\nok\n", now_ns());
    } else if (!strcmp(cmd, "log") && argc == 1) {
        answer_log(s);
    } else if (!strcmp(cmd, "firststep") && argc == 1) {
        say(s, "firststep %" PRId64 " %" PRId64 "\nok\n", s->mark_t, s->mark_step_t);
    } else if (!strcmp(cmd, "feedgap") && argc == 1) {
        say(s, "feedgap %" PRId64 " %" PRIu64 "\nok\n", s->feed_gap, s->feeds);
        s->feed_gap = 0;
        s->feeds = 0;
    } else if (!strcmp(cmd, "flashops") && argc == 1) {
        say(s, "flashops %" PRIu64 "\nok\n", s->flash_ops);
    } else if (!strcmp(cmd, "cutflash") && argc == 2 && !strcmp(argv[1], "off")) {
        s->cut_at = 0;
        say(s, "ok\n");
    } else if (!strcmp(cmd, "cutflash") && argc == 2 && strspn(argv[1], "0123456789") == strlen(argv[1]) &&
               strlen(argv[1]) <= 9 && atoi(argv[1]) >= 1) {
        s->cut_at = s->flash_ops + (uint64_t)atoi(argv[1]);
        say(s, "ok\n");
    } else if (!strcmp(cmd, "estop") && argc == 2 && (!strcmp(argv[1], "open") || !strcmp(argv[1], "closed"))) {
        s->estop_open = !strcmp(argv[1], "open");
        update_outputs(s);
        say(s, "ok\n");
    } else if (!strcmp(cmd, "switch") && argc == 3) {
        const int k = atoi(argv[1]);
        const int force = !strcmp(argv[2], "open") ? SW_OPEN : !strcmp(argv[2], "closed") ? SW_CLOSED
                        : !strcmp(argv[2], "auto") ? SW_AUTO : -1;
        if (k < 1 || k > SLIDES || strspn(argv[1], "0123456789") != strlen(argv[1])) {
            say(s, "error: switch: slide '%s' is not 1..6\n", argv[1]);
        } else if (force < 0) {
            say(s, "error: switch: '%s' is not open, closed or auto\n", argv[2]);
        } else {
            s->slide[k - 1].force = force;
            update_outputs(s);
            say(s, "ok\n");
        }
    } else if (!strcmp(cmd, "canerr") && argc == 2 && (!strcmp(argv[1], "on") || !strcmp(argv[1], "off"))) {
        qemu_set_irq(s->canerr_out, !strcmp(argv[1], "on"));
        say(s, "ok\n");
    } else if (!strcmp(cmd, "reset") && argc == 1) {
        qemu_irq_pulse(s->power_out);
        say(s, "ok\n");
    } else if (!strcmp(cmd, "estop") || !strcmp(cmd, "canerr") || !strcmp(cmd, "switch") ||
               !strcmp(cmd, "slides") || !strcmp(cmd, "steps") || !strcmp(cmd, "time") ||
               !strcmp(cmd, "log") || !strcmp(cmd, "reset") || !strcmp(cmd, "firststep") ||
               !strcmp(cmd, "feedgap") || !strcmp(cmd, "flashops") || !strcmp(cmd, "cutflash")) {
        say(s, "error: %s: wrong arguments (slides | steps | time | log | firststep | feedgap | flashops | reset | "
            "estop open|closed | switch K open|closed|auto | canerr on|off | cutflash N|off)\n", cmd);
    } else {
        say(s, "error: unknown request '%s' (slides, steps, time, log, firststep, feedgap, flashops, reset, estop, "
            "switch, canerr, cutflash)\n", cmd);
    }
}

static int chr_can_read(void *opaque)
{
    return REQUEST_MAX;
}

static void chr_read(void *opaque, const uint8_t *buf, int size)
{
    TseRigState *s = opaque;
    for (int i = 0; i < size; ++i) {
        const char c = buf[i];
        if (c == '\n') {
            s->line[s->line_len] = 0;
            if (s->line_len && s->line[s->line_len - 1] == '\r') {
                s->line[--s->line_len] = 0;
            }
            if (s->line_overflow) {
                say(s, "error: request longer than %d bytes\n", REQUEST_MAX - 1);
            } else {
                request(s, s->line);
            }
            s->line_len = 0;
            s->line_overflow = false;
        } else if (s->line_len < REQUEST_MAX - 1) {
            s->line[s->line_len++] = c;
        } else {
            s->line_overflow = true;
        }
    }
}

/* A client gone: what it left of a request is dropped, so the next client starts afresh. */
static void chr_event(void *opaque, QEMUChrEvent event)
{
    TseRigState *s = opaque;
    if (event == CHR_EVENT_CLOSED || event == CHR_EVENT_OPENED) {
        s->line_len = 0;
        s->line_overflow = false;
    }
}

/* ---- configuration ---- */

/* "X" (all six) or "X1,X2,...,X6", metres. */
static bool parse_six(const char *name, const char *text, double out[SLIDES], Error **errp)
{
    g_auto(GStrv) parts = g_strsplit(text, ",", -1);
    const guint n = g_strv_length(parts);
    if (n != 1 && n != SLIDES) {
        error_setg(errp, "tse-rig: %s '%s': give one value or six, comma-separated", name, text);
        return false;
    }
    for (int k = 0; k < SLIDES; ++k) {
        const char *p = parts[n == 1 ? 0 : k];
        char *end;
        errno = 0;
        out[k] = g_ascii_strtod(p, &end);
        if (errno || end == p || *end || !isfinite(out[k])) {
            error_setg(errp, "tse-rig: %s: '%s' is not a number of metres", name, p);
            return false;
        }
    }
    return true;
}

static void rig_realize(DeviceState *dev, Error **errp)
{
    TseRigState *s = TSE_RIG(dev);
    if (s->steps_per_m == 0) {
        error_setg(errp, "tse-rig: steps-per-m must not be 0");
        return;
    }
    if (!parse_six("initial-m", s->initial_m ? s->initial_m : RIG_DEFAULT_INITIAL_M, s->initial, errp) ||
        !parse_six("switch-m", s->switch_m ? s->switch_m : RIG_DEFAULT_SWITCH_M, s->switch_at, errp)) {
        return;
    }
    for (int k = 0; k < SLIDES; ++k) {
        s->slide[k].sw_sent = -2;
        s->slide[k].dir_change = INT64_MIN / 2;
    }
    s->mark_t = s->mark_step_t = s->feed_t = -1;
    if (qemu_chr_fe_backend_connected(&s->chr)) {
        qemu_chr_fe_set_handlers(&s->chr, chr_can_read, chr_read, chr_event, NULL, s, NULL, true);
    }
}

/* A reset (the controller's) changes nothing of the mechanics; the pins are driven again for
 * the GPIO ports, which forget what drove them. */
static void rig_reset(DeviceState *dev)
{
    TseRigState *s = TSE_RIG(dev);
    for (int k = 0; k < SLIDES; ++k) {
        s->slide[k].sw_sent = -2;
    }
    s->estop_sent = -2;
    s->feed_t = -1; /* a restart is not a pause of the main loop */
    update_outputs(s);
}

static void rig_init(Object *obj)
{
    TseRigState *s = TSE_RIG(obj);
    DeviceState *dev = DEVICE(obj);
    qdev_init_gpio_in_named(dev, step_in, RIG_IN_STEP, SLIDES);
    qdev_init_gpio_in_named(dev, dir_in, RIG_IN_DIR, SLIDES);
    qdev_init_gpio_in_named(dev, enable_in, RIG_IN_ENABLE, 1);
    qdev_init_gpio_in_named(dev, can_rx_in, RIG_IN_CAN_RX, 1);
    qdev_init_gpio_in_named(dev, feed_in, RIG_IN_FEED, 1);
    qdev_init_gpio_in_named(dev, flash_op_in, RIG_IN_FLASH_OP, 1);
    qdev_init_gpio_out_named(dev, s->sw_out, RIG_OUT_SWITCH, SLIDES);
    qdev_init_gpio_out_named(dev, &s->estop_out, RIG_OUT_ESTOP, 1);
    qdev_init_gpio_out_named(dev, &s->power_out, RIG_OUT_POWER, 1);
    qdev_init_gpio_out_named(dev, &s->canerr_out, RIG_OUT_CANERR, 1);
}

static Property rig_properties[] = {
    DEFINE_PROP_CHR("chardev", TseRigState, chr),
    DEFINE_PROP_UINT32("steps-per-m", TseRigState, steps_per_m, 1280000),
    DEFINE_PROP_STRING("initial-m", TseRigState, initial_m),
    DEFINE_PROP_STRING("switch-m", TseRigState, switch_m),
    DEFINE_PROP_UINT32("step-pulse-ns", TseRigState, step_pulse_ns, 2500),
    DEFINE_PROP_UINT32("dir-setup-ns", TseRigState, dir_setup_ns, 5000),
    DEFINE_PROP_BOOL("miss-violations", TseRigState, miss_violations, true),
    DEFINE_PROP_BOOL("enable-active-low", TseRigState, enable_active_low, false),
    DEFINE_PROP_UINT32("mark-id", TseRigState, mark_id, 0x0D1),
    DEFINE_PROP_END_OF_LIST(),
};

static void rig_class_init(ObjectClass *klass, void *data)
{
    DeviceClass *dc = DEVICE_CLASS(klass);
    dc->realize = rig_realize;
    dc->reset = rig_reset;
    device_class_set_props(dc, rig_properties);
}

static const TypeInfo rig_info = {
    .name = TYPE_TSE_RIG,
    .parent = TYPE_SYS_BUS_DEVICE,
    .instance_size = sizeof(TseRigState),
    .instance_init = rig_init,
    .class_init = rig_class_init,
};

static void rig_register_types(void)
{
    type_register_static(&rig_info);
}

type_init(rig_register_types)

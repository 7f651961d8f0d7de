#include "fw/params.h"

#include "fw/doc.h"
#include "fw/proto_table.h"
#include "fw/types.h"
#include "fw/joint_path.h"
#include "tse/ik.h"
#include "tse/prototype.h"

/* Prototype defaults (paper, section VI; kinematics.md).  The slides: a 200-step motor at 1/64
 * microstepping on a 10 mm lead, 0.78 um per step, fine enough that rounding the six slides to
 * whole steps moves the plate by well under 1e-5 rad; their speed limit keeps the step rate
 * (192 kHz at 0.15 m/s) under the 200 kHz a slide may be stepped at. */
#define HOME_SW_DOC(k)                                                                             \
    "where slide " #k "'s homing switch trips: pressed at and below, released above; homing sets "  \
    "the slide's coordinate at the edge; once homed, a disagreement beyond 0.5 mm is a limit "      \
    "fault; a change needs homing again"

/* The kinematic parameters' integer units, um, ppm and urad, are millionths of the SI unit; the
 * prototype's values (tse/prototype.h) rounded to them, at compile time. */
#define MILLIONTHS(x) ((int32_t)((x) * 1e6 + 0.5))

const fw_param_def fw_param_table[FP_COUNT] = {
    [FP_L] = {TSE_PARAM_NAME_L, "um", 100000, 10000000, MILLIONTHS(TSE_PROTO_L), FW_DOC("total scissor length")},
    [FP_K1] = {TSE_PARAM_NAME_K1, "ppm", 1, 1000000, MILLIONTHS(TSE_PROTO_K1), FW_DOC("l0 / L")},
    [FP_ETA] = {TSE_PARAM_NAME_ETA, "urad", -1570796, 1570796, MILLIONTHS(TSE_PROTO_ETA), FW_DOC("slide angle from the local x axis")},
    [FP_K3] = {TSE_PARAM_NAME_K3, "ppm", 0, 1000000, MILLIONTHS(TSE_PROTO_K3), FW_DOC("r_act / L")},
    [FP_K4] = {TSE_PARAM_NAME_K4, "ppm", 1, 1000000, MILLIONTHS(TSE_PROTO_K4), FW_DOC("r_top / L")},
    [FP_ALPHA_MIN] = {TSE_PARAM_NAME_ALPHA_MIN, "urad", 1, 1570796, MILLIONTHS(TSE_PROTO_ALPHA_MIN), FW_DOC("scissor angle stop, low")},
    [FP_ALPHA_MAX] = {TSE_PARAM_NAME_ALPHA_MAX, "urad", 1, 1570796, MILLIONTHS(TSE_PROTO_ALPHA_MAX), FW_DOC("scissor angle stop, high")},
    [FP_S_MIN] = {TSE_PARAM_NAME_S_MIN, "um", 0, 5000000, MILLIONTHS(TSE_PROTO_S_MIN), FW_DOC("slide stroke, low end")},
    [FP_S_MAX] = {TSE_PARAM_NAME_S_MAX, "um", 1, 5000000, MILLIONTHS(TSE_PROTO_S_MAX), FW_DOC("slide stroke, high end")},
    [FP_MU_MIN] = {TSE_PARAM_NAME_MU_MIN, "ppm", 0, 999999, MILLIONTHS(TSE_PROTO_MU_MIN), FW_DOC("type-1 singularity margin")},
    [FP_NU_MIN] = {TSE_PARAM_NAME_NU_MIN, "ppm", 0, 999999, MILLIONTHS(TSE_PROTO_NU_MIN), FW_DOC("type-2 singularity margin")},
    [FP_STEPS_PER_M] = {"steps_per_m", "1/m", 1000, 10000000, 1280000, FW_DOC("slide steps per metre (a change needs homing again)")},
    [FP_SLIDE_VMAX] = {"slide_vmax", "um/s", 1000, 2000000, 150000, FW_DOC("slide speed limit")},
    [FP_SLIDE_AMAX] = {"slide_amax", "um/s^2", 1000, 20000000, 1000000, FW_DOC("slide acceleration limit")},
    [FP_PLATE_VMAX] = {"plate_vmax", "um/s", 1000, 5000000, 300000, FW_DOC("plate speed limit")},
    [FP_PLATE_AMAX] = {"plate_amax", "um/s^2", 1000, 50000000, 1000000, FW_DOC("plate acceleration limit")},
    [FP_PLATE_JMAX] = {"plate_jmax", "um/s^3", 1000, 500000000, 10000000, FW_DOC("plate jerk limit")},
    [FP_PLATE_WMAX] = {"plate_wmax", "urad/s", 1000, 10000000, 500000, FW_DOC("plate angular speed limit")},
    [FP_PLATE_DWMAX] = {"plate_dwmax", "urad/s^2", 1000, 100000000, 2000000,
                        FW_DOC("plate angular acceleration limit")},
    [FP_STEP_RATE_MAX] = {"step_rate_max", "1/s", 1000, 500000, 200000, FW_DOC("step rate limit per slide")},
    [FP_WATCHDOG_MS] = {"watchdog_ms", "ms", 0, 60000, 500, FW_DOC("host heartbeat timeout (0: off)")},
    [FP_STATUS_MS] = {"status_ms", "ms", 10, 10000, 100, FW_DOC("STATUS period")},
    [FP_TELEMETRY_MS] = {"telemetry_ms", "ms", 0, 10000, 50, FW_DOC("SLIDES and FK period (0: off)")},
    [FP_HOMING_SPEED] = {"homing_speed", "um/s", 100, 500000, 20000,
                         FW_DOC("homing speed (held to the slide speed limit)")},
    [FP_HOMING_BACKOFF] = {"homing_backoff", "um", 0, 100000, 2000,
                           FW_DOC("how far a slide that starts on its switch goes on past the release "
                           "before seeking the switch")},
    /* The homing switches: the alpha stop keeps the symmetric pose above s = 0.184 m, so six
     * slides seeking down together never reach s = 0; 0.2 m is above that.  The slides still go
     * below the switches in asymmetric poses: a reference, not an end of travel. */
    [FP_HOME_SW_1] = {"home_sw_1", "um", 0, 5000000, 200000, FW_DOC(HOME_SW_DOC(1))},
    [FP_HOME_SW_2] = {"home_sw_2", "um", 0, 5000000, 200000, FW_DOC(HOME_SW_DOC(2))},
    [FP_HOME_SW_3] = {"home_sw_3", "um", 0, 5000000, 200000, FW_DOC(HOME_SW_DOC(3))},
    [FP_HOME_SW_4] = {"home_sw_4", "um", 0, 5000000, 200000, FW_DOC(HOME_SW_DOC(4))},
    [FP_HOME_SW_5] = {"home_sw_5", "um", 0, 5000000, 200000, FW_DOC(HOME_SW_DOC(5))},
    [FP_HOME_SW_6] = {"home_sw_6", "um", 0, 5000000, 200000, FW_DOC(HOME_SW_DOC(6))},
    /* The Leadshine DM542 (User's Manual V1.0, section 10, Figure 11) asks for a pulse and a low
     * time of at least 2.5 us each and DIR 5 us ahead of the pulse's edge (docs/board.md).  2.5 us
     * is also the longest pulse the board's 200 kHz step interrupts allow at step_rate_max's
     * default 200 kHz (high and low alike in the 5 us between two steps of a slide). */
    [FP_STEP_PULSE_NS] = {"step_pulse_ns", "ns", 100, 1000000, 2500,
                          FW_DOC("STEP high time; refused unless the pulse ends within its step interrupt "
                          "period and leaves a low time at least as long before the same slide's "
                          "next step")},
    [FP_DIR_SETUP_NS] = {"dir_setup_ns", "ns", 0, 1000000, 5000,
                         FW_DOC("DIR stable before a STEP edge (rounded up to whole step interrupts, at "
                         "least one)")},
    [FP_CAN_KBPS] = {"can_kbps", "kbit/s", 125, 1000, 500,
                     FW_DOC("CAN bit rate: 125, 250, 500 or 1000; the board applies it at start-up, so "
                     "it takes effect after PARAM_SAVE and a restart")},
    /* The lead is what the host may fall behind by at the start, before the queue has filled: a
     * row takes about 1 ms on a 500 kbit/s bus, but a host on a general-purpose OS stalls for tens
     * of milliseconds (scheduling, Python's garbage collector, a loaded machine).  0.2 s covers a
     * 100 ms stall twice over at the cost of a 0.2 s wait at rest; with rows 20 ms apart it is ten
     * of the queue's 32 rows, and a queue that fills before it starts the clock anyway. */
    [FP_TRAJ_LEAD] = {"traj_lead", "us", 0, 10000000, 200000,
                      FW_DOC("streamed trajectories: the path the controller holds before the clock of the "
                      "first row starts (or the last row, or a full queue); the plate waits at rest "
                      "until then. 0.2 s covers host stalls (scheduling, garbage collection) of tens "
                      "of ms several times over; a row takes about 1 ms on the bus")},
};

void fw_params_default(fw_param_set *s)
{
    for (int i = 0; i < FP_COUNT; ++i)
        s->v[i] = fw_param_table[i].def;
}

void fw_params_kinematics(const fw_param_set *s, tse_params *p)
{
    const tse_real micro = TSE_R(1e-6);
    p->L = (tse_real)s->v[FP_L] * micro;
    p->k1 = (tse_real)s->v[FP_K1] * micro;
    p->eta = (tse_real)s->v[FP_ETA] * micro;
    p->k3 = (tse_real)s->v[FP_K3] * micro;
    p->k4 = (tse_real)s->v[FP_K4] * micro;
    p->alpha_min = (tse_real)s->v[FP_ALPHA_MIN] * micro;
    p->alpha_max = (tse_real)s->v[FP_ALPHA_MAX] * micro;
    p->s_min = (tse_real)s->v[FP_S_MIN] * micro;
    p->s_max = (tse_real)s->v[FP_S_MAX] * micro;
    p->mu_min = (tse_real)s->v[FP_MU_MIN] * micro;
    p->nu_min = (tse_real)s->v[FP_NU_MIN] * micro;
}

int fw_param_value_ok(uint16_t id, int32_t value)
{
    if (id >= FP_COUNT || value < fw_param_table[id].min || value > fw_param_table[id].max)
        return 0;
    if (id == FP_CAN_KBPS)
        return value == 125 || value == 250 || value == 500 || value == 1000;
    return 1;
}

static fw_param_fault fault(int id, fw_param_rule rule)
{
    const fw_param_fault f = {id, rule};
    return f;
}

/* The homing switches inside the stroke, and reachable all at once (see params.h). */
static fw_param_fault check_switches(const fw_param_set *s, const tse_params *p)
{
    for (int k = 0; k < 6; ++k) {
        const int32_t sw = s->v[FP_HOME_SW_1 + k];
        if (sw < s->v[FP_S_MIN] || sw > s->v[FP_S_MAX])
            return fault(FP_HOME_SW_1 + k, FW_RULE_SWITCH_STROKE);
    }
    /* kinematics.md: a scissor's width w = sqrt(sA^2 + sB^2 + 2 cos(2 eta) sA sB) and
     * alpha = acos(w / (2 l0)); alpha <= alpha_max is w >= 2 l0 cos(alpha_max). */
    const tse_real c = tse_cos(TSE_R(2.0) * p->eta);
    const tse_real w_lo = TSE_R(2.0) * p->k1 * p->L * tse_cos(p->alpha_max);
    for (int j = 0; j < 3; ++j) {
        const tse_real a = (tse_real)s->v[FP_HOME_SW_1 + 2 * j] * (TSE_R(1.0) / PROTO_UM_PER_M);
        const tse_real b = (tse_real)s->v[FP_HOME_SW_1 + 2 * j + 1] * (TSE_R(1.0) / PROTO_UM_PER_M);
        const tse_real w2 = a * a + b * b + TSE_R(2.0) * c * a * b;
        if (w2 < w_lo * w_lo)
            return fault(FP_HOME_SW_1 + 2 * j, FW_RULE_SWITCH_REACH);
    }
    return fault(-1, FW_RULE_NONE);
}

/* The home pose within its own margins, and homing's final move from the switches to it through
 * valid poses only (fw/joint_path.h): otherwise homing ends where every move is refused, or
 * carries the plate through poses the margins exist to keep it from. */
static fw_param_fault check_home(const fw_param_set *s, const tse_params *p)
{
    tse_geometry g;
    if (tse_geometry_init(&g, p) != TSE_PARAM_OK)
        return fault(FP_L, FW_RULE_GEOMETRY); /* tse_params_check passed it: not expected */
    tse_ik_result r;
    const tse_status home = tse_ik(&g, g.home_pose, NULL, &r);
    if (home != TSE_OK)
        /* The margin that home fails, or the stroke or angle stops it needs. */
        return fault(home == TSE_DEGENERATE ? FP_NU_MIN
                     : home == TSE_SINGULAR ? FP_MU_MIN
                     : home == TSE_STROKE   ? FP_S_MAX
                                            : FP_ALPHA_MAX,
                     FW_RULE_HOME_MARGINS);
    /* Six switches at one height make a straight path for the plate (down, level), so the blame
     * goes to the switch farthest from the others' mean. */
    tse_real from[6], where, mean = TSE_R(0.0);
    for (int k = 0; k < 6; ++k) {
        from[k] = (tse_real)s->v[FP_HOME_SW_1 + k] * (TSE_R(1.0) / PROTO_UM_PER_M);
        mean += from[k] / TSE_R(6.0);
    }
    int scissor, odd = 0;
    for (int k = 1; k < 6; ++k)
        if (tse_fabs(from[k] - mean) > tse_fabs(from[odd] - mean))
            odd = k;
    if (fw_joint_path_check(&g, from, &where, &scissor) != TSE_OK)
        return fault(FP_HOME_SW_1 + odd, FW_RULE_HOMING_PATH);
    return fault(-1, FW_RULE_NONE);
}

fw_param_fault fw_params_judge(const fw_param_set *s)
{
    for (int i = 0; i < FP_COUNT; ++i)
        if (!fw_param_value_ok((uint16_t)i, s->v[i]))
            return fault(i, FW_RULE_RANGE);
    tse_params p;
    fw_params_kinematics(s, &p);
    const tse_param_id bad = tse_params_check(&p);
    if (bad == TSE_PARAM_ALPHA_MAX && s->v[FP_ALPHA_MAX] <= s->v[FP_ALPHA_MIN])
        return fault(FP_ALPHA_MAX, FW_RULE_ALPHA_ORDER);
    if (bad == TSE_PARAM_S_MAX && s->v[FP_S_MAX] <= s->v[FP_S_MIN])
        return fault(FP_S_MAX, FW_RULE_STROKE_ORDER);
    if (bad != TSE_PARAM_OK)
        return fault((int)fw_param_of_kin(bad), FW_RULE_GEOMETRY);
    /* r_top * steps_per_m >= 1e6 / FW_PLATE_STEP_URAD, in integers (the board has no double):
     * k4 [ppm] x L [um] x steps_per_m >= 1e18 / urad, each factor within its range. */
    if ((int64_t)s->v[FP_K4] * s->v[FP_L] < INT64_C(1000000000000000000) / FW_PLATE_STEP_URAD / s->v[FP_STEPS_PER_M])
        return fault(FP_K4, FW_RULE_PLATE_STEP);
    const fw_param_fault sw = check_switches(s, &p);
    if (sw.rule != FW_RULE_NONE)
        return sw;
    return check_home(s, &p);
}

int fw_params_check(const fw_param_set *s)
{
    return fw_params_judge(s).id;
}

int fw_params_set_one(fw_param_set *s, uint16_t id, int32_t value, fw_param_fault *why)
{
    fw_param_fault f = fault(id < FP_COUNT ? (int)id : -1, FW_RULE_RANGE);
    int r = FW_REASON_PARAM_RANGE;
    fw_param_set next = *s;
    if (id >= FP_COUNT) {
        r = FW_REASON_PARAM_UNKNOWN;
    } else if (fw_param_value_ok(id, value)) {
        next.v[id] = value;
        f = fw_params_judge(&next);
        r = f.rule == FW_RULE_NONE ? 0 : FW_REASON_PARAM_SET;
    }
    if (why)
        *why = f;
    if (r == 0)
        *s = next;
    return r;
}

/* CRC-32 (IEEE 802.3, reflected), bitwise: the record is small and written rarely. */
static uint32_t crc32(const uint8_t *p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k)
            c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

#define RECORD_MAGIC 0x54534550u /* "PEST" little-endian: TSE Parameters */
/* A record of n parameters: magic, n, a zero byte, the values, the CRC. */
#define RECORD_LEN_OF(n) (4u + 2u + 4u * (unsigned)(n) + 4u)
#define RECORD_LEN RECORD_LEN_OF(FP_COUNT)

static void put32(uint8_t *p, uint32_t v)
{
    for (int k = 0; k < 4; ++k)
        p[k] = (uint8_t)(v >> (8 * k));
}

static uint32_t get32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

size_t fw_params_serialize(const fw_param_set *s, uint8_t *buf, size_t cap)
{
    if (cap < RECORD_LEN)
        return 0;
    put32(buf, RECORD_MAGIC);
    buf[4] = (uint8_t)FP_COUNT;
    buf[5] = 0;
    for (int i = 0; i < FP_COUNT; ++i)
        put32(&buf[6 + 4 * i], (uint32_t)s->v[i]);
    put32(&buf[RECORD_LEN - 4u], crc32(buf, RECORD_LEN - 4u));
    return RECORD_LEN;
}

int fw_params_deserialize(fw_param_set *s, const uint8_t *buf, size_t len)
{
    /* Parameters are only ever appended: a record an older firmware wrote holds the first n, and
     * the ones it did not know take their defaults. */
    if (len < RECORD_LEN_OF(1) || get32(buf) != RECORD_MAGIC)
        return -1;
    const unsigned n = buf[4];
    if (n == 0 || n > FP_COUNT || len != RECORD_LEN_OF(n) || get32(&buf[len - 4u]) != crc32(buf, len - 4u))
        return -1;
    fw_param_set next;
    fw_params_default(&next);
    for (unsigned i = 0; i < n; ++i)
        next.v[i] = (int32_t)get32(&buf[6 + 4 * i]);
    if (fw_params_check(&next) >= 0)
        return -1;
    *s = next;
    return 0;
}

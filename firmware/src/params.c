#include "fw/params.h"

#include "fw/proto_wire.h"
#include "fw/types.h"
#include "fw/joint_path.h"
#include "tse/ik.h"

/* The firmware's part of the parameter table: each parameter's range and default. */
#define FW_PARAM(id, name, unit, min, max, def, doc) [id] = {min, max, def},
const fw_param_spec fw_param_specs[FP_COUNT] = {
#include "fw/params.def"
};

void fw_params_default(fw_param_set *s)
{
    for (int i = 0; i < FP_COUNT; ++i)
        s->v[i] = fw_param_specs[i].def;
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
    if (id >= FP_COUNT || value < fw_param_specs[id].min || value > fw_param_specs[id].max)
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

#include "fk_check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fk_oracle.h"
#include "fuzz_target.h"

/* The kinematics contract (docs/kinematics.md) holds a forward solution to its slides, not to a
 * pose: the inverse kinematics of the pose it reports reproduces the slides within 2e-6 m in float
 * (near a singularity the pose itself may be far less certain: at a symmetric pose of a fuzzed
 * geometry, float FK's pitch was 8.7e-5 rad off for slides off by less than that).  The double
 * IK of the pose on the wire is judged so, with the float IK's own 2e-6 m and the wire's
 * truncation to 1 um and 1 urad (what it moves each slide, from the slides' sensitivity to each
 * coordinate) added. */
#define FK_Q_TOL 4e-6
#define WIRE_QUANTUM 1e-6

static struct {
    double worst_m, worst_rad, worst_q;
    unsigned long judged, no_fk_sent, none_found;
    int reported;
} st;

static void report(void)
{
    fprintf(stderr, "fk check: %lu poses judged by double IK: worst slide error beyond the wire's "
                    "rounding %.3g m (pose from double FK: %.3g m, %.3g rad); homed without FK frames "
                    "%lu (double FK found a pose in %lu of them)\n",
            st.judged, st.worst_q, st.worst_m, st.worst_rad, st.no_fk_sent, st.no_fk_sent - st.none_found);
}

void fk_check_frame(oracle_model *o, rig *r, proto_msg m, const int64_t *v)
{
    (void)r;
    if (m == PM_SLIDES_A)
        o->tel_have = 0; /* a burst starts with the slides */
    if (m >= PM_SLIDES_A && m <= PM_SLIDES_C) {
        const int k = 2 * (int)(m - PM_SLIDES_A);
        o->tel_q[k] = (double)v[0] * 1e-9;
        o->tel_q[k + 1] = (double)v[1] * 1e-9;
        o->tel_have |= 3u << k;
    } else if (m >= PM_FK_A && m <= PM_FK_C) {
        const int k = 2 * (int)(m - PM_FK_A);
        o->tel_fk[k] = (double)v[0] * 1e-6;
        o->tel_fk[k + 1] = (double)v[1] * 1e-6;
        o->tel_have |= 3u << (6 + k);
    }
}

static double angle_diff(double a, double b)
{
    return fabs(remainder(a - b, 6.283185307179586));
}

void fk_check_burst(oracle_model *o, rig *r)
{
    const unsigned have = o->tel_have;
    o->tel_have = 0;
    if ((have & 0x3Fu) != 0x3Fu)
        return;
    if (!st.reported && getenv("TSE_FUZZ_SUMMARY")) {
        st.reported = 1;
        atexit(report);
    }
    fw_inspection in;
    fw_inspect(r->c, &in);
    /* Slides known to the plant only: homed, no e-stop mid-way, no lying switch in the zero. */
    if (!in.homed || o->estop_cut || o->zero_suspect)
        return;
    static const fw_param_id ids[FK_ORACLE_PARAMS] = {FP_L, FP_K1, FP_ETA, FP_K3, FP_K4, FP_ALPHA_MIN,
                                                      FP_ALPHA_MAX, FP_S_MIN, FP_S_MAX, FP_MU_MIN, FP_NU_MIN};
    int64_t kin[FK_ORACLE_PARAMS];
    for (int i = 0; i < FK_ORACLE_PARAMS; ++i)
        kin[i] = o->params.v[ids[i]];
    double pose[6], qe;
    if ((have & 0xFC0u) == 0xFC0u) {
        /* The controller's pose is one of these slides', found by an independent solver from it. */
        const int s = fk_oracle_pose(kin, o->tel_q, o->tel_fk, pose, &qe);
        if (s != 0)
            fprintf(stderr, "FK frames say a pose for slides the double FK finds none for (status %d, %.3g m)\n", s, qe);
        FUZZ_CHECK(s == 0);
        double dm = 0.0, dr = 0.0;
        for (int k = 0; k < 3; ++k) {
            dm = fmax(dm, fabs(pose[k] - o->tel_fk[k]));
            dr = fmax(dr, angle_diff(pose[3 + k], o->tel_fk[3 + k]));
        }
        st.worst_m = fmax(st.worst_m, dm);
        st.worst_rad = fmax(st.worst_rad, dr);
        /* The sent pose's slides, and how far one quantum of each coordinate moves them. */
        double q[6], round[6] = {0};
        FUZZ_CHECK(fk_oracle_slides(kin, o->tel_fk, o->tel_q, q) == 0);
        for (int c = 0; c < 6; ++c) {
            double p[6], qc[6];
            for (int k = 0; k < 6; ++k)
                p[k] = o->tel_fk[k] + (k == c ? WIRE_QUANTUM : 0.0);
            FUZZ_CHECK(fk_oracle_slides(kin, p, q, qc) == 0);
            for (int k = 0; k < 6; ++k)
                round[k] += fabs(qc[k] - q[k]);
        }
        double worst = 0.0;
        int at = 0;
        for (int k = 0; k < 6; ++k) {
            const double e = fabs(q[k] - o->tel_q[k]) - round[k];
            if (e > worst) {
                worst = e;
                at = k;
            }
        }
        st.worst_q = fmax(st.worst_q, worst);
        ++st.judged;
        if (worst > FK_Q_TOL) {
            fprintf(stderr, "FK frames: the pose's slide %d is %.3g m from the slide beyond the wire's rounding "
                            "(%.3g m); pose %.3g m, %.3g rad from the double FK's\n",
                    at + 1, worst, round[at], dm, dr);
            for (int k = 0; k < 6; ++k)
                fprintf(stderr, "  %d: slide %.9f  its pose's %.9f  sent %.6f  double FK %.9f  commanded %.9f\n",
                        k, o->tel_q[k], q[k], o->tel_fk[k], pose[k], (double)in.pose[k]);
        }
        FUZZ_CHECK(worst <= FK_Q_TOL);
        return;
    }
    /* Homed, yet no pose sent: counted for the report only (whether the double FK finds a pose
     * where the float one found none), so solved only when the report is asked for. */
    ++st.no_fk_sent;
    if (!st.reported)
        return;
    double seed[6];
    for (int k = 0; k < 6; ++k)
        seed[k] = (double)in.pose[k];
    if (fk_oracle_pose(kin, o->tel_q, seed, pose, &qe) != 0)
        ++st.none_found;
}

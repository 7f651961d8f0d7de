/* Inverse and forward kinematics on any doubles, in both precisions.
 *
 * The bytes decode (kin_input.h) into a design (mostly the prototype), a pose (mostly near the
 * workspace, but any double including NaN, infinities and huge values), an optional seed, and
 * optionally slides for the forward kinematics made from the inverse kinematics' answer.  Each
 * precision's library (kin_side.h) gets them as it would hold them, and its answers are checked:
 *  - always: the returned status is the one stored, a valid tse_status, with a scissor 1..3 for a
 *    rejection and 0 for ok; a non-finite input is `invalid` and a finite one never is; a ball
 *    joint beyond any scissor's reach is `unreachable` at that scissor;
 *  - IK `ok`: finite slides inside [s_min, s_max], mu and nu above their thresholds, and against
 *    the long-double reference (kin_ref.h): the exact solution within the contract's accuracy,
 *    the apex of each scissor at its ball joint, every check of the contract passed;
 *  - a pose the reference classifies clear of every threshold gets the reference's verdict;
 *  - FK: a non-finite input is `invalid`, a slide outside the stroke `stroke` at its scissor
 *    (before anything else), and `ok` is a finite pose that the library's IK and the reference
 *    both take back to the slides given, within the accuracy;
 *  - the fixed-point IK (kin_fixed.h) agrees with the double build on the same numbers, or
 *    refuses cleanly what its formats cannot hold. */
#include <math.h>
#include <string.h>

#include "fuzz_target.h"
#include "kin_fixed.h"
#include "kin_input.h"
#include "kin_ref.h"
#include "kin_side.h"
#include "tse/status.h"

typedef struct {
    const char *name;
    int is_float;
    int (*init)(const double *, double *);
    void (*ik)(const double *, const double *, side_ik *);
    void (*fk)(const double *, const double *, side_fk *);
} precision;

static const precision precisions[2] = {
    {"double", 0, side_init_d, side_ik_d, side_fk_d},
    {"float", 1, side_init_f, side_ik_f, side_fk_f},
};

#define V6(v) (v)[0], (v)[1], (v)[2], (v)[3], (v)[4], (v)[5]
#define F6 "(%.17g, %.17g, %.17g, %.17g, %.17g, %.17g)"

static int all_finite(const double *v, int n)
{
    for (int k = 0; k < n; ++k)
        if (!isfinite(v[k]))
            return 0;
    return 1;
}

static int valid_status(int s)
{
    return s >= TSE_OK && s < TSE_STATUS_COUNT;
}

/* Returns whether the pose is `ok` and the reference agrees, clear of every threshold. */
static int check_ik(const ref_design *d, const side_ik *r, int seeded)
{
    KIN_CHECK(r->ret == r->status && valid_status(r->status));
    KIN_CHECK(r->status == TSE_OK ? r->scissor == 0 : r->scissor >= 1 && r->scissor <= 3);
    const int finite = all_finite(r->pose, 6) && (!seeded || all_finite(r->seed, 6));
    KIN_CHECK((r->status == TSE_INVALID) == !finite);
    if (!finite)
        return 0;
    if (ref_out_of_reach(d, r->pose, 0)) {
        KIN_CHECK(r->status != TSE_OK);
        /* Only near the prototype: with k1 = 1.7e-77 and k4 = 3.4e38 (a set tse_params_check
         * takes) the quartic's numbers overflow and a joint 6e38 m away was called `alpha`. */
        if (d->plausible)
            KIN_CHECK(r->status == TSE_UNREACHABLE && r->scissor == 1);
    }
    if (r->status == TSE_OK) {
        KIN_CHECK(all_finite(r->q, 6));
        for (int i = 0; i < 3; ++i)
            KIN_CHECK(r->mu[i] >= d->g.p.mu_min);
        KIN_CHECK(r->nu >= d->g.p.nu_min);
        ref_check_accepted(d, r->pose, r->q, 0.0, NULL); /* IK's accuracy holds at any nu */
    }
    if (ref_comparable(d, r->pose)) {
        orc_result o;
        ref_classify(d, r->pose, &o);
        if (!o.ambiguous && !o.multi) {
            KIN_CHECK(r->status == o.status);
            if (o.status != TSE_DEGENERATE)
                KIN_CHECK(r->scissor == o.scissor);
            return r->status == TSE_OK;
        }
    }
    return 0;
}

/* kinematics.md gives no accuracy for the forward kinematics; near a type-2 singularity the
 * slides pin the pose down loosely and a float Newton leaves more of them (2.2e-6 m at nu = 0.002).
 * The IK's figure is held where the kinematics tests hold FK to it (test_precision: mu >= 0.1 and
 * nu >= 0.01). */
#define FK_STRICT_NU 0.01

static void check_fk(const precision *P, const ref_design *d, const side_fk *f, int seeded, int at_answer)
{
    KIN_CHECK(f->ret == f->status && valid_status(f->status));
    if (f->status == TSE_OK || f->status == TSE_INVALID)
        KIN_CHECK(f->scissor == 0);
    else if (f->status == TSE_NOCONVERGE)
        KIN_CHECK(f->scissor >= 0 && f->scissor <= 3);
    else
        KIN_CHECK(f->scissor >= 1 && f->scissor <= 3);
    const int finite = all_finite(f->q, 6) && (!seeded || all_finite(f->seed, 6));
    KIN_CHECK((f->status == TSE_INVALID) == !finite);
    if (!finite)
        return;
    const orc_params *p = &d->g.p;
    for (int k = 0; k < 6; ++k)
        if (!(f->q[k] >= p->s_min && f->q[k] <= p->s_max)) {
            KIN_CHECK(f->status == TSE_STROKE && f->scissor == k / 2 + 1);
            return;
        }
    if (at_answer) {
        /* Newton from the pose whose slides these are (IK took it, clear of every threshold by
         * the reference): it is already there, and the check by IK passes. */
        KIN_CHECK(f->status == TSE_OK);
    }
    if (f->status != TSE_OK)
        return;
    KIN_CHECK(all_finite(f->pose, 6));
    /* The library's own IK takes the pose back (fk.h), and keeps its own promise there. */
    side_ik back;
    P->ik(f->pose, f->q, &back);
    KIN_CHECK(back.status == TSE_OK);
    ref_check_accepted(d, back.pose, back.q, 0.0, NULL);
    /* The exact slides of the pose are the slides given, within the accuracy beyond the error the
     * IK makes at this pose: FK judges its answer with that IK, and can be no finer than it. */
    double ik_err[6];
    ref_slide_errors(d, back.pose, back.q, ik_err);
    ref_check_accepted(d, f->pose, f->q, FK_STRICT_NU, ik_err);
    if (ref_comparable(d, f->pose)) {
        orc_result o;
        ref_classify(d, f->pose, &o);
        if (!o.ambiguous)
            KIN_CHECK(o.status == TSE_OK);
    }
}

static void run(const precision *P, const kin_case *c)
{
    double held[SIDE_NPARAMS];
    const int bad = P->init(c->params, held);
    if (bad != 0) {
        KIN_CHECK(c->fuzz_params); /* the prototype is a valid design */
        return;
    }
    ref_design d;
    ref_design_init(&d, held, P->is_float, c->plausible_params);

    double seed[6];
    if (c->ik_seeded) {
        memcpy(seed, c->ik_seed, sizeof seed);
        if (c->warm_ik_seed) {
            side_ik home;
            P->ik(c->pose, NULL, &home);
            for (int k = 0; k < 6; ++k)
                seed[k] = home.q[k] + c->ik_seed[k];
        }
    }
    side_ik r;
    P->ik(c->pose, c->ik_seeded ? seed : NULL, &r);
    ref_context("%s IK of " F6 " seed %s " F6, P->name, V6(r.pose), c->ik_seeded ? "" : "(none)", V6(r.seed));
    const int clear_ok = check_ik(&d, &r, c->ik_seeded);

    if (!c->run_fk)
        return;
    double q[6];
    for (int k = 0; k < 6; ++k)
        q[k] = c->fk_mode == FK_SLIDES_ANY ? c->fk_slides[k] : r.q[k] + c->fk_slides[k];
    /* FK seeded at IK's answer must take it, where the IK is held to its accuracy: near a
     * scissor's bifurcation (cond(M) > 100 with mu fine, the contract gap of docs/reliability.md)
     * a float IK from q itself can land 9e-6 m from q (cond 4,400 seen), and so refuse the seed. */
    const int at_answer = clear_ok && c->fk_mode == FK_SLIDES_SAME && c->fk_seed_at_pose &&
                          ref_well_conditioned(&d, r.pose, r.q);
    side_fk f;
    P->fk(q, c->fk_seeded ? c->fk_seed : NULL, &f);
    ref_context("%s FK of " F6 " seed %s " F6 " gave %s " F6, P->name, V6(f.q), c->fk_seeded ? "" : "(none)",
                V6(f.seed), tse_status_name((tse_status)f.status), V6(f.pose));
    check_fk(P, &d, &f, c->fk_seeded, at_answer);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    kin_case c;
    kin_decode(data, size, &c);
    for (int k = 0; k < 2; ++k)
        if (k == 0 ? c.run_double : c.run_float)
            run(&precisions[k], &c);
    /* The fixed-point build beside the double one (kin_fixed.h), on the same case. */
    if (c.run_double)
        kin_fixed_run(&c);
    return 0;
}

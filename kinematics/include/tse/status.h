/* Outcome of a kinematic computation, as kinematics.md names them.
 *
 * The order of the enumerators is the order in which the contract checks them: a pose is reported
 * with the first status that fails, for the first failing scissor.  The numeric values go on the
 * CAN wire (reject frames), so they are fixed: append, never renumber. */
#ifndef TSE_STATUS_H
#define TSE_STATUS_H

typedef enum {
    TSE_OK = 0,
    TSE_INVALID = 1,     /* non-finite or malformed input */
    TSE_UNREACHABLE = 2, /* no solution on the det M > 0 branch with positive slides */
    TSE_BELOW = 3,       /* ball joint at or below the base plane */
    TSE_ALPHA = 4,       /* scissor angle outside its stops (or w > 2 l0) */
    TSE_STROKE = 5,      /* slide outside [s_min, s_max] */
    TSE_SINGULAR = 6,    /* type-1 margin mu < mu_min */
    TSE_DEGENERATE = 7,  /* type-2 margin nu < nu_min */
    TSE_NOCONVERGE = 8,  /* a solver gave up */
    TSE_STATUS_COUNT = 9
} tse_status;

/* Lower-case name as used by the CLI and docs ("ok", "invalid", ...); "?" for an unknown value. */
const char *tse_status_name(tse_status s);

/* Inverse of tse_status_name.  Returns 0 and sets *out on success, -1 for an unknown name. */
int tse_status_parse(const char *name, tse_status *out);

#endif

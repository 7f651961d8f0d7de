/* Stand-ins for tse_ik and tse_fk with their signatures, doing nothing: kin-icount's loop-overhead
 * measures call them where the real measures call the library.  Compiled once per precision, in
 * a file of their own so that the compiler cannot see that they do nothing. */
#ifndef KIN_ICOUNT_STUB_H
#define KIN_ICOUNT_STUB_H

#include "tse/fk.h"
#include "tse/ik.h"

#if defined(TSE_REAL_FLOAT) && TSE_REAL_FLOAT
#define ICOUNT_PREC(head, tail) head##_float_##tail
#else
#define ICOUNT_PREC(head, tail) head##_double_##tail
#endif

#define icount_stub_ik ICOUNT_PREC(icount_stub, ik)
#define icount_stub_fk ICOUNT_PREC(icount_stub, fk)

/* Return TSE_OK and touch nothing. */
tse_status icount_stub_ik(const tse_geometry *g, const tse_real pose[6], const tse_real seed_q[6],
                          tse_ik_result *out);
tse_status icount_stub_fk(const tse_geometry *g, const tse_real q[6], const tse_real seed_pose[6],
                          tse_fk_result *out);

#endif

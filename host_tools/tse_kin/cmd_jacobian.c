/* `tse-kin jacobian`: poses in, dq/dp and the singular values of dp/dq out, one line each.
 *
 * Promise: one line of 2 + 36 + 6 fields per input line, so that the ik rules (one line per line,
 * malformed rows answered invalid) carry over unchanged; the numbers are nan unless the pose is ok. */
#include "commands.h"
#include "csv.h"
#include "stream.h"

const char cmd_jacobian_help[] =
    "usage: tse-kin jacobian [--params|--design FILE] [--precision float|double]\n"
    "\n"
    "Differential kinematics. Reads poses like 'ik' and writes one line of 44 fields per line:\n"
    "  status,scissor,J11,J12,...,J16,J21,...,J66,sv1,...,sv6\n"
    "J = dq/dp (36 numbers, row by row: rows s_a1,s_b1,s_a2,s_b2,s_a3,s_b3; columns x,y,z [m/m] and\n"
    "roll,pitch,yaw [m/rad]) at the slides the inverse kinematics finds from home, then sv1 >= ... >= sv6,\n"
    "the singular values of dp/dq (the reciprocals of those of dq/dp). status and scissor are those of\n"
    "the inverse kinematics (or 'singular' from the Jacobian itself); unless ok, all 42 numbers are nan.\n"
    "\n" KIN_HELP_ROWS "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

static void jacobian_row(const kin_run *run, const double *v, int n, FILE *out)
{
    (void)n;
    kin_jacobian_out r;
    run->ops->jacobian(run->ctx, v, &r);
    fprintf(out, "%s,%d", tse_status_name(r.status), r.scissor);
    if (r.status == TSE_OK) {
        for (int i = 0; i < 6; ++i)
            csv_put_numbers(out, r.J[i], 6);
        csv_put_numbers(out, r.sv, 6);
    } else {
        csv_put_nans(out, 42);
    }
    fputc('\n', out);
}

int cmd_jacobian(const kin_run *run)
{
    static const stream_spec spec = {6, 6, 42,
                                     "status,scissor,"
                                     "J11,J12,J13,J14,J15,J16,J21,J22,J23,J24,J25,J26,J31,J32,J33,J34,J35,J36,"
                                     "J41,J42,J43,J44,J45,J46,J51,J52,J53,J54,J55,J56,J61,J62,J63,J64,J65,J66,"
                                     "sv1,sv2,sv3,sv4,sv5,sv6",
                                     jacobian_row};
    return stream_rows(run, stdin, stdout, &spec);
}

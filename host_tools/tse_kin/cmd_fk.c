/* `tse-kin fk`: slides in, pose out, one line each.
 *
 * Promise: the pose is printed only when the library verified it (status ok); any other status
 * comes with nan, never with a pose that might be wrong.  A row may carry its own seed pose, so
 * the answer depends on nothing but its own line. */
#include "commands.h"
#include "csv.h"
#include "stream.h"

const char cmd_fk_help[] =
    "usage: tse-kin fk [--params|--design FILE] [--precision float|double]\n"
    "\n"
    "Forward kinematics. Reads s_a1,s_b1,s_a2,s_b2,s_a3,s_b3 (metres), optionally followed by a seed\n"
    "pose x,y,z,roll,pitch,yaw (six more numbers; without it the home pose is the seed), and writes\n"
    "per line:\n"
    "  status,scissor,x,y,z,roll,pitch,yaw\n"
    "The library checks its pose with the inverse kinematics: status and scissor are its verdict\n"
    "(scissor 0 when ok). Unless the status is ok the six numbers are nan.\n"
    "\n" KIN_HELP_ROWS "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

static void fk_row(const kin_run *run, const double *v, int n, FILE *out)
{
    kin_fk_out r;
    run->ops->fk(run->ctx, v, n == 12 ? v + 6 : NULL, &r);
    fprintf(out, "%s,%d", tse_status_name(r.status), r.scissor);
    csv_put_numbers(out, r.pose, 6);
    fputc('\n', out);
}

int cmd_fk(const kin_run *run)
{
    static const stream_spec spec = {6, 12, 6, "status,scissor,x,y,z,roll,pitch,yaw", fk_row};
    return stream_rows(run, stdin, stdout, &spec);
}

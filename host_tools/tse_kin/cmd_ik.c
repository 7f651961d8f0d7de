/* `tse-kin ik`: poses in, slides out, one line each.
 *
 * Promise: every row is solved with no seed (the library's home configuration), so a line's answer
 * does not depend on the lines before it; a rejected pose still shows the slides the library
 * returned (nan where it found none). */
#include "commands.h"
#include "csv.h"
#include "stream.h"

const char cmd_ik_help[] =
    "usage: tse-kin ik [--params|--design FILE] [--precision float|double]\n"
    "\n"
    "Inverse kinematics. Reads poses x,y,z,roll,pitch,yaw (metres, radians; R = Rz(yaw) Ry(pitch)\n"
    "Rx(roll)), one per line, and writes per line:\n"
    "  status,scissor,s_a1,s_b1,s_a2,s_b2,s_a3,s_b3\n"
    "status is ok, invalid, unreachable, below, alpha, stroke, singular, degenerate or noconverge;\n"
    "scissor is the first failing scissor (1..3), 0 when ok. Each line is solved from the home\n"
    "configuration (no seed), so the output does not depend on the order of the lines. A rejected\n"
    "pose shows the slides the library returned (nan where it found none).\n"
    "\n" KIN_HELP_ROWS "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

static void ik_row(const kin_run *run, const double *v, int n, FILE *out)
{
    (void)n;
    kin_ik_out r;
    run->ops->ik(run->ctx, v, NULL, &r);
    fprintf(out, "%s,%d", tse_status_name(r.status), r.scissor);
    csv_put_numbers(out, r.q, 6);
    fputc('\n', out);
}

int cmd_ik(const kin_run *run)
{
    static const stream_spec spec = {6, 6, 6, "status,scissor,s_a1,s_b1,s_a2,s_b2,s_a3,s_b3", ik_row};
    return stream_rows(run, stdin, stdout, &spec);
}

/* `tse-kin margins`: where the singularities lie, pose by pose.
 *
 * Promise: the ik row rules (one line per line, malformed rows answered invalid, a header answered
 * by ours); each line is status,scissor as ik answers the pose, then the type-1 margin of each
 * scissor's branch solution and the type-2 ratio, whatever the limits say: a singularity outside
 * the stroke or the stops still shows, which is what the paper's figure of internal singularities
 * is about. */
#include "commands.h"
#include "csv.h"
#include "stream.h"

const char cmd_margins_help[] =
    "usage: tse-kin margins [--params|--design FILE] [--precision float|double]\n"
    "\n"
    "Singularity margins. Reads poses like 'ik' and writes one line per line:\n"
    "  status,scissor,mu1,mu2,mu3,nu\n"
    "status and scissor are ik's answer for the pose (every check of docs/kinematics.md); mu1..mu3\n"
    "are the type-1 margins det M / (|row1| |row2|) of each scissor's solution on the branch, found\n"
    "from home as ik finds it, and nu the type-2 ratio of the three, with no limit applied: they show\n"
    "where the singularities lie, inside the workspace or outside it. A scissor without a branch\n"
    "solution has mu nan, and then nu is nan.\n"
    "\n" KIN_HELP_ROWS "\n" KIN_HELP_PARAMS "\n" KIN_HELP_EXIT;

static void margins_row(const kin_run *run, const double *v, int n, FILE *out)
{
    (void)n;
    kin_margins_out r;
    run->ops->margins(run->ctx, v, &r);
    fprintf(out, "%s,%d", tse_status_name(r.status), r.scissor);
    csv_put_numbers(out, r.mu, 3);
    csv_put_numbers(out, &r.nu, 1);
    fputc('\n', out);
}

int cmd_margins(const kin_run *run)
{
    static const stream_spec spec = {6, 6, 4, "status,scissor,mu1,mu2,mu3,nu", margins_row};
    return stream_rows(run, stdin, stdout, &spec);
}

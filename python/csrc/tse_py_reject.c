/* tse.can's words for a REJECT: tsectl's own (host_tools/traj_check/reject_text.c), so that the
 * two can never say a refusal differently.  See tse_py.h. */
#include <string.h>

#include "reject_text.h"
#include "tse_py.h"

const char *tse_py_reject_text(const int fields[7], char *buf, size_t cap)
{
    proto_message m;
    memset(&m, 0, sizeof m);
    m.msg = PM_REJECT;
    for (int k = 0; k < 7; ++k)
        m.v[k] = fields[k];
    return reject_text(&m, buf, cap);
}

/* tsectl's words for REJECT frames (host_tools/tsectl/reject_text.c), one line per combination of
 * fields: "function seq reason scissor kin_status field where<TAB>text".  test_can.py holds tse.can's
 * wording of the same frames equal to these, so a change on either side is seen. */
#include <stdio.h>

#include "fw/proto.h"
#include "reject_text.h"
#include "tse/status.h"

int main(void)
{
    /* Every command the host sends, plus codes no command has. */
    int functions[PM_COUNT + 3], nf = 0;
    for (int i = 0; i < PM_COUNT; ++i)
        if (proto_table[i].dir == PROTO_TO_CONTROLLER)
            functions[nf++] = proto_table[i].function;
    functions[nf++] = 0;
    functions[nf++] = 0x20;
    functions[nf++] = 127;
    /* Timing: slides 1..6 under each limit code (16 times it), and past the codes; param_set: each
     * rule code in where, and past them. */
    static const int fields[] = {0,  1,  2,  3,  4,  5,  6,  7,  8,  9,  11, 17,  18,  20,
                                 22, 23, 25, 30, 33, 34, 40, 49, 54, 65, 70, 250, 255};
    static const int wheres[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 15, 999, 1000, 1001, 1350, 3600, 65535};
    for (int f = 0; f < nf; ++f)
        for (int reason = 0; reason < FW_REASON_COUNT; ++reason)
            for (size_t k = 0; k < sizeof fields / sizeof fields[0]; ++k)
                for (size_t w = 0; w < sizeof wheres / sizeof wheres[0]; ++w) {
                    const int field = fields[k];
                    proto_message m = {PM_REJECT, 1, {functions[f], 7, reason, field % 4, field % TSE_STATUS_COUNT, field,
                                                      wheres[w]}};
                    char text[512];
                    printf("%d %d %d %d %d %d %d\t%s\n", m.v[0], m.v[1], m.v[2], m.v[3], m.v[4], m.v[5], m.v[6],
                           reject_text(&m, text, sizeof text));
                }
    return 0;
}

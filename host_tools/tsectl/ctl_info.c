#include "ctl_info.h"

int ctl_info_read(tlink *l, ctl_info *info, bool *older)
{
    const int32_t page[1] = {0};
    proto_message m;
    const int rc = ctl_ask(l, PM_INFO_GET, page, PM_INFO, -1, "INFO", &m);
    *older = rc == EXIT_REJECTED && m.v[2] == FW_REASON_UNKNOWN;
    if (rc == EXIT_REJECTED && !*older)
        ctl_print_reject(&m);
    if (rc != EXIT_OK)
        return rc;
    *info = (ctl_info){(int)m.v[0], (int)m.v[1], (int)m.v[2], {(uint32_t)m.v[3], (uint32_t)m.v[4]}};
    return EXIT_OK;
}

int ctl_rates(tlink *l, fw_rates *r)
{
    ctl_info info;
    bool older;
    const int rc = ctl_info_read(l, &info, &older);
    if (older) {
        *r = FW_RATES_BUILT_IN;
        ctl_error("warning: node %u does not know INFO_GET (a firmware older than INFO): judged at the built-in "
                  "rates, %u Hz step interrupts and %u Hz control segments, which every such firmware ran at",
                  l->node, r->step_hz, r->segment_hz);
        return EXIT_OK;
    }
    if (rc != EXIT_OK)
        return rc;
    if (!fw_rates_run(info.rates)) {
        ctl_error("node %u reports %u Hz step interrupts and %u Hz control segments, rates no controller runs at "
                  "(a segment of whole microseconds and whole step interrupts): its paths cannot be judged",
                  l->node, info.rates.step_hz, info.rates.segment_hz);
        return EXIT_REJECTED;
    }
    *r = info.rates;
    return EXIT_OK;
}

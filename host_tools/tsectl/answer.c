#define _POSIX_C_SOURCE 200809L
/* The exchanges every command is made of.  See tsectl.h. */
#include <math.h>
#include <stdio.h>

#include "progress.h"
#include "reject_text.h"
#include "rest_wait.h"
#include "tsectl.h"

volatile sig_atomic_t tsectl_interrupted;
volatile sig_atomic_t tsectl_signals;
int tsectl_timeout_ms = 2000;

void ctl_error(const char *fmt, ...)
{
    progress_break();
    fflush(stdout);
    va_list ap;
    va_start(ap, fmt);
    fputs("tsectl: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

int ctl_status(tlink *l, proto_message *status)
{
    proto_message m;
    const uint64_t end = link_now_us() + (uint64_t)tsectl_timeout_ms * 1000u;
    while (link_now_us() < end && !tsectl_interrupted) {
        if (link_recv(l, &m, 100) == 1 && m.msg == PM_STATUS) {
            if (status)
                *status = m;
            return (uint8_t)(m.v[5] + 1);
        }
    }
    return -1;
}

int ctl_status_needed(tlink *l, proto_message *status)
{
    const int seq = ctl_status(l, status);
    if (seq < 0)
        ctl_error("no STATUS from node %u within %d ms (is it on the bus?)", l->node, tsectl_timeout_ms);
    return seq;
}

int ctl_answer(tlink *l, int function, int seq, proto_message *ack, proto_message *reject)
{
    const uint64_t end = link_now_us() + (uint64_t)tsectl_timeout_ms * 1000u;
    proto_message m;
    while (link_now_us() < end) {
        if (tsectl_interrupted)
            return EXIT_INTERRUPTED;
        if (link_recv(l, &m, 50) != 1)
            continue;
        if ((m.msg == PM_ACK || m.msg == PM_REJECT) && m.v[0] == function && (seq < 0 || m.v[1] == seq)) {
            if (m.msg == PM_REJECT) {
                if (reject)
                    *reject = m;
                return EXIT_REJECTED;
            }
            if (ack)
                *ack = m;
            return EXIT_OK;
        }
    }
    ctl_error("no answer from node %u within %d ms (is it on the bus? --timeout MS waits longer)", l->node,
              tsectl_timeout_ms);
    return EXIT_TIMEOUT;
}

int ctl_ask(tlink *l, proto_msg msg, const int32_t *values, proto_msg reply, int key, const char *what,
            proto_message *out)
{
    if (link_send(l, msg, values) != 0) {
        ctl_error("cannot send on the bus");
        return EXIT_BUS;
    }
    const int rc = ctl_answer(l, proto_table[msg].function, -1, NULL, out);
    if (rc != EXIT_OK)
        return rc;
    const uint64_t end = link_now_us() + (uint64_t)tsectl_timeout_ms * 1000u;
    while (link_now_us() < end && !tsectl_interrupted)
        if (link_recv(l, out, 50) == 1 && out->msg == reply && (key < 0 || out->v[0] == key))
            return EXIT_OK;
    if (tsectl_interrupted)
        return EXIT_INTERRUPTED;
    ctl_error("no %s from node %u after its %s was acknowledged", what, l->node, proto_table[msg].name);
    return EXIT_TIMEOUT;
}

int ctl_send_pose(tlink *l, int seq, const double p[6])
{
    for (int k = 0; k < 3; ++k) {
        const int32_t v[3] = {seq, (int32_t)lround(p[2 * k] * proto_pose_units(2 * k)),
                              (int32_t)lround(p[2 * k + 1] * proto_pose_units(2 * k + 1))};
        if (link_send(l, (proto_msg)(PM_POSE_A + k), v) != 0)
            return -1;
    }
    return 0;
}

void ctl_print_reject(const proto_message *reject)
{
    char text[512];
    ctl_error("%s", reject_text(reject, text, sizeof text));
}

int ctl_simple(tlink *l, proto_msg msg, proto_message *reject)
{
    const int seq = ctl_status_needed(l, NULL);
    if (seq < 0)
        return tsectl_interrupted ? EXIT_INTERRUPTED : EXIT_TIMEOUT;
    const int32_t v[1] = {seq};
    if (link_send(l, msg, v) != 0) {
        ctl_error("cannot send on the bus");
        return EXIT_BUS;
    }
    proto_message rej;
    const int rc = ctl_answer(l, proto_table[msg].function, seq, NULL, &rej);
    if (rc == EXIT_OK)
        printf("%s: acknowledged\n", proto_table[msg].name);
    if (rc == EXIT_REJECTED) {
        if (reject)
            *reject = rej;
        else
            ctl_print_reject(&rej);
    }
    return rc;
}

/* ctl_wait_rest's loop, each STATUS judged by rest_wait.h (tse.can judges by the same code).
 * settled: the caller knows that every STATUS from now on reflects what it asked for. */
static int wait_rest(tlink *l, double expected_s, const char *what, int show_progress, proto_message *last,
                     int settled)
{
    const uint64_t t0 = link_now_us();
    rest_wait w;
    rest_wait_begin(&w, expected_s, settled);
    proto_message m;
    progress p;
    progress_start(&p, what, -1);
    char words[160];
    for (;;) {
        const double el = (double)(link_now_us() - t0) * 1e-6;
        if (tsectl_interrupted)
            return EXIT_INTERRUPTED;
        const bool status = link_recv(l, &m, 200) == 1 && m.msg == PM_STATUS;
        if (status && last)
            *last = m;
        const rest_verdict v = rest_wait_status(&w, el, status ? m.v[0] : -1, status ? m.v[1] : 0, what, words,
                                                sizeof words);
        if (v == REST_WAIT_ON) {
            if (status && show_progress)
                progress_update(&p, expected_s > 0 ? fmin(el / expected_s, 0.99) : fmin(el / (el + 5.0), 0.99),
                                NULL);
            continue;
        }
        if (show_progress && v == REST_WAIT_DONE)
            progress_update(&p, 1.0, NULL);
        progress_break();
        if (v > 0) {
            printf("%s\n", words);
            return EXIT_OK;
        }
        ctl_error("%s", words);
        return v == REST_WAIT_TIMEOUT ? EXIT_TIMEOUT : EXIT_REJECTED;
    }
}

int ctl_wait_rest(tlink *l, double expected_s, const char *what, int show_progress, proto_message *last)
{
    return wait_rest(l, expected_s, what, show_progress, last, 0);
}

int ctl_estop(tlink *l)
{
    /* No waiting for a STATUS first: the e-stop goes out at once. */
    const int32_t v[1] = {0};
    if (link_send(l, PM_ESTOP, v) != 0) {
        ctl_error("cannot send on the bus");
        return EXIT_BUS;
    }
    proto_message rej;
    const int rc = ctl_answer(l, proto_table[PM_ESTOP].function, 0, NULL, &rej);
    if (rc == EXIT_OK)
        printf("ESTOP: acknowledged\n");
    else if (rc == EXIT_REJECTED)
        ctl_print_reject(&rej);
    return rc;
}

int ctl_halt(tlink *l, const char *why)
{
    int rc = EXIT_INTERRUPTED;
    /* Two interrupts before we got here (a double Ctrl-C) ask for the e-stop at once. */
    if (tsectl_signals < 2) {
        tsectl_interrupted = 0;
        progress_break();
        printf("%s%sstopping the robot (STOP) and waiting until it is at rest; interrupt again for an e-stop\n",
               why ? why : "", why ? ": " : "");
        fflush(stdout);
        proto_message rej;
        rc = ctl_simple(l, PM_STOP, &rej);
        if (rc == EXIT_OK)
            rc = wait_rest(l, 0, "stopping", 0, NULL, 1);
        else if (rc == EXIT_REJECTED)
            ctl_print_reject(&rej);
    }
    if (rc == EXIT_INTERRUPTED) {
        tsectl_interrupted = 0;
        progress_break();
        ctl_error("interrupted again: e-stop");
        rc = ctl_estop(l);
        if (rc == EXIT_OK) {
            printf("e-stop latched: clear, enable and home before moving again\n");
            rc = EXIT_REJECTED;
        }
    }
    if (rc != EXIT_OK && rc != EXIT_REJECTED)
        ctl_error("the robot may still be moving: check with 'tsectl status'");
    return rc;
}

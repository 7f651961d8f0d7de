/* tsectl's test for two controllers under one node id (status_order.h), on counter sequences
 * written out by hand: one controller (frames lost, a restart, the 16-bit wrap) is one source;
 * two controllers interleaving their counters are found within a few periods. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "status_order.h"

/* The index of the first counter after which two sources are reported, or -1. */
static int first_alarm(const uint16_t *c, int n)
{
    status_order o = {0};
    for (int i = 0; i < n; ++i)
        if (status_order_note(&o, c[i]))
            return i;
    return -1;
}

static void one_controller_is_one_source(void **state)
{
    (void)state;
    uint16_t c[400];
    for (int i = 0; i < 400; ++i)
        c[i] = (uint16_t)(65400 + i); /* wraps through 0 at i = 136 */
    assert_int_equal(first_alarm(c, 400), -1);
    /* Frames lost on the bus: the counter skips ahead. */
    const uint16_t lost[] = {10, 11, 14, 15, 30, 31, 32, 200, 201};
    assert_int_equal(first_alarm(lost, 9), -1);
    /* A controller that restarts now and then (its counter back to 0), with a long run between. */
    uint16_t restarts[90];
    for (int i = 0; i < 90; ++i)
        restarts[i] = (uint16_t)(500 + i % 30); /* back every 30 periods */
    assert_int_equal(first_alarm(restarts, 90), -1);
}

static void two_controllers_are_found(void **state)
{
    (void)state;
    /* Booted together: the same counters, interleaved. */
    const uint16_t same[] = {100, 100, 101, 101, 102, 102, 103, 103};
    assert_int_equal(first_alarm(same, 8), 5);
    /* Booted apart: one far ahead of the other. */
    const uint16_t apart[] = {4000, 17, 4001, 18, 4002, 19, 4003, 20};
    assert_int_equal(first_alarm(apart, 8), 5);
    /* Periods of another length: the fast one is seen twice between the slow one's. */
    const uint16_t uneven[] = {50, 900, 51, 52, 901, 53, 54, 902, 55, 56, 903};
    assert_int_equal(first_alarm(uneven, 11), 8); /* back at 51, 53 and 55 */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(one_controller_is_one_source),
        cmocka_unit_test(two_controllers_are_found),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

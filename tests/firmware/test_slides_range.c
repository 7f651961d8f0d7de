/* SLIDES carries each slide in nanometres in an i32, which holds +-2.147 m, while the stroke may
 * reach 5 m (s_max, home_sw_k): a slide beyond the field is sent as the field's end
 * (docs/protocol.md), never as the garbage of an out-of-range conversion. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "harness.h"

static void set(int id, int32_t value)
{
    const unsigned from = F.tx_count;
    const int32_t v[2] = {id, value};
    send(PM_PARAM_SET, v);
    fw_poll(C);
    assert_int_equal(answer(from, proto_table[PM_PARAM_SET].function, NULL), 'a');
}

/* The SLIDES_A frame of the next telemetry period: s_a1 and s_b1 in nanometres. */
static void slides_a(int32_t *a1, int32_t *b1)
{
    const unsigned from = F.tx_count;
    fake_run(&F, C, (uint32_t)fw_params_of(C)->v[FP_TELEMETRY_MS] + 1u);
    const hal_can_frame *f = fake_last(&F, proto_table[PM_SLIDES_A].function, from);
    assert_non_null(f);
    memcpy(a1, f->data, 4);
    memcpy(b1, f->data + 4, 4);
}

static void slides_beyond_the_field_are_sent_at_its_end(void **state)
{
    (void)state;
    start();
    /* A 5 m stroke: a set the controller takes, and room for a slide beyond the field.  (Switches
     * at 3 m are no longer a set it takes: homing's final move from there has no valid pose.) */
    set(FP_S_MAX, 5000000);
    /* A1 at 3 m and B1 at 1 m (in steps at 1.28M a metre), as homing would leave them. */
    int32_t pos[6] = {3840000, 1280000, 0, 0, 0, 0};
    assert_int_equal(fw_testing_set_positions(C, pos), 0);
    int32_t a1 = 0, b1 = 0;
    slides_a(&a1, &b1);
    assert_int_equal(a1, INT32_MAX);
    assert_int_equal(b1, 1000000000);
    /* And below: -3 m. */
    pos[0] = -3840000;
    assert_int_equal(fw_testing_set_positions(C, pos), 0);
    slides_a(&a1, &b1);
    assert_int_equal(a1, INT32_MIN);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(slides_beyond_the_field_are_sent_at_its_end),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* tsectl's bus time of a frame (host_tools/tsectl/can_bits.h), against what is worked by hand from
 * ISO 11898-1's frame layout: the all-zero frame, and the bounds every 8-byte frame lies within. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "can_bits.h"

/* Identifier 0, no data: SOF, 11 identifier bits, RTR, IDE, r0 and the DLC are 19 zeros; the CRC-15
 * of all-zero bits from a zero register is 0: 15 more, 34 zeros.  A stuff bit (a one) after each
 * fifth equal bit, the run starting afresh after it: after zeros 5, 10, 15, 20, 25 and 30, six.
 * Then the CRC delimiter (1), the ACK slot and delimiter (2), end of frame (7), intermission (3):
 * 34 + 6 + 13 = 53. */
static void test_all_zero_frame(void **state)
{
    (void)state;
    assert_int_equal(can_frame_bits(0, NULL, 0), 53);
}

/* 8 data bytes: 98 bits from SOF to the CRC's last, 13 after them: 111 without a stuff bit; at most
 * one stuff bit per four bits after the first five, (98 - 1) / 4 = 24: 135. */
static void test_eight_bytes_within_bounds(void **state)
{
    (void)state;
    uint32_t x = 12345;
    unsigned lo = 1000, hi = 0;
    for (int n = 0; n < 20000; ++n) {
        uint8_t d[8];
        for (int k = 0; k < 8; ++k) {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            d[k] = (uint8_t)x;
        }
        const unsigned b = can_frame_bits((uint16_t)(x & 0x7FFu), d, 8);
        lo = b < lo ? b : lo;
        hi = b > hi ? b : hi;
    }
    assert_true(lo >= 111);
    assert_true(hi <= 135);
    print_message("20000 random 8-byte frames: %u to %u bits\n", lo, hi);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_all_zero_frame),
        cmocka_unit_test(test_eight_bytes_within_bounds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* tsectl's words for MOVE_INFO (move_text.h): a move that starts otherwise than from rest, or takes
 * longer than asked, says so and why; one at the pace asked from rest adds nothing. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <string.h>

#include "move_text.h"

static const char *words(int start, int bound, int slide, int demand)
{
    static char buf[256];
    proto_message m;
    memset(&m, 0, sizeof m);
    m.msg = PM_MOVE_INFO;
    m.v[1] = start;
    m.v[2] = bound;
    m.v[3] = slide;
    m.v[4] = demand;
    return move_info_text(&m, buf, sizeof buf);
}

static void has(const char *text, const char *part)
{
    if (!strstr(text, part))
        fail_msg("'%s' not in '%s'", part, text);
}

static void move_words(void **state)
{
    (void)state;
    assert_string_equal(words(FW_START_REST, FW_BOUND_ASKED, 0, 0), "");
    has(words(FW_START_BLENDED, FW_BOUND_ASKED, 0, 0), ", blended into the running move");
    has(words(FW_START_AFTER, FW_BOUND_ASKED, 0, 0), ", after the running move (blending the two would break a limit)");
    has(words(FW_START_REST, FW_BOUND_PLATE_VMAX, 0, 0), ", paced by the plate's speed limit (plate_vmax)");
    has(words(FW_START_REST, FW_BOUND_PLATE_DWMAX, 0, 0), "(plate_dwmax)");
    const char *t = words(FW_START_BLENDED, FW_BOUND_SLIDE_AMAX, 4, 1140);
    has(t, ", blended into the running move, slower than asked: ");
    has(t, "the slides set the pace (unstretched, slide B2 (scissor 2) would need 1.14 times its acceleration limit, "
           "slide_amax)");
    has(words(FW_START_REST, FW_BOUND_SLIDE_VMAX, 5, 2500), "slide A3 (scissor 3) would need 2.50 times its speed limit");
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(move_words)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}

#include "target_test.h"

static struct {
    const char *suite;
    unsigned passed, failed, case_failures;
} tt;

bool tt_check(bool cond, const char *file, int line, const char *what)
{
    if (!cond) {
        ++tt.case_failures;
        sh_printf("  FAIL %s:%d: %s\n", file, line, what);
    }
    return cond;
}

void tt_begin(const char *suite)
{
    tt.suite = suite;
    sh_printf("[%s] on the emulated Cortex-M4F\n", suite);
}

void tt_case(const char *name, void (*fn)(void))
{
    tt.case_failures = 0;
    fn();
    if (tt.case_failures == 0) {
        ++tt.passed;
        sh_printf("[ OK ] %s\n", name);
    } else {
        ++tt.failed;
        sh_printf("[FAIL] %s (%u checks)\n", name, tt.case_failures);
    }
}

void tt_finish(void)
{
    sh_printf("%s: %u passed, %u failed\n", tt.suite, tt.passed, tt.failed);
    sh_exit(tt.failed == 0 && tt.passed > 0 ? 0 : 1);
}

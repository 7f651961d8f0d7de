/* A minimal test harness for images that run on the emulated Cortex-M4F (QEMU netduinoplus2):
 * cases and checks reported through semihosting, a closing line "N passed, M failed", and the
 * exit status QEMU returns (0 only when every case passed).  cmocka is not built for the board;
 * this is the little of it the target tests need. */
#ifndef TSE_TARGET_TEST_H
#define TSE_TARGET_TEST_H

#include <stdbool.h>

#include "hal_stm32f4/semihost.h"

/* Records a failed check of the running case and prints where; returns cond. */
bool tt_check(bool cond, const char *file, int line, const char *what);

#define TT_CHECK(cond) tt_check((cond), __FILE__, __LINE__, #cond)
/* A check with a message built like printf's when it fails. */
#define TT_CHECKF(cond, ...)                                                                     \
    do {                                                                                         \
        if (!tt_check((cond), __FILE__, __LINE__, #cond))                                        \
            sh_printf("    " __VA_ARGS__);                                                       \
    } while (0)

void tt_begin(const char *suite);
void tt_case(const char *name, void (*fn)(void));
/* Prints the closing line and leaves QEMU with the verdict. */
__attribute__((noreturn)) void tt_finish(void);

#endif

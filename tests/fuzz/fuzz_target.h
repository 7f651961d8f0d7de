/* What every fuzz target provides, and how it reports a broken promise.
 *
 * A target is one LLVMFuzzerTestOneInput over one module.  It is built twice: against libFuzzer
 * in the `fuzz` preset (clang, -fsanitize=fuzzer,address,undefined), and against replay_main.c in
 * every other host build, where it replays the committed corpus and the crash regressions as an
 * ordinary test.  A crash the fuzzer finds is fixed and its input kept in regressions/<target>/,
 * so that the regular build keeps checking it. */
#ifndef TESTS_FUZZ_TARGET_H
#define TESTS_FUZZ_TARGET_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A broken invariant: say which and where, then abort so that libFuzzer keeps the input (and the
 * replay fails). */
#define FUZZ_CHECK(cond)                                                                            \
    do {                                                                                            \
        if (!(cond)) {                                                                              \
            fprintf(stderr, "%s:%d: invariant broken: %s\n", __FILE__, __LINE__, #cond);           \
            abort();                                                                                \
        }                                                                                           \
    } while (0)

#endif

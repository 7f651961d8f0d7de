/* A scratch directory for tests that write files: made before a test (cmocka setup), removed
 * after it (teardown), with the paths of files inside it. */
#ifndef TESTS_SCRATCH_DIR_H
#define TESTS_SCRATCH_DIR_H

/* cmocka setup / teardown. */
int scratch_dir_make(void **state);
int scratch_dir_remove(void **state);

/* DIR/name, in a static buffer (valid until the next call). */
const char *scratch_path(const char *name);

#endif

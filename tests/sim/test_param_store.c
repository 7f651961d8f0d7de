/* tse-sim's parameter storage (host_tools/tse_sim/param_store.h): the firmware's record saved
 * through it lands in the text file and comes back from it as the same set; a missing file is the
 * defaults; a bad file does not open and is left as it was; a save that cannot be done fails. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "param_store.h"
#include "scratch_dir.h"

static size_t slurp(const char *path, char *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    const size_t n = fread(buf, 1, cap - 1, f);
    buf[n] = '\0';
    fclose(f);
    return n;
}

static void test_save_then_load(void **state)
{
    (void)state;
    const char *p = scratch_path("sim.params");
    char err[512] = "";
    sim_param_store st;
    assert_int_equal(sim_param_store_open(&st, p, FW_RATES_BUILT_IN, NULL, err, sizeof err), 0);
    hal_storage h = sim_param_store_hal(&st);
    uint8_t buf[256];
    assert_int_equal(h.load(h.ctx, buf, sizeof buf), 0); /* nothing stored: the firmware's defaults */
    assert_int_equal(access(p, F_OK), -1);               /* and nothing written */

    /* PARAM_SAVE of a changed set, as the firmware does it: its record. */
    fw_param_set set;
    fw_params_default(&set);
    set.v[FP_SLIDE_VMAX] = 123457;
    set.v[FP_ETA] = -400003;
    set.v[FP_WATCHDOG_MS] = 0;
    set.v[FP_CAN_KBPS] = 1000;
    const size_t n = fw_params_serialize(&set, buf, sizeof buf);
    assert_true(n > 0);
    assert_int_equal(h.save(h.ctx, buf, n), 0);
    char text[16384];
    slurp(p, text, sizeof text);
    if (!strstr(text, "\nslide_vmax = 0.123457\n") || !strstr(text, "\neta = -0.400003\n"))
        fail_msg("not the SI text of the set:\n%s", text);

    /* The next start: a fresh store on that file hands fw_init the same record. */
    sim_param_store again;
    assert_int_equal(sim_param_store_open(&again, p, FW_RATES_BUILT_IN, NULL, err, sizeof err), 0);
    h = sim_param_store_hal(&again);
    uint8_t back[256];
    const int m = h.load(h.ctx, back, sizeof back);
    assert_int_equal(m, (int)n);
    fw_param_set loaded;
    fw_params_default(&loaded);
    assert_int_equal(fw_params_deserialize(&loaded, back, (size_t)m), 0);
    assert_memory_equal(&loaded, &set, sizeof set);
    /* Too little room for the record is an error, not a cut record. */
    assert_int_equal(h.load(h.ctx, back, 8), -1);
}

static void test_bad_file_does_not_open(void **state)
{
    (void)state;
    const char *p = scratch_path("bad.params");
    static const char bad[] = "# mine\nslide_vmax = 0.2\nslide_amax = lots\n";
    FILE *f = fopen(p, "wb");
    assert_non_null(f);
    fputs(bad, f);
    fclose(f);
    char err[512] = "", want[256];
    sim_param_store st;
    assert_int_equal(sim_param_store_open(&st, p, FW_RATES_BUILT_IN, NULL, err, sizeof err), -1);
    snprintf(want, sizeof want, "%s:3: slide_amax: 'lots' is not one finite number (in m/s^2)", p);
    assert_string_equal(err, want);
    char text[256];
    slurp(p, text, sizeof text);
    assert_string_equal(text, bad);
}

static void test_save_that_cannot_be_done(void **state)
{
    (void)state;
    char err[512] = "";
    sim_param_store st;
    uint8_t buf[256];
    fw_param_set set;
    fw_params_default(&set);
    const size_t n = fw_params_serialize(&set, buf, sizeof buf);

    /* No file given. */
    assert_int_equal(sim_param_store_open(&st, NULL, FW_RATES_BUILT_IN, NULL, err, sizeof err), 0);
    hal_storage h = sim_param_store_hal(&st);
    assert_int_equal(h.save(h.ctx, buf, n), -1);
    assert_non_null(strstr(st.err, "no parameter file"));

    /* A record that is not one (a flipped bit breaks its CRC). */
    const char *p = scratch_path("never.params");
    assert_int_equal(sim_param_store_open(&st, p, FW_RATES_BUILT_IN, NULL, err, sizeof err), 0);
    h = sim_param_store_hal(&st);
    buf[10] ^= 1u;
    assert_int_equal(h.save(h.ctx, buf, n), -1);
    assert_int_equal(access(p, F_OK), -1);
    buf[10] ^= 1u;

    /* A directory that does not exist. */
    assert_int_equal(sim_param_store_open(&st, scratch_path("no/such/x.params"), FW_RATES_BUILT_IN, NULL, err, sizeof err), 0);
    h = sim_param_store_hal(&st);
    assert_int_equal(h.save(h.ctx, buf, n), -1);
    assert_non_null(strstr(st.err, "cannot create"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_save_then_load),
        cmocka_unit_test(test_bad_file_does_not_open),
        cmocka_unit_test(test_save_that_cannot_be_done),
    };
    return cmocka_run_group_tests(tests, scratch_dir_make, scratch_dir_remove);
}

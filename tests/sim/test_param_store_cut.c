/* Issue 9 on the simulator: tse-sim killed in the middle of a PARAM_SAVE.  Its storage
 * (host_tools/tse_sim/param_store.h) writes the parameter text file through param_file_write;
 * after the kill the next start must find the previous set or the new one, never a mix, never a
 * file it cannot load, and a further save must work.
 *
 * The kill: a child process does the save under RLIMIT_FSIZE = b.  The kernel lets its writes
 * reach b bytes of a file and kills it with SIGXFSZ at the first write beyond, so the save dies
 * with exactly b bytes written (at b = the new file's length it completes).  The code under test
 * runs unchanged.  With SIGXFSZ ignored the same limit makes the write fail instead (a full
 * disk), which needs no process and so runs at every byte.  What neither shows, the fsyncs
 * against a power cut, is outside this test: the files live in a memory file system where one
 * is available, since the page cache survives a kill anyway.
 *
 * Also counted, as the reason the file is never written in place: what the next start would
 * have loaded had the cut file been the parameter file itself. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <signal.h>
#include <stdbool.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "param_store.h"
#include "param_text.h"

static char dir[64];
static char path[128], tmp_path[160];

static int make_dir(void **state)
{
    (void)state;
    strcpy(dir, "/dev/shm/tse_cut.XXXXXX");
    if (!mkdtemp(dir)) {
        strcpy(dir, "/tmp/tse_cut.XXXXXX");
        if (!mkdtemp(dir))
            return -1;
    }
    snprintf(path, sizeof path, "%s/sim.params", dir);
    /* the temporary's name is param_text.h's promise: PATH.tmp */
    snprintf(tmp_path, sizeof tmp_path, "%s.tmp", path);
    return 0;
}

static int remove_dir(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    return system(cmd) == 0 ? 0 : -1;
}

/* The whole of a file; its length in *len, -1 if it does not exist. */
static char *slurp(const char *p, long *len)
{
    FILE *f = fopen(p, "rb");
    if (!f) {
        *len = -1;
        return NULL;
    }
    struct stat sb;
    assert_int_equal(fstat(fileno(f), &sb), 0);
    char *buf = malloc((size_t)sb.st_size + 1u);
    assert_non_null(buf);
    *len = (long)fread(buf, 1, (size_t)sb.st_size + 1u, f);
    assert_int_equal(*len, (long)sb.st_size);
    fclose(f);
    return buf;
}

static void put_file(const char *p, const char *bytes, long len)
{
    FILE *f = fopen(p, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(bytes, 1, (size_t)len, f), (size_t)len);
    assert_int_equal(fclose(f), 0);
}

/* Three sets, each differing from the others in every parameter changed here. */
static fw_param_set set_of(int n)
{
    fw_param_set s;
    fw_params_default(&s);
    s.v[FP_SLIDE_VMAX] = 120000 + 1111 * n;
    s.v[FP_SLIDE_AMAX] = 800000 + 22222 * n;
    s.v[FP_ETA] = 500000 + 3333 * n;
    s.v[FP_PLATE_JMAX] = 9000000 + 444444 * n;
    s.v[FP_WATCHDOG_MS] = 300 + 55 * n;
    s.v[FP_TELEMETRY_MS] = 20 + 6 * n;
    s.v[FP_MU_MIN] = 40000 + 777 * n;
    s.v[FP_CAN_KBPS] = n == 1 ? 250 : n == 2 ? 1000 : 125;
    return s;
}

/* The firmware's record of set n, as PARAM_SAVE hands it to hal_storage. */
static size_t record_of(int n, uint8_t *buf, size_t cap)
{
    const fw_param_set s = set_of(n);
    const size_t len = fw_params_serialize(&s, buf, cap);
    assert_true(len > 0);
    return len;
}

/* What a fresh start (sim_param_store_open, then fw_init's load) finds at PATH: the number of
 * the set, 0 for none of the three, -1 if the store does not open or loads nothing. */
static int started_with(void)
{
    sim_param_store st;
    char err[512];
    if (sim_param_store_open(&st, path, FW_RATES_BUILT_IN, NULL, err, sizeof err) != 0)
        return -1;
    const hal_storage h = sim_param_store_hal(&st);
    uint8_t buf[256];
    const int n = h.load(h.ctx, buf, sizeof buf);
    if (n <= 0)
        return -1;
    fw_param_set got;
    fw_params_default(&got);
    assert_int_equal(fw_params_deserialize(&got, buf, (size_t)n), 0);
    for (int k = 1; k <= 3; ++k) {
        const fw_param_set want = set_of(k);
        if (memcmp(&got, &want, sizeof got) == 0)
            return k;
    }
    return 0;
}

/* A PARAM_SAVE of set n in a child that the kernel kills at its first write past `limit` bytes
 * (no limit: RLIM_INFINITY).  Returns the child's wait status. */
static int save_in_child(int n, rlim_t limit)
{
    uint8_t rec[256];
    const size_t len = record_of(n, rec, sizeof rec);
    fflush(NULL); /* nothing buffered is written twice */
    const pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        const struct rlimit core = {0, 0}, fsize = {limit, limit};
        signal(SIGXFSZ, SIG_DFL);
        if (setrlimit(RLIMIT_CORE, &core) != 0 || setrlimit(RLIMIT_FSIZE, &fsize) != 0)
            _exit(4);
        sim_param_store st;
        char err[512];
        if (sim_param_store_open(&st, path, FW_RATES_BUILT_IN, NULL, err, sizeof err) != 0)
            _exit(5);
        const hal_storage h = sim_param_store_hal(&st);
        _exit(h.save(h.ctx, rec, len) == 0 ? 0 : 6);
    }
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    return status;
}

/* A PARAM_SAVE of set n by a simulator that started on PATH as it is; it must succeed. */
static void save_here(int n)
{
    uint8_t rec[256];
    const size_t len = record_of(n, rec, sizeof rec);
    sim_param_store st;
    char err[512];
    assert_int_equal(sim_param_store_open(&st, path, FW_RATES_BUILT_IN, NULL, err, sizeof err), 0);
    const hal_storage h = sim_param_store_hal(&st);
    assert_int_equal(h.save(h.ctx, rec, len), 0);
}

/* Set 1's file (what PATH holds before each save) and set 2's (what the save writes). */
static char *old_bytes, *new_bytes;
static long old_len, new_len;

static void make_files(void)
{
    remove(path);
    remove(tmp_path);
    save_here(2);
    new_bytes = slurp(path, &new_len);
    assert_true(new_len > 1000);
    assert_int_equal(access(tmp_path, F_OK), -1);
    save_here(1);
    old_bytes = slurp(path, &old_len);
    assert_int_equal(started_with(), 1);
}

static void free_files(void)
{
    free(old_bytes);
    free(new_bytes);
}

/* PATH holds set 1's file or, if `whole`, set 2's, and the next start has that set. */
static void check_file(long b, bool whole)
{
    const int got = started_with();
    if (got != (whole ? 2 : 1))
        fail_msg("cut at byte %ld of %ld: the next start has %s", b, new_len,
                 got < 0    ? "no set"
                 : got == 0 ? "neither set (a mix, or the defaults)"
                 : got == 1 ? "the old set"
                            : "the new set");
    long len;
    char *now = slurp(path, &len);
    if (whole) {
        assert_int_equal(len, new_len);
        assert_memory_equal(now, new_bytes, (size_t)len);
    } else {
        assert_int_equal(len, old_len);
        assert_memory_equal(now, old_bytes, (size_t)len);
    }
    free(now);
}

/* The simulator goes on: a further save works (over whatever temporary is left) and is what
 * the start after finds. */
static void go_on(void)
{
    save_here(3);
    assert_int_equal(started_with(), 3);
    assert_int_equal(access(tmp_path, F_OK), -1);
}

/* Where the kill test cuts: every byte with TSE_CUT_EVERY_BYTE set (a process each: half a
 * minute here, minutes under the sanitizers); otherwise the first and last bytes, both sides of
 * stdio's 4 KiB writes, and every 37th byte between (37: prime, so that the cuts fall at every
 * place within the lines).  The write failure test covers every byte. */
static bool cut_at(long b)
{
    return getenv("TSE_CUT_EVERY_BYTE") || b <= 16 || new_len - b <= 16 || b % 37 == 0 ||
           b % 4096 <= 1 || b % 4096 == 4095;
}

static void test_killed_during_a_save(void **state)
{
    (void)state;
    make_files();
    unsigned killed = 0;
    for (long b = 0; b <= new_len; ++b) {
        if (b < new_len && !cut_at(b))
            continue;
        put_file(path, old_bytes, old_len);
        /* The temporary of the round before is there too, as a kill would leave it. */
        const int status = save_in_child(2, (rlim_t)b);
        check_file(b, b == new_len);
        if (b < new_len) {
            if (!WIFSIGNALED(status) || WTERMSIG(status) != SIGXFSZ)
                fail_msg("cut at byte %ld: the save was not killed (status 0x%x)", b, status);
            ++killed;
            /* It died with b bytes of the temporary written. */
            long tmp_len;
            char *tmp = slurp(tmp_path, &tmp_len);
            assert_int_equal(tmp_len, b);
            assert_memory_equal(tmp, new_bytes, (size_t)b);
            free(tmp);
        } else {
            assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
        }
        go_on();
        if (b < new_len) {
            /* A leftover temporary for the next round: another set's whole file. */
            long tl;
            char *t = slurp(path, &tl);
            put_file(tmp_path, t, tl);
            free(t);
        }
    }
    /* Killed once the temporary was complete, before the rename: that state by hand. */
    put_file(path, old_bytes, old_len);
    put_file(tmp_path, new_bytes, new_len);
    check_file(new_len, false);
    go_on();

    print_message("tse-sim killed at %u of the %ld byte offsets of a parameter file save (then "
                  "uncut, and killed before the rename): the old set every time, then the new "
                  "one; never a mix or an unloadable file\n",
                  killed, new_len);
    assert_true(killed > 100);
    free_files();
}

static void test_write_failure_at_every_byte(void **state)
{
    (void)state;
    /* With SIGXFSZ ignored the same limit fails the write (EFBIG) instead of killing: a disk
     * that fills up at byte b.  The save must fail and leave the file and no temporary. */
    make_files();
    struct rlimit was;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &was), 0);
    assert_true(was.rlim_cur == RLIM_INFINITY || (long)was.rlim_cur > new_len);
    void (*handler)(int) = signal(SIGXFSZ, SIG_IGN);
    uint8_t rec[256];
    const size_t rec_len = record_of(2, rec, sizeof rec);
    const fw_param_set s2 = set_of(2);
    unsigned failed = 0, in_place_refused = 0, in_place_mix = 0, in_place_new = 0;
    sim_param_store st;
    char err[512];
    bool reopen = true;
    for (long b = 0; b <= new_len; ++b) {
        if (reopen) {
            put_file(path, old_bytes, old_len);
            assert_int_equal(sim_param_store_open(&st, path, FW_RATES_BUILT_IN, NULL, err, sizeof err), 0);
        }
        const hal_storage h = sim_param_store_hal(&st);
        const struct rlimit lim = {(rlim_t)b, was.rlim_max};
        assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
        const int r = h.save(h.ctx, rec, rec_len);
        assert_int_equal(setrlimit(RLIMIT_FSIZE, &was), 0);
        /* Every parse here costs a megabyte's buffer (param_file_read), slow under the
         * sanitizers: the file's bytes at every offset; a restart and a further save at the
         * kill test's offsets. */
        reopen = b == new_len || cut_at(b);
        if (reopen) {
            check_file(b, b == new_len);
        } else {
            long len;
            char *now = slurp(path, &len);
            assert_int_equal(len, old_len);
            assert_memory_equal(now, old_bytes, (size_t)len);
            free(now);
        }
        if (b < new_len) {
            if (r != -1 || !strstr(st.err, "cannot write"))
                fail_msg("write failing at byte %ld: save returned %d (%s)", b, r, st.err);
            ++failed;
            assert_int_equal(access(tmp_path, F_OK), -1);
        } else {
            assert_int_equal(r, 0);
        }
        if (reopen)
            go_on();

        if (b < new_len) {
            /* Had the file been written in place, the next start would have read this. */
            put_file(tmp_path, new_bytes, b);
            fw_param_set s;
            fw_params_default(&s);
            if (param_file_read(tmp_path, &s, FW_RATES_BUILT_IN, err, sizeof err) != 0)
                ++in_place_refused;
            else if (memcmp(&s, &s2, sizeof s) == 0)
                ++in_place_new;
            else
                ++in_place_mix; /* never the old set: the text holds set 2 and defaults */
            remove(tmp_path);
        }
    }
    signal(SIGXFSZ, handler);
    assert_int_equal(failed, (unsigned)new_len);
    assert_true(in_place_mix > 0); /* the hazard the rename avoids is real */
    print_message("tse-sim's parameter file save failing at each of its %ld byte offsets: "
                  "refused every time, the old file kept and no temporary left; had the file "
                  "been written in place, the next start would have refused %u, taken a mix "
                  "of the two sets and defaults %u times, the new set %u times\n",
                  new_len, in_place_refused, in_place_mix, in_place_new);
    free_files();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_killed_during_a_save),
        cmocka_unit_test(test_write_failure_at_every_byte),
    };
    return cmocka_run_group_tests(tests, make_dir, remove_dir);
}

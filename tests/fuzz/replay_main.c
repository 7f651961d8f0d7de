/* The driver of a fuzz target outside libFuzzer: feeds it every file under the directories and
 * files named on the command line, in name order, so that the committed corpus and the crash
 * regressions run as an ordinary test in the host and sanitizer builds. */
#define _DEFAULT_SOURCE /* scandir */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_target.h"

#define REPLAY_MAX_INPUT (1u << 20)

static unsigned long replayed;

static int replay_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        perror(path);
        return -1;
    }
    static uint8_t buf[REPLAY_MAX_INPUT];
    const size_t n = fread(buf, 1, sizeof buf, f);
    const int err = ferror(f) || (n == sizeof buf && fgetc(f) != EOF);
    fclose(f);
    if (err) {
        fprintf(stderr, "%s: unreadable or longer than %u bytes\n", path, REPLAY_MAX_INPUT);
        return -1;
    }
    LLVMFuzzerTestOneInput(buf, n);
    ++replayed;
    return 0;
}

static int by_name(const struct dirent **a, const struct dirent **b)
{
    return strcmp((*a)->d_name, (*b)->d_name);
}

static int replay_path(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        perror(path);
        return -1;
    }
    if (!S_ISDIR(st.st_mode))
        return replay_file(path);
    struct dirent **names;
    const int n = scandir(path, &names, NULL, by_name);
    if (n < 0) {
        perror(path);
        return -1;
    }
    int rc = 0;
    for (int i = 0; i < n; ++i) {
        if (names[i]->d_name[0] != '.' && rc == 0) {
            char sub[4096];
            snprintf(sub, sizeof sub, "%s/%s", path, names[i]->d_name);
            rc = replay_path(sub);
        }
        free(names[i]);
    }
    free(names);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s DIR_OR_FILE...\n", argv[0]);
        return 2;
    }
    for (int i = 1; i < argc; ++i)
        if (replay_path(argv[i]) != 0)
            return 1;
    if (replayed == 0) {
        fprintf(stderr, "%s: no input found\n", argv[0]);
        return 1;
    }
    printf("replayed %lu inputs\n", replayed);
    return 0;
}

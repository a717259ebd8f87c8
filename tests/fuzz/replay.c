/*
 * Replay inputs through the fuzz targets without libFuzzer: the
 * 'fuzz-regressions' test (TAP), in every build, sanitizers or not.
 *
 *     fuzz_replay [--spec | --expr | --pipeline | --runtime] PATH...
 *
 * Each PATH (a file, or a directory whose files are taken in name order)
 * goes through the target named by the option before it.  A crash or a
 * sanitizer report fails the test; diagnostics are expected and silenced.
 */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef int (*Target)(const uint8_t *data, size_t size);

static int ntests;

static void
replay_file(Target fn, const char *name, const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        printf("not ok %d - %s %s: cannot read\n", ++ntests, name, path);
        exit(1);
    }
    size_t cap = 4096, n = 0, k;
    uint8_t *buf = malloc(cap);
    while (buf && (k = fread(buf + n, 1, cap - n, f)) > 0)
        if ((n += k) == cap)
            buf = realloc(buf, cap *= 2);
    fclose(f);
    if (!buf) {
        printf("not ok %d - %s %s: out of memory\n", ++ntests, name, path);
        exit(1);
    }
    /* an exact-size copy, as libFuzzer gives: reading past the end is caught */
    uint8_t *data = malloc(n ? n : 1);
    memcpy(data, buf, n);
    free(buf);
    fn(data, n);
    free(data);
    printf("ok %d - %s %s (%zu bytes)\n", ++ntests, name, path, n);
    fflush(stdout);
}

static int
by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static void
replay(Target fn, const char *name, const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode)) {
        replay_file(fn, name, path);
        return;
    }
    DIR *d = opendir(path);
    if (!d) {
        printf("not ok %d - %s %s: cannot list\n", ++ntests, name, path);
        exit(1);
    }
    char **files = NULL;
    size_t n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        files = realloc(files, (n + 1) * sizeof *files);
        size_t len = strlen(path) + strlen(e->d_name) + 2;
        files[n] = malloc(len);
        snprintf(files[n++], len, "%s/%s", path, e->d_name);
    }
    closedir(d);
    qsort(files, n, sizeof *files, by_name);
    for (size_t i = 0; i < n; i++) {
        replay_file(fn, name, files[i]);
        free(files[i]);
    }
    free(files);
}

int
main(int argc, char **argv)
{
    static const struct {
        const char *opt, *name;
        Target fn;
    } targets[] = {
        {"--spec", "spec", fuzz_spec},
        {"--expr", "expr", fuzz_expr},
        {"--pipeline", "pipeline", fuzz_pipeline},
        {"--runtime", "runtime", fuzz_runtime},
    };
    int t = 0;
    for (int i = 1; i < argc; i++) {
        int opt = 0;
        for (size_t k = 0; k < sizeof targets / sizeof targets[0]; k++)
            if (!strcmp(argv[i], targets[k].opt))
                t = (int)k, opt = 1;
        if (!opt)
            replay(targets[t].fn, targets[t].name, argv[i]);
    }
    printf("1..%d\n", ntests);
    return 0;
}

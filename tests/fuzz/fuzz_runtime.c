/*
 * Fuzz target: the simulator's readers of what a user types, through its
 * command line (eomc_main), on hand-written models (tests/runtime/models.c)
 * and the generated Cartesian pendulum: the values of --init, --set,
 * --hold and --sweep, and the files of --sweep-file and --reference.  Any
 * usage error is fine; a crash, a sanitizer report, a leak or a hang is
 * not.
 *
 * An input is a byte of choices, then fields separated by NUL bytes:
 *
 *     choices  INIT \0 SET \0 HOLD \0 SWEEP \0 SWEEP_FILE \0 REFERENCE
 *
 * INIT, SET and SWEEP hold one option value a line (each line an --init,
 * --set or --sweep); HOLD is --hold's list (with --assemble); SWEEP_FILE
 * and REFERENCE are written to files whose names --sweep-file and
 * --reference get.  The choices: bits 0-1 the model (osc, driven,
 * cartesian_pendulum, osc), bit 2 --sweep, bit 3 --sweep-file, bit 4
 * --assemble --hold; without a sweep, bit 5 a run measured against
 * --reference, else bit 6 --linearize, else --accel; bit 7 every value as
 * --option=VALUE rather than two arguments.  An empty field gives no
 * option.
 *
 * Every run is short whatever the values: t = 0 to 0.5 every 0.1, at most
 * 200 steps; a sweep of more than MAX_RUNS runs is not tried.  The CSV and
 * the summaries go to /dev/null, --accel's lines too; messages go to
 * stderr (run_fuzz.sh closes it).
 */
#define _POSIX_C_SOURCE 200809L
#include "fuzz.h"

#include "eomc.h"
#include "../runtime/models.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

extern const eomc_model cartesian_pendulum_model;

enum { NFIELDS = 6, MAX_LINES = 8, MAX_ARGS = 2 * (3 * MAX_LINES + 8) + 16, MAX_RUNS = 64,
       MAX_FILE_ROWS = 512 };

static char sweep_path[] = "/tmp/eomc-fuzz-sweep-XXXXXX";
static char ref_path[] = "/tmp/eomc-fuzz-reference-XXXXXX";

static void
remove_files(void)
{
    unlink(sweep_path);
    unlink(ref_path);
}

/* The two files' names, made once. */
static int
make_files(void)
{
    static int made;
    if (!made) {
        int a = mkstemp(sweep_path), b = mkstemp(ref_path);
        if (a < 0 || b < 0)
            return -1;
        close(a);
        close(b);
        atexit(remove_files);
        made = 1;
    }
    return 0;
}

static int
write_file(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(text, 1, len, f) == len;
    return (f && fclose(f) != 0) || !ok ? -1 : 0;
}

typedef struct Args {
    int argc, eq;
    char *argv[MAX_ARGS + 1];
} Args;

/* opt and its value, as two arguments or as opt=value. */
static void
add(Args *a, const char *opt, char *val)
{
    if (a->argc + 2 > MAX_ARGS)
        return;
    if (!val) {
        a->argv[a->argc++] = (char *)opt;
        return;
    }
    if (a->eq) {
        size_t n = strlen(opt) + strlen(val) + 2;
        char *s = malloc(n);
        if (!s)
            return;
        snprintf(s, n, "%s=%s", opt, val);
        a->argv[a->argc++] = s;
        return;
    }
    a->argv[a->argc++] = (char *)opt;
    a->argv[a->argc++] = val;
}

/* Each line of field as a value of opt (at most MAX_LINES), none when it
 * is empty; field is cut into its lines in place. */
static void
add_lines(Args *a, const char *opt, char *field)
{
    int n = 0;
    for (char *line = *field ? field : NULL; line && n < MAX_LINES; n++) {
        char *nl = strchr(line, '\n');
        if (nl)
            *nl = '\0';
        add(a, opt, line);
        line = nl ? nl + 1 : NULL;
    }
}

/* The runs a grid of --sweep lines asks for, as cli.c reads COUNT (after
 * the last colon), or a bound on them; MAX_RUNS + 1 when over. */
static long
grid_runs(const char *field)
{
    long runs = 1;
    int n = 0;
    for (const char *line = field; line && n < MAX_LINES; n++) {
        const char *nl = strchr(line, '\n'), *colon = NULL;
        for (const char *p = line; *p && p != nl; p++)
            if (*p == ':')
                colon = p;
        long count = colon ? strtol(colon + 1, NULL, 10) : 1;
        if (count > MAX_RUNS || (count > 1 && runs > MAX_RUNS / count))
            return MAX_RUNS + 1;
        runs *= count > 1 ? count : 1;
        line = nl ? nl + 1 : NULL;
    }
    return runs;
}

FUZZ_ENTRY(runtime)
{
    if (size < 1 || make_files() != 0)
        return 0;
    /* the fields, NUL-terminated copies */
    char *text = malloc(size);
    if (!text)
        return 0;
    memcpy(text, data + 1, size - 1);
    text[size - 1] = '\0';
    char *field[NFIELDS];
    size_t len[NFIELDS];
    char *p = text, *end = text + size - 1;
    for (int k = 0; k < NFIELDS; k++) {
        field[k] = p;
        len[k] = strlen(p);
        p = p + len[k] < end ? p + len[k] + 1 : end;
    }
    int choice = data[0];
    static const eomc_model *const models[] = {&osc_model, &driven_model,
                                               &cartesian_pendulum_model, &osc_model};
    const eomc_model *m = models[choice & 3];
    int rows = 0;
    for (size_t i = 0; i < len[4]; i++)
        rows += field[4][i] == '\n';
    if (((choice & 4) && grid_runs(field[3]) > MAX_RUNS) || rows > MAX_FILE_ROWS ||
        write_file(sweep_path, field[4], len[4]) != 0 ||
        write_file(ref_path, field[5], len[5]) != 0) {
        free(text);
        return 0;
    }

    /* a sweep, or a run against the reference, or --linearize, or --accel */
    int sweep = choice & 12, linearize = !sweep && !(choice & 32) && (choice & 64);
    Args a = {.eq = choice >> 7 & 1};
    a.argv[a.argc++] = "fuzz";
    add(&a, "--t-end", "0.5");
    add(&a, "--dt", "0.1");
    add(&a, "--max-steps", "200");
    if (!linearize)
        add(&a, "-o", "/dev/null");
    add_lines(&a, "--init", field[0]);
    add_lines(&a, "--set", field[1]);
    if (choice & 16) {
        add(&a, "--assemble", NULL);
        add(&a, "--hold", field[2]);
    }
    if (choice & 4)
        add_lines(&a, "--sweep", field[3]);
    if (choice & 8)
        add(&a, "--sweep-file", sweep_path);
    if (!sweep)
        add(&a, choice & 32 ? "--reference" : linearize ? "--linearize" : "--accel",
            choice & 32 ? ref_path : NULL);
    int argc = a.argc;
    a.argv[argc] = NULL;

    /* stdout (--accel's and --linearize's lines) to /dev/null meanwhile */
    fflush(stdout);
    int out = dup(1), null = open("/dev/null", O_WRONLY);
    if (null >= 0)
        dup2(null, 1);
    eomc_main(argc, a.argv, m, NULL);
    fflush(stdout);
    if (out >= 0) {
        dup2(out, 1);
        close(out);
    }
    if (null >= 0)
        close(null);

    if (a.eq) /* the --option=VALUE strings */
        for (int i = 1; i < argc; i++)
            if (a.argv[i][0] == '-' && strchr(a.argv[i], '='))
                free(a.argv[i]);
    free(text);
    return 0;
}

/*
 * eomc_main_mem, the command line with its text returned (the Python
 * package's entry, from several threads at once), on the hand-written
 * models of models.c:
 *  - a run's CSV text is byte for byte the file eomc_main writes with -o,
 *    and its stderr text eomc_main's stderr (empty here);
 *  - a bad option: status 2, nothing on out, the usage message on err,
 *    byte for byte eomc_main's; --help on out;
 *  - numerical failures (the non-positive-definite mass matrix at t = 1,
 *    --max-steps 3): status 3, "error" and the time on err, eomc_main's
 *    text; the rows computed up to then on out;
 *  - a sweep on threads of its own: its rows on out, as -o's file;
 *  - five threads at once, each its own t_end (one of them failing, one
 *    a sweep on threads of its own), several calls each: each thread's texts and status are its own
 *    single-threaded ones;
 *  - nothing reaches the process's fd 1 and fd 2 during any of it.
 */
#include "../unit/check.h"

#include <gsl/gsl_errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "eomc.h"
#include "rtest.h"

static char dir[] = "/tmp/eomc-rt-mem-XXXXXX";


/* fd 1 and fd 2 into a file of their own for a while (quiet_begin ..
 * quiet_end), to see that nothing reaches them. */
static int saved1 = -1, saved2 = -1;
static char quiet_path[64];

static void
quiet_begin(void)
{
    fflush(stdout);
    fflush(stderr);
    FILE *f = fopen(quiet_path, "w");
    if (!f)
        exit(1);
    saved1 = dup(1);
    saved2 = dup(2);
    dup2(fileno(f), 1);
    dup2(fileno(f), 2);
    fclose(f);
}

/* What reached fd 1 and fd 2 since quiet_begin (malloc'd). */
static char *
quiet_end(void)
{
    fflush(stdout);
    fflush(stderr);
    dup2(saved1, 1);
    dup2(saved2, 2);
    close(saved1);
    close(saved2);
    return slurp(quiet_path);
}

/* One command line: its model and arguments, what eomc_main did with it
 * (the CSV file of -o, its stderr, its status), what eomc_main_mem did. */
typedef struct Job {
    const eomc_model *m;
    const char *args[8];   /* without argv[0] and -o */
    char *file, *main_err; /* eomc_main's */
    int main_rc;
    char *out, *err;       /* eomc_main_mem's, single-threaded */
    size_t out_len, err_len;
    int rc;
    int agree;             /* threads: every call agreed with out, err, rc */
} Job;

static int
argv_of(const Job *j, char **argv, const char *csv)
{
    int n = 0;
    argv[n++] = "x";
    for (int k = 0; j->args[k]; k++)
        argv[n++] = (char *)j->args[k];
    if (csv) {
        argv[n++] = "-o";
        argv[n++] = (char *)csv;
    }
    argv[n] = NULL;
    return n;
}

/* eomc_main with -o FILE, its stderr caught in a file. */
static void
run_main(Job *j, int k)
{
    char csv[96], errp[96];
    snprintf(csv, sizeof csv, "%s/run%d.csv", dir, k);
    snprintf(errp, sizeof errp, "%s/run%d.err", dir, k);
    char *argv[16];
    int argc = argv_of(j, argv, csv);
    fflush(stderr);
    int e = dup(2);
    FILE *f = fopen(errp, "w");
    dup2(fileno(f), 2);
    fclose(f);
    j->main_rc = eomc_main(argc, argv, j->m, NULL);
    fflush(stderr);
    dup2(e, 2);
    close(e);
    j->file = slurp(csv);
    j->main_err = slurp(errp);
}

static int
run_mem(const Job *j, char **out, size_t *out_len, char **err, size_t *err_len)
{
    char *argv[16];
    int argc = argv_of(j, argv, NULL);
    return eomc_main_mem(argc, argv, j->m, NULL, out, out_len, err, err_len);
}

static int
lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

enum { REPEATS = 3 };

static void *
thread_job(void *arg)
{
    Job *j = arg;
    j->agree = 1;
    for (int r = 0; r < REPEATS; r++) {
        char *out, *err;
        size_t nout, nerr;
        int rc = run_mem(j, &out, &nout, &err, &nerr);
        j->agree &= rc == j->rc && nout == j->out_len && nerr == j->err_len &&
                    memcmp(out, j->out, nout + 1) == 0 && memcmp(err, j->err, nerr + 1) == 0;
        eomc_free(out);
        eomc_free(err);
    }
    return NULL;
}

int
main(void)
{
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(quiet_path, sizeof quiet_path, "%s/quiet", dir);
    /* the caller's duty under eomc_main_mem (eomc.h): the nonpd models'
     * failures come back as statuses */
    gsl_set_error_handler_off();

    Job jobs[] = {
        {.m = &osc_model, .args = {"--t-end", "1"}},
        {.m = &osc_model, .args = {"--t-end", "2.5", "--dt", "0.05"}},
        {.m = &osc_model, .args = {"--t-end", "4", "--set", "k=3"}},
        {.m = &nonpd_model, .args = {"--t-end", "2"}},                /* fails at t = 1 */
        {.m = &osc_model, .args = {"--max-steps", "3", "--t-end", "10"}},
        {.m = &osc_model, .args = {"--bogus"}},
        /* a sweep on threads of its own, whose rows it writes */
        {.m = &osc_model, .args = {"--sweep", "k=1:4:7", "--threads", "3", "--t-end", "2"}},
    };
    enum { NJOBS = sizeof jobs / sizeof *jobs, NTHREADS = 5 };
    /* at once: t_end 1, 2.5 and 4, the failing nonpd, the sweep */
    const int on_thread[NTHREADS] = {0, 1, 2, 3, 6};
    for (int k = 0; k < NJOBS; k++)
        run_main(&jobs[k], k);

    /* every call single-threaded, with fd 1 and fd 2 watched */
    quiet_begin();
    for (int k = 0; k < NJOBS; k++)
        jobs[k].rc = run_mem(&jobs[k], &jobs[k].out, &jobs[k].out_len, &jobs[k].err,
                             &jobs[k].err_len);
    char *help_out, *help_err;
    size_t help_len;
    char *help_argv[] = {"x", "--help", NULL};
    int help_rc = eomc_main_mem(2, help_argv, &osc_model, NULL, &help_out, &help_len,
                                &help_err, NULL);
    char *quiet = quiet_end();
    CHECK(*quiet == '\0', "nothing on fd 1 or fd 2 from eomc_main_mem (got %zu bytes)",
          strlen(quiet));
    free(quiet);

    /* (a) a run: the CSV of -o, byte for byte */
    for (int k = 0; k < 3; k++) {
        Job *j = &jobs[k];
        CHECK(j->rc == 0 && j->main_rc == 0, "run %d: status 0 (mem %d, main %d)", k, j->rc,
              j->main_rc);
        CHECK(j->out_len == strlen(j->out) && j->out_len > 0, "run %d: out_len is the text's "
              "length (%zu)", k, j->out_len);
        CHECK(strcmp(j->out, j->file) == 0, "run %d: out is the CSV eomc_main writes with -o",
              k);
        CHECK(strncmp(j->out, "t,x,x',T,V,E\n", 13) == 0, "run %d: out starts with the header",
              k);
        CHECK(j->err_len == 0 && strcmp(j->err, j->main_err) == 0,
              "run %d: err empty, as eomc_main's stderr", k);
    }
    /* rows every dt (the scene's 0.1, or --dt) and the last at t_end */
    CHECK(lines(jobs[0].out) == 1 + 11, "t_end 1: 11 rows (%d lines)", lines(jobs[0].out));
    CHECK(strstr(jobs[0].out, "\n1,") != NULL, "t_end 1: the last row at 1");
    CHECK(lines(jobs[2].out) == 1 + 41, "t_end 4: 41 rows (%d lines)", lines(jobs[2].out));
    CHECK(lines(jobs[1].out) == 1 + 51, "t_end 2.5, dt 0.05: 51 rows (%d lines)",
          lines(jobs[1].out));
    CHECK(strstr(jobs[1].out, "\n2.5,") != NULL, "t_end 2.5: the last row at 2.5");
    CHECK(strcmp(jobs[0].out, jobs[2].out) != 0, "--set k=3 changes the rows");

    /* (b) failures */
    Job *np = &jobs[3], *ms = &jobs[4], *bad = &jobs[5];
    CHECK(np->rc == 3 && np->main_rc == 3, "nonpd: status 3 (mem %d, main %d)", np->rc,
          np->main_rc);
    CHECK(strstr(np->err, "x: error: ") == np->err && strstr(np->err, "t = 1") != NULL,
          "nonpd: err says error at t = 1: %.60s", np->err);
    CHECK(strcmp(np->err, np->main_err) == 0, "nonpd: err is eomc_main's stderr");
    CHECK(strcmp(np->out, np->file) == 0 && lines(np->out) > 1,
          "nonpd: the rows kept are -o's (%d lines)", lines(np->out));
    CHECK(ms->rc == 3 && ms->main_rc == 3, "--max-steps 3: status 3 (mem %d, main %d)",
          ms->rc, ms->main_rc);
    CHECK(strstr(ms->err, "error") != NULL && strcmp(ms->err, ms->main_err) == 0,
          "--max-steps 3: err says error, as eomc_main: %.60s", ms->err);
    CHECK(strcmp(ms->out, ms->file) == 0, "--max-steps 3: out is -o's file");
    CHECK(bad->rc == 2 && bad->main_rc == 2, "--bogus: status 2 (mem %d, main %d)", bad->rc,
          bad->main_rc);
    CHECK(bad->out_len == 0 && *bad->out == '\0', "--bogus: out empty");
    CHECK(strstr(bad->err, "x: ") == bad->err && strstr(bad->err, "--bogus") != NULL &&
          strstr(bad->err, "(see x --help)\n") != NULL,
          "--bogus: err is the usage message: %s", bad->err);
    CHECK(strcmp(bad->err, bad->main_err) == 0, "--bogus: err is eomc_main's stderr");
    CHECK(help_rc == 0 && strstr(help_out, "usage: x [OPTION]...") == help_out &&
          help_len == strlen(help_out) && *help_err == '\0', "--help: status 0, usage on out");
    Job *sw = &jobs[6];
    CHECK(sw->rc == 0 && sw->main_rc == 0 && strcmp(sw->out, sw->file) == 0 &&
          lines(sw->out) == 1 + 7 && *sw->err == '\0',
          "--sweep on 3 threads: 7 rows, out is -o's file (%d lines)", lines(sw->out));
    eomc_free(help_out);
    eomc_free(help_err);

    /* (c) threads at once, each its own command line */
    pthread_t th[NTHREADS];
    quiet_begin();
    int started = 0;
    for (int k = 0; k < NTHREADS; k++)
        started += pthread_create(&th[k], NULL, thread_job, &jobs[on_thread[k]]) == 0;
    for (int k = 0; k < started; k++)
        pthread_join(th[k], NULL);
    quiet = quiet_end();
    CHECK(started == NTHREADS, "%d threads started", started);
    for (int k = 0; k < started; k++)
        CHECK(jobs[on_thread[k]].agree, "thread %d (%s %s): %d calls, each its single-threaded "
              "out, err and status", k, jobs[on_thread[k]].args[0], jobs[on_thread[k]].args[1],
              REPEATS);
    CHECK(*quiet == '\0', "nothing on fd 1 or fd 2 from the threads (got %zu bytes)",
          strlen(quiet));
    free(quiet);

    for (int k = 0; k < NJOBS; k++) {
        eomc_free(jobs[k].out);
        eomc_free(jobs[k].err);
        free(jobs[k].file);
        free(jobs[k].main_err);
        char p[96];
        snprintf(p, sizeof p, "%s/run%d.csv", dir, k);
        unlink(p);
        snprintf(p, sizeof p, "%s/run%d.err", dir, k);
        unlink(p);
    }
    unlink(quiet_path);
    rmdir(dir);
    return check_done();
}

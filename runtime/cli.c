/*
 * cli: the command line of a standalone simulator (eomc_main).
 *
 * Options are read completely and checked before anything runs, so a
 * mistake costs nothing but a message (exit status 2).  Parameters are set
 * before the initial state is computed (it may depend on them), and --init
 * overrides that state afterwards, whatever the order on the line.
 *
 * Three things a simulator does: one run written as CSV (the default),
 * the accelerations at the initial state (--accel), and the
 * work-precision report of report.c (--work-precision).  A run can also
 * be measured against the reference solution (--error), which both of
 * the last two share.
 */
#include "eomc.h"
#include "compare.h"
#include "nearest.h"
#include "numfmt.h"
#include "plot.h"
#include "report.h"
#include "sweep.h"

#include <errno.h>
#include <gsl/gsl_errno.h>
#include <float.h>
#include <signal.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef EOMC_VERSION
#define EOMC_VERSION "unknown"
#endif

typedef struct Cli {
    const char *prog;
    const char *self;     /* how the user runs it, for --help: prog, or under
                           * `eomc run` "eomc run SPEC" ($EOMC_RUN_COMMAND) */
    eomc_run_opts run;
    const char *out;
    int stats, summary, accel, assemble, work_precision, error, linearize, equilibrium;
    int accel_extended; /* --accel-extended: --accel, solved by the twin */
    int no_assemble;      /* --no-assemble: not even the scene's assembly */
    int scene_assembles;  /* the model's scene says `assemble:` */
    unsigned char *held;  /* [2nq] what the assembly keeps (held_marks) */
    int stabilize;        /* EOMC_STABILIZE_... */
    double alpha, beta;   /* Baumgarte's rates */
    int rates_given, method_given, fixed_given, t0_given, t_end_given;
    char **set, **init;   /* NAME=VALUE arguments, in order */
    int nset, ninit;
    /* the reference and the report */
    const char *reference, *reference_out, *csv, *plot;
    const char *errors;   /* --errors FILE: the errors by component */
    const char *events;   /* --events FILE */
    const char *hold;     /* --hold LIST, for --assemble */
    char **sweep;         /* --sweep NAME=START:STOP:COUNT, in order */
    int nsweep, threads;  /* and --threads N */
    const char *sweep_file;
    const char **methods; /* NULL-terminated */
    double *tolerances, *steps, target;
    int ntolerances, nsteps;
    unsigned report_given; /* bit k: option O_METHODS + k (report-only) was given */
} Cli;

/* Rows go out in blocks of whole rows, each block one write: a run killed
 * at any moment (SIGKILL) leaves a CSV of whole rows.  64 KiB: a few
 * hundred rows of a small model. */
enum { ROW_BLOCK = 64 << 10 };

typedef struct Csv {
    FILE *f;
    eomc_sim *sim;
    long rows;
    int invariant;       /* the model conserves h (or E) */
    double h0, dh;       /* its first value, largest change seen */
    double *res;         /* [nc] constraint residuals of a row, then [nout]
                          * its outputs */
    double res_max;      /* the largest |residual| written */
    const eomc_reference *ref; /* measure against it, or NULL */
    double *arow;        /* [n] scratch: a row's accelerations */
    int rebase;          /* an event reset the state at t_reset: h starts */
    double t_reset;      /* afresh with the first row after it */
    FILE *events;        /* --events FILE, or NULL */
    FILE *tee;           /* a copy of the rows for --plot, or NULL */
    double *out_max;     /* [nout] each output's largest |value| written (for
                          * --plot's panels), after the block's room in res */
    char *blk;           /* rows not yet written, whole rows only: ROW_BLOCK
                          * and room for one more (in res's allocation) */
    size_t blen;
    double h_first;      /* the conserved quantity at the first row */
    double T_max;        /* the largest kinetic energy written: the scale of the
                          * energy the motion moves about, for the drift's */
    double t_last;       /* the time of the last row written */
    double err_max, err_end;
    Compare cmp;         /* the errors by component, with ref */
} Csv;

/* An event as it fires: a row of --events FILE, and a reset ends the
 * conserved quantity's comparison with the rows before. */
static int
write_event(void *ctx, int k, double t, const double *x)
{
    Csv *w = ctx;
    const eomc_model *m = eomc_sim_model(w->sim);
    if (m->ev_action[k] == EOMC_EVENT_SET)
        w->rebase = 1, w->t_reset = t;
    if (!w->events)
        return EOMC_OK;
    num_put(w->events, t);
    fprintf(w->events, ",%s", m->ev_names[k]);
    for (int i = 0; i < 2 * m->nq; i++) {
        fputc(',', w->events);
        num_put(w->events, x[i]);
    }
    fputc('\n', w->events);
    return EOMC_OK;
}


static void
flush_rows(Csv *w)
{
    if (w->blen == 0)
        return;
    FILE *files[] = {w->f, w->tee};
    for (int j = 0; j < 2 && files[j]; j++) {
        fwrite(w->blk, 1, w->blen, files[j]);
        fflush(files[j]);
    }
    w->blen = 0;
}

/* SIGINT or SIGTERM during a run: the row being written is finished and
 * the run stops there (write_row), with the conventional exit status. */
static volatile sig_atomic_t interrupted;
enum { EOMC_INTERRUPTED = -2 };

static void
on_signal(int sig)
{
    interrupted = sig;
}

/* A writer of rows to f (NULL: none yet); w.res NULL when out of memory. */
static Csv
csv_new(FILE *f, eomc_sim *sim)
{
    const eomc_model *m = eomc_sim_model(sim);
    size_t nres = (size_t)(m->nc + m->nout), n = (size_t)m->nq;
    Csv w = {.f = f, .sim = sim, .invariant = m->invariant != NULL};
    /* a row's cells: t, q, q', T, V, E, h, lambda, res, outputs */
    size_t cells = 1 + 2 * n + 4 + nres + (size_t)m->nc, row = cells * (NUM_MAX + 1) + 1;
    size_t blk = (ROW_BLOCK + row) / sizeof(double) + 1;
    w.res = calloc(nres + n + 1 + blk + (size_t)m->nout, sizeof(double));
    w.arow = w.res ? w.res + nres : NULL;
    w.blk = w.res ? (char *)(w.arow + n + 1) : NULL;
    w.out_max = w.res ? w.arow + n + 1 + blk : NULL;
    return w;
}

/* ---- messages ---- */

/* "s" after a count of n, or "" */
static const char *
plural(long n)
{
    return n == 1 ? "" : "s";
}

static int
usage(const Cli *c, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "%s: ", c->prog);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(see %s --help)\n", c->self);
    return EOMC_EUSAGE;
}

/* " (did you mean 'x'?)" for the nearest of names[0..n) (suffixed), every
 * one as near ("'rk4' or 'rkf45'"), or "": the compiler's rule
 * (nearest.h). */
static const char *
nearest(const char *word, const char *const *names, int n, const char *suffix)
{
    static char buf[600];
    char list[512];
    buf[0] = '\0';
    char *cands = calloc((size_t)(n ? n : 1), NEAREST_MAX + 2);
    const char **ptrs = calloc((size_t)(n ? n : 1), sizeof *ptrs);
    if (cands && ptrs) {
        for (int k = 0; k < n; k++) {
            char *c = cands + (size_t)k * (NEAREST_MAX + 2);
            snprintf(c, NEAREST_MAX + 2, "%s%s", names[k], suffix);
            ptrs[k] = c;
        }
        const char *near = nearest_names(word, ptrs, n, list, sizeof list);
        if (near)
            snprintf(buf, sizeof buf, " (did you mean %s?)", near);
    }
    free(cands);
    free(ptrs);
    return buf;
}

static void
list_names(FILE *f, const char *const *names, int n, const char *suffix)
{
    for (int k = 0; k < n; k++)
        fprintf(f, "%s%s%s", k ? ", " : "", names[k], suffix);
}

/* ---- options ---- */

enum Option {
    /* with a value */
    O_T0, O_T_END, O_DT, O_METHOD, O_RTOL, O_ATOL, O_FIXED_STEP, O_MAX_STEPS, O_SET, O_INIT,
    O_OUT, O_STABILIZE, O_BAUMGARTE, O_REFERENCE, O_REFERENCE_OUT, O_EVENTS, O_SWEEP,
    O_SWEEP_FILE, O_THREADS, O_HOLD, O_ERRORS,
    O_METHODS, O_TOLERANCES, O_STEPS, O_CSV, O_PLOT, O_TARGET, /* report only */
    /* flags */
    O_STATS, O_SUMMARY, O_ACCEL, O_ASSEMBLE, O_NO_ASSEMBLE, O_WORK_PRECISION, O_ERROR,
    O_LINEARIZE, O_EQUILIBRIUM, O_ACCEL_EXTENDED, O_HELP, O_VERSION, NOPTIONS,
    FIRST_FLAG = O_STATS,
};
static const char *const option_names[NOPTIONS] = {
    "--t0", "--t-end", "--dt", "--method", "--rtol", "--atol", "--fixed-step", "--max-steps",
    "--set", "--init", "-o", "--stabilize", "--baumgarte", "--reference",
    "--reference-out", "--events", "--sweep", "--sweep-file", "--threads", "--hold", "--errors", "--methods", "--tolerances", "--steps", "--csv", "--plot",
    "--target", "--stats", "--summary", "--accel", "--assemble", "--no-assemble",
    "--work-precision",
    "--error", "--linearize", "--equilibrium", "--accel-extended", "--help", "--version",
};
static const char *const stabilize_names[] = {"none", "baumgarte", "project"};
/* More threads than this are a typo, not a machine. */
enum { MAX_THREADS = 1024 };
/* Baumgarte's rates when --baumgarte is not given (1/time units). */
#define DEFAULT_RATE 10.0
/* The report's tolerances: 1e-3, 1e-4, ..., 1e-13 (rtol = atol). */
enum { TOL_FIRST_EXP = 3, TOL_LAST_EXP = 13 };
/* Its fixed steps: these fractions of the time span. */
static const double default_steps[] = {1e-2, 1e-3, 1e-4};

static void
help(const Cli *c, const eomc_model *m)
{
    printf("usage: %s [OPTION]...\n"
           "Simulate %s (%s, %s form%s%s%s%s) and write the trajectory as CSV:\n"
           "t, each coordinate, each velocity (name'), T, V and E = T + V%s.\n\n",
           c->self, m->name, m->spec, m->form, *m->options ? ", " : "", m->options,
           *m->scene ? ", scene " : "", m->scene, m->invariant_name && !strcmp(m->invariant_name, "h")
               ? ", h (the conserved energy function)" : "");
    printf("  --t0 T             start time (default 0)\n"
           "  --t-end T          end time, after the start (default %g)\n"
           "  --dt T             output interval (default %g); rows between steps\n"
           "                     are interpolated, so a small dt costs no steps\n"
           "  --method NAME      integration method (default %s):\n",
           m->t_end, m->dt, m->method);
    for (int k = 0; eomc_methods[k]; k++)
        printf("                       %-8s %s\n", eomc_methods[k],
               eomc_method_description(eomc_methods[k]));
    printf("  --rtol X, --atol X adaptive tolerances (default %g, %g)\n"
           "  --fixed-step H     fixed steps of at most H, evenly dividing the time span\n"
           "  --max-steps N      fail after N steps\n"
           "  --set NAME=VALUE   a parameter, or an input held constant\n"
           "  --init NAME=VALUE  initial coordinate NAME or velocity NAME'\n"
           "  -o FILE            write the CSV to FILE instead of stdout\n",
           m->rtol, m->atol);
    if (m->nc > 0)
        printf("  --stabilize NAME   drift control: none (default), baumgarte, project\n"
               "  --baumgarte A,B    Baumgarte's rates: g'' + 2A g' + B^2 g = 0, "
               "phi' + A phi = 0\n"
               "                     (default %g,%g; implies --stabilize baumgarte)\n"
               "  --assemble         project the initial state onto the constraints "
               "first%s\n"
               "  --hold LIST        with --assemble: keep these coordinates (x) and "
               "velocities (x')\n"
               "                     as they are; the others meet the constraints%s\n"
               "%s",
               DEFAULT_RATE, DEFAULT_RATE,
               m->assemble ? "\n                     (the scene does, for every run)" : "",
               m->assemble ? "\n                     (instead of the scene's list)" : "",
               m->assemble ? "  --no-assemble      start from the initial state as given, "
                             "not assembled\n" : "");
    if (m->nevent > 0) {
        static const char *const actions[] = {"stops the run", "is recorded",
                                              "sets the state"};
        printf("  --events FILE      each event as it fires, in CSV: t, event, the\n"
               "                     coordinates and velocities before its action\n"
               "  the scene's events:\n");
        int w = 12;
        for (int k = 0; k < m->nevent; k++)
            if ((int)strlen(m->ev_names[k]) > w)
                w = (int)strlen(m->ev_names[k]);
        for (int k = 0; k < m->nevent; k++)
            printf("                       %-*s %s (g crossing 0 %s)\n", w, m->ev_names[k],
                   actions[m->ev_action[k]], m->ev_direction[k] > 0   ? "upward"
                                             : m->ev_direction[k] < 0 ? "downward"
                                                                       : "either way");
    }
    printf("  --stats            integrator statistics on stderr\n"
           "  --summary          a paragraph about the run on stderr\n"
           "  --accel            print q'' at the initial state and exit\n"
           "  --accel-extended   the same, solved in the extended precision of the\n"
           "                     model's twin (eomc build --extended) and rounded\n"
           "  --error            measure the run's error against the reference solution\n"
           "  --reference FILE   the reference from FILE (a CSV with this simulator's\n"
           "                     columns and rows) instead of computing it\n"
           "  --reference-out FILE  write the reference, in this simulator's columns\n"
           "  --errors FILE      each run's errors by coordinate and velocity, as CSV\n"
           "                     (implies --error; with --work-precision, every run's)\n"
           "  --work-precision   what accuracy costs: run every method over tolerances\n"
           "                     and fixed steps, and report CPU time against error:\n"
           "    --methods LIST       comma-separated (default: all)\n"
           "    --tolerances LIST    rtol = atol of the adaptive runs (default 1e-3, ...,\n"
           "                         1e-13)\n"
           "    --steps LIST         fixed steps (default span/100, /1000, /10000, for\n"
           "                         rk4 rk1imp rk2imp rk4imp; given: every one-step\n"
           "                         method)\n"
           "    --csv FILE           one row per run\n"
           "    --plot FILE          the work-precision diagram, .svg or .png (gnuplot)\n"
           "    --target ERR         the cheapest setting with error_max <= ERR\n"
           "  --sweep NAME=START:STOP:COUNT  one run per value (repeatable: a grid, the\n"
           "                     last one fastest); -o FILE gets the summary: the swept\n"
           "                     values, status, t, the state and the outputs at the end\n"
           "  --sweep-file FILE  one run per row of a CSV (a header of parameter names)\n"
           "  --threads N        run a sweep's runs on N threads (same summary)\n"
           "  --linearize        A = dz'/dz and B = dz'/du at the initial state (or --init),\n"
           "                     z the coordinates and velocities (a constrained model's\n"
           "                     independent ones), exact; A's eigenvalues, the largest\n"
           "                     real part first; with --sweep, one row per value: the\n"
           "                     swept values, re1,im1,re2,im2,...\n"
           "  --equilibrium      an equilibrium (q' = 0, q'' = 0) by Newton's method from\n"
           "                     the initial coordinates, its linearization and stability\n"
           "    --csv FILE       (both) A, B and the eigenvalues as matrix,row,column,value\n"
           "                     (eig,K,re,VALUE and eig,K,im,VALUE)\n"
           "  --help, --version\n\n");
    printf("coordinates: ");
    list_names(stdout, m->q_names, m->nq, "");
    printf("\nparameters: ");
    for (int k = 0; k < m->np; k++)
        printf("%s%s=%g%s", k ? ", " : "", m->p_names[k], m->p_default[k],
               m->p_fixed[k] ? " (fixed)" : "");
    printf("\ninputs: ");
    list_names(stdout, m->u_names, m->nu, "");
    printf("%s\n%s.\nExit status: 0 done, 2 usage error, 3 numerical failure (the rows "
           "computed so far are kept).\n", m->nu ? "" : "(none)", m->invariant_note);
}

/* The whole string as a finite number. */
static int
number(const char *s, double *x)
{
    char *end;
    *x = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*x);
}

static int
real_option(Cli *c, const char *opt, const char *val, double *x, double lo, int open)
{
    if (!number(val, x))
        return usage(c, "%s: '%s' is not a finite number", opt, val);
    if (open ? !(*x > lo) : !(*x >= lo))
        return usage(c, "%s: %s is out of range (must be %s %g)", opt, val,
                     open ? ">" : ">=", lo);
    return EOMC_OK;
}

/* The index of a method by name, or a usage error (-1) suggesting one. */
static int
method_index(Cli *c, const char *opt, const char *val)
{
    int n = 0;
    while (eomc_methods[n])
        n++;
    for (int j = 0; j < n; j++)
        if (strcmp(val, eomc_methods[j]) == 0)
            return j;
    fprintf(stderr, "%s: %s: unknown method '%s'%s; methods: ", c->prog, opt, val,
            nearest(val, eomc_methods, n, ""));
    list_names(stderr, eomc_methods, n, "");
    fprintf(stderr, "\n");
    return -1;
}

/* A comma-separated list of positive numbers, into a new array. */
static int
number_list(Cli *c, const char *opt, const char *val, double **out, int *count)
{
    size_t cap = strlen(val) / 2 + 2;
    double *x = calloc(cap, sizeof *x);
    char *copy = strdup(val), *save = NULL;
    int n = 0, rc = EOMC_OK;
    if (!x || !copy)
        rc = usage(c, "out of memory");
    for (char *w = copy ? strtok_r(copy, ",", &save) : NULL; w && rc == EOMC_OK;
         w = strtok_r(NULL, ",", &save))
        rc = real_option(c, opt, w, &x[n++], 0, 1);
    if (rc == EOMC_OK && n == 0)
        rc = usage(c, "%s: expected a comma-separated list of numbers, not '%s'", opt, val);
    free(copy);
    free(*out);
    *out = rc == EOMC_OK ? x : (free(x), NULL);
    *count = rc == EOMC_OK ? n : 0;
    return rc;
}

static int
method_list(Cli *c, const char *val)
{
    size_t cap = strlen(val) / 2 + 2;
    const char **m = calloc(cap, sizeof *m);
    char *copy = strdup(val), *save = NULL;
    int n = 0, rc = EOMC_OK;
    if (!m || !copy)
        rc = usage(c, "out of memory");
    for (char *w = copy ? strtok_r(copy, ",", &save) : NULL; w && rc == EOMC_OK;
         w = strtok_r(NULL, ",", &save)) {
        int k = method_index(c, "--methods", w);
        if (k < 0)
            rc = EOMC_EUSAGE;
        else
            m[n++] = eomc_methods[k];
    }
    if (rc == EOMC_OK && n == 0)
        rc = usage(c, "--methods: expected a comma-separated list of methods");
    free(copy);
    free(c->methods);
    c->methods = rc == EOMC_OK ? m : (free(m), NULL);
    return rc;
}

static int
take_value(Cli *c, int k, const char *val)
{
    eomc_run_opts *r = &c->run;
    const char *opt = option_names[k];
    double x;
    if (k >= O_METHODS && k <= O_TARGET)
        c->report_given |= 1u << (k - O_METHODS);
    switch (k) {
    case O_T0:
        if (!number(val, &r->t0))
            return usage(c, "%s: '%s' is not a finite number", opt, val);
        c->t0_given = 1;
        return EOMC_OK;
    case O_T_END:
        if (!number(val, &r->t_end))
            return usage(c, "%s: '%s' is not a finite number", opt, val);
        c->t_end_given = 1;
        return EOMC_OK;
    case O_DT: return real_option(c, opt, val, &r->dt, 0, 1);
    case O_METHOD: {
        int j = method_index(c, opt, val);
        if (j < 0)
            return EOMC_EUSAGE;
        r->method = eomc_methods[j];
        c->method_given = 1;
        return EOMC_OK;
    }
    case O_RTOL: return real_option(c, opt, val, &r->rtol, 0, 0);
    case O_ATOL: return real_option(c, opt, val, &r->atol, 0, 0);
    case O_FIXED_STEP:
        c->fixed_given = 1;
        return real_option(c, opt, val, &r->h_fixed, 0, 1);
    case O_MAX_STEPS:
        if (!number(val, &x) || x != floor(x) || x < 1 || x > 1e15)
            return usage(c, "%s: '%s' is not a whole number of steps (1 or more)", opt, val);
        r->max_steps = (long)x;
        return EOMC_OK;
    case O_SET: c->set[c->nset++] = (char *)val; return EOMC_OK;
    case O_INIT: c->init[c->ninit++] = (char *)val; return EOMC_OK;
    case O_OUT: c->out = val; return EOMC_OK;
    case O_HOLD: c->hold = val; return EOMC_OK;
    case O_ERRORS: c->errors = val; return EOMC_OK;
    case O_STABILIZE:
        for (int j = 0; j < 3; j++)
            if (strcmp(val, stabilize_names[j]) == 0) {
                c->stabilize = j;
                return EOMC_OK;
            }
        return usage(c, "--stabilize: unknown method '%s'%s; methods: none, baumgarte, "
                     "project", val, nearest(val, stabilize_names, 3, ""));
    case O_BAUMGARTE: {
        char *comma = strchr(val, ','), *a = strndup(val, comma ? (size_t)(comma - val) : 0);
        int bad = !comma || !a || !number(a, &c->alpha) || !number(comma + 1, &c->beta);
        free(a);
        if (bad)
            return usage(c, "--baumgarte: expected ALPHA,BETA (two numbers), not '%s'", val);
        if (c->alpha < 0 || c->beta < 0)
            return usage(c, "--baumgarte: %s is out of range (the rates must be >= 0)",
                         val);
        c->rates_given = 1;
        return EOMC_OK;
    }
    case O_REFERENCE: c->reference = val; return EOMC_OK;
    case O_REFERENCE_OUT: c->reference_out = val; return EOMC_OK;
    case O_EVENTS: c->events = val; return EOMC_OK;
    case O_SWEEP: c->sweep[c->nsweep++] = (char *)val; return EOMC_OK;
    case O_SWEEP_FILE: c->sweep_file = val; return EOMC_OK;
    case O_THREADS:
        if (!number(val, &x) || x != floor(x) || x < 1 || x > MAX_THREADS)
            return usage(c, "--threads: '%s' is not a whole number from 1 to %d", val,
                         MAX_THREADS);
        c->threads = (int)x;
        return EOMC_OK;
    case O_METHODS: return method_list(c, val);
    case O_TOLERANCES: return number_list(c, opt, val, &c->tolerances, &c->ntolerances);
    case O_STEPS: return number_list(c, opt, val, &c->steps, &c->nsteps);
    case O_CSV: c->csv = val; return EOMC_OK;
    case O_PLOT: c->plot = val; return EOMC_OK;
    case O_TARGET: return real_option(c, opt, val, &c->target, 0, 1);
    }
    return EOMC_OK;
}

static int
find_option(const char *arg, size_t len)
{
    for (int k = 0; k < NOPTIONS; k++)
        if (strlen(option_names[k]) == len && strncmp(arg, option_names[k], len) == 0)
            return k;
    return -1;
}

/* What the options say together: conflicts are usage errors. */
static int
check_combination(Cli *c)
{
    if (c->rates_given && c->stabilize < 0)
        c->stabilize = EOMC_STABILIZE_BAUMGARTE;
    if (c->rates_given && c->stabilize != EOMC_STABILIZE_BAUMGARTE)
        return usage(c, "--baumgarte gives the rates of --stabilize baumgarte, not of "
                     "--stabilize %s", stabilize_names[c->stabilize]);
    if (c->stabilize < 0)
        c->stabilize = EOMC_STABILIZE_NONE;
    if (c->reference || c->errors)
        c->error = 1;
    int linear = c->linearize || c->equilibrium;
    /* the spec's t_end must be > 0; a run's end must come after its start
     * alike (a run of no time writes one row, which no one means) */
    if (!(c->run.t_end > c->run.t0))
        return usage(c, "%s %g must be after the start time %g%s",
                     c->t_end_given ? "--t-end" : "the scene's t_end", c->run.t_end,
                     c->run.t0, c->t0_given ? " (--t0)" : "");
    if (c->nsweep && c->sweep_file)
        return usage(c, "--sweep and --sweep-file: one or the other");
    if (c->nsweep || c->sweep_file) {
        const char *clash = c->work_precision ? "--work-precision" : c->equilibrium
                            ? "--equilibrium" : c->linearize && c->csv
                            ? "--csv (a sweep of --linearize writes its rows with -o)" : c->accel
                            ? "--accel" : c->error ? "--error" : c->reference_out
                            ? "--reference-out" : c->events ? "--events" : c->plot
                            ? "--plot" : c->summary ? "--summary" : c->stats ? "--stats"
                            : NULL;
        if (clash)
            return usage(c, "a sweep (%s) writes one %s row per run: it does not take %s",
                         c->nsweep ? "--sweep" : "--sweep-file",
                         c->linearize ? "linearization's" : "summary", clash);
    } else if (c->threads > 1) {
        return usage(c, "--threads runs the runs of a sweep (--sweep, --sweep-file) at once");
    }
    if (c->no_assemble && (c->assemble || c->hold))
        return usage(c, "--no-assemble starts from the initial state as given: it does not "
                     "take %s", c->assemble ? "--assemble" : "--hold");
    if (c->hold && !c->assemble && !c->scene_assembles)
        return usage(c, "--hold belongs to --assemble: it names what the projection "
                     "onto the constraints keeps as it is");
    /* the scene's `assemble:` unless --no-assemble; --hold replaces its list */
    c->assemble = !c->no_assemble && (c->assemble || c->hold || c->scene_assembles);
    int run_plot = c->plot && !c->work_precision && !linear && !c->accel;
    if (run_plot && !plot_format_ok(c->plot))
        return usage(c, "--plot: '%s' is neither .svg nor .png", c->plot);
    if (run_plot && !plot_have_gnuplot())
        return usage(c, "--plot: gnuplot is not installed (Debian: apt-get install "
                     "gnuplot-nox)");
    for (int k = O_METHODS; k <= O_TARGET && !c->work_precision; k++) {
        if (!(c->report_given >> (k - O_METHODS) & 1) || (k == O_CSV && linear) ||
            (k == O_PLOT && run_plot))
            continue;
        if (k == O_CSV)
            return usage(c, "--csv belongs to --work-precision, --linearize or "
                         "--equilibrium (one run writes its trajectory with -o)");
        if (k == O_PLOT)
            return usage(c, "--plot draws a run or the --work-precision report, not %s",
                         c->accel ? "--accel" : "--linearize or --equilibrium");
        return usage(c, "%s belongs to --work-precision (one run writes its trajectory "
                     "with -o)", option_names[k]);
    }
    int swept = c->nsweep || c->sweep_file; /* a sweep's rows go to -o */
    if (linear && (c->accel || c->work_precision || c->error || (c->out && !swept) ||
                   c->events))
        return usage(c, "--%s does not integrate: it does not take %s",
                     c->linearize ? "linearize" : "equilibrium",
                     c->accel ? "--accel" : c->work_precision ? "--work-precision"
                     : c->error ? "--error" : c->out ? "-o (use --csv FILE)" : "--events");
    if (c->work_precision) {
        const char *clash = c->accel ? "--accel" : c->out ? "-o" : c->method_given
                          ? "--method (--methods chooses the report's)" : c->fixed_given
                          ? "--fixed-step (--steps chooses the report's)" : NULL;
        if (clash)
            return usage(c, "--work-precision does not take %s", clash);
        if (c->plot && !plot_format_ok(c->plot))
            return usage(c, "--plot: '%s' is neither .svg nor .png", c->plot);
        if (c->plot && !plot_have_gnuplot())
            return usage(c, "--plot: gnuplot is not installed (Debian: apt-get install "
                         "gnuplot-nox)");
    }
    if (c->accel && (c->error || c->reference_out))
        return usage(c, "--accel does not integrate: nothing to measure against a "
                     "reference");
    return EOMC_OK;
}

/* Returns EOMC_OK, EOMC_EUSAGE, or -1 when --help or --version was handled. */
static int
parse_args(Cli *c, int argc, char **argv, const eomc_model *m)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i], *eq = strchr(arg, '='), *val = NULL;
        size_t len = eq && arg[0] == '-' ? (size_t)(eq - arg) : strlen(arg);
        int k = find_option(arg, len);
        if (k < 0) {
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)(len < 100 ? len : 100), arg);
            if (arg[0] != '-')
                return usage(c, "unexpected argument '%s' (options start with --)", arg);
            return usage(c, "unknown option '%s'%s", name,
                         nearest(name, option_names, NOPTIONS, ""));
        }
        if (k >= FIRST_FLAG) {
            if (eq)
                return usage(c, "%s takes no value", option_names[k]);
            if (k == O_HELP) {
                help(c, m);
                return -1;
            }
            if (k == O_VERSION) {
                printf("%s: model %s from %s, %s form%s%s; eomc runtime %s\n", c->prog,
                       m->name, m->spec, m->form, *m->options ? ", " : "", m->options,
                       EOMC_VERSION);
                return -1;
            }
            int *flag[] = {&c->stats, &c->summary, &c->accel, &c->assemble, &c->no_assemble,
                           &c->work_precision, &c->error, &c->linearize, &c->equilibrium,
                           &c->accel_extended};
            *flag[k - FIRST_FLAG] = 1;
            c->accel |= c->accel_extended; /* the same, by the twin */
            continue;
        }
        if (eq)
            val = eq + 1;
        else if (i + 1 < argc)
            val = argv[++i];
        else
            return usage(c, "%s needs a value", option_names[k]);
        int rc = take_value(c, k, val);
        if (rc)
            return rc;
    }
    c->scene_assembles = m->assemble;
    return check_combination(c);
}

/* NAME=VALUE split; *name is a copy to free. */
static int
name_value(Cli *c, const char *opt, const char *arg, char **name, double *x)
{
    const char *eq = strchr(arg, '=');
    if (!eq || eq == arg)
        return usage(c, "%s: expected NAME=VALUE, not '%s'", opt, arg);
    if (!number(eq + 1, x))
        return usage(c, "%s %s: '%s' is not a finite number", opt, arg, eq + 1);
    *name = strndup(arg, (size_t)(eq - arg));
    return EOMC_OK;
}

static int
apply_sets(Cli *c, eomc_sim *sim)
{
    const eomc_model *m = eomc_sim_model(sim);
    for (int k = 0; k < c->nset; k++) {
        char *name = NULL;
        double x = 0;
        if (name_value(c, "--set", c->set[k], &name, &x))
            return EOMC_EUSAGE;
        int fixed = 0;
        for (int i = 0; i < m->np; i++)
            fixed |= m->p_fixed[i] && !strcmp(name, m->p_names[i]);
        int rc = eomc_sim_set(sim, name, x);
        if (rc != EOMC_OK && fixed) {
            fprintf(stderr, "%s: --set: %s\n", c->prog, eomc_sim_error(sim));
            free(name);
            return EOMC_EUSAGE;
        } else if (rc != EOMC_OK) {
            const char *hint = nearest(name, m->p_names, m->np, "");
            if (!*hint)
                hint = nearest(name, m->u_names, m->nu, "");
            fprintf(stderr, "%s: --set: '%s' is not a parameter or input%s; "
                    "parameters: ", c->prog, name, hint);
            list_names(stderr, m->p_names, m->np, "");
            fprintf(stderr, m->nu ? "; inputs: " : "; no inputs");
            list_names(stderr, m->u_names, m->nu, "");
            fprintf(stderr, "\n");
            free(name);
            return EOMC_EUSAGE;
        }
        free(name);
    }
    if (eomc_sim_check(sim) != EOMC_OK) {
        fprintf(stderr, "%s: --set: %s\n", c->prog, eomc_sim_error(sim));
        return EOMC_EUSAGE;
    }
    return EOMC_OK;
}

/* NAME (a coordinate) or NAME' (its velocity) given to option opt: its
 * index in the state (i, or n + i), or -1 when it names neither, said on
 * stderr with the nearest name. */
static int
state_index(Cli *c, const eomc_model *m, const char *opt, const char *name)
{
    int n = m->nq;
    size_t len = strlen(name);
    if (len > 2 && name[len - 1] == '\'' && name[len - 2] == '\'') {
        fprintf(stderr, "%s: %s: '%s' is an acceleration: only coordinates (x) and "
                "velocities (x') make the initial state; the accelerations follow from "
                "the equations\n", c->prog, opt, name);
        return -1;
    }
    int vel = len > 1 && name[len - 1] == '\'';
    for (int i = 0; i < n; i++)
        if (strlen(m->q_names[i]) == len - (size_t)vel &&
            !strncmp(name, m->q_names[i], len - (size_t)vel))
            return i + (vel ? n : 0);
    fprintf(stderr, "%s: %s: '%s' is not a coordinate or velocity%s; valid names: ", c->prog,
            opt, name, nearest(name, m->q_names, n, vel ? "'" : ""));
    list_names(stderr, m->q_names, n, "");
    fprintf(stderr, ", ");
    list_names(stderr, m->q_names, n, "'");
    fprintf(stderr, "\n");
    return -1;
}

static int
apply_inits(Cli *c, const eomc_model *m, double *x)
{
    for (int k = 0; k < c->ninit; k++) {
        char *name = NULL;
        double val = 0;
        if (name_value(c, "--init", c->init[k], &name, &val))
            return EOMC_EUSAGE;
        int i = state_index(c, m, "--init", name);
        free(name);
        if (i < 0)
            return EOMC_EUSAGE;
        x[i] = val;
    }
    return EOMC_OK;
}

/* ---- output ---- */

/* Whether the model's conserved quantity is not E = T + V, so that it
 * gets a column of its own. */
static int
own_invariant_column(const eomc_model *m)
{
    return m->invariant && m->invariant_name && strcmp(m->invariant_name, "E") != 0;
}

static void
print_header(FILE *f, const eomc_model *m)
{
    fprintf(f, "t");
    for (int i = 0; i < m->nq; i++)
        fprintf(f, ",%s", m->q_names[i]);
    for (int i = 0; i < m->nq; i++)
        fprintf(f, ",%s'", m->q_names[i]);
    fprintf(f, ",T,V,E");
    if (own_invariant_column(m))
        fprintf(f, ",%s", m->invariant_name);
    for (int k = 0; k < m->nc; k++)
        fprintf(f, ",lambda[%s]", m->c_names[k]);
    for (int k = 0; k < m->nc; k++)
        fprintf(f, ",res[%s]", m->c_names[k]);
    for (int k = 0; k < m->nout; k++)
        fprintf(f, ",%s", m->out_names[k]);
    fprintf(f, "\n");
}

static int
write_row(void *ctx, double t, const double *x)
{
    Csv *w = ctx;
    const eomc_model *m = eomc_sim_model(w->sim);
    int n = m->nq, nc = m->nc;
    double *out = w->res + nc;
    /* the multipliers and outputs of this very state (it also solves
     * for its accelerations) */
    if (m->nout > 0 && eomc_sim_outputs(w->sim, t, x, x + n, out) != EOMC_OK)
        return EOMC_ENUMERIC;
    if (nc > 0 && m->nout == 0 && eomc_sim_accel(w->sim, t, x, x + n, w->arow) != EOMC_OK)
        return EOMC_ENUMERIC;
    if (nc > 0 && eomc_sim_residuals(w->sim, t, x, x + n, w->res) != EOMC_OK)
        return EOMC_ENUMERIC;
    double T, V, h = 0;
    eomc_sim_energy(w->sim, t, x, x + n, &T, &V);
    w->T_max = fmax(w->T_max, fabs(T));
    if (w->invariant) {
        eomc_sim_invariant(w->sim, t, x, x + n, &h);
        if (w->rows == 0)
            w->h_first = h;
        if (w->rows == 0 || (w->rebase && t > w->t_reset))
            w->h0 = h, w->rebase = 0;
        w->dh = fmax(w->dh, fabs(h - w->h0));
    }
    if (w->ref && w->rows < w->ref->nrows) {
        compare_row(&w->cmp, x);
        w->err_end = w->cmp.err_end;
        w->err_max = w->cmp.err_max;
    }
    for (int k = 0; k < nc; k++)
        w->res_max = fmax(w->res_max, fabs(w->res[k]));
    for (int k = 0; k < m->nout; k++)
        w->out_max[k] = fmax(w->out_max[k], fabs(out[k]));
    const double *lam = eomc_sim_multipliers(w->sim);
    /* the row into the block of whole rows (room for one more row is
     * always there: csv_new sized it, and it is flushed past ROW_BLOCK) */
    char num[NUM_MAX];
#define CELL(first, v)                                                                 \
    (w->blen += (size_t)sprintf(w->blk + w->blen, "%s%s", (first) ? "" : ",",         \
                                num_shortest(num, (v))))
    CELL(1, t);
    for (int i = 0; i < 2 * n; i++)
        CELL(0, x[i]);
    CELL(0, T);
    CELL(0, V);
    CELL(0, T + V);
    if (own_invariant_column(m))
        CELL(0, h);
    for (int k = 0; k < nc; k++)
        CELL(0, lam[k]);
    for (int k = 0; k < nc; k++)
        CELL(0, w->res[k]);
    for (int k = 0; k < m->nout; k++)
        CELL(0, out[k]);
#undef CELL
    w->blk[w->blen++] = '\n';
    w->rows++;
    w->t_last = t;
    if (w->blen >= ROW_BLOCK)
        flush_rows(w);
    if (interrupted) { /* this row is whole: stop here */
        flush_rows(w);
        return EOMC_INTERRUPTED;
    }
    return EOMC_OK;
}

static void
print_stats(const Csv *w, const eomc_stats *st, int stabilize)
{
    const eomc_model *m = eomc_sim_model(w->sim);
    fprintf(stderr, "steps %ld\nrejected %ld\nrhs_evals %ld\njac_evals %ld\n"
            "cpu_seconds %.6f\n", st->steps, st->rejected, st->rhs_evals,
            st->jac_evals, st->cpu_seconds);
    if (st->h_used > 0)
        fprintf(stderr, "h_used %.17g\n", st->h_used);
    fprintf(stderr, "side_steps %ld\n", st->side_steps);
    fprintf(stderr, "max_condition %.3g\nt_condition %.17g\n", st->max_condition,
            st->t_condition);
    if (st->invariant_budget > 0)
        fprintf(stderr, "invariant_budget %.3g\n", st->invariant_budget);
    if (m->nc > 0)
        fprintf(stderr, "max_residual %.3g\n", fmax(st->max_residual, w->res_max));
    if (stabilize == EOMC_STABILIZE_PROJECT)
        fprintf(stderr, "max_drift %.3g\n", st->max_drift);
    if (w->invariant)
        fprintf(stderr, "invariant_drift %.3g\n", w->dh);
    if (w->ref)
        fprintf(stderr, "error_end %.3g\nerror_max %.3g\nreference_error %.3g\n"
                "reference_method %s\n", w->err_end, w->err_max, w->ref->error,
                w->ref->method);
    if (m->nevent > 0)
        fprintf(stderr, "events %ld\nevent_evals %ld\n", st->events, st->event_evals);
    if (st->reset_event >= 0)
        fprintf(stderr, "reset_event %s\nt_reset %.17g\nreset_constraint %s\n"
                "reset_inconsistency %.3g\n", m->ev_names[st->reset_event], st->reset_t,
                m->c_names[st->reset_constraint], st->reset_inconsistency);
    if (st->stop_event >= 0)
        fprintf(stderr, "stop_event %s\nt_stop %.17g\n", m->ev_names[st->stop_event],
                st->t_stop);
}

/* Print words wrapped at 72 columns. */
static void
wrap(FILE *f, char *text)
{
    int col = 0;
    for (char *save = NULL, *w = strtok_r(text, " ", &save); w;
         w = strtok_r(NULL, " ", &save)) {
        int len = (int)strlen(w);
        if (col && col + 1 + len > 72) {
            fputc('\n', f);
            col = 0;
        } else if (col) {
            fputc(' ', f);
            col++;
        }
        fputs(w, f);
        col += len;
    }
    fputc('\n', f);
}

static void
print_summary(const Cli *c, const eomc_model *m, const Csv *w, const eomc_stats *st)
{
    char text[4096];
    size_t len = 0, cap = sizeof text;
#define ADD(...) (len += len < cap ? (size_t)snprintf(text + len, cap - len, __VA_ARGS__) : 0)
    ADD("%s: %d coordinate%s (", m->name, m->nq, m->nq == 1 ? "" : "s");
    for (int i = 0; i < m->nq && i < 8; i++)
        ADD("%s%s", i ? ", " : "", m->q_names[i]);
    ADD("%s), equations in %s form from %s. ", m->nq > 8 ? ", ..." : "", m->form,
        m->spec);
    double t_last = st->stop_event >= 0 ? st->t_stop : c->run.t_end;
    ADD("Integrated from t = %g to %.17g with %s", c->run.t0, t_last, c->run.method);
    if (c->run.h_fixed > 0)
        ADD(" in fixed steps of %g: ", st->h_used);
    else
        ADD(" (rtol %g, atol %g): ", c->run.rtol, c->run.atol);
    ADD("%ld step%s (%ld rejected), %ld right-hand side%s and %ld Jacobian%s in %.3g s "
        "of CPU time. ", st->steps, plural(st->steps), st->rejected, st->rhs_evals,
        plural(st->rhs_evals), st->jac_evals, plural(st->jac_evals), st->cpu_seconds);
    ADD("Wrote %ld row%s every %g to %s. ", w->rows, plural(w->rows), c->run.dt,
        c->out ? c->out : "stdout");
    int resets = 0;
    for (int k = 0; k < m->nevent; k++)
        resets |= m->ev_action[k] == EOMC_EVENT_SET;
    if (m->nevent > 0)
        ADD("%ld event%s fired", st->events, st->events == 1 ? "" : "s");
    if (st->stop_event >= 0)
        ADD("; %s stopped the run at t = %.17g (t_end was %g)", m->ev_names[st->stop_event],
            st->t_stop, c->run.t_end);
    if (m->nevent > 0)
        ADD(". ");
    /* the change against the energy the motion moves about, not against h's
     * value, which a potential's constant sets anywhere (0 included) */
    char rel[80] = "";
    if (w->invariant && w->T_max > 0)
        snprintf(rel, sizeof rel, " (%.3g of the largest kinetic energy, %.3g)",
                 w->dh / w->T_max, w->T_max);
    if (w->invariant && resets && st->events > 0)
        ADD("The conserved quantity %s, measured afresh after each reset, changed by at "
            "most %.3g between them%s; it last started at %.10g.", m->invariant_name, w->dh,
            rel, w->h0);
    else if (w->invariant)
        ADD("The conserved quantity %s started at %.10g; its largest change was %.3g%s.",
            m->invariant_name, w->h0, w->dh, rel);
    else
        ADD("No drift is reported: %s.", m->invariant_note);
    if (m->nc > 0)
        ADD(" The largest constraint residual was %.3g", fmax(st->max_residual, w->res_max));
    if (m->nc > 0 && c->stabilize == EOMC_STABILIZE_PROJECT)
        ADD(" with projection after every step (%.3g before it).", st->max_drift);
    else if (m->nc > 0 && c->stabilize == EOMC_STABILIZE_BAUMGARTE)
        ADD(" with Baumgarte's stabilization (rates %g, %g).", c->alpha, c->beta);
    else if (m->nc > 0)
        ADD(", without stabilization.");
    if (w->ref && isnan(w->ref->error))
        /* one read with --reference carries no estimate of its own error */
        ADD(" Against the reference solution read from %s (its own error not known), the "
            "error was at most %.3g over the rows and %.3g at t = %g.", c->reference,
            w->err_max, w->err_end, c->run.t_end);
    else if (w->ref)
        ADD(" Against the reference solution (%s%s, good to %.2g), the error was at "
            "most %.3g over the rows and %.3g at t = %g.", w->ref->method,
            w->ref->stiff ? ", as the problem is stiff" : "", w->ref->error, w->err_max,
            w->err_end, c->run.t_end);
#undef ADD
    text[0] = (char)(text[0]); /* the model's name starts the paragraph as it is */
    wrap(stderr, text);
}

/* ---- main ---- */

/* Whether the model has a constraint below acceleration level. */
static int
has_levels(const eomc_model *m)
{
    for (int k = 0; k < m->nc; k++)
        if (m->c_order[k] <= 1)
            return 1;
    return 0;
}

static int
set_stabilize(Cli *c, eomc_sim *sim)
{
    if (c->stabilize == EOMC_STABILIZE_NONE ||
        eomc_sim_stabilize(sim, c->stabilize, c->alpha, c->beta) == EOMC_OK)
        return EOMC_OK;
    return usage(c, "--stabilize %s: %s", stabilize_names[c->stabilize],
                 eomc_sim_error(sim));
}

/* --hold LIST into hold [2n]: x marks q_x, x' marks q'_x. */
static int
hold_list(Cli *c, const eomc_model *m, unsigned char *hold)
{
    for (const char *p = c->hold; *p;) {
        size_t len = strcspn(p, ",");
        char name[256];
        if (len == 0 || len >= sizeof name)
            return usage(c, "--hold: '%s' is not a list of coordinates (x) and velocities "
                         "(x') separated by commas", c->hold);
        memcpy(name, p, len);
        name[len] = '\0';
        int i = state_index(c, m, "--hold", name);
        if (i < 0)
            return EOMC_EUSAGE;
        hold[i] = 1;
        p += len;
        p += *p == ',';
    }
    return EOMC_OK;
}

/* What the assembly keeps, into c->held [2n]: --hold's list, else the
 * scene's (model->a_hold), else nothing.  An equilibrium has no velocity
 * (eomc_sim_equilibrium sets them to zero): it keeps held positions only. */
static int
held_marks(Cli *c, const eomc_model *m)
{
    size_t n = (size_t)m->nq;
    if (!(c->held = calloc(2 * n, 1)))
        return usage(c, "out of memory");
    if (c->hold && hold_list(c, m, c->held) != EOMC_OK)
        return EOMC_EUSAGE;
    if (!c->hold && m->a_hold)
        memcpy(c->held, m->a_hold, 2 * n);
    if (c->equilibrium)
        memset(c->held + n, 0, n);
    return EOMC_OK;
}

/* Project the initial state onto the constraints (c->held kept) and say
 * what moved. */
static int
assemble(Cli *c, eomc_sim *sim, double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq, moved = 0;
    /* the scene's assembly, or --assemble's */
    const char *who = c->hold || !c->scene_assembles ? "--assemble" : "the scene's assembly";
    if (!has_levels(m))
        return usage(c, "--assemble: %s has no holonomic or first-order constraint to "
                     "assemble", m->name);
    if (!c->held && held_marks(c, m) != EOMC_OK)
        return EOMC_EUSAGE;
    double *x0 = malloc(2 * (size_t)n * sizeof *x0);
    if (!x0)
        return usage(c, "out of memory");
    if (c->equilibrium) /* the search starts at rest */
        memset(x + n, 0, (size_t)n * sizeof *x);
    memcpy(x0, x, 2 * (size_t)n * sizeof *x0);
    int rc = eomc_sim_project_held(sim, c->run.t0, x, x + n, c->held);
    if (rc != EOMC_OK) {
        fprintf(stderr, "%s: error: %s: %s\n", c->prog, who, eomc_sim_error(sim));
        free(x0);
        return rc;
    }
    for (int i = 0; i < 2 * n; i++)
        if (x[i] != x0[i]) {
            if (!moved++)
                fprintf(stderr, "%s: %s moved the initial state onto the "
                        "constraints:\n", c->prog, who);
            fprintf(stderr, "  %s%s %.17g -> %.17g (%+.3g)\n", m->q_names[i % n],
                    i < n ? "" : "'", x0[i], x[i], x[i] - x0[i]);
        }
    if (!moved && !c->scene_assembles)
        fprintf(stderr, "%s: --assemble: the initial state already satisfies the "
                "constraints\n", c->prog);
    free(x0);
    return EOMC_OK;
}

static void check_consistent(const Cli *c, eomc_sim *sim, const double *x);
static void suggest_assembly(Cli *c, eomc_sim *sim, const double *x);

static int
print_accel(Cli *c, eomc_sim *sim, const eomc_model_ext *ext, const double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    double *a = calloc((size_t)m->nq + (size_t)m->nc + 1, sizeof *a), *lam = a + m->nq;
    char num[NUM_MAX];
    check_consistent(c, sim, x); /* the accelerations of a state the model never reaches */
    int rc = c->accel_extended ? eomc_reference_accel(sim, ext, c->run.t0, x, a, lam)
                               : eomc_sim_accel(sim, c->run.t0, x, x + m->nq, a);
    if (rc == EOMC_OK) {
        for (int i = 0; i < m->nq; i++)
            printf("%s'' %s\n", m->q_names[i], num_shortest(num, a[i]));
        for (int k = 0; k < m->nc; k++)
            printf("lambda[%s] %s\n", m->c_names[k],
                   num_shortest(num, c->accel_extended ? lam[k] : eomc_sim_multipliers(sim)[k]));
    } else
        fprintf(stderr, "%s: error: %s\n", c->prog, eomc_sim_error(sim));
    free(a);
    return rc;
}

/* ---- sweeps ---- */

static FILE *open_output(const Cli *c, const char *opt, const char *path);
static int close_output(const Cli *c, FILE *f, const char *path);

typedef struct Plan {
    int nparam;
    const char **names;
    long nruns;
    double *values;
} Plan;

static int
sweep_prepare(void *ctx, eomc_sim *sim)
{
    Cli *c = ctx;
    int rc = apply_sets(c, sim);
    return rc == EOMC_OK ? set_stabilize(c, sim) : rc;
}

/* Each run's initial state as the single run's: the spec's, --init, and
 * --assemble's projection (quietly: a sweep's rows say what it did). */
static int
sweep_initial(void *ctx, eomc_sim *sim, double *x)
{
    Cli *c = ctx;
    const eomc_model *m = eomc_sim_model(sim);
    eomc_sim_initial(sim, x, x + m->nq);
    int rc = apply_inits(c, m, x);
    /* each run assembled with its own parameters, quietly: a failure is
     * the run's status */
    if (rc == EOMC_OK && c->assemble)
        rc = eomc_sim_project_held(sim, c->run.t0, x, x + m->nq, c->held);
    return rc;
}

static int sorted_eigen(eomc_sim *sim, const double *A, int nl, double *pair);

/* A sweep of --linearize: each run's eigenvalues, the largest real part
 * first, as ",re1,im1,re2,im2,...". */
static int
linear_cells(void *ctx, eomc_sim *sim, double *x, char **text)
{
    Cli *c = ctx;
    int nl = eomc_sim_linear_size(sim), nu = eomc_sim_model(sim)->nu;
    double *A = calloc((size_t)nl * (size_t)nl + 1, sizeof *A);
    double *B = calloc((size_t)nl * (size_t)nu + 1, sizeof *B);
    double *eig = calloc(2 * (size_t)nl + 1, sizeof *eig);
    char *cells = calloc(2 * (size_t)nl * (NUM_MAX + 1) + 1, 1), num[NUM_MAX];
    int rc = A && B && eig && cells ? eomc_sim_linearize(sim, c->run.t0, x, A, B) : EOMC_EUSAGE;
    if (rc == EOMC_OK)
        rc = sorted_eigen(sim, A, nl, eig);
    for (int k = 0, at = 0; rc == EOMC_OK && k < 2 * nl; k++)
        at += sprintf(cells + at, ",%s", num_shortest(num, eig[k]));
    free(A);
    free(B);
    free(eig);
    if (rc != EOMC_OK) {
        free(cells);
        cells = NULL;
    }
    *text = cells;
    return rc;
}

/* "re1,im1,re2,im2,...": the columns of linear_cells. */
static char *
linear_columns(int nl)
{
    char *cols = calloc((size_t)nl * 24 + 1, 1);
    for (int k = 0, at = 0; cols && k < nl; k++)
        at += sprintf(cols + at, "%sre%d,im%d", k ? "," : "", k + 1, k + 1);
    return cols;
}

/* A swept name: a parameter, not fixed, not swept twice. */
static int
sweep_name(Cli *c, const eomc_model *m, const Plan *pl, const char *name, const char *where)
{
    int k = -1;
    for (int i = 0; i < m->np && k < 0; i++)
        if (!strcmp(m->p_names[i], name))
            k = i;
    if (k < 0) {
        const char *hint = nearest(name, m->p_names, m->np, "");
        return usage(c, "%s: '%s' is not a parameter%s", where, name, hint);
    }
    if (m->p_fixed[k])
        return usage(c, "%s: parameter '%s' is fixed in %s%s%s (folded into the code): "
                     "it cannot be swept", where, name, *m->scene ? "scene '" : "the spec's "
                     "scene", m->scene, *m->scene ? "'" : "");
    for (int j = 0; j < pl->nparam; j++)
        if (!strcmp(pl->names[j], name))
            return usage(c, "%s: '%s' is swept twice", where, name);
    return EOMC_OK;
}

/* --sweep NAME=START:STOP:COUNT ...: the grid, the first sweep slowest. */
static int
plan_grid(Cli *c, const eomc_model *m, Plan *pl)
{
    double *start = calloc((size_t)c->nsweep, sizeof *start);
    double *stop = calloc((size_t)c->nsweep, sizeof *stop);
    long *count = calloc((size_t)c->nsweep, sizeof *count);
    pl->names = calloc((size_t)c->nsweep, sizeof *pl->names);
    int rc = start && stop && count && pl->names ? EOMC_OK : usage(c, "out of memory");
    pl->nruns = 1;
    for (int j = 0; j < c->nsweep && rc == EOMC_OK; j++) {
        char *arg = c->sweep[j], *eq = strchr(arg, '='), *end;
        if (!eq || eq == arg)
            rc = usage(c, "--sweep: expected NAME=START:STOP:COUNT, not '%s'", arg);
        else {
            *eq = '\0';
            rc = sweep_name(c, m, pl, arg, "--sweep");
            pl->names[pl->nparam++] = strdup(arg);
            errno = 0;
            start[j] = strtod(eq + 1, &end);
            if (rc == EOMC_OK && *end == ':')
                stop[j] = strtod(end + 1, &end);
            if (rc == EOMC_OK && *end == ':')
                count[j] = strtol(end + 1, &end, 10);
            if (rc == EOMC_OK && (*end || errno || !isfinite(start[j]) || !isfinite(stop[j]) ||
                                  count[j] < 1 || count[j] > 1000000))
                rc = usage(c, "--sweep %s=%s: expected START:STOP:COUNT, two finite numbers "
                           "and a count from 1 to 1000000", arg, eq + 1);
            *eq = '=';
            if (rc == EOMC_OK && pl->nruns > 10000000 / count[j])
                rc = usage(c, "--sweep: more than 10000000 runs");
            if (rc == EOMC_OK) /* a bad count is not multiplied in */
                pl->nruns *= count[j];
        }
    }
    if (rc == EOMC_OK && !(pl->values = calloc((size_t)(pl->nruns * pl->nparam), sizeof(double))))
        rc = usage(c, "out of memory");
    for (long r = 0; rc == EOMC_OK && r < pl->nruns; r++) {
        long rest = r;
        for (int j = pl->nparam - 1; j >= 0; j--) { /* the last sweep fastest */
            long i = rest % count[j];
            rest /= count[j];
            pl->values[r * pl->nparam + j] =
                count[j] == 1 ? start[j]
                              : start[j] + (stop[j] - start[j]) * (double)i / (double)(count[j] - 1);
        }
    }
    free(start);
    free(stop);
    free(count);
    return rc;
}

/* --sweep-file FILE: a header of parameter names, then one set per row. */
static int
plan_file(Cli *c, const eomc_model *m, Plan *pl)
{
    FILE *f = fopen(c->sweep_file, "r");
    if (!f)
        return usage(c, "--sweep-file: cannot read '%s': %s", c->sweep_file, strerror(errno));
    char *line = NULL;
    size_t cap = 0;
    long lineno = 0, capv = 0;
    int rc = EOMC_OK;
    ssize_t got;
    while (rc == EOMC_OK && (got = getline(&line, &cap, f)) >= 0) {
        lineno++;
        line[strcspn(line, "\r\n")] = '\0';
        if (!*line)
            continue;
        if (!pl->names) { /* the header: a name in every column */
            int cols = 1;
            for (char *p = line; *p; p++)
                cols += *p == ',';
            if (!(pl->names = calloc((size_t)cols, sizeof *pl->names)))
                rc = usage(c, "out of memory");
            for (char *tok = line, *next; tok && rc == EOMC_OK; tok = next) {
                if ((next = strchr(tok, ',')))
                    *next++ = '\0';
                char where[4200];
                snprintf(where, sizeof where, "%s:%ld:%ld", c->sweep_file, lineno,
                         (long)(tok - line) + 1);
                rc = *tok ? sweep_name(c, m, pl, tok, where)
                          : usage(c, "%s: an empty name: the header names the parameter of "
                                  "every column", where);
                pl->names[pl->nparam++] = strdup(tok);
            }
            continue; /* the names are copies: the line is reused */
        }
        if (pl->nruns == capv) {
            capv = capv ? 2 * capv : 64;
            double *v = realloc(pl->values, (size_t)(capv * pl->nparam) * sizeof *v);
            if (!v) {
                rc = usage(c, "out of memory");
                break;
            }
            pl->values = v;
        }
        char *p = line;
        for (int j = 0; j < pl->nparam && rc == EOMC_OK; j++) {
            char *end;
            errno = 0;
            double v = strtod(p, &end);
            if (end == p || errno || !isfinite(v) || (*end != ',' && *end) ||
                (j < pl->nparam - 1 && *end != ',') || (j == pl->nparam - 1 && *end))
                rc = usage(c, "%s:%ld:%ld: expected %d finite number%s separated by commas "
                           "(the value of %s here)", c->sweep_file, lineno,
                           (long)(p - line) + 1, pl->nparam, plural(pl->nparam),
                           pl->names[j]);
            pl->values[pl->nruns * pl->nparam + j] = v;
            p = end + (*end == ',');
        }
        pl->nruns++;
    }
    free(line);
    fclose(f);
    if (rc == EOMC_OK && (!pl->names || pl->nruns == 0))
        rc = usage(c, "%s: no parameter sets (a header of names, then one row per run)",
                   c->sweep_file);
    return rc;
}

/* --sweep, --sweep-file: every run, and the summary CSV. */
static int
sweep(Cli *c, eomc_sim *sim)
{
    const eomc_model *m = eomc_sim_model(sim);
    Plan pl = {0};
    int rc = c->sweep_file ? plan_file(c, m, &pl) : plan_grid(c, m, &pl);
    FILE *f = NULL;
    if (rc == EOMC_OK && eomc_run_check(sim, &c->run) != EOMC_OK)
        rc = usage(c, "%s", eomc_sim_error(sim));
    if (rc == EOMC_OK && !(f = open_output(c, "-o", c->out)))
        rc = EOMC_EUSAGE;
    char *columns = NULL;
    if (rc == EOMC_OK && c->linearize && !(columns = linear_columns(eomc_sim_linear_size(sim))))
        rc = usage(c, "out of memory");
    if (rc == EOMC_OK) {
        c->run.progress = 0;
        Sweep sw = {m, &c->run, sweep_prepare, sweep_initial, c, pl.nparam, pl.names,
                    pl.nruns, pl.values, c->threads, c->prog,
                    c->linearize ? linear_cells : NULL, columns,
                    c->linearize ? 2 * eomc_sim_linear_size(sim) : 0};
        rc = sweep_run(&sw, f);
        if (close_output(c, f, c->out))
            rc = rc ? rc : EOMC_EUSAGE;
    }
    free(columns);
    for (int j = 0; j < pl.nparam; j++)
        free((char *)pl.names[j]);
    free(pl.names);
    free(pl.values);
    return rc;
}

/* The name of component k of the linearization's state: "theta", "theta'". */
static void
state_name(eomc_sim *sim, int k, char *buf, size_t len)
{
    const eomc_model *m = eomc_sim_model(sim);
    int coord, order;
    eomc_sim_linear_state(sim, k, &coord, &order);
    snprintf(buf, len, "%s%s", m->q_names[coord], order ? "'" : "");
}

/* A labelled matrix [rows x cols] for people. */
static void
print_matrix(eomc_sim *sim, const char *title, const double *X, int rows, int cols,
             int inputs)
{
    const eomc_model *m = eomc_sim_model(sim);
    char name[160];
    int w = 12;
    for (int k = 0; k < rows; k++) {
        state_name(sim, k, name, sizeof name);
        w = (int)strlen(name) + 2 > w ? (int)strlen(name) + 2 : w;
    }
    for (int k = 0; k < m->nu && inputs; k++)
        w = (int)strlen(m->u_names[k]) + 2 > w ? (int)strlen(m->u_names[k]) + 2 : w;
    printf("%s\n%*s", title, w, "");
    for (int c = 0; c < cols; c++) {
        if (inputs)
            snprintf(name, sizeof name, "%s", m->u_names[c]);
        else
            state_name(sim, c, name, sizeof name);
        printf("%*s", w, name);
    }
    printf("\n");
    for (int r = 0; r < rows; r++) {
        state_name(sim, r, name, sizeof name);
        printf("%*s", w, name);
        for (int c = 0; c < cols; c++)
            printf(" %*.6g", w - 1, X[r * cols + c]); /* a space even at full width */
        printf("\n");
    }
}

/* The stability verdict takes a real part within this of the largest
 * modulus for 0 (a conservative system's centre computes as real parts of
 * rounding; a defective eigenvalue, as rounding's square root). */
#define EIG_ZERO_REL 1e-9

/* Largest real part first, the same order everywhere (the printed list,
 * --csv's eig rows, a sweep's re1, im1, ...); of equal real parts (a
 * conjugate pair) the positive imaginary part first. */
static int
cmp_eig(const void *a, const void *b)
{
    const double *x = a, *y = b;
    return x[0] != y[0] ? (x[0] > y[0] ? -1 : 1) : x[1] > y[1] ? -1 : x[1] < y[1];
}

/* A's eigenvalues into pair [2 nl] (re, im), sorted; EOMC_OK or a status
 * with the simulator's message. */
static int
sorted_eigen(eomc_sim *sim, const double *A, int nl, double *pair)
{
    double *re = calloc((size_t)nl + 1, sizeof *re), *im = calloc((size_t)nl + 1, sizeof *im);
    int rc = re && im ? eomc_sim_eigenvalues(sim, A, nl, re, im) : EOMC_EUSAGE;
    for (int k = 0; k < nl && rc == EOMC_OK; k++)
        pair[2 * k] = re[k], pair[2 * k + 1] = im[k];
    if (rc == EOMC_OK)
        qsort(pair, (size_t)nl, 2 * sizeof *pair, cmp_eig);
    free(re);
    free(im);
    return rc;
}

/* What the eigenvalues say of an equilibrium's stability, and how the
 * verdict rounds. */
static void
print_verdict(const double *pair, int nl)
{
    double big = 0, worst = nl ? pair[0] : 0; /* sorted: the largest real part first */
    for (int k = 0; k < nl; k++)
        big = fmax(big, hypot(pair[2 * k], pair[2 * k + 1]));
    char num[NUM_MAX];
    num_shortest(num, worst);
    if (worst > EIG_ZERO_REL * big)
        printf("unstable: the largest real part, %s, is more than %g of the largest modulus "
               "(%.6g)\n", num, EIG_ZERO_REL, big);
    else if (worst < -EIG_ZERO_REL * big)
        printf("asymptotically stable: every real part is below -%g of the largest modulus "
               "(%.6g); the largest is %s\n", EIG_ZERO_REL, big, num);
    else
        printf("stable to first order only: the largest real part, %s, is within %g of the "
               "largest modulus (%.6g) of 0, which this verdict counts as 0 (the rounding "
               "of a centre, or of a defective eigenvalue, reaches that far); on the "
               "imaginary axis the linearization cannot decide\n", num, EIG_ZERO_REL, big);
}

/* The eigenvalues, as computed (the shortest text that reads back as the
 * computed double: nothing rounded away), and for an equilibrium what
 * they say of stability. */
static int
print_eigen(Cli *c, eomc_sim *sim, const double *A, int nl, int verdict, double *pair)
{
    int rc = sorted_eigen(sim, A, nl, pair);
    if (rc != EOMC_OK) {
        fprintf(stderr, "%s: error: %s\n", c->prog, eomc_sim_error(sim));
        return rc;
    }
    char re[NUM_MAX], im[NUM_MAX];
    printf("eigenvalues of A (the largest real part first):\n");
    for (int k = 0; k < nl; k++)
        printf("  %s %c %si\n", num_shortest(re, pair[2 * k]), pair[2 * k + 1] < 0 ? '-' : '+',
               num_shortest(im, fabs(pair[2 * k + 1])));
    if (verdict)
        print_verdict(pair, nl);
    return rc;
}

/* --csv FILE: matrix,row,column,value, one row per entry of A and B, then
 * two per eigenvalue k (1, 2, ... in the printed order): eig,k,re,VALUE
 * and eig,k,im,VALUE. */
static int
write_linear_csv(Cli *c, eomc_sim *sim, const double *A, const double *B, int nl,
                 const double *eig)
{
    const eomc_model *m = eomc_sim_model(sim);
    FILE *f = fopen(c->csv, "w");
    if (!f) {
        fprintf(stderr, "%s: --csv: cannot write '%s': %s\n", c->prog, c->csv,
                strerror(errno));
        return EOMC_EUSAGE;
    }
    char row[160], col[160], num[NUM_MAX];
    fprintf(f, "matrix,row,column,value\n");
    for (int r = 0; r < nl; r++) {
        state_name(sim, r, row, sizeof row);
        for (int k = 0; k < nl; k++) {
            state_name(sim, k, col, sizeof col);
            fprintf(f, "A,%s,%s,%s\n", row, col, num_shortest(num, A[r * nl + k]));
        }
    }
    for (int r = 0; r < nl; r++) {
        state_name(sim, r, row, sizeof row);
        for (int k = 0; k < m->nu; k++)
            fprintf(f, "B,%s,%s,%s\n", row, m->u_names[k], num_shortest(num, B[r * m->nu + k]));
    }
    for (int k = 0; k < nl; k++) {
        fprintf(f, "eig,%d,re,%s\n", k + 1, num_shortest(num, eig[2 * k]));
        fprintf(f, "eig,%d,im,%s\n", k + 1, num_shortest(num, eig[2 * k + 1]));
    }
    if (fclose(f) != 0) {
        fprintf(stderr, "%s: error writing %s\n", c->prog, c->csv);
        return EOMC_EUSAGE;
    }
    return EOMC_OK;
}

/* --linearize and --equilibrium. */
static int
print_linear(Cli *c, eomc_sim *sim, double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq, nl = eomc_sim_linear_size(sim), nu = m->nu, rc = EOMC_OK, its = 0;
    double t = c->run.t0;
    double *A = calloc((size_t)nl * (size_t)nl, sizeof *A);
    double *B = calloc((size_t)nl * (size_t)(nu ? nu : 1), sizeof *B);
    double *eig = calloc(2 * (size_t)nl + 1, sizeof *eig);
    if (!A || !B || !eig)
        rc = EOMC_EUSAGE;
    if (rc == EOMC_OK && c->equilibrium) {
        rc = eomc_sim_equilibrium(sim, t, x, &its);
        char num[NUM_MAX];
        if (rc == EOMC_OK) {
            printf("%s: an equilibrium, found by %d Newton step%s:\n", c->prog, its,
                   its == 1 ? "" : "s");
            for (int i = 0; i < n; i++)
                printf("  %s = %s\n", m->q_names[i], num_shortest(num, x[i]));
        }
    }
    if (rc == EOMC_OK)
        rc = eomc_sim_linearize(sim, t, x, A, B);
    if (rc == EOMC_OK) {
        printf("%s: linearized at t = %g,", c->prog, t);
        for (int i = 0; i < 2 * n; i++)
            printf("%s %s%s = %.6g", i ? "," : "", m->q_names[i % n], i < n ? "" : "'", x[i]);
        printf("\n");
        if (m->nc > 0)
            printf("in the independent coordinates of the elimination (%d of %d)\n", nl,
                   2 * n);
        print_matrix(sim, "A = dz'/dz:", A, nl, nl, 0);
        if (nu)
            print_matrix(sim, "B = dz'/du:", B, nl, nu, 1);
        else
            printf("B = dz'/du: the model has no inputs\n");
        rc = print_eigen(c, sim, A, nl, c->equilibrium, eig);
    } else if (rc != EOMC_EUSAGE || eomc_sim_error(sim)[0]) {
        fprintf(stderr, "%s: error: %s\n", c->prog, eomc_sim_error(sim));
        int worst, level;
        if (rc == EOMC_ENUMERIC && !c->equilibrium &&
            eomc_sim_inconsistency(sim, t, x, x + n, &worst, &level) > EOMC_INCONSISTENT)
            suggest_assembly(c, sim, x);
    }
    if (rc == EOMC_OK && c->csv)
        rc = write_linear_csv(c, sim, A, B, nl, eig);
    free(A);
    free(B);
    free(eig);
    return rc;
}

/* The constraints x is off (eomc_sim_inconsistencies above
 * EOMC_INCONSISTENT), worst first, into buf: "rod (positions: its residual
 * is 0.12 of the size of its terms), ..."; returns how many. */
static int
describe_off(eomc_sim *sim, double t, const double *x, char *buf, size_t len)
{
    const eomc_model *m = eomc_sim_model(sim);
    int nc = m->nc, off = 0;
    double *e = calloc((size_t)nc + 1, sizeof *e);
    int *level = calloc((size_t)nc + 1, sizeof *level);
    buf[0] = '\0';
    if (e && level && has_levels(m) &&
        eomc_sim_inconsistencies(sim, t, x, x + m->nq, e, level) > EOMC_INCONSISTENT) {
        for (int k = 0; k < nc; k++)
            off += e[k] > EOMC_INCONSISTENT;
        size_t at = 0;
        for (int done = 0; done < off && at < len; done++) { /* the largest left */
            int k = 0;
            for (int j = 1; j < nc; j++)
                k = e[j] > e[k] ? j : k;
            at += (size_t)snprintf(buf + at, len - at,
                                   done ? ", %s (%s: %.2g)"
                                        : "%s (%s: its residual is %.2g of the size of its "
                                          "terms)", m->c_names[k],
                                   level[k] ? "velocities" : "positions", e[k]);
            e[k] = -1;
        }
    }
    free(e);
    free(level);
    return off;
}

/* A start off the constraints is allowed (the drift then starts there),
 * but rarely meant: say so, once, before integrating, naming every
 * constraint it violates.  The test is relative to each constraint's terms
 * (eomc_sim_inconsistencies), so that it means the same in any units. */
static void
check_consistent(const Cli *c, eomc_sim *sim, const double *x)
{
    char list[2048];
    int off = describe_off(sim, c->run.t0, x, list, sizeof list);
    if (off == 1)
        fprintf(stderr, "%s: warning: the initial state is off the constraint %s; --assemble "
                "projects the state onto the constraints\n", c->prog, list);
    else if (off > 1)
        fprintf(stderr, "%s: warning: the initial state is off %d constraints, worst first: %s; "
                "--assemble projects the state onto the constraints\n", c->prog, off, list);
}

/* Whether the trial projection keeping hold [2n] puts x on the
 * constraints; moved gets what it would change: "x' 5 -> 0, ...". */
static int
trial_assembly(const Cli *c, eomc_sim *sim, const double *x, const unsigned char *hold,
               char *moved, size_t len)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq;
    double *y = malloc(2 * (size_t)n * sizeof *y);
    if (!y)
        return 0;
    memcpy(y, x, 2 * (size_t)n * sizeof *y);
    int ok = eomc_sim_project_held(sim, c->run.t0, y, y + n, hold) == EOMC_OK;
    size_t at = 0;
    moved[0] = '\0';
    for (int i = 0; ok && i < 2 * n && at < len; i++)
        if (y[i] != x[i])
            at += (size_t)snprintf(moved + at, len - at, "%s%s%s %.6g -> %.6g", at ? ", " : "",
                                   m->q_names[i % n], i < n ? "" : "'", x[i], y[i]);
    free(y);
    return ok;
}

/* The names hold [2n] marks, as --hold takes them. */
static void
hold_names(const eomc_model *m, const unsigned char *hold, char *buf, size_t len)
{
    int n = m->nq;
    size_t at = 0;
    buf[0] = '\0';
    for (int i = 0; i < 2 * n && at < len; i++)
        if (hold[i])
            at += (size_t)snprintf(buf + at, len - at, "%s%s%s", at ? "," : "",
                                   m->q_names[i % n], i < n ? "" : "'");
}

/* After --linearize refused a state off the constraints: the --assemble
 * that would put it on them, tried first, with what it would move.  Two
 * holds make sense: what --init set (the user's values stay; the rest
 * moves), and the linearization's own coordinates and velocities (only
 * those the constraints determine move). */
static void
suggest_assembly(Cli *c, eomc_sim *sim, const double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq, nl = eomc_sim_linear_size(sim), said = 0;
    unsigned char *hold[2] = {calloc(2 * (size_t)n, 1), calloc(2 * (size_t)n, 1)};
    char names[2048], moved[2048];
    const char *why[2] = {"keeps what --init set and moves the rest onto the constraints",
                          "keeps the linearization's coordinates and velocities and moves "
                          "only those the constraints determine"};
    for (int k = 0; hold[0] && k < c->ninit; k++) { /* NAME=VALUE or NAME'=VALUE */
        size_t len = strcspn(c->init[k], "=");
        for (int i = 0; i < 2 * n; i++) {
            size_t name = strlen(m->q_names[i % n]);
            if (name + (i >= n) == len && !strncmp(c->init[k], m->q_names[i % n], name) &&
                (i < n || c->init[k][name] == '\''))
                hold[0][i] = 1;
        }
    }
    for (int k = 0; hold[1] && k < nl; k++) {
        int coord, order;
        eomc_sim_linear_state(sim, k, &coord, &order);
        hold[1][coord + order * n] = 1;
    }
    for (int j = 0; j < 2 && hold[0] && hold[1]; j++) {
        if ((j == 0 && c->ninit == 0) || (j == 1 && !memcmp(hold[0], hold[1], 2 * (size_t)n)))
            continue;
        if (!trial_assembly(c, sim, x, hold[j], moved, sizeof moved))
            continue;
        hold_names(m, hold[j], names, sizeof names);
        fprintf(stderr, "%s: %s --assemble --hold \"%s\" %s: %s\n", c->prog,
                said++ ? "or" : "to linearize on them,", names, why[j], moved);
    }
    if (!said)
        fprintf(stderr, "%s: --assemble --hold LIST puts the state on the constraints keeping "
                "LIST as it is (neither what --init set nor the linearization's coordinates "
                "and velocities can be kept here)\n", c->prog);
    free(hold[0]);
    free(hold[1]);
}

/* An event's `set` that breaks the constraints is the same mistake as
 * such a start, made during the run, where its drift would otherwise pass
 * unseen: say so, for the first one. */
static void
warn_reset(const Cli *c, const eomc_model *m, const eomc_stats *st)
{
    if (st->reset_event < 0)
        return;
    const char *name = m->c_names[st->reset_constraint];
    if (!strchr(st->reset_off, ',')) /* one constraint */
        fprintf(stderr, "%s: warning: t = %.6g: event %s set %s that violate the constraint "
                "%s: its residual is %.2g of the size of its terms; ", c->prog, st->reset_t,
                m->ev_names[st->reset_event], st->reset_level ? "velocities" : "positions",
                name, st->reset_inconsistency);
    else
        fprintf(stderr, "%s: warning: t = %.6g: event %s set a state off the constraints, "
                "worst first: %s (each residual as a share of the size of its terms); ",
                c->prog, st->reset_t, m->ev_names[st->reset_event], st->reset_off);
    if (c->stabilize == EOMC_STABILIZE_PROJECT)
        fprintf(stderr, "the projection after the next step moved the state back onto the "
                "constraints, changing what the event set\n");
    else
        fprintf(stderr, "the motion from there drifts off the constraints (column "
                "res[%s] shows how far; --stabilize project moves the state back onto "
                "them)\n", name);
}

/* The run's solve lost more digits than its tolerance leaves: say so,
 * with where and what (eomc_stats.ill). */
static void
warn_condition(const Cli *c, const eomc_stats *st)
{
    if (isnan(st->ill_t))
        return;
    int fixed = c->run.h_fixed > 0 || !(c->run.rtol > 0);
    int kept = (int)lround(-log10(st->max_condition * DBL_EPSILON));
    fprintf(stderr, "%s: warning: t = %.6g: %s is ill-conditioned (condition %.2g at "
            "worst, at t = %.6g): q'' keeps about %d of its 16 digits, fewer than the %d "
            "%s; the motion is probably less accurate than asked\n", c->prog, st->ill_t,
            st->ill, st->max_condition, st->t_condition, kept > 0 ? kept : 0,
            (int)lround(-log10(st->cond_tol)), fixed ? "a fixed-step run should keep" :
            "its rtol asks for");
}

/* The conserved quantity moves only by the steps' errors, so it may drift
 * by the sum of what their error estimates make of it (eomc_stats'
 * invariant_budget).  The estimates of healthy runs account for their
 * drift to within a factor of 2, bsimp's to within 90 (measured over the
 * shipped specs, every method, rtol 1e-4 .. 1e-12); beyond DRIFT_SLACK
 * times, an error the estimates cannot see is at work. */
#define DRIFT_SLACK 1e3

/* Fixed steps estimate no error of their own: a conserved quantity that
 * moved by more than FIXED_DRIFT of the largest kinetic energy has fewer
 * than two digits right, and the motion is no better. */
#define FIXED_DRIFT 1e-2

static void
warn_drift(const Cli *c, const eomc_model *m, const eomc_stats *st, const Csv *w)
{
    if (st->h_used > 0 && w->invariant && w->dh > FIXED_DRIFT * w->T_max) {
        fprintf(stderr, "%s: warning: fixed steps of %.3g: the conserved quantity %s changed "
                "by %.3g, %.2g of the largest kinetic energy (%.3g): fewer than two of its "
                "digits are right, and the motion's are probably no better (shorter "
                "--fixed-step, or adaptive steps, give more)\n", c->prog, st->h_used,
                m->invariant_name, w->dh, w->dh / w->T_max, w->T_max);
        return;
    }
    if (!(st->invariant_budget > 0) ||
        !(st->invariant_drift > DRIFT_SLACK * st->invariant_budget))
        return;
    fprintf(stderr, "%s: warning: the conserved quantity %s drifted by %.3g, %.3g times "
            "what the steps' own error estimates allow (%.3g): an error the integrator "
            "cannot see is at work (a solve that loses digits, a force that is not "
            "smooth, or a model that does not conserve %s); the motion is probably less "
            "accurate than asked\n", c->prog, m->invariant_name, st->invariant_drift,
            st->invariant_drift / st->invariant_budget, st->invariant_budget,
            m->invariant_name);
}

/* The reference solution follows the equations, not the events that
 * stop or reset the motion: with those, there is nothing to measure
 * against. */
static int
check_event_options(const Cli *c, const eomc_model *m)
{
    int moving = 0;
    for (int k = 0; k < m->nevent; k++)
        moving |= m->ev_action[k] != EOMC_EVENT_RECORD;
    const char *opt = c->work_precision ? "--work-precision"
                      : c->reference    ? "--reference"
                      : c->error        ? "--error"
                      : c->reference_out ? "--reference-out" : NULL;
    if (moving && opt)
        return usage(c, "%s: scene %s has events that stop or reset the motion, which the "
                     "reference solution does not follow (measure the errors on a scene "
                     "without them)", opt, *m->scene ? m->scene : "(the spec's)");
    if (c->events && m->nevent == 0)
        return usage(c, "--events: scene %s has no events", *m->scene ? m->scene
                                                                     : "(the spec's)");
    if (c->events && (c->work_precision || c->accel))
        return usage(c, "--events belongs to a run (not %s)",
                     c->accel ? "--accel" : "--work-precision");
    return EOMC_OK;
}

/* Open -o's file (or stdout); NULL after saying why. */
static FILE *
open_output(const Cli *c, const char *opt, const char *path)
{
    if (!path)
        return stdout;
    FILE *f = fopen(path, "w");
    if (!f)
        fprintf(stderr, "%s: %s: cannot write '%s': %s\n", c->prog, opt, path,
                strerror(errno));
    return f;
}

static int
close_output(const Cli *c, FILE *f, const char *path)
{
    int bad = fflush(f) != 0 || ferror(f);
    if (f != stdout)
        bad |= fclose(f) != 0;
    if (bad)
        fprintf(stderr, "%s: error writing %s\n", c->prog, path ? path : "stdout");
    return bad;
}

/* The reference solution: read (--reference) or computed; written out
 * when --reference-out asks.  EOMC_OK or an exit status. */
static int
get_reference(Cli *c, eomc_sim *sim, const eomc_model_ext *ext, const double *x,
              eomc_reference *ref)
{
    const eomc_model *m = eomc_sim_model(sim);
    int rc;
    if (c->reference)
        rc = eomc_reference_read(sim, c->reference, &c->run, ref);
    else if (!ext)
        return usage(c, "%s was built without its extended-precision functions, so it "
                     "cannot compute a reference solution: rebuild with `eomc build %s "
                     "--extended` (or give --reference FILE)", m->name, m->spec);
    else
        rc = eomc_reference_compute(sim, ext, &c->run, x, ref);
    if (rc != EOMC_OK) {
        fprintf(stderr, "%s: %s%s\n", c->prog, rc == EOMC_ENUMERIC ? "error: " : "",
                eomc_sim_error(sim));
        return rc;
    }
    if (c->reference_out) {
        Csv w = csv_new(open_output(c, "--reference-out", c->reference_out), sim);
        if (!w.f || !w.res) {
            free(w.res);
            eomc_reference_free(ref);
            return EOMC_EUSAGE;
        }
        print_header(w.f, m);
        rc = EOMC_OK;
        for (long k = 0; k < ref->nrows && rc == EOMC_OK; k++)
            rc = write_row(&w, ref->t[k], ref->x + (size_t)k * (size_t)ref->nx);
        flush_rows(&w);
        if (rc != EOMC_OK)
            fprintf(stderr, "%s: --reference-out: %s\n", c->prog, eomc_sim_error(sim));
        if (close_output(c, w.f, c->reference_out) && rc == EOMC_OK)
            rc = EOMC_EUSAGE;
        free(w.res);
        if (rc != EOMC_OK)
            eomc_reference_free(ref);
    }
    return rc;
}

/* After a failure: what the CSV holds. */
static void
say_kept(const Cli *c, const Csv *w)
{
    char num[NUM_MAX];
    if (w->rows == 0)
        fprintf(stderr, "%s: no row was computed: %s holds the header alone\n", c->prog,
                c->out ? c->out : "stdout");
    else if (w->rows == 1)
        fprintf(stderr, "%s: the one row computed, at t = %s, is kept\n", c->prog,
                num_shortest(num, w->t_last));
    else
        fprintf(stderr, "%s: the %ld rows computed up to then, to t = %s, are kept\n",
                c->prog, w->rows, num_shortest(num, w->t_last));
}

static int
simulate(Cli *c, eomc_sim *sim, const eomc_model_ext *ext, double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    eomc_reference ref = {0};
    if (eomc_run_check(sim, &c->run) != EOMC_OK) /* before any file is written */
        return usage(c, "%s", eomc_sim_error(sim));
    Csv w = csv_new(stdout, sim);
    check_consistent(c, sim, x);
    int rc = EOMC_OK;
    if ((c->error || c->reference_out) &&
        (rc = get_reference(c, sim, ext, x, &ref)) != EOMC_OK) {
        free(w.res);
        return rc;
    }
    if (c->error && compare_init(&w.cmp, &ref) != 0) {
        fprintf(stderr, "%s: out of memory\n", c->prog);
        free(w.res);
        eomc_reference_free(&ref);
        compare_free(&w.cmp);
        return EOMC_EUSAGE;
    }
    if (c->error)
        w.ref = &ref;
    /* both files open, or neither is left behind */
    if (c->events && !(w.events = open_output(c, "--events", c->events))) {
        free(w.res);
        eomc_reference_free(&ref);
        compare_free(&w.cmp);
        return EOMC_EUSAGE;
    }
    if (!(w.f = open_output(c, "-o", c->out))) {
        if (w.events) {
            fclose(w.events);
            unlink(c->events);
        }
        free(w.res);
        eomc_reference_free(&ref);
        compare_free(&w.cmp);
        return EOMC_EUSAGE;
    }
    if (w.events) {
        fprintf(w.events, "t,event");
        for (int i = 0; i < m->nq; i++)
            fprintf(w.events, ",%s", m->q_names[i]);
        for (int i = 0; i < m->nq; i++)
            fprintf(w.events, ",%s'", m->q_names[i]);
        fputc('\n', w.events);
    }
    /* --plot: a copy of the rows for gnuplot */
    char data[] = "/tmp/eomc-rows-XXXXXX";
    int fd = c->plot ? mkstemp(data) : -1;
    if (c->plot && (fd < 0 || !(w.tee = fdopen(fd, "w")))) {
        fprintf(stderr, "%s: --plot: cannot write its data: %s\n", c->prog, strerror(errno));
        if (fd >= 0) {
            close(fd);
            unlink(data);
        }
        close_output(c, w.f, c->out);
        if (c->out)
            unlink(c->out);
        free(w.res);
        eomc_reference_free(&ref);
        compare_free(&w.cmp);
        return EOMC_EUSAGE;
    }
    print_header(w.f, m);
    if (w.tee)
        print_header(w.tee, m);
    eomc_stats st;
    c->run.progress = 1;
    c->run.on_event = write_event;
    c->run.event_ctx = &w;
    /* whole blocks of rows, one write each: no half row in the file */
    setvbuf(w.f, NULL, _IONBF, 0);
    if (w.tee)
        setvbuf(w.tee, NULL, _IONBF, 0);
    struct sigaction sa = {0}, old_int, old_term;
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int);
    sigaction(SIGTERM, &sa, &old_term);
    rc = eomc_sim_integrate(sim, &c->run, x, write_row, &w, &st);
    flush_rows(&w);
    sigaction(SIGINT, &old_int, NULL);
    sigaction(SIGTERM, &old_term, NULL);
    if (rc == EOMC_INTERRUPTED) {
        close_output(c, w.f, c->out);
        if (w.events)
            close_output(c, w.events, c->events);
        if (w.tee) {
            fclose(w.tee);
            unlink(data);
        }
        char num[NUM_MAX];
        fprintf(stderr, "%s: interrupted at t = %s (%s): the %ld row%s up to then %s "
                "written\n", c->prog, num_shortest(num, w.t_last),
                interrupted == SIGINT ? "SIGINT" : "SIGTERM", w.rows, plural(w.rows),
                w.rows == 1 ? "is" : "are");
        eomc_reference_free(&ref);
        compare_free(&w.cmp);
        free(w.res);
        return 128 + interrupted; /* 130 for SIGINT, 143 for SIGTERM */
    }
    if (close_output(c, w.f, c->out))
        rc = rc ? rc : EOMC_ENUMERIC;
    if (w.events && close_output(c, w.events, c->events))
        rc = rc ? rc : EOMC_ENUMERIC;

    if (rc)
        fprintf(stderr, "%s: error: %s\n", c->prog, eomc_sim_error(sim));
    if (rc == EOMC_ENUMERIC)
        say_kept(c, &w);
    warn_condition(c, &st);
    warn_drift(c, m, &st, &w);
    warn_reset(c, m, &st);
    if (c->stats)
        print_stats(&w, &st, c->stabilize);
    if (c->summary && !rc)
        print_summary(c, m, &w, &st);
    if (c->error && !rc && !c->stats && !c->summary) {
        char good[200];
        if (isnan(ref.error))
            snprintf(good, sizeof good, "the reference, read from %s, has no estimate of "
                     "its own error", c->reference);
        else
            snprintf(good, sizeof good, "the reference, by %s%s, is good to %.2g",
                     ref.method, ref.stiff ? " (the problem is stiff)" : "", ref.error);
        double digits;
        int i = compare_worst(&w.cmp, &digits), n = m->nq;
        char worst[160] = "; every row is the reference's to the last bit";
        if (digits < INFINITY) /* each component against its own size (compare.h) */
            snprintf(worst, sizeof worst, "; %s%s keeps the fewest digits, %.1f",
                     m->q_names[i % n], i < n ? "" : "'", digits);
        fprintf(stderr, "%s: error against the reference solution: at most %.3g over "
                "the %ld row%s, %.3g at t = %g (%s)%s\n", c->prog, w.err_max, w.rows,
                plural(w.rows), w.err_end, c->run.t_end, good, worst);
    }
    if (c->errors && rc != EOMC_INTERRUPTED) {
        FILE *f = open_output(c, "--errors", c->errors);
        if (f) {
            compare_csv_header(f);
            compare_csv_run(f, m, w.cmp.scale, rc ? NULL : w.cmp.end, rc ? NULL : w.cmp.max,
                            c->run.method, c->run.rtol, c->run.h_fixed > 0 ? st.h_used : 0);
        }
        if (!f || close_output(c, f, c->errors))
            rc = rc ? rc : EOMC_EUSAGE;
    }
    if (w.tee) {
        int resets = 0;
        for (int k = 0; k < m->nevent; k++)
            resets |= m->ev_action[k] == EOMC_EVENT_SET;
        /* the rows written, also those before a failure */
        if (fclose(w.tee) != 0 || (w.rows > 0 && plot_trajectory(c->prog, m, data, c->plot,
                                                                  w.h_first, resets,
                                                                  w.out_max) != EOMC_OK))
            rc = rc ? rc : EOMC_EUSAGE;
        unlink(data);
    }
    eomc_reference_free(&ref);
    compare_free(&w.cmp);
    free(w.res);
    return rc;
}

/* "t = 0 to 10, 1001 rows every 0.01, q1 = 1, ...": the report's setting. */
static void
describe_setting(const Cli *c, const eomc_model *m, const double *x, char *buf,
                 size_t len)
{
    size_t at = (size_t)snprintf(buf, len, "t = %g to %g, %ld rows every %g", c->run.t0,
                                 c->run.t_end, eomc_run_rows(&c->run), c->run.dt);
    for (int i = 0; i < 2 * m->nq && at < len; i++)
        if (x[i] != 0)
            at += (size_t)snprintf(buf + at, len - at, ", %s%s = %.6g",
                                   m->q_names[i % m->nq], i < m->nq ? "" : "'", x[i]);
    if (c->stabilize != EOMC_STABILIZE_NONE && at < len)
        snprintf(buf + at, len - at, ", --stabilize %s", stabilize_names[c->stabilize]);
}

enum {
    NMETHODS = 0 /* the methods in methods.def */
#define METHOD(name, gsl, fixed, jac, description) + 1
#include "methods.def"
#undef METHOD
};

static int
work_precision(Cli *c, eomc_sim *sim, const eomc_model_ext *ext, double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    eomc_reference ref = {0};
    double tols[TOL_LAST_EXP - TOL_FIRST_EXP + 1], steps[3];
    /* a model built without its Jacobian reports the methods that can run
     * on it, and says which it left out and why */
    const char *runnable[NMETHODS + 1];
    const char *const *methods = c->methods ? c->methods : eomc_methods;
    if (!m->jacobian) {
        char left[256] = "";
        int n = 0;
        for (int k = 0; methods[k]; k++) {
            if (eomc_method_jacobian(methods[k]) != 1)
                runnable[n++] = methods[k];
            else if (c->methods)
                return usage(c, "--methods: %s needs the Jacobian of the equations, which "
                             "%s was built without: rebuild with `eomc build %s --jacobian "
                             "auto`", methods[k], m->name, m->spec);
            else
                snprintf(left + strlen(left), sizeof left - strlen(left), "%s%s",
                         *left ? ", " : "", methods[k]);
        }
        runnable[n] = NULL;
        methods = runnable;
        if (*left)
            fprintf(stderr, "%s: note: %s left out: they need the Jacobian of the equations, "
                    "which %s was built without (rebuild with `eomc build %s --jacobian "
                    "auto` to report them)\n", c->prog, left, m->name, m->spec);
    }
    check_consistent(c, sim, x);
    int rc = get_reference(c, sim, ext, x, &ref);
    if (rc != EOMC_OK)
        return rc;
    for (int k = TOL_FIRST_EXP; k <= TOL_LAST_EXP; k++)
        tols[k - TOL_FIRST_EXP] = pow(10.0, -k);
    for (int k = 0; k < 3; k++)
        steps[k] = default_steps[k] * (c->run.t_end - c->run.t0);
    char setting[1024];
    describe_setting(c, m, x, setting, sizeof setting);
    Report r = {
        .sim = sim, .base = c->run, .x0 = x, .ref = &ref,
        .methods = methods,
        .tolerances = c->tolerances ? c->tolerances : tols,
        .ntolerances = c->tolerances ? c->ntolerances : TOL_LAST_EXP - TOL_FIRST_EXP + 1,
        .steps = c->steps ? c->steps : steps, .nsteps = c->steps ? c->nsteps : 3,
        .steps_given = c->steps != NULL, .csv = c->csv, .plot = c->plot, .errors = c->errors,
        .target = c->target, .prog = c->prog, .setting = setting,
    };
    rc = report_run(&r);
    eomc_reference_free(&ref);
    return rc;
}

static int
cli_main(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext)
{
    const char *slash = argc > 0 ? strrchr(argv[0], '/') : NULL;
    Cli c = {0};
    c.stabilize = -1;
    c.alpha = c.beta = DEFAULT_RATE;
    c.target = NAN;
    c.prog = argc > 0 ? (slash ? slash + 1 : argv[0]) : m->name;
    c.self = getenv("EOMC_RUN_COMMAND") ? getenv("EOMC_RUN_COMMAND") : c.prog;
    c.run = eomc_run_defaults(m);
    c.set = calloc((size_t)argc + 1, sizeof *c.set);
    c.init = calloc((size_t)argc + 1, sizeof *c.init);
    c.sweep = calloc((size_t)argc + 1, sizeof *c.sweep);
    c.threads = 1;
    if (sweep_rank() != 0) { /* rank 0 speaks for the job */
        if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
            return EOMC_EUSAGE;
    }
    eomc_sim *sim = eomc_sim_alloc(m);
    double *x = calloc(2 * (size_t)m->nq + 1, sizeof *x);
    int rc;
    if (!sim || !c.set || !c.init || !c.sweep || !x) {
        fprintf(stderr, "%s: out of memory, or a model built for another runtime\n",
                c.prog);
        rc = EOMC_EUSAGE;
    } else if ((rc = parse_args(&c, argc, argv, m)) != EOMC_OK) {
        rc = rc < 0 ? EOMC_OK : rc;
    } else if ((rc = check_event_options(&c, m)) != EOMC_OK) {
        /* said */
    } else if ((rc = apply_sets(&c, sim)) == EOMC_OK &&
               (rc = set_stabilize(&c, sim)) == EOMC_OK) {
        eomc_sim_initial(sim, x, x + m->nq);
        if ((rc = apply_inits(&c, m, x)) == EOMC_OK &&
            (rc = c.assemble ? held_marks(&c, m) : EOMC_OK) == EOMC_OK &&
            (rc = c.assemble && !c.nsweep && !c.sweep_file ? assemble(&c, sim, x)
                                                           : EOMC_OK) == EOMC_OK)
            rc = c.nsweep || c.sweep_file ? sweep(&c, sim)
                 : sweep_rank() != 0 ? EOMC_OK /* one run: rank 0's */
                 : c.accel          ? print_accel(&c, sim, ext, x)
                 : c.linearize || c.equilibrium ? print_linear(&c, sim, x)
                 : c.work_precision ? work_precision(&c, sim, ext, x)
                                    : simulate(&c, sim, ext, x);
    }
    eomc_sim_free(sim);
    free(x);
    free(c.set);
    free(c.init);
    free(c.sweep);
    free(c.methods);
    free(c.tolerances);
    free(c.steps);
    free(c.held);
    return rc;
}

/* The simulator is the program for the time it runs, so its GSL errors
 * come back as statuses and are reported as eomc's (eomc.h); the handler
 * before it is put back for a program that calls eomc_main and goes on. */
int
eomc_main(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext)
{
    gsl_error_handler_t *before = gsl_set_error_handler_off();
    int rc = cli_main(argc, argv, m, ext);
    gsl_set_error_handler(before);
    return rc;
}

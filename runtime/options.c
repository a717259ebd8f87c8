/*
 * options: the command line read into an Options, and checked (options.h).
 *
 * Parameters are set before the initial state is computed (it may depend
 * on them), and --init overrides that state afterwards, whatever the
 * order on the line.
 */
#include "options.h"
#include "nearest.h"
#include "plot.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#ifndef EOMC_VERSION
#define EOMC_VERSION "unknown"
#endif

int
opt_usage(const Options *c, const char *fmt, ...)
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
const char *
opt_nearest(const char *word, const char *const *names, int n, const char *suffix)
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

void
opt_list_names(FILE *f, const char *const *names, int n, const char *suffix)
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

const char *
opt_stabilize_name(int method)
{
    return stabilize_names[method];
}

static void
help(const Options *c, const eomc_model *m)
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
    opt_list_names(stdout, m->q_names, m->nq, "");
    printf("\nparameters: ");
    for (int k = 0; k < m->np; k++)
        printf("%s%s=%g%s", k ? ", " : "", m->p_names[k], m->p_default[k],
               m->p_fixed[k] ? " (fixed)" : "");
    printf("\ninputs: ");
    opt_list_names(stdout, m->u_names, m->nu, "");
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
real_option(Options *c, const char *opt, const char *val, double *x, double lo, int open)
{
    if (!number(val, x))
        return opt_usage(c, "%s: '%s' is not a finite number", opt, val);
    if (open ? !(*x > lo) : !(*x >= lo))
        return opt_usage(c, "%s: %s is out of range (must be %s %g)", opt, val,
                     open ? ">" : ">=", lo);
    return EOMC_OK;
}

/* The index of a method by name, or a usage error (-1) suggesting one. */
static int
method_index(Options *c, const char *opt, const char *val)
{
    int n = 0;
    while (eomc_methods[n])
        n++;
    for (int j = 0; j < n; j++)
        if (strcmp(val, eomc_methods[j]) == 0)
            return j;
    fprintf(stderr, "%s: %s: unknown method '%s'%s; methods: ", c->prog, opt, val,
            opt_nearest(val, eomc_methods, n, ""));
    opt_list_names(stderr, eomc_methods, n, "");
    fprintf(stderr, "\n");
    return -1;
}

/* A comma-separated list of positive numbers, into a new array. */
static int
number_list(Options *c, const char *opt, const char *val, double **out, int *count)
{
    size_t cap = strlen(val) / 2 + 2;
    double *x = calloc(cap, sizeof *x);
    char *copy = strdup(val), *save = NULL;
    int n = 0, rc = EOMC_OK;
    if (!x || !copy)
        rc = opt_usage(c, "out of memory");
    for (char *w = copy ? strtok_r(copy, ",", &save) : NULL; w && rc == EOMC_OK;
         w = strtok_r(NULL, ",", &save))
        rc = real_option(c, opt, w, &x[n++], 0, 1);
    if (rc == EOMC_OK && n == 0)
        rc = opt_usage(c, "%s: expected a comma-separated list of numbers, not '%s'", opt, val);
    free(copy);
    free(*out);
    *out = rc == EOMC_OK ? x : (free(x), NULL);
    *count = rc == EOMC_OK ? n : 0;
    return rc;
}

static int
method_list(Options *c, const char *val)
{
    size_t cap = strlen(val) / 2 + 2;
    const char **m = calloc(cap, sizeof *m);
    char *copy = strdup(val), *save = NULL;
    int n = 0, rc = EOMC_OK;
    if (!m || !copy)
        rc = opt_usage(c, "out of memory");
    for (char *w = copy ? strtok_r(copy, ",", &save) : NULL; w && rc == EOMC_OK;
         w = strtok_r(NULL, ",", &save)) {
        int k = method_index(c, "--methods", w);
        if (k < 0)
            rc = EOMC_EUSAGE;
        else
            m[n++] = eomc_methods[k];
    }
    if (rc == EOMC_OK && n == 0)
        rc = opt_usage(c, "--methods: expected a comma-separated list of methods");
    free(copy);
    free(c->methods);
    c->methods = rc == EOMC_OK ? m : (free(m), NULL);
    return rc;
}

static int
take_value(Options *c, int k, const char *val)
{
    eomc_run_opts *r = &c->run;
    const char *opt = option_names[k];
    double x;
    if (k >= O_METHODS && k <= O_TARGET)
        c->report_given |= 1u << (k - O_METHODS);
    switch (k) {
    case O_T0:
        if (!number(val, &r->t0))
            return opt_usage(c, "%s: '%s' is not a finite number", opt, val);
        c->t0_given = 1;
        return EOMC_OK;
    case O_T_END:
        if (!number(val, &r->t_end))
            return opt_usage(c, "%s: '%s' is not a finite number", opt, val);
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
            return opt_usage(c, "%s: '%s' is not a whole number of steps (1 or more)", opt, val);
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
        return opt_usage(c, "--stabilize: unknown method '%s'%s; methods: none, baumgarte, "
                     "project", val, opt_nearest(val, stabilize_names, 3, ""));
    case O_BAUMGARTE: {
        char *comma = strchr(val, ','), *a = strndup(val, comma ? (size_t)(comma - val) : 0);
        int bad = !comma || !a || !number(a, &c->alpha) || !number(comma + 1, &c->beta);
        free(a);
        if (bad)
            return opt_usage(c, "--baumgarte: expected ALPHA,BETA (two numbers), not '%s'", val);
        if (c->alpha < 0 || c->beta < 0)
            return opt_usage(c, "--baumgarte: %s is out of range (the rates must be >= 0)",
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
            return opt_usage(c, "--threads: '%s' is not a whole number from 1 to %d", val,
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
check_combination(Options *c)
{
    if (c->rates_given && c->stabilize < 0)
        c->stabilize = EOMC_STABILIZE_BAUMGARTE;
    if (c->rates_given && c->stabilize != EOMC_STABILIZE_BAUMGARTE)
        return opt_usage(c, "--baumgarte gives the rates of --stabilize baumgarte, not of "
                     "--stabilize %s", stabilize_names[c->stabilize]);
    if (c->stabilize < 0)
        c->stabilize = EOMC_STABILIZE_NONE;
    if (c->reference || c->errors)
        c->error = 1;
    int linear = c->linearize || c->equilibrium;
    /* the spec's t_end must be > 0; a run's end must come after its start
     * alike (a run of no time writes one row, which no one means) */
    if (!(c->run.t_end > c->run.t0))
        return opt_usage(c, "%s %g must be after the start time %g%s",
                     c->t_end_given ? "--t-end" : "the scene's t_end", c->run.t_end,
                     c->run.t0, c->t0_given ? " (--t0)" : "");
    if (c->nsweep && c->sweep_file)
        return opt_usage(c, "--sweep and --sweep-file: one or the other");
    if (c->nsweep || c->sweep_file) {
        const char *clash = c->work_precision ? "--work-precision" : c->equilibrium
                            ? "--equilibrium" : c->linearize && c->csv
                            ? "--csv (a sweep of --linearize writes its rows with -o)" : c->accel
                            ? "--accel" : c->error ? "--error" : c->reference_out
                            ? "--reference-out" : c->events ? "--events" : c->plot
                            ? "--plot" : c->summary ? "--summary" : c->stats ? "--stats"
                            : NULL;
        if (clash)
            return opt_usage(c, "a sweep (%s) writes one %s row per run: it does not take %s",
                         c->nsweep ? "--sweep" : "--sweep-file",
                         c->linearize ? "linearization's" : "summary", clash);
    } else if (c->threads > 1) {
        return opt_usage(c, "--threads runs the runs of a sweep (--sweep, --sweep-file) at once");
    }
    if (c->no_assemble && (c->assemble || c->hold))
        return opt_usage(c, "--no-assemble starts from the initial state as given: it does not "
                     "take %s", c->assemble ? "--assemble" : "--hold");
    if (c->hold && !c->assemble && !c->scene_assembles)
        return opt_usage(c, "--hold belongs to --assemble: it names what the projection "
                     "onto the constraints keeps as it is");
    /* the scene's `assemble:` unless --no-assemble; --hold replaces its list */
    c->assemble = !c->no_assemble && (c->assemble || c->hold || c->scene_assembles);
    int run_plot = c->plot && !c->work_precision && !linear && !c->accel;
    if (run_plot && !plot_format_ok(c->plot))
        return opt_usage(c, "--plot: '%s' is neither .svg nor .png", c->plot);
    if (run_plot && !plot_have_gnuplot())
        return opt_usage(c, "--plot: gnuplot is not installed (Debian: apt-get install "
                     "gnuplot-nox)");
    for (int k = O_METHODS; k <= O_TARGET && !c->work_precision; k++) {
        if (!(c->report_given >> (k - O_METHODS) & 1) || (k == O_CSV && linear) ||
            (k == O_PLOT && run_plot))
            continue;
        if (k == O_CSV)
            return opt_usage(c, "--csv belongs to --work-precision, --linearize or "
                         "--equilibrium (one run writes its trajectory with -o)");
        if (k == O_PLOT)
            return opt_usage(c, "--plot draws a run or the --work-precision report, not %s",
                         c->accel ? "--accel" : "--linearize or --equilibrium");
        return opt_usage(c, "%s belongs to --work-precision (one run writes its trajectory "
                     "with -o)", option_names[k]);
    }
    int swept = c->nsweep || c->sweep_file; /* a sweep's rows go to -o */
    if (linear && (c->accel || c->work_precision || c->error || (c->out && !swept) ||
                   c->events))
        return opt_usage(c, "--%s does not integrate: it does not take %s",
                     c->linearize ? "linearize" : "equilibrium",
                     c->accel ? "--accel" : c->work_precision ? "--work-precision"
                     : c->error ? "--error" : c->out ? "-o (use --csv FILE)" : "--events");
    if (c->work_precision) {
        const char *clash = c->accel ? "--accel" : c->out ? "-o" : c->method_given
                          ? "--method (--methods chooses the report's)" : c->fixed_given
                          ? "--fixed-step (--steps chooses the report's)" : NULL;
        if (clash)
            return opt_usage(c, "--work-precision does not take %s", clash);
        if (c->plot && !plot_format_ok(c->plot))
            return opt_usage(c, "--plot: '%s' is neither .svg nor .png", c->plot);
        if (c->plot && !plot_have_gnuplot())
            return opt_usage(c, "--plot: gnuplot is not installed (Debian: apt-get install "
                         "gnuplot-nox)");
    }
    if (c->accel && (c->error || c->reference_out))
        return opt_usage(c, "--accel does not integrate: nothing to measure against a "
                     "reference");
    return EOMC_OK;
}

/* NAME=VALUE split; *name is a copy to free. */
static int
name_value(Options *c, const char *opt, const char *arg, char **name, double *x)
{
    const char *eq = strchr(arg, '=');
    if (!eq || eq == arg)
        return opt_usage(c, "%s: expected NAME=VALUE, not '%s'", opt, arg);
    if (!number(eq + 1, x))
        return opt_usage(c, "%s %s: '%s' is not a finite number", opt, arg, eq + 1);
    *name = strndup(arg, (size_t)(eq - arg));
    return EOMC_OK;
}

int
opt_apply_sets(Options *c, eomc_sim *sim)
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
            const char *hint = opt_nearest(name, m->p_names, m->np, "");
            if (!*hint)
                hint = opt_nearest(name, m->u_names, m->nu, "");
            fprintf(stderr, "%s: --set: '%s' is not a parameter or input%s; "
                    "parameters: ", c->prog, name, hint);
            opt_list_names(stderr, m->p_names, m->np, "");
            fprintf(stderr, m->nu ? "; inputs: " : "; no inputs");
            opt_list_names(stderr, m->u_names, m->nu, "");
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
 * stderr with the opt_nearest name. */
static int
state_index(Options *c, const eomc_model *m, const char *opt, const char *name)
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
            opt, name, opt_nearest(name, m->q_names, n, vel ? "'" : ""));
    opt_list_names(stderr, m->q_names, n, "");
    fprintf(stderr, ", ");
    opt_list_names(stderr, m->q_names, n, "'");
    fprintf(stderr, "\n");
    return -1;
}

int
opt_apply_inits(Options *c, const eomc_model *m, double *x)
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

int
opt_stabilize(Options *c, eomc_sim *sim)
{
    if (c->stabilize == EOMC_STABILIZE_NONE ||
        eomc_sim_stabilize(sim, c->stabilize, c->alpha, c->beta) == EOMC_OK)
        return EOMC_OK;
    return opt_usage(c, "--stabilize %s: %s", stabilize_names[c->stabilize],
                 eomc_sim_error(sim));
}

/* --hold LIST into hold [2n]: x marks q_x, x' marks q'_x. */
static int
hold_list(Options *c, const eomc_model *m, unsigned char *hold)
{
    for (const char *p = c->hold; *p;) {
        size_t len = strcspn(p, ",");
        char name[256];
        if (len == 0 || len >= sizeof name)
            return opt_usage(c, "--hold: '%s' is not a list of coordinates (x) and velocities "
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
int
opt_held_marks(Options *c, const eomc_model *m)
{
    size_t n = (size_t)m->nq;
    if (!(c->held = calloc(2 * n, 1)))
        return opt_usage(c, "out of memory");
    if (c->hold && hold_list(c, m, c->held) != EOMC_OK)
        return EOMC_EUSAGE;
    if (!c->hold && m->a_hold)
        memcpy(c->held, m->a_hold, 2 * n);
    if (c->equilibrium)
        memset(c->held + n, 0, n);
    return EOMC_OK;
}

/* The reference solution follows the equations, not the events that
 * stop or reset the motion: with those, there is nothing to measure
 * against. */
static int
check_event_options(const Options *c, const eomc_model *m)
{
    int moving = 0;
    for (int k = 0; k < m->nevent; k++)
        moving |= m->ev_action[k] != EOMC_EVENT_RECORD;
    const char *opt = c->work_precision ? "--work-precision"
                      : c->reference    ? "--reference"
                      : c->error        ? "--error"
                      : c->reference_out ? "--reference-out" : NULL;
    if (moving && opt)
        return opt_usage(c, "%s: scene %s has events that stop or reset the motion, which the "
                     "reference solution does not follow (measure the errors on a scene "
                     "without them)", opt, *m->scene ? m->scene : "(the spec's)");
    if (c->events && m->nevent == 0)
        return opt_usage(c, "--events: scene %s has no events", *m->scene ? m->scene
                                                                     : "(the spec's)");
    if (c->events && (c->work_precision || c->accel))
        return opt_usage(c, "--events belongs to a run (not %s)",
                     c->accel ? "--accel" : "--work-precision");
    return EOMC_OK;
}

int
opt_parse(Options *c, int argc, char **argv, const eomc_model *m)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i], *eq = strchr(arg, '='), *val = NULL;
        size_t len = eq && arg[0] == '-' ? (size_t)(eq - arg) : strlen(arg);
        int k = find_option(arg, len);
        if (k < 0) {
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)(len < 100 ? len : 100), arg);
            if (arg[0] != '-')
                return opt_usage(c, "unexpected argument '%s' (options start with --)", arg);
            return opt_usage(c, "unknown option '%s'%s", name,
                         opt_nearest(name, option_names, NOPTIONS, ""));
        }
        if (k >= FIRST_FLAG) {
            if (eq)
                return opt_usage(c, "%s takes no value", option_names[k]);
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
            return opt_usage(c, "%s needs a value", option_names[k]);
        int rc = take_value(c, k, val);
        if (rc)
            return rc;
    }
    c->scene_assembles = m->assemble;
    int rc = check_combination(c);
    return rc == EOMC_OK ? check_event_options(c, m) : rc;
}

int
opt_init(Options *c, int argc, char **argv, const eomc_model *m)
{
    const char *slash = argc > 0 ? strrchr(argv[0], '/') : NULL;
    *c = (Options){0};
    c->stabilize = -1;
    c->alpha = c->beta = DEFAULT_RATE;
    c->target = NAN;
    c->prog = argc > 0 ? (slash ? slash + 1 : argv[0]) : m->name;
    c->self = getenv("EOMC_RUN_COMMAND") ? getenv("EOMC_RUN_COMMAND") : c->prog;
    c->run = eomc_run_defaults(m);
    c->threads = 1;
    /* every argument at most once in each list */
    c->set = calloc((size_t)argc + 1, sizeof *c->set);
    c->init = calloc((size_t)argc + 1, sizeof *c->init);
    c->sweep = calloc((size_t)argc + 1, sizeof *c->sweep);
    return c->set && c->init && c->sweep ? 0 : -1;
}

void
opt_free(Options *c)
{
    free(c->set);
    free(c->init);
    free(c->sweep);
    free(c->methods);
    free(c->tolerances);
    free(c->steps);
    free(c->held);
}

/*
 * options: the command line read into an Options, and checked (options.h).
 *
 * Parameters are set before the initial state is computed (it may depend
 * on them), and --init overrides that state afterwards, whatever the
 * order on the line.
 */
#include "options.h"
#include "base/io.h"
#include "option_table.h"
#include "base/nearest.h"
#include "model/state.h"
#include "animate.h"
#include "analysis/plot.h"

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
    fprintf(io_err(), "%s: ", c->prog);
    va_start(ap, fmt);
    vfprintf(io_err(), fmt, ap);
    va_end(ap);
    fprintf(io_err(), "\n(see %s --help)\n", c->self);
    return EOMC_EUSAGE;
}

/* " (did you mean 'x'?)" for the nearest of names[0..n) (suffixed), every
 * one as near ("'rk4' or 'rkf45'"), or "": the compiler's rule
 * (nearest.h). */
const char *
opt_nearest(const char *word, const char *const *names, int n, const char *suffix)
{
    /* the thread's own: simulators run in several threads at once
     * (eomc_main_mem) */
    static _Thread_local char buf[600];
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

static const char *const stabilize_names[] = {"none", "baumgarte", "project"};
/* More threads than this are a typo, not a machine. */
enum { MAX_THREADS = 1024 };

const char *
opt_stabilize_name(int method)
{
    return stabilize_names[method];
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
    fprintf(io_err(), "%s: %s: unknown method '%s'%s; methods: ", c->prog, opt, val,
            opt_nearest(val, eomc_methods, n, ""));
    opt_list_names(io_err(), eomc_methods, n, "");
    fprintf(io_err(), "\n");
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
    const char *opt = option_name(k);
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
    case O_OUT: c->out = strcmp(val, "-") ? val : NULL; return EOMC_OK; /* "-": stdout */
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
    case O_REFERENCE_METHOD: {
        static const char *const ways[] = {"extrapolation", "taylor"};
        for (int j = 0; j < 2; j++)
            if (strcmp(val, ways[j]) == 0) {
                c->reference_method = j; /* EOMC_REFERENCE_EXTRAPOLATION, _TAYLOR */
                return EOMC_OK;
            }
        return opt_usage(c, "--reference-method: unknown way '%s'%s; ways: extrapolation, "
                         "taylor", val, opt_nearest(val, ways, 2, ""));
    }
    case O_EVENTS: c->events = val; return EOMC_OK;
    case O_ANIMATE: c->animate = val; return EOMC_OK;
    case O_SWEEP: c->sweep[c->nsweep++] = (char *)val; return EOMC_OK;
    case O_SWEEP_FILE: c->sweep_file = val; return EOMC_OK;
    case O_THREADS:
        if (!number(val, &x) || x != floor(x) || x < 1 || x > MAX_THREADS)
            return opt_usage(c, "--threads: '%s' is not a whole number from 1 to %d", val,
                         MAX_THREADS);
        c->threads = (int)x;
        return EOMC_OK;
    case O_BATCH:
        if (!number(val, &x) || (x != 1 && x != EOMC_LANES))
            return opt_usage(c, "--batch: '%s' is not 1 or %d (a vector's lanes)", val,
                             EOMC_LANES);
        c->batch = (int)x;
        c->batch_given = 1;
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
    } else if (c->batch_given) {
        return opt_usage(c, "--batch runs the runs of a sweep (--sweep, --sweep-file) together");
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
                     "with -o)", option_name(k));
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
            fprintf(io_err(), "%s: --set: %s\n", c->prog, eomc_sim_error(sim));
            free(name);
            return EOMC_EUSAGE;
        } else if (rc != EOMC_OK) {
            const char *hint = opt_nearest(name, m->p_names, m->np, "");
            if (!*hint)
                hint = opt_nearest(name, m->u_names, m->nu, "");
            fprintf(io_err(), "%s: --set: '%s' is not a parameter or input%s; "
                    "parameters: ", c->prog, name, hint);
            opt_list_names(io_err(), m->p_names, m->np, "");
            fprintf(io_err(), m->nu ? "; inputs: " : "; no inputs");
            opt_list_names(io_err(), m->u_names, m->nu, "");
            fprintf(io_err(), "\n");
            free(name);
            return EOMC_EUSAGE;
        }
        free(name);
    }
    if (eomc_sim_check(sim) != EOMC_OK) {
        fprintf(io_err(), "%s: --set: %s\n", c->prog, eomc_sim_error(sim));
        return EOMC_EUSAGE;
    }
    return EOMC_OK;
}

/* NAME (a coordinate) or a speed's name (NAME', a coordinate's velocity;
 * the model's own, "root_wx", where the speeds are not the rates) given to
 * option opt: its index in the state (i, or nq + k), or -1 when it names
 * neither, said on stderr with the opt_nearest name. */
static int
state_index(Options *c, const eomc_model *m, const char *opt, const char *name)
{
    int n = m->nq, rate, i = state_find(m, name, &rate);
    const char *speeds = state_speed_word(m, 1);
    if (i >= 0 && rate) {
        fprintf(io_err(), "%s: %s: '%s' is an acceleration: only coordinates (x) and "
                "%s (%s) make the initial state; the accelerations follow from "
                "the equations\n", c->prog, opt, name, speeds, m->nv > 0 ? m->v_names[0] : "x'");
        return -1;
    }
    if (i >= 0)
        return i;
    size_t len = strlen(name);
    int vel = len > 1 && name[len - 1] == '\'';
    if (m->nv > 0) { /* the speeds have names of their own */
        const char *near = opt_nearest(name, m->v_names, m->nv, "");
        if (!*near)
            near = opt_nearest(name, m->q_names, n, "");
        fprintf(io_err(), "%s: %s: '%s' is not a coordinate or speed%s; valid names: ",
                c->prog, opt, name, near);
        opt_list_names(io_err(), m->q_names, n, "");
        fprintf(io_err(), ", ");
        opt_list_names(io_err(), m->v_names, m->nv, "");
        fprintf(io_err(), "\n");
        return -1;
    }
    fprintf(io_err(), "%s: %s: '%s' is not a coordinate or velocity%s; valid names: ", c->prog,
            opt, name, opt_nearest(name, m->q_names, n, vel ? "'" : ""));
    opt_list_names(io_err(), m->q_names, n, "");
    fprintf(io_err(), ", ");
    opt_list_names(io_err(), m->q_names, n, "'");
    fprintf(io_err(), "\n");
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

/* --hold LIST into hold [nq + nv]: x marks q_x, a speed's name the speed. */
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

/* What the assembly keeps, into c->held [nq + nv]: --hold's list, else
 * the scene's (model->a_hold), else nothing.  An equilibrium has no
 * velocity (eomc_sim_equilibrium sets them to zero): it keeps held
 * positions only. */
int
opt_held_marks(Options *c, const eomc_model *m)
{
    size_t n = (size_t)m->nq, nx = (size_t)eomc_nx(m);
    if (!(c->held = calloc(nx, 1)))
        return opt_usage(c, "out of memory");
    if (c->hold && hold_list(c, m, c->held) != EOMC_OK)
        return EOMC_EUSAGE;
    if (!c->hold && m->a_hold)
        memcpy(c->held, m->a_hold, nx);
    if (c->equilibrium)
        memset(c->held + n, 0, nx - n);
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
    if (c->events && m->nevent == 0 && m->nmode == 0)
        return opt_usage(c, "--events: scene %s has no events", *m->scene ? m->scene
                                                                     : "(the spec's)");
    if (c->events && (c->work_precision || c->accel))
        return opt_usage(c, "--events belongs to a run (not %s)",
                     c->accel ? "--accel" : "--work-precision");
    return EOMC_OK;
}

/* --animate: one run, of a model with something to draw, and three.js
 * there to draw it with; all known before the run starts. */
static int
check_animate(const Options *c, const eomc_model *m)
{
    if (!c->animate)
        return EOMC_OK;
    const char *clash = c->nsweep ? "--sweep" : c->sweep_file ? "--sweep-file"
                        : c->work_precision ? "--work-precision" : c->accel ? "--accel"
                        : c->linearize ? "--linearize" : c->equilibrium ? "--equilibrium"
                        : NULL;
    if (clash)
        return opt_usage(c, "--animate draws one run: it does not take %s", clash);
    char buf[1024];
    const char *why = anim_cannot(m, buf, sizeof buf);
    return why ? opt_usage(c, "%s", why) : EOMC_OK;
}

/* --batch N > 1, given: runs share a series, by Taylor's method, where
 * the model has its series for the lanes (eomc_model.h's taylor_run4). */
static int
check_batch(const Options *c, const eomc_model *m)
{
    if (!c->batch_given || c->batch == 1)
        return EOMC_OK;
    if (c->linearize)
        return opt_usage(c, "--batch %d runs integrations together; a sweep of --linearize "
                         "integrates none", c->batch);
    if (strcmp(c->run.method, "taylor") != 0)
        return opt_usage(c, "--batch %d: runs share a series by Taylor's method alone "
                         "(--method taylor), not by %s", c->batch, c->run.method);
    if (!m->taylor_run4)
        return opt_usage(c, "--batch %d: %s has no series for %d runs at once (that needs a "
                         "constant diagonal M, no constraints, a series short enough to be "
                         "optimized, and a C compiler with GCC's vectors); --batch 1 runs "
                         "them one at a time", c->batch, m->name, c->batch);
    return EOMC_OK;
}

int
opt_parse(Options *c, int argc, char **argv, const eomc_model *m)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i], *eq = strchr(arg, '='), *val = NULL;
        size_t len = eq && arg[0] == '-' ? (size_t)(eq - arg) : strlen(arg);
        int k = option_find(arg, len);
        if (k < 0) {
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)(len < 100 ? len : 100), arg);
            if (arg[0] != '-')
                return opt_usage(c, "unexpected argument '%s' (options start with --)", arg);
            const char *names[NOPTIONS];
            for (int j = 0; j < NOPTIONS; j++)
                names[j] = option_name(j);
            return opt_usage(c, "unknown option '%s'%s", name,
                         opt_nearest(name, names, NOPTIONS, ""));
        }
        if (k >= FIRST_FLAG) {
            if (eq)
                return opt_usage(c, "%s takes no value", option_name(k));
            if (k == O_HELP) {
                option_help(c->self, m);
                return -1;
            }
            if (k == O_VERSION) {
                fprintf(io_out(),
                        "%s: model %s from %s, %s form%s%s; eomc runtime %s\n", c->prog,
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
            return opt_usage(c, "%s needs a value", option_name(k));
        int rc = take_value(c, k, val);
        if (rc)
            return rc;
    }
    c->scene_assembles = m->assemble;
    int rc = check_combination(c);
    if (rc == EOMC_OK)
        rc = check_batch(c, m);
    if (rc == EOMC_OK)
        rc = check_event_options(c, m);
    return rc == EOMC_OK ? check_animate(c, m) : rc;
}

int
opt_init(Options *c, int argc, char **argv, const eomc_model *m)
{
    const char *slash = argc > 0 ? strrchr(argv[0], '/') : NULL;
    *c = (Options){0};
    c->stabilize = -1;
    c->alpha = c->beta = OPTION_DEFAULT_RATE;
    c->target = NAN;
    c->prog = argc > 0 ? (slash ? slash + 1 : argv[0]) : m->name;
    c->self = getenv("EOMC_RUN_COMMAND") ? getenv("EOMC_RUN_COMMAND") : c->prog;
    c->run = eomc_run_defaults(m);
    c->threads = 1;
    c->batch = EOMC_LANES;
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

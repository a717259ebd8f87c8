/*
 * cli: the command line of a standalone simulator (eomc_main): what it
 * does once options.c has read and checked the line.
 *
 * Three things a simulator does: one run written as CSV (the default),
 * the accelerations at the initial state (--accel), and the
 * work-precision report of report.c (--work-precision).  A run can also
 * be measured against the reference solution (--error), which both of
 * the last two share.  Besides: a sweep of runs (sweep.c) and the
 * linearization (stability.c).
 */
#include "eomc.h"
#include "animate.h"
#include "assembly.h"
#include "analysis/compare.h"
#include "base/io.h"
#include "base/numfmt.h"
#include "model/state.h"
#include "options.h"
#include "plan.h"
#include "analysis/plot.h"
#include "analysis/report.h"
#include "rows.h"
#include "signals.h"
#include "stability.h"
#include "summary.h"
#include "sweep.h"

#include <errno.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The report's tolerances: 1e-3, 1e-4, ..., 1e-13 (rtol = atol). */
enum { TOL_FIRST_EXP = 3, TOL_LAST_EXP = 13 };
/* Its fixed steps: these fractions of the time span. */
static const double default_steps[] = {1e-2, 1e-3, 1e-4};


static int
print_accel(Options *c, eomc_sim *sim, const eomc_model_ext *ext, const double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    int nv = eomc_nv(m);
    double *a = calloc((size_t)nv + (size_t)m->nc + 1, sizeof *a), *lam = a + nv;
    char num[NUM_MAX], name[STATE_NAME_MAX];
    assembly_check(c, sim, x); /* the accelerations of a state the model never reaches */
    int rc = c->accel_extended ? eomc_reference_accel(sim, ext, c->run.t0, x, a, lam)
                               : eomc_sim_accel(sim, c->run.t0, x, x + m->nq, a);
    if (rc == EOMC_OK) {
        for (int i = 0; i < nv; i++) /* each speed's rate: x'', root_wx' */
            fprintf(io_out(), "%s %s\n", state_rate(m, i, name, sizeof name),
                    num_shortest(num, a[i]));
        for (int k = 0; k < m->nc; k++)
            fprintf(io_out(), "lambda[%s] %s\n", m->c_names[k],
                    num_shortest(num, c->accel_extended ? lam[k] : eomc_sim_multipliers(sim)[k]));
    } else
        fprintf(io_err(), "%s: error: %s\n", c->prog, eomc_sim_error(sim));
    free(a);
    return rc;
}

static int
sweep_prepare(void *ctx, eomc_sim *sim)
{
    Options *c = ctx;
    int rc = opt_apply_sets(c, sim);
    return rc == EOMC_OK ? opt_stabilize(c, sim) : rc;
}

/* Each run's initial state as the single run's: the spec's, --init, and
 * --assemble's projection (quietly: a sweep's rows say what it did). */
static int
sweep_initial(void *ctx, eomc_sim *sim, double *x)
{
    Options *c = ctx;
    const eomc_model *m = eomc_sim_model(sim);
    eomc_sim_initial(sim, x, x + m->nq);
    int rc = opt_apply_inits(c, m, x);
    if (rc == EOMC_OK) /* quietly: a run's failure is its row's status */
        rc = assembly_unit(c, m, x, 1);
    /* each run assembled with its own parameters, quietly: a failure is
     * the run's status */
    if (rc == EOMC_OK && c->assemble)
        rc = eomc_sim_project_held(sim, c->run.t0, x, x + m->nq, c->held);
    return rc;
}

static int
sweep(Options *c, eomc_sim *sim)
{
    const eomc_model *m = eomc_sim_model(sim);
    Plan pl;
    int rc = plan_make(c, m, &pl);
    FILE *f = NULL;
    if (rc == EOMC_OK && eomc_run_check(sim, &c->run) != EOMC_OK)
        rc = opt_usage(c, "%s", eomc_sim_error(sim));
    if (rc == EOMC_OK && !(f = rows_open(c->prog, "-o", c->out)))
        rc = EOMC_EUSAGE;
    char *columns = NULL;
    if (rc == EOMC_OK && c->linearize && !(columns = stab_columns(eomc_sim_linear_size(sim))))
        rc = opt_usage(c, "out of memory");
    if (rc == EOMC_OK) {
        c->run.on_progress = NULL;
        Sweep sw = {m, &c->run, sweep_prepare, sweep_initial, c, pl.nparam, pl.names,
                    pl.nruns, pl.values, c->threads, c->batch, c->prog,
                    c->linearize ? stab_cells : NULL, columns,
                    c->linearize ? 2 * eomc_sim_linear_size(sim) : 0};
        rc = sweep_run(&sw, f);
        if (rows_close(c->prog, f, c->out))
            rc = rc ? rc : EOMC_EUSAGE;
    }
    free(columns);
    plan_free(&pl);
    return rc;
}

/* The reference solution: read (--reference) or computed; written out
 * when --reference-out asks.  EOMC_OK or an exit status. */
static int
get_reference(Options *c, eomc_sim *sim, const eomc_model_ext *ext, const double *x,
              eomc_reference *ref)
{
    const eomc_model *m = eomc_sim_model(sim);
    int rc;
    if (c->reference)
        rc = eomc_reference_read(sim, c->reference, &c->run, ref);
    else if (!ext)
        return opt_usage(c, "%s was built without its extended-precision functions, so it "
                     "cannot compute a reference solution: rebuild with `eomc build %s "
                     "--extended` (or give --reference FILE)", m->name, m->spec);
    else
        rc = eomc_reference_compute_by(sim, ext, &c->run, x, c->reference_method, ref);
    if (rc != EOMC_OK) {
        fprintf(io_err(), "%s: %s%s\n", c->prog, rc == EOMC_ENUMERIC ? "error: " : "",
                eomc_sim_error(sim));
        return rc;
    }
    if (c->reference_out) {
        Rows w = rows_new(rows_open(c->prog, "--reference-out", c->reference_out), sim);
        if (!w.f || !w.res) {
            rows_free(&w);
            eomc_reference_free(ref);
            return EOMC_EUSAGE;
        }
        rows_header(w.f, m);
        rc = EOMC_OK;
        for (long k = 0; k < ref->nrows && rc == EOMC_OK; k++)
            rc = rows_write(&w, ref->t[k], ref->x + (size_t)k * (size_t)ref->nx);
        rows_flush(&w);
        if (rc != EOMC_OK)
            fprintf(io_err(), "%s: --reference-out: %s\n", c->prog, eomc_sim_error(sim));
        if (rows_close(c->prog, w.f, c->reference_out) && rc == EOMC_OK)
            rc = EOMC_EUSAGE;
        rows_free(&w);
        if (rc != EOMC_OK)
            eomc_reference_free(ref);
    }
    return rc;
}

/* The files of a run: -o's, --events' and --plot's copy of the rows
 * (data, a template mkstemp fills in; *fd its descriptor), their headers
 * written.  All open, or none left behind. */
static int
open_files(const Options *c, Rows *w, char *data, int *fd)
{
    const eomc_model *m = eomc_sim_model(w->sim);
    if (c->events && !(w->events = rows_open(c->prog, "--events", c->events)))
        return EOMC_EUSAGE;
    if (!(w->f = rows_open(c->prog, "-o", c->out))) {
        if (w->events) {
            fclose(w->events);
            unlink(c->events);
        }
        w->events = NULL;
        return EOMC_EUSAGE;
    }
    if (c->plot && ((*fd = mkstemp(data)) < 0 || !(w->tee = fdopen(*fd, "w")))) {
        fprintf(io_err(), "%s: --plot: cannot write its data: %s\n", c->prog, strerror(errno));
        if (*fd >= 0)
            close(*fd);
        rows_close(c->prog, w->f, c->out);
        if (c->out)
            unlink(c->out);
        if (w->events) {
            fclose(w->events);
            unlink(c->events);
        }
        w->f = w->events = NULL;
        return EOMC_EUSAGE;
    }
    if (w->events)
        rows_events_header(w->events, m);
    if (w->csv)
        rows_header(w->f, m);
    if (w->tee)
        rows_header(w->tee, m);
    /* whole blocks of rows, one write each: no half row in the file (a
     * stream in memory, eomc_main_mem's, has no file, and glibc's cannot
     * be unbuffered) */
    if (fileno(w->f) >= 0)
        setvbuf(w->f, NULL, _IONBF, 0);
    if (w->tee)
        setvbuf(w->tee, NULL, _IONBF, 0);
    return EOMC_OK;
}

/* What is said and written after a run that ended with rc (not a
 * signal): its files closed, the error, the warnings, --stats, --summary,
 * --error, --errors FILE and --plot.  Returns the exit status. */
static int
after_run(Options *c, Rows *w, const eomc_stats *st, const eomc_reference *ref,
          const char *data, int rc)
{
    const eomc_model *m = eomc_sim_model(w->sim);
    if (rows_close(c->prog, w->f, c->out))
        rc = rc ? rc : EOMC_ENUMERIC;
    if (w->events && rows_close(c->prog, w->events, c->events))
        rc = rc ? rc : EOMC_ENUMERIC;
    w->f = w->events = NULL;
    if (rc)
        fprintf(io_err(), "%s: error: %s\n", c->prog, eomc_sim_error(w->sim));
    if (rc == EOMC_ENUMERIC)
        summary_kept(c, w);
    if (w->ref && !rc) /* the run's flips against the reference's (fixed steps: no tolerance) */
        compare_switches(&w->cmp, c->run.h_fixed > 0 ? 0 : c->run.rtol,
                         c->run.h_fixed > 0 ? 0 : c->run.atol, c->run.t0, c->run.t_end);
    summary_warnings(c, m, st, w);
    if (c->stats)
        summary_stats(w, st, c->stabilize);
    if (c->summary && !rc)
        summary_text(c, m, w, st);
    /* with --stats too: its lines carry the figures, not the component
     * that keeps the fewest digits */
    if (c->error && !rc && !c->summary)
        summary_error(c, m, w, ref);
    if (c->errors) {
        FILE *f = rows_open(c->prog, "--errors", c->errors);
        if (f) {
            compare_csv_header(f);
            compare_csv_run(f, m, w->cmp.scale, rc ? NULL : w->cmp.end, rc ? NULL : w->cmp.max,
                            c->run.method, c->run.rtol, c->run.h_fixed > 0 ? st->h_used : 0);
        }
        if (!f || rows_close(c->prog, f, c->errors))
            rc = rc ? rc : EOMC_EUSAGE;
    }
    if (w->tee) {
        int resets = 0;
        for (int k = 0; k < m->nevent; k++)
            resets |= m->ev_action[k] == EOMC_EVENT_SET;
        /* the rows written, also those before a failure */
        int bad = fclose(w->tee) != 0;
        w->tee = NULL;
        if (bad || (w->rows > 0 && plot_trajectory(c->prog, m, data, c->plot, w->h_first,
                                                   resets, w->out_max) != EOMC_OK))
            rc = rc ? rc : EOMC_EUSAGE;
    }
    return rc;
}

/* The rows of a run with --animate: each to the CSV, then, written, to
 * the page's collection (the outputs are the row's). */
typedef struct AnimRows {
    Rows *w;
    Anim *a;
} AnimRows;

static int
animate_row(void *ctx, double t, const double *x)
{
    AnimRows *r = ctx;
    int rc = rows_write(r->w, t, x);
    if (rc == EOMC_OK || rc == SIGNALS_STOPPED)
        anim_row(r->a, t, x, r->w->res + eomc_sim_model(r->w->sim)->nc);
    return rc;
}

/* The rows kept in memory handed to extra, with the header's names: 0,
 * or -1 when memory runs out. */
static int
rows_to_extra(Rows *w, eomc_main_extra *extra)
{
    size_t len = 0;
    FILE *f = open_memstream(&extra->columns, &len);
    if (!f)
        return -1;
    rows_header(f, eomc_sim_model(w->sim));
    if (fclose(f) != 0 || !extra->columns)
        return -1;
    if (len > 0 && extra->columns[len - 1] == '\n')
        extra->columns[len - 1] = '\0';
    extra->rows = w->mem, extra->nrows = w->mem_rows, extra->ncols = w->ncols;
    w->mem = NULL;
    return 0;
}

/* One run written as CSV: the reference when measured against one, the
 * files, the run, what is said of it; one cleanup.  SIGINT and SIGTERM
 * stop the run at a row when catch_signals (eomc_main: the program's
 * signals); a caller that is not a program keeps its own handlers. */
static int
simulate(Options *c, eomc_sim *sim, const eomc_model_ext *ext, double *x, int catch_signals,
         eomc_main_extra *extra)
{
    if (eomc_run_check(sim, &c->run) != EOMC_OK) /* before any file is written */
        return opt_usage(c, "%s", eomc_sim_error(sim));
    eomc_reference ref = {0};
    eomc_stats st;
    char data[] = "/tmp/eomc-rows-XXXXXX";
    int fd = -1;
    Rows w = rows_new(NULL, sim);
    if (extra && extra->rows_in_memory) /* numbers, and CSV only into -o FILE */
        w.in_memory = 1, w.csv = c->out != NULL;
    Anim *anim = c->animate ? anim_new(sim, c->animate) : NULL;
    int rc = w.res && (anim || !c->animate) ? EOMC_OK : opt_usage(c, "out of memory");
    AnimRows ar = {&w, anim};
    if (rc == EOMC_OK)
        assembly_check(c, sim, x);
    if (rc == EOMC_OK && (c->error || c->reference_out))
        rc = get_reference(c, sim, ext, x, &ref);
    if (rc == EOMC_OK && c->error && compare_init(&w.cmp, &ref, eomc_sim_model(sim)->nq) != 0) {
        fprintf(io_err(), "%s: out of memory\n", c->prog);
        rc = EOMC_EUSAGE;
    }
    if (c->error)
        w.ref = &ref;
    if (rc == EOMC_OK)
        rc = open_files(c, &w, data, &fd);
    if (rc == EOMC_OK) {
        Progress pr;
        summary_progress_start(&pr, eomc_sim_model(sim), c->run.t_end);
        c->run.on_progress = summary_progress;
        c->run.progress_ctx = &pr;
        c->run.on_event = rows_event;
        c->run.event_ctx = &w;
        if (catch_signals)
            signals_catch();
        rc = anim ? eomc_sim_integrate(sim, &c->run, x, animate_row, &ar, &st)
                  : eomc_sim_integrate(sim, &c->run, x, rows_write, &w, &st);
        summary_progress_end(&pr);
        c->run.on_progress = NULL; /* pr is gone */
        rows_flush(&w);
        if (catch_signals)
            signals_restore();
        if (rc == SIGNALS_STOPPED) {
            int sig = signals_caught();
            rows_close(c->prog, w.f, c->out);
            if (w.events)
                rows_close(c->prog, w.events, c->events);
            summary_interrupted(c, &w, sig);
            rc = 128 + sig; /* 130 for SIGINT, 143 for SIGTERM */
        } else {
            rc = after_run(c, &w, &st, &ref, data, rc);
        }
        /* the page of the rows written, also those before a failure or
         * a signal, as the CSV has them */
        if (anim && anim_write(anim, c->prog) != EOMC_OK)
            rc = rc ? rc : EOMC_EUSAGE;
    }
    anim_free(anim);
    if (w.tee)
        fclose(w.tee);
    if (fd >= 0)
        unlink(data);
    if (w.in_memory && rows_to_extra(&w, extra) != 0)
        rc = rc ? rc : opt_usage(c, "out of memory");
    eomc_reference_free(&ref);
    compare_free(&w.cmp);
    rows_free(&w);
    return rc;
}

/* "t = 0 to 10, 1001 rows every 0.01, q1 = 1, ...": the report's setting. */
static void
describe_setting(const Options *c, const eomc_model *m, const double *x, char *buf,
                 size_t len)
{
    size_t at = (size_t)snprintf(buf, len, "t = %g to %g, %ld rows every %g", c->run.t0,
                                 c->run.t_end, eomc_run_rows(&c->run), c->run.dt);
    char name[STATE_NAME_MAX];
    for (int i = 0; i < eomc_nx(m) && at < len; i++)
        if (x[i] != 0)
            at += (size_t)snprintf(buf + at, len - at, ", %s = %.6g",
                                   state_name(m, i, name, sizeof name), x[i]);
    if (c->stabilize != EOMC_STABILIZE_NONE && at < len)
        snprintf(buf + at, len - at, ", --stabilize %s", opt_stabilize_name(c->stabilize));
}

enum {
    NMETHODS = 0 /* the methods in methods.def */
#define METHOD(name, gsl, fixed, jac, description) + 1
#include "base/methods.def"
#undef METHOD
};

static int
work_precision(Options *c, eomc_sim *sim, const eomc_model_ext *ext, double *x)
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
                return opt_usage(c, "--methods: %s needs the Jacobian of the equations, which "
                             "%s was built without: rebuild with `eomc build %s --jacobian "
                             "auto`", methods[k], m->name, m->spec);
            else
                snprintf(left + strlen(left), sizeof left - strlen(left), "%s%s",
                         *left ? ", " : "", methods[k]);
        }
        runnable[n] = NULL;
        methods = runnable;
        if (*left)
            fprintf(io_err(), "%s: note: %s left out: they need the Jacobian of the equations, "
                    "which %s was built without (rebuild with `eomc build %s --jacobian "
                    "auto` to report them)\n", c->prog, left, m->name, m->spec);
    }
    /* nor Taylor's method without the model's series: the same, saying why */
    const char *with_series[NMETHODS + 1];
    if (!m->taylor) {
        int n = 0, left = 0;
        for (int k = 0; methods[k]; k++) {
            if (strcmp(methods[k], "taylor"))
                with_series[n++] = methods[k];
            else if (c->methods)
                return opt_usage(c, "--methods: taylor needs the model's Taylor series, which "
                                 "%s has none of: %s", m->name,
                                 m->taylor_why ? m->taylor_why : "not generated");
            else
                left = 1;
        }
        with_series[n] = NULL;
        methods = with_series;
        if (left)
            fprintf(io_err(), "%s: note: taylor left out: %s has no Taylor series (%s)\n",
                    c->prog, m->name, m->taylor_why ? m->taylor_why : "not generated");
    }
    assembly_check(c, sim, x);
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

/* program: the caller is a program of its own (eomc_main), whose signals
 * stop a run (simulate) and whose MPI ranks other than 0 are silenced;
 * not under eomc_main_mem, whose caller keeps its handlers and streams. */
static int
cli_main(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext, int program,
         eomc_main_extra *extra)
{
    Options c;
    int ok = opt_init(&c, argc, argv, m) == 0;
    if (program && sweep_rank() != 0) { /* rank 0 speaks for the job */
        if (io_silence() != 0) {
            opt_free(&c);
            return EOMC_EUSAGE;
        }
    }
    eomc_sim *sim = eomc_sim_alloc(m);
    double *x = calloc((size_t)eomc_nx(m) + 1, sizeof *x);
    int rc;
    if (!sim || !ok || !x) {
        fprintf(io_err(), "%s: out of memory, or a model built for another runtime\n",
                c.prog);
        rc = EOMC_EUSAGE;
    } else if ((rc = opt_parse(&c, argc, argv, m)) != EOMC_OK) {
        rc = rc < 0 ? EOMC_OK : rc;
    } else if ((rc = opt_apply_sets(&c, sim)) == EOMC_OK &&
               (rc = opt_stabilize(&c, sim)) == EOMC_OK &&
               (rc = !extra || !extra->controller ? EOMC_OK
                     : eomc_sim_set_controller(sim, extra->controller, extra->controller_ctx,
                                               extra->period, extra->drives)) == EOMC_OK) {
        eomc_sim_initial(sim, x, x + m->nq);
        if ((rc = opt_apply_inits(&c, m, x)) == EOMC_OK &&
            (rc = assembly_unit(&c, m, x, 0)) == EOMC_OK &&
            (rc = c.assemble ? opt_held_marks(&c, m) : EOMC_OK) == EOMC_OK &&
            (rc = c.assemble && !c.nsweep && !c.sweep_file ? assembly_run(&c, sim, x)
                                                           : EOMC_OK) == EOMC_OK)
            rc = (c.nsweep || c.sweep_file) && extra && extra->controller
                     ? opt_usage(&c, "a sweep with a controller: its runs are the sweep's own "
                                 "simulators, which the controller is not set on")
                 : c.nsweep || c.sweep_file ? sweep(&c, sim)
                 : sweep_rank() != 0 ? EOMC_OK /* one run: rank 0's */
                 : c.accel          ? print_accel(&c, sim, ext, x)
                 : c.linearize || c.equilibrium ? stab_print(&c, sim, x)
                 : c.work_precision ? work_precision(&c, sim, ext, x)
                                    : simulate(&c, sim, ext, x, program, extra);
    }
    eomc_sim_free(sim);
    free(x);
    opt_free(&c);
    return rc;
}

/* The simulator is the program for the time it runs, so its GSL errors
 * come back as statuses and are reported as eomc's (eomc.h); the handler
 * before it is put back for a program that calls eomc_main and goes on. */
int
eomc_main(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext)
{
    gsl_error_handler_t *before = gsl_set_error_handler_off();
    int rc = cli_main(argc, argv, m, ext, 1, NULL);
    gsl_set_error_handler(before);
    return rc;
}

/* A stream's text, closed: *text (NULL when it could not be kept) and
 * *len (unless NULL).  -1 when it could not. */
static int
mem_close(FILE *f, char **text, size_t *size, size_t *len)
{
    int bad = fclose(f) != 0 || !*text;
    if (bad) {
        free(*text);
        *text = NULL;
        *size = 0;
    }
    if (len)
        *len = *size;
    return bad ? -1 : 0;
}

/* The command line for a caller that is not a program (the Python
 * package, through ctypes, from several threads at once): the calling
 * thread's streams are memory (io.h), so nothing reaches the process's
 * stdout and stderr and threads keep their text apart; the process's
 * signal handlers and GSL's error handler are the caller's; and it never
 * leaves the job to an MPI rank (the caller is one process). */
int
eomc_main_mem(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext,
              char **out, size_t *out_len, char **err, size_t *err_len)
{
    return eomc_main_with(argc, argv, m, ext, NULL, out, out_len, err, err_len);
}

int
eomc_main_with(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext,
               eomc_main_extra *extra, char **out, size_t *out_len, char **err,
               size_t *err_len)
{
    if (extra)
        extra->rows = NULL, extra->nrows = 0, extra->ncols = 0, extra->columns = NULL;
    size_t nout = 0, nerr = 0;
    *out = *err = NULL;
    FILE *fo = open_memstream(out, &nout), *fe = fo ? open_memstream(err, &nerr) : NULL;
    if (!fe) {
        if (fo)
            fclose(fo);
        free(*out);
        *out = NULL;
        if (out_len)
            *out_len = 0;
        if (err_len)
            *err_len = 0;
        return EOMC_EUSAGE;
    }
    IoSaved saved;
    io_set(fo, fe, &saved);
    int rc = cli_main(argc, argv, m, ext, 0, extra);
    io_restore(&saved);
    int bad = mem_close(fo, out, &nout, out_len);
    bad |= mem_close(fe, err, &nerr, err_len);
    return bad && rc == EOMC_OK ? EOMC_EUSAGE : rc;
}

void
eomc_free(void *p)
{
    free(p);
}

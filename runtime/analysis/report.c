/*
 * report: the work-precision report (report.h).
 *
 * Every setting is one run from the same initial state with the same
 * output times as the reference.  Its error at a row is the largest
 * |x_i - x_ref,i| over coordinates and velocities; error_max is the
 * largest over the rows (rows between steps come from the interpolant,
 * so error_max includes its error), error_end the one at t_end.  The
 * conserved quantity's drift is the largest |h(t) - h(t0)| over the rows,
 * the constraint residual the largest |g|, |g'|, |phi| (or |f|) over the
 * rows and the steps.  All are absolute, in the model's units.
 *
 * CPU time is process time, the minimum per run over BATCHES batches of
 * runs, each batch repeated until it lasts BATCH_MIN (a run of 0.1 ms is
 * timed in batches of 64): shorter intervals are at the mercy of the
 * clock's and the scheduler's granularity.  A run that takes LONG_RUN or
 * more is timed once.  The timed runs pass their rows to a callback that
 * does nothing, as a user's would write them.
 */
#include "report.h"
#include "compare.h"
#include "base/io.h"
#include "base/numfmt.h"
#include "plot.h"
#include "model/simimpl.h"
#include "model/state.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define BATCH_MIN 0.01   /* s: a timed batch lasts at least this */
#define LONG_RUN 0.05    /* s: timed once */
enum { BATCHES = 5 };
/* Errors within this factor of the reference's own are not resolved. */
#define RESOLVED 2.0

enum { RUN_OK, RUN_FAILED, RUN_SKIPPED };

typedef struct Entry {
    const char *method;
    double tol;           /* adaptive: rtol = atol */
    double h;             /* > 0: fixed steps of at most h */
    int status;
    char why[320];        /* the failure, or why skipped */
    eomc_stats st;
    double cpu;           /* seconds per run */
    double err_end, err_max, drift, residual;
    double *comp_end, *comp_max; /* [nx] each component's (compare.h) */
    double digits;        /* the fewest digits of a component */
    int worst;            /* that component */
    int parted;           /* its switches part from the reference's, at part */
    ComparePart part;
} Entry;

/* What a row callback measures against the reference. */
typedef struct Probe {
    eomc_sim *s;
    Compare *cmp;
    long k;
    int invariant;
    double h0, drift;
    double *res, res_max;
} Probe;

static int
probe_row(void *ctx, double t, const double *x)
{
    Probe *p = ctx;
    const eomc_model *m = eomc_sim_model(p->s);
    int n = m->nq;
    if (p->k >= p->cmp->ref->nrows)
        return EOMC_ENUMERIC; /* cannot happen: the grids are the same */
    compare_row(p->cmp, x);
    if (p->invariant) {
        double h;
        eomc_sim_invariant(p->s, t, x, x + n, &h);
        if (p->k == 0)
            p->h0 = h;
        p->drift = fmax(p->drift, fabs(h - p->h0));
    }
    if (m->nc > 0 && eomc_sim_residuals(p->s, t, x, x + n, p->res) == EOMC_OK)
        for (int c = 0; c < m->nc; c++)
            p->res_max = fmax(p->res_max, fabs(p->res[c]));
    p->k++;
    return EOMC_OK;
}

/* A run's flips, for the reference's to be compared with (on_event). */
static int
probe_event(void *ctx, int k, double t, const double *x)
{
    Probe *p = ctx;
    int nevent = eomc_sim_model(p->s)->nevent;
    if (k >= nevent && compare_flip(p->cmp, k - nevent, t, x) != 0)
        return sim_usage_error(p->s, "out of memory for the run's switches");
    return EOMC_OK;
}

static int
no_row(void *ctx, double t, const double *x)
{
    (void)ctx, (void)t, (void)x;
    return EOMC_OK;
}

static eomc_run_opts
entry_opts(const Report *r, const Entry *e)
{
    eomc_run_opts o = r->base;
    o.method = e->method;
    o.h_fixed = e->h;
    if (e->h == 0)
        o.rtol = o.atol = e->tol;
    o.max_steps = r->base.max_steps > 0 ? r->base.max_steps : REPORT_MAX_STEPS;
    o.on_progress = NULL;
    return o;
}

/* One timed run, its CPU seconds; x is scratch [nx]. */
static double
timed_run(const Report *r, const eomc_run_opts *o, double *x)
{
    eomc_stats st;
    memcpy(x, r->x0, (size_t)eomc_nx(eomc_sim_model(r->sim)) * sizeof *x);
    eomc_sim_integrate(r->sim, o, x, no_row, NULL, &st);
    return st.cpu_seconds;
}

/* Seconds per run: the minimum over batches of runs lasting BATCH_MIN. */
static double
time_entry(const Report *r, const eomc_run_opts *o, double first, double *x)
{
    if (first >= LONG_RUN)
        return first;
    long reps = 1;
    double batch = first;
    while (batch < BATCH_MIN) {
        reps *= 2;
        batch = 0;
        for (long i = 0; i < reps; i++)
            batch += timed_run(r, o, x);
    }
    double best = batch / (double)reps;
    for (int b = 1; b < BATCHES; b++) {
        batch = 0;
        for (long i = 0; i < reps; i++)
            batch += timed_run(r, o, x);
        best = fmin(best, batch / (double)reps);
    }
    return best;
}

/* Run e: measure, then time. */
static void
measure(const Report *r, Entry *e, double *x, double *res, Compare *cmp)
{
    const eomc_model *m = eomc_sim_model(r->sim);
    eomc_run_opts o = entry_opts(r, e);
    Probe p = {.s = r->sim, .cmp = cmp, .invariant = m->invariant != NULL, .res = res};
    compare_reset(cmp);
    memcpy(x, r->x0, (size_t)eomc_nx(m) * sizeof *x);
    if (m->nmode > 0) {
        o.on_event = probe_event;
        o.event_ctx = &p;
    }
    int rc = eomc_sim_integrate(r->sim, &o, x, probe_row, &p, &e->st);
    o.on_event = NULL; /* (the timed runs below) */
    e->cpu = e->st.cpu_seconds;
    if (rc == EOMC_EUSAGE) { /* a setting this model cannot take (msbdf with projection) */
        e->status = RUN_SKIPPED;
        snprintf(e->why, sizeof e->why, "%s", eomc_sim_error(r->sim));
        return;
    }
    if (rc != EOMC_OK) {
        e->status = RUN_FAILED;
        snprintf(e->why, sizeof e->why, "%s", eomc_sim_error(r->sim));
        char *state = strstr(e->why, "; state: "); /* the table has no room for it */
        if (state)
            *state = '\0';
        return;
    }
    e->status = RUN_OK;
    e->err_max = cmp->err_max;
    e->err_end = cmp->err_end;
    memcpy(e->comp_end, cmp->end, (size_t)eomc_nx(m) * sizeof *cmp->end);
    memcpy(e->comp_max, cmp->max, (size_t)eomc_nx(m) * sizeof *cmp->max);
    e->worst = compare_worst(cmp, &e->digits);
    double tol = e->h > 0 ? 0 : e->tol; /* fixed steps: the rows' errors alone */
    e->parted = compare_switches(cmp, tol, tol, o.t0, o.t_end);
    e->part = cmp->part;
    e->drift = p.drift;
    e->residual = fmax(p.res_max, e->st.max_residual);
    e->cpu = time_entry(r, &o, e->st.cpu_seconds, x);
}

/* ---- the list of runs ---- */

static int
count_list(const char *const *l)
{
    int n = 0;
    while (l[n])
        n++;
    return n;
}

/* Whether method m gets fixed-step runs. */
static int
fixed_runs(const Report *r, const char *m)
{
    int kind = eomc_method_steps(m);
    return kind == EOMC_STEPS_DOUBLING || (r->steps_given && kind == EOMC_STEPS_EMBEDDED);
}

static Entry *
plan(const Report *r, int *count)
{
    int nm = count_list(r->methods), n = 0;
    Entry *e = calloc((size_t)nm * (size_t)(r->ntolerances + r->nsteps) + 1, sizeof *e);
    if (!e)
        return NULL;
    for (int k = 0; k < nm; k++) {
        for (int j = 0; j < r->ntolerances; j++)
            e[n++] = (Entry){.method = r->methods[k], .tol = r->tolerances[j]};
        for (int j = 0; fixed_runs(r, r->methods[k]) && j < r->nsteps; j++)
            e[n++] = (Entry){.method = r->methods[k], .h = r->steps[j]};
    }
    *count = n;
    return e;
}

/* ---- progress ---- */

static void
progress(const Report *r, double t0, int k, int n, const Entry *e, int *shown)
{
    if (!io_err_tty() || sim_seconds(0) - t0 < 1.0)
        return;
    char what[64];
    if (e->h > 0)
        snprintf(what, sizeof what, "fixed steps %.3g", e->h);
    else
        snprintf(what, sizeof what, "tolerance %.0e", e->tol);
    fprintf(io_err(),
            "\r%s: run %d of %d: %s, %s%-10s", r->prog, k + 1, n, e->method, what, "");
    *shown = 1;
}

/* ---- the table ---- */

/* An error, marked ~ when the reference cannot resolve it. */
static void
error_cell(char *buf, size_t len, const Report *r, double err)
{
    int unresolved = err <= RESOLVED * r->ref->error;
    snprintf(buf, len, "%s%.2e", unresolved ? "~" : "", err);
}

/* The worst column's width: the longest name of the state's. */
static int
name_width(const eomc_model *m)
{
    int w = 5; /* "worst" */
    char name[STATE_NAME_MAX];
    for (int i = 0; i < eomc_nx(m); i++)
        if ((int)strlen(state_name(m, i, name, sizeof name)) > w)
            w = (int)strlen(name);
    return w;
}

static void
print_block_head(const Report *r, const Entry *e)
{
    const eomc_model *m = eomc_sim_model(r->sim);
    fprintf(io_out(), "\n%s, %s: %s\n", e->method, e->h > 0 ? "fixed steps" : "adaptive",
            eomc_method_description(e->method));
    fprintf(io_out(), "  %-11s %12s %8s %8s %10s %9s %9s %10s %10s %6s %-*s",
            e->h > 0 ? "fixed_step" : "tolerance", "cpu_seconds", "steps", "rejected",
            "side_steps", "rhs_evals", "jac_evals", "error_end", "error_max", "digits",
            name_width(m), "worst");
    if (m->invariant)
        fprintf(io_out(), " %15s", "invariant_drift");
    if (m->nc > 0)
        fprintf(io_out(), " %19s", "constraint_residual");
    if (!strcmp(e->method, "taylor")) /* its order follows the tolerance */
        fprintf(io_out(), " %10s", "order_mean");
    fprintf(io_out(), "\n");
}

static void
print_entry(const Report *r, const Entry *e)
{
    const eomc_model *m = eomc_sim_model(r->sim);
    char setting[32];
    if (e->h > 0)
        snprintf(setting, sizeof setting, "%.4g", e->st.h_used > 0 ? e->st.h_used : e->h);
    else
        snprintf(setting, sizeof setting, "%.0e", e->tol);
    fprintf(io_out(), "  %-11s", setting);
    if (e->status == RUN_SKIPPED) {
        fprintf(io_out(), " not run: %s\n", e->why);
        return;
    }
    fprintf(io_out(), " %12.4g %8ld %8ld %10ld %9ld %9ld", e->cpu, e->st.steps, e->st.rejected,
            e->st.side_steps, e->st.rhs_evals, e->st.jac_evals);
    if (e->status == RUN_FAILED) {
        fprintf(io_out(), "  failed: %s\n", e->why);
        return;
    }
    char end[32], max[32];
    error_cell(end, sizeof end, r, e->err_end);
    error_cell(max, sizeof max, r, e->err_max);
    char worst[128] = "-"; /* no error at all: no worst */
    if (e->digits < INFINITY)
        state_name(m, e->worst, worst, sizeof worst);
    fprintf(io_out(), " %10s %10s %6.1f %-*s", end, max, e->digits, name_width(m), worst);
    if (m->invariant)
        fprintf(io_out(), " %15.2e", e->drift);
    if (m->nc > 0)
        fprintf(io_out(), " %19.2e", e->residual);
    if (e->st.order_sum > 0)
        fprintf(io_out(), " %10.3g", (double)e->st.order_sum / (double)e->st.steps);
    fprintf(io_out(), "\n");
    if (e->parted) { /* its errors after that are not its own alone (compare.h) */
        const ComparePart *p = &e->part;
        char a[STATE_NAME_MAX + 40] = "nothing", b[STATE_NAME_MAX + 40] = "nothing";
        char name[STATE_NAME_MAX];
        if (p->ref_k >= 0)
            snprintf(a, sizeof a, "'%s' at %.6g",
                     state_switch_name(m, p->ref_k, name, sizeof name), p->t_ref);
        if (p->run_k >= 0)
            snprintf(b, sizeof b, "'%s' at %.6g",
                     state_switch_name(m, p->run_k, name, sizeof name), p->t_run);
        fprintf(io_out(), "  %-11s ! its switches part from the reference's at t = %.6g (the "
                "reference flipped %s, the run %s); before it the error was at most %.2e\n",
                "", p->t, a, b, p->err_before);
    }
}

static void
describe_setting(const Entry *e, char *buf, size_t len)
{
    if (e->h > 0)
        snprintf(buf, len, "%s, fixed steps of %.4g", e->method,
                 e->st.h_used > 0 ? e->st.h_used : e->h);
    else
        snprintf(buf, len, "%s at tolerance %.0e", e->method, e->tol);
}

/* The settings no other beats in both CPU time and error_max, cheapest
 * first; and the cheapest with error_max <= target. */
static void
print_front(const Report *r, Entry *e, int n)
{
    int *order = malloc((size_t)n * sizeof *order), m = 0;
    if (!order)
        return;
    for (int k = 0; k < n; k++)
        if (e[k].status == RUN_OK)
            order[m++] = k;
    for (int i = 1; i < m; i++) /* by CPU time, then error: insertion sort */
        for (int j = i; j > 0; j--) {
            const Entry *a = &e[order[j - 1]], *b = &e[order[j]];
            if (a->cpu < b->cpu || (a->cpu == b->cpu && a->err_max <= b->err_max))
                break;
            int t = order[j];
            order[j] = order[j - 1], order[j - 1] = t;
        }
    fprintf(io_out(), "\nPareto front (no other setting is both faster and more accurate):\n");
    fprintf(io_out(), "  %12s %10s  %s\n", "cpu_seconds", "error_max", "setting");
    double best = INFINITY;
    for (int i = 0; i < m; i++) {
        const Entry *x = &e[order[i]];
        if (!(x->err_max < best))
            continue;
        best = x->err_max;
        char what[128], err[32];
        describe_setting(x, what, sizeof what);
        error_cell(err, sizeof err, r, x->err_max);
        fprintf(io_out(), "  %12.4g %10s  %s\n", x->cpu, err, what);
    }
    if (!isnan(r->target)) {
        const Entry *pick = NULL, *closest = NULL;
        for (int i = 0; i < m; i++) {
            const Entry *x = &e[order[i]];
            if (!pick && x->err_max <= r->target)
                pick = x;
            if (!closest || x->err_max < closest->err_max)
                closest = x;
        }
        char what[128];
        if (pick) {
            describe_setting(pick, what, sizeof what);
            fprintf(io_out(),
                    "\ntarget error_max <= %.3g: the cheapest measured setting is %s, "
                    "%.4g s of CPU time per run (error_max %.2e)\n", r->target, what,
                    pick->cpu, pick->err_max);
        } else if (closest) {
            describe_setting(closest, what, sizeof what);
            fprintf(io_out(),
                    "\ntarget error_max <= %.3g: no measured setting reaches it; the most "
                    "accurate is %s (error_max %.2e, %.4g s)\n", r->target, what,
                    closest->err_max, closest->cpu);
        }
        if (r->target <= RESOLVED * r->ref->error)
            fprintf(io_out(),
                    "(the reference is good to %.2e only: errors near the target cannot be "
                    "told apart from its own)\n", r->ref->error);
    }
    free(order);
}

/* ---- files ---- */

/* path + ".tmpPID": written, then renamed over path. */
static char *
temp_name(const char *path)
{
    size_t len = strlen(path) + 32;
    char *tmp = malloc(len);
    if (tmp)
        snprintf(tmp, len, "%s.tmp%ld", path, (long)getpid());
    return tmp;
}

static int
finish_file(const Report *r, FILE *f, const char *tmp, const char *path)
{
    int bad = ferror(f) | (fclose(f) != 0);
    if (bad || rename(tmp, path) != 0) {
        fprintf(io_err(), "%s: cannot write %s: %s\n", r->prog, path, strerror(errno));
        unlink(tmp);
        return EOMC_EUSAGE;
    }
    return EOMC_OK;
}

static void
csv_num(FILE *f, double x)
{
    fputc(',', f);
    num_put(f, x);
}

static int
write_csv(const Report *r, const Entry *e, int n)
{
    const eomc_model *m = eomc_sim_model(r->sim);
    char *tmp = temp_name(r->csv);
    FILE *f = tmp ? fopen(tmp, "w") : NULL;
    if (!f) {
        fprintf(io_err(), "%s: --csv: cannot write %s: %s\n", r->prog, r->csv,
                strerror(errno));
        free(tmp);
        return EOMC_EUSAGE;
    }
    fprintf(f, "method,tolerance,fixed_step,cpu_seconds,steps,rejected,rhs_evals,"
               "jac_evals,error_end,error_max,invariant_drift,constraint_residual,"
               "order_mean\n");
    for (int k = 0; k < n; k++) {
        const Entry *x = &e[k];
        if (x->status == RUN_SKIPPED)
            continue;
        fprintf(f, "%s", x->method);
        if (x->h > 0) {
            fprintf(f, ",");
            csv_num(f, x->st.h_used);
        } else {
            csv_num(f, x->tol);
            fprintf(f, ",");
        }
        csv_num(f, x->cpu);
        fprintf(f, ",%ld,%ld,%ld,%ld", x->st.steps, x->st.rejected, x->st.rhs_evals,
                x->st.jac_evals);
        if (x->status == RUN_OK) {
            csv_num(f, x->err_end);
            csv_num(f, x->err_max);
        } else {
            fprintf(f, ",,");
        }
        if (x->status == RUN_OK && m->invariant)
            csv_num(f, x->drift);
        else
            fprintf(f, ",");
        if (x->status == RUN_OK && m->nc > 0)
            csv_num(f, x->residual);
        else
            fprintf(f, ",");
        if (x->st.order_sum > 0) /* Taylor's method's mean order */
            csv_num(f, (double)x->st.order_sum / (double)x->st.steps);
        else
            fprintf(f, ",");
        fprintf(f, "\n");
    }
    int rc = finish_file(r, f, tmp, r->csv);
    free(tmp);
    return rc;
}

/* --errors FILE: each run's errors, component by component (compare.h). */
static int
write_errors(const Report *r, const Entry *e, int n, const double *scale)
{
    const eomc_model *m = eomc_sim_model(r->sim);
    char *tmp = temp_name(r->errors);
    FILE *f = tmp ? fopen(tmp, "w") : NULL;
    if (!f) {
        fprintf(io_err(), "%s: --errors: cannot write %s: %s\n", r->prog, r->errors,
                strerror(errno));
        free(tmp);
        return EOMC_EUSAGE;
    }
    compare_csv_header(f);
    for (int k = 0; k < n; k++) {
        const Entry *x = &e[k];
        if (x->status == RUN_SKIPPED)
            continue;
        int ok = x->status == RUN_OK;
        compare_csv_run(f, m, scale, ok ? x->comp_end : NULL, ok ? x->comp_max : NULL,
                        x->method, x->tol,
                        x->h > 0 ? (x->st.h_used > 0 ? x->st.h_used : x->h) : 0);
    }
    int rc = finish_file(r, f, tmp, r->errors);
    free(tmp);
    return rc;
}

/* Colours told apart in print and by most colour-blind readers: one per
 * method, in eomc_methods order; fixed steps dashed, in the method's. */
static const char *const colours[] = {
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
    "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#000000",
};

static int
method_number(const char *m)
{
    for (int k = 0; eomc_methods[k]; k++)
        if (!strcmp(m, eomc_methods[k]))
            return k;
    return 0;
}

/* One curve per method and kind of steps, through its successful runs
 * (a curve without one is left out); its plot clause into plot. */
static void
plot_data(FILE *f, const Entry *e, int n, char *plot, size_t len)
{
    int curves = 0;
    size_t at = 0;
    for (int k = 0; k < n;) {
        int end = k, points = 0;
        while (end < n && e[end].method == e[k].method && (e[end].h > 0) == (e[k].h > 0))
            points += e[end++].status == RUN_OK && e[end - 1].err_max > 0;
        if (points) {
            fprintf(f, "$d%d << EOD\n", curves);
            for (int j = k; j < end; j++)
                if (e[j].status == RUN_OK && e[j].err_max > 0 && e[j].cpu > 0)
                    fprintf(f, "%.6e %.6e\n", e[j].cpu, e[j].err_max);
            fprintf(f, "EOD\n");
            int c = method_number(e[k].method), fixed = e[k].h > 0;
            at += (size_t)snprintf(plot + at, at < len ? len - at : 0,
                                   "%s$d%d using 1:2 with linespoints linecolor rgb '%s' "
                                   "dashtype %d pointtype %d pointsize 0.9 title '%s%s'",
                                   curves ? ", " : "", curves, colours[c % 11],
                                   fixed ? 2 : 1, fixed ? 6 : 1 + c % 13, e[k].method,
                                   fixed ? " (fixed steps)" : "");
            curves++;
        }
        k = end;
    }
}

static int
write_plot(const Report *r, const Entry *e, int n)
{
    const eomc_model *m = eomc_sim_model(r->sim);
    char script[] = "/tmp/eomc-plot-XXXXXX";
    int fd = mkstemp(script);
    char *tmp = temp_name(r->plot);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f || !tmp) {
        fprintf(io_err(), "%s: --plot: cannot write a gnuplot script: %s\n", r->prog,
                strerror(errno));
        if (f)
            fclose(f);
        if (fd >= 0)
            unlink(script);
        free(tmp);
        return EOMC_EUSAGE;
    }
    plot_terminal(f, r->plot, tmp, 1000, 650);
    char title[512];
    snprintf(title, sizeof title, "%s: error against CPU time", m->name);
    fprintf(f, "set title ");
    plot_string(f, title);
    fprintf(f, " noenhanced offset 0,1\nset label 1 ");
    plot_string(f, r->setting);
    fprintf(f, " at graph 0.5, graph 1.035 center font 'sans,9' noenhanced\n"
               "set logscale xy\nset format x '10^{%%L}'\nset format y '10^{%%L}'\n"
               "set xlabel 'CPU time per run [s]'\n"
               "set ylabel 'largest error at the output times (error_max)' noenhanced\n"
               "set grid\nset key outside right top noenhanced\n");
    size_t len = 256 * (size_t)n + 256;
    char *plot = malloc(len);
    if (plot) {
        plot_data(f, e, n, plot, len);
        fprintf(f, "plot %s, %.6e with lines dashtype 3 linecolor rgb 'gray40' title "
                   "'the reference''s own error'\n", plot, r->ref->error);
    }
    free(plot);
    int bad = ferror(f) | (fclose(f) != 0);
    int rc;
    if (bad) {
        fprintf(io_err(), "%s: --plot: cannot write a gnuplot script\n", r->prog);
        unlink(script);
        rc = EOMC_EUSAGE;
    } else {
        rc = plot_finish(r->prog, script, tmp, r->plot);
    }
    free(tmp);
    return rc;
}

/* ---- the report ---- */

static void
print_title(const Report *r)
{
    const eomc_model *m = eomc_sim_model(r->sim);
    const eomc_reference *ref = r->ref;
    fprintf(io_out(), "%s (%s, %s form): %s\n", m->name, m->spec, m->form, r->setting);
    fprintf(io_out(), "reference: %s", ref->source);
    if (isnan(ref->error))
        fprintf(io_out(), "; its own error is not known\n");
    else
        fprintf(io_out(),
                ";\n  its error is at most %.2e (%.1f digits of the largest entry, %.3g), "
                "computed in %.3g s\n", ref->error, -log10(ref->error / ref->scale),
                ref->scale, ref->cpu_seconds);
    fprintf(io_out(), "%s\n", m->invariant_note);
    fprintf(io_out(),
            "cpu_seconds per run; errors are the largest |x - x_ref| over coordinates and "
            "velocities, at t_end (error_end) and over the rows (error_max); digits: the "
            "fewest of any coordinate or velocity (worst), -log10 of its largest error over "
            "its own largest |x_ref| (at least %g of its group's); ~ marks an error the "
            "reference cannot resolve\n", COMPARE_FLOOR);
}

/* A method's tighter settings, after it reached the step limit: they
 * would need more steps still. */
static void
skip_rest(Entry *e, int k, int n)
{
    for (int j = k + 1; j < n && e[j].method == e[k].method && (e[j].h > 0) == (e[k].h > 0);
         j++) {
        e[j].status = RUN_SKIPPED;
        snprintf(e[j].why, sizeof e[j].why, "%s reached the step limit at a looser setting",
                 e[k].method);
    }
}

int
report_run(const Report *r)
{
    const eomc_model *m = eomc_sim_model(r->sim);
    int n = 0;
    Entry *e = plan(r, &n);
    size_t nx = (size_t)eomc_nx(m);
    double *x = calloc(nx, sizeof *x);
    double *res = calloc((size_t)m->nc + 1, sizeof *res);
    double *comps = calloc(2 * nx * (size_t)(n + 1), sizeof *comps);
    Compare cmp;
    int cmp_ok = compare_init(&cmp, r->ref, m->nq) == 0;
    if (!e || !x || !res || !comps || !cmp_ok) {
        fprintf(io_err(), "%s: out of memory\n", r->prog);
        free(e), free(x), free(res), free(comps);
        compare_free(&cmp);
        return EOMC_EUSAGE;
    }
    for (int k = 0; k < n; k++) {
        e[k].comp_end = comps + 2 * nx * (size_t)k;
        e[k].comp_max = e[k].comp_end + nx;
    }
    print_title(r);
    fflush(io_out());
    double t0 = sim_seconds(0);
    int shown = 0, ok = 0;
    long max_steps = r->base.max_steps > 0 ? r->base.max_steps : REPORT_MAX_STEPS;
    for (int k = 0; k < n; k++) {
        if (e[k].status == RUN_SKIPPED)
            continue;
        double span = r->base.t_end - r->base.t0;
        if (e[k].h > 0 && span / e[k].h > (double)max_steps) {
            e[k].status = RUN_SKIPPED;
            snprintf(e[k].why, sizeof e[k].why, "%.3g steps, more than the limit of %ld",
                     ceil(span / e[k].h), max_steps);
            continue;
        }
        progress(r, t0, k, n, &e[k], &shown);
        measure(r, &e[k], x, res, &cmp);
        if (e[k].status == RUN_OK)
            ok++;
        else if (e[k].st.steps >= max_steps) /* tighter settings need more */
            skip_rest(e, k, n);
    }
    if (shown)
        fprintf(io_err(), "\r%*s\r", 72, "");
    for (int k = 0; k < n; k++) {
        if (k == 0 || e[k].method != e[k - 1].method || (e[k].h > 0) != (e[k - 1].h > 0))
            print_block_head(r, &e[k]);
        print_entry(r, &e[k]);
    }
    print_front(r, e, n);
    fflush(io_out());
    int parted = 0;
    for (int k = 0; k < n; k++)
        parted += e[k].status == RUN_OK && e[k].parted;
    if (parted)
        fprintf(io_err(), "%s: warning: %d run%s switched differently from the reference "
                "(marked ! in the table): %s errors after that compare two branches of the "
                "motion, not the run's error alone\n", r->prog, parted, parted == 1 ? "" : "s",
                parted == 1 ? "its" : "their");
    int rc = EOMC_OK;
    if (r->csv && write_csv(r, e, n) != EOMC_OK)
        rc = EOMC_EUSAGE;
    if (r->plot && write_plot(r, e, n) != EOMC_OK)
        rc = EOMC_EUSAGE;
    if (r->errors && write_errors(r, e, n, cmp.scale) != EOMC_OK)
        rc = EOMC_EUSAGE;
    if (rc == EOMC_OK && ok == 0) {
        fprintf(io_err(), "%s: no run succeeded\n", r->prog);
        rc = EOMC_ENUMERIC;
    }
    free(e), free(x), free(res), free(comps);
    compare_free(&cmp);
    return rc;
}

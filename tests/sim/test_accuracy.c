/*
 * The reference solution and the errors eomc reports, against values
 * obtained independently:
 *  - the reference against the pendulum's elliptic closed form and a
 *    chain5 trajectory, both computed with mpmath to 25 digits
 *    (tests/sim/reference, with how they were made), and against the
 *    Kepler orbit after whole periods (Kepler's equation): good to
 *    2e-15, and never worse than its own error estimate says;
 *  - the errors of --work-precision's CSV (the simulator as `eomc
 *    accuracy` runs it) against the errors of the same runs measured here
 *    on those independent values: the same to within the reference's own
 *    error;
 *  - output rows cost no steps: Kepler's orbit written every 0.031 takes
 *    the steps of one written only at its end, and its interpolated rows
 *    lie on the closed form (Kepler's equation solved here);
 *  - the conserved quantity eomc derives: Jacobi's h for Arenstorf's
 *    orbit (against the formula written out here, conserved to 1e-12 over
 *    the period where T + V changes by 1.9; the orbit back at its start
 *    after the published period), E = T + V for the pendulum,
 *    nothing for a driven, damped cart-pole (the effect named);
 *  - units: Kepler with lengths in micrometres (a = 1e6) needs the same
 *    reference steps and gets the same relative error estimate;
 *  - stiff problems: the damped spring with roots -1 and -1e4
 *    (tests/hard/specs/stiff_spring.yaml) gets the linearly implicit
 *    reference, says so, and lies on the closed form through the
 *    transient and over the decay, at a small part of GBS's work; in
 *    milliseconds it is the same reference; Van der Pol's oscillator with
 *    eps = 1e-6 (tests/sim/specs/van_der_pol.yaml) is on the Bari test
 *    set's published value at t = 2; the pendulum, chain5 and Kepler stay
 *    with GBS;
 *  - fixed implicit steps solve their stages to rounding, not to the
 *    run's tolerance: rk1imp, rk2imp and rk4imp on the pendulum (mpmath's
 *    values) at h and h / 10 with rtol = atol = 1e-6, their error falling
 *    by 10^order.
 *
 * usage: test_accuracy SOURCE_ROOT SIM_PENDULUM SIM_CHAIN5 SIM_KEPLER
 */
#include "../unit/check.h"
#include "eomc.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern const eomc_model pendulum_model, chain5_model, kepler_model, arenstorf_model,
    cart_pole_model, stiff_spring_model, van_der_pol_model;
extern const eomc_model_ext pendulum_model_ext, chain5_model_ext, kepler_model_ext,
    stiff_spring_model_ext, van_der_pol_model_ext;

static const char *root, *sim_pendulum, *sim_chain5, *sim_kepler;

#define KEPLER_T (2 * 3.14159265358979323846) /* the period, a = mu = 1 */

/* ---- the mpmath values ---- */

typedef struct Table {
    int nrow, ncol;
    double v[64][16];
} Table;

static int
read_table(const char *name, Table *tb)
{
    char path[4096], line[2048];
    snprintf(path, sizeof path, "%s/tests/sim/reference/%s", root, name);
    FILE *f = fopen(path, "r");
    tb->nrow = tb->ncol = 0;
    if (!f || !fgets(line, sizeof line, f))
        return -1;
    while (tb->nrow < 64 && fgets(line, sizeof line, f)) {
        char *p = line;
        int c = 0;
        while (c < 16 && *p && *p != '\n') {
            tb->v[tb->nrow][c++] = strtod(p, &p);
            if (*p == ',')
                p++;
        }
        tb->ncol = c;
        tb->nrow++;
    }
    fclose(f);
    return 0;
}

/* The largest |ref row - table row| over the table's rows, each at the
 * reference's row every `stride`. */
static double
table_diff(const eomc_reference *ref, const Table *tb, long stride)
{
    double d = 0;
    for (int r = 0; r < tb->nrow; r++) {
        long k = r * stride;
        if (k >= ref->nrows || fabs(ref->t[k] - tb->v[r][0]) > 1e-12)
            return INFINITY;
        for (int i = 0; i < ref->nx; i++)
            d = fmax(d, fabs(ref->x[k * ref->nx + i] - tb->v[r][1 + i]));
    }
    return d;
}

static eomc_sim *
sim_at_start(const eomc_model *m, double *x)
{
    eomc_sim *s = eomc_sim_alloc(m);
    eomc_sim_initial(s, x, x + m->nq);
    return s;
}

/* The Kepler orbit through the double start (x0, 0, 0, v0), at t: the
 * ellipse of its energy and angular momentum (mu = 1; the rounding of
 * v0 = sqrt(3) to a double shortens the period by 4e-16 of it, which puts
 * the exact orbit 3.6e-14 off its start after three periods of 2 pi),
 * from Kepler's equation E - e sin E = n t, in long double. */
static void
kepler_exact(const double *start, double t, double *x)
{
    long double r0 = start[0], v0 = start[3];
    long double a = 1 / (2 / r0 - v0 * v0), e = 1 - r0 / a;
    long double n = sqrtl(1 / (a * a * a)), b = a * sqrtl(1 - e * e);
    long double M = n * t, E = M;
    for (int it = 0; it < 60; it++)
        E -= (E - e * sinl(E) - M) / (1 - e * cosl(E));
    long double w = 1 - e * cosl(E);
    x[0] = (double)(a * (cosl(E) - e));
    x[1] = (double)(b * sinl(E));
    x[2] = (double)(-a * n * sinl(E) / w);
    x[3] = (double)(b * n * cosl(E) / w);
}

/* Whether GBS made the reference, as its source says first. */
static int
gbs(const eomc_reference *ref)
{
    const char *name = "Gragg-Bulirsch-Stoer extrapolation";
    return !ref->stiff && strncmp(ref->source, name, strlen(name)) == 0 &&
           strcmp(ref->method, name) == 0;
}

static void
reference_vs_mpmath(void)
{
    Table tb;
    double x[10];
    eomc_reference ref;

    int have = read_table("pendulum.csv", &tb) == 0 && tb.nrow == 41;
    eomc_sim *s = sim_at_start(&pendulum_model, x);
    eomc_run_opts o = eomc_run_defaults(&pendulum_model);
    o.t_end = 10, o.dt = 0.25;
    int rc = eomc_reference_compute(s, &pendulum_model_ext, &o, x, &ref);
    double d = rc == EOMC_OK && have ? table_diff(&ref, &tb, 1) : INFINITY;
    CHECK(d <= 2e-15, "pendulum: the reference is on the elliptic closed form to %.2g over "
          "t = 0 .. 10", d);
    CHECK(d <= ref.error + DBL_EPSILON * ref.scale,
          "... within its own error estimate %.2g (plus rounding to doubles)", ref.error);
    CHECK(gbs(&ref), "... made by GBS, not stiff: %s", ref.source);
    eomc_reference_free(&ref);
    eomc_sim_free(s);

    have = read_table("chain5.csv", &tb) == 0 && tb.nrow == 11;
    s = sim_at_start(&chain5_model, x);
    x[0] = 1.0;
    o = eomc_run_defaults(&chain5_model);
    o.dt = 1.0;
    rc = eomc_reference_compute(s, &chain5_model_ext, &o, x, &ref);
    d = rc == EOMC_OK && have ? table_diff(&ref, &tb, 1) : INFINITY;
    CHECK(d <= 2e-15, "chain5 (q1 = 1): the reference agrees with mpmath to %.2g at t = 0, "
          "1, .., 10", d);
    CHECK(d <= ref.error + DBL_EPSILON * ref.scale,
          "... within its own error estimate %.2g", ref.error);
    eomc_reference_free(&ref);
    o.dt = 0.01; /* rows between its steps: side steps */
    rc = eomc_reference_compute(s, &chain5_model_ext, &o, x, &ref);
    d = rc == EOMC_OK && have ? table_diff(&ref, &tb, 100) : INFINITY;
    CHECK(d <= 2e-15, "... and with rows every 0.01 (between its steps), to %.2g", d);
    CHECK(gbs(&ref), "... made by GBS: %s", ref.method);
    eomc_reference_free(&ref);
    eomc_sim_free(s);

    s = sim_at_start(&kepler_model, x);
    o = eomc_run_defaults(&kepler_model);
    o.dt = KEPLER_T;
    rc = eomc_reference_compute(s, &kepler_model_ext, &o, x, &ref);
    d = 0;
    for (long k = 0; rc == EOMC_OK && k < ref.nrows; k++) {
        double want[4];
        kepler_exact(x, ref.t[k], want);
        for (int i = 0; i < 4; i++)
            d = fmax(d, fabs(ref.x[k * 4 + i] - want[i]));
    }
    CHECK(rc == EOMC_OK && ref.nrows == 4 && d <= 4e-15 && gbs(&ref),
          "kepler: after 1, 2, 3 periods the reference (%s) is on Kepler's equation's "
          "solution to %.2g", ref.method, d);
    eomc_reference_free(&ref);
    eomc_sim_free(s);
}

/* ---- the reported errors ---- */

/* A run as --work-precision makes it: from x0, for o (method, rtol = atol
 * = tol or fixed steps h), the largest error at the rows against
 * want(k, x_k) and the one at the last row. */
typedef struct Measure {
    const Table *tb;       /* rows to compare with, every `stride` rows */
    long stride;
    const double *start;   /* or: Kepler's orbit from this start */
    double err_max, err_end;
    long k;
} Measure;

static int
measure_row(void *ctx, double t, const double *x)
{
    Measure *m = ctx;
    if (m->k % m->stride == 0) {
        double orbit[4];
        if (m->start)
            kepler_exact(m->start, t, orbit);
        const double *want = m->start ? orbit : m->tb->v[m->k / m->stride] + 1;
        double e = 0;
        for (int i = 0; i < (m->start ? 4 : m->tb->ncol - 1); i++)
            e = fmax(e, fabs(x[i] - want[i]));
        m->err_max = fmax(m->err_max, e);
        m->err_end = e;
    }
    m->k++;
    return 0;
}

/* A CSV of --work-precision: its rows as method, tolerance, fixed_step
 * and the other columns by name.  Empty cells read as NAN. */
typedef struct Report {
    int nrow;
    char method[64][16];
    double v[64][13];
} Report;

static const char *const report_header =
    "method,tolerance,fixed_step,cpu_seconds,steps,rejected,rhs_evals,jac_evals,"
    "error_end,error_max,invariant_drift,constraint_residual,order_mean";
enum { R_TOL = 1, R_FIXED = 2, R_STEPS = 4, R_END = 8, R_MAX = 9 };

static int
read_report(const char *path, Report *r)
{
    char line[4096];
    FILE *f = fopen(path, "r");
    r->nrow = 0;
    if (!f || !fgets(line, sizeof line, f) || strncmp(line, report_header,
                                                     strlen(report_header)) != 0 ||
        line[strlen(report_header)] != '\n') {
        if (f)
            fclose(f);
        return -1;
    }
    while (r->nrow < 64 && fgets(line, sizeof line, f)) {
        char *p = line, *comma = strchr(p, ',');
        if (!comma)
            break;
        snprintf(r->method[r->nrow], 16, "%.*s", (int)(comma - p), p);
        p = comma + 1;
        for (int c = 1; c < 13; c++) {
            char *end;
            double x = strtod(p, &end);
            r->v[r->nrow][c] = end == p ? NAN : x;
            p = strchr(end, ',');
            p = p ? p + 1 : end;
        }
        r->nrow++;
    }
    fclose(f);
    return 0;
}

/* Run the simulator's report with these options into a CSV; its rows. */
static int
run_report(const char *sim, const char *args, Report *r)
{
    char csv[] = "/tmp/eomc-accuracy-XXXXXX", cmd[4096];
    int fd = mkstemp(csv);
    if (fd < 0)
        return -1;
    close(fd);
    snprintf(cmd, sizeof cmd, "'%s' --work-precision %s --csv '%s' > /dev/null", sim, args,
             csv);
    int st = system(cmd);
    int rc = st != -1 && WIFEXITED(st) && WEXITSTATUS(st) == 0 ? read_report(csv, r) : -1;
    unlink(csv);
    return rc;
}

/* Every row of the report against the same run measured here: the largest
 * |reported - independent| of error_end and error_max, and whether each
 * row was found and ran. */
static double
compare_report(const Report *r, const eomc_model *m, const double *x0, eomc_run_opts base,
               Measure proto, int *all_ok)
{
    double worst = 0;
    *all_ok = r->nrow > 0;
    for (int k = 0; k < r->nrow; k++) {
        eomc_sim *s = eomc_sim_alloc(m);
        eomc_run_opts o = base;
        o.method = r->method[k];
        o.max_steps = 100000;
        if (isnan(r->v[k][R_FIXED]))
            o.rtol = o.atol = r->v[k][R_TOL];
        else
            o.h_fixed = r->v[k][R_FIXED];
        double x[10];
        memcpy(x, x0, 2 * (size_t)m->nq * sizeof *x);
        Measure me = proto;
        int rc = eomc_sim_integrate(s, &o, x, measure_row, &me, NULL);
        eomc_sim_free(s);
        if (rc != EOMC_OK || isnan(r->v[k][R_END])) {
            *all_ok = 0;
            continue;
        }
        worst = fmax(worst, fabs(me.err_end - r->v[k][R_END]));
        worst = fmax(worst, fabs(me.err_max - r->v[k][R_MAX]));
    }
    return worst;
}

static void
reported_errors(void)
{
    Table tb;
    Report r;
    double x[10];
    int ok;

    read_table("pendulum.csv", &tb);
    eomc_sim *s = sim_at_start(&pendulum_model, x);
    eomc_sim_free(s);
    eomc_run_opts o = eomc_run_defaults(&pendulum_model);
    o.t_end = 10, o.dt = 0.25;
    int rc = run_report(sim_pendulum, "--t-end 10 --dt 0.25 --methods rk8pd,rkf45,rk4,msbdf "
                        "--tolerances 1e-5,1e-8,1e-11", &r);
    double worst = rc == 0 ? compare_report(&r, &pendulum_model, x, o,
                                            (Measure){&tb, 1, NULL, 0, 0, 0}, &ok)
                           : INFINITY;
    CHECK(rc == 0 && ok && r.nrow == 15 && worst <= 4e-15,
          "pendulum: the %d errors --work-precision reports are those against the "
          "closed form, to %.2g", 2 * r.nrow, worst);

    read_table("chain5.csv", &tb);
    s = sim_at_start(&chain5_model, x);
    eomc_sim_free(s);
    x[0] = 1.0;
    o = eomc_run_defaults(&chain5_model);
    o.dt = 1.0;
    rc = run_report(sim_chain5, "--init q1=1.0 --dt 1 --methods rk8pd,rkck,rk4imp "
                    "--tolerances 1e-6,1e-10 --steps 0.01", &r);
    worst = rc == 0 ? compare_report(&r, &chain5_model, x, o,
                                     (Measure){&tb, 1, NULL, 0, 0, 0}, &ok)
                    : INFINITY;
    CHECK(rc == 0 && ok && r.nrow == 9 && worst <= 4e-15,
          "chain5: the %d errors reported are those against mpmath's values, to %.2g",
          2 * r.nrow, worst);

    s = sim_at_start(&kepler_model, x);
    eomc_sim_free(s);
    o = eomc_run_defaults(&kepler_model);
    o.dt = KEPLER_T;
    char args[256];
    snprintf(args, sizeof args, "--dt %.17g --methods rk8pd,rkf45,msadams --tolerances "
             "1e-6,1e-9,1e-12", KEPLER_T);
    rc = run_report(sim_kepler, args, &r);
    worst = rc == 0 ? compare_report(&r, &kepler_model, x, o,
                                     (Measure){NULL, 1, x, 0, 0, 0}, &ok)
                    : INFINITY;
    CHECK(rc == 0 && ok && r.nrow == 9 && worst <= 4e-15,
          "kepler: the %d errors reported after whole periods are those against Kepler's "
          "equation, to %.2g", 2 * r.nrow, worst);
}

/* ---- rows cost no steps ---- */

typedef struct Closeness {
    double worst;
    long rows;
    const double *start;
} Closeness;

static int
kepler_row(void *ctx, double t, const double *x)
{
    Closeness *c = ctx;
    double want[4];
    kepler_exact(c->start, t, want);
    for (int i = 0; i < 4; i++)
        c->worst = fmax(c->worst, fabs(x[i] - want[i]));
    c->rows++;
    return 0;
}

static void
rows_cost_no_steps(void)
{
    eomc_stats fine, coarse;
    double x[4], x0[4];
    eomc_sim *s = sim_at_start(&kepler_model, x);
    memcpy(x0, x, sizeof x0);
    Closeness c = {0, 0, x0};
    eomc_run_opts o = eomc_run_defaults(&kepler_model);
    o.dt = 0.031;
    int rc = eomc_sim_integrate(s, &o, x, kepler_row, &c, &fine);
    eomc_sim_initial(s, x, x + 2);
    o.dt = o.t_end;
    rc |= eomc_sim_integrate(s, &o, x, NULL, NULL, &coarse);
    CHECK(rc == EOMC_OK && fine.steps == coarse.steps && fine.rhs_evals == coarse.rhs_evals,
          "kepler, rk8pd at 1e-10: %ld steps and %ld right-hand sides with rows every "
          "0.031, %ld and %ld with one row at the end", fine.steps, fine.rhs_evals,
          coarse.steps, coarse.rhs_evals);
    CHECK(c.rows == 610 && c.worst < 2e-9 && fine.side_steps == 0,
          "... its %ld interpolated rows are within %.2g of Kepler's equation's solution",
          c.rows, c.worst);
    eomc_sim_free(s);
}

/* ---- conserved quantities ---- */

typedef struct Drift {
    eomc_sim *s;
    double h0, E0, dh, dE;
    long n;
} Drift;

static int
drift_row(void *ctx, double t, const double *x)
{
    Drift *d = ctx;
    double h, T, V;
    eomc_sim_invariant(d->s, t, x, x + 2, &h);
    eomc_sim_energy(d->s, t, x, x + 2, &T, &V);
    if (d->n++ == 0)
        d->h0 = h, d->E0 = T + V;
    d->dh = fmax(d->dh, fabs(h - d->h0));
    d->dE = fmax(d->dE, fabs(T + V - d->E0));
    return 0;
}

static void
invariants(void)
{
    const double mu = 0.012277471;
    eomc_sim *s = eomc_sim_alloc(&arenstorf_model);
    double worst = 0;
    for (int k = 0; k < 100; k++) {
        double q[2] = {check_rand(-1.5, 1.5), check_rand(-1.5, 1.5)};
        double v[2] = {check_rand(-2, 2), check_rand(-2, 2)}, h;
        double r1 = hypot(q[0] + mu, q[1]), r2 = hypot(q[0] - 1 + mu, q[1]);
        double jacobi = 0.5 * (v[0] * v[0] + v[1] * v[1]) -
                        0.5 * (q[0] * q[0] + q[1] * q[1]) - (1 - mu) / r1 - mu / r2;
        eomc_sim_invariant(s, 0, q, v, &h);
        worst = fmax(worst, fabs(h - jacobi) / fmax(1, fabs(jacobi)));
    }
    CHECK(arenstorf_model.invariant && !strcmp(arenstorf_model.invariant_name, "h") &&
              worst < 1e-14,
          "arenstorf: the conserved quantity is h = (x'^2 + y'^2)/2 - (x^2 + y^2)/2 + V, "
          "to %.2g at 100 states", worst);
    double x[4];
    eomc_sim_initial(s, x, x + 2);
    eomc_run_opts o = eomc_run_defaults(&arenstorf_model);
    Drift d = {s, 0, 0, 0, 0, 0};
    int rc = eomc_sim_integrate(s, &o, x, drift_row, &d, NULL);
    CHECK(rc == EOMC_OK && d.dh <= 1e-12 * fabs(d.h0) && d.dE > 0.1,
          "arenstorf, rk8pd at 1e-12 over the period: h holds to %.2g (%.2g relative) "
          "where T + V changes by %.2g", d.dh, d.dh / fabs(d.h0), d.dE);
    double back = 0, x0[4];
    eomc_sim_initial(s, x0, x0 + 2);
    for (int i = 0; i < 4; i++)
        back = fmax(back, fabs(x[i] - x0[i]));
    CHECK(rc == EOMC_OK && back < 1e-8,
          "... and after the published period 17.0652165601579625588917206249 it is back "
          "at its start, to %.2g", back);
    eomc_sim_free(s);

    s = eomc_sim_alloc(&pendulum_model);
    worst = 0;
    for (int k = 0; k < 100; k++) {
        double q = check_rand(-3, 3), v = check_rand(-5, 5), h, T, V;
        eomc_sim_invariant(s, 0, &q, &v, &h);
        eomc_sim_energy(s, 0, &q, &v, &T, &V);
        worst = fmax(worst, fabs(h - (0.5 * v * v - 9.81 * cos(q))));
        worst = fmax(worst, fabs(h - (T + V)));
    }
    CHECK(!strcmp(pendulum_model.invariant_name, "E") && worst < 1e-13,
          "pendulum: the conserved quantity is E = T + V = v^2/2 - g cos(theta), to %.2g",
          worst);
    eomc_sim_free(s);
    CHECK(!strcmp(chain5_model.invariant_name, "E") &&
              !strcmp(kepler_model.invariant_name, "E"),
          "chain5 and kepler conserve E = T + V");
    CHECK(!cart_pole_model.invariant && !cart_pole_model.invariant_name &&
              strstr(cart_pole_model.invariant_note, "nothing is conserved") &&
              strstr(cart_pole_model.invariant_note, "'drive'"),
          "a driven, damped cart-pole conserves nothing, and says which effect: %s",
          cart_pole_model.invariant_note);
}

/* ---- units ---- */

static void
scaled_units(void)
{
    eomc_reference ref[2];
    double x[4];
    int rc = 0;
    for (int k = 0; k < 2; k++) {
        eomc_sim *s = eomc_sim_alloc(&kepler_model);
        if (k) { /* lengths in micrometres: a = 1e6, mu = 1e18 keeps the period */
            eomc_sim_set(s, "a", 1e6);
            eomc_sim_set(s, "mu", 1e18);
        }
        eomc_sim_initial(s, x, x + 2);
        eomc_run_opts o = eomc_run_defaults(&kepler_model);
        rc |= eomc_reference_compute(s, &kepler_model_ext, &o, x, &ref[k]);
        eomc_sim_free(s);
    }
    double r0 = ref[0].error / ref[0].scale, r1 = ref[1].error / ref[1].scale;
    CHECK(rc == EOMC_OK && ref[0].steps == ref[1].steps &&
              ref[0].refinements == ref[1].refinements && r1 <= 2 * r0 + 2 * DBL_EPSILON &&
              r0 <= 2 * r1 + 2 * DBL_EPSILON,
          "kepler in metres and in micrometres: the same reference steps (%ld, %ld) and "
          "relative error estimates (%.2g, %.2g)", ref[0].steps, ref[1].steps, r0, r1);
    eomc_reference_free(&ref[0]);
    eomc_reference_free(&ref[1]);
}

/* ---- stiff problems ---- */

/* The damped spring x'' + 10001 x' + 1e4 x = 0 from x = 1, x' = 0: roots
 * -1 and -1e4, in long double. */
static void
spring_exact(long double t, double *x)
{
    long double slow = expl(-t), fast = expl(-1e4L * t), d = 1 - 1e-4L;
    x[0] = (double)((slow - 1e-4L * fast) / d);
    x[1] = (double)((fast - slow) / d);
}

/* The largest distance of ref's rows from the spring's closed form, its
 * time unit `unit` seconds. */
static double
spring_diff(const eomc_reference *ref, double unit)
{
    double d = 0, want[2];
    for (long k = 0; k < ref->nrows; k++) {
        spring_exact((long double)ref->t[k] * unit, want);
        d = fmax(d, fabs(ref->x[2 * k] - want[0]));
        d = fmax(d, fabs(ref->x[2 * k + 1] - want[1] * unit)); /* velocity per unit */
    }
    return d;
}

/* Whether the linearly implicit method made the reference, and says
 * why. */
static int
linearly_implicit(const eomc_reference *ref)
{
    const char *name = "linearly implicit Euler extrapolation";
    return ref->stiff && strcmp(ref->method, name) == 0 &&
           strncmp(ref->source, name, strlen(name)) == 0 &&
           strstr(ref->source, "the problem is stiff") != NULL;
}

static void
stiff_references(void)
{
    const eomc_model *m = &stiff_spring_model;
    eomc_reference ref, ms;
    double x[2];
    /* over the decay (the scene: rows every 1 to 100), then through the
     * transient (rows every 1e-4, its time constant, to 1) */
    eomc_sim *s = sim_at_start(m, x);
    eomc_run_opts o = eomc_run_defaults(m);
    int rc = eomc_reference_compute(s, &stiff_spring_model_ext, &o, x, &ref);
    double d = rc == EOMC_OK ? spring_diff(&ref, 1) : INFINITY;
    CHECK(rc == EOMC_OK && linearly_implicit(&ref),
          "stiff spring: the reference is the linearly implicit one, and says why: %s",
          rc == EOMC_OK ? ref.source : eomc_sim_error(s));
    CHECK(d <= ref.error + DBL_EPSILON * ref.scale,
          "... over t = 0 .. 100 it is on the closed form to %.2g, within its own error "
          "estimate %.2g (plus rounding to doubles)", d, ref.error);
    /* the work of msbdf's run at the scene's rtol 1e-8 (a Jacobian counted as
     * the 2n + 1 right-hand sides of finite differences), against the
     * reference's last solution: GBS's took 1.7e7 right-hand sides */
    eomc_stats st;
    int rc2 = eomc_sim_integrate(s, &o, x, NULL, NULL, &st);
    double run = (double)st.rhs_evals + 3.0 * (double)st.jac_evals;
    CHECK(rc2 == EOMC_OK && (double)ref.rhs_evals <= 100 * run,
          "... its last solution spends %ld right-hand sides, %.1f times the work of "
          "msbdf's run at rtol 1e-8 (%.0f)", ref.rhs_evals, (double)ref.rhs_evals / run,
          run);
    eomc_reference_free(&ref);
    eomc_sim_initial(s, x, x + 1);
    o.t_end = 1, o.dt = 1e-4;
    rc = eomc_reference_compute(s, &stiff_spring_model_ext, &o, x, &ref);
    d = rc == EOMC_OK ? spring_diff(&ref, 1) : INFINITY;
    CHECK(rc == EOMC_OK && linearly_implicit(&ref) &&
              d <= ref.error + DBL_EPSILON * ref.scale,
          "... with rows every 1e-4 (the fast time constant) to t = 1 to %.2g, within "
          "%.2g", d, ref.error);
    eomc_reference_free(&ref);
    eomc_sim_free(s);

    /* in milliseconds: k = 1e4 / ms^2 = 1e-2, c = 10.001, span 1e5 */
    s = eomc_sim_alloc(m);
    eomc_sim_set(s, "k", 1e-2);
    eomc_sim_set(s, "c", 10.001);
    eomc_sim_initial(s, x, x + 1);
    o = eomc_run_defaults(m);
    o.t_end = 1e5, o.dt = 1e3;
    rc = eomc_reference_compute(s, &stiff_spring_model_ext, &o, x, &ms);
    eomc_sim_free(s);
    s = sim_at_start(m, x);
    o = eomc_run_defaults(m);
    rc |= eomc_reference_compute(s, &stiff_spring_model_ext, &o, x, &ref);
    d = rc == EOMC_OK ? spring_diff(&ms, 1e-3) : INFINITY;
    /* (1e-3 is no power of 2: rounding may tip a step's acceptance) */
    CHECK(rc == EOMC_OK && linearly_implicit(&ms) &&
              labs(ms.steps - ref.steps) <= ref.steps / 50 &&
              ms.refinements == ref.refinements && d <= ms.error + DBL_EPSILON * ms.scale,
          "... in milliseconds: the same method, steps (%ld, %ld, within 2 %%) and "
          "refinements, on the closed form to %.2g", ms.steps, ref.steps, d);
    eomc_reference_free(&ms);
    eomc_reference_free(&ref);
    eomc_sim_free(s);

    /* Van der Pol, eps = 1e-6: the test set's reference at t = 2 (vdpol.f,
     * revision 1.2 of 2006; its earlier x' was -0.8928097010248125, 1.5e-14
     * away, which is how well it knows itself) */
    const double published[2] = {1.706167732170483, -0.8928097010247975}, own = 1.5e-14;
    m = &van_der_pol_model;
    s = sim_at_start(m, x);
    o = eomc_run_defaults(m);
    rc = eomc_reference_compute(s, &van_der_pol_model_ext, &o, x, &ref);
    d = INFINITY;
    if (rc == EOMC_OK && ref.t[ref.nrows - 1] == 2)
        d = fmax(fabs(ref.x[2 * ref.nrows - 2] - published[0]),
                 fabs(ref.x[2 * ref.nrows - 1] - published[1]));
    CHECK(rc == EOMC_OK && linearly_implicit(&ref),
          "van der pol, eps = 1e-6: the linearly implicit reference (%s)",
          rc == EOMC_OK ? ref.source : eomc_sim_error(s));
    CHECK(d <= ref.error + own,
          "... at t = 2 it is on the test set's published value to %.2g, within its own "
          "error estimate %.2g and the published value's %.2g", d, ref.error, own);
    eomc_reference_free(&ref);
    eomc_sim_free(s);
}

/* ---- fixed implicit steps ---- */

/* The pendulum with fixed steps h to t = 10 at rtol = atol = 1e-6: the
 * largest error at t = 10 against the mpmath table's last row. */
static double
pendulum_fixed(const char *method, double h, const Table *tb)
{
    double x[2];
    eomc_sim *s = sim_at_start(&pendulum_model, x);
    eomc_run_opts o = eomc_run_defaults(&pendulum_model);
    o.t_end = 10, o.dt = 10, o.method = method, o.h_fixed = h;
    o.rtol = o.atol = 1e-6;
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, NULL);
    eomc_sim_free(s);
    const double *want = tb->v[tb->nrow - 1];
    return rc == EOMC_OK && want[0] == 10 ? fmax(fabs(x[0] - want[1]), fabs(x[1] - want[2]))
                                          : NAN;
}

/* Stopped at the tolerance, the stages' error (the tolerance's, a step)
 * outweighed the method's (rk4imp: 6.8e-6 at h = 1e-2, 6.0e-6 at 1e-3);
 * solved to rounding, the error falls as h^order.  The steps: each
 * method's error at h / 10 well above the rounding of its 10^4 or 10^5
 * steps. */
static void
fixed_implicit_order(void)
{
    static const struct {
        const char *name;
        int order;
        double h;
    } m[] = {{"rk1imp", 1, 1e-3}, {"rk2imp", 2, 1e-3}, {"rk4imp", 4, 1e-2}};
    Table tb;
    int have = read_table("pendulum.csv", &tb) == 0 && tb.nrow == 41;
    for (int k = 0; k < 3; k++) {
        double e1 = have ? pendulum_fixed(m[k].name, m[k].h, &tb) : NAN;
        double e2 = have ? pendulum_fixed(m[k].name, m[k].h / 10, &tb) : NAN;
        double want = pow(10, m[k].order), ratio = e1 / e2;
        CHECK(ratio > 0.5 * want && ratio < 2 * want,
              "%s, fixed steps of %g and %g at rtol 1e-6: errors %.3g and %.3g, falling by "
              "%.3g (10^%d)", m[k].name, m[k].h, m[k].h / 10, e1, e2, ratio, m[k].order);
    }
}

int
main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: test_accuracy SOURCE_ROOT SIM_PENDULUM SIM_CHAIN5 "
                        "SIM_KEPLER\n");
        return 2;
    }
    root = argv[1], sim_pendulum = argv[2], sim_chain5 = argv[3], sim_kepler = argv[4];
    reference_vs_mpmath();
    reported_errors();
    rows_cost_no_steps();
    invariants();
    scaled_units();
    stiff_references();
    fixed_implicit_order();
    return check_done();
}

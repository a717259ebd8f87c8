/*
 * eomc_sim_integrate on hand-written models (models.h):
 *  - output rows at t0, t0 + k dt and exactly t_end (also when t_end is not
 *    a multiple of dt), states on the closed form, x left at the last row;
 *  - a time-dependent input from t0 != 0, and an input held by
 *    eomc_sim_set, against the driven oscillator's closed forms;
 *  - bad options: EOMC_EUSAGE, a message, no rows; max_steps: EOMC_ENUMERIC
 *    naming "steps"; a row callback's nonzero status stops the run;
 *  - energy conserved to 1e-9 (rk8pd at 1e-12) by the oscillator over 100
 *    periods and by the double pendulum (accel NULL) over 10 s;
 *  - M losing positive definiteness at t = 1: EOMC_ENUMERIC, finite rows
 *    before the failure time, a "t = ..." message naming the state;
 *  - after every kind of stop (the row callback, SIGINT through it, an
 *    event callback, a `stop` event, a failure, t_end), x is the state at
 *    st.t_stop: the closed form there.
 */
#define _POSIX_C_SOURCE 200809L
#include "../unit/check.h"
#include "rtest.h"

#include <signal.h>

/* The oscillator with rk8pd at 1e-12 from its initial state. */
static int
osc_run(double t_end, double dt, Rows *r, double *x)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, t_end, dt, "rk8pd", 1e-12, 1e-12);
    eomc_stats st;
    rows_init(r, 1);
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, r, &st);
    eomc_sim_free(s);
    return rc;
}

/* Rows at k dt (k < n - 1) and exactly t_end, on the closed form. */
static int
rows_on_grid(const Rows *r, double dt, double t_end)
{
    int ok = r->n >= 2 && r->t[0] == 0.0 && r->t[r->n - 1] == t_end;
    for (int k = 0; ok && k < r->n; k++) {
        double xe, ve;
        if (k < r->n - 1)
            ok &= fabs(r->t[k] - k * dt) <= 1e-12 && r->t[k] < t_end;
        osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, r->t[k], &xe, &ve);
        ok &= fabs(rows_x(r, k)[0] - xe) < 1e-9 && fabs(rows_x(r, k)[1] - ve) < 1e-9;
    }
    return ok;
}

static void
output_rows(void)
{
    Rows r;
    double x[2];
    int rc = osc_run(1.05, 0.1, &r, x);
    CHECK(rc == EOMC_OK && r.n == 12, "t_end = 1.05, dt = 0.1: 12 rows (got %d)", r.n);
    CHECK(r.n > 0 && r.t[r.n - 1] == 1.05, "... the last exactly at t_end = 1.05 (got %.17g)",
          r.n ? r.t[r.n - 1] : NAN);
    CHECK(rows_on_grid(&r, 0.1, 1.05), "... t0 first, then k dt, states on the closed form");
    CHECK(r.n > 0 && rows_x(&r, 0)[0] == OSC_X0 && rows_x(&r, 0)[1] == OSC_V0,
          "... the first row is the initial state");
    CHECK(r.n > 0 && x[0] == rows_x(&r, r.n - 1)[0] && x[1] == rows_x(&r, r.n - 1)[1],
          "... x is left at the last row's state");
    rows_free(&r);

    rc = osc_run(1.0, 0.1, &r, x);
    CHECK(rc == EOMC_OK && r.n == 11 && rows_on_grid(&r, 0.1, 1.0),
          "t_end = 1.0 = 10 dt: 11 rows, no sliver of a last interval (got %d)", r.n);
    rows_free(&r);
    rc = osc_run(10.0, 0.1, &r, x);
    CHECK(rc == EOMC_OK && r.n == 101 && rows_on_grid(&r, 0.1, 10.0),
          "t_end = 10, dt = 0.1: 101 rows on the grid (got %d)", r.n);
    rows_free(&r);
    rc = osc_run(0.05, 0.1, &r, x);
    CHECK(rc == EOMC_OK && r.n == 2 && rows_on_grid(&r, 0.1, 0.05),
          "dt > t_end - t0: 2 rows, t0 and t_end (got %d)", r.n);
    rows_free(&r);
}

/* The driven oscillator from t0 on its closed form: every row on it. */
static void
driven_from_t0(void)
{
    eomc_sim *s = sim_new(&driven_model);
    eomc_run_opts o = opts_for(&driven_model, 2.3, 0.25, "rk8pd", 1e-12, 1e-12);
    o.t0 = 0.3;
    double x[2];
    Rows r;
    rows_init(&r, 1);
    driven_exact(DRIVEN_M, DRIVEN_K, DRIVEN_A, DRIVEN_W, DRIVEN_X0, DRIVEN_V0, o.t0, &x[0],
                 &x[1]);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    int ok = rc == EOMC_OK && r.n == 9 && r.t[0] == 0.3 && r.t[8] == 2.3;
    for (int k = 0; ok && k < r.n; k++) {
        double xe, ve;
        driven_exact(DRIVEN_M, DRIVEN_K, DRIVEN_A, DRIVEN_W, DRIVEN_X0, DRIVEN_V0, r.t[k], &xe,
                     &ve);
        ok &= fabs(r.t[k] - (0.3 + 0.25 * k)) < 1e-12;
        ok &= fabs(rows_x(&r, k)[0] - xe) < 1e-9 && fabs(rows_x(&r, k)[1] - ve) < 1e-9;
    }
    CHECK(ok, "driven, u = A sin(w t), from t0 = 0.3 (st NULL): 9 rows on the closed form");
    rows_free(&r);
    eomc_sim_free(s);
}

static void
driven_held(void)
{
    eomc_sim *s = sim_new(&driven_model);
    eomc_run_opts o = opts_for(&driven_model, 3.0, 0.5, "rkck", 1e-12, 1e-12);
    double x[2], k = DRIVEN_K, w0 = sqrt(DRIVEN_K / DRIVEN_M), ue = 0.7 / k;
    eomc_sim_set(s, "u", 0.7);
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, NULL);
    double xe = ue + (DRIVEN_X0 - ue) * cos(w0 * 3) + DRIVEN_V0 / w0 * sin(w0 * 3);
    CHECK(rc == EOMC_OK && fabs(x[0] - xe) < 1e-9,
          "driven with u held at 0.7: x(3) = u/k + (x0 - u/k) cos(w0 t) + v0/w0 sin(w0 t) "
          "(error %.3g)",
          fabs(x[0] - xe));
    eomc_sim_free(s);
}

/* One bad option: EOMC_EUSAGE, a message, no rows, x untouched. */
static void
bad_option(const eomc_run_opts *o, const char *what)
{
    eomc_sim *s = sim_new(&osc_model);
    Rows r;
    rows_init(&r, 1);
    double x[2] = {0.25, -0.5};
    int rc = eomc_sim_integrate(s, o, x, rows_add, &r, NULL);
    const char *e = eomc_sim_error(s);
    CHECK(rc == EOMC_EUSAGE && e[0] != '\0' && r.n == 0 && x[0] == 0.25 && x[1] == -0.5,
          "%s: EOMC_EUSAGE (got %d, %d rows): %s", what, rc, r.n, e);
    rows_free(&r);
    eomc_sim_free(s);
}

static void
bad_options(void)
{
    eomc_run_opts good = opts_for(&osc_model, 1.0, 0.1, "rkf45", 1e-8, 1e-8), o;
    o = good, o.method = "nosuch";
    bad_option(&o, "unknown method");
    o = good, o.method = "RK4";
    bad_option(&o, "method names are case-sensitive");
    o = good, o.dt = 0.0;
    bad_option(&o, "dt = 0");
    o = good, o.dt = -0.1;
    bad_option(&o, "dt < 0");
    o = good, o.t0 = 2.0;
    bad_option(&o, "t_end < t0");
    o = good, o.rtol = -1e-8;
    bad_option(&o, "rtol < 0");
    o = good, o.atol = -1e-8;
    bad_option(&o, "atol < 0");
}

static void
max_steps(void)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 10.0, 0.1, "rkf45", 1e-12, 1e-12);
    o.max_steps = 5;
    Rows r;
    rows_init(&r, 1);
    double x[2];
    eomc_stats st;
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    const char *e = eomc_sim_error(s);
    CHECK(rc == EOMC_ENUMERIC && strstr(e, "steps"),
          "max_steps = 5 over 10 s at 1e-12: EOMC_ENUMERIC naming steps (got %d): %s", rc, e);
    CHECK(st.steps <= 5 && r.n >= 1 && r.n < 101 && rows_finite(&r),
          "... %ld steps taken, %d finite rows kept", st.steps, r.n);
    rows_free(&r);

    rows_init(&r, 1);
    o.max_steps = 100000;
    sim_x0(s, x);
    rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    CHECK(rc == EOMC_OK && r.n == 101, "max_steps = 100000: the same run completes (%ld steps)",
          st.steps);
    rows_free(&r);
    eomc_sim_free(s);
}

/* The steps a run needs, S: max_steps = S completes, S - 1 does not. */
static void
max_steps_exact(void)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 2.0, 0.5, "rkf45", 1e-10, 1e-10);
    double x[2];
    eomc_stats st;
    sim_x0(s, x);
    eomc_sim_integrate(s, &o, x, NULL, NULL, &st);
    long need = st.steps;
    o.max_steps = need;
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, &st);
    CHECK(rc == EOMC_OK && st.steps == need, "max_steps = %ld, the steps the run needs: "
          "completes (rc %d, %ld steps)", need, rc, st.steps);
    o.max_steps = need - 1;
    sim_x0(s, x);
    rc = eomc_sim_integrate(s, &o, x, NULL, NULL, &st);
    CHECK(rc == EOMC_ENUMERIC && st.steps <= need - 1,
          "max_steps = %ld, one short: EOMC_ENUMERIC after at most %ld steps (rc %d, %ld steps)",
          need - 1, need - 1, rc, st.steps);
    eomc_sim_free(s);
}

static void
row_stops(void)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 1.0, 0.1, "rk4", 1e-10, 1e-10);
    Rows r;
    rows_init(&r, 1);
    r.stop_at = 3;
    r.stop_status = 42;
    double x[2];
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    CHECK(rc == 42 && r.n == 4, "row callback returns 42 at the 4th row: integrate returns %d "
          "after %d rows", rc, r.n);
    rows_free(&r);
    eomc_sim_free(s);
}

/* ---- where the run stops: x and t_stop (issue 21, item 2) ----
 * After every kind of stop, x holds the state at st.t_stop, checked
 * against the oscillator's closed form there (and the nonpd model's
 * zeta = t). */

/* |x - closed form at t| for the oscillator from its initial state. */
static double
osc_off(double t, const double *x)
{
    double xe, ve;
    osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, t, &xe, &ve);
    return fmax(fabs(x[0] - xe), fabs(x[1] - ve));
}

/* The row callback stops at row 3 (t = 0.3), after two steps have gone
 * past it (rk8pd takes steps of about 0.5 at 1e-12). */
static void
stop_by_row(void)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 10.0, 0.1, "rk8pd", 1e-12, 1e-12);
    Rows r;
    rows_init(&r, 1);
    r.stop_at = 3;
    r.stop_status = 42;
    double x[2];
    eomc_stats st;
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    CHECK(rc == 42 && r.n == 4 && st.t_stop == r.t[3] &&
              st.t_stop == eomc_run_row_time(&o, 3),
          "the row callback stops at row 3: t_stop = %.17g, that row's time", st.t_stop);
    CHECK(r.n == 4 && memcmp(x, rows_x(&r, 3), sizeof x) == 0 && osc_off(st.t_stop, x) < 1e-10,
          "... x is that row's state, on the closed form there to %.2g", osc_off(st.t_stop, x));
    rows_free(&r);
    rows_init(&r, 1);
    sim_x0(s, x);
    rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    CHECK(rc == EOMC_OK && st.t_stop == o.t_end && memcmp(x, rows_x(&r, r.n - 1), sizeof x) == 0,
          "a run to the end: t_stop = t_end = %g, x the last row's state", st.t_stop);
    rows_free(&r);
    eomc_sim_free(s);
}

/* SIGINT, as eomc_main takes it: the handler sets a flag, the row callback
 * returns nonzero on it; the signal arrives at row 7. */
static volatile sig_atomic_t got_signal;
static void
on_sigint(int sig)
{
    got_signal = sig;
}
static int
row_until_signal(void *ctx, double t, const double *x)
{
    Rows *r = ctx;
    rows_add(r, t, x);
    if (r->n == 8)
        raise(SIGINT);
    return got_signal ? 130 : 0;
}

static void
stop_by_signal(void)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 10.0, 0.1, "rkf45", 1e-10, 1e-10);
    struct sigaction sa = {0}, old;
    sa.sa_handler = on_sigint;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old);
    got_signal = 0;
    Rows r;
    rows_init(&r, 1);
    double x[2];
    eomc_stats st;
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, row_until_signal, &r, &st);
    sigaction(SIGINT, &old, NULL);
    CHECK(rc == 130 && r.n == 8 && st.t_stop == r.t[7] &&
              memcmp(x, rows_x(&r, 7), sizeof x) == 0 && osc_off(st.t_stop, x) < 1e-8,
          "SIGINT at row 7: stops there, t_stop = %.17g and x that row's state, on the "
          "closed form to %.2g", st.t_stop, osc_off(st.t_stop, x));
    rows_free(&r);
    eomc_sim_free(s);
}

/* osc_event_model's event: x = 0 falling, at t* below. */
static double
down_time(void)
{
    double w = sqrt(OSC_K / OSC_M);
    return (acos(-1.0) / 2 + atan(OSC_V0 / (w * OSC_X0))) / w;
}

static int
event_says_stop(void *ctx, int k, double t, const double *x)
{
    (void)ctx;
    (void)k;
    (void)t;
    (void)x;
    return 7;
}

/* on_event returning nonzero, and the `stop` event itself. */
static void
stop_by_event(void)
{
    eomc_sim *s = sim_new(&osc_event_model);
    for (int told = 1; told >= 0; told--) {
        eomc_run_opts o = opts_for(&osc_event_model, 10.0, 0.1, "rk8pd", 1e-12, 1e-12);
        o.on_event = told ? event_says_stop : NULL;
        Rows r;
        rows_init(&r, 1);
        double x[2], ts = down_time();
        eomc_stats st;
        sim_x0(s, x);
        int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
        CHECK(rc == (told ? 7 : EOMC_OK) && st.stop_event == (told ? -1 : 0) &&
                  fabs(st.t_stop - ts) <= 1e-12 * ts,
              "%s: rc %d, t_stop = %.17g, the closed form's %.17g", told ?
              "on_event returns 7 at the event" : "the stop event", rc, st.t_stop, ts);
        CHECK(osc_off(st.t_stop, x) < 1e-10 && fabs(x[0]) < 1e-10,
              "... x is the state there: x = %.2g, x' = %.17g, on the closed form to %.2g",
              x[0], x[1], osc_off(st.t_stop, x));
        rows_free(&r);
    }
    eomc_sim_free(s);
}

/* A numerical failure: M = 1 - zeta^2 at zeta = t fails at t = 1.  x is
 * the last state reached, zeta = zeta' t = t_stop, and no row is after it. */
static void
stop_by_failure(void)
{
    eomc_sim *s = sim_new(&nonpd_model);
    eomc_run_opts o = eomc_run_defaults(&nonpd_model);
    Rows r;
    rows_init(&r, 1);
    double x[2];
    eomc_stats st;
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    CHECK(rc == EOMC_ENUMERIC && r.n > 0 && st.t_stop >= r.t[r.n - 1] && st.t_stop < 1.0 &&
              st.t_stop > 1.0 - 1e-6,
          "a failure at t = 1: t_stop = %.17g, just before it, at or after the last row "
          "(%.17g)", st.t_stop, r.n ? r.t[r.n - 1] : NAN);
    CHECK(fabs(x[0] - st.t_stop) <= 1e-12 && fabs(x[1] - 1.0) <= 1e-12,
          "... x is the state there: zeta - t_stop = %.2g, zeta' - 1 = %.2g", x[0] - st.t_stop,
          x[1] - 1.0);
    rows_free(&r);
    eomc_sim_free(s);
}

/* Largest |E - E0| / |E0| over the rows. */
static double
energy_drift(eomc_sim *s, const Rows *r)
{
    int n = eomc_sim_model(s)->nq;
    double T, V, E0 = 0, drift = 0;
    for (int k = 0; k < r->n; k++) {
        const double *x = rows_x(r, k);
        eomc_sim_energy(s, r->t[k], x, x + n, &T, &V);
        if (k == 0)
            E0 = T + V;
        drift = fmax(drift, fabs(T + V - E0) / fabs(E0));
    }
    return drift;
}

static void
energy(const eomc_model *m, double t_end, double dt, const char *what)
{
    eomc_sim *s = sim_new(m);
    eomc_run_opts o = opts_for(m, t_end, dt, "rk8pd", 1e-12, 1e-12);
    Rows r;
    rows_init(&r, m->nq);
    double x[4];
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    double drift = energy_drift(s, &r);
    int want = (int)ceil((t_end - o.t0) / dt - 1e-9) + 1;
    CHECK(rc == EOMC_OK && r.n == want && drift < 1e-9,
          "%s: energy conserved to %.3g relative over %d rows (rk8pd, 1e-12)", what, drift, r.n);
    rows_free(&r);
    eomc_sim_free(s);
}

static void
nonpd(const eomc_model *m)
{
    eomc_sim *s = sim_new(m);
    eomc_run_opts o = eomc_run_defaults(m);
    Rows r;
    rows_init(&r, 1);
    double x[2];
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    const char *e = eomc_sim_error(s);
    CHECK(rc == EOMC_ENUMERIC, "%s: M = 1 - zeta^2 fails at t = 1: EOMC_ENUMERIC (got %d)",
          m->name, rc);
    CHECK(strncmp(e, "t = ", 4) == 0 && strstr(e, "zeta"),
          "%s: the message starts with \"t = \" and names the state: %s", m->name, e);
    double tf = strncmp(e, "t = ", 4) == 0 ? strtod(e + 4, NULL) : NAN;
    int ok = r.n >= 10 && tf >= 1.0 - 1e-9 && tf <= 2.0 && rows_finite(&r);
    for (int k = 0; ok && k < r.n; k++)
        ok &= r.t[k] < tf && r.t[k] < 1.0 && fabs(rows_x(&r, k)[0] - r.t[k]) < 1e-9;
    CHECK(ok, "%s: %d finite rows (zeta = t), all before the failure at t = %g >= 1", m->name,
          r.n, tf);
    CHECK(isfinite(x[0]) && isfinite(x[1]) && x[0] < 1.0,
          "%s: x left at a state reached (zeta = %g)", m->name, x[0]);
    rows_free(&r);
    eomc_sim_free(s);
}

/* Two runs of one simulator: identical results (no state carried over). */
static void
repeatable(const char *method)
{
    eomc_sim *s = sim_new(&coupled_model);
    eomc_run_opts o = opts_for(&coupled_model, 3.0, 0.1, method, 1e-9, 1e-9);
    double x1[4], x2[4];
    eomc_stats st1, st2;
    sim_x0(s, x1);
    sim_x0(s, x2);
    int rc1 = eomc_sim_integrate(s, &o, x1, NULL, NULL, &st1);
    int rc2 = eomc_sim_integrate(s, &o, x2, NULL, NULL, &st2);
    CHECK(rc1 == EOMC_OK && rc2 == EOMC_OK && memcmp(x1, x2, sizeof x1) == 0 &&
              st1.steps == st2.steps && st1.rhs_evals == st2.rhs_evals,
          "%s: a second run of the same simulator is identical (%ld steps)", method, st1.steps);
    eomc_sim_free(s);
}

int
main(void)
{
    output_rows();
    driven_from_t0();
    driven_held();
    bad_options();
    max_steps();
    max_steps_exact();
    row_stops();
    stop_by_row();
    stop_by_signal();
    stop_by_event();
    stop_by_failure();
    energy(&osc_model, 100 * acos(-1.0), 0.05, "oscillator, 100 periods");
    energy(&coupled_model, 10.0, 0.01, "double pendulum (accel NULL), 10 s");
    nonpd(&nonpd_model);
    nonpd(&nonpd_gsl_model);
    repeatable("msbdf");
    repeatable("rk8pd");
    return check_done();
}

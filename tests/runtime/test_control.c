/*
 * A controller in the loop (eomc_sim_set_controller) on ctrlosc_model,
 * m x'' + k x = u, against closed forms computed here:
 *  - sampled, u = -KP x - KD v at t = k T, held between (a zero-order
 *    hold): over each period the motion is the oscillator's about u/k, so
 *    every row follows from the sample before it by that closed form,
 *    propagated sample to sample here in long double.  Under adaptive
 *    methods to 1e-10 of the state's scale; under fixed rk4 steps that
 *    divide each period, to its h^4 error; the controller is called once
 *    a sample, at exactly t0 + k T, and every step ends at or before the
 *    next sample (eomc_sim_step);
 *  - the reference solution (eomc_reference_compute) of the sampled loop,
 *    which calls the controller at the same instants: its rows equal the
 *    closed form within the error it claims, and a run's error against it
 *    is the run's true error;
 *  - continuous, u(t, x, v) inside the right-hand side: the damped
 *    oscillator m x'' + KD x' + (k + KP) x = 0, in closed form;
 *  - a controller that fails (a status, at t = 1) or sets a NaN: the run
 *    stops with that status, the rows up to the failure kept, the message
 *    naming the input and the time; a continuous controller refused by
 *    Taylor's method; a negative period refused.
 */
#include "../unit/check.h"
#include "rtest.h"

#include <float.h>

enum { SAMPLES_MAX = 4096 };

/* The gains: the closed loop is well damped, so the rows stay of order 1. */
static const double KP = 3.0, KD = 2.0;

typedef struct Ctrl {
    long calls;
    double t[SAMPLES_MAX];
    double fail_at; /* return 7 from here on (INFINITY: never) */
    int nan_at_fail; /* ... or set u to NaN there instead */
} Ctrl;

static int
pd(void *ctx, double t, const double *q, const double *v, double *u)
{
    Ctrl *c = ctx;
    if (c->calls < SAMPLES_MAX)
        c->t[c->calls] = t;
    c->calls++;
    if (t >= c->fail_at) {
        if (!c->nan_at_fail)
            return 7;
        u[0] = NAN;
        return 0;
    }
    u[0] = -KP * q[0] - KD * v[0];
    return 0;
}

/* The oscillator m x'' + k x = u (u constant) from (x, v) over tau. */
static void
held_motion(long double m, long double k, long double u, long double tau, long double *x,
            long double *v)
{
    long double w = sqrtl(k / m), c = u / k, x0 = *x - c, v0 = *v;
    *x = c + x0 * cosl(w * tau) + v0 / w * sinl(w * tau);
    *v = -x0 * w * sinl(w * tau) + v0 * cosl(w * tau);
}

/* The sampled loop's exact state at t (T the period), from (x0, v0). */
static void
sampled_exact(double T, double t, double *x, double *v)
{
    long double X = CTRLOSC_X0, V = CTRLOSC_V0, s = 0;
    for (long k = 0;; k++) {
        long double next = (long double)(k + 1) * (long double)T, u = -KP * X - KD * V;
        int last = next >= (long double)t;
        held_motion(CTRLOSC_M, CTRLOSC_K, u, (last ? (long double)t : next) - s, &X, &V);
        if (last)
            break;
        s = next;
    }
    *x = (double)X, *v = (double)V;
}

/* The largest error of the rows against the sampled loop's closed form,
 * relative to the state's scale (its largest entry). */
static double
sampled_error(const Rows *r, double T)
{
    double worst = 0, scale = 0;
    for (int i = 0; i < r->n; i++) {
        double x, v;
        sampled_exact(T, r->t[i], &x, &v);
        const double *y = rows_x(r, i);
        worst = fmax(worst, fmax(fabs(y[0] - x), fabs(y[1] - v)));
        scale = fmax(scale, fmax(fabs(x), fabs(v)));
    }
    return worst / scale;
}

static void
test_sampled(const char *method, double h_fixed, double tol)
{
    const double T = 0.1, t_end = 3;
    eomc_sim *s = sim_new(&ctrlosc_model);
    Ctrl c = {.fail_at = INFINITY};
    CHECK(eomc_sim_set_controller(s, pd, &c, T, NULL) == EOMC_OK, "a sampled controller");
    eomc_run_opts o = opts_for(&ctrlosc_model, t_end, 0.05, method, 1e-12, 1e-12);
    o.h_fixed = h_fixed;
    double x[2];
    sim_x0(s, x);
    Rows r;
    rows_init_model(&r, &ctrlosc_model);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    double err = sampled_error(&r, T);
    CHECK(rc == EOMC_OK && r.n == 61 && err <= tol,
          "%s%s: a sampled PD controller (T = %g) against the zero-order hold's closed "
          "form: %.3g of the state's scale (<= %g)", method, h_fixed > 0 ? " (fixed steps)" : "",
          T, err, tol);
    int at_samples = c.calls == 30;
    for (long k = 0; k < c.calls && k < SAMPLES_MAX && at_samples; k++)
        at_samples = c.t[k] == (double)k * T;
    CHECK(at_samples, "%s: called %ld times, once a sample, at exactly k T (30 samples before "
          "t_end)", method, c.calls);
    rows_free(&r);
    eomc_sim_free(s);
}

/* Every step ends at or before the next sample (eomc_sim_step). */
static void
test_steps_end_at_samples(void)
{
    const double T = 0.1;
    eomc_sim *s = sim_new(&ctrlosc_model);
    Ctrl c = {.fail_at = INFINITY};
    eomc_sim_set_controller(s, pd, &c, T, NULL);
    eomc_run_opts o = opts_for(&ctrlosc_model, 1, 0.05, "rk8pd", 1e-8, 1e-8);
    double x[2];
    sim_x0(s, x);
    eomc_evolve *e = eomc_evolve_alloc(s, &o, x);
    eomc_step d;
    int ok = e != NULL, steps = 0, ends = 0;
    while (ok) {
        if (eomc_sim_step(s, e, &d) != EOMC_OK) {
            ok = 0;
            break;
        }
        steps++;
        double next = (floor(d.t0 / T + 0.5) + 1) * T; /* the sample after t0 */
        ok = d.t1 <= next * (1 + 4 * DBL_EPSILON);
        ends += fabs(d.t1 / T - round(d.t1 / T)) < 1e-12;
        if (d.last)
            break;
    }
    eomc_evolve_free(e);
    CHECK(ok && ends == 10, "eomc_sim_step: %d steps, none across a sample, %d ending at "
          "one (10)", steps, ends);
    eomc_sim_free(s);
}

/* The same loop by hand (eomc_sim_set of the input at each sample,
 * eomc_evolve_restart, eomc_sim_advance to the next): the sampled
 * controller's rows at the samples, to the bit. */
static void
test_hand_loop(const char *method)
{
    const double T = 0.1, t_end = 3;
    eomc_sim *s = sim_new(&ctrlosc_model);
    Ctrl c = {.fail_at = INFINITY};
    eomc_sim_set_controller(s, pd, &c, T, NULL);
    eomc_run_opts o = opts_for(&ctrlosc_model, t_end, T, method, 1e-9, 1e-9);
    double x[2], u;
    sim_x0(s, x);
    Rows r;
    rows_init_model(&r, &ctrlosc_model);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    eomc_sim *h = sim_new(&ctrlosc_model); /* no controller: the loop is the caller's */
    sim_x0(h, x);
    eomc_evolve *e = eomc_evolve_alloc(h, &o, x);
    int same = rc == EOMC_OK && r.n == 31 && e != NULL, k = 0;
    eomc_step d = {.x1 = x};
    while (same && k < 30) {
        const double *y = k ? d.x1 : x;
        same = memcmp(y, rows_x(&r, k), sizeof x) == 0;
        u = -KP * y[0] - KD * y[1];
        same &= eomc_sim_set(h, "u", u) == EOMC_OK && eomc_evolve_restart(h, e, NULL) == EOMC_OK;
        double next = o.t0 + (double)++k * T;
        do
            same &= eomc_sim_advance(h, e, next, &d) == EOMC_OK;
        while (same && d.t1 < next);
    }
    same &= k == 30 && d.last && memcmp(d.x1, rows_x(&r, 30), sizeof x) == 0;
    CHECK(same, "%s: a loop by hand (set u, restart, advance to the next sample) takes the "
          "sampled controller's steps: its states at the %d samples are the run's to the bit",
          method, k);
    eomc_evolve_free(e);
    rows_free(&r);
    eomc_sim_free(h);
    eomc_sim_free(s);
}

/* x of m x'' + c x' + k x = 0 (underdamped) from (x0, v0). */
static void
damped_exact(double m, double c, double k, double t, double *x, double *v)
{
    double z = c / (2 * m), wd = sqrt(k / m - z * z), x0 = CTRLOSC_X0;
    double b = (CTRLOSC_V0 + z * x0) / wd, e = exp(-z * t);
    *x = e * (x0 * cos(wd * t) + b * sin(wd * t));
    *v = -z * *x + e * (-x0 * wd * sin(wd * t) + b * wd * cos(wd * t));
}

static void
test_continuous(void)
{
    eomc_sim *s = sim_new(&ctrlosc_model);
    Ctrl c = {.fail_at = INFINITY};
    CHECK(eomc_sim_set_controller(s, pd, &c, 0, NULL) == EOMC_OK, "a continuous controller");
    eomc_run_opts o = opts_for(&ctrlosc_model, 3, 0.05, "rk8pd", 1e-12, 1e-12);
    double x[2];
    sim_x0(s, x);
    Rows r;
    rows_init_model(&r, &ctrlosc_model);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    double worst = 0;
    for (int i = 0; i < r.n; i++) {
        double xe, ve;
        damped_exact(CTRLOSC_M, KD, CTRLOSC_K + KP, r.t[i], &xe, &ve);
        worst = fmax(worst, fmax(fabs(rows_x(&r, i)[0] - xe), fabs(rows_x(&r, i)[1] - ve)));
    }
    CHECK(rc == EOMC_OK && r.n == 61 && worst <= 1e-10 && c.calls > 100,
          "continuous PD: m x'' + KD x' + (k + KP) x = 0 in closed form to %.3g (<= 1e-10), "
          "%ld calls", worst, c.calls);
    o.method = "taylor";
    sim_x0(s, x);
    rc = eomc_sim_integrate(s, &o, x, NULL, NULL, NULL);
    CHECK(rc == EOMC_EUSAGE && strstr(eomc_sim_error(s), "continuous controller"),
          "taylor refuses a continuous controller: %s", eomc_sim_error(s));
    CHECK(eomc_sim_set_controller(s, pd, &c, -1, NULL) == EOMC_EUSAGE,
          "a negative period: %s", eomc_sim_error(s));
    rows_free(&r);
    eomc_sim_free(s);
}

static void
test_failures(double period, int nan)
{
    eomc_sim *s = sim_new(&ctrlosc_model);
    Ctrl c = {.fail_at = 1.0, .nan_at_fail = nan};
    eomc_sim_set_controller(s, pd, &c, period, NULL);
    eomc_run_opts o = opts_for(&ctrlosc_model, 3, 0.05, "rk8pd", 1e-10, 1e-10);
    double x[2];
    sim_x0(s, x);
    Rows r;
    rows_init_model(&r, &ctrlosc_model);
    eomc_stats st;
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    const char *msg = eomc_sim_error(s);
    int kept = r.n > 0 && r.t[r.n - 1] <= 1.0 && r.t[r.n - 1] >= 0.95;
    if (nan)
        CHECK(rc == EOMC_ENUMERIC && kept && strstr(msg, "set input u to nan") &&
              strstr(msg, "t = 1"), "%s controller setting NaN at t = 1: stops, rows to "
              "t = %g kept: %s", period > 0 ? "a sampled" : "a continuous",
              r.n ? r.t[r.n - 1] : -1.0, msg);
    else
        CHECK(rc == 7 && kept && strstr(msg, "the controller failed (status 7)") &&
              (period == 0 || st.t_stop == 1.0), "%s controller failing at t = 1: status "
              "7, rows to t = %g kept, stopped at %g: %s", period > 0 ? "a sampled"
              : "a continuous", r.n ? r.t[r.n - 1] : -1.0, st.t_stop, msg);
    rows_free(&r);
    eomc_sim_free(s);
}

/* The reference of the sampled loop against the closed form, and a run
 * at rtol 1e-8 measured against it and against the closed form. */
static void
test_reference(void)
{
    const double T = 0.1;
    eomc_sim *s = sim_new(&ctrlosc_model);
    Ctrl c = {.fail_at = INFINITY};
    eomc_sim_set_controller(s, pd, &c, T, NULL);
    eomc_run_opts o = opts_for(&ctrlosc_model, 3, 0.05, "rk8pd", 1e-8, 1e-8);
    double x[2];
    sim_x0(s, x);
    eomc_reference ref;
    int rc = eomc_reference_compute(s, &ctrlosc_model_ext, &o, x, &ref);
    double exact = 0, scale = 0;
    for (long k = 0; rc == EOMC_OK && k < ref.nrows; k++) {
        double xe, ve;
        sampled_exact(T, ref.t[k], &xe, &ve);
        exact = fmax(exact, fmax(fabs(ref.x[2 * k] - xe), fabs(ref.x[2 * k + 1] - ve)));
        scale = fmax(scale, fmax(fabs(xe), fabs(ve)));
    }
    CHECK(rc == EOMC_OK && ref.nrows == 61 && exact <= fmax(ref.error, 4 * DBL_EPSILON * scale) &&
          ref.error <= 1e-15, "the reference of the sampled loop (%s): off the closed form "
          "by %.3g, within the %.3g it claims (<= 1e-15)", rc == EOMC_OK ? ref.method : "",
          exact, ref.error);
    Rows r;
    rows_init_model(&r, &ctrlosc_model);
    sim_x0(s, x);
    rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    double against_ref = 0, truth = 0;
    for (int i = 0; rc == EOMC_OK && i < r.n && i < ref.nrows; i++) {
        double xe, ve;
        sampled_exact(T, r.t[i], &xe, &ve);
        const double *y = rows_x(&r, i);
        truth = fmax(truth, fmax(fabs(y[0] - xe), fabs(y[1] - ve)));
        against_ref = fmax(against_ref, fmax(fabs(y[0] - ref.x[2 * i]),
                                             fabs(y[1] - ref.x[2 * i + 1])));
    }
    CHECK(rc == EOMC_OK && r.n == 61 && truth > 100 * ref.error &&
          fabs(against_ref - truth) <= 2 * ref.error + 4 * DBL_EPSILON * scale,
          "rk8pd at 1e-8 under the sampled controller: its error against the reference, "
          "%.6g, is its true error %.6g", against_ref, truth);
    rows_free(&r);
    eomc_reference_free(&ref);
    eomc_sim_set_controller(s, pd, &c, 0, NULL);
    rc = eomc_reference_compute(s, &ctrlosc_model_ext, &o, x, &ref);
    CHECK(rc == EOMC_EUSAGE && strstr(eomc_sim_error(s), "continuous controller"),
          "no reference under a continuous controller: %s", eomc_sim_error(s));
    eomc_sim_free(s);
}

int
main(void)
{
    test_sampled("rk8pd", 0, 1e-10);
    test_sampled("rkf45", 0, 1e-10);
    test_sampled("msadams", 0, 1e-9);
    /* rk4's error per unit time is about (w h)^4 / 120 of the state, w =
     * sqrt(k + KP)/m ~ 2.4, h = 0.025: 1.2e-7 over the 3 s */
    test_sampled("rk4", 0.03, 2e-7);
    test_steps_end_at_samples();
    test_hand_loop("rk8pd");
    test_hand_loop("msadams");
    test_reference();
    test_continuous();
    test_failures(0.1, 0);
    test_failures(0.1, 1);
    test_failures(0, 0);
    test_failures(0, 1);
    return check_done();
}

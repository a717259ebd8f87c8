/*
 * Every method of eomc_methods[] (GSL's steppers, and Taylor's method on
 * the oscillator's hand-written series) through eomc_sim_integrate:
 *  - adaptive, on the oscillator, against x(t) = x0 cos(wt) + v0/w sin(wt)
 *    at t_end, each with a tolerance fit to its order;
 *  - the explicit Runge-Kutta methods count their attempts, accepted and
 *    rejected: each takes the evaluations its tableau has (GSL passes the
 *    first stage on from the previous attempt, and evaluates the end's
 *    derivative): rk2 3, rkf45 6, rkck 6, rk8pd 13, and rk4, which
 *    estimates its error by step doubling, 3 + 3 + 1 + 3 + 1 = 11; one
 *    more at t0.  So rhs_evals = evals (steps + rejected) + 1, on runs
 *    that reject some steps;
 *  - the implicit steppers (rk1imp rk2imp rk4imp bsimp msbdf) evaluate the
 *    Jacobian, the others never do; on the double pendulum (accel NULL)
 *    they agree with rk8pd;
 *  - fixed steps: the error ratio when h is halved is 2^order (rk4: 16;
 *    GSL's rk2 is the embedded RK2(3) pair, which advances with its
 *    third-order solution: 8; rk4imp 16, rk2imp 4, rk1imp 2); fixed
 *    steps are taken as they are, not rejected, though their local error
 *    estimates exceed rtol = atol = 1e-6; h_used divides the span
 *    t_end - t0 evenly and does not depend on dt;
 *  - a fixed step costs the method's stages only: rk4 takes 4 right-hand
 *    sides a step (GSL's stepper, which estimates its error by step
 *    doubling, takes 12 when adaptive); the implicit ones one Jacobian a
 *    step and their stages times the Newton iterations.
 */
#include "../unit/check.h"
#include "rtest.h"

typedef struct Method {
    const char *name;
    double rtol; /* = atol */
    double tol;  /* allowed error at t_end */
    int implicit;
    int evals; /* right-hand sides an attempted step evaluates; 0: not fixed */
} Method;

static const Method methods[] = {
    {"rk2", 1e-10, 1e-8, 0, 3},     {"rk4", 1e-12, 1e-9, 0, 11},     {"rkf45", 1e-12, 1e-9, 0, 6},
    {"rkck", 1e-12, 1e-9, 0, 6},    {"rk8pd", 1e-12, 1e-10, 0, 13},  {"rk1imp", 1e-8, 1e-3, 1, 0},
    {"rk2imp", 1e-12, 1e-7, 1, 0},  {"rk4imp", 1e-12, 1e-9, 1, 0},   {"bsimp", 1e-12, 1e-10, 1, 0},
    {"msadams", 1e-12, 1e-9, 0, 0}, {"msbdf", 1e-12, 1e-8, 1, 0},
    {"taylor", 1e-12, 1e-12, 0, 0}, /* the oscillator's hand-written series (models.c) */
};
enum { NMETHODS = sizeof methods / sizeof methods[0] };

static const Method *
method_named(const char *name)
{
    for (int i = 0; i < NMETHODS; i++)
        if (strcmp(methods[i].name, name) == 0)
            return &methods[i];
    return NULL;
}

static void
method_list(void)
{
    int n = 0, known = 1;
    for (; eomc_methods[n]; n++)
        known &= method_named(eomc_methods[n]) != NULL;
    CHECK(n == NMETHODS && known, "eomc_methods[] lists the %d methods (got %d)", NMETHODS,
          n);
    int all = 1;
    for (int i = 0; i < NMETHODS; i++) {
        int found = 0;
        for (int j = 0; j < n; j++)
            found |= strcmp(eomc_methods[j], methods[i].name) == 0;
        all &= found;
    }
    CHECK(all, "every stepper of the documentation is in eomc_methods[]");
}

static long rejected_total; /* by the explicit Runge-Kutta methods */

/* The oscillator to t = 2 with method mt, adaptive; error at t_end. */
static void
osc_method(const Method *mt)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 2.0, 0.5, mt->name, mt->rtol, mt->rtol);
    double x[2], xe, ve;
    eomc_stats st;
    memset(&st, 0xff, sizeof st);
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, &st);
    osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, 2.0, &xe, &ve);
    double err = fmax(fabs(x[0] - xe), fabs(x[1] - ve));
    CHECK(rc == EOMC_OK && err <= mt->tol,
          "%s (rtol %g): oscillator at t = 2 within %g of the closed form (error %.3g, rc %d)",
          mt->name, mt->rtol, mt->tol, err, rc);
    if (mt->evals) {
        CHECK(st.steps > 0 && st.rhs_evals == mt->evals * (st.steps + st.rejected) + 1 && st.h_used == 0.0,
              "%s: stats: %ld f evaluations = %d (%ld steps + %ld rejected) + 1, h_used = 0",
              mt->name, st.rhs_evals, mt->evals, st.steps, st.rejected);
        rejected_total += st.rejected;
    } else
        CHECK(st.steps > 0 && st.rhs_evals >= st.steps && st.h_used == 0.0,
              "%s: stats: %ld steps, %ld f evaluations, h_used = 0", mt->name, st.steps,
              st.rhs_evals);
    if (mt->implicit)
        CHECK(st.jac_evals > 0, "%s is implicit: uses the Jacobian (%ld evaluations)",
              mt->name, st.jac_evals);
    else
        CHECK(st.jac_evals == 0, "%s is explicit: no Jacobian evaluations (got %ld)", mt->name,
              st.jac_evals);
    eomc_sim_free(s);
}

/* The double pendulum to t = 2 with method, from the initial state. */
static int
coupled_run(const char *method, double rtol, double *x, eomc_stats *st)
{
    eomc_sim *s = sim_new(&coupled_model);
    eomc_run_opts o = opts_for(&coupled_model, 2.0, 0.1, method, rtol, rtol);
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, st);
    eomc_sim_free(s);
    return rc;
}

static void
coupled_implicit(void)
{
    double ref[4], x[4];
    eomc_stats st;
    int rc = coupled_run("rk8pd", 1e-13, ref, &st);
    CHECK(rc == EOMC_OK, "double pendulum: rk8pd reference run");
    const char *imp[] = {"rk4imp", "bsimp", "msbdf"};
    for (int i = 0; i < 3; i++) {
        rc = coupled_run(imp[i], 1e-11, x, &st);
        double err = 0;
        for (int j = 0; j < 4; j++)
            err = fmax(err, fabs(x[j] - ref[j]));
        CHECK(rc == EOMC_OK && err < 1e-6 && st.jac_evals > 0,
              "double pendulum (accel NULL): %s agrees with rk8pd to %.3g at t = 2, "
              "%ld Jacobian evaluations",
              imp[i], err, st.jac_evals);
    }
}

/* Fixed steps h over [0, 2]: the error at t = 2; st filled. */
static double
osc_fixed(const char *method, double h, double dt, eomc_stats *st)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 2.0, dt, method, 1e-6, 1e-6);
    o.h_fixed = h;
    double x[2], xe, ve;
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, st);
    eomc_sim_free(s);
    if (rc != EOMC_OK)
        return NAN;
    osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, 2.0, &xe, &ve);
    return fmax(fabs(x[0] - xe), fabs(x[1] - ve));
}

static void
fixed_order(const char *method, double h, double want)
{
    eomc_stats st;
    double e1 = osc_fixed(method, h, 0.1, &st);
    long n1 = st.steps;
    double e2 = osc_fixed(method, h / 2, 0.1, &st);
    long n2 = st.steps;
    double ratio = e1 / e2;
    CHECK(isfinite(ratio) && fabs(ratio - want) < 0.15 * want,
          "%s fixed step: error ratio h = %g vs h/2 is %.3f (2^order = %g)", method, h, ratio,
          want);
    CHECK(n1 == (long)(2.0 / h + 0.5) && n2 == 2 * n1 && st.rejected == 0,
          "%s fixed step: %ld and %ld steps over [0, 2], none rejected", method, n1, n2);
}

static void
fixed_h_used(void)
{
    eomc_stats st;
    osc_fixed("rk4", 0.025, 0.1, &st);
    CHECK(fabs(st.h_used - 0.025) < 1e-15, "h = 0.025 divides [0, 2]: h_used = %.17g",
          st.h_used);
    double err = osc_fixed("rk4", 0.03, 0.1, &st);
    CHECK(st.h_used == 2.0 / 67, "h = 0.03 adjusted down to divide [0, 2]: h_used = 2/67 "
          "(got %.17g)", st.h_used);
    CHECK(st.steps == 67 && err < 1e-6, "... and used: %ld steps over [0, 2], error %.3g",
          st.steps, err);
    err = osc_fixed("rk4", 0.3, 0.25, &st);
    CHECK(st.h_used == 2.0 / 7 && st.steps == 7,
          "h = 0.3 > dt = 0.25: steps of 2/7, not shortened to dt (got %.17g, %ld steps)",
          st.h_used, st.steps);
    double err2 = osc_fixed("rk4", 0.3, 2.0, &st);
    CHECK(st.h_used == 2.0 / 7 && err2 == err,
          "... the same steps and end state whatever dt (dt = 2: %.17g, error %.3g)",
          st.h_used, err2);
}

/* t_end = 1.03 is no multiple of h = 0.04: h_used = 1.03 / 26, the end
 * state on the closed form. */
static void
fixed_uneven(void)
{
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 1.03, 0.1, "rk4", 1e-6, 1e-6);
    o.h_fixed = 0.04;
    double x[2], xe, ve;
    eomc_stats st;
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, &st);
    osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, 1.03, &xe, &ve);
    CHECK(rc == EOMC_OK && fabs(x[0] - xe) < 1e-6 && st.h_used == 1.03 / 26 &&
              st.steps == 26,
          "h = 0.04, t_end = 1.03: 26 steps of %.17g, x(t_end) on the closed form",
          st.h_used);
    eomc_sim_free(s);
}

/* rk4 with fixed steps: 4 right-hand sides a step (and one for the start).
 * The implicit methods: one Jacobian a step, and the stages once per
 * Newton iteration plus the end's derivative.  The oscillator is linear,
 * so the simplified Newton iteration with the exact Jacobian is exact
 * after one iteration; a second one measures the contraction, which says
 * that the first left nothing above rounding (fixed.c solves the stages
 * to rounding). */
static void
fixed_cost(void)
{
    eomc_stats st;
    osc_fixed("rk4", 0.01, 0.1, &st);
    CHECK(st.steps == 200 && st.rhs_evals == 4 * st.steps + 1 && st.jac_evals == 0,
          "rk4, fixed steps: %ld right-hand sides for %ld steps: 4 a step", st.rhs_evals,
          st.steps);
    osc_fixed("rk4", 0.01, 2.0, &st);
    CHECK(st.rhs_evals == 4 * st.steps + 1,
          "... also with one row at the end (%ld for %ld steps)", st.rhs_evals, st.steps);
    static const struct { const char *name; int stages; } imp[] = {
        {"rk1imp", 1}, {"rk2imp", 1}, {"rk4imp", 2},
    };
    for (int k = 0; k < 3; k++) {
        osc_fixed(imp[k].name, 0.01, 0.1, &st);
        long s = imp[k].stages, stages = st.rhs_evals - 1 - st.steps;
        CHECK(st.jac_evals == st.steps && stages % s == 0 && stages / s >= st.steps &&
                  stages / s <= 2 * st.steps,
              "%s, fixed steps: one Jacobian a step, %ld right-hand sides for %ld steps: "
              "%.2f Newton iterations of %ld stage%s a step, and the end's derivative",
              imp[k].name, st.rhs_evals, st.steps, (double)stages / s / st.steps, s,
              s > 1 ? "s" : "");
    }
}

int
main(void)
{
    method_list();
    for (int i = 0; i < NMETHODS; i++)
        osc_method(&methods[i]);
    CHECK(rejected_total > 0, "the explicit Runge-Kutta runs rejected %ld steps in all",
          rejected_total);
    coupled_implicit();
    fixed_order("rk4", 0.02, 16.0);
    fixed_order("rk2", 0.02, 8.0);
    fixed_order("rk4imp", 0.02, 16.0);
    fixed_order("rk2imp", 0.02, 4.0);
    fixed_order("rk1imp", 0.02, 2.0);
    fixed_h_used();
    fixed_uneven();
    fixed_cost();
    return check_done();
}

/*
 * libeomcrt without integration, on hand-written models (models.h):
 *  - alloc refuses another ABI; run defaults are the model's scene;
 *  - eomc_sim_set / params / initial: names, values, EOMC_EUSAGE;
 *  - eomc_sim_accel: -k/m x (generated accel member); M a + h = 0 for the
 *    double pendulum (accel NULL: the runtime's own solve); EOMC_ENUMERIC
 *    and a "t = ..." message when M is not positive definite; a state
 *    that is not finite said so, even where x'' is finite and before a
 *    failed pivot; a state whose sum overflows passes; an infinite x''
 *    said so;
 *  - eomc_sim_jacobian: exact for the oscillator, and against central
 *    differences of eomc_sim_accel in x and t (inputs and explicit t);
 *  - an input set by name is held constant;
 *  - eomc_sim_eigenvalues: +-2i, and an error for an infinite entry;
 *  - a model without its Jacobian: exactly GSL's steppers that call the
 *    Jacobian, and the linearization, refuse it (EOMC_EUSAGE, the rebuild
 *    said); the explicit methods run;
 *  - the program's GSL error handler stays in place and is never called.
 */
#include "../unit/check.h"
#include "rtest.h"

#include <gsl/gsl_errno.h>

/* The program's own GSL error handler: libeomcrt must leave it in place
 * and never reach it, its statuses checked where they arise. */
static int gsl_errors;
static void
count_gsl_error(const char *reason, const char *file, int line, int gsl_errno)
{
    printf("# GSL error handler called: %s (%s:%d, %d)\n", reason, file, line, gsl_errno);
    gsl_errors++;
}

static void
alloc_and_defaults(void)
{
    eomc_model bad = osc_model;
    bad.abi = EOMC_ABI_VERSION + 1;
    eomc_sim *s = eomc_sim_alloc(&bad);
    CHECK(s == NULL, "eomc_sim_alloc refuses a model of ABI %d", bad.abi);
    if (s)
        eomc_sim_free(s);

    s = sim_new(&osc_model);
    CHECK(eomc_sim_model(s) == &osc_model, "eomc_sim_model returns the model");
    eomc_sim_free(s);

    eomc_run_opts o = eomc_run_defaults(&osc_model);
    CHECK(o.t0 == 0.0 && o.t_end == 10.0 && o.dt == 0.1,
          "defaults: t0 = 0, t_end = 10, dt = 0.1 from the scene (got %g %g %g)",
          o.t0, o.t_end, o.dt);
    CHECK(o.method && strcmp(o.method, "rk8pd") == 0 && o.rtol == 1e-10 &&
              o.atol == 1e-10 && o.h_fixed == 0.0 && o.max_steps == 0,
          "defaults: rk8pd, rtol = atol = 1e-10, adaptive, no step limit");
    o = eomc_run_defaults(&driven_model);
    CHECK(o.t_end == 5.0 && o.dt == 0.05 && o.method && strcmp(o.method, "rkf45") == 0,
          "defaults follow the model: driven t_end = 5, dt = 0.05, rkf45");
}

static void
set_params(void)
{
    eomc_sim *s = sim_new(&osc_model);
    const double *p = eomc_sim_params(s);
    CHECK(p[0] == OSC_M && p[1] == OSC_K && p[2] == OSC_X0,
          "params start at the model's defaults");
    CHECK(eomc_sim_set(s, "k", 3.5) == EOMC_OK, "set k: EOMC_OK");
    p = eomc_sim_params(s);
    CHECK(p[1] == 3.5 && p[0] == OSC_M && p[2] == OSC_X0,
          "set k = 3.5 changes params[1] only");

    int st = eomc_sim_set(s, "nosuch", 1.0);
    CHECK(st == EOMC_EUSAGE, "set of an unknown name: EOMC_EUSAGE (got %d)", st);
    CHECK(eomc_sim_error(s)[0] != '\0', "... with a message: %s", eomc_sim_error(s));
    CHECK(eomc_sim_set(s, "x", 1.0) == EOMC_EUSAGE,
          "set of a coordinate's name: EOMC_EUSAGE");
    CHECK(eomc_sim_set(s, "K", 1.0) == EOMC_EUSAGE, "names are case-sensitive");
    p = eomc_sim_params(s);
    CHECK(p[0] == OSC_M && p[1] == 3.5 && p[2] == OSC_X0,
          "failed sets leave the parameters alone");

    double q, v;
    eomc_sim_set(s, "x0", -0.25);
    eomc_sim_initial(s, &q, &v);
    CHECK(q == -0.25 && v == OSC_V0, "initial state follows the parameters: x = x0 = %g", q);
    eomc_sim_free(s);
}

static void
osc_accel_energy(void)
{
    eomc_sim *s = sim_new(&osc_model);
    int ok = 1;
    for (int k = 0; k < 20; k++) {
        double m = check_rand(0.1, 10), kk = check_rand(0.1, 50);
        double x = check_rand(-5, 5), v = check_rand(-5, 5), t = check_rand(0, 10), a;
        eomc_sim_set(s, "m", m);
        eomc_sim_set(s, "k", kk);
        ok &= eomc_sim_accel(s, t, &x, &v, &a) == EOMC_OK;
        ok &= check_close(a, -kk / m * x, 1e-14);
        double T, V;
        eomc_sim_energy(s, t, &x, &v, &T, &V);
        ok &= check_close(T, 0.5 * m * v * v, 1e-14) && check_close(V, 0.5 * kk * x * x, 1e-14);
    }
    CHECK(ok, "oscillator: x'' = -k/m x, T = m v^2/2, V = k x^2/2 at random states");

    double x = 0.5, v = 0.0, a;
    eomc_sim_set(s, "m", 0.0);
    int st = eomc_sim_accel(s, 1.25, &x, &v, &a);
    CHECK(st == EOMC_ENUMERIC, "m = 0: accel returns EOMC_ENUMERIC (got %d)", st);
    CHECK(strncmp(eomc_sim_error(s), "t = ", 4) == 0, "... message starts with \"t = \": %s",
          eomc_sim_error(s));
    eomc_sim_set(s, "m", -1.0);
    CHECK(eomc_sim_accel(s, 0.0, &x, &v, &a) == EOMC_ENUMERIC, "m = -1: EOMC_ENUMERIC");

    /* osc has a generated solve (accel), whose inputs are tested after it:
     * a state that is not finite is said so even where x'' is finite
     * (x'' = -k/m x reads no v), and before a failed pivot */
    eomc_sim_set(s, "m", 1.0);
    eomc_sim_set(s, "k", 1.0);
    const char *state = "the state or an input is not finite";
    double xs[3] = {0.5, INFINITY, 0.5}, vs[3] = {NAN, 0.0, 0.0}, ts[3] = {0.0, 0.0, NAN};
    int said = 1;
    for (int i = 0; i < 3; i++)
        said &= eomc_sim_accel(s, ts[i], &xs[i], &vs[i], &a) == EOMC_ENUMERIC &&
                strstr(eomc_sim_error(s), state) != NULL;
    eomc_sim_set(s, "m", 0.0);
    said &= eomc_sim_accel(s, 0.0, &xs[0], &vs[0], &a) == EOMC_ENUMERIC &&
            strstr(eomc_sim_error(s), state) != NULL;
    CHECK(said, "v = NaN (x'' finite), x = inf, t = NaN, and v = NaN with m = 0: \"%s\"", state);
    eomc_sim_set(s, "m", 1.0);
    x = 1e308, v = 1e308; /* finite, though their sum overflows */
    st = eomc_sim_accel(s, 0.0, &x, &v, &a);
    CHECK(st == EOMC_OK && a == -1e308, "x = v = 1e308: EOMC_OK, x'' = %g", a);
    eomc_sim_set(s, "m", 1e-10);
    st = eomc_sim_accel(s, 0.0, &x, &v, &a);
    CHECK(st == EOMC_ENUMERIC && strstr(eomc_sim_error(s), "acceleration x'' is not finite"),
          "m = 1e-10, x = 1e308: %s", eomc_sim_error(s));
    eomc_sim_free(s);
}

/* Two simulators of one model hold their own parameters and errors. */
static void
independent(void)
{
    eomc_sim *s1 = sim_new(&osc_model), *s2 = sim_new(&osc_model);
    double x = 0.5, v = 0.0, a1, a2;
    eomc_sim_set(s2, "k", 2.0);
    eomc_sim_set(s2, "m", 0.0);
    int rc2 = eomc_sim_accel(s2, 0.0, &x, &v, &a2);
    int rc1 = eomc_sim_accel(s1, 0.0, &x, &v, &a1);
    CHECK(rc1 == EOMC_OK && a1 == -OSC_K / OSC_M * x && rc2 == EOMC_ENUMERIC &&
              eomc_sim_params(s1)[1] == OSC_K && eomc_sim_error(s2)[0] != '\0',
          "two simulators of one model: own parameters, own status (a1 = %g)", a1);
    eomc_sim_set(s2, "m", 4.0);
    CHECK(eomc_sim_accel(s2, 0.0, &x, &v, &a2) == EOMC_OK && a2 == -0.25,
          "... and the second recovers once m is positive: x'' = -k/m x = %g", a2);
    eomc_sim_free(s1);
    eomc_sim_free(s2);
}

/* The double pendulum's M and h straight from the model. */
static void
coupled_mh(const double *p, const double *q, const double *v, double *M, double *h)
{
    coupled_model.mass_bias(0.0, q, v, p, NULL, M, h);
}

static void
coupled_accel(void)
{
    eomc_sim *s = sim_new(&coupled_model);
    const double *p = eomc_sim_params(s);
    int ok = 1;
    for (int k = 0; k < 50; k++) {
        double q[2] = {check_rand(-3, 3), check_rand(-3, 3)};
        double v[2] = {check_rand(-4, 4), check_rand(-4, 4)}, a[2], M[4], h[2];
        ok &= eomc_sim_accel(s, 0.0, q, v, a) == EOMC_OK;
        coupled_mh(p, q, v, M, h);
        double det = M[0] * M[3] - M[1] * M[2];
        double a0 = (-h[0] * M[3] + h[1] * M[1]) / det;
        double a1 = (-h[1] * M[0] + h[0] * M[2]) / det;
        ok &= check_close(a[0], a0, 1e-12) && check_close(a[1], a1, 1e-12);
        ok &= check_close(M[0] * a[0] + M[1] * a[1] + h[0], 0.0, 1e-12);
        ok &= check_close(M[2] * a[0] + M[3] * a[1] + h[1], 0.0, 1e-12);
    }
    CHECK(ok, "double pendulum (accel NULL): accel solves M q'' = -h (Cramer's rule)");
    eomc_sim_free(s);
}

/* Central differences of f(t, x) = (v, accel) in x_j (j < 2 nq) or, for
 * j = 2 nq, in t. */
static void
fd_column(eomc_sim *s, double t, const double *x, int j, double *col)
{
    int n = eomc_sim_model(s)->nq;
    double xp[8], xm[8], ap[4], am[4], tp = t, tm = t;
    memcpy(xp, x, (size_t)(2 * n) * sizeof *x);
    memcpy(xm, x, (size_t)(2 * n) * sizeof *x);
    double h = 1e-6 * (j < 2 * n ? fmax(1.0, fabs(x[j])) : fmax(1.0, fabs(t)));
    if (j < 2 * n) {
        xp[j] += h;
        xm[j] -= h;
    } else {
        tp += h;
        tm -= h;
    }
    eomc_sim_accel(s, tp, xp, xp + n, ap);
    eomc_sim_accel(s, tm, xm, xm + n, am);
    for (int i = 0; i < n; i++) {
        col[i] = (xp[n + i] - xm[n + i]) / (2 * h);
        col[n + i] = (ap[i] - am[i]) / (2 * h);
    }
}

/* eomc_sim_jacobian at (t, x) against fd_column, to tol. */
static int
jacobian_matches_fd(eomc_sim *s, double t, const double *x, double tol)
{
    int n = eomc_sim_model(s)->nq, N = 2 * n, ok = 1;
    double J[64], dfdt[8], col[8];
    ok &= eomc_sim_jacobian(s, t, x, J, dfdt) == EOMC_OK;
    for (int j = 0; j <= N; j++) {
        fd_column(s, t, x, j, col);
        for (int i = 0; i < N; i++) {
            double got = j < N ? J[i * N + j] : dfdt[i];
            if (!check_close(got, col[i], tol)) {
                printf("# t = %g: d f%d / d %s%d = %.17g, differences %.17g\n", t, i,
                       j < N ? "x" : "t", j, got, col[i]);
                ok = 0;
            }
        }
    }
    return ok;
}

static void
osc_jacobian(void)
{
    eomc_sim *s = sim_new(&osc_model);
    double x[2] = {0.3, -1.1}, J[4] = {9, 9, 9, 9}, dfdt[2] = {9, 9};
    int st = eomc_sim_jacobian(s, 0.5, x, J, dfdt);
    CHECK(st == EOMC_OK && J[0] == 0 && J[1] == 1 && check_close(J[2], -OSC_K / OSC_M, 1e-15) &&
              J[3] == 0,
          "oscillator: df/dx = [0 1; -k/m 0] (got [%g %g; %g %g])", J[0], J[1], J[2], J[3]);
    CHECK(dfdt[0] == 0 && dfdt[1] == 0, "oscillator: df/dt = 0");
    double J2[4] = {9, 9, 9, 9}, dfdt2[2] = {9, 9};
    CHECK(eomc_sim_jacobian(s, 0.5, x, J2, NULL) == EOMC_OK &&
              memcmp(J, J2, sizeof J) == 0 &&
              eomc_sim_jacobian(s, 0.5, x, NULL, dfdt2) == EOMC_OK &&
              memcmp(dfdt, dfdt2, sizeof dfdt) == 0,
          "jacobian with dfdt or dfdx NULL gives the other unchanged");
    eomc_sim_free(s);
}

static void
coupled_jacobian(void)
{
    eomc_sim *s = sim_new(&coupled_model);
    int ok = 1;
    for (int k = 0; k < 20; k++) {
        double x[4] = {check_rand(-3, 3), check_rand(-3, 3), check_rand(-3, 3),
                       check_rand(-3, 3)};
        ok &= jacobian_matches_fd(s, check_rand(0, 5), x, 2e-7);
    }
    CHECK(ok, "double pendulum (accel NULL): df/dx = -M^-1 dE/dx matches central differences");
    double x[4] = {0.1, 0.2, 0.3, 0.4}, J[16];
    eomc_sim_jacobian(s, 0.0, x, J, NULL);
    CHECK(J[0] == 0 && J[1] == 0 && J[2] == 1 && J[3] == 0 && J[4] == 0 && J[5] == 0 &&
              J[6] == 0 && J[7] == 1,
          "double pendulum: dq'/dx = [0 I] exactly");
    eomc_sim_free(s);
}

static void
driven_jacobian(void)
{
    eomc_sim *s = sim_new(&driven_model);
    double m = DRIVEN_M, c = 0.3, k = DRIVEN_K, A = DRIVEN_A, w = DRIVEN_W, b = 0.5;
    eomc_sim_set(s, "c", c);
    eomc_sim_set(s, "b", b);
    int ok = 1, exact = 1;
    for (int i = 0; i < 20; i++) {
        double t = check_rand(0, 6), x[2] = {check_rand(-2, 2), check_rand(-2, 2)};
        double J[4], dfdt[2], u;
        ok &= jacobian_matches_fd(s, t, x, 2e-7);
        eomc_sim_jacobian(s, t, x, J, dfdt);
        exact &= J[0] == 0 && J[1] == 1 && check_close(J[2], -k / m, 1e-14) &&
                 check_close(J[3], -c / m, 1e-14) && dfdt[0] == 0 &&
                 check_close(dfdt[1], (A * w * cos(w * t) + b) / m, 1e-14);
        eomc_sim_inputs(s, t, &u);
        exact &= check_close(u, A * sin(w * t), 1e-15);
    }
    CHECK(ok, "driven: df/dx and df/dt (input and explicit t) match central differences");
    CHECK(exact, "driven: df/dt = (A w cos(w t) + b)/m, df/dx = [0 1; -k/m -c/m]; u = A sin(w t)");

    CHECK(eomc_sim_set(s, "u", 0.7) == EOMC_OK, "set of an input by name: EOMC_OK");
    int held = 1;
    for (int i = 0; i < 10; i++) {
        double t = check_rand(0, 6), x[2] = {check_rand(-2, 2), check_rand(-2, 2)};
        double u, a, dfdt[2];
        eomc_sim_inputs(s, t, &u);
        eomc_sim_accel(s, t, x, x + 1, &a);
        eomc_sim_jacobian(s, t, x, NULL, dfdt);
        held &= u == 0.7 && check_close(a, (0.7 + b * t - c * x[1] - k * x[0]) / m, 1e-14) &&
                dfdt[0] == 0 && check_close(dfdt[1], b / m, 1e-14);
        held &= jacobian_matches_fd(s, t, x, 2e-7);
    }
    CHECK(held, "u set to 0.7: u(t) = 0.7, accel uses it, df/dt = b/m (no input part)");
    eomc_sim_free(s);
}

static void
nonpd_accel(const eomc_model *m)
{
    eomc_sim *s = sim_new(m);
    double q = 0.5, v = 1.0, a = 9, x[2] = {1.5, 1.0}, J[4], dfdt[2];
    CHECK(eomc_sim_accel(s, 0.5, &q, &v, &a) == EOMC_OK && a == 0.0,
          "%s: M = 3/4 at zeta = 1/2: q'' = 0", m->name);
    q = 1.5;
    int st = eomc_sim_accel(s, 1.5, &q, &v, &a);
    CHECK(st == EOMC_ENUMERIC, "%s: M = -5/4 at zeta = 3/2: EOMC_ENUMERIC (got %d)", m->name,
          st);
    const char *e = eomc_sim_error(s);
    CHECK(strncmp(e, "t = ", 4) == 0 && strstr(e, "zeta"),
          "%s: message starts with \"t = \" and names the state: %s", m->name, e);
    q = 1.0;
    CHECK(eomc_sim_accel(s, 1.0, &q, &v, &a) == EOMC_ENUMERIC, "%s: M = 0: EOMC_ENUMERIC",
          m->name);
    st = eomc_sim_jacobian(s, 1.5, x, J, dfdt);
    CHECK(st == EOMC_ENUMERIC, "%s: jacobian where M is not PD: EOMC_ENUMERIC (got %d)",
          m->name, st);
    eomc_sim_free(s);
}

/* GSL's steppers that take the Jacobian (its manual, "Stepping
 * Functions": rk1imp, rk2imp, rk4imp, bsimp and msbdf need the jacobian
 * function; msadams iterates without it). */
static void
no_jacobian(void)
{
    static const char *const implicit[] = {"rk1imp", "rk2imp", "rk4imp", "bsimp", "msbdf"};
    eomc_model m = osc_model;
    m.jacobian = NULL;
    eomc_sim *s = sim_new(&m);
    int all = 1, count = 0;
    for (int k = 0; eomc_methods[k]; k++) {
        int imp = 0;
        for (size_t j = 0; j < sizeof implicit / sizeof *implicit; j++)
            imp |= !strcmp(eomc_methods[k], implicit[j]);
        count += imp;
        eomc_run_opts o = eomc_run_defaults(&m);
        o.method = eomc_methods[k];
        int st = eomc_run_check(s, &o);
        const char *e = eomc_sim_error(s);
        int ok = eomc_method_jacobian(eomc_methods[k]) == imp &&
                 (imp ? st == EOMC_EUSAGE && strstr(e, eomc_methods[k]) &&
                            strstr(e, "eomc build osc.yaml --jacobian auto")
                      : st == EOMC_OK);
        if (!ok)
            printf("# %s: status %d, %s\n", eomc_methods[k], st, e);
        all &= ok;
    }
    CHECK(all && count == 5, "without the Jacobian: the 5 implicit methods refused, saying "
          "how to rebuild; the others pass eomc_run_check");
    CHECK(eomc_method_jacobian("nosuch") == -1, "eomc_method_jacobian of an unknown name: -1");
    double x[2] = {0.5, 0.1}, J[4], B[2], A[4];
    int it;
    CHECK(eomc_sim_jacobian(s, 0, x, J, NULL) == EOMC_EUSAGE &&
              eomc_sim_linearize(s, 0, x, A, B) == EOMC_EUSAGE &&
              strstr(eomc_sim_error(s), "the linearization needs the Jacobian") &&
              eomc_sim_equilibrium(s, 0, x, &it) == EOMC_EUSAGE,
          "without the Jacobian: eomc_sim_jacobian, _linearize and _equilibrium refuse");
    eomc_sim_free(s);
}

/* Forward kinematics through the runtime (place.c) on the drawn pendulum's
 * places: the bob at l (sin th, -cos th), its Jacobian l (cos th, sin th),
 * the rod turned by th about z; what has no axes refused by name. */
static void
places(void)
{
    eomc_sim *s = sim_new(&draw_model);
    CHECK(eomc_sim_set(s, "l", 1.5) == EOMC_OK, "l set");
    int axes = -1, bob = eomc_model_place(&draw_model, "bob", &axes), rod_axes = -1;
    int rod = eomc_model_place(&draw_model, "rod", &rod_axes);
    CHECK(bob == 1 && axes == 0 && rod == 2 && rod_axes == 1 &&
              eomc_model_place(&draw_model, "nope", NULL) == -1 &&
              eomc_model_count(&draw_model, "place") == 3 &&
              !strcmp(eomc_model_name(&draw_model, "place", 2), "rod"),
          "places by name: the bob (no axes), the rod (axes), none called nope");
    double th = 0.7, pos[3], R[9], Jv[3], Jw[3];
    CHECK(eomc_sim_place(s, bob, 0, &th, pos, NULL) == EOMC_OK &&
              check_close(pos[0], 1.5 * sin(th), 1e-16) &&
              check_close(pos[1], -1.5 * cos(th), 1e-16) && pos[2] == 0,
          "the bob's position: l (sin th, -cos th) (got %g, %g, %g)", pos[0], pos[1], pos[2]);
    CHECK(eomc_sim_place_jacobian(s, bob, 0, &th, Jv, NULL) == EOMC_OK &&
              check_close(Jv[0], 1.5 * cos(th), 1e-16) &&
              check_close(Jv[1], 1.5 * sin(th), 1e-16) && Jv[2] == 0,
          "the bob's Jacobian: l (cos th, sin th) (got %g, %g, %g)", Jv[0], Jv[1], Jv[2]);
    CHECK(eomc_sim_place(s, bob, 0, &th, NULL, R) == EOMC_EUSAGE &&
              strstr(eomc_sim_error(s), "'bob' is a particle") &&
              eomc_sim_place_jacobian(s, bob, 0, &th, Jv, Jw) == EOMC_EUSAGE,
          "a particle's rotation and angular Jacobian refused (%s)", eomc_sim_error(s));
    CHECK(eomc_sim_place(s, rod, 0, &th, NULL, R) == EOMC_OK && R[0] == cos(th) &&
              R[1] == -sin(th) && R[3] == sin(th) &&
              eomc_sim_place_jacobian(s, rod, 0, &th, NULL, Jw) == EOMC_OK && Jw[0] == 0 &&
              Jw[1] == 0 && Jw[2] == 1,
          "the rod turned by th about z, at the rate th'");
    CHECK(eomc_sim_place(s, 3, 0, &th, pos, NULL) == EOMC_EUSAGE &&
              strstr(eomc_sim_error(s), "has 3 places"),
          "a place out of range refused (%s)", eomc_sim_error(s));
    eomc_sim_free(s);
}

int
main(void)
{
    gsl_set_error_handler(count_gsl_error);
    alloc_and_defaults();
    set_params();
    osc_accel_energy();
    independent();
    coupled_accel();
    osc_jacobian();
    coupled_jacobian();
    driven_jacobian();
    nonpd_accel(&nonpd_model);
    nonpd_accel(&nonpd_gsl_model);
    no_jacobian();
    places();
    eomc_sim *s = sim_new(&osc_model);
    double A[4] = {0, 1, -HUGE_VAL, 0}, re[2], im[2];
    CHECK(eomc_sim_eigenvalues(s, A, 2, re, im) != EOMC_OK && eomc_sim_error(s)[0],
          "eigenvalues of a matrix with an infinite entry: an error, said (%s)",
          eomc_sim_error(s));
    A[2] = -4; /* x'' = -4 x: +-2i */
    CHECK(eomc_sim_eigenvalues(s, A, 2, re, im) == EOMC_OK && re[0] == 0 && re[1] == 0 &&
              check_close(fabs(im[0]), 2, 1e-15) && im[0] == -im[1],
          "eigenvalues of [0 1; -4 0]: +-2i (got %g%+gi, %g%+gi)", re[0], im[0], re[1], im[1]);
    eomc_sim_free(s);
    gsl_error_handler_t *now = gsl_set_error_handler(NULL);
    CHECK(now == count_gsl_error, "the program's GSL error handler is still in place");
    CHECK(gsl_errors == 0, "GSL's error handler was never called, even where M = 0 (got %d)",
          gsl_errors);
    return check_done();
}

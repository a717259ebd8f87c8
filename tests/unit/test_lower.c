/*
 * Unit tests of lower.c, without compiling any C: the lowered functions
 * are evaluated (lower_eval) and their derivatives checked against
 * central differences of the lowered functions they differentiate:
 *   jacobian's dE/dq, dE/dq', dE/du, dE/dt against E = M q'' + h from
 *   mass_bias (u moved by hand, inputs held);
 *   the seeded Jacobian's columns against the unrolled one;
 *   inputs' du/dt against u;
 *   c_jacobian's df/dq, df/dq' against constraint's f;
 *   c_levels_jacobian against c_levels;
 * and the array sizes read off the lists.
 */
#include "check.h"
#include "forms/forms.h"
#include "lower/lower.h"
#include "lower/lower_schedule.h"

#include <stdlib.h>
#include <string.h>

static Arena *A;
static ExprPool *P;
static Diff *D;

/* A driven, damped cart-pole with the bob also held on a slot that moves
 * with t (holonomic, explicit in t): inputs, a Q and a constraint. */
static const char *const spec_text =
    "parameters: {M: 1.3, m: 0.4, l: 0.7, g: 9.81, c: 0.3, A: 0.5, w: 2.0}\n"
    "coordinates: [x, theta, y]\n"
    "inputs: {u: A*sin(w*t)}\n"
    "particles:\n"
    "  cart: {mass: M, position: [x, 0]}\n"
    "  bob: {mass: m, position: [x + l*sin(theta), y - l*cos(theta)]}\n"
    "effects:\n"
    "  gravity: {gravity: [0, -g]}\n"
    "  drive: {force: [\"u*cos(theta)\", 0], on: cart}\n"
    "  damper: {force: [\"-c*x'\", \"-c*y'*u\"], on: bob}\n"
    "constraints:\n"
    "  slot: y - 0.1*sin(t)*x\n";

enum { N = 3, NU = 1, NC = 1 };

static Lowered *
lowered(int jacobian)
{
    Spec *s = spec_load_buffer("l.yaml", spec_text, strlen(spec_text), NULL, A, P);
    if (!s)
        return NULL;
    Mech *m = mech_build(s, A, P, D);
    Constraints *c = constraints_build(s, m, A, P, D);
    Invariant *inv = invariant_derive(s, m, c, A, P, D);
    const char *why;
    Eom *e = eom_derive(s, m, form_find("lagrange"), A, P, D, &why);
    return lower_model(s, m, e, c, 0, inv, jacobian, LOWER_CODE_STRAIGHT, 0, A, P, D);
}

static const double pdef[] = {1.3, 0.4, 0.7, 9.81, 0.3, 0.5, 2.0};

typedef struct State {
    double t, q[N], v[N], a[N], u[NU];
} State;

static ExprEnv
env_of(const State *x)
{
    ExprEnv env = {x->t, {x->q, x->v, x->a, NULL}, pdef, x->u, {NULL, NULL}, NULL, NULL};
    return env;
}

/* E = M a + h at x. */
static void
residual(const Lowered *L, const State *x, double *E)
{
    double M[N * N], h[N];
    ExprEnv env = env_of(x);
    lower_eval(P, lower_find(L, "mass_bias"), &env, (double *const[]){M, h});
    for (int i = 0; i < N; i++) {
        E[i] = h[i];
        for (int j = 0; j < N; j++)
            E[i] += M[i * N + j] * x->a[j];
    }
}

/* The component k of x: 0..N-1 q, N..2N-1 v, 2N u, 2N+1 t. */
static double *
component(State *x, int k)
{
    return k < N ? &x->q[k] : k < 2 * N ? &x->v[k - N] : k == 2 * N ? &x->u[0] : &x->t;
}

/* Central difference of a function of the state into d[0..nf-1]. */
typedef void (*StateFn)(const Lowered *, const State *, double *);

static void
central(const Lowered *L, StateFn fn, int nf, const State *x0, int k, double *d)
{
    State xp = *x0, xm = *x0;
    double step = 1e-6 * (1 + fabs(*component(&xp, k)));
    *component(&xp, k) += step;
    *component(&xm, k) -= step;
    double fp[16], fm[16];
    fn(L, &xp, fp);
    fn(L, &xm, fm);
    for (int i = 0; i < nf; i++)
        d[i] = (fp[i] - fm[i]) / (2 * step);
}

static void
constraint_f(const Lowered *L, const State *x, double *f)
{
    double B[NC * N];
    ExprEnv env = env_of(x);
    lower_eval(P, lower_find(L, "constraint"), &env, (double *const[]){f, B});
}

static void
levels(const Lowered *L, const State *x, double *pv)
{
    ExprEnv env = env_of(x);
    lower_eval(P, lower_find(L, "c_levels"), &env, (double *const[]){pv, pv + NC});
}

static State
random_state(void)
{
    State x;
    x.t = check_rand(0, 2);
    for (int i = 0; i < N; i++) {
        x.q[i] = check_rand(-1, 1);
        x.v[i] = check_rand(-1, 1);
        x.a[i] = check_rand(-1, 1);
    }
    x.u[0] = check_rand(-1, 1);
    return x;
}

/* Central differences with step 1e-6 are good to ~1e-9 here. */
static const double FD_TOL = 1e-7;

static void
test_jacobian(const Lowered *L)
{
    State x = random_state();
    double dEdq[N * N], dEdv[N * N], dEdu[N * NU], dEdt[N];
    ExprEnv env = env_of(&x);
    lower_eval(P, lower_find(L, "jacobian"), &env, (double *const[]){dEdq, dEdv, dEdu, dEdt});
    double worst = 0;
    for (int k = 0; k < 2 * N + 2; k++) {
        double d[N];
        central(L, residual, N, &x, k, d);
        for (int i = 0; i < N; i++) {
            double got = k < N       ? dEdq[i * N + k]
                         : k < 2 * N ? dEdv[i * N + k - N]
                         : k == 2 * N ? dEdu[i]
                                      : dEdt[i];
            double err = fabs(got - d[i]) / (1 + fabs(d[i]));
            worst = err > worst ? err : worst;
        }
    }
    CHECK(worst < FD_TOL, "jacobian: dE/dq, dE/dq', dE/du, dE/dt match central differences "
          "of mass_bias's E (worst %.2g)", worst);
}

/* Column j of the seeded functions with the unit seed e_j is column j of
 * the unrolled Jacobian. */
static void
test_seeded(const Lowered *unrolled, const Lowered *seeded)
{
    CHECK(lower_find(seeded, "jacobian") == NULL && seeded->jac_dv && seeded->jac_shared,
          "--jacobian seeded lowers to jacobian_shared, jacobian_dq, jacobian_dv");
    State x = random_state();
    ExprEnv env = env_of(&x);
    double dEdq[N * N], dEdv[N * N], dEdu[N * NU], dEdt[N];
    lower_eval(P, lower_find(unrolled, "jacobian"), &env,
               (double *const[]){dEdq, dEdv, dEdu, dEdt});
    double worst = 0;
    for (int j = 0; j < N; j++) {
        double seed[N] = {0}, colq[N * N], colv[N * N];
        seed[j] = 1;
        env.seed[0] = env.seed[1] = seed;
        lower_eval(P, lower_find(seeded, "jacobian_dq"), &env, (double *const[]){colq});
        lower_eval(P, lower_find(seeded, "jacobian_dv"), &env, (double *const[]){colv});
        for (int i = 0; i < N; i++) {
            double e1 = fabs(colq[i * N] - dEdq[i * N + j]) / (1 + fabs(dEdq[i * N + j]));
            double e2 = fabs(colv[i * N] - dEdv[i * N + j]) / (1 + fabs(dEdv[i * N + j]));
            worst = fmax(worst, fmax(e1, e2));
        }
    }
    CHECK(worst < 1e-14, "seeded columns equal the unrolled Jacobian (worst %.2g)", worst);
}

static void
test_inputs(const Lowered *L)
{
    double t = 0.37, h = 1e-6, u[3], dudt[1];
    const LowFunc *f = lower_find(L, "inputs");
    for (int k = 0; k < 3; k++) {
        ExprEnv env = {t + (k - 1) * h, {NULL}, pdef, NULL, {NULL, NULL}, NULL, NULL};
        lower_eval(P, f, &env, (double *const[]){u + k, k == 1 ? dudt : NULL});
    }
    CHECK_NEAR(dudt[0], (u[2] - u[0]) / (2 * h), FD_TOL, "inputs: du/dt = d/dt A sin(w t)");
    CHECK_NEAR(u[1], 0.5 * sin(2.0 * t), 1e-15, "inputs: u = A sin(w t)");
}

static void
test_constraint(const Lowered *L)
{
    State x = random_state();
    ExprEnv env = env_of(&x);
    double dfdq[NC * N], dfdv[NC * N], dfdu[NC * NU], dfdt[NC];
    double dBdq[NC * N * N], dBdv[NC * N * N], dBda[NC * N * N], dBdu[NC * N * NU], dBdt[NC * N];
    lower_eval(P, lower_find(L, "c_jacobian"), &env,
               (double *const[]){dfdq, dfdv, dfdu, dfdt, dBdq, dBdv, dBda, dBdu, dBdt});
    double worst = 0;
    for (int k = 0; k < 2 * N + 2; k++) {
        if (k == 2 * N)
            continue; /* u: the constraint has none */
        double d[NC];
        central(L, constraint_f, NC, &x, k, d);
        double got = k < N ? dfdq[k] : k < 2 * N ? dfdv[k - N] : dfdt[0];
        worst = fmax(worst, fabs(got - d[0]) / (1 + fabs(d[0])));
    }
    CHECK(worst < FD_TOL, "c_jacobian: df/dq, df/dq', df/dt match central differences of "
          "constraint's f (worst %.2g)", worst);

    double dposdq[NC * N], dveldq[NC * N], dveldv[NC * N], dposdu[NC], dveldu[NC];
    double dposdt[NC], dveldt[NC];
    lower_eval(P, lower_find(L, "c_levels_jacobian"), &env,
               (double *const[]){dposdq, dveldq, dveldv, dposdu, dveldu, dposdt, dveldt});
    worst = 0;
    for (int k = 0; k < 2 * N + 2; k++) {
        if (k == 2 * N)
            continue;
        double d[2 * NC];
        central(L, levels, 2 * NC, &x, k, d);
        double gp = k < N ? dposdq[k] : k < 2 * N ? 0 : dposdt[0];
        double gv = k < N ? dveldq[k] : k < 2 * N ? dveldv[k - N] : dveldt[0];
        worst = fmax(worst, fabs(gp - d[0]) / (1 + fabs(d[0])));
        worst = fmax(worst, fabs(gv - d[1]) / (1 + fabs(d[1])));
    }
    CHECK(worst < FD_TOL, "c_levels_jacobian matches central differences of c_levels "
          "(worst %.2g)", worst);
}

static void
test_sizes(const Lowered *L)
{
    const LowFunc *mb = lower_find(L, "mass_bias"), *cj = lower_find(L, "c_jacobian");
    CHECK(lower_size(mb, 0) == N * N && lower_size(mb, 1) == N,
          "sizes from the list: M has %d entries, h %d", lower_size(mb, 0), lower_size(mb, 1));
    CHECK(lower_size(cj, 4) == NC * N * N && lower_size(cj, 7) == NC * N * NU,
          "sizes from the list: dB/dq has %d entries, dB/du %d", lower_size(cj, 4),
          lower_size(cj, 7));
    CHECK(lower_find(L, "invariant") == NULL, "a model with inputs lowers no invariant");
    LowArgs a;
    lower_args(lower_find(L, "inputs")->sig, &a);
    CHECK(a.n == 4 && a.nin == 2 && !strcmp(a.name[3], "dudt") && a.optional[3] &&
          !a.optional[2], "signature \"t p > u dudt?\": 2 inputs, dudt optional");
}

/* Unit loads through the unrolled LDL^T (Lagrange's form has no solve of
 * its own): accel_solve is q'' without the constraint, M a_f + h = 0, and
 * minv_shared's y solves M y = x for a load x, each against M and h from
 * mass_bias; minv reads from shared[] what accel_solve stores there. */
static void
test_loads(const Lowered *L)
{
    const LowFunc *acc = lower_find(L, "accel_solve"), *mv = lower_find(L, "minv_shared");
    CHECK(L->loads && acc && mv && mv->shared && L->loads_shared > 0,
          "a constrained model's accel_solve and minv_shared, %d values shared", L->loads_shared);
    if (!acc || !mv)
        return;
    State x = random_state();
    ExprEnv env = env_of(&x);
    double M[N * N], h[N], a[N], piv[N], mkk[N], y[N], load[N];
    double *shared = calloc((size_t)L->loads_shared, sizeof *shared);
    lower_eval(P, lower_find(L, "mass_bias"), &env, (double *const[]){M, h});
    lower_eval(P, acc, &env, (double *const[]){a, piv, mkk, shared});
    for (int i = 0; i < N; i++)
        load[i] = check_rand(-1, 1);
    env.seed[2] = load;
    lower_eval(P, mv, &env, (double *const[]){y});
    double worst = 0, stored = 0;
    for (int i = 0; i < N; i++) {
        double ra = h[i], ry = -load[i], sa = fabs(h[i]), sy = fabs(load[i]);
        for (int j = 0; j < N; j++) {
            ra += M[i * N + j] * a[j], sa += fabs(M[i * N + j] * a[j]);
            ry += M[i * N + j] * y[j], sy += fabs(M[i * N + j] * y[j]);
        }
        worst = fmax(worst, fmax(fabs(ra) / sa, fabs(ry) / sy));
    }
    /* each shared value is the node minv reads there */
    for (size_t id = 0; id < expr_pool_size(P); id++)
        if (mv->shared[id] >= 0)
            stored = fmax(stored, fabs(shared[mv->shared[id]] - expr_eval(P, (ExprId)id, &env)));
    CHECK(worst < 1e-14 && stored == 0, "M a_f + h = 0 and M y = x by the LDL^T factors (worst "
          "%.2g of the terms); shared[] holds what minv reads", worst);
    free(shared);
}

int
main(void)
{
    A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    Lowered *L = lowered(LOWER_JACOBIAN_UNROLLED);
    Lowered *S = lowered(LOWER_JACOBIAN_SEEDED);
    CHECK(L && S, "the spec lowers");
    if (L && S) {
        for (int r = 0; r < 3; r++)
            test_jacobian(L);
        test_seeded(L, S);
        test_inputs(L);
        for (int r = 0; r < 3; r++)
            test_constraint(L);
        test_sizes(L);
        test_loads(L);
    }
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}

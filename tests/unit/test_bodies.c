/*
 * Rigid bodies (spec `bodies:`, mech.c) against independent values:
 *  - z-x-z Euler angles give the body rates p, q, r of docs/mechanics.md;
 *  - dS/dq'' = d/dt dT/dq' - dT/dq for a body with a full inertia tensor
 *    and a moving centre (the Gibbs-Appell identity);
 *  - a free body with a body-frame torque satisfies Euler's equations
 *    I w' + w x I w = tau, with q'' from the Lagrange residual, and the
 *    Gibbs-Appell residual gives the same q'';
 *  - the same body placed by a frame (z-x-z turns), with torques given as
 *    world vectors (a damper -c omega(F) and a turn about the vertical):
 *    I w' + w x I w = -c w + tau R^T z, R^T z = (sin th sin phi,
 *    sin th cos phi, cos th) written here;
 *  - a planar body: J theta'' = tau, and gravity on the centre of a
 *    compound pendulum: (J + m d^2) theta'' = -m g d sin(theta).
 */
#include "check.h"
#include "forms/eom.h"

#include <string.h>

static Arena *A;
static ExprPool *P;
static Diff *D;

static Spec *
load(const char *text)
{
    return spec_load_buffer("b.yaml", text, strlen(text), NULL, A, P);
}

typedef struct State {
    double t, q[3], v[3], a[3], p[16];
} State;

static double
eval(ExprId e, const State *s)
{
    double zero[4] = {0};
    ExprEnv env = {.t = s->t, .q = {s->q, s->v, s->a, zero}, .p = s->p, .u = zero};
    return expr_eval(P, e, &env);
}

static void
random_state(State *s, const Spec *sp)
{
    s->t = check_rand(0, 1);
    for (int i = 0; i < 3; i++) {
        s->q[i] = check_rand(0.3, 2.8); /* keep sin(theta) away from 0 */
        s->v[i] = check_rand(-2, 2);
        s->a[i] = check_rand(-2, 2);
    }
    for (int k = 0; k < sp->np; k++)
        s->p[k] = sp->param[k].value;
}

/* q'' = -M^-1 h by Gaussian elimination with partial pivoting. */
static void
accelerations(const Eom *e, State *s)
{
    int n = e->n;
    double M[9], h[3];
    for (int i = 0; i < n * n; i++)
        M[i] = eval(e->M[i], s);
    for (int i = 0; i < n; i++)
        h[i] = -eval(e->h[i], s);
    int singular = check_solve(M, h, n) != 0;
    for (int i = 0; i < n; i++)
        s->a[i] = singular ? NAN : h[i];
}

static const char *const top =
    "parameters: {m: 1.5, A: 0.4, B: 0.7, C: 1.1, t1: 0.3, t2: -0.2, t3: 0.5}\n"
    "coordinates: [psi, theta, phi]\n"
    "bodies:\n"
    "  top:\n"
    "    mass: m\n"
    "    center: [0, 0, 0]\n"
    "    inertia: [A, B, C]\n"
    "    rotation: {zxz: [psi, theta, phi]}\n"
    "effects: {push: {torque: [t1, t2, t3], on: top}}\n";

static void
test_euler_rates(void)
{
    Spec *s = load(top);
    CHECK(s && s->nbody == 1 && s->body[0].dim == 3, "a 3-D body with a z-x-z rotation loads");
    if (!s)
        return;
    int ok = 1;
    for (int k = 0; k < 20; k++) {
        State st;
        random_state(&st, s);
        double ps = st.v[0], th = st.q[1], thd = st.v[1], ph = st.q[2], phd = st.v[2];
        double p = ps * sin(th) * sin(ph) + thd * cos(ph);
        double q = ps * sin(th) * cos(ph) - thd * sin(ph);
        double r = ps * cos(th) + phd;
        ok &= check_close(eval(s->body[0].omega[0], &st), p, 1e-14) &&
              check_close(eval(s->body[0].omega[1], &st), q, 1e-14) &&
              check_close(eval(s->body[0].omega[2], &st), r, 1e-14);
    }
    CHECK(ok, "zxz: p = psi' sin th sin phi + th' cos phi, q = ..., r = psi' cos th + phi'");
}

/* The Lagrange and Gibbs-Appell equations of s. */
typedef struct Both {
    Eom *lag, *ga;
} Both;

static Both
derive_both(Spec *s)
{
    Mech *m = mech_build(s, A, P, D);
    const char *why;
    return (Both){eom_derive(s, m, &form_lagrange, A, P, D, &why),
                  eom_derive(s, m, &form_gibbs_appell, A, P, D, &why)};
}

/* A random state of s, q'' from Lagrange in *st and from Gibbs-Appell in
 * *ga (the same state). */
static void
solve_both(const Spec *s, Both e, State *st, State *ga)
{
    random_state(st, s);
    accelerations(e.lag, st);
    *ga = *st;
    accelerations(e.ga, ga);
}

/* I w' + w x I w, the left side of Euler's equations in principal axes. */
static void
euler_lhs(const double I[3], const double w[3], const double wd[3], double lhs[3])
{
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, l = (i + 2) % 3;
        lhs[i] = I[i] * wd[i] + (w[j] * I[l] * w[l] - w[l] * I[j] * w[j]);
    }
}

/* Euler's equations with the torque, for q'' from Lagrange and from
 * Gibbs-Appell. */
static void
test_euler_equations(void)
{
    Spec *s = load(top);
    if (!s)
        return;
    Both e = derive_both(s);
    int ok = 1, agree = 1;
    for (int k = 0; k < 20; k++) {
        State st, st2;
        solve_both(s, e, &st, &st2);
        double w[3], wd[3], lhs[3], I[3] = {0.4, 0.7, 1.1}, tau[3] = {0.3, -0.2, 0.5};
        for (int i = 0; i < 3; i++) {
            w[i] = eval(s->body[0].omega[i], &st);
            wd[i] = eval(diff_time(D, s->body[0].omega[i]), &st);
            agree &= check_close(st2.a[i], st.a[i], 1e-11);
        }
        euler_lhs(I, w, wd, lhs);
        for (int i = 0; i < 3; i++)
            ok &= check_close(lhs[i], tau[i], 1e-10);
    }
    CHECK(ok, "free body with torque: I w' + w x I w = tau (Lagrange q'')");
    CHECK(agree, "Gibbs-Appell gives the same q'' as Lagrange");
}

/* A body placed by a frame turns with it, and a torque that is a world
 * vector is taken to its axes. */
static void
test_frame_torques(void)
{
    Spec *s = load(
        "parameters: {m: 1.5, A: 0.4, B: 0.7, C: 1.1, c: 0.3, tau: 0.8}\n"
        "coordinates: [psi, theta, phi]\n"
        "frames:\n"
        "  F: {rotation: [{z: psi}, {x: theta}, {z: phi}]}\n"
        "bodies:\n"
        "  top: {mass: m, frame: F, center: [0, 0, 0], inertia: [A, B, C]}\n"
        "effects:\n"
        "  damp: {torque: -c*omega(F), on: top}\n"
        "  turn: {torque: tau*world.z, on: top}\n");
    CHECK(s != NULL, "a body placed by a frame, torques as world vectors: loads");
    if (!s)
        return;
    Both e = derive_both(s);
    double worst = 0, apart = 0;
    for (int k = 0; k < 20; k++) {
        State st, st2;
        solve_both(s, e, &st, &st2);
        /* the body rates and their derivative written out (z-x-z) */
        double ps = st.v[0], th = st.q[1], thd = st.v[1], ph = st.q[2], phd = st.v[2];
        double psd = st.a[0], thdd = st.a[1], phdd = st.a[2];
        double sth = sin(th), cth = cos(th), sph = sin(ph), cph = cos(ph);
        double w[3] = {ps * sth * sph + thd * cph, ps * sth * cph - thd * sph, ps * cth + phd};
        double wd[3] = {psd * sth * sph + ps * thd * cth * sph + ps * sth * cph * phd +
                        thdd * cph - thd * sph * phd,
                        psd * sth * cph + ps * thd * cth * cph - ps * sth * sph * phd -
                        thdd * sph - thd * cph * phd,
                        psd * cth - ps * thd * sth + phdd};
        double I[3] = {0.4, 0.7, 1.1}, up[3] = {sth * sph, sth * cph, cth}, lhs[3];
        euler_lhs(I, w, wd, lhs);
        for (int i = 0; i < 3; i++) {
            worst = fmax(worst, fabs(lhs[i] - (-0.3 * w[i] + 0.8 * up[i])));
            apart = fmax(apart, fabs(st2.a[i] - st.a[i]));
        }
    }
    /* q'' is solved from M, whose condition grows as 1/sin^2 theta
     * (theta in [0.3, 2.8]: up to 13); the values are of order 1 */
    CHECK(worst <= 1e-12, "a body on a frame with world-vector torques: I w' + w x I w = "
          "-c w + tau R^T z (to %.2g)", worst);
    CHECK(apart <= 1e-12, "... and Gibbs-Appell gives the same q'' (to %.2g)", apart);
}

static void
test_appell_identity(void)
{
    Spec *s = load(
        "parameters: {m: 2, a: 0.3}\n"
        "coordinates: [x, th, ph]\n"
        "bodies:\n"
        "  b:\n"
        "    mass: m\n"
        "    center: [x + a*cos(th), a*sin(th)*sin(ph), t*x]\n"
        "    inertia: [[1.2, 0.1, -0.2], [0.1, 0.9, 0.05], [-0.2, 0.05, 1.5]]\n"
        "    rotation: {zyx: [ph, th, x]}\n");
    CHECK(s != NULL, "a body with a full inertia tensor and a zyx rotation loads");
    if (!s)
        return;
    Mech *m = mech_build(s, A, P, D);
    int ok = 1;
    for (int i = 0; i < 3; i++) {
        ExprId dTdv = diff_partial(D, m->T, m->q[1][i]);
        ExprId rhs = expr_sub(P, diff_time(D, dTdv), diff_partial(D, m->T, m->q[0][i]));
        ExprId lhs = diff_partial(D, m->S, m->q[2][i]);
        for (int k = 0; k < 20; k++) {
            State st;
            random_state(&st, s);
            ok &= check_close(eval(lhs, &st), eval(rhs, &st), 1e-11);
        }
    }
    CHECK(ok, "body: dS/dq'' = d/dt dT/dq' - dT/dq at random states");
}

static void
test_planar(void)
{
    Spec *s = load(
        "parameters: {m: 2, J: 0.3, d: 0.4, g: 9.81, tau: 0.7}\n"
        "coordinates: [th]\n"
        "bodies: {arm: {mass: m, center: [d*sin(th), -d*cos(th)], inertia: J, angle: th}}\n"
        "effects:\n"
        "  gravity: {gravity: [0, -g]}\n"
        "  motor: {torque: tau, on: arm}\n");
    CHECK(s && s->body[0].dim == 2, "a planar body loads");
    if (!s)
        return;
    Mech *m = mech_build(s, A, P, D);
    const char *why;
    Eom *e = eom_derive(s, m, &form_lagrange, A, P, D, &why);
    int ok = 1;
    for (int k = 0; k < 10; k++) {
        State st;
        random_state(&st, s);
        accelerations(e, &st);
        double want = (0.7 - 2 * 9.81 * 0.4 * sin(st.q[0])) / (0.3 + 2 * 0.16);
        ok &= check_close(st.a[0], want, 1e-13);
    }
    CHECK(ok, "compound pendulum with a motor: (J + m d^2) th'' = tau - m g d sin th");
}

int
main(void)
{
    A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    test_euler_rates();
    test_euler_equations();
    test_frame_torques();
    test_appell_identity();
    test_planar();
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}

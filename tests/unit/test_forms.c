/*
 * The identities behind the forms (docs/mechanics.md), at random states:
 *     dS/dq'' = d/dt dT/dq' - dT/dq
 *     d(T')/dq' = d/dt dT/dq' + dT/dq
 *     1/2 d(T'')/dq'' = d/dt dT/dq' + 1/2 dT/dq
 * and the four residual forms giving the same M and h (and the seeded
 * directional derivatives of E matching its Jacobian), for models built
 * directly as Specs (no YAML): a double pendulum in absolute angles, and
 * a particle in spherical coordinates with a time-dependent support.
 */
#include "check.h"
#include "forms/eom.h"
#include "forms/form_util.h"

#include <string.h>

static ExprPool *P;
static Diff *D;
static Arena *A;

static ExprId C(double v) { return expr_const(P, v); }
static ExprId q(int i) { return expr_var(P, i, 0); }
static ExprId fn(int op, ExprId a) { return expr_unary(P, op, a); }

/* Double pendulum: masses m1 = 1.3, m2 = 0.7 on rods 1.1, 0.9. */
static Spec *
double_pendulum(void)
{
    Spec *s = arena_alloc(A, sizeof *s);
    s->path = "dp.yaml";
    s->name = "dp";
    s->nq = 2;
    spec_plain_slots(s, A);
    s->coord = arena_new_array(A, SpecCoord, 2);
    s->npart = 2;
    s->part = arena_new_array(A, SpecParticle, 2);
    ExprId x1 = expr_mul(P, C(1.1), fn(EXPR_SIN, q(0)));
    ExprId y1 = expr_mul(P, C(-1.1), fn(EXPR_COS, q(0)));
    s->part[0] = (SpecParticle){"b1", {0}, C(1.3), 2, {x1, y1, 0}, {0}, 0, -1};
    s->part[1] = (SpecParticle){"b2", {0}, C(0.7), 2,
        {expr_add(P, x1, expr_mul(P, C(0.9), fn(EXPR_SIN, q(1)))),
         expr_sub(P, y1, expr_mul(P, C(0.9), fn(EXPR_COS, q(1)))), 0}, {0}, 0, -1};
    s->neffect = 1;
    s->effect = arena_new_array(A, SpecEffect, 1);
    SpecForce *g = arena_new_array(A, SpecForce, 1);
    *g = (SpecForce){.kind = FORCE_GRAVITY, .dim = 2, .vec = {EXPR_ZERO, C(-9.81), 0}};
    s->effect[0] = (SpecEffect){"gravity", {0}, 1, g, 1};
    return s;
}

/* Particle of mass 2 in spherical coordinates (r, theta, phi) about a
 * support moving as (0.3 sin t, 0, 0.1 t^2), with a drag force. */
static Spec *
moving_sphere(void)
{
    Spec *s = arena_alloc(A, sizeof *s);
    s->path = "ms.yaml";
    s->name = "ms";
    s->nq = 3;
    spec_plain_slots(s, A);
    s->coord = arena_new_array(A, SpecCoord, 3);
    s->npart = 1;
    s->part = arena_new_array(A, SpecParticle, 1);
    ExprId t = expr_time(P), r = q(0), th = q(1), ph = q(2);
    ExprId rs = expr_mul(P, r, fn(EXPR_SIN, th));
    s->part[0] = (SpecParticle){"p", {0}, C(2.0), 3, {
        expr_add(P, expr_mul(P, C(0.3), fn(EXPR_SIN, t)), expr_mul(P, rs, fn(EXPR_COS, ph))),
        expr_mul(P, rs, fn(EXPR_SIN, ph)),
        expr_add(P, expr_mul(P, C(0.1), expr_powi(P, t, 2)), expr_mul(P, r, fn(EXPR_COS, th)))}, {0}, 0, -1};
    s->neffect = 2;
    s->effect = arena_new_array(A, SpecEffect, 2);
    SpecForce *f = arena_new_array(A, SpecForce, 2);
    f[0] = (SpecForce){.kind = FORCE_GRAVITY, .dim = 3, .vec = {0, 0, C(-9.81)}};
    ExprId vel[3];
    for (int k = 0; k < 3; k++)
        vel[k] = expr_mul(P, C(-0.4), diff_time(D, s->part[0].pos[k]));
    f[1] = (SpecForce){.kind = FORCE_VECTOR, .particle = 0, .dim = 3,
                       .vec = {vel[0], vel[1], vel[2]}};
    s->effect[0] = (SpecEffect){"gravity", {0}, 1, &f[0], 1};
    s->effect[1] = (SpecEffect){"drag", {0}, 1, &f[1], 1};
    return s;
}

static void
random_env(ExprEnv *env, double st[4][3], int n)
{
    for (int k = 0; k < 4; k++)
        for (int i = 0; i < n; i++)
            st[k][i] = check_rand(-1.5, 1.5);
    st[0][0] = check_rand(0.5, 2); /* r > 0 for the sphere */
    env->t = check_rand(-1, 1);
    for (int k = 0; k < 4; k++)
        env->q[k] = st[k];
}

static void
check_identities(const char *label, const Spec *s)
{
    Mech *m = mech_build(s, A, P, D);
    int n = m->n;
    ExprId *dT = form_gradient(m, m->T, 0, A, D);
    ExprId *dTv = form_gradient(m, m->T, 1, A, D);
    ExprId *dS = form_gradient(m, m->S, 2, A, D);
    ExprId *dT1 = form_gradient(m, diff_time(D, m->T), 1, A, D);
    ExprId *dT2 = form_gradient(m, diff_time(D, diff_time(D, m->T)), 2, A, D);
    int ok[3] = {1, 1, 1};
    for (int trial = 0; trial < 100; trial++) {
        double st[4][3];
        ExprEnv env = {0};
        random_env(&env, st, n);
        for (int i = 0; i < n; i++) {
            double lag = expr_eval(P, diff_time(D, dTv[i]), &env);
            double dq = expr_eval(P, dT[i], &env);
            ok[0] &= check_close(expr_eval(P, dS[i], &env), lag - dq, 1e-12);
            ok[1] &= check_close(expr_eval(P, dT1[i], &env), lag + dq, 1e-12);
            ok[2] &= check_close(0.5 * expr_eval(P, dT2[i], &env), lag + 0.5 * dq, 1e-12);
        }
    }
    CHECK(ok[0], "%s: dS/dq'' = d/dt dT/dq' - dT/dq", label);
    CHECK(ok[1], "%s: d(T')/dq' = d/dt dT/dq' + dT/dq (Nielsen)", label);
    CHECK(ok[2], "%s: 1/2 d(T'')/dq'' = d/dt dT/dq' + 1/2 dT/dq (Tzenoff)", label);
}

static void
check_forms_agree(const char *label, const Spec *s)
{
    Mech *m = mech_build(s, A, P, D);
    int n = m->n;
    const char *names[] = {"lagrange", "nielsen", "tzenoff", "gibbs-appell"};
    Eom *e[4];
    for (int f = 0; f < 4; f++) {
        const char *why = NULL;
        e[f] = eom_derive(s, m, form_find(names[f]), A, P, D, &why);
        if (e[f])
            eom_derive_jacobian(e[f], m, A, P, D);
        CHECK(e[f] != NULL, "%s: form %s applies", label, names[f]);
        if (!e[f])
            return;
    }
    int ok[4] = {1, 1, 1, 1}, sym = 1, affine = 1, jvp = 1;
    for (int trial = 0; trial < 100; trial++) {
        double st[4][3];
        ExprEnv env = {0};
        random_env(&env, st, n);
        for (int i = 0; i < n * n; i++) {
            double want = expr_eval(P, e[0]->M[i], &env);
            for (int f = 1; f < 4; f++)
                ok[f] &= check_close(expr_eval(P, e[f]->M[i], &env), want, 1e-12);
        }
        for (int i = 0; i < n; i++) {
            double want = expr_eval(P, e[0]->h[i], &env);
            for (int f = 1; f < 4; f++)
                ok[f] &= check_close(expr_eval(P, e[f]->h[i], &env), want, 1e-12);
            /* E = M a + h, with the residual evaluated directly */
            double Ma = want;
            for (int j = 0; j < n; j++)
                Ma += expr_eval(P, e[0]->M[i * n + j], &env) * st[2][j];
            affine &= check_close(expr_eval(P, e[0]->E[i], &env), Ma, 1e-12);
        }
        /* the seeded forms: sum_j dE_i/dq_j dq_j (and for q') at a random
         * seed, against the unrolled Jacobian, for every form */
        double seed[2][3];
        for (int j = 0; j < n; j++)
            seed[0][j] = check_rand(-1, 1), seed[1][j] = check_rand(-1, 1);
        env.seed[0] = seed[0];
        env.seed[1] = seed[1];
        for (int f = 0; f < 4; f++)
            for (int i = 0; i < n; i++) {
                double wq = 0, wv = 0;
                for (int j = 0; j < n; j++) {
                    wq += expr_eval(P, e[f]->dEdq[i * n + j], &env) * seed[0][j];
                    wv += expr_eval(P, e[f]->dEdv[i * n + j], &env) * seed[1][j];
                }
                jvp &= check_close(expr_eval(P, e[f]->jvp_q[i], &env), wq, 1e-12);
                jvp &= check_close(expr_eval(P, e[f]->jvp_v[i], &env), wv, 1e-12);
            }
        /* the lower triangle is computed; check the upper one from the
         * residual directly: dE_i/da_j = dE_j/da_i */
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++) {
                double up = expr_eval(P, diff_partial(D, e[0]->E[i], m->q[2][j]), &env);
                sym &= check_close(up, expr_eval(P, e[0]->M[j * n + i], &env), 1e-12);
            }
    }
    for (int f = 1; f < 4; f++)
        CHECK(ok[f], "%s: %s gives the M and h of lagrange", label, names[f]);
    CHECK(sym, "%s: dE/dq'' is symmetric", label);
    CHECK(affine, "%s: E = M q'' + h", label);
    CHECK(jvp, "%s: seeded derivatives of E = its Jacobian times the seeds", label);
}

int
main(void)
{
    P = expr_pool_new();
    D = diff_new(P);
    A = arena_new();
    Spec *dp = double_pendulum(), *ms = moving_sphere();
    check_identities("double pendulum", dp);
    check_identities("moving sphere", ms);
    check_forms_agree("double pendulum", dp);
    check_forms_agree("moving sphere", ms);
    arena_free(A);
    diff_free(D);
    expr_pool_free(P);
    return check_done();
}

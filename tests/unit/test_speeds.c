/*
 * Speeds (spec.h: a quaternion's `speeds:`, its angular velocity in its
 * own axes, in place of its Euler parameters' rates), on a free body that
 * carries an arm on an oblique hinge, with a virtual work on its speeds
 * (delta(wx): the virtual rotation about its x axis):
 *   - the forms that take speeds apply, Lagrange's refuses with its reason;
 *   - the Euler parameters' rates are 1/2 e (x) (0, w), the quaternion
 *     product written out here;
 *   - at random states, q'' of the articulated-body recursion in speeds
 *     equals that of the same model written in the Euler parameters' rates
 *     (their unit constraint met by the recursion itself, mech.h), turned
 *     into w' = 2 L(e) e'' - L(e) L(e')^T w, and the kinetic energies agree;
 *   - the Newton-Euler and Gibbs-Appell residuals in speeds vanish there;
 *   - the Jacobian dE/dq [nv x nq], dE/dv [nv x nv], unrolled and seeded,
 *     equals central differences of E;
 *   - constraints in speeds: a free top whose tip three constraints hold
 *     at the origin, solved here by its KKT system (GSL's LU), turns as
 *     the same top on a ball joint (a tree, no constraint) does.
 */
#include "check.h"
#include "forms/eom.h"
#include "mechanics/constraint.h"

#include <gsl/gsl_linalg.h>
#include <string.h>

static Arena *A;

static const char speeds_spec[] =
    "name: free_arm\n"
    "parameters: {g: 9.81}\n"
    "coordinates: [x, y, z, e0, e1, e2, e3, h]\n"
    "frames:\n"
    "  body_axes: {rotation: {quaternion: [e0, e1, e2, e3], speeds: [wx, wy, wz]}}\n"
    "  arm_axes: {parent: body_axes, rotation: [{axis: [0.6, 0, 0.8], angle: h}]}\n"
    "points:\n"
    "  base: {at: [x, y, z]}\n"
    "  body_c: {frame: body_axes, from: base, at: [0.1, -0.05, 0.2]}\n"
    "  hinge: {frame: body_axes, from: base, at: [0.3, 0, 0]}\n"
    "  arm_c: {frame: arm_axes, from: hinge, at: [0, 0.4, 0]}\n"
    "bodies:\n"
    "  B: {mass: 2, frame: body_axes, center: body_c,\n"
    "      inertia: [[0.3, 0.01, 0.02], [0.01, 0.5, 0.03], [0.02, 0.03, 0.7]]}\n"
    "  C: {mass: 0.5, frame: arm_axes, center: arm_c, inertia: [0.05, 0.01, 0.05]}\n"
    "effects:\n"
    "  gravity: {gravity: [0, 0, -g]}\n"
    "  spin: {work: \"-0.3*wx*delta(wx) + 0.2*delta(wz)\"}\n"
    "initial: {e0: 1, wx: 0.5}\n"
    "scene: {t_end: 1}\n";

typedef struct Model {
    ExprPool *P;
    Diff *D;
    Spec *s;
    Mech *m;
} Model;

/* every model loaded, freed by done() */
static Model loaded[4];
static int nloaded;

static Model
load(const char *text)
{
    Model md = {expr_pool_new(), NULL, NULL, NULL};
    md.D = diff_new(md.P);
    if (nloaded < 4)
        loaded[nloaded++] = md;
    md.s = spec_load_buffer("free_arm.yaml", text, strlen(text), NULL, A, md.P);
    if (md.s)
        md.m = mech_build(md.s, A, md.P, md.D);
    return md;
}

/* The plan and the exit status, everything freed. */
static int
done(void)
{
    for (int i = 0; i < nloaded; i++) {
        diff_free(loaded[i].D);
        expr_pool_free(loaded[i].P);
    }
    arena_free(A);
    return check_done();
}

/* text with its first `from` replaced by `to` (a CHECK fails where there
 * is none). */
static char *
variant(const char *text, const char *from, const char *to)
{
    const char *at = strstr(text, from);
    CHECK(at != NULL, "variant '%s' found", from);
    if (!at)
        return arena_strdup(A, text);
    return arena_printf(A, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
}

/* L(e) [3 x 4]: w = 2 L(e) e' in the turned axes. */
static void
Lmat(const double *e, double L[12])
{
    const double r[12] = {-e[1], e[0], e[3], -e[2], -e[2], -e[3], e[0], e[1],
                          -e[3], e[2], -e[1], e[0]};
    memcpy(L, r, sizeof r);
}

static const char free_top[] =
    "name: free_top\n"
    "parameters: {g: 9.81}\n"
    "coordinates: [x, y, z, e0, e1, e2, e3]\n"
    "frames:\n"
    "  top_axes: {rotation: {quaternion: [e0, e1, e2, e3], speeds: [wx, wy, wz]}}\n"
    "points:\n"
    "  tip: {at: [x, y, z]}\n"
    "  c: {frame: top_axes, from: tip, at: [0.1, 0.05, 0.4]}\n"
    "bodies:\n"
    "  T: {mass: 1.5, frame: top_axes, center: c,\n"
    "      inertia: [[0.2, 0.01, 0], [0.01, 0.25, 0.02], [0, 0.02, 0.1]]}\n"
    "effects:\n"
    "  gravity: {gravity: [0, 0, -g]}\n"
    "constraints: {tip_x: x, tip_y: y, tip_z: z}\n"
    "initial: {e0: 1}\n"
    "scene: {t_end: 1}\n";

static const char ball_top[] =
    "name: ball_top\n"
    "parameters: {g: 9.81}\n"
    "coordinates: [e0, e1, e2, e3]\n"
    "frames:\n"
    "  top_axes: {rotation: {quaternion: [e0, e1, e2, e3], speeds: [wx, wy, wz]}}\n"
    "points:\n"
    "  c: {frame: top_axes, at: [0.1, 0.05, 0.4]}\n"
    "bodies:\n"
    "  T: {mass: 1.5, frame: top_axes, center: c,\n"
    "      inertia: [[0.2, 0.01, 0], [0.01, 0.25, 0.02], [0, 0.02, 0.1]]}\n"
    "effects:\n"
    "  gravity: {gravity: [0, 0, -g]}\n"
    "initial: {e0: 1}\n"
    "scene: {t_end: 1}\n";

/* The free top's KKT solve against the ball joint's recursion. */
static void
check_constrained(void)
{
    Model fr = load(free_top), bl = load(ball_top);
    CHECK(fr.m && bl.m, "the free top and the top on a ball joint load");
    if (!fr.m || !bl.m)
        return;
    const char *why = NULL;
    Constraints *c = constraints_build(fr.s, fr.m, A, fr.P, fr.D);
    Eom *ne = eom_derive(fr.s, fr.m, form_find("newton-euler"), A, fr.P, fr.D, &why);
    Eom *ab = eom_derive(bl.s, bl.m, form_find("articulated-body"), A, bl.P, bl.D, &why);
    CHECK(c && c->n == 6 && c->nc == 3 && ne && ne->M && ab && ab->acc,
          "three constraints on six speeds; both forms apply");
    if (!c || !ne || !ne->M || !ab || !ab->acc)
        return;
    double p[1] = {9.81}, worst = 0;
    gsl_matrix *K = gsl_matrix_alloc(9, 9);
    gsl_vector *r = gsl_vector_alloc(9), *x = gsl_vector_alloc(9);
    gsl_permutation *perm = gsl_permutation_alloc(9);
    for (int trial = 0; trial < 20; trial++) {
        double q[7] = {0}, v[10] = {0}, zero[10] = {0}, n2 = 0;
        for (int i = 3; i < 7; i++)
            q[i] = check_rand(-1, 1), n2 += q[i] * q[i];
        for (int i = 3; i < 7; i++)
            q[i] /= sqrt(n2);
        for (int i = 7; i < 10; i++)
            v[i] = check_rand(-3, 3);
        ExprEnv env = {.p = p};
        env.q[0] = q, env.q[1] = v, env.q[2] = zero;
        gsl_matrix_set_zero(K);
        for (int i = 0; i < 6; i++) {
            for (int j = 0; j < 6; j++)
                gsl_matrix_set(K, i, j, expr_eval(fr.P, ne->M[i * 6 + j], &env));
            gsl_vector_set(r, i, -expr_eval(fr.P, ne->h[i], &env));
        }
        for (int a = 0; a < 3; a++) {
            for (int j = 0; j < 6; j++) {
                double b = expr_eval(fr.P, c->B[a * 6 + j], &env);
                gsl_matrix_set(K, 6 + a, j, b), gsl_matrix_set(K, j, 6 + a, b);
            }
            gsl_vector_set(r, 6 + a, -expr_eval(fr.P, c->b[a], &env));
        }
        int sign;
        gsl_linalg_LU_decomp(K, perm, &sign);
        gsl_linalg_LU_solve(K, perm, r, x);
        /* the ball: q = e, its slots the speeds (leaves 4, 5, 6) */
        double qb[4] = {q[3], q[4], q[5], q[6]}, vb[7] = {0, 0, 0, 0, v[7], v[8], v[9]};
        double zb[7] = {0};
        ExprEnv eb = {.p = p};
        eb.q[0] = qb, eb.q[1] = vb, eb.q[2] = zb;
        double amax = 0, want[3];
        for (int k = 0; k < 3; k++)
            want[k] = expr_eval(bl.P, ab->acc[k], &eb), amax = fmax(amax, fabs(want[k]));
        for (int k = 0; k < 3; k++)
            worst = fmax(worst, fabs(gsl_vector_get(x, 3 + k) - want[k]) / amax);
        for (int k = 0; k < 3; k++) /* the tip stays */
            worst = fmax(worst, fabs(gsl_vector_get(x, k)) / amax);
    }
    gsl_permutation_free(perm);
    gsl_vector_free(x);
    gsl_vector_free(r);
    gsl_matrix_free(K);
    CHECK(worst < 1e-12, "the held free top's w' (KKT in speeds) = the ball joint's (20 states; "
          "worst %.2g of max |w'|)", worst);
}

int
main(void)
{
    A = arena_new();
    Model sp = load(speeds_spec);
    CHECK(sp.s && sp.m, "the free body with speeds loads");
    if (!sp.s || !sp.m)
        return done();
    const Spec *s = sp.s;
    CHECK(s->nq == 8 && s->nv == 7 && s->nspeed == 3 && s->nconstraint == 0,
          "8 coordinates, 7 speeds (x' y' z' wx wy wz h'), no unit constraint");
    const char *why = NULL;
    Eom *lag = eom_derive(s, sp.m, form_find("lagrange"), A, sp.P, sp.D, &why);
    CHECK(!lag && why && strstr(why, "speeds"), "Lagrange's form refuses speeds: %s",
          why ? why : "(no reason)");
    Eom *ab = eom_derive(s, sp.m, form_find("articulated-body"), A, sp.P, sp.D, &why);
    Eom *ne = eom_derive(s, sp.m, form_find("newton-euler"), A, sp.P, sp.D, &why);
    Eom *ga = eom_derive(s, sp.m, form_find("gibbs-appell"), A, sp.P, sp.D, &why);
    CHECK(ab && ab->acc && ne && ga, "articulated-body, newton-euler and gibbs-appell apply");

    /* the same model in the Euler parameters' rates, its work by their
     * variations: w = 2 L e', the virtual rotation 2 L delta(e) */
    char *plain = variant(speeds_spec, ", speeds: [wx, wy, wz]", "");
    plain = variant(plain, ", wx: 0.5", "");
    plain = variant(plain, "-0.3*wx*delta(wx) + 0.2*delta(wz)",
                    "-0.3*(2*(-e1*e0' + e0*e1' + e3*e2' - e2*e3'))*(2*(-e1*delta(e0) + "
                    "e0*delta(e1) + e3*delta(e2) - e2*delta(e3))) + 0.2*2*(-e3*delta(e0) + "
                    "e2*delta(e1) - e1*delta(e2) + e0*delta(e3))");
    Model qm = load(plain);
    Eom *ab0 = qm.m ? eom_derive(qm.s, qm.m, form_find("articulated-body"), A, qm.P, qm.D, &why)
                    : NULL;
    CHECK(ab0 && ab0->acc && qm.s->nv == 8, "the same model without speeds loads and solves");
    if (!ab || !ab->acc || !ne || !ga || !ab0 || !ab0->acc)
        return done();

    double p[1] = {9.81};
    double worst_rate = 0, worst_a = 0, worst_T = 0, worst_ne = 0, worst_ga = 0;
    for (int trial = 0; trial < 50; trial++) {
        /* coordinates by index, and the rates by leaf index: the speeds'
         * after the coordinates (nq + k) */
        double q[8], v[11] = {0}, zero[11] = {0}, e[4], n2 = 0, w[3];
        for (int i = 0; i < 8; i++)
            q[i] = check_rand(-1, 1);
        for (int i = 0; i < 4; i++)
            n2 += q[3 + i] * q[3 + i];
        for (int i = 0; i < 4; i++)
            e[i] = q[3 + i] /= sqrt(n2);
        for (int i = 0; i < 3; i++)
            v[i] = check_rand(-2, 2), w[i] = v[8 + i] = check_rand(-2, 2);
        v[7] = check_rand(-2, 2);
        ExprEnv env = {.p = p, .t = 0};
        env.q[0] = q, env.q[1] = v, env.q[2] = zero;
        /* e' = 1/2 e (x) (0, w): (-ev.w, e0 w + ev x w) / 2 */
        double ed[4] = {-(e[1] * w[0] + e[2] * w[1] + e[3] * w[2]) / 2,
                        (e[0] * w[0] + e[2] * w[2] - e[3] * w[1]) / 2,
                        (e[0] * w[1] + e[3] * w[0] - e[1] * w[2]) / 2,
                        (e[0] * w[2] + e[1] * w[1] - e[2] * w[0]) / 2};
        for (int c = 0; c < 4; c++)
            worst_rate = fmax(worst_rate, fabs(expr_eval(sp.P, sp.m->rate[3 + c], &env) - ed[c]));
        double a[7];
        for (int j = 0; j < 7; j++)
            a[j] = expr_eval(sp.P, ab->acc[j], &env);
        /* the plain model at the same state: its rates e' */
        double v0[8] = {v[0], v[1], v[2], ed[0], ed[1], ed[2], ed[3], v[7]}, z0[8] = {0};
        ExprEnv env0 = {.p = p, .t = 0};
        env0.q[0] = q, env0.q[1] = v0, env0.q[2] = z0;
        double a0[8], amax = 0;
        for (int i = 0; i < 8; i++)
            a0[i] = expr_eval(qm.P, ab0->acc[i], &env0);
        double L[12], Ld[12], wd[3], LdTw[4] = {0};
        Lmat(e, L), Lmat(ed, Ld);
        for (int c = 0; c < 4; c++)
            for (int r = 0; r < 3; r++)
                LdTw[c] += Ld[4 * r + c] * w[r];
        for (int r = 0; r < 3; r++) {
            wd[r] = 0;
            for (int c = 0; c < 4; c++)
                wd[r] += 2 * L[4 * r + c] * a0[3 + c] - L[4 * r + c] * LdTw[c];
        }
        double want[7] = {a0[0], a0[1], a0[2], wd[0], wd[1], wd[2], a0[7]};
        for (int j = 0; j < 7; j++)
            amax = fmax(amax, fabs(want[j]));
        for (int j = 0; j < 7; j++)
            worst_a = fmax(worst_a, fabs(a[j] - want[j]) / amax);
        double T = expr_eval(sp.P, sp.m->T, &env), T0 = expr_eval(qm.P, qm.m->T, &env0);
        worst_T = fmax(worst_T, fabs(T - T0) / T0);
        /* the residuals at the recursion's accelerations (slot j's rate at
         * its leaf: the coordinates' own, the speeds' after them) */
        double acc[11] = {a[0], a[1], a[2], 0, 0, 0, 0, a[6], a[3], a[4], a[5]};
        env.q[2] = acc;
        for (int j = 0; j < 7; j++) {
            worst_ne = fmax(worst_ne, fabs(expr_eval(sp.P, ne->E[j], &env)));
            worst_ga = fmax(worst_ga, fabs(expr_eval(sp.P, ga->E[j], &env)));
        }
    }
    /* dE/dq [7 x 8] and dE/dv [7 x 7] (unrolled and seeded) against
     * central differences of E, at states off the unit sphere too (E is
     * defined for any e; dE/dq_j holds the speeds) */
    eom_derive_jacobian(ne, sp.m, A, sp.P, sp.D);
    double worst_jq = 0, worst_jv = 0, worst_seed = 0;
    for (int trial = 0; trial < 5; trial++) {
        double q[8], v[11] = {0}, acc[11] = {0}, dq[8] = {0}, dv[11] = {0};
        for (int i = 0; i < 8; i++)
            q[i] = check_rand(-1, 1);
        for (int i = 0; i < 11; i++)
            v[i] = i < 3 || i >= 7 ? check_rand(-2, 2) : 0, acc[i] = v[i] ? check_rand(-1, 1) : 0;
        ExprEnv env = {.p = p, .t = 0.3};
        env.q[0] = q, env.q[1] = v, env.q[2] = acc;
        env.seed[0] = dq, env.seed[1] = dv;
        for (int i = 0; i < 7; i++) {
            double scale = 1;
            for (int j = 0; j < 8; j++)
                scale = fmax(scale, fabs(expr_eval(sp.P, ne->dEdq[i * 8 + j], &env)));
            for (int j = 0; j < 8; j++) { /* coordinates */
                double hstep = 1e-6, keep = q[j];
                q[j] = keep + hstep;
                double up = expr_eval(sp.P, ne->E[i], &env);
                q[j] = keep - hstep;
                double down = expr_eval(sp.P, ne->E[i], &env);
                q[j] = keep;
                double fd = (up - down) / (2 * hstep);
                worst_jq = fmax(worst_jq, fabs(expr_eval(sp.P, ne->dEdq[i * 8 + j], &env) - fd) /
                                              scale);
                dq[j] = 1;
                worst_seed = fmax(worst_seed, fabs(expr_eval(sp.P, ne->jvp_q[i], &env) -
                                                   expr_eval(sp.P, ne->dEdq[i * 8 + j], &env)));
                dq[j] = 0;
            }
            for (int j = 0; j < 7; j++) { /* slots, at their leaves */
                int leaf = s->vcoord[j];
                double hstep = 1e-6, keep = v[leaf];
                v[leaf] = keep + hstep;
                double up = expr_eval(sp.P, ne->E[i], &env);
                v[leaf] = keep - hstep;
                double down = expr_eval(sp.P, ne->E[i], &env);
                v[leaf] = keep;
                double fd = (up - down) / (2 * hstep);
                worst_jv = fmax(worst_jv, fabs(expr_eval(sp.P, ne->dEdv[i * 7 + j], &env) - fd) /
                                              scale);
                dv[j] = 1;
                worst_seed = fmax(worst_seed, fabs(expr_eval(sp.P, ne->jvp_v[i], &env) -
                                                   expr_eval(sp.P, ne->dEdv[i * 7 + j], &env)));
                dv[j] = 0;
            }
        }
    }
    /* central differences at h = 1e-6: truncation ~h^2 |E'''|, rounding ~1e-16/h */
    CHECK(worst_jq < 1e-8, "dE/dq [7 x 8] = central differences (worst %.2g)", worst_jq);
    CHECK(worst_jv < 1e-8, "dE/dv [7 x 7] = central differences (worst %.2g)", worst_jv);
    CHECK(worst_seed < 1e-13, "the seeded columns = the unrolled ones (worst %.2g)", worst_seed);

    check_constrained();
    CHECK(worst_rate < 1e-15, "e' = 1/2 e (x) (0, w) (worst %.2g)", worst_rate);
    CHECK(worst_a < 1e-12, "q'' in speeds = q'' in the Euler parameters' rates, turned into w' "
          "(50 states; worst %.2g of max |q''|)", worst_a);
    CHECK(worst_T < 1e-14, "T in speeds = T in rates (worst %.2g)", worst_T);
    CHECK(worst_ne < 1e-12, "the Newton-Euler residual in speeds vanishes there (worst %.2g)",
          worst_ne);
    CHECK(worst_ga < 1e-12, "the Gibbs-Appell residual in speeds vanishes there (worst %.2g)",
          worst_ga);
    return done();
}

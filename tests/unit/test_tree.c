/*
 * The recursive Newton-Euler form (forms/newton_euler.c, tree.c) against
 * Lagrange's equations derived from the energies, at random states of a
 * branched tree with every kind of turn (coordinate axes, a fixed oblique
 * axis, a fixed tilt before a turn), a full inertia tensor, a particle at
 * a point, gravity, a potential, a force, a torque, a damping work and
 * rotors' inertias (kinetic terms of one joint's rate each):
 *   - M (composite-rigid-body) and h equal Lagrange's;
 *   - M is also dE/dq'' of the recursive residual itself;
 *   - the seeded derivatives of E equal its unrolled Jacobian.
 * The articulated-body form (forms/articulated.c) on the same tree, and
 * on one of 15 coordinates: its q'' solve
 * Lagrange's M q'' = -h (solved here by GSL's LU), the product of its
 * pivots is det M (from GSL's LU) and mkk is M's diagonal.
 * And the models it must refuse, each with its reason.
 */
#include "check.h"
#include "forms/eom.h"

#include <gsl/gsl_linalg.h>
#include <string.h>

static ExprPool *P;
static Diff *D;
static Arena *A;

static const char tree_spec[] =
    "name: branched\n"
    "parameters: {g: 9.81, k: 3, c: 0.2}\n"
    "coordinates: [a1, a2, b1, b2, c1, d1]\n"
    "frames:\n"
    "  a_axes: {rotation: [{z: a1}, {x: a2}]}\n"
    "  b_axes: {parent: a_axes, rotation: [{axis: [0.6, 0, 0.8], angle: b1}, {y: b2}]}\n"
    "  c_axes: {parent: a_axes, rotation: [{x: 0.3}, {z: c1}]}\n"
    "  d_axes: {parent: b_axes, rotation: [{y: d1}]}\n"
    "points:\n"
    "  a_joint: {at: [0.1, -0.2, 0.3]}\n"
    "  a_c: {frame: a_axes, from: a_joint, at: [0.2, 0.1, -0.5]}\n"
    "  b_joint: {frame: a_axes, from: a_joint, at: [0, 0.3, -1.0]}\n"
    "  b_c: {frame: b_axes, from: b_joint, at: [0.1, 0, -0.4]}\n"
    "  c_joint: {frame: a_axes, from: a_joint, at: [0.4, 0, -0.2]}\n"
    "  c_c: {frame: c_axes, from: c_joint, at: [0, 0.5, 0]}\n"
    "  d_joint: {frame: b_axes, from: b_joint, at: [0, 0, -0.8]}\n"
    "  tip: {frame: d_axes, from: d_joint, at: [0.3, 0, -0.3]}\n"
    "bodies:\n"
    "  A: {mass: 2, frame: a_axes, center: a_c, inertia: [0.3, 0.4, 0.5]}\n"
    "  B: {mass: 1.5, frame: b_axes, center: b_c,\n"
    "      inertia: [[0.2, 0.01, 0.02], [0.01, 0.3, 0.03], [0.02, 0.03, 0.25]]}\n"
    "  C: {mass: 0.7, frame: c_axes, center: c_c, inertia: [0.1, 0.1, 0.05]}\n"
    "particles:\n"
    "  bob: {mass: 0.4, position: tip}\n"
    "potential: 1/2*k*a2^2\n"
    "effects:\n"
    "  gravity: {gravity: [0, 0, -g]}\n"
    "  push: {force: [0.3, -0.2, 0.1], on: B}\n"
    "  twist: {torque: [0.1, 0.2, -0.3], on: C}\n"
    "  drag: {force: -c*vel(tip), on: bob}\n"
    "  damp: {work: \"-c*b2'*delta(b2)\"}\n"
    "  rotors: [{kinetic: \"1/2*0.05*b2'^2\"}, {kinetic: \"0.02*a1'^2*(1 + a2^2)\"}]\n"
    "scene: {t_end: 1}\n";

/* specs/gen_tree.sh 5 with unequal bodies and a frame that does not
 * turn (the head rides on the neck): 15 coordinates. */
static const char big_tree_spec[] =
    "name: tree5\n"
    "parameters: {m: 1.0, l: 0.3, g: 9.81}\n"
    "coordinates: [pelvis_a, pelvis_b, pelvis_c, spine1_a, spine1_b, spine1_c, spine2_a,\n"
    "              spine2_b, spine2_c, arm_a, arm_b, arm_c, leg_a, leg_b, leg_c]\n"
    "frames:\n"
    "  pelvis_axes: {rotation: [{z: pelvis_a}, {x: pelvis_b}, {y: pelvis_c}]}\n"
    "  spine1_axes: {parent: pelvis_axes, rotation: [{z: spine1_a}, {x: spine1_b}, "
    "{y: spine1_c}]}\n"
    "  spine2_axes: {parent: spine1_axes, rotation: [{z: spine2_a}, {x: spine2_b}, "
    "{y: spine2_c}]}\n"
    "  head_axes: {parent: spine2_axes, rotation: [{x: 0.2}]}\n"
    "  arm_axes: {parent: spine2_axes, rotation: [{z: arm_a}, {x: arm_b}, {y: arm_c}]}\n"
    "  leg_axes: {parent: pelvis_axes, rotation: [{z: leg_a}, {x: leg_b}, {y: leg_c}]}\n"
    "points:\n"
    "  pelvis_joint: {at: [0, 0, 0]}\n"
    "  pelvis_centre: {frame: pelvis_axes, from: pelvis_joint, at: [0.01, 0, -l/2]}\n"
    "  spine1_joint: {frame: pelvis_axes, from: pelvis_joint, at: [0, 0, -l]}\n"
    "  spine1_centre: {frame: spine1_axes, from: spine1_joint, at: [0, 0.02, -l/2]}\n"
    "  spine2_joint: {frame: spine1_axes, from: spine1_joint, at: [0, 0, -l]}\n"
    "  spine2_centre: {frame: spine2_axes, from: spine2_joint, at: [0, 0, -l/2]}\n"
    "  head_centre: {frame: head_axes, from: spine2_joint, at: [0.05, 0, -l]}\n"
    "  arm_joint: {frame: spine2_axes, from: spine2_joint, at: [0.1, 0.2, -l]}\n"
    "  arm_centre: {frame: arm_axes, from: arm_joint, at: [0, 0, -l/2]}\n"
    "  leg_joint: {frame: pelvis_axes, from: pelvis_joint, at: [0, -0.1, -l]}\n"
    "  leg_centre: {frame: leg_axes, from: leg_joint, at: [0, 0, -0.6*l]}\n"
    "bodies:\n"
    "  pelvis: {mass: 3*m, frame: pelvis_axes, center: pelvis_centre, "
    "inertia: [0.05, 0.04, 0.03]}\n"
    "  spine1: {mass: m, frame: spine1_axes, center: spine1_centre, "
    "inertia: [m*l^2/12, m*l^2/12, m*l^2/50]}\n"
    "  spine2: {mass: m, frame: spine2_axes, center: spine2_centre, "
    "inertia: [m*l^2/12, m*l^2/10, m*l^2/50]}\n"
    "  head: {mass: 2*m, frame: head_axes, center: head_centre, inertia: [0.02, 0.02, 0.01]}\n"
    "  arm: {mass: 0.5*m, frame: arm_axes, center: arm_centre, "
    "inertia: [m*l^2/24, m*l^2/24, m*l^2/100]}\n"
    "  leg: {mass: 2*m, frame: leg_axes, center: leg_centre, "
    "inertia: [m*l^2/6, m*l^2/6, m*l^2/25]}\n"
    "effects:\n"
    "  gravity: {gravity: [0, 0, -g]}\n"
    "scene: {t_end: 1}\n";

/* Sliding joints: a cart on a rail (x, a point mass), a pole turning at
 * it (th), a slider telescoping along the pole (y), and an arm turning at
 * the pole's end (ph); a spring on y. */
static const char slide_spec[] =
    "name: cartpole\n"
    "parameters: {M: 1.5, m: 0.4, l: 0.6, g: 9.81, k: 2}\n"
    "coordinates: [x, th, y, ph]\n"
    "frames:\n"
    "  pole_axes: {rotation: [{y: th}]}\n"
    "  arm_axes: {parent: pole_axes, rotation: [{x: ph}]}\n"
    "points:\n"
    "  cart: {at: [x, 0.1, 0]}\n"
    "  slider: {frame: pole_axes, from: cart, at: [0.05, 0, -0.3 - y]}\n"
    "  bob: {frame: pole_axes, from: slider, at: [0, 0, -l]}\n"
    "  tip: {frame: arm_axes, from: bob, at: [0.2, 0, -0.1]}\n"
    "bodies:\n"
    "  pole: {mass: m, frame: pole_axes, center: slider, inertia: [0.015, 0.02, 0.01]}\n"
    "  arm: {mass: 0.3, frame: arm_axes, center: tip, inertia: [0.003, 0.002, 0.004]}\n"
    "particles:\n"
    "  cart_mass: {mass: M, position: cart}\n"
    "potential: 1/2*k*y^2\n"
    "effects:\n"
    "  gravity: {gravity: [0, 0, -g]}\n"
    "  push: {force: [0.3, 0, 0.1], on: arm}\n"
    "  rotor: {kinetic: \"1/2*0.1*y'^2\"}\n"
    "scene: {t_end: 1}\n";

/* A floating body: its centre's offset affine in three coordinates (three
 * slides in a row), oblique directions among them, then three turns,
 * and a wheel that spins about its own axis (its mass symmetric about it:
 * tree.c keeps it in the axes before the turn), on an arm. */
static const char float_spec[] =
    "name: floating\n"
    "parameters: {m: 2, g: 9.81}\n"
    "coordinates: [x, y, z, a, b, c, w, e]\n"
    "frames:\n"
    "  body_axes: {rotation: [{z: a}, {x: b}, {y: c}]}\n"
    "  arm_axes: {parent: body_axes, rotation: [{x: e}]}\n"
    "  wheel_axes: {parent: arm_axes, rotation: [{y: w}]}\n"
    "points:\n"
    "  centre: {at: [0.1 + x + 0.3*z, y - 0.2*x, 0.5 + z]}\n"
    "  shoulder: {frame: body_axes, from: centre, at: [0.2, 0, 0.1]}\n"
    "  hub: {frame: arm_axes, from: shoulder, at: [0, 0.3, 0]}\n"
    "bodies:\n"
    "  body: {mass: m, frame: body_axes, center: centre, inertia: [[0.3, 0.01, 0.02], [0.01, 0.4, 0.03], [0.02, 0.03, 0.5]]}\n"
    "  arm: {mass: 0.5, frame: arm_axes, center: shoulder, inertia: [0.01, 0.02, 0.03]}\n"
    "  wheel: {mass: 0.7, frame: wheel_axes, center: hub, inertia: [0.02, 0.04, 0.02]}\n"
    "effects:\n"
    "  gravity: {gravity: [0, 0, -g]}\n"
    "  push: {force: [0.3, -0.2, 0.1], on: arm}\n"
    "scene: {t_end: 1}\n";

/* A floating body on a ball joint (a frame turned by a quaternion) and
 * three slides, with an arm on a hinge. */
static const char ball_spec[] =
    "name: ball\n"
    "parameters: {m: 3.0}\n"
    "coordinates: [x, y, z, e0, e1, e2, e3, th]\n"
    "frames:\n"
    "  body_axes: {rotation: [{quaternion: [e0, e1, e2, e3]}]}\n"
    "  arm_axes: {parent: body_axes, rotation: [{x: th}]}\n"
    "points:\n"
    "  centre: {at: [x, y, z]}\n"
    "  shoulder: {frame: body_axes, from: centre, at: [0.1, 0.2, 0.05]}\n"
    "  arm_cm: {frame: arm_axes, from: shoulder, at: [0, 0, -0.2]}\n"
    "bodies:\n"
    "  body: {mass: m, frame: body_axes, center: centre, inertia: [0.3, 0.4, 0.5]}\n"
    "  arm: {mass: 0.5, frame: arm_axes, center: arm_cm, inertia: [0.01, 0.012, 0.003]}\n"
    "scene: {t_end: 1}\n";

static Spec *
load(const char *text)
{
    return spec_load_buffer("tree.yaml", text, strlen(text), NULL, A, P);
}

static void
check_agree(const Spec *s, const char *what)
{
    Mech *m = mech_build(s, A, P, D);
    CHECK(m->tree != NULL, "%s is a tree (%s)", what, m->tree_why ? m->tree_why : "");
    if (!m->tree)
        return;
    int n = m->n;
    const char *why = NULL;
    Eom *lag = eom_derive(s, m, form_find("lagrange"), A, P, D, &why);
    Eom *ne = eom_derive(s, m, form_find("newton-euler"), A, P, D, &why);
    CHECK(lag && ne, "%s: both forms apply", what);
    if (!lag || !ne)
        return;
    eom_derive_jacobian(ne, m, A, P, D);
    double *p = arena_new_array(A, double, s->np + 1);
    for (int k = 0; k < s->np; k++)
        p[k] = s->param[k].value;
    int okM = 1, okh = 1, okdM = 1, okE = 1, jvp = 1;
    for (int trial = 0; trial < 100; trial++) {
        double st[4][8], seed[2][8];
        ExprEnv env = {0};
        for (int k = 0; k < 4; k++)
            for (int i = 0; i < n; i++)
                st[k][i] = check_rand(-2, 2);
        for (int k = 0; k < 4; k++)
            env.q[k] = st[k];
        env.t = check_rand(0, 1);
        env.p = p;
        for (int i = 0; i < n * n; i++) {
            double want = expr_eval(P, lag->M[i], &env);
            okM &= check_close(expr_eval(P, ne->M[i], &env), want, 1e-13);
            okdM &= check_close(expr_eval(P, diff_partial(D, ne->E[i / n], m->q[2][i % n]),
                                          &env), want, 1e-13);
        }
        for (int i = 0; i < n; i++) {
            okh &= check_close(expr_eval(P, ne->h[i], &env), expr_eval(P, lag->h[i], &env),
                               1e-13);
            okE &= check_close(expr_eval(P, ne->E[i], &env), expr_eval(P, lag->E[i], &env),
                               1e-12);
        }
        for (int j = 0; j < n; j++)
            seed[0][j] = check_rand(-1, 1), seed[1][j] = check_rand(-1, 1);
        env.seed[0] = seed[0];
        env.seed[1] = seed[1];
        for (int i = 0; i < n; i++) {
            double wq = 0, wv = 0;
            for (int j = 0; j < n; j++) {
                wq += expr_eval(P, ne->dEdq[i * n + j], &env) * seed[0][j];
                wv += expr_eval(P, ne->dEdv[i * n + j], &env) * seed[1][j];
            }
            jvp &= check_close(expr_eval(P, ne->jvp_q[i], &env), wq, 1e-12);
            jvp &= check_close(expr_eval(P, ne->jvp_v[i], &env), wv, 1e-12);
        }
    }
    CHECK(okM, "%s: composite-rigid-body M = Lagrange's M (100 states)", what);
    CHECK(okdM, "%s: M = dE/dq'' of the recursive residual", what);
    CHECK(okh, "%s: recursive h = Lagrange's h", what);
    CHECK(okE, "%s: recursive E = Lagrange's E at random q''", what);
    CHECK(jvp, "%s: seeded derivatives of the recursive E = its Jacobian times the seeds", what);
}

/* Lagrange's M and h at a state, solved by GSL's LU: a = -M^-1 h, and
 * det M.  Returns det M. */
static double
lagrange_solve(const Eom *lag, ExprEnv *env, double *a)
{
    int n = lag->n;
    gsl_matrix *M = gsl_matrix_alloc((size_t)n, (size_t)n);
    gsl_vector *h = gsl_vector_alloc((size_t)n), *x = gsl_vector_alloc((size_t)n);
    gsl_permutation *perm = gsl_permutation_alloc((size_t)n);
    for (int i = 0; i < n; i++) {
        gsl_vector_set(h, (size_t)i, -expr_eval(P, lag->h[i], env));
        for (int j = 0; j < n; j++)
            gsl_matrix_set(M, (size_t)i, (size_t)j, expr_eval(P, lag->M[i * n + j], env));
    }
    int sign;
    gsl_linalg_LU_decomp(M, perm, &sign);
    gsl_linalg_LU_solve(M, perm, h, x);
    for (int i = 0; i < n; i++)
        a[i] = gsl_vector_get(x, (size_t)i);
    double det = gsl_linalg_LU_det(M, sign);
    gsl_matrix_free(M);
    gsl_vector_free(h);
    gsl_vector_free(x);
    gsl_permutation_free(perm);
    return det;
}

/* The articulated-body form's q'', pivots and M_kk against Lagrange's
 * equations at 100 random states (velocities included). */
static void
check_articulated(const Spec *s, const char *what)
{
    Mech *m = mech_build(s, A, P, D);
    CHECK(m->tree != NULL, "%s is a tree", what);
    if (!m->tree)
        return;
    int n = m->n;
    const char *why = NULL;
    Eom *lag = eom_derive(s, m, form_find("lagrange"), A, P, D, &why);
    Eom *ab = eom_derive(s, m, form_find("articulated-body"), A, P, D, &why);
    CHECK(lag && ab && ab->acc, "%s: both forms apply, the articulated one solves", what);
    if (!lag || !ab || !ab->acc)
        return;
    double *p = arena_new_array(A, double, s->np + 1);
    for (int k = 0; k < s->np; k++)
        p[k] = s->param[k].value;
    double *st = arena_new_array(A, double, 3 * n), *a = arena_new_array(A, double, n);
    double worst_a = 0, worst_det = 0, worst_m = 0;
    for (int trial = 0; trial < 100; trial++) {
        ExprEnv env = {0};
        /* angles within 1.2 of 0, clear of the turns' gimbal lock at pi/2
         * where M is singular */
        for (int i = 0; i < 3 * n; i++)
            st[i] = i < n ? check_rand(-1.2, 1.2) : check_rand(-2, 2);
        env.q[0] = st, env.q[1] = st + n, env.q[2] = st + 2 * n;
        env.t = check_rand(0, 1);
        env.p = p;
        double det = lagrange_solve(lag, &env, a), amax = 0, prod = 1;
        for (int i = 0; i < n; i++)
            amax = fmax(amax, fabs(a[i]));
        for (int i = 0; i < n; i++) {
            worst_a = fmax(worst_a, fabs(expr_eval(P, ab->acc[i], &env) - a[i]) / amax);
            prod *= expr_eval(P, ab->piv[i], &env);
            double mkk = expr_eval(P, lag->M[i * n + i], &env);
            worst_m = fmax(worst_m, fabs(expr_eval(P, ab->mkk[i], &env) - mkk) / mkk);
        }
        worst_det = fmax(worst_det, fabs(prod - det) / fabs(det));
    }
    /* clear of gimbal lock, LU's q'' and the recursion's keep about 12
     * digits of the largest entry on these trees */
    CHECK(worst_a < 1e-11, "%s: articulated q'' = Lagrange's -M^-1 h (100 states; worst "
          "%.2g of max |q''|)", what, worst_a);
    CHECK(worst_det < 1e-11, "%s: product of the articulated pivots = det M (worst %.2g)",
          what, worst_det);
    CHECK(worst_m < 1e-13, "%s: mkk = M's diagonal (worst %.2g)", what, worst_m);
}

/* Replace the first `from` in text by `to`. */
static char *
variant(const char *text, const char *from, const char *to)
{
    const char *at = strstr(text, from);
    CHECK(at != NULL, "variant '%s' found", from);
    if (!at)
        return arena_strdup(A, text);
    return arena_printf(A, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
}

/* A variant of the tree that must be refused for a reason containing
 * `want`. */
static void
check_refused(const char *text, const char *want)
{
    Spec *s = load(text);
    CHECK(s != NULL, "variant loads");
    if (!s)
        return;
    Mech *m = mech_build(s, A, P, D);
    const char *why = NULL;
    Eom *e = eom_derive(s, m, form_find("newton-euler"), A, P, D, &why);
    CHECK(!m->tree && !e && why && strstr(why, want), "refused: %s (%s)", want,
          why ? why : "applies");
}

int
main(void)
{
    P = expr_pool_new();
    D = diff_new(P);
    A = arena_new();
    Spec *s = load(tree_spec);
    CHECK(s != NULL, "the branched tree loads");
    if (s) {
        check_agree(s, "the branched tree");
        check_articulated(s, "the branched tree");
    }
    Spec *sl = load(slide_spec);
    CHECK(sl != NULL, "the tree with sliding joints loads");
    if (sl) {
        check_agree(sl, "the tree with sliding joints");
        check_articulated(sl, "the tree with sliding joints");
    }
    Spec *fl = load(float_spec);
    CHECK(fl != NULL, "the floating body loads");
    if (fl) {
        check_agree(fl, "the floating body");
        check_articulated(fl, "the floating body");
    }
    if (fl) { /* the wheel's angle w: a symmetry, so structurally absent */
        Mech *m = mech_build(fl, A, P, D);
        const char *why = NULL;
        Eom *ne = eom_derive(fl, m, form_find("newton-euler"), A, P, D, &why);
        Eom *ab = eom_derive(fl, m, form_find("articulated-body"), A, P, D, &why);
        int absent = ne && ab, w = 6;
        for (int i = 0; absent && i < m->n; i++)
            absent = diff_partial(D, ne->E[i], m->q[0][w]) == EXPR_ZERO &&
                     diff_partial(D, ab->acc[i], m->q[0][w]) == EXPR_ZERO;
        CHECK(absent, "the floating body: the wheel's angle appears in no E_i and no q_i''");
    }
    Spec *bs = load(ball_spec);
    CHECK(bs != NULL, "the floating body on a ball joint loads");
    if (bs) { /* its joints: three slides, the ball's four parameters, the hinge */
        Mech *m = mech_build(bs, A, P, D);
        int balls = 0, order = 1;
        for (int k = 0; m->tree && k < m->tree->nturns; k++) {
            const TreeTurn *tk = &m->tree->turn[k];
            if (tk->ndof == 4) {
                balls++;
                for (int d = 0; d < 4; d++)
                    order &= tk->qc[d] == 3 + d;
                order &= tk->up >= 0 && m->tree->turn[tk->up].slide;
            }
        }
        const char *why = NULL;
        CHECK(m->tree && m->tree->nturns == 5 && balls == 1 && order,
              "a quaternion's turn is one joint of its four parameters, e0..e3 in order, "
              "below the slides (%s)", m->tree_why ? m->tree_why : "");
        CHECK(!form_tables(m, A, P, D, &why) && why && strstr(why, "ball joints"),
              "the tables refuse a ball joint, saying so");
    }
    Spec *big = load(big_tree_spec);
    CHECK(big != NULL, "the 15-coordinate tree loads");
    if (big)
        check_articulated(big, "the 15-coordinate tree");
    const char *t = tree_spec;
    /* a point that slides in its frame other than along a line */
    check_refused(variant(t, "at: [0, 0.5, 0]}", "at: [0, 0.5*cos(c1), 0]}"),
                  "moves in a frame other than along constant directions by its coordinates");
    /* a slide by a coordinate that also turns a frame */
    check_refused(variant(t, "at: [0, 0.5, 0]}", "at: [0, 0.5 + 0.1*c1, 0]}"),
                  "coordinate 'c1' moves two joints");
    /* a chain through a frame the mass does not turn with */
    check_refused(variant(t, "c_joint: {frame: a_axes, from: a_joint",
                          "c_joint: {frame: b_axes, from: b_joint"),
                  "goes through a frame it does not turn with");
    check_refused(variant(t, "rotation: [{y: d1}]}", "rotation: [{y: 2*d1}]}"),
                  "not a coordinate");
    check_refused(variant(t, "rotation: [{x: 0.3}, {z: c1}]}",
                          "rotation: [{x: 0.3}, {z: c1}, {x: a2}]}"),
                  "angle of two turns");
    /* a second mass that c_axes turns about b_joint, not c_joint */
    check_refused(variant(variant(t, "  tip: {", "  off: {frame: c_axes, from: b_joint, "
                                  "at: [0.3, 0, -0.3]}\n  tip: {"),
                          "  bob: {", "  bob2: {mass: 0.1, position: off}\n  bob: {"),
                  "about another point");
    check_refused(variant(t, "{kinetic: \"1/2*0.05*b2'^2\"}", "{kinetic: \"1/2*0.05*(b2' + c1')^2\"}"),
                  "moves with the rates of 'b2' and 'c1', two joints");
    check_refused(variant(t, "center: a_c,", "center: [0.1, 0.2, 0.3],"),
                  "not placed by a frame with its centre at a point");
    check_refused(variant(t, "  bob: {mass: 0.4, position: tip}",
                          "  bob: {mass: 0.4, position: [0, 0, 1]}\n"
                          "  bob3: {mass: 0.4, position: tip}"),
                  "particle 'bob' is not at a point");
    arena_free(A);
    diff_free(D);
    expr_pool_free(P);
    return check_done();
}

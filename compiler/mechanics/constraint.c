/*
 * constraint: classification, acceleration level, virtual displacements,
 * and the choice of dependent coordinates for elimination.
 *
 * The choice, when the spec does not name one: constraints in spec order,
 * each takes the last coordinate (in `coordinates:` order) whose column of
 * df/dq'' is not negligible at the initial state and that no earlier
 * constraint took.  Where none is left, an augmenting path (Kuhn's
 * matching) lets earlier constraints give theirs up for others of their
 * own.  Negligible is relative to the row's own largest entry
 * there: an entry that is zero only through an identity the DAG does not
 * apply (sin^2 + cos^2 = 1, as kinematics written with frames leaves
 * them) is not identically zero as an expression, yet would make the
 * block singular.  Whether that block of B is invertible depends on the
 * state; the runtime checks it at every evaluation and names the
 * constraint when it is not.  A row that is a combination of the rows
 * before it at the initial state (a planar loop's third row) can have no
 * coordinate of its own: it shares one, and the runtime leaves it out of
 * its solves (runtime/model/depend.c), or refuses to eliminate it.
 */
#include "constraint.h"

#include <math.h>
#include <string.h>

/* Velocity slot j's name: its coordinate's, or its speed's. */
static const char *
slot_name(const Spec *s, int j)
{
    int c = s->vcoord[j];
    return c < s->nq ? s->coord[c].name : s->speed[c - s->nq].name;
}

const char *
constraint_order_name(int order)
{
    static const char *const names[] = {"holonomic", "first-order", "second-order"};
    return order >= 0 && order <= 2 ? names[order] : "?";
}

/* e linear (affine) in the leaves q^(order): all second partials vanish. */
static int
is_linear_in(Diff *D, const Mech *m, ExprId e, int order)
{
    int n = order == 0 ? m->nq : m->n; /* coordinates, or velocity slots */
    for (int j = 0; j < n; j++) {
        ExprId d = diff_partial(D, e, m->q[order][j]);
        for (int k = 0; k < n; k++)
            if (diff_partial(D, d, m->q[order][k]) != EXPR_ZERO)
                return 0;
    }
    return 1;
}

static ExprId
dt_checked(Diff *D, const SpecConstraint *sc, ExprId e)
{
    ExprId d = diff_time(D, e);
    if (d == EXPR_NONE)
        diag_error(sc->loc, "constraint '%s' is %s and depends on an input; inputs "
                   "are signals whose derivatives are unknown, so it cannot be "
                   "brought to acceleration level", sc->name,
                   constraint_order_name(sc->order));
    return d;
}

/* g -> (g, g', g''), phi -> (phi, phi'), f -> f. */
static void
to_acceleration(Constraints *c, Diff *D, int a)
{
    const SpecConstraint *sc = &c->spec[a];
    ExprId e = sc->expr;
    c->pos[a] = c->vel[a] = EXPR_NONE;
    if (sc->order == 0) {
        c->pos[a] = e;
        e = dt_checked(D, sc, e);
    }
    if (sc->order <= 1) {
        c->vel[a] = e;
        e = dt_checked(D, sc, e);
    }
    c->f[a] = e;
}

/* An entry of B's row at the initial state smaller than this, relative
 * to the row's largest, is taken for zero: rounding of terms that cancel
 * only through an identity leaves some 1e-16 of them. */
#define DEPENDENT_NEGLIGIBLE 1e-12

/* Can constraint a determine coordinate j: it involves the acceleration
 * of q_j and, where anything in its row stands out at the initial state
 * (big > 0), that entry is not negligible there? */
static int
candidate(const Constraints *c, int a, int j, const double *Bnum, double big)
{
    return c->B[a * c->n + j] != EXPR_ZERO &&
           (big == 0 || fabs(Bnum[a * c->n + j]) > DEPENDENT_NEGLIGIBLE * big);
}

static double
row_big(const Constraints *c, int a, const double *Bnum)
{
    double big = 0;
    for (int k = 0; k < c->n; k++)
        big = fmax(big, fabs(Bnum[a * c->n + k]));
    return big;
}

/* Kuhn's augmenting path: constraint a takes a candidate coordinate
 * (seen: tried on this path), its owner moving to another of its own, and
 * so on; a dependent the spec names stays.  1 if it found one. */
static int
augment(Constraints *c, int a, int *owner, unsigned char *seen, const Spec *s,
        const double *Bnum)
{
    double big = row_big(c, a, Bnum);
    for (int j = c->n - 1; j >= 0; j--) {
        if (seen[j] || !candidate(c, a, j, Bnum, big))
            continue;
        seen[j] = 1;
        int o = owner[j];
        if (o < 0 || (s->constraint[o].dependent < 0 && augment(c, o, owner, seen, s, Bnum))) {
            owner[j] = a;
            c->dependent[a] = j;
            return 1;
        }
    }
    return 0;
}

/* A row whose part outside the span of the rows before it (each at unit
 * length) is at most this of its length is a combination of them: rounding
 * leaves 1e-16 of a row that is one exactly. */
#define DEPENDENT_ROW 1e-9

/* dep[a]: row a of B at the initial state is a combination of the rows
 * before it, by Gram-Schmidt (twice, for orthogonality to rounding) onto
 * an orthonormal basis of theirs. */
static unsigned char *
dependent_rows(const Constraints *c, const double *Bnum, Arena *A)
{
    int n = c->n, nc = c->nc, nb = 0;
    double *Q = arena_new_array(A, double, nc * n), *r = arena_new_array(A, double, n);
    unsigned char *dep = arena_new_array(A, unsigned char, nc);
    for (int a = 0; a < nc; a++) {
        double len = 0, rest = 0;
        for (int j = 0; j < n; j++)
            len = hypot(len, r[j] = Bnum[a * n + j]);
        for (int pass = 0; pass < 2; pass++)
            for (int b = 0; b < nb; b++) {
                double d = 0;
                for (int j = 0; j < n; j++)
                    d += Q[b * n + j] * r[j];
                for (int j = 0; j < n; j++)
                    r[j] -= d * Q[b * n + j];
            }
        for (int j = 0; j < n; j++)
            rest = hypot(rest, r[j]);
        dep[a] = !(rest > DEPENDENT_ROW * len);
        for (int j = 0; !dep[a] && j < n; j++)
            Q[nb * n + j] = r[j] / rest;
        nb += !dep[a];
    }
    return dep;
}

static void
choose_dependent(Constraints *c, int a, int *owner, const Spec *s, const double *Bnum,
                 const unsigned char *dep, Arena *A)
{
    const SpecConstraint *sc = &c->spec[a];
    int n = c->n, j = sc->dependent >= 0 ? s->vslot[sc->dependent] : -1;
    if (sc->dependent >= 0 && j < 0)
        diag_error(sc->dep_loc, "'%s' is an Euler parameter whose rate its quaternion's speeds "
                   "give: it cannot be a dependent coordinate", s->coord[sc->dependent].name);
    if (j >= 0) {
        if (c->B[a * n + j] == EXPR_ZERO)
            diag_error(sc->dep_loc, "constraint '%s' does not involve '%s' at acceleration "
                       "level, so it cannot determine it", sc->name,
                       s->coord[sc->dependent].name);
        owner[j] = a;
        c->dependent[a] = j;
        return;
    }
    double big = row_big(c, a, Bnum);
    for (j = n - 1; j >= 0; j--)
        if (owner[j] < 0 && candidate(c, a, j, Bnum, big))
            break;
    if (j < 0) /* nothing stands out at the initial state: as written */
        for (j = n - 1; j >= 0; j--)
            if (owner[j] < 0 && c->B[a * n + j] != EXPR_ZERO)
                break;
    if (j >= 0) {
        owner[j] = a;
        c->dependent[a] = j;
        return;
    }
    /* every coordinate it involves is taken: earlier constraints may take
     * others of their own (a body held by three rows that all involve the
     * same few joints) */
    unsigned char *seen = arena_new_array(A, unsigned char, n);
    if (augment(c, a, owner, seen, s, Bnum))
        return;
    if (!dep[a])
        diag_error(sc->loc, "no coordinate is left for constraint '%s' to determine: "
                   "every coordinate it involves is taken by an earlier constraint "
                   "(name one with `dependent:`)", sc->name);
    for (j = n - 1; j >= 0; j--) /* dependent on them: it shares one */
        if (c->B[a * n + j] != EXPR_ZERO) {
            c->dependent[a] = j;
            return;
        }
}

/* B at the spec's initial state: t = 0, q and q' as `initial:` gives
 * them, q'' = 0, the parameters' values and the inputs at t = 0. */
static double *
initial_B(const Constraints *c, const Spec *s, Arena *A, ExprPool *P)
{
    int n = c->n, nc = c->nc, nl = s->nq + s->nspeed; /* leaves: the speeds' after q's */
    double *p = arena_new_array(A, double, s->np + 1);
    double *q = arena_new_array(A, double, nl), *v = arena_new_array(A, double, nl);
    double *acc = arena_new_array(A, double, nl), *u = arena_new_array(A, double, s->nu + 1);
    double *Bnum = arena_new_array(A, double, nc * n);
    for (int i = 0; i < s->np; i++)
        p[i] = s->param[i].value;
    ExprEnv env = {.t = 0, .p = p, .u = u};
    for (int k = 0; k < s->nu; k++)
        u[k] = expr_eval(P, s->input[k].expr, &env);
    for (int i = 0; i < s->nq; i++) {
        q[i] = expr_eval(P, s->coord[i].q0, &env);
        v[i] = expr_eval(P, s->coord[i].v0, &env);
    }
    for (int k = 0; k < s->nspeed; k++)
        v[s->nq + k] = expr_eval(P, s->speed[k].v0, &env);
    env.q[0] = q, env.q[1] = v, env.q[2] = acc;
    expr_eval_many(P, nc * n, c->B, &env, Bnum);
    return Bnum;
}

Constraints *
constraints_build(const Spec *s, const Mech *m, Arena *A, ExprPool *P, Diff *D)
{
    if (s->nconstraint == 0)
        return NULL;
    Constraints *c = arena_new_array(A, Constraints, 1);
    int nc = c->nc = s->nconstraint, n = c->n = s->nv; /* B's columns: the velocity slots */
    c->spec = s->constraint;
    c->f = arena_new_array(A, ExprId, nc);
    c->b = arena_new_array(A, ExprId, nc);
    c->pos = arena_new_array(A, ExprId, nc);
    c->vel = arena_new_array(A, ExprId, nc);
    c->B = arena_new_array(A, ExprId, nc * n);
    c->dependent = arena_new_array(A, int, nc);
    c->linear = arena_new_array(A, unsigned char, nc);
    c->affine = 1;
    int *owner = arena_new_array(A, int, n); /* the constraint determining q_j, or -1 */
    ExprId *zero = arena_new_array(A, ExprId, n); /* q'' = 0, for b */
    for (int j = 0; j < n; j++)
        zero[j] = EXPR_ZERO;
    for (int a = 0; a < nc; a++) {
        to_acceleration(c, D, a);
        int any = 0;
        for (int j = 0; j < n; j++)
            any |= (c->B[a * n + j] = diff_partial(D, c->f[a], m->q[2][j])) != EXPR_ZERO;
        if (!any)
            diag_error(s->constraint[a].loc, "constraint '%s' does not restrict the "
                       "accelerations (its acceleration-level form is free of q'')",
                       s->constraint[a].name);
        c->b[a] = expr_subst(P, c->f[a], n, m->q[2], zero);
        int order = s->constraint[a].order;
        c->linear[a] = order == 0 || is_linear_in(D, m, s->constraint[a].expr, order);
        c->affine &= is_linear_in(D, m, c->f[a], 2);
    }
    double *Bnum = initial_B(c, s, A, P);
    unsigned char *dep = dependent_rows(c, Bnum, A);
    for (int j = 0; j < n; j++)
        owner[j] = -1;
    for (int a = 0; a < nc; a++) /* named ones first: they are not negotiable */
        if (s->constraint[a].dependent >= 0)
            choose_dependent(c, a, owner, s, Bnum, dep, A);
    for (int a = 0; a < nc; a++)
        if (s->constraint[a].dependent < 0)
            choose_dependent(c, a, owner, s, Bnum, dep, A);
    return c;
}

int
constraints_by_loads(const Constraints *c, int eliminate)
{
    return c && c->affine && !eliminate;
}

void
constraints_explain(FILE *f, const Constraints *c, const Spec *s, int eliminate)
{
    fprintf(f, "constraints (%d), by %s\n", c->nc, eliminate
            ? "elimination: C^T E = 0 and f = 0, C = [I; -B_h^-1 B_v] spanning the "
              "null space of B"
            : "multipliers: E + B^T lambda = 0 and f = 0 (the KKT system "
              "[M B^T; B 0] [q''; lambda] = [-h; -b] when f is affine in q'')");
    static const char *const how[] = {
        "g(t, q) = 0, differentiated twice; B = dg/dq",
        "phi(t, q, q') = 0, differentiated once; B = dphi/dq' (Chetaev, Appell)",
        "f(t, q, q', q'') = 0 as written; B = df/dq''",
    };
    int w = 14; /* the name column, as wide as the longest name */
    for (int k = 0; k < c->nc; k++)
        if ((int)strlen(c->spec[k].name) > w)
            w = (int)strlen(c->spec[k].name);
    for (int k = 0; k < c->nc; k++) {
        const SpecConstraint *sc = &c->spec[k];
        const char *lin = sc->order == 1 ? (c->linear[k] ? ", linear in q'" : ", nonlinear in q'")
                          : sc->order == 2 ? (c->linear[k] ? ", affine in q''"
                                                           : ", nonlinear in q'' (Newton)")
                                           : "";
        int shared = -1;
        for (int j = 0; j < k && shared < 0; j++)
            if (c->dependent[j] == c->dependent[k])
                shared = j;
        if (shared >= 0) {
            fprintf(f, "  %-*s %s%s: %s; shares %s with %s (a combination of the rows "
                    "before it at the initial state: the runtime leaves a dependent row out "
                    "of its solves, and cannot eliminate it)\n", w, sc->name,
                    constraint_order_name(sc->order), lin, how[sc->order],
                    slot_name(s, c->dependent[k]), c->spec[shared].name);
            continue;
        }
        fprintf(f, "  %-*s %s%s: %s; determines %s (%s)\n", w, sc->name,
                constraint_order_name(sc->order), lin, how[sc->order],
                slot_name(s, c->dependent[k]),
                sc->dependent >= 0 ? "named in the spec" : "chosen: the last coordinate "
                "it involves at the initial state that no earlier constraint took");
    }
}

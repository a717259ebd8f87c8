/*
 * invariant: is h = q'.dL/dq' - L conserved, and what is it (see
 * invariant.h for the conditions and why they suffice).
 */
#include "invariant.h"

#include <math.h>
#include <stdlib.h>

/* Degree of homogeneity in q' of node e, memoized in deg[] (NAN: not
 * homogeneous; known[] marks computed entries).  Operands have smaller
 * ids, so one pass in id order would do; recursion keeps to what e uses. */
static double
degree(ExprPool *P, ExprId e, double *deg, unsigned char *known)
{
    if (known[e])
        return deg[e];
    const ExprNode *nd = expr_node(P, e);
    double a = 0, b = 0, d;
    if (expr_op_arity[nd->op] >= 1)
        a = degree(P, nd->a, deg, known);
    if (expr_op_arity[nd->op] >= 2)
        b = degree(P, nd->b, deg, known);
    switch (nd->op) {
    case EXPR_VAR:
        d = nd->b == 0 ? 0 : nd->b == 1 ? 1 : NAN; /* accelerations: not a velocity form */
        break;
    case EXPR_ADD:
    case EXPR_SUB:
        d = a == b ? a : NAN;
        break;
    case EXPR_MUL:
        d = a + b;
        break;
    case EXPR_DIV:
        d = a - b;
        break;
    case EXPR_NEG:
    case EXPR_ABS: /* |s^k x| = s^k |x| for s > 0 */
        d = a;
        break;
    case EXPR_SIGN:
        d = isnan(a) ? NAN : 0;
        break;
    case EXPR_POWI:
        d = a * (double)(int32_t)nd->b;
        break;
    case EXPR_SQRT:
        d = a / 2;
        break;
    case EXPR_POW: {
        double c;
        d = b != 0 ? NAN : a == 0 ? 0 : expr_is_const(P, nd->b, &c) ? a * c : NAN;
        break;
    }
    case EXPR_ATAN2: /* atan2(s^k y, s^k x) = atan2(y, x) */
        d = a == b ? 0 : NAN;
        break;
    default:
        if (expr_op_arity[nd->op] == 0)
            d = 0; /* constants, parameters, inputs, t */
        else
            d = a == 0 && b == 0 ? 0 : NAN; /* sin, exp, ... of a velocity form */
    }
    known[e] = 1;
    return deg[e] = d;
}

double
invariant_velocity_degree(ExprPool *P, ExprId e)
{
    size_t size = expr_pool_size(P);
    double *deg = malloc(size * sizeof *deg);
    unsigned char *known = calloc(size, 1);
    double d = degree(P, e, deg, known);
    free(deg);
    free(known);
    return d;
}

static int
depends_on_time(const ExprPool *P, ExprId e)
{
    return (expr_deps(P, e) & (DEP_T | DEP_U)) != 0;
}

/* Why h is not conserved, or NULL if it is. */
static const char *
obstacle(const Spec *s, const Mech *m, const Constraints *c, Arena *A, ExprPool *P)
{
    if (depends_on_time(P, m->T))
        return "T depends on t";
    if (depends_on_time(P, m->V))
        return "V depends on t or on an input";
    for (int i = 0; i < m->n; i++)
        if (m->Q[i] != EXPR_ZERO)
            for (int k = 0; k < s->neffect; k++) {
                const SpecEffect *e = &s->effect[k];
                for (int j = 0; e->enabled && j < e->nforce; j++)
                    if (e->force[j].kind != FORCE_GRAVITY &&
                        e->force[j].kind != FORCE_POTENTIAL)
                        return arena_printf(A, "the effect '%s' is a force, not a "
                                            "potential", e->name);
            }
    for (int k = 0; c && k < c->nc; k++) {
        const SpecConstraint *sc = &c->spec[k];
        if (depends_on_time(P, sc->expr))
            return arena_printf(A, "the constraint '%s' depends on t", sc->name);
        if (sc->order == 1 && isnan(invariant_velocity_degree(P, sc->expr)))
            return arena_printf(A, "the constraint '%s' is not homogeneous in the "
                                "velocities, so its force can do work", sc->name);
        if (sc->order == 2)
            return arena_printf(A, "the force of the second-order constraint '%s' can "
                                "do work", sc->name);
    }
    return NULL;
}

Invariant *
invariant_derive(const Spec *s, const Mech *m, const Constraints *c, Arena *A,
                 ExprPool *P, Diff *D)
{
    Invariant *inv = arena_alloc(A, sizeof *inv);
    const char *why = obstacle(s, m, c, A, P);
    if (why) {
        inv->h = EXPR_NONE;
        inv->note = arena_printf(A, "nothing is conserved: %s", why);
        return inv;
    }
    const char *reason = c ? "T, V and the constraints do not depend on t, every effect "
                             "is a potential and the constraint forces do no work"
                           : "T and V do not depend on t and every effect is a potential";
    if (invariant_velocity_degree(P, m->T) == 2) {
        inv->h = expr_add(P, m->T, m->V);
        inv->name = "E";
        inv->note = arena_printf(A, "E = T + V is conserved: %s", reason);
        return inv;
    }
    ExprId *dT = arena_new_array(A, ExprId, m->n);
    diff_gradient(D, m->T, m->n, m->q[1], dT);
    ExprId p = EXPR_ZERO;
    for (int i = 0; i < m->n; i++)
        p = expr_add(P, p, expr_mul(P, dT[i], m->q[1][i]));
    inv->h = expr_add(P, expr_sub(P, p, m->T), m->V);
    inv->name = "h";
    inv->note = arena_printf(A, "h = q'.dT/dq' - T + V = T2 - T0 + V is conserved (T is "
                             "not a quadratic form in q', so E = T + V is not): %s",
                             reason);
    return inv;
}

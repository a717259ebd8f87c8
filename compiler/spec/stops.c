/*
 * stops: compliant stops at the ends of a coordinate's range (stops.h).
 *
 * On the penetration d past an end (lo - q below, q - hi above) a stop
 * pushes back with
 *     F = where(d, max(k d + c d', 0), 0):
 * nothing outside the range, the spring-damper inside, and never a pull
 * (where k d + c d' < 0, on the way out, it is 0).  Each kink is a
 * located switch: EFFECT.q.lo (the end reached or left) and
 * EFFECT.q.lo.push (the push ending or starting again), .hi alike.
 */
#include "stops.h"

#include "checks.h"
#include "names.h"

#include <stdio.h>
#include <string.h>

/* One end of `range:`: an expression of the parameters, or none (null,
 * or .inf of the end's sign: no stop there). */
static ExprId
range_end(Loader *L, yaml_node_t *n, int upper)
{
    if (spec_is_null(n))
        return EXPR_NONE;
    if (n->type == YAML_SCALAR_NODE) {
        const char *v = (const char *)n->data.scalar.value;
        int pos = !strcmp(v, ".inf") || !strcmp(v, "+.inf") || !strcmp(v, ".Inf") ||
                  !strcmp(v, "+.Inf") || !strcmp(v, ".INF") || !strcmp(v, "+.INF");
        int neg = !strcmp(v, "-.inf") || !strcmp(v, "-.Inf") || !strcmp(v, "-.INF");
        if ((pos && upper) || (neg && !upper))
            return EXPR_NONE;
        if (pos || neg)
            diag_error(spec_loc(L, n), "a limit's %s end cannot be %s (.inf above, -.inf "
                       "below, or null: no stop there)", upper ? "upper" : "lower", v);
    }
    return spec_expr(L, n, ALLOW_PARAM, upper ? "a limit's upper end" : "a limit's lower end");
}

/* The force of one stop on penetration d (rate: d'), its switches named
 * NAME and NAME.push. */
static ExprId
stop_force(Loader *L, ExprId d, ExprId rate, ExprId k, ExprId c, const char *name)
{
    ExprPool *P = L->P;
    int first = expr_nswitch(P);
    ExprId spring = expr_mul(P, k, d); /* built first: ids do not depend on C's order */
    ExprId push = expr_add(P, spring, expr_mul(P, c, rate));
    /* without damping k d > 0 wherever d > 0: no second switch (its
     * function k d would flip with d's, at the same instant) */
    ExprId f = c == EXPR_ZERO ? push : expr_max(P, push, EXPR_ZERO);
    f = expr_where(P, d, f, EXPR_ZERO);
    char nm[300];
    for (int j = first; j < expr_nswitch(P); j++) {
        snprintf(nm, sizeof nm, "%s%s", name, expr_switch(P, j) == d ? "" : ".push");
        expr_name_switch(P, j, nm);
    }
    return f;
}

void
spec_load_stop(Loader *L, yaml_node_t *map, yaml_node_t *v, const char *owner, SpecForce *f)
{
    Spec *s = L->s;
    ExprPool *P = L->P;
    int q = spec_scalar_coordinate(L, v, "a limit");
    const char *name = s->coord[q].name;
    yaml_node_t *r = spec_lookup(L, map, "range"), *kn = spec_lookup(L, map, "stiffness");
    yaml_node_t *cn = spec_lookup(L, map, "damping");
    if (!r)
        diag_error(spec_loc(L, map), "a limit needs `range: [lo, hi]` (null or .inf for an "
                   "end with no stop)");
    if (!kn)
        diag_error(spec_loc(L, map), "a limit needs `stiffness: k`, its stops' spring "
                   "constant (and `damping: c` for a damper, 0 if left out)");
    spec_expect(L, r, YAML_SEQUENCE_NODE, "a limit's range [lo, hi]");
    if (NITEMS(r) != 2)
        diag_error(spec_loc(L, r), "a limit's range is [lo, hi], two entries, and this has %d",
                   NITEMS(r));
    ExprId lo = range_end(L, spec_node(L, ITEMS(r)[0]), 0);
    ExprId hi = range_end(L, spec_node(L, ITEMS(r)[1]), 1);
    if (lo == EXPR_NONE && hi == EXPR_NONE)
        diag_error(spec_loc(L, r), "a limit's range needs at least one end (both are open: "
                   "no stop at all)");
    ExprId k = spec_expr(L, kn, ALLOW_PARAM, "a limit's stiffness");
    ExprId c = cn ? spec_expr(L, cn, ALLOW_PARAM, "a limit's damping") : EXPR_ZERO;
    spec_require(L, k, 0, kn, 1, "limit on '%s': its stiffness cannot be negative", name);
    if (cn)
        spec_require(L, c, 0, cn, 1, "limit on '%s': its damping cannot be negative", name);
    if (lo != EXPR_NONE && hi != EXPR_NONE)
        spec_require(L, expr_sub(P, hi, lo), 0, r, 0, "limit on '%s': its range is reversed "
                     "(the lower end above the upper)", name);
    ExprId x = expr_var(P, q, 0), rate = expr_var(P, q, 1), Q = EXPR_ZERO;
    char nm[300];
    if (lo != EXPR_NONE) {
        snprintf(nm, sizeof nm, "%s.%s.lo", owner, name);
        ExprId d = expr_sub(P, lo, x);
        Q = stop_force(L, d, expr_neg(P, rate), k, c, nm);
    }
    if (hi != EXPR_NONE) {
        snprintf(nm, sizeof nm, "%s.%s.hi", owner, name);
        Q = expr_sub(P, Q, stop_force(L, expr_sub(P, x, hi), rate, k, c, nm));
    }
    f->kind = FORCE_WORK;
    f->expr = expr_mul(P, Q, expr_seed(P, q, 0));
}

/*
 * invariant: is h = q'.dL/dq' - L conserved, and what is it (see
 * invariant.h for the conditions and why they suffice).
 */
#include "invariant.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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
    case EXPR_SELECT: /* either branch: both must scale alike */
        d = a == b ? a : NAN;
        break;
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

/* ---- is a quantity free of t? ----
 *
 * By structure when no t (and no input, a signal of t) is left in it, or
 * when its partial derivatives in them fold to 0.  Otherwise t may still
 * cancel through an identity the simplifier does not know (a point on a
 * turning hoop: its speed squared has cos(w t)^2 + sin(w t)^2 inside
 * squares of sums), and the partial derivatives are evaluated in long
 * double, with a bound on their rounding (expr_eval_bound), at random
 * states and parameters.  The quantity is free of t when at every one of
 * ZERO_STATES states every derivative is within its rounding bound of 0:
 * a derivative that is not 0 as a function is, at a random state, of the
 * order of the terms it is made of, orders of magnitude above the bound
 * (a few long double roundings of those terms, 1e-19 to 1e-15).  A state
 * whose bound cannot be trusted (a branch, a value that is not finite)
 * does not count; with fewer than ZERO_STATES good ones in ZERO_TRIES the
 * quantity is taken to depend on t.  docs/mechanics.md has the details. */
enum { ZERO_STATES = 100, ZERO_TRIES = 1000 };

typedef struct ZeroTest {
    const Spec *s;
    ExprPool *P;
    Diff *D;
    Arena *A;
    ExprEnv *env;       /* ZERO_TRIES random states, made when first needed */
    const char *folded; /* what was free of t only once differentiated */
    const char *numeric; /* what the numerical test found free of t */
    double worst;        /* its largest |d/dt| over the magnitude of the terms */
    double margin;       /* its largest |d/dt| over its rounding bound */
    const char *failed;  /* why t was found, or NULL */
    int failed_numerically; /* by the numerical test */
    int ntested;         /* quantities tested: T, V, then the constraints */
    int inputs;          /* the numerical test took derivatives in inputs too */
} ZeroTest;

/* xorshift64*: the same states on every run, so the same decision */
static double
zero_rand(unsigned long long *x, double lo, double hi)
{
    *x ^= *x >> 12;
    *x ^= *x << 25;
    *x ^= *x >> 27;
    double r = (double)((*x * 2685821657736338717ull) >> 11) / 9007199254740992.0;
    return lo + (hi - lo) * r;
}

/* The states: every parameter its value times 2^r (r in [-1, 1]; 2^r
 * where the value is 0), so that what holds for the spec's values by
 * accident (a rate of change set to 0) does not pass for the model's;
 * t in [0, t_end]; q and q' their initial values +- (1 + |value|) r, the
 * higher derivatives and the inputs the same around 0 and their value. */
static void
zero_states(ZeroTest *z)
{
    const Spec *s = z->s;
    int n = s->nq + s->nspeed; /* by leaf index: the speeds after the coordinates */
    unsigned long long x = 0x9E3779B97F4A7C15ull;
    double *p0 = arena_new_array(z->A, double, s->np + 1);
    double *u0 = arena_new_array(z->A, double, s->nu + 1);
    for (int i = 0; i < s->np; i++)
        p0[i] = s->param[i].value;
    ExprEnv e0 = {.t = 0, .p = p0, .u = u0};
    for (int k = 0; k < s->nu; k++)
        u0[k] = expr_eval(z->P, s->input[k].expr, &e0);
    double *c0 = arena_new_array(z->A, double, 2 * n + 1); /* q and q' at the start */
    for (int i = 0; i < n; i++) {
        c0[i] = i < s->nq ? expr_eval(z->P, s->coord[i].q0, &e0) : 0;
        c0[n + i] = expr_eval(z->P, i < s->nq ? s->coord[i].v0 : s->speed[i - s->nq].v0, &e0);
    }
    z->env = arena_new_array(z->A, ExprEnv, ZERO_TRIES);
    for (int j = 0; j < ZERO_TRIES; j++) {
        ExprEnv *e = &z->env[j];
        double *p = arena_new_array(z->A, double, s->np + 1);
        double *u = arena_new_array(z->A, double, s->nu + 1);
        for (int i = 0; i < s->np; i++)
            p[i] = (p0[i] != 0 ? p0[i] : 1) * exp2(zero_rand(&x, -1, 1));
        e->t = zero_rand(&x, 0, s->scene.t_end);
        for (int k = 0; k < s->nu; k++)
            u[k] = u0[k] + (1 + fabs(u0[k])) * zero_rand(&x, -1, 1);
        e->p = p, e->u = u;
        for (int o = 0; o <= EXPR_MAX_ORDER; o++) {
            double *q = arena_new_array(z->A, double, n + 1);
            for (int i = 0; i < n; i++) {
                double c = o < 2 ? c0[o * n + i] : 0;
                q[i] = c + (1 + fabs(c)) * zero_rand(&x, -1, 1);
            }
            e->q[o] = q;
        }
    }
}

/* Where e may jump in t though its derivative in t is 0 on both sides:
 * sign(), atan2() across its cut, or a quotient such as x/|x| whose
 * denominator passes 0 (0/0 at one instant); and pow(), which has no
 * real value for a negative base.  Neither the derivative's structure
 * nor its samples see a jump, so t inside one of them is never credited
 * as cancelling.  The operator, or NULL. */
static const char *
may_jump(ExprPool *P, ExprId e)
{
    const unsigned tu = DEP_T | DEP_U;
    unsigned char *mark = xmalloc(expr_pool_size(P));
    memset(mark, 0, expr_pool_size(P));
    expr_mark(P, 1, &e, mark);
    const char *why = NULL;
    for (ExprId i = 0; i <= e && !why; i++) {
        const ExprNode *nd = expr_node(P, i);
        if (!mark[i] || !(nd->deps & tu))
            continue;
        if (nd->op == EXPR_SIGN || nd->op == EXPR_ATAN2 || nd->op == EXPR_POW)
            why = nd->op == EXPR_SIGN ? "sign()" : nd->op == EXPR_ATAN2 ? "atan2()" : "pow()";
        else if (nd->op == EXPR_DIV && (expr_node(P, nd->b)->deps & tu))
            why = "a denominator";
    }
    free(mark);
    return why;
}

/* Is e free of t and of the inputs?  `name` says what e is, `sym` how
 * its derivative is written (dT/dt), in messages. */
static int
free_of_time(ZeroTest *z, ExprId e, const char *name, const char *sym)
{
    ExprPool *P = z->P;
    z->ntested++;
    if (!(expr_deps(P, e) & (DEP_T | DEP_U)))
        return 1;
    const char *jump = may_jump(P, e);
    if (jump) {
        z->failed = arena_printf(z->A, "%s holds t inside %s, where it may jump without "
                                 "a derivative to show it", name, jump);
        return 0;
    }
    /* the partial derivatives in t and in each input that e holds, and
     * what each is taken in */
    ExprId *d = arena_new_array(z->A, ExprId, z->s->nu + 1);
    const char **in = arena_new_array(z->A, const char *, z->s->nu + 1);
    int m = 0;
    for (int k = -1; k < z->s->nu; k++) {
        ExprId leaf = k < 0 ? expr_time(P) : expr_input(P, k);
        if ((k < 0 && !(expr_deps(P, e) & DEP_T)) || (k >= 0 && !expr_depends(P, e, leaf)))
            continue;
        d[m] = diff_partial(z->D, e, leaf);
        in[m] = k < 0 ? "t" : z->s->input[k].name;
        m += d[m] != EXPR_ZERO;
    }
    if (m == 0) {
        z->folded = z->folded ? arena_printf(z->A, "%s, %s", z->folded, name) : name;
        return 1;
    }
    if (!z->env)
        zero_states(z);
    ExprBound *b = arena_new_array(z->A, ExprBound, (size_t)m * ZERO_STATES);
    int good = 0;
    double worst = 0, margin = 0;
    for (int start = 0; start < ZERO_TRIES && good < ZERO_STATES; start += ZERO_STATES) {
        for (int i = 0; i < m; i++)
            expr_eval_bound(P, d[i], ZERO_STATES, &z->env[start], &b[i * ZERO_STATES]);
        for (int j = 0; j < ZERO_STATES && good < ZERO_STATES; j++) {
            int trusted = 1;
            for (int i = 0; i < m; i++)
                trusted = trusted && isfinite(b[i * ZERO_STATES + j].err);
            if (!trusted)
                continue;
            for (int i = 0; i < m; i++) {
                const ExprBound *r = &b[i * ZERO_STATES + j];
                double rel = r->mag > 0 ? (double)(fabsl(r->value) / r->mag) : 0;
                double bound = r->mag > 0 ? (double)(r->err / r->mag) : 0;
                if (fabsl(r->value) > r->err) {
                    z->failed_numerically = 1;
                    z->failed = arena_printf(z->A, "d%s/d%s is not 0: at a random state it "
                                             "is %.2g of the magnitude of its terms, where "
                                             "rounding allows %.2g", sym, in[i], rel,
                                             bound);
                    return 0;
                }
                worst = fmax(worst, rel);
                if (r->err > 0)
                    margin = fmax(margin, (double)(fabsl(r->value) / r->err));
            }
            good++;
        }
    }
    if (good < ZERO_STATES) {
        z->failed_numerically = 1;
        z->failed = arena_printf(z->A, "d%s/dt could be evaluated with a trusted rounding "
                                 "bound at only %d of %d random states, too few to call it 0",
                                 sym, good, ZERO_TRIES);
        return 0;
    }
    for (int i = 0; i < m; i++)
        z->inputs |= strcmp(in[i], "t") != 0;
    z->numeric = z->numeric ? arena_printf(z->A, "%s, %s", z->numeric, name) : name;
    z->worst = fmax(z->worst, worst);
    z->margin = fmax(z->margin, margin);
    return 1;
}

/* Why h is not conserved, or NULL if it is. */
static const char *
obstacle(const Spec *s, const Mech *m, const Constraints *c, ZeroTest *z)
{
    Arena *A = z->A;
    ExprPool *P = z->P;
    if (!free_of_time(z, m->T, "T", "T"))
        return "T depends on t";
    if (!free_of_time(z, m->V, "V", "V"))
        return "V depends on t or on an input";
    for (int i = 0; i < m->n; i++)
        if (m->Q[i] != EXPR_ZERO)
            for (int k = 0; k < s->neffect; k++) {
                const SpecEffect *e = &s->effect[k];
                for (int j = 0; e->enabled && j < e->nforce; j++)
                    if (e->force[j].kind != FORCE_GRAVITY &&
                        e->force[j].kind != FORCE_POTENTIAL &&
                        e->force[j].kind != FORCE_KINETIC)
                        return arena_printf(A, "the effect '%s' is a force, not a "
                                            "potential", e->name);
            }
    for (int k = 0; c && k < c->nc; k++) {
        const SpecConstraint *sc = &c->spec[k];
        if (!free_of_time(z, sc->expr, arena_printf(A, "the constraint '%s'", sc->name),
                          arena_printf(A, "(%s)", sc->name)))
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

/* For --explain: which test decided whether T, V and the constraints are
 * free of t. */
static const char *
time_test(const ZeroTest *z, int conserved)
{
    Arena *A = z->A;
    if (z->failed)
        return arena_printf(A, "t: %s%s", z->failed_numerically ? "the numerical zero "
                            "test decided: " : "", z->failed);
    const char *folded = z->folded ? arena_printf(A, "by structure, the derivatives in t of "
                                                  "%s fold to 0", z->folded) : NULL;
    if (!z->numeric)
        return arena_printf(A, "t: by structure: %s", folded ? folded
                            : arena_printf(A, "%s hold neither t nor an input",
                                           z->ntested > 2 ? "T, V and the constraints"
                                                          : "T and V"));
    return arena_printf(A, "t: %s hold%s t but not in value: decided by the numerical zero "
                        "test, not by structure: at %d random states and parameters, the "
                        "derivative%s, in long double, within %s rounding bound of 0 "
                        "(at most %.2g of the magnitude of the terms, %.2g of the bound)%s%s%s",
                        z->numeric, strchr(z->numeric, ',') ? "" : "s", ZERO_STATES,
                        z->inputs ? "s in t and the inputs were" : " in t was",
                        z->inputs ? "their" : "its", z->worst,
                        z->margin, folded ? "; " : "", folded ? folded : "",
                        conserved ? "; the conserved quantity is computed from them as "
                                    "written, t and all" : "");
}

Invariant *
invariant_derive(const Spec *s, const Mech *m, const Constraints *c, Arena *A,
                 ExprPool *P, Diff *D)
{
    Invariant *inv = arena_alloc(A, sizeof *inv);
    ZeroTest z = {.s = s, .P = P, .D = D, .A = A};
    const char *why = obstacle(s, m, c, &z);
    inv->test = time_test(&z, !why);
    if (why) {
        inv->h = EXPR_NONE;
        inv->note = arena_printf(A, "nothing is conserved: %s", why);
        return inv;
    }
    const char *cancels = z.numeric ? arena_printf(A, " (t cancels in %s, as a numerical "
                                                   "test found)", z.numeric) : "";
    const char *reason = c ? arena_printf(A, "T, V and the constraints do not depend on t%s, "
                                          "every effect is a potential and the constraint "
                                          "forces do no work", cancels)
                           : arena_printf(A, "T and V do not depend on t%s and every effect "
                                          "is a potential", cancels);
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

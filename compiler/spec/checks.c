/*
 * checks: the physical data's conditions (checks.h).
 */
#include "checks.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* The parameters' default values, for evaluating with them; the
 * parameters must be loaded. */
const double *
spec_defaults(Loader *L)
{
    Spec *s = L->s;
    if (!L->pdef) {
        L->pdef = arena_new_array(L->A, double, s->np + 1);
        for (int i = 0; i < s->np; i++)
            L->pdef[i] = s->param[i].value;
    }
    return L->pdef;
}

/* Require e > 0 (strict) or e >= 0 of the parameters, for the physical
 * datum at n: now, with the parameters' defaults (an error at n, saying
 * what and the value when it is a single number), and in the simulator
 * for the values --set gives (Spec.check).  The parameters must be
 * loaded. */
void
spec_require(Loader *L, ExprId e, int strict, const yaml_node_t *n, int show, const char *fmt,
        ...)
{
    Spec *s = L->s;
    for (int i = 0; i < s->np; i++) /* no value to check it with: its error is said */
        if (L->bad_param && L->bad_param[i] && expr_depends(L->P, e, expr_param(L->P, i)))
            return;
    char what[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    ExprEnv env = {.p = spec_defaults(L)};
    double v = expr_eval(L->P, e, &env);
    for (int i = 0; i < s->np; i++) /* the value may be a scene's choice */
        if (s->param[i].fixed && expr_depends(L->P, e, expr_param(L->P, i)))
            snprintf(what + strlen(what), sizeof what - strlen(what), "%s%s fixed at %g",
                     strstr(what, " fixed at ") ? ", " : " (with ", s->param[i].name,
                     s->param[i].value);
    if (strstr(what, " fixed at "))
        snprintf(what + strlen(what), sizeof what - strlen(what), ")");
    if (!(strict ? v > 0 : v >= 0)) {
        if (show)
            diag_error(spec_loc(L, n), "%s; it is %g", what, v);
        diag_error(spec_loc(L, n), "%s", what);
    }
    if (expr_is_const(L->P, e, NULL))
        return; /* no parameter can change it */
    char params[512] = "";
    for (int i = 0; i < s->np; i++)
        if (expr_depends(L->P, e, expr_param(L->P, i)))
            snprintf(params + strlen(params), sizeof params - strlen(params), "%s%s",
                     params[0] ? ", " : "", s->param[i].name);
    if (s->ncheck == s->capcheck) {
        s->capcheck = s->capcheck ? 2 * s->capcheck : 16;
        SpecCheck *c = arena_new_array(L->A, SpecCheck, s->capcheck);
        if (s->ncheck)
            memcpy(c, s->check, (size_t)s->ncheck * sizeof *c);
        s->check = c;
    }
    s->check[s->ncheck++] = (SpecCheck){e, strict, arena_strdup(L->A, what),
                                        arena_strdup(L->A, params), spec_loc(L, n)};
}

/* A mass: of parameters, not negative (a massless point is fine: forces
 * can act on it). */
ExprId
spec_mass(Loader *L, const yaml_node_t *n, const char *kind, const char *name)
{
    ExprId m = spec_expr(L, n, ALLOW_PARAM, "a mass");
    spec_require(L, m, 0, n, 1, "%s '%s': a mass cannot be negative", kind, name);
    return m;
}

/* Body b's inertia at n, once loaded: a planar moment must be positive; a
 * 3-D tensor I positive definite (a zero principal moment leaves a
 * rotation without inertia: the mass matrix is singular), and that of
 * some distribution of mass: S = tr(I)/2 - I, its second moments
 * sum m x_i x_j, positive semi-definite, which for principal moments is
 * the triangle inequality A + B >= C in every order. */
void
spec_require_inertia(Loader *L, const yaml_node_t *n, const SpecBody *b)
{
    ExprPool *P = L->P;
    const ExprId *I = b->inertia;
    if (b->dim == 2) {
        spec_require(L, I[0], 1, n, 1, "body '%s': its moment of inertia must be positive",
                b->name);
        return;
    }
    const char *pd = "body '%s': its inertia must be positive definite (a principal "
                     "moment of zero or less leaves a rotation with no inertia)";
    ExprId m2b = expr_mul(P, I[1], I[3]);
    ExprId m2 = expr_sub(P, expr_mul(P, I[0], I[4]), m2b);
    ExprId det = EXPR_ZERO, S[9], half = expr_const(P, 0.5);
    for (int j = 0; j < 3; j++) { /* along the first row */
        int a = (j + 1) % 3, c = (j + 2) % 3;
        ExprId ca = expr_mul(P, I[3 + c], I[6 + a]);
        ExprId minor = expr_sub(P, expr_mul(P, I[3 + a], I[6 + c]), ca);
        det = expr_add(P, det, expr_mul(P, I[j], minor));
    }
    spec_require(L, I[0], 1, n, 0, pd, b->name);
    spec_require(L, m2, 1, n, 0, pd, b->name);
    spec_require(L, det, 1, n, 0, pd, b->name);
    ExprId tr = expr_mul(P, half, expr_add(P, expr_add(P, I[0], I[4]), I[8]));
    for (int k = 0; k < 9; k++)
        S[k] = k % 4 == 0 ? expr_sub(P, tr, I[k]) : expr_neg(P, I[k]);
    const char *real = "body '%s': no distribution of mass has this inertia (its principal "
                       "moments must satisfy A + B >= C in every order)";
    for (int k = 0; k < 3; k++) /* every principal minor of S */
        spec_require(L, S[4 * k], 0, n, 0, real, b->name);
    for (int k = 0; k < 3; k++) {
        int a = (k + 1) % 3, c = (k + 2) % 3;
        ExprId off = expr_mul(P, S[3 * a + c], S[3 * c + a]);
        spec_require(L, expr_sub(P, expr_mul(P, S[4 * a], S[4 * c]), off), 0, n, 0, real, b->name);
    }
    ExprId dS = EXPR_ZERO;
    for (int j = 0; j < 3; j++) {
        int a = (j + 1) % 3, c = (j + 2) % 3;
        ExprId ca = expr_mul(P, S[3 + c], S[6 + a]);
        ExprId minor = expr_sub(P, expr_mul(P, S[3 + a], S[6 + c]), ca);
        dS = expr_add(P, dS, expr_mul(P, S[j], minor));
    }
    spec_require(L, dS, 0, n, 0, real, b->name);
}

void
spec_check_axes(Loader *L)
{
    /* an axis of parameters has no direction where they make it zero */
    for (const AxisCheck *c = L->axes; c; c = c->next)
        spec_require(L, c->n2, 1, c->n, 0, "frame '%s': an axis cannot be zero", c->name);
}

/*
 * fold: every expression of a Spec (spec_foreach_expr, spec.h), and the
 * fixed parameters folded into them (fold.h).
 */
#include "fold.h"

#include <string.h>

/* The one list of the Spec's expression fields (spec.h says so where
 * they are declared): every pass over all of them goes through it, so
 * that a new field cannot escape one.  Fields that do not hold an
 * expression are skipped (EXPR_NONE, or a velocity not given). */
void
spec_foreach_expr(Spec *s, SpecExprFn *f, void *ctx)
{
#define VISIT(e)                                                                       \
    do {                                                                               \
        if ((e) != EXPR_NONE)                                                          \
            f(&(e), ctx);                                                              \
    } while (0)
    for (int i = 0; i < s->nq; i++) {
        VISIT(s->coord[i].q0);
        VISIT(s->coord[i].v0);
    }
    for (int k = 0; k < s->nspeed; k++)
        VISIT(s->speed[k].v0);
    for (int i = 0; i < s->nu; i++)
        VISIT(s->input[i].expr);
    for (int i = 0; i < s->npart; i++) {
        VISIT(s->part[i].mass);
        for (int k = 0; k < 3; k++) {
            VISIT(s->part[i].pos[k]);
            if (s->part[i].has_vel)
                VISIT(s->part[i].vel[k]);
        }
    }
    for (int i = 0; i < s->nbody; i++) {
        SpecBody *b = &s->body[i];
        VISIT(b->mass);
        for (int k = 0; k < 3; k++) {
            VISIT(b->center[k]);
            VISIT(b->omega[k]);
            if (b->has_center_vel)
                VISIT(b->center_vel[k]);
        }
        for (int k = 0; k < 9; k++) {
            VISIT(b->inertia[k]);
            if (b->has_rot)
                VISIT(b->rot[k]);
        }
        VISIT(b->angle);
    }
    for (int i = 0; i < s->nshape; i++)
        for (int k = 0; k < 3; k++) {
            VISIT(s->shape[i].esize[k]);
            VISIT(s->shape[i].epos[k]);
        }
    for (int i = 0; i < s->neffect; i++)
        for (int j = 0; j < s->effect[i].nforce; j++) {
            SpecForce *fo = &s->effect[i].force[j];
            for (int k = 0; k < 3; k++)
                VISIT(fo->vec[k]);
            VISIT(fo->expr);
            if (fo->kind == FORCE_CONTACT) {
                VISIT(fo->stiffness);
                VISIT(fo->damping);
            }
            VISIT(fo->bound);
        }
    for (int i = 0; i < s->nkinetic; i++)
        VISIT(s->kinetic[i].expr);
    for (int i = 0; i < s->npotential; i++)
        VISIT(s->potential[i].expr);
    for (int i = 0; i < s->nconstraint; i++)
        VISIT(s->constraint[i].expr);
    for (int i = 0; i < s->ncheck; i++)
        VISIT(s->check[i].expr);
    for (int i = 0; i < s->scene.noutput; i++)
        VISIT(s->scene.output[i].expr);
    for (int i = 0; i < s->scene.nevent; i++) {
        SpecEvent *ev = &s->scene.event[i];
        VISIT(ev->when);
        for (int k = 0; k < ev->nset; k++)
            VISIT(ev->set_expr[k]);
    }
#undef VISIT
}

/* The expression fields collected, to be rebuilt in one pass. */
typedef struct FoldList {
    Arena *A;
    ExprId **at;
    int n, cap;
} FoldList;

static void
collect(ExprId *e, void *ctx)
{
    FoldList *l = ctx;
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 64;
        ExprId **bigger = arena_new_array(l->A, ExprId *, l->cap);
        if (l->n)
            memcpy(bigger, l->at, (size_t)l->n * sizeof *l->at);
        l->at = bigger;
    }
    l->at[l->n++] = e;
}

/* Fixed parameters become constants everywhere: every expression of the
 * spec, rebuilt in one pass, folds them (expr_subst_many). */
void
spec_fold_fixed(Loader *L)
{
    Spec *s = L->s;
    if (s->nfixed == 0)
        return;
    FoldList l = {L->A, NULL, 0, 0};
    spec_foreach_expr(s, collect, &l);
    int n = l.n;
    ExprId *roots = arena_new_array(L->A, ExprId, n + 1);
    ExprId *from = arena_new_array(L->A, ExprId, s->nfixed);
    ExprId *to = arena_new_array(L->A, ExprId, s->nfixed);
    for (int i = 0; i < n; i++)
        roots[i] = *l.at[i];
    int k = 0;
    for (int i = 0; i < s->np; i++)
        if (s->param[i].fixed) {
            from[k] = expr_param(L->P, i);
            to[k++] = expr_const(L->P, s->param[i].value);
        }
    expr_subst_many(L->P, n, roots, k, from, to, roots);
    for (int i = 0; i < n; i++)
        *l.at[i] = roots[i];
    /* conditions that no parameter can change any more held when checked */
    int kept = 0;
    for (int i = 0; i < s->ncheck; i++)
        if (!expr_is_const(L->P, s->check[i].expr, NULL))
            s->check[kept++] = s->check[i];
    s->ncheck = kept;
}

/*
 * friction: dry friction on a coordinate (friction.h).
 *
 * The generalized force on q is
 *     Q = SELECT(stick, 0, where(q', -F, F)):
 * slipping, F against the slip, its direction a switch whose function
 * is q' (EFFECT.q.slip); stuck, nothing here, the runtime holding q
 * with whatever force it takes (runtime/model/friction.c).  The stick
 * switch (EFFECT.q.stick) has no function in the model: the runtime
 * sets its mode and gives its function, F - |the force that holds q|.
 */
#include "friction.h"

#include "checks.h"
#include "names.h"

#include <stdio.h>

/* The friction item already on coordinate q, or NULL. */
static const SpecForce *
friction_on(const Spec *s, int q)
{
    for (int e = 0; e < s->neffect; e++)
        for (int j = 0; s->effect[e].force && j < s->effect[e].nforce; j++)
            if (s->effect[e].force[j].friction && s->effect[e].force[j].coord == q)
                return &s->effect[e].force[j];
    return NULL;
}

void
spec_load_friction(Loader *L, yaml_node_t *map, yaml_node_t *v, const char *owner,
                   SpecForce *f)
{
    Spec *s = L->s;
    ExprPool *P = L->P;
    int q = spec_scalar_coordinate(L, v, "dry friction");
    const char *name = s->coord[q].name;
    const SpecForce *twice = friction_on(s, q);
    if (twice)
        diag_error(spec_loc(L, v), "'%s' has dry friction already (line %d): one item per "
                   "coordinate, its force the sum of both", name, twice->loc.line);
    yaml_node_t *fn = spec_lookup(L, map, "force");
    if (!fn)
        diag_error(spec_loc(L, map), "dry friction on '%s' needs `force: F`, the largest "
                   "force it can exert (mu*m*g for a block on the floor)", name);
    ExprId F = spec_expr(L, fn, ALLOW_FORCE, "a friction force");
    if (expr_is_coeff(P, F))
        spec_require(L, F, 0, fn, 1, "dry friction on '%s': its force cannot be negative",
                     name);
    char nm[300];
    int first = expr_nswitch(P);
    ExprId rate = expr_var(P, q, 1), against = expr_neg(P, F); /* (ids in this order) */
    ExprId slip = expr_where(P, rate, against, F);
    if (expr_nswitch(P) > first) { /* (a switch of q' met before keeps its name) */
        snprintf(nm, sizeof nm, "%s.%s.slip", owner, name);
        expr_name_switch(P, first, nm);
    }
    int stick = expr_switch_held(P);
    snprintf(nm, sizeof nm, "%s.%s.stick", owner, name);
    expr_name_switch(P, stick, nm);
    ExprId Q = expr_select(P, stick, EXPR_ZERO, slip);
    f->kind = FORCE_WORK;
    f->expr = expr_mul(P, Q, expr_seed(P, q, 0));
    f->friction = 1;
    f->coord = q;
    f->bound = F;
    f->slip = -1;
    for (int k = 0; k < expr_nswitch(P); k++)
        if (expr_switch(P, k) == rate)
            f->slip = k;
    f->stick = stick;
}

/*
 * constraints: the spec's constraints and the quaternions' unit
 * constraints (constraints.h).
 */
#include "constraints.h"

#include "checks.h"
#include "names.h"

#include <math.h>
#include <string.h>

static int
find_coordinate(Loader *L, yaml_node_t *n)
{
    const char **cands = arena_new_array(L->A, const char *, L->s->nq + 1);
    for (int i = 0; i < L->s->nq; i++)
        cands[i] = L->s->coord[i].name;
    return spec_find_in(L, n, "coordinate", "coordinates", 1, cands, L->s->nq);
}

/* NAME: EXPR, or NAME: {expr: EXPR, dependent: COORDINATE}. */
static void
load_constraint(Loader *L, yaml_node_t *k, yaml_node_t *v, SpecConstraint *c)
{
    static const char *const keys[] = {"expr", "dependent", NULL};
    c->name = arena_strdup(L->A, spec_scalar(L, k, "a constraint name"));
    c->loc = spec_loc(L, k);
    c->dependent = -1;
    if (!spec_is_identifier(c->name))
        diag_error(c->loc, "'%s' is not a valid constraint name", c->name);
    yaml_node_t *e = v;
    if (v->type == YAML_MAPPING_NODE) {
        spec_map(L, v, "a constraint");
        spec_check_keys(L, v, keys, "a constraint");
        if (!(e = spec_lookup(L, v, "expr")))
            diag_error(spec_loc(L, v), "constraint '%s' has no `expr:`", c->name);
        yaml_node_t *d = spec_lookup(L, v, "dependent");
        if (d) {
            c->dependent = find_coordinate(L, d);
            c->dep_loc = spec_loc(L, d);
        }
    }
    c->expr = spec_expr(L, e, ALLOW_CONSTRAINT, "a constraint");
    c->order = expr_max_order(L->P, c->expr);
    if (!(expr_deps(L->P, c->expr) & DEP_ANY_Q))
        diag_error(spec_loc(L, e), "constraint '%s' involves no coordinate, so it constrains "
                   "nothing (its order cannot be determined)", c->name);
    /* only second-order constraints are used as written: the others are
     * differentiated, and an input's derivative is unknown.  Parsed again
     * without inputs, the error points at the input. */
    if (c->order < 2 && (expr_deps(L->P, c->expr) & DEP_U))
        spec_expr(L, e, ALLOW_CONSTRAINT & ~(unsigned)DEP_U,
                   c->order == 0 ? "a holonomic constraint" : "a first-order constraint");
}

static void
load_constraint_at(Loader *L, yaml_node_t *map, int i)
{
    Spec *s = L->s;
    SpecConstraint *c = &s->constraint[i];
    load_constraint(L, spec_node(L, PAIRS(map)[i].key), spec_node(L, PAIRS(map)[i].value), c);
    for (int j = 0; j < i; j++)
        if (c->dependent >= 0 && s->constraint[j].dependent == c->dependent)
            diag_error(c->dep_loc, "coordinate '%s' is already the dependent coordinate "
                       "of constraint '%s'", s->coord[c->dependent].name,
                       s->constraint[j].name);
}

void
spec_load_constraints(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->nconstraint = NPAIRS(map);
    s->constraint = arena_new_array(L->A, SpecConstraint, s->nconstraint);
    for (int i = 0; i < s->nconstraint; i++)
        s->constraint[i].dependent = -1;
    for (int i = 0; i < s->nconstraint; i++)
        spec_checked(L, load_constraint_at, map, i);
    if (s->nconstraint >= s->nv) /* at the one too many */
        diag_error(s->constraint[s->nv - 1].loc, "%d constraint%s on %d %s%s "
                   "leave%s no freedom of motion", s->nconstraint,
                   s->nconstraint == 1 ? "" : "s", s->nv,
                   s->nspeed ? "speed" : "coordinate", s->nv == 1 ? "" : "s",
                   s->nconstraint == 1 ? "s" : "");
}

/* A quaternion's unit constraint, NAME_unit: e.e - 1 = 0, after the
 * spec's own constraints (holonomic, kept like any other: at acceleration
 * level, projected by --stabilize project), the bodies' first, then the
 * frames'.  For elimination its dependent coordinate is the Euler
 * parameter largest at the start (with the defaults), where
 * df/de'' = 2 e is surest not to vanish; no fixed choice is safe for
 * every orientation. */
void
spec_unit_constraints(Loader *L)
{
    Spec *s = L->s;
    ExprPool *P = L->P;
    SpecQuat *quat = arena_new_array(L->A, SpecQuat, s->nbody + s->nfquat + 1);
    int extra = 0;
    for (int i = 0; i < s->nbody; i++)
        if (s->body[i].quat[0] >= 0 && s->body[i].quat_speed < 0) {
            const SpecBody *b = &s->body[i];
            quat[extra] = (SpecQuat){b->name, arena_printf(L->A, "body '%s'", b->name),
                                     {b->quat[0], b->quat[1], b->quat[2], b->quat[3]},
                                     b->quat_loc, -1};
            extra++;
        }
    for (int i = 0; i < s->nfquat; i++)
        if (s->fquat[i].speed < 0) /* with speeds, |e| keeps its value */
            quat[extra++] = s->fquat[i];
    if (!extra)
        return;
    int nuser = s->nconstraint;
    SpecConstraint *c = arena_new_array(L->A, SpecConstraint, s->nconstraint + extra);
    if (s->nconstraint)
        memcpy(c, s->constraint, (size_t)s->nconstraint * sizeof *c);
    s->constraint = c;
    for (int i = 0; i < extra; i++) {
        const SpecQuat *qu = &quat[i];
        const char *name = arena_printf(L->A, "%s_unit", qu->name);
        for (int j = 0; j < s->nconstraint; j++) {
            if (strcmp(s->constraint[j].name, name))
                continue;
            if (j < nuser)
                diag_error(s->constraint[j].loc, "'%s' is the name of %s's unit quaternion "
                           "constraint; name this one otherwise", name, qu->owner);
            diag_error(qu->loc, "%s and %s would both have the unit quaternion constraint "
                       "'%s': rename one", quat[j - nuser].owner, qu->owner, name);
        }
        ExprId g = expr_const(P, -1);
        for (int k = 0; k < 4; k++)
            g = expr_add(P, g, expr_powi(P, expr_var(P, qu->q[k], 0), 2));
        double best = -1;
        ExprEnv env = {.p = spec_defaults(L)};
        int dep = -1;
        for (int k = 0; k < 4; k++) {
            int taken = 0;
            for (int j = 0; j < s->nconstraint; j++)
                taken |= s->constraint[j].dependent == qu->q[k];
            double v = fabs(expr_eval(P, s->coord[qu->q[k]].q0, &env));
            if (!taken && v > best)
                best = v, dep = qu->q[k];
        }
        s->constraint[s->nconstraint++] = (SpecConstraint){name, qu->loc, g, 0, dep, qu->loc};
    }
    if (s->nconstraint >= s->nq)
        diag_error(s->constraint[s->nconstraint - 1].loc, "%d constraints (with the unit "
                   "quaternions') on %d coordinates leave no freedom of motion",
                   s->nconstraint, s->nq);
}

/*
 * effects: effects and energy terms (effects.h), and --effects
 * (spec_select_effects, spec.h).
 */
#include "effects.h"

#include "contacts.h"
#include "friction.h"
#include "names.h"
#include "stops.h"

#include <stdio.h>
#include <string.h>

/* A scalar or a sequence of scalars: the terms of an energy. */
static SpecTerm *
load_terms(Loader *L, yaml_node_t *n, unsigned allow, const char *what, int *count)
{
    int one = n->type == YAML_SCALAR_NODE;
    if (!one)
        spec_expect(L, n, YAML_SEQUENCE_NODE, what);
    *count = one ? 1 : NITEMS(n);
    SpecTerm *t = arena_new_array(L->A, SpecTerm, *count);
    for (int i = 0; i < *count; i++) {
        yaml_node_t *item = one ? n : spec_node(L, ITEMS(n)[i]);
        t[i].loc = spec_loc(L, item);
        t[i].expr = spec_expr(L, item, allow, what);
    }
    return t;
}

/* The particle or body a force acts on: its index, *is_body set. */
static int
find_target(Loader *L, yaml_node_t *n, int *is_body)
{
    const Spec *s = L->s;
    const char **cands = arena_new_array(L->A, const char *, s->npart + s->nbody + 1);
    for (int i = 0; i < s->npart; i++)
        cands[i] = s->part[i].name;
    for (int i = 0; i < s->nbody; i++)
        cands[s->npart + i] = s->body[i].name;
    int k = spec_find_in(L, n, "particle or body", "particles and bodies", 0, cands,
                    s->npart + s->nbody);
    *is_body = k >= s->npart;
    if (*is_body ? L->bad_body[k - s->npart] : L->bad_part[k])
        diag_abandon(); /* its own error is reported */
    return *is_body ? k - s->npart : k;
}

/* A force vector on a particle or a body's centre, or a torque on a body. */
static void
load_applied(Loader *L, yaml_node_t *map, yaml_node_t *v, yaml_node_t *on, SpecForce *f,
             int torque)
{
    const char *what = torque ? "a torque" : "a force";
    if (!on)
        diag_error(spec_loc(L, map), "%s needs `on: %s`, what it acts on", what,
                   torque ? "BODY" : "PARTICLE");
    int is_body, k = find_target(L, on, &is_body);
    f->particle = is_body ? -1 : k;
    f->body = is_body ? k : -1;
    int dim = is_body ? L->s->body[k].dim : L->s->part[k].dim;
    const char *name = is_body ? L->s->body[k].name : L->s->part[k].name;
    if (torque && !is_body)
        diag_error(spec_loc(L, on), "a torque acts on a body, and '%s' is a particle", name);
    if (torque && dim == 2) {
        f->dim = 1;
        f->vec[0] = spec_expr(L, v, ALLOW_FORCE, what);
        return;
    }
    if (torque && v->type == YAML_SCALAR_NODE) { /* a vector: to the body's axes */
        if (L->body_frame[k] < 0)
            diag_error(spec_loc(L, v), "a torque as a vector needs a body placed by `frame:`; "
                       "on body '%s', give its components in its axes, [tx, ty, tz]", name);
        ExprId w[3];
        spec_world_vector(L, v, ALLOW_FORCE, what, w);
        kin_to_frame(L->K, L->body_frame[k], w, f->vec);
        f->dim = 3;
        return;
    }
    f->dim = torque ? spec_vector(L, v, ALLOW_FORCE, what, f->vec)
                    : spec_world_vector(L, v, ALLOW_FORCE, what, f->vec);
    if (f->dim != dim)
        diag_error(spec_loc(L, v), "%s has %d components but %s '%s' is %d-D", what, f->dim,
                   is_body ? "body" : "particle", name, dim);
}

/* Virtual work W at node v, linear in the variations: W = sum_i Q_i
 * delta(q_i) with no Q_i holding a variation and nothing left over.  An
 * error at v otherwise, with the form it should take. */
#define WORK_HINT "; for example work: \"-c*r'*delta(r) + u*delta(theta_m)\" (a force " \
                  "times the variation of what it acts along)"
static ExprId
work(Loader *L, yaml_node_t *v)
{
    ExprPool *P = L->P;
    ExprId W = spec_expr(L, v, ALLOW_WORK, "a virtual-work expression");
    if (!(expr_deps(P, W) & DEP_S))
        diag_error(spec_loc(L, v), "virtual work is a sum of forces times variations "
                   "delta(...), and this expression has none" WORK_HINT);
    const Spec *s = L->s;
    int n = s->nq + s->nspeed; /* the coordinates' variations, then the speeds' */
    ExprId *seeds = arena_new_array(L->A, ExprId, n), *zeros = arena_new_array(L->A, ExprId, n);
    for (int i = 0; i < n; i++) {
        seeds[i] = expr_seed(P, i, 0), zeros[i] = EXPR_ZERO;
        if (expr_deps(P, diff_partial(L->sc.D, W, seeds[i])) & DEP_S)
            diag_error(spec_loc(L, v), "virtual work is not linear in the variations here: "
                       "delta(%s) is multiplied by a variation, or inside a function"
                       WORK_HINT, i < s->nq ? s->coord[i].name : s->speed[i - s->nq].name);
    }
    if (expr_subst(P, W, n, seeds, zeros) != EXPR_ZERO)
        diag_error(spec_loc(L, v), "a term of this virtual work has no variation: every term is "
                   "a force times a variation delta(...)" WORK_HINT);
    return W;
}

static void
load_force(Loader *L, yaml_node_t *map, SpecForce *f)
{
    static const char *const keys[] = {"gravity", "potential", "force", "torque", "work",
                                       "kinetic", "friction", "on", "contact", "limit",
                                       "stiffness", "damping", "range", NULL};
    spec_map(L, map, "a force");
    spec_check_keys(L, map, keys, "an effect");
    f->loc = spec_loc(L, map);
    int kinds = 0;
    yaml_node_t *v, *on = spec_lookup(L, map, "on"), *lim = spec_lookup(L, map, "limit");
    /* a contact and a limit have keys of their own: the law's */
    int law = !!spec_lookup(L, map, "stiffness") + !!spec_lookup(L, map, "damping");
    if (spec_lookup(L, map, "contact") && NPAIRS(map) > 1 + law +
                                           !!spec_lookup(L, map, "friction") + !!on)
        diag_error(spec_loc(L, map), "an effect item has exactly one of gravity, potential, "
                   "force, torque, work, kinetic, contact, limit, friction (write a list for "
                   "several)");
    if (spec_lookup(L, map, "contact")) {
        spec_load_contact(L, map, f);
        return;
    }
    if (lim && on)
        diag_error(spec_loc(L, on), "`on` belongs to a force or a torque");
    if (lim && NPAIRS(map) > 1 + law + !!spec_lookup(L, map, "range"))
        diag_error(spec_loc(L, map), "an effect item has exactly one of gravity, potential, "
                   "force, torque, work, kinetic, contact, limit, friction (write a list for "
                   "several)");
    if (lim) {
        spec_load_stop(L, map, lim, L->sc.owner, f);
        return;
    }
    /* (friction is an item of its own: dry friction) */
    static const char *const keys_of[] = {"stiffness", "damping", "range"};
    for (int k = 0; k < 3; k++)
        if (spec_lookup(L, map, keys_of[k]))
            diag_error(spec_key_loc(L, map, keys_of[k]), "`%s` belongs to %s", keys_of[k],
                       k < 2 ? "a contact or a limit ({contact: all, stiffness: k, damping: c}, "
                               "{limit: q, range: [lo, hi], stiffness: k, damping: c})"
                             : "a limit ({limit: q, range: [lo, hi], stiffness: k})");
    if ((v = spec_lookup(L, map, "gravity"))) {
        f->kind = FORCE_GRAVITY, kinds++;
        f->dim = spec_vector(L, v, ALLOW_FIELD, "a gravity field", f->vec);
        for (int k = 0; k < L->s->npart; k++)
            if (!L->bad_part[k] && L->s->part[k].dim != f->dim)
                diag_error(spec_loc(L, v), "gravity has %d components but particle '%s' is %d-D",
                           f->dim, L->s->part[k].name, L->s->part[k].dim);
        for (int k = 0; k < L->s->nbody; k++)
            if (!L->bad_body[k] && L->s->body[k].dim != f->dim)
                diag_error(spec_loc(L, v), "gravity has %d components but body '%s' is %d-D",
                           f->dim, L->s->body[k].name, L->s->body[k].dim);
        if (L->s->npart + L->s->nbody == 0)
            diag_error(spec_loc(L, v), "gravity acts on particles and bodies, and this spec "
                       "has none (write a potential instead)");
    }
    if ((v = spec_lookup(L, map, "potential")))
        f->kind = FORCE_POTENTIAL, kinds++,
        f->expr = spec_expr(L, v, ALLOW_POTENTIAL, "a potential");
    if ((v = spec_lookup(L, map, "work")))
        f->kind = FORCE_WORK, kinds++,
        f->expr = work(L, v);
    if ((v = spec_lookup(L, map, "kinetic")))
        f->kind = FORCE_KINETIC, kinds++,
        f->expr = spec_expr(L, v, ALLOW_KINETIC, "a kinetic-energy term");
    yaml_node_t *fr = spec_lookup(L, map, "friction"); /* its `force:` is a bound */
    if (fr)
        kinds++;
    if ((v = spec_lookup(L, map, "force")) && !fr)
        f->kind = FORCE_VECTOR, kinds++, load_applied(L, map, v, on, f, 0);
    if ((v = spec_lookup(L, map, "torque")))
        f->kind = FORCE_TORQUE, kinds++, load_applied(L, map, v, on, f, 1);
    if (on && kinds == 1 && (fr || (f->kind != FORCE_VECTOR && f->kind != FORCE_TORQUE)))
        diag_error(spec_loc(L, on), "`on` belongs to a force or a torque");
    if (kinds != 1)
        diag_error(spec_loc(L, map), kinds ? "an effect item has exactly one of gravity, "
                   "potential, force, torque, work, kinetic, contact, limit, friction (write a "
                   "list for several)"
                   : "an effect item needs one of gravity, potential, force, torque, work, "
                   "kinetic, contact, limit, friction");
    if (fr)
        spec_load_friction(L, map, fr, L->sc.owner, f);
}

static void
load_effect(Loader *L, yaml_node_t *map, int i)
{
    Spec *s = L->s;
    {
        yaml_node_t *k = spec_node(L, PAIRS(map)[i].key), *v = spec_node(L, PAIRS(map)[i].value);
        SpecEffect *e = &s->effect[i];
        e->name = arena_strdup(L->A, spec_scalar(L, k, "an effect name"));
        e->loc = spec_loc(L, k);
        e->enabled = 1;
        if (!spec_is_identifier(e->name))
            diag_error(e->loc, "'%s' is not a valid effect name", e->name);
        int list = v->type == YAML_SEQUENCE_NODE;
        e->nforce = list ? NITEMS(v) : 1;
        if (e->nforce == 0)
            diag_error(spec_loc(L, v), "effect '%s' is empty", e->name);
        e->force = arena_new_array(L->A, SpecForce, e->nforce);
        L->sc.owner = e->name; /* its switches' names */
        for (int j = 0; j < e->nforce; j++)
            load_force(L, list ? spec_node(L, ITEMS(v)[j]) : v, &e->force[j]);
    }
}

void
spec_load_effects(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->neffect = NPAIRS(map);
    s->effect = arena_new_array(L->A, SpecEffect, s->neffect);
    for (int i = 0; i < s->neffect; i++)
        if (!spec_checked(L, load_effect, map, i) && !s->effect[i].name)
            s->effect[i].name = "";
    L->sc.owner = NULL;
}

int
spec_find_effect(Loader *L, yaml_node_t *n)
{
    const char **cands = arena_new_array(L->A, const char *, L->s->neffect + 1);
    for (int i = 0; i < L->s->neffect; i++)
        cands[i] = L->s->effect[i].name;
    return spec_find_in(L, n, "effect", "effects", 0, cands, L->s->neffect);
}

/* `kinetic:` (i = 0) or `potential:` (i = 1) terms. */
void
spec_load_energy(Loader *L, yaml_node_t *root, int i)
{
    yaml_node_t *n = spec_section(L, root, i ? "potential" : "kinetic", 0);
    if (n && i)
        L->s->potential = load_terms(L, n, ALLOW_POTENTIAL, "a potential-energy term",
                                     &L->s->npotential);
    else if (n)
        L->s->kinetic = load_terms(L, n, ALLOW_KINETIC, "a kinetic-energy term",
                                   &L->s->nkinetic);
}

/* --effects with a typo: the nearest effect, or NULL if none is close. */
static const char *
effect_typo(const Spec *s, const char *name, size_t n)
{
    char buf[80];
    const char *cands[64];
    int count = s->neffect < 64 ? s->neffect : 64;
    if (n >= sizeof buf)
        return NULL;
    memcpy(buf, name, n);
    buf[n] = '\0';
    for (int i = 0; i < count; i++)
        cands[i] = s->effect[i].name;
    return diag_nearest(buf, cands, count);
}

int
spec_select_effects(Spec *s, const char *list)
{
    for (int i = 0; i < s->neffect; i++)
        s->effect[i].enabled = 0;
    for (const char *p = list; *p;) {
        size_t n = strcspn(p, ",");
        int found = 0;
        for (int i = 0; i < s->neffect; i++)
            if (strlen(s->effect[i].name) == n && !strncmp(s->effect[i].name, p, n))
                s->effect[i].enabled = found = 1;
        if (!found && n > 0) {
            const char *near = effect_typo(s, p, n);
            fprintf(stderr, "eomc: --effects: unknown effect '%.*s'; ", (int)n, p);
            if (near)
                fprintf(stderr, "did you mean %s? ", near);
            fprintf(stderr, "%s has", s->path);
            for (int i = 0; i < s->neffect; i++)
                fprintf(stderr, "%s %s", i ? "," : "", s->effect[i].name);
            fprintf(stderr, "%s\n", s->neffect ? "" : " no effects");
            return -1;
        }
        p += n;
        p += *p == ',';
    }
    return 0;
}

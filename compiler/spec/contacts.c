/*
 * contacts: a contact item's pairs and parameters (contacts.h).
 */
#include "contacts.h"

#include "checks.h"
#include "names.h"
#include "yaml.h"

#include <string.h>

static const char *const type_name[] = {"a box", "a sphere", "a capsule", "a cylinder",
                                        "an ellipsoid", "a plane"};

/* Why eomc has no gap for shapes of types a and b, or NULL where it has
 * one: a plane with a sphere, capsule, box or ellipsoid, and spheres and
 * capsules with each other (mechanics/contact.c). */
static const char *
no_gap(int a, int b)
{
    if (a == SPEC_SHAPE_CYLINDER || b == SPEC_SHAPE_CYLINDER)
        return "a cylinder's contact is not written yet (the point of its rim nearest a plane "
               "is undefined where it stands on a face): a capsule or a box can stand in "
               "for it";
    if (a == SPEC_SHAPE_PLANE || b == SPEC_SHAPE_PLANE)
        return NULL;
    if (a == SPEC_SHAPE_BOX || b == SPEC_SHAPE_BOX)
        return "a box touches a plane at its corners, but other shapes along its faces and "
               "edges too, whose switches eomc does not have yet";
    if (a == SPEC_SHAPE_ELLIPSOID || b == SPEC_SHAPE_ELLIPSOID)
        return "an ellipsoid's point nearest another curved shape has no closed form";
    return NULL;
}

/* Does a shape take part when its owner is named (not itself)?  Where
 * both its masks are 0 it is drawn only (MuJoCo's visual geoms). */
static int
collides(const SpecShape *sh)
{
    return sh->contype != 0 || sh->conaffinity != 0;
}

/* The shapes the name at n stands for, into out (a count): a shape's
 * name, a body's (its colliding shapes), or `ground` (the ground's). */
static int
shapes_named(Loader *L, yaml_node_t *n, int *out)
{
    const Spec *s = L->s;
    const char *name = spec_scalar(L, n, "a shape, body or ground");
    for (int k = 0; k < s->nshape; k++)
        if (s->shape[k].name && !strcmp(s->shape[k].name, name)) {
            out[0] = k;
            return 1;
        }
    int owner = -1, count = 0;
    for (int b = 0; b < s->nbody && owner < 0; b++)
        if (!strcmp(s->body[b].name, name))
            owner = b;
    if (owner < 0 && !strcmp(name, "ground"))
        owner = s->nbody; /* (the ground's shapes are past the bodies) */
    if (owner >= 0) {
        for (int k = 0; k < s->nshape; k++)
            if ((owner < s->nbody ? s->shape[k].body == owner : s->shape[k].body >= s->nbody) &&
                collides(&s->shape[k]))
                out[count++] = k;
        if (!count)
            diag_error(spec_loc(L, n), "%s has no shape that collides (each a `shapes:` item "
                       "whose contype or conaffinity is not 0)",
                       owner < s->nbody ? arena_printf(L->A, "body '%s'", name)
                                        : "the ground");
        return count;
    }
    const char **cands = arena_new_array(L->A, const char *, s->nshape + s->nbody + 2);
    for (int k = 0; k < s->nshape; k++)
        cands[count++] = s->shape[k].name ? s->shape[k].name : "";
    for (int b = 0; b < s->nbody; b++)
        cands[count++] = s->body[b].name;
    cands[count++] = "ground";
    return spec_find_in(L, n, "shape, body or ground", "shapes, bodies and ground", 0, cands,
                        count); /* (an error: no name matched) */
}

/* Shape k's owner, for messages. */
static const char *
owner(Loader *L, int k)
{
    int b = L->s->shape[k].body;
    return b < L->s->nbody ? arena_printf(L->A, "body '%s'", L->s->body[b].name) : "the ground";
}

/* Shape k's name (its own, or its body's) names it alone: its pairs and
 * switches are named by it. */
static void
unique_name(Loader *L, int k)
{
    const Spec *s = L->s;
    const SpecShape *sh = &s->shape[k];
    for (int j = 0; j < s->nshape; j++)
        if (j != k && s->shape[j].name && !strcmp(s->shape[j].name, sh->name))
            diag_error(sh->loc, "shape '%s' touches others in effect '%s', and shape '%s' at "
                       "line %d has its name: give each a `name:` of its own", sh->name,
                       L->sc.owner, sh->name, s->shape[j].loc.line);
    for (int b = 0; b < s->nbody; b++)
        if (b != sh->body && !strcmp(s->body[b].name, sh->name))
            diag_error(sh->loc, "shape '%s' touches others in effect '%s', and body '%s' has "
                       "its name: give it a `name:` of its own", sh->name, L->sc.owner,
                       sh->name);
}

/* Pair (a, b) found at node n (NULL: by the filters) of the item map:
 * one eomc has a gap for, of shapes that can move, placed, with a plane
 * if the item has friction; appended to f. */
static void
add_pair(Loader *L, SpecForce *f, int a, int b, yaml_node_t *n, yaml_node_t *map)
{
    const Spec *s = L->s;
    const SpecShape *sa = &s->shape[a], *sb = &s->shape[b];
    const char *effect = L->sc.owner;
    if (sa->body == sb->body || (sa->body >= s->nbody && sb->body >= s->nbody))
        diag_error(spec_loc(L, n), "'%s' and '%s' are shapes of %s: shapes of one body do not "
                   "touch each other", sa->name, sb->name, owner(L, a));
    const char *why = no_gap(sa->type, sb->type);
    if (why && n)
        diag_error(spec_loc(L, n), "no contact of %s ('%s') with %s ('%s'): %s", type_name[sa->type],
                   sa->name, type_name[sb->type], sb->name, why);
    if (why) { /* at the shape eomc cannot do */
        int bad = no_gap(sa->type, sa->type) ? a : b;
        diag_error(s->shape[bad].loc, "shape '%s' (%s) would touch '%s' (%s) by the filters of "
                   "effect '%s' (`contact: all`), and %s; give it `contype: 0` and "
                   "`conaffinity: 0` to draw it only, or list the pairs",
                   s->shape[bad].name, type_name[s->shape[bad].type],
                   s->shape[bad == a ? b : a].name, type_name[s->shape[bad == a ? b : a].type],
                   effect, why);
    }
    for (int e = 0; e < 2; e++) {
        int k = e ? b : a, body = s->shape[k].body;
        if (body < s->nbody && L->bad_body[body])
            diag_abandon(); /* its own error is reported */
        if (body < s->nbody && s->view.item[body].unturned)
            diag_error(n ? spec_loc(L, n) : s->shape[k].loc, "shape '%s' is on body '%s', which "
                       "is turned by `omega:` alone: nothing says where the shape is (place the "
                       "body by a `frame:`, or turn it by a `rotation:`)", s->shape[k].name,
                       s->body[body].name);
    }
    if (f->mu != EXPR_ZERO && sa->type != SPEC_SHAPE_PLANE && sb->type != SPEC_SHAPE_PLANE)
        diag_error(n ? spec_loc(L, n) : spec_key_loc(L, map, "friction"),
                   "effect '%s' has friction, and its pair '%s', '%s' has no plane: eomc's "
                   "contact friction acts between a plane and a shape (list the pairs with a "
                   "plane in an item with `friction:`, the others in one without)",
                   effect, sa->name, sb->name);
    for (int j = 0; j < f->npair; j++)
        if ((f->pair[2 * j] == a && f->pair[2 * j + 1] == b) ||
            (f->pair[2 * j] == b && f->pair[2 * j + 1] == a))
            diag_error(spec_loc(L, n), "the pair '%s', '%s' is listed twice (a force each time)",
                       sa->name, sb->name);
    f->pair[2 * f->npair] = a;
    f->pair[2 * f->npair + 1] = b;
    f->npair++;
}

/* A size of parameters of a shape that touches: > 0 with the values
 * --set gives too (a radius of 0 or less is no contact the law means). */
static void
require_sizes(Loader *L, int k, unsigned char *done)
{
    const SpecShape *sh = &L->s->shape[k];
    if (done[k]++)
        return;
    yaml_node_t *sz = spec_lookup(L, L->shape_node[k], "size");
    for (int j = 0; sz && j < NITEMS(sz); j++)
        if (sh->esize[j] != EXPR_NONE)
            spec_require(L, sh->esize[j], 1, spec_node(L, ITEMS(sz)[j]), 1,
                         "shape '%s': its size must be positive", sh->name);
}

/* The stiffness or damping at n (NULL: 0), of parameters, >= 0. */
static ExprId
coefficient(Loader *L, yaml_node_t *n, const char *what)
{
    if (!n)
        return EXPR_ZERO;
    ExprId e = spec_expr(L, n, ALLOW_PARAM, what);
    spec_require(L, e, 0, n, 1, "effect '%s': %s cannot be negative", L->sc.owner, what);
    return e;
}

void
spec_load_contact(Loader *L, yaml_node_t *map, SpecForce *f)
{
    const Spec *s = L->s;
    yaml_node_t *c = spec_lookup(L, map, "contact"), *v;
    if ((v = spec_lookup(L, map, "on")))
        diag_error(spec_key_loc(L, map, "on"), "a contact acts on the shapes of its pairs: "
                   "`on` belongs to a force or a torque");
    if (!spec_lookup(L, map, "stiffness"))
        diag_error(spec_loc(L, map), "a contact needs `stiffness: k`, its normal force's k in "
                   "N = max(0, k d + c d') for a penetration d");
    if (L->bad_shapes) /* (their errors are reported: which pairs there are is unknown) */
        diag_abandon();
    f->kind = FORCE_CONTACT;
    f->stiffness = coefficient(L, spec_lookup(L, map, "stiffness"), "a contact's stiffness");
    f->damping = coefficient(L, spec_lookup(L, map, "damping"), "a contact's damping");
    f->mu = coefficient(L, spec_lookup(L, map, "friction"), "a contact's friction coefficient");
    int ns = s->nshape;
    if (c->type == YAML_SCALAR_NODE) {
        const char *w = spec_scalar(L, c, "`contact:` (all, or a list of pairs [A, B])");
        if (strcmp(w, "all"))
            diag_error(spec_loc(L, c), "`contact:` is `all` (every pair the shapes' contype "
                       "and conaffinity let touch) or a list of pairs [A, B], not '%s'", w);
        f->pair = arena_new_array(L->A, int, ns * (ns - 1) + 1);
        for (int a = 0; a < ns; a++)
            for (int b = a + 1; b < ns; b++) {
                const SpecShape *sa = &s->shape[a], *sb = &s->shape[b];
                if (sa->body == sb->body || (sa->body >= s->nbody && sb->body >= s->nbody))
                    continue;
                if ((sa->contype & sb->conaffinity) || (sb->contype & sa->conaffinity))
                    add_pair(L, f, a, b, NULL, map);
            }
        if (!f->npair)
            diag_error(spec_loc(L, c), "`contact: all` finds no pair of shapes that can touch: "
                       "two shapes of different bodies (or of a body and the ground) touch "
                       "where one's contype and the other's conaffinity share a bit");
    } else {
        spec_expect(L, c, YAML_SEQUENCE_NODE, "`contact:` (all, or a list of pairs [A, B])");
        int *x = arena_new_array(L->A, int, ns + 1), *y = arena_new_array(L->A, int, ns + 1);
        f->pair = arena_new_array(L->A, int, 2 * NITEMS(c) * ns * ns + 1);
        for (int i = 0; i < NITEMS(c); i++) {
            yaml_node_t *p = spec_node(L, ITEMS(c)[i]);
            spec_expect(L, p, YAML_SEQUENCE_NODE, "a contact pair [A, B]");
            if (NITEMS(p) != 2)
                diag_error(spec_loc(L, p), "a contact pair is 2 names [A, B] (a shape, a body "
                           "or ground), not %d", NITEMS(p));
            int nx = shapes_named(L, spec_node(L, ITEMS(p)[0]), x);
            int ny = shapes_named(L, spec_node(L, ITEMS(p)[1]), y);
            for (int a = 0; a < nx; a++)
                for (int b = 0; b < ny; b++)
                    add_pair(L, f, x[a], y[b], p, map);
        }
        if (!f->npair)
            diag_error(spec_loc(L, c), "`contact:` lists no pair");
    }
    unsigned char *done = arena_new_array(L->A, unsigned char, ns + 1);
    for (int j = 0; j < 2 * f->npair; j++) {
        if (!done[f->pair[j]])
            unique_name(L, f->pair[j]);
        require_sizes(L, f->pair[j], done);
    }
}

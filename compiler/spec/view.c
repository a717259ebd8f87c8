/*
 * view: shapes, draw items and a scene's view (view.h).
 */
#include "view.h"

#include "checks.h"
#include "names.h"
#include "yaml.h"

#include <math.h>
#include <string.h>

static const char *const shape_types[] = {"box", "sphere", "capsule", "cylinder", "ellipsoid",
                                          "plane"};
enum { NSHAPE_TYPES = 6 };
static const int shape_sizes[] = {3, 1, 2, 2, 3, 0};
static const char *const shape_size_what[] = {
    "half-sizes", "radius", "radius and half-length", "radius and half-length", "semi-axes",
    "none"};
/* MuJoCo's contype and conaffinity are C ints */
#define MAX_FILTER 2147483647.0

/* A shape's size or position at n: a number, or an expression of the
 * parameters (*e; else EXPR_NONE), its number then their defaults'. */
static double
shape_number(Loader *L, yaml_node_t *n, const char *what, ExprId *e)
{
    *e = spec_expr(L, n, ALLOW_PARAM, what);
    double v;
    if (expr_is_const(L->P, *e, &v))
        *e = EXPR_NONE;
    else
        v = expr_eval(L->P, *e, &(ExprEnv){.p = spec_defaults(L)});
    if (!isfinite(v))
        diag_error(spec_loc(L, n), "%s is not a finite number (%g)", what, v);
    return v;
}

/* n numbers of a list at v, into out. */
static void
numbers(Loader *L, yaml_node_t *v, int n, const char *what, double *out)
{
    spec_expect(L, v, YAML_SEQUENCE_NODE, what);
    if (NITEMS(v) != n)
        diag_error(spec_loc(L, v), "%s has %d numbers, not %d", what, n, NITEMS(v));
    for (int k = 0; k < n; k++)
        out[k] = spec_number(L, spec_node(L, ITEMS(v)[k]), what);
}

/* A collision filter's bit mask at n: an integer from 0 to MAX_FILTER. */
static unsigned
filter(Loader *L, yaml_node_t *n, const char *what)
{
    double v = spec_number(L, n, what);
    if (!(v >= 0 && v <= MAX_FILTER && v == floor(v)))
        diag_error(spec_loc(L, n), "%s is a bit mask, an integer from 0 to %.0f, not %g", what,
                   MAX_FILTER, v);
    return (unsigned)v;
}

static void
load_shape(Loader *L, yaml_node_t *seq, int i)
{
    static const char *const keys[] = {"type", "size", "pos", "quat", "rgba", "name",
                                       "contype", "conaffinity", NULL};
    Spec *s = L->s;
    yaml_node_t *m = spec_map(L, spec_node(L, ITEMS(seq)[i]), "a shape");
    spec_check_keys(L, m, keys, "a shape");
    yaml_node_t *ty = spec_lookup(L, m, "type"), *sz = spec_lookup(L, m, "size");
    if (!ty)
        diag_error(spec_loc(L, m), "a shape has no type (box, sphere, capsule, cylinder, "
                   "ellipsoid or plane)");
    SpecShape sh = {.body = L->shape_body, .quat = {1, 0, 0, 0}, .rgba = {0.5, 0.6, 0.8, 1},
                    .esize = {EXPR_NONE, EXPR_NONE, EXPR_NONE},
                    .epos = {EXPR_NONE, EXPR_NONE, EXPR_NONE}, .contype = 1,
                    .conaffinity = 1, .loc = spec_loc(L, m)};
    sh.type = spec_find_in(L, ty, "shape type", "shape types", 1, (const char **)shape_types,
                           NSHAPE_TYPES);
    yaml_node_t *v;
    if ((v = spec_lookup(L, m, "name"))) {
        sh.name = arena_strdup(L->A, spec_scalar(L, v, "a shape's name"));
        if (!spec_is_identifier(sh.name))
            diag_error(spec_loc(L, v), "'%s' is not a valid shape name (letters, digits, _)",
                       sh.name);
    }
    if ((v = spec_lookup(L, m, "contype")))
        sh.contype = filter(L, v, "a shape's contype");
    if ((v = spec_lookup(L, m, "conaffinity")))
        sh.conaffinity = filter(L, v, "a shape's conaffinity");
    if (sh.type == SPEC_SHAPE_PLANE && L->shape_body < s->nbody)
        diag_error(spec_loc(L, ty), "a plane is a half-space fixed to the world: it belongs in "
                   "`ground:`, not in a body's shapes");
    if (sh.type == SPEC_SHAPE_PLANE && sz)
        diag_error(spec_loc(L, sz), "a plane has no size: it is the half-space below its pos, "
                   "across its quat's z axis, without end");
    if (!sz && sh.type != SPEC_SHAPE_PLANE)
        diag_error(spec_loc(L, m), "a %s has no size (its %s)", shape_types[sh.type],
                   shape_size_what[sh.type]);
    if (sz)
        spec_expect(L, sz, YAML_SEQUENCE_NODE, "a shape's size");
    int ns = shape_sizes[sh.type];
    if (sz && NITEMS(sz) != ns)
        diag_error(spec_loc(L, sz), "a %s's size is %d number%s (its %s), not %d",
                   shape_types[sh.type], ns, ns == 1 ? "" : "s", shape_size_what[sh.type],
                   NITEMS(sz));
    for (int k = 0; k < ns; k++) {
        yaml_node_t *e = spec_node(L, ITEMS(sz)[k]);
        sh.size[k] = shape_number(L, e, "a shape's size", &sh.esize[k]);
        if (!(sh.size[k] > 0))
            diag_error(spec_loc(L, e), "a shape's size must be positive, not %g%s", sh.size[k],
                       sh.esize[k] != EXPR_NONE ? " (with the parameters' defaults)" : "");
    }
    if ((v = spec_lookup(L, m, "pos"))) {
        spec_expect(L, v, YAML_SEQUENCE_NODE, "a shape's pos");
        if (NITEMS(v) != 3)
            diag_error(spec_loc(L, v), "a shape's pos has 3 numbers, not %d", NITEMS(v));
        for (int k = 0; k < 3; k++) {
            yaml_node_t *e = spec_node(L, ITEMS(v)[k]);
            sh.pos[k] = shape_number(L, e, "a shape's pos", &sh.epos[k]);
            if (sh.type == SPEC_SHAPE_PLANE && sh.epos[k] != EXPR_NONE)
                diag_error(spec_loc(L, e), "a plane's pos is numbers: the page draws the floor "
                           "where it is");
        }
    }
    if ((v = spec_lookup(L, m, "quat"))) {
        numbers(L, v, 4, "a shape's quat", sh.quat);
        double nq = sqrt(sh.quat[0] * sh.quat[0] + sh.quat[1] * sh.quat[1] +
                         sh.quat[2] * sh.quat[2] + sh.quat[3] * sh.quat[3]);
        if (!(nq > 0))
            diag_error(spec_loc(L, v), "a shape's quat [w, x, y, z] must not be zero");
        for (int k = 0; k < 4; k++)
            sh.quat[k] /= nq;
    }
    if ((v = spec_lookup(L, m, "rgba"))) {
        numbers(L, v, 4, "a shape's rgba", sh.rgba);
        for (int k = 0; k < 4; k++)
            if (sh.rgba[k] < 0 || sh.rgba[k] > 1)
                diag_error(spec_loc(L, spec_node(L, ITEMS(v)[k])),
                           "a shape's rgba is 4 numbers in [0, 1], not %g", sh.rgba[k]);
    }
    SpecShape *bigger = arena_new_array(L->A, SpecShape, s->nshape + 1);
    if (s->nshape)
        memcpy(bigger, s->shape, (size_t)s->nshape * sizeof *bigger);
    bigger[s->nshape++] = sh;
    s->shape = bigger;
    yaml_node_t **nodes = arena_new_array(L->A, yaml_node_t *, s->nshape);
    if (s->nshape > 1)
        memcpy(nodes, L->shape_node, (size_t)(s->nshape - 1) * sizeof *nodes);
    nodes[s->nshape - 1] = m;
    L->shape_node = nodes;
}

/* The shapes from `first` on that have no `name:` are their owner's:
 * `owner`, or owner.k (k from 1) where it has several. */
static void
default_names(Loader *L, int first, const char *owner)
{
    Spec *s = L->s;
    for (int k = first; k < s->nshape; k++)
        if (!s->shape[k].name)
            s->shape[k].name = s->nshape - first == 1
                                   ? owner
                                   : arena_printf(L->A, "%s.%d", owner, k - first + 1);
}

void
spec_load_shapes(Loader *L, yaml_node_t *seq, int body)
{
    spec_expect(L, seq, YAML_SEQUENCE_NODE, "a body's shapes (a list)");
    int first = L->s->nshape;
    for (int i = 0; i < NITEMS(seq); i++) {
        L->shape_body = body;
        L->bad_shapes |= !spec_checked(L, load_shape, seq, i);
    }
    default_names(L, first, L->s->body[body].name);
}

/* A name a shape is given is its own: a contact's pairs and its switches
 * are named by it, and a shape named as another body is would make a
 * pair's name mean two things.  (The names it takes from its body are
 * checked where a contact uses them: spec/contacts.c.) */
static void
check_shape_names(Loader *L)
{
    const Spec *s = L->s;
    for (int k = 0; k < s->nshape; k++) {
        const SpecShape *sh = &s->shape[k];
        if (!sh->name || !spec_lookup(L, L->shape_node[k], "name"))
            continue;
        for (int j = 0; j < s->nshape; j++)
            if (j != k && s->shape[j].name && !strcmp(s->shape[j].name, sh->name))
                diag_error(sh->loc, "two shapes are named '%s' (the other at line %d): give "
                           "each a `name:` of its own", sh->name, s->shape[j].loc.line);
        for (int b = 0; b < s->nbody; b++)
            if (b != sh->body && !strcmp(s->body[b].name, sh->name))
                diag_error(sh->loc, "shape '%s' is named as body '%s' is: give it a `name:` "
                           "of its own", sh->name, s->body[b].name);
    }
}

/* The page's floor where the ground has a plane facing up (+z): its
 * height, the first such plane's. */
static void
plane_floor(Loader *L, int first)
{
    Spec *s = L->s;
    for (int k = first; k < s->nshape; k++) {
        const SpecShape *sh = &s->shape[k];
        const double *e = sh->quat; /* the normal, e's z axis: exactly up only if e turns about z */
        double nx = 2 * (e[1] * e[3] + e[0] * e[2]), ny = 2 * (e[2] * e[3] - e[0] * e[1]);
        double nz = 1 - 2 * (e[1] * e[1] + e[2] * e[2]);
        if (sh->type == SPEC_SHAPE_PLANE && nx == 0 && ny == 0 && nz > 0) {
            s->view.floor = sh->pos[2];
            L->floor_plane = k;
            return;
        }
    }
}

void
spec_draw_items(Loader *L, yaml_node_t *ground)
{
    Spec *s = L->s;
    SpecView *v = &s->view;
    v->nitem = s->nbody + s->npart;
    v->item = arena_new_array(L->A, SpecDrawItem, v->nitem + 2);
    v->follow = -1;
    L->floor_plane = -1;
    int planar = v->nitem > 0;
    for (int i = 0; i < s->nbody; i++) {
        const SpecBody *b = &s->body[i];
        int turns = 0; /* by omega alone: nothing says where it points */
        for (int k = 0; k < 3; k++)
            turns |= b->omega[k] != EXPR_ZERO;
        int unturned = turns && b->frame < 0 && !b->has_rot && b->angle == EXPR_NONE;
        v->item[i] = (SpecDrawItem){b->name, SPEC_DRAW_BODY, i, b->dim, unturned};
        planar &= b->dim == 2;
    }
    for (int i = 0; i < s->npart; i++) {
        v->item[s->nbody + i] = (SpecDrawItem){s->part[i].name, SPEC_DRAW_PARTICLE, i,
                                               s->part[i].dim, 0};
        planar &= s->part[i].dim == 2;
    }
    if (ground && !spec_is_null(ground)) {
        /* an item of its own, drawn as a body that never moves: at the
         * world's origin, in its axes (in the plane where all is planar) */
        spec_expect(L, ground, YAML_SEQUENCE_NODE, "`ground:` (a list of shapes)");
        int k = v->nitem, before = s->nshape, drawn = 0;
        for (int i = 0; i < NITEMS(ground); i++) {
            L->shape_body = k;
            L->bad_shapes |= !spec_checked(L, load_shape, ground, i);
        }
        for (int j = before; j < s->nshape; j++) /* (a plane is not drawn: it is the floor) */
            drawn += s->shape[j].type != SPEC_SHAPE_PLANE;
        if (drawn)
            v->item[v->nitem++] = (SpecDrawItem){"ground", SPEC_DRAW_GROUND, 0, planar ? 2 : 3,
                                                 0};
        default_names(L, before, "ground");
        if (!planar)
            plane_floor(L, before);
    }
    check_shape_names(L);
    s->place = arena_new_array(L->A, SpecDrawItem, s->nbody + s->npart + L->ndef + 1);
    for (int i = 0; i < s->nbody + s->npart; i++)
        s->place[s->nplace++] = v->item[i];
    for (int k = 0; k < L->ndef; k++)
        if (L->def[k].kind != ITEM_DEFINE && !L->def[k].bad)
            s->place[s->nplace++] = (SpecDrawItem){L->def[k].name, L->def[k].kind == ITEM_FRAME
                                                   ? SPEC_DRAW_FRAME : SPEC_DRAW_POINT,
                                                   L->def[k].kin, 3, 0};
}

/* The item that name n stands for in v, added if it is a point or a frame
 * not yet drawn. */
static int
item_of(Loader *L, SpecView *v, yaml_node_t *n)
{
    const char *name = spec_scalar(L, n, "a name to draw");
    for (int k = 0; k < v->nitem; k++) /* (the ground is no name of the spec's) */
        if (v->item[k].kind != SPEC_DRAW_GROUND && !strcmp(v->item[k].name, name))
            return k;
    int kind = -1, index = 0;
    if (!strcmp(name, "origin")) {
        kind = SPEC_DRAW_POINT, index = KIN_ORIGIN;
    } else {
        Name *nm = spec_find_name(L, name);
        if (nm && (nm->kind == NAME_POINT || nm->kind == NAME_FRAME)) {
            kind = nm->kind == NAME_POINT ? SPEC_DRAW_POINT : SPEC_DRAW_FRAME;
            index = spec_item(L, nm)->kin;
        }
    }
    if (kind < 0) { /* an error: which names could be drawn */
        const char **cands = arena_new_array(L->A, const char *, v->nitem + L->ndef + 1);
        int nc = 0;
        for (int k = 0; k < v->nitem; k++)
            if (v->item[k].kind != SPEC_DRAW_GROUND)
                cands[nc++] = v->item[k].name;
        cands[nc++] = "origin";
        for (int k = 0; k < L->ndef; k++)
            if (L->def[k].kind == ITEM_FRAME || L->def[k].kind == ITEM_POINT)
                cands[nc++] = L->def[k].name;
        spec_find_in(L, n, "thing to draw (a body, particle, point, frame or origin)",
                     "things to draw", 0, cands, nc);
    }
    SpecDrawItem *bigger = arena_new_array(L->A, SpecDrawItem, v->nitem + 1);
    memcpy(bigger, v->item, (size_t)v->nitem * sizeof *bigger);
    bigger[v->nitem] = (SpecDrawItem){arena_strdup(L->A, name), kind, index, 3, 0};
    v->item = bigger;
    return v->nitem++;
}

/* Is every body and particle planar?  (The page then looks at z = 0.) */
static int
is_planar(const SpecView *v)
{
    int planar = v->nitem > 0;
    for (int k = 0; k < v->nitem; k++)
        if (v->item[k].kind == SPEC_DRAW_BODY || v->item[k].kind == SPEC_DRAW_PARTICLE)
            planar &= v->item[k].dim == 2;
    return planar;
}

static void
load_camera(Loader *L, yaml_node_t *m, SpecView *v)
{
    static const char *const keys[] = {"position", "target", "up", NULL};
    spec_map(L, m, "the camera");
    spec_check_keys(L, m, keys, "the camera");
    static const char *const what[] = {"the camera's position", "the camera's target",
                                       "the camera's up"};
    int planar = is_planar(v);
    double up[3] = {0, planar, !planar};
    memcpy(v->camera + 6, up, sizeof up);
    for (int j = 0; j < 3; j++) {
        yaml_node_t *n = spec_lookup(L, m, keys[j]);
        if (!n && j < 2)
            diag_error(spec_loc(L, m), "the camera has no %s", keys[j]);
        if (n)
            numbers(L, n, 3, what[j], v->camera + 3 * j);
    }
    if (v->camera[6] == 0 && v->camera[7] == 0 && v->camera[8] == 0)
        diag_error(spec_key_loc(L, m, "up"), "the camera's up must not be zero");
    v->has_camera = 1;
}

static void
load_view(Loader *L, yaml_node_t *m, SpecView *v)
{
    static const char *const keys[] = {"links", "trace", "frames", "camera", "follow",
                                       "floor", NULL};
    spec_map(L, m, "a view");
    spec_check_keys(L, m, keys, "a view");
    yaml_node_t *n;
    if ((n = spec_lookup(L, m, "links")) && !spec_is_null(n)) {
        spec_expect(L, n, YAML_SEQUENCE_NODE, "the view's links: [[A, B], ...]");
        v->nlink = NITEMS(n);
        v->link = arena_new_array(L->A, int, 2 * v->nlink + 1);
        for (int i = 0; i < v->nlink; i++) {
            yaml_node_t *pair = spec_node(L, ITEMS(n)[i]);
            spec_expect(L, pair, YAML_SEQUENCE_NODE, "a link: [A, B]");
            if (NITEMS(pair) != 2)
                diag_error(spec_loc(L, pair), "a link joins 2 things, [A, B], not %d",
                           NITEMS(pair));
            for (int e = 0; e < 2; e++)
                v->link[2 * i + e] = item_of(L, v, spec_node(L, ITEMS(pair)[e]));
        }
    }
    if ((n = spec_lookup(L, m, "trace")) && !spec_is_null(n)) {
        spec_expect(L, n, YAML_SEQUENCE_NODE, "the view's traces: [A, ...]");
        v->ntrace = NITEMS(n);
        v->trace = arena_new_array(L->A, int, v->ntrace + 1);
        for (int i = 0; i < v->ntrace; i++)
            v->trace[i] = item_of(L, v, spec_node(L, ITEMS(n)[i]));
    }
    if ((n = spec_lookup(L, m, "frames"))) {
        if (n->type == YAML_SEQUENCE_NODE) {
            for (int i = 0; i < NITEMS(n); i++) {
                yaml_node_t *e = spec_node(L, ITEMS(n)[i]);
                int k = item_of(L, v, e);
                if (v->item[k].kind != SPEC_DRAW_FRAME)
                    diag_error(spec_loc(L, e), "'%s' is not a frame: `frames:` draws frames' "
                               "axes", v->item[k].name);
            }
            v->frames = 1;
        } else {
            const char *b = spec_scalar(L, n, "`frames:` (true, false or a list of frames)");
            if (!strcmp(b, "true"))
                v->frames = 2; /* every frame's axes, and each body's own */
            else if (strcmp(b, "false"))
                diag_error(spec_loc(L, n), "`frames:` is true, false or a list of frames, "
                           "not '%s'", b);
            for (int k = 0; v->frames && k < L->ndef; k++) /* every frame of the spec */
                if (L->def[k].kind == ITEM_FRAME) {
                    int seen = 0;
                    for (int j = 0; j < v->nitem; j++)
                        seen |= v->item[j].kind != SPEC_DRAW_GROUND &&
                                !strcmp(v->item[j].name, L->def[k].name);
                    if (seen)
                        continue;
                    Name *nm = spec_find_name(L, L->def[k].name);
                    SpecDrawItem *bigger = arena_new_array(L->A, SpecDrawItem, v->nitem + 1);
                    memcpy(bigger, v->item, (size_t)v->nitem * sizeof *bigger);
                    bigger[v->nitem++] = (SpecDrawItem){L->def[k].name, SPEC_DRAW_FRAME,
                                                        spec_item(L, nm)->kin, 3, 0};
                    v->item = bigger;
                }
        }
    }
    if ((n = spec_lookup(L, m, "camera")))
        load_camera(L, n, v);
    if ((n = spec_lookup(L, m, "follow")) && !spec_is_null(n))
        v->follow = item_of(L, v, n);
    if ((n = spec_lookup(L, m, "floor"))) {
        if (is_planar(v))
            diag_error(spec_key_loc(L, m, "floor"), "`floor:` is for a 3-D page: a planar "
                       "page's grid is the plane of the motion, z = 0");
        double h = spec_number(L, n, "the floor's height");
        if (L->floor_plane >= 0 && h != v->floor) /* a floor drawn off the one things rest on */
            diag_error(spec_loc(L, n), "the floor is the ground's plane '%s', at z = %g: a "
                       "floor at %g would not be where things rest (leave `floor:` out)",
                       L->s->shape[L->floor_plane].name, v->floor, h);
        v->floor = h;
    }
}

void
spec_load_view(Loader *L, yaml_node_t *v, int live)
{
    SpecView scratch = L->s->view;
    load_view(L, v, live ? &L->s->view : &scratch);
}

/*
 * view: shapes, draw items and a scene's view (view.h).
 */
#include "view.h"

#include "checks.h"
#include "names.h"
#include "yaml.h"

#include <math.h>
#include <string.h>

static const char *const shape_types[] = {"box", "sphere", "capsule", "cylinder", "ellipsoid"};
static const int shape_sizes[] = {3, 1, 2, 2, 3};
static const char *const shape_size_what[] = {
    "half-sizes", "radius", "radius and half-length", "radius and half-length", "semi-axes"};

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

static void
load_shape(Loader *L, yaml_node_t *seq, int i)
{
    static const char *const keys[] = {"type", "size", "pos", "quat", "rgba", NULL};
    Spec *s = L->s;
    yaml_node_t *m = spec_map(L, spec_node(L, ITEMS(seq)[i]), "a shape");
    spec_check_keys(L, m, keys, "a shape");
    yaml_node_t *ty = spec_lookup(L, m, "type"), *sz = spec_lookup(L, m, "size");
    if (!ty)
        diag_error(spec_loc(L, m), "a shape has no type (box, sphere, capsule, cylinder or "
                   "ellipsoid)");
    SpecShape sh = {.body = L->shape_body, .quat = {1, 0, 0, 0}, .rgba = {0.5, 0.6, 0.8, 1},
                    .esize = {EXPR_NONE, EXPR_NONE, EXPR_NONE},
                    .epos = {EXPR_NONE, EXPR_NONE, EXPR_NONE}};
    sh.type = spec_find_in(L, ty, "shape type", "shape types", 1, (const char **)shape_types, 5);
    if (!sz)
        diag_error(spec_loc(L, m), "a %s has no size (its %s)", shape_types[sh.type],
                   shape_size_what[sh.type]);
    spec_expect(L, sz, YAML_SEQUENCE_NODE, "a shape's size");
    int ns = shape_sizes[sh.type];
    if (NITEMS(sz) != ns)
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
    yaml_node_t *v;
    if ((v = spec_lookup(L, m, "pos"))) {
        spec_expect(L, v, YAML_SEQUENCE_NODE, "a shape's pos");
        if (NITEMS(v) != 3)
            diag_error(spec_loc(L, v), "a shape's pos has 3 numbers, not %d", NITEMS(v));
        for (int k = 0; k < 3; k++)
            sh.pos[k] = shape_number(L, spec_node(L, ITEMS(v)[k]), "a shape's pos",
                                     &sh.epos[k]);
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
}

void
spec_load_shapes(Loader *L, yaml_node_t *seq, int body)
{
    spec_expect(L, seq, YAML_SEQUENCE_NODE, "a body's shapes (a list)");
    for (int i = 0; i < NITEMS(seq); i++) {
        L->shape_body = body;
        spec_checked(L, load_shape, seq, i);
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
        int k = v->nitem, before = s->nshape;
        for (int i = 0; i < NITEMS(ground); i++) {
            L->shape_body = k;
            spec_checked(L, load_shape, ground, i);
        }
        if (s->nshape > before)
            v->item[v->nitem++] = (SpecDrawItem){"ground", SPEC_DRAW_GROUND, 0, planar ? 2 : 3,
                                                 0};
    }
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
        v->floor = spec_number(L, n, "the floor's height");
    }
}

void
spec_load_view(Loader *L, yaml_node_t *v, int live)
{
    SpecView scratch = L->s->view;
    load_view(L, v, live ? &L->s->view : &scratch);
}

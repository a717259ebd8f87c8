/*
 * frames: frames, points and defines (frames.h).
 */
#include "frames.h"

#include "checks.h"

#include <stdio.h>
#include <string.h>

/* The Euler parameters [e0, e1, e2, e3] at v, of `owner` ("body 'top'"):
 * four distinct coordinates, none another quaternion's, into q. */
void
spec_quaternion_coords(Loader *L, yaml_node_t *v, const char *owner, int q[4])
{
    spec_expect(L, v, YAML_SEQUENCE_NODE, "the Euler parameters of a rotation");
    if (NITEMS(v) != 4)
        diag_error(spec_loc(L, v), "a quaternion has 4 Euler parameters [e0, e1, e2, e3] "
                   "(scalar first), not %d", (int)NITEMS(v));
    for (int i = 0; i < 4; i++) {
        yaml_node_t *n = spec_node(L, ITEMS(v)[i]);
        const char *name = spec_scalar(L, n, "an Euler parameter");
        Name *nm = spec_find_name(L, name);
        if (!nm || nm->kind != NAME_COORD)
            diag_error(spec_loc(L, n), "the Euler parameters of a quaternion are coordinates, "
                       "and '%s' is not one (list it in `coordinates:`)", name);
        for (int j = 0; j < i; j++)
            if (q[j] == nm->index)
                diag_error(spec_loc(L, n), "'%s' is already an Euler parameter of this "
                           "quaternion", name);
        if (L->quat_of[nm->index])
            diag_error(spec_loc(L, n), "'%s' is already an Euler parameter of %s", name,
                       L->quat_of[nm->index]);
        q[i] = nm->index;
    }
    for (int i = 0; i < 4; i++)
        L->quat_of[q[i]] = owner;
}

/* ---- speeds ---- */

/* The `speeds:` beside a `quaternion:` in map m (a turn, a rotation), or
 * NULL. */
static yaml_node_t *
speeds_of(Loader *L, yaml_node_t *m)
{
    if (!m || m->type != YAML_MAPPING_NODE || !spec_lookup(L, m, "quaternion"))
        return NULL;
    return spec_lookup(L, m, "speeds");
}

/* Speed k's name at n, or only count it (L->s->speed NULL). */
static void
name_speed(Loader *L, yaml_node_t *n, int k)
{
    Spec *s = L->s;
    if (!s->speed || n->type != YAML_SCALAR_NODE)
        return;
    s->speed[k] = (SpecSpeed){spec_add_name(L, n, NAME_SPEED, k), spec_loc(L, n), EXPR_ZERO};
}

static int
scan_speeds(Loader *L, yaml_node_t *sp, int k)
{
    if (!sp || sp->type != YAML_SEQUENCE_NODE)
        return k;
    for (int i = 0; i < NITEMS(sp); i++)
        name_speed(L, spec_node(L, ITEMS(sp)[i]), k++);
    return k;
}

/* Every speed of the frames' turns and the bodies' rotations, counted
 * (L->s->speed NULL) or named, speed k the k-th met: all names are known
 * before any expression is read (names.h).  Malformed lists are left to
 * the frame or body they are in.  Returns how many. */
static int
all_speeds(Loader *L, yaml_node_t *frames, yaml_node_t *bodies)
{
    int k = 0;
    for (int i = 0; frames && frames->type == YAML_MAPPING_NODE && i < NPAIRS(frames); i++) {
        yaml_node_t *f = spec_node(L, PAIRS(frames)[i].value), *r;
        if (f->type != YAML_MAPPING_NODE || !(r = spec_lookup(L, f, "rotation")))
            continue;
        if (r->type == YAML_MAPPING_NODE)
            k = scan_speeds(L, speeds_of(L, r), k);
        for (int j = 0; r->type == YAML_SEQUENCE_NODE && j < NITEMS(r); j++)
            k = scan_speeds(L, speeds_of(L, spec_node(L, ITEMS(r)[j])), k);
    }
    for (int i = 0; bodies && bodies->type == YAML_MAPPING_NODE && i < NPAIRS(bodies); i++) {
        yaml_node_t *b = spec_node(L, PAIRS(bodies)[i].value), *r;
        if (b->type == YAML_MAPPING_NODE && (r = spec_lookup(L, b, "rotation")))
            k = scan_speeds(L, speeds_of(L, r), k);
    }
    return k;
}

int
spec_count_speeds(Loader *L, yaml_node_t *frames, yaml_node_t *bodies)
{
    return all_speeds(L, frames, bodies);
}

void
spec_name_speeds(Loader *L, yaml_node_t *frames, yaml_node_t *bodies)
{
    Spec *s = L->s;
    s->speed = NULL;
    int n = all_speeds(L, frames, bodies);
    s->speed = arena_new_array(L->A, SpecSpeed, n + 1);
    s->nspeed = all_speeds(L, frames, bodies);
}

/* `speeds: [wx, wy, wz]` beside the quaternion q of `owner` (sp, the
 * list; named by spec_name_speeds): its angular velocity in the turned
 * axes, w, and the Euler parameters' rates e' = 1/2 e (x) (0, w) from
 * them, so that |e| keeps its value and no constraint is needed. */
void
spec_quaternion_speeds(Loader *L, yaml_node_t *sp, const int q[4], int *first, ExprId w[3])
{
    Spec *s = L->s;
    spec_expect(L, sp, YAML_SEQUENCE_NODE, "the speeds of a quaternion");
    if (NITEMS(sp) != 3)
        diag_error(spec_loc(L, sp), "a quaternion has 3 speeds [wx, wy, wz], its angular "
                   "velocity in its own turned axes, not %d", (int)NITEMS(sp));
    for (int i = 0; i < 3; i++) {
        yaml_node_t *n = spec_node(L, ITEMS(sp)[i]);
        Name *nm = spec_find_name(L, spec_scalar(L, n, "a speed's name"));
        if (!nm || nm->kind != NAME_SPEED || nm->loc.line != spec_loc(L, n).line ||
            nm->loc.col != spec_loc(L, n).col)
            diag_unreachable(); /* all_speeds named it here */
        if (i == 0)
            *first = nm->index;
        w[i] = expr_var(L->P, s->nq + nm->index, 1);
    }
    ExprId e[4], ed[4];
    for (int c = 0; c < 4; c++)
        e[c] = expr_var(L->P, q[c], 0);
    kin_quat_rates(L->P, e, w, ed);
    for (int c = 0; c < 4; c++)
        expr_set_rate(L->P, q[c], ed[c]);
}

/* A frame's turn {quaternion: [e0, e1, e2, e3]} (t, its map; v, the
 * list), and its `speeds:` (sp, or NULL): the Euler parameters are
 * coordinates, kept in Spec.fquat for the unit constraint and the inertia
 * along e (mech.c), as a body's are, or turned by the speeds. */
static void
frame_quaternion(Loader *L, int f, const char *name, yaml_node_t *t, yaml_node_t *v,
                 yaml_node_t *sp)
{
    Spec *s = L->s;
    SpecQuat fq = {name, arena_printf(L->A, "frame '%s'", name), {-1, -1, -1, -1},
                   spec_loc(L, spec_node(L, PAIRS(t)[0].key)), -1};
    spec_quaternion_coords(L, v, fq.owner, fq.q);
    ExprId e[4], w[3];
    for (int k = 0; k < 4; k++)
        e[k] = expr_var(L->P, fq.q[k], 0);
    if (sp) {
        spec_quaternion_speeds(L, sp, fq.q, &fq.speed, w);
        kin_turn_quaternion_speeds(L->K, f, e, w);
    } else {
        kin_turn_quaternion(L->K, f, e);
    }
    if (s->nfquat == L->capfquat) {
        L->capfquat = L->capfquat ? 2 * L->capfquat : 4;
        SpecQuat *more = arena_new_array(L->A, SpecQuat, L->capfquat);
        if (s->nfquat)
            memcpy(more, s->fquat, (size_t)s->nfquat * sizeof *more);
        s->fquat = more;
    }
    s->fquat[s->nfquat++] = fq;
}

/* One turn of a frame's rotation: {x: ANGLE} (or y, z), about its own
 * axis as turned so far, or {axis: [ax, ay, az], angle: ANGLE} about a
 * fixed direction in those axes (any length but zero). */
static void
frame_turn(Loader *L, int f, const char *name, yaml_node_t *t)
{
    static const char *const keys[] = {"x", "y", "z", "axis", "angle", "quaternion", "speeds",
                                       NULL};
    spec_map(L, t, "a turn");
    spec_check_keys(L, t, keys, "a turn");
    yaml_node_t *qn = spec_lookup(L, t, "quaternion"), *sp = speeds_of(L, t);
    if (qn) {
        if (NPAIRS(t) != 1 + !!sp)
            diag_error(spec_loc(L, t), "a turn by a quaternion is {quaternion: [e0, e1, e2, "
                       "e3]}, with its speeds {..., speeds: [wx, wy, wz]} or alone");
        frame_quaternion(L, f, name, t, qn, sp);
        return;
    }
    if (spec_lookup(L, t, "speeds"))
        diag_error(spec_loc(L, spec_lookup(L, t, "speeds")), "`speeds:` are a quaternion's: "
                   "{quaternion: [e0, e1, e2, e3], speeds: [wx, wy, wz]}");
    yaml_node_t *ax = spec_lookup(L, t, "axis"), *ang = spec_lookup(L, t, "angle");
    if (ax || ang) {
        if (!ax || !ang || NPAIRS(t) != 2)
            diag_error(spec_loc(L, t), "a turn about a fixed direction is {axis: [ax, ay, az], "
                       "angle: ANGLE}");
        ExprId a[3];
        if (spec_vector(L, ax, ALLOW_PARAM, "an axis", a) != 3)
            diag_error(spec_loc(L, ax), "an axis has 3 components, in the frame's axes as "
                       "turned so far");
        ExprId n2 = EXPR_ZERO;
        for (int k = 0; k < 3; k++)
            n2 = expr_add(L->P, n2, expr_mul(L->P, a[k], a[k]));
        if (n2 == EXPR_ZERO)
            diag_error(spec_loc(L, ax), "an axis cannot be zero");
        AxisCheck *c = arena_new_array(L->A, AxisCheck, 1);
        *c = (AxisCheck){n2, ax, name, L->axes};
        L->axes = c;
        ExprId len = expr_unary(L->P, EXPR_SQRT, n2);
        for (int k = 0; k < 3; k++)
            a[k] = expr_div(L->P, a[k], len);
        kin_turn(L->K, f, a, spec_expr(L, ang, ALLOW_POSITION, "an angle"));
        return;
    }
    if (NPAIRS(t) != 1)
        diag_error(spec_loc(L, t), "a turn is one of {x: ANGLE}, {y: ANGLE}, {z: ANGLE}, "
                   "{axis: [ax, ay, az], angle: ANGLE} or {quaternion: [e0, e1, e2, e3]}");
    const char *k = spec_key(L, &PAIRS(t)[0]);
    kin_turn_axis(L->K, f, k[0] - 'x',
                  spec_expr(L, spec_node(L, PAIRS(t)[0].value), ALLOW_POSITION, "an angle"));
}

/* FRAME: {parent: FRAME, rotation: [TURN, ...], origin: POINT}, every key
 * optional (the world, no turn, no origin). */
static void
build_frame(Loader *L, Define *d)
{
    static const char *const keys[] = {"parent", "rotation", "origin", NULL};
    yaml_node_t *m = d->node, *v;
    int parent = KIN_WORLD;
    if (!spec_is_null(m)) {
        spec_map(L, m, "a frame");
        spec_check_keys(L, m, keys, "a frame");
    }
    if (!spec_is_null(m) && (v = spec_lookup(L, m, "parent")))
        parent = spec_frame_or_point(L, spec_scalar(L, v, "a frame"), NAME_FRAME, spec_loc(L, v));
    int f = kin_frame(L->K, parent);
    if (!spec_is_null(m) && (v = spec_lookup(L, m, "rotation"))) {
        if (v->type == YAML_MAPPING_NODE) {
            frame_turn(L, f, d->name, v);
        } else {
            spec_expect(L, v, YAML_SEQUENCE_NODE, "a frame's rotation (a list of turns)");
            for (int i = 0; i < NITEMS(v); i++)
                frame_turn(L, f, d->name, spec_node(L, ITEMS(v)[i]));
        }
    }
    if (!spec_is_null(m) && (v = spec_lookup(L, m, "origin")))
        kin_set_origin(L->K, f, spec_frame_or_point(L, spec_scalar(L, v, "a point"), NAME_POINT,
                                               spec_loc(L, v)));
    d->kin = f;
}

/* A point's offset written as a vector expression: vec(F, a, b, c) is
 * the offset [a, b, c] in F's axes (as {frame: F, at: [a, b, c]}, so that
 * velocities keep the links' structure, kin.h); any other vector, such as
 * -R*world.z or pos(Q) - pos(P), is its world components. */
static void
offset_expression(Loader *L, yaml_node_t *m, yaml_node_t *v, int *f, ExprId at[3])
{
    for (int i = 0; i < NPAIRS(m); i++)
        if (!strcmp(spec_key(L, &PAIRS(m)[i]), "frame"))
            diag_error(spec_loc(L, spec_node(L, PAIRS(m)[i].key)), "a point's offset "
                       "written as a vector expression takes no `frame:` (vec(F, a, b, c) is "
                       "in F's axes, any other vector in the world's); with `frame:`, give "
                       "the offset as components [a, b, c] in that frame's axes");
    Scalar sc;
    spec_scalar_src(L, &sc, v, "a point's offset");
    L->sc.allow = ALLOW_POSITION;
    L->sc.what = "a point's offset";
    if (!parse_frame_vector(&L->sc, &sc.src, f, at)) {
        *f = KIN_WORLD;
        parse_vector(&L->sc, &sc.src, at);
    }
}

/* POINT: {frame: FRAME, from: POINT, at: [x, y, z]}: at from, offset by
 * at in the frame's axes; every key optional (the world, its origin,
 * [0, 0, 0]).  An offset of 2 components has z = 0.  `at` may instead be
 * a vector expression (offset_expression). */
static void
build_point(Loader *L, Define *d)
{
    static const char *const keys[] = {"frame", "from", "at", NULL};
    yaml_node_t *m = d->node, *v;
    int f = KIN_WORLD, from = KIN_ORIGIN;
    ExprId at[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    if (!spec_is_null(m)) {
        spec_map(L, m, "a point");
        spec_check_keys(L, m, keys, "a point");
        if ((v = spec_lookup(L, m, "frame")))
            f = spec_frame_or_point(L, spec_scalar(L, v, "a frame"), NAME_FRAME, spec_loc(L, v));
        if ((v = spec_lookup(L, m, "from")))
            from = spec_frame_or_point(L, spec_scalar(L, v, "a point"), NAME_POINT, spec_loc(L, v));
        if ((v = spec_lookup(L, m, "at")) && v->type == YAML_SCALAR_NODE && !spec_is_null(v))
            offset_expression(L, m, v, &f, at);
        else if (v)
            spec_vector(L, v, ALLOW_POSITION, "a point's offset", at);
    }
    d->kin = kin_point(L->K, from, f, at);
}

/* ---- the items, in the order their uses need ---- */

/* Item `at` of L->def, the i-th pair of map, a define, frame or point. */
static void
name_item(Loader *L, yaml_node_t *map, int i, int at, ItemKind kind)
{
    static const NameKind kinds[] = {NAME_DEFINE, NAME_FRAME, NAME_POINT};
    Define *d = &L->def[at];
    d->kind = kind;
    d->node = spec_node(L, PAIRS(map)[i].value);
    d->value = (ParseVal){0, {EXPR_NONE, EXPR_NONE, EXPR_NONE}};
    yaml_node_t *k = spec_node(L, PAIRS(map)[i].key);
    const char *name = spec_scalar(L, k, "a name");
    if (kind == ITEM_FRAME && !strcmp(name, "world"))
        diag_error(spec_loc(L, k), "'world' is the inertial frame, there from the start: "
                   "name this frame otherwise");
    if (kind == ITEM_POINT && !strcmp(name, "origin"))
        diag_error(spec_loc(L, k), "'origin' is the world's origin, there from the start: "
                   "name this point otherwise");
    d->name = spec_add_name(L, k, kinds[kind], at);
}

static void
name_define(Loader *L, yaml_node_t *map, int i)
{
    name_item(L, map, i, i, ITEM_DEFINE);
}

static void
name_frame(Loader *L, yaml_node_t *map, int i)
{
    name_item(L, map, i, L->nitem_defs + i, ITEM_FRAME);
}

static void
name_point(Loader *L, yaml_node_t *map, int i)
{
    name_item(L, map, i, L->nitem_defs + L->nframes + i, ITEM_POINT);
}

/* Every define, frame and point named, as items of L->def. */
void
spec_name_items(Loader *L, yaml_node_t *defines, yaml_node_t *frames, yaml_node_t *points)
{
    L->nitem_defs = defines ? NPAIRS(defines) : 0;
    L->nframes = frames ? NPAIRS(frames) : 0;
    L->npoints = points ? NPAIRS(points) : 0;
    L->ndef = L->nitem_defs + L->nframes + L->npoints;
    L->def = arena_new_array(L->A, Define, L->ndef + 1);
    for (int i = 0; i < L->nitem_defs; i++)
        spec_checked(L, name_define, defines, i);
    for (int i = 0; i < L->nframes; i++)
        spec_checked(L, name_frame, frames, i);
    for (int i = 0; i < L->npoints; i++)
        spec_checked(L, name_point, points, i);
    L->K = kin_new(L->A, L->P, L->sc.D, L->nframes, L->npoints);
    L->sc.K = L->K;
    L->s->kin = L->K;
}

typedef struct DepCollect {
    Loader *L;
    Define *d;
    yaml_node_t *node; /* the scalar being read */
    int cap;
} DepCollect;

static void
collect_dep(void *ctx, const char *name, size_t len, size_t off)
{
    DepCollect *c = ctx;
    char buf[80];
    if (len >= sizeof buf)
        return;
    memcpy(buf, name, len);
    buf[len] = '\0';
    Name *nm = spec_find_name(c->L, buf);
    if (!nm || (nm->kind != NAME_DEFINE && nm->kind != NAME_FRAME && nm->kind != NAME_POINT))
        return;
    Define *d = c->d;
    if (d->ndeps == c->cap) {
        int cap = c->cap ? 2 * c->cap : 8;
        int *deps = arena_new_array(c->L->A, int, cap);
        size_t *offs = arena_new_array(c->L->A, size_t, cap);
        yaml_node_t **nodes = arena_new_array(c->L->A, yaml_node_t *, cap);
        if (d->ndeps) {
            memcpy(deps, d->deps, sizeof *deps * (size_t)d->ndeps);
            memcpy(offs, d->dep_off, sizeof *offs * (size_t)d->ndeps);
            memcpy(nodes, d->dep_node, sizeof *nodes * (size_t)d->ndeps);
        }
        d->deps = deps, d->dep_off = offs, d->dep_node = nodes, c->cap = cap;
    }
    d->deps[d->ndeps] = nm->index;
    d->dep_node[d->ndeps] = c->node;
    d->dep_off[d->ndeps++] = off;
}

/* The names in every scalar under n (a mapping's values, not its keys). */
static void
collect_deps(DepCollect *c, yaml_node_t *n)
{
    Loader *L = c->L;
    if (n->type == YAML_SCALAR_NODE) {
        Scalar sc;
        spec_scalar_src(L, &sc, n, "a name");
        c->node = n;
        parse_names(&sc.src, collect_dep, c);
    } else if (n->type == YAML_SEQUENCE_NODE) {
        for (int i = 0; i < NITEMS(n); i++)
            collect_deps(c, spec_node(L, ITEMS(n)[i]));
    } else if (n->type == YAML_MAPPING_NODE) {
        for (int i = 0; i < NPAIRS(n); i++)
            collect_deps(c, spec_node(L, PAIRS(n)[i].value));
    }
}

/* Define i refers to itself: report the cycle at its first step. */
static _Noreturn void
define_cycle(Loader *L, const int *stack, const int *edge, int sp, int i)
{
    int from = sp - 1;
    while (from > 0 && stack[from] != i)
        from--;
    char path[1024] = "";
    for (int k = from; k < sp; k++)
        snprintf(path + strlen(path), sizeof path - strlen(path), "%s -> ", L->def[stack[k]].name);
    snprintf(path + strlen(path), sizeof path - strlen(path), "%s", L->def[i].name);
    Define *d = &L->def[stack[from]];
    Scalar sc;
    spec_scalar_src(L, &sc, d->dep_node[edge[from] - 1], "a define");
    SrcLoc at = spec_scalar_where(&sc.src, d->dep_off[edge[from] - 1]);
    static const char *const kinds[] = {"define", "frame", "point"};
    diag_error(at, "%s '%s' refers to itself: %s", kinds[L->def[i].kind], L->def[i].name,
               path);
}

static void
resolve_define_at(Loader *L, yaml_node_t *map, int i)
{
    (void)map;
    Define *d = &L->def[i];
    if (d->kind == ITEM_FRAME) {
        build_frame(L, d);
        return;
    }
    if (d->kind == ITEM_POINT) {
        build_point(L, d);
        return;
    }
    char what[120];
    snprintf(what, sizeof what, "define '%s'", d->name);
    Scalar sc;
    spec_scalar_src(L, &sc, d->node, "a define");
    L->sc.allow = ALLOW_ALL;
    L->sc.what = arena_strdup(L->A, what);
    const char *owner = L->sc.owner; /* the define names its switches */
    L->sc.owner = d->name;
    d->value = parse_value(&L->sc, &sc.src);
    L->sc.owner = owner;
}

/* A define with an error is marked, and so are the defines and the
 * expressions that use it, silently: the one message is its own. */
static void
resolve_define(Loader *L, Define *d)
{
    if (!spec_checked(L, resolve_define_at, NULL, (int)(d - L->def)))
        d->bad = 1;
}

/* Resolve every define after the defines it names: a depth-first
 * post-order with an explicit stack (chains of defines can be long). */
void
spec_resolve_defines(Loader *L)
{
    for (int i = 0; i < L->ndef; i++) {
        DepCollect c = {L, &L->def[i], NULL, 0};
        collect_deps(&c, L->def[i].node);
    }
    int *stack = arena_new_array(L->A, int, L->ndef + 1);
    int *edge = arena_new_array(L->A, int, L->ndef + 1);
    for (int root = 0; root < L->ndef; root++) {
        if (L->def[root].state)
            continue;
        int sp = 0;
        stack[sp] = root, edge[sp++] = 0;
        L->def[root].state = 1;
        while (sp) {
            Define *d = &L->def[stack[sp - 1]];
            if (edge[sp - 1] == d->ndeps) {
                resolve_define(L, d);
                d->state = 2;
                sp--;
                continue;
            }
            int next = d->deps[edge[sp - 1]++];
            if (L->def[next].state == 1)
                define_cycle(L, stack, edge, sp, next);
            if (L->def[next].state == 0) {
                L->def[next].state = 1;
                stack[sp] = next, edge[sp++] = 0;
            }
        }
    }
}

/* Spec.nv, vcoord and vslot (spec.h): a quaternion with speeds gives its
 * three where its first Euler parameter is, its parameters no slot. */
void
spec_velocity_slots(Loader *L)
{
    Spec *s = L->s;
    int nc = s->nq + s->nspeed;
    s->vslot = arena_new_array(L->A, int, nc + 1);
    s->vcoord = arena_new_array(L->A, int, nc + 1);
    int *first = arena_new_array(L->A, int, s->nq + 1); /* speed of a quaternion's e0, or -1 */
    for (int i = 0; i < s->nq; i++)
        first[i] = -2; /* its own rate */
    for (int k = 0; k < s->nfquat + s->nbody; k++) {
        const int *q = k < s->nfquat ? s->fquat[k].q : s->body[k - s->nfquat].quat;
        int sp = k < s->nfquat ? s->fquat[k].speed : s->body[k - s->nfquat].quat_speed;
        if (q[0] < 0 || sp < 0)
            continue;
        int lo = q[0];
        for (int d = 1; d < 4; d++)
            lo = q[d] < lo ? q[d] : lo;
        for (int d = 0; d < 4; d++)
            first[q[d]] = q[d] == lo ? sp : -1;
    }
    int nv = 0;
    for (int i = 0; i < s->nq; i++) {
        s->vslot[i] = first[i] == -2 ? nv : -1;
        if (first[i] == -2)
            s->vcoord[nv++] = i;
        for (int d = 0; first[i] >= 0 && d < 3; d++) {
            s->vslot[s->nq + first[i] + d] = nv;
            s->vcoord[nv++] = s->nq + first[i] + d;
        }
    }
    s->nv = nv;
}

void
spec_plain_slots(Spec *s, Arena *A)
{
    s->nv = s->nq;
    s->vcoord = arena_new_array(A, int, s->nq + 1);
    s->vslot = arena_new_array(A, int, s->nq + 1);
    for (int i = 0; i < s->nq; i++)
        s->vcoord[i] = s->vslot[i] = i;
}

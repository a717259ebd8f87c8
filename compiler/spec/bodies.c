/*
 * bodies: particles and rigid bodies (bodies.h).
 */
#include "bodies.h"

#include "checks.h"
#include "frames.h"
#include "names.h"
#include "view.h"

#include <string.h>

static void
load_particle(Loader *L, yaml_node_t *map, int i)
{
    static const char *const keys[] = {"mass", "position", NULL};
    {
        yaml_node_t *k = spec_node(L, PAIRS(map)[i].key), *v = spec_node(L, PAIRS(map)[i].value);
        SpecParticle *pt = &L->s->part[i];
        pt->name = arena_strdup(L->A, spec_scalar(L, k, "a particle name"));
        pt->loc = spec_loc(L, k);
        spec_map(L, v, "a particle");
        spec_check_keys(L, v, keys, "a particle");
        yaml_node_t *mass = spec_lookup(L, v, "mass"), *pos = spec_lookup(L, v, "position");
        if (!mass)
            diag_error(spec_loc(L, v), "particle '%s' has no mass", pt->name);
        if (!pos)
            diag_error(spec_loc(L, v), "particle '%s' has no position", pt->name);
        pt->mass = spec_mass(L, mass, "particle", pt->name);
        pt->dim = spec_world_vector(L, pos, ALLOW_POSITION, "a position", pt->pos);
        Name *nm = pos->type == YAML_SCALAR_NODE
                       ? spec_find_name(L, spec_scalar(L, pos, "a point")) : NULL;
        pt->point = -1;
        if (nm && nm->kind == NAME_POINT) {
            pt->point = spec_item(L, nm)->kin;
            kin_vel(L->K, pt->point, pt->vel);
            pt->has_vel = 1;
        }
    }
}

/* A particle or body that failed keeps a name ("" if even that failed),
 * so that a force on it is abandoned, not reported as unknown. */
void
spec_load_particles(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->npart = NPAIRS(map);
    s->part = arena_new_array(L->A, SpecParticle, s->npart);
    L->bad_part = arena_new_array(L->A, char, s->npart + 1);
    for (int i = 0; i < s->npart; i++)
        if (!spec_checked(L, load_particle, map, i)) {
            L->bad_part[i] = 1;
            if (!s->part[i].name)
                s->part[i].name = "";
        }
}

/* Inertia about the centre in the body frame: a scalar (planar), three
 * principal moments, or a symmetric 3 x 3 tensor. */
static void
load_inertia(Loader *L, yaml_node_t *n, SpecBody *b)
{
    for (int k = 0; k < 9; k++)
        b->inertia[k] = EXPR_ZERO;
    if (b->dim == 2) {
        b->inertia[0] = spec_expr(L, n, ALLOW_PARAM, "an inertia");
        return;
    }
    spec_expect(L, n, YAML_SEQUENCE_NODE, "an inertia (3 principal moments or a 3 x 3 tensor)");
    if (NITEMS(n) != 3)
        diag_error(spec_loc(L, n), "an inertia has 3 principal moments or 3 rows, not %d",
                   (int)NITEMS(n));
    int tensor = spec_node(L, ITEMS(n)[0])->type == YAML_SEQUENCE_NODE;
    for (int i = 0; i < 3; i++) {
        yaml_node_t *row = spec_node(L, ITEMS(n)[i]);
        if ((row->type == YAML_SEQUENCE_NODE) != tensor)
            diag_error(spec_loc(L, row), "write an inertia as 3 moments or as 3 rows, not both");
        if (!tensor) {
            b->inertia[4 * i] = spec_expr(L, row, ALLOW_PARAM, "a principal moment");
            continue;
        }
        if (NITEMS(row) != 3)
            diag_error(spec_loc(L, row), "a row of the inertia tensor has 3 entries, not %d",
                       (int)NITEMS(row));
        for (int j = 0; j < 3; j++)
            b->inertia[3 * i + j] = spec_expr(L, spec_node(L, ITEMS(row)[j]), ALLOW_PARAM,
                                               "an inertia entry");
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < i; j++)
            if (b->inertia[3 * i + j] != b->inertia[3 * j + i])
                diag_error(spec_loc(L, n), "the inertia tensor of body '%s' is not symmetric "
                           "(row %d, column %d)", b->name, i + 1, j + 1);
}

/* The Euler parameters e = (e0, e1, e2, e3) of a rotation, scalar first:
 * R = (e0^2 - |v|^2) I + 2 v v^T + 2 e0 [v x] with v = (e1, e2, e3), and
 * in body axes w = 2 L e' with
 *     L = [-e1  e0  e3 -e2;  -e2 -e3  e0  e1;  -e3  e2 -e1  e0]
 * (on |e| = 1, which the unit constraint keeps).  The parameters must be
 * four distinct coordinates. */
static void
quaternion_omega(Loader *L, yaml_node_t *k, yaml_node_t *v, yaml_node_t *sp, SpecBody *b)
{
    ExprPool *P = L->P;
    ExprId e[4], d[4];
    spec_quaternion_coords(L, v, arena_printf(L->A, "body '%s'", b->name), b->quat);
    for (int i = 0; i < 4; i++) {
        e[i] = expr_var(P, b->quat[i], 0);
        d[i] = expr_var(P, b->quat[i], 1);
    }
    b->quat_loc = spec_loc(L, k);
    kin_quat_matrix(P, e, b->rot); /* for drawing it */
    b->has_rot = 1;
    if (sp) { /* its speeds are omega, and e' follows from them */
        spec_quaternion_speeds(L, sp, b->quat, &b->quat_speed, b->omega);
        return;
    }
    kin_quat_omega(P, e, d, b->omega);
}

/* omega for intrinsic rotations R = R_a1(th1) R_a2(th2) ... about the
 * axes of the sequence ("zxz": z, then the new x, then the new z):
 *     w = e_an th_n' + R_an^T (e_a(n-1) th_(n-1)' + R_a(n-1)^T (...)),
 * the recursion of a frame's turns (kin_rate_turn): a body so turned has
 * no frame of its own. */
static void
rotation_omega(Loader *L, yaml_node_t *map, SpecBody *b)
{
    ExprPool *P = L->P;
    yaml_node_t *qn = spec_lookup(L, map, "quaternion"), *sp = spec_lookup(L, map, "speeds");
    if (qn && sp && NPAIRS(map) == 2) {
        quaternion_omega(L, spec_node(L, PAIRS(map)[0].key), qn, sp, b);
        return;
    }
    if (NPAIRS(map) != 1)
        diag_error(spec_loc(L, map), "a rotation is one sequence of axes with its angles, "
                   "such as {zxz: [psi, theta, phi]}, or {quaternion: [e0, e1, e2, e3]} with "
                   "its speeds {..., speeds: [wx, wy, wz]} or alone");
    yaml_node_t *k = spec_node(L, PAIRS(map)[0].key), *v = spec_node(L, PAIRS(map)[0].value);
    const char *axes = spec_scalar(L, k, "a rotation sequence");
    if (!strcmp(axes, "quaternion")) {
        quaternion_omega(L, k, v, NULL, b);
        return;
    }
    if (!strcmp(axes, "speeds"))
        diag_error(spec_loc(L, k), "`speeds:` are a quaternion's: {quaternion: [e0, e1, e2, "
                   "e3], speeds: [wx, wy, wz]}");
    size_t na = strlen(axes);
    if (na < 1 || na > 3 || strspn(axes, "xyz") != na)
        diag_error(spec_loc(L, k), "'%s' is not a rotation sequence: 1 to 3 of the axes "
                   "x, y, z, such as zxz or zyx, or quaternion", axes);
    spec_expect(L, v, YAML_SEQUENCE_NODE, "the angles of a rotation");
    if ((size_t)NITEMS(v) != na)
        diag_error(spec_loc(L, v), "rotation %s has %zu angles, not %d", axes, na,
                   (int)NITEMS(v));
    ExprId w[3] = {EXPR_ZERO, EXPR_ZERO, EXPR_ZERO};
    ExprId R[9] = {EXPR_ONE, EXPR_ZERO, EXPR_ZERO, EXPR_ZERO, EXPR_ONE, EXPR_ZERO,
                   EXPR_ZERO, EXPR_ZERO, EXPR_ONE};
    for (size_t i = 0; i < na; i++) {
        ExprId th = spec_expr(L, spec_node(L, ITEMS(v)[i]), ALLOW_POSITION, "an angle");
        ExprId Rk[9], a[3], own[3];
        kin_axis_turn(P, axes[i] - 'x', th, Rk, a);
        ExprId rate = diff_time(L->sc.D, th);
        for (int k = 0; k < 3; k++)
            own[k] = expr_mul(P, a[k], rate);
        kin_rate_turn(P, Rk, own, w);
        kin_mat3_mul(P, R, Rk, R); /* the axes after the turn, for drawing it */
    }
    for (int i = 0; i < 3; i++)
        b->omega[i] = w[i];
    for (int k = 0; k < 9; k++)
        b->rot[k] = R[k];
    b->has_rot = 1;
}

/* More than one of rotation, omega, angle: at the second one written. */
static _Noreturn void
two_orientations(Loader *L, const SpecBody *b, yaml_node_t *map)
{
    static const char *const keys[] = {"rotation", "omega", "angle", "frame"};
    int found[2], n = 0;
    for (int i = 0; i < NPAIRS(map) && n < 2; i++)
        for (int k = 0; k < 4; k++)
            if (!strcmp(spec_key(L, &PAIRS(map)[i]), keys[k]))
                found[n++] = i;
    const char *first = spec_key(L, &PAIRS(map)[found[0]]);
    const char *second = spec_key(L, &PAIRS(map)[found[1]]);
    diag_error(spec_loc(L, spec_node(L, PAIRS(map)[found[1]].key)), "body '%s' has both `%s` and "
               "`%s`; its orientation is exactly one of frame, rotation, omega, angle", b->name,
               first, second);
}

static void
load_body(Loader *L, yaml_node_t *map, int i)
{
    static const char *const keys[] = {"mass", "center", "inertia", "rotation", "omega",
                                       "angle", "frame", "shapes", NULL};
    Spec *s = L->s;
    {
        yaml_node_t *k = spec_node(L, PAIRS(map)[i].key), *v = spec_node(L, PAIRS(map)[i].value);
        SpecBody *b = &s->body[i];
        b->name = arena_strdup(L->A, spec_scalar(L, k, "a body name"));
        b->loc = spec_loc(L, k);
        for (int j = 0; j < s->npart; j++)
            if (!strcmp(s->part[j].name, b->name))
                diag_error(b->loc, "'%s' is already the name of a particle (line %d)", b->name,
                           s->part[j].loc.line);
        spec_map(L, v, "a body");
        spec_check_keys(L, v, keys, "a body");
        yaml_node_t *mass = spec_lookup(L, v, "mass"), *c = spec_lookup(L, v, "center");
        yaml_node_t *in = spec_lookup(L, v, "inertia"), *rot = spec_lookup(L, v, "rotation");
        yaml_node_t *om = spec_lookup(L, v, "omega"), *ang = spec_lookup(L, v, "angle");
        yaml_node_t *fr = spec_lookup(L, v, "frame");
        const char *missing = !mass ? "mass" : !c ? "center" : !in ? "inertia" : NULL;
        if (missing)
            diag_error(spec_loc(L, v), "body '%s' has no %s", b->name, missing);
        b->quat[0] = -1;
        b->quat_speed = -1;
        b->frame = b->point = -1;
        b->angle = EXPR_NONE;
        yaml_node_t *shapes = spec_lookup(L, v, "shapes");
        if (shapes && !spec_is_null(shapes))
            spec_load_shapes(L, shapes, i);
        b->mass = spec_mass(L, mass, "body", b->name);
        int how = !!rot + !!om + !!ang + !!fr;
        if (how > 1)
            two_orientations(L, b, v);
        if (fr) { /* placed by a frame: it turns with it, its inertia in its axes */
            int f = spec_frame_or_point(L, spec_scalar(L, fr, "a frame"), NAME_FRAME,
                                        spec_loc(L, fr));
            b->dim = spec_world_vector(L, c, ALLOW_POSITION, "a centre of mass", b->center);
            if (b->dim != 3)
                diag_error(spec_loc(L, c), "a body placed by a frame has a 3-D centre: a point, "
                           "or [x, y, z]");
            const char *cn = c->type == YAML_SCALAR_NODE ? spec_scalar(L, c, "a point") : "";
            Name *nm = spec_find_name(L, cn);
            if (kin_origin(L->K, f) < 0 && nm && nm->kind == NAME_POINT)
                kin_set_origin(L->K, f, spec_item(L, nm)->kin); /* vel(P, F) moves with it */
            if (nm && nm->kind == NAME_POINT) { /* its velocity by the links' structure */
                b->point = spec_item(L, nm)->kin;
                kin_vel(L->K, b->point, b->center_vel);
                b->has_center_vel = 1;
            }
            b->frame = f;
            L->body_frame[i] = f;
            load_inertia(L, in, b);
            spec_require_inertia(L, in, b);
            kin_omega_local(L->K, f, b->omega);
            return;
        }
        b->dim = spec_vector(L, c, ALLOW_POSITION, "a centre of mass", b->center);
        load_inertia(L, in, b);
        spec_require_inertia(L, in, b);
        b->omega[0] = b->omega[1] = b->omega[2] = EXPR_ZERO;
        if (how != 1)
            diag_error(spec_loc(L, v), "body '%s' needs exactly one of %s", b->name,
                       b->dim == 2 ? "angle (planar), omega"
                                   : "frame, rotation (e.g. {zxz: [psi, theta, phi]}), omega");
        if (ang && b->dim != 2)
            diag_error(spec_loc(L, ang), "`angle` is for planar bodies; a 3-D body takes a "
                       "`rotation` or `omega`");
        if (ang) {
            b->angle = spec_expr(L, ang, ALLOW_POSITION, "an angle");
            b->omega[0] = diff_time(L->sc.D, b->angle);
        }
        else if (rot && b->dim != 2)
            rotation_omega(L, spec_map(L, rot, "a rotation"), b);
        else if (rot)
            diag_error(spec_loc(L, rot), "a planar body turns by an `angle`");
        else if (b->dim == 2)
            b->omega[0] = spec_expr(L, om, ALLOW_KINETIC, "an angular velocity");
        else if (spec_vector(L, om, ALLOW_KINETIC, "an angular velocity", b->omega) != 3)
            diag_error(spec_loc(L, om), "a 3-D body's angular velocity has 3 components");
    }
}

void
spec_load_bodies(Loader *L, yaml_node_t *map)
{
    Spec *s = L->s;
    s->nbody = NPAIRS(map);
    s->body = arena_new_array(L->A, SpecBody, s->nbody);
    L->bad_body = arena_new_array(L->A, char, s->nbody + 1);
    L->body_frame = arena_new_array(L->A, int, s->nbody + 1);
    for (int i = 0; i < s->nbody; i++)
        L->body_frame[i] = -1;
    for (int i = 0; i < s->nbody; i++)
        if (!spec_checked(L, load_body, map, i)) {
            L->bad_body[i] = 1;
            if (!s->body[i].name)
                s->body[i].name = "";
        }
}

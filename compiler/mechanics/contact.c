/*
 * contact: a contact effect's normal forces (contact.h).
 *
 * A pair of shapes gives one contact or several (a capsule's two end
 * spheres on a plane, a box's eight corners), each
 *   d    its gap: the depth of the overlap, > 0 where they overlap,
 *   n    the unit normal, along which the force pushes the second shape
 *        (and the first the other way),
 *   pa, pb the material points of each shape that touch.
 * The force's size is N = where(d, max(0, k d + c d'), 0): a linear
 * spring and damper on the penetration that never pulls, 0 apart.  d' is
 * d's time derivative, which for these smooth convex shapes is the
 * normal relative speed of pa and pb (the nearest points' own motion
 * along the surfaces is across n).  It acts on each body as a force at
 * its centre and the torque (p - centre) x F, which is what a force at
 * the material point p does.  The nearest points of a capsule's axis are
 * clamped parameters, switches of their own.
 *
 * Each pair's whole share of the generalized forces (its gaps, forces
 * and their projection on the coordinates) is a switched expression of
 * one more switch, EFFECT.A.B.near: where(s, share, 0), s > 0 where the
 * shapes' bounding spheres, grown by a margin, overlap (near_bound).  The
 * emitter computes a branch only in its mode (lower_schedule.h), so a
 * pair that is far apart costs a right-hand side nothing.  It is exact,
 * not an approximation: a gap is at most its bounding spheres' overlap,
 * so while far (s < 0) every gap is below -margin, and the near switch
 * flips before any touch switch can.
 */
#include "contact.h"

#include "expr/kin.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct Ctx {
    const Spec *s;
    ExprPool *P;
    Diff *D;
    const char *prefix; /* EFFECT.A.B: its switches' names */
    ExprId k, c;
    ExprId (*F)[3], (*tau)[3]; /* per body: the pair's force, and torque about its centre
                                * (world axes) */
    ExprId mu;                 /* the friction coefficient (EXPR_ZERO: none) */
    const ExprId *tangent[2];  /* the plane's x and y axes while its contacts are made;
                                * NULL otherwise (no friction) */
    const ContactQ *out;
    ExprId near; /* the pair's near switch's function (EXPR_NONE: none yet) */
    ExprId far;  /* the sign a switch of the pair's own has while far */
    ExprId close; /* two capsules' close gate's function (EXPR_NONE: none) */
} Ctx;

/* The margin by which the near switch's bounding spheres are grown, a
 * share of their radii (a plane's partner's alone): any margin > 0 keeps
 * the near switch ahead of the touch switches (their kinks apart, each
 * located on its own); a larger one computes the pair longer before a
 * touch, a smaller one brings the two switches' times closer. */
#define NEAR_MARGIN_REL 0.125

/* A shape where it is: its centre o, its axes A (row-major, world from
 * shape), its sizes, and its body (>= nbody: the ground). */
typedef struct Placed {
    int body, type;
    ExprId o[3], A[9], size[3];
} Placed;

/* A where(s, a, b) whose new switch is named prefix.suffix.  A switch of
 * the pair's own (not its near switch) is watched only while the pair is
 * near, its function x->far (a sign: -1 for a touch, which is off
 * while far, else 1) while far: the pair's share is 0 there
 * whatever its modes, and a clamp's function on the lines of two
 * parallel capsules far apart (a humanoid's two feet) swings with
 * rounding, which would flip it back and forth for nothing. */
static ExprId
named_where(Ctx *x, ExprId s, ExprId a, ExprId b, const char *suffix)
{
    if (x->close != EXPR_NONE && s != x->close)
        s = expr_where(x->P, x->close, s, x->far);
    if (x->near != EXPR_NONE && s != x->near)
        s = expr_where(x->P, x->near, s, x->far);
    int before = expr_nswitch(x->P);
    ExprId e = expr_where(x->P, s, a, b);
    char name[512];
    snprintf(name, sizeof name, "%s.%s", x->prefix, suffix);
    for (int k = before; k < expr_nswitch(x->P); k++)
        expr_name_switch(x->P, k, name);
    return e;
}

/* clamp(v, lo, hi) as expr_clamp builds it (hi where v > hi, else
 * max(v, lo)), its switches named prefix.which.lo and .hi; inside: while
 * far, each switch's sign is that of v inside (.lo on, .hi off), else
 * both on. */
static ExprId
named_clamp(Ctx *x, ExprId v, ExprId lo, ExprId hi, const char *which, int inside)
{
    char lo_name[64], hi_name[64];
    snprintf(lo_name, sizeof lo_name, "%s.lo", which);
    snprintf(hi_name, sizeof hi_name, "%s.hi", which);
    ExprId low = named_where(x, expr_sub(x->P, v, lo), v, lo, lo_name);
    ExprId far = x->far;
    if (inside)
        x->far = expr_neg(x->P, EXPR_ONE);
    ExprId e = named_where(x, expr_sub(x->P, v, hi), hi, low, hi_name);
    x->far = far;
    return e;
}

/* Body b's centre and rotation (world from body), as the page draws it
 * (lower_draw): the frame that places it, its rotation, its planar angle;
 * unturned where it does not turn (spec/contacts.c refuses a body turned
 * by omega alone).  The ground: the world's origin and axes. */
static void
body_pose(const Spec *s, int b, ExprPool *P, ExprId c[3], ExprId R[9])
{
    for (int j = 0; j < 9; j++)
        R[j] = j % 4 == 0 ? EXPR_ONE : EXPR_ZERO;
    c[0] = c[1] = c[2] = EXPR_ZERO;
    if (b >= s->nbody)
        return;
    const SpecBody *bd = &s->body[b];
    for (int j = 0; j < bd->dim; j++)
        c[j] = bd->center[j];
    if (bd->frame >= 0) {
        kin_rotation(s->kin, bd->frame, R);
    } else if (bd->has_rot) {
        memcpy(R, bd->rot, sizeof bd->rot);
    } else if (bd->dim == 2 && bd->angle != EXPR_NONE) {
        ExprId co = expr_unary(P, EXPR_COS, bd->angle), si = expr_unary(P, EXPR_SIN, bd->angle);
        R[0] = co, R[1] = expr_neg(P, si), R[3] = si, R[4] = co;
    }
}

static void
place(const Spec *s, int k, ExprPool *P, Placed *out)
{
    const SpecShape *sh = &s->shape[k];
    ExprId c[3], R[9], pos[3], Q[9];
    out->body = sh->body >= s->nbody ? s->nbody : sh->body;
    out->type = sh->type;
    body_pose(s, out->body, P, c, R);
    const double *e = sh->quat; /* its own turn, in the body's axes */
    double q[9] = {
        1 - 2 * (e[2] * e[2] + e[3] * e[3]), 2 * (e[1] * e[2] - e[0] * e[3]),
        2 * (e[1] * e[3] + e[0] * e[2]),     2 * (e[1] * e[2] + e[0] * e[3]),
        1 - 2 * (e[1] * e[1] + e[3] * e[3]), 2 * (e[2] * e[3] - e[0] * e[1]),
        2 * (e[1] * e[3] - e[0] * e[2]),     2 * (e[2] * e[3] + e[0] * e[1]),
        1 - 2 * (e[1] * e[1] + e[2] * e[2])};
    for (int j = 0; j < 9; j++)
        Q[j] = expr_const(P, q[j]);
    kin_mat3_mul(P, R, Q, out->A);
    for (int j = 0; j < 3; j++) {
        pos[j] = sh->epos[j] != EXPR_NONE ? sh->epos[j] : expr_const(P, sh->pos[j]);
        out->size[j] = sh->esize[j] != EXPR_NONE ? sh->esize[j] : expr_const(P, sh->size[j]);
    }
    for (int i = 0; i < 3; i++)
        out->o[i] = expr_add(P, c[i], kin_dot(P, &R[3 * i], (ExprId[3]){pos[0], pos[1], pos[2]}));
}

/* Column j of A: a shape's j-th axis in the world's components. */
static void
axis(const ExprId *A, int j, ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = A[3 * i + j];
}

/* o + A v */
static void
at(ExprPool *P, const Placed *sh, const ExprId v[3], ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = expr_add(P, sh->o[i], kin_dot(P, &sh->A[3 * i], v));
}

/* a + t b */
static void
along(ExprPool *P, const ExprId a[3], ExprId t, const ExprId b[3], ExprId out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = expr_add(P, a[i], expr_mul(P, t, b[i]));
}

/* The force f dir on body bb at pb, -f dir on ba at pa (the ground takes
 * its own), into the pair's forces and torques. */
static void
apply(Ctx *x, ExprId f, const ExprId dir[3], int ba, const ExprId pa[3], int bb,
      const ExprId pb[3])
{
    ExprPool *P = x->P;
    for (int e = 0; e < 2; e++) {
        int b = e ? bb : ba;
        if (b >= x->s->nbody) /* the ground takes it */
            continue;
        const ExprId *p = e ? pb : pa;
        ExprId F[3], arm[3], t[3], c[3], R[9];
        body_pose(x->s, b, P, c, R);
        for (int i = 0; i < 3; i++) {
            F[i] = expr_mul(P, f, e ? dir[i] : expr_neg(P, dir[i]));
            arm[i] = expr_sub(P, p[i], c[i]);
            x->F[b][i] = expr_add(P, x->F[b][i], F[i]);
        }
        kin_cross(P, arm, F, t);
        for (int i = 0; i < 3; i++)
            x->tau[b][i] = expr_add(P, x->tau[b][i], t[i]);
    }
}

/* The velocity of body b's material point at p (world axes): its
 * centre's, and w x (p - centre); the ground's 0. */
static void
material_velocity(Ctx *x, int b, const ExprId p[3], ExprId out[3])
{
    ExprPool *P = x->P;
    out[0] = out[1] = out[2] = EXPR_ZERO;
    if (b >= x->s->nbody)
        return;
    const SpecBody *bd = &x->s->body[b];
    ExprId c[3], R[9], w[3], arm[3], turn[3];
    body_pose(x->s, b, P, c, R);
    for (int i = 0; i < bd->dim; i++)
        out[i] = bd->has_center_vel ? bd->center_vel[i] : diff_time(x->D, bd->center[i]);
    if (bd->dim == 2) { /* turning about z */
        w[0] = w[1] = EXPR_ZERO;
        w[2] = bd->omega[0];
    } else { /* R omega: omega is in the body's axes */
        for (int i = 0; i < 3; i++)
            w[i] = kin_dot(P, &R[3 * i], bd->omega);
    }
    for (int i = 0; i < 3; i++)
        arm[i] = expr_sub(P, p[i], c[i]);
    kin_cross(P, w, arm, turn);
    for (int i = 0; i < 3; i++)
        out[i] = expr_add(P, out[i], turn[i]);
}

/* The friction item of a contact with a plane along its axis t (named
 * by axis): the slip speed s = t . rel (rel the velocity of b's touching
 * point less a's), at most mu N against it while it slips (a switch on
 * s, SUFFIX.AXIS.slip), whatever holds it while stuck (a held switch,
 * .stick: the runtime's), acting along t at the touching points.  An
 * axis along which the model's motion cannot move the points (s of no
 * velocity slot) has none. */
static void
friction(Ctx *x, const char *suffix, ExprId N, const ExprId t[3], const char *axis,
         const ExprId rel[3], int ba, const ExprId pa[3], int bb, const ExprId pb[3])
{
    ExprPool *P = x->P;
    const ContactQ *out = x->out;
    ExprId speed = kin_dot(P, t, rel);
    int moves = 0;
    for (int j = 0; j < out->n && !moves; j++)
        moves = diff_partial(x->D, speed, out->v[j]) != EXPR_ZERO;
    if (!moves)
        return;
    char name[600];
    snprintf(name, sizeof name, "%s%s%s.%s", x->prefix, *suffix ? "." : "", suffix, axis);
    ExprId F = expr_mul(P, x->mu, N);
    int first = expr_nswitch(P);
    ExprId slip = expr_where(P, speed, expr_neg(P, F), F);
    char sw[640];
    if (expr_nswitch(P) > first) { /* (a speed met before keeps its switch and name) */
        snprintf(sw, sizeof sw, "%s.slip", name);
        expr_name_switch(P, first, sw);
    }
    int stick = expr_switch_held(P);
    snprintf(sw, sizeof sw, "%s.stick", name);
    expr_name_switch(P, stick, sw);
    apply(x, expr_select(P, stick, EXPR_ZERO, slip), t, ba, pa, bb, pb);
    int k = -1;
    for (int j = 0; j < expr_nswitch(P) && k < 0; j++)
        if (expr_switch(P, j) == speed)
            k = j;
    ContactFrics *fr = out->fric;
    if (fr->n == fr->cap) {
        fr->cap = fr->cap ? 2 * fr->cap : 16;
        ContactFric *bigger = arena_new_array(out->A, ContactFric, fr->cap);
        for (int j = 0; j < fr->n; j++)
            bigger[j] = fr->item[j];
        fr->item = bigger;
    }
    fr->item[fr->n++] = (ContactFric){arena_strdup(out->A, name), k, stick, F, speed};
}

/* One contact: its gap d, normal n, material points pa (of shape a, on
 * body ba) and pb.  The force N n on b at pb, -N n on a at pa. */
static void
contact(Ctx *x, const char *suffix, ExprId d, const ExprId n[3], int ba, const ExprId pa[3],
        int bb, const ExprId pb[3])
{
    ExprPool *P = x->P;
    char name[64], touch[64];
    snprintf(touch, sizeof touch, "%s%stouch", suffix, *suffix ? "." : "");
    snprintf(name, sizeof name, "%s%spush", suffix, *suffix ? "." : "");
    ExprId rate = diff_time(x->D, d);
    ExprId spring = expr_mul(P, x->k, d), damper = expr_mul(P, x->c, rate);
    ExprId law = expr_add(P, spring, damper);
    /* The push's switch watches k d + c d' only while the shapes touch:
     * apart, the law acts on nothing, and two shapes near each other
     * whose d' swings as a third body lands (a humanoid's feet) would
     * flip it back and forth for nothing, or stop a run as sliding along
     * a kink.  Apart its function is 1, a sign: the push is on there,
     * so a touchdown (d = 0, c d' > 0) flips the touch alone. */
    x->far = expr_neg(P, EXPR_ONE);
    ExprId watched = named_where(x, d, law, EXPR_ONE, touch);
    x->far = EXPR_ONE;
    ExprId push = named_where(x, watched, law, EXPR_ZERO, name); /* max(0, k d + c d') */
    x->far = expr_neg(P, EXPR_ONE);
    ExprId N = named_where(x, d, push, EXPR_ZERO, touch);
    x->far = EXPR_ONE;
    apply(x, N, n, ba, pa, bb, pb);
    if (x->mu == EXPR_ZERO || !x->tangent[0])
        return;
    ExprId va[3], vb[3], rel[3];
    material_velocity(x, ba, pa, va);
    material_velocity(x, bb, pb, vb);
    for (int i = 0; i < 3; i++)
        rel[i] = expr_sub(P, vb[i], va[i]);
    for (int a = 0; a < 2; a++)
        friction(x, suffix, N, x->tangent[a], a ? "y" : "x", rel, ba, pa, bb, pb);
}

/* A sphere (centre o, radius r, on body bs) on a plane (pl): d = r - n.(o - p0).
 * It touches at the plane's surface, o's projection p = o - h n (h = n.(o
 * - p0) its height), where a rigid floor holds a body its spring lets
 * sink: every touch point of one body on one plane is in that plane, so
 * their friction rows are combinations of three (the body's two speeds
 * along it and its turn about n) whatever their depths, not rows apart by
 * a rounding-sized tilt (docs/spec.md, "The touch point is on the
 * plane").  The normal force along n acts through p and through the
 * sphere's own lowest point alike. */
static void
plane_point(Ctx *x, const char *suffix, const Placed *pl, const ExprId o[3], ExprId r,
            int bs)
{
    ExprPool *P = x->P;
    ExprId n[3], rel[3], p[3];
    axis(pl->A, 2, n);
    for (int i = 0; i < 3; i++)
        rel[i] = expr_sub(P, o[i], pl->o[i]);
    ExprId h = kin_dot(P, n, rel), d = expr_sub(P, r, h);
    for (int i = 0; i < 3; i++)
        p[i] = expr_sub(P, o[i], expr_mul(P, h, n[i]));
    contact(x, suffix, d, n, pl->body, p, bs, p);
}

/* Two spheres (oa, ra) and (ob, rb): d = ra + rb - |ob - oa|. */
static void
spheres(Ctx *x, const char *suffix, const ExprId oa[3], ExprId ra, int ba, const ExprId ob[3],
        ExprId rb, int bb)
{
    ExprPool *P = x->P;
    ExprId delta[3], n[3], pa[3], pb[3];
    for (int i = 0; i < 3; i++)
        delta[i] = expr_sub(P, ob[i], oa[i]);
    ExprId len = expr_unary(P, EXPR_SQRT, kin_dot(P, delta, delta));
    for (int i = 0; i < 3; i++)
        n[i] = expr_div(P, delta[i], len);
    ExprId d = expr_sub(P, expr_add(P, ra, rb), len);
    along(P, oa, ra, n, pa);
    along(P, ob, expr_neg(P, rb), n, pb);
    contact(x, suffix, d, n, ba, pa, bb, pb);
}

/* The plane's contacts with a sphere, a capsule's end spheres, a box's
 * corners, an ellipsoid's lowest point. */
static void
with_plane(Ctx *x, const Placed *pl, const Placed *o)
{
    ExprPool *P = x->P;
    ExprId zero = EXPR_ZERO, tx[3], ty[3];
    axis(pl->A, 0, tx);
    axis(pl->A, 1, ty);
    x->tangent[0] = tx, x->tangent[1] = ty;
    switch (o->type) {
    case SPEC_SHAPE_SPHERE:
        plane_point(x, "", pl, o->o, o->size[0], o->body);
        break;
    case SPEC_SHAPE_CAPSULE:
        for (int e = 0; e < 2; e++) { /* end1 at -h along its z, end2 at +h */
            ExprId h = e ? o->size[1] : expr_neg(P, o->size[1]), end[3];
            at(P, o, (ExprId[3]){zero, zero, h}, end);
            plane_point(x, e ? "end2" : "end1", pl, end, o->size[0], o->body);
        }
        break;
    case SPEC_SHAPE_BOX:
        for (int v = 0; v < 8; v++) { /* v1 = (-, -, -); x changes first, then y, z */
            ExprId local[3], corner[3];
            char name[8];
            for (int j = 0; j < 3; j++)
                local[j] = v >> j & 1 ? o->size[j] : expr_neg(P, o->size[j]);
            at(P, o, local, corner);
            snprintf(name, sizeof name, "v%d", v + 1);
            plane_point(x, name, pl, corner, zero, o->body);
        }
        break;
    case SPEC_SHAPE_ELLIPSOID: {
        /* the point farthest along -n: o - A S^2 m / |S m|, m = A^T n
         * the normal in its axes, S its semi-axes; d = |S m| - n.(o - p0) */
        ExprId n[3], m[3], w = zero, local[3], p[3], rel[3];
        axis(pl->A, 2, n);
        for (int j = 0; j < 3; j++) {
            ExprId col[3];
            axis(o->A, j, col);
            m[j] = kin_dot(P, col, n);
            w = expr_add(P, w, expr_powi(P, expr_mul(P, o->size[j], m[j]), 2));
        }
        w = expr_unary(P, EXPR_SQRT, w);
        for (int j = 0; j < 3; j++)
            local[j] = expr_neg(P, expr_div(P, expr_mul(P, expr_powi(P, o->size[j], 2), m[j]), w));
        at(P, o, local, p);
        for (int i = 0; i < 3; i++)
            rel[i] = expr_sub(P, o->o[i], pl->o[i]);
        ExprId d = expr_sub(P, w, kin_dot(P, n, rel));
        contact(x, "", d, n, pl->body, p, o->body, p);
        break;
    }
    }
    x->tangent[0] = x->tangent[1] = NULL;
}

/* A sphere (a) and a capsule (b), or the other way round (flip): the
 * point of the capsule's axis nearest the sphere's centre, t clamped to
 * its half-length, and the two spheres there. */
static void
sphere_capsule(Ctx *x, const Placed *sp, const Placed *ca, int flip)
{
    ExprPool *P = x->P;
    ExprId u[3], rel[3], q[3];
    axis(ca->A, 2, u);
    for (int i = 0; i < 3; i++)
        rel[i] = expr_sub(P, sp->o[i], ca->o[i]);
    ExprId h = ca->size[1];
    ExprId along_axis = kin_dot(P, u, rel), nh = expr_neg(P, h);
    ExprId t = named_clamp(x, along_axis, nh, h, flip ? "a" : "b", 0);
    along(P, ca->o, t, u, q);
    if (flip)
        spheres(x, "", q, ca->size[0], ca->body, sp->o, sp->size[0], sp->body);
    else
        spheres(x, "", sp->o, sp->size[0], sp->body, q, ca->size[0], ca->body);
}

/* Two capsules: the nearest points of their axes, oa + s ua and ob + t ub
 * (|s| <= ha, |t| <= hb), the one pair of the segments' distance, which
 * is the least of |oa + s ua - ob - t ub| over that rectangle, a convex
 * quadratic.  Its least point is the lines' own where that lies inside
 * both (the interior), and else on the rectangle's edge: an end of one
 * axis against the other segment, its projection clamped, conditioned
 * whatever the angle.  So the gap is the interior's where both of the
 * lines' parameters are inside (switches .a.in, .b.in), and else the
 * nearest of the four ends' (.a.end1.lo/.hi ... .b.end2.lo/.hi their
 * clamps, .a.end and .b.end which end of each, .end which axis's).
 * Where a line's parameter crosses an end the interior and that end's
 * candidate are the same points, so the gap is continuous.
 *
 * Each switch is well conditioned near parallel, where the lines'
 * parameters s0 = xs/den and t0 = xt/den are rounding over rounding:
 * with n = ua x ub, den = n.n (1 - (ua.ub)^2 without its cancellation),
 * xs = n.(ub x r) and xt = n.(ua x r) (r = oa - ob), the lines' s0 is
 * inside where (ha den)^2 - xs^2 > 0, a product that keeps its sign to
 * the last bit: near parallel the lines' nearest points are far outside
 * (|xs| ~ |n| |r| against ha |n|^2) and the switch stays off, where a
 * clamp of x/den flipped with rounding (a humanoid's two feet).  Two
 * capsules exactly parallel (n = 0) take the ends, whichever is nearer
 * (the distance is the same along their overlap). */
#define TIE_REL 1e-12
static void
capsules(Ctx *x, const Placed *a, const Placed *b)
{
    ExprPool *P = x->P;
    ExprId ua[3], ub[3], r[3], n[3], wa[3], wb[3];
    axis(a->A, 2, ua);
    axis(b->A, 2, ub);
    for (int i = 0; i < 3; i++)
        r[i] = expr_sub(P, a->o[i], b->o[i]);
    ExprId ha = a->size[1], hb = b->size[1];
    kin_cross(P, ua, ub, n);
    kin_cross(P, ub, r, wb);
    kin_cross(P, ua, r, wa);
    ExprId den = kin_dot(P, n, n), xs = kin_dot(P, n, wb), xt = kin_dot(P, n, wa);
    /* the close gate: watch the pair's own switches only where the
     * segments may be within R = (ra + rb)(1 + margin): a point
     * oa + s ua is |wb + s n| >= |wb| - ha |n| from b's line, so the
     * segments are farther than R wherever |wb|^2 >= 2 R^2 + 2 ha^2 den
     * (>= (R + ha |n|)^2), without a square root at n = 0 */
    ExprId grow = expr_const(P, 1 + NEAR_MARGIN_REL), radii = expr_add(P, a->size[0], b->size[0]);
    ExprId R = expr_mul(P, grow, radii);
    ExprId R2 = expr_powi(P, R, 2), ha2 = expr_powi(P, ha, 2);
    ExprId reach = expr_add(P, R2, expr_mul(P, ha2, den));
    ExprId two = expr_const(P, 2);
    ExprId twice = expr_mul(P, two, reach), wb2 = kin_dot(P, wb, wb);
    ExprId close = expr_sub(P, twice, wb2);
    close = expr_where(P, x->near, close, expr_neg(P, EXPR_ONE));
    ExprId near = x->near;
    x->near = EXPR_NONE;
    (void)named_where(x, close, EXPR_ONE, EXPR_ZERO, "close");
    x->near = near;
    x->close = close;
    /* the four ends, each against the other segment: (p on a's axis, q on b's) */
    ExprId cand[4][2][3], dist2[4];
    for (int k = 0; k < 4; k++) {
        const Placed *from = k < 2 ? a : b, *onto = k < 2 ? b : a;
        ExprId h = k % 2 ? from->size[1] : expr_neg(P, from->size[1]), end[3], rel[3], on[3],
               u[3];
        at(P, from, (ExprId[3]){EXPR_ZERO, EXPR_ZERO, h}, end);
        axis(onto->A, 2, u);
        for (int i = 0; i < 3; i++)
            rel[i] = expr_sub(P, end[i], onto->o[i]);
        char which[16];
        snprintf(which, sizeof which, "%s.end%d", k < 2 ? "a" : "b", k % 2 + 1);
        ExprId proj = kin_dot(P, u, rel), lo = expr_neg(P, onto->size[1]);
        ExprId t = named_clamp(x, proj, lo, onto->size[1], which, 1);
        along(P, onto->o, t, u, on);
        ExprId d[3];
        for (int i = 0; i < 3; i++) {
            cand[k][0][i] = k < 2 ? end[i] : on[i];
            cand[k][1][i] = k < 2 ? on[i] : end[i];
            d[i] = expr_sub(P, cand[k][1][i], cand[k][0][i]);
        }
        dist2[k] = kin_dot(P, d, d);
    }
    /* the nearest end of each axis, then of the two; a tie (their
     * distances equal to rounding) goes to the first */
    ExprId tie_rel = expr_const(P, TIE_REL), radii2 = expr_powi(P, radii, 2);
    ExprId tie = expr_mul(P, tie_rel, radii2);
    ExprId best[2][2][3], bd2[2];
    for (int e = 0; e < 2; e++) {
        ExprId s = expr_add(P, expr_sub(P, dist2[2 * e + 1], dist2[2 * e]), tie); /* > 0: end1 */
        const char *name = e ? "b.end" : "a.end";
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 3; i++)
                best[e][j][i] =
                    named_where(x, s, cand[2 * e][j][i], cand[2 * e + 1][j][i], name);
        bd2[e] = named_where(x, s, dist2[2 * e], dist2[2 * e + 1], name);
    }
    ExprId sel = expr_add(P, expr_sub(P, bd2[1], bd2[0]), tie); /* > 0: a's end */
    ExprId pa[3], pb[3];
    for (int i = 0; i < 3; i++) {
        pa[i] = named_where(x, sel, best[0][0][i], best[1][0][i], "end");
        pb[i] = named_where(x, sel, best[0][1][i], best[1][1][i], "end");
    }
    /* the interior, where both lines' parameters are inside */
    ExprId hda = expr_powi(P, expr_mul(P, ha, den), 2), xs2 = expr_powi(P, xs, 2);
    ExprId ina = expr_sub(P, hda, xs2);
    ExprId hdb = expr_powi(P, expr_mul(P, hb, den), 2), xt2 = expr_powi(P, xt, 2);
    ExprId inb = expr_sub(P, hdb, xt2);
    ExprId s0 = expr_div(P, xs, den), t0 = expr_div(P, xt, den), la[3], lb[3];
    along(P, a->o, s0, ua, la);
    along(P, b->o, t0, ub, lb);
    x->far = expr_neg(P, EXPR_ONE); /* (off while far: off as the pair comes near) */
    for (int i = 0; i < 3; i++) {
        pa[i] = named_where(x, ina, named_where(x, inb, la[i], pa[i], "b.in"), pa[i], "a.in");
        pb[i] = named_where(x, ina, named_where(x, inb, lb[i], pb[i], "b.in"), pb[i], "a.in");
    }
    x->far = EXPR_ONE;
    spheres(x, "", pa, a->size[0], a->body, pb, b->size[0], b->body);
    x->close = EXPR_NONE;
}

/* The radius of a sphere about a shape's centre that holds it (a box's
 * corners, an ellipsoid within the sphere of its semi-axes' norm). */
static ExprId
bounding_radius(ExprPool *P, const Placed *sh)
{
    switch (sh->type) {
    case SPEC_SHAPE_SPHERE:
        return sh->size[0];
    case SPEC_SHAPE_CAPSULE:
        return expr_add(P, sh->size[0], sh->size[1]);
    default: { /* box, ellipsoid */
        ExprId w = EXPR_ZERO;
        for (int j = 0; j < 3; j++)
            w = expr_add(P, w, expr_powi(P, sh->size[j], 2));
        return expr_unary(P, EXPR_SQRT, w);
    }
    }
}

/* The near switch's function: > 0 where the pair's bounding spheres,
 * grown by the margin, overlap.  A plane and a shape: R + margin -
 * n.(o - p0), the grown sphere's depth below the plane; two shapes:
 * (Ra + Rb + margin)^2 - |oa - ob|^2, its sign that of the distance's
 * without a square root.  Every gap of the pair is at most the
 * spheres' overlap, so it is below -margin wherever this is below 0. */
static ExprId
near_bound(ExprPool *P, const Placed *a, const Placed *b)
{
    if (b->type == SPEC_SHAPE_PLANE) {
        const Placed *t = a;
        a = b, b = t;
    }
    ExprId rb = bounding_radius(P, b), rel[3];
    for (int i = 0; i < 3; i++)
        rel[i] = expr_sub(P, b->o[i], a->o[i]);
    if (a->type == SPEC_SHAPE_PLANE) {
        ExprId n[3];
        axis(a->A, 2, n);
        ExprId grown = expr_mul(P, expr_const(P, 1 + NEAR_MARGIN_REL), rb);
        return expr_sub(P, grown, kin_dot(P, n, rel));
    }
    ExprId sum = expr_add(P, bounding_radius(P, a), rb);
    ExprId grown = expr_mul(P, expr_const(P, 1 + NEAR_MARGIN_REL), sum);
    ExprId sq = expr_powi(P, grown, 2);
    return expr_sub(P, sq, kin_dot(P, rel, rel));
}

/* Body b's force and torque (x->F[b], x->tau[b]) on the coordinates,
 * added to Qq and Q: F . dc/dq_i, and (R^T tau) . dw/dv_j in its axes. */
static void
project(Ctx *x, int b, const ContactQ *out, ExprId *Qq, ExprId *Q)
{
    ExprPool *P = x->P;
    const SpecBody *bd = &x->s->body[b];
    for (int i = 0; i < out->nq; i++) {
        ExprId w = EXPR_ZERO;
        for (int k = 0; k < bd->dim; k++)
            w = expr_add(P, w, expr_mul(P, x->F[b][k],
                                        diff_partial(x->D, bd->center[k], out->q[i])));
        Qq[i] = expr_add(P, Qq[i], w);
    }
    ExprId c[3], R[9], tb[3];
    body_pose(x->s, b, P, c, R);
    int nw = bd->dim == 2 ? 1 : 3;
    if (nw == 1) /* about z, the plane's normal */
        tb[0] = x->tau[b][2];
    else
        for (int k = 0; k < 3; k++) /* R^T tau */
            tb[k] = kin_dot(P, (ExprId[3]){R[k], R[3 + k], R[6 + k]}, x->tau[b]);
    for (int j = 0; j < out->n; j++) {
        ExprId w = EXPR_ZERO;
        for (int k = 0; k < nw; k++)
            w = expr_add(P, w, expr_mul(P, tb[k], diff_partial(x->D, bd->omega[k], out->v[j])));
        Q[j] = expr_add(P, Q[j], w);
    }
}

void
contact_add(const Spec *s, const SpecEffect *e, const SpecForce *f, ExprPool *P, Diff *D,
            const ContactQ *out)
{
    int nb = s->nbody;
    Ctx x = {s, P, D, NULL, f->stiffness, f->damping, NULL, NULL, f->mu, {NULL, NULL}, out, EXPR_NONE, EXPR_ONE, EXPR_NONE};
    x.F = xmalloc(((size_t)nb + 1) * sizeof *x.F);
    x.tau = xmalloc(((size_t)nb + 1) * sizeof *x.tau);
    ExprId *Qq = xmalloc(((size_t)out->nq + 1) * sizeof *Qq);
    ExprId *Q = xmalloc(((size_t)out->n + 1) * sizeof *Q);
    for (int j = 0; j < f->npair; j++) {
        int ka = f->pair[2 * j], kb = f->pair[2 * j + 1];
        size_t len = strlen(e->name) + strlen(s->shape[ka].name) + strlen(s->shape[kb].name) + 3;
        char *prefix = xmalloc(len);
        snprintf(prefix, len, "%s.%s.%s", e->name, s->shape[ka].name, s->shape[kb].name);
        x.prefix = prefix;
        Placed a, b;
        place(s, ka, P, &a);
        place(s, kb, P, &b);
        /* the near switch first: the pair's own come after it */
        ExprId near = near_bound(P, &a, &b);
        x.near = EXPR_NONE;
        (void)named_where(&x, near, EXPR_ONE, EXPR_ZERO, "near");
        x.near = near;
        for (int i = 0; i < 3; i++)
            x.F[a.body][i] = x.tau[a.body][i] = x.F[b.body][i] = x.tau[b.body][i] = EXPR_ZERO;
        if (a.type == SPEC_SHAPE_PLANE)
            with_plane(&x, &a, &b);
        else if (b.type == SPEC_SHAPE_PLANE)
            with_plane(&x, &b, &a);
        else if (a.type == SPEC_SHAPE_SPHERE && b.type == SPEC_SHAPE_SPHERE)
            spheres(&x, "", a.o, a.size[0], a.body, b.o, b.size[0], b.body);
        else if (a.type == SPEC_SHAPE_SPHERE)
            sphere_capsule(&x, &a, &b, 0);
        else if (b.type == SPEC_SHAPE_SPHERE)
            sphere_capsule(&x, &b, &a, 1);
        else
            capsules(&x, &a, &b);
        /* the pair's share, on the coordinates, while near */
        for (int i = 0; i < out->nq; i++)
            Qq[i] = EXPR_ZERO;
        for (int i = 0; i < out->n; i++)
            Q[i] = EXPR_ZERO;
        for (int e2 = 0; e2 < 2; e2++) {
            int body = e2 ? b.body : a.body;
            if (body < nb) /* (the ground takes its own) */
                project(&x, body, out, Qq, Q);
        }
        for (int i = 0; i < out->nq; i++)
            out->Qq[i] = expr_add(P, out->Qq[i], named_where(&x, near, Qq[i], EXPR_ZERO, "near"));
        for (int i = 0; i < out->n; i++)
            out->Q[i] = expr_add(P, out->Q[i], named_where(&x, near, Q[i], EXPR_ZERO, "near"));
        free(prefix);
    }
    free(Qq);
    free(Q);
    free(x.F);
    free(x.tau);
}

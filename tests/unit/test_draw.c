/*
 * Unit tests of what a run's page draws (lower.c's draw and draw_mass),
 * without compiling any C: the lowered functions are evaluated
 * (lower_eval) at random states and held to closed forms built here
 * independently:
 *   the double pendulum's bobs at (l1 sin th1, -l1 cos th1, 0) and
 *   (x1 + l2 sin th2, y1 - l2 cos th2, 0);
 *   the rolling disk's pose: Rz(psi) Rx(theta) Rz(phi), orthonormal to
 *   1e-15, at its centre (x, y, 0) + Rz(psi) Rx(theta) (0, R, 0);
 *   a body turned by z-x-z Euler angles, one by a quaternion, a planar
 *   one by an angle; a view's point, frame and origin; a fixed
 *   parameter folded into a point; draw_mass against the spec's numbers;
 *   the view's links and traces and the items they name.
 * argv: specs/double_pendulum.yaml specs/rolling_disk.yaml
 */
#include "check.h"
#include "forms/forms.h"
#include "lower/lower.h"
#include "lower/lower_schedule.h"
#include "runtime/include/eomc_model.h"

#include <math.h>
#include <string.h>

static Arena *A;
static ExprPool *P;
static Diff *D;

static Lowered *
lowered(Spec *s)
{
    if (!s)
        return NULL;
    Mech *m = mech_build(s, A, P, D);
    Constraints *c = constraints_build(s, m, A, P, D);
    Invariant *inv = invariant_derive(s, m, c, A, P, D);
    char why[600];
    Eom *e = eom_derive_cheapest(s, m, c ? c->nc : 0, constraints_by_loads(c, 0), 0, A, P, D, why,
                                 sizeof why);
    if (!e)
        return NULL;
    return lower_model(s, m, e, c, e->form->eliminate, inv, LOWER_JACOBIAN_NONE,
                       LOWER_CODE_STRAIGHT, 0, A, P, D);
}

static void
draw(const Lowered *L, const double *q, const double *p, double *X)
{
    ExprEnv env = {0.25, {q, NULL, NULL, NULL}, p, NULL, {NULL, NULL}, NULL, NULL};
    lower_eval(P, L->draw, &env, (double *const[]){X});
}

/* C = A B */
static void
mul(const double *a, const double *b, double *c)
{
    double t[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            t[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    memcpy(c, t, sizeof t);
}

static void
rot_z(double a, double *R)
{
    double r[9] = {cos(a), -sin(a), 0, sin(a), cos(a), 0, 0, 0, 1};
    memcpy(R, r, sizeof r);
}

static void
rot_x(double a, double *R)
{
    double r[9] = {1, 0, 0, 0, cos(a), -sin(a), 0, sin(a), cos(a)};
    memcpy(R, r, sizeof r);
}

static double
max_diff(const double *a, const double *b, int n)
{
    double d = 0;
    for (int i = 0; i < n; i++)
        d = fmax(d, fabs(a[i] - b[i]));
    return d;
}

/* |R^T R - I|, entrywise */
static double
orthonormal_error(const double *R)
{
    double e = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double s = 0;
            for (int k = 0; k < 3; k++)
                s += R[3 * k + i] * R[3 * k + j];
            e = fmax(e, fabs(s - (i == j)));
        }
    return e;
}

static void
double_pendulum(const char *path)
{
    Lowered *L = lowered(spec_load(path, NULL, A, P));
    CHECK(L && L->draw && !L->draw_mass && L->model.ndraw == 3, "double pendulum: draw, no "
          "draw_mass (no bodies), 3 items (the view's origin)");
    if (!L)
        return;
    const LowModel *md = &L->model;
    CHECK(!strcmp(md->draw_item[0].name, "bob1") && md->draw_item[0].kind == EOMC_DRAW_PARTICLE &&
          md->draw_item[0].dim == 2 && !strcmp(md->draw_item[1].name, "bob2"),
          "double pendulum: items bob1, bob2, particles in the plane");
    /* view: links [[origin, bob1], [bob1, bob2]], trace [bob2] */
    CHECK((md->ndraw == 3 && !strcmp(md->draw_item[2].name, "origin") &&
                             md->draw_item[2].kind == EOMC_DRAW_POINT),
          "double pendulum: the view's origin is a point item");
    CHECK(md->nlink == 2 && md->view_link[0] == 2 && md->view_link[1] == 0 &&
          md->view_link[2] == 0 && md->view_link[3] == 1 && md->ntrace == 1 &&
          md->view_trace[0] == 1, "double pendulum: links origin-bob1, bob1-bob2, trace bob2");
    double p[5] = {1.0, 1.0, 1.3, 0.8, 9.81}; /* m1 m2 l1 l2 g */
    for (int trial = 0; trial < 5; trial++) {
        double q[2] = {check_rand(-3, 3), check_rand(-3, 3)};
        p[2] = check_rand(0.5, 2), p[3] = check_rand(0.5, 2);
        double X[3 * EOMC_POSE];
        draw(L, q, p, X);
        double x1 = p[2] * sin(q[0]), y1 = -p[2] * cos(q[0]);
        double want[2][3] = {{x1, y1, 0}, {x1 + p[3] * sin(q[1]), y1 - p[3] * cos(q[1]), 0}};
        double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[3] = {0, 0, 0};
        CHECK(max_diff(X, want[0], 3) <= 1e-15 && max_diff(X + 3, I, 9) == 0 &&
              max_diff(X + EOMC_POSE, want[1], 3) <= 2e-15 &&
              max_diff(X + EOMC_POSE + 3, I, 9) == 0 && max_diff(X + 2 * EOMC_POSE, zero, 3) == 0,
              "double pendulum at th = (%.3f, %.3f): bob1, bob2 at the closed form, unturned; "
              "origin at 0", q[0], q[1]);
    }
}

static void
rolling_disk(const char *path)
{
    Lowered *L = lowered(spec_load(path, NULL, A, P));
    CHECK(L && L->draw && L->draw_mass && L->model.ndraw == 1 &&
          L->model.draw_item[0].kind == EOMC_DRAW_BODY && L->model.draw_item[0].dim == 3,
          "rolling disk: one body item, 3-D");
    if (!L)
        return;
    double p[4] = {1.7, 0.45, 9.81, 6.0}; /* m R g spin */
    for (int trial = 0; trial < 5; trial++) {
        double q[5];
        for (int i = 0; i < 5; i++)
            q[i] = check_rand(-3, 3);
        double X[EOMC_POSE], R[9], Rx[9], Rz2[9];
        draw(L, q, p, X);
        rot_z(q[2], R);
        rot_x(q[3], Rx);
        rot_z(q[4], Rz2);
        mul(R, Rx, R); /* lean */
        double c[3] = {q[0] + p[1] * R[1], q[1] + p[1] * R[4], p[1] * R[7]};
        mul(R, Rz2, R);
        CHECK(max_diff(X, c, 3) <= 1e-15 && max_diff(X + 3, R, 9) <= 1e-15 &&
              orthonormal_error(X + 3) <= 1e-15,
              "rolling disk at a random state: centre and Rz(psi) Rx(theta) Rz(phi) to 1e-15 "
              "(%.2g, %.2g), R orthonormal to 1e-15 (%.2g)", max_diff(X, c, 3),
              max_diff(X + 3, R, 9), orthonormal_error(X + 3));
    }
    double Dm[EOMC_DRAW_MASS];
    ExprEnv env = {0, {NULL, NULL, NULL, NULL}, p, NULL, {NULL, NULL}, NULL, NULL};
    lower_eval(P, L->draw_mass, &env, (double *const[]){Dm});
    double m = p[0], r2 = p[1] * p[1];
    double want[13] = {m, 0, 0, 0, m * r2 / 4, 0, 0, 0, m * r2 / 4, 0, 0, 0, m * r2 / 2};
    CHECK(max_diff(Dm, want, 13) <= 1e-15, "rolling disk: draw_mass is m, centre 0, "
          "diag(m R^2/4, m R^2/4, m R^2/2)");
}

/* Bodies turned by z-x-z angles, a quaternion and a planar angle; a
 * particle; a view naming a point, a frame and the origin; L fixed. */
static const char *const spec_text =
    "parameters: {m: 2.0, a: 0.3, b: 0.2, c: 0.1, L: 0.7, g: 9.81}\n"
    "coordinates: [psi, theta, phi, e0, e1, e2, e3, x]\n"
    "frames:\n"
    "  f: {rotation: [{z: psi}]}\n"
    "points:\n"
    "  tip: {frame: f, at: [L, 0, 0]}\n"
    "bodies:\n"
    "  top: {mass: m, center: [0, 0, L], inertia: [a, a, b], rotation: {zxz: [psi, theta, phi]},\n"
    "        shapes: [{type: cylinder, size: [0.1, 0.2], pos: [0, 0, 0.2]},\n"
    "                 {type: sphere, size: [0.05], rgba: [1, 0, 0, 0.5]}]}\n"
    "  ball: {mass: m, center: [x, 0, 0], inertia: [[c, 0.01, 0], [0.01, c, 0], [0, 0, c]],\n"
    "         rotation: {quaternion: [e0, e1, e2, e3]}}\n"
    "particles:\n"
    "  bead: {mass: m, position: [x, L, 0]}\n"
    "effects:\n"
    "  gravity: {gravity: [0, 0, -g]}\n"
    "initial: {e0: 1}\n"
    "scene:\n"
    "  fix: {L: 0.7}\n"
    "  view:\n"
    "    links: [[origin, tip], [tip, top]]\n"
    "    trace: [bead, tip]\n"
    "    frames: [f]\n"
    "    camera: {position: [3, -3, 2], target: [0, 0, 0.5]}\n";

static const char *const planar_text =
    "parameters: {m: 2.0, c: 0.1}\n"
    "coordinates: [x, th]\n"
    "bodies:\n"
    "  slab: {mass: m, center: [x, 0], inertia: c, angle: 2*th}\n"
    "scene: {view: {camera: {position: [0, 0, 5], target: [0, 0, 0]}}}\n";

static void
turned_bodies(void)
{
    Spec *s = spec_load_buffer("draw.yaml", spec_text, strlen(spec_text), NULL, A, P);
    Lowered *L = lowered(s);
    CHECK(L != NULL, "the bodies' spec lowers");
    if (!L)
        return;
    const LowModel *md = &L->model;
    static const char *const names[] = {"top", "ball", "bead", "origin", "tip", "f"};
    static const int kinds[] = {EOMC_DRAW_BODY, EOMC_DRAW_BODY, EOMC_DRAW_PARTICLE,
                                EOMC_DRAW_POINT, EOMC_DRAW_POINT, EOMC_DRAW_FRAME};
    int items_ok = md->ndraw == 6;
    for (int k = 0; items_ok && k < 6; k++)
        items_ok = !strcmp(md->draw_item[k].name, names[k]) && md->draw_item[k].kind == kinds[k];
    CHECK(items_ok, "items: the bodies, the particle, then origin, tip, f in the view's order");
    CHECK(md->nlink == 2 && md->view_link[0] == 3 && md->view_link[1] == 4 &&
          md->view_link[2] == 4 && md->view_link[3] == 0 && md->ntrace == 2 &&
          md->view_trace[0] == 2 && md->view_trace[1] == 4 && md->view_frames == 1,
          "links origin-tip, tip-top; traces bead, tip; frames drawn");
    double cam[9] = {3, -3, 2, 0, 0, 0.5, 0, 0, 1};
    CHECK(md->has_camera && max_diff(md->camera, cam, 9) == 0, "camera, up [0, 0, 1] in 3-D");
    CHECK(md->nshape == 2 && md->shape[0].body == 0 && md->shape[0].type == EOMC_SHAPE_CYLINDER &&
          md->shape[0].size[0] == 0.1 && md->shape[0].size[1] == 0.2 &&
          md->shape[0].pos[2] == 0.2 && md->shape[0].quat[0] == 1 &&
          md->shape[1].type == EOMC_SHAPE_SPHERE && md->shape[1].rgba[0] == 1 &&
          md->shape[1].rgba[3] == 0.5 && md->shape[1].size[1] == 0,
          "shapes: a cylinder and a sphere of body 0, defaults filled in");
    double p[6] = {2.0, 0.3, 0.2, 0.1, 99.0, 9.81}; /* L is fixed at 0.7: 99 is not read */
    for (int trial = 0; trial < 5; trial++) {
        double q[8];
        for (int i = 0; i < 8; i++)
            q[i] = check_rand(-3, 3);
        double n = sqrt(q[3] * q[3] + q[4] * q[4] + q[5] * q[5] + q[6] * q[6]);
        for (int i = 3; i < 7; i++)
            q[i] /= n;
        double X[6 * EOMC_POSE];
        draw(L, q, p, X);
        double R[9], Rx[9], Rz2[9];
        rot_z(q[0], R);
        rot_x(q[1], Rx);
        rot_z(q[2], Rz2);
        mul(R, Rx, R);
        mul(R, Rz2, R);
        double c0[3] = {0, 0, 0.7};
        CHECK(max_diff(X, c0, 3) == 0 && max_diff(X + 3, R, 9) <= 1e-15 &&
              orthonormal_error(X + 3) <= 1e-15,
              "top: Rz(psi) Rx(theta) Rz(phi) to 1e-15 (%.2g), orthonormal (%.2g)",
              max_diff(X + 3, R, 9), orthonormal_error(X + 3));
        /* the quaternion's matrix, written out */
        double w = q[3], x = q[4], y = q[5], z = q[6];
        double Rq[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                        2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                        2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)};
        const double *B = X + EOMC_POSE;
        CHECK(B[0] == q[7] && B[1] == 0 && B[2] == 0 && max_diff(B + 3, Rq, 9) <= 2e-15 &&
              orthonormal_error(B + 3) <= 2e-15,
              "ball: the unit quaternion's rotation to 2e-15 (%.2g), orthonormal (%.2g)",
              max_diff(B + 3, Rq, 9), orthonormal_error(B + 3));
        double bead[3] = {q[7], 0.7, 0}, tip[3] = {0.7 * cos(q[0]), 0.7 * sin(q[0]), 0};
        double Rf[9], I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[3] = {0, 0, 0};
        rot_z(q[0], Rf);
        CHECK(max_diff(X + 2 * EOMC_POSE, bead, 3) == 0 &&
              max_diff(X + 2 * EOMC_POSE + 3, I, 9) == 0 &&
              max_diff(X + 3 * EOMC_POSE, zero, 3) == 0 &&
              max_diff(X + 4 * EOMC_POSE, tip, 3) <= 1e-15 &&
              max_diff(X + 4 * EOMC_POSE + 3, I, 9) == 0 &&
              max_diff(X + 5 * EOMC_POSE, zero, 3) == 0 &&
              max_diff(X + 5 * EOMC_POSE + 3, Rf, 9) <= 1e-15,
              "bead, origin, tip (L fixed at 0.7), frame f (at the origin, Rz(psi))");
    }
    double Dm[2 * EOMC_DRAW_MASS];
    ExprEnv env = {0, {NULL, NULL, NULL, NULL}, p, NULL, {NULL, NULL}, NULL, NULL};
    lower_eval(P, L->draw_mass, &env, (double *const[]){Dm});
    double want[26] = {2, 0, 0, 0, 0.3, 0, 0, 0, 0.3, 0, 0, 0, 0.2,
                       2, 0, 0, 0, 0.1, 0.01, 0, 0.01, 0.1, 0, 0, 0, 0.1};
    CHECK(max_diff(Dm, want, 26) == 0, "draw_mass: the spec's masses and inertias (a tensor "
          "with products too)");

    s = spec_load_buffer("planar.yaml", planar_text, strlen(planar_text), NULL, A, P);
    L = lowered(s);
    CHECK(L && L->model.ndraw == 1 && L->model.draw_item[0].dim == 2, "planar body: one item");
    if (!L)
        return;
    double cam2[9] = {0, 0, 5, 0, 0, 0, 0, 1, 0};
    CHECK(max_diff(L->model.camera, cam2, 9) == 0, "planar: the camera's up is [0, 1, 0]");
    double q[2] = {0.3, 0.7}, pp[2] = {2.0, 0.1}, X[EOMC_POSE];
    draw(L, q, pp, X);
    double c = cos(1.4), sn = sin(1.4);
    double want2[12] = {0.3, 0, 0, c, -sn, 0, sn, c, 0, 0, 0, 1};
    CHECK(max_diff(X, want2, 12) <= 1e-16, "planar: at (x, 0, 0) turned by 2 th about z");
    lower_eval(P, L->draw_mass, &env, (double *const[]){Dm});
    double want3[13] = {2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0.1};
    env.p = pp;
    lower_eval(P, L->draw_mass, &env, (double *const[]){Dm});
    CHECK(max_diff(Dm, want3, 13) == 0, "planar: draw_mass's inertia about z");
}

/* A planar slab, a particle, a point the view names, and `ground:`: the
 * ground is an item of its own after the particle and before the view's
 * point, drawn as a body at the world's origin in its axes, planar where
 * all else is; its shapes in the world's axes; a view's "ground" is the
 * spec's point of that name, not it. */
static const char *const ground_text =
    "coordinates: [x, th]\n"
    "points:\n"
    "  ground: {at: [1, 2]}\n"
    "bodies:\n"
    "  slab: {mass: 2, center: [x, 0], inertia: 0.1, angle: th,\n"
    "         shapes: [{type: box, size: [0.2, 0.1, 0.05]}]}\n"
    "particles:\n"
    "  bead: {mass: 1, position: [0, x]}\n"
    "ground:\n"
    "  - {type: box, size: [1, 1, 0.1], pos: [0, -1, 0]}\n"
    "  - {type: cylinder, size: [0.1, 0.5], quat: [0, 1, 0, 0], rgba: [1, 0, 0, 1]}\n"
    "scene: {view: {links: [[ground, bead]]}}\n";

static void
ground(void)
{
    Spec *s = spec_load_buffer("ground.yaml", ground_text, strlen(ground_text), NULL, A, P);
    Lowered *L = lowered(s);
    CHECK(L != NULL, "ground: the spec lowers");
    if (!L)
        return;
    const LowModel *md = &L->model;
    CHECK(md->ndraw == 4 && !strcmp(md->draw_item[2].name, "ground") &&
          md->draw_item[2].kind == EOMC_DRAW_BODY && md->draw_item[2].dim == 2 &&
          !strcmp(md->draw_item[3].name, "ground") && md->draw_item[3].kind == EOMC_DRAW_POINT,
          "ground: slab, bead, the ground (a planar body), then the view's point 'ground'");
    CHECK(md->nlink == 1 && md->view_link[0] == 3 && md->view_link[1] == 1,
          "ground: the view's link is from the point named ground, not from the ground");
    CHECK(md->nshape == 3 && md->shape[0].body == 0 && md->shape[1].body == 2 &&
          md->shape[1].size[2] == 0.1 && md->shape[1].pos[1] == -1 &&
          md->shape[2].body == 2 && md->shape[2].type == EOMC_SHAPE_CYLINDER &&
          md->shape[2].quat[1] == 1 && md->shape[2].rgba[0] == 1,
          "ground: the slab's box, then the ground's box and cylinder, as written");
    double q[2] = {0.3, 0.7}, X[4 * EOMC_POSE];
    draw(L, q, NULL, X);
    double want[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, pt[3] = {1, 2, 0};
    CHECK(max_diff(X + 2 * EOMC_POSE, want, 12) == 0 && max_diff(X + 3 * EOMC_POSE, pt, 3) == 0,
          "ground: at the origin, unturned; the point at (1, 2, 0)");
}

int
main(int argc, char **argv)
{
    A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    if (argc < 3) {
        fprintf(stderr, "usage: test_draw double_pendulum.yaml rolling_disk.yaml\n");
        return 2;
    }
    double_pendulum(argv[1]);
    rolling_disk(argv[2]);
    turned_bodies();
    ground();
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}

/*
 * freebody.c: hand-written models whose speeds are not their coordinates'
 * rates, as eomc generates a free joint (models.h has what they are).
 * The state is q = (x, y, z, e0, e1, e2, e3), the centre of mass and the
 * unit quaternion that turns the body's axes into the world's, and
 * v = (x', y', z', wx, wy, wz), the centre's world velocity and the
 * angular velocity in the body's axes, MuJoCo's qpos and qvel; q' = W(q) v
 * is x' for the centre and e' = e (x) (0, w) / 2 for the quaternion.
 *
 * Compiled twice, as eomc compiles a generated model: as it is, and with
 * -DEOMC_EXTENDED for the twin the reference solution evaluates (in
 * eomc_real: double, or long double).
 */
#include "eomc_model.h"
#include "models.h"

#include <stddef.h>

/* ---- rotations of a quaternion (the homogeneous formula: a rotation
 * when |e| = 1, and what the model computes off it) ---- */

/* R (row-major [9]) from e [4]. */
static void
rot(const eomc_real *e, eomc_real *R)
{
    eomc_real a = e[0], b = e[1], c = e[2], d = e[3];
    R[0] = a * a + b * b - c * c - d * d, R[1] = 2 * (b * c - a * d), R[2] = 2 * (b * d + a * c);
    R[3] = 2 * (b * c + a * d), R[4] = a * a - b * b + c * c - d * d, R[5] = 2 * (c * d - a * b);
    R[6] = 2 * (b * d - a * c), R[7] = 2 * (c * d + a * b), R[8] = a * a - b * b - c * c + d * d;
}

/* ---- the kinematic equation, shared by both models ---- */

static void
fb_qdot(const eomc_real *q, const eomc_real *v, eomc_real *qd)
{
    const eomc_real *e = q + 3, *w = v + 3;
    qd[0] = v[0], qd[1] = v[1], qd[2] = v[2];
    qd[3] = -(e[1] * w[0] + e[2] * w[1] + e[3] * w[2]) / 2;
    qd[4] = (e[0] * w[0] + e[2] * w[2] - e[3] * w[1]) / 2;
    qd[5] = (e[0] * w[1] + e[3] * w[0] - e[1] * w[2]) / 2;
    qd[6] = (e[0] * w[2] + e[1] * w[1] - e[2] * w[0]) / 2;
}

/* w x (In w) for In = diag(I1, I2, I3): Euler's gyroscopic term. */
static void
gyro(const eomc_real *In, const eomc_real *w, eomc_real *c)
{
    c[0] = (In[2] - In[1]) * w[1] * w[2];
    c[1] = (In[0] - In[2]) * w[0] * w[2];
    c[2] = (In[1] - In[0]) * w[0] * w[1];
}

/* The free body's M = diag(m, m, m, I1, I2, I3) and h = (0, 0, m g,
 * w x In w): In its inertia about the centre in its axes (not I, which
 * tgmath.h makes the imaginary unit). */
static void
body_mass_bias(eomc_real mass, const eomc_real *In, eomc_real g, const eomc_real *v,
               eomc_real *M, eomc_real *h)
{
    for (int i = 0; i < 36; i++)
        M[i] = 0;
    M[0] = M[7] = M[14] = mass;
    M[21] = In[0], M[28] = In[1], M[35] = In[2];
    h[0] = h[1] = 0;
    h[2] = mass * g;
    gyro(In, v + 3, h + 3);
}

static void
no_inputs(eomc_real t, const eomc_real *p, eomc_real *u, eomc_real *dudt)
{
    (void)t, (void)p, (void)u, (void)dudt;
}

/* ---- the free body: p = (m, I1, I2, I3, g) ---- */

static void
fb_mass_bias(eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p,
             const eomc_real *u, eomc_real *M, eomc_real *h)
{
    (void)t, (void)q, (void)u;
    body_mass_bias(p[0], p + 1, p[4], v, M, h);
}

/* ---- the heavy symmetric top: the free body (p = (m, A, C, l, g),
 * inertia diag(A, A, C) about the centre) whose tip, at -l along its
 * axis z, is held at the world's origin by tip_x, tip_y, tip_z:
 * g = x + R (0, 0, -l) = 0 ---- */

/* The top's inertia about its centre in its axes. */
static void
top_inertia(const eomc_real *p, eomc_real *In)
{
    In[0] = In[1] = p[1];
    In[2] = p[2];
}

static void
top_mass_bias(eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p,
              const eomc_real *u, eomc_real *M, eomc_real *h)
{
    (void)t, (void)q, (void)u;
    eomc_real In[3];
    top_inertia(p, In);
    body_mass_bias(p[0], In, p[4], v, M, h);
}

/* f = a + R (w' x r) + R (w x (w x r)), r = (0, 0, -l), and B = df/da. */
static void
top_constraint(eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *a,
               const eomc_real *p, const eomc_real *u, eomc_real *f, eomc_real *B)
{
    (void)t, (void)u;
    eomc_real R[9], l = p[3];
    const eomc_real *w = v + 3, *dw = a + 3;
    rot(q + 3, R);
    /* w x (w x r) */
    eomc_real ww[3] = {-l * w[0] * w[2], -l * w[1] * w[2], l * (w[0] * w[0] + w[1] * w[1])};
    for (int k = 0; k < 3; k++) {
        f[k] = a[k] + l * (dw[0] * R[3 * k + 1] - dw[1] * R[3 * k]) +
               R[3 * k] * ww[0] + R[3 * k + 1] * ww[1] + R[3 * k + 2] * ww[2];
        for (int j = 0; j < 6; j++)
            B[6 * k + j] = 0;
        B[6 * k + k] = 1;
        B[6 * k + 3] = l * R[3 * k + 1];
        B[6 * k + 4] = -l * R[3 * k];
    }
}

#ifndef EOMC_EXTENDED

#include <math.h>

/* dR/de_k into D [9]. */
static void
drot(const eomc_real *e, int k, eomc_real *D)
{
    eomc_real a = e[0], b = e[1], c = e[2], d = e[3];
    const eomc_real rows[4][9] = {
        {a, -d, c, d, a, -b, -c, b, a},
        {b, c, d, c, -b, -a, d, a, -b},
        {-c, b, a, b, c, d, -a, d, -c},
        {-d, -a, b, a, -d, c, b, c, d},
    };
    for (int i = 0; i < 9; i++)
        D[i] = 2 * rows[k][i];
}


static const char *const fb_q[] = {"root_x", "root_y", "root_z", "root_e0", "root_e1",
                                   "root_e2", "root_e3"};
static const char *const fb_v[] = {"root_x'", "root_y'", "root_z'", "root_wx", "root_wy",
                                   "root_wz"};
static const int fb_quat[] = {3, 4, 5, 6};
static const char *const no_u[] = {NULL};
static const unsigned char no_fixed[8];
static const char *const fb_p[] = {"m", "I1", "I2", "I3", "g"};
static const double fb_pdef[] = {FREEBODY_M, FREEBODY_I1, FREEBODY_I2, FREEBODY_I3,
                                 FREEBODY_G};

static void
fb_initial(const double *p, double *q, double *v)
{
    (void)p;
    freebody_start(q, v);
}

static void
fb_energy(double t, const double *q, const double *v, const double *p, const double *u,
          double *TV)
{
    (void)t, (void)u;
    TV[0] = 0.5 * p[0] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
            0.5 * (p[1] * v[3] * v[3] + p[2] * v[4] * v[4] + p[3] * v[5] * v[5]);
    TV[1] = p[0] * p[4] * q[2];
}

static void
fb_invariant(double t, const double *q, const double *v, const double *p, const double *u,
             double *h)
{
    double TV[2];
    fb_energy(t, q, v, p, u, TV);
    h[0] = TV[0] + TV[1];
}

/* dE/dq = 0 (gravity is uniform, the inertia the body's own); dE/dv:
 * the gyroscopic term's. */
static void
body_dEdv(const double *In, const double *w, double *dEdv)
{
    for (int i = 0; i < 36; i++)
        dEdv[i] = 0;
    double *r = dEdv + 18; /* rows 3 .. 5, columns 3 .. 5 */
    r[4] = (In[2] - In[1]) * w[2], r[5] = (In[2] - In[1]) * w[1];
    r[9] = (In[0] - In[2]) * w[2], r[11] = (In[0] - In[2]) * w[0];
    r[15] = (In[1] - In[0]) * w[1], r[16] = (In[1] - In[0]) * w[0];
}

static void
fb_jacobian(double t, const double *q, const double *v, const double *a, const double *p,
            const double *u, double *dEdq, double *dEdv, double *dEdu, double *dEdt)
{
    (void)t, (void)q, (void)a, (void)u, (void)dEdu;
    for (int i = 0; i < 6 * 7; i++)
        dEdq[i] = 0;
    body_dEdv(p + 1, v + 3, dEdv);
    for (int i = 0; i < 6; i++)
        dEdt[i] = 0;
}

static void
fb_qdot_jacobian(const double *q, const double *v, double *dqdq, double *dqdv)
{
    const double *e = q + 3, *w = v + 3;
    for (int i = 0; i < 49; i++)
        dqdq[i] = 0;
    for (int i = 0; i < 42; i++)
        dqdv[i] = 0;
    dqdv[0] = dqdv[7] = dqdv[14] = 1;
    const double de[4][4] = {{0, -w[0], -w[1], -w[2]},
                             {w[0], 0, w[2], -w[1]},
                             {w[1], -w[2], 0, w[0]},
                             {w[2], w[1], -w[0], 0}};
    const double dw[4][3] = {{-e[1], -e[2], -e[3]},
                             {e[0], -e[3], e[2]},
                             {e[3], e[0], -e[1]},
                             {-e[2], e[1], e[0]}};
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++)
            dqdq[(3 + i) * 7 + 3 + j] = de[i][j] / 2;
        for (int j = 0; j < 3; j++)
            dqdv[(3 + i) * 6 + 3 + j] = dw[i][j] / 2;
    }
}

/* The unconstrained accelerations as a generated accel gives them (M is
 * diagonal: its pivots are its diagonal, each its own M_kk). */
static int
body_accel(double g, const double *In, const double *v, double *a, double *pivot)
{
    double c[3];
    gyro(In, v + 3, c);
    a[0] = a[1] = 0;
    a[2] = -g;
    for (int i = 0; i < 3; i++)
        a[3 + i] = -c[i] / In[i];
    if (pivot)
        *pivot = 1;
    return 0;
}

static int
fb_accel(double t, const double *q, const double *v, const double *p, const double *u,
         double *a, double *pivot)
{
    (void)t, (void)q, (void)u;
    return body_accel(p[4], p + 1, v, a, pivot);
}

#define FREEBODY_COMMON                                                                   \
    .abi = EOMC_ABI_VERSION, .spec = "freebody.yaml", .form = "lagrange", .options = "",  \
    .nq = 7, .np = 5, .nu = 0, .q_names = fb_q, .p_names = fb_p, .u_names = no_u,         \
    .p_default = fb_pdef, .scene = "", .p_fixed = no_fixed, .t_end = 2.0, .dt = 0.05,     \
    .method = "rk8pd", .rtol = 1e-10, .atol = 1e-10, .initial = fb_initial,              \
    .inputs = no_inputs, .mass_bias = fb_mass_bias, .energy = fb_energy,                 \
    .jacobian = fb_jacobian, .c_affine = 1, .invariant = fb_invariant,                   \
    .invariant_name = "E", .invariant_note = "E = T + V is conserved", .nv = 6,        \
    .v_names = fb_v, .qdot = fb_qdot, .qdot_jacobian = fb_qdot_jacobian, .nquat = 1,     \
    .quat = fb_quat
#define NO_SERIES "a hand-written model without series"

const eomc_model freebody_model = {FREEBODY_COMMON, .name = "freebody",
                                   .taylor_why = NO_SERIES};
const eomc_model freebody_accel_model = {FREEBODY_COMMON, .name = "freebody_accel",
                                         .accel = fb_accel, .taylor_why = NO_SERIES};

/* Series that must never run: a model with speeds of their own and series,
 * but without the series of q' = W(q) v (taylor_qd) that Taylor's method
 * sums q from (the runtime refuses before). */
static void
fb_no_series(int k, int K, double t0, const double *p, const double *u, double *T)
{
    (void)k, (void)K, (void)t0, (void)p, (void)u, (void)T;
}
const eomc_model freebody_series_model = {FREEBODY_COMMON, .name = "freebody_series",
                                          .taylor = fb_no_series};

/* ---- the free body bouncing on the floor z = 0 (its centre: an
 * elastic `set` of z'), with the output wz_rate = wz' ---- */

static const char *const fb_ev[] = {"floor"};
static const int fb_ev_dir[] = {-1};
static const int fb_ev_act[] = {EOMC_EVENT_SET};
static const char *const fb_out[] = {"wz_rate"};

static void
fb_events(double t, const double *q, const double *v, const double *p, const double *u,
          double *g)
{
    (void)t, (void)v, (void)p, (void)u;
    g[0] = q[2];
}

static void
fb_event_set(int k, double t, const double *q, const double *v, const double *p,
             const double *u, double *q1, double *v1)
{
    (void)k, (void)t, (void)q, (void)p, (void)u, (void)q1;
    v1[2] = -v[2];
}

static void
fb_outputs(double t, const double *q, const double *v, const double *a, const double *p,
           const double *u, const double *lam, double *out)
{
    (void)t, (void)q, (void)v, (void)p, (void)u, (void)lam;
    out[0] = a[5];
}

const eomc_model freebody_bounce_model = {
    FREEBODY_COMMON, .name = "freebody_bounce", .taylor_why = NO_SERIES,
    .nout = 1, .out_names = fb_out, .outputs = fb_outputs,
    .nevent = 1, .ev_names = fb_ev, .ev_direction = fb_ev_dir, .ev_action = fb_ev_act,
    .events = fb_events, .event_set = fb_event_set,
};

/* ---- the top ---- */

static const char *const top_p[] = {"m", "A", "C", "l", "g"};
static const double top_pdef[] = {TOP_M, TOP_A, TOP_C, TOP_L, TOP_G};
static const char *const top_c[] = {"tip_x", "tip_y", "tip_z"};
static const int top_order[] = {0, 0, 0};
static const int top_dep[] = {0, 1, 2};

static void
top_initial(const double *p, double *q, double *v)
{
    top_start(p, q, v);
}

static void
top_energy(double t, const double *q, const double *v, const double *p, const double *u,
           double *TV)
{
    (void)t, (void)u;
    TV[0] = 0.5 * p[0] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) +
            0.5 * (p[1] * (v[3] * v[3] + v[4] * v[4]) + p[2] * v[5] * v[5]);
    TV[1] = p[0] * p[4] * q[2];
}

static void
top_invariant(double t, const double *q, const double *v, const double *p, const double *u,
              double *h)
{
    double TV[2];
    top_energy(t, q, v, p, u, TV);
    h[0] = TV[0] + TV[1];
}

static void
top_jacobian(double t, const double *q, const double *v, const double *a, const double *p,
             const double *u, double *dEdq, double *dEdv, double *dEdu, double *dEdt)
{
    (void)t, (void)q, (void)a, (void)u, (void)dEdu;
    double In[3];
    top_inertia(p, In);
    for (int i = 0; i < 6 * 7; i++)
        dEdq[i] = 0;
    body_dEdv(In, v + 3, dEdv);
    for (int i = 0; i < 6; i++)
        dEdt[i] = 0;
}

/* pos = g = x - l R e_z, vel = g' = x' + l (wx R e_y - wy R e_x). */
static void
top_levels(double t, const double *q, const double *v, const double *p, const double *u,
           double *pos, double *vel)
{
    (void)t, (void)u;
    double R[9], l = p[3];
    rot(q + 3, R);
    for (int k = 0; k < 3; k++) {
        pos[k] = q[k] - l * R[3 * k + 2];
        vel[k] = v[k] + l * (v[3] * R[3 * k + 1] - v[4] * R[3 * k]);
    }
}

static void
top_c_jacobian(double t, const double *q, const double *v, const double *a, const double *p,
               const double *u, double *dfdq, double *dfdv, double *dfdu, double *dfdt,
               double *dBdq, double *dBdv, double *dBda, double *dBdu, double *dBdt)
{
    (void)t, (void)u, (void)dfdu, (void)dBdu;
    double R[9], D[4][9], l = p[3];
    const double *w = v + 3, *dw = a + 3;
    rot(q + 3, R);
    for (int m = 0; m < 4; m++)
        drot(q + 3, m, D[m]);
    double ww[3] = {-l * w[0] * w[2], -l * w[1] * w[2], l * (w[0] * w[0] + w[1] * w[1])};
    /* d(w x (w x r))/dw, row j, column i */
    double dww[3][3] = {{-l * w[2], 0, -l * w[0]},
                        {0, -l * w[2], -l * w[1]},
                        {2 * l * w[0], 2 * l * w[1], 0}};
    for (int i = 0; i < 3 * 6 * 7; i++)
        dBdq[i] = 0;
    for (int i = 0; i < 3 * 6 * 6; i++)
        dBdv[i] = dBda[i] = 0;
    for (int i = 0; i < 3 * 6; i++)
        dBdt[i] = 0;
    for (int k = 0; k < 3; k++) {
        dfdt[k] = 0;
        for (int j = 0; j < 3; j++)
            dfdq[7 * k + j] = 0;
        for (int m = 0; m < 4; m++) {
            const double *Dm = D[m];
            dfdq[7 * k + 3 + m] = l * (dw[0] * Dm[3 * k + 1] - dw[1] * Dm[3 * k]) +
                                  Dm[3 * k] * ww[0] + Dm[3 * k + 1] * ww[1] +
                                  Dm[3 * k + 2] * ww[2];
            dBdq[(6 * k + 3) * 7 + 3 + m] = l * Dm[3 * k + 1];
            dBdq[(6 * k + 4) * 7 + 3 + m] = -l * Dm[3 * k];
        }
        for (int j = 0; j < 3; j++)
            dfdv[6 * k + j] = 0;
        for (int i = 0; i < 3; i++)
            dfdv[6 * k + 3 + i] = R[3 * k] * dww[0][i] + R[3 * k + 1] * dww[1][i] +
                                  R[3 * k + 2] * dww[2][i];
    }
}

static void
top_c_levels_jacobian(double t, const double *q, const double *v, const double *p,
                      const double *u, double *dposdq, double *dveldq, double *dveldv,
                      double *dposdu, double *dveldu, double *dposdt, double *dveldt)
{
    (void)t, (void)u, (void)dposdu, (void)dveldu;
    double R[9], D[4][9], l = p[3];
    rot(q + 3, R);
    for (int m = 0; m < 4; m++)
        drot(q + 3, m, D[m]);
    for (int k = 0; k < 3; k++) {
        dposdt[k] = dveldt[k] = 0;
        for (int j = 0; j < 3; j++)
            dposdq[7 * k + j] = j == k, dveldq[7 * k + j] = 0;
        for (int m = 0; m < 4; m++) {
            dposdq[7 * k + 3 + m] = -l * D[m][3 * k + 2];
            dveldq[7 * k + 3 + m] = l * (v[3] * D[m][3 * k + 1] - v[4] * D[m][3 * k]);
        }
        for (int j = 0; j < 6; j++)
            dveldv[6 * k + j] = j == k;
        dveldv[6 * k + 3] = l * R[3 * k + 1];
        dveldv[6 * k + 4] = -l * R[3 * k];
    }
}

/* |x_k| + l times the terms of R_k2, each made positive. */
static void
top_scale(double t, const double *q, const double *p, const double *u, double *mag)
{
    (void)t, (void)u;
    const double *e = q + 3;
    double l = p[3];
    mag[0] = fabs(q[0]) + 2 * l * (fabs(e[1] * e[3]) + fabs(e[0] * e[2]));
    mag[1] = fabs(q[1]) + 2 * l * (fabs(e[2] * e[3]) + fabs(e[0] * e[1]));
    mag[2] = fabs(q[2]) + l * (e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
}

/* The unit loads: the free top's accelerations, and M^-1 (diagonal). */
static int
top_free_accel(double t, const double *q, const double *v, const double *p, const double *u,
               double *a, double *pivot)
{
    (void)t, (void)q, (void)u;
    double In[3];
    top_inertia(p, In);
    return body_accel(p[4], In, v, a, pivot);
}

static void
top_minv(double t, const double *q, const double *v, const double *p, const double *u,
         const double *x, double *y)
{
    (void)t, (void)q, (void)v, (void)u;
    double d[6] = {p[0], p[0], p[0], p[1], p[1], p[2]};
    for (int i = 0; i < 6; i++)
        y[i] = x[i] / d[i];
}

#define TOP_COMMON                                                                        \
    .abi = EOMC_ABI_VERSION, .spec = "top.yaml", .form = "lagrange", .options = "",       \
    .nq = 7, .np = 5, .nu = 0, .q_names = fb_q, .p_names = top_p, .u_names = no_u,        \
    .p_default = top_pdef, .scene = "", .p_fixed = no_fixed, .t_end = 2.0, .dt = 0.05,    \
    .method = "rk8pd", .rtol = 1e-10, .atol = 1e-10, .initial = top_initial,             \
    .inputs = no_inputs, .mass_bias = top_mass_bias, .energy = top_energy,               \
    .jacobian = top_jacobian, .nc = 3, .c_names = top_c, .c_order = top_order,           \
    .c_dependent = top_dep, .c_affine = 1, .eliminate = 0,                               \
    .constraint = top_constraint, .c_levels = top_levels,                                \
    .c_jacobian = top_c_jacobian, .c_levels_jacobian = top_c_levels_jacobian,            \
    .invariant = top_invariant, .invariant_name = "E",                                   \
    .invariant_note = "E = T + V is conserved",                                          \
    .taylor_why = NO_SERIES, .nv = 6, .v_names = fb_v, .qdot = fb_qdot,                  \
    .qdot_jacobian = fb_qdot_jacobian, .nquat = 1, .quat = fb_quat

const eomc_model top_model = {TOP_COMMON, .name = "top", .c_scale = top_scale};
const eomc_model top_noscale_model = {TOP_COMMON, .name = "top_noscale"};
const eomc_model top_loads_model = {TOP_COMMON, .name = "top_loads", .c_scale = top_scale,
                                    .free_accel = top_free_accel, .minv = top_minv};

#else /* the twins: what the reference evaluates */

const eomc_model_ext freebody_model_ext = {
    .abi = EOMC_ABI_VERSION, .name = "freebody", .qdot = fb_qdot, .inputs = no_inputs,
    .mass_bias = fb_mass_bias,
};
const eomc_model_ext top_model_ext = {
    .abi = EOMC_ABI_VERSION, .name = "top", .qdot = fb_qdot, .inputs = no_inputs,
    .mass_bias = top_mass_bias, .constraint = top_constraint,
};

#endif

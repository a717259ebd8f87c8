/*
 * models.c: hand-written models for the runtime tests (see models.h).
 * Each is what eomc would generate: straight-line functions of the residual
 * E(t, q, q', q'') = M q'' + h, its exact partial derivatives, T and V.
 */
#include <math.h>
#include <stddef.h>

#include "models.h"
#include "eomc_taylor.h"

/* ---- the harmonic oscillator: E = m x'' + k x ---- */

static const char *const osc_q[] = {"x"};
static const char *const osc_p[] = {"m", "k", "x0"};
static const char *const osc_u[] = {NULL};
static const double osc_pdef[] = {OSC_M, OSC_K, OSC_X0};

static void
osc_initial(const double *p, double *q, double *v)
{
    q[0] = p[2];
    v[0] = OSC_V0;
}

static void
no_inputs(double t, const double *p, double *u, double *dudt)
{
    (void)t;
    (void)p;
    (void)u;
    (void)dudt;
}

static void
osc_mass_bias(double t, const double *q, const double *v, const double *p,
              const double *u, double *M, double *h)
{
    (void)t;
    (void)v;
    (void)u;
    M[0] = p[0];
    h[0] = p[1] * q[0];
}

static void
osc_energy(double t, const double *q, const double *v, const double *p,
           const double *u, double *TV)
{
    (void)t;
    (void)u;
    TV[0] = 0.5 * p[0] * v[0] * v[0];
    TV[1] = 0.5 * p[1] * q[0] * q[0];
}

static void
osc_jacobian(double t, const double *q, const double *v, const double *a,
             const double *p, const double *u, double *dEdq, double *dEdv,
             double *dEdu, double *dEdt)
{
    (void)t;
    (void)q;
    (void)v;
    (void)a;
    (void)u;
    (void)dEdu;
    dEdq[0] = p[1];
    dEdv[0] = 0.0;
    dEdt[0] = 0.0;
}

/* The generator's 1x1 LDL^T: d_0 = M_00, pivot check d_0 > TOL M_00. */
static int
osc_accel(double t, const double *q, const double *v, const double *p,
          const double *u, double *a, double *pivot)
{
    (void)t;
    (void)v;
    (void)u;
    double M = p[0], h = p[1] * q[0], piv = M - EOMC_PIVOT_TOL * M;
    a[0] = piv > 0.0 ? -h / M : NAN;
    if (pivot)
        *pivot = 1.0; /* d_0 / M_00 */
    return piv > 0.0 ? 0 : 1;
}

/* Taylor's method's series, as eomc would generate them: slot 0 is x
 * (the caller's), 1 is M = m, 2 is k, 3 is h = k x. */
static const int osc_taylor_q[] = {0}, osc_taylor_v[] = {-1}, osc_taylor_M[] = {1},
                 osc_taylor_h[] = {3}, osc_taylor_g[] = {0};

static void
osc_taylor(int k, int K, double t0, const double *p, const double *u, double *T)
{
    (void)t0;
    (void)u;
    const int S = K + 1;
    eomc_tay_const(T + 1 * S, p[0], k);
    eomc_tay_const(T + 2 * S, p[1], k);
    eomc_tay_scale(T + 3 * S, T + 2 * S, T + 0 * S, k);
}

/* No speeds (v = q'), no recursion shared by unit loads, no series of
 * q' = W(q) v, nothing known of M's series and no taylor_run, no
 * switches and no dry friction (the last members). */
#define NO_SPEEDS 0, NULL, NULL, NULL, 0, NULL, 0, NULL, NULL, NULL, 0, NULL, NULL, 0, NULL, NULL, \
    0, NULL, NULL, NULL, NULL, NULL, NULL

#define OSC_TAYLOR 4, osc_taylor_q, osc_taylor_v, osc_taylor_M, osc_taylor_h, osc_taylor_g, \
    NULL, NULL, NULL, NULL, NULL, osc_taylor, NULL, NO_SPEEDS

/* No parameter is fixed (p_fixed). */
static const unsigned char no_fixed[8];

/* The constraint members of a model without constraints. */
#define NO_CONSTRAINTS 0, NULL, NULL, NULL, 1, 0, NULL, NULL, NULL, NULL
#define NO_INVARIANT NULL, NULL, "nothing is conserved: a hand-written test model"
/* The physical-data members of a model with nothing to check. */
#define NO_CHECKS 0, NULL, NULL, NULL
/* Nothing to draw (--animate): the members after c_nz, and no places
 * (eomc_sim_place); and no Taylor series (the last members but the
 * speeds). */
#define NO_TAYLOR 0, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, \
    "a hand-written test model", NO_SPEEDS
#define NO_PLACES 0, NULL, NULL, NULL
#define NO_DRAW_BUT(...) 0, NULL, NULL, NULL, 0, NULL, 0, 0, 0, NULL, NULL, NULL, NULL, 0.0, NULL, \
    NO_PLACES, __VA_ARGS__
#define NO_DRAW NO_DRAW_BUT(NO_TAYLOR)
/* ... and no outputs nor events (they follow the checks), nor the scene's
 * assembly, nor a sparse mass matrix, nor unit loads, nor drawing (but
 * for the Taylor series given). */
#define NO_OUTPUTS_BUT(...) 0, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL, 0, NULL, NULL, NULL, NULL, NULL, NULL, 0, NULL, NO_DRAW_BUT(__VA_ARGS__)
#define NO_OUTPUTS NO_OUTPUTS_BUT(NO_TAYLOR)

/* E = T + V, as eomc emits it for a conservative model. */
static void
osc_invariant(double t, const double *q, const double *v, const double *p,
              const double *u, double *h)
{
    double TV[2];
    osc_energy(t, q, v, p, u, TV);
    h[0] = TV[0] + TV[1];
}

const eomc_model osc_model = {
    EOMC_ABI_VERSION, "osc", "osc.yaml", "lagrange", "",
    1, 3, 0, osc_q, osc_p, osc_u, osc_pdef,
    "", no_fixed, 0, NULL,
    10.0, 0.1, "rk8pd", 1e-10, 1e-10, 0.0,
    osc_initial, no_inputs, osc_mass_bias, osc_energy, osc_jacobian,
    osc_accel,
    NO_CONSTRAINTS,
    osc_invariant, "E", "E = T + V is conserved",
    NO_CHECKS,
    NO_OUTPUTS_BUT(OSC_TAYLOR),
};

/* ---- the leaky oscillator: m x'' + c x' + k x = 0 that claims to conserve
 * E = T + V (a model that lies: the drift warning's test) ---- */

static const char *const lk_p[] = {"m", "k", "x0", "c"};
static const double lk_pdef[] = {OSC_M, OSC_K, OSC_X0, LEAKY_C};

static void
lk_mass_bias(double t, const double *q, const double *v, const double *p,
             const double *u, double *M, double *h)
{
    (void)t;
    (void)u;
    M[0] = p[0];
    h[0] = p[1] * q[0] + p[3] * v[0];
}

static void
lk_jacobian(double t, const double *q, const double *v, const double *a,
            const double *p, const double *u, double *dEdq, double *dEdv,
            double *dEdu, double *dEdt)
{
    (void)t;
    (void)q;
    (void)v;
    (void)a;
    (void)u;
    (void)dEdu;
    dEdq[0] = p[1];
    dEdv[0] = p[3];
    dEdt[0] = 0.0;
}

const eomc_model leaky_model = {
    EOMC_ABI_VERSION, "leaky", "leaky.yaml", "lagrange", "",
    1, 4, 0, osc_q, lk_p, osc_u, lk_pdef,
    "", no_fixed, 0, NULL,
    10.0, 0.1, "rk8pd", 1e-10, 1e-10, 0.0,
    osc_initial, no_inputs, lk_mass_bias, osc_energy, lk_jacobian,
    NULL,
    NO_CONSTRAINTS,
    osc_invariant, "E", "E = T + V is conserved (it is not: the model lies)",
    NO_CHECKS,
    NO_OUTPUTS,
};

/* ---- the oscillator with a `stop` event where x falls through 0 ---- */

static const char *const ose_names[] = {"down"};
static const int ose_direction[] = {-1};
static const int ose_action[] = {EOMC_EVENT_STOP};

static void
ose_events(double t, const double *q, const double *v, const double *p, const double *u,
           double *g)
{
    (void)t;
    (void)v;
    (void)p;
    (void)u;
    g[0] = q[0];
}

const eomc_model osc_event_model = {
    EOMC_ABI_VERSION, "osc_event", "osc_event.yaml", "lagrange", "",
    1, 3, 0, osc_q, osc_p, osc_u, osc_pdef,
    "", no_fixed, 0, NULL,
    10.0, 0.1, "rk8pd", 1e-10, 1e-10, 0.0,
    osc_initial, no_inputs, osc_mass_bias, osc_energy, osc_jacobian,
    osc_accel,
    NO_CONSTRAINTS,
    osc_invariant, "E", "E = T + V is conserved",
    NO_CHECKS,
    0, NULL, NULL,
    1, ose_names, ose_direction, ose_action, ose_events, NULL,
    0, NULL, /* no assembly */
    NULL,    /* M dense */
    NULL, NULL, /* no unit loads */
    NULL,       /* no c_scale: residuals against B q */
    NULL,       /* no rows held */
    0, NULL,    /* B dense */
    NO_DRAW_BUT(OSC_TAYLOR),
};

/* ---- a pendulum to draw (--animate): a bob of mass m on a rod of mass mr
 * (a uniform box of half-sizes ROD_W, l/2, ROD_D hanging from the pivot),
 * turning by theta about z; its items: the pivot ("origin", a point), the
 * bob (a particle), the rod (a body in its frame, turned by theta), the
 * link pivot-bob and the bob's trace; outputs x_bob, y_bob ---- */

#define ROD_W 0.04
#define ROD_D 0.02
static const char *const pd_q[] = {"theta"};
static const char *const pd_p[] = {"m", "l", "g", "mr"};
static const double pd_pdef[] = {1.0, 1.0, 9.81, 0.5};

static void
pd_initial(const double *p, double *q, double *v)
{
    (void)p;
    q[0] = 1.0;
    v[0] = 0.0;
}

/* the rod's moment about the pivot: mr (w^2 + (l/2)^2) / 3 + mr (l/2)^2 */
static double
pd_rod_izz(const double *p)
{
    double hl = p[1] / 2;
    return p[3] * (ROD_W * ROD_W + hl * hl) / 3 + p[3] * hl * hl;
}

static void
pd_mass_bias(double t, const double *q, const double *v, const double *p,
             const double *u, double *M, double *h)
{
    (void)t;
    (void)v;
    (void)u;
    M[0] = p[0] * p[1] * p[1] + pd_rod_izz(p);
    h[0] = (p[0] + p[3] / 2) * p[1] * p[2] * sin(q[0]);
}

static void
pd_energy(double t, const double *q, const double *v, const double *p,
          const double *u, double *TV)
{
    (void)t;
    (void)u;
    TV[0] = 0.5 * (p[0] * p[1] * p[1] + pd_rod_izz(p)) * v[0] * v[0];
    TV[1] = -(p[0] + p[3] / 2) * p[1] * p[2] * cos(q[0]);
}

static void
pd_invariant(double t, const double *q, const double *v, const double *p,
             const double *u, double *h)
{
    double TV[2];
    pd_energy(t, q, v, p, u, TV);
    h[0] = TV[0] + TV[1];
}

static const char *const pd_out[] = {"x_bob", "y_bob"};

static void
pd_outputs(double t, const double *q, const double *v, const double *a, const double *p,
           const double *u, const double *lam, double *out)
{
    (void)t;
    (void)v;
    (void)a;
    (void)u;
    (void)lam;
    out[0] = p[1] * sin(q[0]);
    out[1] = -p[1] * cos(q[0]);
}

static const eomc_draw_item pd_items[] = {
    {"origin", EOMC_DRAW_POINT, 2, 0},
    {"bob", EOMC_DRAW_PARTICLE, 2, 0},
    {"rod", EOMC_DRAW_BODY, 2, 0},
};
static const int pd_links[] = {0, 1};
static const int pd_trace[] = {1};

static void
pd_draw(double t, const double *q, const double *p, const double *u, double *X)
{
    (void)t;
    (void)u;
    double s = sin(q[0]), c = cos(q[0]);
    for (int k = 0; k < 3; k++) { /* at the origin, unturned */
        double *x = X + k * EOMC_POSE;
        for (int i = 0; i < EOMC_POSE; i++)
            x[i] = i >= 3 && (i - 3) % 4 == 0;
    }
    X[EOMC_POSE + 0] = p[1] * s; /* the bob */
    X[EOMC_POSE + 1] = -p[1] * c;
    double *R = X + 2 * EOMC_POSE + 3; /* the rod: turned by theta about z */
    R[0] = c, R[1] = -s, R[3] = s, R[4] = c;
}

/* Its places are its draw items (the same poses), moving at the speed
 * dv[0] = theta': the bob at (l cos, l sin) theta', the rod turning about
 * z, the origin still. */
static void
pd_place_velocity(double t, const double *q, const double *p, const double *u, const double *dv,
                  double *W)
{
    (void)t;
    (void)u;
    for (int i = 0; i < 18; i++)
        W[i] = 0;
    W[6] = p[1] * cos(q[0]) * dv[0];
    W[7] = p[1] * sin(q[0]) * dv[0];
    W[12 + 5] = dv[0];
}

/* the rod's mass, centre (0, -l/2, 0) and inertia about it, in its frame */
static void
pd_draw_mass(const double *p, double *D)
{
    double *d = D + 2 * EOMC_DRAW_MASS, m = p[3];
    double a[3] = {ROD_W, p[1] / 2, ROD_D};
    for (int i = 0; i < EOMC_DRAW_MASS; i++)
        d[i] = 0;
    d[0] = m;
    d[2] = -p[1] / 2;
    for (int i = 0; i < 3; i++)
        d[4 + 4 * i] = m * (a[(i + 1) % 3] * a[(i + 1) % 3] + a[(i + 2) % 3] * a[(i + 2) % 3]) / 3;
}

const eomc_model draw_model = {
    EOMC_ABI_VERSION, "drawn", "drawn.yaml", "lagrange", "",
    1, 4, 0, pd_q, pd_p, osc_u, pd_pdef,
    "", no_fixed, 0, NULL,
    2.0, 0.01, "rk8pd", 1e-10, 1e-10, 0.0,
    pd_initial, no_inputs, pd_mass_bias, pd_energy, NULL,
    NULL,
    NO_CONSTRAINTS,
    pd_invariant, "E", "E = T + V is conserved",
    NO_CHECKS,
    2, pd_out, pd_outputs,
    0, NULL, NULL, NULL, NULL, NULL, /* no events */
    0, NULL, /* no assembly */
    NULL,    /* M dense */
    NULL, NULL, /* no unit loads */
    NULL,       /* no c_scale */
    NULL,       /* no rows held */
    0, NULL,    /* B dense */
    3, pd_items, pd_draw, pd_draw_mass, 0, NULL, 1, 1, 0, pd_links, pd_trace, NULL,
    NULL, 0.0, NULL, /* not followed, the ground at 0, no shapes of parameters */
    3, pd_items, pd_draw, pd_place_velocity, NO_TAYLOR,
};

void
osc_exact(double m, double k, double x0, double v0, double t, double *x, double *v)
{
    double w = sqrt(k / m);
    *x = x0 * cos(w * t) + v0 / w * sin(w * t);
    *v = -x0 * w * sin(w * t) + v0 * cos(w * t);
}

/* ---- the double pendulum, absolute angles ----
 * With A = (m1 + m2) l1^2, B = m2 l1 l2, C = m2 l2^2, G1 = (m1 + m2) g l1,
 * G2 = m2 g l2 and d = th1 - th2:
 *   E1 = A a1 + B cos(d) a2 + B sin(d) v2^2 + G1 sin(th1)
 *   E2 = B cos(d) a1 + C a2 - B sin(d) v1^2 + G2 sin(th2)
 */

static const char *const cp_q[] = {"th1", "th2"};
static const char *const cp_p[] = {"m1", "m2", "l1", "l2", "g"};
static const double cp_pdef[] = {1.0, 1.5, 1.0, 0.7, 9.81};

typedef struct Coef {
    double A, B, C, G1, G2;
} Coef;

static Coef
cp_coef(const double *p)
{
    double m1 = p[0], m2 = p[1], l1 = p[2], l2 = p[3], g = p[4];
    return (Coef){(m1 + m2) * l1 * l1, m2 * l1 * l2, m2 * l2 * l2,
                  (m1 + m2) * g * l1, m2 * g * l2};
}

static void
cp_initial(const double *p, double *q, double *v)
{
    (void)p;
    q[0] = 0.6;
    q[1] = -0.4;
    v[0] = 0.3;
    v[1] = -0.2;
}

static void
cp_mass_bias(double t, const double *q, const double *v, const double *p,
             const double *u, double *M, double *h)
{
    (void)t;
    (void)u;
    Coef c = cp_coef(p);
    double d = q[0] - q[1], cd = cos(d), sd = sin(d);
    M[0] = c.A;
    M[1] = c.B * cd;
    M[2] = c.B * cd;
    M[3] = c.C;
    h[0] = c.B * sd * v[1] * v[1] + c.G1 * sin(q[0]);
    h[1] = -c.B * sd * v[0] * v[0] + c.G2 * sin(q[1]);
}

static void
cp_energy(double t, const double *q, const double *v, const double *p,
          const double *u, double *TV)
{
    (void)t;
    (void)u;
    Coef c = cp_coef(p);
    TV[0] = 0.5 * c.A * v[0] * v[0] + 0.5 * c.C * v[1] * v[1] +
            c.B * v[0] * v[1] * cos(q[0] - q[1]);
    TV[1] = -c.G1 * cos(q[0]) - c.G2 * cos(q[1]);
}

static void
cp_jacobian(double t, const double *q, const double *v, const double *a,
            const double *p, const double *u, double *dEdq, double *dEdv,
            double *dEdu, double *dEdt)
{
    (void)t;
    (void)u;
    (void)dEdu;
    Coef c = cp_coef(p);
    double d = q[0] - q[1], cd = cos(d), sd = sin(d);
    dEdq[0] = -c.B * sd * a[1] + c.B * cd * v[1] * v[1] + c.G1 * cos(q[0]);
    dEdq[1] = c.B * sd * a[1] - c.B * cd * v[1] * v[1];
    dEdq[2] = -c.B * sd * a[0] - c.B * cd * v[0] * v[0];
    dEdq[3] = c.B * sd * a[0] + c.B * cd * v[0] * v[0] + c.G2 * cos(q[1]);
    dEdv[0] = 0.0;
    dEdv[1] = 2.0 * c.B * sd * v[1];
    dEdv[2] = -2.0 * c.B * sd * v[0];
    dEdv[3] = 0.0;
    dEdt[0] = 0.0;
    dEdt[1] = 0.0;
}

const eomc_model coupled_model = {
    EOMC_ABI_VERSION, "coupled", "coupled.yaml", "lagrange", "",
    2, 5, 0, cp_q, cp_p, osc_u, cp_pdef,
    "", no_fixed, 0, NULL,
    10.0, 0.01, "rk8pd", 1e-12, 1e-12, 0.0,
    cp_initial, no_inputs, cp_mass_bias, cp_energy, cp_jacobian,
    NULL,
    NO_CONSTRAINTS,
    NO_INVARIANT,
    NO_CHECKS,
    NO_OUTPUTS,
};

/* ---- the driven oscillator: E = m x'' + c x' + k x - u - b t ---- */

static const char *const dr_q[] = {"x"};
static const char *const dr_p[] = {"m", "c", "k", "A", "w", "b"};
static const char *const dr_u[] = {"u"};
static const double dr_pdef[] = {DRIVEN_M, 0.0, DRIVEN_K, DRIVEN_A, DRIVEN_W, 0.0};

static void
dr_initial(const double *p, double *q, double *v)
{
    (void)p;
    q[0] = DRIVEN_X0;
    v[0] = DRIVEN_V0;
}

static void
dr_inputs(double t, const double *p, double *u, double *dudt)
{
    u[0] = p[3] * sin(p[4] * t);
    if (dudt)
        dudt[0] = p[3] * p[4] * cos(p[4] * t);
}

static void
dr_mass_bias(double t, const double *q, const double *v, const double *p,
             const double *u, double *M, double *h)
{
    M[0] = p[0];
    h[0] = p[1] * v[0] + p[2] * q[0] - u[0] - p[5] * t;
}

static void
dr_energy(double t, const double *q, const double *v, const double *p,
          const double *u, double *TV)
{
    (void)t;
    (void)u;
    TV[0] = 0.5 * p[0] * v[0] * v[0];
    TV[1] = 0.5 * p[2] * q[0] * q[0];
}

static void
dr_jacobian(double t, const double *q, const double *v, const double *a,
            const double *p, const double *u, double *dEdq, double *dEdv,
            double *dEdu, double *dEdt)
{
    (void)t;
    (void)q;
    (void)v;
    (void)a;
    (void)u;
    dEdq[0] = p[2];
    dEdv[0] = p[1];
    dEdu[0] = -1.0;
    dEdt[0] = -p[5];
}

static int
dr_accel(double t, const double *q, const double *v, const double *p,
         const double *u, double *a, double *pivot)
{
    double M = p[0], h = p[1] * v[0] + p[2] * q[0] - u[0] - p[5] * t;
    double piv = M - EOMC_PIVOT_TOL * M;
    a[0] = piv > 0.0 ? -h / M : NAN;
    if (pivot)
        *pivot = 1.0;
    return piv > 0.0 ? 0 : 1;
}

const eomc_model driven_model = {
    EOMC_ABI_VERSION, "driven", "driven.yaml", "lagrange", "",
    1, 6, 1, dr_q, dr_p, dr_u, dr_pdef,
    "", no_fixed, 0, NULL,
    5.0, 0.05, "rkf45", 1e-10, 1e-10, 0.0,
    dr_initial, dr_inputs, dr_mass_bias, dr_energy, dr_jacobian,
    dr_accel,
    NO_CONSTRAINTS,
    NO_INVARIANT,
    NO_CHECKS,
    NO_OUTPUTS,
};

void
driven_exact(double m, double k, double A, double w, double x0, double v0,
             double t, double *x, double *v)
{
    double w0 = sqrt(k / m), P = A / m / (w0 * w0 - w * w);
    double c1 = x0, c2 = (v0 - P * w) / w0;
    *x = c1 * cos(w0 * t) + c2 * sin(w0 * t) + P * sin(w * t);
    *v = -c1 * w0 * sin(w0 * t) + c2 * w0 * cos(w0 * t) + P * w * cos(w * t);
}

/* ---- M = 1 - zeta^2, h = 0: zeta = t until M = 0 at t = 1 ---- */

static const char *const np_q[] = {"zeta"};
static const char *const np_p[] = {NULL};
static const double np_pdef[] = {0.0};

static void
np_initial(const double *p, double *q, double *v)
{
    (void)p;
    q[0] = 0.0;
    v[0] = 1.0;
}

static void
np_mass_bias(double t, const double *q, const double *v, const double *p,
             const double *u, double *M, double *h)
{
    (void)t;
    (void)v;
    (void)p;
    (void)u;
    M[0] = 1.0 - q[0] * q[0];
    h[0] = 0.0;
}

static void
np_energy(double t, const double *q, const double *v, const double *p,
          const double *u, double *TV)
{
    (void)t;
    (void)p;
    (void)u;
    TV[0] = 0.5 * (1.0 - q[0] * q[0]) * v[0] * v[0];
    TV[1] = 0.0;
}

static void
np_jacobian(double t, const double *q, const double *v, const double *a,
            const double *p, const double *u, double *dEdq, double *dEdv,
            double *dEdu, double *dEdt)
{
    (void)t;
    (void)v;
    (void)p;
    (void)u;
    (void)dEdu;
    dEdq[0] = -2.0 * q[0] * a[0];
    dEdv[0] = 0.0;
    dEdt[0] = 0.0;
}

static int
np_accel(double t, const double *q, const double *v, const double *p,
         const double *u, double *a, double *pivot)
{
    (void)t;
    (void)v;
    (void)p;
    (void)u;
    double M = 1.0 - q[0] * q[0], piv = M - EOMC_PIVOT_TOL * M;
    a[0] = piv > 0.0 ? -0.0 / M : NAN;
    if (pivot)
        *pivot = 1.0;
    return piv > 0.0 ? 0 : 1;
}

const eomc_model nonpd_model = {
    EOMC_ABI_VERSION, "nonpd", "nonpd.yaml", "lagrange", "",
    1, 0, 0, np_q, np_p, osc_u, np_pdef,
    "", no_fixed, 0, NULL,
    2.0, 0.1, "rk8pd", 1e-10, 1e-10, 0.0,
    np_initial, no_inputs, np_mass_bias, np_energy, np_jacobian,
    np_accel,
    NO_CONSTRAINTS,
    NO_INVARIANT,
    NO_CHECKS,
    NO_OUTPUTS,
};

const eomc_model nonpd_gsl_model = {
    EOMC_ABI_VERSION, "nonpd_gsl", "nonpd_gsl.yaml", "lagrange", "",
    1, 0, 0, np_q, np_p, osc_u, np_pdef,
    "", no_fixed, 0, NULL,
    2.0, 0.1, "rk8pd", 1e-10, 1e-10, 0.0,
    np_initial, no_inputs, np_mass_bias, np_energy, np_jacobian,
    NULL,
    NO_CONSTRAINTS,
    NO_INVARIANT,
    NO_CHECKS,
    NO_OUTPUTS,
};

/* ---- free bodies' starts and closed forms (freebody.c has the models) ---- */

void
freebody_start(double *q, double *v)
{
    static const double e[4] = {0.9, 0.1, -0.3, 0.2};
    double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
    q[0] = 0.1, q[1] = -0.2, q[2] = 1.0;
    for (int i = 0; i < 4; i++)
        q[3 + i] = e[i] / len;
    v[0] = 0.5, v[1] = -0.3, v[2] = 2.0;
    v[3] = 0.4, v[4] = -0.7, v[5] = 2.5;
}

void
quat_rotation(const double *e, double *R)
{
    double a = e[0], b = e[1], c = e[2], d = e[3];
    R[0] = a * a + b * b - c * c - d * d, R[1] = 2 * (b * c - a * d), R[2] = 2 * (b * d + a * c);
    R[3] = 2 * (b * c + a * d), R[4] = a * a - b * b + c * c - d * d, R[5] = 2 * (c * d - a * b);
    R[6] = 2 * (b * d - a * c), R[7] = 2 * (c * d + a * b), R[8] = a * a - b * b - c * c + d * d;
}

/* r = a (x) b. */
static void
quat_mul(const double *a, const double *b, double *r)
{
    r[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    r[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    r[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    r[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

/* The quaternion of a turn by angle about the unit axis u. */
static void
quat_turn(const double *u, double angle, double *r)
{
    double s = sin(angle / 2);
    r[0] = cos(angle / 2), r[1] = s * u[0], r[2] = s * u[1], r[3] = s * u[2];
}

void
freebody_exact(const double *p, const double *q0, const double *v0, double t, double *q,
               double *v)
{
    double g = p[4], A = p[1], C = p[3], R0[9], Lb[3], L[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
        q[i] = q0[i] + v0[i] * t;
        v[i] = v0[i];
    }
    q[2] -= g * t * t / 2;
    v[2] -= g * t;
    const double *w0 = v0 + 3;
    Lb[0] = A * w0[0], Lb[1] = A * w0[1], Lb[2] = C * w0[2];
    quat_rotation(q0 + 3, R0);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            L[i] += R0[3 * i + j] * Lb[j];
    double len = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
    double u[3] = {L[0] / len, L[1] / len, L[2] / len}, z[3] = {0, 0, 1};
    double precess[4], spin[4], tmp[4];
    quat_turn(u, len / A * t, precess);
    quat_turn(z, (1 - C / A) * w0[2] * t, spin);
    quat_mul(precess, q0 + 3, tmp);
    quat_mul(tmp, spin, q + 3);
    double W = (C - A) / A * w0[2] * t;
    v[3] = w0[0] * cos(W) - w0[1] * sin(W);
    v[4] = w0[0] * sin(W) + w0[1] * cos(W);
    v[5] = w0[2];
}

void
top_start(const double *p, double *q, double *v)
{
    double l = p[3], R[9];
    q[3] = cos(TOP_TILT / 2), q[4] = sin(TOP_TILT / 2), q[5] = q[6] = 0;
    quat_rotation(q + 3, R);
    v[3] = 0.3, v[4] = -0.2, v[5] = TOP_SPIN;
    /* the tip at the origin: x = l R e_z, and at rest there: x' = -R (w x r) */
    for (int k = 0; k < 3; k++) {
        q[k] = l * R[3 * k + 2];
        v[k] = -l * (v[3] * R[3 * k + 1] - v[4] * R[3 * k]);
    }
}

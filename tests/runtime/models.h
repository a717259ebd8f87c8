/*
 * models.h: hand-written models, as the generator would emit them, for the
 * runtime tests (models.c has the equations and their closed forms).
 *
 *   osc_model        m x'' + k x = 0; p = (m, k, x0), x(0) = x0, x'(0) = 1/2;
 *                    accel member set
 *   osc_event_model  the same with the event `down`: g = x, downward, `stop`
 *                    (it fires at t = (pi/2 + atan(v0 / (w x0))) / w,
 *                    w = sqrt(k/m))
 *   coupled_model    the double pendulum in absolute angles th1, th2: a
 *                    q-dependent, non-diagonal SPD mass matrix; accel NULL
 *                    (the runtime's GSL Cholesky solve)
 *   driven_model     m x'' + c x' + k x = u + b t, u = A sin(w t);
 *                    p = (m, c, k, A, w, b); accel member set
 *   nonpd_model      (1 - zeta^2) zeta'' = 0 from zeta = 0, zeta' = 1: M
 *                    loses positive definiteness at t = 1; accel member set
 *   nonpd_gsl_model  the same with accel NULL
 *   leaky_model      m x'' + c x' + k x = 0, p = (m, k, x0, c), c = LEAKY_C:
 *                    damped, yet it claims to conserve E = T + V
 *   draw_model       a pendulum with its drawing filled in (--animate): a bob
 *                    (a particle) on a rod (a body drawn as its equivalent
 *                    box, half-sizes 0.04, l/2, 0.02), a link and a trace;
 *                    p = (m, l, g, mr), theta(0) = 1; outputs x_bob, y_bob;
 *                    its places are its draw items (origin, bob, rod)
 */
#ifndef EOMC_TEST_MODELS_H
#define EOMC_TEST_MODELS_H

#include "eomc_model.h"

extern const eomc_model osc_model;
extern const eomc_model osc_event_model;
extern const eomc_model coupled_model;
extern const eomc_model driven_model;
extern const eomc_model nonpd_model;
extern const eomc_model nonpd_gsl_model;
extern const eomc_model leaky_model;
extern const eomc_model draw_model;
/* ctrlosc.c: m x'' + k x = u, u an input held at 0 (the plant of the
 * controller tests), with its twin ctrlosc_model_ext */
extern const eomc_model ctrlosc_model;
extern const eomc_model_ext ctrlosc_model_ext;
#define CTRLOSC_M 1.5
#define CTRLOSC_K 6.0
#define CTRLOSC_X0 0.2
#define CTRLOSC_V0 (-0.1)
#define LEAKY_C 1e-3

/* Defaults of osc_model. */
#define OSC_M 2.0
#define OSC_K 8.0
#define OSC_X0 1.0
#define OSC_V0 0.5

/* x(t), x'(t) of m x'' + k x = 0 from (x0, v0) at t = 0. */
void osc_exact(double m, double k, double x0, double v0, double t, double *x,
               double *v);

/* Defaults of driven_model (c = b = 0: undamped, no ramp). */
#define DRIVEN_M 1.5
#define DRIVEN_K 6.0
#define DRIVEN_A 0.8
#define DRIVEN_W 3.1
#define DRIVEN_X0 0.2
#define DRIVEN_V0 (-0.1)

/* x(t), x'(t) of m x'' + k x = A sin(w t) (w^2 != k/m) with x = x0,
 * x' = v0 at t = 0. */
void driven_exact(double m, double k, double A, double w, double x0, double v0,
                  double t, double *x, double *v);

/* Models whose speeds are not their coordinates' rates (freebody.c): q =
 * (root_x, root_y, root_z, root_e0 .. root_e3), the centre and the unit
 * quaternion of the body's axes; v = (root_x', root_y', root_z', root_wx,
 * root_wy, root_wz), the centre's velocity and the angular velocity in the
 * body's axes; q' = W(q) v, e' = e (x) (0, w) / 2.
 *
 *   freebody_model   a free rigid body under gravity -g z: M = diag(m, m,
 *                    m, I1, I2, I3), h from Euler's equations; p = (m, I1,
 *                    I2, I3, g), I1 < I2 < I3 by default; started at
 *                    freebody_start; accel NULL (the runtime's LDL^T)
 *   freebody_accel_model  the same with its own accel
 *   freebody_series_model the same claiming Taylor series (a stub)
 *   freebody_bounce_model the same bouncing on the floor: event floor (g =
 *                    root_z, down) sets root_z' to -root_z'; output wz_rate
 *                    (root_wz')
 *   top_model        the heavy symmetric top: the free body (p = (m, A, C,
 *                    l, g), inertia diag(A, A, C)) whose tip, at -l along
 *                    its axis, is held at the origin by three holonomic
 *                    constraints tip_x, tip_y, tip_z; started at top_start
 *                    (tilted by TOP_TILT about x, spinning); the KKT solve
 *   top_loads_model  the same with free_accel and minv: unit loads
 *   top_noscale_model the same without c_scale (g's terms from
 *                    c_levels_jacobian's gradient)
 * Their twins freebody_model_ext and top_model_ext (the same file compiled
 * with -DEOMC_EXTENDED) are what the reference evaluates. */
extern const eomc_model freebody_model;
extern const eomc_model freebody_accel_model;
extern const eomc_model freebody_series_model; /* Taylor series it must not be given */
extern const eomc_model freebody_bounce_model;
extern const eomc_model top_model;
extern const eomc_model top_loads_model;
extern const eomc_model top_noscale_model; /* c_scale NULL */
extern const eomc_model_ext freebody_model_ext;
extern const eomc_model_ext top_model_ext;

#define FREEBODY_M 2.0
#define FREEBODY_I1 1.0
#define FREEBODY_I2 2.0
#define FREEBODY_I3 3.0
#define FREEBODY_G 9.81
void freebody_start(double *q, double *v);
/* R [9] (row-major, body to world) of the quaternion e [4]. */
void quat_rotation(const double *e, double *R);
/* The free body's exact motion from (q0, v0) at t = 0, for a body whose
 * p has I1 = I2 (symmetric about its axis z): the centre's parabola, and
 * the turn R(t) = Rot(L, |L| t / I1) R0 Rot(z, (1 - I3/I1) wz t), L the
 * world angular momentum; its speeds (wx, wy) turning at (I3 - I1) wz /
 * I1, wz constant. */
void freebody_exact(const double *p, const double *q0, const double *v0, double t, double *q,
                    double *v);

#define TOP_M 1.0
#define TOP_A 0.3
#define TOP_C 0.5
#define TOP_L 0.4
#define TOP_G 9.81
#define TOP_TILT 0.4
#define TOP_SPIN 12.0
void top_start(const double *p, double *q, double *v);

#endif

/*
 * Constrained models through the runtime API, against closed forms, for
 * the form this executable was built with (tests/sim/meson.build builds
 * it once per form: lagrange and maggi from generated/, and nielsen,
 * tzenoff, gibbs-appell, each with multipliers and with elimination):
 *  - cartesian_pendulum at random consistent states: q'' of the simple
 *    pendulum, theta'' = -g/l sin(theta), mapped to x, y; the multiplier
 *    lambda = m (g cos(theta) + l theta'^2) / (2 l) (the rod's tension T
 *    with constraint force -B^T lambda = -2 lambda (x, y));
 *  - appell on the branch z' = a v: the closed form of docs/mechanics.md;
 *  - precession (second-order constraint on a rigid body): the paper's
 *    two equations of motion, C r' - (A - B) p q = 0 and
 *    C r' psi' cos(theta) + A p p' + B q q' + (A - B) p q phi' = 0, and the
 *    constraint itself, at random states;
 *  - Baumgarte's stabilization at inconsistent states: the computed q''
 *    satisfy g'' + 2 alpha g' + beta^2 g = 0 (pendulum) and
 *    phi' + alpha phi = 0 (appell), with g', g'', phi' written out by hand;
 *  - the Jacobian of x' = f(t, x) against central differences of the
 *    accelerations, for these models, with and without Baumgarte's terms.
 */
#include "../unit/check.h"
#include "eomc.h"

#include <stdlib.h>

extern const eomc_model cartesian_pendulum_model, appell_model, precession_model;

static void
pendulum(void)
{
    eomc_sim *s = eomc_sim_alloc(&cartesian_pendulum_model);
    double m = 1.3, l = 0.8, g = 9.81;
    eomc_sim_set(s, "m", m);
    eomc_sim_set(s, "l", l);
    int ok = 1, lam_ok = 1;
    for (int k = 0; k < 50; k++) {
        double th = check_rand(-3, 3), w = check_rand(-4, 4);
        double q[2] = {l * sin(th), -l * cos(th)}, v[2] = {l * cos(th) * w, l * sin(th) * w};
        double a[2], thdd = -g / l * sin(th);
        ok &= eomc_sim_accel(s, 0.0, q, v, a) == EOMC_OK;
        ok &= check_close(a[0], l * cos(th) * thdd - l * sin(th) * w * w, 1e-12) &&
              check_close(a[1], l * sin(th) * thdd + l * cos(th) * w * w, 1e-12);
        double lam = eomc_sim_multipliers(s)[0];
        lam_ok &= check_close(lam, m * (g * cos(th) + l * w * w) / (2 * l), 1e-12);
    }
    CHECK(ok, "%s: cartesian pendulum q'' = the pendulum's, 50 random states",
          cartesian_pendulum_model.form);
    CHECK(lam_ok, "%s: lambda = m (g cos(theta) + l theta'^2) / (2 l)",
          cartesian_pendulum_model.form);
    eomc_sim_free(s);
}

static void
appell(void)
{
    eomc_sim *s = eomc_sim_alloc(&appell_model);
    double A = 0.7, g = 9.81;
    eomc_sim_set(s, "a", A);
    int ok = 1;
    for (int k = 0; k < 50; k++) {
        double q[3] = {check_rand(-5, 5), check_rand(-5, 5), check_rand(-5, 5)};
        double xd = check_rand(-3, 3), yd = check_rand(-3, 3), vv = sqrt(xd * xd + yd * yd);
        double v[3] = {xd, yd, A * vv}, a[3];
        ok &= eomc_sim_accel(s, 0.0, q, v, a) == EOMC_OK;
        double xdd = A * g * xd / ((1 + A * A) * vv), ydd = A * g * yd / ((1 + A * A) * vv);
        ok &= check_close(a[0], xdd, 1e-11) && check_close(a[1], ydd, 1e-11) &&
              check_close(a[2], A * (xd * xdd + yd * ydd) / vv, 1e-11);
    }
    CHECK(ok, "%s: appell q'' = the closed form on z' = a v, 50 random states",
          appell_model.form);
    eomc_sim_free(s);
}

static void
precession(void)
{
    eomc_sim *s = eomc_sim_alloc(&precession_model);
    const double A = 1.0, B = 1.5, C = 2.0, lam = 0.5;
    int ok = 1, con = 1;
    for (int k = 0; k < 50; k++) {
        double q[3] = {check_rand(-3, 3), check_rand(0.3, 2.8), check_rand(-3, 3)};
        double v[3] = {check_rand(-1, 1), check_rand(-1, 1), check_rand(-1, 1)}, a[3];
        ok &= eomc_sim_accel(s, 0.0, q, v, a) == EOMC_OK;
        double th = q[1], ph = q[2], ps1 = v[0], th1 = v[1], ph1 = v[2];
        double st = sin(th), ct = cos(th), sp = sin(ph), cp = cos(ph);
        double p = ps1 * st * sp + th1 * cp, qq = ps1 * st * cp - th1 * sp, r = ps1 * ct + ph1;
        double pd = a[0] * st * sp + ps1 * ct * th1 * sp + ps1 * st * cp * ph1 + a[1] * cp -
                    th1 * sp * ph1;
        double qd = a[0] * st * cp + ps1 * ct * th1 * cp - ps1 * st * sp * ph1 - a[1] * sp -
                    th1 * cp * ph1;
        double rd = a[0] * ct - ps1 * st * th1 + a[2];
        double e1 = C * rd - (A - B) * p * qq;
        double e2 = C * rd * ps1 * ct + A * p * pd + B * qq * qd + (A - B) * p * qq * ph1;
        double s2 = p * p + qq * qq, f = (p * qd - qq * pd) + r * s2 - lam * pow(s2, 1.5);
        ok &= fabs(e1) < 1e-12 && fabs(e2) < 1e-12;
        con &= fabs(f) < 1e-12;
    }
    CHECK(ok, "%s: precession: C r' = (A - B) p q and the paper's second equation hold",
          precession_model.form);
    CHECK(con, "%s: precession: the constraint holds at the computed q''",
          precession_model.form);
    eomc_sim_free(s);
}

static void
baumgarte(void)
{
    const double al = 3.0, be = 5.0, l = 1.0, A = 0.7;
    eomc_sim *s = eomc_sim_alloc(&cartesian_pendulum_model);
    eomc_sim_set(s, "l", l);
    int ok = eomc_sim_stabilize(s, EOMC_STABILIZE_BAUMGARTE, al, be) == EOMC_OK;
    for (int k = 0; k < 50; k++) {
        double q[2] = {check_rand(-1.2, 1.2), check_rand(-1.2, 1.2)};
        double v[2] = {check_rand(-3, 3), check_rand(-3, 3)}, a[2];
        ok &= eomc_sim_accel(s, 0.0, q, v, a) == EOMC_OK;
        double g = q[0] * q[0] + q[1] * q[1] - l * l, g1 = 2 * (q[0] * v[0] + q[1] * v[1]);
        double g2 = 2 * (v[0] * v[0] + v[1] * v[1] + q[0] * a[0] + q[1] * a[1]);
        ok &= fabs(g2 + 2 * al * g1 + be * be * g) < 1e-11 * (1 + fabs(g2));
    }
    CHECK(ok, "%s: baumgarte: g'' + 2 alpha g' + beta^2 g = 0 at 50 inconsistent states",
          cartesian_pendulum_model.form);
    eomc_sim_free(s);
    s = eomc_sim_alloc(&appell_model);
    eomc_sim_set(s, "a", A);
    ok = eomc_sim_stabilize(s, EOMC_STABILIZE_BAUMGARTE, al, be) == EOMC_OK;
    for (int k = 0; k < 50; k++) {
        double q[3] = {check_rand(-5, 5), check_rand(-5, 5), check_rand(-5, 5)};
        double v[3] = {check_rand(-3, 3), check_rand(-3, 3), 0}, a[3];
        v[2] = A * sqrt(v[0] * v[0] + v[1] * v[1]) * check_rand(0.8, 1.2);
        ok &= eomc_sim_accel(s, 0.0, q, v, a) == EOMC_OK;
        double phi = v[2] * v[2] - A * A * (v[0] * v[0] + v[1] * v[1]);
        double phi1 = 2 * v[2] * a[2] - 2 * A * A * (v[0] * a[0] + v[1] * a[1]);
        ok &= fabs(phi1 + al * phi) < 1e-11 * (1 + fabs(phi1));
    }
    CHECK(ok, "%s: baumgarte: phi' + alpha phi = 0 at 50 inconsistent states",
          appell_model.form);
    eomc_sim_free(s);
}

/* Largest |J - J_fd| / (1 + |J|) over entries, J from eomc_sim_jacobian;
 * with Baumgarte's stabilization when stab. */
static double
jacobian_error(const eomc_model *m, const double *x0, int stab)
{
    eomc_sim *s = eomc_sim_alloc(m);
    if (stab)
        eomc_sim_stabilize(s, EOMC_STABILIZE_BAUMGARTE, 3.0, 5.0);
    int n = m->nq, W = 2 * n;
    double *J = calloc((size_t)(W * W), sizeof *J), x[16], ap[8], am[8], worst = 0;
    if (eomc_sim_jacobian(s, 0.0, x0, J, NULL) != EOMC_OK)
        worst = INFINITY;
    for (int j = 0; j < W && worst < INFINITY; j++) {
        double h = 1e-6 * (1 + fabs(x0[j]));
        for (int i = 0; i < W; i++)
            x[i] = x0[i];
        x[j] = x0[j] + h;
        eomc_sim_accel(s, 0.0, x, x + n, ap);
        x[j] = x0[j] - h;
        eomc_sim_accel(s, 0.0, x, x + n, am);
        for (int i = 0; i < n; i++) {
            double fd = (ap[i] - am[i]) / (2 * h), e = J[(n + i) * W + j];
            worst = fmax(worst, fabs(e - fd) / (1 + fabs(e)));
        }
    }
    free(J);
    eomc_sim_free(s);
    return worst;
}

static void
jacobians(void)
{
    double th = 0.7, w = 1.3;
    double xp[4] = {sin(th), -cos(th), cos(th) * w, sin(th) * w};
    double e = jacobian_error(&cartesian_pendulum_model, xp, 0);
    CHECK(e < 1e-7, "%s: cartesian pendulum Jacobian = central differences (%.2g)",
          cartesian_pendulum_model.form, e);
    double xa[6] = {0.3, -0.2, 1.1, 1.5, -0.4, 0.5 * sqrt(1.5 * 1.5 + 0.16)};
    e = jacobian_error(&appell_model, xa, 0);
    CHECK(e < 1e-7, "%s: appell Jacobian = central differences (%.2g)", appell_model.form, e);
    /* off the constraints, where Baumgarte's terms are not zero */
    double xpb[4] = {1.1 * sin(th), -cos(th), cos(th) * w + 0.3, sin(th) * w};
    e = jacobian_error(&cartesian_pendulum_model, xpb, 1);
    CHECK(e < 1e-7, "%s: cartesian pendulum Jacobian with Baumgarte = central "
          "differences (%.2g)", cartesian_pendulum_model.form, e);
    double xab[6] = {0.3, -0.2, 1.1, 1.5, -0.4, 0.6 * sqrt(1.5 * 1.5 + 0.16)};
    e = jacobian_error(&appell_model, xab, 1);
    CHECK(e < 1e-7, "%s: appell Jacobian with Baumgarte = central differences (%.2g)",
          appell_model.form, e);
    double xr[6] = {0.4, 1.1, -0.7, 0.5, -0.3, 0.9};
    e = jacobian_error(&precession_model, xr, 0);
    CHECK(e < 1e-7, "%s: precession Jacobian = central differences (%.2g)",
          precession_model.form, e);
}

int
main(void)
{
    pendulum();
    appell();
    precession();
    baumgarte();
    jacobians();
    return check_done();
}

/*
 * Linearization and equilibria (runtime/analysis/linearize.c) against independent
 * values:
 *  - the pendulum's eigenvalues: +-i sqrt(g/l) at the bottom, +-sqrt(g/l)
 *    at the top;
 *  - the driven, damped cart-pole's A and B against the linearization
 *    derived by hand: x'' = (u - c x' + m g th)/M,
 *    th'' = -(u - c x' + (M + m) g th)/(M l);
 *  - every spec of specs/ against central differences: each column of A
 *    is the difference of z' over a perturbation of one independent
 *    component, the dependent ones put back on the constraints by a
 *    Newton iteration of this test's own (finite-difference Jacobian, no
 *    generated derivative); each column of B the difference over an input
 *    held at u +- h;
 *  - equilibria: the double pendulum's hanging and upside-down states from
 *    nearby starts, the Cartesian pendulum's bottom on its constraint;
 *    how far from rest a state is (the pendulum at pi and at 0.7);
 *  - a state off the constraints is refused, naming the constraint and
 *    its share worked out by hand (the Cartesian pendulum's bob at 1.2 l:
 *    0.44 against terms of 5.32); one on them to rounding is not.
 */
#include "../unit/check.h"
#include "eomc.h"

#include <stdlib.h>
#include <string.h>

#define SPECS(X)                                                                        \
    X(falling_particle) X(pendulum) X(gear_link) X(double_pendulum) X(chain5) X(kepler) \
    X(arenstorf) X(cartesian_pendulum) X(appell) X(precession) X(central_constant_speed) \
    X(chaplygin_sleigh) X(rolling_disk) X(swing) X(bouncing_ball) X(bicycle_tree) \
    X(spinning_hoop)
#define DECLARE(name) extern const eomc_model name##_model;
SPECS(DECLARE)
extern const eomc_model cart_pole_model;

enum { NMAX = 16 };
static const double PI = 3.14159265358979323846;

/* Put the dependent components (not among the linearization's states) of
 * x back on the constraints, the others held: Newton with a central-
 * difference Jacobian of the generated c_levels only. */
static int
on_constraints(eomc_sim *s, double t, double *x)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, N = 2 * n, nl = eomc_sim_linear_size(s), nd = N - nl;
    if (nd == 0)
        return 0;
    int dep[2 * NMAX], isind[2 * NMAX] = {0};
    for (int k = 0; k < nl; k++) {
        int c, o;
        eomc_sim_linear_state(s, k, &c, &o);
        isind[o * n + c] = 1;
    }
    for (int j = 0, a = 0; j < N; j++)
        if (!isind[j])
            dep[a++] = j;
    double u[NMAX + 1] = {0}, pos[NMAX], vel[NMAX];
    const double *p = eomc_sim_params(s);
    for (int it = 0; it < 50; it++) {
        eomc_sim_inputs(s, t, u);
        double r[2 * NMAX], J[4 * NMAX * NMAX];
        /* the residuals: holonomic g and g', first order phi */
#define RESID(xx, out)                                                                 \
        do {                                                                           \
            m->c_levels(t, xx, (xx) + n, p, u, pos, vel);                              \
            int rr_ = 0;                                                               \
            for (int k_ = 0; k_ < m->nc; k_++) {                                       \
                if (m->c_order[k_] == 0)                                               \
                    out[rr_++] = pos[k_];                                              \
                if (m->c_order[k_] <= 1)                                               \
                    out[rr_++] = vel[k_];                                              \
            }                                                                          \
        } while (0)
        RESID(x, r);
        double worst = 0;
        for (int a = 0; a < nd; a++) {
            double xp[2 * NMAX], xm[2 * NMAX], rp[2 * NMAX], rm[2 * NMAX];
            double h = 1e-6 * (1 + fabs(x[dep[a]]));
            memcpy(xp, x, sizeof(double) * (size_t)N);
            memcpy(xm, x, sizeof(double) * (size_t)N);
            xp[dep[a]] += h, xm[dep[a]] -= h;
            RESID(xp, rp);
            RESID(xm, rm);
            for (int b = 0; b < nd; b++)
                J[b * nd + a] = (rp[b] - rm[b]) / (2 * h);
        }
#undef RESID
        if (check_solve(J, r, nd) != 0)
            return -1;
        for (int a = 0; a < nd; a++) {
            x[dep[a]] -= r[a];
            worst = fmax(worst, fabs(r[a]) / (1 + fabs(x[dep[a]])));
        }
        if (worst < 1e-15)
            return 0;
    }
    return 0;
}

/* z' at x: the independent components of (q', q''). */
static int
zdot(eomc_sim *s, double t, const double *x, double *zd)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, nl = eomc_sim_linear_size(s);
    double a[NMAX];
    if (eomc_sim_accel(s, t, x, x + n, a) != EOMC_OK)
        return -1;
    for (int k = 0; k < nl; k++) {
        int c, o;
        eomc_sim_linear_state(s, k, &c, &o);
        zd[k] = o ? a[c] : x[n + c];
    }
    return 0;
}

/* Central differences of z' against A and B at the model's initial
 * state (put on its constraints): the worst entry, relative to the
 * column's largest. */
static double
check_fd(const eomc_model *m)
{
    eomc_sim *s = eomc_sim_alloc(m);
    int n = m->nq, N = 2 * n, nl = eomc_sim_linear_size(s), nu = m->nu;
    double x[2 * NMAX], A[4 * NMAX * NMAX], B[2 * NMAX * 4], t = 0.1, worst = 0;
    eomc_sim_initial(s, x, x + n);
    for (int i = 0; i < N; i++) /* a generic state: no zero that hides a term */
        x[i] += 0.013 * (i + 1);
    if (on_constraints(s, t, x) != 0 || eomc_sim_linearize(s, t, x, A, B) != EOMC_OK) {
        eomc_sim_free(s);
        return INFINITY;
    }
    for (int k = 0; k < nl; k++) {
        int c, o;
        eomc_sim_linear_state(s, k, &c, &o);
        double zp[2 * NMAX], zm[2 * NMAX], d[2][2 * NMAX];
        double h = 1e-4 * (1 + fabs(x[o * n + c]));
        /* central differences at h and h/2, extrapolated (Richardson):
         * O(h^4), for the steep fields of Arenstorf's orbit too */
        for (int pass = 0; pass < 2; pass++) {
            double hh = pass ? h / 2 : h, xp[2 * NMAX], xm[2 * NMAX];
            memcpy(xp, x, sizeof xp);
            memcpy(xm, x, sizeof xm);
            xp[o * n + c] += hh, xm[o * n + c] -= hh;
            if (on_constraints(s, t, xp) || on_constraints(s, t, xm) ||
                zdot(s, t, xp, zp) || zdot(s, t, xm, zm)) {
                eomc_sim_free(s);
                return INFINITY;
            }
            for (int r = 0; r < nl; r++)
                d[pass][r] = (zp[r] - zm[r]) / (2 * hh);
        }
        double col = 0;
        for (int r = 0; r < nl; r++)
            col = fmax(col, fabs(A[r * nl + k]));
        /* each entry against its column's largest, or, for a column that
         * is (nearly) zero, against the size of z'_r per unit of z_k */
        for (int r = 0; r < nl; r++) {
            double fd = (4 * d[1][r] - d[0][r]) / 3;
            double scale = fmax(col, fmax(fabs(zp[r]), fabs(zm[r])) / (1 + fabs(x[o * n + c])));
            worst = fmax(worst, fabs(fd - A[r * nl + k]) / fmax(scale, 1e-300));
        }
    }
    for (int k = 0; k < nu && isfinite(worst); k++) {
        double u[4], zp[2 * NMAX], zm[2 * NMAX], col = 0;
        eomc_sim_inputs(s, t, u);
        double h = 1e-5 * (1 + fabs(u[k]));
        char set[64];
        for (int sgn = 1; sgn >= -1; sgn -= 2) {
            eomc_sim *s2 = eomc_sim_alloc(m);
            for (int j = 0; j < nu; j++) { /* every input held at its value at t */
                snprintf(set, sizeof set, "%s", m->u_names[j]);
                eomc_sim_set(s2, set, u[j] + (j == k ? sgn * h : 0));
            }
            zdot(s2, t, x, sgn > 0 ? zp : zm);
            eomc_sim_free(s2);
        }
        for (int r = 0; r < nl; r++)
            col = fmax(col, fabs(B[r * nu + k]));
        for (int r = 0; r < nl; r++)
            worst = fmax(worst, fabs((zp[r] - zm[r]) / (2 * h) - B[r * nu + k]) /
                                    fmax(col, 1e-300));
    }
    eomc_sim_free(s);
    return worst;
}

static void
test_pendulum(void)
{
    eomc_sim *s = eomc_sim_alloc(&pendulum_model);
    double x[2] = {0, 0}, A[4], re[2], im[2], w = sqrt(9.81 / 1.0);
    eomc_sim_linearize(s, 0, x, A, NULL);
    eomc_sim_eigenvalues(s, A, 2, re, im);
    CHECK(fabs(re[0]) < 1e-15 * w && fabs(re[1]) < 1e-15 * w &&
          check_close(fabs(im[0]), w, 1e-14) && check_close(fabs(im[1]), w, 1e-14) &&
          im[0] * im[1] < 0, "pendulum at the bottom: eigenvalues +-i sqrt(g/l) = +-%.17gi",
          fabs(im[0]));
    x[0] = PI;
    eomc_sim_linearize(s, 0, x, A, NULL);
    eomc_sim_eigenvalues(s, A, 2, re, im);
    CHECK(fabs(im[0]) < 1e-15 * w && check_close(fabs(re[0]), w, 1e-14) &&
          check_close(fabs(re[1]), w, 1e-14) && re[0] * re[1] < 0,
          "pendulum at the top: eigenvalues +-sqrt(g/l) = +-%.17g", fabs(re[0]));
    /* how far from rest: at the top -g/l sin(pi) is rounding, against
     * what theta's own size would change q'' by, g/l pi; at 0.7 it is
     * -g/l sin(0.7) against g/l cos(0.7) 0.7 */
    double acc[1];
    int worst;
    double top = eomc_sim_accel_residual(s, 0, x, acc, &worst);
    x[0] = 0.7;
    double off = eomc_sim_accel_residual(s, 0, x, acc, &worst);
    CHECK(top <= EOMC_ACCEL_ZERO && check_close(off, tan(0.7) / 0.7, 1e-14) && worst == 0 &&
          check_close(acc[0], -9.81 * sin(0.7), 1e-15),
          "eomc_sim_accel_residual: %.2g at the top (rounding), %.17g = tan(0.7)/0.7 at 0.7",
          top, off);
    eomc_sim_free(s);
}

static void
test_cart_pole(void)
{
    eomc_sim *s = eomc_sim_alloc(&cart_pole_model);
    const double *p = eomc_sim_params(s); /* M, m, l, g, c, A, w */
    double M = p[0], m = p[1], l = p[2], g = p[3], c = p[4];
    double x[4] = {0, 0, 0, 0}, A[16], B[4];
    int rc = eomc_sim_linearize(s, 0, x, A, B);
    double want_A[16] = {0, 0, 1, 0,
                         0, 0, 0, 1,
                         0, m * g / M, -c / M, 0,
                         0, -(M + m) * g / (M * l), c / (M * l), 0};
    double want_B[4] = {0, 0, 1 / M, -1 / (M * l)};
    double worst = 0;
    for (int i = 0; i < 16; i++)
        worst = fmax(worst, fabs(A[i] - want_A[i]));
    for (int i = 0; i < 4; i++)
        worst = fmax(worst, fabs(B[i] - want_B[i]));
    CHECK(rc == EOMC_OK && worst < 1e-13, "cart-pole upright: A and B as derived by hand, "
          "to %.2g", worst);
    eomc_sim_free(s);
}

static void
test_equilibria(void)
{
    eomc_sim *s = eomc_sim_alloc(&double_pendulum_model);
    double x[4] = {0.3, -0.2, 0.5, 0.5};
    int its, rc = eomc_sim_equilibrium(s, 0, x, &its);
    CHECK(rc == EOMC_OK && fabs(x[0]) < 1e-14 && fabs(x[1]) < 1e-14 && x[2] == 0 && x[3] == 0,
          "double pendulum from (0.3, -0.2): hanging (%.2g, %.2g) in %d Newton steps", x[0],
          x[1], its);
    double y[4] = {2.9, 3.3, 0, 0};
    rc = eomc_sim_equilibrium(s, 0, y, &its);
    CHECK(rc == EOMC_OK && check_close(y[0], PI, 1e-14) && check_close(y[1], PI, 1e-14),
          "double pendulum from (2.9, 3.3): upside down (pi, pi) in %d steps", its);
    eomc_sim_free(s);
    s = eomc_sim_alloc(&cartesian_pendulum_model);
    double z[4] = {0.84, -0.54, 0, 0};
    rc = eomc_sim_equilibrium(s, 0, z, &its);
    CHECK(rc == EOMC_OK && fabs(z[0]) < 1e-14 && check_close(z[1], -1, 1e-14),
          "Cartesian pendulum: the bottom (x, y) = (%.2g, %.17g), on x^2 + y^2 = 1", z[0],
          z[1]);
    eomc_sim_free(s);
    s = eomc_sim_alloc(&rolling_disk_model);
    double d[10] = {0};
    rc = eomc_sim_equilibrium(s, 0, d, &its);
    CHECK(rc == EOMC_EUSAGE && strstr(eomc_sim_error(s), "not isolated"),
          "rolling disk (nonholonomic): no isolated equilibrium, said so");
    eomc_sim_free(s);
}

/* The Cartesian pendulum's bob at (1.2, 0) with l = 1: g = x^2 + y^2 - l^2
 * = 0.44 against its terms |g - B q| + |B q| = 2.44 + 2.88 (B = (2x, 2y)):
 * 0.083, far off; at (sin 1, -cos 1) on the rod to rounding. */
static void
test_off_constraints(void)
{
    eomc_sim *s = eomc_sim_alloc(&cartesian_pendulum_model);
    double off[4] = {1.2, 0, 0, 0.3}, on[4] = {sin(1.0), -cos(1.0), 0.3 * cos(1.0),
                                               0.3 * sin(1.0)};
    double A[4], B[1];
    int rc = eomc_sim_linearize(s, 0, off, A, B);
    const char *msg = eomc_sim_error(s);
    CHECK(rc == EOMC_ENUMERIC && strstr(msg, "the linearization: the state is off the "
                                        "constraint rod (positions: its residual is 0.083 "
                                        "of the size of its terms)"),
          "a state off the rod (x = 1.2 l): refused, naming rod and its share 0.44/5.32: %s",
          msg);
    rc = eomc_sim_linearize(s, 0, on, A, B);
    CHECK(rc == EOMC_OK, "a state on the rod to rounding: linearized (status %d)", rc);
    eomc_sim_free(s);
}

int
main(void)
{
    test_pendulum();
    test_off_constraints();
    test_cart_pole();
    test_equilibria();
#define FD(name)                                                                       \
    {                                                                                  \
        double w_ = check_fd(&name##_model);                                           \
        CHECK(w_ < 1e-7, "%s: A and B match central differences (worst %.2g of the "   \
              "column)", #name, w_);                                                   \
    }
    SPECS(FD)
    FD(cart_pole)
    return check_done();
}

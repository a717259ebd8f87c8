/*
 * Constrained motion over time (runtime integration, rk8pd at 1e-12):
 *  - chaplygin_sleigh: the forward speed v(t) = V tanh(kappa V t + c) of
 *    the closed form, and the energy, conserved;
 *  - central_constant_speed: T = m v0^2 / 2 throughout, and the same
 *    trajectory as the Cartesian formulation (tests/sim/specs/
 *    central_cartesian.yaml), mapped to x, y, z;
 *  - cartesian_pendulum: theta = atan2(x, -y) has the period
 *    4 K(sin(theta0/2)) sqrt(l/g) of the simple pendulum;
 *  - drift: over 100 periods at a loose tolerance (rkf45, 1e-6), the
 *    pendulum's x^2 + y^2 - l^2 and its derivative drift without
 *    stabilization, shrink with Baumgarte's, and stay below 1e-12 with
 *    projection, in every row (recomputed here) and after every step
 *    (the runtime's statistics);
 *  - rolling_disk (defaults m = 1, R = 0.5, g = 9.81): the energy, written
 *    out here from the centre's velocity and the z-x-z body rates, is
 *    conserved over 10 s of leaning, turning motion; started upright and
 *    rolling straight, the disk stays upright and its contact point moves
 *    at -R phi' along x;
 *  - projection: a point off the circle goes to l q / |q| and its
 *    velocity to the tangential part (M = m I, so the mass metric is the
 *    Euclidean one); central_constant_speed's velocity is scaled to speed
 *    v0 with q unchanged (Gauss-Newton's steps are all along M^-1 dphi/dv,
 *    which is parallel to v).
 */
#include "../unit/check.h"
#include "eomc.h"

#include <gsl/gsl_sf_ellint.h>
#include <stdlib.h>

extern const eomc_model chaplygin_sleigh_model, central_constant_speed_model,
    central_cartesian_model, cartesian_pendulum_model, rolling_disk_model;

enum { MAXROWS = 4096 };

typedef struct Rows {
    int n, w;
    double t[MAXROWS], x[MAXROWS][12];
} Rows;

static int
keep(void *ctx, double t, const double *x)
{
    Rows *r = ctx;
    if (r->n < MAXROWS) {
        r->t[r->n] = t;
        for (int i = 0; i < r->w; i++)
            r->x[r->n][i] = x[i];
        r->n++;
    }
    return EOMC_OK;
}

typedef struct Opts {
    const char *method;
    double tol;
    int stabilize;
    double alpha, beta;
} Opts;

/* Integrate m from x (the model's initial state if NULL) to t_end, with
 * rk8pd at 1e-12 unless o says otherwise; statistics into st if given. */
static Rows *
run_with(const eomc_model *m, const double *x0, double t_end, double dt, const Opts *op,
         eomc_stats *st)
{
    eomc_sim *s = eomc_sim_alloc(m);
    if (op && op->stabilize &&
        eomc_sim_stabilize(s, op->stabilize, op->alpha, op->beta) != EOMC_OK)
        printf("# %s: %s\n", m->name, eomc_sim_error(s));
    Rows *r = calloc(1, sizeof *r);
    r->w = 2 * m->nq;
    double x[12];
    if (x0)
        for (int i = 0; i < r->w; i++)
            x[i] = x0[i];
    else
        eomc_sim_initial(s, x, x + m->nq);
    eomc_run_opts o = eomc_run_defaults(m);
    o.t_end = t_end, o.dt = dt, o.method = "rk8pd", o.rtol = o.atol = 1e-12;
    if (op)
        o.method = op->method, o.rtol = o.atol = op->tol;
    if (eomc_sim_integrate(s, &o, x, keep, r, st) != EOMC_OK)
        printf("# %s: %s\n", m->name, eomc_sim_error(s));
    eomc_sim_free(s);
    return r;
}

static Rows *
run(const eomc_model *m, const double *x0, double t_end, double dt)
{
    return run_with(m, x0, t_end, dt, NULL, NULL);
}

static void
sleigh(void)
{
    const double m = 1.0, J = 0.2, b = 0.5, v0 = 0.3, w0 = 2.0, I = J + m * b * b;
    Rows *r = run(&chaplygin_sleigh_model, NULL, 10, 0.05);
    double E = 0.5 * m * v0 * v0 + 0.5 * I * w0 * w0, V = sqrt(2 * E / m);
    double kappa = m * b / I, c = atanh(v0 / V), worst = 0, drift = 0;
    for (int k = 0; k < r->n; k++) {
        double th = r->x[k][2], v = r->x[k][3] * cos(th) + r->x[k][4] * sin(th);
        double w = r->x[k][5];
        worst = fmax(worst, fabs(v - V * tanh(kappa * V * r->t[k] + c)));
        drift = fmax(drift, fabs(0.5 * m * v * v + 0.5 * I * w * w - E) / E);
    }
    CHECK(r->n == 201 && worst < 1e-9, "sleigh: v(t) = V tanh(kappa V t + c) to %.2g", worst);
    CHECK(drift < 1e-10, "sleigh: energy conserved to %.2g", drift);
    free(r);
}

static void
central(void)
{
    Rows *r = run(&central_constant_speed_model, NULL, 5, 0.05);
    const double m = 1.0, v0 = 1.2;
    double tdrift = 0, far = 0;
    /* the same start in Cartesian coordinates */
    double R = r->x[0][0], th = r->x[0][1], ph = r->x[0][2];
    double Rd = r->x[0][3], thd = r->x[0][4], phd = r->x[0][5];
    double ct = cos(th), st = sin(th), cp = cos(ph), sp = sin(ph);
    double xc[6] = {R * ct * cp, R * ct * sp, R * st,
                    Rd * ct * cp - R * st * thd * cp - R * ct * sp * phd,
                    Rd * ct * sp - R * st * thd * sp + R * ct * cp * phd,
                    Rd * st + R * ct * thd};
    Rows *c = run(&central_cartesian_model, xc, 5, 0.05);
    for (int k = 0; k < r->n && k < c->n; k++) {
        double *x = r->x[k];
        double v2 = x[3] * x[3] + x[0] * x[0] * cos(x[1]) * cos(x[1]) * x[5] * x[5] +
                    x[0] * x[0] * x[4] * x[4];
        tdrift = fmax(tdrift, fabs(0.5 * m * v2 - 0.5 * m * v0 * v0));
        double p[3] = {x[0] * cos(x[1]) * cos(x[2]), x[0] * cos(x[1]) * sin(x[2]),
                       x[0] * sin(x[1])};
        for (int i = 0; i < 3; i++)
            far = fmax(far, fabs(p[i] - c->x[k][i]));
    }
    CHECK(r->n == 101 && tdrift < 1e-10, "central: T = m v0^2 / 2 throughout (%.2g)", tdrift);
    CHECK(c->n == r->n && far < 1e-8,
          "central: spherical and Cartesian formulations agree to %.2g over 5 s", far);
    free(r);
    free(c);
}

static void
pendulum_period(void)
{
    const double th0 = 1.0, l = 1.0, g = 9.81;
    double T = 4 * gsl_sf_ellint_Kcomp(sin(th0 / 2), GSL_PREC_DOUBLE) * sqrt(l / g);
    Rows *r = run(&cartesian_pendulum_model, NULL, 2.2 * T, 0.001);
    double down[2];
    int nd = 0;
    for (int k = 1; k < r->n && nd < 2; k++) /* x crosses 0 going negative */
        if (r->x[k - 1][0] > 0 && r->x[k][0] <= 0) {
            double t0 = r->t[k - 1], t1 = r->t[k], x0 = r->x[k - 1][0], x1 = r->x[k][0];
            double v0 = r->x[k - 1][2], v1 = r->x[k][2], h = t1 - t0, lo = 0, hi = 1;
            for (int it = 0; it < 80; it++) { /* root of the cubic Hermite */
                double s = 0.5 * (lo + hi), s2 = s * s, s3 = s2 * s;
                double y = (2 * s3 - 3 * s2 + 1) * x0 + (s3 - 2 * s2 + s) * h * v0 +
                           (-2 * s3 + 3 * s2) * x1 + (s3 - s2) * h * v1;
                *(y > 0 ? &lo : &hi) = s;
            }
            down[nd++] = t0 + 0.5 * (lo + hi) * h;
        }
    CHECK(nd == 2 && check_close(down[1] - down[0], T, 1e-9),
          "cartesian pendulum: period = 4 K(sin(theta0/2)) sqrt(l/g) = %.10f", T);
    free(r);
}

/* The rolling disk's T + V, from its definition (A = m R^2 / 4, C = m R^2 / 2). */
static double
disk_energy(const double *x)
{
    const double m = 1.0, R = 0.5, g = 9.81, A = m * R * R / 4, C = m * R * R / 2;
    double ps = x[2], th = x[3], xd = x[5], yd = x[6], psd = x[7], thd = x[8], phd = x[9];
    double cx = xd + R * sin(th) * thd * sin(ps) - R * cos(th) * cos(ps) * psd;
    double cy = yd - R * sin(th) * thd * cos(ps) - R * cos(th) * sin(ps) * psd;
    double cz = R * cos(th) * thd, r3 = psd * cos(th) + phd;
    double T = 0.5 * m * (cx * cx + cy * cy + cz * cz) +
               0.5 * A * (psd * psd * sin(th) * sin(th) + thd * thd) + 0.5 * C * r3 * r3;
    return T + m * g * R * sin(th);
}

static void
rolling_disk(void)
{
    Rows *r = run(&rolling_disk_model, NULL, 10, 0.01);
    double E0 = disk_energy(r->x[0]), drift = 0, lean = 0;
    for (int k = 0; k < r->n; k++) {
        drift = fmax(drift, fabs(disk_energy(r->x[k]) - E0) / E0);
        lean = fmax(lean, fabs(r->x[k][3] - r->x[0][3]));
    }
    CHECK(r->n == 1001 && drift < 1e-12 && lean > 0.1,
          "rolling disk: energy conserved to %.2g over 10 s (the lean varies by %.2f rad)",
          drift, lean);
    free(r);
    const double R = 0.5, spin = 6.0;
    double x0[10] = {0, 0, 0, (2 * atan(1.0)), 0, -R * spin, 0, 0, 0, spin};
    r = run(&rolling_disk_model, x0, 5, 0.05);
    double off = 0;
    for (int k = 0; k < r->n; k++) {
        off = fmax(off, fabs(r->x[k][0] + R * spin * r->t[k]) + fabs(r->x[k][1]));
        off = fmax(off, fabs(r->x[k][3] - (2 * atan(1.0))) + fabs(r->x[k][2]));
    }
    CHECK(r->n == 101 && off < 1e-9, "rolling disk: upright, it rolls straight at R phi' "
          "(%.2g)", off);
    free(r);
}

/* Largest |g| and |g'| of the pendulum (l = 1) over the rows. */
static double
pendulum_residual(const Rows *r)
{
    double worst = 0;
    for (int k = 0; k < r->n; k++) {
        const double *x = r->x[k];
        worst = fmax(worst, fabs(x[0] * x[0] + x[1] * x[1] - 1.0));
        worst = fmax(worst, fabs(2 * (x[0] * x[2] + x[1] * x[3])));
    }
    return worst;
}

static void
drift(void)
{
    const double th0 = 1.0, l = 1.0, g = 9.81;
    double T = 4 * gsl_sf_ellint_Kcomp(sin(th0 / 2), GSL_PREC_DOUBLE) * sqrt(l / g);
    double span = 100 * T, dt = span / 2000;
    eomc_stats st[3];
    double rows[3];
    for (int k = 0; k < 3; k++) {
        Opts o = {"rkf45", 1e-6, k, 10.0, 10.0};
        Rows *r = run_with(&cartesian_pendulum_model, NULL, span, dt, &o, &st[k]);
        rows[k] = r->n == 2001 ? pendulum_residual(r) : INFINITY;
        free(r);
    }
    printf("# drift over 100 periods: none %.3g, baumgarte %.3g, project %.3g "
           "(%.3g before each projection)\n", rows[0], rows[1], rows[2], st[2].max_drift);
    CHECK(rows[0] > 1e-8 && st[0].max_residual >= rows[0],
          "drift: unstabilized, the rows drift by %.2g (the steps' largest %.2g)", rows[0],
          st[0].max_residual);
    CHECK(rows[1] < rows[0] / 100 && st[1].max_residual < st[0].max_residual / 100,
          "drift: baumgarte (10, 10) keeps it %.0fx smaller", rows[0] / rows[1]);
    CHECK(rows[2] < 1e-12 && st[2].max_residual < 1e-12 && st[2].max_drift > 1e-12,
          "drift: projection keeps every row (%.2g) and step (%.2g) below 1e-12 over 100 "
          "periods", rows[2], st[2].max_residual);
}

static void
projection(void)
{
    eomc_sim *s = eomc_sim_alloc(&cartesian_pendulum_model);
    const double l = 0.8, v0 = 1.2;
    eomc_sim_set(s, "l", l);
    int ok = 1;
    for (int k = 0; k < 50; k++) {
        double q[2] = {check_rand(-2, 2), check_rand(-2, 2)};
        double v[2] = {check_rand(-3, 3), check_rand(-3, 3)}, r = hypot(q[0], q[1]);
        double e[2] = {q[0] / r, q[1] / r}, vr = v[0] * e[0] + v[1] * e[1];
        double vt[2] = {v[0] - vr * e[0], v[1] - vr * e[1]};
        ok &= eomc_sim_project(s, 0.0, q, v) == EOMC_OK;
        ok &= check_close(q[0], l * e[0], 1e-14) && check_close(q[1], l * e[1], 1e-14);
        ok &= fabs(v[0] - vt[0]) < 1e-13 && fabs(v[1] - vt[1]) < 1e-13;
    }
    CHECK(ok, "projection: cartesian pendulum q -> l q / |q|, v -> its tangential part, "
              "50 random states");
    eomc_sim_free(s);
    s = eomc_sim_alloc(&central_constant_speed_model);
    ok = 1;
    for (int k = 0; k < 50; k++) {
        double q[3] = {check_rand(0.5, 3), check_rand(-1.2, 1.2), check_rand(-3, 3)};
        double v[3] = {check_rand(-2, 2), check_rand(-2, 2), check_rand(-2, 2)}, q0[3], w[3];
        double ct = cos(q[1]);
        double speed = sqrt(v[0] * v[0] + q[0] * q[0] * (v[1] * v[1] + ct * ct * v[2] * v[2]));
        for (int i = 0; i < 3; i++)
            q0[i] = q[i], w[i] = v[i] * v0 / speed;
        ok &= eomc_sim_project(s, 0.0, q, v) == EOMC_OK;
        for (int i = 0; i < 3; i++)
            ok &= q[i] == q0[i] && check_close(v[i], w[i], 1e-13);
    }
    CHECK(ok, "projection: central_constant_speed v -> v v0 / |v| (q unchanged), 50 "
              "random states");
    eomc_sim_free(s);
}

int
main(void)
{
    sleigh();
    central();
    pendulum_period();
    rolling_disk();
    drift();
    projection();
    return check_done();
}

/*
 * Constrained motion over time (runtime integration, rk8pd at 1e-12):
 *  - chaplygin_sleigh: the forward speed v(t) = V tanh(kappa V t + c) of
 *    the closed form, and the energy, conserved;
 *  - central_constant_speed: T = m v0^2 / 2 throughout, and the same
 *    trajectory as the Cartesian formulation (tests/sim/specs/
 *    central_cartesian.yaml), mapped to x, y, z;
 *  - cartesian_pendulum: theta = atan2(x, -y) has the period
 *    4 K(sin(theta0/2)) sqrt(l/g) of the simple pendulum.
 */
#include "../unit/check.h"
#include "eomc.h"

#include <gsl/gsl_sf_ellint.h>
#include <stdlib.h>

extern const eomc_model chaplygin_sleigh_model, central_constant_speed_model,
    central_cartesian_model, cartesian_pendulum_model;

enum { MAXROWS = 4096 };

typedef struct Rows {
    int n, w;
    double t[MAXROWS], x[MAXROWS][8];
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

/* Integrate m from x (the model's initial state if NULL) to t_end. */
static Rows *
run(const eomc_model *m, const double *x0, double t_end, double dt)
{
    eomc_sim *s = eomc_sim_alloc(m);
    Rows *r = calloc(1, sizeof *r);
    r->w = 2 * m->nq;
    double x[8];
    if (x0)
        for (int i = 0; i < r->w; i++)
            x[i] = x0[i];
    else
        eomc_sim_initial(s, x, x + m->nq);
    eomc_run_opts o = eomc_run_defaults(m);
    o.t_end = t_end, o.dt = dt, o.method = "rk8pd", o.rtol = o.atol = 1e-12;
    if (eomc_sim_integrate(s, &o, x, keep, r, NULL) != EOMC_OK)
        printf("# %s: %s\n", m->name, eomc_sim_error(s));
    eomc_sim_free(s);
    return r;
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

int
main(void)
{
    sleigh();
    central();
    pendulum_period();
    return check_done();
}

/*
 * Trajectories of the shipped specs against independent values:
 *   falling_particle  y(t) = y0 + 1/2 (f/m - g) t^2 (closed form)
 *   pendulum          period = 4 K(sin(theta0/2)) sqrt(l/g) (GSL's
 *                     complete elliptic integral) for several amplitudes
 *   double_pendulum   energy conserved to 1e-9 relative over 10 s with
 *                     rk8pd at 1e-12; E(0) against the closed form
 *   gear_link, chain5 energy, written out here from the state, conserved (the
 *                     input held at zero) and equal to the CSV's E
 *
 * usage: test_motion SIM_FALLING SIM_PENDULUM SIM_GEAR SIM_DOUBLE SIM_CHAIN5
 */
#include "../unit/check.h"
#include "simrun.h"

#include <gsl/gsl_sf_ellint.h>

static const char *sim[5];

static SimTable
run(int which, const char *args)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "'%s' %s", sim[which], args);
    int st;
    char *out = sim_capture(cmd, &st);
    if (st != 0)
        printf("# %s exited %d\n", cmd, st);
    SimTable t = sim_parse_csv(out);
    free(out);
    return t;
}

static void
falling(void)
{
    SimTable t = run(0, "");
    int ct = sim_column(&t, "t"), cy = sim_column(&t, "y"), cv = sim_column(&t, "y'");
    double a = 5.0 / 2.0 - 9.81, ok = 1;
    for (int r = 0; r < t.nrow; r++) {
        double tt = sim_at(&t, r, ct);
        ok = ok && check_close(sim_at(&t, r, cy), 10 + 0.5 * a * tt * tt, 1e-11) &&
             check_close(sim_at(&t, r, cv), a * tt, 1e-11);
    }
    CHECK(t.nrow == 101, "falling_particle: 101 rows for t in [0, 1] by 0.01 (got %d)", t.nrow);
    CHECK(ok, "falling_particle: y(t) = y0 + (f/m - g) t^2 / 2");
    sim_table_free(&t);
}

/* Root of the cubic Hermite interpolant of theta between two rows. */
static double
crossing(double t0, double t1, double y0, double y1, double d0, double d1)
{
    double h = t1 - t0, lo = 0, hi = 1;
    for (int it = 0; it < 100; it++) {
        double s = 0.5 * (lo + hi), s2 = s * s, s3 = s2 * s;
        double y = (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * h * d0 +
                   (-2 * s3 + 3 * s2) * y1 + (s3 - s2) * h * d1;
        if ((y > 0) == (y0 > 0))
            lo = s;
        else
            hi = s;
    }
    return t0 + 0.5 * (lo + hi) * h;
}

static void
pendulum_period(void)
{
    const double amp[] = {0.1, 0.5, 1.0, 2.0, 3.0};
    const double l = 1.0, g = 9.81;
    for (size_t k = 0; k < sizeof amp / sizeof amp[0]; k++) {
        double T = 4 * gsl_sf_ellint_Kcomp(sin(amp[k] / 2), GSL_PREC_DOUBLE) * sqrt(l / g);
        char args[256];
        snprintf(args, sizeof args, "--init theta=%.17g --t-end %.17g --dt 0.01 "
                 "--rtol 1e-12 --atol 1e-12", amp[k], 2.2 * T);
        SimTable t = run(1, args);
        int ct = sim_column(&t, "t"), cy = sim_column(&t, "theta"), cv = sim_column(&t, "theta'");
        double down[4];
        int nd = 0;
        for (int r = 1; r < t.nrow && nd < 4; r++) {
            double y0 = sim_at(&t, r - 1, cy), y1 = sim_at(&t, r, cy);
            if (y0 > 0 && y1 <= 0)
                down[nd++] = crossing(sim_at(&t, r - 1, ct), sim_at(&t, r, ct), y0, y1,
                                      sim_at(&t, r - 1, cv), sim_at(&t, r, cv));
        }
        CHECK(nd >= 2, "pendulum theta0 = %g: two downward crossings", amp[k]);
        if (nd >= 2)
            CHECK_NEAR(down[1] - down[0], T, 1e-7,
                       "pendulum theta0 = %g: period = 4 K(sin(theta0/2)) sqrt(l/g) = %.10f",
                       amp[k], T);
        sim_table_free(&t);
    }
}

/* The double pendulum's energy written out here, not taken from the
 * generated code (a wrong T used consistently would conserve its own E):
 * m = l = 1, T = th1'^2 + th2'^2 / 2 + th1' th2' cos(th1 - th2),
 * V = -g (2 cos th1 + cos th2). */
static double
dp_energy(const SimTable *t, int r)
{
    double a = sim_at(t, r, sim_column(t, "th1")), b = sim_at(t, r, sim_column(t, "th2"));
    double va = sim_at(t, r, sim_column(t, "th1'")), vb = sim_at(t, r, sim_column(t, "th2'"));
    return va * va + vb * vb / 2 + va * vb * cos(a - b) - 9.81 * (2 * cos(a) + cos(b));
}

static void
double_pendulum(void)
{
    SimTable t = run(3, "--method rk8pd --rtol 1e-12 --atol 1e-12 --t-end 10");
    double E0 = dp_energy(&t, 0), drift = 0, column = 0;
    int ce = sim_column(&t, "E");
    for (int r = 0; r < t.nrow; r++) {
        double e = dp_energy(&t, r);
        drift = fmax(drift, fabs(e - E0) / fabs(E0));
        column = fmax(column, fabs(sim_at(&t, r, ce) - e) / fabs(E0));
    }
    CHECK(column < 1e-13, "double_pendulum: the CSV's E is the energy computed here from "
          "the state, to %.2g", column);
    /* initial state of the spec: th1 = 2, th2 = 1, at rest; m = l = 1 */
    double want = -9.81 * (2 * cos(2.0) + cos(1.0));
    CHECK_NEAR(E0, want, 1e-14, "double_pendulum: E(0) = -g (2 cos th1 + cos th2)");
    CHECK(t.nrow > 100 && sim_at(&t, t.nrow - 1, 0) == 10.0, "double_pendulum: ran to t = 10");
    CHECK(drift < 1e-9, "double_pendulum: energy drift %.3g < 1e-9 over 10 s (rk8pd, 1e-12)", drift);
    sim_table_free(&t);
}

/* gear_link's energy written out here: 1/2 (Jm r^2 + Jl) th'^2 +
 * M g l (1 - cos th), with the spec's Jm = 0.01, r = 10, Jl = 0.5, M = 2,
 * l = 0.3; conserved with the motor's torque held at 0. */
static void
gear_link_energy(void)
{
    SimTable t = run(2, "--set u=0 --rtol 1e-12 --atol 1e-12");
    int cq = sim_column(&t, "theta_l"), cv = sim_column(&t, "theta_l'"), ce = sim_column(&t, "E");
    double E0 = 0, drift = 0, column = 0;
    for (int r = 0; r < t.nrow; r++) {
        double th = sim_at(&t, r, cq), w = sim_at(&t, r, cv);
        double e = 0.5 * (0.01 * 100 + 0.5) * w * w + 2 * 9.81 * 0.3 * (1 - cos(th));
        if (r == 0)
            E0 = e;
        drift = fmax(drift, fabs(e - E0) / E0);
        column = fmax(column, fabs(sim_at(&t, r, ce) - e) / E0);
    }
    CHECK(t.nrow > 10 && column < 1e-13 && drift < 1e-9, "gear_link (u = 0): the energy "
          "computed here from the state is conserved to %.2g, and is the CSV's E to %.2g",
          drift, column);
    sim_table_free(&t);
}

/* chain5's energy written out here: unit masses at the ends of unit
 * rods, joint angles relative (a_k = q1 + ... + qk), g = 9.81; each
 * mass's velocity by summing the rods' (cos a, sin a) a' before it. */
static double
chain5_energy_at(const SimTable *t, int r)
{
    char name[8];
    double a = 0, w = 0, y = 0, vx = 0, vy = 0, T = 0, V = 0;
    for (int k = 1; k <= 5; k++) {
        snprintf(name, sizeof name, "q%d", k);
        a += sim_at(t, r, sim_column(t, name));
        snprintf(name, sizeof name, "q%d'", k);
        w += sim_at(t, r, sim_column(t, name));
        y -= cos(a);
        vx += cos(a) * w, vy += sin(a) * w;
        T += 0.5 * (vx * vx + vy * vy);
        V += 9.81 * y;
    }
    return T + V;
}

static void
chain5_energy(void)
{
    SimTable t = run(4, "--rtol 1e-12 --atol 1e-12 --t-end 5");
    int ce = sim_column(&t, "E");
    double E0 = chain5_energy_at(&t, 0), drift = 0, column = 0;
    for (int r = 0; r < t.nrow; r++) {
        double e = chain5_energy_at(&t, r);
        drift = fmax(drift, fabs(e - E0) / fabs(E0));
        column = fmax(column, fabs(sim_at(&t, r, ce) - e) / fabs(E0));
    }
    CHECK(t.nrow > 10 && column < 1e-13 && drift < 1e-9, "chain5: the energy computed here "
          "from the state is conserved to %.2g, and is the CSV's E to %.2g", drift, column);
    sim_table_free(&t);
}


int
main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: test_motion FALLING PENDULUM GEAR DOUBLE CHAIN5\n");
        return 2;
    }
    for (int i = 0; i < 5; i++)
        sim[i] = argv[i + 1];
    falling();
    pendulum_period();
    double_pendulum();
    gear_link_energy();
    chain5_energy();
    return check_done();
}

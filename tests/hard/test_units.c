/*
 * Hard case: units.  Rescaling a model's units of mass, length and time by
 * factors from 1e-12 to 1e12 must change no answer beyond rounding.
 *  - The Cartesian pendulum's q'' and multiplier at a state, for masses
 *    1e-12 .. 1e12 kg (7e6 kg: a 7-tonne bob), lengths 1e-7 .. 1e6 m and
 *    units of time 1e-12 .. 1e12 s, against the closed form
 *    q'' = -g sin th (cos th, sin th) - w^2 l (sin th, -cos th),
 *    lambda = m (g cos th + w^2 l) / (2 l).
 *  - Its consistency check: an exactly consistent state is consistent
 *    (to rounding) in every unit, also upright, where each term of g' is
 *    rounding; a velocity off the rod by 1e-3 reads as its share of the
 *    velocity, 1e-3 / sqrt(1 + 1e-6).
 *  - Each constraint's own inconsistency (eomc_sim_inconsistencies), on
 *    the Cartesian double pendulum with bob 1 at 1.2 l1 from the pivot
 *    and bob 2 moving along rod 2 at u: rod1's position residual against
 *    its terms, (rho^2 - l1^2) / (3 rho^2 + l1^2) = 0.44 / 5.32 by hand
 *    (g = rho^2 - l1^2 over |g - B q| + |B q|, B = dg/dq), and rod2's
 *    velocity share, the cosine 1 / sqrt(1 + m2/m1) in the metric of M
 *    (g2' = 2 l2 u against |B2| |v| in that metric), in every unit.
 *  - The pendulum with its unit of time made 1e-12 .. 1e12 s
 *    (g = 9.81 / tau^2, t_end = 10 tau, atol = 0): the same rows in units
 *    of tau, each against the elliptic closed form
 *    th = 2 asin(k sn(K - w t, k)), k = sin(th0 / 2) (GSL's sn and K).
 *  - The double pendulum in Cartesian coordinates with two rods (a DAE:
 *    the KKT system, and with --stabilize project the projection), with
 *    its units of mass, length and time rescaled together and apart: the
 *    same dimensionless rows as in SI, and those rows against the angular
 *    model of the same motion (specs/double_pendulum.yaml) at a tight
 *    tolerance.
 */
#include "hard.h"

#include <float.h>
#include <gsl/gsl_sf_elljac.h>
#include <gsl/gsl_sf_ellint.h>

extern const eomc_model cartesian_pendulum_model, pendulum_model, double_pendulum_model,
    cartesian_double_pendulum_model;

/* Rounding, with room for the few dozen operations between a state and
 * its q'' (64 units). */
#define ROUNDING (64 * DBL_EPSILON)
/* The unit changes: factors on mass, length and time. */
static const double mass_units[] = {1e-12, 1e-6, 1.0, 7e6, 1e12};
static const double length_units[] = {1e-7, 1e-3, 1.0, 1e3, 1e6};
static const double time_units[] = {1e-12, 1e-6, 1.0, 1e6, 1e12};
#define COUNT(a) (int)(sizeof(a) / sizeof(a)[0])

static void
set(eomc_sim *s, const char *name, double value)
{
    if (eomc_sim_set(s, name, value) != EOMC_OK)
        printf("# cannot set %s\n", name);
}

/* ---- the Cartesian pendulum's accelerations ---- */

static void
pendulum_accel(void)
{
    eomc_sim *s = eomc_sim_alloc(&cartesian_pendulum_model);
    double worst_a = 0, worst_l = 0;
    int fails = 0, cases = 0;
    const double th[] = {1.0, -2.5, 0.3}, w[] = {0.0, 0.7};
    for (int im = 0; im < COUNT(mass_units); im++)
        for (int il = 0; il < COUNT(length_units); il++)
            for (int it = 0; it < COUNT(time_units); it++)
                for (int k = 0; k < COUNT(th); k++)
                    for (int j = 0; j < COUNT(w); j++) {
                        double m = 2.5 * mass_units[im], l = 0.8 * length_units[il];
                        double tau = time_units[it], g = 9.81 / (tau * tau);
                        double om = w[j] * sqrt(g / l), c = cos(th[k]), sn = sin(th[k]);
                        set(s, "m", m), set(s, "l", l), set(s, "g", g);
                        double q[2] = {l * sn, -l * c}, v[2] = {om * l * c, om * l * sn};
                        double want[2] = {-g * sn * c - om * om * l * sn,
                                          -g * sn * sn + om * om * l * c};
                        double lam = m * (g * c + om * om * l) / (2 * l), a[2];
                        cases++;
                        if (eomc_sim_accel(s, 0.0, q, v, a) != EOMC_OK) {
                            if (fails++ == 0)
                                printf("# m %g l %g tau %g: %s\n", m, l, tau,
                                       eomc_sim_error(s));
                            continue;
                        }
                        double scale = g + om * om * l; /* the accelerations' size */
                        for (int i = 0; i < 2; i++)
                            worst_a = fmax(worst_a, fabs(a[i] - want[i]) / scale);
                        worst_l = fmax(worst_l,
                                       fabs(eomc_sim_multipliers(s)[0] - lam) / lam);
                    }
    CHECK(fails == 0 && worst_a <= ROUNDING && worst_l <= ROUNDING,
          "cartesian pendulum: q'' and lambda in %d unit systems (m 2.5e-12 .. 2.5e12, "
          "l 8e-8 .. 8e5, tau 1e-12 .. 1e12), %d failed; largest relative errors %.2g, "
          "%.2g <= %.2g", cases, fails, worst_a, worst_l, ROUNDING);
    eomc_sim_free(s);
}

/* ---- the consistency check ---- */

static void
consistency(void)
{
    eomc_sim *s = eomc_sim_alloc(&cartesian_pendulum_model);
    double worst = 0, off_worst = 0;
    int worst_row = -2, level = -1, off_level = 1;
    /* a radial velocity of 1e-3 of the tangential: the share of the
     * velocity along the rod's normal (in the metric of M = m I, the
     * Euclidean one), the cosine 1e-3 / sqrt(1 + 1e-6) */
    double share = 1e-3 / sqrt(1 + 1e-6);
    for (int im = 0; im < COUNT(mass_units); im++)
        for (int il = 0; il < COUNT(length_units); il++)
            for (int it = 0; it < COUNT(time_units); it++) {
                double l = length_units[il], tau = time_units[it], om = 1.3 / tau;
                set(s, "m", mass_units[im]);
                set(s, "l", l);
                /* at theta = 1, and upright with y' = 0 as a user types it:
                 * x = l sin(pi) is rounding, and so is g' = 2 (x x' + y y') */
                for (int up = 0; up < 2; up++) {
                    double th = up ? 3.14159265358979323846 : 1.0;
                    double q[2] = {l * sin(th), -l * cos(th)};
                    double v[2] = {om * l * cos(th), up ? 0 : om * l * sin(th)};
                    int row;
                    double e = eomc_sim_inconsistency(s, 0.0, q, v, &row, &level);
                    if (e > worst)
                        worst = e, worst_row = row;
                    double vr[2] = {v[0] + 1e-3 * om * q[0], v[1] + 1e-3 * om * q[1]};
                    e = eomc_sim_inconsistency(s, 0.0, q, vr, &row, &level);
                    off_worst = fmax(off_worst, fabs(e / share - 1));
                    off_level &= level == 1 && row == 0;
                }
            }
    CHECK(worst <= ROUNDING,
          "consistency: the pendulum exactly on its rod (at theta = 1 and upright), m 1e-12 .. "
          "1e12, l 1e-7 .. 1e6, tau 1e-12 .. 1e12: at most %.2g of its terms (row %d) <= %.2g",
          worst, worst_row, ROUNDING);
    /* g' cancels terms 1/share times its size: its rounding grows as much */
    CHECK(off_worst <= ROUNDING / share && off_level,
          "consistency: a radial velocity of 1e-3 reads as its share 1e-3 / sqrt(1 + 1e-6) at "
          "velocity level in every unit, to %.2g of it", off_worst);
    eomc_sim_free(s);
}

/* ---- each constraint's inconsistency ---- */

static void
inconsistencies(void)
{
    eomc_sim *s = eomc_sim_alloc(&cartesian_double_pendulum_model);
    double worst = 0;
    int order_ok = 1, cases = 0;
    const double m2_m1[] = {1.0, 3.0};
    for (int im = 0; im < COUNT(mass_units); im++)
        for (int il = 0; il < COUNT(length_units); il++)
            for (int r = 0; r < COUNT(m2_m1); r++) {
                double l = length_units[il], m = mass_units[im], u = 0.7 * l;
                set(s, "m1", m);
                set(s, "m2", m2_m1[r] * m);
                set(s, "l1", l);
                set(s, "l2", 0.8 * l);
                /* bob 1 at 1.2 l1 at 1 rad from the downward vertical; bob 2
                 * 0.8 l on from it at 0.3 rad, moving along rod 2 at u */
                double rho = 1.2 * l, n[2] = {sin(0.3), -cos(0.3)};
                double q[4] = {rho * sin(1.0), -rho * cos(1.0), 0, 0};
                q[2] = q[0] + 0.8 * l * n[0], q[3] = q[1] + 0.8 * l * n[1];
                double v[4] = {0, 0, u * n[0], u * n[1]}, e[2];
                int level[2], row, lev;
                double big = eomc_sim_inconsistencies(s, 0.0, q, v, e, level);
                double one = eomc_sim_inconsistency(s, 0.0, q, v, &row, &lev);
                double want1 = 0.44 / 5.32, want2 = 1 / sqrt(1 + m2_m1[r]);
                worst = fmax(worst, fmax(fabs(e[0] / want1 - 1), fabs(e[1] / want2 - 1)));
                order_ok &= level[0] == 0 && level[1] == 1 && big == one && row == 1 &&
                            lev == 1 && big == e[1];
                cases++;
            }
    CHECK(worst <= ROUNDING && order_ok,
          "inconsistencies: rod1's positions 0.44/5.32 and rod2's velocities 1/sqrt(1 + "
          "m2/m1) each (to %.2g), at their levels, the largest eomc_sim_inconsistency's, in "
          "%d settings of m, l, m2/m1", worst, cases);
    eomc_sim_free(s);
}

/* ---- the time-scaled pendulum ---- */

/* theta(t) released from rest at th0 with w = sqrt(g / l). */
static double
pendulum_exact(double th0, double w, double t)
{
    double k = sin(th0 / 2), K = gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE), sn, cn, dn;
    gsl_sf_elljac_e(K - w * t, k * k, &sn, &cn, &dn);
    return 2 * asin(k * sn);
}

static void
time_scaled_pendulum(void)
{
    eomc_sim *s = eomc_sim_alloc(&pendulum_model);
    Rows base = {0};
    double worst_exact = 0, worst_same = 0;
    long steps_min = 0, steps_max = 0;
    int fails = 0;
    for (int it = 0; it < COUNT(time_units); it++) {
        double tau = time_units[it], g = 9.81 / (tau * tau), th0 = 1.0;
        set(s, "g", g);
        eomc_run_opts o = eomc_run_defaults(&pendulum_model);
        o.t_end = 10 * tau, o.dt = 0.1 * tau, o.rtol = 1e-10, o.atol = 0;
        Rows r = hard_run(s, &o, NULL);
        if (r.rc != EOMC_OK) {
            if (fails++ == 0)
                printf("# tau %g: %s\n", tau, r.error);
            hard_free(&r);
            continue;
        }
        steps_min = steps_min ? (r.st.steps < steps_min ? r.st.steps : steps_min) : r.st.steps;
        steps_max = r.st.steps > steps_max ? r.st.steps : steps_max;
        for (long k = 0; k < r.nrows; k++)
            worst_exact = fmax(worst_exact, fabs(r.x[2 * k] -
                               pendulum_exact(th0, sqrt(9.81), r.t[k] / tau)));
        if (tau == 1.0)
            base = r;
        else {
            for (long k = 0; base.nrows && k < r.nrows && k < base.nrows; k++)
                worst_same = fmax(worst_same, fabs(r.x[2 * k] - base.x[2 * k]));
            hard_free(&r);
        }
    }
    /* rk8pd at rtol 1e-10: a global error of a few 1e-10 over 3 periods */
    CHECK(fails == 0 && worst_exact <= 5e-10,
          "time-scaled pendulum: tau 1e-12 .. 1e12 s, 101 rows each within %.2g rad of "
          "the elliptic closed form (<= 5e-10 at rtol 1e-10), %d failed", worst_exact, fails);
    /* Powers of 10 are not exact in binary: a step accepted in one unit
     * of time may be rejected in another, and the discretizations then
     * differ, each within the tolerance of the true motion. */
    CHECK(fails == 0 && worst_same <= 1e-10 && steps_max <= steps_min + steps_min / 50,
          "time-scaled pendulum: the same rows in every unit of time, %.2g rad apart "
          "(<= rtol 1e-10), %ld .. %ld steps (within 2%%)", worst_same, steps_min, steps_max);
    hard_free(&base);
    eomc_sim_free(s);
}

/* ---- the Cartesian double pendulum ---- */

typedef struct Units { double mass, length, time; } Units;

static const Units unit_sets[] = {
    {1, 1, 1},       {1e12, 1, 1},        {1e-12, 1, 1},     {1, 1e6, 1},
    {1, 1e-7, 1},    {1, 1, 1e-12},       {1, 1, 1e12},      {1e-12, 1e6, 1e-12},
    {1e12, 1e-7, 1e12},
};

/* The Cartesian run in units u (atol 0: tolerances with no unit), its
 * rows made dimensionless again into r. */
static Rows
cartesian_run(eomc_sim *s, Units u, int stabilize, const char *method)
{
    double L = u.length, T = u.time;
    set(s, "m1", 1.0 * u.mass), set(s, "m2", 1.0 * u.mass);
    set(s, "l1", 1.0 * L), set(s, "l2", 1.0 * L), set(s, "g", 9.81 * L / (T * T));
    eomc_sim_stabilize(s, stabilize, 0, 0);
    eomc_run_opts o = eomc_run_defaults(&cartesian_double_pendulum_model);
    o.t_end = 3 * T, o.dt = 0.05 * T, o.rtol = 1e-10, o.atol = 0;
    if (method) /* else the default */
        o.method = method;
    Rows r = hard_run(s, &o, NULL);
    for (long k = 0; k < r.nrows; k++) {
        r.t[k] /= T;
        for (int i = 0; i < 8; i++)
            r.x[8 * k + i] /= i < 4 ? L : L / T;
    }
    return r;
}

static void
cartesian_double(void)
{
    /* the reference: the angular model, in SI, at 1e-13 */
    eomc_sim *a = eomc_sim_alloc(&double_pendulum_model);
    eomc_run_opts o = eomc_run_defaults(&double_pendulum_model);
    o.t_end = 3, o.dt = 0.05, o.rtol = 1e-13, o.atol = 0;
    Rows ref = hard_run(a, &o, NULL);
    eomc_sim *s = eomc_sim_alloc(&cartesian_double_pendulum_model);
    /* the default method, and Taylor's (issue 26: its step is a time, its
     * KKT system scaled as the solves' are, so its rows agree to rounding
     * grown over 3 s of a chaotic motion: 6.4e-15 measured) */
    static const char *const methods[] = {NULL, "taylor"};
    static const double same_tol[] = {1e-10, 1e-12};
    for (int me = 0; me < 2; me++)
    for (int stab = EOMC_STABILIZE_NONE; stab <= EOMC_STABILIZE_PROJECT;
         stab += EOMC_STABILIZE_PROJECT - EOMC_STABILIZE_NONE) {
        const char *method = methods[me], *name = method ? method : "default method";
        Rows base = cartesian_run(s, unit_sets[0], stab, method);
        double worst_ref = 0, worst_same = 0;
        int fails = base.rc != EOMC_OK;
        for (long k = 0; k < base.nrows && k < ref.nrows; k++) {
            double t1 = ref.x[4 * k], t2 = ref.x[4 * k + 1];
            double x[4] = {sin(t1), -cos(t1), sin(t1) + sin(t2), -cos(t1) - cos(t2)};
            for (int i = 0; i < 4; i++)
                worst_ref = fmax(worst_ref, fabs(base.x[8 * k + i] - x[i]));
        }
        for (int u = 1; u < COUNT(unit_sets); u++) {
            Rows r = cartesian_run(s, unit_sets[u], stab, method);
            if (r.rc != EOMC_OK || r.nrows != base.nrows) {
                if (fails++ == 0)
                    printf("# units %g %g %g: %s\n", unit_sets[u].mass,
                           unit_sets[u].length, unit_sets[u].time, r.error);
            }
            for (long k = 0; k < r.nrows && k < base.nrows; k++)
                for (int i = 0; i < 8; i++)
                    worst_same = fmax(worst_same, fabs(r.x[8 * k + i] - base.x[8 * k + i]) /
                                                      (i < 4 ? 2.0 : 10.0));
            hard_free(&r);
        }
        const char *how = stab ? "with projection" : "unstabilized";
        CHECK(fails == 0 && worst_ref <= 1e-10,
              "cartesian double pendulum, %s %s: the bobs within %.2g of the angular model's "
              "over 3 s (<= rtol 1e-10)", name, how, worst_ref);
        CHECK(fails == 0 && worst_same <= same_tol[me],
              "cartesian double pendulum, %s %s: the same dimensionless rows in %d systems "
              "of units (m 1e-12 .. 1e12, l 1e-7 .. 1e6, tau 1e-12 .. 1e12): %.2g apart "
              "relative (<= %g), %d failed", name, how, COUNT(unit_sets), worst_same,
              same_tol[me], fails);
        hard_free(&base);
    }
    hard_free(&ref);
    eomc_sim_free(s);
    eomc_sim_free(a);
}

int
main(void)
{
    pendulum_accel();
    consistency();
    inconsistencies();
    time_scaled_pendulum();
    cartesian_double();
    return check_done();
}

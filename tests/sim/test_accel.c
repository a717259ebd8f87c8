/*
 * `--accel` of every shipped spec against an independent derivation, at
 * random states and parameter values set from the command line:
 *   falling_particle  m y'' = f - m g                        (seed 000)
 *   pendulum          theta'' = -g/l sin(theta)
 *   gear_link         (r^2 Jm + Jl) theta_l'' + M g l sin(theta_l) = r u
 *   double_pendulum   the textbook closed form (absolute angles)
 *   chain5            Newton + d'Alembert on the particles, solved by
 *                     Gaussian elimination: plain loops, no eomc code
 *
 * usage: test_accel SIM_FALLING SIM_PENDULUM SIM_GEAR SIM_DOUBLE SIM_CHAIN5
 */
#include "../unit/check.h"
#include "simrun.h"

static const char *sim[5];

/* Run `sim --accel ARGS` and return its output (exit status checked). */
static char *
accel(int which, const char *args)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "'%s' --accel %s", sim[which], args);
    int st;
    char *out = sim_capture(cmd, &st);
    if (st != 0)
        printf("# %s exited %d\n", cmd, st);
    return out;
}

static void
falling(void)
{
    int ok = 1;
    for (int k = 0; k < 10; k++) {
        double m = check_rand(0.5, 5), g = check_rand(1, 20), f = check_rand(-30, 30);
        double y = check_rand(-10, 10), yd = check_rand(-5, 5);
        char args[512];
        snprintf(args, sizeof args, "--set m=%.17g --set g=%.17g --set f=%.17g "
                 "--init y=%.17g --init \"y'=%.17g\"", m, g, f, y, yd);
        char *out = accel(0, args);
        ok &= check_close(sim_accel_value(out, "y''"), f / m - g, 1e-13);
        free(out);
    }
    CHECK(ok, "falling_particle: y'' = f/m - g");
}

static void
pendulum(void)
{
    int ok = 1;
    for (int k = 0; k < 10; k++) {
        double l = check_rand(0.2, 3), g = check_rand(1, 20);
        double th = check_rand(-3, 3), thd = check_rand(-4, 4);
        char args[512];
        snprintf(args, sizeof args, "--set l=%.17g --set g=%.17g --init theta=%.17g "
                 "--init \"theta'=%.17g\"", l, g, th, thd);
        char *out = accel(1, args);
        ok &= check_close(sim_accel_value(out, "theta''"), -g / l * sin(th), 1e-13);
        free(out);
    }
    CHECK(ok, "pendulum: theta'' = -g/l sin(theta)");
}

static void
gear_link(void)
{
    int ok = 1;
    for (int k = 0; k < 10; k++) {
        double Jm = check_rand(0.001, 0.1), Jl = check_rand(0.1, 2), r = check_rand(1, 50);
        double M = check_rand(0.5, 5), l = check_rand(0.1, 1), g = 9.81;
        double u = check_rand(-2, 2), th = check_rand(-3, 3), thd = check_rand(-3, 3);
        char args[1024];
        snprintf(args, sizeof args,
                 "--set Jm=%.17g --set Jl=%.17g --set r=%.17g --set M=%.17g "
                 "--set l=%.17g --set u=%.17g --init theta_l=%.17g --init \"theta_l'=%.17g\"",
                 Jm, Jl, r, M, l, u, th, thd);
        char *out = accel(2, args);
        double want = (r * u - M * g * l * sin(th)) / (r * r * Jm + Jl);
        ok &= check_close(sim_accel_value(out, "theta_l''"), want, 1e-13);
        free(out);
    }
    CHECK(ok, "gear_link: (r^2 Jm + Jl) theta_l'' + M g l sin(theta_l) = r u");
    /* the input as a signal: u(0) = 0.5 sin(0) = 0 at the spec's initial state */
    char *out = accel(2, "--init theta_l=0.7");
    double want = -2.0 * 9.81 * 0.3 * sin(0.7) / (100 * 0.01 + 0.5);
    CHECK_NEAR(sim_accel_value(out, "theta_l''"), want, 1e-13,
               "gear_link: input signal u(t) used when not --set");
    free(out);
}

static void
double_pendulum(void)
{
    int ok = 1;
    for (int k = 0; k < 20; k++) {
        double m1 = check_rand(0.5, 3), m2 = check_rand(0.5, 3);
        double l1 = check_rand(0.5, 2), l2 = check_rand(0.5, 2), g = check_rand(1, 20);
        double t1 = check_rand(-3, 3), t2 = check_rand(-3, 3);
        double w1 = check_rand(-3, 3), w2 = check_rand(-3, 3);
        char args[1024];
        snprintf(args, sizeof args,
                 "--set m1=%.17g --set m2=%.17g --set l1=%.17g --set l2=%.17g --set g=%.17g "
                 "--init th1=%.17g --init th2=%.17g --init \"th1'=%.17g\" --init \"th2'=%.17g\"",
                 m1, m2, l1, l2, g, t1, t2, w1, w2);
        char *out = accel(3, args);
        double d = t1 - t2, den = 2 * m1 + m2 - m2 * cos(2 * d);
        double a1 = (-g * (2 * m1 + m2) * sin(t1) - m2 * g * sin(t1 - 2 * t2) -
                     2 * sin(d) * m2 * (w2 * w2 * l2 + w1 * w1 * l1 * cos(d))) / (l1 * den);
        double a2 = (2 * sin(d) * (w1 * w1 * l1 * (m1 + m2) + g * (m1 + m2) * cos(t1) +
                     w2 * w2 * l2 * m2 * cos(d))) / (l2 * den);
        ok &= check_close(sim_accel_value(out, "th1''"), a1, 1e-12);
        ok &= check_close(sim_accel_value(out, "th2''"), a2, 1e-12);
        free(out);
    }
    CHECK(ok, "double_pendulum: closed-form accelerations");
}

/* Solve A x = b (n x n) by Gaussian elimination with partial pivoting. */
static void
gauss(int n, double *A, double *b)
{
    for (int c = 0; c < n; c++) {
        int p = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(A[r * n + c]) > fabs(A[p * n + c]))
                p = r;
        for (int j = 0; j < n; j++) {
            double t = A[c * n + j];
            A[c * n + j] = A[p * n + j];
            A[p * n + j] = t;
        }
        double t = b[c];
        b[c] = b[p];
        b[p] = t;
        for (int r = c + 1; r < n; r++) {
            double f = A[r * n + c] / A[c * n + c];
            for (int j = c; j < n; j++)
                A[r * n + j] -= f * A[c * n + j];
            b[r] -= f * b[c];
        }
    }
    for (int r = n - 1; r >= 0; r--) {
        for (int j = r + 1; j < n; j++)
            b[r] -= A[r * n + j] * b[j];
        b[r] /= A[r * n + r];
    }
}

/* N-link chain, relative angles: r_k'' = sum_j A_kj q_j'' + c_k with
 * A_kj = dr_k/dq_j; sum_k m (r_k'' - g) . A_ki = 0. */
static void
chain_reference(int n, double m, double l, double g, const double *q,
                const double *qd, double *qdd)
{
    double phi[16], w[16], A[16][16][2], c[16][2], M[256], b[16];
    double s = 0, sd = 0;
    for (int a = 0; a < n; a++) {
        phi[a] = s += q[a];
        w[a] = sd += qd[a];
    }
    for (int k = 0; k < n; k++) {
        c[k][0] = c[k][1] = 0;
        for (int a = 0; a <= k; a++) {
            c[k][0] += -l * sin(phi[a]) * w[a] * w[a];
            c[k][1] += l * cos(phi[a]) * w[a] * w[a];
        }
        for (int j = 0; j < n; j++) {
            A[k][j][0] = A[k][j][1] = 0;
            for (int a = j; a <= k; a++) {
                A[k][j][0] += l * cos(phi[a]);
                A[k][j][1] += l * sin(phi[a]);
            }
        }
    }
    for (int i = 0; i < n; i++) {
        b[i] = 0;
        for (int k = 0; k < n; k++)
            b[i] -= m * (c[k][0] * A[k][i][0] + (c[k][1] + g) * A[k][i][1]);
        for (int j = 0; j < n; j++) {
            M[i * n + j] = 0;
            for (int k = 0; k < n; k++)
                M[i * n + j] += m * (A[k][i][0] * A[k][j][0] + A[k][i][1] * A[k][j][1]);
        }
    }
    gauss(n, M, b);
    for (int i = 0; i < n; i++)
        qdd[i] = b[i];
}

static void
chain5(void)
{
    int ok = 1;
    for (int k = 0; k < 20; k++) {
        double m = check_rand(0.5, 3), l = check_rand(0.5, 2), g = check_rand(1, 20);
        double q[5], qd[5], want[5];
        char args[2048];
        int len = snprintf(args, sizeof args, "--set m=%.17g --set l=%.17g --set g=%.17g", m, l, g);
        for (int i = 0; i < 5; i++) {
            q[i] = check_rand(-2, 2);
            qd[i] = check_rand(-2, 2);
            len += snprintf(args + len, sizeof args - (size_t)len,
                            " --init q%d=%.17g --init \"q%d'=%.17g\"", i + 1, q[i], i + 1, qd[i]);
        }
        chain_reference(5, m, l, g, q, qd, want);
        char *out = accel(4, args);
        for (int i = 0; i < 5; i++) {
            char name[16];
            snprintf(name, sizeof name, "q%d''", i + 1);
            double got = sim_accel_value(out, name);
            if (!check_close(got, want[i], 1e-9)) {
                printf("# chain5 %s: got %.17g want %.17g\n", name, got, want[i]);
                ok = 0;
            }
        }
        free(out);
    }
    CHECK(ok, "chain5: accelerations match Newton + d'Alembert on the particles");
}

int
main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: test_accel FALLING PENDULUM GEAR DOUBLE CHAIN5\n");
        return 2;
    }
    for (int i = 0; i < 5; i++)
        sim[i] = argv[i + 1];
    falling();
    pendulum();
    gear_link();
    double_pendulum();
    chain5();
    return check_done();
}

/*
 * A user's program may use any name outside eomc's: it defines its own
 * functions named as the runtime's internals of every module (linalg.c's
 * la_dot, sim.c's sim_zeros, numfmt.c's num_shortest, ...), and links with
 * libeomcrt.  Before the library hid its internals, each of these was a
 * second definition and the link failed.  Checked: each call reaches the
 * program's own function, and the library still computes the oscillator of
 * models.c, through the API and through eomc_main writing a CSV, to its
 * closed form (models.c's osc_exact).
 */
#include "../unit/check.h"
#include "rtest.h"

#include <unistd.h>

/* The program's own functions, with its own signatures: each returns a
 * different number. */
double la_dot(double a, double b);
double sim_zeros(void);
const char *num_shortest(void);
int num_put(int k);
int kkt_alloc(void);
int proj_alloc(void);
int dense_eval(void);
int ev_root(void);
int fixed_rk4(void);
int plot_trajectory(void);
int report_run(void);
int sweep_run(void);

double la_dot(double a, double b) { return a + b; }
double sim_zeros(void) { return 42.0; }
const char *num_shortest(void) { return "mine"; }
int num_put(int k) { return k + 1; }
int kkt_alloc(void) { return 3; }
int proj_alloc(void) { return 4; }
int dense_eval(void) { return 5; }
int ev_root(void) { return 6; }
int fixed_rk4(void) { return 7; }
int plot_trajectory(void) { return 8; }
int report_run(void) { return 9; }
int sweep_run(void) { return 10; }

/* The closing row of eomc_main's CSV (t, x, x', ...) at t_end. */
static int
last_row(const char *path, double *t, double *x, double *v)
{
    FILE *f = fopen(path, "r");
    char line[1024];
    int n = 0;
    while (f && fgets(line, sizeof line, f))
        n += sscanf(line, "%lf,%lf,%lf", t, x, v) == 3;
    if (f)
        fclose(f);
    return n;
}

int
main(void)
{
    CHECK(la_dot(1, 2) == 3 && sim_zeros() == 42 && !strcmp(num_shortest(), "mine") &&
              num_put(1) == 2 && kkt_alloc() == 3 && proj_alloc() == 4 &&
              dense_eval() == 5 && ev_root() == 6 && fixed_rk4() == 7 &&
              plot_trajectory() == 8 && report_run() == 9 && sweep_run() == 10,
          "the program's la_dot, sim_zeros, num_shortest, ... are its own");

    /* the API: integrate to t = 3 (rk8pd, the defaults) */
    eomc_sim *s = sim_new(&osc_model);
    eomc_run_opts o = opts_for(&osc_model, 3.0, 0.5, "rk8pd", 1e-12, 1e-12);
    Rows r;
    rows_init(&r, 1);
    double x[2];
    sim_x0(s, x);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, NULL);
    double xe, ve;
    osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, 3.0, &xe, &ve);
    CHECK(rc == EOMC_OK && r.n == 7 && fabs(x[0] - xe) < 1e-9 && fabs(x[1] - ve) < 1e-9,
          "eomc_sim_integrate: x(3) = %.12g, x'(3) = %.12g (closed form %.12g, %.12g)",
          x[0], x[1], xe, ve);
    rows_free(&r);
    eomc_sim_free(s);

    /* the command line: a CSV to a file */
    char path[] = "/tmp/eomc-namespace-XXXXXX";
    int fd = mkstemp(path);
    if (fd >= 0)
        close(fd);
    char *argv[] = {"osc", "--t-end", "2", "--dt", "0.5", "--rtol", "1e-12", "--atol",
                    "1e-12", "-o", path, NULL};
    rc = eomc_main(11, argv, &osc_model, NULL);
    double t = NAN, xc = NAN, vc = NAN;
    int rows = last_row(path, &t, &xc, &vc);
    osc_exact(OSC_M, OSC_K, OSC_X0, OSC_V0, 2.0, &xe, &ve);
    CHECK(rc == 0 && rows == 5 && t == 2.0 && fabs(xc - xe) < 1e-9 && fabs(vc - ve) < 1e-9,
          "eomc_main: %d rows, x(%g) = %.12g, x' = %.12g (closed form %.12g, %.12g)", rows, t,
          xc, vc, xe, ve);
    unlink(path);
    return check_done();
}

/*
 * eomc_main, the simulator's command line, on hand-written models built by
 * model_main.c, run through the shell as a user would:
 *  - --accel with --set / --init (both "--opt V" and "--opt=V"): x'' = -k/m x;
 *  - the CSV: header "t,x,x',T,V,E", rows at k dt and exactly t_end, on the
 *    closed form; --init "x'=2"; -o FILE; options spelled either way;
 *  - the driven oscillator's input: u(0) = 0, or held by --set u=0.7;
 *  - --help, --stats: exit 0; --version names the model and the runtime's
 *    version, which is meson's project version (PROJECT_VERSION);
 *  - usage errors exit 2 with a message naming the culprit, nothing on stdout;
 *  - numerical failure (M not positive definite at t = 1) exits 3, keeps the
 *    rows computed so far (all finite) and says "t = ..." on stderr.
 *
 *  - the drift warning: the leaky oscillator, which claims to conserve E
 *    while damped, drifts far beyond what its steps' error estimates
 *    allow and is warned about (with its drift: E(0) (1 - e^(-c t / m))
 *    to first order); the honest oscillator is not.
 *
 * usage: test_cli OSC_SIM DRIVEN_SIM NONPD_SIM NONPD_GSL_SIM LEAKY_SIM
 */
#include "../unit/check.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "csv_table.h"
#include "rtest.h"

static const char *osc_sim, *driven_sim, *nonpd_sim[2], *leaky_sim;
static char dir[] = "/tmp/eomc-rt-cli-XXXXXX";
static char out_path[64], err_path[64], csv_path[64];
static char *out, *err; /* the last run's stdout and stderr */

/* Run `EXE ARGS` (ARGS as the shell reads them); its exit status, with
 * stdout and stderr in out and err. */
static int
run(const char *exe, const char *args)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "'%s' %s >'%s' 2>'%s'", exe, args, out_path, err_path);
    int st = system(cmd);
    free(out);
    free(err);
    out = slurp(out_path);
    err = slurp(err_path);
    return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* s on one line for a TAP description: trailing space cut, newlines
 * turned into spaces. */
static const char *
one_line(char *s)
{
    size_t n = strlen(s);
    while (n && isspace((unsigned char)s[n - 1]))
        s[--n] = '\0';
    for (char *c = s; *c; c++)
        if (*c == '\n' || *c == '\r')
            *c = ' ';
    return s;
}

static double
at(const Table *t, int row, int col)
{
    return t->v[(size_t)row * (size_t)t->ncol + (size_t)col];
}

static void
accel(void)
{
    int st = run(osc_sim, "--accel");
    CHECK(st == 0 && accel_value(out, "x''") == -OSC_K / OSC_M * OSC_X0,
          "--accel at the defaults: x'' = -k/m x0 = -4 (exit %d)", st);
    int ok = 1;
    for (int i = 0; i < 5; i++) {
        double m = check_rand(0.1, 10), k = check_rand(0.1, 50), x = check_rand(-3, 3);
        char args[512];
        snprintf(args, sizeof args, "--accel --set m=%.17g --set k=%.17g --init x=%.17g", m, k,
                 x);
        ok &= run(osc_sim, args) == 0 && check_close(accel_value(out, "x''"), -k / m * x, 1e-13);
        snprintf(args, sizeof args, "--set=m=%.17g --set=k=%.17g --init=x=%.17g --accel", m, k,
                 x);
        ok &= run(osc_sim, args) == 0 && check_close(accel_value(out, "x''"), -k / m * x, 1e-13);
    }
    CHECK(ok, "--accel --set m=.. --set k=.. --init x=.. (and --set=..): x'' = -k/m x");
}

/* Rows at k dt and exactly t_end, x on the closed form from (x0, v0),
 * E = T + V; the columns are t,x,x',T,V,E. */
static int
on_closed_form(const Table *t, double dt, double t_end, double x0, double v0, double tol)
{
    int ok = t->ok && t->ncol == 6 && t->nrow >= 2;
    for (int r = 0; ok && r < t->nrow; r++) {
        double tt = at(t, r, 0), xe, ve;
        osc_exact(OSC_M, OSC_K, x0, v0, tt, &xe, &ve);
        ok &= fabs(tt - (r + 1 < t->nrow ? r * dt : t_end)) <= 1e-12;
        ok &= fabs(at(t, r, 1) - xe) < tol && fabs(at(t, r, 2) - ve) < tol;
        ok &= check_close(at(t, r, 3), 0.5 * OSC_M * at(t, r, 2) * at(t, r, 2), 1e-12) &&
              check_close(at(t, r, 4), 0.5 * OSC_K * at(t, r, 1) * at(t, r, 1), 1e-12) &&
              check_close(at(t, r, 5), at(t, r, 3) + at(t, r, 4), 1e-12);
    }
    return ok;
}

static void
csv(void)
{
    int st = run(osc_sim, "");
    Table t = parse_csv(out);
    CHECK(st == 0 && strcmp(t.header, "t,x,x',T,V,E") == 0,
          "CSV header is exactly t,x,x',T,V,E (got \"%s\")", t.header);
    CHECK(t.nrow == 101 && on_closed_form(&t, 0.1, 10.0, OSC_X0, OSC_V0, 1e-7),
          "the scene's defaults: 101 rows over [0, 10] on the closed form (got %d)", t.nrow);
    free(t.v);

    const char *spans[] = {"--t-end 1.05 --dt 0.1", "--t-end=1.05 --dt=0.1"};
    for (int i = 0; i < 2; i++) {
        st = run(osc_sim, spans[i]);
        t = parse_csv(out);
        CHECK(st == 0 && t.nrow == 12 && t.ncol == 6 && at(&t, 11, 0) == 1.05 &&
                  on_closed_form(&t, 0.1, 1.05, OSC_X0, OSC_V0, 1e-7),
              "%s: 12 rows, the last at t = 1.05, on the closed form (got %d)", spans[i],
              t.nrow);
        free(t.v);
    }

    st = run(osc_sim, "--init \"x'=2\" --init x=-0.5 --t-end 0.5 --dt 0.25");
    t = parse_csv(out);
    CHECK(st == 0 && t.nrow == 3 && at(&t, 0, 1) == -0.5 && at(&t, 0, 2) == 2.0 &&
              on_closed_form(&t, 0.25, 0.5, -0.5, 2.0, 1e-7),
          "--init \"x'=2\" --init x=-0.5: starts there, follows the closed form");
    free(t.v);
}

/* `args` and `args2` print the same CSV, on the closed form at rtol. */
static void
same_csv(const char *args, const char *args2, double tol)
{
    int st = run(osc_sim, args);
    char *first = out;
    out = NULL;
    int st2 = run(osc_sim, args2);
    Table t = parse_csv(out);
    CHECK(st == 0 && st2 == 0 && strcmp(first, out) == 0 &&
              on_closed_form(&t, 0.1, 2.0, OSC_X0, OSC_V0, tol),
          "\"%s\" = \"%s\", on the closed form to %g", args, args2, tol);
    free(t.v);
    free(first);
}

static void
options(void)
{
    same_csv("--method rk4 --fixed-step 0.01 --t-end 2",
             "--method=rk4 --fixed-step=0.01 --t-end=2", 1e-8);
    same_csv("--method msbdf --rtol 1e-11 --atol 1e-11 --t-end 2",
             "--method=msbdf --rtol=1e-11 --atol=1e-11 --t-end=2", 1e-7);
    char args[256];
    snprintf(args, sizeof args, "--t-end 2 -o '%s'", csv_path);
    int st = run(osc_sim, args);
    char *file = slurp(csv_path);
    int empty = out[0] == '\0';
    run(osc_sim, "--t-end 2");
    CHECK(st == 0 && empty && strcmp(file, out) == 0 && file[0],
          "-o FILE: the CSV goes to FILE, nothing to stdout");
    free(file);
    remove(csv_path);

    st = run(osc_sim, "--help");
    CHECK(st == 0 && (strstr(out, "--set") || strstr(err, "--set")),
          "--help exits 0 and describes --set (exit %d)", st);
    st = run(osc_sim, "--version");
    char want[512];
    const char *base = strrchr(osc_sim, '/');
    snprintf(want, sizeof want, "%s: model %s from %s, %s form; eomc runtime %s\n",
             base ? base + 1 : osc_sim, osc_model.name, osc_model.spec, osc_model.form,
             PROJECT_VERSION);
    CHECK(st == 0 && !strcmp(out, want) && !err[0],
          "--version: exit 0, the model and meson's project version %s (exit %d: %s)",
          PROJECT_VERSION, st, one_line(out));
    st = run(osc_sim, "--stats --t-end 1");
    Table t = parse_csv(out);
    CHECK(st == 0 && strstr(err, "steps") && t.nrow == 11,
          "--stats: exit 0, \"steps\" on stderr, the CSV on stdout");
    free(t.v);
}

/* The driven oscillator: its input u = A sin(w t) (0 at t = 0), or held
 * by --set u=...; the CSV has no input columns. */
static void
driven(void)
{
    int st = run(driven_sim, "--accel --init x=0.1");
    CHECK(st == 0 && check_close(accel_value(out, "x''"), -DRIVEN_K * 0.1 / DRIVEN_M, 1e-14),
          "driven --accel: u(0) = 0, x'' = -k x/m");
    st = run(driven_sim, "--accel --set u=0.7 --set c=0.3 --init x=0.1 --init \"x'=-1\"");
    CHECK(st == 0 && check_close(accel_value(out, "x''"),
                                 (0.7 - 0.3 * -1.0 - DRIVEN_K * 0.1) / DRIVEN_M, 1e-14),
          "driven --accel --set u=0.7 --set c=0.3: x'' = (u - c x' - k x)/m");
    st = run(driven_sim, "--set=u=0.7 --t-end 3 --dt 0.5 --rtol 1e-12 --atol 1e-12");
    Table t = parse_csv(out);
    double w0 = sqrt(DRIVEN_K / DRIVEN_M), ue = 0.7 / DRIVEN_K;
    double xe = ue + (DRIVEN_X0 - ue) * cos(w0 * 3) + DRIVEN_V0 / w0 * sin(w0 * 3);
    CHECK(st == 0 && t.ok && strcmp(t.header, "t,x,x',T,V,E") == 0 && t.nrow == 7 &&
              fabs(at(&t, 6, 1) - xe) < 1e-9,
          "driven --set=u=0.7: header t,x,x',T,V,E, x(3) on the closed form of a held input");
    free(t.v);
}

/* A usage error: exit 2, `names` on stderr, nothing on stdout. */
static void
usage_error(const char *args, const char *names)
{
    int st = run(osc_sim, args);
    CHECK(st == 2 && strstr(err, names) && out[0] == '\0',
          "%s: exit 2 (got %d), stderr names %s: \"%s\"", args, st, names, one_line(err));
}

static void
usage_errors(void)
{
    usage_error("--bogus", "--bogus");
    usage_error("--bogus=1", "--bogus");
    usage_error("stray", "stray");
    usage_error("--set nosuch=1", "nosuch");
    usage_error("--set=nosuch=1", "nosuch");
    usage_error("--init nosuch=1", "nosuch");
    usage_error("--init \"y'=1\"", "y'");
    usage_error("--set m", "--set");
    usage_error("--init x", "--init");
    usage_error("--atol=-1", "--atol");
    usage_error("--fixed-step -0.1", "--fixed-step");
    usage_error("--set m=abc", "abc");
    usage_error("--set k=1x", "1x");
    usage_error("--t-end abc", "--t-end");
    usage_error("--t-end=abc", "--t-end");
    usage_error("--dt 1x", "--dt");
    usage_error("--dt=", "--dt");
    usage_error("--rtol", "--rtol");
    usage_error("--method nosuch_method", "nosuch_method");
    usage_error("--method=nosuch_method", "nosuch_method");
    usage_error("--dt 0", "--dt");
    usage_error("--dt=-0.1", "--dt");
    usage_error("--t-end -1", "--t-end");
    usage_error("--rtol -1e-6", "--rtol");
    /* the end must come after the start, as the spec's t_end > 0 must */
    usage_error("--t-end 0", "--t-end 0 must be after the start time 0");
    usage_error("--t0 2 --t-end 1", "--t-end 1 must be after the start time 2 (--t0)");
    usage_error("--t0 abc", "--t0");
    /* one message, not two */
    usage_error("--max-steps 0", "'0' is not a whole number of steps (1 or more)");
    CHECK(!strstr(err, "out of range"), "--max-steps 0: one message only");
    usage_error("--init \"x''=1\"", "is an acceleration");
}

static void
numeric_failure(const char *sim)
{
    char args[256];
    snprintf(args, sizeof args, "--t-end 2 --dt=0.1 -o '%s'", csv_path);
    int st = run(sim, args);
    char *file = slurp(csv_path), *lower = strdup(file);
    for (char *c = lower; *c; c++)
        *c = (char)tolower((unsigned char)*c);
    Table t = parse_csv(file);
    CHECK(st == 3 && strstr(err, "t = ") && strstr(err, "zeta"),
          "%s: M not positive definite at t = 1: exit 3 (got %d), stderr: %s", sim, st,
          one_line(err));
    int ok = t.ok && t.nrow >= 10 && strcmp(t.header, "t,zeta,zeta',T,V,E") == 0 &&
             !strstr(lower, "nan") && !strstr(lower, "inf");
    for (int r = 0; ok && r < t.nrow; r++)
        ok &= at(&t, r, 0) < 1.0 && fabs(at(&t, r, 1) - at(&t, r, 0)) < 1e-9;
    CHECK(ok, "... the CSV keeps the %d rows before t = 1, all finite, zeta = t", t.nrow);
    free(t.v);
    free(lower);
    free(file);
    remove(csv_path);
}

static void
drift_warning(void)
{
    int st = run(leaky_sim, "-o /dev/null --stats");
    const char *d = strstr(err, "invariant_drift ");
    double drift = d ? atof(d + 16) : 0;
    /* E(0) = k x0^2 / 2 + m v0^2 / 2; the damper takes about the fraction
     * c t / m of it over t = 10 (average of e^(-c t / m) over the cycle) */
    double E0 = 0.5 * OSC_K * OSC_X0 * OSC_X0 + 0.5 * OSC_M * OSC_V0 * OSC_V0;
    double want = E0 * (1 - exp(-LEAKY_C * 10 / OSC_M));
    CHECK(st == 0 && strstr(err, "warning: the conserved quantity E drifted by") &&
          strstr(err, "what the steps' own error estimates allow") &&
          fabs(drift - want) <= 0.2 * want,
          "a model that claims E while damped: warned, drift %.3g (about %.3g), stderr: %s",
          drift, want, one_line(err));
    st = run(osc_sim, "-o /dev/null");
    CHECK(st == 0 && err[0] == '\0', "the honest oscillator: no warning (stderr: %s)",
          one_line(err));
}

int
main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: test_cli OSC_SIM DRIVEN_SIM NONPD_SIM NONPD_GSL_SIM "
                "LEAKY_SIM\n");
        return 1;
    }
    leaky_sim = argv[5];
    osc_sim = argv[1];
    driven_sim = argv[2];
    nonpd_sim[0] = argv[3];
    nonpd_sim[1] = argv[4];
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    snprintf(out_path, sizeof out_path, "%s/out", dir);
    snprintf(err_path, sizeof err_path, "%s/err", dir);
    snprintf(csv_path, sizeof csv_path, "%s/rows.csv", dir);
    accel();
    csv();
    options();
    driven();
    usage_errors();
    numeric_failure(nonpd_sim[0]);
    numeric_failure(nonpd_sim[1]);
    drift_warning();
    free(out);
    free(err);
    remove(out_path);
    remove(err_path);
    rmdir(dir);
    return check_done();
}

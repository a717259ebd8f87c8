/*
 * Issue 21 (A4): a conserved quantity that t cancels from only through an
 * identity.  A bead on a hoop turned about its vertical diameter
 * (specs/spinning_hoop.yaml: m = 0.1, R = 0.5, g = 9.81, rate w = 6):
 *  - eomc compile --explain finds Jacobi's h conserved, and says the
 *    numerical zero test decided;
 *  - along a 200 s run (rk8pd at 1e-12), h written out here from the
 *    CSV's columns, 1/2 m R^2 (th'^2 - w^2 sin^2 th) - m g R cos th, holds
 *    to 1e-11 of the largest kinetic energy, the CSV's h column is it, and
 *    --summary reports the drift this test measures;
 *  - the hoop turned at a rate w0 + a t (tests/sim/specs/forced_hoop.yaml):
 *    nothing is conserved, and the same closed form with w = w0 + a t
 *    does change along its run (dh/dt = -dL/dt = -m R^2 w a sin^2 th),
 *    so "nothing" is the truth.
 *
 * usage: test_hoop EOMC SIM_SPINNING_HOOP SIM_FORCED_HOOP SOURCE_ROOT
 */
#include "../unit/check.h"
#include "simrun.h"

#include <unistd.h>

static const double m = 0.1, R = 0.5, g = 9.81;

/* Jacobi's h for the hoop turning at rate w. */
static double
jacobi(double th, double v, double w)
{
    double s = sin(th);
    return 0.5 * m * R * R * (v * v - w * w * s * s) - m * g * R * cos(th);
}

static char *
slurp(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return strdup("");
    char *buf = calloc(1 << 16, 1);
    size_t n = fread(buf, 1, (1 << 16) - 1, f);
    buf[n] = '\0';
    fclose(f);
    for (char *p = buf; *p; p++) /* the summary wraps its lines */
        if (*p == '\n')
            *p = ' ';
    return buf;
}

static void
explain(const char *eomc, const char *spec, const char *conserved, const char *decided,
        const char *what)
{
    char cmd[2048];
    int st;
    snprintf(cmd, sizeof cmd, "'%s' compile '%s' --explain", eomc, spec);
    char *out = sim_capture(cmd, &st);
    CHECK(st == 0 && strstr(out, conserved) && strstr(out, decided),
          "%s: --explain says '%s' and '%s'", what, conserved, decided);
    if (!(st == 0 && strstr(out, conserved) && strstr(out, decided)))
        printf("# %s", out);
    free(out);
}

static void
spinning(const char *eomc, const char *sim, const char *root)
{
    char spec[1024], cmd[2048], errpath[] = "/tmp/eomc-hoop-XXXXXX";
    snprintf(spec, sizeof spec, "%s/specs/spinning_hoop.yaml", root);
    explain(eomc, spec, "h = q'.dT/dq' - T + V = T2 - T0 + V is conserved",
            "decided by the numerical zero test, not by structure: at 100 random states",
            "spinning hoop");
    int fd = mkstemp(errpath), st;
    close(fd);
    snprintf(cmd, sizeof cmd, "'%s' --summary 2> '%s'", sim, errpath);
    char *out = sim_capture(cmd, &st);
    SimTable t = sim_parse_csv(out);
    free(out);
    char *summary = slurp(errpath);
    unlink(errpath);
    int ct = sim_column(&t, "t"), cq = sim_column(&t, "th"), cv = sim_column(&t, "th'");
    int cT = sim_column(&t, "T"), ch = -1;
    for (int j = 0; j < t.ncol; j++)
        if (!strcmp(t.col[j], "h"))
            ch = j;
    double h0 = jacobi(sim_at(&t, 0, cq), sim_at(&t, 0, cv), 6.0);
    double drift = 0, column = 0, Tmax = 0;
    for (int r = 0; r < t.nrow; r++) {
        double h = jacobi(sim_at(&t, r, cq), sim_at(&t, r, cv), 6.0);
        drift = fmax(drift, fabs(h - h0));
        if (ch >= 0)
            column = fmax(column, fabs(sim_at(&t, r, ch) - h));
        Tmax = fmax(Tmax, sim_at(&t, r, cT));
    }
    CHECK(st == 0 && t.nrow == 2001 && sim_at(&t, t.nrow - 1, ct) == 200,
          "spinning hoop: ran to t = 200 (exit %d, %d rows)", st, t.nrow);
    CHECK(drift < 1e-11 * Tmax, "... h from the CSV's th, th' holds to %.2g, %.2g of the "
          "largest kinetic energy %.3g", drift, drift / Tmax, Tmax);
    CHECK(ch >= 0 && column < 1e-14 * Tmax, "... the CSV has a column h, and it is that h "
          "to %.2g", column);
    /* "The conserved quantity h started at X; its largest change was Y" */
    const char *p = strstr(summary, "The conserved quantity h started at ");
    double start = NAN, change = NAN;
    if (p && sscanf(p, "The conserved quantity h started at %lf; its largest change was %lf",
                    &start, &change) != 2)
        start = change = NAN;
    CHECK(fabs(start - h0) < 1e-9 * fabs(h0) && change >= 0.5 * drift && change <= 2 * drift,
          "... --summary: h started at %.10g (here %.10g) and changed by %.3g (here %.3g)",
          start, h0, change, drift);
    if (!p)
        printf("# %s\n", summary);
    free(summary);
    sim_table_free(&t);
}

static void
forced(const char *eomc, const char *sim, const char *root)
{
    const double w0 = 6.0, a = 0.05; /* tests/sim/specs/forced_hoop.yaml */
    char spec[1024], cmd[2048];
    snprintf(spec, sizeof spec, "%s/tests/sim/specs/forced_hoop.yaml", root);
    explain(eomc, spec, "nothing is conserved: T depends on t",
            "t: the numerical zero test decided: dT/dt is not 0", "hoop at a rate w0 + a t");
    int st;
    snprintf(cmd, sizeof cmd, "'%s' --summary 2>&1 >/dev/null", sim);
    char *summary = sim_capture(cmd, &st);
    for (char *q = summary; *q; q++)
        if (*q == '\n')
            *q = ' ';
    CHECK(st == 0 && strstr(summary, "No drift is reported: nothing is conserved: T depends "
                                     "on t"), "... --summary reports no drift, and says why");
    free(summary);
    snprintf(cmd, sizeof cmd, "'%s'", sim);
    char *out = sim_capture(cmd, &st);
    SimTable t = sim_parse_csv(out);
    free(out);
    int ct = sim_column(&t, "t"), cq = sim_column(&t, "th"), cv = sim_column(&t, "th'");
    int cT = sim_column(&t, "T");
    double h0 = jacobi(sim_at(&t, 0, cq), sim_at(&t, 0, cv), w0), change = 0, Tmax = 0;
    for (int r = 0; r < t.nrow; r++) {
        double w = w0 + a * sim_at(&t, r, ct);
        change = fmax(change, fabs(jacobi(sim_at(&t, r, cq), sim_at(&t, r, cv), w) - h0));
        Tmax = fmax(Tmax, sim_at(&t, r, cT));
    }
    CHECK(st == 0 && t.nrow > 100 && change > 0.1 * Tmax,
          "... and indeed h, with w = w0 + a t, changes by %.3g along the run, %.2g of the "
          "largest kinetic energy", change, change / Tmax);
    sim_table_free(&t);
}

int
main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: test_hoop EOMC SIM_SPINNING_HOOP SIM_FORCED_HOOP ROOT\n");
        return 2;
    }
    spinning(argv[1], argv[2], argv[4]);
    forced(argv[1], argv[3], argv[4]);
    return check_done();
}

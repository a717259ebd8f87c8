/*
 * The simulator's command line on models whose speeds are not their
 * coordinates' rates (freebody.c's free body and top, each with its
 * extended-precision twin), run through the shell as a user would:
 *  - the CSV's header: t, the coordinates, then the speeds by their own
 *    names (root_x' .. root_wz), then T, V, E; its rows on the closed form
 *    of the symmetric body, each quaternion of length 1;
 *  - --init takes the speeds' names (root_wx=...), refuses a speed's rate
 *    (root_wx') as an acceleration and an unknown name, listing the
 *    speeds; a quaternion set off length 1 is divided by its length, with
 *    a warning; one of length 0 is refused;
 *  - --accel names each speed's rate by one more quote (root_z'', root_wx')
 *    with Euler's and gravity's values;
 *  - --error: the error it reports against the reference is the closed
 *    form's true error of the rows, to the reference's own estimate;
 *  - --stats and --summary say how far the quaternion drifted; fixed steps
 *    that move its length by more than 1e-2 in a step are warned about;
 *  - --method taylor: exit 2 naming why (the hand-written model has no
 *    series); --linearize by the rotations' names (root_rx); --equilibrium
 *    of a free body: exit 3, none;
 *  - the top: --assemble puts a start off its constraints onto them; --hold
 *    of a quaternion's coordinate alone is refused (exit 2).
 *
 * usage: test_speeds_cli FREEBODY_SIM TOP_SIM
 */
#include "../unit/check.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "csv_table.h"
#include "rtest.h"

enum { NQ = 7, NV = 6, NX = NQ + NV };

static const char *freebody_sim, *top_sim;
static char dir[] = "/tmp/eomc-rt-speeds-XXXXXX";
static char out_path[64], err_path[64], csv_path[64];
static char *out, *err; /* the last run's stdout and stderr */

/* Run `EXE ARGS`: its exit status, with stdout and stderr in out and err. */
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

/* s on one line for a TAP description: a copy (the last two kept), its
 * newlines turned into spaces. */
static const char *
one_line(const char *s)
{
    static char buf[2][4096];
    static int k;
    char *b = buf[k ^= 1];
    snprintf(b, sizeof buf[0], "%s", s);
    for (char *c = b; *c; c++)
        *c = *c == '\n' || *c == '\r' ? ' ' : *c;
    return b;
}

static const double *
row(const Table *t, int i)
{
    return t->v + (size_t)i * (size_t)t->ncol;
}

/* The largest | |e| - 1 | over the rows (columns 4 .. 7 after t). */
static double
unit_error(const Table *t)
{
    double worst = 0;
    for (int i = 0; i < t->nrow; i++) {
        const double *e = row(t, i) + 4;
        worst = fmax(worst, fabs(sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]) - 1));
    }
    return worst;
}

/* The rows' largest error against the symmetric body's closed form
 * (parameters p) from their first row. */
static double
exact_error(const Table *t, const double *p)
{
    double worst = 0, ex[NX];
    const double *x0 = row(t, 0) + 1;
    for (int i = 0; i < t->nrow; i++) {
        freebody_exact(p, x0, x0 + NQ, row(t, i)[0], ex, ex + NQ);
        for (int j = 0; j < NX; j++)
            worst = fmax(worst, fabs(row(t, i)[1 + j] - ex[j]));
    }
    return worst;
}

static const double symmetric[5] = {FREEBODY_M, FREEBODY_I1, FREEBODY_I1, FREEBODY_I3,
                                    FREEBODY_G};

static void
header_and_rows(void)
{
    int st = run(freebody_sim, "--set I2=1");
    Table t = parse_csv(out);
    const char *want = "t,root_x,root_y,root_z,root_e0,root_e1,root_e2,root_e3,root_x',"
                       "root_y',root_z',root_wx,root_wy,root_wz,T,V,E";
    CHECK(st == 0 && !strcmp(t.header, want), "the CSV's header: the coordinates, then the "
          "speeds by their names (%s)", t.header);
    double e = exact_error(&t, symmetric), unit = unit_error(&t);
    CHECK(t.ok && t.nrow == 41 && e < 1e-8 && unit <= 8 * DBL_EPSILON,
          "41 rows on the symmetric body's closed form (%.2g), each quaternion of length 1 "
          "(%.2g)", e, unit);
    free(t.v);
}

static void
init_names(void)
{
    int st = run(freebody_sim, "--init root_wx=1.5 --init \"root_x'=0.25\" --t-end 0.1");
    Table t = parse_csv(out);
    CHECK(st == 0 && t.nrow > 0 && row(&t, 0)[1 + NQ + 3] == 1.5 && row(&t, 0)[1 + NQ] == 0.25,
          "--init root_wx=1.5 --init root_x'=0.25: the first row has them (exit %d)", st);
    free(t.v);
    st = run(freebody_sim, "--init \"root_wx'=1\"");
    CHECK(st == 2 && strstr(err, "'root_wx'' is an acceleration") && !*out,
          "--init root_wx'=1: exit 2, an acceleration (%s)", one_line(err));
    st = run(freebody_sim, "--init root_w=1");
    CHECK(st == 2 && strstr(err, "not a coordinate or speed") && strstr(err, "root_wz") &&
              strstr(err, "root_e3") && !*out,
          "--init root_w=1: exit 2, naming the coordinates and speeds (%s)", one_line(err));
    st = run(freebody_sim, "--init root_e0=2 --init root_e1=0 --init root_e2=0 "
                           "--init root_e3=0 --t-end 0.1");
    t = parse_csv(out);
    CHECK(st == 0 && strstr(err, "warning: the unit quaternion (root_e0, root_e1, root_e2, "
                                 "root_e3) of the initial state has length 2") &&
              t.nrow > 0 && row(&t, 0)[4] == 1 && unit_error(&t) <= 8 * DBL_EPSILON,
          "a quaternion of length 2: divided by it, with a warning (%s)", one_line(err));
    free(t.v);
    st = run(freebody_sim, "--init root_e0=0 --init root_e1=0 --init root_e2=0 "
                           "--init root_e3=0");
    CHECK(st == 2 && strstr(err, "length 0: it is no rotation") && !*out,
          "a quaternion of length 0: exit 2 (%s)", one_line(err));
}

static void
accel(void)
{
    int st = run(freebody_sim, "--accel --init root_wx=0.5 --init root_wy=-1 --init root_wz=2");
    double w[3] = {0.5, -1, 2}, In[3] = {FREEBODY_I1, FREEBODY_I2, FREEBODY_I3};
    double want[3] = {-(In[2] - In[1]) * w[1] * w[2] / In[0],
                      -(In[0] - In[2]) * w[0] * w[2] / In[1],
                      -(In[1] - In[0]) * w[0] * w[1] / In[2]};
    CHECK(st == 0 && accel_value(out, "root_x''") == 0 && accel_value(out, "root_z''") == -FREEBODY_G &&
              accel_value(out, "root_wx'") == want[0] && accel_value(out, "root_wy'") == want[1] &&
              accel_value(out, "root_wz'") == want[2] && isnan(accel_value(out, "root_wz''")),
          "--accel: root_z'' = -g and root_wx', root_wy', root_wz' Euler's (%s)", one_line(out));
}

static void
error_against_closed_form(void)
{
    char args[512];
    snprintf(args, sizeof args, "--set I2=1 --error --stats --rtol 1e-8 --atol 1e-8 -o '%s'",
             csv_path);
    int st = run(freebody_sim, args);
    char *csv = slurp(csv_path);
    Table t = parse_csv(csv);
    double said = accel_value(err, "error_max"), ref = accel_value(err, "reference_error");
    double truth = exact_error(&t, symmetric);
    CHECK(st == 0 && t.nrow == 41 && said > 0 && ref < 1e-13 && fabs(said - truth) <= ref,
          "--error: the error it reports (%.6g) is the closed form's (%.6g) to the "
          "reference's own estimate (%.2g)", said, truth, ref);
    double drift = accel_value(err, "quat_drift"), ratio = accel_value(err, "quat_ratio");
    CHECK(drift > 0 && drift < 1e-6 && ratio >= 0 && ratio < 1,
          "--stats: quat_drift %.2g (the quaternion's length before renormalizing), "
          "quat_ratio %.2g (against the steps' error estimates)", drift, ratio);
    free(csv);
    free(t.v);
    st = run(freebody_sim, "--summary -o /dev/null");
    for (char *c = err; *c; c++) /* the paragraph is wrapped */
        *c = *c == '\n' ? ' ' : *c;
    CHECK(st == 0 && strstr(err, "and 6 speeds (root_x', root_y', root_z', root_wx") &&
              strstr(err, "The unit quaternion was renormalized after every step"),
          "--summary names the speeds and the renormalization");
}

/* Fixed steps too long for the turn: the quaternion's drift in a step
 * (0.012 here) said, as fewer than two digits right, which the reference
 * confirms (the rows off by 0.8); none at 0.01, where they are good to 1e-5. */
static void
fixed_step_drift(void)
{
    int st = run(freebody_sim, "--fixed-step 0.4 --method rk4 --t-end 3 --init root_wz=6 "
                               "--error --stats -o /dev/null");
    double drift = accel_value(err, "quat_drift"), e = accel_value(err, "error_max");
    CHECK(st == 0 && drift > 1e-2 && e > 0.1 &&
              strstr(err, "warning: fixed steps of 0.375: the unit quaternion (root_e0, "
                          "root_e1, root_e2, root_e3) moved off length 1"),
          "rk4 in fixed steps of 0.375: warned (quat_drift %.3g; the rows off by %.3g)", drift,
          e);
    st = run(freebody_sim, "--fixed-step 0.01 --method rk4 --t-end 3 --init root_wz=6 "
                           "--error --stats -o /dev/null");
    e = accel_value(err, "error_max");
    CHECK(st == 0 && !strstr(err, "warning") && e < 1e-5,
          "... in steps of 0.01: no warning (the rows off by %.2g)", e);
}

static void
refusals(void)
{
    int st = run(freebody_sim, "--method taylor");
    CHECK(st == 2 && strstr(err, "has no Taylor series: a hand-written model without series") &&
          !*out, "--method taylor: exit 2 (%s)", one_line(err));
    /* the linearization in the tangent space: the rotations by name */
    st = run(freebody_sim, "--linearize --set g=0 --init root_wx=0 --init root_wy=0 --init root_wz=0.5");
    CHECK(st == 0 && strstr(out, "root_rx") && strstr(out, "root_wz") && !*err,
          "--linearize: exit 0, A by the rotations' names (root_rx ...) and the speeds'");
    st = run(freebody_sim, "--equilibrium");
    CHECK(st == 3 && strstr(err, "no equilibrium") && !*out,
          "--equilibrium of a free body: exit 3 (%s)", one_line(err));
}

static void
top(void)
{
    /* a spin about the axis moves no tip: the velocities are off the
     * constraints only through root_x' */
    int st = run(top_sim, "--init \"root_x'=1\" --t-end 0.2");
    CHECK(st == 0 && strstr(err, "warning: the initial state is off the constraint"),
          "top --init root_x'=1: off its constraints, warned (%s)", one_line(err));
    st = run(top_sim, "--init \"root_x'=1\" --assemble --t-end 0.2");
    Table t = parse_csv(out);
    double res = 0;
    for (int i = 0; i < t.nrow; i++)
        for (int c = t.ncol - 3; c < t.ncol; c++)
            res = fmax(res, fabs(row(&t, i)[c]));
    CHECK(st == 0 && strstr(err, "moved the initial state onto the constraints") &&
              strstr(err, "root_x'") && !strstr(t.header, "root_x'',") && t.nrow == 5 &&
              res < 1e-8 && unit_error(&t) <= 8 * DBL_EPSILON,
          "top --assemble: onto the constraints, res[...] %.2g in the rows", res);
    free(t.v);
    st = run(top_sim, "--assemble --hold root_e0");
    CHECK(st == 2 && strstr(err, "root_e0") && strstr(err, "four together") && !*out,
          "top --assemble --hold root_e0: exit 2 (%s)", one_line(err));
}

int
main(int argc, char **argv)
{
    if (argc != 3) {
        printf("Bail out! usage: %s FREEBODY_SIM TOP_SIM\n", argv[0]);
        return 1;
    }
    freebody_sim = argv[1], top_sim = argv[2];
    if (!mkdtemp(dir)) {
        printf("Bail out! cannot make a temporary directory\n");
        return 1;
    }
    snprintf(out_path, sizeof out_path, "%s/out", dir);
    snprintf(err_path, sizeof err_path, "%s/err", dir);
    snprintf(csv_path, sizeof csv_path, "%s/rows.csv", dir);
    header_and_rows();
    init_names();
    accel();
    error_against_closed_form();
    fixed_step_drift();
    refusals();
    top();
    unlink(out_path);
    unlink(err_path);
    unlink(csv_path);
    rmdir(dir);
    free(out);
    free(err);
    return check_done();
}

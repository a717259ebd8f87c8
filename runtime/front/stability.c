/*
 * stability: the linearization and its eigenvalues, printed (stability.h).
 */
#include "stability.h"
#include "assembly.h"
#include "base/io.h"
#include "base/numfmt.h"
#include "model/state.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The name of component k of the linearization's state: a coordinate
 * "theta", a speed "theta'" or "root_wx", a rotation "root_rx". */
static void
lin_name(eomc_sim *sim, int k, char *buf, size_t len)
{
    const eomc_model *m = eomc_sim_model(sim);
    int coord, order;
    eomc_sim_linear_state(sim, k, &coord, &order);
    if (order == 0)
        snprintf(buf, len, "%s", m->q_names[coord]);
    else if (order == 1)
        state_speed(m, coord, buf, len);
    else
        state_rotation_name(m, coord, buf, len);
}

/* A labelled matrix [rows x cols] for people. */
static void
print_matrix(eomc_sim *sim, const char *title, const double *X, int rows, int cols,
             int inputs)
{
    const eomc_model *m = eomc_sim_model(sim);
    char name[160];
    int w = 12;
    for (int k = 0; k < rows; k++) {
        lin_name(sim, k, name, sizeof name);
        w = (int)strlen(name) + 2 > w ? (int)strlen(name) + 2 : w;
    }
    for (int k = 0; k < m->nu && inputs; k++)
        w = (int)strlen(m->u_names[k]) + 2 > w ? (int)strlen(m->u_names[k]) + 2 : w;
    fprintf(io_out(), "%s\n%*s", title, w, "");
    for (int c = 0; c < cols; c++) {
        if (inputs)
            snprintf(name, sizeof name, "%s", m->u_names[c]);
        else
            lin_name(sim, c, name, sizeof name);
        fprintf(io_out(), "%*s", w, name);
    }
    fprintf(io_out(), "\n");
    for (int r = 0; r < rows; r++) {
        lin_name(sim, r, name, sizeof name);
        fprintf(io_out(), "%*s", w, name);
        for (int c = 0; c < cols; c++)
            fprintf(io_out(),
                    " %*.6g", w - 1, X[r * cols + c]); /* a space even at full width */
        fprintf(io_out(), "\n");
    }
}

/* The stability verdict takes a real part within this of the largest
 * modulus for 0 (a conservative system's centre computes as real parts of
 * rounding; a defective eigenvalue, as rounding's square root). */
#define EIG_ZERO_REL 1e-9

/* Largest real part first, the same order everywhere (the printed list,
 * --csv's eig rows, a sweep's re1, im1, ...); of equal real parts (a
 * conjugate pair) the positive imaginary part first. */
static int
cmp_eig(const void *a, const void *b)
{
    const double *x = a, *y = b;
    return x[0] != y[0] ? (x[0] > y[0] ? -1 : 1) : x[1] > y[1] ? -1 : x[1] < y[1];
}

/* A's eigenvalues into pair [2 nl] (re, im), sorted; EOMC_OK or a status
 * with the simulator's message. */
static int
sorted_eigen(eomc_sim *sim, const double *A, int nl, double *pair)
{
    double *re = calloc((size_t)nl + 1, sizeof *re), *im = calloc((size_t)nl + 1, sizeof *im);
    int rc = re && im ? eomc_sim_eigenvalues(sim, A, nl, re, im) : EOMC_EUSAGE;
    for (int k = 0; k < nl && rc == EOMC_OK; k++)
        pair[2 * k] = re[k], pair[2 * k + 1] = im[k];
    if (rc == EOMC_OK)
        qsort(pair, (size_t)nl, 2 * sizeof *pair, cmp_eig);
    free(re);
    free(im);
    return rc;
}

/* What the eigenvalues say of an equilibrium's stability, and how the
 * verdict rounds. */
static void
print_verdict(const double *pair, int nl)
{
    double big = 0, worst = nl ? pair[0] : 0; /* sorted: the largest real part first */
    for (int k = 0; k < nl; k++)
        big = fmax(big, hypot(pair[2 * k], pair[2 * k + 1]));
    char num[NUM_MAX];
    num_shortest(num, worst);
    if (worst > EIG_ZERO_REL * big)
        fprintf(io_out(),
                "unstable: the largest real part, %s, is more than %g of the largest modulus "
                "(%.6g)\n", num, EIG_ZERO_REL, big);
    else if (worst < -EIG_ZERO_REL * big)
        fprintf(io_out(),
                "asymptotically stable: every real part is below -%g of the largest modulus "
                "(%.6g); the largest is %s\n", EIG_ZERO_REL, big, num);
    else
        fprintf(io_out(),
                "stable to first order only: the largest real part, %s, is within %g of the "
                "largest modulus (%.6g) of 0, which this verdict counts as 0 (the rounding "
                "of a centre, or of a defective eigenvalue, reaches that far); on the "
                "imaginary axis the linearization cannot decide\n", num, EIG_ZERO_REL, big);
}

/* The eigenvalues, as computed (the shortest text that reads back as the
 * computed double: nothing rounded away), and for an equilibrium what
 * they say of stability. */
static int
print_eigen(Options *c, eomc_sim *sim, const double *A, int nl, int verdict, double *pair)
{
    int rc = sorted_eigen(sim, A, nl, pair);
    if (rc != EOMC_OK) {
        fprintf(io_err(), "%s: error: %s\n", c->prog, eomc_sim_error(sim));
        return rc;
    }
    char re[NUM_MAX], im[NUM_MAX];
    fprintf(io_out(), "eigenvalues of A (the largest real part first):\n");
    for (int k = 0; k < nl; k++)
        fprintf(io_out(),
                "  %s %c %si\n", num_shortest(re, pair[2 * k]), pair[2 * k + 1] < 0 ? '-' : '+',
                num_shortest(im, fabs(pair[2 * k + 1])));
    if (verdict)
        print_verdict(pair, nl);
    return rc;
}

/* --csv FILE: matrix,row,column,value, one row per entry of A and B, then
 * two per eigenvalue k (1, 2, ... in the printed order): eig,k,re,VALUE
 * and eig,k,im,VALUE. */
static int
write_linear_csv(Options *c, eomc_sim *sim, const double *A, const double *B, int nl,
                 const double *eig)
{
    const eomc_model *m = eomc_sim_model(sim);
    FILE *f = fopen(c->csv, "w");
    if (!f) {
        fprintf(io_err(), "%s: --csv: cannot write '%s': %s\n", c->prog, c->csv,
                strerror(errno));
        return EOMC_EUSAGE;
    }
    char row[160], col[160], num[NUM_MAX];
    fprintf(f, "matrix,row,column,value\n");
    for (int r = 0; r < nl; r++) {
        lin_name(sim, r, row, sizeof row);
        for (int k = 0; k < nl; k++) {
            lin_name(sim, k, col, sizeof col);
            fprintf(f, "A,%s,%s,%s\n", row, col, num_shortest(num, A[r * nl + k]));
        }
    }
    for (int r = 0; r < nl; r++) {
        lin_name(sim, r, row, sizeof row);
        for (int k = 0; k < m->nu; k++)
            fprintf(f, "B,%s,%s,%s\n", row, m->u_names[k], num_shortest(num, B[r * m->nu + k]));
    }
    for (int k = 0; k < nl; k++) {
        fprintf(f, "eig,%d,re,%s\n", k + 1, num_shortest(num, eig[2 * k]));
        fprintf(f, "eig,%d,im,%s\n", k + 1, num_shortest(num, eig[2 * k + 1]));
    }
    if (fclose(f) != 0) {
        fprintf(io_err(), "%s: error writing %s\n", c->prog, c->csv);
        return EOMC_EUSAGE;
    }
    return EOMC_OK;
}

/* The whole turns of q beyond (-pi, pi], and into *w the value there.  In
 * long double, so that 2 pi's rounding, times the turns, stays below the
 * value's own. */
static long
turns(double q, double *w)
{
    const long double two_pi = 6.283185307179586476925286766559L;
    long double r = remainderl((long double)q, two_pi); /* in [-pi, pi] */
    if (r <= -two_pi / 2)
        r += two_pi;
    *w = (double)r;
    return lroundl(((long double)q - r) / two_pi);
}

/* After an equilibrium's coordinates, those beyond (-pi, pi] as angles
 * would read them ("1.5707963267948966 + 2 pi"): nothing tells eomc which
 * coordinates are angles, so it leaves them as they are. */
static void
print_turns(Options *c, const eomc_model *m, const double *x)
{
    int said = 0;
    char num[NUM_MAX];
    for (int i = 0; i < m->nq; i++) {
        double w;
        long k = turns(x[i], &w);
        if (k == 0)
            continue;
        if (!said++)
            fprintf(io_out(), "%s: the coordinates are as Newton's method left them, not "
                    "wrapped (eomc cannot tell an angle from a length); as angles,", c->prog);
        fprintf(io_out(), "%s %s = %s %c %ld pi", said > 1 ? "," : "", m->q_names[i],
                num_shortest(num, w), k < 0 ? '-' : '+', 2 * labs(k));
    }
    if (said)
        fprintf(io_out(), "\n");
}

/* --linearize at a state where q'' is not 0: say so, and what A and B
 * then are.  q'' counts as 0 within EOMC_ACCEL_ZERO of what the state's
 * own values would change it by (eomc_sim_accel_residual), so an
 * equilibrium, or a steady motion (a bicycle running upright), passes. */
static void
rest_note(Options *c, eomc_sim *sim, double t, const double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    double *acc = calloc((size_t)eomc_nv(m), sizeof *acc);
    int worst;
    double r = acc ? eomc_sim_accel_residual(sim, t, x, acc, &worst) : NAN;
    char num[NUM_MAX], name[STATE_NAME_MAX];
    if (r > EOMC_ACCEL_ZERO)
        fprintf(io_err(), "%s: warning: t = %g: q'' is not 0 here (%s = %s): the state is "
                "no equilibrium and no steady motion, so A and B describe the motion through "
                "it only near it and for a short time (z' = z0' + A (z - z0) + B (u - u0), "
                "z0' not 0), and A's eigenvalues say how nearby motions part from it at "
                "first, not whether anything is stable\n", c->prog, t,
                state_rate(m, worst, name, sizeof name),
                num_shortest(num, acc[worst]));
    free(acc);
}

/* --linearize or --equilibrium at a state on a kink of a switched
 * expression: A and B there are one side's (the modes of the state: a
 * switch function at 0 takes the side where it is negative), and the
 * other side's differ.  Said, not refused: a state on a stop's edge is a
 * fair question, and the answer for one side is exact.  An equilibrium is
 * known to the scale of its start (start [nx], else NULL). */
static void
kink_note(Options *c, eomc_sim *sim, double t, const double *x, const double *start)
{
    const eomc_model *m = eomc_sim_model(sim);
    unsigned char *on = calloc((size_t)m->nmode + 1, 1);
    int n = on ? eomc_sim_kinks(sim, t, x, start, on) : 0;
    if (n > 0) {
        fprintf(io_err(), "%s: warning: t = %g: the state is on the kink%s of", c->prog, t,
                n == 1 ? "" : "s");
        for (int k = 0, said = 0; k < m->nmode; k++)
            if (on[k])
                fprintf(io_err(), "%s %s", !said++ ? "" : said == n ? " and" : ",",
                        m->sw_names[k]);
        fprintf(io_err(), " (%s 0 to rounding here): A and B are those of the side where "
                "%s negative, and the other side's differ, so they describe the motion only "
                "while it stays on that side\n", n == 1 ? "its switch function is"
                : "their switch functions are", n == 1 ? "it is" : "each is");
    }
    free(on);
}

/* The first speed that turns a unit quaternion (model->nquat > 0). */
static int
first_rotation(const eomc_model *m)
{
    int *slot = malloc((size_t)m->nv * sizeof *slot), k = 0;
    if (slot && state_tangent(m, slot) == 0)
        while (k < m->nv - 1 && slot[k] >= 0)
            k++;
    free(slot);
    return k;
}

/* --linearize and --equilibrium. */
int
stab_print(Options *c, eomc_sim *sim, double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq, nl = eomc_sim_linear_size(sim), nu = m->nu, rc = EOMC_OK, its = 0;
    double t = c->run.t0;
    double *A = calloc((size_t)nl * (size_t)nl, sizeof *A);
    double *B = calloc((size_t)nl * (size_t)(nu ? nu : 1), sizeof *B);
    double *eig = calloc(2 * (size_t)nl + 1, sizeof *eig);
    double *start = malloc((size_t)eomc_nx(m) * sizeof *start);
    if (!A || !B || !eig || !start)
        rc = EOMC_EUSAGE;
    else
        memcpy(start, x, (size_t)eomc_nx(m) * sizeof *start);
    if (rc == EOMC_OK && c->equilibrium) {
        rc = eomc_sim_equilibrium(sim, t, x, &its);
        char num[NUM_MAX];
        if (rc == EOMC_OK) {
            fprintf(io_out(), "%s: an equilibrium, found by %d Newton step%s:\n", c->prog, its,
                    its == 1 ? "" : "s");
            for (int i = 0; i < n; i++)
                fprintf(io_out(), "  %s = %s\n", m->q_names[i], num_shortest(num, x[i]));
            print_turns(c, m, x);
        }
    }
    if (rc == EOMC_OK)
        rc = eomc_sim_linearize(sim, t, x, A, B);
    if (rc == EOMC_OK && !c->equilibrium)
        rest_note(c, sim, t, x);
    if (rc == EOMC_OK)
        kink_note(c, sim, t, x, c->equilibrium ? start : NULL);
    if (rc == EOMC_OK) {
        char name[STATE_NAME_MAX];
        fprintf(io_out(), "%s: linearized at t = %g,", c->prog, t);
        for (int i = 0; i < eomc_nx(m); i++)
            fprintf(io_out(), "%s %s = %.6g", i ? "," : "", state_name(m, i, name, sizeof name),
                    x[i]);
        fprintf(io_out(), "\n");
        if (m->nquat > 0)
            fprintf(io_out(), "in the tangent space: each unit quaternion's small rotation "
                    "in its body's axes (%s, ...) in place of its four parameters\n",
                    state_rotation_name(m, first_rotation(m), name, sizeof name));
        if (m->nc > 0)
            fprintf(io_out(),
                    "in the independent coordinates of the elimination (%d of %d)\n", nl,
                    2 * eomc_nv(m));
        print_matrix(sim, "A = dz'/dz:", A, nl, nl, 0);
        if (nu)
            print_matrix(sim, "B = dz'/du:", B, nl, nu, 1);
        else
            fprintf(io_out(), "B = dz'/du: the model has no inputs\n");
        rc = print_eigen(c, sim, A, nl, c->equilibrium, eig);
    } else if (rc != EOMC_EUSAGE || eomc_sim_error(sim)[0]) {
        fprintf(io_err(), "%s: error: %s\n", c->prog, eomc_sim_error(sim));
        int worst, level;
        if (rc == EOMC_ENUMERIC && !c->equilibrium &&
            eomc_sim_inconsistency(sim, t, x, x + n, &worst, &level) > EOMC_INCONSISTENT)
            assembly_suggest(c, sim, x);
    }
    if (rc == EOMC_OK && c->csv)
        rc = write_linear_csv(c, sim, A, B, nl, eig);
    free(A);
    free(B);
    free(eig);
    free(start);
    return rc;
}

/* A sweep of --linearize: each run's eigenvalues, the largest real part
 * first, as ",re1,im1,re2,im2,...". */
int
stab_cells(void *ctx, eomc_sim *sim, double *x, char **text)
{
    Options *c = ctx;
    int nl = eomc_sim_linear_size(sim), nu = eomc_sim_model(sim)->nu;
    double *A = calloc((size_t)nl * (size_t)nl + 1, sizeof *A);
    double *B = calloc((size_t)nl * (size_t)nu + 1, sizeof *B);
    double *eig = calloc(2 * (size_t)nl + 1, sizeof *eig);
    char *cells = calloc(2 * (size_t)nl * (NUM_MAX + 1) + 1, 1), num[NUM_MAX];
    int rc = A && B && eig && cells ? eomc_sim_linearize(sim, c->run.t0, x, A, B) : EOMC_EUSAGE;
    if (rc == EOMC_OK)
        rc = sorted_eigen(sim, A, nl, eig);
    for (int k = 0, at = 0; rc == EOMC_OK && k < 2 * nl; k++)
        at += sprintf(cells + at, ",%s", num_shortest(num, eig[k]));
    free(A);
    free(B);
    free(eig);
    if (rc != EOMC_OK) {
        free(cells);
        cells = NULL;
    }
    *text = cells;
    return rc;
}

/* "re1,im1,re2,im2,...": the columns of stab_cells. */
char *
stab_columns(int nl)
{
    char *cols = calloc((size_t)nl * 24 + 1, 1);
    for (int k = 0, at = 0; cols && k < nl; k++)
        at += sprintf(cols + at, "%sre%d,im%d", k ? "," : "", k + 1, k + 1);
    return cols;
}


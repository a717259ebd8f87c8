/*
 * linearize: a model's linearization and its equilibria (eomc.h).
 *
 * A = dx'/dx and B = dx'/du come from the generated residual Jacobians,
 * exactly: the simulator's own Jacobian (eomc_sim_jacobian) for A, and
 * for B the accelerations' response to the inputs, -M^-1 dE/du, or for a
 * constrained model the KKT system's (its time column with a unit input
 * rate: the column is linear in the rates).
 *
 * A constrained model's state moves on the constraints' manifold, so its
 * linearization is given in the independent coordinates of the
 * elimination: a holonomic constraint removes its dependent coordinate and
 * velocity, a first-order one its dependent velocity.  The full
 * perturbation follows from the reduced one through the linearized
 * constraints (T below), and the reduced rows are read off A T.
 */
#include "model/simimpl.h"
#include "model/kkt.h"
#include "model/linalg.h"
#include "model/state.h"
#include "base/numfmt.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

/* Whether component j of x = (q, q') is determined by the constraints:
 * the dependent coordinate and velocity of a holonomic constraint, the
 * dependent velocity of a first-order one. */
static int
dependent(const eomc_model *m, int j)
{
    int n = m->nq, i = j % n, vel = j >= n;
    for (int k = 0; k < m->nc; k++)
        if (m->c_dependent[k] == i && (m->c_order[k] == 0 || (m->c_order[k] == 1 && vel)))
            return 1;
    return 0;
}

/* A model whose speeds are not its coordinates' rates has no
 * linearization here (eomc.h): EOMC_EUSAGE naming what it would need. */
static int
no_speeds(eomc_sim *s, const char *what)
{
    const eomc_model *m = eomc_sim_model(s);
    return sim_usage_error(s, "%s of %s is not available: its speeds are not its "
                           "coordinates' rates (%s, ...: a free or ball joint's angular "
                           "velocity, whose coordinates are a unit quaternion), and the "
                           "runtime linearizes only where the state is a vector space, "
                           "not in each quaternion's tangent space", what, m->name,
                           state_own_speed(m));
}

int
eomc_sim_linear_size(const eomc_sim *s)
{
    const eomc_model *m = eomc_sim_model(s);
    int N = 2 * m->nq, size = 0;
    if (m->nv > 0) /* refused by every function below: the whole state */
        return eomc_nx(m);
    for (int j = 0; j < N; j++)
        size += !dependent(m, j);
    return size;
}

void
eomc_sim_linear_state(const eomc_sim *s, int k, int *coord, int *order)
{
    const eomc_model *m = eomc_sim_model(s);
    int N = 2 * m->nq;
    if (m->nv > 0) { /* the whole state, as eomc_sim_linear_size */
        *coord = k < m->nq ? k : k - m->nq;
        *order = k >= m->nq;
        return;
    }
    for (int j = 0; j < N; j++)
        if (!dependent(m, j) && k-- == 0) {
            *coord = j % m->nq;
            *order = j / m->nq;
            return;
        }
    *coord = *order = -1;
}

/* The linearized constraints C dx = 0 at (t, x), C [nr x N]: holonomic
 * g (dg/dq) and g' (dg'/dq, dg'/dq'), first order phi (dphi/dq,
 * dphi/dq'); nr is the number of dependent components. */
static int
constraint_rows(eomc_sim *s, double t, const double *x, double *C)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, nc = m->nc, nu = m->nu, N = 2 * n, r = 0;
    if (nc == 0)
        return 0;
    size_t nn = (size_t)nc * (size_t)n;
    double *w = calloc(3 * nn + 2 * (size_t)(nc * nu) + 2 * (size_t)nc + 1, sizeof *w);
    if (!w)
        return -1;
    double *dposdq = w, *dveldq = w + nn, *dveldv = w + 2 * nn;
    double *dposdu = w + 3 * nn, *dveldu = dposdu + nc * nu, *dposdt = dveldu + nc * nu;
    double *dveldt = dposdt + nc;
    const double *u = sim_inputs_at(s, t);
    m->c_levels_jacobian(t, x, x + n, sim_p(s), u, dposdq, dveldq, dveldv, dposdu, dveldu,
                         dposdt, dveldt);
    for (int k = 0; k < nc; k++) {
        if (m->c_order[k] == 0) {
            for (int j = 0; j < N; j++)
                C[r * N + j] = j < n ? dposdq[k * n + j] : 0;
            r++;
        }
        if (m->c_order[k] <= 1) {
            for (int j = 0; j < N; j++)
                C[r * N + j] = j < n ? dveldq[k * n + j] : dveldv[k * n + j - n];
            r++;
        }
    }
    free(w);
    return r;
}

/* The componentwise backward error of y as a solution of C y = b [nd]
 * (Oettli and Prager): the least relative change of C's entries and b's
 * that makes it exact, max_i |b - C y|_i / (|C| |y| + |b|)_i; 0 for an
 * exact one.  Free of the rows' and the unknowns' scales. */
static double
backward_error(const double *C, int nd, const double *y, const double *b)
{
    double worst = 0;
    for (int i = 0; i < nd; i++) {
        double r = b[i], mag = fabs(b[i]);
        for (int j = 0; j < nd; j++)
            r -= C[i * nd + j] * y[j], mag += fabs(C[i * nd + j] * y[j]);
        if (r != 0)
            worst = fmax(worst, mag > 0 ? fabs(r) / mag : HUGE_VAL);
    }
    return worst;
}

/* An entry of a solve's result that is 0 to the solve's accuracy is made
 * 0: one whose zeroing leaves the solution's componentwise backward error
 * at rounding (ZERO_BACKWARD units of it on every row, about LU's own).
 * A cyclic coordinate's influence on a dependent velocity cancels exactly
 * (a bicycle's heading turns its rolling constraints and their solution
 * alike), and its rounding, left in T, would couple the coordinate's
 * zero eigenvalue to the others. */
#define ZERO_BACKWARD 8
static void
clean_zeros(const double *C, int nd, double *y, const double *b, double *trial)
{
    double bound = ZERO_BACKWARD * nd * DBL_EPSILON;
    if (backward_error(C, nd, y, b) > bound)
        return; /* not a solve accurate to rounding: nothing to tell from 0 */
    memcpy(trial, y, (size_t)nd * sizeof *y);
    for (int r = 0; r < nd; r++) {
        if (y[r] == 0)
            continue;
        trial[r] = 0;
        if (backward_error(C, nd, trial, b) <= bound)
            y[r] = 0;
        else
            trial[r] = y[r];
    }
}

/* T [N x nl]: the full perturbation of each reduced one: dx_i = dz for
 * the independent components, dx_d = -C_d^-1 C_i dz for the dependent. */
static int
tangent(eomc_sim *s, double t, const double *x, int nl, double *T)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, N = 2 * n, nd = N - nl;
    double *C = calloc((size_t)(nd ? nd : 1) * (size_t)N, sizeof *C);
    double *Cd = calloc((size_t)(nd ? nd * nd : 1), sizeof *Cd);
    double *col = calloc(3 * (size_t)(nd ? nd : 1), sizeof *col);
    double *rhs = col + (nd ? nd : 1), *trial = rhs + (nd ? nd : 1);
    int *dep = calloc((size_t)N, sizeof *dep), *ind = calloc((size_t)N, sizeof *ind);
    LaLu *lu = la_lu_alloc(nd ? nd : 1);
    int rc = -1;
    if (!C || !Cd || !col || !dep || !ind || !lu || constraint_rows(s, t, x, C) != nd)
        goto done;
    int a = 0, b = 0;
    for (int j = 0; j < N; j++) {
        if (dependent(m, j))
            dep[a++] = j;
        else
            ind[b++] = j;
    }
    for (int r = 0; r < nd; r++)
        for (int c = 0; c < nd; c++)
            Cd[r * nd + c] = C[r * N + dep[c]];
    if (nd && la_lu_factor(lu, Cd) != 0)
        goto done;
    memset(T, 0, (size_t)N * (size_t)nl * sizeof *T);
    for (int k = 0; k < nl; k++) {
        T[ind[k] * nl + k] = 1;
        for (int r = 0; r < nd; r++)
            rhs[r] = col[r] = -C[r * N + ind[k]];
        if (nd) {
            la_lu_solve(lu, col);
            clean_zeros(Cd, nd, col, rhs, trial);
        }
        for (int r = 0; r < nd; r++)
            T[dep[r] * nl + k] = col[r];
    }
    rc = 0;
done:
    free(C);
    free(Cd);
    free(col);
    free(dep);
    free(ind);
    la_lu_free(lu);
    return rc;
}

static int
linearize(eomc_sim *s, double t, const double *x, double *A, double *B)
{
    const eomc_model *m = eomc_sim_model(s);
    if (m->nv > 0)
        return no_speeds(s, "the linearization");
    if (!m->jacobian)
        return sim_no_jacobian(s, "the linearization");
    int n = m->nq, nu = m->nu, N = 2 * n, nl = eomc_sim_linear_size(s);
    /* off the constraints, the linearization describes no motion of the
     * model, and its eigenvalues nothing the model does */
    int rc = sim_off_constraints(s, t, x, x + n, "the linearization");
    if (rc == EOMC_OK)
        rc = sim_choose_rows(s, t, x, x + n);
    if (rc != EOMC_OK)
        return rc;
    /* the state it keeps leaves out one coordinate for each constraint
     * (its dependent one): a row left out determines none */
    if (sim_dropped_rows(s))
        return sim_usage_error(s, "the linearization needs independent constraints, and "
                               "these are dependent (%s; the simulations leave the dependent "
                               "rows out): write the model without them",
                               sim_dropped_note(s));
    double *Af = calloc((size_t)N * (size_t)N, sizeof *Af);
    double *Bf = calloc((size_t)N * (size_t)(nu ? nu : 1), sizeof *Bf);
    double *T = calloc((size_t)N * (size_t)nl, sizeof *T);
    int *ind = calloc((size_t)N, sizeof *ind);
    if (!Af || !Bf || !T || !ind) {
        rc = sim_usage_error(s, "out of memory linearizing %s", m->name);
        goto done;
    }
    if ((rc = eomc_sim_jacobian(s, t, x, Af, NULL)) != EOMC_OK)
        goto done;
    if (sim_input_jacobian(s, t, x, Bf) != 0) {
        rc = sim_numeric_error(s, t, x, x + n, "the response to the inputs could not be "
                               "solved");
        goto done;
    }
    if (tangent(s, t, x, nl, T) != 0) {
        rc = sim_numeric_error(s, t, x, x + n, "the constraints cannot be solved for their "
                               "dependent coordinates here (their rows are singular)");
        goto done;
    }
    for (int j = 0, k = 0; j < N; j++)
        if (!dependent(m, j))
            ind[k++] = j;
    /* the reduced rows of A T and of B.  An entry no larger than the
     * rounding of its own sum (N units of it on the sum of the terms'
     * magnitudes) is 0 to the accuracy it has, and 0 it is: a cyclic
     * coordinate's column (a bicycle's heading) then stays exactly 0, and
     * its eigenvalue exactly 0 (eomc_sim_eigenvalues) */
    for (int r = 0; r < nl; r++) {
        for (int c = 0; c < nl; c++) {
            double sum = 0, mag = 0;
            for (int j = 0; j < N; j++) {
                sum += Af[ind[r] * N + j] * T[j * nl + c];
                mag += fabs(Af[ind[r] * N + j] * T[j * nl + c]);
            }
            A[r * nl + c] = fabs(sum) <= N * DBL_EPSILON * mag ? 0 : sum;
        }
        for (int k = 0; k < nu; k++)
            B[r * nu + k] = Bf[ind[r] * nu + k];
    }
done:
    free(Af);
    free(Bf);
    free(T);
    free(ind);
    return rc;
}

/* Isolate the eigenvalues that rows or columns of zeros give exactly, as
 * LAPACK's balancing does by permutation (GSL's balancing only scales):
 * a component k whose column (or row) is 0 off the diagonal among those
 * left has the eigenvalue A_kk, and the others are those of A without
 * row and column k (expand det(A - s I) along it).  A cyclic coordinate
 * (a bicycle's position, heading, wheel angles) is such a column; left in
 * the QR iteration, the zeros of such a chain form a Jordan block, which
 * rounding splits into +-1e-8 where the true eigenvalues are 0.
 * keep [nl] marks those left; returns how many were isolated, their
 * eigenvalues into re, im [nl] from the end. */
static int
isolate(const double *A, int nl, unsigned char *keep, double *re, double *im)
{
    int found = 0;
    memset(keep, 1, (size_t)nl);
    for (int again = 1; again;) {
        again = 0;
        for (int k = 0; k < nl; k++) {
            if (!keep[k])
                continue;
            int col = 1, row = 1;
            for (int i = 0; i < nl && (col || row); i++)
                if (keep[i] && i != k) {
                    col &= A[i * nl + k] == 0;
                    row &= A[k * nl + i] == 0;
                }
            if (col || row) {
                keep[k] = 0;
                found++;
                re[nl - found] = A[k * nl + k], im[nl - found] = 0;
                again = 1;
            }
        }
    }
    return found;
}

int
eomc_sim_eigenvalues(eomc_sim *s, const double *A, int nl, double *re, double *im)
{
    unsigned char *keep = malloc((size_t)nl + 1);
    /* QR iteration takes a NaN for a number and fails on an infinity
     * through GSL's error handler: neither reaches it */
    for (size_t k = 0; k < (size_t)nl * (size_t)nl; k++)
        if (!isfinite(A[k])) {
            free(keep);
            return sim_usage_error(s, "the matrix has a non-finite entry (row %zu, column "
                                   "%zu): no eigenvalues", k / (size_t)nl + 1,
                                   k % (size_t)nl + 1);
        }
    if (!keep)
        return sim_usage_error(s, "out of memory for the eigenvalues");
    int nr = nl - isolate(A, nl, keep, re, im);
    if (nr == 0) {
        free(keep);
        return EOMC_OK;
    }
    gsl_matrix *M = gsl_matrix_alloc((size_t)nr, (size_t)nr);
    gsl_vector_complex *ev = gsl_vector_complex_alloc((size_t)nr);
    gsl_eigen_nonsymm_workspace *w = gsl_eigen_nonsymm_alloc((size_t)nr);
    int rc = EOMC_OK;
    if (!M || !ev || !w) {
        rc = sim_usage_error(s, "out of memory for the eigenvalues");
    } else {
        for (int i = 0, a = 0; i < nl; i++) {
            if (!keep[i])
                continue;
            for (int j = 0, b = 0; j < nl; j++)
                if (keep[j])
                    gsl_matrix_set(M, (size_t)a, (size_t)b++, A[i * nl + j]);
            a++;
        }
        gsl_eigen_nonsymm_params(0, 1, w); /* balanced: A mixes units */
        if (gsl_eigen_nonsymm(M, ev, w) != GSL_SUCCESS)
            rc = sim_usage_error(s, "the eigenvalues did not converge (QR iteration)");
        for (int k = 0; k < nr && !rc; k++) {
            re[k] = GSL_REAL(gsl_vector_complex_get(ev, (size_t)k));
            im[k] = GSL_IMAG(gsl_vector_complex_get(ev, (size_t)k));
        }
    }
    gsl_eigen_nonsymm_free(w);
    gsl_vector_complex_free(ev);
    gsl_matrix_free(M);
    free(keep);
    return rc;
}

/* ---- how far a state is from rest ---- */

/* Jz [n x nl] = dq''/dz at (t, x), z the linearization's state: the q''
 * rows of the simulator's Jacobian along T [N x nl] (Af [N x N] its
 * workspace). */
static int
accel_jacobian(eomc_sim *s, double t, const double *x, int nl, double *Af, double *T,
               double *Jz)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, N = 2 * n, rc = eomc_sim_jacobian(s, t, x, Af, NULL);
    if (rc != EOMC_OK)
        return rc;
    if (tangent(s, t, x, nl, T) != 0)
        return sim_numeric_error(s, t, x, x + n, "the constraints' rows are singular here");
    for (int i = 0; i < n; i++)
        for (int k = 0; k < nl; k++) {
            double sum = 0;
            for (int j = 0; j < N; j++)
                sum += Af[(n + i) * N + j] * T[j * nl + k];
            Jz[i * nl + k] = sum;
        }
    return EOMC_OK;
}

/* reach [n]: sum_k |Jz_ik| w_k, what q''_i would change by if every z_k
 * moved by w_k [nl]. */
static void
accel_reach(int n, int nl, const double *Jz, const double *w, double *reach)
{
    for (int i = 0; i < n; i++) {
        reach[i] = 0;
        for (int k = 0; k < nl; k++)
            reach[i] += fabs(Jz[i * nl + k]) * w[k];
    }
}

/* The largest |acc_i| / floor_i [n] (0 where acc_i is 0, infinite where
 * only floor_i is), its i into *worst. */
static double
accel_ratio(int n, const double *acc, const double *reach, int *worst)
{
    double big = 0;
    *worst = 0;
    for (int i = 0; i < n; i++) {
        double r = acc[i] == 0 ? 0 : reach[i] > 0 ? fabs(acc[i]) / reach[i] : HUGE_VAL;
        if (r > big)
            big = r, *worst = i;
    }
    return big;
}

static double
accel_residual(eomc_sim *s, double t, const double *x, double *acc, int *worst)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, N = 2 * n, nl = eomc_sim_linear_size(s);
    *worst = -1;
    if (m->nv > 0) {
        no_speeds(s, "the test for rest");
        return NAN;
    }
    if (!m->jacobian) {
        sim_no_jacobian(s, "the test for rest");
        return NAN;
    }
    size_t snl = nl > 0 ? (size_t)nl : 1;
    double *Af = calloc((size_t)N * (size_t)N, sizeof *Af);
    double *T = calloc((size_t)N * snl, sizeof *T), *Jz = calloc((size_t)n * snl, sizeof *Jz);
    double *w = calloc(snl, sizeof *w), *reach = calloc((size_t)n, sizeof *reach);
    double r = NAN;
    if (!Af || !T || !Jz || !w || !reach)
        sim_usage_error(s, "out of memory testing %s for rest", m->name);
    else if (eomc_sim_accel(s, t, x, x + n, acc) == EOMC_OK &&
             accel_jacobian(s, t, x, nl, Af, T, Jz) == EOMC_OK) {
        for (int k = 0; k < nl; k++) {
            int coord, order;
            eomc_sim_linear_state(s, k, &coord, &order);
            w[k] = fabs(x[order * n + coord]);
        }
        accel_reach(n, nl, Jz, w, reach);
        r = accel_ratio(n, acc, reach, worst);
    }
    free(Af);
    free(T);
    free(Jz);
    free(w);
    free(reach);
    return r;
}

/* ---- equilibria ---- */

/* Newton's method stops when its step is this many units of rounding of
 * the coordinate (or of the coordinate's scale, for one near 0), or when
 * steps below 1e-8 of that stop shrinking; it gives up after EQ_MAX_ITER
 * iterations.  Where it stops, q'' must be 0 (EOMC_ACCEL_ZERO, eomc.h)
 * for what it found to be an equilibrium. */
enum { EQ_MAX_ITER = 100, EQ_HALVINGS = 40 };
#define EQ_SETTLED (16 * DBL_EPSILON)
#define EQ_STALL 1e-8
/* Newton's method runs away when its full step has not shrunk in
 * EQ_RUNAWAY steps running, each taking it farther from the start: it
 * then follows q'' down a slope that reaches 0 only at infinity (on
 * f ~ 1/z Newton's step doubles z; on f ~ exp(-z) it adds 1), where near
 * a root its steps shrink.  Eight: on f ~ 1/z, 256 times as far out as
 * where the run began.  Not shrinking means by less than EQ_SHRUNK: at a
 * root of multiplicity m the steps shrink by (m - 1)/m each, so only a
 * root of multiplicity above 100 is taken for a runaway.  Damped steps
 * (which may crawl round to a root far from the start) are not counted;
 * EQ_MAX_ITER steps, the last EQ_RUNAWAY of them or more each farther
 * out, are a runaway too. */
enum { EQ_RUNAWAY = 8 };
#define EQ_SHRUNK 0.99

/* Put the dependent coordinates of the holonomic constraints back on
 * g(q) = 0 (the independent ones held): Newton on the dependent columns. */
static int
hold_on_constraints(eomc_sim *s, double t, double *x)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq, nc = m->nc, nh = 0;
    for (int k = 0; k < nc; k++)
        nh += m->c_order[k] == 0;
    if (nh == 0)
        return 0;
    double *pos = calloc((size_t)nc, sizeof *pos), *vel = calloc((size_t)nc, sizeof *vel);
    double *C = calloc((size_t)(2 * nc + 1) * (size_t)(2 * n), sizeof *C);
    double *G = calloc((size_t)(nh * nh), sizeof *G), *r = calloc((size_t)nh, sizeof *r);
    double *first = calloc((size_t)nh, sizeof *first);
    int *dep = calloc((size_t)nh, sizeof *dep), *row = calloc((size_t)nh, sizeof *row);
    LaLu *lu = la_lu_alloc(nh);
    int rc = -1;
    if (!pos || !vel || !C || !G || !r || !first || !dep || !row || !lu)
        goto done;
    for (int k = 0, h = 0, rr = 0; k < nc; k++) {
        if (m->c_order[k] == 0)
            dep[h] = m->c_dependent[k], row[h++] = rr;
        rr += m->c_order[k] == 0 ? 2 : m->c_order[k] == 1;
    }
    double prev = HUGE_VAL;
    for (int it = 0; it < EQ_MAX_ITER; it++) {
        m->c_levels(t, x, x + n, sim_p(s), sim_inputs_at(s, t), pos, vel);
        if (constraint_rows(s, t, x, C) < 0)
            goto done;
        double worst = 0;
        for (int a = 0, h = 0; a < nc; a++)
            if (m->c_order[a] == 0)
                r[h++] = -pos[a];
        for (int a = 0; a < nh; a++)
            for (int b = 0; b < nh; b++)
                G[a * nh + b] = C[row[a] * 2 * n + dep[b]];
        if (la_lu_factor(lu, G) != 0)
            goto done;
        la_lu_solve(lu, r);
        for (int a = 0; a < nh; a++) {
            x[dep[a]] += r[a];
            if (it == 0) /* a coordinate at 0 is measured by the first correction */
                first[a] = fabs(r[a]);
            worst = fmax(worst, fabs(r[a]) / fmax(fmax(fabs(x[dep[a]]), first[a]), DBL_MIN));
        }
        if (worst <= EQ_SETTLED || (worst <= EQ_STALL && worst >= prev)) {
            rc = 0;
            break;
        }
        prev = worst;
    }
done:
    free(pos);
    free(vel);
    free(C);
    free(G);
    free(r);
    free(first);
    free(dep);
    free(row);
    la_lu_free(lu);
    return rc;
}

/* The weights of the accelerations at (t, x), whatever the units of the
 * coordinates: wt [n] gets sqrt(M_ii), the diagonal of the mass matrix
 * (M_ii q''_i^2 is a power per time whatever coordinate i measures; a
 * coordinate without inertia, which a constrained model may have, weighs
 * nothing).  M [n x n] and h [n] are workspace. */
static void
weights(eomc_sim *s, double t, const double *x, double *M, double *h, double *wt)
{
    const eomc_model *m = eomc_sim_model(s);
    int n = m->nq;
    m->mass_bias(t, x, x + n, sim_p(s), sim_inputs_at(s, t), M, h);
    for (int i = 0; i < n; i++)
        wt[i] = M[i * n + i] > 0 ? sqrt(M[i * n + i]) : 0;
}

/* sqrt(sum_i (wt_i acc_i)^2). */
static double
weighed(int n, const double *acc, const double *wt)
{
    double sum = 0;
    for (int i = 0; i < n; i++)
        sum += (wt[i] * acc[i]) * (wt[i] * acc[i]);
    return sqrt(sum);
}

/* The message of a runaway, how as it says, naming the coordinate that
 * has gone farthest from the start relative to its scale. */
static int
runaway_error(eomc_sim *s, double t, double *x, const double *z0, const double *S,
              const int *qc, int nzq, const char *how)
{
    const eomc_model *m = eomc_sim_model(s);
    int far = 0;
    double most = -1;
    for (int cq = 0; cq < nzq; cq++) {
        double d = S[cq] > 0 ? fabs(x[qc[cq]] - z0[cq]) / S[cq] : 0;
        if (d > most)
            most = d, far = cq;
    }
    char a[NUM_MAX], b[NUM_MAX];
    return sim_numeric_error(s, t, x, x + m->nq, "Newton's method runs away: %s (%s from %s "
                             "to %s), and q'' does not reach 0 that way: no equilibrium was "
                             "found there (try another --init)", how, m->q_names[qc[far]],
                             num_shortest(a, z0[far]), num_shortest(b, x[qc[far]]));
}

static int
equilibrium(eomc_sim *s, double t, double *x, int *iterations)
{
    const eomc_model *m = eomc_sim_model(s);
    if (m->nv > 0)
        return no_speeds(s, "the equilibrium search");
    if (!m->jacobian)
        return sim_no_jacobian(s, "the equilibrium search");
    int n = m->nq, N = 2 * n, nl = eomc_sim_linear_size(s);
    /* the independent coordinates: their place k among the states, and
     * which coordinate each is */
    int nzq = 0, nzv = 0, *qk = calloc((size_t)N, sizeof *qk), *qc = calloc((size_t)N, sizeof *qc);
    for (int k = 0; k < nl && qk && qc; k++) {
        int c, o;
        eomc_sim_linear_state(s, k, &c, &o);
        if (o)
            nzv++;
        else
            qk[nzq] = k, qc[nzq++] = c;
    }
    size_t snl = nl > 0 ? (size_t)nl : 1, szq = nzq > 0 ? (size_t)nzq : 1;
    double *Af = calloc((size_t)N * (size_t)N, sizeof *Af);
    double *T = calloc((size_t)N * snl, sizeof *T), *Jz = calloc((size_t)n * snl, sizeof *Jz);
    double *x0 = calloc((size_t)N, sizeof *x0), *w = calloc(snl, sizeof *w);
    /* scales from the start, none from the iterate (which a runaway
     * inflates): z0 [nzq] the independent coordinates there, S [nzq] each
     * one's scale (the larger of its value there and its first Newton
     * step; a coordinate with neither takes its first nonzero step), R0
     * [n] each acceleration's (its value there, and what the coordinates'
     * values there would change it by) */
    double *S = calloc(szq, sizeof *S), *z0 = calloc(szq, sizeof *z0);
    double *R0 = calloc((size_t)n, sizeof *R0);
    double *reach = calloc((size_t)n, sizeof *reach);
    double *acc = calloc((size_t)n, sizeof *acc); /* q'' at x */
    double *M = calloc((size_t)n * (size_t)n, sizeof *M), *h = calloc((size_t)n, sizeof *h);
    double *wt = calloc((size_t)n, sizeof *wt); /* the rows' weights (weights) */
    gsl_matrix *J = gsl_matrix_alloc((size_t)n, szq);
    gsl_matrix *V = gsl_matrix_alloc(szq, szq);
    gsl_vector *Sv = gsl_vector_alloc(szq), *work = gsl_vector_alloc(szq);
    gsl_vector *F = gsl_vector_alloc((size_t)n), *dz = gsl_vector_alloc(szq);
    int rc = EOMC_OK;
    *iterations = 0;
    if (!qk || !qc || !Af || !T || !Jz || !x0 || !w || !S || !z0 || !R0 || !reach || !acc ||
        !M || !h || !wt || !J || !V || !Sv || !work || !F || !dz) {
        rc = sim_usage_error(s, "out of memory searching for an equilibrium");
        goto done;
    }
    if (nzv != nzq || nzq == 0) {
        rc = sim_usage_error(s, "%s has %d independent coordinate%s but %d independent "
                             "velocit%s: its equilibria are not isolated points (a "
                             "nonholonomic model rests anywhere its forces allow), so "
                             "Newton's method has no single answer to find", m->name, nzq,
                             nzq == 1 ? "" : "s", nzv, nzv == 1 ? "y" : "ies");
        goto done;
    }
    memset(x + n, 0, (size_t)n * sizeof *x);
    if (hold_on_constraints(s, t, x) != 0) {
        rc = sim_numeric_error(s, t, x, x + n, "the start is too far from the constraints "
                               "to put it on them");
        goto done;
    }
    for (int cq = 0; cq < nzq; cq++)
        z0[cq] = x[qc[cq]];
    double prev = HUGE_VAL, prev_full = HUGE_VAL, prev_far = 0;
    int growing = 0, outward = 0;
    char how[160];
    for (int it = 1;; it++) {
        *iterations = it;
        if (it > EQ_MAX_ITER && outward >= EQ_RUNAWAY) {
            snprintf(how, sizeof how, "in %d iterations it found no equilibrium, and each of "
                     "its last %d steps took it farther from the start", EQ_MAX_ITER, outward);
            rc = runaway_error(s, t, x, z0, S, qc, nzq, how);
            goto done;
        }
        if (it > EQ_MAX_ITER) {
            rc = sim_numeric_error(s, t, x, x + n, "Newton's method found no equilibrium in "
                                   "%d iterations from the start given (try another --init)",
                                   EQ_MAX_ITER);
            goto done;
        }
        if ((rc = accel_jacobian(s, t, x, nl, Af, T, Jz)) != EOMC_OK)
            goto done;
        if ((rc = eomc_sim_accel(s, t, x, x + n, acc)) != EOMC_OK)
            goto done;
        if (it == 1) {
            for (int k = 0; k < nl; k++)
                w[k] = 0;
            for (int cq = 0; cq < nzq; cq++)
                w[qk[cq]] = fabs(z0[cq]);
            accel_reach(n, nl, Jz, w, R0);
            for (int i = 0; i < n; i++)
                R0[i] += fabs(acc[i]);
        }
        /* F = every acceleration (a dependent coordinate's too: a reduced
         * coordinate may stand still where the motion does not); J = their
         * derivative along the independent coordinates, (dq''/dx) T.  Each
         * row weighted by sqrt(M_ii), each column in the units of its
         * coordinate's scale once it has one: the least-squares step, and
         * the directions it drops, are then the same in any units */
        weights(s, t, x, M, h, wt);
        double f0 = weighed(n, acc, wt);
        for (int i = 0; i < n; i++) {
            gsl_vector_set(F, (size_t)i, -wt[i] * acc[i]);
            for (int cq = 0; cq < nzq; cq++)
                gsl_matrix_set(J, (size_t)i, (size_t)cq,
                               wt[i] * Jz[i * nl + qk[cq]] * (S[cq] > 0 ? S[cq] : 1));
        }
        /* the least-squares step: robust where J is nearly singular (a
         * flat direction) */
        if (gsl_linalg_SV_decomp(J, V, Sv, work) != GSL_SUCCESS ||
            !(gsl_vector_get(Sv, 0) > 0)) {
            rc = sim_numeric_error(s, t, x, x + n, "the accelerations do not depend on the "
                                   "coordinates here: no Newton step");
            goto done;
        }
        for (size_t k = 1; k < Sv->size; k++) /* drop what rounding cannot resolve */
            if (gsl_vector_get(Sv, k) < 1e3 * DBL_EPSILON * gsl_vector_get(Sv, 0))
                gsl_vector_set(Sv, k, 0);
        gsl_linalg_SV_solve(J, V, Sv, F, dz);
        for (int cq = 0; cq < nzq; cq++)
            if (S[cq] > 0)
                gsl_vector_set(dz, (size_t)cq, gsl_vector_get(dz, (size_t)cq) * S[cq]);
        /* the full step's size, relative to the coordinates' scales */
        double full = 0;
        for (int cq = 0; cq < nzq; cq++) {
            double step = fabs(gsl_vector_get(dz, (size_t)cq));
            if (S[cq] == 0)
                S[cq] = fmax(fabs(z0[cq]), step);
            if (step > 0)
                full = fmax(full, S[cq] > 0 ? step / S[cq] : HUGE_VAL);
        }
        /* damped: the full step, or halves of it, until the accelerations
         * shrink, weighed as here (a step past a fold of the constraints,
         * or overshooting a maximum, comes back) */
        double worst = 0, lambda = 1;
        memcpy(x0, x, (size_t)N * sizeof *x);
        for (int tries = 0;; tries++, lambda *= 0.5) {
            memcpy(x, x0, (size_t)N * sizeof *x);
            worst = 0;
            for (int cq = 0; cq < nzq; cq++) {
                double step = lambda * gsl_vector_get(dz, (size_t)cq);
                for (int j = 0; j < n; j++)
                    x[j] += T[j * nl + qk[cq]] * step;
                worst = fmax(worst, fabs(step) / fmax(fmax(fabs(x[qc[cq]]), S[cq]), DBL_MIN));
            }
            int ok = hold_on_constraints(s, t, x) == 0 &&
                     eomc_sim_accel(s, t, x, x + n, acc) == EOMC_OK;
            double f1 = ok ? weighed(n, acc, wt) : HUGE_VAL;
            if (ok && (f1 < f0 || worst <= EQ_STALL))
                break;
            if (tries == EQ_HALVINGS) {
                memcpy(x, x0, (size_t)N * sizeof *x);
                rc = sim_numeric_error(s, t, x, x + n, "Newton's method cannot reduce the "
                                       "accelerations from here (no step along its "
                                       "direction does; try another --init)");
                goto done;
            }
        }
        /* a runaway (EQ_RUNAWAY): full steps that do not shrink, each
         * farther out */
        double far = 0;
        for (int cq = 0; cq < nzq; cq++)
            if (S[cq] > 0)
                far = fmax(far, fabs(x[qc[cq]] - z0[cq]) / S[cq]);
        outward = far > prev_far ? outward + 1 : 0;
        growing = outward && lambda == 1 && full >= EQ_SHRUNK * prev_full ? growing + 1 : 0;
        prev_full = full, prev_far = far;
        if (growing >= EQ_RUNAWAY) {
            snprintf(how, sizeof how, "%d full Newton steps running did not shrink, each "
                     "taking it farther from the start", growing);
            rc = runaway_error(s, t, x, z0, S, qc, nzq, how);
            goto done;
        }
        if (worst <= EQ_SETTLED || (worst <= EQ_STALL && worst >= prev))
            break;
        prev = worst;
    }
    /* found only where q'' is 0: each q''_i within EOMC_ACCEL_ZERO of the
     * larger of its scale at the start, R0_i, and what the coordinates'
     * values here would change it by (their rounding reaches that far).
     * Steps stop shrinking also at a minimum of |q''| that is not 0 (the
     * least-squares step drops the direction that would reduce it), and
     * far out where q'' only falls as a coordinate grows (a force on a
     * longer lever, divided by an inertia that grows as its square). */
    if ((rc = accel_jacobian(s, t, x, nl, Af, T, Jz)) != EOMC_OK ||
        (rc = eomc_sim_accel(s, t, x, x + n, acc)) != EOMC_OK)
        goto done;
    for (int k = 0; k < nl; k++)
        w[k] = 0;
    for (int cq = 0; cq < nzq; cq++)
        w[qk[cq]] = fabs(x[qc[cq]]);
    accel_reach(n, nl, Jz, w, reach);
    for (int i = 0; i < n; i++)
        reach[i] = fmax(reach[i], R0[i]);
    int bad;
    double ratio = accel_ratio(n, acc, reach, &bad);
    if (ratio > EOMC_ACCEL_ZERO) {
        char a[NUM_MAX];
        rc = sim_numeric_error(s, t, x, x + n, "Newton's method stopped making progress "
                               "after %d steps where q'' is not 0 (%s'' = %s, where rounding "
                               "would leave at most %.2g): no equilibrium there (try another "
                               "--init)", *iterations, m->q_names[bad],
                               num_shortest(a, acc[bad]), EOMC_ACCEL_ZERO * reach[bad]);
    }
done:
    free(qk);
    free(qc);
    free(Af);
    free(T);
    free(Jz);
    free(x0);
    free(w);
    free(S);
    free(z0);
    free(R0);
    free(reach);
    free(acc);
    free(M);
    free(h);
    free(wt);
    gsl_matrix_free(J);
    gsl_matrix_free(V);
    gsl_vector_free(Sv);
    gsl_vector_free(work);
    gsl_vector_free(F);
    gsl_vector_free(dz);
    return rc;
}

/* ---- the analyses, on the dense solve ----
 * Each differentiates q'' and reads exact zeros in it (a cyclic
 * coordinate's row, a steady motion's q''), so each runs on the dense
 * KKT solve, whose zeros are the equations' own: unit loads give the same
 * q''(x) to the rounding of its terms, which is all a zero there would
 * read as (a_f - Y lambda: 1.7e-15 where the bicycle's x'' is 0). */

int
eomc_sim_linearize(eomc_sim *s, double t, const double *x, double *A, double *B)
{
    sim_set_dense(s, 1);
    int rc = linearize(s, t, x, A, B);
    sim_set_dense(s, 0);
    return rc;
}

double
eomc_sim_accel_residual(eomc_sim *s, double t, const double *x, double *acc, int *worst)
{
    sim_set_dense(s, 1);
    double r = accel_residual(s, t, x, acc, worst);
    sim_set_dense(s, 0);
    return r;
}

int
eomc_sim_equilibrium(eomc_sim *s, double t, double *x, int *iterations)
{
    sim_set_dense(s, 1);
    int rc = equilibrium(s, t, x, iterations);
    sim_set_dense(s, 0);
    return rc;
}

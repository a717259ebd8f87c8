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

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_blas.h>
#include <gsl/gsl_linalg.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
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

int
eomc_sim_linear_size(const eomc_sim *s)
{
    const eomc_model *m = eomc_sim_model(s);
    int N = 2 * m->nq, size = 0;
    for (int j = 0; j < N; j++)
        size += !dependent(m, j);
    return size;
}

void
eomc_sim_linear_state(const eomc_sim *s, int k, int *coord, int *order)
{
    const eomc_model *m = eomc_sim_model(s);
    int N = 2 * m->nq;
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

int
eomc_sim_linearize(eomc_sim *s, double t, const double *x, double *A, double *B)
{
    const eomc_model *m = eomc_sim_model(s);
    if (!m->jacobian)
        return sim_no_jacobian(s, "the linearization");
    int n = m->nq, nu = m->nu, N = 2 * n, nl = eomc_sim_linear_size(s);
    /* off the constraints, the linearization describes no motion of the
     * model, and its eigenvalues nothing the model does */
    int rc = sim_off_constraints(s, t, x, x + n, "the linearization");
    if (rc != EOMC_OK)
        return rc;
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

/* ---- equilibria ---- */

/* Newton's method stops when its step is this many units of rounding of
 * the coordinate (or of the first step's size, for a coordinate near 0),
 * or when steps below 1e-8 of that stop shrinking; it gives up after
 * EQ_MAX_ITER iterations. */
enum { EQ_MAX_ITER = 100, EQ_HALVINGS = 40 };
#define EQ_SETTLED (16 * DBL_EPSILON)
#define EQ_STALL 1e-8

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

int
eomc_sim_equilibrium(eomc_sim *s, double t, double *x, int *iterations)
{
    const eomc_model *m = eomc_sim_model(s);
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
    size_t snl = nl > 0 ? (size_t)nl : 1;
    double *Af = calloc((size_t)N * (size_t)N, sizeof *Af);
    double *T = calloc((size_t)N * snl, sizeof *T);
    double *scale = calloc(snl, sizeof *scale), *x0 = calloc((size_t)N, sizeof *x0);
    double *acc = calloc((size_t)n, sizeof *acc); /* q'' at x */
    gsl_matrix *J = gsl_matrix_alloc((size_t)n, (size_t)(nzq ? nzq : 1));
    gsl_matrix *V = gsl_matrix_alloc((size_t)(nzq ? nzq : 1), (size_t)(nzq ? nzq : 1));
    gsl_vector *S = gsl_vector_alloc((size_t)(nzq ? nzq : 1));
    gsl_vector *work = gsl_vector_alloc((size_t)(nzq ? nzq : 1));
    gsl_vector *F = gsl_vector_alloc((size_t)n);
    gsl_vector *dz = gsl_vector_alloc((size_t)(nzq ? nzq : 1));
    int rc = EOMC_OK;
    *iterations = 0;
    if (!qk || !qc || !Af || !T || !scale || !x0 || !acc || !J || !V || !S || !work || !F || !dz) {
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
    double prev = HUGE_VAL;
    for (int it = 1;; it++) {
        *iterations = it;
        if (it > EQ_MAX_ITER) {
            rc = sim_numeric_error(s, t, x, x + n, "Newton's method found no equilibrium in "
                                   "%d iterations from the start given (try another --init)",
                                   EQ_MAX_ITER);
            goto done;
        }
        if ((rc = eomc_sim_jacobian(s, t, x, Af, NULL)) != EOMC_OK)
            goto done;
        if (tangent(s, t, x, nl, T) != 0) {
            rc = sim_numeric_error(s, t, x, x + n, "the constraints' rows are singular here");
            goto done;
        }
        if ((rc = eomc_sim_accel(s, t, x, x + n, acc)) != EOMC_OK)
            goto done;
        /* F = every acceleration (a dependent coordinate's too: a reduced
         * coordinate may stand still where the motion does not); J = their
         * derivative along the independent coordinates, (dq''/dx) T */
        for (int i = 0; i < n; i++) {
            gsl_vector_set(F, (size_t)i, -acc[i]);
            for (int cq = 0; cq < nzq; cq++) {
                double sum = 0;
                for (int j = 0; j < N; j++)
                    sum += Af[(n + i) * N + j] * T[j * nl + qk[cq]];
                gsl_matrix_set(J, (size_t)i, (size_t)cq, sum);
            }
        }
        /* the least-squares step: robust where J is nearly singular (a
         * flat direction) */
        if (gsl_linalg_SV_decomp(J, V, S, work) != GSL_SUCCESS ||
            !(gsl_vector_get(S, 0) > 0)) {
            rc = sim_numeric_error(s, t, x, x + n, "the accelerations do not depend on the "
                                   "coordinates here: no Newton step");
            goto done;
        }
        for (size_t k = 1; k < S->size; k++) /* drop what rounding cannot resolve */
            if (gsl_vector_get(S, k) < 1e3 * DBL_EPSILON * gsl_vector_get(S, 0))
                gsl_vector_set(S, k, 0);
        gsl_linalg_SV_solve(J, V, S, F, dz);
        /* damped: the full step, or halves of it, until the accelerations
         * shrink (a step past a fold of the constraints, or overshooting a
         * maximum, comes back) */
        double f0 = gsl_blas_dnrm2(F), worst = 0, lambda = 1;
        memcpy(x0, x, (size_t)N * sizeof *x);
        for (int tries = 0;; tries++, lambda *= 0.5) {
            memcpy(x, x0, (size_t)N * sizeof *x);
            worst = 0;
            for (int cq = 0; cq < nzq; cq++) {
                double step = lambda * gsl_vector_get(dz, (size_t)cq);
                for (int j = 0; j < n; j++)
                    x[j] += T[j * nl + qk[cq]] * step;
                if (it == 1 && tries == 0)
                    scale[cq] = fabs(step);
                worst = fmax(worst, fabs(step) / fmax(fmax(fabs(x[qc[cq]]), scale[cq]), DBL_MIN));
            }
            int ok = hold_on_constraints(s, t, x) == 0 &&
                     eomc_sim_accel(s, t, x, x + n, acc) == EOMC_OK;
            double f1 = HUGE_VAL;
            if (ok) {
                f1 = 0;
                for (int i = 0; i < n; i++)
                    f1 += acc[i] * acc[i];
                f1 = sqrt(f1);
            }
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
        if (worst <= EQ_SETTLED || (worst <= EQ_STALL && worst >= prev))
            break;
        prev = worst;
    }
    rc = eomc_sim_accel(s, t, x, x + n, acc);
done:
    free(qk);
    free(qc);
    free(Af);
    free(T);
    free(scale);
    free(x0);
    free(acc);
    gsl_matrix_free(J);
    gsl_matrix_free(V);
    gsl_vector_free(S);
    gsl_vector_free(work);
    gsl_vector_free(F);
    gsl_vector_free(dz);
    return rc;
}

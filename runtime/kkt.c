/*
 * kkt: the accelerations of a constrained model, and its Jacobian.
 *
 * With multipliers, (q'', lambda) solve
 *     M q'' + h + B(q'')^T lambda = 0,   f(q'') = 0,
 * by Newton's method on this (Gauss) KKT system, whose matrix is
 *     K = [M + sum_k lambda_k d2f_k/dq''2, B^T; B, 0].
 * When every f is affine in q'' the Hessian term vanishes and one step
 * from (0, 0) is the exact solution: the linear KKT system.
 *
 * With elimination (Maggi), each constraint determines one dependent
 * coordinate h; with B = [B_v B_h] and g = -B_h^-1 B_v, C = [I; g] spans
 * the null space of B and
 *     C^T (M q'' + h) = 0,   f(q'') = 0
 * is a square system.  For f nonlinear in q'' C depends on q'' too; we
 * take Newton steps with C held at the current iterate (the fixed point
 * is the same, convergence is linear instead of quadratic).  The
 * multipliers follow from the dependent rows: B_h^T lambda = -E_h.
 *
 * The Jacobian of x' = (q', q''(t, q, q')) follows by differentiating the
 * KKT system at the solution (it is the same function q''(x) whichever
 * way it was solved):  d(q'', lambda)/dx = -K^-1 dR/dx  with
 *     dR/dx = [dE/dx + sum_k lambda_k dB_k/dx; df/dx].
 *
 * Baumgarte's stabilization replaces f by f + w_v vel + w_p pos (the
 * constraint's own levels from c_levels; w_v = 2 alpha, w_p = beta^2 for
 * a holonomic one, w_v = alpha for a first-order one).  The offset does
 * not depend on q'', so it is computed once per solve, and B is unchanged.
 *
 * Every array is allocated in kkt_alloc; LU factorizations are GSL's.
 */
#include "simimpl.h"

#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { NEWTON_MAX = 50 };
#define NEWTON_TOL 1e-13   /* relative size of the last Newton step */

struct Kkt {
    int n, nc, N, np;           /* N = n + nc unknowns, np = n - nc independent */
    double *K, *r;              /* [N*N], [N] */
    double *A, *ra;             /* elimination: [n*n], [n] */
    double *f, *B, *lam, *zero; /* [nc], [nc*n], [nc], [n] */
    double *prev_a, *prev_lam;  /* Newton's start: the last solution */
    int have_prev;
    double *dfdq, *dfdv, *dfdu, *dfdt;         /* [nc*n] [nc*n] [nc*nu] [nc] */
    double *dBdq, *dBdv, *dBda, *dBdu, *dBdt;  /* [nc*n*n] x3, [nc*n*nu], [nc*n] */
    double *BH, *G, *E;         /* [nc*nc], [nc*np], [n] */
    double *off;                /* [nc] Baumgarte's terms, else 0 */
    double *dposdq, *dveldq, *dveldv, *dposdu, *dveldu, *dposdt, *dveldt;
    int *dep, *indep;           /* [nc], [np] */
    gsl_permutation *permN, *permn, *permc;
    char *names;                /* "rod (y), cone (z)" for messages */
};

Kkt *
kkt_alloc(const eomc_model *m)
{
    Kkt *k = calloc(1, sizeof *k);
    if (!k)
        return NULL;
    size_t n = (size_t)m->nq, nc = (size_t)m->nc, nu = (size_t)m->nu, N = n + nc;
    k->n = m->nq, k->nc = m->nc, k->N = (int)N, k->np = m->nq - m->nc;
    k->K = sim_zeros(N * N), k->r = sim_zeros(N), k->A = sim_zeros(n * n), k->ra = sim_zeros(n);
    k->f = sim_zeros(nc), k->B = sim_zeros(nc * n), k->lam = sim_zeros(nc), k->zero = sim_zeros(n);
    k->prev_a = sim_zeros(n), k->prev_lam = sim_zeros(nc);
    k->dfdq = sim_zeros(nc * n), k->dfdv = sim_zeros(nc * n), k->dfdu = sim_zeros(nc * nu);
    k->dfdt = sim_zeros(nc);
    k->dBdq = sim_zeros(nc * n * n), k->dBdv = sim_zeros(nc * n * n), k->dBda = sim_zeros(nc * n * n);
    k->dBdu = sim_zeros(nc * n * nu), k->dBdt = sim_zeros(nc * n);
    k->BH = sim_zeros(nc * nc), k->G = sim_zeros(nc * n), k->E = sim_zeros(n);
    k->off = sim_zeros(nc), k->dposdq = sim_zeros(nc * n), k->dveldq = sim_zeros(nc * n);
    k->dveldv = sim_zeros(nc * n), k->dposdu = sim_zeros(nc * nu);
    k->dveldu = sim_zeros(nc * nu), k->dposdt = sim_zeros(nc), k->dveldt = sim_zeros(nc);
    k->dep = calloc(nc, sizeof *k->dep), k->indep = calloc(n, sizeof *k->indep);
    k->permN = gsl_permutation_alloc(N), k->permn = gsl_permutation_alloc(n);
    k->permc = gsl_permutation_alloc(nc);
    size_t len = 1;
    for (int c = 0; c < m->nc; c++)
        len += strlen(m->c_names[c]) + strlen(m->q_names[m->c_dependent[c]]) + 8;
    k->names = calloc(len, 1);
    if (!k->K || !k->r || !k->A || !k->ra || !k->f || !k->B || !k->lam || !k->zero ||
        !k->prev_a || !k->prev_lam || !k->dfdq || !k->dfdv || !k->dfdu || !k->dfdt ||
        !k->dBdq || !k->dBdv || !k->dBda || !k->dBdu || !k->dBdt || !k->BH || !k->G ||
        !k->E || !k->off || !k->dposdq || !k->dveldq || !k->dveldv || !k->dposdu ||
        !k->dveldu || !k->dposdt || !k->dveldt || !k->dep || !k->indep || !k->permN || !k->permn || !k->permc ||
        !k->names) {
        kkt_free(k);
        return NULL;
    }
    for (int c = 0; c < m->nc; c++) {
        k->dep[c] = m->c_dependent[c];
        size_t at = strlen(k->names);
        snprintf(k->names + at, len - at, "%s%s (%s)", c ? ", " : "", m->c_names[c],
                 m->q_names[k->dep[c]]);
    }
    for (int i = 0, r = 0; i < m->nq; i++) {
        int dependent = 0;
        for (int c = 0; c < m->nc; c++)
            dependent |= k->dep[c] == i;
        if (!dependent)
            k->indep[r++] = i;
    }
    return k;
}

void
kkt_free(Kkt *k)
{
    if (!k)
        return;
    void *arrays[] = {k->K, k->r, k->A, k->ra, k->f, k->B, k->lam, k->zero, k->prev_a,
                      k->prev_lam, k->dfdq, k->dfdv, k->dfdu, k->dfdt, k->dBdq, k->dBdv,
                      k->dBda, k->dBdu, k->dBdt, k->BH, k->G, k->E, k->off, k->dposdq,
                      k->dveldq, k->dveldv, k->dposdu, k->dveldu, k->dposdt, k->dveldt,
                      k->dep, k->indep, k->names};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++)
        free(arrays[i]);
    if (k->permN)
        gsl_permutation_free(k->permN);
    if (k->permn)
        gsl_permutation_free(k->permn);
    if (k->permc)
        gsl_permutation_free(k->permc);
    free(k);
}

const double *
kkt_multipliers(const Kkt *k)
{
    return k->lam;
}

int
kkt_lu_factor(double *A, int N, gsl_permutation *perm)
{
    double scale = 0;
    for (int i = 0; i < N * N; i++)
        scale = fmax(scale, fabs(A[i]));
    gsl_matrix_view Av = gsl_matrix_view_array(A, (size_t)N, (size_t)N);
    int sign;
    gsl_linalg_LU_decomp(&Av.matrix, perm, &sign);
    for (int i = 0; i < N; i++)
        if (!(fabs(A[i * N + i]) > KKT_SINGULAR_TOL * scale))
            return -1;
    return 0;
}

void
kkt_lu_solve(double *A, int N, gsl_permutation *perm, double *b)
{
    gsl_matrix_view Av = gsl_matrix_view_array(A, (size_t)N, (size_t)N);
    gsl_vector_view bv = gsl_vector_view_array(b, (size_t)N);
    gsl_linalg_LU_svx(&Av.matrix, perm, &bv.vector);
}

/* K = [M + sum_c lam_c dB_c/da, B^T; B, 0]; the Hessian term only when
 * the constraints are nonlinear in a (dBda is then current). */
static void
build_kkt(Kkt *k, const double *M, int hessian)
{
    int n = k->n, nc = k->nc, N = k->N;
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            double x = M[i * n + j];
            for (int c = 0; hessian && c < nc; c++)
                x += k->lam[c] * k->dBda[(c * n + i) * n + j];
            k->K[i * N + j] = x;
        }
        for (int c = 0; c < nc; c++)
            k->K[i * N + n + c] = k->K[(n + c) * N + i] = k->B[c * n + i];
    }
    for (int c = 0; c < nc; c++)
        for (int d = 0; d < nc; d++)
            k->K[(n + c) * N + n + d] = 0;
}

double
kkt_dot(const double *a, const double *b, int n)
{
    double d = 0;
    for (int i = 0; i < n; i++)
        d += a[i] * b[i];
    return d;
}

double
kkt_max_abs(const double *x, int n)
{
    double m = 0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(x[i]));
    return m;
}

/* Baumgarte's weights of constraint c's levels: f + *wv vel + *wp pos. */
static void
baumgarte_weights(const eomc_sim *s, int c, double *wv, double *wp)
{
    int order = s->m->c_order[c], on = s->stabilize == EOMC_STABILIZE_BAUMGARTE;
    *wv = !on ? 0 : order == 0 ? 2 * s->alpha : order == 1 ? s->alpha : 0;
    *wp = on && order == 0 ? s->beta * s->beta : 0;
}

/* k->off at (t, q, v): Baumgarte's terms, or zeros. */
static void
baumgarte_offset(eomc_sim *s, double t, const double *q, const double *v)
{
    Kkt *k = s->kkt;
    double *pos = k->r, *vel = k->ra; /* free until the solve; N, n >= nc */
    memset(k->off, 0, (size_t)k->nc * sizeof *k->off);
    if (s->stabilize != EOMC_STABILIZE_BAUMGARTE)
        return;
    s->m->c_levels(t, q, v, s->p, s->u, pos, vel);
    for (int c = 0; c < k->nc; c++) {
        double wv, wp;
        baumgarte_weights(s, c, &wv, &wp);
        k->off[c] = wv * vel[c] + wp * pos[c];
    }
}

/* What Baumgarte's terms add to df/dq, df/dv, df/du and df/dt. */
static void
baumgarte_jacobian(eomc_sim *s, double t, const double *q, const double *v)
{
    Kkt *k = s->kkt;
    int n = k->n, nu = s->nu;
    if (s->stabilize != EOMC_STABILIZE_BAUMGARTE)
        return;
    s->m->c_levels_jacobian(t, q, v, s->p, s->u, k->dposdq, k->dveldq, k->dveldv,
                            k->dposdu, k->dveldu, k->dposdt, k->dveldt);
    for (int c = 0; c < k->nc; c++) {
        double wv, wp;
        baumgarte_weights(s, c, &wv, &wp);
        for (int j = 0; j < n; j++) {
            k->dfdq[c * n + j] += wv * k->dveldq[c * n + j] + wp * k->dposdq[c * n + j];
            k->dfdv[c * n + j] += wv * k->dveldv[c * n + j];
        }
        for (int l = 0; l < nu; l++)
            k->dfdu[c * nu + l] += wv * k->dveldu[c * nu + l] + wp * k->dposdu[c * nu + l];
        k->dfdt[c] += wv * k->dveldt[c] + wp * k->dposdt[c];
    }
}

/* f (with Baumgarte's terms) and B at (t, q, v, a) into k. */
static void
eval_constraint(eomc_sim *s, double t, const double *q, const double *v, const double *a)
{
    Kkt *k = s->kkt;
    s->m->constraint(t, q, v, a, s->p, s->u, k->f, k->B);
    for (int c = 0; c < k->nc; c++)
        k->f[c] += k->off[c];
}

/* E = M a + h into k->E. */
static void
residual_E(const eomc_sim *s, const double *a)
{
    int n = s->n;
    for (int i = 0; i < n; i++) {
        double x = s->h[i];
        for (int j = 0; j < n; j++)
            x += s->M[i * n + j] * a[j];
        s->kkt->E[i] = x;
    }
}

/* One Newton step on the KKT system at (a, lam); returns 1 when the step
 * was negligible, 0 after a step, -1 if K is singular. */
static int
step_multipliers(eomc_sim *s, double t, const double *q, const double *v, double *a)
{
    Kkt *k = s->kkt;
    const eomc_model *m = s->m;
    int n = k->n, nc = k->nc, N = k->N;
    eval_constraint(s, t, q, v, a);
    if (!m->c_affine)
        m->c_jacobian(t, q, v, a, s->p, s->u, k->dfdq, k->dfdv, k->dfdu, k->dfdt,
                      k->dBdq, k->dBdv, k->dBda, k->dBdu, k->dBdt);
    build_kkt(k, s->M, !m->c_affine);
    residual_E(s, a);
    for (int i = 0; i < n; i++) {
        double x = k->E[i];
        for (int c = 0; c < nc; c++)
            x += k->B[c * n + i] * k->lam[c];
        k->r[i] = -x;
    }
    for (int c = 0; c < nc; c++)
        k->r[n + c] = -k->f[c];
    if (kkt_lu_factor(k->K, N, k->permN) != 0)
        return -1;
    kkt_lu_solve(k->K, N, k->permN, k->r);
    for (int i = 0; i < n; i++)
        a[i] += k->r[i];
    for (int c = 0; c < nc; c++)
        k->lam[c] += k->r[n + c];
    return kkt_max_abs(k->r, n) <= NEWTON_TOL * (1 + kkt_max_abs(a, n)) &&
           kkt_max_abs(k->r + n, nc) <= NEWTON_TOL * (1 + kkt_max_abs(k->lam, nc));
}

/* B_h into k->BH, factored; g = -B_h^-1 B_v into k->G [nc*np]. */
static int
null_space(Kkt *k)
{
    int n = k->n, nc = k->nc, np = k->np;
    for (int c = 0; c < nc; c++)
        for (int l = 0; l < nc; l++)
            k->BH[c * nc + l] = k->B[c * n + k->dep[l]];
    if (kkt_lu_factor(k->BH, nc, k->permc) != 0)
        return -1;
    double *x = k->E; /* free here; n >= nc entries */
    for (int r = 0; r < np; r++) {
        for (int c = 0; c < nc; c++)
            x[c] = k->B[c * n + k->indep[r]];
        kkt_lu_solve(k->BH, nc, k->permc, x);
        for (int l = 0; l < nc; l++)
            k->G[l * np + r] = -x[l];
    }
    return 0;
}

/* One (frozen-C) Newton step on [C^T E; f] = 0; 1, 0 or -1 as above, -2
 * when B_h is singular. */
static int
step_eliminate(eomc_sim *s, double t, const double *q, const double *v, double *a)
{
    Kkt *k = s->kkt;
    int n = k->n, nc = k->nc, np = k->np;
    eval_constraint(s, t, q, v, a);
    if (null_space(k) != 0)
        return -2;
    residual_E(s, a);
    for (int r = 0; r < np; r++) {
        int vi = k->indep[r];
        double e = k->E[vi];
        for (int j = 0; j < n; j++)
            k->A[r * n + j] = s->M[vi * n + j];
        for (int l = 0; l < nc; l++) {
            double g = k->G[l * np + r];
            e += g * k->E[k->dep[l]];
            for (int j = 0; j < n; j++)
                k->A[r * n + j] += g * s->M[k->dep[l] * n + j];
        }
        k->ra[r] = -e;
    }
    for (int c = 0; c < nc; c++) {
        memcpy(k->A + (np + c) * n, k->B + c * n, (size_t)n * sizeof(double));
        k->ra[np + c] = -k->f[c];
    }
    if (kkt_lu_factor(k->A, n, k->permn) != 0)
        return -1;
    kkt_lu_solve(k->A, n, k->permn, k->ra);
    for (int i = 0; i < n; i++)
        a[i] += k->ra[i];
    return kkt_max_abs(k->ra, n) <= NEWTON_TOL * (1 + kkt_max_abs(a, n));
}

/* The multipliers after elimination: B_h^T lambda = -E_h at the solution. */
static int
eliminated_multipliers(eomc_sim *s, double t, const double *q, const double *v,
                       const double *a)
{
    Kkt *k = s->kkt;
    int n = k->n, nc = k->nc;
    s->m->constraint(t, q, v, a, s->p, s->u, k->f, k->B);
    residual_E(s, a);
    for (int c = 0; c < nc; c++)
        for (int l = 0; l < nc; l++)
            k->BH[l * nc + c] = k->B[c * n + k->dep[l]]; /* transposed */
    if (kkt_lu_factor(k->BH, nc, k->permc) != 0)
        return -1;
    for (int l = 0; l < nc; l++)
        k->lam[l] = -k->E[k->dep[l]];
    kkt_lu_solve(k->BH, nc, k->permc, k->lam);
    return 0;
}

int
kkt_accel(eomc_sim *s, double t, const double *q, const double *v, double *a)
{
    Kkt *k = s->kkt;
    const eomc_model *m = s->m;
    int n = k->n, nc = k->nc, rc = 0;
    m->mass_bias(t, q, v, s->p, s->u, s->M, s->h);
    baumgarte_offset(s, t, q, v);
    int iters = m->c_affine ? 1 : NEWTON_MAX;
    if (m->c_affine || !k->have_prev) { /* one exact step from zero when affine */
        memset(a, 0, (size_t)n * sizeof *a);
        memset(k->lam, 0, (size_t)nc * sizeof *k->lam);
    } else {
        memcpy(a, k->prev_a, (size_t)n * sizeof *a);
        memcpy(k->lam, k->prev_lam, (size_t)nc * sizeof *k->lam);
    }
    for (int it = 0; it < iters && rc == 0; it++)
        rc = m->eliminate ? step_eliminate(s, t, q, v, a) : step_multipliers(s, t, q, v, a);
    if (rc == -2)
        return sim_numeric_error(s, t, q, v, "the constraints cannot be solved for their "
                                 "dependent coordinates (df/dq'' of the dependent ones is "
                                 "singular): %s", k->names);
    if (rc < 0 || (m->eliminate && eliminated_multipliers(s, t, q, v, a) != 0))
        return sim_numeric_error(s, t, q, v, "the constrained system is singular: the "
                                 "constraints %s are dependent or degenerate here",
                                 k->names);
    if (rc == 0 && !m->c_affine)
        return sim_numeric_error(s, t, q, v, "Newton's method on the constraints %s did "
                                 "not converge in %d iterations", k->names, NEWTON_MAX);
    memcpy(k->prev_a, a, (size_t)n * sizeof *a);
    memcpy(k->prev_lam, k->lam, (size_t)nc * sizeof *k->lam);
    k->have_prev = 1;
    return EOMC_OK;
}

/* dR/dx_j for column j (q_j for j < n, else v_(j-n)) into k->r. */
static void
jacobian_column(eomc_sim *s, int j)
{
    Kkt *k = s->kkt;
    int n = k->n, nc = k->nc, jj = j % n;
    const double *dE = j < n ? s->dEdq : s->dEdv, *dB = j < n ? k->dBdq : k->dBdv;
    const double *df = j < n ? k->dfdq : k->dfdv;
    for (int i = 0; i < n; i++) {
        double x = dE[i * n + jj];
        for (int c = 0; c < nc; c++)
            x += k->lam[c] * dB[(c * n + i) * n + jj];
        k->r[i] = x;
    }
    for (int c = 0; c < nc; c++)
        k->r[n + c] = df[c * n + jj];
}

/* dR/dt, with the inputs' derivatives, into k->r. */
static void
time_column(eomc_sim *s)
{
    Kkt *k = s->kkt;
    int n = k->n, nc = k->nc, nu = s->nu;
    for (int i = 0; i < n; i++) {
        double x = s->dEdt[i];
        for (int c = 0; c < nc; c++)
            x += k->lam[c] * k->dBdt[c * n + i];
        for (int l = 0; l < nu; l++) {
            double d = s->dEdu[i * nu + l];
            for (int c = 0; c < nc; c++)
                d += k->lam[c] * k->dBdu[(c * n + i) * nu + l];
            x += d * s->dudt[l];
        }
        k->r[i] = x;
    }
    for (int c = 0; c < nc; c++) {
        double x = k->dfdt[c];
        for (int l = 0; l < nu; l++)
            x += k->dfdu[c * nu + l] * s->dudt[l];
        k->r[n + c] = x;
    }
}

int
kkt_jacobian(eomc_sim *s, double t, const double *x, double *dfdx, double *dfdt)
{
    Kkt *k = s->kkt;
    const eomc_model *m = s->m;
    int n = k->n, N = k->N, W = 2 * n;
    const double *q = x, *v = x + n;
    int rc = eomc_sim_accel(s, t, q, v, s->a);
    if (rc)
        return rc;
    m->jacobian(t, q, v, s->a, s->p, s->u, s->dEdq, s->dEdv, s->dEdu, s->dEdt);
    m->c_jacobian(t, q, v, s->a, s->p, s->u, k->dfdq, k->dfdv, k->dfdu, k->dfdt, k->dBdq,
                  k->dBdv, k->dBda, k->dBdu, k->dBdt);
    baumgarte_jacobian(s, t, q, v);
    /* s->M is this state's, from kkt_accel; B is re-evaluated because a
     * Newton solve leaves the previous iterate's. */
    m->constraint(t, q, v, s->a, s->p, s->u, k->f, k->B);
    build_kkt(k, s->M, !m->c_affine);
    if (kkt_lu_factor(k->K, N, k->permN) != 0)
        return sim_numeric_error(s, t, q, v, "the constrained system is singular: the "
                                 "constraints %s are dependent or degenerate here",
                                 k->names);
    if (dfdx) {
        for (int i = 0; i < n; i++)
            for (int j = 0; j < W; j++)
                dfdx[i * W + j] = j == n + i;
        for (int j = 0; j < W; j++) {
            jacobian_column(s, j);
            kkt_lu_solve(k->K, N, k->permN, k->r);
            for (int i = 0; i < n; i++)
                dfdx[(n + i) * W + j] = -k->r[i];
        }
    }
    if (dfdt) {
        time_column(s);
        kkt_lu_solve(k->K, N, k->permN, k->r);
        for (int i = 0; i < n; i++) {
            dfdt[i] = 0;
            dfdt[n + i] = -k->r[i];
        }
    }
    return EOMC_OK;
}

void
kkt_residuals(eomc_sim *s, double t, const double *q, const double *v, const double *a,
              double *res)
{
    Kkt *k = s->kkt;
    const eomc_model *m = s->m;
    double *pos = k->r, *vel = k->ra; /* N >= nc and n > nc entries */
    m->c_levels(t, q, v, s->p, s->u, pos, vel);
    m->constraint(t, q, v, a, s->p, s->u, k->f, k->B);
    for (int c = 0; c < k->nc; c++)
        res[c] = m->c_order[c] == 0 ? pos[c] : m->c_order[c] == 1 ? vel[c] : k->f[c];
}

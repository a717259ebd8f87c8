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
 * In the speeds: q'' stands for v' [nv] throughout (a model whose speeds
 * are not its coordinates' rates has M nv x nv and B nc x nv, and its
 * derivatives by q nq columns, eomc_model.h), so n below is nv.
 *
 * The Jacobian of v'(t, q, v) follows by differentiating the
 * KKT system at the solution (it is the same function q''(x) whichever
 * way it was solved):  d(q'', lambda)/dx = -K^-1 dR/dx  with
 *     dR/dx = [dE/dx + sum_k lambda_k dB_k/dx; df/dx].
 *
 * A constrained tree has a cheaper way (eomc_model's free_accel and
 * minv; with multipliers, every f affine in q''): unit loads.  With a_f =
 * -M^-1 h its accelerations without the constraints and Y = M^-1 B^T,
 * one recursion per row of B (or, where the model keeps the recursion's
 * values between the two, free_accel_shared, one load's inward and
 * outward pass), q'' = a_f - Y lambda, and f(q'') = 0 is
 *     (B M^-1 B^T) lambda = f(a_f),
 * an nc x nc system, symmetric positive definite when M is and B has full
 * rank (GSL's pivoted Cholesky).  M is never formed: O(n nc) work where
 * the KKT system costs (n + nc)^3.  Where a pivot of M or of that system
 * fails, the same state is solved again the dense way, whose messages
 * name the cause; the condition estimate (with its near-null direction)
 * and the Jacobian, which need M, form it on demand (mass_bias) at the
 * state their caller gives, the solve's: the solve keeps no copy of it.
 * One row, the common case of one equality on an arm, is one division,
 * without the blocks and the factorization of several.
 *
 * Rows dependent on the others (kkt_set_dropped: the simulator finds
 * them at the start) are left out of every solve as though the model did
 * not have them: in K a dropped row c and its column are 0 but for a 1 on
 * the diagonal, with 0 on the right, so lambda_c = 0 and the rest is the
 * system of the kept rows, at the same size and with the same code; the
 * unit loads skip the row.  The kept rows span the dropped ones, so q''
 * meets those too (sim.c watches that they stay met).
 *
 * Baumgarte's stabilization replaces f by f + w_v vel + w_p pos (the
 * constraint's own levels from c_levels; w_v = 2 alpha, w_p = beta^2 for
 * a holonomic one, w_v = alpha for a first-order one).  The offset does
 * not depend on q'', so it is computed once per solve, and B is unchanged.
 *
 * Every array is allocated in kkt_alloc (linalg.c factors them).  The
 * functions return a status; sim.c turns it into a message.
 */
#include "kkt.h"
#include "linalg.h"
#include "state.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct Kkt {
    const eomc_model *m;
    int n, nq, nc, N, np, nu;   /* n = nv speeds, nq coordinates; N = n + nc unknowns,
                                 * np = n - nc independent */
    double *M, *h;              /* [n*n], [n] */
    double *dEdq, *dEdv, *dEdu, *dEdt;  /* the residual's partials */
    double wv_hol, wp_hol, wv_first;    /* Baumgarte's weights, 0 when off */
    int baumgarte;              /* any of them not 0 (off, k->off stays 0) */
    double *K, *r, *dK;         /* [N*N], [N], [N] K's scaling (la_kkt_scaling) */
    double *A, *ra;             /* elimination: [n*n], [n] */
    double *f, *B, *lam;        /* [nc], [nc*n], [nc] */
    double *prev_a, *prev_lam;  /* Newton's start: the last solution */
    int have_prev;
    double rel;                 /* the last Newton iterate's relative residual */
    double *save_a, *save_lam;  /* kkt_save_start's copy of them */
    int have_save;
    double *dfdq, *dfdv, *dfdu, *dfdt;         /* [nc*nq] [nc*n] [nc*nu] [nc] */
    double *dBdq, *dBdv, *dBda, *dBdu, *dBdt;  /* [nc*n*nq], [nc*n*n] x2, [nc*n*nu],
                                                * [nc*n] */
    double *BH, *G, *E;         /* [nc*nc], [nc*np], [n] */
    double *off;                /* [nc] Baumgarte's terms, else 0 */
    double *bmax;               /* [nc*n] the largest |B_ci| of the solves so far */
    double *pos, *vel;          /* [nc] the constraints' own levels */
    double *dposdq, *dveldq, *dveldv, *dposdu, *dveldu, *dposdt, *dveldt;
    int *dep, *indep;           /* [nc], [np] */
    LaLu *luN, *lun, *luc;      /* K, A, B_h (or B_h^T) */
    char *names;                /* "rod (y), cone (z)" for messages */
    /* unit loads (m->minv): Y = (M^-1 B^T)^T [nc*n], S = B M^-1 B^T
     * [nc*nc], its relative pivots and permutation [nc] */
    double *Y, *S, *Srel;
    double *Ylam;               /* [nc] the multipliers of the rows solved, in their order */
    double *shared;             /* [m->nshared] the recursion's values the load passes read */
    int *act;                   /* [nc] those rows: the constraints not held (c_held) */
    size_t *Sperm;
    /* B's nonzero columns, row by row (from c_nz; NULL: every column):
     * row c's are nzcol[nzrow[c] .. nzrow[c+1]) */
    int *nzrow, *nzcol;
    /* the blocks of S (rows coupled through M^-1: a tree's), rows in
     * block order: blk[r] a row's block (union-find), ord [nc] the rows
     * by block, bstart [nc+1] each block's first there, Sb [nc*nc] one
     * block's matrix, Sr [nc] its right-hand side */
    int *blk, *ord, *bstart;
    double *Sb, *Sr;
    int loads;                  /* the model can solve by unit loads (minv, every f
                                 * affine in q'', multipliers) */
    int shared_loads;           /* ... keeping the recursion's values (minv_shared) */
    int by_loads;               /* the last kkt_accel solved so: M not formed (its
                                 * state is the caller's, who forms M there: form_mass) */
    int dense;                  /* kkt_set_dense: never by loads */
    double pivot_loads;         /* its smallest relative pivot, of M or S */
    unsigned solves;            /* solves by unit loads so far (KKT_PIVOT_EVERY) */
    const unsigned char *drop;  /* [nc] rows left out of the solves, or NULL */
};

/* M's smallest pivot, for the condition watch, at every KKT_PIVOT_EVERY-th
 * solve by unit loads (a power of 2), as sim.c's for an unconstrained
 * model: finding it is a tenth of the loads' own work on a small arm, and
 * the test of M's pivots runs at every solve all the same. */
enum { KKT_PIVOT_EVERY = 4 };

/* A zeroed array of n doubles (at least one), or NULL. */
static double *
zeros(size_t n)
{
    return calloc(n ? n : 1, sizeof(double));
}

Kkt *
kkt_alloc(const eomc_model *m)
{
    Kkt *k = calloc(1, sizeof *k);
    if (!k)
        return NULL;
    size_t n = (size_t)eomc_nv(m), nq = (size_t)m->nq, nc = (size_t)m->nc;
    size_t nu = (size_t)m->nu, N = n + nc;
    k->m = m;
    k->loads = m->minv && m->c_affine && !m->eliminate;
    k->shared_loads = k->loads && m->free_accel_shared && m->minv_shared;
    k->n = (int)n, k->nq = m->nq, k->nc = m->nc, k->N = (int)N, k->np = (int)n - m->nc;
    k->nu = m->nu;
    double **arrays[] = {
        &k->M, &k->h, &k->dEdq, &k->dEdv, &k->dEdu, &k->dEdt, &k->K, &k->r, &k->dK,
        &k->A, &k->ra, &k->f, &k->B, &k->lam, &k->prev_a, &k->prev_lam, &k->save_a,
        &k->save_lam, &k->dfdq,
        &k->dfdv, &k->dfdu, &k->dfdt, &k->dBdq, &k->dBdv, &k->dBda, &k->dBdu, &k->dBdt,
        &k->BH, &k->G, &k->E, &k->off, &k->bmax, &k->pos, &k->vel, &k->dposdq, &k->dveldq,
        &k->dveldv, &k->dposdu, &k->dveldu, &k->dposdt, &k->dveldt,
    };
    size_t sizes[] = {
        n * n, n, n * nq, n * n, n * nu, n, N * N, N, N,
        n * n, n, nc, nc * n, nc, n, nc, n, nc, nc * nq,
        nc * n, nc * nu, nc, nc * n * nq, nc * n * n, nc * n * n, nc * n * nu, nc * n,
        nc * nc, nc * n, n, nc, nc * n, nc, nc, nc * nq, nc * nq,
        nc * n, nc * nu, nc * nu, nc, nc,
    };
    int ok = 1;
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
        ok &= (*arrays[i] = zeros(sizes[i])) != NULL;
    k->dep = calloc(nc ? nc : 1, sizeof *k->dep), k->indep = calloc(n, sizeof *k->indep);
    k->luN = la_lu_alloc((int)N), k->lun = la_lu_alloc((int)n), k->luc = la_lu_alloc((int)nc);
    k->Y = zeros(nc * n), k->S = zeros(nc * nc), k->Srel = zeros(nc);
    k->Ylam = zeros(nc), k->act = calloc(nc ? (size_t)nc : 1, sizeof *k->act);
    k->shared = zeros((size_t)m->nshared);
    k->Sperm = calloc(nc ? nc : 1, sizeof *k->Sperm);
    ok &= k->Y && k->S && k->Srel && k->Sperm;
    ok &= k->Ylam && k->act && k->shared;
    k->blk = calloc(nc + 1, sizeof *k->blk), k->ord = calloc(nc + 1, sizeof *k->ord);
    k->bstart = calloc(nc + 2, sizeof *k->bstart);
    k->Sb = zeros(nc * nc), k->Sr = zeros(nc);
    ok &= k->blk && k->ord && k->bstart && k->Sb && k->Sr;
    if (ok && m->c_nz) { /* c_nz is in increasing order: row by row */
        k->nzrow = calloc(nc + 1, sizeof *k->nzrow);
        k->nzcol = calloc((size_t)m->c_nnz + 1, sizeof *k->nzcol);
        ok &= k->nzrow && k->nzcol;
        for (int j = 0; ok && j < m->c_nnz; j++) {
            k->nzrow[m->c_nz[j] / (int)n + 1]++;
            k->nzcol[j] = m->c_nz[j] % (int)n;
        }
        for (size_t c = 0; ok && c < nc; c++)
            k->nzrow[c + 1] += k->nzrow[c];
    }
    size_t len = 1;
    char dep[STATE_NAME_MAX];
    for (int c = 0; c < m->nc; c++)
        len += strlen(m->c_names[c]) +
               strlen(kkt_dependent_name(m, c, dep, sizeof dep)) + 8;
    k->names = calloc(len, 1);
    if (!ok || !k->dep || !k->indep || !k->luN || !k->lun || !k->luc || !k->names) {
        kkt_free(k);
        return NULL;
    }
    for (int c = 0; c < m->nc; c++) {
        k->dep[c] = m->c_dependent[c];
        size_t at = strlen(k->names);
        snprintf(k->names + at, len - at, "%s%s (%s)", c ? ", " : "", m->c_names[c],
                 kkt_dependent_name(m, c, dep, sizeof dep));
    }
    for (int i = 0, r = 0; i < k->n; i++) {
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
    void *arrays[] = {
        k->M, k->h, k->dEdq, k->dEdv, k->dEdu, k->dEdt, k->K, k->r, k->dK, k->A,
        k->ra, k->f, k->B, k->lam, k->prev_a, k->prev_lam, k->save_a, k->save_lam, k->dfdq, k->dfdv, k->dfdu,
        k->dfdt, k->dBdq, k->dBdv, k->dBda, k->dBdu, k->dBdt, k->BH, k->G, k->E, k->off,
        k->bmax, k->pos, k->vel, k->dposdq, k->dveldq, k->dveldv, k->dposdu, k->dveldu,
        k->dposdt, k->dveldt, k->dep, k->indep, k->names, k->Y, k->S, k->Srel, k->Sperm,
        k->Ylam, k->act, k->nzrow, k->nzcol, k->blk, k->ord, k->bstart, k->Sb, k->Sr,
        k->shared,
    };
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++)
        free(arrays[i]);
    la_lu_free(k->luN);
    la_lu_free(k->lun);
    la_lu_free(k->luc);
    free(k);
}

void
kkt_set_dropped(Kkt *k, const unsigned char *drop)
{
    k->drop = drop;
}

/* Whether row c is left out of the solves. */
static int
dropped(const Kkt *k, int c)
{
    return k->drop && k->drop[c];
}

void
kkt_set_dense(Kkt *k, int dense)
{
    k->dense = dense;
}

void
kkt_set_baumgarte(Kkt *k, double wv_hol, double wp_hol, double wv_first)
{
    k->wv_hol = wv_hol;
    k->wp_hol = wp_hol;
    k->wv_first = wv_first;
    k->baumgarte = wv_hol != 0 || wp_hol != 0 || wv_first != 0;
    if (!k->baumgarte) /* f is the constraints' own: no offset */
        memset(k->off, 0, (size_t)k->nc * sizeof *k->off);
}

const double *
kkt_multipliers(const Kkt *k)
{
    return k->lam;
}

void
kkt_save_start(Kkt *k)
{
    memcpy(k->save_a, k->prev_a, (size_t)k->n * sizeof *k->save_a);
    memcpy(k->save_lam, k->prev_lam, (size_t)k->nc * sizeof *k->save_lam);
    k->have_save = k->have_prev;
}

void
kkt_restore_start(Kkt *k)
{
    memcpy(k->prev_a, k->save_a, (size_t)k->n * sizeof *k->prev_a);
    memcpy(k->prev_lam, k->save_lam, (size_t)k->nc * sizeof *k->prev_lam);
    k->have_prev = k->have_save;
}

const char *
kkt_names(const Kkt *k)
{
    return k->names;
}

/* K = [M + sum_c lam_c dB_c/da, B^T; B, 0]; the Hessian term only when
 * the constraints are nonlinear in a (dBda is then current). */
static void
build_kkt(Kkt *k, int hessian)
{
    int n = k->n, nc = k->nc, N = k->N;
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) {
            double x = k->M[i * n + j];
            for (int c = 0; hessian && c < nc; c++)
                x += k->lam[c] * k->dBda[(c * n + i) * n + j];
            k->K[i * N + j] = x;
        }
        for (int c = 0; c < nc; c++)
            k->K[i * N + n + c] = k->K[(n + c) * N + i] = dropped(k, c) ? 0 : k->B[c * n + i];
    }
    for (int c = 0; c < nc; c++)
        for (int d = 0; d < nc; d++)
            k->K[(n + c) * N + n + d] = c == d && dropped(k, c);
}

/* K, scaled (la_kkt_scaling), factored; 0 or -1. */
static int
factor_kkt(Kkt *k)
{
    la_kkt_scaling(k->K, k->n, k->nc, k->dK);
    return la_lu_factor_scaled(k->luN, k->K, k->dK);
}

void
kkt_baumgarte_weights(const Kkt *k, int c, double *wv, double *wp)
{
    int order = k->m->c_order[c];
    *wv = order == 0 ? k->wv_hol : order == 1 ? k->wv_first : 0;
    *wp = order == 0 ? k->wp_hol : 0;
}

/* k->off at (t, q, v): Baumgarte's terms (off, it stays 0). */
static void
baumgarte_offset(Kkt *k, double t, const double *q, const double *v, const double *p,
                 const double *u)
{
    if (!k->baumgarte)
        return;
    k->m->c_levels(t, q, v, p, u, k->pos, k->vel);
    for (int c = 0; c < k->nc; c++) {
        double wv, wp;
        kkt_baumgarte_weights(k, c, &wv, &wp);
        k->off[c] = wv * k->vel[c] + wp * k->pos[c];
    }
}

/* What Baumgarte's terms add to df/dq, df/dv, df/du and df/dt. */
static void
baumgarte_jacobian(Kkt *k, double t, const double *q, const double *v, const double *p,
                   const double *u)
{
    int n = k->n, nq = k->nq, nu = k->nu;
    if (!k->baumgarte)
        return;
    k->m->c_levels_jacobian(t, q, v, p, u, k->dposdq, k->dveldq, k->dveldv, k->dposdu,
                            k->dveldu, k->dposdt, k->dveldt);
    for (int c = 0; c < k->nc; c++) {
        double wv, wp;
        kkt_baumgarte_weights(k, c, &wv, &wp);
        for (int j = 0; j < nq; j++)
            k->dfdq[c * nq + j] += wv * k->dveldq[c * nq + j] + wp * k->dposdq[c * nq + j];
        for (int j = 0; j < n; j++)
            k->dfdv[c * n + j] += wv * k->dveldv[c * n + j];
        for (int l = 0; l < nu; l++)
            k->dfdu[c * nu + l] += wv * k->dveldu[c * nu + l] + wp * k->dposdu[c * nu + l];
        k->dfdt[c] += wv * k->dveldt[c] + wp * k->dposdt[c];
    }
}

/* f (with Baumgarte's terms) and B at (t, q, v, a) into k (inline, as
 * row_dot: both are on the unit loads' path of every right-hand side). */
static inline void
eval_constraint(Kkt *k, double t, const double *q, const double *v, const double *a,
                const double *p, const double *u)
{
    k->m->constraint(t, q, v, a, p, u, k->f, k->B);
    for (int c = 0; k->baumgarte && c < k->nc; c++)
        k->f[c] += k->off[c];
}

/* E = M a + h into k->E, and the magnitude of its terms,
 * |h_i| + sum_j |M_ij a_j|, into terms [n]. */
static void
residual_E(Kkt *k, const double *a, double *terms)
{
    int n = k->n;
    for (int i = 0; i < n; i++) {
        double e = k->h[i], mag = fabs(e);
        for (int j = 0; j < n; j++) {
            double x = k->M[i * n + j] * a[j];
            e += x;
            mag += fabs(x);
        }
        k->E[i] = e;
        terms[i] = mag;
    }
}

/* f_c relative to its terms at a: B_c a and the rest of f. */
static double
constraint_relative(const Kkt *k, int c, const double *a)
{
    int n = k->n;
    const double *Bc = k->B + c * n;
    double lin = la_dot(Bc, a, n), mag = fabs(k->f[c] - lin);
    for (int i = 0; i < n; i++)
        mag += fabs(Bc[i] * a[i]);
    return la_relative(k->f[c], mag);
}

/* One Newton step on the KKT system at (a, lam); returns 1 when (a, lam)
 * had settled (la_settled; k->rel is the last iterate's residual), 0
 * after a step, -1 if K is singular.  An affine system takes its one step
 * unconditionally. */
static int
step_multipliers(Kkt *k, double t, const double *q, const double *v, const double *p,
                 const double *u, double *a)
{
    const eomc_model *m = k->m;
    int n = k->n, nc = k->nc;
    eval_constraint(k, t, q, v, a, p, u);
    if (!m->c_affine)
        m->c_jacobian(t, q, v, a, p, u, k->dfdq, k->dfdv, k->dfdu, k->dfdt, k->dBdq,
                      k->dBdv, k->dBda, k->dBdu, k->dBdt);
    build_kkt(k, !m->c_affine);
    double *terms = k->ra; /* free here */
    residual_E(k, a, terms);
    double rel = 0;
    for (int i = 0; i < n; i++) {
        double x = k->E[i], mag = terms[i];
        for (int c = 0; c < nc; c++) {
            x += k->B[c * n + i] * k->lam[c];
            mag += fabs(k->B[c * n + i] * k->lam[c]);
        }
        k->r[i] = -x;
        rel = fmax(rel, la_relative(x, mag));
    }
    for (int c = 0; c < nc; c++) {
        k->r[n + c] = dropped(k, c) ? 0 : -k->f[c];
        if (!dropped(k, c))
            rel = fmax(rel, constraint_relative(k, c, a));
    }
    if (!m->c_affine && la_settled(rel, k->rel))
        return 1;
    k->rel = rel;
    if (factor_kkt(k) != 0)
        return -1;
    la_lu_solve(k->luN, k->r);
    for (int i = 0; i < n; i++)
        a[i] += k->r[i];
    for (int c = 0; c < nc; c++)
        k->lam[c] += k->r[n + c];
    return 0;
}

/* B_h into k->BH, factored; g = -B_h^-1 B_v into k->G [nc*np]. */
static int
null_space(Kkt *k)
{
    int n = k->n, nc = k->nc, np = k->np;
    for (int c = 0; c < nc; c++)
        for (int l = 0; l < nc; l++)
            k->BH[c * nc + l] = k->B[c * n + k->dep[l]];
    if (la_lu_factor(k->luc, k->BH) != 0)
        return -1;
    double *x = k->E; /* free here; n >= nc entries */
    for (int r = 0; r < np; r++) {
        for (int c = 0; c < nc; c++)
            x[c] = k->B[c * n + k->indep[r]];
        la_lu_solve(k->luc, x);
        for (int l = 0; l < nc; l++)
            k->G[l * np + r] = -x[l];
    }
    return 0;
}

/* One (frozen-C) Newton step on [C^T E; f] = 0; 1, 0 or -1 as above, -2
 * when B_h is singular.  Each row of C^T E is measured against its terms
 * as they enter it. */
static int
step_eliminate(Kkt *k, double t, const double *q, const double *v, const double *p,
               const double *u, double *a)
{
    int n = k->n, nc = k->nc, np = k->np;
    eval_constraint(k, t, q, v, a, p, u);
    if (null_space(k) != 0)
        return -2;
    double *terms = k->r; /* free here; N >= n entries */
    residual_E(k, a, terms);
    double rel = 0;
    for (int r = 0; r < np; r++) {
        int vi = k->indep[r];
        double e = k->E[vi], mag = terms[vi];
        for (int j = 0; j < n; j++)
            k->A[r * n + j] = k->M[vi * n + j];
        for (int l = 0; l < nc; l++) {
            double g = k->G[l * np + r];
            e += g * k->E[k->dep[l]];
            mag += fabs(g) * terms[k->dep[l]];
            for (int j = 0; j < n; j++)
                k->A[r * n + j] += g * k->M[k->dep[l] * n + j];
        }
        k->ra[r] = -e;
        rel = fmax(rel, la_relative(e, mag));
    }
    for (int c = 0; c < nc; c++) {
        memcpy(k->A + (np + c) * n, k->B + c * n, (size_t)n * sizeof(double));
        k->ra[np + c] = -k->f[c];
        rel = fmax(rel, constraint_relative(k, c, a));
    }
    if (!k->m->c_affine && la_settled(rel, k->rel))
        return 1;
    k->rel = rel;
    if (la_lu_factor(k->lun, k->A) != 0)
        return -1;
    la_lu_solve(k->lun, k->ra);
    for (int i = 0; i < n; i++)
        a[i] += k->ra[i];
    return 0;
}

/* The multipliers after elimination: B_h^T lambda = -E_h at the solution. */
static int
eliminated_multipliers(Kkt *k, double t, const double *q, const double *v,
                       const double *a, const double *p, const double *u)
{
    int n = k->n, nc = k->nc;
    k->m->constraint(t, q, v, a, p, u, k->f, k->B);
    residual_E(k, a, k->r);
    for (int c = 0; c < nc; c++)
        for (int l = 0; l < nc; l++)
            k->BH[l * nc + c] = k->B[c * n + k->dep[l]]; /* transposed */
    if (la_lu_factor(k->luc, k->BH) != 0)
        return -1;
    for (int l = 0; l < nc; l++)
        k->lam[l] = -k->E[k->dep[l]];
    la_lu_solve(k->luc, k->lam);
    return 0;
}

/* B_c . y over B's nonzero columns (the same sum as la_dot: the rest are
 * exact zeros). */
static inline double
row_dot(const Kkt *k, int c, const double *y)
{
    const double *b = k->B + (size_t)c * k->n;
    if (!k->nzrow)
        return la_dot(b, y, k->n);
    double d = 0;
    for (int j = k->nzrow[c]; j < k->nzrow[c + 1]; j++)
        d += b[k->nzcol[j]] * y[k->nzcol[j]];
    return d;
}

static int
root(int *up, int x)
{
    while (up[x] != x)
        x = up[x] = up[up[x]];
    return x;
}

/* The blocks of S's na rows: rows r and d in one where S_rd is not 0.
 * M^-1 couples only the coordinates of one tree, and a unit load's
 * recursion leaves the other trees' at exactly 0, so independent trees'
 * rows are blocks of their own, solved apart.  k->ord: the rows by block,
 * each block's in increasing order; start[b] its first; the count. */
static int
blocks(Kkt *k, int na, int *start)
{
    int *up = k->blk, nb = 0;
    for (int r = 0; r < na; r++)
        up[r] = r;
    for (int r = 0; r < na; r++)
        for (int d = 0; d < r; d++)
            if (k->S[r * na + d] != 0) {
                int a = root(up, r), b = root(up, d);
                if (a != b)
                    up[a > b ? a : b] = a < b ? a : b;
            }
    int at = 0;
    for (int r = 0; r < na; r++) /* roots are their block's least row */
        if (root(up, r) == r) {
            start[nb++] = at;
            for (int d = r; d < na; d++)
                if (root(up, d) == r)
                    k->ord[at++] = d;
        }
    start[nb] = at;
    return nb;
}

/* Ylam = S^-1 Ylam, block by block where S has several (blocks()); Srel
 * the relative pivots.  0, or -1 where a pivot fails. */
static int
solve_blocks(Kkt *k, int na)
{
    int *start = k->bstart;
    if (na == 0)
        return 0;
    int nb = blocks(k, na, start);
    if (nb <= 1) {
        if (la_ldlt_factor(k->S, na, k->Srel, k->Sperm) != 0)
            return -1;
        la_ldlt_solve(k->S, na, k->Sperm, k->Ylam);
        return 0;
    }
    for (int b = 0; b < nb; b++) {
        int s0 = start[b], w = start[b + 1] - s0;
        for (int i = 0; i < w; i++) {
            k->Sr[i] = k->Ylam[k->ord[s0 + i]];
            for (int j = 0; j < w; j++)
                k->Sb[i * w + j] = k->S[k->ord[s0 + i] * na + k->ord[s0 + j]];
        }
        if (la_ldlt_factor(k->Sb, w, k->Srel + s0, k->Sperm + s0) != 0)
            return -1;
        la_ldlt_solve(k->Sb, w, k->Sperm + s0, k->Sr);
        for (int i = 0; i < w; i++)
            k->Ylam[k->ord[s0 + i]] = k->Sr[i];
    }
    return 0;
}

/* solve_loads' one row, k->act[0] (an arm's one equality), after the
 * free solve: S is a number, so no blocks to find and no calls to factor
 * it; the same operations as for several rows, so the same bits.  pivot:
 * M's, or 1. */
static int
solve_row(Kkt *k, double t, const double *q, const double *v, const double *p,
          const double *u, double *a, double pivot)
{
    const eomc_model *m = k->m;
    int n = k->n, c = k->act[0];
    const double *b = k->B + (size_t)c * n;
    double *y = k->Y;
    if (k->shared_loads)
        m->minv_shared(t, q, v, p, u, k->shared, b, y);
    else
        m->minv(t, q, v, p, u, b, y);
    double s = row_dot(k, c, y);
    if (!(s > EOMC_PIVOT_TOL * s)) /* la_ldlt_factor's test of one pivot */
        return -1;
    double lam = k->lam[c] = k->f[c] / s;
    for (int i = 0; i < n; i++)
        a[i] -= y[i] * lam;
    k->pivot_loads = pivot < 1 ? pivot : 1; /* a 1 x 1 S's relative pivot is 1 */
    return 0;
}

/* q'' and the multipliers by unit loads (the top of this file); 0, or -1
 * when a pivot of M or of B M^-1 B^T fails (a left as garbage).  M is
 * not formed, nor the state kept: form_mass has it from the caller. */
static int
solve_loads(Kkt *k, double t, const double *q, const double *v, const double *p,
            const double *u, double *a)
{
    const eomc_model *m = k->m;
    int n = k->n, nc = k->nc, na = 0;
    double pivot = 1;
    /* the recursion once, its values kept for the load passes, where the
     * model can (eomc_model.h's free_accel_shared) */
    int shared = k->shared_loads;
    double *want = (++k->solves & (KKT_PIVOT_EVERY - 1)) == 0 ? &pivot : NULL;
    if ((shared ? m->free_accel_shared(t, q, v, p, u, a, want, k->shared)
                : m->free_accel(t, q, v, p, u, a, want)) != 0)
        return -1;
    eval_constraint(k, t, q, v, a, p, u); /* f(a_f) and B */
    /* the rows the recursion does not hold by itself (c_held): a ball's
     * unit constraint is met by a_f, its multiplier 0; not with
     * Baumgarte's terms, which ask more of the row than its own level */
    int baumgarte = k->baumgarte;
    for (int c = 0; c < nc; c++)
        if ((!m->c_held || !m->c_held[c] || baumgarte) && !dropped(k, c))
            k->act[na++] = c;
        else
            k->lam[c] = 0;
    if (na == 1)
        return solve_row(k, t, q, v, p, u, a, pivot);
    for (int r = 0; r < na; r++)
        if (shared)
            m->minv_shared(t, q, v, p, u, k->shared, k->B + k->act[r] * n, k->Y + r * n);
        else
            m->minv(t, q, v, p, u, k->B + k->act[r] * n, k->Y + r * n);
    for (int r = 0; r < na; r++)
        for (int d = 0; d <= r; d++)
            k->S[r * na + d] = k->S[d * na + r] = row_dot(k, k->act[r], k->Y + d * n);
    for (int r = 0; r < na; r++)
        k->Ylam[r] = k->f[k->act[r]];
    if (solve_blocks(k, na) != 0)
        return -1;
    for (int r = 0; r < na; r++) {
        k->lam[k->act[r]] = k->Ylam[r];
        if (k->Srel[r] < pivot)
            pivot = k->Srel[r];
        for (int i = 0; i < n; i++)
            a[i] -= k->Y[r * n + i] * k->Ylam[r];
    }
    k->pivot_loads = pivot;
    return 0;
}

/* After a solve by unit loads, which did not form it: M (and h) at its
 * state (t, q, v, p, u), the caller's, and 1; else 0 (the last dense
 * solve's are current). */
static int
form_mass(Kkt *k, double t, const double *q, const double *v, const double *p,
          const double *u)
{
    if (!k->by_loads)
        return 0;
    k->by_loads = 0;
    k->m->mass_bias(t, q, v, p, u, k->M, k->h);
    return 1;
}

/* q'' and the multipliers by the KKT system (or elimination), M formed;
 * KKT_OK or the failure. */
static int
solve_dense(Kkt *k, double t, const double *q, const double *v, const double *p,
            const double *u, double *a)
{
    const eomc_model *m = k->m;
    int n = k->n, nc = k->nc, rc = 0;
    m->mass_bias(t, q, v, p, u, k->M, k->h);
    int iters = m->c_affine ? 1 : KKT_NEWTON_MAX + 1; /* the next tests a step */
    k->rel = HUGE_VAL;
    if (m->c_affine || !k->have_prev) { /* one exact step from zero when affine */
        memset(a, 0, (size_t)n * sizeof *a);
        memset(k->lam, 0, (size_t)nc * sizeof *k->lam);
    } else {
        memcpy(a, k->prev_a, (size_t)n * sizeof *a);
        memcpy(k->lam, k->prev_lam, (size_t)nc * sizeof *k->lam);
    }
    for (int it = 0; it < iters && rc == 0; it++)
        rc = m->eliminate ? step_eliminate(k, t, q, v, p, u, a)
                          : step_multipliers(k, t, q, v, p, u, a);
    if (rc == -2)
        return KKT_DEPENDENT;
    if (rc < 0 || (m->eliminate && eliminated_multipliers(k, t, q, v, a, p, u) != 0))
        return KKT_SINGULAR;
    if (rc == 0 && !m->c_affine)
        return KKT_NEWTON;
    return KKT_OK;
}

/* bmax[i], B's entry i at its largest so far (a loop per case, not a
 * test per entry: this is every right-hand side's) */
static inline void
watch_entry(Kkt *k, int i)
{
    double b = fabs(k->B[i]);
    k->bmax[i] = b > k->bmax[i] ? b : k->bmax[i];
}

int
kkt_accel(Kkt *k, double t, const double *q, const double *v, const double *p,
          const double *u, double *a)
{
    const eomc_model *m = k->m;
    int n = k->n, nc = k->nc, rc;
    baumgarte_offset(k, t, q, v, p, u);
    k->by_loads = k->loads && !k->dense && solve_loads(k, t, q, v, p, u, a) == 0;
    if (!k->by_loads && (rc = solve_dense(k, t, q, v, p, u, a)) != KKT_OK)
        return rc;
    if (!m->c_affine) { /* Newton's next start (an affine system starts from 0) */
        memcpy(k->prev_a, a, (size_t)n * sizeof *a);
        memcpy(k->prev_lam, k->lam, (size_t)nc * sizeof *k->lam);
        k->have_prev = 1;
    }
    /* (the entries that can be nonzero: a dense pass over nc n would cost
     * more than the recursion on a model of many free bodies) */
    if (m->c_nz)
        for (int j = 0; j < m->c_nnz; j++)
            watch_entry(k, m->c_nz[j]);
    else
        for (int i = 0; i < nc * n; i++)
            watch_entry(k, i);
    return KKT_OK;
}

/* The factorization that gave q'': the KKT matrix, or elimination's. */
static LaLu *
solved_lu(const Kkt *k)
{
    return k->m->eliminate ? k->lun : k->luN;
}

double
kkt_condition(Kkt *k, double t, const double *q, const double *v, const double *p,
              const double *u)
{
    if (form_mass(k, t, q, v, p, u)) {
        build_kkt(k, 0);
        factor_kkt(k);
    }
    return la_lu_condition(solved_lu(k));
}

void
kkt_near_null(Kkt *k, double *y)
{
    memset(y, 0, (size_t)k->N * sizeof *y);
    if (!k->by_loads) /* else no factorization is this solve's: y stays 0 */
        la_lu_near_null(solved_lu(k), y);
}

double
kkt_pivot(const Kkt *k)
{
    return k->by_loads ? k->pivot_loads : la_lu_pivot(solved_lu(k));
}

int
kkt_vanished(const Kkt *k, double *fraction)
{
    int n = k->n;
    for (int c = 0; c < k->nc; c++) {
        double worst = 0;
        int seen = 0;
        if (dropped(k, c))
            continue;
        for (int i = 0; i < n; i++)
            if (k->bmax[c * n + i] > 0) {
                seen = 1;
                worst = fmax(worst, fabs(k->B[c * n + i]) / k->bmax[c * n + i]);
            }
        if (seen && worst <= KKT_VANISHED) {
            *fraction = worst;
            return c;
        }
    }
    return -1;
}

/* dR/dx_j for column j (q_j for j < nq, else v_(j-nq)) into k->r. */
static void
jacobian_column(Kkt *k, int j)
{
    int n = k->n, nc = k->nc, byq = j < k->nq, jj = byq ? j : j - k->nq;
    int w = byq ? k->nq : n; /* the derivatives' columns */
    const double *dE = byq ? k->dEdq : k->dEdv, *dB = byq ? k->dBdq : k->dBdv;
    const double *df = byq ? k->dfdq : k->dfdv;
    for (int i = 0; i < n; i++) {
        double x = dE[i * w + jj];
        for (int c = 0; c < nc; c++)
            x += k->lam[c] * dB[(c * n + i) * w + jj];
        k->r[i] = x;
    }
    for (int c = 0; c < nc; c++)
        k->r[n + c] = dropped(k, c) ? 0 : df[c * w + jj];
}

/* dR/dt, with the inputs' derivatives, into k->r. */
static void
time_column(Kkt *k, const double *dudt)
{
    int n = k->n, nc = k->nc, nu = k->nu;
    for (int i = 0; i < n; i++) {
        double x = k->dEdt[i];
        for (int c = 0; c < nc; c++)
            x += k->lam[c] * k->dBdt[c * n + i];
        for (int l = 0; l < nu; l++) {
            double d = k->dEdu[i * nu + l];
            for (int c = 0; c < nc; c++)
                d += k->lam[c] * k->dBdu[(c * n + i) * nu + l];
            x += d * dudt[l];
        }
        k->r[i] = x;
    }
    for (int c = 0; c < nc; c++) {
        double x = k->dfdt[c];
        for (int l = 0; l < nu; l++)
            x += k->dfdu[c * nu + l] * dudt[l];
        k->r[n + c] = dropped(k, c) ? 0 : x;
    }
}

int
kkt_jacobian(Kkt *k, double t, const double *x, const double *p, const double *u,
             const double *dudt, const double *a, double *dfdx, double *dfdt)
{
    const eomc_model *m = k->m;
    int n = k->n, nq = k->nq, W = nq + n;
    const double *q = x, *v = x + nq;
    form_mass(k, t, q, v, p, u); /* after unit loads; K is built and factored below */
    m->jacobian(t, q, v, a, p, u, k->dEdq, k->dEdv, k->dEdu, k->dEdt);
    m->c_jacobian(t, q, v, a, p, u, k->dfdq, k->dfdv, k->dfdu, k->dfdt, k->dBdq, k->dBdv,
                  k->dBda, k->dBdu, k->dBdt);
    baumgarte_jacobian(k, t, q, v, p, u);
    /* k->M is this state's, from kkt_accel; B is re-evaluated because a
     * Newton solve leaves the previous iterate's. */
    m->constraint(t, q, v, a, p, u, k->f, k->B);
    build_kkt(k, !m->c_affine);
    if (factor_kkt(k) != 0)
        return KKT_SINGULAR;
    if (dfdx)
        for (int j = 0; j < W; j++) {
            jacobian_column(k, j);
            la_lu_solve(k->luN, k->r);
            for (int i = 0; i < n; i++)
                dfdx[(nq + i) * W + j] = -k->r[i];
        }
    if (dfdt) {
        time_column(k, dudt);
        la_lu_solve(k->luN, k->r);
        for (int i = 0; i < n; i++)
            dfdt[nq + i] = -k->r[i];
    }
    return KKT_OK;
}

void
kkt_residuals(Kkt *k, double t, const double *q, const double *v, const double *a,
              const double *p, const double *u, double *res)
{
    const eomc_model *m = k->m;
    m->c_levels(t, q, v, p, u, k->pos, k->vel);
    m->constraint(t, q, v, a, p, u, k->f, k->B);
    for (int c = 0; c < k->nc; c++)
        res[c] = m->c_order[c] == 0 ? k->pos[c] : m->c_order[c] == 1 ? k->vel[c] : k->f[c];
}

const double *
kkt_rows(const Kkt *k)
{
    return k->B;
}

const char *
kkt_dependent_name(const eomc_model *m, int c, char *buf, size_t len)
{
    if (m->nv > 0)
        return state_speed(m, m->c_dependent[c], buf, len);
    snprintf(buf, len, "%s", m->q_names[m->c_dependent[c]]);
    return buf;
}

/*
 * project: move a state back onto its constraints.
 *
 * Positions go onto the holonomic constraints g(t, q) = 0, then
 * velocities onto every velocity-level one (g' for holonomic, phi for
 * first order), each by Gauss-Newton in the metric of the mass matrix:
 * the smallest change dq^T M dq that satisfies the linearized
 * constraints,
 *     dq = -M^-1 G^T (G M^-1 G^T)^-1 r,
 * with G the rows of B = df/dq'' that belong to the level (B is dg/dq for
 * a holonomic constraint and dphi/dq' for a first-order one, so the model
 * already supplies it).  The kinetic-energy metric makes the correction
 * what a constraint impulse would do, independent of the coordinates'
 * units.  M is taken once, at the state given.
 *
 * In the speeds (eomc.h): with speeds that are not the coordinates' rates,
 * M is nv x nv and G's rows are dg/dq W(q), so the position correction is
 * a displacement d of the speeds' space, moved into the coordinates as
 * dq = W(q) d (q' = W(q) v for a motion of d in unit time), each unit
 * quaternion then renormalized (the exact positions have |e| = 1; the
 * correction is tangent to it, to first order).  Holding coordinates
 * holds the speeds that move only them (hold_speeds).  A position's
 * residual is measured against g's terms dg/dq_i q_i from
 * c_levels_jacobian's gradient, where B (dg/dq W) gives no such terms.
 *
 * Second-order constraints have nothing below acceleration level and are
 * left alone.  Rows left out of the solves (proj_set_dropped) are left out
 * of the corrections too, and of the test that they have settled: the kept
 * rows span them; their residuals are still measured with the others'.
 */
#include "project.h"
#include "linalg.h"
#include "state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct Proj {
    const eomc_model *m;
    int n, nq, nc;             /* n = nv: the speeds (n below), nq coordinates */
    int npos, nvel;            /* rows at each level */
    int *pos_rows, *vel_rows;  /* [nc] constraint indices */
    int nfix[2], *fix_rows[2]; /* each level's rows the corrections use: [nc]
                                * the kept ones of pos_rows, vel_rows */
    double *M, *h;             /* [n*n] the mass matrix (the metric), [n] */
    double *L;                 /* [n*n] the pivoted LDL^T factor of M on what moves */
    double *F, *Frel;          /* [n*n] that of the whole M when L is not, [n] */
    size_t *Fperm;             /* [n] */
    int full;                  /* F: -1 not yet factored for this M, 0 failed, 1 holds it */
    double *rel;               /* [n] its pivots relative to M_kk */
    size_t *perm;              /* [n] its pivot order */
    int *moves, nmoves;        /* [n] the coordinates (or velocities) a level moves */
    double *col;               /* [n] one solve's right-hand side, on those */
    const unsigned char *hold; /* [2n] what stays: the speeds whose positions (then
                                * whose velocities) the corrections keep, or NULL */
    unsigned char *hv;         /* [2n] hold_speeds' (hold points here or is NULL) */
    double *w, *dq;            /* [n] a direction of the speeds, [nq] W(q) times it */
    int held_q, held_v;        /* hold_speeds' refusal: a held coordinate, a speed
                                * not held that moves it */
    int factored;              /* L holds M on moves, for this proj_apply */
    double vMv0;               /* v^T M v at the start of a velocity projection: the
                                * scale of its rounding (0 outside one) */
    double *f, *B;             /* [nc], [nc*n] */
    double *pos, *vel, *zero;  /* [nc], [nc], [n] */
    double *scale;             /* [nc] the magnitude of each g_k's terms (c_scale) */
    /* with speeds of their own, g's gradient dg/dq [nc*nq] from
     * c_levels_jacobian (NULL without it), for g's terms dg/dq_i q_i as B
     * gives them where the speeds are the rates; and its other outputs */
    double *dgdq, *lj;
    double *Y, *S, *mu;        /* [nc*n] rows M^-1 G_r^T, [nc*nc], [nc] */
    LaLu *lu[2];               /* G M^-1 G^T at each level */
    char *names[2];            /* constraint names of each level, for messages */
};

static double *
zeros(size_t n)
{
    return calloc(n ? n : 1, sizeof(double));
}

static char *
join_names(const eomc_model *m, const int *rows, int nr)
{
    size_t len = 1;
    for (int r = 0; r < nr; r++)
        len += strlen(m->c_names[rows[r]]) + 2;
    char *s = calloc(len, 1);
    for (int r = 0; s && r < nr; r++) {
        if (r)
            strcat(s, ", ");
        strcat(s, m->c_names[rows[r]]);
    }
    return s;
}

Proj *
proj_alloc(const eomc_model *m)
{
    Proj *j = calloc(1, sizeof *j);
    if (!j)
        return NULL;
    size_t n = (size_t)eomc_nv(m), nq = (size_t)m->nq, nc = (size_t)m->nc;
    j->m = m;
    j->n = (int)n, j->nq = m->nq, j->nc = m->nc;
    j->hv = calloc(2 * n, 1), j->w = zeros(n), j->dq = zeros(nq);
    j->pos_rows = calloc(nc, sizeof(int)), j->vel_rows = calloc(nc, sizeof(int));
    j->fix_rows[0] = calloc(nc, sizeof(int)), j->fix_rows[1] = calloc(nc, sizeof(int));
    j->L = zeros(n * n), j->h = zeros(n), j->f = zeros(nc);
    j->M = zeros(n * n), j->col = zeros(n), j->moves = calloc(n ? n : 1, sizeof *j->moves);
    j->B = zeros(nc * n), j->pos = zeros(nc), j->vel = zeros(nc), j->scale = zeros(nc);
    /* dg/dq, then c_levels_jacobian's other outputs: dveldq, dveldv, dposdu,
     * dveldu, dposdt, dveldt */
    size_t nu = (size_t)m->nu, lj = nc * nq + nc * n + 2 * nc * nu + 2 * nc;
    int gradient = m->nv > 0 && m->c_levels_jacobian;
    if (gradient)
        j->dgdq = zeros(nc * nq + lj);
    j->lj = j->dgdq ? j->dgdq + nc * nq : NULL;
    j->zero = zeros(n), j->Y = zeros(nc * n), j->S = zeros(nc * nc);
    j->mu = zeros(nc), j->rel = zeros(n), j->perm = calloc(n ? n : 1, sizeof *j->perm);
    j->F = zeros(n * n), j->Frel = zeros(n), j->Fperm = calloc(n ? n : 1, sizeof *j->Fperm);
    if (j->pos_rows && j->vel_rows)
        for (int c = 0; c < m->nc; c++) {
            if (m->c_order[c] == 0)
                j->pos_rows[j->npos++] = c;
            if (m->c_order[c] <= 1)
                j->vel_rows[j->nvel++] = c;
        }
    if (!j->pos_rows || !j->vel_rows || !j->fix_rows[0] || !j->fix_rows[1] || !j->L ||
        !j->h || !j->f || !j->B || !j->pos || !j->vel || !j->zero || !j->Y || !j->S ||
        !j->mu || !j->rel || !j->perm || !j->F || !j->Frel || !j->Fperm || !j->M ||
        !j->col || !j->moves || !j->hv || !j->w || !j->dq || (gradient && !j->dgdq) ||
        proj_set_dropped(j, NULL) != 0) {
        proj_free(j);
        return NULL;
    }
    return j;
}

void
proj_free(Proj *j)
{
    if (!j)
        return;
    void *arrays[] = {j->pos_rows, j->vel_rows, j->fix_rows[0], j->fix_rows[1], j->L, j->h, j->f, j->B, j->pos,
                      j->vel, j->scale, j->zero, j->Y, j->S, j->mu, j->rel, j->perm, j->F, j->Frel,
                      j->Fperm, j->M, j->col,
                      j->moves, j->names[0], j->names[1], j->hv, j->w, j->dq, j->dgdq};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++)
        free(arrays[i]);
    la_lu_free(j->lu[0]);
    la_lu_free(j->lu[1]);
    free(j);
}

int
proj_set_dropped(Proj *j, const unsigned char *drop)
{
    for (int level = 0; level < 2; level++) {
        int nr = level ? j->nvel : j->npos, nf = 0;
        const int *rows = level ? j->vel_rows : j->pos_rows;
        for (int k = 0; k < nr; k++)
            if (!drop || !drop[rows[k]])
                j->fix_rows[level][nf++] = rows[k];
        j->nfix[level] = nf;
        la_lu_free(j->lu[level]);
        free(j->names[level]);
        j->lu[level] = la_lu_alloc(nf);
        j->names[level] = join_names(j->m, j->fix_rows[level], nf);
        if (!j->lu[level] || !j->names[level])
            return -1;
    }
    return 0;
}

const int *
proj_rows(const Proj *j, int level, int *nr)
{
    *nr = j->nfix[level != 0];
    return j->fix_rows[level != 0];
}

int
proj_levels(const Proj *j)
{
    return j->nvel > 0;
}

const char *
proj_names(const Proj *j, int level)
{
    return j->names[level != 0];
}

/* |r_k| over the magnitude of its terms at x (q for positions, v for
 * velocities): sum_i |B_ki x_i|, or bound when larger (positions: the
 * magnitude of g_k's own terms, c_scale; velocities: below), and the
 * rest of r_k.  B's row is the constraint's gradient in x, so this is
 * r_k's size against what the state contributes to it.  0 when r_k is
 * exactly 0. */
static double
relative_residual(const double *Bk, const double *x, int n, double rk, double bound)
{
    double lin = la_dot(Bk, x, n), terms = 0;
    for (int i = 0; i < n; i++)
        terms += fabs(Bk[i] * x[i]);
    return la_relative(rk, fabs(rk - lin) + fmax(terms, bound));
}

/* A factor of the whole of M: the level's metric when it is all of M
 * (nothing held), else one of its own, made once for each M.  NULL when
 * M is not positive definite. */
static double *
whole_factor(Proj *j, size_t **perm)
{
    int n = j->n;
    if (j->factored && j->nmoves == n) {
        *perm = j->perm;
        return j->L;
    }
    if (j->full < 0) {
        memcpy(j->F, j->M, (size_t)n * n * sizeof *j->F);
        j->full = la_ldlt_factor(j->F, n, j->Frel, j->Fperm) == 0;
    }
    *perm = j->Fperm;
    return j->full ? j->F : NULL;
}

/* The most B_k v can be for a motion of v's kinetic energy, given as
 * v^T M v: |B_k v| <= sqrt(B_k M^-1 B_k^T) sqrt(v^T M v) (Cauchy-Schwarz
 * in the mass matrix's metric, so free of the coordinates' units).  The
 * terms B_ki v_i alone are no scale for a velocity constraint: a state
 * that satisfies it has v along the constraint, and where each term
 * vanishes too (a Cartesian pendulum at the bottom: x = 0 and y' = 0)
 * rounding would look like a violation of 100%.  With it, a linear
 * velocity constraint's relative residual is the cosine of the angle
 * between v and the constraint's normal in that metric.  0 when M is not
 * positive definite, leaving the terms. */
static double
velocity_bound(Proj *j, const double *Bk, double vMv)
{
    size_t *perm;
    double *LDL = whole_factor(j, &perm);
    if (!LDL)
        return 0;
    memcpy(j->col, Bk, (size_t)j->n * sizeof *j->col);
    la_ldlt_solve(LDL, j->n, perm, j->col);
    return sqrt(fmax(la_dot(Bk, j->col, j->n), 0) * fmax(vMv, 0));
}

/* c_levels and B at (t, q, v) into j. */
static void
levels(Proj *j, double t, const double *q, const double *v, const double *p,
       const double *u)
{
    const eomc_model *m = j->m;
    m->c_levels(t, q, v, p, u, j->pos, j->vel);
    m->constraint(t, q, v, j->zero, p, u, j->f, j->B);
    if (m->c_scale)
        m->c_scale(t, q, p, u, j->scale);
    if (j->dgdq) { /* dposdq, dveldq, dveldv, dposdu, dveldu, dposdt, dveldt */
        size_t nc = (size_t)j->nc, nq = (size_t)j->nq, nu = (size_t)m->nu;
        double *d = j->lj;
        m->c_levels_jacobian(t, q, v, p, u, j->dgdq, d, d + nc * nq, d + nc * (nq + j->n),
                             d + nc * (nq + j->n + nu), d + nc * (nq + j->n + 2 * nu),
                             d + nc * (nq + j->n + 2 * nu + 1));
    }
}

/* The largest relative residual of a level's rows (fix: the kept ones
 * alone), its row into *worst; each row's into each [nc] (at the
 * constraint's index) unless NULL. */
static double
level_residual(Proj *j, const double *q, const double *v, int level, int fix, int *worst,
               double *each)
{
    int nr = fix ? j->nfix[level] : level ? j->nvel : j->npos;
    const int *rows = fix ? j->fix_rows[level] : level ? j->vel_rows : j->pos_rows;
    const double *x = level ? v : q, *r = level ? j->vel : j->pos;
    /* with speeds of their own, B's rows are not dg/dq: g's terms are
     * dg/dq_i q_i from c_levels_jacobian's gradient, else c_scale's alone */
    int own = !level && j->m->nv > 0;
    /* a projection that takes every velocity to 0 (a wheel held still
     * stops the bicycle) ends in rounding of the velocities it started
     * from, not of the zeros it reached */
    double big = 0, vMv = level ? fmax(la_quadratic(j->M, v, j->n), j->vMv0) : 0;
    for (int k = 0; k < nr; k++) {
        const double *Bk = j->B + rows[k] * j->n, *Gk = Bk;
        int len = !own ? j->n : j->dgdq ? j->nq : 0;
        if (own && j->dgdq)
            Gk = j->dgdq + rows[k] * j->nq;
        double e = relative_residual(Gk, x, len, r[rows[k]],
                                     level ? velocity_bound(j, Bk, vMv) : j->scale[rows[k]]);
        if (each)
            each[rows[k]] = e;
        if (e > big || (k == 0 && worst)) {
            big = e;
            if (worst)
                *worst = rows[k];
        }
    }
    return big;
}

double
proj_residual(Proj *j, double t, const double *q, const double *v, const double *p,
              const double *u)
{
    double r = 0;
    if (j->nvel == 0)
        return 0;
    j->m->c_levels(t, q, v, p, u, j->pos, j->vel);
    for (int k = 0; k < j->npos; k++)
        r = fmax(r, fabs(j->pos[j->pos_rows[k]]));
    for (int k = 0; k < j->nvel; k++)
        r = fmax(r, fabs(j->vel[j->vel_rows[k]]));
    return r;
}

double
proj_inconsistency(Proj *j, double t, const double *q, const double *v, const double *p,
                   const double *u, int *worst, int *level)
{
    return proj_inconsistencies(j, t, q, v, p, u, worst, level, NULL, NULL);
}

double
proj_inconsistencies(Proj *j, double t, const double *q, const double *v, const double *p,
                     const double *u, int *worst, int *level, double *each, int *each_level)
{
    int w0 = -1, w1 = -1;
    *worst = -1, *level = 0;
    for (int k = 0; k < j->nc && each; k++)
        each[k] = 0;
    for (int k = 0; k < j->nc && each_level; k++)
        each_level[k] = 0;
    if (j->nvel == 0)
        return 0;
    levels(j, t, q, v, p, u);
    j->m->mass_bias(t, q, v, p, u, j->M, j->h);
    j->factored = 0, j->full = -1; /* a new M: no factor of it yet */
    double e0 = j->npos ? level_residual(j, q, v, 0, 0, &w0, each) : 0;
    /* a holonomic constraint's g' after its g: the larger of the two is its
     * inconsistency (mu is a projection's scratch, free here) */
    double *e1s = each ? j->mu : NULL;
    double e1 = level_residual(j, q, v, 1, 0, &w1, e1s);
    for (int r = 0; r < j->nvel && each; r++) {
        int k = j->vel_rows[r];
        int pos = j->m->c_order[k] == 0;
        if (!pos || e1s[k] > each[k]) {
            each[k] = e1s[k];
            if (each_level)
                each_level[k] = 1;
        }
    }
    *level = !(e0 >= e1 && w0 >= 0);
    *worst = *level ? w1 : w0;
    return fmax(e0, e1);
}

/* One Gauss-Newton correction of x (q at level 0, v at level 1): 1 when
 * the level's constraints have settled (la_settled, from *rel, the last
 * iterate's relative residual), 0 after a correction, -1 when G M^-1 G^T
 * is singular. */
static int
correct(Proj *j, double t, double *q, double *v, const double *p, const double *u,
        int level, double *rel)
{
    int n = j->n, nr = j->nfix[level];
    const int *rows = j->fix_rows[level];
    double *x = level ? v : q, *r = level ? j->vel : j->pos;
    levels(j, t, q, v, p, u);
    double now = level_residual(j, q, v, level, 1, NULL, NULL);
    if (la_settled(now, *rel))
        return 1;
    *rel = now;
    for (int k = 0; k < nr; k++) { /* y = M^-1 G_k^T on what moves, 0 on what is held */
        double *y = j->Y + k * n;
        memset(y, 0, (size_t)n * sizeof *y);
        for (int a = 0; a < j->nmoves; a++)
            j->col[a] = j->B[rows[k] * n + j->moves[a]];
        if (j->nmoves)
            la_ldlt_solve(j->L, j->nmoves, j->perm, j->col);
        for (int a = 0; a < j->nmoves; a++)
            y[j->moves[a]] = j->col[a];
    }
    for (int k = 0; k < nr; k++)
        for (int l = 0; l < nr; l++)
            j->S[k * nr + l] = la_dot(j->B + rows[k] * n, j->Y + l * n, n);
    if (la_lu_factor(j->lu[level], j->S) != 0)
        return -1;
    for (int k = 0; k < nr; k++)
        j->mu[k] = r[rows[k]];
    la_lu_solve(j->lu[level], j->mu);
    for (int i = 0; i < n; i++) {
        double d = 0;
        for (int k = 0; k < nr; k++)
            d += j->Y[k * n + i] * j->mu[k];
        j->w[i] = d;
    }
    if (level == 0 && j->m->nv > 0) { /* dq = W(q) d, e back to length 1 */
        const eomc_model *m = j->m;
        state_qdot(m, q, j->w, j->dq);
        for (int i = 0; i < j->nq; i++)
            q[i] -= j->dq[i];
        for (int g = 0; g < m->nquat; g++) { /* those it moved: a held one stays */
            const int *e = m->quat + 4 * g;
            if (j->dq[e[0]] != 0 || j->dq[e[1]] != 0 || j->dq[e[2]] != 0 || j->dq[e[3]] != 0)
                state_normalize_quat(m, q, g);
        }
    } else {
        for (int i = 0; i < n; i++)
            x[i] -= j->w[i];
    }
    return 0;
}

/* The level's metric: M on the coordinates (level 0) or velocities (1)
 * the caller does not hold, factored.  Holding some, the correction is
 * the smallest in that metric among those that leave them as they are. */
static int
metric(Proj *j, int level)
{
    int n = j->n, nm = 0;
    /* the velocities' metric is the positions' when the same ones move */
    if (level == 1 && j->factored && (!j->hold || !memcmp(j->hold, j->hold + n, (size_t)n)))
        return PROJ_OK;
    for (int i = 0; i < n; i++)
        if (!j->hold || !j->hold[level * n + i])
            j->moves[nm++] = i;
    j->nmoves = nm;
    for (int a = 0; a < nm; a++)
        for (int b = 0; b < nm; b++)
            j->L[a * nm + b] = j->M[j->moves[a] * n + j->moves[b]];
    if (nm && la_ldlt_factor(j->L, nm, j->rel, j->perm) != 0)
        return PROJ_NOT_PD;
    j->factored = 1;
    return PROJ_OK;
}

static int
project_level(Proj *j, double t, double *q, double *v, const double *p, const double *u,
              int level)
{
    if (j->nfix[level] == 0)
        return PROJ_OK;
    int rc = metric(j, level);
    if (rc != PROJ_OK)
        return rc;
    double rel = HUGE_VAL;
    j->vMv0 = level ? la_quadratic(j->M, v, j->n) : 0;
    for (int it = 0; it <= PROJ_MAX && rc == 0; it++) /* the next tests a correction */
        rc = correct(j, t, q, v, p, u, level, &rel);
    /* a velocity the projection left at the rounding of those it started
     * from is 0 to its accuracy, and 0 it is: a state at rest whose
     * velocities were the corrections' rounding would look, against their
     * own size, nowhere near its constraints */
    for (int a = 0; level && rc == 1 && a < j->nmoves; a++) {
        int i = j->moves[a];
        if (fabs(v[i]) * sqrt(fmax(j->M[i * j->n + i], 0)) <= LA_SETTLED_TIGHT * sqrt(j->vMv0))
            v[i] = 0;
    }
    j->vMv0 = 0;
    return rc < 0 ? PROJ_SINGULAR : rc == 0 ? PROJ_NO_CONVERGENCE : PROJ_OK;
}

int
proj_apply(Proj *j, double t, double *q, double *v, const double *p, const double *u,
           int *level)
{
    return proj_apply_held(j, t, q, v, p, u, NULL, level);
}

/* What hold [nq + n] keeps, as the speeds that stay, into j->hv [2n]
 * (j->hold: it, or NULL when nothing is held): at velocity level the
 * speeds held; at position level those that move only held coordinates
 * (a column of W(q): qdot of a unit speed), a unit quaternion's four
 * moving together (renormalized), PROJ_HOLD where a held coordinate
 * would move with a speed that is not held (j->held_q, j->held_v). */
static int
hold_speeds(Proj *j, const double *q, const unsigned char *hold)
{
    const eomc_model *m = j->m;
    int n = j->n, nq = j->nq;
    j->hold = hold ? j->hv : NULL;
    if (!hold)
        return PROJ_OK;
    memcpy(j->hv + n, hold + nq, (size_t)n);
    if (m->nv == 0) {
        memcpy(j->hv, hold, (size_t)n);
        return PROJ_OK;
    }
    for (int k = 0; k < n; k++) {
        memset(j->w, 0, (size_t)n * sizeof *j->w);
        j->w[k] = 1;
        state_qdot(m, q, j->w, j->dq);
        for (int g = 0; g < m->nquat; g++) { /* the whole quaternion moves */
            const int *e = m->quat + 4 * g;
            if (j->dq[e[0]] != 0 || j->dq[e[1]] != 0 || j->dq[e[2]] != 0 || j->dq[e[3]] != 0)
                for (int i = 0; i < 4; i++)
                    j->dq[e[i]] = 1;
        }
        int keeps = 1, moves_held = -1;
        for (int i = 0; i < nq; i++)
            if (j->dq[i] != 0 && !hold[i])
                keeps = 0;
            else if (j->dq[i] != 0 && moves_held < 0)
                moves_held = i;
        j->hv[k] = (unsigned char)keeps;
        if (!keeps && moves_held >= 0) {
            j->held_q = moves_held, j->held_v = k;
            return PROJ_HOLD;
        }
    }
    return PROJ_OK;
}

void
proj_hold_conflict(const Proj *j, int *coord, int *speed)
{
    *coord = j->held_q;
    *speed = j->held_v;
}

int
proj_apply_held(Proj *j, double t, double *q, double *v, const double *p, const double *u,
                const unsigned char *hold, int *level)
{
    *level = 0;
    if (j->nvel == 0)
        return PROJ_OK;
    int rc = hold_speeds(j, q, hold);
    if (rc != PROJ_OK)
        return rc;
    j->m->mass_bias(t, q, v, p, u, j->M, j->h);
    j->factored = 0, j->full = -1;
    rc = project_level(j, t, q, v, p, u, 0);
    if (rc == PROJ_OK)
        rc = project_level(j, t, q, v, p, u, *level = 1);
    j->hold = NULL;
    return rc;
}

/*
 * depend: which constraint rows the solves use (depend.h).
 *
 * Constraints may be dependent: a planar loop closed by a point-to-point
 * constraint written in three dimensions has three rows of which two are
 * independent at every pose.  Then K = [M B^T; B 0] and B M^-1 B^T are
 * singular, although q'' is unique where the constraints are consistent.
 * Two ways out: solve the multipliers in the least-squares sense at every
 * right-hand side (the minimum-norm ones, which MuJoCo's regularized
 * solve tends to), or leave the dependent rows out.  The first needs a
 * rank decision in every solve, a pseudo-inverse in the Jacobian, the
 * reference and Taylor's series, and near a pose where the rank changes
 * it decides by rounding.  The second is taken here: the rows are chosen
 * once, at the start, and the solves stay the full-rank solves of the
 * kept rows, at no cost per step.
 *
 * Why that is exact: when sum_c w_c(q) g_c(q) = 0 at every pose (the
 * dependency is structural), differentiating twice gives sum_c w_c f_c =
 * -(2 sum_c w_c' g_c' + sum_c w_c'' g_c), which vanishes on the
 * constraints: the kept rows met, the dropped ones are met too, and their
 * residuals follow the kept ones' drift.  Where the dependency held at
 * the start only (a mechanism started at a singular pose), the dropped
 * rows are not met as the motion leaves it: depend_watch sees a dropped
 * row's residual leave the kept ones' behind, and the run stops there
 * (sim.c).  Where the kept rows become dependent later (the mechanism
 * reaches a singular pose), the solve is singular and depend_involved
 * names the rows at fault.
 *
 * Which rows: QR with column pivoting of B^T at the start (la_rank_rows:
 * each column scaled by the kinetic metric, each row to unit length)
 * keeps the best-conditioned set, and a dropped row is then a combination
 * of the kept ones with coefficients near 1, so its residual follows
 * theirs closely.  Its multiplier is 0: the constraint force B^T lambda is
 * unique, its split among dependent rows is not.  Second-order rows are
 * never dropped (nothing below acceleration level would watch them).
 */
#include "depend.h"
#include "linalg.h"
#include "eomc.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct Depend {
    const eomc_model *m;
    int n, nc, ndrop;
    LaRank *rank;
    double *d;                       /* [n] the columns' scaling, 1/sqrt(M_ii) */
    int *rows;                       /* [nc] */
    unsigned char *keep, *inv, *drop; /* [nc] kept, involved, dropped */
    size_t len;                      /* the texts' room */
    char *note, *names;              /* depend_note's, depend_involved's */
};

Depend *
depend_alloc(const eomc_model *m)
{
    Depend *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    size_t nc = (size_t)m->nc + 1;
    w->m = m;
    w->n = eomc_nv(m), w->nc = m->nc;
    w->len = 64;
    for (int c = 0; c < m->nc; c++)
        w->len += strlen(m->c_names[c]) + 2;
    w->rank = la_rank_alloc(m->nc, eomc_nv(m));
    w->d = calloc((size_t)eomc_nv(m) + 1, sizeof *w->d);
    w->rows = calloc(nc, sizeof *w->rows);
    w->keep = calloc(nc, 1), w->inv = calloc(nc, 1), w->drop = calloc(nc, 1);
    w->note = calloc(w->len, 1), w->names = calloc(w->len, 1);
    if (!w->rank || !w->d || !w->rows || !w->keep || !w->inv || !w->drop || !w->note ||
        !w->names) {
        depend_free(w);
        return NULL;
    }
    return w;
}

void
depend_free(Depend *w)
{
    if (!w)
        return;
    la_rank_free(w->rank);
    free(w->d);
    free(w->rows);
    free(w->keep);
    free(w->inv);
    free(w->drop);
    free(w->note);
    free(w->names);
    free(w);
}

/* The columns' scaling from M's diagonal (a coordinate without mass: 1). */
static const double *
scaling(Depend *w, const double *M)
{
    if (!M)
        return NULL;
    for (int i = 0; i < w->n; i++) {
        double h = M[i * w->n + i];
        w->d[i] = h > 0 && isfinite(h) ? 1 / sqrt(h) : 1;
    }
    return w->d;
}

/* The names of the rows mask marks (only those wanted: 1 or 0) into buf
 * after at; the new end. */
static size_t
put_names(const Depend *w, const unsigned char *mask, int wanted, char *buf, size_t at)
{
    for (int c = 0, first = 1; c < w->nc && at < w->len; c++)
        if (mask[c] == wanted) {
            at += (size_t)snprintf(buf + at, w->len - at, "%s%s", first ? "" : ", ",
                                   w->m->c_names[c]);
            first = 0;
        }
    return at;
}

int
depend_choose(Depend *w, const double *B, const double *M)
{
    int nc = w->nc;
    depend_clear(w);
    for (int c = 0; c < nc; c++)
        w->rows[c] = c, w->keep[c] = 1, w->inv[c] = 0;
    int rank = la_rank_rows(w->rank, B, w->n, w->rows, nc, scaling(w, M), w->keep, w->inv);
    if (rank == nc)
        return DEPEND_NONE;
    /* "loop_z, dependent on loop_x, loop_y": the dropped, then the kept
     * rows their combinations use */
    size_t at = put_names(w, w->keep, 0, w->note, 0);
    for (int c = 0; c < nc; c++)
        w->inv[c] = w->inv[c] && w->keep[c];
    int on = 0;
    for (int c = 0; c < nc; c++)
        on |= w->inv[c];
    if (at < w->len)
        at += (size_t)snprintf(w->note + at, w->len - at, on ? ", dependent on " :
                               ", each 0 here");
    put_names(w, w->inv, 1, w->note, at);
    for (int c = 0; c < nc; c++)
        if (!w->keep[c] && w->m->c_order[c] == 2)
            return DEPEND_SECOND;
    for (int c = 0; c < nc; c++)
        w->drop[c] = !w->keep[c];
    w->ndrop = nc - rank;
    return DEPEND_DROPPED;
}

const unsigned char *
depend_dropped(const Depend *w)
{
    return w->ndrop ? w->drop : NULL;
}

void
depend_clear(Depend *w)
{
    memset(w->drop, 0, (size_t)w->nc);
    w->ndrop = 0;
    w->note[0] = '\0';
}

const char *
depend_note(const Depend *w)
{
    return w->note;
}

const char *
depend_involved(Depend *w, const double *B, const double *M, const int *rows, int nr,
                int *rank)
{
    memset(w->inv, 0, (size_t)w->nc);
    *rank = la_rank_rows(w->rank, B, w->n, rows, nr, scaling(w, M), NULL, w->inv);
    w->names[0] = '\0';
    put_names(w, w->inv, 1, w->names, 0);
    return w->names;
}

int
depend_watch(const Depend *w, const double *each, double *kept)
{
    int worst = -1;
    *kept = 0;
    for (int c = 0; c < w->nc; c++)
        if (!w->drop[c])
            *kept = fmax(*kept, each[c]);
        else if (worst < 0 || each[c] > each[worst])
            worst = c;
    if (worst < 0 || !(each[worst] > fmax(DEPEND_FOLLOW * *kept, EOMC_INCONSISTENT)))
        return -1;
    return worst;
}

/*
 * refswitch: the reference solution's switches (refswitch.h).
 *
 * The reference holds every mode through a step, so an accepted step
 * integrates the branch the step started on, a smooth equation, past any
 * kink: its error control is the smooth problem's.  After the step each
 * switch function s is taken at the end; where one is past 0 (on the
 * other side of its mode), its crossing is located by Anderson-Bjorck's
 * secant steps on side steps from the step's start (the states of that
 * smooth branch), to a bracket SETTLED_ULPS units of long double's
 * rounding of the time scale wide; the step ends at the earliest, and
 * there every switch located within that bracket, and every other past 0
 * already, flips.  Nothing else changes: the state goes on as it was.
 *
 * A switch function that leaves 0 and comes back within one step (a
 * grazing touch) has one sign at both ends.  As the doubles' pair search
 * (stepevents.c), a step whose s heads for 0 at its start and away from
 * it at its end has its turning point searched, by bisection on the sign
 * of s's rate on the solution, from where the cubic through s and its
 * rates at the ends turns; where s has crossed there, the crossing before
 * it is located as above.  The doubles stop after 12 bisections; here the
 * search goes on until s is seen across, or until s cannot reach 0 in the
 * bracket left: with its rate changing monotonically there (one turning
 * point, what the search assumes), s lies above both tangents at the
 * bracket's ends, so where they meet above 0 it does not cross; or until
 * the bracket is settled.  Like the doubles', it finds one pair a step: a
 * switch function turning twice inside one step is not looked for.
 *
 * Rates along the motion are central differences along the tangent,
 * s(t + d, x + d x') - s(t - d, x - d x') over 2d, which is ds/dt to
 * O(d^2); d is PROBE_REL of the step, near the cube root of long
 * double's rounding, where truncation and rounding balance.
 */
#include "refswitch.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A bracket this many units of rounding of the time scale wide is
 * settled: no two times in it are worth telling apart (events.c's rule,
 * in long double). */
#define SETTLED_ULPS 4
/* A flip this many units of the doubles' rounding of the time scale
 * after others follows them (their sensitivities are its too): the
 * window in which the runs flip switches together (stepevents.c's
 * SIMULTANEOUS_ULPS), which holds a crossing they located a few units
 * after a flip that caused it. */
#define FOLLOW_ULPS 16
/* Secant steps and bisections of one location, at most: bisection alone
 * from a whole step settles in about 2 x 64. */
enum { ROOT_EVALS = 200, PAIR_ITERS = 200 };
/* The start's probe: the doubles' (evolve.c's START_PROBE_REL). */
#define START_PROBE_REL 1e-7L
/* The probe of a rate, in steps (the cube root of LDBL_EPSILON is 2.4e-7
 * on x86-64, 4.8e-12 in IEEE quadruple; this serves both). */
#define PROBE_REL 1e-6L

typedef struct Flip {
    double t;
    int k;
} Flip;

struct RefSwitches {
    int nm, N;
    eomc_ext *mode;               /* [nm] the caller's */
    RefSwMotion mo;
    eomc_ext t0, span, settled;   /* the span's start and length; a settled bracket */
    eomc_ext h;                   /* the step checked last */
    eomc_ext *s0, *s1, *sa, *sb;  /* [nm] s at the ends, scratch */
    eomc_ext *r0, *r1, *ra;       /* [nm] rates at the ends, scratch */
    eomc_ext *hit;                /* [nm] each located crossing, or NAN */
    eomc_ext *last;               /* [nm] each switch's last flip */
    int *quick;                   /* [nm] its flips in a row, each within
                                   * STEPEV_ACCUMULATE_REL of the span after the
                                   * one before */
    eomc_ext *xs, *fs, *xp;       /* [N] a state, its rate, a probe */
    long n, cap;                  /* the record */
    double *rt, *rsens;           /* [cap], [cap N] */
    double *rx, *rf;              /* [cap N]: the state and its rate as the flip's
                                   * instant arrived */
    double *xa, *fa;              /* [N] those of the instant in hand */
    int *rk;                      /* [cap] */
    double *then;                 /* [N] the largest sensitivities of the flips at */
    eomc_ext then_t;              /* then_t, or at most FOLLOW_ULPS before it */
};

RefSwitches *
refsw_alloc(int nmode, int N, eomc_ext *mode, RefSwMotion mo, eomc_ext t0, eomc_ext t_end)
{
    RefSwitches *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    eomc_ext span = t_end - t0;
    *w = (RefSwitches){.nm = nmode, .N = N, .mode = mode, .mo = mo, .t0 = t0, .span = span,
                       .h = span};
    /* a bracket's width against the times it holds, as the run's least
     * step is (evolve.c's hmin) */
    w->settled = SETTLED_ULPS * LDBL_EPSILON * fmaxl(fmaxl(fabsl(t0), fabsl(t_end)), span);
    size_t m = (size_t)(nmode > 0 ? nmode : 1), n = (size_t)(N > 0 ? N : 1);
    eomc_ext **arrays[] = {&w->s0, &w->s1, &w->sa, &w->sb, &w->r0, &w->r1, &w->ra, &w->hit,
                           &w->last, &w->xs, &w->fs, &w->xp};
    size_t sizes[] = {m, m, m, m, m, m, m, m, m, n, n, n};
    int ok = 1;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++)
        ok &= (*arrays[k] = calloc(sizes[k], sizeof(eomc_ext))) != NULL;
    ok &= (w->then = calloc(n, sizeof *w->then)) != NULL;
    ok &= (w->quick = calloc(m, sizeof *w->quick)) != NULL;
    ok &= (w->xa = calloc(n, sizeof *w->xa)) != NULL;
    ok &= (w->fa = calloc(n, sizeof *w->fa)) != NULL;
    w->then_t = -INFINITY;
    if (!ok) {
        refsw_free(w);
        return NULL;
    }
    return w;
}

void
refsw_free(RefSwitches *w)
{
    if (!w)
        return;
    eomc_ext *arrays[] = {w->s0, w->s1, w->sa, w->sb, w->r0, w->r1, w->ra, w->hit,
                          w->last, w->xs, w->fs, w->xp};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; k++)
        free(arrays[k]);
    free(w->rt);
    free(w->rx);
    free(w->rf);
    free(w->xa);
    free(w->fa);
    free(w->then);
    free(w->quick);
    free(w->rsens);
    free(w->rk);
    free(w);
}

long
refsw_count(const RefSwitches *w)
{
    return w->n;
}

const double *
refsw_times(const RefSwitches *w)
{
    return w->rt;
}

const int *
refsw_which(const RefSwitches *w)
{
    return w->rk;
}

const double *
refsw_sens(const RefSwitches *w)
{
    return w->rsens;
}

const double *
refsw_states(const RefSwitches *w)
{
    return w->rx;
}

const double *
refsw_rates(const RefSwitches *w)
{
    return w->rf;
}

/* s past 0 on the other side of switch k's mode (not at 0). */
static int
past(const RefSwitches *w, int k, eomc_ext s)
{
    return w->mode[k] != 0 ? s < 0 : s > 0;
}

/* Every s's rate along the motion at (t, x), rate f, over a probe of d,
 * into out [nm] (sa, sb and xp scratch). */
static void
rates(RefSwitches *w, eomc_ext t, const eomc_ext *x, const eomc_ext *f, eomc_ext d,
      eomc_ext *out)
{
    for (int side = 0; side < 2; side++) {
        eomc_ext e = side ? d : -d;
        for (int i = 0; i < w->N; i++)
            w->xp[i] = x[i] + e * f[i];
        w->mo.functions(w->mo.ctx, t + e, w->xp, side ? w->sb : w->sa);
    }
    for (int k = 0; k < w->nm; k++)
        out[k] = (w->sb[k] - w->sa[k]) / (2 * d);
}

/* Whether mode k is dry friction's stick switch (RefSwMotion.held). */
static int
held(const RefSwitches *w, int k)
{
    return w->mo.held && w->mo.held(w->mo.ctx, k);
}

int
refsw_signs(RefSwitches *w, eomc_ext t, const eomc_ext *x)
{
    /* a switch function may read other modes (a max of a max): each pass
     * settles at least the modes the ones before decided */
    for (int pass = 0; pass <= w->nm; pass++) {
        int changed = 0;
        w->mo.functions(w->mo.ctx, t, x, w->s0);
        for (int k = 0; k < w->nm; k++) {
            eomc_ext on = w->s0[k] > 0;
            if (held(w, k))
                continue;
            changed |= on != w->mode[k];
            w->mode[k] = on;
        }
        if (!changed)
            break;
    }
    return w->mo.settle ? w->mo.settle(w->mo.ctx, t, x) : 0;
}

/* Switch k's rate at the start along the motion in the modes as they
 * are (its sign is all that is used): 0, or -1. */
static int
start_rate(RefSwitches *w, const eomc_ext *x, int k, eomc_ext *r)
{
    if (w->mo.rate(w->mo.ctx, w->t0, x, w->fs) != 0)
        return -1;
    rates(w, w->t0, x, w->fs, START_PROBE_REL * w->span, w->ra);
    *r = w->ra[k];
    return 0;
}

int
refsw_start(RefSwitches *w, const eomc_ext *x0, int *bad)
{
    w->n = 0;
    for (int k = 0; k < w->nm; k++)
        w->last[k] = -INFINITY, w->hit[k] = NAN, w->quick[k] = 0;
    if (refsw_signs(w, w->t0, x0) != 0)
        return -1;
    w->mo.functions(w->mo.ctx, w->t0, x0, w->s1);
    for (int k = 0; k < w->nm; k++) {
        eomc_ext r0, r1;
        if (w->s1[k] != 0 || held(w, k))
            continue;
        if (start_rate(w, x0, k, &r0) != 0)
            return -1;
        if (r0 == 0 || (r0 > 0) == (w->mode[k] != 0)) /* (a tangency keeps mode 0) */
            continue;
        w->mode[k] = r0 > 0;
        if (start_rate(w, x0, k, &r1) != 0)
            return -1;
        if (r1 != 0 && (r1 > 0) != (r0 > 0)) {
            *bad = k;
            return -2;
        }
    }
    return 0;
}

/* s_k on the solution at t of the step from t0, into *g (the state in
 * w->xs); 0 or -1. */
static int
g_at(RefSwitches *w, int k, eomc_ext t0, eomc_ext t, eomc_ext *g)
{
    if (w->mo.state(w->mo.ctx, t0, t, w->xs) != 0)
        return -1;
    w->mo.functions(w->mo.ctx, t, w->xs, w->sa);
    *g = w->sa[k];
    return 0;
}

static int
sign(eomc_ext x)
{
    return (x > 0) - (x < 0);
}

/* Switch k's crossing between a (g = ga, not past 0) and b (gb, past
 * 0), on the solution of the step from t0: Anderson-Bjorck, as events.c's
 * ev_root in doubles; the end of the settled bracket past 0 (or a time
 * where s is 0) into *t.  0, or -1 where the solution cannot be made. */
static int
locate(RefSwitches *w, int k, eomc_ext t0, eomc_ext a, eomc_ext ga, eomc_ext b, eomc_ext gb,
       eomc_ext guess, eomc_ext *root)
{
    int post = sign(gb), since = 0;
    eomc_ext width0 = fabsl(b - a);
    for (int evals = 0; evals < ROOT_EVALS; evals++) {
        eomc_ext lo = fminl(a, b), hi = fmaxl(a, b), t, gt;
        if (hi - lo <= w->settled)
            break;
        if (evals == 0 && guess > lo && guess < hi)
            t = guess;
        else if (since >= 3 && hi - lo > 0.5L * width0)
            t = 0.5L * (lo + hi), since = 0, width0 = hi - lo;
        else
            t = b - gb * (b - a) / (gb - ga);
        /* never nearer an end than the bracket is to settling: a point
         * next to the root is followed by one just across it */
        if (isnan(t))
            t = 0.5L * (lo + hi);
        else if (t - lo < w->settled)
            t = fminl(lo + w->settled, 0.5L * (lo + hi));
        else if (hi - t < w->settled)
            t = fmaxl(hi - w->settled, 0.5L * (lo + hi));
        if (g_at(w, k, t0, t, &gt) != 0)
            return -1;
        if (gt == 0) {
            *root = t;
            return 0;
        }
        if (sign(gt) == sign(gb)) {
            eomc_ext m = 1 - gt / gb;
            ga *= m > 0 ? m : 0.5L;
        } else {
            a = b, ga = gb;
        }
        b = t, gb = gt;
        if (++since >= 3 && fabsl(b - a) <= 0.5L * width0)
            since = 0, width0 = fabsl(b - a);
    }
    *root = sign(gb) == post ? b : a;
    return 0;
}

/* Switch k, on its mode's side at both ends of the step from (t0, x0)
 * to t1, heading for 0 at the start and away at the end (u = side * s
 * falls, then rises): its turning point searched (the file's comment);
 * where s is past 0 there, the crossing before it located into hit[k].
 * 0, or -1 where the solution cannot be made. */
static int
pair(RefSwitches *w, int k, eomc_ext t0, eomc_ext t1)
{
    eomc_ext sd = w->mode[k] != 0 ? 1 : -1, h = t1 - t0, d = PROBE_REL * h;
    eomc_ext ul = sd * w->s0[k], dl = sd * w->r0[k], uh = sd * w->s1[k], dh = sd * w->r1[k];
    eomc_ext lo = t0, hi = t1;
    /* where the cubic through u and its rates at the ends turns first */
    eomc_ext c1 = dl * h, c2 = 3 * (uh - ul) - 2 * dl * h - dh * h;
    eomc_ext c3 = 2 * (ul - uh) + dl * h + dh * h, qa = 3 * c3, qb = 2 * c2;
    eomc_ext disc = qb * qb - 4 * qa * c1, tau = 0.5L;
    if (qa != 0 && disc >= 0) {
        eomc_ext x1 = (-qb - sqrtl(disc)) / (2 * qa), x2 = (-qb + sqrtl(disc)) / (2 * qa);
        tau = x1 > 0 && x1 < 1 ? x1 : x2 > 0 && x2 < 1 ? x2 : 0.5L;
    } else if (qa == 0 && qb != 0 && -c1 / qb > 0 && -c1 / qb < 1) {
        tau = -c1 / qb;
    }
    for (int it = 0; it < PAIR_ITERS && hi - lo > w->settled; it++) {
        /* the tangents at the ends meet at u = floor: u lies above both */
        if (dl < 0 && dh > 0) {
            eomc_ext meet = (uh - ul - dh * hi + dl * lo) / (dl - dh);
            if (ul + dl * (meet - lo) > 0)
                return 0;
        }
        eomc_ext tm = it == 0 ? t0 + tau * h : 0.5L * (lo + hi), g;
        if (!(tm > lo && tm < hi))
            tm = 0.5L * (lo + hi);
        if (g_at(w, k, t0, tm, &g) != 0 || w->mo.rate(w->mo.ctx, tm, w->xs, w->fs) != 0)
            return -1;
        if (g == 0) {
            w->hit[k] = tm;
            return 0;
        }
        if (past(w, k, g))
            return locate(w, k, t0, t0, w->s0[k], tm, g, NAN, &w->hit[k]);
        rates(w, tm, w->xs, w->fs, d, w->ra);
        eomc_ext du = sd * w->ra[k];
        if (du < 0) /* still heading for 0: the turn is later */
            lo = tm, ul = sd * g, dl = du;
        else
            hi = tm, uh = sd * g, dh = du;
    }
    return 0;
}

int
refsw_check(RefSwitches *w, eomc_ext t0, const eomc_ext *x0, const eomc_ext *f0,
            eomc_ext t1, const eomc_ext *x1, const eomc_ext *f1, eomc_ext *t_hit,
            eomc_ext *x_hit)
{
    w->h = t1 - t0;
    w->mo.functions(w->mo.ctx, t0, x0, w->s0);
    w->mo.functions(w->mo.ctx, t1, x1, w->s1);
    int have_rates = 0;
    eomc_ext first = INFINITY;
    for (int k = 0; k < w->nm; k++) {
        w->hit[k] = NAN;
        /* flipped here as one of several crossings within a settled
         * bracket, it may start a rounding short of 0: it is at 0 */
        if (w->last[k] == t0 && past(w, k, w->s0[k]))
            w->s0[k] = 0;
        if (past(w, k, w->s0[k])) { /* (cannot be: every mode agrees where a step starts) */
            w->hit[k] = t0;
        } else if (past(w, k, w->s1[k])) {
            if (locate(w, k, t0, t0, w->s0[k], t1, w->s1[k], NAN, &w->hit[k]) != 0)
                return -1;
        } else if (w->s0[k] != 0 && w->s1[k] != 0) {
            if (!have_rates++) {
                eomc_ext d = PROBE_REL * w->h;
                rates(w, t0, x0, f0, d, w->r0);
                rates(w, t1, x1, f1, d, w->r1);
            }
            eomc_ext sd = w->mode[k] != 0 ? 1 : -1;
            if (sd * w->r0[k] < 0 && sd * w->r1[k] > 0 && pair(w, k, t0, t1) != 0)
                return -1;
        }
        if (!isnan(w->hit[k]))
            first = fminl(first, w->hit[k]);
    }
    if (first == INFINITY)
        return 0;
    *t_hit = first;
    if (first == t1)
        memcpy(x_hit, x1, (size_t)w->N * sizeof *x_hit);
    else if (w->mo.state(w->mo.ctx, t0, first, x_hit) != 0)
        return -1;
    return 1;
}

/* The record's next entry: switch k at t, sensitivities [N], the
 * instant's arrival (xa, fa); 0 or -1. */
static int
record(RefSwitches *w, eomc_ext t, int k, const double *sens)
{
    if (w->n == w->cap) {
        long cap = w->cap ? 2 * w->cap : 16;
        double *rt = realloc(w->rt, (size_t)cap * sizeof *rt);
        if (rt)
            w->rt = rt;
        double *rs = realloc(w->rsens, (size_t)cap * (size_t)w->N * sizeof *rs);
        if (rs)
            w->rsens = rs;
        int *rk = realloc(w->rk, (size_t)cap * sizeof *rk);
        if (rk)
            w->rk = rk;
        double *rx = realloc(w->rx, (size_t)cap * (size_t)w->N * sizeof *rx);
        if (rx)
            w->rx = rx;
        double *rf = realloc(w->rf, (size_t)cap * (size_t)w->N * sizeof *rf);
        if (rf)
            w->rf = rf;
        if (!rt || !rs || !rk || !rx || !rf)
            return -1;
        w->cap = cap;
    }
    size_t at = (size_t)w->n * (size_t)w->N;
    w->rt[w->n] = (double)t;
    w->rk[w->n] = k;
    memcpy(w->rsens + at, sens, (size_t)w->N * sizeof *sens);
    memcpy(w->rx + at, w->xa, (size_t)w->N * sizeof *w->xa);
    memcpy(w->rf + at, w->fa, (size_t)w->N * sizeof *w->fa);
    w->n++;
    return 0;
}

/* How far switch k's crossing at (t, x) moves per unit error of each
 * component, |ds/dx_i| / |ds/dt| into sens [N], by central differences
 * (x_i's over PROBE_REL of its scale sc_i, t's along the motion over
 * PROBE_REL of the step); w->fs holds x' there.  In the modes as they
 * are. */
static void
sensitivity(RefSwitches *w, int k, eomc_ext t, const eomc_ext *x, const eomc_ext *sc,
            double *sens)
{
    rates(w, t, x, w->fs, PROBE_REL * w->h, w->ra);
    eomc_ext rate = fabsl(w->ra[k]);
    memcpy(w->xp, x, (size_t)w->N * sizeof *w->xp);
    for (int i = 0; i < w->N; i++) {
        eomc_ext e = PROBE_REL * fmaxl(fmaxl(sc[i], fabsl(x[i])), LDBL_MIN / PROBE_REL);
        w->xp[i] = x[i] + e;
        w->mo.functions(w->mo.ctx, t, w->xp, w->sb);
        w->xp[i] = x[i] - e;
        w->mo.functions(w->mo.ctx, t, w->xp, w->sa);
        w->xp[i] = x[i];
        eomc_ext grad = fabsl(w->sb[k] - w->sa[k]) / (2 * e);
        sens[i] = grad == 0 ? 0 : rate > 0 ? (double)(grad / rate) : INFINITY;
    }
}

/* refsw_flip (jump 0) and refsw_jump (1: no switch was located, and the
 * passes go on past the first, which flips none, to those past 0). */
static int
flip_at(RefSwitches *w, eomc_ext t, eomc_ext *x, const eomc_ext *sc, int *bad, int jump)
{
    size_t N = (size_t)(w->N > 0 ? w->N : 1), nm = (size_t)(w->nm > 0 ? w->nm : 1);
    double *sens = malloc((nm + 1) * N * sizeof *sens); /* [nm][N] each flip's, at arrival */
    double *start = sens + nm * N; /* [N] w->then as this instant began */
    double *seq = calloc((size_t)w->nm + 1, sizeof *seq); /* the order of each flip at t */
    unsigned char *was = calloc((size_t)w->nm + 1, 1);     /* the modes before a flip */
    unsigned char *wait = calloc((size_t)w->nm + 1, 1);    /* located, after the contacts */
    double order = 0;
    int rc = sens && seq && was && wait ? 0 : -1;
    /* A flip at t, or within FOLLOW_ULPS after others (a touch point's
     * slip speed, 0 in the air but for rounding, leaves 0 the moment the
     * floor's friction acts: a crossing located a few units of rounding
     * after the touch), flips when they do: its time is as uncertain as
     * theirs.  Those at this instant take the earlier ones'; those a flip
     * here moved across (a capsule's clamp, a push switched on as its
     * shapes part), the largest of all before them. */
    if (!(t - w->then_t <= FOLLOW_ULPS * DBL_EPSILON * fmaxl(fabsl(t), w->span)))
        for (size_t i = 0; i < N; i++)
            w->then[i] = 0;
    w->then_t = t;
    double *then = w->then;
    for (size_t i = 0; rc == 0 && i < N; i++)
        start[i] = then[i];
    /* the located ones first, each with its arrival's rate (the modes it
     * came in), then, until none is left, those past 0 there: kinks at
     * this instant, and functions a flip moved (a max of a max).  Those
     * as the runs flip them (stepevents.c): without dry friction one a
     * pass in their order, each function reading only the modes before
     * it, one flipped at t again where one before it flipped after it;
     * with it too, but a friction switch once an instant */
    for (int pass = 0; rc == 0 && pass <= 2 * w->nm; pass++) {
        if (w->mo.rate(w->mo.ctx, t, x, w->fs) != 0) {
            rc = -1;
            break;
        }
        w->mo.functions(w->mo.ctx, t, x, w->s1);
        for (int i = 0; pass == 0 && i < w->N; i++) /* (the instant's arrival) */
            w->xa[i] = (double)x[i], w->fa[i] = (double)w->fs[i];
        int flips = 0;
        eomc_ext *flip = w->r1; /* (free once the step is checked) */
        for (int k = 0; k < w->nm; k++)
            flip[k] = pass == 0 && !isnan(w->hit[k]) && w->hit[k] - t <= w->settled;
        double below = 0; /* the latest flip at t of the switches before k */
        for (int k = 0; pass > 0 && k < w->nm; k++) {
            int at_t = w->last[k] == t && seq[k] > 0;
            int again = at_t && ((w->mo.friction && w->mo.friction(w->mo.ctx, k)) ||
                                 !(below > seq[k]));
            if (at_t)
                below = fmax(below, seq[k]);
            if (again || !past(w, k, w->s1[k]))
                continue;
            flip[k] = 1, flips++;
            break; /* the first alone: its flip moves the functions after it */
        }
        /* with dry friction, a pass that flips a contact's switch flips
         * no friction switch, one located here waiting for a later pass:
         * who sticks is decided with the instant's contacts all made */
        int contact = 0;
        for (int k = 0; w->mo.friction && k < w->nm; k++)
            contact |= flip[k] != 0 && !w->mo.friction(w->mo.ctx, k);
        for (int k = 0; w->mo.friction && k < w->nm; k++) {
            if (!w->mo.friction(w->mo.ctx, k))
                continue;
            if (contact) { /* (wait: 1 + the mode it goes to) */
                if (flip[k] != 0 && pass == 0)
                    wait[k] = (unsigned char)(1 + (w->mode[k] == 0));
                flip[k] = 0;
            } else if (wait[k]) { /* (unless a flip since set it) */
                flip[k] = (w->mode[k] != 0) != (wait[k] == 2);
                wait[k] = 0;
            }
        }
        flips = 0;
        for (int k = 0; rc == 0 && k < w->nm; k++) {
            if (flip[k] == 0)
                continue;
            if (t != w->last[k])
                w->quick[k] =
                    t - w->last[k] < STEPEV_ACCUMULATE_REL * w->span ? w->quick[k] + 1 : 0;
            if (w->quick[k] >= STEPEV_CHATTER_FLIPS) {
                *bad = k;
                rc = -2;
                break;
            }
            double *sk = sens + (size_t)k * N;
            sensitivity(w, k, t, x, sc, sk);
            for (size_t i = 0; i < N; i++)
                sk[i] = fmax(sk[i], pass > 0 ? then[i] : start[i]);
        }
        double first = order + 1; /* the order of this pass's first flip */
        for (int k = 0; rc == 0 && k < w->nm; k++) {
            /* (one an earlier flip of this pass set, a group's, is set) */
            if (flip[k] == 0 || seq[k] >= first)
                continue;
            const double *sk = sens + (size_t)k * N;
            if (record(w, t, k, sk) != 0)
                rc = -1;
            for (size_t i = 0; i < N; i++)
                then[i] = fmax(then[i], sk[i]);
            flips++;
            w->last[k] = t;
            /* over: a located crossing may sit a rounding short of 0 (s1
             * still on its mode's side, which must not read as a flip
             * back at the next pass: seq) and one past 0 is over */
            int on = w->mode[k] == 0;
            seq[k] = ++order;
            for (int j = 0; j < w->nm; j++)
                was[j] = w->mode[j] != 0;
            if (!w->mo.flip)
                w->mode[k] = on;
            else if (w->mo.flip(w->mo.ctx, k, on, t, x) != 0)
                rc = -1;
            /* the modes its flip set too (dry friction: a group stuck or
             * let go with it, and the slip side of each let go), each
             * flipped at t; the stick switches among them listed, with its
             * sensitivities, in the order of the switches, as the runs
             * list them */
            for (int j = 0; rc == 0 && j < w->nm; j++) {
                if (j == k || was[j] == (w->mode[j] != 0))
                    continue;
                w->last[j] = t;
                seq[j] = ++order;
                if (held(w, j) && record(w, t, j, sk) != 0)
                    rc = -1;
            }
        }
        if (!flips && !(jump && pass == 0))
            break;
    }
    for (int k = 0; k < w->nm; k++)
        w->hit[k] = NAN;
    free(sens);
    free(seq);
    free(was);
    free(wait);
    return rc;
}

int
refsw_flip(RefSwitches *w, eomc_ext t, eomc_ext *x, const eomc_ext *sc, int *bad)
{
    return flip_at(w, t, x, sc, bad, 0);
}

int
refsw_jump(RefSwitches *w, eomc_ext t, eomc_ext *x, const eomc_ext *sc, int *bad)
{
    return flip_at(w, t, x, sc, bad, 1);
}

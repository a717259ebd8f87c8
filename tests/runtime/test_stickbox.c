/*
 * runtime/model/stick.h's box problem (box): the shares psi of the stuck
 * rows that a point's Coulomb friction at speed 0 allows, the psi in
 * |psi_r| <= 1 minimizing psi^T G psi / 2 - c^T psi, on random problems
 * of 1 to 8 rows, G = A^T A semidefinite, of full rank and of every
 * lower rank (rows alike: a foot's points), at scales 1e-9 .. 1e9.  Each
 * answer is checked by what certifies it, computed here in long double
 * from G, c and psi alone (the problem is convex: its conditions are
 * sufficient):
 *  - psi is in the box;
 *  - the rates g = G psi - c: 0 where psi is inside (the row holds),
 *    <= 0 at +1 and >= 0 at -1 (it slides against its friction), to
 *    1e-10 of the terms' size;
 *  - box's own g (its returned rates) agree with these;
 *  - the problem times s (G and c scaled alike, as a change of units
 *    scales them) gives the same rates, times s, to 1e-12 of the terms'
 *    size (the rates are unique; psi is not where rows are alike, and
 *    is only as well determined as G's condition allows where they are
 *    not).
 * And two rows alike, asked less than their bounds give, share alike.
 *
 * Its least largest share (cheb, the shares of redundant rows that the
 * stick switches read): min over z of max_r |a_r + (N z)_r| on random
 * problems of 2 to 7 rows and 1 to 3 free directions (N's orthonormal
 * columns), against the least over every vertex of the problem: each
 * choice of d + 1 rows and signs, s_i (a_i + N_i z) = t solved by GSL's
 * LU, kept where every row is within t.  The value to 1e-12, and cheb's z
 * reaching it.
 *
 * Its shares read by the switches (lexi, the lexicographic least: the
 * largest least, then the next, ...), on such problems, half of them
 * with rows that no direction moves and one of those the largest (the
 * least largest then leaves the others free, where the simplex's
 * answer turns on N's basis): the same shares, to 1e-12, from another
 * basis of the same directions (N Q, Q a random rotation), another start
 * (a + N w), and with that row moved by rounding alone (its N row 1e-17,
 * as a rounded row is: it takes no direction from the others); the
 * largest is cheb's least; and no share vector nearby (psi + N dz, dz
 * random, short and long) is less in that order.
 */
#include "../unit/check.h"
#include "model/friction.h"

#include <float.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#define STICK_REAL double
#define STICK_EPS DBL_EPSILON
#define STICK_MODEL eomc_model
#define STICK_(name) tbox_##name
#define STICK_API static
#include "model/stick.h"
#pragma GCC diagnostic pop

enum { MAXN = 8, TRIALS = 4000 };

static double
uniform(unsigned *seed)
{
    *seed = *seed * 1103515245u + 12345u;
    return ((*seed >> 8) & 0xffffff) / (double)0x1000000 * 2 - 1;
}

/* The worst breach of the box's conditions, over the terms' size. */
static double
breach(const double *G, const double *c, int n, const double *psi)
{
    long double scale = 0, worst = 0;
    for (int r = 0; r < n; r++) {
        long double row = fabsl((long double)c[r]);
        for (int k = 0; k < n; k++)
            row += fabsl((long double)G[r * n + k]);
        if (row > scale)
            scale = row;
    }
    for (int r = 0; r < n; r++) {
        if (fabs(psi[r]) > 1)
            return INFINITY;
        long double g = -(long double)c[r];
        for (int k = 0; k < n; k++)
            g += (long double)G[r * n + k] * psi[k];
        long double off = psi[r] == 1 ? g : psi[r] == -1 ? -g : fabsl(g);
        if (off > worst)
            worst = off;
    }
    return scale > 0 ? (double)(worst / scale) : 0;
}

static double s_[2 * MAXN * MAXN + 3 * MAXN];
static int fr_[MAXN];

static void
solve(const double *G, const double *c, int n, double *psi, signed char *at, double *g)
{
    tbox_box(G, c, n, psi, at, g, s_, fr_);
}

/* The least largest |a + N z| by the vertices (above); INFINITY if none. */
static double
vertices(const double *a, const double *N, int n, int d)
{
    double best = INFINITY;
    int k = d + 1, pick[MAXN];
    for (int i = 0; i < k; i++)
        pick[i] = i;
    gsl_matrix *A = gsl_matrix_alloc((size_t)k, (size_t)k);
    gsl_vector *b = gsl_vector_alloc((size_t)k), *x = gsl_vector_alloc((size_t)k);
    gsl_permutation *perm = gsl_permutation_alloc((size_t)k);
    for (;;) {
        for (int signs = 0; signs < 1 << k; signs++) {
            for (int i = 0; i < k; i++) {
                double sg = signs >> i & 1 ? -1 : 1;
                for (int c = 0; c < d; c++)
                    gsl_matrix_set(A, (size_t)i, (size_t)c, sg * N[pick[i] * d + c]);
                gsl_matrix_set(A, (size_t)i, (size_t)d, -1);
                gsl_vector_set(b, (size_t)i, -sg * a[pick[i]]);
            }
            int sgn;
            gsl_linalg_LU_decomp(A, perm, &sgn);
            if (fabs(gsl_linalg_LU_det(A, sgn)) < 1e-12)
                continue;
            gsl_linalg_LU_solve(A, perm, b, x);
            double t = gsl_vector_get(x, (size_t)d), worst = 0;
            for (int r = 0; r < n; r++) {
                double e = a[r];
                for (int c = 0; c < d; c++)
                    e += N[r * d + c] * gsl_vector_get(x, (size_t)c);
                worst = fmax(worst, fabs(e));
            }
            if (worst <= t * (1 + 1e-12) + 1e-15 && t < best)
                best = t;
        }
        int i = k - 1; /* the next choice of k rows of n */
        while (i >= 0 && pick[i] == n - k + i)
            i--;
        if (i < 0)
            break;
        pick[i]++;
        for (int j = i + 1; j < k; j++)
            pick[j] = pick[j - 1] + 1;
    }
    gsl_matrix_free(A), gsl_vector_free(b), gsl_vector_free(x), gsl_permutation_free(perm);
    return best;
}

/* Random orthonormal columns N [n d] by Gram-Schmidt; rows r with
 * zero[r] set are 0 (no direction moves them). */
static void
orthonormal(unsigned *seed, double *N, int n, int d, const int *zero)
{
    for (int c = 0; c < d; c++) {
        for (int r = 0; r < n; r++)
            N[r * d + c] = zero[r] ? 0 : uniform(seed);
        for (int p = 0; p < c; p++) {
            double dot = 0;
            for (int r = 0; r < n; r++)
                dot += N[r * d + c] * N[r * d + p];
            for (int r = 0; r < n; r++)
                N[r * d + c] -= dot * N[r * d + p];
        }
        double len = 0;
        for (int r = 0; r < n; r++)
            len += N[r * d + c] * N[r * d + c];
        for (int r = 0; r < n; r++)
            N[r * d + c] /= sqrt(len);
    }
}

static double lp_[(2 * MAXN + 1) * (4 * MAXN + 3)];
static int lpb_[2 * MAXN];

/* the least largest share by cheb and by the vertices, over random
 * problems: the worst difference of the values, and of cheb's value from
 * the largest |a + N z| at its z */
static void
least_largest(unsigned *seed, double *value, double *reach)
{
    for (int trial = 0; trial < 600; trial++) {
        int n = 2 + trial % 6, d = 1 + (trial / 6) % (n - 1 < 3 ? n - 1 : 3);
        double N[MAXN * MAXN], a[MAXN], z[MAXN];
        int none[MAXN] = {0};
        orthonormal(seed, N, n, d, none);
        for (int r = 0; r < n; r++)
            a[r] = 2 * uniform(seed);
        double m = tbox_cheb(a, N, n, d, z, lp_, lpb_), want = vertices(a, N, n, d), got = 0;
        for (int r = 0; r < n; r++) {
            double e = a[r];
            for (int c = 0; c < d; c++)
                e += N[r * d + c] * z[c];
            got = fmax(got, fabs(e));
        }
        *value = fmax(*value, fabs(m - want));
        *reach = fmax(*reach, fabs(got - m));
    }
}

static int
by_size_down(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? 1 : x > y ? -1 : 0;
}

/* Where b's |shares| sorted down first differ from a's by more than tol:
 * -1 where b's is less there (b comes first in the order), 1 where more,
 * 0 where they do not. */
static int
compare_sorted(const double *a, const double *b, int n, double tol)
{
    double sa[MAXN], sb[MAXN];
    for (int r = 0; r < n; r++)
        sa[r] = fabs(a[r]), sb[r] = fabs(b[r]);
    qsort(sa, (size_t)n, sizeof *sa, by_size_down);
    qsort(sb, (size_t)n, sizeof *sb, by_size_down);
    for (int r = 0; r < n; r++)
        if (fabs(sa[r] - sb[r]) > tol)
            return sb[r] < sa[r] ? -1 : 1;
    return 0;
}

static double lx_[STICK_LEXI_SCRATCH(MAXN)];
static int lxi_[MAXN];

/* lexi on random problems: the worst difference of the shares from
 * another basis and start, of the largest from cheb's value, and the
 * count of nearby share vectors before them in the order (0) */
static void
lexicographic(unsigned *seed, double *basis, double *largest, int *beaten, int *fixed_rows)
{
    for (int trial = 0; trial < 600; trial++) {
        int n = 3 + trial % 5, d = 1 + (trial / 5) % (n - 1 < 3 ? n - 1 : 3), zero[MAXN] = {0};
        double N[MAXN * MAXN], N2[MAXN * MAXN], Nc[MAXN * MAXN], a[MAXN], a2[MAXN], z[MAXN];
        double psi[MAXN], psi2[MAXN], Q[MAXN * MAXN], w[MAXN];
        int fix = trial % 2; /* a row no direction moves, the largest */
        if (fix)
            zero[0] = 1, *fixed_rows += 1;
        orthonormal(seed, N, n, d, zero);
        for (int r = 0; r < n; r++)
            a[r] = uniform(seed);
        if (fix)
            a[0] = 3;
        int nz[MAXN] = {0};
        orthonormal(seed, Q, d, d, nz); /* a rotation of the directions */
        for (int r = 0; r < n; r++)
            for (int c = 0; c < d; c++) {
                N2[r * d + c] = 0;
                for (int k = 0; k < d; k++)
                    N2[r * d + c] += N[r * d + k] * Q[k * d + c];
            }
        for (int k = 0; k < d; k++)
            w[k] = 2 * uniform(seed);
        for (int r = 0; r < n; r++) {
            a2[r] = a[r];
            for (int k = 0; k < d; k++)
                a2[r] += N[r * d + k] * w[k];
            psi[r] = a[r], psi2[r] = a2[r];
        }
        double least = tbox_cheb(a, N, n, d, z, lp_, lpb_);
        memcpy(Nc, N, sizeof N);
        tbox_lexi(psi, Nc, n, d, lx_, lxi_, lpb_);
        memcpy(Nc, N2, sizeof N2);
        tbox_lexi(psi2, Nc, n, d, lx_, lxi_, lpb_);
        double top = 0;
        for (int r = 0; r < n; r++) {
            *basis = fmax(*basis, fabs(psi[r] - psi2[r]));
            top = fmax(top, fabs(psi[r]));
        }
        if (fix) { /* the row no direction moves, moved by rounding alone */
            memcpy(Nc, N, sizeof N);
            for (int c = 0; c < d; c++)
                Nc[c] = 1e-17 * uniform(seed);
            for (int r = 0; r < n; r++)
                psi2[r] = a[r];
            tbox_lexi(psi2, Nc, n, d, lx_, lxi_, lpb_);
            for (int r = 0; r < n; r++)
                *basis = fmax(*basis, fabs(psi[r] - psi2[r]));
        }
        *largest = fmax(*largest, fabs(top - least));
        for (int k = 0; k < 200; k++) { /* nearby vectors: none before psi */
            double len = k % 2 ? 1e-3 : 0.3, near[MAXN];
            for (int r = 0; r < n; r++)
                near[r] = psi[r];
            for (int c = 0; c < d; c++) {
                double dz = len * uniform(seed);
                for (int r = 0; r < n; r++)
                    near[r] += N[r * d + c] * dz;
            }
            *beaten += compare_sorted(psi, near, n, 1e-12) < 0;
        }
    }
}

int
main(void)
{
    unsigned seed = 20261130u;
    double G[MAXN * MAXN], Gs[MAXN * MAXN], c[MAXN], cs[MAXN], A[MAXN * MAXN];
    double psi[MAXN], psis[MAXN], g[MAXN], gs[MAXN];
    signed char at[MAXN];
    double worst = 0, rates = 0, units = 0;
    int bounded = 0, inside = 0, trials = 0;
    for (int trial = 0; trial < TRIALS; trial++) {
        int n = 1 + trial % MAXN, rank = 1 + (trial / MAXN) % n;
        double scale = pow(10, 18 * (uniform(&seed) + 1) / 2 - 9);
        for (int i = 0; i < rank * n; i++)
            A[i] = uniform(&seed);
        for (int r = 0; r < n; r++)
            for (int k = 0; k < n; k++) {
                double s = 0;
                for (int i = 0; i < rank; i++)
                    s += A[i * n + r] * A[i * n + k];
                G[r * n + k] = scale * s;
            }
        /* c from a psi beyond the box half the time: some rows slip */
        double reach = trial % 2 ? 3 : 0.8;
        for (int r = 0; r < n; r++)
            psis[r] = reach * uniform(&seed);
        for (int r = 0; r < n; r++) {
            double s = 0;
            for (int k = 0; k < n; k++)
                s += G[r * n + k] * psis[k];
            c[r] = s;
        }
        solve(G, c, n, psi, at, g);
        double b = breach(G, c, n, psi);
        if (b > worst)
            worst = b;
        for (int r = 0; r < n; r++) {
            long double gr = -(long double)c[r], size = fabs(c[r]);
            for (int k = 0; k < n; k++)
                gr += (long double)G[r * n + k] * psi[k], size += fabs(G[r * n + k]);
            double off = size > 0 ? (double)(fabsl(gr - g[r]) / size) : 0;
            if (off > rates)
                rates = off;
            bounded += at[r] != 0;
            inside += at[r] == 0;
        }
        double s = pow(10, 12 * uniform(&seed));
        for (int i = 0; i < n * n; i++)
            Gs[i] = s * G[i];
        for (int r = 0; r < n; r++)
            cs[r] = s * c[r];
        solve(Gs, cs, n, psis, at, gs);
        for (int r = 0; r < n; r++) {
            double size = fabs(c[r]);
            for (int k = 0; k < n; k++)
                size += fabs(G[r * n + k]);
            if (size > 0 && fabs(gs[r] / s - g[r]) / size > units)
                units = fabs(gs[r] / s - g[r]) / size;
        }
        trials++;
    }
    CHECK(worst <= 1e-10, "Coulomb's conditions hold at box's psi in %d problems: worst "
          "breach %.2g of the terms' size (rows at a bound %d, inside %d)", trials, worst,
          bounded, inside);
    CHECK(bounded > TRIALS && inside > TRIALS, "both kinds of rows are met: %d at a bound, "
          "%d inside", bounded, inside);
    CHECK(rates <= 1e-12, "box's rates are G psi - c: worst %.2g of the terms' size", rates);
    CHECK(units <= 1e-12, "the problem in other units gives the same rates: worst %.2g of the "
          "terms' size", units);

    /* two rows alike (a foot's two points along one line), each bound
     * 1, asked 1.2 together: each holds 0.6 */
    double G2[4] = {1, 1, 1, 1}, c2[2] = {1.2, 1.2};
    solve(G2, c2, 2, psi, at, g);
    CHECK(fabs(psi[0] - 0.6) <= 1e-15 && fabs(psi[1] - 0.6) <= 1e-15 && !at[0] && !at[1],
          "two rows alike share alike: psi = %.17g, %.17g", psi[0], psi[1]);
    /* ... asked 3: both slide, at their bounds, the rate 1 each way */
    c2[0] = c2[1] = 3;
    solve(G2, c2, 2, psi, at, g);
    CHECK(psi[0] == 1 && psi[1] == 1 && fabs(g[0] + 1) <= 1e-15 && fabs(g[1] + 1) <= 1e-15,
          "two rows alike asked beyond their bounds both slide: psi = %g, %g, rates %g, %g",
          psi[0], psi[1], g[0], g[1]);

    double value = 0, reach = 0;
    least_largest(&seed, &value, &reach);
    CHECK(value <= 1e-12 && reach <= 1e-12, "the least largest share is the least over the "
          "problem's vertices (worst %.2g), and cheb's z reaches it (worst %.2g)", value, reach);
    double basis = 0, largest = 0;
    int beaten = 0, fixed_rows = 0;
    lexicographic(&seed, &basis, &largest, &beaten, &fixed_rows);
    CHECK(basis <= 1e-12 && largest <= 1e-12 && beaten == 0 && fixed_rows == 300,
          "the lexicographic least shares are the same from another basis and start, and "
          "with a row moved by rounding alone (worst %.2g; %d problems with a largest row "
          "no direction moves), their largest is the least largest (worst %.2g), and no "
          "nearby shares come before them (%d do)", basis, fixed_rows, largest, beaten);
    return check_done();
}

/*
 * One model written two ways gives the same motion (tests/sim/meson.build
 * builds this once per pair, each spec compiled and renamed
 * same_a_model, the model written out by hand, and same_b_model, written
 * with frames and points).  At 100 random states near the initial one
 * (coordinates and velocities moved by up to 0.3 (1 + |x|), time in
 * [0, 1]), projected onto the constraints, q'' and the multipliers agree
 * to 1e-13, each component relative to itself (plus a hundredth of its
 * own largest over the states, for one passing near zero).  Neither is
 * derived from the other: the hand-written one has its rotation matrices,
 * angular velocities and contact velocities worked out on paper.
 */
#include "../unit/check.h"
#include "eomc.h"

#include <stdlib.h>

extern const eomc_model same_a_model, same_b_model;
enum { NSTATES = 100 };
#define TOL 1e-13

int
main(void)
{
    const eomc_model *ma = &same_a_model, *mb = &same_b_model;
    CHECK(ma->nq == mb->nq && ma->nc == mb->nc && ma->np == mb->np,
          "%s and %s: the same coordinates, constraints and parameters", ma->name, mb->name);
    if (ma->nq != mb->nq || ma->nc != mb->nc)
        return check_done();
    int n = ma->nq, nc = ma->nc, N = n + nc, bad = 0;
    eomc_sim *sa = eomc_sim_alloc(ma), *sb = eomc_sim_alloc(mb);
    double q0[64], v0[64], q[64], v[64], aa[64], ab[64];
    double *A = calloc((size_t)(NSTATES * N), sizeof *A), *B = calloc((size_t)(NSTATES * N), sizeof *B);
    unsigned char ok[NSTATES] = {0};
    eomc_sim_initial(sa, q0, v0);
    for (int s = 0; s < NSTATES; s++) {
        double t = check_rand(0, 1);
        for (int i = 0; i < n; i++) {
            q[i] = q0[i] + 0.3 * (1 + fabs(q0[i])) * check_rand(-1, 1);
            v[i] = v0[i] + 0.3 * (1 + fabs(v0[i])) * check_rand(-1, 1);
        }
        if (eomc_sim_project(sa, t, q, v) != EOMC_OK || eomc_sim_accel(sa, t, q, v, aa) != EOMC_OK ||
            eomc_sim_accel(sb, t, q, v, ab) != EOMC_OK) {
            printf("# state %d: %s%s\n", s, eomc_sim_error(sa), eomc_sim_error(sb));
            bad++;
            continue;
        }
        ok[s] = 1;
        for (int i = 0; i < n; i++)
            A[s * N + i] = aa[i], B[s * N + i] = ab[i];
        for (int c = 0; c < nc; c++) {
            A[s * N + n + c] = eomc_sim_multipliers(sa)[c];
            B[s * N + n + c] = eomc_sim_multipliers(sb)[c];
        }
    }
    double worst_a = 0, worst_l = 0;
    for (int i = 0; i < N; i++) {
        double scale = 0;
        for (int s = 0; s < NSTATES; s++)
            if (ok[s])
                scale = fmax(scale, fabs(A[s * N + i]));
        for (int s = 0; s < NSTATES; s++) {
            if (!ok[s])
                continue;
            double e = fabs(B[s * N + i] - A[s * N + i]) /
                       fmax(fabs(A[s * N + i]) + 1e-2 * scale, 1e-300);
            if (i < n)
                worst_a = fmax(worst_a, e);
            else
                worst_l = fmax(worst_l, e);
        }
    }
    CHECK(bad == 0, "%s: %d random states projected and solved", ma->name, NSTATES - bad);
    CHECK(worst_a <= TOL, "%s with frames: q'' the same to %.2g relative", mb->name, worst_a);
    if (nc)
        CHECK(worst_l <= TOL, "%s with frames: multipliers the same to %.2g relative", mb->name,
              worst_l);
    eomc_sim_free(sa);
    eomc_sim_free(sb);
    free(A);
    free(B);
    return check_done();
}

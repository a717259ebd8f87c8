/*
 * Every form agrees, on one spec (tests/sim/meson.build builds this once
 * per spec in specs/, linking that spec compiled with each form and
 * constraint handling, each renamed v_TAG_model):
 *  - unconstrained: lagrange, maggi, nielsen, tzenoff and gibbs-appell;
 *  - constrained: the same with multipliers and with elimination
 *    (maggi is lagrange with elimination);
 *  - but no gibbs-appell for a spec with explicit kinetic terms, which
 *    define no acceleration energy (GIBBS_APPELL = 0).
 * At 100 random states near the spec's initial one (coordinates and
 * velocities moved by up to 0.3 (1 + |x|), time in [0, 1]), projected
 * onto the constraints so that they are consistent, every variant's q''
 * and multipliers equal the lagrange-with-multipliers ones to 1e-12,
 * each component relative to itself (plus a hundredth of its own largest
 * over the states, for one passing near zero).  Each form is derived from its own
 * definition, so agreement is the check.
 */
#include "../unit/check.h"
#include "eomc.h"

#include <stdlib.h>

#if GIBBS_APPELL && CONSTRAINED
#define VARIANTS X(lagrange) X(maggi) X(nielsen) X(tzenoff) X(gibbs_appell) \
    X(nielsen_elim) X(tzenoff_elim) X(gibbs_appell_elim)
#elif CONSTRAINED
#define VARIANTS X(lagrange) X(maggi) X(nielsen) X(tzenoff) X(nielsen_elim) X(tzenoff_elim)
#elif GIBBS_APPELL
#define VARIANTS X(lagrange) X(maggi) X(nielsen) X(tzenoff) X(gibbs_appell)
#else
#define VARIANTS X(lagrange) X(maggi) X(nielsen) X(tzenoff)
#endif

#define X(tag) extern const eomc_model v_##tag##_model;
VARIANTS
#undef X
#define X(tag) &v_##tag##_model,
static const eomc_model *const variants[] = {VARIANTS};
#undef X
enum { NV = sizeof variants / sizeof variants[0], NSTATES = 100 };

int
main(void)
{
    const eomc_model *ref = variants[0];
    int n = ref->nq, nc = ref->nc, bad_state = 0;
    eomc_sim *sim[NV];
    for (int k = 0; k < NV; k++)
        sim[k] = eomc_sim_alloc(variants[k]);
    double *q0 = calloc((size_t)n, sizeof *q0), *v0 = calloc((size_t)n, sizeof *v0);
    double *q = calloc((size_t)n, sizeof *q), *v = calloc((size_t)n, sizeof *v);
    double *a0 = calloc((size_t)n, sizeof *a0), *a = calloc((size_t)n, sizeof *a);
    double *l0 = calloc((size_t)nc + 1, sizeof *l0);
    double worst_a[NV] = {0}, worst_l[NV] = {0};
    int fails[NV] = {0};
    /* every state's values, for a tolerance per component: each compared
     * with itself, plus a hundredth of that component's largest over the
     * states (so that one passing near zero is not divided by ~0) */
    double *A0 = calloc((size_t)(NSTATES * n), sizeof *A0), *AK = calloc((size_t)(NV * NSTATES * n), sizeof *AK);
    double *L0 = calloc((size_t)(NSTATES * (nc + 1)), sizeof *L0), *LK = calloc((size_t)(NV * NSTATES * (nc + 1)), sizeof *LK);
    unsigned char *okst = calloc((size_t)(NV * NSTATES), 1);
    eomc_sim_initial(sim[0], q0, v0);
    for (int s = 0; s < NSTATES; s++) {
        double t = check_rand(0, 1);
        for (int i = 0; i < n; i++) {
            q[i] = q0[i] + 0.3 * (1 + fabs(q0[i])) * check_rand(-1, 1);
            v[i] = v0[i] + 0.3 * (1 + fabs(v0[i])) * check_rand(-1, 1);
        }
        if (eomc_sim_project(sim[0], t, q, v) != EOMC_OK ||
            eomc_sim_accel(sim[0], t, q, v, a0) != EOMC_OK) {
            printf("# state %d: %s\n", s, eomc_sim_error(sim[0]));
            bad_state++;
            continue;
        }
        okst[s] = 1;
        for (int i = 0; i < n; i++)
            A0[s * n + i] = a0[i];
        for (int c = 0; c < nc; c++)
            L0[s * (nc + 1) + c] = l0[c] = eomc_sim_multipliers(sim[0])[c];
        for (int k = 1; k < NV; k++) {
            if (eomc_sim_accel(sim[k], t, q, v, a) != EOMC_OK) {
                if (!fails[k]++)
                    printf("# %s: %s\n", variants[k]->form, eomc_sim_error(sim[k]));
                continue;
            }
            okst[k * NSTATES + s] = 1;
            for (int i = 0; i < n; i++)
                AK[(k * NSTATES + s) * n + i] = a[i];
            for (int c = 0; c < nc; c++)
                LK[(k * NSTATES + s) * (nc + 1) + c] = eomc_sim_multipliers(sim[k])[c];
        }
    }
    for (int i = 0; i < n + nc; i++) {
        int acc = i < n;
        double scale = 0;
        for (int s = 0; s < NSTATES; s++)
            if (okst[s])
                scale = fmax(scale, fabs(acc ? A0[s * n + i] : L0[s * (nc + 1) + i - n]));
        for (int k = 1; k < NV; k++)
            for (int s = 0; s < NSTATES; s++) {
                if (!okst[s] || !okst[k * NSTATES + s])
                    continue;
                double want = acc ? A0[s * n + i] : L0[s * (nc + 1) + i - n];
                double got = acc ? AK[(k * NSTATES + s) * n + i]
                                 : LK[(k * NSTATES + s) * (nc + 1) + i - n];
                double e = fabs(got - want) / fmax(fabs(want) + 1e-2 * scale, 1e-300);
                if (acc)
                    worst_a[k] = fmax(worst_a[k], e);
                else
                    worst_l[k] = fmax(worst_l[k], e);
            }
    }
    free(A0);
    free(AK);
    free(L0);
    free(LK);
    free(okst);
    CHECK(bad_state == 0, "%s: %d random states projected and solved by lagrange",
          ref->name, NSTATES - bad_state);
    for (int k = 1; k < NV; k++) {
        const eomc_model *m = variants[k];
        const char *how = m->nc ? (m->eliminate ? ", elimination" : ", multipliers") : "";
        CHECK(fails[k] == 0 && worst_a[k] <= 1e-12,
              "%s: %s%s q'' = lagrange's to %.2g relative", ref->name, m->form, how,
              worst_a[k]);
        if (nc)
            CHECK(fails[k] == 0 && worst_l[k] <= 1e-12,
                  "%s: %s%s lambda = lagrange's to %.2g relative", ref->name, m->form, how,
                  worst_l[k]);
    }
    if (!GIBBS_APPELL)
        printf("# %s: no gibbs-appell form: explicit kinetic terms define no S\n",
               ref->name);
    for (int k = 0; k < NV; k++)
        eomc_sim_free(sim[k]);
    free(q0), free(v0), free(q), free(v), free(a0), free(a), free(l0);
    return check_done();
}

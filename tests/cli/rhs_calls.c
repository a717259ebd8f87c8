/*
 * eomc_sim_accel called N times (argv[1]) at the state the benchmarks
 * time (bench/rhs_bench.c: q_i = 0.3 / (i + 1), v_i = 0.2, q_0 moved by
 * 1e-9 a call so that nothing is hoisted), for test_rhs_cost.sh to count
 * its instructions.  Prints the calls' status (0: all EOMC_OK) and the sum
 * of the last entry of q''.  Compiled with -DMODEL=NAME_model.
 */
#include <stdio.h>
#include <stdlib.h>

#include "eomc.h"

extern const eomc_model MODEL;

int
main(int argc, char **argv)
{
    const eomc_model *m = &MODEL;
    long calls = argc > 1 ? atol(argv[1]) : 1;
    int nq = m->nq, nv = eomc_nv(m), rc = 0;
    eomc_sim *s = eomc_sim_alloc(m);
    double *q = calloc((size_t)nq, sizeof *q), *v = calloc((size_t)nv, sizeof *v);
    double *a = calloc((size_t)nv, sizeof *a), sum = 0;
    if (!s || !q || !v || !a)
        return 1;
    for (int i = 0; i < nq; i++)
        q[i] = 0.3 / (i + 1);
    for (int i = 0; i < nv; i++)
        v[i] = 0.2;
    for (long k = 0; k < calls; k++) {
        q[0] = 0.3 + 1e-9 * (double)k;
        rc |= eomc_sim_accel(s, 0.0, q, v, a);
        sum += a[nv - 1];
    }
    printf("%d %.17g\n", rc, sum);
    free(q);
    free(v);
    free(a);
    eomc_sim_free(s);
    return 0;
}

/*
 * ns per right-hand side (generated M and h, then the runtime's solve) of
 * one generated model, a check that the right-hand side allocates
 * nothing, and ns per call of the model's full Jacobian (jacobian member).  Compiled by chain_bench.sh with -DMODEL=chainN_model and
 * -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "eomc.h"

extern const eomc_model MODEL;

static long nalloc;
void *__real_malloc(size_t n);
void *__real_calloc(size_t n, size_t k);
void *__real_realloc(void *p, size_t n);
void *__wrap_malloc(size_t n) { nalloc++; return __real_malloc(n); }
void *__wrap_calloc(size_t n, size_t k) { nalloc++; return __real_calloc(n, k); }
void *__wrap_realloc(void *p, size_t n) { nalloc++; return __real_realloc(p, n); }

static double
now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int
main(void)
{
    const eomc_model *m = &MODEL;
    int n = m->nq;
    eomc_sim *sim = eomc_sim_alloc(m);
    double *q = calloc((size_t)n, sizeof *q), *v = calloc((size_t)n, sizeof *v);
    double *a = calloc((size_t)n, sizeof *a), sum = 0;
    for (int i = 0; i < n; i++) {
        q[i] = 0.3 / (i + 1);
        v[i] = 0.2;
    }
    /* warm up, then time enough calls for ~0.3 s */
    long calls = 1000;
    double t0, t1;
    for (;;) {
        t0 = now();
        for (long k = 0; k < calls; k++) {
            q[0] = 0.3 + 1e-9 * (double)k; /* defeat hoisting */
            eomc_sim_accel(sim, 0.0, q, v, a);
            sum += a[n - 1];
        }
        t1 = now();
        if (t1 - t0 > 0.3)
            break;
        calls *= 4;
    }
    /* the Jacobian, timed the same way */
    double *dEdq = calloc((size_t)n * (size_t)n, sizeof *dEdq);
    double *dEdv = calloc((size_t)n * (size_t)n, sizeof *dEdv);
    double *dEdt = calloc((size_t)n, sizeof *dEdt);
    double *dEdu = calloc((size_t)(n * m->nu + 1), sizeof *dEdu);
    double *u = calloc((size_t)m->nu + 1, sizeof *u);
    long jcalls = 10;
    double j0, j1;
    for (;;) {
        j0 = now();
        for (long k = 0; k < jcalls; k++) {
            q[0] = 0.3 + 1e-9 * (double)k;
            m->jacobian(0.0, q, v, a, m->p_default, u, dEdq, dEdv, dEdu, dEdt);
            sum += dEdq[n * n - 1];
        }
        j1 = now();
        if (j1 - j0 > 0.3)
            break;
        jcalls *= 4;
    }
    long before = nalloc;
    for (int k = 0; k < 1000; k++)
        eomc_sim_accel(sim, 0.0, q, v, a);
    long allocs = nalloc - before;
    printf("%.1f %ld %.0f\n", (t1 - t0) / (double)calls * 1e9, allocs,
           (j1 - j0) / (double)jcalls * 1e9);
    fprintf(stderr, "(checksum %g)\n", sum);
    eomc_sim_free(sim);
    free(q);
    free(v);
    free(a);
    free(dEdq);
    free(dEdv);
    free(dEdt);
    free(dEdu);
    free(u);
    return allocs != 0;
}

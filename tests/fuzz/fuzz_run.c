/*
 * fuzz_run (fuzz.h): inputs run one at a time on a worker thread with a
 * 512 MB stack, started on the first input and kept: a thread per input
 * would map a new stack each time, and the sanitizer's shadow of every
 * stack ever touched would stay resident.
 */
#include "fuzz.h"

#include "base/diag.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

enum { STACK_BYTES = 512 << 20 }; /* as main.c */

static pthread_mutex_t mutex = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t changed = PTHREAD_COND_INITIALIZER;
static void (*job_fn)(void *ctx); /* the input to run, NULL when done */
static void *job_ctx;

static void *
worker(void *arg)
{
    (void)arg;
    pthread_mutex_lock(&mutex);
    for (;;) {
        while (!job_fn)
            pthread_cond_wait(&changed, &mutex);
        pthread_mutex_unlock(&mutex);
        job_fn(job_ctx);
        pthread_mutex_lock(&mutex);
        job_fn = NULL;
        pthread_cond_broadcast(&changed);
    }
    return NULL;
}

void
fuzz_run(void (*fn)(void *ctx), void *ctx)
{
    static int started;
    if (!started) {
        if (!getenv("EOMC_FUZZ_VERBOSE")) {
            FILE *devnull = fopen("/dev/null", "w");
            if (devnull)
                diag_set_output(devnull);
        }
        pthread_attr_t attr;
        pthread_t th;
        if (pthread_attr_init(&attr) != 0 ||
            pthread_attr_setstacksize(&attr, STACK_BYTES) != 0 ||
            pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED) != 0 ||
            pthread_create(&th, &attr, worker, NULL) != 0) {
            fprintf(stderr, "fuzz: cannot start the worker thread\n");
            abort();
        }
        pthread_attr_destroy(&attr);
        started = 1;
    }
    pthread_mutex_lock(&mutex);
    job_ctx = ctx;
    job_fn = fn;
    pthread_cond_broadcast(&changed);
    while (job_fn)
        pthread_cond_wait(&changed, &mutex);
    pthread_mutex_unlock(&mutex);
}

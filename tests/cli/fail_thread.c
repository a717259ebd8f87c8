/*
 * fail_thread: an LD_PRELOAD shim for test_threads.sh.  Its first
 * pthread_create fails with EAGAIN (as when a process may have no more
 * threads) and the others are libc's; it keeps the threads they made, and
 * says on stderr when pthread_join is given one it did not make, or when
 * the process ends with one of them not joined.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <pthread.h>
#include <stdio.h>

typedef int (*create_fn)(pthread_t *, const pthread_attr_t *, void *(*)(void *), void *);
typedef int (*join_fn)(pthread_t, void **);

enum { THREADS_MAX = 256 };
static pthread_t made[THREADS_MAX];
static int nmade, calls, joined[THREADS_MAX];

int
pthread_create(pthread_t *th, const pthread_attr_t *attr, void *(*fn)(void *), void *arg)
{
    create_fn real;
    *(void **)&real = dlsym(RTLD_NEXT, "pthread_create"); /* POSIX's way to a function */
    if (calls++ == 0 || !real || nmade == THREADS_MAX)
        return EAGAIN;
    int rc = real(th, attr, fn, arg);
    if (rc == 0)
        made[nmade++] = *th;
    return rc;
}

int
pthread_join(pthread_t th, void **ret)
{
    join_fn real;
    *(void **)&real = dlsym(RTLD_NEXT, "pthread_join");
    int k = 0;
    while (k < nmade && !pthread_equal(made[k], th))
        k++;
    if (k == nmade || !real) {
        fputs("fail_thread: pthread_join of a thread never created\n", stderr);
        return ESRCH;
    }
    joined[k] = 1;
    return real(th, ret);
}

__attribute__((destructor)) static void
all_joined(void)
{
    for (int k = 0; k < nmade; k++)
        if (!joined[k])
            fputs("fail_thread: a thread created was never joined\n", stderr);
}

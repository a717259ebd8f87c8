/*
 * friction: dry friction in doubles (friction.h), stick.h's functions.
 */
#include "friction.h"

#include <float.h>

#define STICK_REAL double
#define STICK_EPS DBL_EPSILON
#define STICK_MODEL eomc_model
#define STICK_(name) fric_##name
#define STICK_API
#include "stick.h"

int fric_bad(const Fric *w) { return w->bad; }
double fric_bound_of(const Fric *w, int j) { return w->F[j]; }
double fric_phi(const Fric *w, int j) { return w->phi[j]; }
double fric_pivot(const Fric *w) { return w->pivot; }

double
fric_condition(Fric *w, double *near)
{
    int n = w->nR;
    for (int j = 0; j < w->nf; j++)
        near[j] = 0;
    if (w->rank < 2)
        return 1;
    /* G again (eigen destroyed it), balanced by its diagonal: free of the
     * items' bounds and of their rows' sizes, so that only the rows'
     * directions (in the metric M_FF^-1) count; in the spread's scratch */
    double *B = w->lp, *E = w->lx, *ev = E + (size_t)n * n;
    fric_gram(w, B);
    for (int r = 0; r < n; r++)
        ev[r] = B[r * n + r] > 0 ? 1 / sqrt(B[r * n + r]) : 0;
    for (int r = 0; r < n; r++)
        for (int s = 0; s < n; s++)
            B[r * n + s] *= ev[r] * ev[s];
    fric_jacobi(B, E, ev, n);
    /* the rank-th largest: the least of the directions the solve counts */
    int *order = w->lxi;
    for (int i = 0; i < n; i++)
        order[i] = i;
    for (int i = 0; i < n; i++)
        for (int k = i + 1; k < n; k++)
            if (ev[order[k]] > ev[order[i]]) {
                int o = order[i];
                order[i] = order[k], order[k] = o;
            }
    int top = order[0], least = order[w->rank - 1];
    double most = 0;
    for (int r = 0; r < n; r++)
        most = fmax(most, fabs(E[r * n + least]));
    for (int r = 0; r < n; r++)
        near[w->R[r]] = most > 0 ? fabs(E[r * n + least]) / most : 0;
    return ev[least] > 0 ? ev[top] / ev[least] : INFINITY;
}

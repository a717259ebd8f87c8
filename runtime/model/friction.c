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

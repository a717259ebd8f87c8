/*
 * methods.h: the integration methods (methods.c), for the step layer
 * (evolve.c).  Not installed, and nothing of it leaves the library.
 */
#ifndef EOMC_METHODS_H
#define EOMC_METHODS_H

#include <gsl/gsl_odeiv2.h>

typedef struct Method {
    const char *name;
    const gsl_odeiv2_step_type *const *adaptive; /* GSL's pointer variable; it
                                                  * holds NULL for Taylor's method
                                                  * (taylor.h), which is not GSL's */
    const gsl_odeiv2_step_type *const *fixed;    /* NULL: no fixed steps */
    int own_fixed;                               /* fixed is fixed.c's */
    int jacobian;                                /* solves with the Jacobian */
    const char *description;
} Method;

/* The method of that name (methods.def), or NULL. */
const Method *method_find(const char *name);

#endif

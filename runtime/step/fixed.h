/*
 * fixed: steppers for fixed-step runs of the methods whose GSL steppers
 * estimate their error by step doubling (rk4, rk1imp, rk2imp, rk4imp).
 * GSL's take a whole step and two half steps for every step, three times
 * the method's own work; a fixed-step run has no use for the estimate.
 * These take one step of the same method and report a zero error.  They
 * are GSL odeiv2 step types, so the driver treats them like GSL's own.
 */
#ifndef EOMC_FIXED_H
#define EOMC_FIXED_H

#include <gsl/gsl_odeiv2.h>

/* The classical Runge-Kutta 4: four right-hand sides a step (the first
 * is the last step's dydt_out). */
extern const gsl_odeiv2_step_type *const fixed_rk4;
/* Implicit Euler, the implicit midpoint rule and the 2-stage Gauss
 * method: a simplified Newton iteration on the stages with the exact
 * Jacobian at the step's start, which must reach the driver's tolerances
 * as GSL's own implicit steppers' do (the driver must be set), and goes
 * on to the rounding of the stage values (fixed.c). */
extern const gsl_odeiv2_step_type *const fixed_rk1imp;
extern const gsl_odeiv2_step_type *const fixed_rk2imp;
extern const gsl_odeiv2_step_type *const fixed_rk4imp;

#endif

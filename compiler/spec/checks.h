/*
 * checks: the physical data's conditions on the parameters (masses not
 * negative, inertias positive definite and of some distribution of mass,
 * fixed axes not zero).  Each is checked now with the parameters'
 * defaults, and kept in Spec.check for the simulator to check again with
 * the values --set gives.
 */
#ifndef EOMC_SPEC_CHECKS_H
#define EOMC_SPEC_CHECKS_H

#include "names.h"

/* A turn's axis of parameters, |a|^2 at node n of frame name: frames are
 * built before the parameters' values are read, so its check waits. */
struct AxisCheck {
    ExprId n2;
    const yaml_node_t *n;
    const char *name;
    AxisCheck *next;
};

/* The parameters' default values (they must be loaded). */
const double *spec_defaults(Loader *L);
/* Require e > 0 (strict) or e >= 0 for the datum at n: an error at n
 * saying what fmt says (show: and e's value), and Spec.check. */
void spec_require(Loader *L, ExprId e, int strict, const yaml_node_t *n, int show,
                  const char *fmt, ...);
/* A mass at n, of parameters, not negative. */
ExprId spec_mass(Loader *L, const yaml_node_t *n, const char *kind, const char *name);
/* Body b's inertia, loaded from n: what an inertia must be. */
void spec_require_inertia(Loader *L, const yaml_node_t *n, const SpecBody *b);
/* Every fixed axis of L->axes: not zero with the parameters' values. */
void spec_check_axes(Loader *L);

#endif

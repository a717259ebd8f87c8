/*
 * reffric: dry friction in extended precision (reffric.h).
 */
#include "reffric.h"

#include <float.h>

#define STICK_REAL eomc_ext
#define STICK_EPS LDBL_EPSILON
#define STICK_MODEL eomc_model_ext
#define STICK_(name) reffric_##name
#define STICK_API
#include "model/stick.h"

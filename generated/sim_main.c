/* The simulator of one of generated/'s models, for the tests: the main
 * that compiling the model's file with -DEOMC_MAIN would add, here apart,
 * so that the model itself is compiled once (model_lib) for every test
 * that links it.  SIM_NAME is the model's name (-DSIM_NAME=pendulum). */
#include "eomc_main.h"

#define SIM_CAT(a, b) a##b
#define SIM_XCAT(a, b) SIM_CAT(a, b)
#define SIM_MODEL SIM_XCAT(SIM_NAME, _model)
#define SIM_MODEL_EXT SIM_XCAT(SIM_NAME, _model_ext)

extern const eomc_model SIM_MODEL;
extern const eomc_model_ext SIM_MODEL_EXT;
EOMC_DEFINE_MAIN(SIM_MODEL, SIM_MODEL_EXT)

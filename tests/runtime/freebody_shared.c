/*
 * freebody_shared.c: the free body of freebody.c as `eomc build --shared`
 * makes a model's library (the model, its twin and the whole runtime,
 * eomc_shared_model naming it), for the Python package's tests.
 */
#define EOMC_SHARED
#include "eomc_main.h"
#include "models.h"

EOMC_DEFINE_MAIN(freebody_model, freebody_model_ext)

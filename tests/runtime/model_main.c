/*
 * model_main.c: a standalone simulator of one hand-written model, as
 * `eomc build` makes one; SIM_MODEL names the model and SIM_EXT, when
 * given, its extended-precision twin (see meson.build).
 */
#include "eomc.h"
#include "models.h"

int
main(int argc, char **argv)
{
#ifdef SIM_EXT
    return eomc_main(argc, argv, &SIM_MODEL, &SIM_EXT);
#else
    return eomc_main(argc, argv, &SIM_MODEL, NULL);
#endif
}

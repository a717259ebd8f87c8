/*
 * model_main.c: a standalone simulator of one hand-written model, as
 * `eomc build` makes one; SIM_MODEL names the model (see meson.build).
 */
#include "eomc.h"
#include "models.h"

int
main(int argc, char **argv)
{
    return eomc_main(argc, argv, &SIM_MODEL, NULL);
}

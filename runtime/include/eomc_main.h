/*
 * eomc_main.h: the main of a simulator, for the generated file's
 * EOMC_MAIN part.  It is eomc_main, or eomc_mpi_main where the file is
 * compiled with -DEOMC_MPI (eomc build --mpi: a sweep over the ranks).
 *
 *     EOMC_DEFINE_MAIN(pendulum_model, pendulum_model_ext)
 *
 * defines main for that model and its extended-precision twin (a weak
 * symbol the generated file declares: NULL where eomc build did not link
 * the twin, and the simulator then runs without a reference solution).
 *
 * Compiled with -DEOMC_SHARED instead (eomc build --shared: a shared
 * library of the model and the runtime), the same line defines no main
 * but the model and its twin under fixed names, for a caller that opens
 * the library by path and cannot know the model's name first: the Python
 * package, through ctypes.
 */
#ifndef EOMC_MAIN_H
#define EOMC_MAIN_H

#include "eomc.h"

#ifdef EOMC_MPI
#include "eomc_mpi.h"
#define EOMC_MAIN_FN eomc_mpi_main
#else
#define EOMC_MAIN_FN eomc_main
#endif

#ifdef EOMC_SHARED
const eomc_model *eomc_shared_model(void);
const eomc_model_ext *eomc_shared_model_ext(void); /* NULL: built without */
#define EOMC_DEFINE_MAIN(model, model_ext)                                  \
    const eomc_model *eomc_shared_model(void) { return &(model); }         \
    const eomc_model_ext *eomc_shared_model_ext(void) { return &(model_ext); }
#else
#define EOMC_DEFINE_MAIN(model, model_ext)                                  \
    int main(int argc, char **argv)                                        \
    {                                                                      \
        return EOMC_MAIN_FN(argc, argv, &(model), &(model_ext));          \
    }
#endif

#endif

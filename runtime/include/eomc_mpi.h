/*
 * eomc_mpi.h: a sweep over the ranks of an MPI job.  `eomc build --mpi`
 * compiles the generated simulator with mpicc and -DEOMC_MPI, and its
 * main is then eomc_mpi_main: MPI_Init, the ranks share the sweep's runs
 * (runtime/front/sweep.c: run j on rank j mod size), rank 0 gathers the rows and
 * writes the summary in sweep order, MPI_Finalize.  A run that is not a
 * sweep is done by rank 0 alone.  Header-only, so that the runtime library
 * itself never needs MPI.
 */
#ifndef EOMC_MPI_H
#define EOMC_MPI_H

#include <mpi.h>
#include <stdlib.h>

#include "eomc.h"

static int
eomc_mpi_gather(const char *mine, size_t len, char **all, size_t **lens)
{
    int rank, size, mylen = (int)len, ok = len <= (size_t)0x7fffffff;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    int *counts = rank == 0 ? calloc((size_t)size, sizeof *counts) : NULL;
    int *displs = rank == 0 ? calloc((size_t)size, sizeof *displs) : NULL;
    *all = NULL;
    *lens = NULL;
    if (MPI_Gather(&mylen, 1, MPI_INT, counts, 1, MPI_INT, 0, MPI_COMM_WORLD) != MPI_SUCCESS)
        ok = 0;
    long total = 0;
    if (rank == 0 && counts && displs) {
        for (int r = 0; r < size; r++)
            displs[r] = (int)total, total += counts[r];
        *all = malloc((size_t)total + 1);
        *lens = calloc((size_t)size, sizeof **lens);
        for (int r = 0; *lens && r < size; r++)
            (*lens)[r] = (size_t)counts[r];
    }
    if (MPI_Gatherv(mine, mylen, MPI_CHAR, *all, counts, displs, MPI_CHAR, 0,
                    MPI_COMM_WORLD) != MPI_SUCCESS)
        ok = 0;
    if (rank == 0 && (!*all || !*lens))
        ok = 0;
    free(counts);
    free(displs);
    return ok ? 0 : -1;
}

static int
eomc_mpi_main(int argc, char **argv, const eomc_model *m, const eomc_model_ext *x)
{
    static eomc_parallel p;
    MPI_Init(&argc, &argv);
    MPI_Comm_rank(MPI_COMM_WORLD, &p.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &p.size);
    p.gather = eomc_mpi_gather;
    eomc_set_parallel(&p);
    int rc = eomc_main(argc, argv, m, x), worst = rc;
    MPI_Allreduce(&rc, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    MPI_Finalize();
    return worst;
}

#endif

/*
 * build: turn generated C into a simulator executable with $CC, and keep
 * built simulators and the objects they link in a cache keyed by content.
 */
#ifndef EOMC_BUILD_H
#define EOMC_BUILD_H

#include <stddef.h>

/* Whether path names something other than a regular file or nothing (a
 * device such as /dev/null, a pipe): written in place, since renaming a
 * temporary file over it would replace the device itself. */
int build_is_special(const char *path);

/* Compile c_file, the C of the model named model, with the runtime into
 * exe (written to a temporary name and renamed when complete): as the
 * translation units it has (units, emit_model's EMIT_UNIT1 | ...: each
 * -DEOMC_UNIT=k, emit.h), and, if
 * twin, a second time with EOMC_EXTENDED for the reference solution
 * (through a file model_ext.c written next to it); the main in a unit of
 * its own (main.c, next to it).  The compilations run at once, each unit
 * position-independent, and each object is kept in the object cache under
 * its content (docs/internals.md): a unit compiled before, for a
 * simulator or a library, is not compiled again.  Everything but exe and
 * the cache is removed.  mpi: with $EOMC_MPICC (default mpicc) and
 * -DEOMC_MPI, so that its main shares a sweep among the ranks of an MPI
 * job (runtime/include/eomc_mpi.h).  shared: a shared library instead
 * (-DEOMC_SHARED: no main, the model under fixed names, eomc_main.h)
 * holding the whole runtime, for the Python package.  native: the units
 * for this CPU's instruction set (build_native_flags).  Returns 0, or -1
 * after printing why. */
int build_executable(const char *c_file, const char *model, const char *exe, int mpi,
                     int units, int twin, int shared, int native);

/* Where `eomc run` keeps the simulator for this key; the directory is
 * created.  Returns a malloc'd path, or NULL after printing why. */
char *build_cache_path(const char *name, const char *key_text, size_t len);

#endif

/*
 * taylor_ops_ext.c: eomc_taylor.h in extended precision (EOMC_EXTENDED,
 * as the model's twin compiles it), for test_taylor_ops.c.
 */
#define EOMC_EXTENDED
#define TAY_RUN taylor_run_ext
#include "taylor_ops_run.h"

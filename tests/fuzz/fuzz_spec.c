/*
 * Fuzz target: the spec loader.  The input is a spec's text; any error
 * is fine, a crash, a sanitizer report, a leak or a hang is not.
 */
#include "fuzz.h"

#include "spec/spec.h"

typedef struct Input {
    const uint8_t *data;
    size_t size;
} Input;

static void
load(void *ctx)
{
    Input *in = ctx;
    Arena *A = arena_new();
    ExprPool *P = expr_pool_new();
    spec_load_buffer("fuzz.yaml", (const char *)in->data, in->size, NULL, A, P);
    diag_forget_sources(); /* they borrow the input and the arena */
    expr_pool_free(P);
    arena_free(A);
}

FUZZ_ENTRY(spec)
{
    Input in = {data, size};
    fuzz_run(load, &in);
    return 0;
}

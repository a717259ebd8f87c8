/*
 * Fuzz target: the whole compiler on specs that load.  A spec that the
 * loader accepts goes through mech_build, constraints_build, eom_derive
 * and emit_model (to /dev/null), with a form and a handling of the
 * constraints chosen by a hash of the input.  Errors are fine; crashes,
 * sanitizer reports, leaks and hangs are not.  Inputs are kept small (few
 * coordinates, few nodes after loading) so that each runs in milliseconds.
 */
#include "fuzz.h"

#include "mechanics/constraint.h"
#include "emit/emit.h"
#include "spec/spec.h"

#include <setjmp.h>
#include <stdio.h>

enum { MAX_COORDS = 4, MAX_CONSTRAINTS = 2, MAX_NODES = 3000 };

typedef struct Input {
    const uint8_t *data;
    size_t size;
} Input;

static void
compile(void *ctx)
{
    Input *in = ctx;
    static FILE *devnull;
    if (!devnull)
        devnull = fopen("/dev/null", "w");
    uint32_t h = 2166136261u; /* FNV-1a */
    for (size_t i = 0; i < in->size; i++)
        h = (h ^ in->data[i]) * 16777619u;
    static const Form *const forms[] = {&form_lagrange, &form_nielsen, &form_tzenoff,
                                        &form_gibbs_appell, &form_maggi};
    const Form *form = forms[h % 5];
    int eliminate = form->eliminate || (h >> 8) % 4 == 0;
    int jacobian = (int)((h >> 12) % 3);

    Arena *A = arena_new();
    ExprPool *P = expr_pool_new();
    Diff *D = diff_new(P);
    Spec *s = spec_load_buffer("fuzz.yaml", (const char *)in->data, in->size, NULL, A, P);
    jmp_buf jb;
    jmp_buf *old = diag_set_jump(&jb);
    int small = s && s->nq <= MAX_COORDS && s->nconstraint <= MAX_CONSTRAINTS &&
                expr_pool_size(P) <= MAX_NODES;
    if (setjmp(jb) == 0) {
        if (small) {
            const char *why;
            Mech *m = mech_build(s, A, P, D);
            Constraints *c = constraints_build(s, m, A, P, D);
            Invariant *inv = invariant_derive(s, m, c, A, P, D);
            Eom *e = eom_derive(s, m, form, A, P, D, &why);
            if (e && devnull) {
                EmitInfo info = {.version = "fuzz", .options = "", .eliminate = eliminate};
                EmitStats st[EMIT_NFUNCS];
                Lowered *L = lower_model(s, m, e, c, 0, inv, jacobian, LOWER_CODE_AUTO, 1, A, P, D);
                emit_model(devnull, L, P, &info, st);
            }
        }
    }
    diag_set_jump(old);
    diag_forget_sources();
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
}

FUZZ_ENTRY(pipeline)
{
    Input in = {data, size};
    fuzz_run(compile, &in);
    return 0;
}

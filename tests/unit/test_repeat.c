/*
 * Unit tests of repeat.c, without compiling any C: a model of three
 * identical driven double pendulums and a fourth of another length,
 * lowered; its accel_solve split into one copy and a loop
 * (repeat_split, every saving accepted) must
 *   find the three copies, their shifts (coordinates 0, 2, 4; inputs 0,
 *   1, 2), and not the fourth, whose expressions differ;
 *   give, through lower_eval's loop over the shifted arrays, the very
 *   bits of the unsplit function at random states;
 * a function whose outputs are not one slot per coordinate (the full
 * mass matrix) is not split; and a unit load's copies without a load
 * store zeros only where their outputs vanish with it.
 */
#include "check.h"
#include "forms/forms.h"
#include "lower/lower.h"
#include "lower/lower_schedule.h"
#include "lower/repeat.h"

#include <stdint.h>
#include <string.h>

static Arena *A;
static ExprPool *P;
static Diff *D;

#define PENDULUM(i, len)                                                               \
    "  top" #i ": {mass: m, position: [\"" len "*sin(a" #i ")\", \"-" len "*cos(a" #i     \
    ")\"]}\n"                                                                          \
    "  bob" #i ": {mass: m, position: [\"" len "*sin(a" #i ") + " len "*sin(b" #i         \
    ")\", \"-" len "*cos(a" #i ") - " len "*cos(b" #i ")\"]}\n"

static const char *const spec_text =
    "parameters: {m: 0.7, l: 0.9, l4: 1.3, g: 9.81, c: 0.2}\n"
    "coordinates: [a1, b1, a2, b2, a3, b3, a4, b4]\n"
    "inputs: {u1: 0.3*sin(t), u2: 0.4*cos(t), u3: 0.5, u4: 0.1*t}\n"
    "particles:\n" PENDULUM(1, "l") PENDULUM(2, "l") PENDULUM(3, "l") PENDULUM(4, "l4")
    "effects:\n"
    "  gravity: {gravity: [0, -g]}\n"
    "  drive: [{work: \"u1*delta(a1)\"}, {work: \"u2*delta(a2)\"}, {work: \"u3*delta(a3)\"},\n"
    "          {work: \"u4*delta(a4)\"}]\n"
    "  damper: [{work: \"-c*b1'*delta(b1)\"}, {work: \"-c*b2'*delta(b2)\"},\n"
    "           {work: \"-c*b3'*delta(b3)\"}, {work: \"-c*b4'*delta(b4)\"}]\n";

enum { N = 8, NU = 4 };
static const double pdef[] = {0.7, 0.9, 1.3, 9.81, 0.2};

/* uniform in [-1, 1) (splitmix64) */
static double
uniform(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    return 2 * ((double)(z >> 11) * 0x1p-53) - 1;
}

/* A unit load's function by hand, "t q v p u da > y", three copies of
 * y_j = (2 + sin q_j) da_j + q_{j+1} da_{j+1} on pairs (j, j+1): linear in
 * the load, so a copy without one stores zeros (zero_skip); and the same
 * plus a constant 1 in every y, which does not vanish with the load. */
static const LowSig s_load = {"load", "a test's unit load", "t q v p u da > y", 0};

static LowFunc
load_function(int affine)
{
    LowFunc f = {.sig = &s_load, .per_step = 1};
    f.out = arena_new_array(A, LowSlot, 6), f.cap = 6;
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 2; k++) {
            int j = 2 * c + k, o = 2 * c + 1 - k;
            ExprId e = expr_add(P,
                expr_mul(P, expr_add(P, expr_const(P, 2), expr_unary(P, EXPR_SIN, expr_var(P, j, 0))),
                         expr_seed(P, j, 2)),
                expr_mul(P, expr_var(P, o, 0), expr_seed(P, o, 2)));
            if (affine)
                e = expr_add(P, e, EXPR_ONE);
            f.out[f.nout++] = (LowSlot){e, 0, j};
        }
    return f;
}

static void
test_zero_skip(void)
{
    LowFunc f = load_function(0), g = f;
    int split = repeat_split(&g, 6, 0, 0, A, P);
    CHECK(split && g.ncopy == 3 && g.zero_skip && g.span0 == 0 && g.span == 2,
          "a load's function: three copies, zero_skip (y vanishes with da)");
    double q[6] = {0.3, -1.1, 2.0, 0.7, -0.4, 1.9}, da[6] = {0, 0, 1.5, -0.5, 0, 0};
    double want[6], got[6];
    ExprEnv env = {0, {q, NULL, NULL, NULL}, NULL, NULL, {NULL, NULL, da}, NULL, NULL};
    lower_eval(P, &f, &env, (double *const[]){want});
    memset(got, 0xff, sizeof got);
    lower_eval(P, &g, &env, (double *const[]){got});
    CHECK(!memcmp(want, got, sizeof want) && got[0] == 0 && got[5] == 0,
          "unloaded copies store zeros, the loaded one its values: the unsplit bits");
    LowFunc h = load_function(1);
    CHECK(repeat_split(&h, 6, 0, 0, A, P) && h.ncopy == 3 && !h.zero_skip,
          "y = ... + 1: copies, but no zero_skip (y does not vanish with the load)");
}

int
main(void)
{
    A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    Spec *s = spec_load_buffer("r.yaml", spec_text, strlen(spec_text), NULL, A, P);
    CHECK(s != NULL, "the spec loads");
    if (!s)
        return check_done();
    Mech *m = mech_build(s, A, P, D);
    Invariant *inv = invariant_derive(s, m, NULL, A, P, D);
    const char *why;
    Eom *e = eom_derive(s, m, form_find("lagrange"), A, P, D, &why);
    Lowered *L = lower_model(s, m, e, NULL, 0, inv, LOWER_JACOBIAN_NONE, LOWER_CODE_STRAIGHT, 0,
                             A, P, D);
    const LowFunc *f = lower_find(L, "accel_solve");
    CHECK(f && !f->copy, "accel_solve: straight-line as lowered (below REPEAT_MIN_SAVED)");
    if (!f)
        return check_done();
    LowFunc g = *f;
    int split = repeat_split(&g, N, NU, 0, A, P);
    CHECK(split && g.ncopy == 3 && g.dq[0] == 0 && g.dq[1] == 2 && g.dq[2] == 4 &&
              g.du[0] == 0 && g.du[1] == 1 && g.du[2] == 2,
          "three copies found, shifted by 0, 2, 4 coordinates and 0, 1, 2 inputs (%d)",
          split ? g.ncopy : 0);
    /* what stays straight: the fourth's six slots, and values of the
     * parameters alone (M_kk of a top is 2 m l^2 wherever it swings) */
    int fourth = 0, other = 0, first = 1;
    for (int k = 0; split && k < g.nout; k++) {
        fourth += g.out[k].index >= 6;
        other += g.out[k].index < 6 && !expr_is_coeff(P, g.out[k].e);
    }
    for (int k = 0; split && k < g.copy->nout; k++)
        first &= g.copy->out[k].index < 2;
    CHECK(split && first && fourth == 6 && other == 0,
          "the copy stores pendulum 1's slots; the fourth (length l4) stays as it was, with "
          "only values of the parameters beside it (%d copied, %d kept)",
          split ? g.copy->nout : 0, g.nout);
    CHECK(lower_size(&g, 0) == N && lower_size(&g, 1) == N && lower_size(&g, 2) == N,
          "sizes with the copies: %d %d %d", lower_size(&g, 0), lower_size(&g, 1),
          lower_size(&g, 2));
    uint64_t seed = 7;
    int same = 1;
    for (int r = 0; r < 20; r++) {
        double q[N], v[N], u[NU], want[3][N], got[3][N];
        for (int i = 0; i < N; i++)
            q[i] = 3 * uniform(&seed), v[i] = 2 * uniform(&seed);
        for (int i = 0; i < NU; i++)
            u[i] = uniform(&seed);
        ExprEnv env = {0.3 * r, {q, v, NULL, NULL}, pdef, u, {NULL, NULL, NULL}, NULL, NULL};
        lower_eval(P, f, &env, (double *const[]){want[0], want[1], want[2]});
        memset(got, 0xff, sizeof got);
        lower_eval(P, &g, &env, (double *const[]){got[0], got[1], got[2]});
        same &= !memcmp(want, got, sizeof want);
    }
    CHECK(same, "split and unsplit: the same bits of a, piv and mkk at 20 random states");
    test_zero_skip();
    const LowFunc *mb = lower_find(L, "mass_bias");
    LowFunc h = *mb;
    CHECK(mb && !repeat_split(&h, N, NU, 0, A, P) && !h.copy,
          "mass_bias (M[i*n + j], not a slot per coordinate): not split");
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}

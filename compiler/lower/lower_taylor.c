/*
 * lower_taylor: the program of the model's taylor member (eomc_model.h),
 * Taylor's method's series of M, h and the event functions g, as a list
 * of calls of runtime/include/eomc_taylor.h (lowered.h's LowTaylor) that the
 * emitter prints.
 *
 * Every node that mass_bias or events computes gets a slot, its series:
 * one slot per DAG node (the DAG is hash-consed, so a shared value is one
 * series), in id order, which is a topological order.  Leaves are written
 * by the caller (q, q') or are constant in t (constants, parameters,
 * derived values, inputs held), but t itself.  An operator is one call,
 * with auxiliary slots where its recurrence needs a second series (tan's
 * 1 + tan^2, asin's 1 - a^2 and its root) or where it is written with
 * others (an integer power by squaring, a real power of a varying
 * exponent as exp(b log a)).  The sine and the cosine of one angle are
 * one call (each needs the other's series), and so are sinh and cosh.
 * A product by a value constant in t is a scale, not a convolution.
 *
 * The calls are then put in levels, each after every call whose result
 * it reads (order k of a level needs order k of the levels before it
 * and nothing of its own), and the products of a level go four (or two)
 * to a call, mul4: one loop over the order with four sums, each added
 * up in the same order as alone, so the same bits, in three quarters of
 * the time (chain5's series, measured).  A product alone is a short loop
 * whose every step waits on the last one's sum.
 *
 * With constraints the program also has the series of f, of B = df/dq''
 * and of the constraints' own levels (c_levels: Baumgarte's
 * stabilization adds them to f), and the runtime solves the KKT system
 * order by order.  When every constraint is affine in q'' (f = B q'' +
 * b), f's DAG is read with the accelerations 0, which gives b; when one
 * is not, the accelerations are slots the caller writes, as q and q'.
 *
 * With speeds of their own (a quaternion's angular velocity, spec.h) the
 * leaves the caller writes are q and the speeds v, M and h are in the
 * speeds, and the program also has the series of the kinematic equation
 * q' = W(q) v (qdot's outputs, a quaternion's bilinear products of e and
 * w), from which the runtime sums q: its coefficient k needs q's and v's
 * up to k, which the caller has written by then.
 */
#include "lower_taylor.h"
#include "lower_series.h"
#include "expr/monomial.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* How an acceleration q'' reads: nowhere (an unconstrained model's
 * functions have none), as 0 (every constraint affine: f's DAG then gives
 * b = f at q'' = 0), or as a series the caller writes (taylor_a: a
 * constraint nonlinear in q''). */
enum { ACCEL_NONE, ACCEL_ZERO, ACCEL_SLOT };

typedef struct Build {
    ExprPool *P;
    const int *derived; /* per node id its index in pd[], -1: not derived */
    size_t nderived;    /* derived's length */
    int np;
    int accel;          /* how q'' reads (only constraint's f reads it) */
    const int *vslot;   /* per leaf coordinate its velocity slot (lowered.h) */
    int nu;             /* inputs: mode k is u[nu + mode_slot[k]] */
    const int *mode_slot;
    int *slot;          /* per node id, -1: none */
    unsigned char *konst; /* per node id: constant in t */
    int *pair;          /* per operand id: sin, cos, sinh, cosh slots (-1) */
    int nslot;
    LowTayStep *step;
    int nstep, cap;
    const char *why;
} Build;

static int
new_slot(Build *b)
{
    return b->nslot++;
}

/* Append the call eomc_tay_CALL(slots..., k). */
static LowTayStep *
call(Build *b, const char *name, int n, int s0, int s1, int s2, int s3)
{
    if (b->nstep == b->cap) {
        b->cap = b->cap ? 2 * b->cap : 64;
        b->step = xrealloc(b->step, (size_t)b->cap * sizeof *b->step);
    }
    LowTayStep *st = &b->step[b->nstep++];
    /* sincos and sinhcosh write two series, the others one and their
     * auxiliary ones */
    static const char *const two[] = {"sincos", "sinhcosh", "tan", "tanh", "atan", "atan2"};
    int nres = !strcmp(name, "asin") || !strcmp(name, "acos") ? 3 : 1;
    for (size_t j = 0; j < sizeof two / sizeof two[0]; j++)
        if (!strcmp(name, two[j]))
            nres = 2;
    *st = (LowTayStep){.call = name, .nslot = n, .nres = nres, .slot = {s0, s1, s2, s3},
                       .src = LOW_TAY_SRC_NONE};
    return st;
}

/* A series constant in t: the value from src. */
static int
constant(Build *b, int src, int index, double value)
{
    int s = new_slot(b);
    LowTayStep *st = call(b, "const", 1, s, -1, -1, -1);
    st->src = src, st->index = index, st->value = value;
    return s;
}

static int power_aux(Build *b, int base, int m);

/* dst = base^m, m >= 2, by squaring. */
static void
power_into(Build *b, int dst, int base, int m)
{
    if (m % 2 == 0)
        call(b, "sqr", 2, dst, power_aux(b, base, m / 2), -1, -1);
    else
        call(b, "mul", 3, dst, power_aux(b, base, m - 1), base, -1);
}

/* base^m in a slot of its own (base itself for m = 1). */
static int
power_aux(Build *b, int base, int m)
{
    if (m == 1)
        return base;
    int s = new_slot(b);
    power_into(b, s, base, m);
    return s;
}

/* The sine (which 0) or cosine (1) of a, or hyperbolic (2, 3): both made
 * by one call where the first of them is met. */
static int
pair_slot(Build *b, ExprId a, int which)
{
    int *p = &b->pair[4 * (size_t)a + (which & 2)];
    if (p[0] < 0) {
        p[0] = new_slot(b);
        p[1] = new_slot(b);
        call(b, which & 2 ? "sinhcosh" : "sincos", 3, p[0], p[1], b->slot[a], -1);
    }
    return p[which & 1];
}

/* The program in levels (above), each level's products grouped: the
 * steps of b reordered in place, a level's other calls first, in their
 * order, then its products.  A slot with two writers (none is made now)
 * would make the order matter beyond reads: the program is then left as
 * it is. */
static void
schedule(Build *b)
{
    int n = b->nstep, top = 0, twice = 0;
    int *writer = xmalloc(((size_t)b->nslot + 1) * sizeof *writer);
    int *level = xmalloc(((size_t)n + 1) * sizeof *level);
    memset(writer, -1, ((size_t)b->nslot + 1) * sizeof *writer);
    for (int i = 0; i < n; i++) {
        const LowTayStep *st = &b->step[i];
        level[i] = 0;
        for (int j = st->nres; j < st->nslot; j++)
            if (st->slot[j] >= 0 && writer[st->slot[j]] >= 0 &&
                level[writer[st->slot[j]]] + 1 > level[i])
                level[i] = level[writer[st->slot[j]]] + 1;
        for (int j = 0; j < st->nres; j++) {
            twice |= writer[st->slot[j]] >= 0;
            writer[st->slot[j]] = i;
        }
        top = level[i] > top ? level[i] : top;
    }
    free(writer);
    if (twice || n == 0) {
        free(level);
        return;
    }
    /* the steps by level, each level's in program order, its products
     * after the rest (a counting sort: a large model has thousands of
     * levels and hundreds of thousands of calls) */
    int *start = xmalloc(((size_t)top + 2) * sizeof *start);
    int *order = xmalloc((size_t)n * sizeof *order);
    memset(start, 0, ((size_t)top + 2) * sizeof *start);
    for (int i = 0; i < n; i++)
        start[level[i] + 1]++;
    for (int l = 0; l <= top; l++)
        start[l + 1] += start[l];
    for (int pass = 0; pass < 2; pass++) /* the rest, then the products */
        for (int i = 0; i < n; i++)
            if ((strcmp(b->step[i].call, "mul") == 0) == pass)
                order[start[level[i]]++] = i;
    LowTayStep *out = xmalloc((size_t)n * sizeof *out);
    int m = 0;
    for (int at = 0; at < n;) {
        const LowTayStep *st = &b->step[order[at]];
        /* a run of products of one level: in fours, then a two, then one */
        int g = 1;
        while (g < 4 && at + g < n && level[order[at + g]] == level[order[at]] &&
               !strcmp(st->call, "mul") && !strcmp(b->step[order[at + g]].call, "mul"))
            g++;
        g = g == 3 ? 2 : g;
        if (g == 1) {
            out[m++] = *st;
        } else {
            LowTayStep *grp = &out[m++];
            *grp = (LowTayStep){.call = g == 4 ? "mul4" : "mul2", .nslot = 3 * g, .nres = g,
                                .src = LOW_TAY_SRC_NONE};
            for (int j = 0; j < g; j++) {
                const LowTayStep *one = &b->step[order[at + j]];
                grp->slot[j] = one->slot[0];
                grp->slot[g + 2 * j] = one->slot[1];
                grp->slot[g + 2 * j + 1] = one->slot[2];
            }
        }
        at += g;
    }
    memcpy(b->step, out, (size_t)m * sizeof *out);
    b->nstep = m;
    free(out);
    free(order);
    free(start);
    free(level);
}

static int
is_derived(const Build *b, ExprId id)
{
    return b->derived && (size_t)id < b->nderived && b->derived[id] >= 0;
}

/* Node id's slot, its operands' slots made before. */
static void
build_node(Build *b, ExprId id)
{
    const ExprNode *nd = expr_node(b->P, id);
    int ar = expr_op_arity[nd->op];
    if (is_derived(b, id)) {
        b->slot[id] = constant(b, LOW_TAY_SRC_P, b->np + b->derived[id], 0);
        b->konst[id] = 1;
        return;
    }
    int A = ar > 0 ? b->slot[nd->a] : -1, B = ar > 1 ? b->slot[nd->b] : -1;
    b->konst[id] = ar > 0 && b->konst[nd->a] && (ar < 2 || b->konst[nd->b]);
    int c = -1;
    switch (nd->op) {
    case EXPR_CONST:
        c = constant(b, LOW_TAY_SRC_CONST, 0, nd->value);
        b->konst[id] = 1;
        break;
    case EXPR_PARAM:
        c = constant(b, LOW_TAY_SRC_P, (int)nd->a, 0);
        b->konst[id] = 1;
        break;
    case EXPR_INPUT: /* held constant over a step (the runtime refuses signals) */
        c = constant(b, LOW_TAY_SRC_U, (int)nd->a, 0);
        b->konst[id] = 1;
        break;
    case EXPR_TIME:
        c = new_slot(b);
        call(b, "time", 1, c, -1, -1, -1)->src = LOW_TAY_SRC_T;
        break;
    case EXPR_VAR:
        if (nd->b > 0 && b->vslot[nd->a] < 0) { /* (the spec writes e' in the speeds) */
            b->why = "its expressions read the rate of an Euler parameter that has speeds";
            return;
        }
        if (nd->b > 1 && b->accel == ACCEL_ZERO) {
            c = constant(b, LOW_TAY_SRC_CONST, 0, 0);
            b->konst[id] = 1;
            break;
        }
        if (nd->b > 1 && b->accel == ACCEL_NONE) {
            b->why = "its mass matrix or bias reads accelerations";
            return;
        }
        c = new_slot(b); /* the caller's */
        break;
    case EXPR_SEED:
    case EXPR_MULT:
        b->why = "its mass matrix or bias reads a seed or a multiplier";
        return;
    case EXPR_ADD:
    case EXPR_SUB:
        c = new_slot(b);
        call(b, nd->op == EXPR_ADD ? "add" : "sub", 3, c, A, B, -1);
        break;
    case EXPR_MUL:
        c = new_slot(b);
        if (b->konst[nd->a] && !b->konst[nd->b])
            call(b, "scale", 3, c, A, B, -1);
        else if (b->konst[nd->b] && !b->konst[nd->a])
            call(b, "scale", 3, c, B, A, -1);
        else if (A == B)
            call(b, "sqr", 2, c, A, -1, -1);
        else
            call(b, "mul", 3, c, A, B, -1);
        break;
    case EXPR_DIV:
        c = new_slot(b);
        call(b, "div", 3, c, A, B, -1);
        break;
    case EXPR_NEG:
        c = new_slot(b);
        call(b, "neg", 2, c, A, -1, -1);
        break;
    case EXPR_POWI: {
        int n = (int32_t)nd->b, m = n < 0 ? -n : n;
        c = new_slot(b);
        if (n > 0)
            power_into(b, c, A, m);
        else
            call(b, "inv", 2, c, power_aux(b, A, m), -1, -1);
        break;
    }
    case EXPR_POW:
        c = new_slot(b);
        if (b->konst[nd->b]) {
            call(b, "powc", 3, c, A, B, -1);
        } else { /* a^b = exp(b log a) */
            int l = new_slot(b);
            call(b, "log", 2, l, A, -1, -1);
            int e = new_slot(b);
            call(b, "mul", 3, e, B, l, -1);
            call(b, "exp", 2, c, e, -1, -1);
        }
        break;
    case EXPR_ATAN2: { /* atan2(a, b): the angle of the point (b, a) */
        c = new_slot(b);
        int w = new_slot(b);
        call(b, "atan2", 4, c, w, A, B);
        break;
    }
    case EXPR_SIN:
    case EXPR_COS:
    case EXPR_SINH:
    case EXPR_COSH: {
        int which = nd->op == EXPR_SIN ? 0 : nd->op == EXPR_COS ? 1 : nd->op == EXPR_SINH ? 2 : 3;
        c = pair_slot(b, nd->a, which);
        break;
    }
    case EXPR_TAN:
    case EXPR_TANH:
    case EXPR_ATAN: {
        c = new_slot(b);
        int w = new_slot(b);
        call(b, nd->op == EXPR_TAN ? "tan" : nd->op == EXPR_TANH ? "tanh" : "atan", 3, c, w, A,
             -1);
        break;
    }
    case EXPR_ASIN:
    case EXPR_ACOS: {
        c = new_slot(b);
        int r = new_slot(b), s = new_slot(b);
        call(b, nd->op == EXPR_ASIN ? "asin" : "acos", 4, c, r, s, A);
        break;
    }
    case EXPR_EXP:
    case EXPR_LOG:
    case EXPR_SQRT:
    case EXPR_ABS:
    case EXPR_SIGN: {
        static const char *const name[] = {"exp", "log", "sqrt", "abs", "sign"};
        c = new_slot(b);
        call(b, name[nd->op - EXPR_EXP], 2, c, A, -1, -1);
        break;
    }
    case EXPR_SELECT: { /* the branch its mode chooses: held over a step */
        c = new_slot(b);
        LowTayStep *st = call(b, "select", 3, c, A, B, -1);
        st->src = LOW_TAY_SRC_U, st->index = b->nu + b->mode_slot[expr_select_mode(b->P, id)];
        break;
    }
    default:
        b->why = "its mass matrix or bias has an operation without a Taylor recurrence";
        return;
    }
    b->slot[id] = c;
}

/* The reason, or NULL: what the program cannot be built from. */
static const char *
refused(const Lowered *L, const LowFunc *mb, const LowFunc *cf)
{
    if (L->model.constrained && !cf)
        return "its constraints have no expressions (eomc_model's constraint)";
    if (L->code == LOWER_CODE_TABLES)
        return "its mass matrix and bias are loops over the model's tables (--code tables), "
               "not expressions; --code straight gives the expressions";
    if (L->mass_times || !mb)
        return "its form computes the mass matrix by columns (mass_times), not as the "
               "expressions of its entries";
    if (mb->copy || (L->events && L->events->copy))
        return "its mass matrix repeats the code of one subtree for several copies "
               "(repeat.h), which the Taylor program does not unroll";
    return NULL;
}

/* The functions whose outputs the program computes, and those outputs'
 * expressions: as the functions have them, or with their products as
 * monomials (monomial.h) where that merges roots into fewer real powers
 * (a potential's force, mu x / r^3 with r a root: one power of the sum
 * of squares).  Products alone are left as they are: associated again
 * they cost the same, and chain5's series rounded to 2.4 times the error
 * at rtol 1e-13 and 1e-14 when they were taken too (steps the same). */
enum { NROOT = 6 };
typedef struct Roots {
    const LowFunc *f[NROOT];
    ExprId *e[NROOT]; /* [f->nout] each */
} Roots;

static void
roots_choose(Roots *R, ExprPool *P)
{
    size_t n = 0;
    for (int r = 0; r < NROOT; r++)
        n += R->f[r] ? (size_t)R->f[r]->nout : 0;
    ExprId *as = xmalloc((n + 1) * sizeof *as), *mono = xmalloc((n + 1) * sizeof *mono);
    Monomials *mo = mono_new(P, DEP_T | DEP_ANY_Q | DEP_S | DEP_L);
    size_t i = 0;
    for (int r = 0; r < NROOT; r++)
        for (int k = 0; R->f[r] && k < R->f[r]->nout; k++, i++) {
            as[i] = R->f[r]->out[k].e;
            mono[i] = mono_rewrite(mo, as[i]);
        }
    for (i = 0; i < n; i++)
        if (!(mono_real_powers(mo, mono[i]) < mono_real_powers(mo, as[i])))
            mono[i] = as[i];
    mono_free(mo);
    /* and only where the whole costs less: a root written again shares
     * less with the others (the servo arm's contacts: 3 198 calls instead
     * of 2 574) */
    ExprCount ca = expr_count_ops(P, (int)n, as), cm = expr_count_ops(P, (int)n, mono);
    long opsa = ca.adds + ca.muls + ca.divs + ca.calls;
    long opsm = cm.adds + cm.muls + cm.divs + cm.calls;
    const ExprId *use = opsm < opsa ? mono : as;
    i = 0;
    for (int r = 0; r < NROOT; r++) {
        int nout = R->f[r] ? R->f[r]->nout : 0;
        R->e[r] = xmalloc(((size_t)nout + 1) * sizeof *R->e[r]);
        memcpy(R->e[r], use + i, (size_t)nout * sizeof *use);
        i += (size_t)nout;
    }
    free(as);
    free(mono);
}

/* Output k of f as the program computes it. */
static ExprId
root(const Roots *R, const LowFunc *f, int k)
{
    for (int r = 0; r < NROOT; r++)
        if (R->f[r] == f)
            return R->e[r][k];
    return f->out[k].e;
}

/* taylor_run's tail (eomc_model.h), where there are no constraints.  A q
 * or v that nothing reads gets a slot of its own, since the run leaves the
 * state's whole series in X; then each q_i's next coefficient from its
 * rate (v, or q' = W(q) v's row), and each v_j's:
 *  - M constant in t and diagonal, each M_jj a series (a 0 there is a
 *    singular M, which the runtime reports): from -h_j / M_jj;
 *  - else from a_j's series, a_k = -M_0^-1 b_k with b_k = h_k + sum_{i=1..k}
 *    M_i a_{k-i} (mrhs, one a row) solved by the caller's hook (solve), in
 *    place over a's consecutive slots.  Only written out (lower_series):
 *    above its orders the runtime's loop does the same. */
static void
run_tail(LowTaylor *ty, int nq, int nv, Arena *A)
{
    if (ty->nc)
        return;
    int diagonal = ty->mass == (LOW_TAYLOR_M_CONSTANT | LOW_TAYLOR_M_DIAGONAL);
    for (int j = 0; j < nv && diagonal; j++)
        if (ty->M_slot[j * nv + j] < 0)
            return;
    for (int i = 0; i < nq; i++)
        if (ty->q_slot[i] < 0)
            ty->q_slot[i] = ty->nslot++;
    for (int j = 0; j < nv; j++)
        if (ty->v_slot[j] < 0)
            ty->v_slot[j] = ty->nslot++;
    ty->nstate = nq + nv, ty->nv = nv;
    ty->state_slot = arena_new_array(A, int, nq + nv + 1);
    memcpy(ty->state_slot, ty->q_slot, (size_t)nq * sizeof *ty->q_slot);
    memcpy(ty->state_slot + nq, ty->v_slot, (size_t)nv * sizeof *ty->v_slot);
    int ntail = nq + nv + (diagonal ? 0 : nv + 1);
    LowTayStep *step = arena_new_array(A, LowTayStep, ty->nstep + ntail + 1);
    if (ty->nstep)
        memcpy(step, ty->step, (size_t)ty->nstep * sizeof *step);
    LowTayStep *st = step + ty->nstep;
    for (int i = 0; i < nq; i++, st++) {
        /* without speeds of their own q_i's rate is v_i, whose slot the
         * tail has just given where nothing read it */
        int rate = ty->qd_slot ? ty->qd_slot[i] : ty->v_slot[i];
        if (rate < 0)
            *st = (LowTayStep){.call = "hold", .nslot = 1, .nres = 1, .slot = {ty->q_slot[i]}};
        else if (diagonal && !ty->qd_slot && ty->h_slot[i] >= 0)
            /* that speed's rate is -h / M_ii (accel, below): q's coefficients
             * from h's quotient by M_ii (eomc_tay_integ2) */
            *st = (LowTayStep){.call = "integ2", .nslot = 4, .nres = 1,
                               .slot = {ty->q_slot[i], rate, ty->h_slot[i],
                                        ty->M_slot[i * nv + i]}};
        else
            *st = (LowTayStep){.call = "integ", .nslot = 2, .nres = 1,
                               .slot = {ty->q_slot[i], rate}};
    }
    if (!diagonal) {
        ty->acc_slot = arena_new_array(A, int, nv + 1);
        for (int j = 0; j < nv; j++)
            ty->acc_slot[j] = ty->nslot++;
        for (int j = 0; j < nv; j++, st++)
            *st = (LowTayStep){.call = "mrhs", .nslot = 1, .nres = 1,
                               .slot = {ty->acc_slot[j]}, .index = j};
        *st++ = (LowTayStep){.call = "solve", .nslot = 1, .nres = 1, .slot = {ty->acc_slot[0]}};
        for (int j = 0; j < nv; j++, st++)
            *st = (LowTayStep){.call = "integ", .nslot = 2, .nres = 1,
                               .slot = {ty->v_slot[j], ty->acc_slot[j]}};
    } else {
        for (int j = 0; j < nv; j++, st++)
            *st = ty->h_slot[j] < 0 ? (LowTayStep){.call = "hold", .nslot = 1, .nres = 1,
                                                   .slot = {ty->v_slot[j]}}
                                    : (LowTayStep){.call = "accel", .nslot = 3, .nres = 1,
                                                   .slot = {ty->v_slot[j], ty->h_slot[j],
                                                            ty->M_slot[j * nv + j]}};
    }
    ty->step = step;
    ty->nrun = ntail;
}

LowTaylor *
lower_taylor(const Lowered *L, int wanted, ExprPool *P, Arena *A)
{
    LowTaylor *ty = arena_alloc(A, sizeof *ty);
    *ty = (LowTaylor){0};
    const LowFunc *mb = lower_find(L, "mass_bias");
    const LowFunc *cf = L->model.constrained ? lower_find(L, "constraint") : NULL;
    const LowFunc *lv = L->model.constrained ? lower_find(L, "c_levels") : NULL;
    if ((ty->why = refused(L, mb, cf)))
        return ty;
    /* the series are much of a large model's C: a chain of 50 links
     * compiles in 2 s without them, 7 to 9 with */
    if (!wanted) {
        ty->why = "it was built without them (eomc writes them when the scene's method is "
                  "taylor, for eomc run --method taylor, and with eomc build --taylor)";
        return ty;
    }
    /* nq coordinates, nv speeds (nv = nq without speeds of their own):
     * M, h, a and B's columns are the speeds' */
    int nq = L->n, nv = L->nv, ne = L->events ? L->model.nevent : 0, nc = cf ? L->model.nc : 0;
    int nm = L->switches ? L->model.nmode : 0;
    const int *vslot = L->model.vslot;
    Roots R = {.f = {mb, L->events, L->switches, cf, lv, L->qdot}};
    roots_choose(&R, P); /* (before size: it writes nodes) */
    size_t size = expr_pool_size(P);
    Build b = {.P = P, .derived = mb->derived, .nderived = L->derived_ids, .np = L->model.np,
               .accel = !cf ? ACCEL_NONE : L->model.affine ? ACCEL_ZERO : ACCEL_SLOT,
               .vslot = vslot, .nu = L->model.nu, .mode_slot = L->model.mode_slot};
    b.slot = xmalloc(size * sizeof *b.slot);
    b.konst = xmalloc(size);
    b.pair = xmalloc(4 * size * sizeof *b.pair);
    memset(b.slot, -1, size * sizeof *b.slot);
    memset(b.konst, 0, size);
    memset(b.pair, -1, 4 * size * sizeof *b.pair);

    /* the nodes the outputs need, down to the leaves and derived values
     * (an output that is 0 needs none: its slot is -1) */
    int nroot = 0;
    for (int r = 0; r < NROOT; r++)
        nroot += R.f[r] ? R.f[r]->nout : 0;
    ExprId *stack = xmalloc(((size_t)nroot + 1) * sizeof *stack);
    size_t sp = 0, cap = (size_t)nroot + 1;
    for (int r = 0; r < NROOT; r++)
        for (int k = 0; R.f[r] && k < R.f[r]->nout; k++)
            if (R.e[r][k] != EXPR_ZERO)
                stack[sp++] = R.e[r][k];
    unsigned char *mark = xmalloc(size);
    memset(mark, 0, size);
    while (sp) {
        ExprId e = stack[--sp];
        if (mark[e])
            continue;
        mark[e] = 1;
        const ExprNode *nd = expr_node(P, e);
        int ar = expr_op_arity[nd->op];
        if (ar == 0 || is_derived(&b, e))
            continue;
        if (sp + 2 >= cap)
            stack = xrealloc(stack, (cap *= 2) * sizeof *stack);
        stack[sp++] = nd->a;
        if (ar == 2)
            stack[sp++] = nd->b;
    }
    for (size_t id = 0; id < size && !b.why; id++)
        if (mark[id])
            build_node(&b, (ExprId)id);
    if (!b.why)
        schedule(&b);

    if (b.why) {
        ty->why = b.why;
    } else {
        ty->nslot = b.nslot;
        ty->nstep = b.nstep;
        ty->step = arena_new_array(A, LowTayStep, b.nstep + 1);
        if (b.nstep)
            memcpy(ty->step, b.step, (size_t)b.nstep * sizeof *b.step);
        ty->q_slot = arena_new_array(A, int, nq + 1);
        ty->v_slot = arena_new_array(A, int, nv + 1);
        ty->M_slot = arena_new_array(A, int, nv * nv + 1);
        ty->h_slot = arena_new_array(A, int, nv + 1);
        ty->g_slot = arena_new_array(A, int, ne + nm + 1);
        ty->nevent = ne;
        ty->nmode = nm;
        ty->a_slot = arena_new_array(A, int, nv + 1);
        for (int i = 0; i < nq; i++)
            ty->q_slot[i] = -1;
        for (int j = 0; j < nv; j++)
            ty->v_slot[j] = ty->h_slot[j] = ty->a_slot[j] = -1;
        for (int i = 0; i < nv * nv; i++)
            ty->M_slot[i] = -1;
        /* a leaf is coordinate nd->a's (a speed's: nq + k); its rates are
         * velocity slot vslot[nd->a]'s */
        for (size_t id = 0; id < size; id++) {
            const ExprNode *nd = expr_node(P, (ExprId)id);
            if (!mark[id] || nd->op != EXPR_VAR)
                continue;
            if (nd->b == 0)
                ty->q_slot[nd->a] = b.slot[id];
            else if (nd->b == 1)
                ty->v_slot[vslot[nd->a]] = b.slot[id];
            else if (b.accel == ACCEL_SLOT)
                ty->a_slot[vslot[nd->a]] = b.slot[id];
        }
        if (L->qdot) { /* q' = W(q) v: a rate that is a speed is its leaf's slot */
            ty->qd_slot = arena_new_array(A, int, nq + 1);
            for (int i = 0; i < nq; i++)
                ty->qd_slot[i] = -1;
            for (int k = 0; k < L->qdot->nout; k++) {
                const LowSlot *o = &L->qdot->out[k];
                ExprId e = root(&R, L->qdot, k);
                ty->qd_slot[o->index] = e == EXPR_ZERO ? -1 : b.slot[e];
            }
        }
        /* M constant in t (a system of particles, a body's own frame):
         * its orders past the first are 0, and the runtime skips their
         * sums; diagonal too, its solve is a division */
        ty->mass = LOW_TAYLOR_M_CONSTANT | LOW_TAYLOR_M_DIAGONAL;
        for (int k = 0; k < mb->nout; k++) {
            const LowSlot *o = &mb->out[k];
            ExprId e = root(&R, mb, k);
            int s = e == EXPR_ZERO ? -1 : b.slot[e];
            if (o->arg == 0) {
                ty->M_slot[o->index] = s;
                if (s >= 0 && !b.konst[e])
                    ty->mass &= ~LOW_TAYLOR_M_CONSTANT;
                if (s >= 0 && o->index / nv != o->index % nv)
                    ty->mass &= ~LOW_TAYLOR_M_DIAGONAL;
            } else {
                ty->h_slot[o->index] = s;
            }
        }
        for (int e = 0; e < ne + nm; e++)
            ty->g_slot[e] = -1;
        for (int k = 0; L->events && k < L->events->nout; k++) {
            const LowSlot *o = &L->events->out[k];
            ExprId e = root(&R, L->events, k);
            ty->g_slot[o->index] = e == EXPR_ZERO ? -1 : b.slot[e];
        }
        for (int k = 0; L->switches && k < L->switches->nout; k++) {
            const LowSlot *o = &L->switches->out[k];
            ExprId e = root(&R, L->switches, k);
            ty->g_slot[ne + o->index] = e == EXPR_ZERO ? -1 : b.slot[e];
        }
        ty->nc = nc;
        ty->nonlinear = b.accel == ACCEL_SLOT;
        ty->B_slot = arena_new_array(A, int, nc * nv + 1);
        ty->f_slot = arena_new_array(A, int, nc + 1);
        ty->pos_slot = arena_new_array(A, int, nc + 1);
        ty->vel_slot = arena_new_array(A, int, nc + 1);
        for (int i = 0; i < nc * nv; i++)
            ty->B_slot[i] = -1;
        for (int c = 0; c < nc; c++)
            ty->f_slot[c] = ty->pos_slot[c] = ty->vel_slot[c] = -1;
        for (int k = 0; cf && k < cf->nout; k++) {
            const LowSlot *o = &cf->out[k];
            ExprId e = root(&R, cf, k);
            (o->arg == 0 ? ty->f_slot : ty->B_slot)[o->index] = e == EXPR_ZERO ? -1 : b.slot[e];
        }
        for (int k = 0; lv && k < lv->nout; k++) {
            const LowSlot *o = &lv->out[k];
            ExprId e = root(&R, lv, k);
            (o->arg == 0 ? ty->pos_slot : ty->vel_slot)[o->index] =
                e == EXPR_ZERO ? -1 : b.slot[e];
        }
        run_tail(ty, nq, nv, A);
        if (ty->nrun)
            ty->series = lower_series(ty, A);
        if (ty->acc_slot && !ty->series) /* (its tail is only written out) */
            ty->nrun = 0;
    }
    for (int r = 0; r < NROOT; r++)
        free(R.e[r]);
    free(mark);
    free(stack);
    free(b.step);
    free(b.pair);
    free(b.konst);
    free(b.slot);
    return ty;
}

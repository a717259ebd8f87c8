/*
 * lower: from the derived model to its list of functions (lower.h).
 */
#include "lower.h"
#include "expr/kin.h"
#include "lower_describe.h"
#include "lower_taylor.h"
#include "repeat.h"

#include <stdlib.h>
#include <string.h>

/* ---- the signatures ---- */

static const LowSig s_initial = {
    "initial", "Initial state from the spec's `initial`.", "p > q v", 1,
};
static const LowSig s_qdot = {
    "qdot", "The coordinates' rates q' = W(q) v: a quaternion's 1/2 e (x) (0, w).", "q v > qd", 1,
};
static const LowSig s_qdot_jacobian = {
    "qdot_jacobian", "dq'/dq [nq*nq] and dq'/dv [nq*nv].", "q v > dqdq dqdv", 1,
};
static const LowSig s_inputs = {
    "inputs", "Input signals u(t) and du/dt.", "t p > u dudt?", 1,
};
static const LowSig s_mass_bias = {
    "mass_bias", "Mass matrix M = dE/dq'' (row-major, symmetric) and bias h = E(q'' = 0).",
    "t q v p u > M h", 1,
};
static const LowSig s_bias = {
    "bias", "The bias h = E(q'' = 0), for mass_bias.", "t q v p u > h", 0,
};
static const LowSig s_mass_times = {
    "mass_times",
    "Mx[i] = sum_j M_ij da[j]: the derivative of E along da in q'' (E is\n"
    " * linear in q''), for mass_bias and energy.",
    "t q v p u da > Mx", 0,
};
static const LowSig s_potential = {
    "potential", "Potential energy V, for energy.", "t q v p u > V", 0,
};
static const LowSig s_tau = {
    "tau",
    "The generalized forces Q - dV/dq but for uniform gravity, which the tables'\n"
    " * a0 stands for: accel's and mass_bias's loops add the rest.",
    "t q v p u > tau", 0,
};
static const LowSig s_energy = {
    "energy", "Kinetic energy T and potential energy V.", "t q v p u > TV", 1,
};
const LowSig lower_jacobian_sig = { /* the seeded one's driver too */
    "jacobian", "Partial derivatives of the residual E(t, q, q', q'') with u held fixed.",
    "t q v a p u > dEdq dEdv dEdu dEdt", 1,
};
static const LowSig s_jac_shared = {
    "jacobian_shared",
    "The values every column of the Jacobian needs (into shared[]), and dE/du,\n"
    " * dE/dt.",
    "t q v a p u > shared dEdu dEdt", 0,
};
static const LowSig s_jac_dq = {
    "jacobian_dq",
    "dE[i*nq] = sum_j dE_i/dq_j dq[j], given shared[] from jacobian_shared.",
    "t q v a p u shared dq > dE", 0,
};
static const LowSig s_jac_dv = {
    "jacobian_dv",
    "dE[i*nq] = sum_j dE_i/dq'_j dv[j], given shared[] from jacobian_shared.",
    "t q v a p u shared dv > dE", 0,
};
static const LowSig s_accel_solve = {
    "accel_solve",
    "a = -M^-1 h by an unrolled LDL^T factorization (structural zeros of M\n"
    " * skipped; last coordinate first); its pivots piv[k] = d_k, and mkk[k] =\n"
    " * M_kk.",
    "t q v p u > a piv mkk", 0,
};
static const LowSig s_accel_recursive = {
    "accel_solve",
    "a = -M^-1 h by the form's recursion, M never formed; its pivots\n"
    " * piv[k] = d_k (those of LDL^T eliminating the leaves first), and\n"
    " * mkk[k] = M_kk.",
    "t q v p u > a piv mkk", 0,
};
static const LowSig s_minv = {
    "minv",
    "y = M^-1 da by the form's recursion at rest, with no force but the load\n"
    " * da (M never formed): the runtime's unit-load passes, M^-1 B^T a row of\n"
    " * B at a time.",
    "t q v p u da > y", 1,
};
/* The same two sharing what they both compute (lower_loads_shared). */
static const LowSig s_accel_shared = {
    "accel_solve",
    "a = -M^-1 h (the form's recursion, or an unrolled LDL^T), its pivots\n"
    " * piv[k] = d_k, mkk[k] = M_kk, and (unless NULL) into shared[] what\n"
    " * minv_shared reads of the solve.",
    "t q v p u > a piv mkk shared", 0,
};
static const LowSig s_minv_shared = {
    "minv_shared",
    "y = M^-1 da by accel_solve's solve (a recursion at rest with no force\n"
    " * but the load da, or the LDL^T factors), given shared[] from\n"
    " * accel_solve at the same (t, q, p): one unit load's passes alone.",
    "t q v p u shared da > y", 1,
};
static const LowSig s_constraint = {
    "constraint", "Constraints at acceleration level f(t, q, q', q'') and B = df/dq''.",
    "t q v a p u > f B", 1,
};
static const LowSig s_c_levels = {
    "c_levels", "Constraints at their own level: pos = g (holonomic), vel = g' or phi.",
    "t q v p u > pos vel", 1,
};
static const LowSig s_c_scale = {
    "c_scale",
    "The magnitude of each holonomic constraint's terms (sums of absolute\n"
    " * values): what its residual is measured against when the projection\n"
    " * decides it holds, where q = 0 leaves B q no size.",
    "t q p u > mag", 1,
};
static const LowSig s_c_jacobian = {
    "c_jacobian", "Partial derivatives of f and of B = df/dq'' (u held fixed).",
    "t q v a p u > dfdq dfdv dfdu dfdt dBdq dBdv dBda dBdu dBdt", 1,
};
static const LowSig s_c_levels_jacobian = {
    "c_levels_jacobian",
    "Partial derivatives of pos and vel (u held fixed): what Baumgarte's\n"
    " * stabilization adds to df/dx.",
    "t q v p u > dposdq dveldq dveldv dposdu dveldu dposdt dveldt", 1,
};
const LowSig lower_invariant_sig = { /* printed by hand when it is T + V */
    "invariant", "The conserved quantity (eomc_model.h: invariant).", "t q v p u > h", 1,
};
static const LowSig s_derive = {
    "derive",
    "The values of the parameters alone that the other functions read:\n"
    " * computed when the parameters change, not at every step.",
    "p > pd", 1,
};
static const LowSig s_outputs = {
    "outputs", "The scene's outputs, at a state and its accelerations and multipliers.",
    "t q v a p u lam > out", 1,
};
static const LowSig s_events = {
    "events", "The scene's events: g[k], whose zero crossings they are.",
    "t q v p u > g", 1,
};
static const LowSig s_switches = {
    "switches", "The switch functions of max, min and clamp: mode k is 1 where sw[k] > 0,\n"
    " * 0 where sw[k] < 0, and the runtime flips it where sw[k] crosses 0.",
    /* (not s: a function split into parts shares its values in s[]) */
    "t q v p u > sw", 1,
};
static const LowSig s_fric_bound = {
    "fric_bound", "The largest force of each dry-friction item (fric_names).",
    "t q v p u > F", 1,
};
static const LowSig s_fric_rows = {
    "fric_rows", "Each dry-friction item's row J[nv j + i] = d(its speed)/dv_i and bias\n"
    " * b[j] = J' v: its speed's rate is J v' + b (a coordinate's: a unit row, 0).",
    "t q v p u > J b", 1,
};
static const LowSig s_draw = {
    "draw", "What a run's page draws: item k's position and rotation (row-major,\n"
    " * to the world) at X[12 k ...] (eomc_model.h's draw_items).",
    "t q p u > X", 1,
};
static const LowSig s_places = {
    "places", "Each place k's position and rotation (row-major, to the world) at\n"
    " * X[12 k ...] (eomc_model.h's places).",
    "t q p u > X", 1,
};
static const LowSig s_place_velocity = {
    "place_velocity", "Each place k's velocity and angular velocity (world components) along\n"
    " * the speeds dv at W[6 k ...], without what time alone moves: at a unit\n"
    " * dv, a column of its Jacobian.",
    "t q p u dv > W", 1,
};
static const LowSig s_draw_mass = {
    "draw_mass", "Each body item k's mass, centre and inertia about it in its frame\n"
    " * at D[13 k ...], from which a body without shapes is drawn.",
    "p > D", 1,
};
static const LowSig s_draw_shapes = {
    "draw_shapes", "Each shape k's size and position at S[6 k ...], where some depend on\n"
    " * the parameters (the shapes' table has their numbers at the defaults).",
    "p > S", 1,
};
static const LowSig s_check_values = {
    "check_values", "The values that must be positive (or not negative): check_what.",
    "p > chk", 0,
};

/* ---- building the lists ---- */

typedef struct Lowering {
    Lowered *L;
    Arena *A;
    ExprPool *P;
    Diff *D;
    const Spec *s;
} Lowering;

static LowFunc *
func(Lowering *lw, const LowSig *sig, const char *stat, int double_only)
{
    LowFunc *f = arena_alloc(lw->A, sizeof *f);
    /* all but initial and check, which run before derive */
    int per_step = sig != &s_initial && sig != &s_check_values;
    *f = (LowFunc){.sig = sig, .stat = stat, .double_only = double_only, .per_step = per_step};
    Lowered *L = lw->L;
    if (L->nfunc == L->cap) {
        L->cap = L->cap ? 2 * L->cap : 32;
        LowFunc **bigger = arena_new_array(lw->A, LowFunc *, L->cap);
        if (L->nfunc)
            memcpy(bigger, L->func, (size_t)L->nfunc * sizeof *bigger);
        L->func = bigger;
    }
    L->func[L->nfunc++] = f;
    return f;
}

/* Zero slots past which one loop setting the array to 0 is shorter than
 * their stores (a store is a line of C; the loop is one). */
enum { LOW_FILL_MIN = 16 };

/* The functions the emitter prints slot by slot: not those it wraps in
 * hand-written loops (the seeded Jacobian's columns, the solve, the
 * checks; their fields are set when they are made, before their
 * outputs), nor those reading shared values (jacobian_dq, _dv: strided
 * outputs, a column of the caller's matrix).  jacobian_shared is: its
 * dE/du is dense, n nu entries most of which are 0 (the 22 humanoids:
 * 274 000 zeros, 35 s of cc as as many stores). */
static int
fillable(const Lowered *L, const LowFunc *f)
{
    return f != L->jac_dv && f != L->accel_solve && f != L->check_values && !f->shared;
}

/* The lists grow by doubling in the arena: at most twice their size.  An
 * output of LOW_FILL_MIN zeros is filled by a loop (LowFunc.fill, its
 * size so far), and its zeros leave the list: a constraint Jacobian's
 * derivatives are nc n^2 slots of mostly zeros. */
static void
out(Lowering *lw, LowFunc *f, int arg, int index, ExprId e)
{
    if (f->fill[arg] && index >= f->fill[arg])
        f->fill[arg] = index + 1;
    if (e == EXPR_ZERO && f->fill[arg])
        return;
    if (e == EXPR_ZERO && ++f->zeros[arg] == LOW_FILL_MIN && fillable(lw->L, f)) {
        int kept = 0, size = index + 1;
        for (int i = 0; i < f->nout; i++) {
            if (f->out[i].arg == arg && f->out[i].index + 1 > size)
                size = f->out[i].index + 1;
            if (f->out[i].arg != arg || f->out[i].e != EXPR_ZERO)
                f->out[kept++] = f->out[i];
        }
        f->nout = kept;
        f->fill[arg] = size;
        return;
    }
    if (f->nout == f->cap) {
        int cap = f->cap ? 2 * f->cap : 16;
        LowSlot *o = arena_new_array(lw->A, LowSlot, cap);
        if (f->nout)
            memcpy(o, f->out, (size_t)f->nout * sizeof *o);
        f->out = o, f->cap = cap;
    }
    f->out[f->nout++] = (LowSlot){e, arg, index};
}

static ExprId orzero(ExprId e) { return e == EXPR_NONE ? EXPR_ZERO : e; }

static void
lower_inputs(Lowering *lw)
{
    const Spec *s = lw->s;
    LowFunc *f = func(lw, &s_inputs, "inputs", 0);
    for (int i = 0; i < s->nu; i++)
        out(lw, f, 0, i, s->input[i].expr);
    for (int i = 0; i < s->nu; i++)
        out(lw, f, 1, i, diff_time(lw->D, s->input[i].expr));
}

/* The operator nodes without seeds that the seeded nodes below roots
 * read (and any seed-free root): what a seeded function takes from
 * shared[] instead of computing it again, numbered by id (deterministic).
 * Per node id its index there, or -1; *nw their number.  Values of the
 * parameters alone that derive computed (pd[]) are read from there. */
static int *
seed_free_reads(Lowering *lw, int n, const ExprId *roots, int *nw)
{
    ExprPool *P = lw->P;
    const Lowered *L = lw->L;
    size_t size = expr_pool_size(P);
    unsigned char *mark = xmalloc(size), *need = xmalloc(size);
    memset(mark, 0, size);
    memset(need, 0, size);
    expr_mark(P, n, roots, mark);
    for (size_t id = 0; id < size; id++) {
        const ExprNode *nd = expr_node(P, (ExprId)id);
        int ar = expr_op_arity[nd->op];
        if (!mark[id] || ar == 0 || !(nd->deps & DEP_S))
            continue;
        ExprId ops[2] = {nd->a, nd->b};
        for (int j = 0; j < ar; j++)
            if (!(expr_deps(P, ops[j]) & DEP_S) && expr_op_arity[expr_node(P, ops[j])->op])
                need[ops[j]] = 1;
    }
    for (int i = 0; i < n; i++)
        if (!(expr_deps(P, roots[i]) & DEP_S) && expr_op_arity[expr_node(P, roots[i])->op])
            need[roots[i]] = 1;
    int *shared = arena_new_array(lw->A, int, size);
    *nw = 0;
    for (size_t id = 0; id < size; id++) {
        int derived = L->derived && id < L->derived_ids && L->derived[id] >= 0;
        shared[id] = need[id] && !derived ? (*nw)++ : -1;
    }
    free(need);
    free(mark);
    return shared;
}

/* A constrained tree's unit loads, the recursion computed once: what a
 * unit load's pass reads that does not depend on the load (the
 * articulated inertias' U_i and D_i, the joints' axes: every one a value
 * of q and p alone) is free_accel's too, or computed beside it, so
 * accel_solve stores those values into shared[] and minv reads them from
 * there: each row of B then costs its load's own operations, not a
 * recursion (kkt.c).  shared[] is not optional: guarded stores cut the
 * straight-line code into blocks the C compiler schedules apart (measured:
 * the arm's solve 30 % slower).  Not where repeat split either function
 * into copies (a function with shared[] is not shifted, repeat.c): a
 * copy's loop already skips the trees a load leaves at rest. */
static void
lower_loads_shared(Lowering *lw)
{
    Lowered *L = lw->L;
    LowFunc *acc = L->accel_solve, *mv = L->minv;
    if (!L->loads || !acc || !mv || acc->copy || mv->copy)
        return;
    ExprId *roots = xmalloc((size_t)(mv->nout ? mv->nout : 1) * sizeof *roots);
    for (int i = 0; i < mv->nout; i++)
        roots[i] = mv->out[i].e;
    int nw = 0;
    int *shared = seed_free_reads(lw, mv->nout, roots, &nw);
    free(roots);
    if (nw == 0) /* minv reads nothing of the solve (a constant M) */
        return;
    acc->sig = &s_accel_shared;
    for (size_t id = 0; id < expr_pool_size(lw->P); id++)
        if (shared[id] >= 0)
            out(lw, acc, 3, shared[id], (ExprId)id);
    mv->sig = &s_minv_shared;
    mv->shared = shared;
    L->loads_shared = nw;
}

/* The seeded jacobian: the seeded expressions e->jvp_q, e->jvp_v are
 * linear in the seeds; what they need that does not depend on the seeds
 * (sines, products, ...) is the same for every column, so jacobian_shared
 * computes it once into shared[], and jacobian_dq and jacobian_dv compute
 * only the seed-dependent rest, once per column with a unit seed. */
static void
lower_seeded_jacobian(Lowering *lw, const Eom *e)
{
    ExprPool *P = lw->P;
    int n = e->n, nu = e->nu, nw = 0;
    size_t size = expr_pool_size(P);
    ExprId *roots = xmalloc(2 * (size_t)n * sizeof *roots);
    for (int i = 0; i < n; i++) {
        roots[i] = e->jvp_q[i];
        roots[n + i] = e->jvp_v[i];
    }
    int *shared = seed_free_reads(lw, 2 * n, roots, &nw);
    unsigned char *need = xmalloc(size);
    for (size_t id = 0; id < size; id++)
        need[id] = shared[id] >= 0;

    LowFunc *f = func(lw, &s_jac_shared, "jacobian", 1);
    lw->L->jac_shared = f; /* before its outputs: fillable() */
    for (size_t id = 0; id < size; id++)
        if (need[id])
            out(lw, f, 0, shared[id], (ExprId)id);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < nu; j++)
            out(lw, f, 1, i * nu + j, e->dEdu[i * nu + j]);
        out(lw, f, 2, i, e->dEdt[i]);
    }
    f = func(lw, &s_jac_dq, "jacobian", 1);
    f->shared = shared;
    for (int i = 0; i < n; i++)
        out(lw, f, 0, i * e->nq, e->jvp_q[i]);
    f = func(lw, &s_jac_dv, "jacobian", 1);
    f->shared = shared;
    for (int i = 0; i < n; i++)
        out(lw, f, 0, i * n, e->jvp_v[i]);
    lw->L->jac_dv = f;
    free(need);
    free(roots);
}

static void
lower_jacobian(Lowering *lw, const Eom *e, int how)
{
    int n = e->n, nq = e->nq, nu = e->nu;
    lw->L->jacobian = how;
    if (how == LOWER_JACOBIAN_NONE) /* not derived either (eom_derive_jacobian) */
        return;
    ExprId *jroots = xmalloc((size_t)n * (size_t)(nq + n) * sizeof *jroots);
    for (int i = 0; i < n * nq; i++)
        jroots[i] = e->dEdq[i];
    for (int i = 0; i < n * n; i++)
        jroots[n * nq + i] = e->dEdv[i];
    ExprCount jc = expr_count_ops(lw->P, n * (nq + n), jroots);
    free(jroots);
    long jops = jc.adds + jc.muls + jc.divs + jc.calls;
    long max = how == LOWER_JACOBIAN_AUTO_LIBRARY ? LOWER_UNROLLED_JACOBIAN_LIBRARY_MAX
                                                  : LOWER_UNROLLED_JACOBIAN_MAX;
    if (how == LOWER_JACOBIAN_AUTO || how == LOWER_JACOBIAN_AUTO_LIBRARY)
        how = jops > max ? LOWER_JACOBIAN_SEEDED : LOWER_JACOBIAN_UNROLLED;
    lw->L->jacobian = how;
    if (how == LOWER_JACOBIAN_SEEDED) {
        lower_seeded_jacobian(lw, e);
        return;
    }
    LowFunc *f = func(lw, &lower_jacobian_sig, "jacobian", 1);
    for (int i = 0; i < n; i++) { /* row by row: rows share their work */
        for (int j = 0; j < nq; j++)
            out(lw, f, 0, i * nq + j, e->dEdq[i * nq + j]);
        for (int j = 0; j < n; j++)
            out(lw, f, 1, i * n + j, e->dEdv[i * n + j]);
        for (int j = 0; j < nu; j++)
            out(lw, f, 2, i * nu + j, e->dEdu[i * nu + j]);
        out(lw, f, 3, i, e->dEdt[i]);
    }
}

/* constraint, c_levels, c_jacobian and c_levels_jacobian. */
static void
lower_constraints(Lowering *lw, const Constraints *c)
{
    ExprPool *P = lw->P;
    Diff *D = lw->D;
    const Spec *s = lw->s;
    int n = s->nv, nq = s->nq, nu = s->nu, nc = c->nc; /* B's columns: velocity slots */
    ExprId t = expr_time(P);
    /* the leaves: q_j (j < nq), and slot j's speed and its rate */
    ExprId *q0 = arena_new_array(lw->A, ExprId, nq), *v1 = arena_new_array(lw->A, ExprId, n);
    ExprId *v2 = arena_new_array(lw->A, ExprId, n);
    for (int j = 0; j < nq; j++)
        q0[j] = expr_var(P, j, 0);
    for (int j = 0; j < n; j++)
        v1[j] = expr_var(P, s->vcoord[j], 1), v2[j] = expr_var(P, s->vcoord[j], 2);
    LowFunc *f = func(lw, &s_constraint, "constraint", 0);
    /* B arrives zeroed where it is mostly zeros: on a model of many free
     * bodies, setting nc n zeros would cost more than the recursion */
    f->zeroed = 1u << 1;
    for (int a = 0; a < nc; a++) {
        out(lw, f, 0, a, c->f[a]);
        for (int j = 0; j < n; j++)
            out(lw, f, 1, a * n + j, c->B[a * n + j]);
    }
    f = func(lw, &s_c_levels, "c_levels", 1);
    for (int a = 0; a < nc; a++) {
        out(lw, f, 0, a, orzero(c->pos[a]));
        out(lw, f, 1, a, orzero(c->vel[a]));
    }
    int holonomic = 0; /* c_scale only where there is a position level */
    for (int a = 0; a < nc; a++)
        holonomic |= c->pos[a] != EXPR_NONE;
    if (holonomic) {
        f = func(lw, &s_c_scale, "c_levels", 1);
        ExprId *g = arena_new_array(lw->A, ExprId, nc + 1);
        ExprId *mag = arena_new_array(lw->A, ExprId, nc + 1);
        for (int a = 0; a < nc; a++)
            g[a] = orzero(c->pos[a]);
        expr_magnitude_many(P, nc, g, mag);
        for (int a = 0; a < nc; a++)
            out(lw, f, 0, a, mag[a]);
    }
    /* Newton's method needs c_jacobian only when f is not affine */
    f = func(lw, &s_c_jacobian, "c_jacobian", c->affine);
    for (int a = 0; a < nc; a++) {
        ExprId fa = c->f[a];
        if (nq == n) { /* interleaved as ever: the same nodes in the same order */
            for (int j = 0; j < n; j++) {
                out(lw, f, 0, a * n + j, diff_partial(D, fa, q0[j]));
                out(lw, f, 1, a * n + j, diff_partial(D, fa, v1[j]));
            }
        } else {
            for (int j = 0; j < nq; j++)
                out(lw, f, 0, a * nq + j, diff_partial(D, fa, q0[j]));
            for (int j = 0; j < n; j++)
                out(lw, f, 1, a * n + j, diff_partial(D, fa, v1[j]));
        }
        for (int l = 0; l < nu; l++)
            out(lw, f, 2, a * nu + l, diff_partial(D, fa, expr_input(P, l)));
        out(lw, f, 3, a, diff_partial(D, fa, t));
        for (int i = 0; i < n; i++) {
            ExprId b = c->B[a * n + i];
            int row = a * n + i;
            if (b == EXPR_ZERO) { /* its derivatives too, without taking them */
                for (int j = 0; j < (nq > n ? nq : n); j++)
                    for (int o = 4; o <= 6; o++)
                        if (j < (o == 4 ? nq : n))
                            out(lw, f, o, row * (o == 4 ? nq : n) + j, EXPR_ZERO);
                for (int l = 0; l < nu; l++)
                    out(lw, f, 7, row * nu + l, EXPR_ZERO);
                out(lw, f, 8, row, EXPR_ZERO);
                continue;
            }
            if (nq == n) {
                for (int j = 0; j < n; j++) {
                    out(lw, f, 4, row * n + j, diff_partial(D, b, q0[j]));
                    out(lw, f, 5, row * n + j, diff_partial(D, b, v1[j]));
                    out(lw, f, 6, row * n + j, diff_partial(D, b, v2[j]));
                }
            } else {
                for (int j = 0; j < nq; j++)
                    out(lw, f, 4, row * nq + j, diff_partial(D, b, q0[j]));
                for (int j = 0; j < n; j++) {
                    out(lw, f, 5, row * n + j, diff_partial(D, b, v1[j]));
                    out(lw, f, 6, row * n + j, diff_partial(D, b, v2[j]));
                }
            }
            for (int l = 0; l < nu; l++)
                out(lw, f, 7, row * nu + l, diff_partial(D, b, expr_input(P, l)));
            out(lw, f, 8, row, diff_partial(D, b, t));
        }
    }
    f = func(lw, &s_c_levels_jacobian, "c_levels_jacobian", 1);
    for (int a = 0; a < nc; a++) {
        ExprId g = orzero(c->pos[a]), w = orzero(c->vel[a]);
        if (nq == n) {
            for (int j = 0; j < n; j++) {
                out(lw, f, 0, a * n + j, diff_partial(D, g, q0[j]));
                out(lw, f, 1, a * n + j, diff_partial(D, w, q0[j]));
                out(lw, f, 2, a * n + j, diff_partial(D, w, v1[j]));
            }
        } else {
            for (int j = 0; j < nq; j++) {
                out(lw, f, 0, a * nq + j, diff_partial(D, g, q0[j]));
                out(lw, f, 1, a * nq + j, diff_partial(D, w, q0[j]));
            }
            for (int j = 0; j < n; j++)
                out(lw, f, 2, a * n + j, diff_partial(D, w, v1[j]));
        }
        for (int l = 0; l < nu; l++) {
            ExprId ul = expr_input(P, l);
            out(lw, f, 3, a * nu + l, diff_partial(D, g, ul));
            out(lw, f, 4, a * nu + l, diff_partial(D, w, ul));
        }
        out(lw, f, 5, a, diff_partial(D, g, t));
        out(lw, f, 6, a, diff_partial(D, w, t));
    }
}

/* The largest subexpressions of the parameters alone (operator nodes
 * that are coefficients, not constants) that the per-step functions use,
 * in id order; derive goes first, so that it is printed before them. */
static void
lower_derive(Lowering *lw)
{
    Lowered *L = lw->L;
    ExprPool *P = lw->P;
    size_t size = expr_pool_size(P);
    /* E's Jacobian (unit 3, which a simulator may go without) reads what
     * the others need derived and computes the rest itself: derive, in
     * unit 1, is then the same function with it or without */
#define DERIVES(f) ((f)->per_step && strcmp((f)->stat, "jacobian") != 0)
    int nroots = 0;
    for (int k = 0; k < L->nfunc; k++)
        nroots += DERIVES(L->func[k]) ? L->func[k]->nout : 0;
    ExprId *roots = xmalloc(((size_t)nroots + 1) * sizeof *roots);
    nroots = 0;
    for (int k = 0; k < L->nfunc; k++)
        for (int i = 0; DERIVES(L->func[k]) && i < L->func[k]->nout; i++)
            roots[nroots++] = L->func[k]->out[i].e;
#undef DERIVES
    unsigned char *mark = xmalloc(size), *want = xmalloc(size);
    memset(mark, 0, size);
    memset(want, 0, size);
    expr_mark(P, nroots, roots, mark);
#define DERIVABLE(e) (expr_node(P, e)->coeff && expr_op_arity[expr_node(P, e)->op] > 0)
    for (size_t id = 0; id < size; id++) {
        const ExprNode *nd = expr_node(P, (ExprId)id);
        int ar = expr_op_arity[nd->op];
        if (!mark[id] || nd->coeff || ar == 0)
            continue;
        if (DERIVABLE(nd->a))
            want[nd->a] = 1;
        if (ar == 2 && DERIVABLE(nd->b))
            want[nd->b] = 1;
    }
    for (int i = 0; i < nroots; i++)
        if (DERIVABLE(roots[i]))
            want[roots[i]] = 1;
#undef DERIVABLE
    L->derived = arena_new_array(lw->A, int, size);
    L->derived_ids = size;
    for (size_t id = 0; id < size; id++)
        L->derived[id] = want[id] ? L->nd++ : -1;
    for (int k = 0; k < L->nfunc; k++) /* (derive, made below, computes them) */
        if (L->func[k]->per_step)
            L->func[k]->derived = L->derived;
    int ntab = L->tables ? FORM_TABLE_STRIDE * L->tables->nt + 6 : 0;
    L->tree_base = L->nd;
    L->nd += ntab;
    if (L->nd) { /* a function only when there is something to derive */
        LowFunc *f = func(lw, &s_derive, "derive", 0);
        f->per_step = 0;
        for (size_t id = 0; id < size; id++)
            if (want[id])
                out(lw, f, 0, L->derived[id], (ExprId)id);
        for (int k = 0; k < ntab; k++) /* constants: copied from a table (emit.c) */
            if (!expr_is_const(P, L->tables->num[k], NULL))
                out(lw, f, 0, L->tree_base + k, L->tables->num[k]);
        /* first in the list: printed before its readers */
        memmove(L->func + 1, L->func, (size_t)(L->nfunc - 1) * sizeof *L->func);
        L->func[0] = f;
        L->derive = f;
    }
    free(want);
    free(mark);
    free(roots);
}

/* events, and one reset function set_NAME per `set` event: q1, v1 get
 * the values it sets, all computed from the state before. */
static void
lower_events(Lowering *lw)
{
    const SpecScene *sc = &lw->s->scene;
    LowFunc *f = func(lw, &s_events, "events", 1);
    for (int k = 0; k < sc->nevent; k++)
        out(lw, f, 0, k, sc->event[k].when);
    lw->L->events = f;
    lw->L->event_set = arena_new_array(lw->A, LowFunc *, sc->nevent);
    for (int k = 0; k < sc->nevent; k++) {
        const SpecEvent *ev = &sc->event[k];
        if (ev->action != EVENT_SET)
            continue;
        LowSig *sig = arena_alloc(lw->A, sizeof *sig);
        sig->name = arena_printf(lw->A, "set_%s", ev->name);
        sig->comment = arena_printf(lw->A, "Event %s: the coordinates and velocities it "
                                    "sets (q1, v1 hold the others).", ev->name);
        sig->args = "t q v p u > q1 v1";
        f = func(lw, sig, "events", 1);
        for (int i = 0; i < ev->nset; i++) {
            const ExprNode *var = expr_node(lw->P, ev->set_var[i]);
            out(lw, f, (int)var->b, (int)var->a, ev->set_expr[i]);
        }
        lw->L->event_set[k] = lw->L->last_set = f;
    }
}

/* The switches the model's functions read, numbered in the pool's order
 * (mode_slot): a kink of an effect that is off, or one a substitution
 * replaced, is none of the model's.  A switch function may read other
 * modes (max of a max): theirs are the model's too.  Then the function
 * switches, s [nmode], in the twin too (the reference will locate them). */
static void
lower_switches(Lowering *lw)
{
    ExprPool *P = lw->P;
    Lowered *L = lw->L;
    int ns = expr_nswitch(P), nroots = 0, *slot = arena_new_array(lw->A, int, ns + 1);
    for (int k = 0; k < L->nfunc; k++)
        nroots += L->func[k]->nout;
    ExprId *roots = xmalloc(((size_t)nroots + (size_t)ns + 1) * sizeof *roots);
    nroots = 0;
    for (int k = 0; k < L->nfunc; k++)
        for (int i = 0; i < L->func[k]->nout; i++)
            roots[nroots++] = L->func[k]->out[i].e;
    size_t size = expr_pool_size(P);
    unsigned char *mark = xmalloc(size), *used = xmalloc((size_t)ns + 1);
    memset(used, 0, (size_t)ns + 1);
    for (int grew = 1; grew;) {
        memset(mark, 0, size);
        expr_mark(P, nroots, roots, mark);
        grew = 0;
        for (size_t id = 0; id < size; id++)
            if (mark[id] && expr_node(P, (ExprId)id)->op == EXPR_SELECT) {
                int k = expr_select_mode(P, (ExprId)id);
                if (!used[k]) /* its switch function's modes next */
                    used[k] = 1, roots[nroots++] = expr_switch(P, k), grew = 1;
            }
    }
    int nmode = 0;
    for (int k = 0; k < ns; k++)
        slot[k] = used[k] ? nmode++ : -1;
    L->model.nmode = nmode;
    L->model.mode_slot = slot;
    L->model.mode_name = arena_new_array(lw->A, const char *, nmode + 1);
    for (int k = 0; k < ns; k++)
        if (used[k]) { /* a switch built outside the parser has no name of its own */
            const char *nm = expr_switch_name(P, k);
            L->model.mode_name[slot[k]] = nm ? arena_strdup(lw->A, nm)
                                             : arena_printf(lw->A, "switch %d", slot[k]);
        }
    if (nmode) {
        LowFunc *f = func(lw, &s_switches, "events", 0);
        for (int k = 0; k < ns; k++)
            if (used[k])
                out(lw, f, 0, slot[k], expr_switch(P, k));
        L->switches = f;
    }
    free(mark);
    free(used);
    free(roots);
}

/* The dry-friction items of the effects that are on (an item whose force
 * folded to 0 exerts none, and is left out): the coordinates' items
 * (spec/friction.c), then the contacts' (mechanics/contact.c), and
 * fric_bound; where a contact has friction, fric_rows too.  Their modes
 * are the pool's switches until lower_switches numbers them
 * (friction_modes). */
static void
lower_friction(Lowering *lw, const Mech *m)
{
    const Spec *s = lw->s;
    LowModel *md = &lw->L->model;
    ExprPool *P = lw->P;
    int n = 0, rows = 0;
    for (int e = 0; e < s->neffect; e++)
        for (int j = 0; s->effect[e].enabled && j < s->effect[e].nforce; j++)
            n += s->effect[e].force[j].friction && s->effect[e].force[j].expr != EXPR_ZERO;
    for (int j = 0; j < m->fric.n; j++)
        rows += m->fric.item[j].bound != EXPR_ZERO;
    if (!n && !rows)
        return;
    md->fric = arena_new_array(lw->A, LowFric, n + rows);
    LowFunc *f = func(lw, &s_fric_bound, "events", 0);
    for (int e = 0; e < s->neffect; e++)
        for (int j = 0; s->effect[e].enabled && j < s->effect[e].nforce; j++) {
            const SpecForce *fo = &s->effect[e].force[j];
            if (!fo->friction || fo->expr == EXPR_ZERO)
                continue;
            md->fric[md->nfric] = (LowFric){
                .name = arena_printf(lw->A, "%s.%s", s->effect[e].name, s->coord[fo->coord].name),
                .speed = s->vslot[fo->coord], .slip = fo->slip, .stick = fo->stick};
            out(lw, f, 0, md->nfric++, fo->bound);
        }
    for (int j = 0; j < m->fric.n; j++) {
        const ContactFric *cf = &m->fric.item[j];
        if (cf->bound == EXPR_ZERO)
            continue;
        md->fric[md->nfric] = (LowFric){.name = cf->name, .speed = -1, .slip = cf->slip,
                                        .stick = cf->stick, .row = cf->speed};
        out(lw, f, 0, md->nfric++, cf->bound);
    }
    lw->L->fric_bound = f;
    if (!rows)
        return;
    /* the rows: J = ds/dv, and b = J' v = ds/dt with v' = 0, the rates of q
     * (and t) through s's partials */
    int nv = s->nv;
    LowFunc *r = func(lw, &s_fric_rows, "events", 0);
    for (int j = 0; j < md->nfric; j++) {
        const LowFric *fr = &md->fric[j];
        ExprId b = EXPR_ZERO;
        for (int i = 0; i < nv; i++)
            out(lw, r, 0, j * nv + i, fr->speed >= 0 ? (i == fr->speed ? EXPR_ONE : EXPR_ZERO)
                                                     : diff_partial(lw->D, fr->row, m->q[1][i]));
        if (fr->speed < 0) {
            for (int k = 0; k < s->nq; k++)
                b = expr_add(P, b, expr_mul(P, diff_partial(lw->D, fr->row, m->q[0][k]),
                                            m->rate[k]));
            b = expr_add(P, b, diff_partial(lw->D, fr->row, expr_time(P)));
        }
        out(lw, r, 1, j, b);
    }
    lw->L->fric_rows = r;
}

/* The friction items' switches numbered as the model's modes. */
static void
friction_modes(Lowering *lw)
{
    LowModel *md = &lw->L->model;
    for (int k = 0; k < md->nfric; k++) {
        md->fric[k].slip = md->mode_slot[md->fric[k].slip];
        md->fric[k].stick = md->mode_slot[md->fric[k].stick];
    }
}

/* Whether the model's accel and mass_bias are loops over its tables; *why
 * when they are asked for and cannot be. */
static const FormTables *
tables_for(const Mech *m, const Eom *e, const Constraints *c, int loads, int code, Arena *A,
           ExprPool *P, Diff *D, const char **why)
{
    *why = NULL;
    int refused = (c && !loads) || !e->acc || e->form != &form_articulated;
    if (code == LOWER_CODE_TABLES && refused)
        *why = !e->acc || e->form != &form_articulated
                   ? "its form is not articulated-body"
                   : "its constraints are not all affine in q'' with multipliers";
    if (code == LOWER_CODE_STRAIGHT || refused)
        return NULL;
    if (code == LOWER_CODE_AUTO) { /* the solve, the bias and the energies */
        int n = e->n;
        ExprId *roots = xmalloc((4 * (size_t)n + 2) * sizeof *roots);
        for (int i = 0; i < n; i++)
            roots[i] = e->acc[i], roots[n + i] = e->piv[i], roots[2 * n + i] = e->mkk[i],
            roots[3 * n + i] = e->h[i];
        roots[4 * n] = m->T, roots[4 * n + 1] = m->V;
        ExprCount k = expr_count_ops(P, 4 * n + 2, roots);
        free(roots);
        if (k.adds + k.muls + k.divs + k.calls <= LOWER_TABLES_MIN)
            return NULL;
    }
    const char *no;
    const FormTables *tb = form_tables(m, A, P, D, &no);
    if (!tb && code == LOWER_CODE_TABLES)
        *why = no;
    return tb;
}

/* Lowered.held: a frame's unit quaternion e is met by the articulated
 * recursion's q'' alone where nothing but the masses and T_joint's
 * 1/2 c (e.e')^2 acts on e: the masses' forces S^T F have no part along e
 * (L e = 0), and that term's is c (e.e'' + e'.e'), so q'' keeps e.e'' +
 * e'.e' = 0 with multiplier 0.  A potential, force or kinetic term of the
 * spec's own on e may have a part along e (a ball's armature: -2 a |w|^2),
 * and then the row is solved. */
static unsigned char *
held_rows(const Spec *s, const Mech *m, const Constraints *c, Arena *A, ExprPool *P)
{
    if (!c || s->nfquat == 0)
        return NULL;
    unsigned char *held = arena_new_array(A, unsigned char, c->nc + 1);
    unsigned char *inV = calloc(expr_pool_size(P), 1);
    expr_mark(P, 1, &m->V_rest, inV);
    /* the frames' come last (spec/constraints.c), but for those with speeds */
    int *unit = arena_new_array(A, int, s->nfquat + 1), nunit = 0, any = 0;
    for (int k = 0; k < s->nfquat; k++)
        if (s->fquat[k].speed < 0)
            unit[nunit++] = k;
    int first = c->nc - nunit;
    for (int k = 0; k < c->nc; k++) {
        held[k] = k >= first;
        for (int d = 0; held[k] && d < 4; d++) {
            int i = s->fquat[unit[k - first]].q[d];
            held[k] = !m->in_kinetic[i] && m->Q[s->vslot[i]] == EXPR_ZERO && !inV[m->q[0][i]];
        }
        any |= held[k];
    }
    free(inV);
    return any ? held : NULL;
}

/* An item's pose: a body at its centre of mass, turned as the frame that
 * places it, else by its rotation (a sequence, a quaternion, a planar
 * angle about z; a body given by `omega:` alone is not turned); a
 * particle or point at its position, a frame at its origin (the world's
 * if it has none) with its rotation, the ground at the world's origin in
 * its axes; z = 0 in the plane. */
static void
item_pose(const Lowering *lw, const SpecDrawItem *it, ExprId pos[3], ExprId R[9])
{
    const Spec *s = lw->s;
    ExprPool *P = lw->P;
    const Kin *K = s->kin;
    for (int j = 0; j < 9; j++)
        R[j] = j % 4 == 0 ? EXPR_ONE : EXPR_ZERO;
    pos[0] = pos[1] = pos[2] = EXPR_ZERO;
    int frame = -1;
    if (it->kind == SPEC_DRAW_BODY) {
        const SpecBody *b = &s->body[it->index];
        for (int j = 0; j < it->dim; j++)
            pos[j] = b->center[j];
        if (b->frame >= 0) {
            frame = b->frame;
        } else if (b->has_rot) {
            for (int j = 0; j < 9; j++)
                R[j] = b->rot[j];
        } else if (b->dim == 2 && b->angle != EXPR_NONE) {
            ExprId c = expr_unary(P, EXPR_COS, b->angle);
            ExprId sn = expr_unary(P, EXPR_SIN, b->angle);
            R[0] = c, R[1] = expr_neg(P, sn), R[3] = sn, R[4] = c;
        }
    } else if (it->kind == SPEC_DRAW_PARTICLE) {
        for (int j = 0; j < it->dim; j++)
            pos[j] = s->part[it->index].pos[j];
    } else if (it->kind == SPEC_DRAW_POINT) {
        kin_pos(K, it->index, pos);
    } else if (it->kind == SPEC_DRAW_GROUND) { /* the world's origin and axes */
    } else {
        frame = it->index;
        int o = kin_origin(K, frame);
        kin_pos(K, o < 0 ? KIN_ORIGIN : o, pos);
    }
    if (frame >= 0)
        kin_rotation(K, frame, R);
}

/* The fixed parameters' values folded into n expressions of frames and
 * points (the spec's own are already). */
static void
fold_fixed(const Lowering *lw, int n, ExprId *X)
{
    const Spec *s = lw->s;
    if (!s->nfixed)
        return;
    ExprId *from = arena_new_array(lw->A, ExprId, s->nfixed);
    ExprId *to = arena_new_array(lw->A, ExprId, s->nfixed);
    int nf = 0;
    for (int i = 0; i < s->np; i++)
        if (s->param[i].fixed) {
            from[nf] = expr_param(lw->P, i);
            to[nf++] = expr_const(lw->P, s->param[i].value);
        }
    expr_subst_many(lw->P, n, X, nf, from, to, X);
}

/* The draw items' poses (draw, item_pose) and the bodies' masses
 * (draw_mass).  Computed from p alone, not per step: the page calls them
 * once per frame. */
static void
lower_draw(Lowering *lw)
{
    const Spec *s = lw->s;
    ExprPool *P = lw->P;
    const SpecView *v = &s->view;
    int ni = v->nitem, nx = EOMC_POSE_SIZE * ni;
    ExprId *X = arena_new_array(lw->A, ExprId, nx + 1);
    for (int k = 0; k < ni; k++)
        item_pose(lw, &v->item[k], X + EOMC_POSE_SIZE * k, X + EOMC_POSE_SIZE * k + 3);
    int nd = EOMC_DRAW_MASS_SIZE * s->nbody;
    ExprId *D = arena_new_array(lw->A, ExprId, nd + 1);
    for (int k = 0; k < s->nbody; k++) { /* the bodies are the first items */
        const SpecBody *b = &s->body[k];
        ExprId *d = D + EOMC_DRAW_MASS_SIZE * k;
        d[0] = b->mass;
        d[1] = d[2] = d[3] = EXPR_ZERO; /* the pose is at the centre */
        for (int j = 0; j < 9; j++)
            d[4 + j] = b->dim == 2 ? (j == 8 ? b->inertia[0] : EXPR_ZERO) : b->inertia[j];
    }
    fold_fixed(lw, nx, X);
    LowFunc *f = func(lw, &s_draw, "draw", 1);
    f->per_step = 0;
    for (int i = 0; i < nx; i++)
        out(lw, f, 0, i, orzero(X[i]));
    lw->L->draw = f;
    if (s->nbody) {
        f = func(lw, &s_draw_mass, "draw", 1);
        f->per_step = 0;
        for (int i = 0; i < nd; i++)
            out(lw, f, 0, i, orzero(D[i]));
        lw->L->draw_mass = f;
    }
    int ns = 0; /* shapes of parameters: sized when the page is written */
    for (int k = 0; k < s->nshape; k++)
        for (int j = 0; j < 3; j++)
            ns += s->shape[k].esize[j] != EXPR_NONE || s->shape[k].epos[j] != EXPR_NONE;
    if (ns) {
        f = func(lw, &s_draw_shapes, "draw", 1);
        f->per_step = 0;
        for (int k = 0, d = 0; k < s->nshape; k++) {
            const SpecShape *sh = &s->shape[k];
            if (sh->type == SPEC_SHAPE_PLANE) /* not drawn (lower_describe) */
                continue;
            for (int j = 0; j < 3; j++) {
                ExprId e = sh->esize[j], x = sh->epos[j];
                out(lw, f, 0, EOMC_SHAPE_NUMS_SIZE * d + j,
                    e != EXPR_NONE ? e : expr_const(P, sh->size[j]));
                out(lw, f, 0, EOMC_SHAPE_NUMS_SIZE * d + 3 + j,
                    x != EXPR_NONE ? x : expr_const(P, sh->pos[j]));
            }
            d++;
        }
        lw->L->draw_shapes = f;
    }
}

/* A place's angular velocity in world components, of q and the slots
 * (EXPR_ZERO for a point or particle; w[0] EXPR_NONE where the model does
 * not give it: a body turned by `omega:` alone, a frame turned by an
 * input, whose rate has no expression). */
static void
place_omega(const Lowering *lw, const SpecDrawItem *it, ExprId w[3])
{
    const Spec *s = lw->s;
    ExprPool *P = lw->P;
    w[0] = w[1] = w[2] = EXPR_ZERO;
    int frame = it->kind == SPEC_DRAW_FRAME ? it->index : -1;
    if (it->kind == SPEC_DRAW_BODY) {
        const SpecBody *b = &s->body[it->index];
        if (b->frame >= 0) {
            frame = b->frame;
        } else if (b->dim == 2) {
            w[2] = b->omega[0];
        } else if (b->has_rot) { /* omega is in the body's axes */
            for (int i = 0; i < 3; i++) {
                for (int j = 0; j < 3; j++)
                    w[i] = expr_add(P, w[i], expr_mul(P, b->rot[3 * i + j], b->omega[j]));
            }
        } else {
            w[0] = EXPR_NONE;
        }
    }
    if (frame >= 0)
        kin_omega(s->kin, frame, w);
    for (int i = 0; i < 3; i++)
        if (w[i] == EXPR_NONE)
            w[0] = EXPR_NONE;
}

/* The places' poses (places: item_pose) and their velocities along the
 * speeds (place_velocity): the position's derivative by the chain rule
 * through the coordinates' rates, sum_i dr/dq_i (dq_i'/dv . dv), and the
 * angular velocity's along the slots, sum_j dw/dv_j dv_j.  Both leave out
 * what time alone moves (a driven frame), so that the values at unit dv
 * are the columns of the place's velocity Jacobian.  A place whose
 * angular velocity the model does not give is marked unturned: the
 * runtime refuses its rotation and angular rows by name. */
static void
lower_places(Lowering *lw, const Mech *m)
{
    LowDrawItem *low = lw->L->model.place;
    const Spec *s = lw->s;
    ExprPool *P = lw->P;
    int np = s->nplace, nq = s->nq, nv = s->nv;
    ExprId *X = arena_new_array(lw->A, ExprId, EOMC_POSE_SIZE * np + 1);
    ExprId *W = arena_new_array(lw->A, ExprId, 6 * np + 1);
    ExprId *seed = arena_new_array(lw->A, ExprId, nv + 1);
    ExprId *qdv = arena_new_array(lw->A, ExprId, nq + 1);
    for (int j = 0; j < nv; j++)
        seed[j] = expr_seed(P, j, 1);
    diff_jvp(lw->D, nq, m->rate, nv, m->q[1], seed, qdv);
    ExprId *lin = arena_new_array(lw->A, ExprId, 3 * np + 1);
    ExprId *ang = arena_new_array(lw->A, ExprId, 3 * np + 1);
    for (int k = 0; k < np; k++) {
        ExprId *pos = X + EOMC_POSE_SIZE * k;
        item_pose(lw, &s->place[k], pos, pos + 3);
        for (int i = 0; i < 3; i++)
            lin[3 * k + i] = pos[i];
        place_omega(lw, &s->place[k], ang + 3 * k);
        if (ang[3 * k] == EXPR_NONE) {
            low[k].unturned = 1;
            ang[3 * k] = EXPR_ZERO;
        }
    }
    ExprId *dlin = arena_new_array(lw->A, ExprId, 3 * np + 1);
    ExprId *dang = arena_new_array(lw->A, ExprId, 3 * np + 1);
    diff_jvp(lw->D, 3 * np, lin, nq, m->q[0], qdv, dlin);
    diff_jvp(lw->D, 3 * np, ang, nv, m->q[1], seed, dang);
    for (int k = 0; k < np; k++)
        for (int i = 0; i < 3; i++) {
            W[6 * k + i] = dlin[3 * k + i];
            W[6 * k + 3 + i] = dang[3 * k + i];
        }
    fold_fixed(lw, EOMC_POSE_SIZE * np, X);
    fold_fixed(lw, 6 * np, W);
    LowFunc *f = func(lw, &s_places, "draw", 1);
    f->per_step = 0;
    for (int i = 0; i < EOMC_POSE_SIZE * np; i++)
        out(lw, f, 0, i, orzero(X[i]));
    lw->L->places = f;
    f = func(lw, &s_place_velocity, "draw", 1);
    f->per_step = 0;
    for (int i = 0; i < 6 * np; i++)
        out(lw, f, 0, i, orzero(W[i]));
    lw->L->place_velocity = f;
}

Lowered *
lower_model(const Spec *s, const Mech *m, Eom *e, const Constraints *c, int eliminate,
            const Invariant *inv, int jacobian, int code, int taylor, Arena *A, ExprPool *P,
            Diff *D)
{
    Lowering lw = {arena_alloc(A, sizeof(Lowered)), A, P, D, s};
    *lw.L = (Lowered){0};
    lower_describe(lw.L, s, e, c, inv, A);
    lw.L->n = s->nq;
    lw.L->nv = s->nv;
    int n = s->nv; /* the velocity slots: every function but initial's q and qdot's */

    LowFunc *f = func(&lw, &s_initial, "initial", 1);
    for (int i = 0; i < s->nq; i++)
        out(&lw, f, 0, i, s->coord[i].q0);
    for (int j = 0; j < s->nv; j++) {
        int c = s->vcoord[j];
        out(&lw, f, 1, j, c < s->nq ? s->coord[c].v0 : s->speed[c - s->nq].v0);
    }
    if (s->nspeed) {
        f = func(&lw, &s_qdot, "qdot", 0);
        for (int i = 0; i < s->nq; i++)
            out(&lw, f, 0, i, m->rate[i]);
        lw.L->qdot = f;
        f = func(&lw, &s_qdot_jacobian, "qdot", 1);
        for (int i = 0; i < s->nq; i++) {
            for (int j = 0; j < s->nq; j++)
                out(&lw, f, 0, i * s->nq + j, diff_partial(D, m->rate[i], m->q[0][j]));
            for (int j = 0; j < s->nv; j++)
                out(&lw, f, 1, i * s->nv + j, diff_partial(D, m->rate[i], m->q[1][j]));
        }
        lw.L->qdot_jacobian = f;
    }

    lower_inputs(&lw);

    /* a constrained tree: the multipliers by unit loads (kkt.c) */
    int loads = constraints_by_loads(c, eliminate) && eom_loads(e);
    const FormTables *tb = tables_for(m, e, c, loads, code, A, P, D, &lw.L->tables_why);
    lw.L->loads = loads;
    lw.L->held = loads ? held_rows(s, m, c, A, P) : NULL;
    lw.L->code = tb ? LOWER_CODE_TABLES : LOWER_CODE_STRAIGHT;
    lw.L->tables = tb;
    if (tb) {
        f = func(&lw, &s_tau, "accel", 0);
        for (int i = 0; i < n; i++)
            out(&lw, f, 0, i, tb->tau[i]);
        lw.L->tau = f;
    } else if (e->acc && e->form->solve) {
        /* M only off the hot path (conditioning, Jacobians): by columns,
         * from code that grows as E does, not as n^2 entries */
        f = func(&lw, &s_bias, "mass_bias", 0);
        for (int i = 0; i < n; i++)
            out(&lw, f, 0, i, e->h[i]);
        ExprId *seed = arena_new_array(A, ExprId, n), *Mx = arena_new_array(A, ExprId, n);
        for (int j = 0; j < n; j++)
            seed[j] = expr_seed(P, j, 2);
        diff_jvp(D, n, e->E, n, m->q[2], seed, Mx);
        f = func(&lw, &s_mass_times, "mass_bias", 0);
        for (int i = 0; i < n; i++)
            out(&lw, f, 0, i, Mx[i]);
        lw.L->mass_times = f;
    } else {
        eom_mass(e, m, A, P, D);
        f = func(&lw, &s_mass_bias, "mass_bias", 0);
        for (int i = 0; i < n; i++) /* lower triangle and h, then the mirrored upper one */
            for (int j = 0; j <= i; j++)
                out(&lw, f, 0, i * n + j, e->M[i * n + j]);
        for (int i = 0; i < n; i++)
            out(&lw, f, 1, i, e->h[i]);
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++)
                out(&lw, f, 0, i * n + j, e->M[i * n + j]);
    }

    if (tb || lw.L->mass_times) {
        /* T = q' . M q' / 2 (a tree's T is a quadratic form in q') by the
         * tables' recursion or mass_times: energy by hand */
        f = func(&lw, &s_potential, "energy", 1);
        out(&lw, f, 0, 0, m->V);
        lw.L->potential = f;
    } else {
        f = func(&lw, &s_energy, "energy", 1);
        out(&lw, f, 0, 0, m->T);
        out(&lw, f, 0, 1, m->V);
    }

    /* E = T + V is what energy computes: the invariant adds its two
     * results rather than compute them again */
    lw.L->invariant_energy = inv->h != EXPR_NONE && inv->h == expr_add(P, m->T, m->V);
    if (inv->h != EXPR_NONE && !lw.L->invariant_energy) {
        f = func(&lw, &lower_invariant_sig, "invariant", 1);
        out(&lw, f, 0, 0, inv->h);
    }
    if (c)
        lower_constraints(&lw, c);
    if (e->acc && (!c || loads) && !tb) {
        /* constrained: free_accel, which the reference does not use */
        f = func(&lw, e->form->solve ? &s_accel_recursive : &s_accel_solve, "accel", c != NULL);
        lw.L->accel_solve = f; /* before its outputs: fillable() */
        for (int i = 0; i < n; i++)
            out(&lw, f, 1, i, e->piv[i]);
        for (int i = 0; i < n; i++)
            out(&lw, f, 2, i, e->mkk[i]);
        for (int i = 0; i < n; i++)
            out(&lw, f, 0, i, e->acc[i]);
    }
    if (loads && !tb) {
        ExprId *y = eom_minv(e, m, A, P, D);
        f = func(&lw, &s_minv, "minv", 1);
        for (int i = 0; i < n; i++)
            out(&lw, f, 0, i, y[i]);
        lw.L->minv = f;
    }
    if (s->scene.noutput) {
        f = func(&lw, &s_outputs, "outputs", 1);
        for (int k = 0; k < s->scene.noutput; k++)
            out(&lw, f, 0, k, s->scene.output[k].expr);
        lw.L->outputs = f;
    }
    if (s->scene.nevent)
        lower_events(&lw);
    lower_friction(&lw, m);
    if (s->ncheck) {
        f = func(&lw, &s_check_values, "check", 1);
        lw.L->check_values = f; /* before its outputs: fillable() */
        for (int i = 0; i < s->ncheck; i++)
            out(&lw, f, 0, i, s->check[i].expr);
    }
    if (s->view.nitem)
        lower_draw(&lw);
    if (s->nplace)
        lower_places(&lw, m);
    /* E's Jacobian last: the nodes of its derivatives come after every
     * other function's, whose C is then the same with it or without */
    if (jacobian != LOWER_JACOBIAN_NONE)
        eom_derive_jacobian(e, m, A, P, D);
    lower_jacobian(&lw, e, jacobian);
    lower_derive(&lw);
    lower_switches(&lw);
    friction_modes(&lw);
    /* after derive, which has seen every copy's parameter values */
    for (int k = 0; k < lw.L->nfunc; k++) {
        LowFunc *fk = lw.L->func[k];
        if (!s->nspeed)
            repeat_split(fk, n, s->nu, REPEAT_MIN_SAVED, A, P);
        else if (fk != lw.L->qdot && fk != lw.L->qdot_jacobian) /* (by coordinate: cheap) */
            repeat_split_speeds(fk, s->nq, s->nv, lw.L->model.vslot, lw.L->model.vcoord, s->nu,
                                REPEAT_MIN_SAVED, A, P);
    }
    lower_loads_shared(&lw);
    lw.L->taylor = lower_taylor(lw.L, taylor, P, A); /* from the lists as they are printed */
    return lw.L;
}

/*
 * Unit tests of lower_schedule.c, without compiling any C, on models
 * read from the spec files named on the command line (meson.build): for
 * every lowered function,
 *   the schedule is a topological order: each operator node once, after
 *   the nodes it reads, each output stored after its value;
 *   lower_eval, which runs that list node by node (the list the C is
 *   printed from), stores in every slot the very bits expr_eval gives on
 *   the DAG: the same arithmetic, whatever the order; with switches, in
 *   each of four patterns of the modes (all off, all on, alternating);
 *   a value computed in a lazy block (a node only one branch of a
 *   switch's SELECTs needs) is read only in that branch: by a node of a
 *   block of the same mode and branch, or as that branch of a SELECT on
 *   that switch.
 * And laziness itself: tests/unit/contact_far.yaml's bodies far apart
 * (every mode 0) cost its right-hand side and Jacobian no division or
 * call beyond the model's without contact, and at most two additions or
 * multiplications per SELECT, the test of a pair's mode.
 * The models: a pendulum, the 5-link chain (sines and cosines computed
 * together), the Cartesian pendulum (a constraint, multipliers), the
 * rolling disk (nonholonomic), the Whipple bicycle (functions past
 * LOWER_PART_SIZE nodes, listed depth-first), contact scenes (the
 * switches of contact and of step and max); each with the unrolled and
 * the seeded Jacobian (shared[] values).
 */
#include "check.h"
#include "forms/forms.h"
#include "lower/lower.h"
#include "lower/lower_schedule.h"

#include <stdlib.h>
#include <string.h>

static Arena *A;
static ExprPool *P;
static Diff *D;
static int ncut; /* schedules of functions printed in parts */

static Lowered *
lowered(const char *path, int jacobian, const char *scene)
{
    SpecOptions o = {scene, NULL};
    /* a Diff of this spec's: its memos of time derivatives hold the
     * last spec's coordinate rates (a quaternion's) */
    diff_free(D);
    D = diff_new(P);
    Spec *s = spec_load(path, &o, A, P);
    if (!s)
        return NULL;
    Mech *m = mech_build(s, A, P, D);
    Constraints *c = constraints_build(s, m, A, P, D);
    Invariant *inv = invariant_derive(s, m, c, A, P, D);
    char why[600];
    Eom *e = eom_derive_cheapest(s, m, c ? c->nc : 0, constraints_by_loads(c, 0), 0, A, P, D, why,
                                 sizeof why);
    if (!e)
        return NULL;
    return lower_model(s, m, e, c, e->form->eliminate, inv, jacobian, LOWER_CODE_STRAIGHT, 0, A,
                       P, D);
}

static int nblocks; /* lazy blocks in the schedules */

/* A block's tests, 2 k + branch: it runs where any holds (n -1: no block). */
typedef struct Tests {
    int n, k[64];
} Tests;

static int
holds(const Tests *t, int k)
{
    for (int i = 0; i < t->n; i++)
        if (t->k[i] == k)
            return 1;
    return 0;
}

/* Each node once, after the nodes it reads; each store after its value;
 * a value of a lazy block read only where its block ran: by a node of a
 * block whose every test is one of its block's, or by a SELECT outside
 * blocks, as the branch one of its block's tests takes. */
static int
topological(const LowFunc *f, const LowSched *S)
{
    size_t size = expr_pool_size(P);
    unsigned char *done = calloc(size, 1);
    int *where = malloc(size * sizeof *where); /* its block's tests in blocks[], or -1 */
    Tests *blocks = malloc(((size_t)S->nstep + 1) * sizeof *blocks);
    int ok = 1, nnode = 0, in = -1, nb = 0;
    for (int k = 0; k < S->nstep && ok; k++) {
        const LowStep *st = &S->step[k];
        if (st->kind == LOW_STEP_IF) {
            ok = in < 0;
            in = nb++;
            blocks[in] = (Tests){1, {2 * st->i + st->branch}};
            nblocks++;
        } else if (st->kind == LOW_STEP_OR) {
            ok = in >= 0 && blocks[in].n < 64 && k > 0 && S->step[k - 1].kind != LOW_STEP_NODE;
            if (ok)
                blocks[in].k[blocks[in].n++] = 2 * st->i + st->branch;
        } else if (st->kind == LOW_STEP_ELSE) {
            ok = in >= 0 && blocks[in].n == 1;
            if (ok) {
                blocks[nb] = (Tests){1, {blocks[in].k[0] ^ 1}};
                in = nb++;
            }
        } else if (st->kind == LOW_STEP_END) {
            ok = in >= 0;
            in = -1;
        } else if (st->kind == LOW_STEP_NODE) {
            const ExprNode *nd = expr_node(P, st->id);
            int ar = expr_op_arity[nd->op];
            ExprId ops[2] = {nd->a, nd->b};
            ok = lower_computed(P, f, st->id) && !done[st->id];
            for (int j = 0; j < ar && ok; j++) {
                ok = done[ops[j]] || !lower_computed(P, f, ops[j]);
                if (!ok || !lower_computed(P, f, ops[j]) || where[ops[j]] < 0)
                    continue;
                const Tests *t = &blocks[where[ops[j]]];
                if (in < 0) { /* a SELECT's branch its block's test takes */
                    ok = nd->op == EXPR_SELECT &&
                         holds(t, 2 * expr_select_mode(P, st->id) + (j == 0));
                    continue;
                }
                for (int i = 0; i < blocks[in].n && ok; i++)
                    ok = holds(t, blocks[in].k[i]);
            }
            done[st->id] = 1;
            where[st->id] = in;
            nnode++;
        } else if (st->kind == LOW_STEP_STORE) {
            ExprId e = f->out[st->i].e;
            ok = in < 0 && (done[e] || !lower_computed(P, f, e));
            ok = ok && (!lower_computed(P, f, e) || where[e] < 0);
        }
    }
    free(blocks);
    free(where);
    free(done);
    return ok && in < 0 && nnode == S->nnode;
}

/* Distinct values, none of them special: a state no derivation is
 * tuned to. */
static void
fill_values(double *x, int n, double base)
{
    for (int i = 0; i < n; i++)
        x[i] = base + 0.37 * i - 0.011 * i * i;
}

/* lower_eval's slots against expr_eval's, bit for bit: f's own outputs,
 * and its first copy's (unshifted) if it has copies; mode: the switches'
 * modes (NULL: none). */
static int
same_bits(const Lowered *L, const LowFunc *f, const double *mode)
{
    const LowModel *md = &L->model;
    /* (a speed's leaf is a coordinate after the nq: vcoord) */
    int n = md->nq + md->nv + 1, nu = md->nu + 1, nc = md->nc + 1;
    double *q[EXPR_MAX_ORDER + 1], *seed[3], *p = malloc((size_t)(md->np + 1) * sizeof *p);
    double *u = malloc((size_t)nu * sizeof *u), *lam = malloc((size_t)nc * sizeof *lam);
    for (int k = 0; k <= EXPR_MAX_ORDER; k++)
        fill_values(q[k] = malloc((size_t)n * sizeof *q[k]), n, 0.3 - 0.2 * k);
    for (int k = 0; k < 3; k++)
        fill_values(seed[k] = malloc((size_t)n * sizeof *seed[k]), n, 0.7 + 0.1 * k);
    for (int k = 0; k < md->np; k++)
        p[k] = md->param[k].value;
    fill_values(u, nu, 0.45);
    fill_values(lam, nc, -0.25);
    ExprEnv env = {0.8, {q[0], q[1], q[2], q[3]}, p, u, {seed[0], seed[1], seed[2]}, lam, mode};
    LowArgs a;
    lower_args(f->sig, &a);
    double *out[LOW_MAX_ARGS];
    for (int k = 0; k < a.n - a.nin; k++) {
        size_t len = (size_t)lower_size(f, k) + 1;
        out[k] = malloc(len * sizeof *out[k]);
        for (size_t i = 0; i < len; i++)
            out[k][i] = NAN;
    }
    lower_eval(P, f, &env, out);
    int ok = 1;
    for (int i = 0; i < f->nout && ok; i++) {
        double want = expr_eval(P, f->out[i].e, &env);
        ok = !memcmp(&want, &out[f->out[i].arg][f->out[i].index], sizeof want);
    }
    for (int i = 0; f->copy && i < f->copy->nout && ok; i++) {
        const LowSlot *o = &f->copy->out[i];
        double want = expr_eval(P, o->e, &env);
        ok = !memcmp(&want, &out[o->arg][o->index], sizeof want);
    }
    for (int k = 0; k < a.n - a.nin; k++)
        free(out[k]);
    for (int k = 0; k <= EXPR_MAX_ORDER; k++)
        free(q[k]);
    for (int k = 0; k < 3; k++)
        free(seed[k]);
    free(p);
    free(u);
    free(lam);
    return ok;
}

static void
test_model(const char *path, int jacobian, const char *how)
{
    Lowered *L = lowered(path, jacobian, NULL);
    CHECK(L != NULL, "%s: lowered (%s Jacobian)", path, how);
    if (!L)
        return;
    int nfunc = 0, nsched = 0, ntopo = 0, nsame = 0;
    for (int k = 0; k < L->nfunc; k++) {
        const LowFunc *f = L->func[k];
        for (const LowFunc *g = f; g; g = g->copy) {
            LowSched *S = lower_schedule(P, g, 1);
            ntopo += topological(g, S);
            ncut += !S->whole;
            nsched++;
            lower_sched_free(S);
        }
        /* the modes: none, or each switch off, on, then alternating */
        int nsw = expr_nswitch(P), same = 1;
        double *mode = malloc(((size_t)nsw + 1) * sizeof *mode);
        for (int pat = 0; pat < (nsw ? 4 : 1); pat++) {
            for (int j = 0; j < nsw; j++)
                mode[j] = pat == 1 ? 1 : pat == 2 ? j % 2 : pat == 3 ? (j + 1) % 2 : 0;
            same &= same_bits(L, f, nsw ? mode : NULL);
        }
        free(mode);
        nsame += same;
        nfunc++;
    }
    CHECK(ntopo == nsched, "%s (%s): every schedule in topological order", path, how);
    CHECK(nsame == nfunc, "%s (%s): lower_eval = expr_eval to the bit, %d of %d functions",
          path, how, nsame, nfunc);
}

/* The operations f's schedule runs with every mode 0 (no lazy block of
 * mode 1, every one of mode 0), and in *nsel the SELECTs among them. */
static ExprCount
run_apart(const LowFunc *f, int *nsel)
{
    LowSched *S = lower_schedule(P, f, 1);
    ExprId *run = malloc(((size_t)S->nnode + 1) * sizeof *run);
    size_t n = 0;
    int skip = 0;
    *nsel = 0;
    for (int k = 0; k < S->nstep; k++) {
        const LowStep *st = &S->step[k];
        if (st->kind == LOW_STEP_IF)
            skip = st->branch == 1;
        else if (st->kind == LOW_STEP_ELSE)
            skip = !skip;
        else if (st->kind == LOW_STEP_END)
            skip = 0;
        else if (st->kind == LOW_STEP_NODE && !skip) {
            run[n++] = st->id;
            *nsel += expr_node(P, st->id)->op == EXPR_SELECT;
        }
    }
    ExprCount c = expr_count_list(P, n, run);
    free(run);
    lower_sched_free(S);
    return c;
}

static const LowFunc *
func_named(const Lowered *L, const char *name)
{
    for (int k = 0; k < L->nfunc; k++)
        if (!strcmp(L->func[k]->sig->name, name))
            return L->func[k];
    return NULL;
}

/* path's scene 'apart' (bodies far from each other and the floor)
 * against its scene 'off' (no contact): with every mode 0, mass_bias,
 * accel and the Jacobian run the same divisions and calls, and at most
 * two more additions or multiplications per SELECT they run (the sum a
 * pair's share joins, its product in the solve). */
static void
test_far(const char *path)
{
    static const char *const names[] = {"mass_bias", "accel_solve", "jacobian"};
    for (int j = 0; j < 3; j++) {
        Lowered *on = lowered(path, LOWER_JACOBIAN_UNROLLED, "apart");
        const LowFunc *f = on ? func_named(on, names[j]) : NULL;
        int nsel = 0, nsel_off = 0;
        ExprCount a = f ? run_apart(f, &nsel) : (ExprCount){0, 0, 0, 0};
        ExprCount e = {0, 0, 0, 0};
        if (f) { /* what the C computed before: every branch */
            LowSched *S = lower_schedule(P, f, 0);
            for (int k = 0; k < S->nstep; k++)
                if (S->step[k].kind == LOW_STEP_NODE) {
                    ExprCount one = expr_count_list(P, 1, &S->step[k].id);
                    e.adds += one.adds, e.muls += one.muls, e.divs += one.divs,
                        e.calls += one.calls;
                }
            lower_sched_free(S);
        }
        Lowered *off = lowered(path, LOWER_JACOBIAN_UNROLLED, "off");
        const LowFunc *g = off ? func_named(off, names[j]) : NULL;
        ExprCount b = g ? run_apart(g, &nsel_off) : (ExprCount){0, 0, 0, 0};
        CHECK(f && g && a.divs == b.divs && a.calls == b.calls &&
                  a.adds + a.muls <= b.adds + b.muls + 2 * nsel && nsel > 0,
              "%s, every pair far: %s runs %ld + %ld + %ld + %ld operations (adds, muls, divs, "
              "calls; %d modes tested), without the contact %ld + %ld + %ld + %ld; every branch "
              "computed, %ld + %ld + %ld + %ld", path, names[j], a.adds, a.muls, a.divs, a.calls,
              nsel, b.adds, b.muls, b.divs, b.calls, e.adds, e.muls, e.divs, e.calls);
    }
}

int
main(int argc, char **argv)
{
    A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--far") && i + 1 < argc) {
            test_far(argv[++i]);
            continue;
        }
        test_model(argv[i], LOWER_JACOBIAN_UNROLLED, "unrolled");
        test_model(argv[i], LOWER_JACOBIAN_SEEDED, "seeded");
    }
    CHECK(ncut > 0, "%d schedules of functions past LOWER_PART_SIZE nodes (depth-first)", ncut);
    CHECK(nblocks > 0, "%d lazy blocks in the schedules", nblocks);
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}

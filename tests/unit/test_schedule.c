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
lowered(const char *path, int jacobian)
{
    Spec *s = spec_load(path, NULL, A, P);
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

/* Each node once, after the nodes it reads; each store after its value;
 * a value of a lazy block read only where its mode and branch hold. */
static int
topological(const LowFunc *f, const LowSched *S)
{
    size_t size = expr_pool_size(P);
    unsigned char *done = calloc(size, 1);
    int *where = malloc(size * sizeof *where); /* 2 mode + branch of its block, or -1 */
    int ok = 1, nnode = 0, in = -1;
    for (int k = 0; k < S->nstep && ok; k++) {
        const LowStep *st = &S->step[k];
        if (st->kind == LOW_STEP_IF) {
            ok = in < 0;
            in = 2 * st->i + st->branch;
            nblocks++;
        } else if (st->kind == LOW_STEP_ELSE) {
            ok = in >= 0;
            in ^= 1;
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
                int taken = nd->op == EXPR_SELECT && in < 0 &&
                            where[ops[j]] == 2 * expr_select_mode(P, st->id) + (j == 0);
                ok = taken || where[ops[j]] == in;
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
    int n = md->nq + 1, nu = md->nu + 1, nc = md->nc + 1;
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
    Lowered *L = lowered(path, jacobian);
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

int
main(int argc, char **argv)
{
    A = arena_new();
    P = expr_pool_new();
    D = diff_new(P);
    for (int i = 1; i < argc; i++) {
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

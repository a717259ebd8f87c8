/*
 * emit: the C printer.
 *
 * A function is a list of outputs (an expression and the C lvalue it goes
 * to).  We schedule the operator nodes the outputs need depth-first, in
 * output order, then (in a function printed whole) in the order they could
 * start on a core that runs them out of order (order_by_start), and print
 * one `const double` temporary per node; each output is assigned as soon
 * as its value exists.  All cleverness is in the DAG; this is a plain
 * loop.
 *
 * Very large functions (the Jacobian of a 50-link chain has ~70 000
 * nodes) are cut into parts of at most PART_SIZE temporaries, each its own
 * non-inlined C function: the C compiler's register allocator is
 * superlinear in function size, and parts keep `cc -O2` time linear.
 * A part ends after an output, or inside one output's nodes when they
 * alone are too many (a recursive solve writes q'' only at its end).
 * Values needed by a later part travel through a stack array s[].
 */
#include "emit.h"
#include "../runtime/numfmt.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* gcc -O2's time per statement grows with the function: on the 30-body
 * tree's articulated-body solve, parts of 6000 took 11.7 s of cc, of 1500
 * 7.6 s (its register allocation alone 4.2 -> 0.6 s), for no loss of
 * speed. */
enum { PART_SIZE = 1500 };

/* A model whose cut functions give the second unit at least this many
 * parts (some 4 500 operations, ~0.5 s of cc -O1) is printed as two
 * translation units that eomc build compiles at once (tree 30: 3.3 s of
 * cc as one, ~1.7 s each as two); fewer would save less than a second
 * compiler costs to start. */
enum { SPLIT_MIN_PARTS = 3 };

/* The arrays leaves are read from, in the order their locals are
 * declared and unused ones are (void)ed: a function reads only those
 * among its inputs. */
enum { SRC_Q, SRC_V, SRC_A, SRC_P, SRC_U, SRC_T, SRC_DQ, SRC_DV, SRC_DA, SRC_LAM, NSRC };
static const char *const src_name[NSRC] = {"q", "v", "a", "p", "u", "t", "dq", "dv", "da",
                                           "lam"};

/* A function being printed: its list and its signature. */
typedef struct Func {
    const LowFunc *low;
    LowArgs args;
    char params[600]; /* the C parameter list */
    char names[300];  /* the parameter names, comma-separated */
    int has[NSRC];    /* which sources are among the inputs */
} Func;

typedef struct Printer {
    FILE *f;
    ExprPool *P;
    const Spec *s;
    const Lowered *L;
    /* per node id, for the function being printed */
    int *temp;  /* temporary number, -1 if not scheduled */
    int *part;  /* the part that computes it */
    int *slot;  /* index in s[], -1 if only its own part uses it */
    const int *ext; /* NULL, or per node its index in an input array shared[]
                     * (-1: not there): values computed once by another function */
    const int *derived; /* NULL, or per node its index in pd[] (-1: not there):
                         * values of the parameters alone, read from p[np + k] */
    int cur;    /* the part being printed */
    unsigned used; /* bit k: source k is read in this part */
    int fenced;    /* inside #ifndef EOMC_EXTENDED */
    /* A large model is two translation units (SPLIT_MIN_PARTS): the even
     * parts of each cut function go to unit2, with its own fence. */
    FILE *unit2;   /* NULL: one unit */
    int fenced2;
    int nunit2;    /* parts printed to unit2 */
    long nodes[2]; /* temporaries printed to each unit: a part goes to the one behind */
} Printer;


static void
println(Printer *pr, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfprintf(pr->f, fmt, ap);
    va_end(ap);
    fputc('\n', pr->f);
}

/* What follows is compiled in double only (1: the functions the
 * reference solution does not need), or in both precisions (0). */
static void
fence(Printer *pr, int double_only)
{
    if (double_only && !pr->fenced)
        println(pr, "#ifndef EOMC_EXTENDED");
    else if (!double_only && pr->fenced)
        println(pr, "#endif /* EOMC_EXTENDED */\n");
    pr->fenced = double_only;
}

/* Swap the stream and fence being printed with the second unit's. */
static void
unit2_swap(Printer *pr)
{
    FILE *f = pr->f;
    pr->f = pr->unit2, pr->unit2 = f;
    int fenced = pr->fenced;
    pr->fenced = pr->fenced2, pr->fenced2 = fenced;
}

/* A part of a function compiled in double only or in both precisions
 * goes to the second unit, fenced so. */
static void
unit2_begin(Printer *pr, int double_only)
{
    unit2_swap(pr);
    fence(pr, double_only);
    pr->nunit2++;
}

static void
unit2_end(Printer *pr)
{
    unit2_swap(pr);
}

/* Lines of generated code are wrapped before this column. */
enum { WRAP = 80 };

/* "TYPE\nNAME(PARAMS)" then tail, the comma-separated parameters wrapped. */
static void
print_decl(Printer *pr, const char *type, const char *name, const char *params,
           const char *tail)
{
    fprintf(pr->f, "%s\n%s(", type, name);
    int col = (int)strlen(name) + 1;
    for (const char *p = params; *p;) {
        int len = (int)strcspn(p, ",");
        if (p != params && col + 2 + len + 1 > WRAP) {
            fputs(",\n    ", pr->f);
            col = 4;
        } else if (p != params) {
            fputs(", ", pr->f);
            col += 2;
        }
        fprintf(pr->f, "%.*s", len, p);
        col += len;
        p += len;
        p += strspn(p, ", ");
    }
    fprintf(pr->f, ")%s\n", tail);
}

/* "TYPE\nNAME(PARAMS)\n{" */
static void
print_head(Printer *pr, const char *type, const char *name, const char *params)
{
    print_decl(pr, type, name, params, "\n{");
}

/* The shortest text that reads back as the same double (runtime/numfmt.h:
 * 9.81, not 9.8100000000000005; 10, not 1e+01), made to look like a
 * double to C. */
static void
format_const(char *buf, size_t len, double v)
{
    char num[NUM_MAX];
    snprintf(buf, len, "%s", num_shortest(num, v));
    if (!strpbrk(buf, ".eEn"))
        strncat(buf, ".0", len - strlen(buf) - 1);
}

static int is_leaf(const ExprNode *nd) { return expr_op_arity[nd->op] == 0; }

static int is_ext(const Printer *pr, ExprId e) { return pr->ext && pr->ext[e] >= 0; }
static int is_derived(const Printer *pr, ExprId e)
{
    return pr->derived && pr->derived[e] >= 0 && !is_ext(pr, e);
}
/* Not computed here: a leaf, a shared value or a derived one. */
static int is_input(const Printer *pr, ExprId e)
{
    return is_leaf(expr_node(pr->P, e)) || is_ext(pr, e) || is_derived(pr, e);
}

static void
leaf_name(Printer *pr, const ExprNode *nd, char *buf, size_t len)
{
    static const char prefix[] = {'q', 'v', 'a', 'j'};
    switch (nd->op) {
    case EXPR_SEED:
        snprintf(buf, len, "%s_%s", src_name[SRC_DQ + nd->b], pr->s->coord[nd->a].name);
        break;
    case EXPR_VAR:
        snprintf(buf, len, "%c_%s", prefix[nd->b], pr->s->coord[nd->a].name);
        break;
    case EXPR_PARAM:
        snprintf(buf, len, "p_%s", pr->s->param[nd->a].name);
        break;
    case EXPR_INPUT:
        snprintf(buf, len, "u_%s", pr->s->input[nd->a].name);
        break;
    case EXPR_MULT:
        snprintf(buf, len, "lam_%s", pr->s->constraint[nd->a].name);
        break;
    default:
        snprintf(buf, len, "t");
    }
}

/* The spelling of an operand: a constant (negative ones in parentheses so
 * that `x - -1` never appears), a leaf's local, a value computed by
 * another function (shared[]), a temporary of this part, or a value shared from
 * an earlier part. */
static const char *
operand(Printer *pr, ExprId e, char *buf, size_t len)
{
    const ExprNode *nd = expr_node(pr->P, e);
    if (nd->op == EXPR_CONST) {
        char num[40];
        format_const(num, sizeof num, nd->value);
        snprintf(buf, len, nd->value < 0 ? "(%s)" : "%s", num);
    } else if (is_leaf(nd)) {
        leaf_name(pr, nd, buf, len);
    } else if (is_ext(pr, e)) {
        snprintf(buf, len, "shared[%d]", pr->ext[e]);
    } else if (is_derived(pr, e)) {
        snprintf(buf, len, "pd%d", pr->derived[e]);
    } else if (pr->part[e] == pr->cur) {
        snprintf(buf, len, "w%d", pr->temp[e]);
    } else {
        snprintf(buf, len, "s[%d]", pr->slot[e]);
    }
    return buf;
}

static void
print_powi(const char *x, int n, char *rhs, size_t len)
{
    if (n > 4) {
        snprintf(rhs, len, "pow(%s, %d)", x, n);
        return;
    }
    rhs[0] = '\0';
    for (int k = 0; k < n; k++) {
        if (k)
            strncat(rhs, " * ", len - strlen(rhs) - 1);
        strncat(rhs, x, len - strlen(rhs) - 1);
    }
}

/* After node id's statement: its copy for later parts. */
static void
print_share(Printer *pr, ExprId id)
{
    if (pr->slot[id] >= 0)
        println(pr, "    s[%d] = w%d;", pr->slot[id], pr->temp[id]);
}

static void
print_node(Printer *pr, ExprId id)
{
    const ExprNode *nd = expr_node(pr->P, id);
    char ba[200], bb[200], rhs[512];
    const char *x = NULL, *y = NULL;
    int ar = expr_op_arity[nd->op];
    if (ar >= 1)
        x = operand(pr, nd->a, ba, sizeof ba);
    if (ar >= 2)
        y = operand(pr, nd->b, bb, sizeof bb);
    const char *sp = expr_op_spelling[nd->op];
    switch (expr_op_kind[nd->op]) {
    case OPK_INFIX:
        snprintf(rhs, sizeof rhs, "%s %s %s", x, sp, y);
        break;
    case OPK_PREFIX:
        snprintf(rhs, sizeof rhs, "-%s", x);
        break;
    default:
        if (nd->op == EXPR_POWI)
            print_powi(x, (int32_t)nd->b, rhs, sizeof rhs);
        else if (nd->op == EXPR_SIGN)
            snprintf(rhs, sizeof rhs, "(eomc_real)((%s > 0) - (%s < 0))", x, x);
        else if (ar == 2)
            snprintf(rhs, sizeof rhs, "%s(%s, %s)", sp, x, y);
        else
            snprintf(rhs, sizeof rhs, "%s(%s)", sp, x);
    }
    println(pr, "    const eomc_real w%d = %s;", pr->temp[id], rhs);
    print_share(pr, id);
}

/* ---- scheduling ---- */

typedef struct Sched {
    ExprId *node;  /* operator nodes in print order */
    int n;
    /* node[angles, angles_end) are sines and cosines computed together
     * (schedule_angles): nangle angles, angle_of[k - angles] the one
     * node k is the sine (2 j) or cosine (2 j + 1) of */
    int angles, angles_end, nangle;
    ExprId *angle;
    int *angle_of;
    int *after;    /* per output: nodes printed before its assignment */
    int *order;    /* the outputs in print order (NULL: as listed) */
    int *pstart;   /* per part: first node; pstart[nparts] = n */
    int *ostart;   /* per part: first output; ostart[nparts] = nout */
    int nparts, nslots;
} Sched;

/* Append the unscheduled operator nodes that root needs, operands first. */
static void
schedule_tree(Printer *pr, Sched *S, ExprId root)
{
    size_t cap = 64, sp = 0;
    struct { ExprId id; int expanded; } *stack = xmalloc(cap * sizeof *stack);
    stack[sp].id = root;
    stack[sp++].expanded = 0;
    while (sp) {
        ExprId e = stack[sp - 1].id;
        const ExprNode *nd = expr_node(pr->P, e);
        if (is_input(pr, e) || pr->temp[e] >= 0) {
            sp--;
        } else if (stack[sp - 1].expanded) {
            sp--;
            pr->temp[e] = S->n;
            S->node[S->n++] = e;
        } else {
            stack[sp - 1].expanded = 1;
            if (sp + 2 >= cap)
                stack = xrealloc(stack, (cap *= 2) * sizeof *stack);
            int ar = expr_op_arity[nd->op];
            ExprId ops[2] = {nd->a, nd->b};
            for (int k = ar - 1; k >= 0; k--) { /* operand a comes first */
                stack[sp].id = ops[k];
                stack[sp++].expanded = 0;
            }
        }
    }
    free(stack);
}

/* The sines and cosines whose angles need no other sine or cosine (a
 * turn's coordinate, a sum of coordinates) come first, all computed by one
 * call of eomc_sincos (eomc_model.h), which computes several at once
 * where the machine has vector instructions for it: each angle's
 * operations, then the angles' sines and cosines.  Fewer than
 * ANGLES_MIN angles keep their own sin and cos calls. */
enum { ANGLES_MIN = 2 };

static void
schedule_angles(Printer *pr, Sched *S, int nout, const LowSlot *out)
{
    size_t size = expr_pool_size(pr->P);
    /* per node: 0 unseen, 1 seen, no sine or cosine in it, 2 one in it */
    unsigned char *seen = xmalloc(size);
    memset(seen, 0, size);
    /* a node is pushed once per edge into it at most: 2 per node (arity <= 2) */
    ExprId *trig = xmalloc(size * sizeof *trig), *stack = xmalloc((2 * size + 1) * sizeof *stack);
    size_t ntrig = 0;
    for (int i = 0; i < nout; i++) { /* post-order, iteratively: DAGs are deep */
        size_t sp = 0;
        if (!seen[out[i].e])
            stack[sp++] = out[i].e;
        while (sp) {
            ExprId e = stack[sp - 1];
            const ExprNode *nd = expr_node(pr->P, e);
            int ar = is_input(pr, e) ? 0 : expr_op_arity[nd->op];
            ExprId ops[2] = {nd->a, nd->b};
            int pushed = 0;
            for (int k = ar - 1; k >= 0; k--)
                if (!seen[ops[k]])
                    stack[sp++] = ops[k], pushed = 1;
            if (pushed)
                continue;
            sp--;
            if (seen[e])
                continue;
            int below = 0;
            for (int k = 0; k < ar; k++)
                below |= seen[ops[k]] == 2;
            int is_trig = ar && (nd->op == EXPR_SIN || nd->op == EXPR_COS);
            if (is_trig && !below)
                trig[ntrig++] = e;
            seen[e] = below || is_trig ? 2 : 1;
        }
    }
    /* the angles, in order of first use; each one's sine and cosine, */
    S->angle = xmalloc((ntrig + 1) * sizeof *S->angle);
    ExprId(*pair)[2] = xmalloc((ntrig + 1) * sizeof *pair);
    int na = 0;
    for (size_t t = 0; t < ntrig; t++) {
        const ExprNode *nd = expr_node(pr->P, trig[t]);
        int j = 0;
        while (j < na && S->angle[j] != nd->a)
            j++;
        if (j == na) {
            S->angle[na] = nd->a;
            pair[na][0] = pair[na][1] = EXPR_NONE;
            na++;
        }
        pair[j][nd->op == EXPR_COS] = trig[t];
    }
    /* then by height, stably: the vector of the angles ready first does
     * not wait for the last one (a chain's sum of all its coordinates) */
    for (int j = 1; j < na; j++)
        for (int k = j; k > 0 && expr_node(pr->P, S->angle[k - 1])->height >
                                     expr_node(pr->P, S->angle[k])->height; k--) {
            ExprId a = S->angle[k], p0 = pair[k][0], p1 = pair[k][1];
            S->angle[k] = S->angle[k - 1], pair[k][0] = pair[k - 1][0];
            pair[k][1] = pair[k - 1][1];
            S->angle[k - 1] = a, pair[k - 1][0] = p0, pair[k - 1][1] = p1;
        }
    S->nangle = 0;
    S->angles = S->angles_end = S->n;
    S->angle_of = NULL;
    if (na >= ANGLES_MIN) {
        S->nangle = na;
        for (int j = 0; j < na; j++)
            schedule_tree(pr, S, S->angle[j]);
        S->angles = S->n;
        S->angle_of = xmalloc(2 * (size_t)na * sizeof *S->angle_of);
        for (int j = 0; j < na; j++)
            for (int k = 0; k < 2; k++)
                if (pair[j][k] != EXPR_NONE) {
                    S->angle_of[S->n - S->angles] = 2 * j + k;
                    pr->temp[pair[j][k]] = S->n;
                    S->node[S->n++] = pair[j][k];
                }
        S->angles_end = S->n;
    }
    free(pair);
    free(trig);
    free(stack);
    free(seen);
}

/* A value crossing into another part gets a slot in s[]. */
/* Latencies in cycles on a current x86-64 core (an addition or a
 * multiplication 3 to 4, a division 13 to 15, a libm call some 20): only
 * their ratios matter. */
enum { LAT_ADD = 3, LAT_MUL = 3, LAT_DIV = 13, LAT_CALL = 20 };

static int
latency(int op)
{
    switch (op) {
    case EXPR_ADD: case EXPR_SUB: case EXPR_NEG: return LAT_ADD;
    case EXPR_MUL: case EXPR_POWI: return LAT_MUL; /* powi 2: x * x, the most common */
    case EXPR_DIV: return LAT_DIV;
    default: return LAT_CALL;
    }
}

typedef struct Start {
    int at, k; /* the cycle a node could start, its place depth-first */
} Start;

static int
start_cmp(const void *pa, const void *pb)
{
    const Start *a = pa, *b = pb;
    return a->at != b->at ? (a->at > b->at) - (a->at < b->at) : (a->k > b->k) - (a->k < b->k);
}

/* A core runs instructions out of order, but only within a window of a
 * few hundred after the oldest one it waits on.  Depth-first, a solve's
 * chain of dependent pivots comes first and fills that window, and the
 * independent work printed after it (the bias's terms) waits behind it.
 * So the nodes after the angles are printed in the order they could
 * start, by the latencies above, depth-first order breaking ties (a
 * topological order still: a node starts after its operands), and are
 * numbered so; each output is stored when its value is done.  The
 * angles' sines and cosines count as ready at the start, as the leaves:
 * counting their call's latency put the work that needs none of them
 * first, which measured slower (chain 5: 80 against 77 ns).  Chain 5's
 * right-hand side: 80 -> 75 ns.  Only for a function printed whole: a cut
 * one keeps its parts depth-first, which keeps the values they share
 * few. */
static void
order_by_start(Printer *pr, Sched *S, int nout, const LowSlot *out)
{
    int n = S->n, from = S->angles_end;
    int *done = xmalloc(((size_t)n + 1) * sizeof *done);
    Start *st = xmalloc(((size_t)n + 1) * sizeof *st);
    for (int k = 0; k < n; k++) {
        const ExprNode *nd = expr_node(pr->P, S->node[k]);
        int at = 0;
        if (k >= S->angles && k < S->angles_end) {
            done[k] = 0;
        } else {
            int ar = expr_op_arity[nd->op];
            ExprId ops[2] = {nd->a, nd->b};
            for (int j = 0; j < ar; j++) {
                int t = is_input(pr, ops[j]) ? -1 : pr->temp[ops[j]];
                if (t >= 0 && done[t] > at)
                    at = done[t];
            }
            done[k] = at + latency(nd->op);
        }
        st[k] = (Start){at, k};
    }
    qsort(st + from, (size_t)(n - from), sizeof *st, start_cmp);
    ExprId *node = xmalloc(((size_t)n + 1) * sizeof *node);
    for (int k = from; k < n; k++)
        node[k] = S->node[st[k].k];
    for (int k = from; k < n; k++) {
        S->node[k] = node[k];
        pr->temp[node[k]] = k;
    }
    /* an output's store when its value is done, by the same order: after
     * the nodes that could start before, its place depth-first breaking
     * ties (a leaf's: done at once) */
    Start *os = xmalloc(((size_t)nout + 1) * sizeof *os);
    for (int i = 0; i < nout; i++) {
        int t = is_input(pr, out[i].e) ? -1 : pr->temp[out[i].e];
        Start key = {t < 0 ? 0 : done[t >= from ? st[t].k : t], S->after[i]};
        int lo = from, hi = n; /* the first node after key */
        while (lo < hi) {
            int mid = lo + (hi - lo) / 2;
            if (start_cmp(&st[mid], &key) < 0)
                lo = mid + 1;
            else
                hi = mid;
        }
        if (t >= 0 && lo <= t)
            lo = t + 1;
        os[i] = (Start){lo < S->angles_end ? S->angles_end : lo, i};
    }
    qsort(os, (size_t)nout, sizeof *os, start_cmp);
    S->order = xmalloc(((size_t)nout + 1) * sizeof *S->order);
    for (int i = 0; i < nout; i++) {
        S->order[i] = os[i].k;
        S->after[os[i].k] = os[i].at;
    }
    free(os);
    free(node);
    free(st);
    free(done);
}

static void
share(Printer *pr, Sched *S, ExprId e, int part)
{
    if (!is_input(pr, e) && pr->part[e] != part &&
        pr->slot[e] < 0)
        pr->slot[e] = S->nslots++;
}

static void
schedule(Printer *pr, Sched *S, int nout, const LowSlot *out)
{
    size_t size = expr_pool_size(pr->P);
    S->node = xmalloc(size * sizeof *S->node);
    S->after = xmalloc(((size_t)nout + 1) * sizeof *S->after);
    S->n = S->nparts = S->nslots = 0;
    S->order = NULL;
    schedule_angles(pr, S, nout, out);
    for (int i = 0; i < nout; i++) {
        schedule_tree(pr, S, out[i].e);
        S->after[i] = S->n;
    }
    if (S->n < PART_SIZE) { /* printed whole */
        order_by_start(pr, S, nout, out);
        S->pstart = xmalloc(2 * sizeof *S->pstart);
        S->ostart = xmalloc(2 * sizeof *S->ostart);
        S->nparts = 1;
        S->pstart[0] = S->ostart[0] = 0;
        S->pstart[1] = S->n;
        S->ostart[1] = nout;
        return;
    }
    /* Cut after an output once a part has PART_SIZE nodes, and inside
     * one output's nodes where they alone would pass it (a recursive
     * solve's outputs come only at its end). */
    size_t cap = (size_t)nout + 2 + (size_t)S->n / PART_SIZE + 1;
    S->pstart = xmalloc(cap * sizeof *S->pstart);
    S->ostart = xmalloc(cap * sizeof *S->ostart);
    S->pstart[0] = S->ostart[0] = 0;
    for (int i = 0; i < nout; i++) {
        while (S->after[i] - S->pstart[S->nparts] > PART_SIZE) {
            int cut = S->pstart[S->nparts] + PART_SIZE;
            if (cut > S->angles && cut < S->angles_end) /* not inside the one call */
                cut = S->angles_end;
            S->nparts++;
            S->pstart[S->nparts] = cut;
            S->ostart[S->nparts] = i;
        }
        if (S->after[i] - S->pstart[S->nparts] >= PART_SIZE || i == nout - 1) {
            S->nparts++;
            S->pstart[S->nparts] = S->after[i];
            S->ostart[S->nparts] = i + 1;
        }
    }
    if (S->nparts == 0) { /* no outputs */
        S->nparts = 1;
        S->pstart[1] = S->ostart[1] = 0;
    }
    for (int p = 0; p < S->nparts; p++)
        for (int k = S->pstart[p]; k < S->pstart[p + 1]; k++)
            pr->part[S->node[k]] = p;
    for (int p = 0; p < S->nparts; p++) {
        for (int k = S->pstart[p]; k < S->pstart[p + 1]; k++) {
            const ExprNode *nd = expr_node(pr->P, S->node[k]);
            int ar = expr_op_arity[nd->op];
            if (ar >= 1)
                share(pr, S, nd->a, p);
            if (ar >= 2)
                share(pr, S, nd->b, p);
        }
        for (int i = S->ostart[p]; i < S->ostart[p + 1]; i++)
            share(pr, S, out[i].e, p);
    }
}

/* ---- printing ---- */

/* The leaves and derived values a part reads, each once: marked in a
 * byte per node of the pool (allocated once per printer, cleared after
 * each part by the list, not by a sweep of the pool) and listed. */
typedef struct LeafSet {
    unsigned char *mark; /* [pool size] */
    ExprId *list;
    size_t n, cap;
} LeafSet;

static void
mark_leaf(Printer *pr, ExprId e, LeafSet *ls)
{
    if (ls->mark[e] || !(is_leaf(expr_node(pr->P, e)) || is_derived(pr, e)))
        return;
    ls->mark[e] = 1;
    if (ls->n == ls->cap) {
        ls->cap = ls->cap ? 2 * ls->cap : 64;
        ls->list = xrealloc(ls->list, ls->cap * sizeof *ls->list);
    }
    ls->list[ls->n++] = e;
}

static int
cmp_id(const void *x, const void *y)
{
    ExprId a = *(const ExprId *)x, b = *(const ExprId *)y;
    return (a > b) - (a < b);
}

/* Named locals for the leaves part p reads, in a fixed order: t, the
 * coordinates by derivative order, parameters, inputs, seeds, then the
 * parameters' derived values (pdK = p[np + K]); within a kind, by id. */
static void
print_leaves(Printer *pr, const Sched *S, int nout, const LowSlot *out)
{
    static const int kinds[] = {EXPR_TIME, EXPR_VAR, EXPR_PARAM, EXPR_INPUT, EXPR_SEED,
                                EXPR_MULT};
    size_t size = expr_pool_size(pr->P);
    LeafSet ls = {xmalloc(size), NULL, 0, 0};
    memset(ls.mark, 0, size);
    for (int k = S->pstart[pr->cur]; k < S->pstart[pr->cur + 1]; k++) {
        const ExprNode *nd = expr_node(pr->P, S->node[k]);
        int ar = expr_op_arity[nd->op];
        if (ar >= 1)
            mark_leaf(pr, nd->a, &ls);
        if (ar >= 2)
            mark_leaf(pr, nd->b, &ls);
    }
    for (int i = S->ostart[pr->cur]; i < S->ostart[pr->cur + 1] && i < nout; i++)
        mark_leaf(pr, out[i].e, &ls);
    if (ls.n)
        qsort(ls.list, ls.n, sizeof *ls.list, cmp_id);
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++)
        for (size_t j = 0; j < ls.n; j++) {
            const ExprNode *nd = expr_node(pr->P, ls.list[j]);
            if (nd->op != kinds[k])
                continue;
            if (nd->op == EXPR_TIME) {
                pr->used |= 1u << SRC_T;
                continue;
            }
            int arr = nd->op == EXPR_VAR    ? SRC_Q + (int)nd->b
                      : nd->op == EXPR_PARAM  ? SRC_P
                      : nd->op == EXPR_INPUT  ? SRC_U
                      : nd->op == EXPR_MULT   ? SRC_LAM
                                              : SRC_DQ + (int)nd->b; /* seeds */
            char buf[160];
            leaf_name(pr, nd, buf, sizeof buf);
            pr->used |= 1u << arr;
            println(pr, "    const eomc_real %s = %s[%u];", buf, src_name[arr], nd->a);
        }
    for (size_t j = 0; j < ls.n; j++)
        if (is_derived(pr, ls.list[j])) {
            ExprId id = ls.list[j];
            pr->used |= 1u << SRC_P;
            println(pr, "    const eomc_real pd%d = p[%d];", pr->derived[id],
                    pr->s->np + pr->derived[id]);
        }
    free(ls.mark);
    free(ls.list);
}

/* The sines and cosines of schedule_angles: the angles into an array,
 * one call, each value its temporary.  Returns the node after them. */
static int
print_angles(Printer *pr, const Sched *S)
{
    int na = S->nangle;
    println(pr, "    eomc_real ang[%d], ang_sin[%d], ang_cos[%d]; /* %d angles at once */", na,
            na, na, na);
    for (int j = 0; j < na; j++) {
        char buf[200];
        println(pr, "    ang[%d] = %s;", j, operand(pr, S->angle[j], buf, sizeof buf));
    }
    println(pr, "    eomc_sincos(%d, ang, ang_sin, ang_cos);", na);
    for (int k = S->angles; k < S->angles_end; k++) {
        ExprId id = S->node[k];
        int a = S->angle_of[k - S->angles];
        println(pr, "    const eomc_real w%d = ang_%s[%d];", pr->temp[id],
                a % 2 ? "cos" : "sin", a / 2);
        print_share(pr, id);
    }
    return S->angles_end;
}

/* Node k's statement, or the angles' call where they start; the next k. */
static int
print_step(Printer *pr, const Sched *S, int k)
{
    if (k == S->angles && S->angles < S->angles_end)
        return print_angles(pr, S);
    print_node(pr, S->node[k]);
    return k + 1;
}

/* The statements of part p: leaves, temporaries, assignments. */
static void
print_part(Printer *pr, const Sched *S, const Func *fn)
{
    const LowFunc *lf = fn->low;
    const LowArgs *a = &fn->args;
    pr->used = 0;
    for (int k = 0; pr->cur == 0 && k < a->n - a->nin; k++) {
        const char *arr = a->name[a->nin + k];
        if (!lf->fill[k])
            continue;
        if (lf->zeroed >> k & 1) {
            println(pr, "    /* %s's other entries are 0: the caller's (eomc_model.h, c_nz) */",
                    arr);
            continue;
        }
        if (a->optional[a->nin + k])
            println(pr, "    if (%s)", arr);
        println(pr, "    %sfor (int i = 0; i < %d; i++) /* the nonzeros follow */\n"
                "    %s    %s[i] = 0.0;", a->optional[a->nin + k] ? "    " : "", lf->fill[k],
                a->optional[a->nin + k] ? "    " : "", arr);
    }
    print_leaves(pr, S, lf->nout, lf->out);
    if (S->nparts == 1) { /* silence -Wunused-parameter */
        for (int k = 0; k < NSRC; k++)
            if (fn->has[k] && !(pr->used >> k & 1))
                println(pr, "    (void)%s;", src_name[k]);
        for (int k = 0; k < a->nin; k++) /* read through ext, not as leaves */
            if (!strcmp(a->name[k], "shared"))
                println(pr, "    (void)%s;", a->name[k]);
        for (int k = a->nin; k < a->n; k++)
            if (lower_size(lf, k - a->nin) == 0)
                println(pr, "    (void)%s;", a->name[k]);
    }
    int k = S->pstart[pr->cur];
    for (int j = S->ostart[pr->cur]; j < S->ostart[pr->cur + 1]; j++) {
        int i = S->order ? S->order[j] : j;
        while (k < S->after[i])
            k = print_step(pr, S, k);
        const LowSlot *o = &lf->out[i];
        const char *arr = a->name[a->nin + o->arg];
        char buf[200];
        operand(pr, o->e, buf, sizeof buf);
        if (a->optional[a->nin + o->arg])
            println(pr, "    if (%s) %s[%d] = %s;", arr, arr, o->index, buf);
        else
            println(pr, "    %s[%d] = %s;", arr, o->index, buf);
    }
    while (k < S->pstart[pr->cur + 1]) /* a cut inside an output's nodes */
        k = print_step(pr, S, k);
}

/* (void) every parameter: a part uses only some of them. */
static void
print_voids(Printer *pr, const char *args)
{
    fprintf(pr->f, "    (void)s;");
    for (const char *p = args; *p;) {
        size_t n = strcspn(p, ", ");
        fprintf(pr->f, " (void)%.*s;", (int)n, p);
        p += n;
        p += strspn(p, ", ");
    }
    fputc('\n', pr->f);
}

/* The C parameter list and names of a signature. */
static void
func_of(Func *fn, const LowFunc *lf)
{
    fn->low = lf;
    lower_args(lf->sig, &fn->args);
    const LowArgs *a = &fn->args;
    fn->params[0] = fn->names[0] = '\0';
    memset(fn->has, 0, sizeof fn->has);
    for (int k = 0; k < a->n; k++) {
        size_t lp = strlen(fn->params), ln = strlen(fn->names);
        const char *sep = k ? ", " : "";
        if (k >= a->nin)
            snprintf(fn->params + lp, sizeof fn->params - lp, "%seomc_real *%s", sep, a->name[k]);
        else if (!strcmp(a->name[k], "t"))
            snprintf(fn->params + lp, sizeof fn->params - lp, "%seomc_real t", sep);
        else
            snprintf(fn->params + lp, sizeof fn->params - lp, "%sconst eomc_real *%s", sep,
                     a->name[k]);
        snprintf(fn->names + ln, sizeof fn->names - ln, "%s%s", sep, a->name[k]);
        for (int j = 0; j < NSRC && k < a->nin; j++)
            if (!strcmp(a->name[k], src_name[j]))
                fn->has[j] = 1;
    }
}

/* Print a lowered function; returns its operation counts. */
/* derive with tables: their constant numbers first, from NAME_numbers */
static void
print_prologue(Printer *pr, const LowFunc *lf)
{
    const Lowered *L = pr->L;
    if (lf != L->derive || !L->tables)
        return;
    println(pr, "    for (int k = 0; k < %d; k++) /* the tables' constants */",
            FORM_TABLE_STRIDE * L->tables->nt + 6);
    println(pr, "        pd[%d + k] = %s_numbers[k];", L->tree_base, pr->s->name);
}

/* The shifts of each copy (repeat.h), before the function that loops. */
static void
print_shifts(Printer *pr, const LowFunc *lf, int *du_any)
{
    *du_any = 0;
    for (int c = 0; c < lf->ncopy; c++)
        *du_any |= lf->du[c] != 0;
    for (int u = 0; u <= *du_any; u++) {
        const int *d = u ? lf->du : lf->dq;
        fprintf(pr->f, "static const int %s_%s_%s[%d] = {", pr->s->name, lf->sig->name,
                u ? "du" : "dq", lf->ncopy);
        for (int c = 0; c < lf->ncopy; c++)
            fprintf(pr->f, "%s%d", c ? ", " : "", d[c]);
        fputs("};\n", pr->f);
    }
}

/* The loop over the copies: the first copy's function on each copy's
 * arrays, every one but t and p shifted (u by its own shift). */
static void
print_copies(Printer *pr, const LowFunc *lf, const Func *fn, int du_any)
{
    if (!lf->copy)
        return;
    const char *nm = pr->s->name, *name = lf->sig->name;
    char call[2048] = "";
    size_t k = 0;
    for (int i = 0; i < fn->args.n && k < sizeof call; i++) {
        const char *arg = fn->args.name[i], *sep = i ? ", " : "";
        if (!strcmp(arg, "t") || !strcmp(arg, "p") || (!strcmp(arg, "u") && !du_any))
            k += (size_t)snprintf(call + k, sizeof call - k, "%s%s", sep, arg);
        else
            k += (size_t)snprintf(call + k, sizeof call - k, "%s%s + %s_%s_%s[c]", sep, arg, nm,
                                  name, strcmp(arg, "u") ? "dq" : "du");
    }
    if (!lf->zero_skip) {
        println(pr, "    for (int c = 0; c < %d; c++) /* copies of one subtree (repeat.c) */",
                lf->ncopy);
        println(pr, "        %s_%s(%s);", nm, lf->copy->sig->name, call);
        return;
    }
    /* a copy without a load stays at rest: zeros, not its recursion (the
     * outputs after the loop are stored after these) */
    const LowArgs *a = &fn->args;
    int hi = lf->span0 + lf->span;
    char from[32] = ""; /* " + span0" where it is not 0 */
    if (lf->span0)
        snprintf(from, sizeof from, " + %d", lf->span0);
    println(pr, "    for (int c = 0; c < %d; c++) { /* copies of one subtree (repeat.c) */",
            lf->ncopy);
    println(pr, "        const int d = %s_%s_dq[c];", nm, name);
    println(pr, "        int loaded = 0;");
    for (int i = 0; i < a->nin; i++)
        if (!strcmp(a->name[i], "dq") || !strcmp(a->name[i], "dv") || !strcmp(a->name[i], "da"))
            println(pr, "        for (int i = d%s; i < d + %d && !loaded; i++)\n"
                    "            loaded = %s[i] != 0.0;", from, hi, a->name[i]);
    println(pr, "        if (loaded) {");
    println(pr, "            %s_%s(%s);", nm, lf->copy->sig->name, call);
    println(pr, "            continue;");
    println(pr, "        }");
    for (int k = a->nin; k < a->n; k++)
        if (lower_size(lf->copy, k - a->nin) > 0)
            println(pr, "        for (int i = d%s; i < d + %d; i++) /* no load: at rest */\n"
                    "            %s[i] = 0.0;", from, hi, a->name[k]);
    println(pr, "    }");
}

static ExprCount
print_function(Printer *pr, const LowFunc *lf)
{
    Func fnb, *fn = &fnb;
    ExprCount copied = {0};
    int du_any = 0;
    if (lf->copy) {
        copied = print_function(pr, lf->copy);
        print_shifts(pr, lf, &du_any);
        fputc('\n', pr->f);
    }
    func_of(fn, lf);
    int nout = lf->nout;
    const LowSlot *out = lf->out;
    pr->ext = lf->shared;
    pr->derived = lf->per_step ? pr->L->derived : NULL;
    size_t size = expr_pool_size(pr->P);
    pr->temp = xmalloc(size * sizeof *pr->temp);
    pr->part = xmalloc(size * sizeof *pr->part);
    pr->slot = xmalloc(size * sizeof *pr->slot);
    for (size_t i = 0; i < size; i++)
        pr->temp[i] = pr->slot[i] = -1, pr->part[i] = 0;
    Sched S;
    schedule(pr, &S, nout, out);
    const char *nm = pr->s->name;
    char fname[128];
    const char *name = lf->sig->name;
    snprintf(fname, sizeof fname, "%s_%s", nm, name);
    fence(pr, lf->double_only);
    if (S.nparts == 1) {
        pr->nodes[0] += S.n;
        println(pr, "/* %s */", lf->sig->comment);
        print_head(pr, "static void", fname, fn->params);
        print_prologue(pr, lf);
        print_copies(pr, lf, fn, du_any);
        pr->cur = 0;
        print_part(pr, &S, fn);
        println(pr, "}\n");
    } else {
        char params[1024];
        snprintf(params, sizeof params, "%s, eomc_real *s", fn->params);
        char *in2 = xmalloc((size_t)S.nparts);
        for (pr->cur = 0; pr->cur < S.nparts; pr->cur++) {
            char part[160];
            int second = in2[pr->cur] = pr->unit2 && pr->nodes[1] < pr->nodes[0];
            pr->nodes[second] += S.pstart[pr->cur + 1] - S.pstart[pr->cur];
            snprintf(part, sizeof part, "%s_part%d", fname, pr->cur + 1);
            if (second)
                unit2_begin(pr, lf->double_only);
            println(pr, "/* %s: part %d of %d%s */", name, pr->cur + 1, S.nparts,
                    second ? ", in the second unit" : "");
            print_head(pr, second ? "EOMC_PART void" : "static EOMC_NOINLINE void", part,
                       params);
            print_voids(pr, fn->names);
            print_part(pr, &S, fn);
            println(pr, "}\n");
            if (second)
                unit2_end(pr);
        }
        for (int p = 0; p < S.nparts; p++) { /* called before they are defined */
            char part[160];
            snprintf(part, sizeof part, "%s_part%d", fname, p + 1);
            if (in2[p])
                print_decl(pr, "EOMC_PART void", part, params, ";");
        }
        free(in2);
        println(pr, "/* %s */", lf->sig->comment);
        print_head(pr, "static void", fname, fn->params);
        println(pr, "    eomc_real s[%d]; /* values shared between the parts */", S.nslots ? S.nslots : 1);
        print_prologue(pr, lf);
        print_copies(pr, lf, fn, du_any);
        for (int p = 0; p < S.nparts; p++)
            println(pr, "    %s_%s_part%d(%s, s);", nm, name, p + 1, fn->names);
        println(pr, "}\n");
    }
    pr->ext = NULL;
    pr->derived = NULL;
    /* exactly what was printed: values from shared[] and pd[] are counted
     * where made */
    ExprCount c = expr_count_list(pr->P, (size_t)S.n, S.node);
    c.adds += lf->ncopy * copied.adds; /* what runs: each copy's */
    c.muls += lf->ncopy * copied.muls;
    c.divs += lf->ncopy * copied.divs;
    c.calls += lf->ncopy * copied.calls;
    free(S.node);
    free(S.angle);
    free(S.angle_of);
    free(S.after);
    free(S.order);
    free(S.pstart);
    free(S.ostart);
    free(pr->temp);
    free(pr->part);
    free(pr->slot);
    return c;
}

/* ---- the model file ---- */

static void
print_names(Printer *pr, const char *array, int n, const char *(*name)(const Spec *, int))
{
    fprintf(pr->f, "static const char *const %s[%d] = {", array, n ? n : 1);
    for (int i = 0; i < n; i++)
        fprintf(pr->f, "%s\"%s\"", i ? ", " : "", name(pr->s, i));
    println(pr, n ? "};" : "NULL};");
}

static const char *coord_name(const Spec *s, int i) { return s->coord[i].name; }
static const char *param_name(const Spec *s, int i) { return s->param[i].name; }
static const char *input_name(const Spec *s, int i) { return s->input[i].name; }

/* The spec's file name without directories: output must not depend on
 * where eomc was run from. */
static const char *
base_name(const char *path)
{
    const char *base = strrchr(path, '/');
    return base ? base + 1 : path;
}

/* A sentence in the banner, " * " lines wrapped before WRAP. */
static void
print_wrapped(Printer *pr, const char *text)
{
    int col = 0;
    for (const char *p = text; *p;) {
        int len = (int)strcspn(p, " ");
        if (col && col + 1 + len + 1 >= WRAP) {
            fputc('\n', pr->f);
            col = 0;
        }
        col += fprintf(pr->f, "%s%.*s", col ? " " : " * ", len, p);
        p += len;
        p += strspn(p, " ");
    }
    fputs(".\n", pr->f);
}

static void
print_banner(Printer *pr, const Eom *e, const Constraints *c, const Invariant *inv,
             const EmitInfo *info)
{
    const Spec *s = pr->s;
    const char *base = base_name(s->path);
    println(pr, "/*");
    println(pr, " * %s: equations of motion generated by eomc %s from %s.",
            s->name, info->version, base);
    println(pr, " * Do not edit; regenerate with `eomc compile`.");
    println(pr, " *");
    println(pr, " * form:    %s, E = %s", e->form->name, e->form->formula);
    if (info->form_why) {
        char note[700];
        snprintf(note, sizeof note, "The form is %s", info->form_why);
        print_wrapped(pr, note);
    }
    println(pr, " * options: %s", info->options[0] ? info->options : "(none)");
    fprintf(pr->f, " * scene:   %s", s->scene.name ? s->scene.name : "(the spec's `scene:`)");
    for (int i = 0, k = 0; i < s->np; i++)
        if (s->param[i].fixed) {
            char num[40];
            format_const(num, sizeof num, s->param[i].value);
            fprintf(pr->f, "%s%s = %s", k++ ? ", " : "; fixed: ", s->param[i].name, num);
        }
    println(pr, "");
    fprintf(pr->f, " * effects:");
    int any = 0;
    for (int k = 0; k < s->neffect; k++)
        if (s->effect[k].enabled)
            fprintf(pr->f, " %s", s->effect[k].name), any = 1;
    println(pr, "%s", any ? "" : " (none)");
    fprintf(pr->f, " * off:    ");
    any = 0;
    for (int k = 0; k < s->neffect; k++)
        if (!s->effect[k].enabled)
            fprintf(pr->f, " %s", s->effect[k].name), any = 1;
    println(pr, "%s (no code is generated for these)", any ? "" : " (none)");
    println(pr, " *");
    println(pr, " * E(t, q, q', q'') = M(t, q) q'' + h(t, q, q') = 0");
    print_wrapped(pr, inv->note);
    if (pr->L->jacobian == LOWER_JACOBIAN_NONE) {
        char why[200];
        if (strstr(info->options, "--jacobian none"))
            snprintf(why, sizeof why, "--jacobian none leaves it out");
        else
            snprintf(why, sizeof why, "the scene's method, %s, needs none",
                     s->scene.method);
        char note[400];
        snprintf(note, sizeof note, "No Jacobian of E: %s.  The implicit methods and the "
                 "linearization refuse this model; --jacobian seeded adds it", why);
        print_wrapped(pr, note);
    }
    if (pr->L->code == LOWER_CODE_TABLES) {
        char note[400];
        snprintf(note, sizeof note, "The accelerations and the mass matrix are loops over "
                 "the model's tables (eomc_tree.h: %d turns), not straight-line code: %s",
                 pr->L->tables->nt, strstr(info->options, "--code tables")
                 ? "--code tables asks for them"
                 : "the straight-line solve would be too long to compile quickly");
        print_wrapped(pr, note);
    }
    if (c) {
        println(pr, " *");
        println(pr, " * constraints, by %s:", info->eliminate
                ? "elimination (C^T E = 0, f = 0)" : "multipliers (E + B^T lambda = 0, f = 0)");
        int w = 12; /* the name column, as wide as the longest name */
        for (int k = 0; k < c->nc; k++)
            if ((int)strlen(c->spec[k].name) > w)
                w = (int)strlen(c->spec[k].name);
        for (int k = 0; k < c->nc; k++)
            println(pr, " *   %-*s %s, determines %s", w, c->spec[k].name,
                    constraint_order_name(c->spec[k].order), s->coord[c->dependent[k]].name);
        println(pr, " *   %s in q''", c->affine ? "all affine" : "not all affine (Newton)");
        if (pr->L->loads)
            print_wrapped(pr, "The multipliers by unit loads: q'' without the constraints, "
                          "then M^-1 B^T one row of B at a time by the same recursion (minv), "
                          "and the nc x nc system B M^-1 B^T; M is never formed (kkt.c).");
    }
    println(pr, " *");
    println(pr, " * Compiled with -DEOMC_EXTENDED, the functions that the reference solution");
    println(pr, " * needs are compiled in extended precision instead (%s_model_ext).",
            s->name);
    println(pr, " */");
    println(pr, "#include <math.h>");
    println(pr, "#include <stddef.h>");
    println(pr, "");
    println(pr, "#include \"eomc_model.h\"");
    if (pr->L->code == LOWER_CODE_TABLES)
        println(pr, "#include \"eomc_tree.h\"");
    println(pr, "");
    println(pr, "#if defined(__GNUC__)");
    println(pr, "#define EOMC_NOINLINE __attribute__((noinline))");
    println(pr, "#define EOMC_WEAK __attribute__((weak))");
    println(pr, "#else");
    println(pr, "#define EOMC_NOINLINE");
    println(pr, "#define EOMC_WEAK");
    println(pr, "#endif");
    println(pr, "");
}

static void
print_tables(Printer *pr)
{
    const Spec *s = pr->s;
    print_names(pr, "q_names", s->nq, coord_name);
    print_names(pr, "p_names", s->np, param_name);
    print_names(pr, "u_names", s->nu, input_name);
    fprintf(pr->f, "static const double p_default[%d] = {", s->np ? s->np : 1);
    for (int i = 0; i < s->np; i++) {
        char num[40];
        format_const(num, sizeof num, s->param[i].value);
        fprintf(pr->f, "%s%s", i ? ", " : "", num);
    }
    println(pr, s->np ? "};" : "0.0};");
    fprintf(pr->f, "static const unsigned char p_fixed[%d] = {", s->np ? s->np : 1);
    for (int i = 0; i < s->np; i++)
        fprintf(pr->f, "%s%d", i ? ", " : "", s->param[i].fixed);
    println(pr, s->np ? "};" : "0};");
    if (s->scene.assemble && s->scene.hold) { /* what the scene's assembly keeps */
        fprintf(pr->f, "static const unsigned char a_hold[%d] = {", 2 * s->nq);
        for (int i = 0; i < 2 * s->nq; i++)
            fprintf(pr->f, "%s%d", i ? ", " : "", s->scene.hold[i]);
        println(pr, "};");
    }
    println(pr, "");
}

/* The jacobian member when it is seeded: shared values, then one column
 * per call of jacobian_dq and jacobian_dv. */
static void
print_seeded_driver(Printer *pr, const Lowered *L)
{
    const char *nm = pr->s->name;
    int n = L->n, nw = lower_size(L->jac_shared, 0);
    Func fj;
    LowFunc jac = {.sig = &lower_jacobian_sig, .double_only = 1, .per_step = 1};
    func_of(&fj, &jac);
    println(pr, "/* %s", lower_jacobian_sig.comment);
    println(pr, " * Column j of dE/dq (dE/dq') is the derivative along the unit seed");
    println(pr, " * dq = e_j (dq' = e_j): exact, in code about the size of E instead of");
    println(pr, " * %d times that. */", n);
    char fname[128];
    snprintf(fname, sizeof fname, "%s_jacobian", nm);
    print_head(pr, "static void", fname, fj.params);
    println(pr, "    eomc_real shared[%d]; /* values every column needs */", nw ? nw : 1);
    println(pr, "    eomc_real seed[%d];", n);
    println(pr, "    %s_jacobian_shared(t, q, v, a, p, u, shared, dEdu, dEdt);", nm);
    println(pr, "    for (int j = 0; j < %d; j++)", n);
    println(pr, "        seed[j] = 0.0;");
    println(pr, "    for (int j = 0; j < %d; j++) {", n);
    println(pr, "        seed[j] = 1.0;");
    println(pr, "        %s_jacobian_dq(t, q, v, a, p, u, shared, seed, dEdq + j);", nm);
    println(pr, "        %s_jacobian_dv(t, q, v, a, p, u, shared, seed, dEdv + j);", nm);
    println(pr, "        seed[j] = 0.0;");
    println(pr, "    }");
    println(pr, "}\n");
}

/* The mass_bias member from bias and mass_times: column j of M is E's
 * derivative along q'' = e_j. */
static void
print_mass_columns(Printer *pr, const Lowered *L)
{
    const char *nm = pr->s->name;
    int n = L->n;
    println(pr, "/* Mass matrix M = dE/dq'' (row-major, symmetric) and bias h = E(q'' = 0).");
    println(pr, " * Column j of M is the derivative of E along q'' = e_j: exact, in code");
    println(pr, " * about the size of E instead of %d x %d entries.  Off the hot path: the", n, n);
    println(pr, " * accelerations come from the recursion, which never forms M. */");
    char fname[128];
    snprintf(fname, sizeof fname, "%s_mass_bias", nm);
    print_head(pr, "static void", fname, "eomc_real t, const eomc_real *q, const eomc_real *v, "
               "const eomc_real *p, const eomc_real *u, eomc_real *M, eomc_real *h");
    println(pr, "    eomc_real seed[%d], col[%d];", n, n);
    println(pr, "    %s_bias(t, q, v, p, u, h);", nm);
    println(pr, "    for (int j = 0; j < %d; j++)", n);
    println(pr, "        seed[j] = 0.0;");
    println(pr, "    for (int j = 0; j < %d; j++) { /* the lower triangle, mirrored */", n);
    println(pr, "        seed[j] = 1.0;");
    println(pr, "        %s_mass_times(t, q, v, p, u, seed, col);", nm);
    println(pr, "        for (int i = j; i < %d; i++)", n);
    println(pr, "            M[i * %d + j] = M[j * %d + i] = col[i];", n, n);
    println(pr, "        seed[j] = 0.0;");
    println(pr, "    }");
    println(pr, "}\n");
}

/* The invariant member when it is E = T + V: energy's two results added,
 * the same sum in the same order as the expression T + V. */
static void
print_energy_sum(Printer *pr)
{
    const char *nm = pr->s->name;
    Func fi;
    LowFunc inv = {.sig = &lower_invariant_sig, .double_only = 1, .per_step = 1};
    func_of(&fi, &inv);
    println(pr, "/* %s", lower_invariant_sig.comment);
    println(pr, " * E = T + V, from energy. */");
    char fname[128];
    snprintf(fname, sizeof fname, "%s_invariant", nm);
    print_head(pr, "static void", fname, fi.params);
    println(pr, "    eomc_real TV[2];");
    println(pr, "    %s_energy(t, q, v, p, u, TV);", nm);
    println(pr, "    h[0] = TV[0] + TV[1];");
    println(pr, "}\n");
}

/* The end of an accel member: its pivots piv[] against mkk[] (the first
 * failing one in elimination order), and the smallest d_k / M_kk. */
static void
print_pivot_check(Printer *pr, int n)
{
    println(pr, "    return eomc_pivots(%d, piv, mkk, pivot); /* eomc_model.h */", n);
    println(pr, "}\n");
}

/* The accel member of eomc_model: the solve, then the pivot check. */
static void
print_accel(Printer *pr, const Lowered *L)
{
    int n = lower_size(L->accel_solve, 0);
    const char *nm = pr->s->name;
    println(pr, "/* q'' = -M^-1 h; 0, or k + 1 if the pivot of coordinate k fails (M");
    println(pr, " * singular or not positive definite).  *pivot (unless NULL): the");
    println(pr, " * smallest d_k / M_kk, compared without dividing in the loop. */");
    char fname[128];
    snprintf(fname, sizeof fname, "%s_accel", nm);
    print_head(pr, "static int", fname, "eomc_real t, const eomc_real *q, const eomc_real *v, "
               "const eomc_real *p, const eomc_real *u, eomc_real *a, eomc_real *pivot");
    println(pr, "    eomc_real piv[%d], mkk[%d];", n, n);
    println(pr, "    %s_accel_solve(t, q, v, p, u, a, piv, mkk);", nm);
    print_pivot_check(pr, n);
}

/* The tables' turns, then accel and mass_bias as loops over them
 * (runtime/eomc_tree.h): tau first, then the recursion. */
static void
print_tree_turns(Printer *pr, const Lowered *L)
{
    const FormTables *tb = L->tables;
    println(pr, "/* The joints: the one above (-1: the world), the coordinate, the axis (0-2:");
    println(pr, " * its own x, y, z; 3: a vector), whether a constant rotation comes first,");
    println(pr, " * whether it slides.  Their numbers are pd[%d ...] (derive). */", L->tree_base);
    fprintf(pr->f, "static const eomc_tree_turn %s_turns[%d] = {", pr->s->name, tb->nt);
    for (int k = 0; k < tb->nt; k++) {
        const int *t = tb->turn + FORM_TABLE_INTS * k;
        fprintf(pr->f, "%s{%d, %d, %d, %d, %d}", k == 0 ? "\n    " : k % 5 ? ", " : ",\n    ",
                t[0], t[1], t[2], t[3], t[4]);
    }
    println(pr, "\n};\n");
    int nn = FORM_TABLE_STRIDE * tb->nt + 6;
    println(pr, "/* Their numbers, %d per turn (eomc_tree.h) and a0, where constant; derive",
            FORM_TABLE_STRIDE);
    println(pr, " * computes the others (0 here). */");
    fprintf(pr->f, "static const double %s_numbers[%d] = {", pr->s->name, nn);
    for (int k = 0; k < nn; k++) {
        double v = 0;
        char num[40];
        expr_is_const(pr->P, tb->num[k], &v);
        format_const(num, sizeof num, v);
        fprintf(pr->f, "%s%s", k == 0 ? "\n    " : k % FORM_TABLE_STRIDE ? ", " : ",\n    ", num);
    }
    println(pr, "\n};\n");
}

/* energy of a tree: V from potential, T = q' . M q' / 2 (T is a
 * quadratic form in q' on a tree) with M q' by mass_times, or by the
 * Newton-Euler recursion over the tables at q' = 0, q'' = q'. */
static void
print_tree_energy(Printer *pr, const Lowered *L)
{
    const char *nm = pr->s->name;
    int n = L->n;
    char fname[128];
    println(pr, "/* Kinetic energy T and potential energy V: T = q'.M q'/2, with M q' by");
    println(pr, " * %s. */", L->tables ? "the recursion over the tables" : "mass_times");
    snprintf(fname, sizeof fname, "%s_energy", nm);
    print_head(pr, "static void", fname, "eomc_real t, const eomc_real *q, const eomc_real *v, "
               "const eomc_real *p, const eomc_real *u, eomc_real *TV");
    println(pr, "    eomc_real Mv[%d], T = 0.0;", n);
    println(pr, "    %s_potential(t, q, v, p, u, TV + 1);", nm);
    if (L->tables) {
        int nt = L->tables->nt;
        println(pr, "    eomc_real zero[%d], w[%d * EOMC_TREE_WORK];", n, nt);
        println(pr, "    for (int j = 0; j < %d; j++)", n);
        println(pr, "        zero[j] = 0.0;");
        println(pr, "    eomc_tree_rnea(%s_turns, %d, p + %d, NULL, q, zero, v, w, Mv);", nm, nt,
                pr->s->np + L->tree_base);
    } else {
        println(pr, "    %s_mass_times(t, q, v, p, u, v, Mv);", nm);
    }
    println(pr, "    for (int i = 0; i < %d; i++)", n);
    println(pr, "        T += v[i] * Mv[i];");
    println(pr, "    TV[0] = 0.5 * T;");
    println(pr, "}\n");
}

static void
print_tree_functions(Printer *pr, const Lowered *L)
{
    const char *nm = pr->s->name;
    int n = L->n, nt = L->tables->nt, np = pr->s->np;
    char fname[128], dat[64];
    snprintf(dat, sizeof dat, "p + %d", np + L->tree_base);
    if (L->loads) /* free_accel and minv: not the reference's */
        fence(pr, 1);
    println(pr, "/* q'' = -M^-1 h by the articulated-body recursion over the tables; 0, or");
    println(pr, " * k + 1 if the pivot of coordinate k fails (M singular or not positive");
    println(pr, " * definite).  *pivot (unless NULL): the smallest d_k / M_kk. */");
    snprintf(fname, sizeof fname, "%s_accel", nm);
    print_head(pr, "static int", fname, "eomc_real t, const eomc_real *q, const eomc_real *v, "
               "const eomc_real *p, const eomc_real *u, eomc_real *a, eomc_real *pivot");
    println(pr, "    eomc_real tau[%d], piv[%d], mkk[%d], w[%d * EOMC_TREE_WORK];", n, n, n, nt);
    println(pr, "    %s_tau(t, q, v, p, u, tau);", nm);
    println(pr, "    eomc_tree_aba(%s_turns, %d, %s, NULL, q, v, tau, w, a, piv, mkk);", nm, nt,
            dat);
    print_pivot_check(pr, n);
    if (L->loads) {
        println(pr, "/* y = M^-1 da by the articulated-body recursion over the tables at rest,");
        println(pr, " * with no force but the load da: the runtime's unit-load passes. */");
        snprintf(fname, sizeof fname, "%s_minv", nm);
        print_head(pr, "static void", fname, "eomc_real t, const eomc_real *q, "
                   "const eomc_real *v, const eomc_real *p, const eomc_real *u, "
                   "const eomc_real *da, eomc_real *y");
        println(pr, "    static const eomc_real still[6] = {0, 0, 0, 0, 0, 0};");
        println(pr, "    eomc_real zero[%d], piv[%d], mkk[%d], w[%d * EOMC_TREE_WORK];", n, n,
                n, nt);
        println(pr, "    (void)t, (void)v, (void)u;");
        println(pr, "    for (int j = 0; j < %d; j++)", n);
        println(pr, "        zero[j] = 0.0;");
        println(pr, "    eomc_tree_aba(%s_turns, %d, %s, still, q, zero, da, w, y, piv, mkk);",
                nm, nt, dat);
        println(pr, "}\n");
        fence(pr, 0); /* mass_bias: the reference's too */
    }
    println(pr, "/* Mass matrix M = dE/dq'' (row-major, symmetric) and bias h = E(q'' = 0),");
    println(pr, " * by the Newton-Euler recursion over the tables: h at q'' = 0, column j of");
    println(pr, " * M at q' = 0, q'' = e_j with no gravity and no forces (E is linear in");
    println(pr, " * q'').  Off the hot path: the accelerations never form M. */");
    snprintf(fname, sizeof fname, "%s_mass_bias", nm);
    print_head(pr, "static void", fname, "eomc_real t, const eomc_real *q, const eomc_real *v, "
               "const eomc_real *p, const eomc_real *u, eomc_real *M, eomc_real *h");
    println(pr, "    eomc_real tau[%d], x[%d], zero[%d], col[%d], w[%d * EOMC_TREE_WORK];", n, n,
            n, n, nt);
    println(pr, "    %s_tau(t, q, v, p, u, tau);", nm);
    println(pr, "    for (int j = 0; j < %d; j++)", n);
    println(pr, "        x[j] = zero[j] = 0.0;");
    println(pr, "    eomc_tree_rnea(%s_turns, %d, %s, %s + %d, q, v, zero, w, h);", nm, nt, dat,
            dat, FORM_TABLE_STRIDE * nt);
    println(pr, "    for (int i = 0; i < %d; i++)", n);
    println(pr, "        h[i] -= tau[i];");
    println(pr, "    for (int j = 0; j < %d; j++) { /* the lower triangle, mirrored */", n);
    println(pr, "        x[j] = 1.0;");
    println(pr, "        eomc_tree_rnea(%s_turns, %d, %s, NULL, q, zero, x, w, col);", nm, nt,
            dat);
    println(pr, "        for (int i = j; i < %d; i++)", n);
    println(pr, "            M[i * %d + j] = M[j * %d + i] = col[i];", n, n);
    println(pr, "        x[j] = 0.0;");
    println(pr, "    }");
    println(pr, "}\n");
}

/* A C string literal for any text: quotes, backslashes and control
 * characters escaped (file names may contain anything). */
static void
print_c_string(FILE *f, const char *text)
{
    fputc('"', f);
    for (const unsigned char *c = (const unsigned char *)text; *c; c++) {
        if (*c == '"' || *c == '\\')
            fprintf(f, "\\%c", *c);
        else if (*c < 0x20 || *c >= 0x7f || *c == '?')
            fprintf(f, "\\%03o", *c); /* octal: no trigraphs, no runaway hex */
        else
            fputc(*c, f);
    }
    fputc('"', f);
}

static void
print_model_struct(Printer *pr, const Spec *s, const Eom *e, const Constraints *c,
                   const Invariant *inv, const Lowered *L, const EmitInfo *info)
{
    const char *nm = s->name;
    println(pr, "const eomc_model %s_model = {", nm);
    fprintf(pr->f, "    .abi = EOMC_ABI_VERSION, .name = \"%s\", .spec = ", nm);
    print_c_string(pr->f, base_name(s->path));
    fprintf(pr->f, ", .form = \"%s\",\n    .options = ", e->form->name);
    print_c_string(pr->f, info->options);
    println(pr, ",");
    println(pr, "    .nq = %d, .np = %d, .nu = %d,", s->nq, s->np, s->nu);
    println(pr, "    .q_names = q_names, .p_names = p_names, .u_names = u_names,");
    fprintf(pr->f, "    .p_default = p_default, .scene = ");
    print_c_string(pr->f, s->scene.name ? s->scene.name : "");
    println(pr, ", .p_fixed = p_fixed,");
    if (L->derive)
        println(pr, "    .nd = %d, .derive = %s_derive,", L->nd, nm);
    else
        println(pr, "    .nd = 0, .derive = NULL, /* no value of the parameters alone to derive */");
    char a[40], b[40], rt[40], at[40], h[40];
    format_const(a, sizeof a, s->scene.t_end);
    format_const(b, sizeof b, s->scene.dt);
    format_const(rt, sizeof rt, s->scene.rtol);
    format_const(at, sizeof at, s->scene.atol);
    format_const(h, sizeof h, s->scene.h_fixed);
    println(pr, "    .t_end = %s, .dt = %s, .method = \"%s\", .rtol = %s, .atol = %s, .h_fixed = %s,",
            a, b, s->scene.method, rt, at, h);
    println(pr, "    .initial = %s_initial, .inputs = %s_inputs, .mass_bias = %s_mass_bias,\n"
            "    .energy = %s_energy,", nm, nm, nm, nm);
    if (L->jacobian == LOWER_JACOBIAN_NONE)
        println(pr, "    .jacobian = NULL, /* no Jacobian (the banner says why) */");
    else
        println(pr, "    .jacobian = %s_jacobian,", nm);
    if (c)
        println(pr, "    .accel = NULL, /* constrained: the runtime solves the KKT system */");
    else if (L->accel_solve || L->tau)
        println(pr, "    .accel = %s_accel,", nm);
    else
        println(pr, "    .accel = NULL, /* more than %d coordinates, M too dense to unroll: the "
                "runtime solves with GSL */",
                EOM_SOLVE_MAX);
    if (c)
        println(pr, "    .nc = %d, .c_names = c_names, .c_order = c_order, .c_dependent = "
                "c_dependent,\n"
                "    .c_affine = %d, .eliminate = %d,\n"
                "    .constraint = %s_constraint, .c_levels = %s_c_levels, .c_jacobian = "
                "%s_c_jacobian,\n"
                "    .c_levels_jacobian = %s_c_levels_jacobian,",
                c->nc, c->affine, info->eliminate, nm, nm, nm, nm);
    else
        println(pr, "    .nc = 0, .c_affine = 1, /* no constraints */");
    if (inv->h != EXPR_NONE)
        fprintf(pr->f, "    .invariant = %s_invariant, .invariant_name = \"%s\",\n", nm,
                inv->name);
    else
        fprintf(pr->f, "    .invariant = NULL, .invariant_name = NULL,\n");
    fprintf(pr->f, "    .invariant_note = ");
    print_c_string(pr->f, inv->note);
    println(pr, ",");
    if (s->ncheck)
        println(pr, "    .ncheck = %d, .check = %s_check, .check_what = check_what,\n"
                "    .check_params = check_params,", s->ncheck, nm);
    else
        println(pr, "    .ncheck = 0, /* nothing to check of the parameters */");
    if (L->outputs)
        println(pr, "    .nout = %d, .out_names = out_names, .outputs = %s_outputs,",
                s->scene.noutput, nm);
    else
        println(pr, "    .nout = 0, /* the scene asks for no outputs */");
    if (L->events)
        println(pr, "    .nevent = %d, .ev_names = ev_names, .ev_direction = ev_direction,\n"
                "    .ev_action = ev_action, .events = %s_events, .event_set = %s%s,",
                s->scene.nevent, nm, L->last_set ? nm : "NULL",
                L->last_set ? "_event_set" : "");
    else
        println(pr, "    .nevent = 0, /* the scene asks for no events */");
    if (s->scene.assemble)
        println(pr, "    .assemble = 1, .a_hold = %s, /* runs start assembled onto the "
                "constraints */", s->scene.hold ? "a_hold" : "NULL");
    else
        println(pr, "    .assemble = 0, /* the scene does not assemble */");
    if (e->mass_parent && !c)
        println(pr, "    .mass_parent = mass_parent, /* M factored by LTDL along this tree */");
    else
        println(pr, "    .mass_parent = NULL, /* M factored densely (or not at all: accel) */");
    if (L->loads)
        println(pr, "    .free_accel = %s_accel, .minv = %s_minv, /* the multipliers by unit "
                "loads */", nm, nm);
    else
        println(pr, "    .free_accel = NULL, .minv = NULL, /* no unit-load passes */");
    if (lower_find(L, "c_scale"))
        println(pr, "    .c_scale = %s_c_scale,", nm);
    else
        println(pr, "    .c_scale = NULL, /* no holonomic constraint to scale */");
    if (c && L->held)
        println(pr, "    .c_held = c_held,");
    else
        println(pr, "    .c_held = NULL, /* every constraint's row in the unit loads */");
    const LowFunc *cf = c ? lower_find(L, "constraint") : NULL;
    if (cf && cf->fill[1]) {
        int nnz = 0;
        for (int i = 0; i < cf->nout; i++)
            nnz += cf->out[i].arg == 1;
        println(pr, "    .c_nnz = %d, .c_nz = c_nz,", nnz);
    } else {
        println(pr, "    .c_nnz = 0, .c_nz = NULL, /* B dense */");
    }
    println(pr, "};\n");
    println(pr, "#ifdef EOMC_MAIN /* a simulator: eomc_main.h's main (with -DEOMC_MPI, MPI's) */");
    println(pr, "#include \"eomc_main.h\"");
    println(pr, "/* The reference solution's functions: this file compiled again with");
    println(pr, " * -DEOMC_EXTENDED and linked (eomc build does); without it the simulator");
    println(pr, " * runs but cannot measure its errors. */");
    println(pr, "extern const eomc_model_ext %s_model_ext EOMC_WEAK;", nm);
    println(pr, "EOMC_DEFINE_MAIN(%s_model, %s_model_ext)", nm, nm);
    println(pr, "#endif");
    println(pr, "#else");
    println(pr, "const eomc_model_ext %s_model_ext = {", nm);
    println(pr, "    .abi = EOMC_ABI_VERSION, .name = \"%s\", .derive = %s%s, .inputs = %s_inputs,\n"
            "    .mass_bias = %s_mass_bias, .accel = %s%s,", nm,
            L->derive ? nm : "NULL", L->derive ? "_derive" : "", nm, nm,
            (L->accel_solve || L->tau) && !c ? nm : "NULL",
            (L->accel_solve || L->tau) && !c ? "_accel" : "");
    if (c)
        println(pr, "    .constraint = %s_constraint, .c_jacobian = %s%s,", nm,
                c->affine ? "NULL" : nm, c->affine ? "" : "_c_jacobian");
    else
        println(pr, "    .constraint = NULL, .c_jacobian = NULL,");
    println(pr, "};");
    println(pr, "#endif /* EOMC_EXTENDED */");
}

static int
int_cmp(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* Names, orders and dependent coordinates of the constraints. */
static void
print_constraint_tables(Printer *pr, const Constraints *c)
{
    fprintf(pr->f, "static const char *const c_names[%d] = {", c->nc);
    for (int k = 0; k < c->nc; k++)
        fprintf(pr->f, "%s\"%s\"", k ? ", " : "", c->spec[k].name);
    println(pr, "};");
    fprintf(pr->f, "static const int c_order[%d] = {", c->nc);
    for (int k = 0; k < c->nc; k++)
        fprintf(pr->f, "%s%d", k ? ", " : "", c->spec[k].order);
    println(pr, "};");
    fprintf(pr->f, "static const int c_dependent[%d] = {", c->nc);
    for (int k = 0; k < c->nc; k++)
        fprintf(pr->f, "%s%d", k ? ", " : "", c->dependent[k]);
    println(pr, "};\n");
    const LowFunc *cf = lower_find(pr->L, "constraint");
    if (cf && cf->fill[1]) { /* B's zeros are a loop: its other entries */
        int nnz = 0, *nz = xmalloc(((size_t)cf->nout + 1) * sizeof *nz);
        for (int i = 0; i < cf->nout; i++)
            if (cf->out[i].arg == 1)
                nz[nnz++] = cf->out[i].index;
        qsort(nz, (size_t)nnz, sizeof *nz, int_cmp);
        println(pr, "/* The entries of B that can be nonzero (the rest are 0 at every state). */");
        fprintf(pr->f, "static const int c_nz[%d] = {", nnz ? nnz : 1);
        for (int i = 0; i < nnz; i++)
            fprintf(pr->f, "%s%d", i ? ", " : "", nz[i]);
        println(pr, "%s};\n", nnz ? "" : "0");
        free(nz);
    }
    if (!pr->L->held)
        return;
    println(pr, "/* The recursion's q'' meets these already (a ball's unit quaternion):");
    println(pr, " * their multipliers are 0, and the unit loads skip them. */");
    fprintf(pr->f, "static const unsigned char c_held[%d] = {", c->nc);
    for (int k = 0; k < c->nc; k++)
        fprintf(pr->f, "%s%d", k ? ", " : "", pr->L->held[k]);
    println(pr, "};\n");
}

/* The check member and its tables, after check_values. */
static void
print_checks(Printer *pr, const Lowered *L)
{
    const Spec *s = pr->s;
    const char *nm = s->name;
    int nk = lower_size(L->check_values, 0);
    for (int t = 0; t < 2; t++) {
        println(pr, "static const char *const %s[%d] = {", t ? "check_params" : "check_what",
                nk);
        for (int i = 0; i < nk; i++) {
            fprintf(pr->f, "    ");
            print_c_string(pr->f, t ? s->check[i].params : s->check[i].what);
            println(pr, ",");
        }
        println(pr, "};");
    }
    fprintf(pr->f, "static const unsigned char check_strict[%d] = {", nk);
    for (int i = 0; i < nk; i++)
        fprintf(pr->f, "%s%d", i ? ", " : "", s->check[i].strict);
    println(pr, "};\n");
    println(pr, "/* 0, or k + 1 for the first condition k the parameters p break. */");
    char fname[128];
    snprintf(fname, sizeof fname, "%s_check", nm);
    print_head(pr, "static int", fname, "const double *p");
    println(pr, "    eomc_real chk[%d];", nk);
    println(pr, "    %s_check_values(p, chk);", nm);
    println(pr, "    return eomc_checks(%d, chk, check_strict); /* eomc_model.h */", nk);
    println(pr, "}\n");
}

static void
add_count(ExprCount *c, ExprCount d)
{
    c->adds += d.adds;
    c->muls += d.muls;
    c->divs += d.divs;
    c->calls += d.calls;
}

/* The event_set member: the reset of event k. */
static void
print_event_set(Printer *pr, const Lowered *L)
{
    const Spec *s = pr->s;
    const char *nm = s->name;
    println(pr, "/* The reset of event k (a `set` event): q1 and v1 hold q and v, and get");
    println(pr, " * the values the event sets. */");
    char fname[128];
    snprintf(fname, sizeof fname, "%s_event_set", nm);
    print_head(pr, "static void", fname, "int k, double t, const double *q, const double *v, "
               "const double *p, const double *u, double *q1, double *v1");
    println(pr, "    switch (k) {");
    for (int k = 0; k < s->scene.nevent; k++)
        if (L->event_set[k])
            println(pr, "    case %d:\n        %s_set_%s(t, q, v, p, u, q1, v1);\n"
                    "        break;", k, nm, s->scene.event[k].name);
    println(pr, "    }");
    println(pr, "}\n");
}

/* The rows of --stats, in order. */
static const char *const stat_names[EMIT_NFUNCS] = {
    "initial", "inputs", "mass_bias", "energy", "jacobian", "accel", "minv", "constraint",
    "c_levels", "c_jacobian", "c_levels_jacobian", "invariant", "derive", "outputs",
    "events",
};

/* Everything after the banner and the includes. */
static void
print_body(Printer *pr_, const Eom *e, const Constraints *c, const Invariant *inv,
           const EmitInfo *info, EmitStats stats[EMIT_NFUNCS])
{
    Printer pr = *pr_;
    const Spec *s = pr.s;
    const Lowered *L = pr.L;
    FILE *f = pr.f;
    for (int k = 0; k < EMIT_NFUNCS; k++)
        stats[k] = (EmitStats){stat_names[k], {0, 0, 0, 0}};
    if (L->code == LOWER_CODE_TABLES)
        print_tree_turns(&pr, L);
    fence(&pr, 1);
    print_tables(&pr);
    if (c)
        print_constraint_tables(&pr, c);
    if (e->mass_parent && !c) {
        fprintf(f, "/* M's structural nonzeros as a tree: each coordinate's parent (-1: a\n"
                   " * root); M_ij = 0 unless one is above the other. */\n"
                   "static const int mass_parent[%d] = {", s->nq);
        for (int i = 0; i < s->nq; i++)
            fprintf(f, "%s%d", i == 0 ? "" : i % 20 ? ", " : ",\n    ", e->mass_parent[i]);
        println(&pr, "};\n");
    }
    if (L->outputs) {
        fprintf(f, "static const char *const out_names[%d] = {", s->scene.noutput);
        for (int k = 0; k < s->scene.noutput; k++)
            fprintf(f, "%s\"%s\"", k ? ", " : "", s->scene.output[k].name);
        println(&pr, "};\n");
    }
    if (L->events) {
        int ne = s->scene.nevent;
        fprintf(f, "static const char *const ev_names[%d] = {", ne);
        for (int k = 0; k < ne; k++)
            fprintf(f, "%s\"%s\"", k ? ", " : "", s->scene.event[k].name);
        fprintf(f, "};\nstatic const int ev_direction[%d] = {", ne);
        for (int k = 0; k < ne; k++)
            fprintf(f, "%s%d", k ? ", " : "", s->scene.event[k].direction);
        fprintf(f, "};\nstatic const int ev_action[%d] = {", ne);
        for (int k = 0; k < ne; k++)
            fprintf(f, "%s%d", k ? ", " : "", s->scene.event[k].action);
        println(&pr, "}; /* EOMC_EVENT_STOP, _RECORD, _SET */\n");
    }
    for (int k = 0; k < L->nfunc; k++) {
        const LowFunc *lf = L->func[k];
        ExprCount n = print_function(&pr, lf);
        for (int r = 0; r < EMIT_NFUNCS; r++)
            if (!strcmp(stats[r].function, lf->stat))
                add_count(&stats[r].count, n);
        if (lf == L->potential)
            print_tree_energy(&pr, L);
        if (lf == L->jac_dv)
            print_seeded_driver(&pr, L);
        else if (lf == L->mass_times)
            print_mass_columns(&pr, L);
        else if (lf == L->tau)
            print_tree_functions(&pr, L);
        else if (L->invariant_energy &&
                 (lf == L->potential || !strcmp(lf->sig->name, "energy"))) {
            print_energy_sum(&pr);
            for (int r = 0; r < EMIT_NFUNCS; r++)
                stats[r].count.adds += !strcmp(stats[r].function, "invariant");
        }
        else if (lf == L->accel_solve)
            print_accel(&pr, L);
        else if (lf == L->check_values)
            print_checks(&pr, L);
        if (lf == L->last_set)
            print_event_set(&pr, L);
    }
    fence(&pr, 1);
    print_model_struct(&pr, s, e, c, inv, L, info);
    if (pr.unit2) {
        unit2_swap(&pr);
        fence(&pr, 0);
        unit2_swap(&pr);
    }
    *pr_ = pr;
}

/* Read a memory stream's text back (NULL and 0 if it failed). */
static char *
closed_text(FILE *f, char **buf, size_t *len)
{
    if (fclose(f) != 0) {
        free(*buf);
        *buf = NULL, *len = 0;
    }
    return *buf;
}

int
emit_model(FILE *f, const Spec *s, const Eom *e, const Constraints *c, const Invariant *inv,
           const Lowered *L, ExprPool *P, const EmitInfo *info, EmitStats stats[EMIT_NFUNCS])
{
    Printer pr = {.f = f, .P = P, .s = s, .L = L};
    print_banner(&pr, e, c, inv, info);
    /* The body is printed aside with the second unit's parts in their own
     * stream; a model with few parts is printed again as one unit. */
    char *body = NULL, *second = NULL;
    size_t blen = 0, slen = 0;
    pr.f = open_memstream(&body, &blen);
    pr.unit2 = open_memstream(&second, &slen);
    if (pr.f && pr.unit2) {
        print_body(&pr, e, c, inv, info, stats);
        closed_text(pr.f, &body, &blen);
        closed_text(pr.unit2, &second, &slen);
        int split = pr.nunit2 >= SPLIT_MIN_PARTS && body && second;
        if (split) {
            fputs("/* eomc build compiles this file as two translation units at once: with\n"
                  " * -DEOMC_UNIT=1 all but the parts marked for the second unit, with\n"
                  " * -DEOMC_UNIT=2 those alone.  Without EOMC_UNIT it is one unit. */\n"
                  "#if !defined(EOMC_UNIT)\n"
                  "#define EOMC_PART static EOMC_NOINLINE\n"
                  "#elif defined(__GNUC__)\n"
                  "#define EOMC_PART __attribute__((visibility(\"hidden\"), noinline))\n"
                  "#else\n"
                  "#define EOMC_PART\n"
                  "#endif\n\n"
                  "#if !defined(EOMC_UNIT) || EOMC_UNIT == 1\n", f);
            fwrite(body, 1, blen, f);
            fputs("#endif /* EOMC_UNIT 1 */\n\n"
                  "#if !defined(EOMC_UNIT) || EOMC_UNIT == 2\n", f);
            fwrite(second, 1, slen, f);
            fputs("#endif /* EOMC_UNIT 2 */\n", f);
        }
        free(body);
        free(second);
        if (split)
            return 2;
    } else { /* no memory streams: one unit, printed directly */
        if (pr.f)
            fclose(pr.f);
        if (pr.unit2)
            fclose(pr.unit2);
        free(body);
        free(second);
    }
    pr.f = f;
    pr.unit2 = NULL;
    pr.nunit2 = pr.fenced = pr.fenced2 = 0;
    pr.nodes[0] = pr.nodes[1] = 0;
    print_body(&pr, e, c, inv, info, stats);
    return 1;
}

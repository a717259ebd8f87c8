/*
 * emit_func: the printer of one function, for emit.c (emit_func.h).
 *
 * A function's schedule (lower_schedule: which operator nodes, in which
 * order, and where each output is stored) is the lower layer's, so that
 * lower_eval evaluates the very list printed here.  This file names it:
 * one `const double` temporary per node, the leaves' locals, the shared[]
 * and pd[] values other functions computed, the guarded stores to
 * optional outputs, the zero fills and the loop over copies.
 *
 * Very large functions (the Jacobian of a 50-link chain has ~70 000
 * nodes) are cut into parts of at most LOWER_PART_SIZE temporaries, each
 * its own non-inlined C function: the C compiler's register allocator is
 * superlinear in function size, and parts keep `cc -O2` time linear.
 * A part ends after an output, or inside one output's nodes when they
 * alone are too many (a recursive solve writes q'' only at its end).
 * Values needed by a later part travel through a stack array s[].
 * Cutting is the printer's: a C function's size is a C compiler's
 * concern, and the list is the same whole or cut.
 */
#include "emit_func.h"
#include "lower/lower_schedule.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* the names of the sources (emit_func.h's SRC_*) */
static const char *const src_name[NSRC] = {"q", "v", "a", "p", "u", "t", "dq", "dv", "da",
                                           "lam"};

static int is_leaf(const ExprNode *nd) { return expr_op_arity[nd->op] == 0; }

static int is_ext(const Printer *pr, ExprId e) { return pr->ext && pr->ext[e] >= 0; }
static int is_derived(const Printer *pr, ExprId e)
{
    return pr->derived && pr->derived[e] >= 0 && !is_ext(pr, e);
}
/* Not computed here: a leaf, a shared value or a derived one. */
static int is_input(const Printer *pr, ExprId e)
{
    return !lower_computed(pr->P, pr->lf, e);
}

static void
leaf_name(Printer *pr, const ExprNode *nd, char *buf, size_t len)
{
    static const char prefix[] = {'q', 'v', 'a', 'j'};
    switch (nd->op) {
    case EXPR_SEED: /* dq by coordinate, dv and da by velocity slot */
        snprintf(buf, len, "%s_%s", src_name[SRC_DQ + nd->b],
                 pr->md->coord[nd->b ? pr->md->vcoord[nd->a] : (int)nd->a]);
        break;
    case EXPR_VAR:
        snprintf(buf, len, "%c_%s", prefix[nd->b], pr->md->coord[nd->a]);
        break;
    case EXPR_PARAM:
        snprintf(buf, len, "p_%s", pr->md->param[nd->a].name);
        break;
    case EXPR_INPUT:
        snprintf(buf, len, "u_%s", pr->md->input[nd->a]);
        break;
    case EXPR_MULT:
        snprintf(buf, len, "lam_%s", pr->md->constraint[nd->a].name);
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
        emit_const(num, sizeof num, nd->value);
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

/* expr.h's EXPR_POWI_MUL_MAX: what the evaluators compute */
static void
print_powi(const char *x, int n, char *rhs, size_t len)
{
    if (n > EXPR_POWI_MUL_MAX) {
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

/* After node id's statement: its copy for later parts (ind: the
 * statements' indentation). */
static void
print_share(Printer *pr, ExprId id, const char *ind)
{
    if (pr->slot[id] >= 0)
        emit_line(pr, "%ss[%d] = w%d;", ind, pr->slot[id], pr->temp[id]);
}

/* Node id's statement, indented by ind: its temporary declared here, or
 * (set) assigned, declared before the block it is in. */
static void
print_node(Printer *pr, ExprId id, const char *ind, int set)
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
    case OPK_SELECT: { /* mode k, after the nu inputs (eomc_model.h) */
        int slot = pr->md->mode_slot[expr_select_mode(pr->P, id)];
        if (slot < 0) /* (lower_switches marked every SELECT of every function) */
            diag_unreachable();
        snprintf(rhs, sizeof rhs, "(u[%d] != 0.0 ? %s : %s)", pr->md->nu + slot, x, y);
        break;
    }
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
    emit_line(pr, "%s%sw%d = %s;", ind, set ? "" : "const eomc_real ", pr->temp[id], rhs);
    print_share(pr, id, ind);
}

/* ---- parts ---- */

/* A lazy block (lower_schedule.h): nodes start .. mid-1 run where any
 * of its tests holds, switch k in mode b (2 k + b, at Sched.cond[cond
 * ...]), mid .. end-1 (a test alone) where it fails; end .. tail-1 are
 * SELECTs on its switch that follow it (a test alone), printed as an
 * assignment in each branch. */
typedef struct Block {
    int start, mid, end, tail, cond, ncond;
} Block;

/* The schedule (lower_schedule) as the printer walks it: the nodes
 * numbered in order (their temporaries), each store after so many of
 * them, the lazy blocks, and the parts it is cut in. */
typedef struct Sched {
    const LowSched *low;
    int copies;    /* the copies' loop comes first */
    int nfill, fill[LOW_MAX_ARGS]; /* the output arguments zero-filled first */
    ExprId *node;  /* the NODE steps in order */
    int n;
    int *order;    /* per store: the output it stores */
    int *after;    /* per store: nodes printed before it */
    int *pstart;   /* per part: first node; pstart[nparts] = n */
    int *ostart;   /* per part: first store; ostart[nparts] = nout */
    int nparts, nslots;
    Block *block;
    int nblock;
    int *cond; /* the blocks' tests */
    int *blk;      /* per node: its block, or -1 */
    unsigned char *outward; /* per node in a block: read outside it (declared before) */
} Sched;

/* A value crossing into another part gets a slot in s[]. */
static void
share(Printer *pr, Sched *S, ExprId e, int part)
{
    if (!is_input(pr, e) && pr->part[e] != part &&
        pr->slot[e] < 0)
        pr->slot[e] = S->nslots++;
}

/* The nodes of a block that a node of its part outside it reads: their
 * temporaries are declared before the block (a later part reads s[]). */
static void
find_outward(Printer *pr, Sched *S)
{
    for (int k = 0; k < S->n; k++) {
        const ExprNode *nd = expr_node(pr->P, S->node[k]);
        ExprId ops[2] = {nd->a, nd->b};
        for (int j = 0; j < expr_op_arity[nd->op]; j++) {
            if (is_input(pr, ops[j]))
                continue;
            int o = pr->temp[ops[j]];
            if (S->blk[o] >= 0 && S->blk[o] != S->blk[k] &&
                pr->part[ops[j]] == pr->part[S->node[k]])
                S->outward[o] = 1;
        }
    }
}

/* Number the list's nodes, and cut it in parts of at most
 * LOWER_PART_SIZE nodes. */
static void
schedule(Printer *pr, Sched *S, const LowSched *low, int nout, const LowSlot *out)
{
    S->low = low;
    S->node = xmalloc(((size_t)low->nnode + 1) * sizeof *S->node);
    S->order = xmalloc(((size_t)nout + 1) * sizeof *S->order);
    S->after = xmalloc(((size_t)nout + 1) * sizeof *S->after);
    S->block = xmalloc(((size_t)low->nnode + 1) * sizeof *S->block);
    S->cond = xmalloc(((size_t)low->nstep + 1) * sizeof *S->cond);
    S->blk = xmalloc(((size_t)low->nnode + 1) * sizeof *S->blk);
    S->outward = xmalloc((size_t)low->nnode + 1);
    memset(S->outward, 0, (size_t)low->nnode + 1);
    S->n = S->nparts = S->nslots = S->copies = S->nfill = S->nblock = 0;
    int nst = 0, in = 0, ncond = 0, after = -1; /* after: the block just closed */
    for (int k = 0; k < low->nstep; k++) {
        const LowStep *st = &low->step[k];
        switch (st->kind) {
        case LOW_STEP_COPIES:
            S->copies = 1;
            break;
        case LOW_STEP_FILL:
            S->fill[S->nfill++] = st->i;
            break;
        case LOW_STEP_NODE: {
            const ExprNode *nd = expr_node(pr->P, st->id);
            Block *b = after >= 0 ? &S->block[after] : NULL;
            if (b && b->tail == S->n && b->ncond == 1 && nd->op == EXPR_SELECT &&
                expr_select_mode(pr->P, st->id) == S->cond[b->cond] / 2)
                b->tail++; /* a SELECT on its switch right after it */
            else
                after = -1;
            pr->temp[st->id] = S->n;
            S->blk[S->n] = in ? S->nblock : after;
            S->node[S->n++] = st->id;
            break;
        }
        case LOW_STEP_STORE:
            S->order[nst] = st->i;
            S->after[nst++] = S->n;
            after = -1;
            break;
        case LOW_STEP_IF:
            after = -1;
            S->block[S->nblock] = (Block){S->n, -1, -1, -1, ncond, 0};
            in = 1;
            S->cond[ncond++] = 2 * st->i + st->branch;
            S->block[S->nblock].ncond++;
            break;
        case LOW_STEP_OR:
            S->cond[ncond++] = 2 * st->i + st->branch;
            S->block[S->nblock].ncond++;
            break;
        case LOW_STEP_ELSE:
            S->block[S->nblock].mid = S->n;
            break;
        case LOW_STEP_END: {
            Block *b = &S->block[S->nblock];
            b->end = b->tail = S->n;
            if (b->mid < 0)
                b->mid = b->end;
            after = S->nblock++;
            in = 0;
            break;
        }
        }
    }
    if (low->whole) {
        S->pstart = xmalloc(2 * sizeof *S->pstart);
        S->ostart = xmalloc(2 * sizeof *S->ostart);
        S->nparts = 1;
        S->pstart[0] = S->ostart[0] = 0;
        S->pstart[1] = S->n;
        S->ostart[1] = nout;
        find_outward(pr, S);
        return;
    }
    /* Cut after a store once a part has LOWER_PART_SIZE nodes, and inside
     * one output's nodes where they alone would pass it (a recursive
     * solve's outputs come only at its end). */
    size_t cap = (size_t)nout + 2 + (size_t)S->n / LOWER_PART_SIZE + 1;
    S->pstart = xmalloc(cap * sizeof *S->pstart);
    S->ostart = xmalloc(cap * sizeof *S->ostart);
    S->pstart[0] = S->ostart[0] = 0;
    for (int j = 0; j < nout; j++) {
        while (S->after[j] - S->pstart[S->nparts] > LOWER_PART_SIZE) {
            int cut = S->pstart[S->nparts] + LOWER_PART_SIZE;
            if (cut > low->angles && cut < low->angles_end) /* not inside the one call */
                cut = low->angles_end;
            if (S->blk[cut] >= 0 && S->block[S->blk[cut]].start < cut) /* nor a block */
                cut = S->block[S->blk[cut]].tail;
            S->nparts++;
            S->pstart[S->nparts] = cut;
            S->ostart[S->nparts] = j;
        }
        if (S->after[j] - S->pstart[S->nparts] >= LOWER_PART_SIZE || j == nout - 1) {
            S->nparts++;
            S->pstart[S->nparts] = S->after[j];
            S->ostart[S->nparts] = j + 1;
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
        for (int j = S->ostart[p]; j < S->ostart[p + 1]; j++)
            share(pr, S, out[S->order[j]].e, p);
    }
    find_outward(pr, S);
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
        if (nd->op == EXPR_SELECT || S->blk[k] >= 0) /* a mode is read from u */
            pr->used |= 1u << SRC_U;
        if (ar >= 1)
            mark_leaf(pr, nd->a, &ls);
        if (ar >= 2)
            mark_leaf(pr, nd->b, &ls);
    }
    for (int j = S->ostart[pr->cur]; j < S->ostart[pr->cur + 1] && j < nout; j++)
        mark_leaf(pr, out[S->order[j]].e, &ls);
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
            /* a rate of coordinate (or speed) c is velocity slot vslot[c] */
            int at = nd->op == EXPR_VAR && nd->b > 0 ? pr->md->vslot[nd->a] : (int)nd->a;
            emit_line(pr, "    const eomc_real %s = %s[%d];", buf, src_name[arr], at);
        }
    for (size_t j = 0; j < ls.n; j++)
        if (is_derived(pr, ls.list[j])) {
            ExprId id = ls.list[j];
            pr->used |= 1u << SRC_P;
            emit_line(pr, "    const eomc_real pd%d = p[%d];", pr->derived[id],
                    pr->md->np + pr->derived[id]);
        }
    free(ls.mark);
    free(ls.list);
}

/* The sines and cosines of schedule_angles: the angles into an array,
 * one call, each value its temporary.  Returns the node after them. */
static int
print_angles(Printer *pr, const Sched *S)
{
    const LowSched *low = S->low;
    int na = low->nangle;
    emit_line(pr, "    eomc_real ang[%d], ang_sin[%d], ang_cos[%d]; /* %d angles at once */", na,
            na, na, na);
    for (int j = 0; j < na; j++) {
        char buf[200];
        emit_line(pr, "    ang[%d] = %s;", j, operand(pr, low->angle[j], buf, sizeof buf));
    }
    emit_line(pr, "    eomc_sincos(%d, ang, ang_sin, ang_cos);", na);
    for (int k = low->angles; k < low->angles_end; k++) {
        ExprId id = S->node[k];
        int a = low->angle_of[k - low->angles];
        emit_line(pr, "    const eomc_real w%d = ang_%s[%d];", pr->temp[id],
                a % 2 ? "cos" : "sin", a / 2);
        print_share(pr, id, "    ");
    }
    return low->angles_end;
}

/* Switch k's name for a comment ("switch N" where it has none, or one a
 * comment cannot hold). */
static void
switch_name(Printer *pr, int k, char *buf, size_t len)
{
    const char *sw = expr_switch_name(pr->P, k);
    if (sw && !strstr(sw, "*/") && strlen(sw) < len)
        snprintf(buf, len, "%s", sw);
    else
        snprintf(buf, len, "switch %d", pr->md->mode_slot[k]);
}

/* The names of a block's switches, for its comment: the first few, and
 * how many more (a body's pose under each of its pairs' switches). */
enum { NAMES_SHOWN = 2 };

/* The SELECTs that follow a block on its switch, as assignments of
 * the operand a mode takes (on: its branch a). */
static void
print_tail(Printer *pr, const Sched *S, const Block *b, int on)
{
    for (int k = b->end; k < b->tail; k++) {
        const ExprNode *nd = expr_node(pr->P, S->node[k]);
        char buf[200];
        emit_line(pr, "        w%d = %s;", pr->temp[S->node[k]],
                  operand(pr, on ? nd->a : nd->b, buf, sizeof buf));
        print_share(pr, S->node[k], "        ");
    }
}

/* A lazy block: the temporaries read after it declared first (set to
 * 0, never read in a mode that skips them: a defined value all the
 * same), then `if (tests) { ... } else { ... }`, commented with the
 * switches' names.  Returns the node after it. */
static int
print_block(Printer *pr, const Sched *S, const Block *b)
{
    char decl[WRAP + 40] = "", line[WRAP + 60], name[160];
    for (int k = b->start; k < b->tail; k++) {
        if (!S->outward[k] && k < b->end) /* (the SELECTs after it: set in its branches) */
            continue;
        char w[40];
        snprintf(w, sizeof w, "w%d = 0.0", pr->temp[S->node[k]]);
        if (decl[0] && strlen(decl) + strlen(w) + 2 > WRAP) {
            emit_line(pr, "%s;", decl);
            decl[0] = '\0';
        }
        size_t len = strlen(decl);
        snprintf(decl + len, sizeof decl - len, "%s%s", len ? ", " : "    eomc_real ", w);
    }
    if (decl[0])
        emit_line(pr, "%s;", decl);
    /* the comment: which mode of which switches */
    char comment[2 * sizeof name + 80] = "";
    for (int c = 0; c < b->ncond && c < NAMES_SHOWN; c++) {
        int t = S->cond[b->cond + c];
        switch_name(pr, t / 2, name, sizeof name);
        size_t len = strlen(comment);
        snprintf(comment + len, sizeof comment - len, "%s%s %s", c ? ", " : "", name,
                 t % 2 ? "on" : "off");
    }
    if (b->ncond > NAMES_SHOWN) {
        size_t len = strlen(comment);
        snprintf(comment + len, sizeof comment - len, " or %d more", b->ncond - NAMES_SHOWN);
    }
    emit_line(pr, "    /* where %s%s */", b->ncond > 1 ? "any of " : "", comment);
    /* the tests, wrapped */
    snprintf(line, sizeof line, "    if (");
    for (int c = 0; c < b->ncond; c++) {
        int t = S->cond[b->cond + c];
        char test[64];
        snprintf(test, sizeof test, "u[%d] %s 0.0%s", pr->md->nu + pr->md->mode_slot[t / 2],
                 t % 2 ? "!=" : "==", c + 1 < b->ncond ? " ||" : ") {");
        if (c && strlen(line) + strlen(test) + 1 > WRAP) {
            emit_line(pr, "%s", line);
            snprintf(line, sizeof line, "        ");
        } else if (c) {
            strcat(line, " ");
        }
        strcat(line, test);
    }
    emit_line(pr, "%s", line);
    for (int k = b->start; k < b->mid; k++)
        print_node(pr, S->node[k], "        ", S->outward[k]);
    print_tail(pr, S, b, b->ncond == 1 && S->cond[b->cond] % 2);
    if (b->mid < b->end || b->tail > b->end) {
        emit_line(pr, "    } else {");
        for (int k = b->mid; k < b->end; k++)
            print_node(pr, S->node[k], "        ", S->outward[k]);
        print_tail(pr, S, b, !(S->cond[b->cond] % 2));
    }
    emit_line(pr, "    }");
    return b->tail;
}

/* Node k's statement, the angles' call where they start, or the lazy
 * block that starts at k; the next k. */
static int
print_step(Printer *pr, const Sched *S, int k)
{
    if (k == S->low->angles && S->low->angles < S->low->angles_end)
        return print_angles(pr, S);
    if (S->blk[k] >= 0)
        return print_block(pr, S, &S->block[S->blk[k]]);
    print_node(pr, S->node[k], "    ", 0);
    return k + 1;
}

/* The statements of part p: leaves, temporaries, assignments. */
static void
print_part(Printer *pr, const Sched *S, const Func *fn)
{
    const LowFunc *lf = fn->low;
    const LowArgs *a = &fn->args;
    pr->used = 0;
    for (int j = 0; pr->cur == 0 && j < S->nfill; j++) {
        int k = S->fill[j];
        const char *arr = a->name[a->nin + k];
        if (lf->zeroed >> k & 1) {
            emit_line(pr, "    /* %s's other entries are 0: the caller's (eomc_model.h, c_nz) */",
                    arr);
            continue;
        }
        if (a->optional[a->nin + k])
            emit_line(pr, "    if (%s)", arr);
        emit_line(pr, "    %sfor (int i = 0; i < %d; i++) /* the nonzeros follow */\n"
                "    %s    %s[i] = 0.0;", a->optional[a->nin + k] ? "    " : "", lf->fill[k],
                a->optional[a->nin + k] ? "    " : "", arr);
    }
    print_leaves(pr, S, lf->nout, lf->out);
    if (S->nparts == 1) { /* silence -Wunused-parameter */
        for (int k = 0; k < NSRC; k++)
            if (fn->has[k] && !(pr->used >> k & 1))
                emit_line(pr, "    (void)%s;", src_name[k]);
        for (int k = 0; k < a->nin; k++) /* read through ext, not as leaves */
            if (!strcmp(a->name[k], "shared"))
                emit_line(pr, "    (void)%s;", a->name[k]);
        for (int k = a->nin; k < a->n; k++)
            if (lower_size(lf, k - a->nin) == 0)
                emit_line(pr, "    (void)%s;", a->name[k]);
    }
    int k = S->pstart[pr->cur];
    for (int j = S->ostart[pr->cur]; j < S->ostart[pr->cur + 1]; j++) {
        int i = S->order[j];
        while (k < S->after[j])
            k = print_step(pr, S, k);
        const LowSlot *o = &lf->out[i];
        const char *arr = a->name[a->nin + o->arg];
        char buf[200];
        operand(pr, o->e, buf, sizeof buf);
        if (a->optional[a->nin + o->arg])
            emit_line(pr, "    if (%s) %s[%d] = %s;", arr, arr, o->index, buf);
        else
            emit_line(pr, "    %s[%d] = %s;", arr, o->index, buf);
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
void
emit_func_of(Func *fn, const LowFunc *lf)
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
    emit_line(pr, "    for (int k = 0; k < %d; k++) /* the tables' constants */",
            FORM_TABLE_STRIDE * L->tables->nt + 6);
    emit_line(pr, "        pd[%d + k] = %s_numbers[k];", L->tree_base, pr->md->name);
}

/* The shifts of each copy (repeat.h), before the function that loops. */
static void
print_shifts(Printer *pr, const LowFunc *lf, int *du_any)
{
    *du_any = 0;
    for (int c = 0; c < lf->ncopy; c++)
        *du_any |= lf->du[c] != 0;
    static const char *const what[] = {"dq", "du", "dv"};
    for (int u = 0; u < 3; u++) {
        const int *d = u == 0 ? lf->dq : u == 1 ? lf->du : lf->dv;
        if ((u == 1 && !*du_any) || !d)
            continue;
        fprintf(pr->f, "static const int %s_%s_%s[%d] = {", pr->md->name, lf->sig->name,
                what[u], lf->ncopy);
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
    const char *nm = pr->md->name, *name = lf->sig->name;
    char call[2048] = "";
    size_t k = 0;
    for (int i = 0; i < fn->args.n && k < sizeof call; i++) {
        const char *arg = fn->args.name[i], *sep = i ? ", " : "";
        /* with speeds (dv), all but q and the seed dq shift as the speeds do */
        int by_q = !lf->dv || !strcmp(arg, "q") || !strcmp(arg, "dq");
        if (!strcmp(arg, "t") || !strcmp(arg, "p") || (!strcmp(arg, "u") && !du_any))
            k += (size_t)snprintf(call + k, sizeof call - k, "%s%s", sep, arg);
        else
            k += (size_t)snprintf(call + k, sizeof call - k, "%s%s + %s_%s_%s[c]", sep, arg, nm,
                                  name, !strcmp(arg, "u") ? "du" : by_q ? "dq" : "dv");
    }
    if (!lf->zero_skip) {
        emit_line(pr, "    for (int c = 0; c < %d; c++) /* copies of one subtree (repeat.c) */",
                lf->ncopy);
        emit_line(pr, "        %s_%s(%s);", nm, lf->copy->sig->name, call);
        return;
    }
    /* a copy without a load stays at rest: zeros, not its recursion (the
     * outputs after the loop are stored after these) */
    const LowArgs *a = &fn->args;
    int hi = lf->span0 + lf->span;
    char from[32] = ""; /* " + span0" where it is not 0 */
    if (lf->span0)
        snprintf(from, sizeof from, " + %d", lf->span0);
    emit_line(pr, "    for (int c = 0; c < %d; c++) { /* copies of one subtree (repeat.c) */",
            lf->ncopy);
    emit_line(pr, "        const int d = %s_%s_%s[c];", nm, name, lf->dv ? "dv" : "dq");
    emit_line(pr, "        int loaded = 0;");
    for (int i = 0; i < a->nin; i++)
        if (!strcmp(a->name[i], "dq") || !strcmp(a->name[i], "dv") || !strcmp(a->name[i], "da"))
            emit_line(pr, "        for (int i = d%s; i < d + %d && !loaded; i++)\n"
                    "            loaded = %s[i] != 0.0;", from, hi, a->name[i]);
    emit_line(pr, "        if (loaded) {");
    emit_line(pr, "            %s_%s(%s);", nm, lf->copy->sig->name, call);
    emit_line(pr, "            continue;");
    emit_line(pr, "        }");
    for (int k = a->nin; k < a->n; k++)
        if (lower_size(lf->copy, k - a->nin) > 0)
            emit_line(pr, "        for (int i = d%s; i < d + %d; i++) /* no load: at rest */\n"
                    "            %s[i] = 0.0;", from, hi, a->name[k]);
    emit_line(pr, "    }");
}

/* A function's head: a member of eomc_model's, or a static helper's. */
static void
print_head(Printer *pr, const LowFunc *lf, const char *fname, const char *params)
{
    if (lf->sig->member)
        emit_entry_head(pr, "void", fname, params);
    else
        emit_head(pr, "static void", fname, params);
}

ExprCount
emit_function(Printer *pr, const LowFunc *lf)
{
    Func fnb, *fn = &fnb;
    ExprCount copied = {0};
    int du_any = 0;
    if (lf->copy) {
        copied = emit_function(pr, lf->copy);
        print_shifts(pr, lf, &du_any);
        fputc('\n', pr->f);
    }
    emit_func_of(fn, lf);
    int nout = lf->nout;
    const LowSlot *out = lf->out;
    pr->lf = lf;
    pr->ext = lf->shared;
    pr->derived = lf->derived;
    size_t size = expr_pool_size(pr->P);
    pr->temp = xmalloc(size * sizeof *pr->temp);
    pr->part = xmalloc(size * sizeof *pr->part);
    pr->slot = xmalloc(size * sizeof *pr->slot);
    for (size_t i = 0; i < size; i++)
        pr->temp[i] = pr->slot[i] = -1, pr->part[i] = 0;
    LowSched *low = lower_schedule(pr->P, lf, !pr->L->eager_branches);
    Sched S;
    schedule(pr, &S, low, nout, out);
    const char *nm = pr->md->name;
    char fname[128];
    const char *name = lf->sig->name;
    snprintf(fname, sizeof fname, "%s_%s", nm, name);
    emit_fence(pr, lf->double_only);
    if (S.nparts == 1) {
        pr->nodes[0] += S.n;
        emit_line(pr, "/* %s */", lf->sig->comment);
        print_head(pr, lf, fname, fn->params);
        print_prologue(pr, lf);
        if (S.copies)
            print_copies(pr, lf, fn, du_any);
        pr->cur = 0;
        print_part(pr, &S, fn);
        emit_line(pr, "}\n");
    } else {
        char params[1024];
        snprintf(params, sizeof params, "%s, eomc_real *s", fn->params);
        char *in2 = xmalloc((size_t)S.nparts);
        for (pr->cur = 0; pr->cur < S.nparts; pr->cur++) {
            char part[160];
            int second = in2[pr->cur] =
                emit_part_half(pr, S.pstart[pr->cur + 1] - S.pstart[pr->cur], 1);
            snprintf(part, sizeof part, "%s_part%d", fname, pr->cur + 1);
            if (second)
                emit_unit2_begin(pr, lf->double_only);
            emit_line(pr, "/* %s: part %d of %d%s */", name, pr->cur + 1, S.nparts,
                    !second ? "" : pr->in3 ? ", in the fourth unit" : ", in the second unit");
            emit_head(pr, second ? "EOMC_PART void" : "static EOMC_NOINLINE void", part,
                       params);
            print_voids(pr, fn->names);
            print_part(pr, &S, fn);
            emit_line(pr, "}\n");
            if (second)
                emit_unit2_end(pr);
        }
        for (int p = 0; p < S.nparts; p++) { /* called before they are defined */
            char part[160];
            snprintf(part, sizeof part, "%s_part%d", fname, p + 1);
            if (in2[p])
                emit_decl(pr, "EOMC_PART void", part, params, ";");
        }
        free(in2);
        emit_line(pr, "/* %s */", lf->sig->comment);
        print_head(pr, lf, fname, fn->params);
        emit_line(pr, "    eomc_real s[%d]; /* values shared between the parts */", S.nslots ? S.nslots : 1);
        print_prologue(pr, lf);
        if (S.copies)
            print_copies(pr, lf, fn, du_any);
        for (int p = 0; p < S.nparts; p++)
            emit_line(pr, "    %s_%s_part%d(%s, s);", nm, name, p + 1, fn->names);
        emit_line(pr, "}\n");
    }
    pr->lf = NULL;
    pr->ext = NULL;
    pr->derived = NULL;
    /* exactly what was printed: values from shared[] and pd[] are counted
     * where made */
    ExprCount c = expr_count_list(pr->P, (size_t)S.n, S.node);
    c.adds += lf->ncopy * copied.adds; /* what runs: each copy's */
    c.muls += lf->ncopy * copied.muls;
    c.divs += lf->ncopy * copied.divs;
    c.calls += lf->ncopy * copied.calls;
    lower_sched_free(low);
    free(S.node);
    free(S.after);
    free(S.order);
    free(S.pstart);
    free(S.ostart);
    free(S.block);
    free(S.cond);
    free(S.blk);
    free(S.outward);
    free(pr->temp);
    free(pr->part);
    free(pr->slot);
    return c;
}


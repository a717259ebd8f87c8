/*
 * lower_pack: packs of the written-out series (lowered.h's LowSerLine.pack).
 *
 * The N-body's series repeats one recurrence per pair of bodies: the
 * Pleiades' 21 pairs each square their dx and dy, add the squares, raise
 * the sum to -3/2 and multiply dx and dy by it, at every order.  Lines of
 * one shape whose cells are consecutive run as one line on a vector of
 * four (or two) doubles, lane by lane the same arithmetic, so the same
 * bits.  Two things make them consecutive:
 *
 *  - the slots' columns (pack_columns).  A group is the program's results
 *    of one call with the same constants and the same calls making its
 *    operands (r^2 = dx^2 + dy^2 apart from the forces' sums, which chain
 *    their slots in another order); each, costliest first, orders
 *    its members and asks that their results, and each operand's slots,
 *    lie side by side in that order.  Slots side by side form a chain,
 *    each slot at a position; two chains that must meet are joined at a
 *    shift where none of their positions collide, and a request that
 *    cannot be met is dropped (as an SLP vectorizer's packs are built).
 *    The members' order comes from what is already chained (their
 *    results', else an operand's), else from an operand used more than
 *    once: the products x r^-3 and y r^-3 read each r^-3 twice, so all
 *    the x ones come first, then the y ones, and r^-3 is read in one run
 *    each time.
 *  - the lines' order within an order (pack_lines): a list schedule that
 *    takes every ready line of the first ready line's shape at once, by
 *    their cells.
 *
 * gcc's own vectorizer is not used for this: under -march=native it
 * fuses a*b - c beside d*e + f into fmaddsub whatever -ffp-contract says
 * (compiler/driver/build.c's opt_flag), which would change the bits.
 */
#include "lower_pack.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- the columns ---- */

/* The most operands a packed call has (powc's base and exponent,
 * select's two). */
enum { PACK_OPS = 2 };

typedef struct Node {
    int slot, prog;  /* its result, and its place in the program */
    int nop;
    int op[PACK_OPS];
    char key[96];    /* the call, its constants and its operands' calls */
} Node;

/* Chains of slots: chain[s] (-1: none) and pos[s], each chain's slots in
 * the order of their positions. */
typedef struct Chains {
    int *chain, *pos;   /* [nslot] */
    int **mem, *len;    /* [nslot] chains' slots, by position */
    int nchain;
    const unsigned char *free_slot; /* [nslot] not the state's */
} Chains;

/* The slot at position p of chain c, or -1. */
static int
slot_at(const Chains *ch, int c, int p)
{
    int lo = 0, hi = ch->len[c] - 1;
    while (lo <= hi) {
        int mid = (lo + hi) / 2, q = ch->pos[ch->mem[c][mid]];
        if (q == p)
            return ch->mem[c][mid];
        if (q < p)
            lo = mid + 1;
        else
            hi = mid - 1;
    }
    return -1;
}

static int
by_pos_cmp(const Chains *ch, int a, int b)
{
    return ch->pos[a] - ch->pos[b];
}

/* Put slot s (in no chain) at position p of chain c, which is free. */
static void
put_at(Chains *ch, int c, int s, int p)
{
    ch->chain[s] = c, ch->pos[s] = p;
    ch->mem[c] = xrealloc(ch->mem[c], ((size_t)ch->len[c] + 1) * sizeof *ch->mem[c]);
    int i = ch->len[c]++;
    while (i > 0 && by_pos_cmp(ch, ch->mem[c][i - 1], s) > 0) {
        ch->mem[c][i] = ch->mem[c][i - 1];
        i--;
    }
    ch->mem[c][i] = s;
}

/* Chain d joined to chain c, its positions moved by shift, unless two
 * slots would collide; 1 when joined. */
static int
join(Chains *ch, int c, int d, int shift)
{
    for (int i = 0; i < ch->len[d]; i++)
        if (slot_at(ch, c, ch->pos[ch->mem[d][i]] + shift) >= 0)
            return 0;
    int n = ch->len[c] + ch->len[d], i = 0, j = 0, k = 0;
    int *m = xmalloc((size_t)n * sizeof *m);
    for (int t = 0; t < ch->len[d]; t++)
        ch->pos[ch->mem[d][t]] += shift, ch->chain[ch->mem[d][t]] = c;
    while (k < n) /* both already by position: merged */
        if (j == ch->len[d] || (i < ch->len[c] && by_pos_cmp(ch, ch->mem[c][i], ch->mem[d][j]) < 0))
            m[k++] = ch->mem[c][i++];
        else
            m[k++] = ch->mem[d][j++];
    free(ch->mem[c]);
    free(ch->mem[d]);
    ch->mem[c] = m, ch->len[c] = n;
    ch->mem[d] = NULL, ch->len[d] = 0;
    return 1;
}

/* Ask that slots s[0 .. n-1] (distinct) be consecutive in this order:
 * done where it can be, else nothing more is done. */
static void
demand(Chains *ch, const int *s, int n)
{
    if (n < 2)
        return;
    for (int m = 0; m < n; m++)
        if (s[m] < 0 || !ch->free_slot[s[m]])
            return;
    int c = -1, base = 0;
    for (int m = 0; m < n && c < 0; m++)
        if (ch->chain[s[m]] >= 0)
            c = ch->chain[s[m]], base = ch->pos[s[m]] - m;
    if (c < 0) {
        c = ch->nchain++;
        for (int m = 0; m < n; m++)
            put_at(ch, c, s[m], m);
        return;
    }
    for (int m = 0; m < n; m++) { /* the other chains joined at their shift */
        int d = ch->chain[s[m]];
        if (d >= 0 && d != c && !join(ch, c, d, base + m - ch->pos[s[m]]))
            return;
    }
    for (int m = 0; m < n; m++) { /* then every slot where it must be */
        int at = slot_at(ch, c, base + m);
        if (ch->chain[s[m]] == c ? ch->pos[s[m]] != base + m : at >= 0)
            return;
    }
    for (int m = 0; m < n; m++)
        if (ch->chain[s[m]] < 0)
            put_at(ch, c, s[m], base + m);
}

/* The nodes of ty's program that could pack: one per result of the calls
 * whose lines have a shape of their own (sums of products), keyed by the
 * call, its constants and what makes its operands.  *n: how many. */
static Node *
nodes_of(const LowTaylor *ty, const unsigned char *free_slot, int *n)
{
    static const char *const packed[] = {"add", "sub",  "neg", "scale", "mul",  "mul2",
                                         "mul4", "sqr", "div", "inv",   "sqrt", "exp",
                                         "powc", "sincos", "sinhcosh"};
    Node *nd = xmalloc(((size_t)ty->nstep * 4 + 1) * sizeof *nd);
    /* each slot's producer, for the key: "state" or a call's name */
    const char **made = xmalloc(((size_t)ty->nslot + 1) * sizeof *made);
    for (int s = 0; s < ty->nslot; s++)
        made[s] = free_slot[s] ? "none" : "state";
    for (int i = 0; i < ty->nstep; i++)
        for (int r = 0; r < ty->step[i].nres; r++)
            if (free_slot[ty->step[i].slot[r]])
                made[ty->step[i].slot[r]] = ty->step[i].call;
    int k = 0;
    double exponent = 0;
    for (int i = 0; i < ty->nstep; i++) {
        const LowTayStep *st = &ty->step[i];
        int ok = 0;
        for (size_t j = 0; j < sizeof packed / sizeof packed[0] && !ok; j++)
            ok = !strcmp(st->call, packed[j]);
        if (!ok)
            continue;
        int multi = !strcmp(st->call, "mul2") || !strcmp(st->call, "mul4");
        if (!strcmp(st->call, "powc")) { /* its exponent: a constant's value */
            exponent = 0;
            for (int j = 0; j < ty->nstep; j++)
                if (!strcmp(ty->step[j].call, "const") && ty->step[j].slot[0] == st->slot[2])
                    exponent = ty->step[j].value;
        }
        for (int r = 0; r < st->nres; r++) {
            Node *d = &nd[k];
            *d = (Node){.slot = st->slot[r], .prog = 4 * i + r};
            if (!free_slot[d->slot])
                continue;
            if (multi) { /* results first, then each one's two factors */
                d->nop = 2;
                d->op[0] = st->slot[st->nres + 2 * r], d->op[1] = st->slot[st->nres + 2 * r + 1];
            } else {
                d->nop = st->nslot - st->nres;
                if (d->nop > PACK_OPS)
                    continue;
                for (int j = 0; j < d->nop; j++)
                    d->op[j] = st->slot[st->nres + j];
            }
            /* (mul2's and mul4's results are alike; sincos' are not) and
             * what makes each operand: r^2 = dx^2 + dy^2 apart from the
             * sums of the forces, which chain their slots another way */
            int at = snprintf(d->key, sizeof d->key, "%s %d %a", multi ? "mul" : st->call,
                              multi ? 0 : r, !strcmp(st->call, "powc") ? exponent : 0.0);
            for (int j = 0; j < d->nop && at < (int)sizeof d->key; j++)
                at += snprintf(d->key + at, sizeof d->key - (size_t)at, " %s",
                               d->op[j] < 0 ? "-" : made[d->op[j]]);
            k++;
        }
    }
    free(made);
    *n = k;
    return nd;
}

static int
node_cmp(const void *a, const void *b)
{
    const Node *x = a, *y = b;
    int c = strcmp(x->key, y->key);
    return c ? c : x->prog - y->prog;
}

/* A group's weight: members times the products a line of it sums per
 * order (about). */
static double
group_weight(const Node *d, int n)
{
    const char *w2[] = {"mul", "div", "inv", "exp", "powc", "sincos", "sinhcosh"};
    double w = 1;
    for (size_t i = 0; i < sizeof w2 / sizeof w2[0]; i++)
        if (!strncmp(d->key, w2[i], strlen(w2[i])) && d->key[strlen(w2[i])] == ' ')
            w = 4;
    if (!strncmp(d->key, "sqr ", 4) || !strncmp(d->key, "sqrt ", 5))
        w = 2;
    return w * n;
}

typedef struct Sorted {
    int member;    /* index into the group */
    long k1, k2, k3;
} Sorted;

static int
sorted_cmp(const void *a, const void *b)
{
    const Sorted *x = a, *y = b;
    if (x->k1 != y->k1)
        return x->k1 < y->k1 ? -1 : 1;
    if (x->k2 != y->k2)
        return x->k2 < y->k2 ? -1 : 1;
    if (x->k3 != y->k3)
        return x->k3 < y->k3 ? -1 : 1;
    return x->member - y->member;
}

/* The occurrence count of each slot in list v[0 .. n-1] so far: use[i]
 * = how many times v[i] came before it (cnt: [nslot] scratch of 0s, left
 * so). */
static void
occurrences(const int *v, int n, int *use, int *cnt)
{
    for (int i = 0; i < n; i++)
        use[i] = v[i] >= 0 ? cnt[v[i]]++ : 0;
    for (int i = 0; i < n; i++)
        if (v[i] >= 0)
            cnt[v[i]] = 0;
}

/* Order group g's members (nodes d[0 .. n-1], already by program) and ask
 * for their chains. */
static void
pack_group(Chains *ch, Node *d, int n, int *cnt)
{
    Sorted *so = xmalloc((size_t)n * sizeof *so);
    int *v = xmalloc((size_t)n * sizeof *v), *use = xmalloc((size_t)n * sizeof *use);
    /* those whose results are chained already, by their chain, then the
     * others by the rule below; each part asked for separately */
    int na = 0;
    for (int i = 0; i < n; i++)
        if (ch->chain[d[i].slot] >= 0)
            so[na++] = (Sorted){i, ch->chain[d[i].slot], ch->pos[d[i].slot], 0};
    qsort(so, (size_t)na, sizeof *so, sorted_cmp);
    int nb = 0;
    Sorted *sb = so + na;
    for (int i = 0; i < n; i++)
        if (ch->chain[d[i].slot] < 0)
            sb[nb++] = (Sorted){i, 0, 0, d[i].prog};
    /* the rest: by an operand already chained (its k-th use, chain,
     * position), else by an operand read more than once (its k-th use,
     * then the program's order), else by the program's order */
    int nop = d[0].nop, done = 0;
    for (int t = 0; t < nop && !done && nb; t++) {
        int all = 1;
        for (int i = 0; i < nb && all; i++) {
            int o = d[sb[i].member].op[t];
            all = o >= 0 && ch->chain[o] >= 0;
        }
        if (!all)
            continue;
        for (int i = 0; i < nb; i++)
            v[i] = d[sb[i].member].op[t];
        occurrences(v, nb, use, cnt);
        for (int i = 0; i < nb; i++)
            sb[i].k1 = use[i], sb[i].k2 = ch->chain[v[i]], sb[i].k3 = ch->pos[v[i]];
        done = 1;
    }
    for (int t = 0, best = 0; t < nop && !done && nb; t++) {
        int most = 0;
        for (int i = 0; i < nb; i++)
            v[i] = d[sb[i].member].op[t];
        occurrences(v, nb, use, cnt);
        for (int i = 0; i < nb; i++)
            if (v[i] >= 0 && ch->free_slot[v[i]] && use[i] > most)
                most = use[i];
        if (most > best) {
            best = most;
            for (int i = 0; i < nb; i++)
                sb[i].k1 = use[i], sb[i].k2 = 0, sb[i].k3 = d[sb[i].member].prog;
        }
    }
    qsort(sb, (size_t)nb, sizeof *sb, sorted_cmp);
    for (int part = 0; part < 2; part++) {
        Sorted *s = part ? sb : so;
        int m = part ? nb : na;
        for (int i = 0; i < m; i++)
            v[i] = d[s[i].member].slot;
        demand(ch, v, m);
        for (int t = 0; t < nop; t++) { /* each operand in runs without a repeat */
            for (int i = 0, r = 0; i <= m; i++) {
                int o = i < m ? d[s[i].member].op[t] : -1, seen = 0;
                for (int j = r; j < i && !seen; j++)
                    seen = v[j] == o;
                if (i == m || seen || o < 0) {
                    demand(ch, v + r, i - r);
                    r = o < 0 ? i + 1 : i;
                }
                if (i < m)
                    v[i] = o;
            }
        }
    }
    free(so), free(v), free(use);
}

typedef struct ChainAt {
    int chain, first;
} ChainAt;

static int
chain_at_cmp(const void *a, const void *b)
{
    const ChainAt *x = a, *y = b;
    return x->first != y->first ? x->first - y->first : x->chain - y->chain;
}

void
pack_columns(const LowTaylor *ty, int *col)
{
    int ns = ty->nslot;
    unsigned char *free_slot = xmalloc((size_t)ns + 1);
    memset(free_slot, 1, (size_t)ns + 1);
    for (int i = 0; i < ty->nstate; i++)
        free_slot[ty->state_slot[i]] = 0;
    Chains ch = {.free_slot = free_slot};
    ch.chain = xmalloc(((size_t)ns + 1) * sizeof *ch.chain);
    ch.pos = xmalloc(((size_t)ns + 1) * sizeof *ch.pos);
    ch.mem = xmalloc(((size_t)ns + 1) * sizeof *ch.mem);
    ch.len = xmalloc(((size_t)ns + 1) * sizeof *ch.len);
    int *cnt = xmalloc(((size_t)ns + 1) * sizeof *cnt);
    for (int s = 0; s < ns; s++)
        ch.chain[s] = -1, ch.mem[s] = NULL, ch.len[s] = 0, cnt[s] = 0;
    int n;
    Node *nd = nodes_of(ty, free_slot, &n);
    qsort(nd, (size_t)n, sizeof *nd, node_cmp);
    /* the groups, costliest first */
    int ng = 0, *gfirst = xmalloc(((size_t)n + 1) * sizeof *gfirst);
    for (int i = 0; i < n; i++)
        if (i == 0 || strcmp(nd[i].key, nd[i - 1].key))
            gfirst[ng++] = i;
    gfirst[ng] = n;
    Sorted *gs = xmalloc(((size_t)ng + 1) * sizeof *gs);
    for (int g = 0; g < ng; g++) {
        int m = gfirst[g + 1] - gfirst[g];
        gs[g] = (Sorted){g, -(long)(group_weight(&nd[gfirst[g]], m) * 4), nd[gfirst[g]].prog, 0};
    }
    qsort(gs, (size_t)ng, sizeof *gs, sorted_cmp);
    for (int i = 0; i < ng; i++) {
        int g = gs[i].member, m = gfirst[g + 1] - gfirst[g];
        if (m >= 2)
            pack_group(&ch, nd + gfirst[g], m, cnt);
    }
    /* the layout: the chains in the program's order of their first slot,
     * each by its positions, then every other slot in its own order */
    int *first = xmalloc(((size_t)ns + 1) * sizeof *first);
    for (int s = 0; s < ns; s++)
        first[s] = s;
    for (int i = 0; i < n; i++)
        first[nd[i].slot] = nd[i].prog;
    ChainAt *ca = xmalloc(((size_t)ch.nchain + 1) * sizeof *ca);
    int nc = 0;
    for (int c = 0; c < ch.nchain; c++) {
        if (!ch.len[c])
            continue;
        ca[nc] = (ChainAt){c, first[ch.mem[c][0]]};
        for (int j = 1; j < ch.len[c]; j++)
            if (first[ch.mem[c][j]] < ca[nc].first)
                ca[nc].first = first[ch.mem[c][j]];
        nc++;
    }
    qsort(ca, (size_t)nc, sizeof *ca, chain_at_cmp);
    int next = 0;
    for (int i = 0; i < nc; i++)
        for (int j = 0; j < ch.len[ca[i].chain]; j++)
            col[ch.mem[ca[i].chain][j]] = next++;
    for (int s = 0; s < ns; s++)
        if (ch.chain[s] < 0)
            col[s] = next++;
    for (int c = 0; c < ch.nchain; c++)
        free(ch.mem[c]);
    free(ca), free(first), free(gs), free(gfirst), free(nd), free(cnt);
    free(ch.chain), free(ch.pos), free(ch.mem), free(ch.len), free(free_slot);
}

/* ---- the lines ---- */

/* Where cell c lives, as a number in which consecutive cells of one array
 * are consecutive: W's own, X's past W's (-1: none, a 0). */
static long
address(const PackCells *pc, int c)
{
    if (c < 0)
        return -1;
    int at = pc->place[c % pc->nslot];
    return at < 0 ? c : (long)pc->ncell + 2 + (long)(c / pc->nslot) * pc->N + at;
}

/* The operand cells of a line, in an order the same for lines of one
 * shape; how many (at most 2 nterm + 3). */
static int
operands(const LowSerLine *l, const LowSerTerm *term, int *op)
{
    int n = 0;
    if (l->kind == LOW_SER_SUM) {
        for (int t = 0; t < l->nterm; t++)
            op[n++] = term[l->first + t].x, op[n++] = term[l->first + t].y;
        if (l->last >= 0)
            op[n++] = term[l->last].x, op[n++] = term[l->last].y;
        op[n++] = l->over_cell;
    } else if (l->kind == LOW_SER_CALL || l->kind == LOW_SER_SELECT) {
        op[n++] = l->x, op[n++] = l->y;
    }
    return n;
}

/* Whether a and b are sums of the same shape: the same terms' signs,
 * numbers and factors where the cells may differ. */
static int
same_shape(const LowSerLine *a, const LowSerLine *b, const LowSerTerm *term)
{
    if (a->kind != LOW_SER_SUM || b->kind != LOW_SER_SUM || a->nterm != b->nterm ||
        a->times != b->times || (a->last < 0) != (b->last < 0) || a->over != b->over ||
        (a->over_cell < 0) != (b->over_cell < 0) || a->negate != b->negate ||
        a->after != b->after)
        return 0;
    for (int t = 0; t <= a->nterm; t++) {
        if (t == a->nterm && a->last < 0)
            break;
        const LowSerTerm *x = &term[t < a->nterm ? a->first + t : a->last];
        const LowSerTerm *y = &term[t < a->nterm ? b->first + t : b->last];
        if (x->coef != y->coef || (x->x < 0) != (y->x < 0) || (x->y < 0) != (y->y < 0))
            return 0;
    }
    return 1;
}

/* Lines line[i .. i+w-1] as one pack: sums of one shape writing w
 * consecutive cells, each operand either consecutive cells or one cell
 * for every lane, at least one of them consecutive cells, and none of
 * them a cell the pack writes. */
static int
packable(const LowSerLine *line, int i, int w, const LowSerTerm *term, const PackCells *pc,
         int *op0, int *op)
{
    const LowSerLine *l0 = &line[i];
    int n = operands(l0, term, op0), cells = 0;
    long d0 = address(pc, l0->dst);
    for (int o = 0; o < n; o++)
        cells += op0[o] >= 0;
    if (l0->kind != LOW_SER_SUM || !cells)
        return 0;
    int *spread = op + n; /* operand o the same in every lane */
    int loads = 0;        /* operands that are w cells (else the line is a number) */
    for (int l = 1; l < w; l++) {
        const LowSerLine *li = &line[i + l];
        if (!same_shape(l0, li, term) || address(pc, li->dst) != d0 + l)
            return 0;
        operands(li, term, op);
        for (int o = 0; o < n; o++) {
            long a0 = address(pc, op0[o]), a = address(pc, op[o]);
            if (l == 1) {
                spread[o] = a == a0;
                loads += a0 >= 0 && !spread[o];
            }
            if (a0 >= 0 && a0 + w > d0 && a0 < d0 + w)
                return 0;
            if (a != (spread[o] ? a0 : a0 + l) && !(a0 < 0 && a < 0))
                return 0;
        }
    }
    return loads > 0;
}

/* Line order: the first ready line's, then the cells it writes. */
typedef struct Ready {
    const LowSerLine *line;
    int at;
    long dst;
} Ready;

static int
ready_cmp(const void *a, const void *b)
{
    const Ready *x = a, *y = b;
    return x->dst != y->dst ? (x->dst < y->dst ? -1 : 1) : x->at - y->at;
}

static int
int_cmp(const void *a, const void *b)
{
    return *(const int *)a - *(const int *)b;
}

void
pack_lines(LowSerLine *line, int n, const LowSerTerm *term, const PackCells *pc, int *writer)
{
    if (n < 2)
        return;
    int maxop = 3;
    for (int i = 0; i < n; i++)
        if (2 * line[i].nterm + 3 > maxop)
            maxop = 2 * line[i].nterm + 3;
    int *op = xmalloc((size_t)maxop * 2 * sizeof *op);
    int *op1 = xmalloc((size_t)maxop * 2 * sizeof *op1);
    for (int i = 0; i < n; i++)
        writer[line[i].dst] = i;
    /* each line's readers among these (CSR), and what it waits for */
    int *ndep = xmalloc((size_t)n * sizeof *ndep);
    int *nsucc = xmalloc(((size_t)n + 1) * sizeof *nsucc);
    memset(ndep, 0, (size_t)n * sizeof *ndep);
    memset(nsucc, 0, ((size_t)n + 1) * sizeof *nsucc);
    for (int i = 0; i < n; i++) {
        int m = operands(&line[i], term, op);
        for (int o = 0; o < m; o++)
            if (op[o] >= 0 && writer[op[o]] >= 0 && writer[op[o]] != i)
                nsucc[writer[op[o]] + 1]++, ndep[i]++;
    }
    for (int i = 0; i < n; i++)
        nsucc[i + 1] += nsucc[i];
    int *succ = xmalloc(((size_t)nsucc[n] + 1) * sizeof *succ);
    int *fill = xmalloc((size_t)n * sizeof *fill);
    memcpy(fill, nsucc, (size_t)n * sizeof *fill);
    for (int i = 0; i < n; i++) {
        int m = operands(&line[i], term, op);
        for (int o = 0; o < m; o++)
            if (op[o] >= 0 && writer[op[o]] >= 0 && writer[op[o]] != i)
                succ[fill[writer[op[o]]]++] = i;
    }
    int *ready = xmalloc((size_t)n * sizeof *ready), nready = 0;
    int *order = xmalloc((size_t)n * sizeof *order), nout = 0;
    Ready *take = xmalloc((size_t)n * sizeof *take);
    for (int i = 0; i < n; i++)
        if (!ndep[i])
            ready[nready++] = i;
    while (nready) {
        int first = ready[0], nt = 0, keep = 0;
        for (int r = 0; r < nready; r++) {
            int i = ready[r];
            if (i == first || same_shape(&line[first], &line[i], term))
                take[nt++] = (Ready){&line[i], i, address(pc, line[i].dst)};
            else
                ready[keep++] = i;
        }
        nready = keep;
        qsort(take, (size_t)nt, sizeof *take, ready_cmp);
        int before = nready;
        for (int t = 0; t < nt; t++) {
            int i = take[t].at;
            order[nout++] = i;
            for (int e = nsucc[i]; e < nsucc[i + 1]; e++)
                if (--ndep[succ[e]] == 0)
                    ready[nready++] = succ[e];
        }
        if (nready > before) /* the ready ones by the program's order */
            qsort(ready, (size_t)nready, sizeof *ready, int_cmp);
    }
    LowSerLine *was = xmalloc((size_t)n * sizeof *was);
    memcpy(was, line, (size_t)n * sizeof *was);
    for (int i = 0; i < n; i++)
        line[i] = was[order[i]];
    for (int i = 0; i < n; i++)
        writer[line[i].dst] = -1;
    /* the packs: four lines where they can be, else two */
    for (int i = 0; i < n;) {
        int w = 4;
        while (w >= 2 && !(i + w <= n && packable(line, i, w, term, pc, op, op1)))
            w /= 2;
        if (w >= 2) {
            line[i].pack = w;
            i += w;
        } else {
            i++;
        }
    }
    free(was), free(take), free(order), free(ready), free(fill), free(succ);
    free(nsucc), free(ndep), free(op1), free(op);
}

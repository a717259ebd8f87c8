/*
 * lower_series: taylor_run's program written out (lowered.h's LowSeries).
 *
 * The Taylor program (lower_taylor.c) is a list of calls of
 * runtime/include/eomc_taylor.h, each a loop over the order: taylor_run
 * runs it once per order, and each call sums its convolution term by term
 * in a loop whose bounds and indices the C compiler does not know.  Here
 * every call at every order k < LOW_SERIES_ORDERS becomes its sum with
 * the indices fixed: eomc_tay_mul at k = 3 is c3 = a0 b3 + a1 b2 + a2 b1
 * + a3 b0, over cells of a local array (each order's coefficients side by
 * side), as heyoka compiles its series.  Kepler's program went
 * from 8 800 instructions a step to 3 300 (callgrind, 100 periods at
 * 1e-15, cc -O2), the rows the same to the bit.
 *
 * The arithmetic is each recurrence's own, term for term in its order
 * (a sum's terms by the later of their two orders, the earlier first:
 * term_at), so the bits are those of the loop: a sum starts from its
 * first term rather than from 0 (the same value but for the sign of a
 * zero), and a difference s - b c is s + (-1) b c (negation is exact).
 * What is left out: a term with a factor that is 0 at every step, such as a constant's
 * coefficients past the first or a product of polynomials past its
 * degree (t's series is t0, 1: its square has three coefficients).  A
 * cell is known to be 0 where no term reaches it; its readers see -1.
 */
#include "lower_series.h"
#include "lower_pack.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct Out {
    const LowTaylor *ty;
    int orders, nslot;     /* LOW_SERIES_ORDERS + 1, the program's slots */
    const int *col;        /* [nslot] each slot's column (lower_pack.c) */
    unsigned char *nz;     /* [ncell] written by a line (else 0 at every step) */
    double *literal;       /* [nslot] a constant's value where it is a number, else NAN */
    LowSerLine *line;
    int nline, capl;
    LowSerTerm *term;
    int nterm, capt;
    const char *why;       /* a call without a straight form */
} Out;

/* Slot s's coefficient j's cell: order by order, each order's slots side
 * by side in their columns (lowered.h), so that a step of a lower order
 * than the most touches only the first orders' cells (the Pleiades' 405 slots: 52 KB at
 * order 15, where a slot's 21 cells side by side would spread over 68 KB
 * and miss the first-level cache). */
static int
at(const Out *o, int s, int j)
{
    return j * o->nslot + o->col[s];
}

/* Slot s's coefficient j as an operand: its cell, or -1 where it is 0. */
static int
cell(const Out *o, int s, int j)
{
    if (s < 0 || j < 0 || j >= o->orders)
        return -1;
    int c = at(o, s, j);
    return o->nz[c] ? c : -1;
}

static LowSerLine *
new_line(Out *o, int dst, int kind)
{
    if (o->nline == o->capl) {
        o->capl = o->capl ? 2 * o->capl : 256;
        o->line = xrealloc(o->line, (size_t)o->capl * sizeof *o->line);
    }
    LowSerLine *l = &o->line[o->nline++];
    *l = (LowSerLine){.dst = dst, .kind = kind, .first = o->nterm, .times = 1, .last = -1,
                      .over_cell = -1, .x = -1, .y = -1};
    return l;
}

/* Append coef * x * y (y -1: coef * x) to the line being built, unless a
 * factor is 0; 1 when appended. */
static int
add_term(Out *o, double coef, int x, int y, int two)
{
    if (x < 0 || (two && y < 0))
        return 0;
    if (o->nterm == o->capt) {
        o->capt = o->capt ? 2 * o->capt : 1024;
        o->term = xrealloc(o->term, (size_t)o->capt * sizeof *o->term);
    }
    o->term[o->nterm++] = (LowSerTerm){.coef = coef, .x = x, .y = two ? y : -1};
    return 1;
}

/* Append the number coef alone (inv's 1 at order 0). */
static void
add_number(Out *o, double coef)
{
    add_term(o, coef, 0, -1, 0);
    o->term[o->nterm - 1].x = -1;
}

/* Close a SUM line whose terms were appended since it was opened (the
 * last of them its term[last], where it has one): it writes its cell, or
 * (no term) is dropped and its cell stays 0. */
static void
close_sum(Out *o, LowSerLine *l)
{
    l->nterm = (l->last >= 0 ? l->last : o->nterm) - l->first;
    if (l->nterm == 0 && l->last < 0) {
        o->nline--;
        return;
    }
    o->nz[l->dst] = 1;
}

/* The i-th j of a convolution's terms f(j, k - j), j = 0 .. k, in the
 * order eomc_taylor.h sums them (eomc_tay_at_): by the later of the two
 * orders, max(j, k - j), the earlier first, j before k - j. */
static int
term_at(int i, int k)
{
    int t = i + (k % 2 == 0 && i > 0);
    return t % 2 == 0 ? k / 2 - t / 2 : (k + 1) / 2 + t / 2;
}

/* dst = the sum of a_j b_{k-j}, j = 0 .. k (eomc_tay_mul). */
static void
product(Out *o, int c, int a, int b, int k)
{
    LowSerLine *l = new_line(o, at(o, c, k), LOW_SER_SUM);
    for (int i = 0; i <= k; i++) {
        int j = term_at(i, k);
        add_term(o, 1, cell(o, a, j), cell(o, b, k - j), 1);
    }
    close_sum(o, l);
}

static void
value_line(Out *o, int dst, int src, int index, double value)
{
    LowSerLine *l = new_line(o, dst, LOW_SER_VALUE);
    l->src = src, l->index = index, l->value = value;
    o->nz[dst] = 1;
}

static void
call_line(Out *o, int dst, const char *fn, int x, int y)
{
    LowSerLine *l = new_line(o, dst, LOW_SER_CALL);
    l->fn = fn, l->x = x, l->y = y;
    o->nz[dst] = 1;
}

/* Call st at order k, written out. */
static void
expand(Out *o, const LowTayStep *st, int k)
{
    const int *s = st->slot;
    int c = at(o, s[0], k);
    const char *f = st->call;
    LowSerLine *l;
    if (!strcmp(f, "const")) {
        if (k == 0)
            value_line(o, c, st->src, st->index, st->value);
    } else if (!strcmp(f, "time")) {
        if (k <= 1)
            value_line(o, c, k == 0 ? LOW_TAY_SRC_T : LOW_TAY_SRC_CONST, 0, 1);
    } else if (!strcmp(f, "add") || !strcmp(f, "sub") || !strcmp(f, "neg")) {
        /* 0 - b is -b, and -(a) is a times -1: exact */
        l = new_line(o, c, LOW_SER_SUM);
        int neg = !strcmp(f, "neg");
        add_term(o, neg ? -1 : 1, cell(o, s[1], k), -1, 0);
        if (!neg)
            add_term(o, f[0] == 's' ? -1 : 1, cell(o, s[2], k), -1, 0);
        close_sum(o, l);
    } else if (!strcmp(f, "scale")) {
        l = new_line(o, c, LOW_SER_SUM);
        add_term(o, 1, cell(o, s[1], 0), cell(o, s[2], k), 1);
        close_sum(o, l);
    } else if (!strcmp(f, "mul")) {
        product(o, s[0], s[1], s[2], k);
    } else if (!strcmp(f, "mul2") || !strcmp(f, "mul4")) {
        int g = st->nres; /* results first, then the factors' pairs */
        for (int i = 0; i < g; i++)
            product(o, s[i], s[g + 2 * i], s[g + 2 * i + 1], k);
    } else if (!strcmp(f, "sqr")) {
        l = new_line(o, c, LOW_SER_SUM);
        for (int i = 0; i <= k; i++) {
            int j = term_at(i, k);
            if (j < k - j)
                add_term(o, 1, cell(o, s[1], j), cell(o, s[1], k - j), 1);
        }
        l->times = 2;
        if (k % 2 == 0) {
            int at = o->nterm;
            if (add_term(o, 1, cell(o, s[1], k / 2), cell(o, s[1], k / 2), 1))
                l->last = at;
        }
        close_sum(o, l);
    } else if (!strcmp(f, "div") || !strcmp(f, "inv")) {
        /* c_k = (a_k - sum_{j=1..k} b_j c_{k-j}) / b_0; inv's a is 1, 0, ... */
        int inv = f[0] == 'i', b = s[inv ? 1 : 2];
        l = new_line(o, c, LOW_SER_SUM);
        for (int i = 0; i <= k; i++) {
            int j = term_at(i, k);
            if (j > 0)
                add_term(o, -1, cell(o, b, j), cell(o, s[0], k - j), 1);
            else if (inv && k == 0) /* a_k in c_k b_0's place */
                add_number(o, 1);
            else if (!inv)
                add_term(o, 1, cell(o, s[1], k), -1, 0);
        }
        l->over = 1, l->over_cell = cell(o, b, 0);
        close_sum(o, l);
    } else if (!strcmp(f, "sqrt") || !strcmp(f, "exp") || !strcmp(f, "powc")) {
        if (k == 0) {
            if (f[0] == 'p')
                call_line(o, c, "pow", cell(o, s[1], 0), cell(o, s[2], 0));
            else
                call_line(o, c, f, cell(o, s[1], 0), -1);
            return;
        }
        l = new_line(o, c, LOW_SER_SUM);
        if (f[1] == 'q') { /* (a_k - sum_{j=1..k-1} c_j c_{k-j}) / (2 c_0) */
            for (int i = 0; i <= k; i++) {
                int j = term_at(i, k);
                if (j > 0 && j < k)
                    add_term(o, -1, cell(o, s[0], j), cell(o, s[0], k - j), 1);
                else if (j == 0) /* a_k in 2 c_0 c_k's place */
                    add_term(o, 1, cell(o, s[1], k), -1, 0);
            }
            l->over = 2, l->over_cell = cell(o, s[0], 0);
        } else if (f[0] == 'e') { /* sum_{j=1..k} j a_j c_{k-j} / k */
            for (int i = 0; i <= k; i++) {
                int j = term_at(i, k);
                if (j > 0)
                    add_term(o, j, cell(o, s[1], j), cell(o, s[0], k - j), 1);
            }
            l->after = k;
        } else { /* sum_{j<k} (e (k - j) - j) a_{k-j} c_j / (k a_0) */
            double e = o->literal[s[2]];
            for (int i = 0; i <= k; i++) {
                int j = term_at(i, k);
                if (j < k)
                    add_term(o, e * (k - j) - j, cell(o, s[1], k - j), cell(o, s[0], j), 1);
            }
            l->over = k, l->over_cell = cell(o, s[1], 0);
        }
        close_sum(o, l);
    } else if (!strcmp(f, "sincos") || !strcmp(f, "sinhcosh")) {
        if (k == 0) {
            int h = f[3] == 'h';
            call_line(o, c, h ? "sinh" : "sin", cell(o, s[2], 0), -1);
            call_line(o, at(o, s[1], 0), h ? "cosh" : "cos", cell(o, s[2], 0), -1);
            return;
        }
        /* s_k = sum j a_j c_{k-j} / k, c_k = sign sum j a_j s_{k-j} / k,
         * both from orders below k */
        for (int w = 0; w < 2; w++) {
            l = new_line(o, at(o, s[w], k), LOW_SER_SUM);
            for (int i = 0; i <= k; i++) {
                int j = term_at(i, k);
                if (j > 0)
                    add_term(o, j, cell(o, s[2], j), cell(o, s[1 - w], k - j), 1);
            }
            l->negate = w == 1 && !strcmp(f, "sincos");
            l->after = k;
            close_sum(o, l);
        }
    } else if (!strcmp(f, "select")) {
        l = new_line(o, c, LOW_SER_SELECT);
        l->x = cell(o, s[1], k), l->y = cell(o, s[2], k);
        l->src = st->src, l->index = st->index;
        if (l->x < 0 && l->y < 0)
            o->nline--;
        else
            o->nz[c] = 1;
    } else if (!strcmp(f, "integ") || (!strcmp(f, "integ2") && k == 0)) {
        /* q_{k+1} = r_k / (k + 1) */
        l = new_line(o, at(o, s[0], k + 1), LOW_SER_SUM);
        add_term(o, 1, cell(o, s[1], k), -1, 0);
        l->after = k + 1;
        close_sum(o, l);
    } else if (!strcmp(f, "accel") || !strcmp(f, "integ2")) {
        /* v_{k+1} = h_k / m_0 / -(k + 1), q_{k+1} = h_{k-1} / m_0 / -(k (k + 1)):
         * h / m_0 the same quotient in both, which the C compiler computes
         * once; / -c is -(x / c) to the bit, without the negation's
         * instruction, but at k = 0: -h_0 / m_0 */
        int two = f[0] == 'i', h = s[two ? 2 : 1], m = s[two ? 3 : 2];
        l = new_line(o, at(o, s[0], k + 1), LOW_SER_SUM);
        add_term(o, 1, cell(o, h, two ? k - 1 : k), -1, 0);
        l->over = 1, l->over_cell = cell(o, m, 0);
        l->after = -(two ? k * (k + 1) : k + 1);
        if (l->after == -1)
            l->after = 0, l->negate = 1;
        close_sum(o, l);
    } else if (!strcmp(f, "mrhs")) {
        /* b_k = h_k + sum_l sum_{i=1..k} M_i a_{k-i}, the runtime loop's
         * mass_terms from 0 then h_k added (its last term) */
        const LowTaylor *ty = o->ty;
        int j = st->index, n = ty->nv; /* M is nv x nv */
        l = new_line(o, c, LOW_SER_SUM);
        for (int m = 0; m < n; m++)
            for (int i = 1; i <= k; i++)
                add_term(o, 1, cell(o, ty->M_slot[j * n + m], i), cell(o, ty->acc_slot[m], k - i),
                         1);
        int at = o->nterm;
        if (add_term(o, 1, cell(o, ty->h_slot[j], k), -1, 0))
            l->last = at;
        close_sum(o, l);
    } else if (!strcmp(f, "solve")) {
        /* a cell no term reached is 0; then a_k = -M_0^-1 b_k in place,
         * by the caller's hook; at order 0 it factors M_0, whose entries
         * are the line's terms */
        const LowTaylor *ty = o->ty;
        int n = ty->nv;
        for (int m = 0; m < n; m++)
            if (!o->nz[at(o, ty->acc_slot[m], k)])
                value_line(o, at(o, ty->acc_slot[m], k), LOW_TAY_SRC_CONST, 0, 0.0);
        l = new_line(o, c, LOW_SER_SOLVE);
        l->x = n, l->index = k;
        for (int e = 0; k == 0 && e < n * n; e++)
            if (!add_term(o, 1, cell(o, ty->M_slot[e], 0), -1, 0))
                add_number(o, 0.0);
        l->nterm = o->nterm - l->first;
        for (int m = 0; m < n; m++)
            o->nz[at(o, ty->acc_slot[m], k)] = 1;
    } else if (!strcmp(f, "hold")) {
        /* q_{k+1} = 0: nothing written */
    } else {
        o->why = f;
    }
}

/* The literal value of each slot that is a numeric constant. */
static void
literals(Out *o)
{
    const LowTaylor *ty = o->ty;
    for (int s = 0; s < ty->nslot; s++)
        o->literal[s] = NAN;
    for (int i = 0; i < ty->nstep; i++)
        if (!strcmp(ty->step[i].call, "const") && ty->step[i].src == LOW_TAY_SRC_CONST)
            o->literal[ty->step[i].slot[0]] = ty->step[i].value;
}

/* Each order's lines in packs (lower_pack.c), every cell being written
 * once. */
static void
pack_orders(LowSeries *se, const LowTaylor *ty)
{
    int *writer = xmalloc(((size_t)se->ncell + 1) * sizeof *writer);
    for (int c = 0; c < se->ncell; c++)
        writer[c] = -1;
    PackCells pc = {se->place, ty->nslot, ty->nstate, se->ncell};
    for (int k = 0; k < LOW_SERIES_ORDERS; k++)
        pack_lines(se->line + se->start[k], se->start[k + 1] - se->start[k], se->term, &pc,
                   writer);
    free(writer);
}

LowSeries *
lower_series(const LowTaylor *ty, Arena *A)
{
    int S = LOW_SERIES_ORDERS + 1, ncell = ty->nslot * S, nall = ty->nstep + ty->nrun;
    /* a real power's exponent must be a number (a parameter's would be a
     * product more per term) */
    int *col = arena_new_array(A, int, ty->nslot + 1);
    for (int s = 0; s < ty->nslot; s++)
        col[s] = s;
    if (!ty->acc_slot) /* (a solve's cells must stay as they are) */
        pack_columns(ty, col);
    Out o = {.ty = ty, .orders = S, .nslot = ty->nslot, .col = col};
    o.literal = xmalloc(((size_t)ty->nslot + 1) * sizeof *o.literal);
    literals(&o);
    for (int i = 0; i < ty->nstep && !o.why; i++)
        if (!strcmp(ty->step[i].call, "powc") && isnan(o.literal[ty->step[i].slot[2]]))
            o.why = "powc";
    o.nz = xmalloc((size_t)ncell + 1);
    memset(o.nz, 0, (size_t)ncell + 1);
    int ns = ty->nstate; /* the state's coefficient 0, which the caller writes */
    for (int i = 0; i < ns; i++)
        o.nz[at(&o, ty->state_slot[i], 0)] = 1;
    int *start = arena_new_array(A, int, LOW_SERIES_ORDERS + 1);
    for (int k = 0; k < LOW_SERIES_ORDERS && !o.why && o.nterm <= LOW_SERIES_MAX_TERMS; k++) {
        start[k] = o.nline;
        for (int i = 0; i < nall && !o.why; i++)
            expand(&o, &ty->step[i], k);
    }
    start[LOW_SERIES_ORDERS] = o.nline;
    LowSeries *se = NULL;
    if (!o.why && o.nterm <= LOW_SERIES_MAX_TERMS) {
        se = arena_alloc(A, sizeof *se);
        *se = (LowSeries){.ncell = ncell, .col = col, .nline = o.nline, .start = start,
                          .nterm = o.nterm, .parted = o.nterm > LOW_SERIES_OPTIMIZED_TERMS};
        se->place = arena_new_array(A, int, ty->nslot + 1);
        for (int s = 0; s < ty->nslot; s++)
            se->place[s] = -1;
        for (int i = 0; i < ns; i++)
            se->place[col[ty->state_slot[i]]] = i;
        /* four runs at once where M is constant and diagonal (no solve, whose
         * hook is one run's) and the series is one function */
        se->lanes = !ty->acc_slot && !se->parted;
        se->line = arena_new_array(A, LowSerLine, o.nline + 1);
        se->term = arena_new_array(A, LowSerTerm, o.nterm + 1);
        if (o.nline)
            memcpy(se->line, o.line, (size_t)o.nline * sizeof *o.line);
        if (o.nterm)
            memcpy(se->term, o.term, (size_t)o.nterm * sizeof *o.term);
        if (!ty->acc_slot)
            pack_orders(se, ty);
        /* the cells taylor_run copies out (the state's, the switches' and
         * events', M's diagonal's first) that stay 0 */
        int nout = 0, cap = 2 * ns * S + (ty->nevent + ty->nmode) * S + 1;
        se->zero_out = arena_new_array(A, int, cap);
        for (int i = 0; i < ns; i++) {
            int s = ty->state_slot[i];
            for (int j = 0; j < S; j++)
                if (!o.nz[at(&o, s, j)]) {
                    se->zero_out[nout++] = at(&o, s, j);
                    o.nz[at(&o, s, j)] = 1; /* listed once */
                }
        }
        for (int e = 0; e < ty->nevent + ty->nmode; e++)
            for (int j = 0; ty->g_slot[e] >= 0 && j < S - 1; j++)
                if (!o.nz[at(&o, ty->g_slot[e], j)]) {
                    se->zero_out[nout++] = at(&o, ty->g_slot[e], j);
                    o.nz[at(&o, ty->g_slot[e], j)] = 1;
                }
        se->nzero_out = nout;
    }
    free(o.literal);
    free(o.nz);
    free(o.line);
    free(o.term);
    return se;
}

/*
 * emit: the C printer.
 *
 * A function is a list of outputs (an expression and the C lvalue it goes
 * to).  We schedule the operator nodes the outputs need depth-first, in
 * output order, so that each value is computed shortly before its first
 * use, and print one `const double` temporary per node; each output is
 * assigned as soon as its value exists.  All cleverness is in the DAG;
 * this is a plain loop.
 *
 * Very large functions (the Jacobian of a 50-link chain has ~70 000
 * nodes) are cut into parts of at most PART_SIZE temporaries, each its own
 * non-inlined C function: the C compiler's register allocator is
 * superlinear in function size, and parts keep `cc -O2` time linear.
 * Values needed by a later part travel through a stack array s[].
 */
#include "emit.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

enum { PART_SIZE = 6000 };

typedef struct Out {
    ExprId e;
    char dest[48];
} Out;

/* What a generated function looks like from outside. */
typedef struct Func {
    const char *name;    /* e.g. "mass_bias" */
    const char *comment;
    const char *params;  /* C parameter list */
    const char *args;    /* the parameter names, comma-separated */
    const char *src[9];  /* names of the q, v, a, -, p, u, t, dq, dv parameters */
    const char *unused;  /* outputs nothing is written to, or NULL */
} Func;

typedef struct Printer {
    FILE *f;
    ExprPool *P;
    const Spec *s;
    /* per node id, for the function being printed */
    int *temp;  /* temporary number, -1 if not scheduled */
    int *part;  /* the part that computes it */
    int *slot;  /* index in s[], -1 if only its own part uses it */
    int *ext;   /* NULL, or per node its index in an input array shared[] (-1:
                 * not there): values computed once by another function */
    int cur;    /* the part being printed */
    unsigned used; /* bit k: parameter src[k] is read in this part */
    int fenced;    /* inside #ifndef EOMC_EXTENDED */
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

/* Lines of generated code are wrapped before this column. */
enum { WRAP = 80 };

/* "TYPE\nNAME(PARAMS)\n{", the comma-separated parameters wrapped. */
static void
print_head(Printer *pr, const char *type, const char *name, const char *params)
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
    fputs(")\n{\n", pr->f);
}

/* The shortest %g form that reads back as the same double (9.81, not
 * 9.8100000000000005), made to look like a double to C. */
static void
format_const(char *buf, size_t len, double v)
{
    for (int prec = 1; prec <= 17; prec++) {
        snprintf(buf, len, "%.*g", prec, v);
        if (strtod(buf, NULL) == v)
            break;
    }
    if (!strpbrk(buf, ".eEn"))
        strncat(buf, ".0", len - strlen(buf) - 1);
}

static int is_leaf(const ExprNode *nd) { return expr_op_arity[nd->op] == 0; }

static int is_ext(const Printer *pr, ExprId e) { return pr->ext && pr->ext[e] >= 0; }

static void
leaf_name(Printer *pr, const ExprNode *nd, char *buf, size_t len)
{
    static const char prefix[] = {'q', 'v', 'a', 'j'};
    switch (nd->op) {
    case EXPR_SEED:
        snprintf(buf, len, "%s_%s", nd->b ? "dv" : "dq", pr->s->coord[nd->a].name);
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
    if (pr->slot[id] >= 0)
        println(pr, "    s[%d] = w%d;", pr->slot[id], pr->temp[id]);
}

/* ---- scheduling ---- */

typedef struct Sched {
    ExprId *node;  /* operator nodes in print order */
    int n;
    int *after;    /* per output: nodes printed before its assignment */
    int *pstart;   /* per part: first node; pstart[nparts] = n */
    int *ostart;   /* per part: first output; ostart[nparts] = nout */
    int nparts, nslots;
} Sched;

/* Append the unscheduled operator nodes that root needs, operands first. */
static void
schedule_tree(Printer *pr, Sched *S, ExprId root)
{
    size_t cap = 64, sp = 0;
    struct { ExprId id; int expanded; } *stack = malloc(cap * sizeof *stack);
    stack[sp].id = root;
    stack[sp++].expanded = 0;
    while (sp) {
        ExprId e = stack[sp - 1].id;
        const ExprNode *nd = expr_node(pr->P, e);
        if (is_leaf(nd) || pr->temp[e] >= 0 || is_ext(pr, e)) {
            sp--;
        } else if (stack[sp - 1].expanded) {
            sp--;
            pr->temp[e] = S->n;
            S->node[S->n++] = e;
        } else {
            stack[sp - 1].expanded = 1;
            if (sp + 2 >= cap)
                stack = realloc(stack, (cap *= 2) * sizeof *stack);
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

/* A value crossing into another part gets a slot in s[]. */
static void
share(Printer *pr, Sched *S, ExprId e, int part)
{
    if (!is_leaf(expr_node(pr->P, e)) && !is_ext(pr, e) && pr->part[e] != part &&
        pr->slot[e] < 0)
        pr->slot[e] = S->nslots++;
}

static void
schedule(Printer *pr, Sched *S, int nout, const Out *out)
{
    size_t size = expr_pool_size(pr->P);
    S->node = malloc(size * sizeof *S->node);
    S->after = malloc(((size_t)nout + 1) * sizeof *S->after);
    S->pstart = malloc(((size_t)nout + 2) * sizeof *S->pstart);
    S->ostart = malloc(((size_t)nout + 2) * sizeof *S->ostart);
    S->n = S->nparts = S->nslots = 0;
    S->pstart[0] = S->ostart[0] = 0;
    for (int i = 0; i < nout; i++) {
        schedule_tree(pr, S, out[i].e);
        S->after[i] = S->n;
        if (S->n - S->pstart[S->nparts] >= PART_SIZE || i == nout - 1) {
            S->nparts++;
            S->pstart[S->nparts] = S->n;
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

static void
mark_leaf(Printer *pr, ExprId e, unsigned char *mark)
{
    if (is_leaf(expr_node(pr->P, e)))
        mark[e] = 1;
}

/* Named locals for the leaves part p reads, in a fixed order: t, the
 * coordinates by derivative order, parameters, inputs, seeds. */
static void
print_leaves(Printer *pr, const Sched *S, int nout, const Out *out,
             const char *const *src)
{
    static const int kinds[] = {EXPR_TIME, EXPR_VAR, EXPR_PARAM, EXPR_INPUT, EXPR_SEED};
    size_t size = expr_pool_size(pr->P);
    unsigned char *mark = calloc(size, 1);
    for (int k = S->pstart[pr->cur]; k < S->pstart[pr->cur + 1]; k++) {
        const ExprNode *nd = expr_node(pr->P, S->node[k]);
        int ar = expr_op_arity[nd->op];
        if (ar >= 1)
            mark_leaf(pr, nd->a, mark);
        if (ar >= 2)
            mark_leaf(pr, nd->b, mark);
    }
    for (int i = S->ostart[pr->cur]; i < S->ostart[pr->cur + 1] && i < nout; i++)
        mark_leaf(pr, out[i].e, mark);
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++)
        for (size_t id = 0; id < size; id++) {
            const ExprNode *nd = expr_node(pr->P, (ExprId)id);
            if (!mark[id] || nd->op != kinds[k])
                continue;
            if (nd->op == EXPR_TIME) {
                pr->used |= 1u << 6;
                continue;
            }
            int arr = nd->op == EXPR_VAR    ? (int)nd->b
                      : nd->op == EXPR_PARAM  ? 4
                      : nd->op == EXPR_INPUT  ? 5
                                              : 7 + (int)nd->b; /* seeds */
            char buf[160];
            leaf_name(pr, nd, buf, sizeof buf);
            pr->used |= 1u << arr;
            println(pr, "    const eomc_real %s = %s[%u];", buf, src[arr], nd->a);
        }
    free(mark);
}

/* The statements of part p: leaves, temporaries, assignments. */
static void
print_part(Printer *pr, const Sched *S, int nout, const Out *out,
           const Func *fn)
{
    pr->used = 0;
    print_leaves(pr, S, nout, out, fn->src);
    if (S->nparts == 1) {
        for (int k = 0; k < 9; k++) /* silence -Wunused-parameter */
            if (fn->src[k] && !(pr->used >> k & 1))
                println(pr, "    (void)%s;", fn->src[k]);
        if (fn->unused)
            println(pr, "    %s", fn->unused);
    }
    int k = S->pstart[pr->cur];
    for (int i = S->ostart[pr->cur]; i < S->ostart[pr->cur + 1]; i++) {
        for (; k < S->after[i]; k++)
            print_node(pr, S->node[k]);
        char buf[200];
        println(pr, "    %s = %s;", out[i].dest, operand(pr, out[i].e, buf, sizeof buf));
    }
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

/* Print `fn` computing the outputs; returns its operation counts. */
static ExprCount
print_function(Printer *pr, const Func *fn, int nout, const Out *out)
{
    size_t size = expr_pool_size(pr->P);
    pr->temp = malloc(size * sizeof *pr->temp);
    pr->part = malloc(size * sizeof *pr->part);
    pr->slot = malloc(size * sizeof *pr->slot);
    for (size_t i = 0; i < size; i++)
        pr->temp[i] = pr->slot[i] = -1, pr->part[i] = 0;
    Sched S;
    schedule(pr, &S, nout, out);
    const char *nm = pr->s->name;
    char fname[128];
    snprintf(fname, sizeof fname, "%s_%s", nm, fn->name);
    if (S.nparts == 1) {
        println(pr, "/* %s */", fn->comment);
        print_head(pr, "static void", fname, fn->params);
        pr->cur = 0;
        print_part(pr, &S, nout, out, fn);
        println(pr, "}\n");
    } else {
        for (pr->cur = 0; pr->cur < S.nparts; pr->cur++) {
            char part[160], params[600];
            println(pr, "/* %s: part %d of %d */", fn->name, pr->cur + 1, S.nparts);
            snprintf(part, sizeof part, "%s_part%d", fname, pr->cur + 1);
            snprintf(params, sizeof params, "%s, eomc_real *s", fn->params);
            print_head(pr, "static EOMC_NOINLINE void", part, params);
            print_voids(pr, fn->args);
            print_part(pr, &S, nout, out, fn);
            println(pr, "}\n");
        }
        println(pr, "/* %s */", fn->comment);
        print_head(pr, "static void", fname, fn->params);
        println(pr, "    eomc_real s[%d]; /* values shared between the parts */", S.nslots ? S.nslots : 1);
        for (int p = 0; p < S.nparts; p++)
            println(pr, "    %s_%s_part%d(%s, s);", nm, fn->name, p + 1, fn->args);
        println(pr, "}\n");
    }
    /* exactly what was printed: values from shared[] are counted where made */
    ExprCount c = expr_count_list(pr->P, (size_t)S.n, S.node);
    free(S.node);
    free(S.after);
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
    println(pr, " * options: %s", info->options[0] ? info->options : "(none)");
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
    if (c) {
        println(pr, " *");
        println(pr, " * constraints, by %s:", info->eliminate
                ? "elimination (C^T E = 0, f = 0)" : "multipliers (E + B^T lambda = 0, f = 0)");
        for (int k = 0; k < c->nc; k++)
            println(pr, " *   %-12s %s, determines %s", c->spec[k].name,
                    constraint_order_name(c->spec[k].order), s->coord[c->dependent[k]].name);
        println(pr, " *   %s in q''", c->affine ? "all affine" : "not all affine (Newton)");
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
    println(pr, "");
}

static void
add_out(Out *o, int *n, ExprId e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(o[*n].dest, sizeof o[*n].dest, fmt, ap);
    va_end(ap);
    o[(*n)++].e = e;
}

#define SRC(q, v, a, p, u, t) {q, v, a, NULL, p, u, t, NULL, NULL}

static const Func f_initial = {
    "initial", "Initial state from the spec's `initial`.",
    "const eomc_real *p, eomc_real *q, eomc_real *v", "p, q, v",
    SRC(NULL, NULL, NULL, "p", NULL, NULL), NULL,
};
static const Func f_inputs = {
    "inputs", "Input signals u(t) and du/dt.",
    "eomc_real t, const eomc_real *p, eomc_real *u, eomc_real *dudt", "t, p, u, dudt",
    SRC(NULL, NULL, NULL, "p", NULL, "t"), "(void)u;\n    (void)dudt;",
};
static const Func f_mass_bias = {
    "mass_bias",
    "Mass matrix M = dE/dq'' (row-major, symmetric) and bias h = E(q'' = 0).",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p, const eomc_real *u, eomc_real *M, eomc_real *h", "t, q, v, p, u, M, h",
    SRC("q", "v", NULL, "p", "u", "t"), NULL,
};
static const Func f_energy = {
    "energy", "Kinetic energy T and potential energy V.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p, const eomc_real *u, eomc_real *TV", "t, q, v, p, u, TV",
    SRC("q", "v", NULL, "p", "u", "t"), NULL,
};
static const Func f_jacobian = {
    "jacobian",
    "Partial derivatives of the residual E(t, q, q', q'') with u held fixed.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *a, const eomc_real *p, const eomc_real *u, eomc_real *dEdq, eomc_real *dEdv, eomc_real *dEdu, eomc_real *dEdt", "t, q, v, a, p, u, dEdq, dEdv, dEdu, dEdt",
    SRC("q", "v", "a", "p", "u", "t"), "(void)dEdu;",
};

/* The seeded jacobian (print_seeded_jacobian): shared values, then one
 * column per call. */
static const Func f_jac_shared = {
    "jacobian_shared",
    "The values every column of the Jacobian needs (into shared[]), and dE/du,\n"
    " * dE/dt.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *a, const eomc_real *p, const eomc_real *u, eomc_real *shared, eomc_real *dEdu, eomc_real *dEdt", "t, q, v, a, p, u, shared, dEdu, dEdt",
    SRC("q", "v", "a", "p", "u", "t"), NULL,
};
static const Func f_jac_dq = {
    "jacobian_dq",
    "dE[i*nq] = sum_j dE_i/dq_j dq[j], given shared[] from jacobian_shared.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *a, const eomc_real *p, const eomc_real *u, const eomc_real *shared, const eomc_real *dq, eomc_real *dE", "t, q, v, a, p, u, shared, dq, dE",
    {"q", "v", "a", NULL, "p", "u", "t", "dq", NULL}, "(void)shared;",
};
static const Func f_jac_dv = {
    "jacobian_dv",
    "dE[i*nq] = sum_j dE_i/dq'_j dv[j], given shared[] from jacobian_shared.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *a, const eomc_real *p, const eomc_real *u, const eomc_real *shared, const eomc_real *dv, eomc_real *dE", "t, q, v, a, p, u, shared, dv, dE",
    {"q", "v", "a", NULL, "p", "u", "t", NULL, "dv"}, "(void)shared;",
};

static const Func f_accel_solve = {
    "accel_solve",
    "a = -M^-1 h by an unrolled LDL^T factorization (structural zeros of M\n"
    " * skipped; last coordinate first); its pivots piv[k] = d_k, and mkk[k] =\n"
    " * M_kk.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p, const eomc_real *u, eomc_real *a, eomc_real *piv, eomc_real *mkk", "t, q, v, p, u, a, piv, mkk",
    SRC("q", "v", NULL, "p", "u", "t"), NULL,
};

static const Func f_constraint = {
    "constraint",
    "Constraints at acceleration level f(t, q, q', q'') and B = df/dq''.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *a, const eomc_real *p, const eomc_real *u, eomc_real *f, eomc_real *B",
    "t, q, v, a, p, u, f, B",
    SRC("q", "v", "a", "p", "u", "t"), NULL,
};
static const Func f_c_levels = {
    "c_levels",
    "Constraints at their own level: pos = g (holonomic), vel = g' or phi.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p, const eomc_real *u, eomc_real *pos, eomc_real *vel", "t, q, v, p, u, pos, vel",
    SRC("q", "v", NULL, "p", "u", "t"), NULL,
};
static const Func f_c_levels_jacobian = {
    "c_levels_jacobian",
    "Partial derivatives of pos and vel (u held fixed): what Baumgarte's\n"
    " * stabilization adds to df/dx.",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p, const eomc_real *u, eomc_real *dposdq, eomc_real *dveldq, eomc_real *dveldv, eomc_real *dposdu, eomc_real *dveldu, eomc_real *dposdt, eomc_real *dveldt",
    "t, q, v, p, u, dposdq, dveldq, dveldv, dposdu, dveldu, dposdt, dveldt",
    SRC("q", "v", NULL, "p", "u", "t"), "(void)dposdu;\n    (void)dveldu;",
};
static const Func f_c_jacobian = {
    "c_jacobian",
    "Partial derivatives of f and of B = df/dq'' (u held fixed).",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *a, const eomc_real *p, const eomc_real *u, eomc_real *dfdq, eomc_real *dfdv, eomc_real *dfdu, eomc_real *dfdt, eomc_real *dBdq, eomc_real *dBdv, eomc_real *dBda, eomc_real *dBdu, eomc_real *dBdt",
    "t, q, v, a, p, u, dfdq, dfdv, dfdu, dfdt, dBdq, dBdv, dBda, dBdu, dBdt",
    SRC("q", "v", "a", "p", "u", "t"), "(void)dfdu;\n    (void)dBdu;",
};

static void
add_count(ExprCount *c, ExprCount d)
{
    c->adds += d.adds;
    c->muls += d.muls;
    c->divs += d.divs;
    c->calls += d.calls;
}

/* The jacobian member as directional derivatives (EMIT_JACOBIAN_SEEDED).
 * The seeded expressions e->jvp_q, e->jvp_v are linear in the seeds; what
 * they need that does not depend on the seeds (sines, products, ...) is
 * the same for every column, so jacobian_shared computes it once into shared[],
 * and jacobian_dq and jacobian_dv compute only the seed-dependent rest,
 * once per column with a unit seed.  Returns the operations printed. */
static ExprCount
print_seeded_jacobian(Printer *pr, const Eom *e)
{
    ExprPool *P = pr->P;
    const char *nm = pr->s->name;
    int n = e->n, nu = e->nu, nw = 0, k;
    size_t size = expr_pool_size(P);
    ExprId *roots = malloc(2 * (size_t)n * sizeof *roots);
    for (int i = 0; i < n; i++) {
        roots[i] = e->jvp_q[i];
        roots[n + i] = e->jvp_v[i];
    }
    /* shared[] holds the seed-free operator nodes that seeded nodes read (and
     * any seed-free root), numbered by id: deterministic. */
    unsigned char *mark = calloc(size, 1), *need = calloc(size, 1);
    expr_mark(P, 2 * n, roots, mark);
    for (size_t id = 0; id < size; id++) {
        const ExprNode *nd = expr_node(P, (ExprId)id);
        if (!mark[id] || is_leaf(nd) || !(nd->deps & DEP_S))
            continue;
        int ar = expr_op_arity[nd->op];
        ExprId ops[2] = {nd->a, nd->b};
        for (int j = 0; j < ar; j++)
            if (!(expr_deps(P, ops[j]) & DEP_S) && !is_leaf(expr_node(P, ops[j])))
                need[ops[j]] = 1;
    }
    for (int i = 0; i < 2 * n; i++)
        if (!(expr_deps(P, roots[i]) & DEP_S) && !is_leaf(expr_node(P, roots[i])))
            need[roots[i]] = 1;
    int *ext = malloc(size * sizeof *ext);
    for (size_t id = 0; id < size; id++)
        ext[id] = need[id] ? nw++ : -1;

    Out *o = calloc((size_t)nw + (size_t)n * ((size_t)nu + 2) + 1, sizeof *o);
    k = 0;
    for (size_t id = 0; id < size; id++)
        if (need[id])
            add_out(o, &k, (ExprId)id, "shared[%d]", ext[id]);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < nu; j++)
            add_out(o, &k, e->dEdu[i * nu + j], "dEdu[%d]", i * nu + j);
        add_out(o, &k, e->dEdt[i], "dEdt[%d]", i);
    }
    Func fs = f_jac_shared;
    fs.unused = nu ? (nw ? NULL : "(void)shared;") : nw ? "(void)dEdu;" : "(void)shared;\n    (void)dEdu;";
    ExprCount c = print_function(pr, &fs, k, o);
    pr->ext = ext;
    k = 0;
    for (int i = 0; i < n; i++)
        add_out(o, &k, e->jvp_q[i], "dE[%d]", i * n);
    add_count(&c, print_function(pr, &f_jac_dq, k, o));
    k = 0;
    for (int i = 0; i < n; i++)
        add_out(o, &k, e->jvp_v[i], "dE[%d]", i * n);
    add_count(&c, print_function(pr, &f_jac_dv, k, o));
    pr->ext = NULL;

    println(pr, "/* %s", f_jacobian.comment);
    println(pr, " * Column j of dE/dq (dE/dq') is the derivative along the unit seed");
    println(pr, " * dq = e_j (dq' = e_j): exact, in code about the size of E instead of");
    println(pr, " * %d times that. */", n);
    char fname[128];
    snprintf(fname, sizeof fname, "%s_jacobian", nm);
    print_head(pr, "static void", fname, f_jacobian.params);
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
    free(o);
    free(ext);
    free(need);
    free(mark);
    free(roots);
    return c;
}

/* The accel member of eomc_model: the solve, then the pivot check. */
static void
print_accel(Printer *pr, int n)
{
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
    println(pr, "    for (int k = %d; k >= 0; k--) /* in elimination order */", n - 1);
    println(pr, "        if (!(piv[k] > EOMC_PIVOT_TOL * mkk[k]))");
    println(pr, "            return k + 1;");
    println(pr, "    if (pivot) {");
    println(pr, "        eomc_real dmin = piv[0], mmin = mkk[0];");
    println(pr, "        for (int k = 1; k < %d; k++)", n);
    println(pr, "            if (piv[k] * mmin < dmin * mkk[k])");
    println(pr, "                dmin = piv[k], mmin = mkk[k];");
    println(pr, "        *pivot = dmin / mmin;");
    println(pr, "    }");
    println(pr, "    return 0;");
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
                   const Invariant *inv, const EmitInfo *info)
{
    const char *nm = s->name;
    println(pr, "const eomc_model %s_model = {", nm);
    fprintf(pr->f, "    EOMC_ABI_VERSION, \"%s\", ", nm);
    print_c_string(pr->f, base_name(s->path));
    fprintf(pr->f, ", \"%s\", ", e->form->name);
    print_c_string(pr->f, info->options);
    println(pr, ",");
    println(pr, "    %d, %d, %d, q_names, p_names, u_names, p_default,", s->nq, s->np, s->nu);
    char a[40], b[40], rt[40], at[40], h[40];
    format_const(a, sizeof a, s->scene.t_end);
    format_const(b, sizeof b, s->scene.dt);
    format_const(rt, sizeof rt, s->scene.rtol);
    format_const(at, sizeof at, s->scene.atol);
    format_const(h, sizeof h, s->scene.h_fixed);
    println(pr, "    %s, %s, \"%s\", %s, %s, %s,", a, b, s->scene.method, rt, at, h);
    println(pr, "    %s_initial, %s_inputs, %s_mass_bias, %s_energy, %s_jacobian,",
            nm, nm, nm, nm, nm);
    if (c)
        println(pr, "    NULL, /* constrained: the runtime solves the KKT system */");
    else if (e->acc)
        println(pr, "    %s_accel,", nm);
    else
        println(pr, "    NULL, /* more than %d coordinates: the runtime solves with GSL */",
                EOM_SOLVE_MAX);
    if (c)
        println(pr, "    %d, c_names, c_order, c_dependent, %d, %d,\n"
                "    %s_constraint, %s_c_levels, %s_c_jacobian, %s_c_levels_jacobian,",
                c->nc, c->affine, info->eliminate, nm, nm, nm, nm);
    else
        println(pr, "    0, NULL, NULL, NULL, 1, 0, NULL, NULL, NULL, NULL,");
    if (inv->h != EXPR_NONE)
        fprintf(pr->f, "    %s_invariant, \"%s\",\n    ", nm, inv->name);
    else
        fprintf(pr->f, "    NULL, NULL,\n    ");
    print_c_string(pr->f, inv->note);
    if (s->ncheck)
        println(pr, ",\n    %d, %s_check, check_what, check_params,\n};\n", s->ncheck, nm);
    else
        println(pr, ",\n    0, NULL, NULL, NULL,\n};\n");
    println(pr, "#ifdef EOMC_MAIN");
    println(pr, "#include \"eomc.h\"");
    println(pr, "/* The reference solution's functions: this file compiled again with");
    println(pr, " * -DEOMC_EXTENDED and linked (eomc build does); without it the simulator");
    println(pr, " * runs but cannot measure its errors. */");
    println(pr, "extern const eomc_model_ext %s_model_ext EOMC_WEAK;", nm);
    println(pr, "int main(int argc, char **argv)");
    println(pr, "{");
    println(pr, "    return eomc_main(argc, argv, &%s_model, &%s_model_ext);", nm, nm);
    println(pr, "}");
    println(pr, "#endif");
    println(pr, "#else");
    println(pr, "const eomc_model_ext %s_model_ext = {", nm);
    println(pr, "    EOMC_ABI_VERSION, \"%s\", %s_inputs, %s_mass_bias, %s%s,", nm, nm, nm,
            !c && e->acc ? nm : "NULL", !c && e->acc ? "_accel" : "");
    if (c)
        println(pr, "    %s_constraint, %s%s,", nm, c->affine ? "NULL" : nm,
                c->affine ? "" : "_c_jacobian");
    else
        println(pr, "    NULL, NULL,");
    println(pr, "};");
    println(pr, "#endif /* EOMC_EXTENDED */");
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
}

/* The derivatives of pos and vel into o; returns the count. */
static int
add_levels_jacobian(Printer *pr, const Constraints *c, Diff *D, Out *o)
{
    int n = pr->s->nq, nu = pr->s->nu, k = 0;
    ExprId t = expr_time(pr->P);
    for (int a = 0; a < c->nc; a++) {
        ExprId g = c->pos[a] == EXPR_NONE ? EXPR_ZERO : c->pos[a];
        ExprId w = c->vel[a] == EXPR_NONE ? EXPR_ZERO : c->vel[a];
        for (int j = 0; j < n; j++) {
            ExprId qj = expr_var(pr->P, j, 0), vj = expr_var(pr->P, j, 1);
            add_out(o, &k, diff_partial(D, g, qj), "dposdq[%d]", a * n + j);
            add_out(o, &k, diff_partial(D, w, qj), "dveldq[%d]", a * n + j);
            add_out(o, &k, diff_partial(D, w, vj), "dveldv[%d]", a * n + j);
        }
        for (int l = 0; l < nu; l++) {
            ExprId ul = expr_input(pr->P, l);
            add_out(o, &k, diff_partial(D, g, ul), "dposdu[%d]", a * nu + l);
            add_out(o, &k, diff_partial(D, w, ul), "dveldu[%d]", a * nu + l);
        }
        add_out(o, &k, diff_partial(D, g, t), "dposdt[%d]", a);
        add_out(o, &k, diff_partial(D, w, t), "dveldt[%d]", a);
    }
    return k;
}

/* constraint, c_levels, c_jacobian and c_levels_jacobian; their counts
 * into stats[0..3]. */
static void
print_constraints(Printer *pr, const Constraints *c, Diff *D, EmitStats *stats)
{
    const Spec *s = pr->s;
    int n = s->nq, nu = s->nu, nc = c->nc, k = 0;
    Out *o = calloc((size_t)(nc * (3 * n * n + n * nu + 3 * n + 2 * nu + 4)), sizeof *o);
    for (int a = 0; a < nc; a++) {
        add_out(o, &k, c->f[a], "f[%d]", a);
        for (int j = 0; j < n; j++)
            add_out(o, &k, c->B[a * n + j], "B[%d]", a * n + j);
    }
    fence(pr, 0);
    stats[0] = (EmitStats){"constraint", print_function(pr, &f_constraint, k, o)};
    fence(pr, 1);
    k = 0;
    for (int a = 0; a < nc; a++) {
        add_out(o, &k, c->pos[a] == EXPR_NONE ? EXPR_ZERO : c->pos[a], "pos[%d]", a);
        add_out(o, &k, c->vel[a] == EXPR_NONE ? EXPR_ZERO : c->vel[a], "vel[%d]", a);
    }
    stats[1] = (EmitStats){"c_levels", print_function(pr, &f_c_levels, k, o)};
    k = 0;
    ExprId t = expr_time(pr->P);
    for (int a = 0; a < nc; a++) {
        ExprId fa = c->f[a];
        for (int j = 0; j < n; j++) {
            add_out(o, &k, diff_partial(D, fa, expr_var(pr->P, j, 0)), "dfdq[%d]", a * n + j);
            add_out(o, &k, diff_partial(D, fa, expr_var(pr->P, j, 1)), "dfdv[%d]", a * n + j);
        }
        for (int l = 0; l < nu; l++)
            add_out(o, &k, diff_partial(D, fa, expr_input(pr->P, l)), "dfdu[%d]", a * nu + l);
        add_out(o, &k, diff_partial(D, fa, t), "dfdt[%d]", a);
        for (int i = 0; i < n; i++) {
            ExprId b = c->B[a * n + i];
            int row = a * n + i;
            for (int j = 0; j < n; j++) {
                add_out(o, &k, diff_partial(D, b, expr_var(pr->P, j, 0)), "dBdq[%d]", row * n + j);
                add_out(o, &k, diff_partial(D, b, expr_var(pr->P, j, 1)), "dBdv[%d]", row * n + j);
                add_out(o, &k, diff_partial(D, b, expr_var(pr->P, j, 2)), "dBda[%d]", row * n + j);
            }
            for (int l = 0; l < nu; l++)
                add_out(o, &k, diff_partial(D, b, expr_input(pr->P, l)), "dBdu[%d]", row * nu + l);
            add_out(o, &k, diff_partial(D, b, t), "dBdt[%d]", row);
        }
    }
    Func fj = f_c_jacobian;
    fj.unused = nu ? NULL : f_c_jacobian.unused;
    fence(pr, c->affine); /* Newton's method needs it only when f is not affine */
    stats[2] = (EmitStats){"c_jacobian", print_function(pr, &fj, k, o)};
    fence(pr, 1);
    k = add_levels_jacobian(pr, c, D, o);
    Func fl = f_c_levels_jacobian;
    fl.unused = nu ? NULL : f_c_levels_jacobian.unused;
    stats[3] = (EmitStats){"c_levels_jacobian", print_function(pr, &fl, k, o)};
    free(o);
}

/* The physical data's conditions on the parameters (Spec.check). */
static const Func f_check_values = {
    "check_values", "The values that must be positive (or not negative): check_what.",
    "const eomc_real *p, eomc_real *chk", "p, chk",
    SRC(NULL, NULL, NULL, "p", NULL, NULL), NULL,
};

/* check_values, the check member, and its tables. */
static void
print_checks(Printer *pr)
{
    const Spec *s = pr->s;
    const char *nm = s->name;
    int nk = s->ncheck;
    if (nk == 0)
        return;
    Out *o = calloc((size_t)nk, sizeof *o);
    int k = 0;
    for (int i = 0; i < nk; i++)
        add_out(o, &k, s->check[i].expr, "chk[%d]", i);
    print_function(pr, &f_check_values, k, o);
    free(o);
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
    println(pr, "    for (int k = 0; k < %d; k++)", nk);
    println(pr, "        if (check_strict[k] ? !(chk[k] > 0) : !(chk[k] >= 0))");
    println(pr, "            return k + 1;");
    println(pr, "    return 0;");
    println(pr, "}\n");
}

/* The conserved quantity, when there is one. */
static const Func f_invariant = {
    "invariant", "The conserved quantity (eomc_model.h: invariant).",
    "eomc_real t, const eomc_real *q, const eomc_real *v, const eomc_real *p, "
    "const eomc_real *u, eomc_real *h", "t, q, v, p, u, h",
    SRC("q", "v", NULL, "p", "u", "t"), NULL,
};

void
emit_model(FILE *f, const Spec *s, const Mech *m, const Eom *e, const Constraints *c,
           const Invariant *inv, ExprPool *P, Diff *D, const EmitInfo *info,
           EmitStats stats[EMIT_NFUNCS])
{
    Printer pr = {.f = f, .P = P, .s = s};
    int n = s->nq, nu = s->nu, k;
    Out *o = calloc((size_t)(2 * n * n + n * nu + 4 * n + 2 * nu + 2), sizeof *o);
    print_banner(&pr, e, c, inv, info);
    fence(&pr, 1);
    print_tables(&pr);
    if (c)
        print_constraint_tables(&pr, c);

    k = 0;
    for (int i = 0; i < n; i++)
        add_out(o, &k, s->coord[i].q0, "q[%d]", i);
    for (int i = 0; i < n; i++)
        add_out(o, &k, s->coord[i].v0, "v[%d]", i);
    stats[0] = (EmitStats){"initial", print_function(&pr, &f_initial, k, o)};

    fence(&pr, 0);
    k = 0;
    for (int i = 0; i < nu; i++)
        add_out(o, &k, s->input[i].expr, "u[%d]", i);
    for (int i = 0; i < nu; i++)
        add_out(o, &k, diff_time(D, s->input[i].expr), "if (dudt) dudt[%d]", i);
    Func fin = f_inputs;
    fin.unused = nu ? NULL : f_inputs.unused;
    stats[1] = (EmitStats){"inputs", print_function(&pr, &fin, k, o)};

    k = 0; /* lower triangle and h, then the mirrored upper triangle */
    for (int i = 0; i < n; i++)
        for (int j = 0; j <= i; j++)
            add_out(o, &k, e->M[i * n + j], "M[%d]", i * n + j);
    for (int i = 0; i < n; i++)
        add_out(o, &k, e->h[i], "h[%d]", i);
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            add_out(o, &k, e->M[i * n + j], "M[%d]", i * n + j);
    stats[2] = (EmitStats){"mass_bias", print_function(&pr, &f_mass_bias, k, o)};

    fence(&pr, 1);
    k = 0;
    add_out(o, &k, m->T, "TV[0]");
    add_out(o, &k, m->V, "TV[1]");
    stats[3] = (EmitStats){"energy", print_function(&pr, &f_energy, k, o)};

    k = 0;
    ExprId *jroots = malloc(2 * (size_t)n * (size_t)n * sizeof *jroots);
    for (int i = 0; i < n * n; i++) {
        jroots[i] = e->dEdq[i];
        jroots[n * n + i] = e->dEdv[i];
    }
    ExprCount jc = expr_count_ops(P, 2 * n * n, jroots);
    free(jroots);
    long jops = jc.adds + jc.muls + jc.divs + jc.calls;
    int seeded = info->jacobian == EMIT_JACOBIAN_SEEDED ||
                 (info->jacobian == EMIT_JACOBIAN_AUTO && jops > EMIT_UNROLLED_JACOBIAN_MAX);
    if (seeded)
        stats[4] = (EmitStats){"jacobian", print_seeded_jacobian(&pr, e)};
    for (int i = 0; i < n && !seeded; i++) { /* row by row: rows share their work */
        for (int j = 0; j < n; j++)
            add_out(o, &k, e->dEdq[i * n + j], "dEdq[%d]", i * n + j);
        for (int j = 0; j < n; j++)
            add_out(o, &k, e->dEdv[i * n + j], "dEdv[%d]", i * n + j);
        for (int j = 0; j < nu; j++)
            add_out(o, &k, e->dEdu[i * nu + j], "dEdu[%d]", i * nu + j);
        add_out(o, &k, e->dEdt[i], "dEdt[%d]", i);
    }
    if (!seeded) {
        Func fj = f_jacobian;
        fj.unused = nu ? NULL : f_jacobian.unused;
        stats[4] = (EmitStats){"jacobian", print_function(&pr, &fj, k, o)};
    }

    stats[5] = (EmitStats){"accel", {0, 0, 0, 0}};
    stats[6] = (EmitStats){"constraint", {0, 0, 0, 0}};
    stats[7] = (EmitStats){"c_levels", {0, 0, 0, 0}};
    stats[8] = (EmitStats){"c_jacobian", {0, 0, 0, 0}};
    stats[9] = (EmitStats){"c_levels_jacobian", {0, 0, 0, 0}};
    stats[10] = (EmitStats){"invariant", {0, 0, 0, 0}};
    if (inv->h != EXPR_NONE) {
        k = 0;
        add_out(o, &k, inv->h, "h[0]");
        stats[10].count = print_function(&pr, &f_invariant, k, o);
    }
    if (c)
        print_constraints(&pr, c, D, stats + 6);
    if (e->acc && !c) {
        fence(&pr, 0);
        k = 0;
        for (int i = 0; i < n; i++)
            add_out(o, &k, e->piv[i], "piv[%d]", i);
        for (int i = 0; i < n; i++)
            add_out(o, &k, e->mkk[i], "mkk[%d]", i);
        for (int i = 0; i < n; i++)
            add_out(o, &k, e->acc[i], "a[%d]", i);
        stats[5].count = print_function(&pr, &f_accel_solve, k, o);
        print_accel(&pr, n);
    }
    free(o);
    fence(&pr, 1);
    print_checks(&pr);
    print_model_struct(&pr, s, e, c, inv, info);
}

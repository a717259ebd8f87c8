/*
 * emit: the C printer.
 *
 * A function body is built from a list of outputs (an expression and the
 * C lvalue it goes to).  We mark what the outputs reach, give each used
 * leaf a named local, walk the marked nodes in id order (a topological
 * order) and print one temporary per operator node, then the
 * assignments.  All cleverness is in the DAG; this is a plain loop.
 */
#include "emit.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

typedef struct Out {
    ExprId e;
    char dest[48];
} Out;

typedef struct Printer {
    FILE *f;
    ExprPool *P;
    const Spec *s;
    char **name; /* per node id: its C spelling once emitted, or NULL */
    unsigned char *mark;
    size_t size;
    unsigned used; /* bit k: source array k (see print_body) is read */
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

/* %.17g round-trips; make sure C reads it as a double, not an int. */
static void
format_const(char *buf, size_t len, double v)
{
    snprintf(buf, len, "%.17g", v);
    if (!strpbrk(buf, ".eEn"))
        strncat(buf, ".0", len - strlen(buf) - 1);
}

static const char *
leaf_name(Printer *pr, const ExprNode *nd, char *buf, size_t len)
{
    static const char prefix[] = {'q', 'v', 'a', 'j'};
    switch (nd->op) {
    case EXPR_VAR:
        snprintf(buf, len, "%c_%s", prefix[nd->b], pr->s->coord[nd->a].name);
        break;
    case EXPR_PARAM:
        snprintf(buf, len, "p_%s", pr->s->param[nd->a].name);
        break;
    case EXPR_INPUT:
        snprintf(buf, len, "u_%s", pr->s->input[nd->a].name);
        break;
    case EXPR_TIME:
        snprintf(buf, len, "t");
        break;
    }
    return buf;
}

/* The spelling of an operand: a name, or a constant (negative ones in
 * parentheses so that `x - -1` never appears). */
static const char *
operand(Printer *pr, ExprId e, char *buf, size_t len)
{
    const ExprNode *nd = expr_node(pr->P, e);
    if (nd->op != EXPR_CONST)
        return pr->name[e];
    char num[40];
    format_const(num, sizeof num, nd->value);
    snprintf(buf, len, nd->value < 0 ? "(%s)" : "%s", num);
    return buf;
}

static void
print_powi(Printer *pr, const char *x, int n, char *rhs, size_t len)
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
print_node(Printer *pr, ExprId id, int *ntemp)
{
    const ExprNode *nd = expr_node(pr->P, id);
    char ba[64], bb[64], rhs[256];
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
            print_powi(pr, x, (int32_t)nd->b, rhs, sizeof rhs);
        else if (nd->op == EXPR_SIGN)
            snprintf(rhs, sizeof rhs, "(double)((%s > 0) - (%s < 0))", x, x);
        else if (ar == 2)
            snprintf(rhs, sizeof rhs, "%s(%s, %s)", sp, x, y);
        else
            snprintf(rhs, sizeof rhs, "%s(%s)", sp, x);
    }
    char name[24];
    snprintf(name, sizeof name, "w%d", (*ntemp)++);
    println(pr, "    const double %s = %s;", name, rhs);
    pr->name[id] = strdup(name);
}

/* Locals for the leaves the outputs use, in a fixed order: t, then
 * coordinates by derivative order, parameters, inputs. */
static void
print_leaves(Printer *pr, const char *const *src)
{
    static const int kinds[] = {EXPR_TIME, EXPR_VAR, EXPR_PARAM, EXPR_INPUT};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++)
        for (size_t id = 0; id < pr->size; id++) {
            const ExprNode *nd = expr_node(pr->P, (ExprId)id);
            if (!pr->mark[id] || nd->op != kinds[k])
                continue;
            char buf[160];
            leaf_name(pr, nd, buf, sizeof buf);
            pr->name[id] = strdup(buf);
            if (nd->op == EXPR_TIME) {
                pr->used |= 1u << 6;
                continue;
            }
            int arr = nd->op == EXPR_VAR ? (int)nd->b
                    : nd->op == EXPR_PARAM ? 4 : 5;
            pr->used |= 1u << arr;
            println(pr, "    const double %s = %s[%u];", buf, src[arr], nd->a);
        }
}

/* Emit the body of one function: locals, temporaries, assignments.
 * `src` names the arguments holding q, v, a, (none), p, u, t; NULL
 * where the function has no such argument. */
static ExprCount
print_body(Printer *pr, int nout, const Out *out, const char *const *src)
{
    pr->used = 0;
    size_t size = expr_pool_size(pr->P);
    pr->size = size;
    pr->mark = calloc(size, 1);
    pr->name = calloc(size, sizeof *pr->name);
    ExprId *roots = malloc((size_t)(nout ? nout : 1) * sizeof *roots);
    for (int i = 0; i < nout; i++)
        roots[i] = out[i].e;
    expr_mark(pr->P, nout, roots, pr->mark);
    print_leaves(pr, src);
    for (int k = 0; k < 7; k++) /* silence -Wunused-parameter */
        if (src[k] && !(pr->used >> k & 1))
            println(pr, "    (void)%s;", src[k]);
    int ntemp = 0;
    for (size_t id = 0; id < size; id++)
        if (pr->mark[id] && expr_op_arity[expr_node(pr->P, (ExprId)id)->op] > 0)
            print_node(pr, (ExprId)id, &ntemp);
    for (int i = 0; i < nout; i++) {
        char buf[64];
        println(pr, "    %s = %s;", out[i].dest, operand(pr, out[i].e, buf, sizeof buf));
    }
    ExprCount c = expr_count_ops(pr->P, nout, roots);
    for (size_t id = 0; id < size; id++)
        free(pr->name[id]);
    free(pr->name);
    free(pr->mark);
    free(roots);
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

static void
print_banner(Printer *pr, const Eom *e, const EmitInfo *info)
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
    println(pr, " */");
    println(pr, "#include <math.h>");
    println(pr, "#include <stddef.h>");
    println(pr, "");
    println(pr, "#include \"eomc_model.h\"");
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

/* `unused`: output arguments nothing is written to, or NULL. */
static ExprCount
print_function(Printer *pr, const char *comment, const char *proto,
               int nout, const Out *out, const char *const src[7],
               const char *unused)
{
    println(pr, "/* %s */", comment);
    println(pr, "static void\n%s_%s\n{", pr->s->name, proto);
    if (unused)
        println(pr, "    %s", unused);
    ExprCount c = print_body(pr, nout, out, src);
    println(pr, "}\n");
    return c;
}

void
emit_model(FILE *f, const Spec *s, const Mech *m, const Eom *e, ExprPool *P,
           Diff *D, const EmitInfo *info, EmitStats stats[EMIT_NFUNCS])
{
    Printer pr = {.f = f, .P = P, .s = s};
    int n = s->nq, nu = s->nu, k = 0, cap = 2 * n * n + n * nu + 4 * n + 2 * nu + 2;
    Out *o = calloc((size_t)cap, sizeof *o);
    (void)m;
    print_banner(&pr, e, info);
    print_tables(&pr);

    for (int i = 0; i < n; i++)
        add_out(o, &k, s->coord[i].q0, "q[%d]", i);
    for (int i = 0; i < n; i++)
        add_out(o, &k, s->coord[i].v0, "v[%d]", i);
    stats[0].function = "initial";
    stats[0].count = print_function(&pr, "Initial state from the spec's `initial`.",
        "initial(const double *p, double *q, double *v)", k, o,
        (const char *const[7]){NULL, NULL, NULL, NULL, "p", NULL, NULL}, NULL);

    k = 0;
    for (int i = 0; i < nu; i++)
        add_out(o, &k, s->input[i].expr, "u[%d]", i);
    for (int i = 0; i < nu; i++)
        add_out(o, &k, diff_time(D, s->input[i].expr), "if (dudt) dudt[%d]", i);
    stats[1].function = "inputs";
    stats[1].count = print_function(&pr, "Input signals u(t) and du/dt.",
        "inputs(double t, const double *p, double *u, double *dudt)", k, o,
        (const char *const[7]){NULL, NULL, NULL, NULL, "p", NULL, "t"},
        nu ? NULL : "(void)u;\n    (void)dudt;");

    k = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j <= i; j++)
            add_out(o, &k, e->M[i * n + j], "M[%d]", i * n + j);
    for (int i = 0; i < n; i++)
        add_out(o, &k, e->h[i], "h[%d]", i);
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            add_out(o, &k, e->M[i * n + j], "M[%d]", i * n + j);
    stats[2].function = "mass_bias";
    stats[2].count = print_function(&pr,
        "Mass matrix M = dE/dq'' (row-major, symmetric) and bias h = E(q'' = 0).",
        "mass_bias(double t, const double *q, const double *v, const double *p,\n"
        "    const double *u, double *M, double *h)", k, o,
        (const char *const[7]){"q", "v", NULL, NULL, "p", "u", "t"}, NULL);

    k = 0;
    add_out(o, &k, m->T, "TV[0]");
    add_out(o, &k, m->V, "TV[1]");
    stats[3].function = "energy";
    stats[3].count = print_function(&pr, "Kinetic energy T and potential energy V.",
        "energy(double t, const double *q, const double *v, const double *p,\n"
        "    const double *u, double *TV)", k, o,
        (const char *const[7]){"q", "v", NULL, NULL, "p", "u", "t"}, NULL);

    k = 0;
    for (int i = 0; i < n * n; i++)
        add_out(o, &k, e->dEdq[i], "dEdq[%d]", i);
    for (int i = 0; i < n * n; i++)
        add_out(o, &k, e->dEdv[i], "dEdv[%d]", i);
    for (int i = 0; i < n * nu; i++)
        add_out(o, &k, e->dEdu[i], "dEdu[%d]", i);
    for (int i = 0; i < n; i++)
        add_out(o, &k, e->dEdt[i], "dEdt[%d]", i);
    stats[4].function = "jacobian";
    stats[4].count = print_function(&pr,
        "Partial derivatives of the residual E(t, q, q', q'') with u held fixed.",
        "jacobian(double t, const double *q, const double *v, const double *a,\n"
        "    const double *p, const double *u, double *dEdq, double *dEdv,\n"
        "    double *dEdu, double *dEdt)", k, o,
        (const char *const[7]){"q", "v", "a", NULL, "p", "u", "t"},
        nu ? NULL : "(void)dEdu;");
    free(o);

    const char *nm = s->name;
    println(&pr, "const eomc_model %s_model = {", nm);
    println(&pr, "    EOMC_ABI_VERSION, \"%s\", \"%s\", \"%s\", \"%s\",", nm,
            base_name(s->path), e->form->name, info->options);
    println(&pr, "    %d, %d, %d, q_names, p_names, u_names, p_default,", n, s->np, nu);
    char a[40], b[40], c[40], d[40], h[40];
    format_const(a, sizeof a, s->scene.t_end);
    format_const(b, sizeof b, s->scene.dt);
    format_const(c, sizeof c, s->scene.rtol);
    format_const(d, sizeof d, s->scene.atol);
    format_const(h, sizeof h, s->scene.h_fixed);
    println(&pr, "    %s, %s, \"%s\", %s, %s, %s,", a, b, s->scene.method, c, d, h);
    println(&pr, "    %s_initial, %s_inputs, %s_mass_bias, %s_energy, %s_jacobian,",
            nm, nm, nm, nm, nm);
    println(&pr, "};");
    println(&pr, "");
    println(&pr, "#ifdef EOMC_MAIN");
    println(&pr, "#include \"eomc.h\"");
    println(&pr, "int main(int argc, char **argv) { return eomc_main(argc, argv, &%s_model); }", nm);
    println(&pr, "#endif");
}

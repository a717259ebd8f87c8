/*
 * cli: the command line of a standalone simulator (eomc_main).
 *
 * Options are read completely and checked before anything runs, so a
 * mistake costs nothing but a message (exit status 2).  Parameters are set
 * before the initial state is computed (it may depend on them), and --init
 * overrides that state afterwards, whatever the order on the line.
 */
#include "eomc.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#ifndef EOMC_VERSION
#define EOMC_VERSION "unknown"
#endif

typedef struct Cli {
    const char *prog;
    eomc_run_opts run;
    const char *out;
    int stats, summary, accel, assemble;
    int stabilize;        /* EOMC_STABILIZE_... */
    double alpha, beta;   /* Baumgarte's rates */
    int rates_given;
    char **set, **init; /* NAME=VALUE arguments, in order */
    int nset, ninit;
} Cli;

typedef struct Csv {
    FILE *f;
    eomc_sim *sim;
    long rows;
    double E0, dE; /* first energy, largest change seen */
    double *res;   /* [nc] constraint residuals of a row */
    double res_max; /* the largest |residual| written */
} Csv;

/* ---- messages ---- */

static int
usage(const Cli *c, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "%s: ", c->prog);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(see %s --help)\n", c->prog);
    return EOMC_EUSAGE;
}

static size_t
edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b), row[64];
    if (lb >= 64)
        return (size_t)-1;
    for (size_t j = 0; j <= lb; j++)
        row[j] = j;
    for (size_t i = 1; i <= la; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; j++) {
            size_t up = row[j], best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best)
                best = up + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

/* " (did you mean 'x'?)" for the nearest of names[0..n) (suffixed), or "". */
static const char *
nearest(const char *word, const char *const *names, int n, const char *suffix)
{
    static char buf[160];
    size_t best = (size_t)-1, limit = strlen(word) / 3 + 1;
    buf[0] = '\0';
    for (int k = 0; k < n; k++) {
        char cand[128];
        snprintf(cand, sizeof cand, "%s%s", names[k], suffix);
        size_t d = edit_distance(word, cand);
        if (d <= limit && d < best) {
            best = d;
            snprintf(buf, sizeof buf, " (did you mean '%s'?)", cand);
        }
    }
    return buf;
}

static void
list_names(FILE *f, const char *const *names, int n, const char *suffix)
{
    for (int k = 0; k < n; k++)
        fprintf(f, "%s%s%s", k ? ", " : "", names[k], suffix);
}

/* ---- options ---- */

static const char *const option_names[] = {
    "--t-end", "--dt", "--method", "--rtol", "--atol", "--fixed-step",
    "--max-steps", "--set", "--init", "-o", "--stabilize", "--baumgarte", "--stats",
    "--summary", "--accel", "--assemble", "--help", "--version",
};
enum { NOPTIONS = sizeof option_names / sizeof option_names[0], FIRST_FLAG = 12 };
static const char *const stabilize_names[] = {"none", "baumgarte", "project"};
/* Baumgarte's rates when --baumgarte is not given (1/time units). */
#define DEFAULT_RATE 10.0

static void
help(const Cli *c, const eomc_model *m)
{
    printf("usage: %s [OPTION]...\n"
           "Simulate %s (%s, %s form%s%s) and write the trajectory as CSV:\n"
           "t, each coordinate, each velocity (name'), T, V and E = T + V.\n\n",
           c->prog, m->name, m->spec, m->form, *m->options ? ", " : "", m->options);
    printf("  --t-end T          end time (default %g)\n"
           "  --dt T             output interval (default %g)\n"
           "  --method NAME      GSL odeiv2 stepper (default %s): ",
           m->t_end, m->dt, m->method);
    for (int k = 0; eomc_methods[k]; k++)
        printf("%s%s", k ? ", " : "", eomc_methods[k]);
    printf("\n  --rtol X, --atol X adaptive tolerances (default %g, %g)\n"
           "  --fixed-step H     fixed steps of at most H, evenly dividing dt\n"
           "  --max-steps N      fail after N steps\n"
           "  --set NAME=VALUE   a parameter, or an input held constant\n"
           "  --init NAME=VALUE  initial coordinate NAME or velocity NAME'\n"
           "  -o FILE            write the CSV to FILE instead of stdout\n",
           m->rtol, m->atol);
    if (m->nc > 0)
        printf("  --stabilize NAME   drift control: none (default), baumgarte, project\n"
               "  --baumgarte A,B    Baumgarte's rates: g'' + 2A g' + B^2 g = 0, "
               "phi' + A phi = 0\n"
               "                     (default %g,%g; implies --stabilize baumgarte)\n"
               "  --assemble         project the initial state onto the constraints "
               "first\n", DEFAULT_RATE, DEFAULT_RATE);
    printf("  --stats            integrator statistics on stderr\n"
           "  --summary          a paragraph about the run on stderr\n"
           "  --accel            print q'' at the initial state and exit\n"
           "  --help, --version\n\n");
    printf("coordinates: ");
    list_names(stdout, m->q_names, m->nq, "");
    printf("\nparameters: ");
    for (int k = 0; k < m->np; k++)
        printf("%s%s=%g", k ? ", " : "", m->p_names[k], m->p_default[k]);
    printf("\ninputs: ");
    list_names(stdout, m->u_names, m->nu, "");
    printf("%s\nExit status: 0 done, 2 usage error, 3 numerical failure (the rows "
           "computed so far are kept).\n", m->nu ? "" : "(none)");
}

/* The whole string as a finite number. */
static int
number(const char *s, double *x)
{
    char *end;
    *x = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*x);
}

static int
real_option(Cli *c, const char *opt, const char *val, double *x, double lo, int open)
{
    if (!number(val, x))
        return usage(c, "%s: '%s' is not a finite number", opt, val);
    if (open ? !(*x > lo) : !(*x >= lo))
        return usage(c, "%s: %s is out of range (must be %s %g)", opt, val,
                     open ? ">" : ">=", lo);
    return EOMC_OK;
}

static int
take_value(Cli *c, int k, const char *val)
{
    eomc_run_opts *r = &c->run;
    const char *opt = option_names[k];
    double x;
    switch (k) {
    case 0: return real_option(c, opt, val, &r->t_end, 0, 0);
    case 1: return real_option(c, opt, val, &r->dt, 0, 1);
    case 2:
        for (int j = 0; eomc_methods[j]; j++)
            if (strcmp(val, eomc_methods[j]) == 0) {
                r->method = eomc_methods[j];
                return EOMC_OK;
            }
        {
            int n = 0;
            while (eomc_methods[n])
                n++;
            fprintf(stderr, "%s: --method: unknown method '%s'%s; methods: ", c->prog,
                    val, nearest(val, eomc_methods, n, ""));
            list_names(stderr, eomc_methods, n, "");
            fprintf(stderr, "\n");
        }
        return EOMC_EUSAGE;
    case 3: return real_option(c, opt, val, &r->rtol, 0, 0);
    case 4: return real_option(c, opt, val, &r->atol, 0, 0);
    case 5: return real_option(c, opt, val, &r->h_fixed, 0, 1);
    case 6:
        if (real_option(c, opt, val, &x, 1, 0) || x != floor(x) || x > 1e15)
            return usage(c, "%s: '%s' is not a whole number of steps", opt, val);
        r->max_steps = (long)x;
        return EOMC_OK;
    case 7: c->set[c->nset++] = (char *)val; return EOMC_OK;
    case 8: c->init[c->ninit++] = (char *)val; return EOMC_OK;
    case 9: c->out = val; return EOMC_OK;
    case 10:
        for (int j = 0; j < 3; j++)
            if (strcmp(val, stabilize_names[j]) == 0) {
                c->stabilize = j;
                return EOMC_OK;
            }
        return usage(c, "--stabilize: unknown method '%s'%s; methods: none, baumgarte, "
                     "project", val, nearest(val, stabilize_names, 3, ""));
    case 11: {
        char *comma = strchr(val, ','), *a = strndup(val, comma ? (size_t)(comma - val) : 0);
        int bad = !comma || !a || !number(a, &c->alpha) || !number(comma + 1, &c->beta);
        free(a);
        if (bad)
            return usage(c, "--baumgarte: expected ALPHA,BETA (two numbers), not '%s'", val);
        if (c->alpha < 0 || c->beta < 0)
            return usage(c, "--baumgarte: %s is out of range (the rates must be >= 0)",
                         val);
        c->rates_given = 1;
        return EOMC_OK;
    }
    }
    return EOMC_OK;
}

static int
find_option(const char *arg, size_t len)
{
    for (int k = 0; k < NOPTIONS; k++)
        if (strlen(option_names[k]) == len && strncmp(arg, option_names[k], len) == 0)
            return k;
    return -1;
}

/* Returns EOMC_OK, EOMC_EUSAGE, or -1 when --help or --version was handled. */
static int
parse_args(Cli *c, int argc, char **argv, const eomc_model *m)
{
    for (int i = 1; i < argc; i++) {
        const char *arg = argv[i], *eq = strchr(arg, '='), *val = NULL;
        size_t len = eq && arg[0] == '-' ? (size_t)(eq - arg) : strlen(arg);
        int k = find_option(arg, len);
        if (k < 0) {
            char name[128];
            snprintf(name, sizeof name, "%.*s", (int)(len < 100 ? len : 100), arg);
            if (arg[0] != '-')
                return usage(c, "unexpected argument '%s' (options start with --)", arg);
            return usage(c, "unknown option '%s'%s", name,
                         nearest(name, option_names, NOPTIONS, ""));
        }
        if (k >= FIRST_FLAG) {
            if (eq)
                return usage(c, "%s takes no value", option_names[k]);
            if (k == FIRST_FLAG + 4) {
                help(c, m);
                return -1;
            }
            if (k == FIRST_FLAG + 5) {
                printf("%s: model %s from %s, %s form%s%s; eomc runtime %s\n", c->prog,
                       m->name, m->spec, m->form, *m->options ? ", " : "", m->options,
                       EOMC_VERSION);
                return -1;
            }
            int *flag[] = {&c->stats, &c->summary, &c->accel, &c->assemble};
            *flag[k - FIRST_FLAG] = 1;
            continue;
        }
        if (eq)
            val = eq + 1;
        else if (i + 1 < argc)
            val = argv[++i];
        else
            return usage(c, "%s needs a value", option_names[k]);
        int rc = take_value(c, k, val);
        if (rc)
            return rc;
    }
    if (c->rates_given && c->stabilize < 0)
        c->stabilize = EOMC_STABILIZE_BAUMGARTE;
    if (c->rates_given && c->stabilize != EOMC_STABILIZE_BAUMGARTE)
        return usage(c, "--baumgarte gives the rates of --stabilize baumgarte, not of "
                     "--stabilize %s", stabilize_names[c->stabilize]);
    if (c->stabilize < 0)
        c->stabilize = EOMC_STABILIZE_NONE;
    return EOMC_OK;
}

/* NAME=VALUE split; *name is a copy to free. */
static int
name_value(Cli *c, const char *opt, const char *arg, char **name, double *x)
{
    const char *eq = strchr(arg, '=');
    if (!eq || eq == arg)
        return usage(c, "%s: expected NAME=VALUE, not '%s'", opt, arg);
    if (!number(eq + 1, x))
        return usage(c, "%s %s: '%s' is not a finite number", opt, arg, eq + 1);
    *name = strndup(arg, (size_t)(eq - arg));
    return EOMC_OK;
}

static int
apply_sets(Cli *c, eomc_sim *sim)
{
    const eomc_model *m = eomc_sim_model(sim);
    for (int k = 0; k < c->nset; k++) {
        char *name;
        double x;
        if (name_value(c, "--set", c->set[k], &name, &x))
            return EOMC_EUSAGE;
        if (eomc_sim_set(sim, name, x) != EOMC_OK) {
            const char *hint = nearest(name, m->p_names, m->np, "");
            if (!*hint)
                hint = nearest(name, m->u_names, m->nu, "");
            fprintf(stderr, "%s: --set: '%s' is not a parameter or input%s; "
                    "parameters: ", c->prog, name, hint);
            list_names(stderr, m->p_names, m->np, "");
            fprintf(stderr, m->nu ? "; inputs: " : "; no inputs");
            list_names(stderr, m->u_names, m->nu, "");
            fprintf(stderr, "\n");
            free(name);
            return EOMC_EUSAGE;
        }
        free(name);
    }
    return EOMC_OK;
}

static int
apply_inits(Cli *c, const eomc_model *m, double *x)
{
    int n = m->nq;
    for (int k = 0; k < c->ninit; k++) {
        char *name;
        double val;
        if (name_value(c, "--init", c->init[k], &name, &val))
            return EOMC_EUSAGE;
        size_t len = strlen(name);
        int vel = len > 1 && name[len - 1] == '\'', found = -1;
        if (vel)
            name[len - 1] = '\0';
        for (int i = 0; i < n && found < 0; i++)
            if (strcmp(name, m->q_names[i]) == 0)
                found = i;
        if (found < 0) {
            if (vel)
                name[len - 1] = '\'';
            const char *hint = nearest(name, m->q_names, n, vel ? "'" : "");
            fprintf(stderr, "%s: --init: '%s' is not a coordinate or velocity%s; "
                    "valid names: ", c->prog, name, hint);
            list_names(stderr, m->q_names, n, "");
            fprintf(stderr, ", ");
            list_names(stderr, m->q_names, n, "'");
            fprintf(stderr, "\n");
            free(name);
            return EOMC_EUSAGE;
        }
        x[found + (vel ? n : 0)] = val;
        free(name);
    }
    return EOMC_OK;
}

/* ---- output ---- */

static void
print_header(FILE *f, const eomc_model *m)
{
    fprintf(f, "t");
    for (int i = 0; i < m->nq; i++)
        fprintf(f, ",%s", m->q_names[i]);
    for (int i = 0; i < m->nq; i++)
        fprintf(f, ",%s'", m->q_names[i]);
    fprintf(f, ",T,V,E");
    for (int k = 0; k < m->nc; k++)
        fprintf(f, ",lambda[%s]", m->c_names[k]);
    for (int k = 0; k < m->nc; k++)
        fprintf(f, ",res[%s]", m->c_names[k]);
    fprintf(f, "\n");
}

static int
write_row(void *ctx, double t, const double *x)
{
    Csv *w = ctx;
    const eomc_model *m = eomc_sim_model(w->sim);
    int n = m->nq, nc = m->nc;
    if (nc > 0 && eomc_sim_residuals(w->sim, t, x, x + n, w->res) != EOMC_OK)
        return EOMC_ENUMERIC;
    double T, V;
    eomc_sim_energy(w->sim, t, x, x + n, &T, &V);
    double E = T + V;
    if (w->rows == 0)
        w->E0 = E;
    else if (fabs(E - w->E0) > w->dE)
        w->dE = fabs(E - w->E0);
    fprintf(w->f, "%.17g", t);
    for (int i = 0; i < 2 * n; i++)
        fprintf(w->f, ",%.17g", x[i]);
    fprintf(w->f, ",%.17g,%.17g,%.17g", T, V, E);
    const double *lam = eomc_sim_multipliers(w->sim);
    for (int k = 0; k < nc; k++)
        fprintf(w->f, ",%.17g", lam[k]);
    for (int k = 0; k < nc; k++) {
        fprintf(w->f, ",%.17g", w->res[k]);
        w->res_max = fmax(w->res_max, fabs(w->res[k]));
    }
    fputc('\n', w->f);
    w->rows++;
    return EOMC_OK;
}

static void
print_stats(const eomc_stats *st)
{
    fprintf(stderr, "steps %ld\nrejected %ld\nrhs_evals %ld\njac_evals %ld\n"
            "cpu_seconds %.6f\n", st->steps, st->rejected, st->rhs_evals,
            st->jac_evals, st->cpu_seconds);
    if (st->h_used > 0)
        fprintf(stderr, "h_used %.17g\n", st->h_used);
}

/* Print words wrapped at 72 columns. */
static void
wrap(FILE *f, char *text)
{
    int col = 0;
    for (char *save = NULL, *w = strtok_r(text, " ", &save); w;
         w = strtok_r(NULL, " ", &save)) {
        int len = (int)strlen(w);
        if (col && col + 1 + len > 72) {
            fputc('\n', f);
            col = 0;
        } else if (col) {
            fputc(' ', f);
            col++;
        }
        fputs(w, f);
        col += len;
    }
    fputc('\n', f);
}

static void
print_summary(const Cli *c, const eomc_model *m, const Csv *w, const eomc_stats *st)
{
    char text[4096];
    size_t len = 0, cap = sizeof text;
#define ADD(...) (len += len < cap ? (size_t)snprintf(text + len, cap - len, __VA_ARGS__) : 0)
    ADD("%s: %d coordinate%s (", m->name, m->nq, m->nq == 1 ? "" : "s");
    for (int i = 0; i < m->nq && i < 8; i++)
        ADD("%s%s", i ? ", " : "", m->q_names[i]);
    ADD("%s), equations in %s form from %s. ", m->nq > 8 ? ", ..." : "", m->form,
        m->spec);
    ADD("Integrated from t = %g to %g with %s", c->run.t0, c->run.t_end, c->run.method);
    if (c->run.h_fixed > 0)
        ADD(" in fixed steps of %g: ", st->h_used);
    else
        ADD(" (rtol %g, atol %g): ", c->run.rtol, c->run.atol);
    ADD("%ld steps (%ld rejected), %ld right-hand sides and %ld Jacobians in %.3g s "
        "of CPU time. ", st->steps, st->rejected, st->rhs_evals, st->jac_evals,
        st->cpu_seconds);
    ADD("Wrote %ld rows every %g to %s. ", w->rows, c->run.dt, c->out ? c->out : "stdout");
    ADD("Energy E = T + V started at %.10g; its largest change was %.3g (%.3g relative).",
        w->E0, w->dE, w->dE / fmax(fabs(w->E0), 1e-300));
    if (m->nc > 0)
        ADD(" The largest constraint residual was %.3g", fmax(st->max_residual, w->res_max));
    if (m->nc > 0 && c->stabilize == EOMC_STABILIZE_PROJECT)
        ADD(" with projection after every step (%.3g before it).", st->max_drift);
    else if (m->nc > 0 && c->stabilize == EOMC_STABILIZE_BAUMGARTE)
        ADD(" with Baumgarte's stabilization (rates %g, %g).", c->alpha, c->beta);
    else if (m->nc > 0)
        ADD(", without stabilization.");
#undef ADD
    wrap(stderr, text);
}

/* ---- main ---- */

/* Whether the model has a constraint below acceleration level. */
static int
has_levels(const eomc_model *m)
{
    for (int k = 0; k < m->nc; k++)
        if (m->c_order[k] <= 1)
            return 1;
    return 0;
}

static int
set_stabilize(Cli *c, eomc_sim *sim)
{
    if (c->stabilize == EOMC_STABILIZE_NONE ||
        eomc_sim_stabilize(sim, c->stabilize, c->alpha, c->beta) == EOMC_OK)
        return EOMC_OK;
    return usage(c, "--stabilize %s: %s", stabilize_names[c->stabilize],
                 eomc_sim_error(sim));
}

/* Project the initial state onto the constraints and say what moved. */
static int
assemble(Cli *c, eomc_sim *sim, double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    int n = m->nq, moved = 0;
    if (!has_levels(m))
        return usage(c, "--assemble: %s has no holonomic or first-order constraint to "
                     "assemble", m->name);
    double *x0 = malloc(2 * (size_t)n * sizeof *x0);
    if (!x0)
        return usage(c, "out of memory");
    memcpy(x0, x, 2 * (size_t)n * sizeof *x0);
    int rc = eomc_sim_project(sim, c->run.t0, x, x + n);
    if (rc != EOMC_OK) {
        fprintf(stderr, "%s: error: --assemble: %s\n", c->prog, eomc_sim_error(sim));
        free(x0);
        return rc;
    }
    for (int i = 0; i < 2 * n; i++)
        if (x[i] != x0[i]) {
            if (!moved++)
                fprintf(stderr, "%s: --assemble moved the initial state onto the "
                        "constraints:\n", c->prog);
            fprintf(stderr, "  %s%s %.17g -> %.17g (%+.3g)\n", m->q_names[i % n],
                    i < n ? "" : "'", x0[i], x[i], x[i] - x0[i]);
        }
    if (!moved)
        fprintf(stderr, "%s: --assemble: the initial state already satisfies the "
                "constraints\n", c->prog);
    free(x0);
    return EOMC_OK;
}

static int
print_accel(Cli *c, eomc_sim *sim, const double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    double *a = calloc((size_t)m->nq, sizeof *a);
    int rc = eomc_sim_accel(sim, c->run.t0, x, x + m->nq, a);
    if (rc == EOMC_OK) {
        for (int i = 0; i < m->nq; i++)
            printf("%s'' %.17g\n", m->q_names[i], a[i]);
        for (int k = 0; k < m->nc; k++)
            printf("lambda[%s] %.17g\n", m->c_names[k], eomc_sim_multipliers(sim)[k]);
    } else
        fprintf(stderr, "%s: error: %s\n", c->prog, eomc_sim_error(sim));
    free(a);
    return rc;
}

/* A start off the constraints is allowed (the drift then starts there),
 * but rarely meant: say so, once, before integrating. */
#define INCONSISTENT_TOL 1e-8

static void
check_consistent(const Cli *c, eomc_sim *sim, const double *x, double *res)
{
    const eomc_model *m = eomc_sim_model(sim);
    if (!has_levels(m) || eomc_sim_residuals(sim, c->run.t0, x, x + m->nq, res) != EOMC_OK)
        return; /* a failure here is reported by the integration */
    for (int k = 0; k < m->nc; k++)
        if (m->c_order[k] <= 1 && !(fabs(res[k]) <= INCONSISTENT_TOL)) {
            fprintf(stderr, "%s: warning: the initial state violates the constraint %s "
                    "by %.3g (--assemble projects it onto the constraints)\n", c->prog,
                    m->c_names[k], res[k]);
            return;
        }
}

static int
simulate(Cli *c, eomc_sim *sim, double *x)
{
    const eomc_model *m = eomc_sim_model(sim);
    Csv w = {stdout, sim, 0, 0, 0, calloc((size_t)m->nc + 1, sizeof(double)), 0};
    check_consistent(c, sim, x, w.res);
    if (c->out && !(w.f = fopen(c->out, "w"))) {
        fprintf(stderr, "%s: -o: cannot write '%s'\n", c->prog, c->out);
        free(w.res);
        return EOMC_EUSAGE;
    }
    print_header(w.f, m);
    eomc_stats st;
    c->run.progress = 1;
    int rc = eomc_sim_integrate(sim, &c->run, x, write_row, &w, &st);
    if (fflush(w.f) != 0 || ferror(w.f)) {
        fprintf(stderr, "%s: error writing %s\n", c->prog, c->out ? c->out : "stdout");
        rc = rc ? rc : EOMC_ENUMERIC;
    }
    if (w.f != stdout)
        fclose(w.f);
    if (rc)
        fprintf(stderr, "%s: error: %s\n", c->prog, eomc_sim_error(sim));
    if (rc == EOMC_ENUMERIC)
        fprintf(stderr, "%s: the %ld rows computed up to then are kept\n", c->prog,
                w.rows);
    if (c->stats) {
        print_stats(&st);
        if (m->nc > 0)
            fprintf(stderr, "max_residual %.3g\n", fmax(st.max_residual, w.res_max));
        if (c->stabilize == EOMC_STABILIZE_PROJECT)
            fprintf(stderr, "max_drift %.3g\n", st.max_drift);
    }
    if (c->summary && !rc)
        print_summary(c, m, &w, &st);
    free(w.res);
    return rc;
}

int
eomc_main(int argc, char **argv, const eomc_model *m, const eomc_model_ext *ext)
{
    (void)ext;
    const char *slash = argc > 0 ? strrchr(argv[0], '/') : NULL;
    Cli c = {0};
    c.stabilize = -1;
    c.alpha = c.beta = DEFAULT_RATE;
    c.prog = argc > 0 ? (slash ? slash + 1 : argv[0]) : m->name;
    c.run = eomc_run_defaults(m);
    c.set = calloc((size_t)argc + 1, sizeof *c.set);
    c.init = calloc((size_t)argc + 1, sizeof *c.init);
    eomc_sim *sim = eomc_sim_alloc(m);
    double *x = calloc(2 * (size_t)m->nq + 1, sizeof *x);
    int rc;
    if (!sim || !c.set || !c.init || !x) {
        fprintf(stderr, "%s: out of memory, or a model built for another runtime\n",
                c.prog);
        rc = EOMC_EUSAGE;
    } else if ((rc = parse_args(&c, argc, argv, m)) != EOMC_OK) {
        rc = rc < 0 ? EOMC_OK : rc;
    } else if ((rc = apply_sets(&c, sim)) == EOMC_OK &&
               (rc = set_stabilize(&c, sim)) == EOMC_OK) {
        eomc_sim_initial(sim, x, x + m->nq);
        if ((rc = apply_inits(&c, m, x)) == EOMC_OK &&
            (rc = c.assemble ? assemble(&c, sim, x) : EOMC_OK) == EOMC_OK)
            rc = c.accel ? print_accel(&c, sim, x) : simulate(&c, sim, x);
    }
    eomc_sim_free(sim);
    free(x);
    free(c.set);
    free(c.init);
    return rc;
}

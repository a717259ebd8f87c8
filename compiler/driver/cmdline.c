/*
 * cmdline: eomc's command line (cmdline.h).
 */
#include "cmdline.h"
#include "base/arena.h"
#include "config.h" /* EOMC_VERSION */
#include "base/diag.h"
#include "lower/lower.h"
#include "forms/forms.h"

#include <stddef.h> /* offsetof */
#include <stdlib.h>
#include <string.h>

void
cmdline_usage(FILE *f)
{
    fputs(
        "usage: eomc compile SPEC [-o FILE.c] [--scene NAME] [--fix NAME=VALUE] [--form NAME]\n"
        "                    [--effects LIST] [--stats] [--explain]\n"
        "       eomc build SPEC [-o EXE] [--mpi | --shared] [--extended] [--portable] [--cache]\n"
        "                  [the same]\n"
        "       eomc run SPEC [the same] [SIMULATOR OPTIONS]\n"
        "       eomc accuracy SPEC [the same] [SIMULATOR OPTIONS]\n"
        "       eomc import MODEL.xml [-o SPEC.yaml] [--strict] [--floating]\n"
        "                   [--joint-inputs] [--parameters]  (MJCF or URDF, read by MuJoCo)\n"
        "  (compile, build, run and accuracy also take MODEL.xml or MODEL.urdf as SPEC)\n"
        "       eomc --help | --version\n"
        "\n"
        "  --scene NAME     which of the spec's `scenes:` to compile (default: the first)\n"
        "  --fix NAME=VALUE make a parameter a constant of the generated code, folded\n"
        "                   into it (repeatable, or NAME=VALUE,NAME=VALUE; on top of\n"
        "                   the scene's `fix:`); the simulator's --set refuses it then\n"
        "  --mpi            (build) with mpicc, for sweeps over the ranks of an MPI\n"
        "                   job: mpirun -n K EXE --sweep ... (OpenMPI: libopenmpi-dev)\n"
        "  --shared         (build) a shared library of the model and the runtime\n"
        "                   (default -o libSPEC.so), which the Python package loads;\n"
        "                   with the Jacobian (--jacobian auto) unless told none\n"
        "  --portable       (build, run) compile the model for any CPU of this kind, not\n"
        "                   for this one's instruction set (-march=native, the default\n"
        "                   on x86-64 and arm64, which leaves every result the same to\n"
        "                   the bit: -ffp-contract=off); --mpi implies it\n"
        "  --cache          (build) into eomc's cache, as run does (nothing is built\n"
        "                   when an identical build is there); prints its path\n"
        "  --taylor         the series of Taylor's method (--method taylor), also when\n"
        "                   the scene's method is another; done anyway for a library\n"
        "                   (--shared) and when eomc run/accuracy is asked for taylor\n"
        "  --extended       (build) also compile the model in extended precision, so\n"
        "                   that the simulator computes its own reference solution\n"
        "                   (--error, --work-precision, --reference-out,\n"
        "                   --accel-extended).  Done\n"
        "                   anyway for a model whose functions are one translation\n"
        "                   unit; a large one (two) gets it only so, or when eomc\n"
        "                   run/accuracy is asked for a reference\n",
        f);
    /* two strings: one would pass the 4095 characters C99 promises */
    fprintf(f,
        "  --form NAME      equation form: %s;\n"
        "                   default: the cheapest that applies (fewest operations\n"
        "                   per right-hand side; --explain says which and why)\n"
        "  --effects LIST   comma-separated effects to turn on, replacing the\n"
        "                   scene's choice (\"\" = none)\n"
        "  --floating       (a URDF given as SPEC, and import) give the URDF's root\n"
        "                   link a free joint: MuJoCo welds it to the world\n"
        "  --strict         (import) what eomc drops from the model is an error\n"
        "  --joint-inputs   (an MJCF given as SPEC, and import) an input tau_J on each\n"
        "                   joint, as a URDF's joints always have\n"
        "  --parameters     (a model given as SPEC, and import) masses, inertias,\n"
        "                   damping, stiffness and armature as named parameters\n"
        "  --stats          print the operation counts of each emitted function\n"
        "  --explain        (compile) say how the model was classified and derived,\n"
        "                   on stdout; the C goes only to -o FILE then\n"
        "  --eliminate      eliminate the constraints (C^T E = 0, f = 0) instead of\n"
        "                   using multipliers; --form maggi is lagrange with it\n"
        "  --jacobian HOW   auto (default), unrolled, seeded or none: how the\n"
        "                   Jacobian of the equations is printed.  auto: unrolled\n"
        "                   for a small model; for a large one seeded if the\n"
        "                   scene's method is implicit (or eomc run/accuracy is\n"
        "                   asked for one, or for --linearize), else none\n"
        "  --code HOW       auto (default), straight or tables: how the\n"
        "                   articulated-body form's accelerations and mass matrix\n"
        "                   are written: straight-line code (fastest to run), or\n"
        "                   loops over the model's tables (fast to compile).\n"
        "                   auto: tables past %d operations of straight-line solve,\n"
        "                   bias and energies\n"
        "  --branches HOW   lazy (default) or eager: whether what only one branch\n"
        "                   of a switched expression needs (a contact's force\n"
        "                   while its shapes are apart) is computed only in that\n"
        "                   mode, or always (branch-free code; the same values)\n"
        "Simulator options (eomc run, and built executables): see `EXE --help`.\n"
        "eomc accuracy runs the simulator's --work-precision report: every method\n"
        "over tolerances and fixed steps, CPU time against the error measured on a\n"
        "reference solution (--methods, --tolerances, --steps, --csv, --plot,\n"
        "--target; see `EXE --help`).\n",
        form_names(), LOWER_TABLES_MIN);
}

_Noreturn void
cmdline_usage_error(const char *fmt, const char *arg)
{
    fprintf(stderr, "eomc: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n(see eomc --help)\n");
    exit(EXIT_USAGE);
}

/* The commands, a bit each, for the commands that take an option. */
enum {
    CMD_COMPILE = 1,
    CMD_BUILD = 2,
    CMD_RUN = 4,
    CMD_ACCURACY = 8,
    CMD_DERIVE = CMD_COMPILE | CMD_BUILD | CMD_RUN | CMD_ACCURACY,
};

/* eomc's own options of compile, build, run and accuracy: one table, for
 * the parse, the checks and the messages (cmdline_usage() is their help).  What
 * run and accuracy do not take, after the spec, is the simulator's. */
typedef struct OptionSpec {
    const char *name;
    int cmds; /* the commands that take it */
    enum { OPT_VALUE, OPT_LIST, OPT_FLAG } kind;
    size_t field;     /* offsetof(Options, ...): const char *, char * (LIST) or int */
    const char *what; /* a flag of one command: what it asks for there */
    const char *const *values; /* a VALUE from a fixed set: the set, NULL-ended */
    int sim_after;    /* once the simulator's options began, it is theirs */
} OptionSpec;

/* --jacobian's and --code's values, in lower.h's order of their modes */
static const char *const jacobian_modes[] = {"auto", "unrolled", "seeded", "none", NULL};
static const char *const code_modes[] = {"auto", "straight", "tables", NULL};
static const char *const branch_modes[] = {"lazy", "eager", NULL};

static const OptionSpec options[] = {
    {"-o", CMD_COMPILE | CMD_BUILD, OPT_VALUE, offsetof(Options, out), NULL, NULL, 0},
    {"--form", CMD_DERIVE, OPT_VALUE, offsetof(Options, form), NULL, NULL, 0},
    {"--effects", CMD_DERIVE, OPT_VALUE, offsetof(Options, effects), NULL, NULL, 0},
    {"--jacobian", CMD_DERIVE, OPT_VALUE, offsetof(Options, jacobian), NULL, jacobian_modes, 0},
    {"--scene", CMD_DERIVE, OPT_VALUE, offsetof(Options, scene), NULL, NULL, 0},
    {"--code", CMD_DERIVE, OPT_VALUE, offsetof(Options, code), NULL, code_modes, 0},
    {"--branches", CMD_DERIVE, OPT_VALUE, offsetof(Options, branches), NULL, branch_modes, 0},
    {"--fix", CMD_DERIVE, OPT_LIST, offsetof(Options, fix), NULL, NULL, 0},
    {"--stats", CMD_COMPILE, OPT_FLAG, offsetof(Options, stats),
     "the operation counts of the generated functions", NULL, 0},
    {"--explain", CMD_COMPILE, OPT_FLAG, offsetof(Options, explain),
     "what eomc made of the spec", NULL, 0},
    {"--mpi", CMD_BUILD, OPT_FLAG, offsetof(Options, mpi), "a simulator for MPI sweeps", NULL, 0},
    {"--taylor", CMD_DERIVE, OPT_FLAG, offsetof(Options, taylor), NULL, NULL, 0},
    {"--shared", CMD_BUILD, OPT_FLAG, offsetof(Options, shared),
     "a shared library of the model, for Python", NULL, 0},
    {"--cache", CMD_BUILD, OPT_FLAG, offsetof(Options, cache),
     "a build kept in eomc's cache", NULL, 0},
    {"--extended", CMD_BUILD | CMD_RUN | CMD_ACCURACY, OPT_FLAG, offsetof(Options, extended),
     "the extended-precision functions", NULL, 0},
    {"--portable", CMD_BUILD | CMD_RUN | CMD_ACCURACY, OPT_FLAG, offsetof(Options, portable),
     "code for any CPU of this kind", NULL, 0},
    {"--eliminate", CMD_DERIVE, OPT_FLAG, offsetof(Options, eliminate), NULL, NULL, 1},
    {"--floating", CMD_DERIVE, OPT_FLAG, offsetof(Options, floating), NULL, NULL, 0},
    {"--joint-inputs", CMD_DERIVE, OPT_FLAG, offsetof(Options, joint_inputs), NULL, NULL, 0},
    {"--parameters", CMD_DERIVE, OPT_FLAG, offsetof(Options, parameters), NULL, NULL, 0},
};
enum { NOPTIONS = sizeof options / sizeof options[0] };

static const OptionSpec *
option_find(const char *name)
{
    for (int i = 0; i < NOPTIONS; i++)
        if (!strcmp(options[i].name, name))
            return &options[i];
    return NULL;
}

/* The index of VALUE in a NULL-ended set, or -1. */
static int
mode_index(const char *const *set, const char *value)
{
    for (int i = 0; set[i]; i++)
        if (!strcmp(set[i], value))
            return i;
    return -1;
}

/* An option eomc does not know: the nearest one it does, if close. */
_Noreturn void
cmdline_unknown_option(const char *a)
{
    const char *opts[NOPTIONS + 2] = {"--help", "--version"};
    for (int i = 0; i < NOPTIONS; i++)
        opts[i + 2] = options[i].name;
    const char *near = diag_nearest(a, opts, NOPTIONS + 2);
    if (!near)
        cmdline_usage_error("unknown option '%s'", a);
    fprintf(stderr, "eomc: unknown option '%s'; did you mean %s?\n(see eomc --help)\n", a,
            near);
    exit(EXIT_USAGE);
}

/* Whether the simulator options of `eomc run` ask for what solves with
 * the Jacobian: an implicit method (runtime/base/methods.def), the
 * linearization, an equilibrium, or the accuracy report of every method. */
static int
implicit(const char *method)
{
    return spec_method_jacobian(method) == 1;
}

static int
is_taylor(const char *method)
{
    return !strcmp(method, "taylor");
}

/* Whether a method the simulator options of `eomc run` name (--method M,
 * --methods M1,M2,..., --reference-method M) is one that want() says yes
 * to. */
static int
sim_names_method(const Options *o, int (*want)(const char *method))
{
    for (int i = 0; i < o->nsim; i++) {
        const char *a = o->sim[i], *val = NULL;
        if ((!strcmp(a, "--method") || !strcmp(a, "--methods") ||
             !strcmp(a, "--reference-method")) && i + 1 < o->nsim)
            val = o->sim[i + 1];
        else if (!strncmp(a, "--method=", 9) || !strncmp(a, "--methods=", 10) ||
                 !strncmp(a, "--reference-method=", 19))
            val = strchr(a, '=') + 1;
        for (const char *w = val; w && *w; w += strcspn(w, ",") + (w[strcspn(w, ",")] != 0)) {
            char name[32];
            snprintf(name, sizeof name, "%.*s", (int)strcspn(w, ","), w);
            if (want(name))
                return 1;
        }
    }
    return 0;
}

static int
sim_needs_jacobian(const Options *o)
{
    for (int i = 0; i < o->nsim; i++)
        if (!strcmp(o->sim[i], "--linearize") || !strcmp(o->sim[i], "--equilibrium") ||
            !strcmp(o->sim[i], "--work-precision"))
            return 1;
    return sim_names_method(o, implicit);
}

/* Whether the accuracy report's methods are its default, all of them. */
static int
sim_default_methods(const Options *o)
{
    for (int i = 0; i < o->nsim; i++)
        if (!strcmp(o->sim[i], "--methods") || !strncmp(o->sim[i], "--methods=", 10))
            return 0;
    return 1;
}

/* Whether the simulator options of `eomc run` ask for a reference
 * solution it must compute (none given by --reference FILE), or q'' in
 * extended precision. */
static int
sim_needs_twin(const Options *o)
{
    int needs = 0;
    for (int i = 0; i < o->nsim; i++) {
        const char *a = o->sim[i];
        if (!strcmp(a, "--reference") || !strncmp(a, "--reference=", 12))
            return 0;
        needs |= !strcmp(a, "--error") || !strcmp(a, "--work-precision") ||
                 !strcmp(a, "--accel-extended") ||
                 !strcmp(a, "--errors") || !strncmp(a, "--errors=", 9) ||
                 !strcmp(a, "--reference-out") || !strncmp(a, "--reference-out=", 16);
    }
    return needs;
}

/* The value of option name among the simulator's options at i (`name V`
 * or `name=V`), or NULL. */
static const char *
sim_value(const Options *o, int i, const char *name)
{
    size_t n = strlen(name);
    if (strncmp(o->sim[i], name, n))
        return NULL;
    if (!o->sim[i][n])
        return i + 1 < o->nsim ? o->sim[i + 1] : NULL;
    return o->sim[i][n] == '=' ? o->sim[i] + n + 1 : NULL;
}

/* What the simulator options of `eomc run` ask of Taylor's method (the
 * Options members run_method, run_integrates, taylor_reference): as the
 * simulator reads them, the last --method wins; --accel,
 * --accel-extended, --linearize, --equilibrium, --work-precision,
 * --help and --version take no step of it. */
static void
sim_taylor_use(Options *o)
{
    static const char *const still[] = {"--accel", "--accel-extended", "--linearize",
                                        "--equilibrium", "--work-precision", "--help", "-h",
                                        "--version", NULL};
    int run = !strcmp(o->cmd, "run"), integrates = run, by_taylor = 0, given = 0;
    int computed = !strcmp(o->cmd, "accuracy"); /* a reference the run computes */
    const char *v;
    for (int i = 0; i < o->nsim; i++) {
        const char *a = o->sim[i];
        for (int k = 0; still[k]; k++)
            if (!strcmp(a, still[k]))
                integrates = 0;
        if ((v = sim_value(o, i, "--method")))
            o->run_method = v;
        if ((v = sim_value(o, i, "--reference-method")))
            by_taylor = !strcmp(v, "taylor");
        given |= sim_value(o, i, "--reference") != NULL;
        computed |= !strcmp(a, "--error") || !strcmp(a, "--work-precision") ||
                    sim_value(o, i, "--errors") || sim_value(o, i, "--reference-out");
    }
    o->run_integrates = integrates;
    o->taylor_reference = by_taylor && computed && !given;
}

void
cmdline_parse(int argc, char **argv, Options *o)
{
    if (argc < 2)
        cmdline_usage(stderr), exit(EXIT_USAGE);
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))
        cmdline_usage(stdout), exit(0);
    if (!strcmp(argv[1], "--version"))
        printf("eomc %s\n", EOMC_VERSION), exit(0);
    o->cmd = argv[1];
    static const char *const cmds[] = {"compile", "build", "run", "accuracy", "import"};
    if (strcmp(o->cmd, "compile") && strcmp(o->cmd, "build") && strcmp(o->cmd, "run") &&
        strcmp(o->cmd, "accuracy")) {
        const char *near = diag_nearest(o->cmd, cmds, 5);
        if (near)
            fprintf(stderr, "eomc: unknown command '%s'; did you mean %s?\n", o->cmd, near),
                exit(EXIT_USAGE);
        cmdline_usage_error("unknown command '%s'; expected compile, build, run, accuracy or import",
                    o->cmd);
    }
    /* accuracy is run with --work-precision: the simulator takes the rest */
    int run = !strcmp(o->cmd, "run") || !strcmp(o->cmd, "accuracy");
    o->sim = calloc((size_t)argc + 1, sizeof *o->sim);
    int cmd = !strcmp(o->cmd, "compile") ? CMD_COMPILE
              : !strcmp(o->cmd, "build") ? CMD_BUILD
              : !strcmp(o->cmd, "run") ? CMD_RUN : CMD_ACCURACY;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        const OptionSpec *op = option_find(a);
        char *field = op ? (char *)o + op->field : NULL;
        if (op && (op->cmds & cmd) && !(op->sim_after && run && o->spec && o->nsim)) {
            if (op->kind == OPT_FLAG) {
                *(int *)(void *)field = 1;
                continue;
            }
            if (i + 1 >= argc)
                cmdline_usage_error("option %s needs a value", a);
            const char *v = argv[++i];
            if (op->kind == OPT_VALUE) {
                *(const char **)(void *)field = v;
            } else { /* comma-joined: "g=9.81,l=1" */
                char **list = (char **)(void *)field;
                size_t old = *list ? strlen(*list) : 0;
                *list = xrealloc(*list, old + strlen(v) + 2);
                snprintf(*list + old, strlen(v) + 2, "%s%s", old ? "," : "", v);
            }
        } else if (run && o->spec) {
            o->sim[o->nsim++] = argv[i];
        } else if (op && op->what) {
            /* an option of another command: say whose */
            fprintf(stderr, "eomc %s: %s belongs to `eomc %s` (%s)\n(see eomc --help)\n",
                    o->cmd, a, op->cmds & CMD_BUILD ? "build" : "compile", op->what);
            exit(EXIT_USAGE);
        } else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            cmdline_usage(stdout), exit(0); /* `eomc build --help` as `eomc --help` */
        } else if (a[0] == '-' && a[1]) {
            cmdline_unknown_option(a);
        } else if (!o->spec) {
            o->spec = a;
        } else {
            cmdline_usage_error("unexpected argument '%s'", a);
        }
    }
    if (!o->spec)
        cmdline_usage_error("%s: no spec file given", o->cmd);
    if (o->shared && o->mpi)
        cmdline_usage_error("%s: --shared and --mpi cannot go together (a library has no "
                            "main for mpirun to start)", "build");
    /* "-o -" is stdout, where compile writes without -o; a simulator
     * cannot go there */
    if (o->out && !strcmp(o->out, "-")) {
        if (strcmp(o->cmd, "compile") != 0)
            cmdline_usage_error("%s: -o -: an executable cannot be written to stdout; name "
                                "a file", o->cmd);
        o->out = NULL;
    }
    if (o->cache && o->out)
        cmdline_usage_error("%s: --cache and -o cannot go together (the cache names the "
                            "file)", "build");
    if (o->jacobian && mode_index(jacobian_modes, o->jacobian) < 0)
        cmdline_usage_error("--jacobian must be auto, unrolled, seeded or none, not '%s'",
                    o->jacobian);
    if (o->code && mode_index(code_modes, o->code) < 0)
        cmdline_usage_error("--code must be auto, straight or tables, not '%s'", o->code);
    if (o->branches && mode_index(branch_modes, o->branches) < 0)
        cmdline_usage_error("--branches must be lazy or eager, not '%s'", o->branches);
    /* a library serves every task (linearization, implicit methods):
     * it has the Jacobian unless --jacobian none says not */
    o->needs_jacobian = !strcmp(o->cmd, "accuracy") || sim_needs_jacobian(o) || o->shared;
    o->needs_twin = !strcmp(o->cmd, "accuracy") || sim_needs_twin(o);
    /* the series are much of a large model's C: printed when asked, when
     * the run names taylor, for the report of every method, and for a
     * library (which serves every task); or when the scene's method is
     * taylor (main.c) */
    o->needs_taylor = o->taylor || o->shared || sim_names_method(o, is_taylor) ||
                      (!strcmp(o->cmd, "accuracy") && sim_default_methods(o));
    sim_taylor_use(o);
    if (o->form && !form_find(o->form)) {
        const char *near = form_nearest(o->form);
        fprintf(stderr, "eomc: unknown form '%s'; %s%s%svalid forms: %s\n", o->form,
                near ? "did you mean " : "", near ? near : "", near ? "? " : "",
                form_names());
        exit(EXIT_USAGE);
    }
}


int
cmdline_jacobian_mode(const char *jacobian)
{
    return LOWER_JACOBIAN_AUTO + mode_index(jacobian_modes, jacobian);
}

int
cmdline_code_mode(const char *code)
{
    return LOWER_CODE_AUTO + mode_index(code_modes, code);
}

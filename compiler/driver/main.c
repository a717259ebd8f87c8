/*
 * eomc: the commands, on the options cmdline.c reads:
 *
 *   eomc compile SPEC [-o FILE.c] [--form NAME] [--effects LIST] [--stats]
 *                [--jacobian auto|unrolled|seeded] [--code auto|straight|tables]
 *   eomc build   SPEC [-o EXE]    [--form NAME] [--effects LIST] [--jacobian HOW]
 *                [--extended] [--mpi]
 *   eomc run     SPEC [--form NAME] [--effects LIST] [--jacobian HOW] [simulator options]
 *   eomc accuracy SPEC [the same]: run's simulator with --work-precision
 *
 * The pipeline: spec_load (YAML -> Spec) -> mech_build (T, V, S, Q) ->
 * a form's residual -> eom_derive (M, h, Jacobians) -> lower_model (the
 * functions, as lists of expressions and slots) -> emit_model (C).
 * Files are written under a temporary name and renamed when complete, so
 * a failure never leaves a half-written output behind.
 */
#include "build.h"
#include "cmdline.h"
#include "import.h"
#include "mechanics/constraint.h"
#include "config.h"
#include "emit/emit.h"
#include "mechanics/invariant.h"
#include "runtime/base/numfmt.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h> /* strcasecmp */
#include <sys/stat.h>
#include <unistd.h>

static void
print_stats(const EmitStats *st)
{
    int w = (int)strlen("function");
    for (int i = 0; i < EMIT_NFUNCS; i++)
        if ((int)strlen(st[i].function) > w)
            w = (int)strlen(st[i].function);
    fprintf(stderr, "%-*s %8s %8s %8s %8s %8s\n", w, "function", "adds", "muls", "divs",
            "calls", "total");
    for (int i = 0; i < EMIT_NFUNCS; i++) {
        ExprCount c = st[i].count;
        fprintf(stderr, "%-*s %8ld %8ld %8ld %8ld %8ld\n", w, st[i].function, c.adds,
                c.muls, c.divs, c.calls, c.adds + c.muls + c.divs + c.calls);
    }
}

/* --explain: what eomc made of the spec. */
static void
explain(const Spec *s, const Form *form, const Constraints *c, const Invariant *inv,
        const EmitInfo *info, const Lowered *L)
{
    printf("%s (%s): %d coordinate%s (", s->name, s->path, s->nq, s->nq == 1 ? "" : "s");
    for (int i = 0; i < s->nq; i++)
        printf("%s%s", i ? ", " : "", s->coord[i].name);
    printf("), %d parameter%s, %d input%s, %d particle%s, %d bod%s\n", s->np,
           s->np == 1 ? "" : "s", s->nu, s->nu == 1 ? "" : "s", s->npart,
           s->npart == 1 ? "" : "s", s->nbody, s->nbody == 1 ? "y" : "ies");
    printf("form %s: E = %s\n", form->name, form->formula);
    printf("  %s\n", info->form_why ? info->form_why : "chosen by --form");
    if (L && L->code == LOWER_CODE_TABLES)
        printf("  code: loops over the model's tables (%d turns; eomc_tree.h), %s\n",
               L->tables->nt, strstr(info->options, "--code tables") ? "as --code asks"
               : "the straight-line solve being too long to compile quickly");
    if (s->nscenes) {
        int w = 0;
        for (int k = 0; k < s->nscenes; k++)
            if ((int)strlen(s->scenes[k].name) > w)
                w = (int)strlen(s->scenes[k].name);
        printf("scenes (--scene NAME; the first is the default):\n");
        for (int k = 0; k < s->nscenes; k++)
            printf("  %s %-*s  %s\n", s->scene.name == s->scenes[k].name ? "*" : " ", w,
                   s->scenes[k].name, s->scenes[k].summary);
    }
    if (s->nfixed) {
        char num[NUM_MAX];
        printf("fixed (folded into the code):");
        for (int i = 0; i < s->np; i++)
            if (s->param[i].fixed)
                printf(" %s = %s", s->param[i].name, num_shortest(num, s->param[i].value));
        printf("\n");
    }
    for (int on = 1; on >= 0; on--) {
        int any = 0;
        printf(on ? "effects on:" : "; off (no code):");
        for (int k = 0; k < s->neffect; k++)
            if (s->effect[k].enabled == on)
                printf(" %s", s->effect[k].name), any = 1;
        printf("%s", any ? "" : " (none)");
    }
    printf("\n");
    if (c)
        constraints_explain(stdout, c, s, info->eliminate);
    else
        printf("no constraints: q'' = -M^-1 h\n");
    printf("%s\n%s\n", inv->note, inv->test);
}

/* The spec's file name without directory and extension. */
static void
spec_stem(const char *path, char *out, size_t len)
{
    const char *b = strrchr(path, '/');
    snprintf(out, len, "%s", b ? b + 1 : path);
    char *dot = strrchr(out, '.');
    if (dot && dot != out)
        *dot = '\0';
}

/* Whether the run, its reference or the scene's simulator takes Taylor's
 * method (not --taylor or --shared, which write series the form may have). */
static int
taylor_run(const Options *o, const Spec *s)
{
    const char *method = o->run_method ? o->run_method : s->scene.method;
    return (o->run_integrates && !strcmp(method, "taylor")) || o->taylor_reference ||
           (!strcmp(o->cmd, "build") && !strcmp(s->scene.method, "taylor"));
}

/* Whether `eomc run` would be refused for want of Taylor series, which the
 * model's lowering says it has not (why): its simulator refuses to take a
 * step of Taylor's method, or to compute a reference by it, without them.
 * Said here, as the simulator says it, before any C is compiled. */
static int
refuse_taylor(const Options *o, const Spec *s, const char *why)
{
    const char *method = o->run_method ? o->run_method : s->scene.method;
    const char *opt = o->run_integrates && !strcmp(method, "taylor") ? "--method taylor"
                      : o->taylor_reference ? "--reference-method taylor" : NULL;
    if (why && !opt && !strcmp(o->cmd, "build") && !strcmp(s->scene.method, "taylor"))
        /* the simulator is still of use with another --method */
        fprintf(stderr, "%s: warning: the scene's method is taylor, but %s has no Taylor "
                "series (%s): its simulator will refuse to run without another --method\n",
                o->spec, s->name, why);
    if (!why || !opt)
        return 0;
    char stem[200];
    spec_stem(o->spec, stem, sizeof stem);
    fprintf(stderr, "%s: %s: %s has no Taylor series: %s\n(see eomc %s %s%s%s --help)\n", stem,
            opt, s->name, why, o->cmd, o->spec, o->scene ? " --scene " : "",
            o->scene ? o->scene : "");
    return 1;
}

/* Load, derive and emit to `out` (NULL: nothing, --explain only).
 * Returns 0, or an exit status. */
/* *units (unless NULL): the translation units of the C written (emit.h);
 * *model (unless model is NULL): the model's name in it (its NAME_model),
 * malloc'd. */
static int
compile(const Options *o, FILE *out, int *units, char **model)
{
    Arena *A = arena_new();
    ExprPool *P = expr_pool_new();
    Diff *D = diff_new(P);
    int rc = EXIT_USAGE;
    SpecOptions so = {o->scene, o->fix};
    Spec *s = o->imported ? spec_load_buffer(o->imported_name, o->imported, o->imported_len,
                                             &so, A, P)
                          : spec_load(o->spec, &so, A, P);
    jmp_buf jb;
    jmp_buf *old = diag_set_jump(&jb);
    if (setjmp(jb) != 0) { /* a diagnostic while deriving: nothing emitted */
        diag_set_jump(old);
        diff_free(D);
        expr_pool_free(P);
        arena_free(A);
        return EXIT_USAGE;
    }
    if (s && (!o->effects || spec_select_effects(s, o->effects) == 0)) {
        const char *why = NULL;
        Mech *m = mech_build(s, A, P, D);
        Constraints *c = constraints_build(s, m, A, P, D);
        Invariant *inv = invariant_derive(s, m, c, A, P, D);
        char picked[600];
        const Form *form = o->form ? form_find(o->form) : &form_lagrange;
        Eom *e = NULL;
        int loads = constraints_by_loads(c, o->eliminate);
        if (!o->form && o->code && !strcmp(o->code, "tables") && (!c || loads)) {
            /* the tables are the articulated-body form's: it, where it applies */
            const char *no;
            if ((e = eom_derive(s, m, &form_articulated, A, P, D, &no)))
                snprintf(picked, sizeof picked, "the one --code tables writes");
        }
        if (!e)
            e = o->form ? eom_derive(s, m, form, A, P, D, &why)
                        : eom_derive_cheapest(s, m, c ? c->nc : 0, loads, taylor_run(o, s),
                                              A, P, D, picked, sizeof picked);
        if (e)
            form = e->form;
        else if (!o->form)
            why = "no form applies";
        if (!e) {
            fprintf(stderr, "%s: error: form '%s' does not apply: %s\n",
                    o->spec, form->name, why);
        } else {
            char opts[256] = "";
            /* the Jacobian is most of a model's C and of its build time
             * (71 % of the bicycle's): printed only when the scene's
             * method or the simulator's task needs it */
            int jac = o->needs_jacobian || spec_method_jacobian(s->scene.method) == 1
                          ? LOWER_JACOBIAN_AUTO : LOWER_JACOBIAN_NONE;
            if (o->effects)
                snprintf(opts, sizeof opts, "--effects %s", o->effects);
            if (o->jacobian) { /* it changes the code */
                size_t len = strlen(opts);
                snprintf(opts + len, sizeof opts - len, "%s--jacobian %s",
                         len ? " " : "", o->jacobian);
                jac = cmdline_jacobian_mode(o->jacobian);
            }
            if (jac == LOWER_JACOBIAN_AUTO && o->shared) /* its callers' loops */
                jac = LOWER_JACOBIAN_AUTO_LIBRARY;
            int code = LOWER_CODE_AUTO;
            if (o->code) {
                size_t len = strlen(opts);
                snprintf(opts + len, sizeof opts - len, "%s--code %s", len ? " " : "", o->code);
                code = cmdline_code_mode(o->code);
            }
            if (o->branches && !strcmp(o->branches, "eager")) {
                size_t len = strlen(opts);
                snprintf(opts + len, sizeof opts - len, "%s--branches eager", len ? " " : "");
            }
            if (o->eliminate) {
                size_t len = strlen(opts);
                snprintf(opts + len, sizeof opts - len, "%s--eliminate", len ? " " : "");
            }
            if (o->needs_taylor) { /* it changes the code */
                size_t len = strlen(opts);
                snprintf(opts + len, sizeof opts - len, "%s--taylor", len ? " " : "");
            }
            EmitInfo info = {.version = EOMC_VERSION, .options = opts,
                             .eliminate = form->eliminate || o->eliminate,
                             .form_why = o->form ? NULL : picked};
            EmitStats st[EMIT_NFUNCS];
            int taylor = o->needs_taylor || !strcmp(s->scene.method, "taylor");
            Lowered *L = out ? lower_model(s, m, e, c, info.eliminate, inv, jac, code, taylor, A,
                                           P, D) : NULL;
            if (L)
                L->eager_branches = o->branches && !strcmp(o->branches, "eager");
            if (L && refuse_taylor(o, s, L->taylor->why)) {
                rc = EXIT_USAGE;
            } else {
                if (L && L->tables_why)
                    fprintf(stderr, "%s: note: --code tables: not here (%s); the code is "
                            "straight-line\n", o->spec, L->tables_why);
                if (o->explain)
                    explain(s, form, c, inv, &info, L);
                if (out) {
                    int nu = emit_model(out, L, P, &info, st);
                    if (units)
                        *units = nu;
                    if (model) {
                        *model = xmalloc(strlen(L->model.name) + 1);
                        strcpy(*model, L->model.name);
                    }
                    if (o->stats)
                        print_stats(st);
                }
                rc = 0;
            }
        }
    }
    diag_set_jump(old);
    diff_free(D);
    expr_pool_free(P);
    arena_free(A);
    return rc;
}

/* Write to path.tmpPID, then rename: never a half-written file (but a
 * device such as /dev/null is written in place). */
static int
compile_to_file(const Options *o, const char *path, int *units, char **model)
{
    size_t len = strlen(path) + 32;
    char *tmp = xmalloc(len);
    int special = build_is_special(path);
    snprintf(tmp, len, special ? "%s" : "%s.tmp%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    if (!f) { /* named as the user wrote it: the temporary name is ours */
        fprintf(stderr, "eomc: cannot write %s: %s\n", path, strerror(errno));
        free(tmp);
        return EXIT_USAGE;
    }
    int rc = compile(o, f, units, model);
    if (fclose(f) != 0 && rc == 0) {
        fprintf(stderr, "eomc: cannot write %s: %s\n", path, strerror(errno));
        rc = EXIT_USAGE;
    }
    if (rc == 0 && !special && rename(tmp, path) != 0) {
        fprintf(stderr, "eomc: cannot write %s: %s\n", path, strerror(errno));
        rc = EXIT_USAGE;
    }
    if (rc != 0 && !special)
        unlink(tmp);
    free(tmp);
    return rc;
}

/* Generate into a temporary directory and build `exe` from it. */
static int
build(const Options *o, const char *exe)
{
    /* the directory exe goes to must be there: the linker would say so
     * in its own words, and blame the generated code */
    char *outdir = xmalloc(strlen(exe) + 2);
    strcpy(outdir, exe);
    char *slash = strrchr(outdir, '/');
    if (slash)
        slash[slash == outdir] = '\0'; /* "/x" -> "/" */
    else
        strcpy(outdir, ".");
    struct stat st;
    if (stat(outdir, &st) != 0 || !S_ISDIR(st.st_mode) || access(outdir, W_OK) != 0) {
        int err = errno;
        fprintf(stderr, "eomc: cannot write %s: the directory '%s' %s\n", exe, outdir,
                stat(outdir, &st) != 0 ? "does not exist" : !S_ISDIR(st.st_mode)
                ? "is not a directory" : strerror(err));
        free(outdir);
        return EXIT_USAGE;
    }
    free(outdir);
    char dir[] = "/tmp/eomc-XXXXXX";
    if (!mkdtemp(dir)) {
        fprintf(stderr, "eomc: cannot create a temporary directory: %s\n", strerror(errno));
        return 1;
    }
    char cfile[sizeof dir + 16];
    snprintf(cfile, sizeof cfile, "%s/model.c", dir);
    int units = EMIT_UNIT1;
    char *model = NULL;
    int rc = compile_to_file(o, cfile, &units, &model);
    /* The extended-precision twin doubles the compiler's work: a model
     * whose functions are two units (a large one) gets it only when asked
     * for. */
    int twin = !(units & EMIT_UNIT2) || o->extended || o->needs_twin;
    if (rc == 0 && build_executable(cfile, model, exe, o->mpi, units, twin, o->shared,
                                      !o->portable && !o->mpi) != 0)
        rc = 1;
    free(model);
    unlink(cfile);
    rmdir(dir);
    return rc;
}

static char *
read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, n = 0;
    char *buf = xmalloc(cap);
    size_t k;
    while ((k = fread(buf + n, 1, cap - n, f)) > 0)
        if ((n += k) == cap)
            buf = xrealloc(buf, cap *= 2);
    fclose(f);
    buf[n] = '\0'; /* (n < cap: the loop grows buf whenever it fills) */
    *len = n;
    return buf;
}

/* The build in eomc's cache for o's spec and options (name: the file's
 * name there), built unless an identical build is there.  A malloc'd
 * path, or NULL with *rc the exit status after saying why. */
static char *
cached_build(const Options *o, const char *name, int *rc)
{
    size_t len = o->imported_len;
    char *text = o->imported ? memcpy(xmalloc(len + 1), o->imported, len)
                             : read_file(o->spec, &len);
    *rc = EXIT_USAGE;
    if (!text) {
        fprintf(stderr, "eomc: cannot read %s: %s\n", o->spec, strerror(errno));
        return NULL;
    }
    const char *jac = o->jacobian ? o->jacobian : "auto";
    const char *form = o->form ? o->form : "(default)";
    const char *code = o->code ? o->code : "auto";
    const char *branches = o->branches ? o->branches : "lazy";
    /* the options after the text, the buffer grown until they fit (an
     * estimate of their length went stale as options were added) */
    size_t extra = 256;
    for (;;) {
        text = xrealloc(text, len + extra);
        int n = snprintf(text + len, extra,
                         "\n--form %s --effects %s --eliminate %d --jacobian %s%s --code %s "
                         "--branches %s --extended %d --taylor %d --scene %s --fix %s%s%s", form,
                         o->effects ? o->effects : "(scene)",
                         o->eliminate, jac, o->needs_jacobian ? " (needed)" : "", code,
                         branches, o->extended || o->needs_twin, o->needs_taylor,
                         o->scene ? o->scene : "(first)",
                         o->fix ? o->fix : "(none)", o->shared ? " --shared" : "",
                         o->portable ? " --portable" : "");
        if (n >= 0 && (size_t)n < extra) {
            len += (size_t)n;
            break;
        }
        extra = n >= 0 ? (size_t)n + 1 : 2 * extra;
    }
    char *path = build_cache_path(name, text, len);
    free(text);
    if (!path) {
        *rc = 1;
        return NULL;
    }
    *rc = 0;
    if (access(path, o->shared ? R_OK : X_OK) != 0 && (*rc = build(o, path)) != 0) {
        free(path);
        return NULL;
    }
    return path;
}

/* `run` and `accuracy`: build into the cache unless an identical build is
 * there, then become the simulator (with --work-precision for accuracy). */
static int
run(const Options *o)
{
    char stem[200], name[256];
    spec_stem(o->spec, stem, sizeof stem);
    snprintf(name, sizeof name, "sim-%s", stem);
    int rc;
    char *exe = cached_build(o, name, &rc);
    if (!exe)
        return rc;
    char **argv = calloc((size_t)o->nsim + 3, sizeof *argv);
    int argc = 0;
    argv[argc++] = stem; /* messages name the model, not the cache path */
    if (!strcmp(o->cmd, "accuracy"))
        argv[argc++] = "--work-precision";
    for (int i = 0; i < o->nsim; i++)
        argv[argc++] = o->sim[i];
    /* the simulator's usage errors and --help name the command typed
     * ("see eomc run specs/kepler.yaml --help"), not the cached binary */
    char self[4608]; /* a path, and a scene's name */
    snprintf(self, sizeof self, "eomc %s %s%s%s", o->cmd, o->spec, o->scene ? " --scene " : "",
             o->scene ? o->scene : "");
    setenv("EOMC_RUN_COMMAND", self, 1);
    fflush(stdout);
    execv(exe, argv);
    fprintf(stderr, "eomc: cannot run %s: %s\n", exe, strerror(errno));
    return 1;
}

/* Whether path names an MJCF or URDF model (.xml, .urdf), not a spec. */
static int
is_model_file(const char *path)
{
    const char *dot = strrchr(path, '.');
    return dot && (!strcasecmp(dot, ".xml") || !strcasecmp(dot, ".urdf"));
}

/* The spec of the model at path into *text (malloc'd), what it drops
 * named on stderr; 0, or exit 2 after the error (at its place in the
 * file where that is known). */
static int
import_text(const char *path, const ImportOptions *opt, char **text, size_t *len)
{
    char err[1200];
    ImportWhere at;
    FILE *mem = open_memstream(text, len);
    int rc = import_model(path, opt, mem, stderr, err, sizeof err, &at);
    fclose(mem);
    if (rc == 0)
        return 0;
    free(*text);
    *text = NULL;
    diag_error(import_where_find(path, &at), "%s", err);
}

/* A model file given as SPEC: imported first, as `eomc import` would, and
 * its spec kept in o; 0, or the exit status. */
static int
import_spec(Options *o)
{
    const char *flag = o->floating ? "--floating" : o->joint_inputs ? "--joint-inputs"
                       : o->parameters ? "--parameters" : NULL;
    if (!is_model_file(o->spec) && flag) /* (the spec is named by the usage line) */
        cmdline_usage_error("%s is for an MJCF or URDF model given where the spec goes, "
                            "not for a spec", flag);
    if (!is_model_file(o->spec))
        return 0;
    ImportOptions opt = {.floating = o->floating, .joint_inputs = o->joint_inputs,
                         .parameters = o->parameters};
    int rc = import_text(o->spec, &opt, &o->imported, &o->imported_len);
    snprintf(o->imported_name, sizeof o->imported_name, "%s (as imported)", o->spec);
    return rc;
}

/* `eomc import MODEL [-o SPEC] [--strict] [--floating] [--joint-inputs]
 * [--parameters]`: the spec of an MJCF or URDF model, to SPEC (written
 * whole or not at all: path.tmpPID, renamed) or stdout (ImportOptions). */
static int
import_cmd(int argc, char **argv)
{
    const char *model = NULL, *out = NULL;
    ImportOptions opt = {0};
    for (int i = 2; i < argc; i++) {
        if (!strcmp(argv[i], "--strict")) {
            opt.strict = 1;
        } else if (!strcmp(argv[i], "--floating")) {
            opt.floating = 1;
        } else if (!strcmp(argv[i], "--joint-inputs")) {
            opt.joint_inputs = 1;
        } else if (!strcmp(argv[i], "--parameters")) {
            opt.parameters = 1;
        } else if (!strcmp(argv[i], "-o")) {
            if (i + 1 >= argc)
                cmdline_usage_error("option %s needs a value", "-o");
            out = argv[++i];
            if (!strcmp(out, "-")) /* stdout, as without -o */
                out = NULL;
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            cmdline_usage(stdout), exit(0); /* import's usage is a line of eomc's */
        } else if (argv[i][0] == '-' && argv[i][1]) {
            cmdline_unknown_option(argv[i]);
        } else if (!model) {
            model = argv[i];
        } else {
            cmdline_usage_error("unexpected argument '%s'", argv[i]);
        }
    }
    if (!model)
        cmdline_usage_error("%s: no model file given (MJCF or URDF)", "import");
    char *text = NULL;
    size_t len = 0;
    int rc = import_text(model, &opt, &text, &len);
    if (rc != 0)
        return rc;
    char tmp[4200] = "";
    if (out && !build_is_special(out))
        snprintf(tmp, sizeof tmp, "%s.tmp%ld", out, (long)getpid());
    const char *path = *tmp ? tmp : out;
    FILE *f = out ? fopen(path, "w") : stdout;
    int bad = !f || fwrite(text, 1, len, f) != len;
    if (out && f && fclose(f) != 0)
        bad = 1;
    if (!bad && *tmp && rename(tmp, out) != 0)
        bad = 1;
    if (bad) {
        fprintf(stderr, "eomc: cannot write %s: %s\n", out ? out : "stdout", strerror(errno));
        if (*tmp)
            unlink(tmp);
        rc = EXIT_USAGE;
    }
    free(text);
    return rc;
}

static int
eomc_main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "import"))
        return import_cmd(argc, argv);
    Options o = {0};
    cmdline_parse(argc, argv, &o);
    int rc;
    if ((rc = import_spec(&o)) != 0)
        return rc;
    if (!strcmp(o.cmd, "compile"))
        rc = o.out ? compile_to_file(&o, o.out, NULL, NULL)
                   : compile(&o, o.explain ? NULL : stdout, NULL, NULL);
    else if (!strcmp(o.cmd, "build")) {
        char stem[200], def[256];
        spec_stem(o.spec, stem, sizeof stem);
        /* default: the spec's name in the current directory (a library's,
         * libNAME.so) */
        snprintf(def, sizeof def, o.shared ? "lib%s.so" : "%s", stem);
        if (o.cache) {
            char *path = cached_build(&o, o.shared ? def : stem, &rc);
            if (path)
                printf("%s\n", path);
            free(path);
        } else {
            rc = build(&o, o.out ? o.out : def);
        }
    } else
        rc = run(&o); /* run and accuracy */
    free(o.sim);
    free(o.fix);
    free(o.imported);
    return rc;
}

/* Derivatives and emission walk expressions recursively, as deep as an
 * expression is high.  parse.c bounds the height of what a spec can write
 * (10 000), derivatives are a few times higher, and a sanitizer build's
 * frames are large: the work runs on a thread whose stack is sized for
 * that (address space only: untouched pages cost nothing).  Specs at that
 * bound (chains of 5 000 defines of sin(cos(d)), d x + y, exp(d)/(1 + d^2),
 * compiled with --jacobian auto --taylor) ran within 4 MB in clang's -O0
 * build and within 16 MB under AddressSanitizer: 64 MB leaves four times
 * the worst.  (It was 512 MB: valgrind's memcheck then spent 2 s setting up
 * the stack of every eomc it ran, most of the valgrind test's time.) */
enum { STACK_BYTES = 64 << 20 };

typedef struct MainArgs {
    int argc;
    char **argv;
    int rc;
} MainArgs;

static void *
main_thread(void *arg)
{
    MainArgs *m = arg;
    m->rc = eomc_main(m->argc, m->argv);
    return NULL;
}

int
main(int argc, char **argv)
{
    MainArgs m = {argc, argv, 0};
    pthread_attr_t attr;
    pthread_t th;
    if (pthread_attr_init(&attr) != 0 ||
        pthread_attr_setstacksize(&attr, STACK_BYTES) != 0 ||
        pthread_create(&th, &attr, main_thread, &m) != 0)
        return eomc_main(argc, argv); /* the default stack, then */
    pthread_attr_destroy(&attr);
    pthread_join(th, NULL);
    return m.rc;
}

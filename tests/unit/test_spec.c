/*
 * Unit tests of the spec loader (spec/): what a spec means (values of
 * its expressions against the formulas written in C), defines in any
 * order, effect selection, and the line:column of errors through YAML's
 * quoting and folding styles.
 */
#define _POSIX_C_SOURCE 200809L
#include "check.h"
#include "mechanics/mech.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static Arena *A;
static ExprPool *P;

static Spec *
load(const char *text)
{
    return spec_load_buffer("t.yaml", text, strlen(text), NULL, A, P);
}

/* Load text expecting an error: "line:col: message" of its first line. */
static void
load_error(const char *text, char *msg, size_t len)
{
    fflush(stdout);
    int saved = dup(2);
    FILE *tmp = tmpfile();
    dup2(fileno(tmp), 2);
    Spec *s = load(text);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(tmp);
    if (!fgets(msg, (int)len, tmp))
        msg[0] = '\0';
    fclose(tmp);
    msg[strcspn(msg, "\n")] = '\0';
    if (s)
        snprintf(msg, len, "(no error)");
    else if (!strncmp(msg, "t.yaml:", 7))
        memmove(msg, msg + 7, strlen(msg + 7) + 1);
}

static double
eval(ExprId e, double t, const double *q, const double *v, const double *p)
{
    double zero[8] = {0};
    ExprEnv env = {.t = t, .q = {q, v, zero, zero}, .p = p, .u = zero};
    return expr_eval(P, e, &env);
}

static void
test_meaning(void)
{
    Spec *s = load(
        "name: swing\n"
        "parameters: {m: 2, l: 1.5, g: 9.81, c: 0.25}\n"
        "coordinates: [th, r]\n"
        "define:\n"
        "  y: -rr*cos(th)      # uses rr before it is defined\n"
        "  rr: l + r\n"
        "  x: rr*sin(th)\n"
        "particles:\n"
        "  bob: {mass: m, position: [x, y]}\n"
        "kinetic: 1/2*c*r'^2\n"
        "effects:\n"
        "  gravity: {gravity: [0, -g]}\n"
        "  spring: {potential: 1/2*40*r^2}\n"
        "  damper: [{work: -c*r'*delta(r)}, {force: [0, -c*y'], on: bob}]\n"
        "initial: {th: 2*pi/10, \"r'\": l/3}\n"
        "scene: {effects: [gravity, damper], t_end: 3, method: msbdf, rtol: 1e-8}\n");
    CHECK(s != NULL, "a spec with defines in any order loads");
    if (!s)
        return;
    CHECK(!strcmp(s->name, "swing") && s->nq == 2 && s->np == 4 && s->npart == 1 &&
          s->neffect == 3, "names and counts");
    CHECK(s->effect[0].enabled && !s->effect[1].enabled && s->effect[2].enabled,
          "scene effects: gravity and damper on, spring off");
    CHECK(s->effect[2].nforce == 2 && s->effect[2].force[0].kind == FORCE_WORK &&
          s->effect[2].force[1].kind == FORCE_VECTOR, "an effect as a list of forces");
    CHECK(s->scene.t_end == 3 && !strcmp(s->scene.method, "msbdf") && s->scene.rtol == 1e-8 &&
          s->scene.atol == 1e-10 && s->scene.dt == 0.01, "scene values and defaults");
    double p[4] = {2, 1.5, 9.81, 0.25};
    double q[2] = {0.7, 0.2}, v[2] = {-0.3, 0.9};
    double rr = 1.5 + 0.2;
    CHECK_NEAR(eval(s->part[0].pos[0], 0, q, v, p), rr * sin(0.7), 1e-15, "x = (l + r) sin th");
    CHECK_NEAR(eval(s->part[0].pos[1], 0, q, v, p), -rr * cos(0.7), 1e-15, "y = -(l + r) cos th");
    CHECK_NEAR(eval(s->kinetic[0].expr, 0, q, v, p), 0.5 * 0.25 * 0.81, 1e-15, "kinetic term");
    CHECK_NEAR(eval(s->coord[0].q0, 0, q, v, p), 2 * 3.14159265358979323846 / 10, 1e-15, "initial th = 2 pi/10");
    CHECK_NEAR(eval(s->coord[1].v0, 0, q, v, p), 0.5, 1e-15, "initial r' = l/3");
    CHECK(s->coord[1].q0 == EXPR_ZERO && s->coord[0].v0 == EXPR_ZERO, "unset initial values are 0");
    /* the force on the bob: F = (0, -c y'), y' = -r' cos th + rr sin th th' */
    double ydot = -v[1] * cos(q[0]) + rr * sin(q[0]) * v[0];
    CHECK_NEAR(eval(s->effect[2].force[1].vec[1], 0, q, v, p), -0.25 * ydot, 1e-15,
               "y' inside a force is the total time derivative");
    /* virtual work: W = -c r' delta(r), evaluated along the variations
     * (delta th, delta r) = (1, 0) and (0, 1): Q = (0, -c r') */
    double zero[8] = {0}, d_th[2] = {1, 0}, d_r[2] = {0, 1};
    ExprEnv env = {.t = 0, .q = {q, v, zero, zero}, .p = p, .u = zero, .seed = {d_th, NULL}};
    double Q_th = expr_eval(P, s->effect[2].force[0].expr, &env);
    env.seed[0] = d_r;
    double Q_r = expr_eval(P, s->effect[2].force[0].expr, &env);
    CHECK(Q_th == 0 && check_close(Q_r, -0.25 * v[1], 1e-15),
          "work: -c*r'*delta(r) is -c r' along delta(r), nothing along delta(th)");
    CHECK(spec_select_effects(s, "spring") == 0 && !s->effect[0].enabled &&
          s->effect[1].enabled && !s->effect[2].enabled, "--effects replaces the scene's choice");
    fflush(stdout);
    int saved = dup(2);
    FILE *tmp = tmpfile();
    dup2(fileno(tmp), 2);
    int rc = spec_select_effects(s, "gravity,sprin");
    dup2(saved, 2);
    close(saved);
    fclose(tmp);
    CHECK(rc == -1, "--effects with an unknown effect fails");
    Spec *d = load("coordinates: [a]\nkinetic: a'^2/2\n");
    CHECK(d && !strcmp(d->name, "t"), "the default name is the file's base name");
}

static void
test_long_define_chain(void)
{
    enum { N = 5000 };
    size_t cap = 64 * N + 256, len = 0;
    char *text = malloc(cap);
    len += (size_t)snprintf(text + len, cap - len, "coordinates: [x]\ndefine:\n");
    /* written last-first, so every define names one defined further down */
    for (int i = N; i >= 1; i--)
        len += (size_t)snprintf(text + len, cap - len, "  d%d: d%d + x\n", i, i - 1);
    len += (size_t)snprintf(text + len, cap - len, "  d0: x\nkinetic: d%d'^2/2\n", N);
    Spec *s = load(text);
    CHECK(s != NULL, "a chain of %d defines loads (no recursion through defines)", N);
    if (s) {
        double q[1] = {0}, v[1] = {0.01}, p[1] = {0};
        CHECK_NEAR(eval(s->kinetic[0].expr, 0, q, v, p), 0.5 * pow((N + 1) * 0.01, 2), 1e-12,
                   "and means ((N + 1) x')^2 / 2");
    }
    free(text);
}

static void
test_error_places(void)
{
    static const struct {
        const char *text, *want;
    } cases[] = {
        {"coordinates: [x]\nkinetic: \"x'^2 \\t+ zz\"\n",
         "2:20: error: unknown name 'zz'"},
        {"coordinates: [x]\nkinetic: 'x''^2 + zz'\n",
         "2:19: error: unknown name 'zz'"},
        {"coordinates: [x]\nkinetic:\n  - x'^2 +\n    2*zz\n",
         "4:7: error: unknown name 'zz'"},
        {"coordinates: [x]\nkinetic: |\n  x'^2\n   + zz\n",
         "4:6: error: unknown name 'zz'"},
        {"coordinates: [x]\nkinetic: >\n  x'^2\n  + zz\n",
         "4:5: error: unknown name 'zz'"},
        {"coordinates: [x]\nkinetic: \"\\u00e9 + x'^2\"\n",
         "2:11: error: unexpected character"},
        {"coordinates: [x]\nparameters: {m: 1, m: 2}\nkinetic: x'^2\n",
         "2:20: error: duplicate key 'm'"},
        {"coordinates: [x, m]\nparameters: {m: 1}\nkinetic: x'^2\n",
         "1:18: error: 'm' is already a parameter (line 2)"},
        {"coordinates: [x]\ndefine: {t: x}\nkinetic: x'^2\n",
         "2:10: error: 't' is reserved"},
        {"coordinates: [x]\nkinetic: x'^2 + cos\n",
         "2:17: error: 'cos' is a function: write cos(...)"},
        {"coordinates: [x]\nkinetic: x'^2\nscene: {method: rk45}\n",
         "3:17: error: unknown method 'rk45'; did you mean 'rk4' or 'rkf45'?"},
        {"coordinates: [x]\nkinetic: x'^2\nscene: {dt: -1}\n",
         "3:13: error: dt must be positive"},
        {"coordinates: [x]\nparticles: {p: {mass: 1, position: [x, 0, 0, 0]}}\n",
         "2:36: error: a position must have 2 or 3 components, not 4"},
        {"coordinates: [x]\nparticles: {p: {position: [x, 0]}}\n",
         "2:16: error: particle 'p' has no mass"},
        {"coordinates: [x]\nparticles: {p: {mass: 1, position: [x, 0]}}\n"
         "effects: {push: {force: [1, 0], on: q}}\n",
         "3:37: error: unknown particle or body 'q'"},
        {"coordinates: [x]\nparticles: {p: {mass: 1, position: [x, 0]}}\n"
         "effects: {g: {gravity: [0, 0, -1]}}\n",
         "3:24: error: gravity has 3 components but particle 'p' is 2-D"},
        {"coordinates: [x]\nkinetic: x'^2\ninitial: {\"y'\": 1}\n",
         "3:11: error: 'y'' is not a coordinate"},
        {"coordinates: [x]\nkinetic: x'^2\nscene: {effects: [grav]}\n",
         "3:19: error: unknown effect 'grav'"},
        {"coordinates: [x]\nkinetic: x'^2\n---\ncoordinates: [y]\n",
         "3:1: error: a spec is one YAML document"},
        {"[1, 2]\n", "1:1: error: the top level of a spec must be a mapping"},
        {"name: 3d-model\ncoordinates: [x]\nkinetic: x'^2\n",
         "1:7: error: name '3d-model' must be a C identifier"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char msg[512];
        load_error(cases[i].text, msg, sizeof msg);
        CHECK(!strncmp(msg, cases[i].want, strlen(cases[i].want)), "%s (got %s)",
              cases[i].want, msg);
    }
}

int
main(void)
{
    A = arena_new();
    P = expr_pool_new();
    test_meaning();
    test_long_define_chain();
    test_error_places();
    expr_pool_free(P);
    arena_free(A);
    return check_done();
}

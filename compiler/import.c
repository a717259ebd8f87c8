/*
 * import: MuJoCo's compiled model (mjModel) printed as an eomc spec.
 *
 * MuJoCo places body b in its parent p by a constant offset and turn
 * (body_pos, body_quat), then applies b's joints in order: a hinge turns
 * the body about its axis through its anchor (jnt_pos, in the body's axes)
 * by q - qpos0, a slide moves it along its axis by q - qpos0.  Here that is
 * a frame per turn and a point per offset, so the spec is the tree the
 * recursive forms take: the anchor is each turn's pivot.  The inertia,
 * principal moments about body_ipos in the axes body_iquat turns to, is
 * printed as the full tensor in the body's axes.
 *
 * What is imported so far: hinge and slide joints, masses and inertias,
 * gravity, joint damping and stiffness.  Other joints, armature, actuators,
 * equality constraints and tendons are refused by name; limits, friction
 * loss and contacts are dropped, each named in a warning (--strict: an
 * error).
 */
#include "import.h"

#include "../runtime/numfmt.h"
#include "arena.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef EOMC_HAVE_MUJOCO
#include <mujoco/mujoco.h>

int
import_available(void)
{
    return 1;
}

/* Names: identifiers made of the model's, unique (a later duplicate gets
 * _2, _3, ...). */
typedef struct Names {
    char **name;
    int n, cap;
} Names;

static int
taken(const Names *N, const char *s)
{
    for (int i = 0; i < N->n; i++)
        if (!strcmp(N->name[i], s))
            return 1;
    return 0;
}

/* An identifier from src, in a new string with room for a suffix: every
 * character but a letter, a digit or _ made _, a leading digit given a _. */
static char *
ident(const char *src, size_t *end)
{
    size_t len = strlen(src);
    char *s = xmalloc(len + 16);
    size_t k = 0;
    if (!((src[0] >= 'a' && src[0] <= 'z') || (src[0] >= 'A' && src[0] <= 'Z') || src[0] == '_'))
        s[k++] = '_';
    for (size_t i = 0; i < len; i++) {
        char c = src[i];
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
        s[k++] = ok ? c : '_';
    }
    s[k] = '\0';
    *end = k;
    return s;
}

/* An identifier from raw (or from fallback where raw is empty), unique
 * among N's; kept in N. */
static const char *
unique(Names *N, const char *raw, const char *fallback)
{
    size_t k;
    char *s = ident(raw && *raw ? raw : fallback, &k);
    for (int d = 2; taken(N, s); d++)
        snprintf(s + k, 16, "_%d", d);
    if (N->n == N->cap) {
        N->cap = N->cap ? 2 * N->cap : 64;
        N->name = xrealloc(N->name, (size_t)N->cap * sizeof *N->name);
    }
    return N->name[N->n++] = s;
}

static void
names_free(Names *N)
{
    for (int i = 0; i < N->n; i++)
        free(N->name[i]);
    free(N->name);
}

static const char *
num(char *buf, double x)
{
    return num_shortest(buf, x);
}

static void
put_vec(FILE *f, const double *v)
{
    char a[NUM_MAX], b[NUM_MAX], c[NUM_MAX];
    fprintf(f, "[%s, %s, %s]", num(a, v[0]), num(b, v[1]), num(c, v[2]));
}

static int
is_zero3(const double *v)
{
    return v[0] == 0 && v[1] == 0 && v[2] == 0;
}

/* R (row-major) of a unit quaternion (w, x, y, z). */
static void
quat_mat(const double *q, double *R)
{
    double w = q[0], x = q[1], y = q[2], z = q[3];
    R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - w * z), R[2] = 2 * (x * z + w * y);
    R[3] = 2 * (x * y + w * z), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - w * x);
    R[6] = 2 * (x * z - w * y), R[7] = 2 * (y * z + w * x), R[8] = 1 - 2 * (x * x + y * y);
}

/* A constant turn by quaternion q, not the identity, as `{axis: [...],
 * angle: ...}`. */
static void
put_fixed_turn(FILE *f, const double *q)
{
    double w = q[0], s = sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    double axis[3] = {q[1] / s, q[2] / s, q[3] / s};
    char a[NUM_MAX];
    fputs("{axis: ", f);
    put_vec(f, axis);
    fprintf(f, ", angle: %s}", num(a, 2 * atan2(s, w)));
}

/* What this slice cannot import yet, by name: a reason in err, else 0. */
static int
refused(const mjModel *m, char *err, size_t len)
{
    for (int j = 0; j < m->njnt; j++) {
        const char *nm = m->names + m->name_jntadr[j];
        int dof = m->jnt_dofadr[j];
        if (m->jnt_type[j] != mjJNT_HINGE && m->jnt_type[j] != mjJNT_SLIDE)
            return snprintf(err, len, "joint %s: %s joints are not imported yet", nm,
                            m->jnt_type[j] == mjJNT_BALL ? "ball" : "free");
        if (m->dof_armature[dof] != 0)
            return snprintf(err, len, "joint %s: its armature is not imported yet", nm);
    }
    if (m->nu > 0)
        return snprintf(err, len, "actuator %s: actuators are not imported yet",
                        m->names + m->name_actuatoradr[0]);
    if (m->neq > 0)
        return snprintf(err, len, "equality constraint %s: not imported yet",
                        m->names + m->name_eqadr[0]);
    if (m->ntendon > 0)
        return snprintf(err, len, "tendon %s: not imported yet", m->names + m->name_tendonadr[0]);
    return 0;
}

/* What eomc drops, since it simulates smooth dynamics only, each
 * named on warn; their number. */
static int
dropped(const mjModel *m, const char *path, FILE *warn)
{
    int n = 0;
    for (int j = 0; j < m->njnt; j++) {
        const char *nm = m->names + m->name_jntadr[j];
        if (m->jnt_limited[j])
            n++, fprintf(warn, "%s: warning: joint %s: its limits are dropped (eomc simulates "
                         "smooth dynamics: the joint moves past them)\n", path, nm);
        if (m->dof_frictionloss[m->jnt_dofadr[j]] != 0)
            n++, fprintf(warn, "%s: warning: joint %s: its friction loss is dropped (dry "
                         "friction is not smooth dynamics)\n", path, nm);
    }
    int contacts = 0;
    for (int g = 0; g < m->ngeom; g++)
        contacts += m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0;
    if (contacts)
        n++, fprintf(warn, "%s: warning: contacts between its %d colliding geoms are dropped "
                     "(eomc simulates smooth dynamics: bodies pass through one another)\n",
                     path, contacts);
    return n;
}

/* q - ref for joint j: its coordinate alone where ref is 0. */
static void
displacement(char *buf, size_t len, const char *coord, double ref)
{
    char a[NUM_MAX];
    if (ref == 0)
        snprintf(buf, len, "%s", coord);
    else
        snprintf(buf, len, "(%s - %s)", coord, num(a, ref));
}

/* The effects, each named so a scene can pick it: gravity; damping, the
 * generalized force -b q' on each joint that has it; stiffness, the
 * potential k/2 (q - springref)^2 (MuJoCo's passive spring force
 * -k (q - qpos_spring)). */
static void
put_effects(const mjModel *m, const char *const *coord, FILE *out)
{
    char a[NUM_MAX], d[400];
    int any = 0;
    if (!is_zero3(m->opt.gravity)) {
        fputs("effects:\n  gravity: {gravity: ", out);
        put_vec(out, m->opt.gravity);
        fputs("}\n", out);
        any = 1;
    }
    int first = 1;
    for (int j = 0; j < m->njnt; j++) {
        double b = m->dof_damping[m->jnt_dofadr[j]];
        if (b == 0)
            continue;
        fprintf(out, "%s%s{work: \"%s*%s'*delta(%s)\"}", any ? "" : "effects:\n",
                first ? "  damping: [" : ", ", num(a, -b), coord[j], coord[j]);
        any = 1, first = 0;
    }
    if (!first)
        fputs("]\n", out);
    first = 1;
    for (int j = 0; j < m->njnt; j++) {
        double k = m->jnt_stiffness[j];
        if (k == 0)
            continue;
        displacement(d, sizeof d, coord[j], m->qpos_spring[m->jnt_qposadr[j]]);
        fprintf(out, "%s%s{potential: \"%s*%s^2\"}", any ? "" : "effects:\n",
                first ? "  stiffness: [" : ", ", num(a, k / 2), d);
        any = 1, first = 0;
    }
    if (!first)
        fputs("]\n", out);
}

int
import_model(const char *path, FILE *out, FILE *warn, int strict, char *err, size_t len)
{
    char load_err[1000] = "";
    mjModel *m = mj_loadXML(path, NULL, load_err, sizeof load_err);
    if (!m) { /* MuJoCo's message on one line: it has line breaks and a trailing one */
        for (char *c = load_err; *c; c++)
            if (*c == '\n')
                *c = ' ';
        for (size_t k = strlen(load_err); k > 0 && load_err[k - 1] == ' '; k--)
            load_err[k - 1] = '\0';
        snprintf(err, len, "MuJoCo cannot load it: %s", load_err);
        return -1;
    }
    if (refused(m, err, len)) {
        mj_deleteModel(m);
        return -1;
    }
    if (dropped(m, path, warn) && strict) {
        snprintf(err, len, "--strict: the elements named above would be dropped");
        mj_deleteModel(m);
        return -1;
    }
    Names N = {0};
    int nb = m->nbody;
    const char **body = xmalloc((size_t)nb * sizeof *body), **axes = xmalloc((size_t)nb * sizeof *axes);
    const char **origin = xmalloc((size_t)nb * sizeof *origin);
    const char **com = xmalloc((size_t)nb * sizeof *com);
    const char **coord = xmalloc(((size_t)m->njnt + 1) * sizeof *coord);
    char fb[64];
    /* coordinates first: joints keep their names (docs/import.md) */
    for (int j = 0; j < m->njnt; j++) {
        snprintf(fb, sizeof fb, "%s_joint%d", m->names + m->name_bodyadr[m->jnt_bodyid[j]], j);
        coord[j] = unique(&N, m->names + m->name_jntadr[j], fb);
    }
    body[0] = "world", axes[0] = "world", origin[0] = "origin";
    for (int b = 1; b < nb; b++) {
        snprintf(fb, sizeof fb, "body%d", b);
        body[b] = unique(&N, m->names + m->name_bodyadr[b], fb);
    }
    size_t k;
    char *model = ident(*m->names ? m->names : "imported", &k); /* the model's name first */
    const char *dot = strrchr(path, '.');
    fprintf(out, "# Imported by `eomc import` from %s: MuJoCo's compiled model, its\n"
                 "# bodies, joints, inertias and effects (docs/import.md).\n", path);
    fprintf(out, "name: %s\n", model);
    fprintf(out, "description: \"%s, imported from %s.\"\n", model,
            dot && !strcmp(dot, ".urdf") ? "URDF" : "MJCF");
    free(model);
    fputs("coordinates: [", out);
    for (int j = 0; j < m->njnt; j++)
        fprintf(out, "%s%s", j ? ", " : "", coord[j]);
    fputs("]\n", out);

    /* frames and points, body by body (parents come first in MuJoCo's order) */
    char *fr = NULL, *pt = NULL;
    size_t frn = 0, ptn = 0;
    FILE *F = open_memstream(&fr, &frn), *P = open_memstream(&pt, &ptn);
    char a[NUM_MAX], nm[300];
    for (int b = 1; b < nb; b++) {
        int p = m->body_parentid[b];
        const char *cur = axes[p];
        snprintf(nm, sizeof nm, "%s_origin", body[b]);
        const char *o = unique(&N, nm, nm);
        fprintf(P, "  %s: {frame: %s, from: %s, at: ", o, axes[p], origin[p]);
        put_vec(P, m->body_pos + 3 * b);
        fputs("}\n", P);
        const double *bq = m->body_quat + 4 * b;
        if (bq[1] != 0 || bq[2] != 0 || bq[3] != 0) { /* not a turn by 0 (or 2 pi) */
            snprintf(nm, sizeof nm, "%s_fixed", body[b]);
            const char *fx = unique(&N, nm, nm);
            fprintf(F, "  %s: {parent: %s, rotation: [", fx, cur);
            put_fixed_turn(F, bq);
            fputs("]}\n", F);
            cur = fx;
        }
        for (int k = 0; k < m->body_jntnum[b]; k++) {
            int j = m->body_jntadr[b] + k;
            double ref = m->qpos0[m->jnt_qposadr[j]];
            const double *ax = m->jnt_axis + 3 * j, *an = m->jnt_pos + 3 * j;
            char angle[400]; /* q - ref, in parentheses where ref is not 0 */
            displacement(angle, sizeof angle, coord[j], ref);
            if (m->jnt_type[j] == mjJNT_SLIDE) {
                snprintf(nm, sizeof nm, "%s_at", coord[j]);
                const char *s = unique(&N, nm, nm);
                fprintf(P, "  %s: {frame: %s, from: %s, at: [", s, cur, o);
                for (int c = 0; c < 3; c++) {
                    fputs(c ? ", " : "", P);
                    if (ax[c] == 0 || ax[c] == 1 || ax[c] == -1)
                        fprintf(P, "%s%s", ax[c] < 0 ? "-" : "", ax[c] ? angle : "0");
                    else
                        fprintf(P, "%s*%s", num(a, ax[c]), angle);
                }
                fputs("]}\n", P);
                o = s;
                continue;
            }
            if (!is_zero3(an)) { /* the turn's pivot, then back to the origin */
                snprintf(nm, sizeof nm, "%s_anchor", coord[j]);
                const char *an_pt = unique(&N, nm, nm);
                fprintf(P, "  %s: {frame: %s, from: %s, at: ", an_pt, cur, o);
                put_vec(P, an);
                fputs("}\n", P);
                o = an_pt;
            }
            snprintf(nm, sizeof nm, "%s_axes", coord[j]);
            const char *t = unique(&N, nm, nm);
            fprintf(F, "  %s: {parent: %s, rotation: [{axis: ", t, cur);
            put_vec(F, ax);
            fprintf(F, ", angle: \"%s\"}]}\n", angle);
            cur = t;
            if (!is_zero3(an)) {
                double back[3] = {-an[0], -an[1], -an[2]};
                snprintf(nm, sizeof nm, "%s_origin", coord[j]);
                const char *bo = unique(&N, nm, nm);
                fprintf(P, "  %s: {frame: %s, from: %s, at: ", bo, cur, o);
                put_vec(P, back);
                fputs("}\n", P);
                o = bo;
            }
        }
        axes[b] = cur;
        origin[b] = o;
        snprintf(nm, sizeof nm, "%s_com", body[b]);
        com[b] = unique(&N, nm, nm);
        fprintf(P, "  %s: {frame: %s, from: %s, at: ", com[b], cur, o);
        put_vec(P, m->body_ipos + 3 * b);
        fputs("}\n", P);
    }
    fclose(F);
    fclose(P);
    if (frn)
        fprintf(out, "frames:\n%s", fr);
    fprintf(out, "points:\n%s", pt);
    free(fr);
    free(pt);
    fputs("bodies:\n", out);
    for (int b = 1; b < nb; b++) {
        if (m->body_mass[b] == 0)
            continue;
        double R[9], I[9], d[3] = {m->body_inertia[3 * b], m->body_inertia[3 * b + 1],
                                   m->body_inertia[3 * b + 2]};
        quat_mat(m->body_iquat + 4 * b, R);
        for (int r = 0; r < 3; r++) /* one triangle, mirrored: symmetric exactly */
            for (int c = r; c < 3; c++)
                I[3 * r + c] = I[3 * c + r] = R[3 * r] * d[0] * R[3 * c] +
                                              R[3 * r + 1] * d[1] * R[3 * c + 1] +
                                              R[3 * r + 2] * d[2] * R[3 * c + 2];
        fprintf(out, "  %s: {mass: %s, frame: %s, center: %s, inertia: [", body[b],
                num(a, m->body_mass[b]), axes[b], com[b]);
        for (int r = 0; r < 3; r++) {
            fputs(r ? ", " : "", out);
            put_vec(out, I + 3 * r);
        }
        fputs("]}\n", out);
    }
    put_effects(m, coord, out);
    int any = 0;
    for (int j = 0; j < m->njnt; j++)
        if (m->qpos0[m->jnt_qposadr[j]] != 0) {
            fprintf(out, "%s  %s: %s\n", any++ ? "" : "initial:\n", coord[j],
                    num(a, m->qpos0[m->jnt_qposadr[j]]));
        }
    fputs("scene: {t_end: 1, dt: 0.01}\n", out);
    free(body);
    free(axes);
    free(origin);
    free(com);
    free(coord);
    names_free(&N);
    mj_deleteModel(m);
    return 0;
}

#else

int
import_available(void)
{
    return 0;
}

int
import_model(const char *path, FILE *out, FILE *warn, int strict, char *err, size_t len)
{
    (void)path;
    (void)out;
    (void)warn;
    (void)strict;
    snprintf(err, len, "this eomc was built without MuJoCo, which reads MJCF and URDF: "
             "install libmujoco-dev and build it again");
    return -1;
}

#endif

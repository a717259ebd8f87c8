/*
 * import: MuJoCo's compiled model (mjModel) printed as an eomc spec.
 *
 * MuJoCo places body b in its parent p by a constant offset and turn
 * (body_pos, body_quat), then applies b's joints in order: a hinge turns
 * the body about its axis through its anchor (jnt_pos, in the body's axes)
 * by q - qpos0, a ball by its quaternion about the anchor, a slide moves it
 * along its axis by q - qpos0; a free joint alone places its body in the
 * world.  Here that is a frame per turn and a point per offset, so the
 * spec is the tree the recursive forms take: the anchor is each turn's
 * pivot.  The inertia, principal moments about body_ipos in the axes
 * body_iquat turns to, is printed as the full tensor in the body's axes.
 *
 * Effects: gravity, damping, stiffness, fluid (MuJoCo's inertia-box
 * model of the medium), armature (kinetic terms of one joint's rates),
 * limits (a hinge's or slide's, as compliant stops) and actuators (virtual
 * work of an input each, clamped to their ranges as MuJoCo clamps them;
 * actuators_unclamped beside), joint inputs (tau_J's virtual work on its
 * joint: a URDF's always, an MJCF's with --joint-inputs); connect and
 * joint equalities are exact
 * holonomic constraints.  What the model's <flag>s disable is left out,
 * as mj_forward leaves it out, with a note.  What the importer cannot
 * write is refused by name; what eomc does not simulate (a ball's and a
 * tendon's limits, friction loss, contacts) is dropped, one warning per
 * kind (--strict: an error).  With --parameters, the masses, inertias,
 * damping, stiffness and armature are named parameters, their defaults
 * the model's values.
 *
 * One file past ~800 lines: every element of mjModel it prints shares the
 * naming (identifiers, collisions, renames) and the placement in the
 * tree above, and it is the one file that knows MuJoCo's structures.
 */
#include "import.h"
#include "import_contact.h"
#include "import_urdf.h"

#include "runtime/base/numfmt.h"
#include "base/arena.h"

#include <limits.h>
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
    FILE *warn; /* where a renamed element is told */
    const char *path;
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

/* unique() for an element's name that the user reads (a joint, body,
 * tendon, actuator's input or equality): where it had to take a suffix
 * since another has its name, a warning says so. */
static const char *
named(Names *N, const char *kind, const char *raw, const char *fallback)
{
    const char *s = unique(N, raw, fallback);
    size_t k;
    const char *from = raw && *raw ? raw : fallback;
    char *want = ident(from, &k);
    if (strcmp(s, want))
        fprintf(N->warn, "%s: warning: renamed: %s '%s' is '%s' in the spec ('%s' is another's "
                "name)\n", N->path, kind, from, s, want);
    free(want);
    return s;
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

/* The element an error is about, for its position in the file: its name,
 * and the MJCF elements an object of its type is written as, in which
 * section (a joint in a body, not an equality's `<joint>`; an actuator's
 * `<motor>`, not the `<site>` of the same name it acts at). */
static void
blame(ImportWhere *at, const mjModel *m, int type, int id)
{
    const char *nm = mj_id2name(m, type, id);
    snprintf(at->name, sizeof at->name, "%s", nm ? nm : "");
    switch (type) {
    case mjOBJ_JOINT:
        at->tags = "joint freejoint", at->section = "worldbody";
        break;
    case mjOBJ_ACTUATOR:
        at->tags = "general motor position velocity cylinder muscle adhesion intvelocity "
                   "damper plugin";
        at->section = "actuator";
        break;
    case mjOBJ_EQUALITY:
        at->tags = "connect weld joint tendon distance flex", at->section = "equality";
        break;
    case mjOBJ_TENDON:
        at->tags = "fixed spatial", at->section = "tendon";
        break;
    }
}

/* An element's name for messages: MuJoCo's, or its kind and index. */
static const char *
label(const mjModel *m, int type, int id, char *buf, size_t len)
{
    const char *nm = mj_id2name(m, type, id);
    if (nm && *nm)
        return nm;
    snprintf(buf, len, "#%d", id);
    return buf;
}

/* Does the importer write actuator i as an input (a motor or a servo of
 * fixed or affine gain and affine bias, on a hinge or slide), or why not. */
/* Is tendon t fixed: a linear combination of joint coordinates (MuJoCo's
 * `fixed` tendon), not a spatial path through sites and wrapping geoms? */
static int
fixed_tendon(const mjModel *m, int t)
{
    for (int w = m->tendon_adr[t]; w < m->tendon_adr[t] + m->tendon_num[t]; w++)
        if (m->wrap_type[w] != mjWRAP_JOINT)
            return 0;
    return 1;
}

static const char *
actuator_refused(const mjModel *m, int i)
{
    int trn = m->actuator_trntype[i], j = m->actuator_trnid[2 * i];
    if (trn == mjTRN_TENDON) {
        if (!fixed_tendon(m, j))
            return "only actuators on fixed tendons are imported (not on spatial ones)";
    } else if (trn != mjTRN_JOINT && trn != mjTRN_JOINTINPARENT) {
        return "only actuators on joints and fixed tendons are imported (not on sites, "
               "bodies or slider-cranks)";
    } else if (m->jnt_type[j] != mjJNT_HINGE && m->jnt_type[j] != mjJNT_SLIDE) {
        return "only actuators on hinge and slide joints are imported";
    }
    if (m->actuator_dyntype[i] != mjDYN_NONE)
        return "its activation dynamics (dyntype) is not imported: the control must be the "
               "force's input itself";
    if (m->actuator_gaintype[i] != mjGAIN_FIXED && m->actuator_gaintype[i] != mjGAIN_AFFINE)
        return "its gain (muscle or user) is not imported";
    if (m->actuator_biastype[i] != mjBIAS_NONE && m->actuator_biastype[i] != mjBIAS_AFFINE)
        return "its bias (muscle or user) is not imported";
    return NULL;
}

static int
scalar_joint(const mjModel *m, int j)
{
    return m->jnt_type[j] == mjJNT_HINGE || m->jnt_type[j] == mjJNT_SLIDE;
}

/* MuJoCo's <option><flag>s (mjOption's disableflags): what its mj_forward
 * leaves out, the spec leaves out too (docs/import.md lists every flag). */
static int
disabled(const mjModel *m, int bits)
{
    return (m->opt.disableflags & bits) != 0;
}

static int
gravity_on(const mjModel *m)
{
    return !disabled(m, mjDSBL_GRAVITY) && !is_zero3(m->opt.gravity);
}

/* springs, damping and fluid forces (mj_passive) */
static int
passive_on(const mjModel *m)
{
    return !disabled(m, mjDSBL_PASSIVE);
}

/* The actuators MuJoCo applies: none where actuation is disabled. */
static int
actuators(const mjModel *m)
{
    return disabled(m, mjDSBL_ACTUATION) ? 0 : m->nu;
}

/* Joint j's limit, where MuJoCo computes it (flags limit and constraint),
 * as a stop: a hinge's or a slide's (a ball's, on its angle of rotation,
 * is dropped). */
static int
stop_of(const mjModel *m, int j)
{
    return m->jnt_limited[j] && !disabled(m, mjDSBL_LIMIT | mjDSBL_CONSTRAINT) &&
           scalar_joint(m, j);
}

/* Is actuator i's control clamped to its ctrlrange (flag clampctrl)? */
static int
ctrl_clamped(const mjModel *m, int i)
{
    return m->actuator_ctrllimited[i] && !disabled(m, mjDSBL_CLAMPCTRL);
}

/* MuJoCo's soft limit of joint j as a stop's stiffness k and damping c
 * (docs/import.md, "Joint limits and actuator ranges").  In constraint
 * space MuJoCo's limit obeys a + d (b v + k_r r) = (1 - d) a0 (a0 the
 * acceleration without it, d the impedance of solimp); its part free of
 * a0 is the force m_eff d (-b v - k_r r) on the joint, m_eff = 1/(M^-1)_jj
 * at qpos0 (MuJoCo's dof_invweight0 is that diagonal).  solref (timeconst,
 * dampratio) gives b = 2/(dmax timeconst), k_r = d/(dmax timeconst
 * dampratio)^2, and (-stiffness, -damping) b = damping/dmax, k_r =
 * stiffness d/dmax^2; with d at its dmax, d cancels:
 *   k = m_eff/(timeconst dampratio)^2, c = 2 m_eff/timeconst, or
 *   k = m_eff stiffness,               c = m_eff damping.
 * timeconst is at least twice the time step, as MuJoCo makes it (flag
 * refsafe). */
static void
stop_constants(const mjModel *m, int j, double *k, double *c)
{
    const double *ref = m->jnt_solref + mjNREF * j;
    double meff = 1 / m->dof_invweight0[m->jnt_dofadr[j]];
    if (ref[0] > 0) {
        double tc = ref[0], dr = ref[1];
        if (!disabled(m, mjDSBL_REFSAFE))
            tc = fmax(tc, 2 * m->opt.timestep);
        *k = meff / fmax(mjMINVAL, tc * tc * dr * dr); /* (MuJoCo's guard too) */
        *c = 2 * meff / tc;
    } else {
        *k = -ref[0] * meff;
        *c = -ref[1] * meff;
    }
}

/* Does equality constraint e hold: active, and not disabled (the flag
 * equality, or constraint, which disables every constraint)? */
static int
eq_on(const mjModel *m, int e)
{
    return m->eq_active[e] && !disabled(m, mjDSBL_EQUALITY | mjDSBL_CONSTRAINT);
}

/* Whether dof d of joint j has a friction loss that becomes dry friction
 * on its coordinate (effect friction_loss): one MuJoCo computes (not
 * disabled), on a coordinate of its own (a hinge's, a slide's, a free
 * joint's position; a ball's turn has none), in a model without
 * equality constraints (the stuck solve does not take them yet). */
static int
friction_kept(const mjModel *m, int j, int d)
{
    if (m->dof_frictionloss[m->jnt_dofadr[j] + d] == 0 ||
        disabled(m, mjDSBL_FRICTIONLOSS | mjDSBL_CONSTRAINT))
        return 0;
    for (int e = 0; e < m->neq; e++)
        if (eq_on(m, e))
            return 0;
    int type = m->jnt_type[j];
    return type == mjJNT_HINGE || type == mjJNT_SLIDE || (type == mjJNT_FREE && d < 3);
}

enum { FLUID_NONE, FLUID_BOX, FLUID_ELLIPSOID };

/* MuJoCo's fluid forces (opt.density, opt.viscosity, mj_passive) on body b:
 * by the box of its inertia, by its geoms' ellipsoids where one of them
 * has fluidshape="ellipsoid" (geom_fluid[0] > 0), or none (no medium,
 * passive forces off, no mass, or a body welded to the world, on which a
 * force does nothing). */
static int
fluid_model(const mjModel *m, int b)
{
    if (!passive_on(m) || !(m->opt.viscosity > 0 || m->opt.density > 0) ||
        m->body_mass[b] < mjMINVAL || m->body_weldid[b] == 0)
        return FLUID_NONE;
    for (int g = m->body_geomadr[b]; g < m->body_geomadr[b] + m->body_geomnum[b]; g++)
        if (m->geom_fluid[mjNFLUID * g] > 0)
            return FLUID_ELLIPSOID;
    return FLUID_BOX;
}

/* What MuJoCo's flags leave out of this model, as a list for a note:
 * "gravity (flag gravity), ..."; empty where they leave out nothing it
 * has. */
static void
left_out(const mjModel *m, char *buf, size_t len)
{
    int passive = m->opt.density > 0 || m->opt.viscosity > 0, eqs = 0;
    for (int j = 0; j < m->njnt; j++)
        passive |= m->jnt_stiffness[j] != 0;
    for (int k = 0; k < m->nv; k++)
        passive |= m->dof_damping[k] != 0;
    for (int t = 0; t < m->ntendon; t++)
        passive |= m->tendon_stiffness[t] != 0 || m->tendon_damping[t] != 0;
    for (int e = 0; e < m->neq; e++)
        eqs |= m->eq_active[e];
    const char *what[4] = {
        disabled(m, mjDSBL_GRAVITY) && !is_zero3(m->opt.gravity) ? "gravity (flag gravity)" : NULL,
        disabled(m, mjDSBL_PASSIVE) && passive
            ? "springs, damping and fluid forces (flag passive)" : NULL,
        disabled(m, mjDSBL_ACTUATION) && m->nu ? "actuators (flag actuation)" : NULL,
        !eqs ? NULL : disabled(m, mjDSBL_CONSTRAINT) ? "equality constraints (flag constraint)"
        : disabled(m, mjDSBL_EQUALITY) ? "equality constraints (flag equality)" : NULL};
    size_t k = 0;
    buf[0] = '\0';
    for (int i = 0; i < 4; i++)
        if (what[i] && k < len)
            k += (size_t)snprintf(buf + k, len - k, "%s%s", k ? ", " : "", what[i]);
}

/* What the importer cannot write, by name: a reason in err, else 0.  What
 * a flag disables is not refused: it is left out. */
static int
refused(const mjModel *m, char *err, size_t len, ImportWhere *at)
{
    char b[32];
    for (int j = 0; j < m->njnt; j++) {
        const char *nm = label(m, mjOBJ_JOINT, j, b, sizeof b);
        int type = m->jnt_type[j];
        if ((type == mjJNT_BALL || type == mjJNT_FREE) && m->jnt_stiffness[j] != 0 &&
            passive_on(m))
            return blame(at, m, mjOBJ_JOINT, j), snprintf(err, len, "joint %s: the stiffness of a %s joint is not imported "
                            "(MuJoCo's spring acts on the rotation vector of its quaternion, "
                            "which is not smooth where the turn is zero)", nm,
                            type == mjJNT_BALL ? "ball" : "free");
        if (type == mjJNT_FREE && m->body_jntnum[m->jnt_bodyid[j]] != 1)
            return blame(at, m, mjOBJ_JOINT, j), snprintf(err, len, "joint %s: a free joint with other joints in its body",
                            nm);
    }
    for (int i = 0; i < actuators(m); i++) {
        const char *why = actuator_refused(m, i);
        if (why)
            return blame(at, m, mjOBJ_ACTUATOR, i), snprintf(err, len, "actuator %s: %s", label(m, mjOBJ_ACTUATOR, i, b,
                                                                 sizeof b), why);
    }
    for (int e = 0; e < m->neq; e++) {
        const char *nm = label(m, mjOBJ_EQUALITY, e, b, sizeof b);
        int type = m->eq_type[e], j1 = m->eq_obj1id[e], j2 = m->eq_obj2id[e];
        if (!eq_on(m, e))
            continue;
        if (type == mjEQ_DISTANCE) /* MuJoCo 2.2.2 refuses it itself; later ones lack it */
            return blame(at, m, mjOBJ_EQUALITY, e), snprintf(err, len, "equality constraint %s: a distance constraint", nm);
        if (type == mjEQ_JOINT && (!scalar_joint(m, j1) || (j2 >= 0 && !scalar_joint(m, j2))))
            return blame(at, m, mjOBJ_EQUALITY, e), snprintf(err, len, "equality constraint %s: couples a ball or free joint "
                            "(a joint coupling is between hinges and slides)", nm);
        if (type == mjEQ_TENDON && (!fixed_tendon(m, j1) || (j2 >= 0 && !fixed_tendon(m, j2))))
            return blame(at, m, mjOBJ_EQUALITY, e), snprintf(err, len, "equality constraint %s: couples a spatial tendon (only "
                            "fixed tendons, sums of joint coordinates, are imported)", nm);
    }
    for (int t = 0; t < m->ntendon; t++) {
        const char *nm = label(m, mjOBJ_TENDON, t, b, sizeof b);
        if (!fixed_tendon(m, t) && (m->tendon_stiffness[t] != 0 || m->tendon_damping[t] != 0) &&
            passive_on(m))
            return blame(at, m, mjOBJ_TENDON, t), snprintf(err, len, "tendon %s: the stiffness or damping of a spatial tendon "
                            "(only fixed tendons, sums of joint coordinates, are imported)", nm);
        for (int w = m->tendon_adr[t]; w < m->tendon_adr[t] + m->tendon_num[t]; w++)
            if (m->wrap_type[w] == mjWRAP_JOINT && !scalar_joint(m, m->wrap_objid[w]))
                return blame(at, m, mjOBJ_TENDON, t), snprintf(err, len, "tendon %s: a fixed tendon on a ball or free joint",
                                nm);
    }
    return 0;
}

/* Elements something is dropped from, for one warning: the first few
 * named, the rest counted. */
enum { DROP_NAMED = 6 };
typedef struct Drop {
    int n;
    char names[DROP_NAMED * 104];
} Drop;

static void
drop_add(Drop *d, const char *name)
{
    size_t k = strlen(d->names);
    if (d->n++ < DROP_NAMED)
        snprintf(d->names + k, sizeof d->names - k, "%s%.100s", k ? ", " : "", name);
}

/* "LEVEL: HEADING KIND name (WHY)", or "LEVEL: HEADING n KINDs: a, b, ...
 * and k more (WHY)"; 1, or 0 where d is empty. */
static int
drop_tell(FILE *warn, const char *path, const char *level, const char *heading, const Drop *d,
          const char *kind, const char *why)
{
    if (d->n == 0)
        return 0;
    if (d->n == 1)
        fprintf(warn, "%s: %s: %s %s %s (%s)\n", path, level, heading, kind, d->names, why);
    else if (d->n <= DROP_NAMED)
        fprintf(warn, "%s: %s: %s %d %ss: %s (%s)\n", path, level, heading, d->n, kind,
                d->names, why);
    else
        fprintf(warn, "%s: %s: %s %d %ss: %s and %d more (%s)\n", path, level, heading, d->n,
                kind, d->names, d->n - DROP_NAMED, why);
    return 1;
}

/* "dropped: WHAT KIND name" or "dropped: WHAT n KINDs: a, b, ... and k more"
 * (WHAT may be empty) */
static int
drop_say(FILE *warn, const char *path, const Drop *d, const char *what, const char *kind,
         const char *why)
{
    char heading[100];
    snprintf(heading, sizeof heading, "dropped:%s%s", *what ? " " : "", what);
    return drop_tell(warn, path, "warning", heading, d, kind, why);
}

/* What eomc drops, since it simulates smooth dynamics only, named on
 * warn, one warning for each kind; the number of kinds.  What MuJoCo's
 * flags disable (limits, friction loss, contacts, the clamping of
 * controls) it does not compute either: nothing is dropped there. */
static int
dropped(const mjModel *m, const char *path, FILE *warn)
{
    Drop lim = {0}, fric = {0}, turn = {0};
    char b[32];
    int limits = !disabled(m, mjDSBL_LIMIT | mjDSBL_CONSTRAINT);
    int friction = !disabled(m, mjDSBL_FRICTIONLOSS | mjDSBL_CONSTRAINT);
    for (int j = 0; j < m->njnt; j++) {
        const char *nm = label(m, mjOBJ_JOINT, j, b, sizeof b);
        if (m->jnt_limited[j] && limits && !stop_of(m, j))
            drop_add(&lim, nm);
        int any = 0, kept = 0;
        for (int k = m->jnt_dofadr[j]; k < m->nv && m->dof_jntid[k] == j; k++) {
            any |= m->dof_frictionloss[k] != 0;
            kept |= friction_kept(m, j, k - m->jnt_dofadr[j]);
        }
        if (any && friction && !kept)
            drop_add(m->jnt_type[j] == mjJNT_BALL || m->jnt_type[j] == mjJNT_FREE ? &turn
                                                                                : &fric, nm);
    }
    Drop tlim = {0}, tfric = {0}, spatial = {0};
    for (int t = 0; t < m->ntendon; t++) {
        const char *nm = label(m, mjOBJ_TENDON, t, b, sizeof b);
        if (m->tendon_limited[t] && limits)
            drop_add(&tlim, nm);
        if (m->tendon_frictionloss[t] != 0 && friction)
            drop_add(&tfric, nm);
        if (!fixed_tendon(m, t))
            drop_add(&spatial, nm);
    }
    int n = 0;
    n += drop_say(warn, path, &lim, "the limits of", "ball joint",
                  "MuJoCo's limit on a ball joint's angle of rotation is not imported: the "
                  "joint turns past it");
    n += drop_say(warn, path, &tlim, "the limits of", "tendon",
                  "tendon limits are not imported: tendons stretch past them");
    n += drop_say(warn, path, &fric, "the friction loss of", "joint",
                  "eomc's dry friction does not take equality constraints yet");
    n += drop_say(warn, path, &turn, "the friction loss of the turn of", "joint",
                  "eomc's dry friction acts on a coordinate, and a ball's turn has none");
    n += drop_say(warn, path, &tfric, "the friction loss of", "tendon",
                  "eomc's dry friction acts on a coordinate, not along a tendon");
    n += drop_say(warn, path, &spatial, "", "spatial tendon",
                  "nothing acts along it: no stiffness, damping, actuator or equality "
                  "constraint uses it");
    Drop fluid = {0};
    for (int bb = 1; bb < m->nbody; bb++)
        if (fluid_model(m, bb) == FLUID_ELLIPSOID)
            drop_add(&fluid, label(m, mjOBJ_BODY, bb, b, sizeof b));
    n += drop_say(warn, path, &fluid, "the fluid forces on", "body",
                  "MuJoCo's ellipsoid model of a body's geoms, fluidshape=\"ellipsoid\", is not "
                  "imported; its inertia-box model, the default, is");
    return n;
}

static int drawn(const mjModel *m, int g, int urdf_visuals);

/* Which geoms the spec has a shape for (put_shapes, put_ground), a
 * contact's plane of the world included: [ngeom], to free. */
static unsigned char *
shapes_written(const mjModel *m, int urdf_visuals)
{
    unsigned char *w = xmalloc((size_t)m->ngeom + 1);
    for (int g = 0; g < m->ngeom; g++) {
        int b = m->geom_bodyid[g], t = m->geom_type[g];
        int ground = m->body_weldid[b] == 0 && (b == 0 || m->body_mass[b] == 0);
        w[g] = t != mjGEOM_HFIELD && drawn(m, g, urdf_visuals) &&
               (ground || (t != mjGEOM_PLANE && b != 0 && m->body_mass[b] != 0));
    }
    return w;
}

/* Does the spec have equality constraints (those that hold, eq_on)? */
static int
constrained(const mjModel *m)
{
    for (int e = 0; e < m->neq; e++)
        if (eq_on(m, e))
            return 1;
    return 0;
}

/* The contact pairs eomc's contact cannot take, one warning for each
 * reason; and what it takes otherwise (margins as 0, friction where it
 * can: docs/import.md "Contacts"): the number of kinds. */
static int
contact_drops(const mjModel *m, const ImportContacts *ic, const char *path, FILE *warn)
{
    int n = 0;
    char b1[32], b2[32], nm[80];
    for (int i = 0; i < ic->nskip; i++) {
        int first = 1;
        for (int j = 0; j < i && first; j++)
            first = strcmp(ic->skip[j].why, ic->skip[i].why) != 0;
        if (!first)
            continue;
        Drop d = {0};
        for (int j = i; j < ic->nskip; j++)
            if (!strcmp(ic->skip[j].why, ic->skip[i].why)) {
                snprintf(nm, sizeof nm, "%s-%s", label(m, mjOBJ_GEOM, ic->skip[j].g1, b1,
                                                       sizeof b1),
                         label(m, mjOBJ_GEOM, ic->skip[j].g2, b2, sizeof b2));
                drop_add(&d, nm);
            }
        char why[200];
        snprintf(why, sizeof why, "eomc's contact has no gap for %s", ic->skip[i].why);
        n += drop_say(warn, path, &d, "the contacts of", "geom pair", why);
    }
    /* friction: not written (no plane; equality constraints), or written
     * with less than MuJoCo's (spin, rolling, a second sliding
     * coefficient; an elliptic cone) */
    Drop noplane = {0}, eq = {0}, spin = {0}, roll = {0}, second = {0}, cone = {0}, mg = {0};
    for (int i = 0; i < ic->npair; i++) {
        const ImportPair *p = &ic->pair[i];
        snprintf(nm, sizeof nm, "%s-%s", label(m, mjOBJ_GEOM, p->g1, b1, sizeof b1),
                 label(m, mjOBJ_GEOM, p->g2, b2, sizeof b2));
        if (p->condim > 1 && m->geom_type[p->g1] != mjGEOM_PLANE)
            drop_add(&noplane, nm);
        else if (p->condim > 1 && !p->friction)
            drop_add(&eq, nm);
        if (p->friction && p->condim == 4)
            drop_add(&spin, nm);
        if (p->friction && p->condim == 6)
            drop_add(&roll, nm);
        if (p->friction && p->condim >= 3 && p->mu2 != p->mu)
            drop_add(&second, nm);
        if (p->friction && m->opt.cone == mjCONE_ELLIPTIC)
            drop_add(&cone, nm);
        if (p->margin)
            drop_add(&mg, nm);
    }
    static const char *const said[][2] = { /* (the Drops below, in order) */
        {"the friction of", "eomc's contact friction acts where a shape touches a plane: "
                            "written without friction"},
        {"the friction of", "the model has equality constraints, with which a run refuses "
                            "contact friction: written without friction, so that the model runs"},
        {"the torsional friction of", "condim 4: eomc's contact friction is sliding only, "
                                      "friction[0]; its spin about the normal, friction[1], "
                                      "is free"},
        {"the torsional and rolling friction of", "condim 6: eomc's contact friction is "
                                                  "sliding only, friction[0]; its spin and "
                                                  "rolling, friction[1] and friction[2], are "
                                                  "free"},
        {"the second sliding friction of", "the <pair>'s friction[1] differs from its "
                                           "friction[0]: eomc's contact friction has one "
                                           "coefficient, friction[0], along both of the "
                                           "plane's axes"}};
    Drop *dropped[] = {&noplane, &eq, &spin, &roll, &second};
    for (size_t i = 0; i < sizeof dropped / sizeof *dropped; i++)
        n += drop_say(warn, path, dropped[i], said[i][0], "contact pair", said[i][1]);
    n += drop_tell(warn, path, "warning", "changed: the friction cone of", &cone,
                   "contact pair", "MuJoCo's cone=\"elliptic\" is Coulomb's circle |f| <= mu N; "
                   "eomc's two items per touch point bound the square |f_x|, |f_y| <= mu N "
                   "along the plane's axes: the same along an axis, up to sqrt(2) mu N on a "
                   "diagonal");
    n += drop_say(warn, path, &mg, "the margin or gap of", "contact pair",
                  "eomc's contact begins where the shapes touch");
    return n;
}

/* Geoms the page cannot draw as they are, for a warning each kind: meshes
 * (drawn as the box that bounds them), planes and height fields (not
 * drawn). */
typedef struct Unshaped {
    Drop meshes, planes;
    int plane_floor; /* a contact's plane faces up: the page's floor, so no view: floor: */
    int floors;   /* planes of the world across z: the page's grid stands for them */
    double floor; /* the first one's height */
} Unshaped;

/* Is g one of a URDF's <visual>s: MuJoCo gives them no contacts
 * (contype = conaffinity = 0), its <collision>s contacts. */
static int
visual(const mjModel *m, int g)
{
    return m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0;
}

/* Is geom g drawn?  All are, but in a URDF whose visuals were kept: a
 * link's <collision>s are drawn only where its body has no <visual> (the
 * same link twice, the coarser over the finer, otherwise). */
static int
drawn(const mjModel *m, int g, int urdf_visuals)
{
    if (!urdf_visuals || visual(m, g))
        return 1;
    int b = m->geom_bodyid[g];
    for (int k = m->body_geomadr[b]; k < m->body_geomadr[b] + m->body_geomnum[b]; k++)
        if (visual(m, k))
            return 0;
    return 1;
}

/* A shape's ", pos: [...]" and ", quat: [...]", each where it is not 0
 * and unturned. */
static void
put_placed(FILE *out, const double *pos, const double *quat)
{
    char a[NUM_MAX];
    if (!is_zero3(pos)) {
        fputs(", pos: ", out);
        put_vec(out, pos);
    }
    if (quat[1] != 0 || quat[2] != 0 || quat[3] != 0) {
        fputs(", quat: [", out);
        for (int k = 0; k < 4; k++)
            fprintf(out, "%s%s", k ? ", " : "", num(a, quat[k]));
        fputs("]", out);
    }
}

/* Geom g as a shape (spec.md's `shapes:`) at pos, turned by quat, after
 * sep: 0, or -1 where the page cannot draw it (a plane, a height field;
 * told in *u), a mesh drawn as the box that bounds it (MuJoCo's geom_size
 * of a mesh: the half-sizes of its bounding box about its centroid, in
 * its principal axes, which geom_pos and geom_quat place).  Colours are
 * rounded to 3 decimals (MuJoCo keeps floats). */
static int
put_shape(const mjModel *m, int g, const double *pos, const double *quat, const char *name,
          const char *sep, FILE *out, Unshaped *u)
{
    static const char *const types[mjNGEOMTYPES] = {
        [mjGEOM_SPHERE] = "sphere", [mjGEOM_CAPSULE] = "capsule",
        [mjGEOM_ELLIPSOID] = "ellipsoid", [mjGEOM_CYLINDER] = "cylinder", [mjGEOM_BOX] = "box",
        [mjGEOM_MESH] = "box"};
    static const int nsize[mjNGEOMTYPES] = {
        [mjGEOM_SPHERE] = 1, [mjGEOM_CAPSULE] = 2, [mjGEOM_ELLIPSOID] = 3,
        [mjGEOM_CYLINDER] = 2, [mjGEOM_BOX] = 3, [mjGEOM_MESH] = 3};
    char a[NUM_MAX], b[32], nm[200];
    int t = m->geom_type[g];
    const double *size = m->geom_size + 3 * g;
    int ok = t >= 0 && t < mjNGEOMTYPES && types[t];
    for (int k = 0; ok && k < nsize[t]; k++)
        ok = size[k] > 0 && isfinite(size[k]); /* spec.md: sizes > 0 */
    const char *bn = mj_id2name(m, mjOBJ_BODY, m->geom_bodyid[g]);
    const char *of = m->geom_bodyid[g] == 0 ? "the world" : bn && *bn ? bn : "an unnamed body";
    /* a plane of the world whose normal is z (exactly: a floor is written
     * unturned, or turned about z) is the page's floor: its grid is drawn
     * at its height (view: floor:) */
    const double *gq = quat;
    int up = gq[1] * gq[3] + gq[0] * gq[2] == 0 && gq[2] * gq[3] - gq[0] * gq[1] == 0;
    if (t == mjGEOM_PLANE && name) { /* a contact's: the half-space below it */
        fprintf(out, "%s{type: plane, name: %s", sep, name);
        put_placed(out, pos, quat);
        fputs("}", out);
        u->plane_floor |= up && quat[0] * quat[0] + quat[3] * quat[3] >
                                      quat[1] * quat[1] + quat[2] * quat[2];
        return 0;
    }
    if (!ok) {
        if (t == mjGEOM_PLANE && m->geom_bodyid[g] == 0 && up) {
            if (!u->floors++)
                u->floor = pos[2];
            if (pos[2] == u->floor)
                return -1;
        }
        snprintf(nm, sizeof nm, "%s of %s (%s)", label(m, mjOBJ_GEOM, g, b, sizeof b), of,
                 t == mjGEOM_PLANE ? "a plane" : t == mjGEOM_HFIELD ? "a height field"
                 : "a size of 0");
        drop_add(&u->planes, nm);
        return -1;
    }
    if (t == mjGEOM_MESH) {
        const char *mesh = mj_id2name(m, mjOBJ_MESH, m->geom_dataid[g]);
        snprintf(nm, sizeof nm, "%s of %s (mesh %s)", label(m, mjOBJ_GEOM, g, b, sizeof b), of,
                 mesh && *mesh ? mesh : "unnamed");
        drop_add(&u->meshes, nm);
    }
    fprintf(out, "%s{type: %s", sep, types[t]);
    if (name)
        fprintf(out, ", name: %s", name);
    int ct = m->geom_contype[g], ca = m->geom_conaffinity[g];
    if (name && (ct != 1 || ca != 1)) /* a pair's: MuJoCo's filters, for a `contact: all` */
        fprintf(out, ", contype: %d, conaffinity: %d", ct, ca);
    fputs(", size: [", out);
    for (int k = 0; k < nsize[t]; k++)
        fprintf(out, "%s%s", k ? ", " : "", num(a, size[k]));
    fputs("]", out);
    put_placed(out, pos, quat);
    fputs(", rgba: [", out);
    for (int k = 0; k < 4; k++) {
        double c = round(1000 * (double)m->geom_rgba[4 * g + k]) / 1000;
        fprintf(out, "%s%s", k ? ", " : "", num(a, c < 0 ? 0 : c > 1 ? 1 : c));
    }
    fputs("]}", out);
    return 0;
}

/* Body b's geoms as its `shapes:` (spec.md), in the frame its pose is
 * drawn in: its axes at its centre of mass, so at geom_pos - body_ipos. */
static void
put_shapes(const mjModel *m, int b, int urdf_visuals, const char *const *gname, FILE *out,
           Unshaped *u)
{
    int n = 0;
    for (int g = m->body_geomadr[b]; g < m->body_geomadr[b] + m->body_geomnum[b]; g++) {
        if (!drawn(m, g, urdf_visuals))
            continue;
        double pos[3];
        for (int k = 0; k < 3; k++)
            pos[k] = m->geom_pos[3 * g + k] - m->body_ipos[3 * b + k];
        if (put_shape(m, g, pos, m->geom_quat + 4 * g, gname[g], n ? ", " : ", shapes: [", out,
                      u) == 0)
            n++;
    }
    if (n)
        fputs("]", out);
}

/* The geoms fixed to the world that no body of the spec carries, as its
 * `ground:` (spec.md), in the world's axes: the world body's (a URDF's
 * root link, which MuJoCo fuses into it) and those of bodies welded to
 * it without mass (placed by MuJoCo's kinematics at qpos0). */
static void
put_ground(const mjModel *m, int urdf_visuals, const char *const *gname, FILE *out, Unshaped *u)
{
    mjData *d = NULL;
    int n = 0;
    for (int g = 0; g < m->ngeom; g++) {
        int b = m->geom_bodyid[g];
        if (m->body_weldid[b] != 0 || (b != 0 && m->body_mass[b] != 0) ||
            !drawn(m, g, urdf_visuals))
            continue;
        double pos[3], quat[4];
        if (b == 0) { /* in the world's axes already */
            memcpy(pos, m->geom_pos + 3 * g, sizeof pos);
            memcpy(quat, m->geom_quat + 4 * g, sizeof quat);
        } else {
            if (!d) {
                d = mj_makeData(m);
                mj_kinematics(m, d);
            }
            memcpy(pos, d->geom_xpos + 3 * g, sizeof pos);
            mju_mat2Quat(quat, d->geom_xmat + 9 * g);
        }
        if (put_shape(m, g, pos, quat, gname[g], n ? "\n  - " : "ground:\n  - ", out, u) == 0)
            n++;
    }
    if (n)
        fputs("\n", out);
    if (d)
        mj_deleteData(d);
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

/* Appends c*f to an expression of terms in buf (f NULL: c alone),
 * nothing for c = 0. */
static void
term(char *buf, size_t len, double c, const char *f)
{
    char a[NUM_MAX];
    size_t k = strlen(buf);
    if (c == 0 || k >= len)
        return;
    const char *sep = k ? (c < 0 ? " - " : " + ") : (c < 0 ? "-" : "");
    if (f && fabs(c) == 1)
        snprintf(buf + k, len - k, "%s%s", sep, f);
    else
        snprintf(buf + k, len - k, "%s%s%s%s", sep, num(a, fabs(c)), f ? "*" : "", f ? f : "");
}

/* Is the expression term() wrote a sum of several? */
static int
is_sum(const char *e)
{
    return strstr(e, " + ") || strstr(e, " - ");
}

/* Actuator i's force, MuJoCo's gain * u + bias, for a fixed or affine
 * gain and none or an affine bias of the actuator's length L = gear*J and
 * velocity V = gear*J' (J its joint or tendon), into force. */
static void
actuator_force(char *force, size_t len, const mjModel *m, int i, const char *J, const char *u)
{
    const double *g = m->actuator_gainprm + mjNGAIN * i, *b = m->actuator_biasprm + mjNBIAS * i;
    double gear = m->actuator_gear[6 * i];
    char L[300], V[302], gain[700] = "", a[NUM_MAX];
    snprintf(L, sizeof L, "%s%s%s", gear == 1 ? "" : num(a, gear), gear == 1 ? "" : "*", J);
    snprintf(V, sizeof V, "%s'", L);
    term(gain, sizeof gain, g[0], NULL);
    if (m->actuator_gaintype[i] == mjGAIN_AFFINE) {
        term(gain, sizeof gain, g[1], L);
        term(gain, sizeof gain, g[2], V);
    }
    force[0] = '\0';
    if (*gain && strcmp(gain, "1")) { /* gain*u, in parentheses where a sum */
        snprintf(force, len, is_sum(gain) ? "(%s)*%s" : "%s*%s", gain, u);
    } else if (*gain) {
        snprintf(force, len, "%s", u);
    }
    if (m->actuator_biastype[i] == mjBIAS_AFFINE) {
        term(force, len, b[0], NULL);
        term(force, len, b[1], L);
        term(force, len, b[2], V);
    }
    if (!*force)
        snprintf(force, len, "0");
}

/* Actuator i's force (actuator_force's, or a define of it) as virtual
 * work on its joint or tendon J: gear*force*delta(J). */
static void
actuator_work(char *buf, size_t len, const mjModel *m, int i, const char *J, const char *force)
{
    double gear = m->actuator_gear[6 * i];
    char a[NUM_MAX];
    const char *open = is_sum(force) ? "(" : "", *close = *open ? ")" : "";
    if (gear == 1)
        snprintf(buf, len, "%s%s%s*delta(%s)", open, force, close, J);
    else
        snprintf(buf, len, "%s*%s%s%s*delta(%s)", num(a, gear), open, force, close, J);
}

/* The rate of dof d of joint j (delta: its variation instead): q' for a
 * hinge or slide, a free joint's x', y', z', and for a rotation its speed
 * (vn, by dof: MuJoCo's qvel, the angular velocity in the joint's own
 * axes; delta(w) its virtual rotation). */
static void
dof_rate(char *buf, size_t len, const mjModel *m, const char *const *qn,
         const char *const *vn, int j, int d, int delta)
{
    const char *const *q = qn + m->jnt_qposadr[j];
    int type = m->jnt_type[j];
    if (type == mjJNT_FREE && d < 3) {
        snprintf(buf, len, delta ? "delta(%s)" : "%s'", q[d]);
        return;
    }
    if (type != mjJNT_FREE && type != mjJNT_BALL) {
        snprintf(buf, len, delta ? "delta(%s)" : "%s'", q[0]);
        return;
    }
    snprintf(buf, len, delta ? "delta(%s)" : "%s", vn[m->jnt_dofadr[j] + d]);
}

static int
joint_dofs(const mjModel *m, int j)
{
    switch (m->jnt_type[j]) {
    case mjJNT_FREE: return 6;
    case mjJNT_BALL: return 3;
    default: return 1;
    }
}

/* The model's values --parameters names (NULL: not a parameter, the
 * number is printed): by body, a mass and 6 inertia entries (xx, yy, zz,
 * xy, xz, yz); by joint, its damping, stiffness and armature. */
typedef struct Params {
    const char **mass, **inertia, **damping, **stiffness, **armature;
} Params;

/* A value into buf: parameter name's, else the number x. */
static const char *
value(char *buf, const char *name, double x)
{
    if (name)
        return name;
    return num(buf, x);
}

/* n names, none given yet */
static const char **
no_names(size_t n)
{
    const char **a = xmalloc((n + 1) * sizeof *a);
    for (size_t i = 0; i <= n; i++)
        a[i] = NULL;
    return a;
}

static void
params_free(Params *P)
{
    free(P->mass);
    free(P->inertia);
    free(P->damping);
    free(P->stiffness);
    free(P->armature);
}

/* Whether joint j's dofs share one value of x (by dof; a ball's and a free
 * joint's do, from one attribute of the joint): a parameter can stand
 * for them. */
static int
one_value(const mjModel *m, const double *x, int j)
{
    for (int k = 1; k < joint_dofs(m, j); k++)
        if (x[m->jnt_dofadr[j] + k] != x[m->jnt_dofadr[j]])
            return 0;
    return 1;
}

/* --parameters: the names of the values Params holds, printed as the
 * spec's parameters with the model's values.  Every body with a mass has
 * its mass and inertia (about its centre, in its axes); every joint but a
 * free one its damping and armature, a hinge or slide its stiffness,
 * zeros included, so that a fit can reach them.  A free joint is a
 * body's freedom, not a joint with a motor or a spring: its values stay
 * numbers. */
static void
put_params(const mjModel *m, Names *N, const char *const *body, const char *const *coord,
           const double *inertia, Params *P, FILE *out)
{
    static const char *const entry[6] = {"xx", "yy", "zz", "xy", "xz", "yz"};
    static const int at[6] = {0, 4, 8, 1, 2, 5}; /* their places in the tensor */
    char nm[300], a[NUM_MAX];
    fputs("parameters:\n", out);
    for (int b = 1; b < m->nbody; b++) {
        if (m->body_mass[b] == 0)
            continue;
        snprintf(nm, sizeof nm, "mass_%s", body[b]);
        P->mass[b] = named(N, "parameter", nm, nm);
        fprintf(out, "  %s: %s\n", P->mass[b], num(a, m->body_mass[b]));
        for (int k = 0; k < 6; k++) {
            snprintf(nm, sizeof nm, "inertia_%s_%s", body[b], entry[k]);
            P->inertia[6 * b + k] = named(N, "parameter", nm, nm);
            fprintf(out, "  %s: %s\n", P->inertia[6 * b + k], num(a, inertia[9 * b + at[k]]));
        }
    }
    for (int j = 0; j < m->njnt; j++) {
        int type = m->jnt_type[j], d = m->jnt_dofadr[j];
        if (type == mjJNT_FREE)
            continue;
        if (one_value(m, m->dof_damping, j)) {
            snprintf(nm, sizeof nm, "damping_%s", coord[j]);
            P->damping[j] = named(N, "parameter", nm, nm);
            fprintf(out, "  %s: %s\n", P->damping[j], num(a, m->dof_damping[d]));
        }
        if (scalar_joint(m, j)) {
            snprintf(nm, sizeof nm, "stiffness_%s", coord[j]);
            P->stiffness[j] = named(N, "parameter", nm, nm);
            fprintf(out, "  %s: %s\n", P->stiffness[j], num(a, m->jnt_stiffness[j]));
        }
        if (one_value(m, m->dof_armature, j)) {
            snprintf(nm, sizeof nm, "armature_%s", coord[j]);
            P->armature[j] = named(N, "parameter", nm, nm);
            fprintf(out, "  %s: %s\n", P->armature[j], num(a, m->dof_armature[d]));
        }
    }
}

/* Body b's inertia about its centre in its axes, the full tensor from
 * MuJoCo's principal moments (body_inertia) in the axes body_iquat turns
 * to; one triangle, mirrored: symmetric exactly. */
static void
body_inertia(const mjModel *m, int b, double *I)
{
    double R[9], d[3] = {m->body_inertia[3 * b], m->body_inertia[3 * b + 1],
                         m->body_inertia[3 * b + 2]};
    quat_mat(m->body_iquat + 4 * b, R);
    for (int r = 0; r < 3; r++)
        for (int c = r; c < 3; c++)
            I[3 * r + c] = I[3 * c + r] = R[3 * r] * d[0] * R[3 * c] +
                                          R[3 * r + 1] * d[1] * R[3 * c + 1] +
                                          R[3 * r + 2] * d[2] * R[3 * c + 2];
}

/* k/2*d^2 into buf, without a factor 1 */
static const char *
half_square(char *buf, size_t len, double k, const char *d)
{
    char a[NUM_MAX];
    if (k == 2)
        snprintf(buf, len, "%s^2", d);
    else
        snprintf(buf, len, "%s*%s^2", num(a, k / 2), d);
    return buf;
}

/* k/2*d^2 for a parameter k */
static const char *
half_square_of(char *buf, size_t len, const char *k, const char *d)
{
    snprintf(buf, len, "%s/2*%s^2", k, d);
    return buf;
}

/* The effects written: whether any, and their names ("gravity, damping"),
 * for a scene that lists those it turns on. */
typedef struct Effects {
    int any;
    char on[300];
    int unclamped; /* actuators_unclamped written: not in `on`, off in the scene */
} Effects;

/* Opens effect `name`'s list with its first item, or separates the next. */
static void
item(FILE *out, Effects *E, int *first, const char *name)
{
    if (!E->any)
        fputs("effects:\n", out);
    if (*first) {
        fprintf(out, "  %s: [", name);
        size_t k = strlen(E->on);
        snprintf(E->on + k, sizeof E->on - k, "%s%s", k ? ", " : "", name);
    } else {
        fputs(", ", out);
    }
    E->any = 1, *first = 0;
}

static double
pow4(double x)
{
    return x * x * x * x;
}

/* MuJoCo's fluid forces on body b by its inertia box
 * (mj_inertiaBoxFluidModel): the box of b's mass and principal moments
 * (sides b_k), its centre's velocity v through the medium and its angular
 * velocity w in its principal axes P (the defines flow[0..5]), and for
 * each axis k (i, j the other two, d the box's mean side)
 *   force_k  = -3 pi d mu v_k - rho/2 b_i b_j |v_k| v_k
 *   torque_k = -pi d^3 mu w_k - rho b_k (b_i^4 + b_j^4)/64 |w_k| w_k
 * at its centre: a force and a torque item of the effect fluid. */
static void
put_fluid(const mjModel *m, int b, const char *body, const char *P, const char *const *flow,
          FILE *out)
{
    const double *I = m->body_inertia + 3 * b, mu = m->opt.viscosity, rho = m->opt.density;
    double box[3];
    for (int k = 0; k < 3; k++) /* as MuJoCo computes it, to the last bit */
        box[k] = sqrt(fmax(mjMINVAL, I[(k + 1) % 3] + I[(k + 2) % 3] - I[k]) /
                      m->body_mass[b] * 6.0);
    double diam = (box[0] + box[1] + box[2]) / 3.0;
    for (int torque = 0; torque < 2; torque++) {
        char vec[2000] = "";
        for (int k = 0; k < 3; k++) {
            int i = k == 0 ? 1 : 0, j = k == 2 ? 1 : 2;
            const char *x = flow[3 * torque + k];
            char x2[300], sum[700] = "";
            snprintf(x2, sizeof x2, "abs(%s)*%s", x, x);
            if (mu > 0)
                term(sum, sizeof sum, torque ? -mjPI * diam * diam * diam * mu
                                             : -3.0 * mjPI * diam * mu, x);
            if (rho > 0)
                term(sum, sizeof sum, torque ? -rho * box[k] * (pow4(box[i]) + pow4(box[j])) / 64.0
                                             : -0.5 * rho * box[i] * box[j], x2);
            size_t n = strlen(vec);
            snprintf(vec + n, sizeof vec - n, "%s(%s)*%s.%c", k ? " + " : "", *sum ? sum : "0",
                     P, 'x' + k);
        }
        fprintf(out, "{%s: \"%s\", on: %s}", torque ? "torque" : "force", vec, body);
        fputs(torque ? "" : ", ", out);
    }
}

/* The effects, each named so a scene can pick it: gravity; damping, the
 * generalized force -b v on each dof that has it (v its velocity as
 * MuJoCo's qvel has it); stiffness, the potential k/2 (q - springref)^2
 * (MuJoCo's passive spring force -k (q - qpos_spring)); fluid, MuJoCo's
 * forces of the medium; armature, a rotor's inertia on each dof, 1/2 a
 * v^2 in T; friction_loss, dry friction of at most frictionloss on each
 * coordinate that has it (friction_kept); limits, a stop at each end of a
 * limited hinge's or slide's range (stop_constants); actuators, each
 * one's force on its joint, its control an input, clamped to its ranges
 * as MuJoCo clamps them (ua: the control, clamped where it is; fa: the
 * clamped force's define, or NULL), and where any is clamped,
 * actuators_unclamped, the same unclamped.  What MuJoCo's flags disable
 * is not written.  Into E, what was. */
static void
put_effects(const mjModel *m, const char *const *qn, const char *const *vn,
            const char *const *un, const char *const *ua, const char *const *fa,
            const char *const *tn, const char *const *body, const char *const *principal,
            const char *const *flow, const ImportContacts *ic, const char *const *gname,
            const Params *P, const char *const *jn, FILE *out, Effects *E)
{
    char a[NUM_MAX], d[400], r[400], v[400], hs[900];
    if (gravity_on(m)) {
        fputs("effects:\n  gravity: {gravity: ", out);
        put_vec(out, m->opt.gravity);
        fputs("}\n", out);
        E->any = 1;
        snprintf(E->on, sizeof E->on, "gravity");
    }
    int first = 1, passive = passive_on(m);
    for (int j = 0; j < m->njnt && passive; j++)
        for (int k = 0; k < joint_dofs(m, j); k++) {
            double b = m->dof_damping[m->jnt_dofadr[j] + k];
            if (b == 0 && !P->damping[j])
                continue;
            dof_rate(r, sizeof r, m, qn, vn, j, k, 0);
            dof_rate(v, sizeof v, m, qn, vn, j, k, 1);
            item(out, E, &first, "damping");
            if (P->damping[j])
                fprintf(out, "{work: \"-%s*%s*%s\"}", P->damping[j], r, v);
            else
                fprintf(out, "{work: \"%s*%s*%s\"}", num(a, -b), r, v);
        }
    for (int t = 0; t < m->ntendon && passive; t++) /* a fixed tendon's: -b L' along L */
        if (m->tendon_damping[t] != 0) {
            item(out, E, &first, "damping");
            fprintf(out, "{work: \"%s*%s'*delta(%s)\"}", num(a, -m->tendon_damping[t]), tn[t],
                    tn[t]);
        }
    if (!first)
        fputs("]\n", out);
    first = 1;
    for (int j = 0; j < m->njnt && passive; j++) { /* hinges and slides (import refuses the rest) */
        double k = m->jnt_stiffness[j];
        if (k == 0 && !P->stiffness[j])
            continue;
        const char *q = qn[m->jnt_qposadr[j]];
        displacement(d, sizeof d, q, m->qpos_spring[m->jnt_qposadr[j]]);
        item(out, E, &first, "stiffness");
        fprintf(out, "{potential: \"%s\"}", P->stiffness[j]
                ? half_square_of(hs, sizeof hs, P->stiffness[j], d)
                : half_square(hs, sizeof hs, k, d));
    }
    for (int t = 0; t < m->ntendon && passive; t++) /* a fixed tendon's, about lengthspring */
        if (m->tendon_stiffness[t] != 0) {
            displacement(d, sizeof d, tn[t], m->tendon_lengthspring[t]);
            item(out, E, &first, "stiffness");
            fprintf(out, "{potential: \"%s\"}", half_square(hs, sizeof hs, m->tendon_stiffness[t], d));
        }
    if (!first)
        fputs("]\n", out);
    first = 1;
    for (int b = 1; b < m->nbody; b++)
        if (fluid_model(m, b) == FLUID_BOX) {
            item(out, E, &first, "fluid");
            put_fluid(m, b, body[b], principal[b], flow + 6 * b, out);
        }
    if (!first)
        fputs("]\n", out);
    first = 1;
    for (int j = 0; j < m->njnt; j++)
        for (int k = 0; k < joint_dofs(m, j); k++) {
            double arm = m->dof_armature[m->jnt_dofadr[j] + k];
            if (arm == 0 && !P->armature[j])
                continue;
            dof_rate(r, sizeof r, m, qn, vn, j, k, 0);
            item(out, E, &first, "armature");
            if (P->armature[j])
                fprintf(out, "{kinetic: \"%s/2*%s^2\"}", P->armature[j], r);
            else
                fprintf(out, "{kinetic: \"%s*%s^2\"}", num(a, arm / 2), r);
        }
    if (!first)
        fputs("]\n", out);
    first = 1;
    for (int j = 0; j < m->njnt; j++) /* dry friction, MuJoCo's frictionloss as its force */
        for (int k = 0; k < joint_dofs(m, j); k++) {
            if (!friction_kept(m, j, k))
                continue;
            item(out, E, &first, "friction_loss");
            fprintf(out, "{friction: %s, force: %s}", qn[m->jnt_qposadr[j] + k],
                    num(a, m->dof_frictionloss[m->jnt_dofadr[j] + k]));
        }
    if (!first)
        fputs("]\n", out);
    first = 1;
    for (int j = 0; j < m->njnt; j++)
        if (stop_of(m, j)) {
            double k, c, lo = m->jnt_range[2 * j] + m->jnt_margin[j];
            double hi = m->jnt_range[2 * j + 1] - m->jnt_margin[j];
            char b1[NUM_MAX], b2[NUM_MAX], b3[NUM_MAX];
            stop_constants(m, j, &k, &c);
            item(out, E, &first, "limits");
            fprintf(out, "{limit: %s, range: [%s, %s], stiffness: %s, damping: %s}",
                    qn[m->jnt_qposadr[j]], num(a, lo), num(b1, hi), num(b2, k), num(b3, c));
        }
    if (!first)
        fputs("]\n", out);
    int clamped = 0;
    size_t on = 0;
    for (int pass = 0; pass < 2; pass++) { /* clamped, then without the clamps */
        first = 1;
        on = strlen(E->on);
        for (int i = 0; i < actuators(m); i++) {
            char w[2000], f[1500];
            int id = m->actuator_trnid[2 * i];
            const char *J = m->actuator_trntype[i] == mjTRN_TENDON ? tn[id]
                            : qn[m->jnt_qposadr[id]];
            clamped |= fa[i] || ua[i] != un[i];
            if (pass == 0 && fa[i])
                snprintf(f, sizeof f, "%s", fa[i]);
            else
                actuator_force(f, sizeof f, m, i, J, pass ? un[i] : ua[i]);
            actuator_work(w, sizeof w, m, i, J, f);
            item(out, E, &first, pass ? "actuators_unclamped" : "actuators");
            fprintf(out, "{work: \"%s\"}", w);
        }
        if (!first)
            fputs("]\n", out);
        if (!clamped)
            break;
    }
    if (clamped) /* the scene leaves the unclamped ones out */
        E->on[on] = '\0', E->unclamped = 1;
    first = 1; /* a joint input's: tau_J's virtual work on its dof */
    for (int j = 0; j < m->njnt; j++)
        for (int k = 0; k < joint_dofs(m, j); k++) {
            const char *u = jn[m->jnt_dofadr[j] + k];
            if (!u)
                continue;
            dof_rate(v, sizeof v, m, qn, vn, j, k, 1);
            item(out, E, &first, "joint_inputs");
            fprintf(out, "{work: \"%s*%s\"}", u, v);
        }
    if (!first)
        fputs("]\n", out);
    /* each pair its own law: its effective mass differs (import_contact.c) */
    for (int i = 0; i < ic->npair; i++) {
        const ImportPair *p = &ic->pair[i];
        if (i == 0) {
            fprintf(out, "%s  contacts:\n", E->any ? "" : "effects:\n");
            size_t k = strlen(E->on);
            snprintf(E->on + k, sizeof E->on - k, "%scontacts", k ? ", " : "");
            E->any = 1;
        }
        fprintf(out, "    - {contact: [[%s, %s]], stiffness: %s, ", gname[p->g1], gname[p->g2],
                num(a, p->k));
        fprintf(out, "damping: %s", num(a, p->c));
        if (p->friction)
            fprintf(out, ", friction: %s", num(a, p->mu));
        fputs("}\n", out);
    }
}

/* Scalar e's displacement from its value at qpos0, for an equality
 * constraint: joint e's coordinate (joint: nonzero), or fixed tendon e's
 * length, in parentheses. */
static void
scalar_of(char *buf, size_t len, const mjModel *m, const char *const *qn,
          const char *const *tn, int joint, int e)
{
    char a[NUM_MAX];
    if (joint) {
        int q = m->jnt_qposadr[e];
        displacement(buf, len, qn[q], m->qpos0[q]);
    } else if (m->tendon_length0[e] == 0) {
        snprintf(buf, len, "%s", tn[e]);
    } else {
        snprintf(buf, len, "(%s %s %s)", tn[e], m->tendon_length0[e] < 0 ? "+" : "-",
                 num(a, fabs(m->tendon_length0[e])));
    }
}

/* A row of a connect or weld that has one value at every pose constrains
 * nothing (a planar linkage's connect across its plane), and eomc refuses
 * a constraint free of the coordinates: it is found at CONST_POSES poses
 * drawn at random (every hinge and ball turned anywhere, every slide and
 * free position moved by up to 1) besides qpos0, and dropped with a note
 * where it moves by less than CONST_MOVES of the model's size there (its
 * anchors' largest distance from the origin; 1 for a turn's rows): rounding
 * leaves 1e-16 of it, a row that moves moves by a fraction of a link's
 * length.  A row constant but not 0 there is kept (the constraint cannot
 * hold; the spec's check then names it). */
enum { CONST_POSES = 8 };
#define CONST_MOVES 1e-9

/* The values at d's pose of equality e's rows as put_constraints writes
 * them: the anchors' offset in body 1's axes, then a weld's turn; the
 * size they are measured against into *size (at least what it was). */
static void
eq_rows_at(const mjModel *m, const mjData *d, int e, double *v, double *size)
{
    const double *c = m->eq_data + mjNEQDATA * e;
    int weld = m->eq_type[e] == mjEQ_WELD;
    int b[2] = {m->eq_obj1id[e] < 0 ? 0 : m->eq_obj1id[e],
                m->eq_obj2id[e] < 0 ? 0 : m->eq_obj2id[e]};
    double p[2][3], A[9], R[9];
    for (int k = 0; k < 2; k++) {
        const double *X = d->xmat + 9 * b[k], *x = d->xpos + 3 * b[k];
        const double *an = c + 3 * (weld ? 1 - k : k);
        for (int i = 0; i < 3; i++)
            p[k][i] = x[i] + X[3 * i] * an[0] + X[3 * i + 1] * an[1] + X[3 * i + 2] * an[2];
        *size = fmax(*size, sqrt(p[k][0] * p[k][0] + p[k][1] * p[k][1] + p[k][2] * p[k][2]));
    }
    const double *X1 = d->xmat + 9 * b[0], *X2 = d->xmat + 9 * b[1];
    for (int i = 0; i < 3; i++) /* X1^T (p1 - p2): column i of X1 is its axis i */
        v[i] = X1[i] * (p[0][0] - p[1][0]) + X1[3 + i] * (p[0][1] - p[1][1]) +
               X1[6 + i] * (p[0][2] - p[1][2]);
    v[3] = v[4] = v[5] = 0;
    if (!weld)
        return;
    quat_mat(c + 6, R); /* A = X1 R: body 1's axes turned by the relpose */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            A[3 * i + j] = X1[3 * i] * R[j] + X1[3 * i + 1] * R[3 + j] + X1[3 * i + 2] * R[6 + j];
    for (int k = 0; k < 3; k++) { /* dot(A.j, B.i) - dot(A.i, B.j) */
        int i = (k + 1) % 3, j = (k + 2) % 3;
        v[3 + k] = 0;
        for (int r = 0; r < 3; r++)
            v[3 + k] += A[3 * r + j] * X2[3 * r + i] - A[3 * r + i] * X2[3 * r + j];
    }
}

/* empty[6 e + r]: row r of connect or weld e has one value, 0, at every
 * pose (above). */
static void
empty_rows(const mjModel *m, unsigned char *empty)
{
    mjData *d = mj_makeData(m);
    int ne = m->neq;
    double *lo = xmalloc(12 * ((size_t)ne + 1) * sizeof *lo), *hi = lo + 6 * ne;
    double size = 0, v[6];
    unsigned long long x = 0x9e3779b97f4a7c15u; /* a fixed seed: the same spec every time */
    for (int pose = 0; pose <= CONST_POSES; pose++) {
        mju_copy(d->qpos, m->qpos0, m->nq);
        for (int j = 0; pose > 0 && j < m->njnt; j++) {
            int type = m->jnt_type[j], q = m->jnt_qposadr[j];
            int nq = type == mjJNT_FREE ? 7 : type == mjJNT_BALL ? 4 : 1;
            for (int k = 0; k < nq; k++) { /* in [-1, 1) */
                x = x * 6364136223846793005u + 1442695040888963407u; /* Knuth's MMIX */
                double r = (double)(x >> 11) * 0x1p-52 - 1;
                d->qpos[q + k] = type == mjJNT_HINGE ? r * mjPI : r;
            }
            if (type == mjJNT_BALL || type == mjJNT_FREE)
                mju_normalize4(d->qpos + q + nq - 4);
        }
        mj_kinematics(m, d);
        for (int e = 0; e < ne; e++) {
            int type = m->eq_type[e];
            if (!m->eq_active[e] || (type != mjEQ_CONNECT && type != mjEQ_WELD))
                continue;
            eq_rows_at(m, d, e, v, &size);
            for (int r = 0; r < 6; r++) {
                lo[6 * e + r] = pose ? fmin(lo[6 * e + r], v[r]) : v[r];
                hi[6 * e + r] = pose ? fmax(hi[6 * e + r], v[r]) : v[r];
            }
        }
    }
    for (int e = 0; e < ne; e++)
        for (int r = 0; r < 6; r++) {
            int type = m->eq_type[e];
            if (!m->eq_active[e] || (type != mjEQ_CONNECT && type != mjEQ_WELD)) {
                empty[6 * e + r] = 0;
                continue;
            }
            double s = r < 3 ? size : 1;
            empty[6 * e + r] = hi[6 * e + r] - lo[6 * e + r] <= CONST_MOVES * s &&
                               fabs(hi[6 * e + r]) <= CONST_MOVES * s &&
                               fabs(lo[6 * e + r]) <= CONST_MOVES * s;
        }
    free(lo);
    mj_deleteData(d);
}

/* The active equality constraints, as holonomic constraints:
 * - a connect as its two anchors' offset in body 1's axes, one constraint
 *   per axis (NAME_x, NAME_y, NAME_z): a planar loop's rows across its
 *   plane are then the same at every pose, wherever the loop turns, and
 *   are dropped (empty_rows), where in the world's axes they would be
 *   dependent on the others with weights that change with the pose;
 * - a weld as the same, and (unless its torquescale is 0, which leaves the
 *   turn free) the turn R = A^T B from body 1's turned axes A to body 2's B
 *   held at the identity by its skew part, R - R^T = 2 sin(th) [n]x:
 *   NAME_rx = dot(A.z, B.y) - dot(A.y, B.z) and its cyclic shifts, whose
 *   rows span MuJoCo's (the quaternion's vector part, sin(th/2) n) there;
 * - a joint or tendon coupling s1 - s1_0 = c0 + c1 (s2 - s2_0) + ... +
 *   c4 (s2 - s2_0)^4 (s_0 their qpos0 values; without a second, c0).
 * The rows of a connect or weld that constrain nothing are named in a
 * note on warn. */
static void
put_constraints(const mjModel *m, const char *const *qn, const char *const *tn,
                const char *const *eqn, const char *const *eqp, const char *const *axes,
                FILE *out, const char *path, FILE *warn)
{
    char d1[400], d2[400];
    int any = 0;
    unsigned char *empty = xmalloc(6 * ((size_t)m->neq + 1));
    empty_rows(m, empty);
    Drop dropped_rows = {0};
    for (int e = 0; e < m->neq; e++) {
        if (!eq_on(m, e))
            continue;
        fputs(any++ ? "" : "constraints:\n", out);
        int type = m->eq_type[e];
        const double *c = m->eq_data + mjNEQDATA * e;
        if (type == mjEQ_CONNECT || type == mjEQ_WELD) {
            int b1 = m->eq_obj1id[e] < 0 ? 0 : m->eq_obj1id[e];
            char row[300];
            for (int k = 0; k < 6; k++) {
                if (k >= 3 && (type == mjEQ_CONNECT || c[10] == 0))
                    break;
                int i = (k + 1) % 3, j = (k + 2) % 3;
                snprintf(row, sizeof row, k < 3 ? "%s_%c" : "%s_r%c", eqn[e], 'x' + k % 3);
                if (empty[6 * e + k]) {
                    drop_add(&dropped_rows, row);
                    continue;
                }
                if (k < 3)
                    fprintf(out, "  %s: \"dot(pos(%s, %s), %s.%c)\"\n", row, eqp[3 * e],
                            eqp[3 * e + 1], axes[b1], 'x' + k);
                else
                    fprintf(out, "  %s: \"dot(%s.%c, %s.%c) - dot(%s.%c, %s.%c)\"\n", row,
                            eqp[3 * e + 2], 'x' + j, axes[m->eq_obj2id[e] < 0 ? 0 : m->eq_obj2id[e]],
                            'x' + i, eqp[3 * e + 2], 'x' + i,
                            axes[m->eq_obj2id[e] < 0 ? 0 : m->eq_obj2id[e]], 'x' + j);
            }
            continue;
        }
        int joint = type == mjEQ_JOINT, s1 = m->eq_obj1id[e], s2 = m->eq_obj2id[e];
        scalar_of(d1, sizeof d1, m, qn, tn, joint, s1);
        char poly[2000] = "";
        term(poly, sizeof poly, c[0], NULL);
        if (s2 >= 0) {
            scalar_of(d2, sizeof d2, m, qn, tn, joint, s2);
            for (int k = 1; k <= 4; k++) {
                char f[420];
                snprintf(f, sizeof f, k == 1 ? "%s" : "%s^%d", d2, k);
                term(poly, sizeof poly, c[k], f);
            }
        }
        if (!*poly)
            fprintf(out, "  %s: \"%s\"\n", eqn[e], d1);
        else if (is_sum(poly))
            fprintf(out, "  %s: \"%s - (%s)\"\n", eqn[e], d1, poly);
        else if (poly[0] == '-')
            fprintf(out, "  %s: \"%s + %s\"\n", eqn[e], d1, poly + 1);
        else
            fprintf(out, "  %s: \"%s - %s\"\n", eqn[e], d1, poly);
    }
    drop_tell(warn, path, "note", "dropped:", &dropped_rows, "constraint row",
              "0 at every pose, it constrains nothing: a planar loop's row across its "
              "plane");
    free(empty);
}

/* The file's text, NUL-ended, or NULL. */
static char *
slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 1 << 16, n = 0, k;
    char *buf = xmalloc(cap);
    while ((k = fread(buf + n, 1, cap - n - 1, f)) > 0)
        if ((n += k) == cap - 1)
            buf = xrealloc(buf, cap *= 2);
    fclose(f);
    buf[n] = '\0';
    *len = n;
    return buf;
}

/* mj_loadXML of text in place of the file at path: MuJoCo's virtual file
 * system holds it under the file's name, and MuJoCo looks there before it
 * reads the disk (mesh files are still read from the model's folder). */
static mjModel *
load_text(const char *path, const char *text, size_t len, char *err, int errlen)
{
    mjVFS *vfs = xmalloc(sizeof *vfs); /* 2 MB of names: not on the stack */
    mj_defaultVFS(vfs);
    mjModel *m = NULL;
    if (len > 0 && len < (size_t)INT_MAX && mj_makeEmptyFileVFS(vfs, path, (int)len) == 0) {
        memcpy(vfs->filedata[mj_findFileVFS(vfs, path)], text, len);
        m = mj_loadXML(path, vfs, err, errlen);
    } else {
        snprintf(err, (size_t)errlen, "the file does not fit MuJoCo's virtual file system");
    }
    mj_deleteVFS(vfs);
    free(vfs);
    return m;
}

/* MuJoCo's model of the file at path, its text (NULL: unread, MuJoCo
 * reads the file and says why it cannot), or NULL with MuJoCo's message in
 * err.  A URDF is loaded with its <visual>s kept (*urdf_visuals 1), for
 * drawing: MuJoCo gives them no mass and no contacts, so the dynamics are
 * those of the file as MuJoCo loads it by default.  Where MuJoCo cannot
 * load them (a mesh file it cannot read), the URDF is loaded as it is
 * (edited, the text as given), with a warning saying why its visuals are
 * not drawn; where the URDF itself cannot be loaded, the error is that
 * load's, on the file's own lines. */
static mjModel *
load(const char *path, const char *text, size_t len, int edited, FILE *warn, int *urdf_visuals,
     char *err, int errlen)
{
    size_t mlen;
    char *mod = text && urdf_is(text) ? urdf_keep_visuals(text, len, &mlen) : NULL;
    *urdf_visuals = 0;
    mjModel *m = NULL;
    if (mod) {
        char why[1000] = "";
        m = load_text(path, mod, mlen, why, sizeof why);
        *urdf_visuals = m != NULL;
        if (!m && (m = edited ? load_text(path, text, len, err, errlen)
                              : mj_loadXML(path, NULL, err, errlen))) {
            for (char *c = why; *c; c++)
                if (*c == '\n')
                    *c = ' ';
            for (size_t k = strlen(why); k > 0 && why[k - 1] == ' '; k--)
                why[k - 1] = '\0';
            fprintf(warn, "%s: warning: the URDF's visuals are not drawn: MuJoCo cannot load "
                    "them (%s); each link is drawn as its collision geoms, else as the box "
                    "of its mass and inertia\n", path, why);
        }
    } else {
        m = edited ? load_text(path, text, len, err, errlen) : mj_loadXML(path, NULL, err, errlen);
    }
    free(mod);
    return m;
}

static void
mimic_add(void *drop, const char *joint)
{
    drop_add(drop, *joint ? joint : "(unnamed)");
}

/* The model at path, as load() loads it; with floating, a URDF whose root
 * links have free joints (import_urdf.h).  A URDF's joints with a <mimic>,
 * which MuJoCo's reader ignores, into *mimic; *urdf whether it is a URDF.
 * NULL with the reason in err, *mujoco set where it is MuJoCo's loader
 * message. */
static mjModel *
load_model(const char *path, int floating, FILE *warn, int *urdf_visuals, Drop *mimic,
           int *urdf, char *err, size_t errlen, int *mujoco)
{
    size_t len = 0, flen;
    char *text = slurp(path, &len), *edit = NULL;
    *mujoco = 0;
    *urdf = text && urdf_is(text);
    if (*urdf)
        urdf_mimics(text, mimic_add, mimic);
    if (floating && text && !urdf_is(text)) {
        snprintf(err, errlen, "--floating frees the root link of a URDF, which MuJoCo welds to "
                 "the world; an MJCF says itself how its bodies move: give its root body a "
                 "<freejoint/>");
        free(text);
        return NULL;
    }
    if (floating && text && !(edit = urdf_floating(text, len, &flen, err, errlen))) {
        free(text);
        return NULL;
    }
    *mujoco = 1;
    mjModel *m = load(path, edit ? edit : text, edit ? flen : len, edit != NULL, warn,
                      urdf_visuals, err, (int)errlen);
    free(edit);
    free(text);
    return m;
}

int
import_model(const char *path, const ImportOptions *opt, FILE *out, FILE *warn, char *err,
             size_t len, ImportWhere *at)
{
    *at = (ImportWhere){0};
    char load_err[1000] = "";
    int urdf_visuals = 0, mujoco, urdf;
    Drop mimic = {0};
    mjModel *m = load_model(path, opt->floating, warn, &urdf_visuals, &mimic, &urdf, load_err,
                            sizeof load_err, &mujoco);
    if (!m && !mujoco) {
        snprintf(err, len, "%s", load_err);
        return -1;
    }
    if (!m) { /* MuJoCo's message on one line: it has line breaks and a trailing one */
        import_where_parse(load_err, at);
        for (char *c = load_err; *c; c++)
            if (*c == '\n')
                *c = ' ';
        for (size_t k = strlen(load_err); k > 0 && load_err[k - 1] == ' '; k--)
            load_err[k - 1] = '\0';
        snprintf(err, len, "MuJoCo cannot load it: %s", load_err);
        return -1;
    }
    if (refused(m, err, len, at)) {
        mj_deleteModel(m);
        return -1;
    }
    int drops = dropped(m, path, warn);
    unsigned char *written = shapes_written(m, urdf_visuals);
    ImportContacts ic;
    import_contacts(m, written, constrained(m), &ic);
    free(written);
    drops += contact_drops(m, &ic, path, warn);
    drops += drop_say(warn, path, &mimic, "the <mimic> of", "joint",
                      "MuJoCo's URDF reader ignores it: the joint moves on its own");
    if (drops && opt->strict) {
        snprintf(err, len, "--strict: the elements named above would be dropped or changed");
        import_contacts_free(&ic);
        mj_deleteModel(m);
        return -1;
    }
    char off[300];
    left_out(m, off, sizeof off);
    if (*off)
        fprintf(warn, "%s: note: left out, as the model's <option><flag> disables them in "
                "MuJoCo too: %s\n", path, off);
    /* bodies have a namespace of their own in a spec; the rest share one */
    Names N = {.warn = warn, .path = path}, NB = N;
    int nb = m->nbody;
    const char **body = xmalloc((size_t)nb * sizeof *body), **axes = xmalloc((size_t)nb * sizeof *axes);
    const char **origin = xmalloc((size_t)nb * sizeof *origin);
    const char **com = xmalloc((size_t)nb * sizeof *com);
    const char **coord = xmalloc(((size_t)m->njnt + 1) * sizeof *coord);
    const char **qn = xmalloc(((size_t)m->nq + 1) * sizeof *qn);
    char fb[64], nm[300];
    /* coordinates first: joints keep their names (docs/import.md); a
     * ball's are its Euler parameters, a free joint's its position and
     * those */
    static const char *const part[7] = {"_x", "_y", "_z", "_qw", "_qx", "_qy", "_qz"};
    for (int j = 0; j < m->njnt; j++) {
        snprintf(fb, sizeof fb, "%s_joint%d", m->names + m->name_bodyadr[m->jnt_bodyid[j]], j);
        coord[j] = named(&N, "joint", m->names + m->name_jntadr[j], fb);
        int adr = m->jnt_qposadr[j], type = m->jnt_type[j];
        int nq = type == mjJNT_FREE ? 7 : type == mjJNT_BALL ? 4 : 1;
        for (int d = 0; d < nq; d++) {
            snprintf(nm, sizeof nm, "%s%s", coord[j], part[d + 7 - nq]);
            qn[adr + d] = nq == 1 ? coord[j] : named(&N, "coordinate", nm, nm);
        }
    }
    /* a rotation's speeds, its angular velocity in its own axes (qvel) */
    const char **vn = xmalloc(((size_t)m->nv + 1) * sizeof *vn);
    for (int j = 0; j < m->njnt; j++) {
        int type = m->jnt_type[j], dof = m->jnt_dofadr[j] + (type == mjJNT_FREE ? 3 : 0);
        for (int r = 0; (type == mjJNT_FREE || type == mjJNT_BALL) && r < 3; r++) {
            snprintf(nm, sizeof nm, "%s_w%c", coord[j], 'x' + r);
            vn[dof + r] = named(&N, "speed", nm, nm);
        }
    }
    body[0] = "world", axes[0] = "world", origin[0] = "origin";
    for (int b = 1; b < nb; b++) {
        snprintf(fb, sizeof fb, "body%d", b);
        body[b] = named(&NB, "body", m->names + m->name_bodyadr[b], fb);
    }
    /* the geoms of contact pairs are named shapes, apart from the bodies */
    const char **gname = xmalloc(((size_t)m->ngeom + 1) * sizeof *gname);
    for (int g = 0; g < m->ngeom; g++)
        gname[g] = NULL;
    for (int i = 0; i < 2 * ic.npair; i++) {
        int g = i % 2 ? ic.pair[i / 2].g2 : ic.pair[i / 2].g1;
        if (gname[g])
            continue;
        snprintf(fb, sizeof fb, "%s_geom%d", body[m->geom_bodyid[g]], g);
        gname[g] = unique(&NB, m->names + m->name_geomadr[g], fb);
    }
    size_t k;
    char *model = ident(*m->names ? m->names : "imported", &k); /* the model's name first */
    const char *dot = strrchr(path, '.');
    fprintf(out, "# Imported by `eomc import` from %s: MuJoCo's compiled model, its\n"
                 "# bodies, joints, inertias and effects (docs/import.md).\n", path);
    if (*off) /* MuJoCo's flags: docs/import.md */
        fprintf(out, "# Left out, as the model's <option><flag> disables them: %s.\n", off);
    fprintf(out, "name: %s\n", model);
    fprintf(out, "description: \"%s, imported from %s.\"\n", model,
            dot && !strcmp(dot, ".urdf") ? "URDF" : "MJCF");
    free(model);
    Params prm = {no_names((size_t)nb), no_names(6 * (size_t)nb), no_names((size_t)m->njnt),
                no_names((size_t)m->njnt), no_names((size_t)m->njnt)};
    double *inertia = xmalloc(9 * (size_t)nb * sizeof *inertia);
    for (int b = 1; b < nb; b++)
        body_inertia(m, b, inertia + 9 * b);
    if (opt->parameters)
        put_params(m, &N, body, coord, inertia, &prm, out);
    fputs("coordinates: [", out);
    for (int q = 0; q < m->nq; q++)
        fprintf(out, "%s%s", q ? ", " : "", qn[q]);
    fputs("]\n", out);
    /* an actuator's control: an input u_NAME, 0 as in MuJoCo's mjData
     * until --set (or a scene) gives it a value or a signal */
    const char **un = xmalloc(((size_t)m->nu + 1) * sizeof *un);
    /* a fixed tendon: a define, its length as MuJoCo's ten_length */
    const char **tn = xmalloc(((size_t)m->ntendon + 1) * sizeof *tn);
    char *df = NULL;
    size_t dfn = 0;
    FILE *D = open_memstream(&df, &dfn); /* the defines, printed after the inputs */
    for (int t = 0; t < m->ntendon; t++) {
        snprintf(fb, sizeof fb, "tendon%d", t);
        tn[t] = named(&N, "tendon", m->names + m->name_tendonadr[t], fb);
        if (!fixed_tendon(m, t))
            continue;
        char len_t[4000] = "";
        for (int w = m->tendon_adr[t]; w < m->tendon_adr[t] + m->tendon_num[t]; w++)
            term(len_t, sizeof len_t, m->wrap_prm[w], qn[m->jnt_qposadr[m->wrap_objid[w]]]);
        fprintf(D, "  %s: \"%s\"\n", tn[t], *len_t ? len_t : "0");
    }
    for (int i = 0; i < actuators(m); i++) {
        const char *an = mj_id2name(m, mjOBJ_ACTUATOR, i);
        int id = m->actuator_trnid[2 * i];
        snprintf(nm, sizeof nm, "u_%s", an && *an ? an
                 : m->actuator_trntype[i] == mjTRN_TENDON ? tn[id] : coord[id]);
        un[i] = named(&N, "input", nm, nm);
        fprintf(out, "%s  %s: 0\n", i ? "" : "inputs:\n", un[i]);
    }
    /* a joint's input tau_J, by dof (a ball's tau_J_x .. _z, about its
     * axes): a URDF has no actuators, so its joints have them always */
    const char **jn = no_names((size_t)m->nv);
    int nin = actuators(m);
    for (int j = 0; j < m->njnt && (urdf || opt->joint_inputs); j++) {
        if (m->jnt_type[j] == mjJNT_FREE)
            continue;
        for (int k = 0; k < joint_dofs(m, j); k++) {
            if (scalar_joint(m, j))
                snprintf(nm, sizeof nm, "tau_%s", coord[j]);
            else
                snprintf(nm, sizeof nm, "tau_%s_%c", coord[j], 'x' + k);
            int d = m->jnt_dofadr[j] + k;
            jn[d] = named(&N, "input", nm, nm);
            fprintf(out, "%s  %s: 0\n", nin++ ? "" : "inputs:\n", jn[d]);
        }
    }
    /* a clamped actuator's control and force, each a define, so that
     * their switches are named after it: ctrl_NAME.clamp.lo, and
     * force_NAME.clamp.hi for the force range MuJoCo clamps gain*u + bias
     * to (before the gear) */
    const char **ua = xmalloc(((size_t)m->nu + 1) * sizeof *ua);
    const char **fa = xmalloc(((size_t)m->nu + 1) * sizeof *fa);
    for (int i = 0; i < actuators(m); i++) {
        const char *base = un[i] + 2; /* u_NAME */
        int id = m->actuator_trnid[2 * i];
        char lo[NUM_MAX], hi[NUM_MAX], f[1500];
        ua[i] = un[i], fa[i] = NULL;
        if (ctrl_clamped(m, i)) {
            snprintf(nm, sizeof nm, "ctrl_%s", base);
            ua[i] = unique(&N, nm, nm);
            fprintf(D, "  %s: \"clamp(%s, %s, %s)\"\n", ua[i], un[i],
                    num(lo, m->actuator_ctrlrange[2 * i]), num(hi, m->actuator_ctrlrange[2 * i + 1]));
        }
        if (m->actuator_forcelimited[i]) {
            actuator_force(f, sizeof f, m, i, m->actuator_trntype[i] == mjTRN_TENDON ? tn[id]
                           : qn[m->jnt_qposadr[id]], ua[i]);
            snprintf(nm, sizeof nm, "force_%s", base);
            fa[i] = unique(&N, nm, nm);
            fprintf(D, "  %s: \"clamp(%s, %s, %s)\"\n", fa[i], f,
                    num(lo, m->actuator_forcerange[2 * i]), num(hi, m->actuator_forcerange[2 * i + 1]));
        }
    }

    /* frames and points, body by body (parents come first in MuJoCo's order) */
    char *fr = NULL, *pt = NULL;
    size_t frn = 0, ptn = 0;
    FILE *F = open_memstream(&fr, &frn), *P = open_memstream(&pt, &ptn);
    char a[NUM_MAX];
    for (int b = 1; b < nb; b++) {
        int p = m->body_parentid[b];
        const char *cur = axes[p];
        if (m->body_jntnum[b] == 1 && m->jnt_type[m->body_jntadr[b]] == mjJNT_FREE) {
            /* MuJoCo places it in the world by its coordinates alone:
             * body_pos and body_quat are only its qpos0 */
            const char **q = qn + m->jnt_qposadr[m->body_jntadr[b]];
            snprintf(nm, sizeof nm, "%s_origin", body[b]);
            origin[b] = unique(&N, nm, nm);
            fprintf(P, "  %s: {at: [%s, %s, %s]}\n", origin[b], q[0], q[1], q[2]);
            snprintf(nm, sizeof nm, "%s_axes", coord[m->body_jntadr[b]]);
            axes[b] = unique(&N, nm, nm);
            const char **w = vn + m->jnt_dofadr[m->body_jntadr[b]] + 3;
            fprintf(F, "  %s: {rotation: [{quaternion: [%s, %s, %s, %s], speeds: [%s, %s, %s]}]}\n",
                    axes[b], q[3], q[4], q[5], q[6], w[0], w[1], w[2]);
            snprintf(nm, sizeof nm, "%s_com", body[b]);
            com[b] = unique(&N, nm, nm);
            fprintf(P, "  %s: {frame: %s, from: %s, at: ", com[b], axes[b], origin[b]);
            put_vec(P, m->body_ipos + 3 * b);
            fputs("}\n", P);
            continue;
        }
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
            if (m->jnt_type[j] == mjJNT_BALL) { /* turned by its Euler parameters */
                const char **q = qn + m->jnt_qposadr[j], **w = vn + m->jnt_dofadr[j];
                fprintf(F, "  %s: {parent: %s, rotation: [{quaternion: [%s, %s, %s, %s], "
                        "speeds: [%s, %s, %s]}]}\n", t, cur, q[0], q[1], q[2], q[3], w[0], w[1],
                        w[2]);
            } else {
                fprintf(F, "  %s: {parent: %s, rotation: [{axis: ", t, cur);
                put_vec(F, ax);
                fprintf(F, ", angle: \"%s\"}]}\n", angle);
            }
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
    /* a body in a medium: its principal axes P (body_iquat in its axes),
     * and the defines BODY_vx .. BODY_vz and BODY_wx .. BODY_wz, its
     * centre's velocity through the medium (less the wind) and its
     * angular velocity in them, by which MuJoCo's fluid forces act */
    const char **principal = xmalloc((size_t)nb * sizeof *principal);
    const char **flow = xmalloc(6 * (size_t)nb * sizeof *flow);
    char wind[300] = "", c1[NUM_MAX], c2[NUM_MAX];
    if (!is_zero3(m->opt.wind))
        snprintf(wind, sizeof wind, " - vec(world, %s, %s, %s)", num(a, m->opt.wind[0]),
                 num(c1, m->opt.wind[1]), num(c2, m->opt.wind[2]));
    for (int b = 1; b < nb; b++) {
        const double *iq = m->body_iquat + 4 * b;
        principal[b] = axes[b];
        if (fluid_model(m, b) != FLUID_BOX)
            continue;
        if (iq[1] != 0 || iq[2] != 0 || iq[3] != 0) {
            snprintf(nm, sizeof nm, "%s_principal", body[b]);
            principal[b] = unique(&N, nm, nm);
            fprintf(F, "  %s: {parent: %s, rotation: [", principal[b], axes[b]);
            put_fixed_turn(F, iq);
            fputs("]}\n", F);
        }
        for (int k = 0; k < 6; k++) {
            char x = (char)('x' + k % 3);
            snprintf(nm, sizeof nm, "%s_%c%c", body[b], k < 3 ? 'v' : 'w', x);
            flow[6 * b + k] = unique(&N, nm, nm);
            if (k < 3)
                fprintf(D, "  %s: \"dot(vel(%s)%s, %s.%c)\"\n", flow[6 * b + k], com[b], wind,
                        principal[b], x);
            else
                fprintf(D, "  %s: \"dot(omega(%s), %s.%c)\"\n", flow[6 * b + k], principal[b],
                        principal[b], x);
        }
    }
    /* a connect's anchors: on body 1 (eq_data 0..2, in its axes) and on
     * body 2 (3..5: where MuJoCo's compiler put the same point at qpos0).
     * A weld's the other way round: 3..5 on body 1 (its relpose), 0..2 on
     * body 2 (its anchor); and body 1's axes turned by the relpose's
     * quaternion (6..9), which the weld holds on body 2's.  eqp: for each
     * equality, the two points and that frame. */
    const char **eqn = xmalloc(((size_t)m->neq + 1) * sizeof *eqn);
    const char **eqp = xmalloc((3 * (size_t)m->neq + 1) * sizeof *eqp);
    for (int e = 0; e < m->neq; e++) {
        snprintf(fb, sizeof fb, "equality%d", e);
        eqn[e] = named(&N, "equality", m->names + m->name_eqadr[e], fb);
        int type = m->eq_type[e];
        if (!eq_on(m, e) || (type != mjEQ_CONNECT && type != mjEQ_WELD))
            continue;
        const double *c = m->eq_data + mjNEQDATA * e;
        for (int k = 0; k < 2; k++) {
            int bb = k ? m->eq_obj2id[e] : m->eq_obj1id[e];
            bb = bb < 0 ? 0 : bb;
            snprintf(nm, sizeof nm, "%s_%d", eqn[e], k + 1);
            const char *an = eqp[3 * e + k] = unique(&N, nm, nm);
            fprintf(P, "  %s: {frame: %s, from: %s, at: ", an, axes[bb], origin[bb]);
            put_vec(P, c + 3 * (type == mjEQ_WELD ? 1 - k : k));
            fputs("}\n", P);
        }
        int b1 = m->eq_obj1id[e] < 0 ? 0 : m->eq_obj1id[e];
        eqp[3 * e + 2] = axes[b1];
        if (type == mjEQ_WELD && (c[7] != 0 || c[8] != 0 || c[9] != 0)) {
            snprintf(nm, sizeof nm, "%s_axes", eqn[e]);
            eqp[3 * e + 2] = unique(&N, nm, nm);
            fprintf(F, "  %s: {parent: %s, rotation: [", eqp[3 * e + 2], axes[b1]);
            put_fixed_turn(F, c + 6);
            fputs("]}\n", F);
        }
    }
    fclose(D);
    fclose(F);
    fclose(P);
    if (dfn)
        fprintf(out, "define:\n%s", df);
    if (frn)
        fprintf(out, "frames:\n%s", fr);
    fprintf(out, "points:\n%s", pt);
    free(df);
    free(fr);
    free(pt);
    fputs("bodies:\n", out);
    Unshaped u = {0};
    for (int b = 1; b < nb; b++) {
        if (m->body_mass[b] == 0)
            continue;
        const double *I = inertia + 9 * b;
        fprintf(out, "  %s: {mass: %s, frame: %s, center: %s, inertia: [", body[b],
                value(a, prm.mass[b], m->body_mass[b]), axes[b], com[b]);
        if (prm.mass[b]) { /* by name, the entries put_params printed */
            const char *const *e = prm.inertia + 6 * b;
            fprintf(out, "[%s, %s, %s], [%s, %s, %s], [%s, %s, %s]", e[0], e[3], e[4], e[3], e[1],
                    e[5], e[4], e[5], e[2]);
        }
        for (int r = 0; r < 3 && !prm.mass[b]; r++) {
            fputs(r ? ", " : "", out);
            put_vec(out, I + 3 * r);
        }
        fputs("]", out);
        put_shapes(m, b, urdf_visuals, gname, out, &u);
        fputs("}\n", out);
    }
    put_ground(m, urdf_visuals, gname, out, &u);
    drop_tell(warn, path, "warning", "drawn as boxes:", &u.meshes, "mesh geom",
              "--animate draws no meshes: each is drawn as the box that bounds it");
    drop_tell(warn, path, "note", "not drawn:", &u.planes, "geom",
              "--animate draws boxes, spheres, capsules, cylinders and ellipsoids, not "
              "planes or height fields");
    Effects E = {0};
    put_effects(m, qn, vn, un, ua, fa, tn, body, principal, flow, &ic, gname, &prm, jn, out, &E);
    put_constraints(m, qn, tn, eqn, eqp, axes, out, path, warn);
    int any = 0;
    for (int q = 0; q < m->nq; q++)
        if (m->qpos0[q] != 0)
            fprintf(out, "%s  %s: %s\n", any++ ? "" : "initial:\n", qn[q], num(a, m->qpos0[q]));
    /* MuJoCo starts at qpos0 and lets its soft equality constraints pull
     * the state onto them; eomc's are exact, so the start is put there */
    int eq = 0;
    for (int e = 0; e < m->neq; e++)
        eq |= eq_on(m, e);
    fputs("scene: {", out);
    if (E.unclamped) /* every effect but the actuators without their ranges */
        fprintf(out, "effects: [%s], ", E.on);
    fprintf(out, "t_end: 1, dt: 0.01%s", eq ? ", assemble: true" : "");
    /* a robot on one free joint walks off the page: the camera follows
     * its base from the start (the page's menu can let it go) */
    int nfree = 0, base = -1;
    for (int j = 0; j < m->njnt; j++)
        if (m->jnt_type[j] == mjJNT_FREE)
            nfree++, base = m->jnt_bodyid[j];
    int floor_put = u.floors && u.floor != 0 && !u.plane_floor; /* the grid is at z = 0 unless told */
    if (floor_put || nfree == 1) {
        fputs(", view: {", out);
        if (floor_put)
            fprintf(out, "floor: %s%s", num(a, u.floor), nfree == 1 ? ", " : "");
        if (nfree == 1)
            fprintf(out, "follow: %s", body[base]);
        fputs("}", out);
    }
    fputs("}\n", out);
    free(gname);
    import_contacts_free(&ic);
    free(body);
    free(axes);
    free(origin);
    free(com);
    free(coord);
    free(qn);
    free(vn);
    free(un);
    free(ua);
    free(fa);
    free(tn);
    free(eqn);
    free(eqp);
    free(principal);
    free(flow);
    free(jn);
    free(inertia);
    params_free(&prm);
    names_free(&N);
    names_free(&NB);
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
import_model(const char *path, const ImportOptions *opt, FILE *out, FILE *warn, char *err,
             size_t len, ImportWhere *at)
{
    (void)path;
    (void)opt;
    (void)out;
    (void)warn;
    *at = (ImportWhere){0};
    snprintf(err, len, "this eomc was built without MuJoCo, which reads MJCF and URDF: "
             "install libmujoco-dev and build it again");
    return -1;
}

#endif

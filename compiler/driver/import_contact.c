/*
 * import_contact: which of a MuJoCo model's geom pairs touch, as MuJoCo's
 * collision driver decides (engine_collision_driver.c, MuJoCo 2.x: its
 * mj_collision and mj_contactFilter, whose rules are followed here, not
 * its code), and the linear spring and damper of eomc's contact
 * (docs/spec.md "Contact") nearest to each pair's soft constraint.
 *
 * Pairs.  With <option collision="all"> (the default) both kinds count:
 *  - dynamic: every two geoms of two bodies that are not welded together,
 *    whose contype and conaffinity agree ((ct1 & ca2) || (ct2 & ca1)),
 *    not of a body and its parent where both move (the flag filterparent,
 *    on unless disabled), not of two bodies an <exclude> names;
 *  - predefined: every <pair>, whatever the filters say; a dynamic pair
 *    of the same two geoms is that one.
 * "pair" keeps the predefined only, "dynamic" the dynamic only.
 *
 * The law.  MuJoCo makes a contact's acceleration along its normal
 *     a = (1 - d) a0 + d (-b v - k r)
 * a0 the acceleration without it, r the penetration (negative), d in
 * (0, 1) the impedance (solimp: dmin at r = 0 to dmax past its width),
 * b = 2 / (dmax tc) and k = d / (dmax^2 tc^2 dr^2) from solref = (tc, dr)
 * (tc at least twice the time step unless refsafe is off; a negative
 * solref = (-K, -B) gives d k = K and d b = B at d = dmax).  At d = dmax
 * the contact's own response, a0 = 0, is that of the force
 *     F = m (k_e pen + b_e pen'),  k_e = 1 / (tc^2 dr^2),  b_e = 2 / tc
 * m the pair's effective mass along the normal: 1 / (n (J1 - J2) M^-1
 * (J1 - J2)^T n) at the geoms' centres at qpos0, n the plane's normal, or
 * for two shapes the mean over the world's axes.  That is eomc's law with
 * k = m k_e, c = m b_e: a touch lasts as long and rebounds as much.  What
 * differs (docs/import.md): MuJoCo's (1 - d) a0 lets only that share of
 * the load press, so its resting contact sinks 1 - dmax as deep (0.05 by
 * default); d rises from dmin over solimp's width; the effective mass is
 * the one at qpos0.
 *
 * Friction.  A MuJoCo contact carries five coefficients: two sliding
 * (along the contact frame's two tangents), one torsional (spin about
 * the normal), two rolling; condim says how many of its directions resist
 * (1: the normal alone, 3: and sliding, 4: and spin, 6: and rolling).
 * MuJoCo's mj_contactParam (in 2.2, which eomc is built with, part of
 * mj_collideGeoms) fills them so:
 *  - a <pair>: its own five, pair_friction, and its own condim;
 *  - a dynamic pair of unequal geom_priority: the higher one's three
 *    (slide, spin, roll), and its condim;
 *  - a dynamic pair of equal priority: each of the three the larger of
 *    the two geoms', condim the larger;
 * a dynamic pair's three spread to five as (slide, slide, spin, roll,
 * roll), so its two sliding directions agree; every coefficient is at
 * least mjMINMU (1e-5).  (MuJoCo 3's <flag override> puts o_friction in
 * their place; 2.2 has no o_friction, and override leaves friction be.)
 * A contact's friction is the one of the pair, so
 * eomc's `friction: mu` of a pair with a plane is friction[0] (mu here,
 * friction[1] mu2); where MuJoCo's cone is pyramidal (the default), its
 * edges n +- mu t1, n +- mu2 t2 bound the tangential force by the diamond
 * |f1|/mu + |f2|/mu2 <= N, t1 and t2 the contact frame's tangents (for a
 * sphere or a box on a plane, mju_makeFrame's from the normal: a level
 * plane's y and x; for a capsule, its axis first), where eomc's two items
 * per touch point bound the square |f1|, |f2| <= mu N along the plane's x
 * and y: the same along an axis they share, mu N; on a diagonal the
 * pyramid holds mu N / sqrt 2, the square sqrt 2 mu N (docs/spec.md
 * "Friction at a contact").  What eomc does not take (a pair
 * without a plane, spin and rolling, mu2 != mu, an elliptic cone, a model
 * with equality constraints) import.c names in warnings.
 */
#include "import_contact.h"

#ifdef EOMC_HAVE_MUJOCO
#include "base/arena.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The pairs a model's code holds at most before those between two free
 * trees are dropped: each is some hundred nodes of the DAG, and 22
 * humanoids' 83 000 took the compiler past 17 GB. */
enum { MAX_PAIRS = 4096 };

/* NULL where eomc's contact takes geom types t1 <= t2 (MuJoCo's order:
 * plane, hfield, sphere, capsule, ellipsoid, cylinder, box, mesh), else why
 * not (docs/spec.md's table). */
static const char *
unsupported(int t1, int t2)
{
    if (t1 == mjGEOM_HFIELD || t2 == mjGEOM_HFIELD)
        return "a height field";
    if (t1 == mjGEOM_MESH || t2 == mjGEOM_MESH)
        return "a mesh (its convex hull has no closed-form gap)";
    if (t1 == mjGEOM_CYLINDER || t2 == mjGEOM_CYLINDER)
        return "a cylinder (the point of its rim nearest a plane has no value on a face)";
    if (t1 == mjGEOM_PLANE)
        return NULL;
    if (t2 <= mjGEOM_CAPSULE)
        return NULL; /* sphere and capsule pairs */
    return "a box or an ellipsoid against a shape other than a plane";
}

/* MuJoCo's filter for a dynamic pair: 1 where it keeps g1, g2. */
static int
kept(const mjModel *m, int g1, int g2)
{
    int b1 = m->geom_bodyid[g1], b2 = m->geom_bodyid[g2];
    int w1 = m->body_weldid[b1], w2 = m->body_weldid[b2];
    if (!((m->geom_contype[g1] & m->geom_conaffinity[g2]) ||
          (m->geom_contype[g2] & m->geom_conaffinity[g1])))
        return 0;
    if (w1 == w2)
        return 0;
    int p1 = m->body_weldid[m->body_parentid[w1]], p2 = m->body_weldid[m->body_parentid[w2]];
    if (!(m->opt.disableflags & mjDSBL_FILTERPARENT) && w1 && w2 && (w1 == p2 || w2 == p1))
        return 0;
    int lo = b1 < b2 ? b1 : b2, hi = b1 < b2 ? b2 : b1, sig = ((lo + 1) << 16) + hi + 1;
    for (int e = 0; e < m->nexclude; e++)
        if (m->exclude_signature[e] == sig)
            return 0;
    return 1;
}

/* Is geoms g1, g2 one of the predefined pairs? */
static int
predefined(const mjModel *m, int g1, int g2)
{
    for (int p = 0; p < m->npair; p++)
        if ((m->pair_geom1[p] == g1 && m->pair_geom2[p] == g2) ||
            (m->pair_geom1[p] == g2 && m->pair_geom2[p] == g1))
            return 1;
    return 0;
}

/* A dynamic pair's solref, condim and sliding friction, mixed as MuJoCo
 * mixes them: the geom of higher priority's, else solref mixed by solmix
 * (standard) or the smaller (direct), condim and friction the larger. */
static void
mixed(const mjModel *m, int g1, int g2, double *solref, int *condim, double *mu)
{
    if (m->geom_priority[g1] != m->geom_priority[g2]) {
        int g = m->geom_priority[g1] > m->geom_priority[g2] ? g1 : g2;
        memcpy(solref, m->geom_solref + mjNREF * g, mjNREF * sizeof *solref);
        *condim = m->geom_condim[g];
        *mu = fmax(mjMINMU, m->geom_friction[3 * g]);
        return;
    }
    double s1 = m->geom_solmix[g1], s2 = m->geom_solmix[g2];
    double mix = s1 >= mjMINVAL && s2 >= mjMINVAL ? s1 / (s1 + s2)
                 : s1 < mjMINVAL && s2 < mjMINVAL ? 0.5 : s1 < mjMINVAL ? 0 : 1;
    const double *r1 = m->geom_solref + mjNREF * g1, *r2 = m->geom_solref + mjNREF * g2;
    for (int i = 0; i < mjNREF; i++)
        solref[i] = r1[0] > 0 && r2[0] > 0 ? mix * r1[i] + (1 - mix) * r2[i]
                                           : fmin(r1[i], r2[i]);
    *condim = m->geom_condim[g1] > m->geom_condim[g2] ? m->geom_condim[g1]
                                                       : m->geom_condim[g2];
    *mu = fmax(mjMINMU, fmax(m->geom_friction[3 * g1], m->geom_friction[3 * g2]));
}

/* The pair's effective mass along its normal at qpos0 (d: mj_forward's
 * there): 1 / (n W n) with W = (J1 - J2) M^-1 (J1 - J2)^T at the geoms'
 * centres, n a plane's normal (g1 a plane) or the mean over the axes;
 * 0 where W n is 0 (nothing moves along it). */
static double
effective_mass(const mjModel *m, mjData *d, int g1, int g2, double *J, double *MJ)
{
    int nv = m->nv;
    double *J2 = J + 3 * nv, *jr = J + 6 * nv;
    mj_jacGeom(m, d, J, jr, g1);
    mj_jacGeom(m, d, J2, jr, g2);
    for (int i = 0; i < 3 * nv; i++)
        J[i] -= J2[i];
    mj_solveM(m, d, MJ, J, 3); /* M^-1 J^T, row by row */
    double W[9];
    mju_mulMatMatT(W, J, MJ, 3, nv, 3);
    double a = 0;
    if (m->geom_type[g1] == mjGEOM_PLANE) {
        const double *R = d->geom_xmat + 9 * g1, n[3] = {R[2], R[5], R[8]};
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                a += n[r] * W[3 * r + c] * n[c];
    } else {
        a = (W[0] + W[4] + W[8]) / 3;
    }
    return a > 0 ? 1 / a : 0;
}

static void
add_skip(ImportContacts *ic, int *cap, int g1, int g2, const char *why)
{
    if (ic->nskip == *cap) {
        *cap = *cap ? 2 * *cap : 16;
        ic->skip = xrealloc(ic->skip, (size_t)*cap * sizeof *ic->skip);
    }
    ic->skip[ic->nskip++] = (ImportSkip){g1, g2, why};
}

/* One pair MuJoCo collides, with its solref (already mixed, or the
 * <pair>'s), condim, sliding friction mu and mu2, margin and gap: taken,
 * or skipped with why. */
static void
consider(const mjModel *m, mjData *d, const unsigned char *written, int constrained, int g1,
         int g2, const double *solref, int condim, double mu, double mu2, double margin,
         double *J, ImportContacts *ic, int *cap, int *skipcap)
{
    if (m->geom_type[g1] > m->geom_type[g2]) { /* MuJoCo's order: the plane first */
        int g = g1;
        g1 = g2, g2 = g;
    }
    int t1 = m->geom_type[g1], t2 = m->geom_type[g2];
    if (t1 == mjGEOM_PLANE && t2 == mjGEOM_PLANE)
        return; /* MuJoCo has no collision of two planes either */
    const char *why = unsupported(t1, t2);
    if (!why && (!written[g1] || !written[g2]))
        why = "a geom the spec has no shape for (on a body without mass, or a URDF "
              "collision geom whose link is drawn by its visual)";
    double me = why ? 0 : effective_mass(m, d, g1, g2, J, J + 9 * m->nv);
    if (!why && me == 0)
        why = "neither geom can move along the contact's normal";
    if (why) {
        add_skip(ic, skipcap, g1, g2, why);
        return;
    }
    if (m->opt.enableflags & mjENBL_OVERRIDE) /* <flag override>: o_solref for all */
        solref = m->opt.o_solref;
    double tc = solref[0], dr = solref[1], k, c;
    if (tc > 0) {
        if (!(m->opt.disableflags & mjDSBL_REFSAFE))
            tc = fmax(tc, 2 * m->opt.timestep);
        k = me / (tc * tc * dr * dr);
        c = 2 * me / tc;
    } else {
        k = me * -tc;
        c = me * -dr;
    }
    if (ic->npair == *cap) {
        *cap = *cap ? 2 * *cap : 16;
        ic->pair = xrealloc(ic->pair, (size_t)*cap * sizeof *ic->pair);
    }
    int friction = condim > 1 && t1 == mjGEOM_PLANE && !constrained;
    ic->pair[ic->npair++] = (ImportPair){g1, g2, k, c, condim, condim > 1 ? mu : 0,
                                         condim > 1 ? mu2 : 0, friction, margin != 0};
}

void
import_contacts(const mjModel *m, const unsigned char *written, int constrained,
                ImportContacts *ic)
{
    *ic = (ImportContacts){0};
    if (m->opt.disableflags & (mjDSBL_CONTACT | mjDSBL_CONSTRAINT))
        return;
    mjData *d = mj_makeData(m);
    mj_forward(m, d); /* at qpos0 */
    double *J = xmalloc((12 * (size_t)m->nv + 1) * sizeof *J); /* J1, J2, jacr, M^-1 J^T */
    int cap = 0, skipcap = 0, condim;
    double solref[mjNREF], mu;
    int all = m->opt.collision == mjCOL_ALL;
    for (int g1 = 0; g1 < m->ngeom && m->opt.collision != mjCOL_PAIR; g1++)
        for (int g2 = g1 + 1; g2 < m->ngeom; g2++) {
            if (!kept(m, g1, g2) || (all && predefined(m, g1, g2)))
                continue;
            mixed(m, g1, g2, solref, &condim, &mu);
            double margin = fmax(m->geom_margin[g1], m->geom_margin[g2]) -
                            fmax(m->geom_gap[g1], m->geom_gap[g2]);
            consider(m, d, written, constrained, g1, g2, solref, condim, mu, mu, margin, J, ic,
                     &cap, &skipcap);
        }
    /* Pairs between two free trees (22 humanoids: 83 000 of them) are each
     * code of the model's: past MAX_PAIRS they are dropped, by name, and
     * the pairs with the world and within a tree kept. */
    if (ic->npair > MAX_PAIRS) {
        int kept = 0;
        for (int i = 0; i < ic->npair; i++) {
            ImportPair *p = &ic->pair[i];
            int r1 = m->body_rootid[m->geom_bodyid[p->g1]], r2 = m->body_rootid[m->geom_bodyid[p->g2]];
            if (r1 != 0 && r2 != 0 && r1 != r2)
                add_skip(ic, &skipcap, p->g1, p->g2, "two free bodies' trees, beyond the "
                         "4096 pairs the code of a model holds (eomc chooses its pairs when it "
                         "compiles; MuJoCo, at each step)");
            else
                ic->pair[kept++] = *p;
        }
        ic->npair = kept;
    }
    for (int p = 0; p < m->npair && m->opt.collision != mjCOL_DYNAMIC; p++)
        consider(m, d, written, constrained, m->pair_geom1[p], m->pair_geom2[p],
                 m->pair_solref + mjNREF * p, m->pair_dim[p],
                 fmax(mjMINMU, m->pair_friction[5 * p]),
                 fmax(mjMINMU, m->pair_friction[5 * p + 1]),
                 m->pair_margin[p] - m->pair_gap[p], J, ic, &cap, &skipcap);
    free(J);
    mj_deleteData(d);
}

void
import_contacts_free(ImportContacts *ic)
{
    free(ic->pair);
    free(ic->skip);
    *ic = (ImportContacts){0};
}

#else
typedef int import_contact_unused; /* a translation unit has a declaration */
#endif

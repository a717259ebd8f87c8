/*
 * MuJoCo's q'' of a model at a random state, in the coordinates of eomc's
 * import: the peer eomc's imported models are checked against
 * (test_import.sh).  Contact, joint limits and friction loss are off.
 * MuJoCo's limits are soft constraints that eomc imports as compliant
 * stops of another law (docs/import.md), so each limited hinge and slide
 * is drawn inside its range (less its margin), where neither acts.
 *
 *   mj_accel MODEL SEED [COUNT] ->  a line of nq coordinates q, a line of
 *                              nv speeds v, a line of nu controls (empty
 *                              without actuators), then v' one per line;
 *                              with COUNT, a block so for each seed SEED ..
 *                              SEED + COUNT - 1 (one process, one load);
 *                              with actuators, on stderr at the end: "a
 *                              control or force clamped at K of N states";
 *                              with MJ_ACCEL_JOINT_INPUTS=1 in the
 *                              environment, a force drawn on each dof of a
 *                              joint but a free one (qfrc_applied: eomc's
 *                              tau_J) and printed after the controls
 *   mj_accel MODEL com    ->   for each line "t q_1 .. q_nq" on stdin (rows of
 *                              an eomc run), "t x y z" of the whole model's
 *                              centre of mass there (MuJoCo's kinematics)
 *   mj_accel MODEL lowest  ->  "z g": the lowest point of the spheres and
 *                              capsules of bodies other than the world at
 *                              qpos0 (a capsule's end sphere), and the
 *                              gravity's size
 *   mj_accel MODEL sinks  ->   "M g", the model's mass and gravity's size,
 *                              then for each line "t q_1 .. q_nq" on stdin
 *                              "t NAME d" for each point of a sphere, a
 *                              capsule's end sphere or a box's corner below
 *                              the plane z = 0 by d > 0 (MuJoCo's kinematics;
 *                              NAME the geom's, or BODY_geomID as eomc's
 *                              import names one without)
 *   mj_accel MODEL rest T ->   MuJoCo's own run of T seconds from qpos0 at its
 *                              step, contact on: its qpos at the end, a line
 *   mj_accel MODEL kinetic ->  for each line "t q_1 .. q_nq v_1 .. v_nv" on
 *                              stdin (eomc's speeds), "t T": MuJoCo's kinetic
 *                              energy there (mj_energyVel: armature included)
 *
 * Controls are clamped to their ranges and forces to theirs as the model
 * says, as the import writes them.  The model's own <option><flag>s stand
 * otherwise (gravity, passive forces, actuation, equality constraints,
 * the clamping of controls disabled: the import leaves out what they
 * disable).  The state: each hinge and slide coordinate, each qvel entry
 * and each control uniform in [-1.5, 1.5] (splitmix64, seeded), a limited
 * joint's coordinate mapped onto its range; a ball's or free joint's
 * quaternion four such numbers normalized.  eomc's coordinates are MuJoCo's qpos and its speeds
 * MuJoCo's qvel: a rotation's are its angular velocity in the joint's own
 * axes (a free joint's after its position's rates, in the world), the
 * import's `speeds:` (docs/import.md).  So v' is qacc.
 *
 * With equality constraints, MuJoCo's own qacc is soft (its solver
 * regularizes them), so this takes MuJoCo's parts of the hard-constrained
 * motion instead: the state is put on the constraints (Newton steps along
 * -J^T (J J^T)^-1 r on MuJoCo's residuals efc_pos and Jacobian efc_J, the
 * velocity projected onto J v = 0), and q'' solves
 *     [M  J^T] [a  ]   [f       ]
 *     [J  0  ] [lam] = [-J' v   ]
 * with MuJoCo's M, f = qfrc_smooth and J, by GSL's LU.  J' v is the rate of
 * J v along the motion, (J(q(s)) v) at s = +-h, +-h/2 (mj_integratePos,
 * constant v) by central differences and Richardson's extrapolation, its
 * error O(h^4) = 1e-12 at h = 1e-3.
 *
 * J's rows may be dependent (a planar loop closed by a connect's three
 * world rows: rank 2), where J J^T and the system above are singular, yet
 * q'' is unique: the rows a pivoted QR of J^T (rows scaled to unit length)
 * finds dependent, |R_kk| <= DEPENDENT, are left out of every solve, the
 * same rows at the shifted states of J' v.  That q'' is also the limit of
 * MuJoCo's own as its regularization goes to 0 (its multipliers are the
 * least-squares ones, its accelerations these).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <mujoco/mujoco.h>

enum { NEWTON_MAX = 50, DRAWS_MAX = 100 };
static const double DIFF_STEP = 1e-3; /* Richardson's h for J' v */
/* on the constraints: residuals below this, in the test models' lengths
 * (about 1), where Newton's steps stop at rounding */
static const double ON_CONSTRAINTS = 1e-12;
/* a row of J (at unit length) whose part independent of the rows before
 * it in QR's order is below this is dependent: rounding leaves 1e-16 */
static const double DEPENDENT = 1e-9;

/* uniform in [-1.5, 1.5), by splitmix64: the same states everywhere */
static double
uniform(uint64_t *s)
{
    uint64_t z = (*s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    z ^= z >> 31;
    return 3 * ((double)(z >> 11) * 0x1p-53) - 1.5;
}

/* The equality rows of the constraint Jacobian and residual at d->qpos
 * (J: ne x nv, row-major); ne.  A row that is zero everywhere is left
 * out: a weld's turn with torquescale 0 (MuJoCo scales those rows by it,
 * and the weld holds only the anchor's position). */
static int
eq_rows(const mjModel *m, mjData *d, double *J, double *r)
{
    mj_fwdPosition(m, d);
    int ne = 0, nv = m->nv;
    for (int i = 0; i < d->nefc; i++) {
        const double *row = d->efc_J + (size_t)i * nv;
        int any = 0;
        for (int k = 0; k < nv; k++)
            any |= row[k] != 0;
        if (d->efc_type[i] == mjCNSTR_EQUALITY && any) {
            memcpy(J + (size_t)ne * nv, row, (size_t)nv * sizeof *J);
            r[ne++] = d->efc_pos[i];
        }
    }
    return ne;
}

/* The rows of J [ne x nv] that QR with column pivoting of J^T (each row
 * at unit length) finds independent, in their own order, into keep;
 * their count. */
static int
independent(int ne, int nv, const double *J, int *keep)
{
    if (ne == 0)
        return 0;
    gsl_matrix *A = gsl_matrix_alloc((size_t)nv, (size_t)ne);
    gsl_vector *tau = gsl_vector_alloc((size_t)(ne < nv ? ne : nv));
    gsl_vector *norm = gsl_vector_alloc((size_t)ne);
    gsl_permutation *p = gsl_permutation_alloc((size_t)ne);
    for (int i = 0; i < ne; i++) {
        double s = 0;
        for (int k = 0; k < nv; k++)
            s += J[i * nv + k] * J[i * nv + k];
        for (int k = 0; k < nv; k++)
            gsl_matrix_set(A, (size_t)k, (size_t)i, J[i * nv + k] / sqrt(s));
    }
    int sign, rank = 0;
    gsl_linalg_QRPT_decomp(A, tau, p, &sign, norm);
    char *kept = calloc((size_t)ne, 1);
    for (int k = 0; k < ne && k < nv; k++)
        if (fabs(gsl_matrix_get(A, (size_t)k, (size_t)k)) > DEPENDENT)
            kept[gsl_permutation_get(p, (size_t)k)] = 1, rank++;
    for (int i = 0, r = 0; i < ne; i++)
        if (kept[i])
            keep[r++] = i;
    free(kept);
    gsl_matrix_free(A);
    gsl_vector_free(tau);
    gsl_vector_free(norm);
    gsl_permutation_free(p);
    return rank;
}

/* J's and r's rows keep [nk] moved to the top. */
static void
compact(int nk, int nv, const int *keep, double *J, double *r)
{
    for (int i = 0; i < nk; i++) {
        memmove(J + (size_t)i * nv, J + (size_t)keep[i] * nv, (size_t)nv * sizeof *J);
        r[i] = r[keep[i]];
    }
}

/* x -= J^T (J J^T)^-1 J x for x of length nv: b = J x, or the given
 * residual r where r is not NULL (then x = -J^T (J J^T)^-1 r); 0, or -1
 * where J J^T is singular (a draw that Newton took to a singular pose). */
static int
project(int ne, int nv, const double *J, const double *r, double *x)
{
    gsl_matrix *A = gsl_matrix_alloc((size_t)ne, (size_t)ne);
    gsl_vector *b = gsl_vector_alloc((size_t)ne), *y = gsl_vector_alloc((size_t)ne);
    for (int i = 0; i < ne; i++) {
        double s = 0;
        for (int k = 0; k < nv; k++)
            s += J[i * nv + k] * x[k];
        gsl_vector_set(b, (size_t)i, r ? r[i] : s);
        for (int j = 0; j < ne; j++) {
            double t = 0;
            for (int k = 0; k < nv; k++)
                t += J[i * nv + k] * J[j * nv + k];
            gsl_matrix_set(A, (size_t)i, (size_t)j, t);
        }
    }
    if (gsl_linalg_cholesky_decomp1(A) != GSL_SUCCESS) {
        gsl_matrix_free(A);
        gsl_vector_free(b);
        gsl_vector_free(y);
        return -1;
    }
    gsl_linalg_cholesky_solve(A, b, y);
    for (int k = 0; k < nv; k++) {
        double s = 0;
        for (int i = 0; i < ne; i++)
            s += J[i * nv + k] * gsl_vector_get(y, (size_t)i);
        x[k] = r ? -s : x[k] - s;
    }
    gsl_matrix_free(A);
    gsl_vector_free(b);
    gsl_vector_free(y);
    return 0;
}

/* J(q(s)) v at q(s) = q moved by s v */
static void
jv_at(const mjModel *m, mjData *w, const double *q, const double *v, double s, double *J,
      double *r, double *out)
{
    memcpy(w->qpos, q, (size_t)m->nq * sizeof *q);
    mj_integratePos(m, w->qpos, v, s);
    int ne = eq_rows(m, w, J, r), nv = m->nv;
    for (int i = 0; i < ne; i++) {
        out[i] = 0;
        for (int k = 0; k < nv; k++)
            out[i] += J[i * nv + k] * v[k];
    }
}

/* The state put on the equality constraints, and the hard-constrained
 * q'' there into d->qacc (see the top).  -1 if Newton does not converge. */
static int
constrained(const mjModel *m, mjData *d)
{
    int nv = m->nv, ne;
    size_t rows = (size_t)d->nefc + 1;
    double *J = calloc(rows * (size_t)nv, sizeof *J), *r = calloc(rows, sizeof *r);
    double *dq = calloc((size_t)nv, sizeof *dq);
    int *keep = calloc(rows, sizeof *keep), nk;
    double last = INFINITY;
    for (int it = 0;; it++) {
        ne = eq_rows(m, d, J, r);
        double rmax = 0;
        for (int i = 0; i < ne; i++)
            rmax = fmax(rmax, fabs(r[i]));
        if (rmax == 0 || rmax >= last || it == NEWTON_MAX)
            break;
        last = rmax;
        nk = independent(ne, nv, J, keep);
        compact(nk, nv, keep, J, r);
        if (project(nk, nv, J, r, dq) != 0)
            break;
        mj_integratePos(m, d->qpos, dq, 1);
    }
    if (last > ON_CONSTRAINTS) {
        free(J), free(r), free(dq), free(keep);
        return -1;
    }
    ne = eq_rows(m, d, J, r);
    nk = independent(ne, nv, J, keep);
    compact(nk, nv, keep, J, r);
    if (project(nk, nv, J, NULL, d->qvel) != 0) {
        free(J), free(r), free(dq), free(keep);
        return -1;
    }
    mj_forward(m, d);
    /* J' v by Richardson's extrapolation of central differences */
    mjData *w = mj_makeData(m);
    double *Jw = calloc(rows * (size_t)nv, sizeof *Jw), *rw = calloc(rows, sizeof *rw);
    double *p = calloc(rows, sizeof *p), *n = calloc(rows, sizeof *n);
    double *g1 = calloc(rows, sizeof *g1), h = DIFF_STEP;
    jv_at(m, w, d->qpos, d->qvel, h, Jw, rw, p);
    jv_at(m, w, d->qpos, d->qvel, -h, Jw, rw, n);
    for (int i = 0; i < nk; i++)
        g1[i] = (p[keep[i]] - n[keep[i]]) / (2 * h);
    jv_at(m, w, d->qpos, d->qvel, h / 2, Jw, rw, p);
    jv_at(m, w, d->qpos, d->qvel, -h / 2, Jw, rw, n);
    int W = nv + nk;
    gsl_matrix *K = gsl_matrix_calloc((size_t)W, (size_t)W);
    gsl_vector *b = gsl_vector_alloc((size_t)W), *x = gsl_vector_alloc((size_t)W);
    double *M = calloc((size_t)nv * (size_t)nv, sizeof *M);
    mj_fullM(m, M, d->qM);
    for (int i = 0; i < nv; i++) {
        for (int k = 0; k < nv; k++)
            gsl_matrix_set(K, (size_t)i, (size_t)k, M[i * nv + k]);
        gsl_vector_set(b, (size_t)i, d->qfrc_smooth[i]);
    }
    for (int i = 0; i < nk; i++) {
        double g2 = (p[keep[i]] - n[keep[i]]) / h;
        gsl_vector_set(b, (size_t)(nv + i), -(4 * g2 - g1[i]) / 3);
        for (int k = 0; k < nv; k++) {
            gsl_matrix_set(K, (size_t)(nv + i), (size_t)k, J[i * nv + k]);
            gsl_matrix_set(K, (size_t)k, (size_t)(nv + i), J[i * nv + k]);
        }
    }
    gsl_permutation *perm = gsl_permutation_alloc((size_t)W);
    int sign;
    gsl_linalg_LU_decomp(K, perm, &sign);
    gsl_linalg_LU_solve(K, perm, b, x);
    for (int i = 0; i < nv; i++)
        d->qacc[i] = gsl_vector_get(x, (size_t)i);
    gsl_permutation_free(perm);
    gsl_matrix_free(K);
    gsl_vector_free(b);
    gsl_vector_free(x);
    mj_deleteData(w);
    free(J), free(r), free(dq), free(Jw), free(rw), free(p), free(n), free(g1), free(M);
    free(keep);
    return 0;
}

/* A row "t q_1 .. q_nq" from stdin into t and d->qpos: 1, 0 at the end,
 * or -1 on a short row (said on stderr). */
static int
read_row(const mjModel *m, mjData *d, double *t)
{
    if (scanf("%lf", t) != 1)
        return 0;
    for (int i = 0; i < m->nq; i++)
        if (scanf("%lf", &d->qpos[i]) != 1) {
            fprintf(stderr, "mj_accel: a row has fewer than nq = %d coordinates\n", m->nq);
            return -1;
        }
    return 1;
}

/* The com mode (the top): 0, or 2 on a short line. */
static int
centre_of_mass(const mjModel *m)
{
    mjData *d = mj_makeData(m);
    double t;
    int rc;
    while ((rc = read_row(m, d, &t)) > 0) {
        mj_fwdPosition(m, d);
        printf("%.17g %.17g %.17g %.17g\n", t, d->subtree_com[0], d->subtree_com[1],
               d->subtree_com[2]);
    }
    mj_deleteData(d);
    return rc < 0 ? 2 : 0;
}

/* The lowest mode (the top): 0, or 2 where no sphere or capsule moves. */
static int
lowest(const mjModel *m)
{
    mjData *d = mj_makeData(m);
    mj_kinematics(m, d);
    double low = INFINITY;
    for (int g = 0; g < m->ngeom; g++) {
        const double *R = d->geom_xmat + 9 * g, *sz = m->geom_size + 3 * g;
        double z = d->geom_xpos[3 * g + 2];
        if (m->geom_bodyid[g] == 0)
            continue;
        if (m->geom_type[g] == mjGEOM_SPHERE)
            low = fmin(low, z - sz[0]);
        else if (m->geom_type[g] == mjGEOM_CAPSULE) /* its axis is the geom's z */
            low = fmin(low, z - sz[0] - sz[1] * fabs(R[8]));
    }
    mj_deleteData(d);
    if (isinf(low))
        return 2;
    printf("%.17g %.17g\n", low, mju_norm3(m->opt.gravity));
    return 0;
}

/* The sinks mode (the top): 0, or 2 on a short line. */
static int
sinks(const mjModel *m)
{
    mjData *d = mj_makeData(m);
    double t;
    int rc;
    printf("%.17g %.17g\n", mj_getTotalmass(m), mju_norm3(m->opt.gravity));
    while ((rc = read_row(m, d, &t)) > 0) {
        mj_kinematics(m, d);
        for (int g = 0; g < m->ngeom; g++) {
            const double *R = d->geom_xmat + 9 * g, *sz = m->geom_size + 3 * g;
            double z = d->geom_xpos[3 * g + 2], low[8];
            int n = 0, b = m->geom_bodyid[g];
            if (b == 0)
                continue;
            if (m->geom_type[g] == mjGEOM_SPHERE)
                low[n++] = z - sz[0];
            else if (m->geom_type[g] == mjGEOM_CAPSULE) /* its axis is the geom's z */
                for (int e = -1; e <= 1; e += 2)
                    low[n++] = z + e * sz[1] * R[8] - sz[0];
            else if (m->geom_type[g] == mjGEOM_BOX) /* (row 2 of R: world z of its axes) */
                for (int v = 0; v < 8; v++)
                    low[n++] = z + (v & 1 ? 1 : -1) * sz[0] * R[6] +
                               (v & 2 ? 1 : -1) * sz[1] * R[7] + (v & 4 ? 1 : -1) * sz[2] * R[8];
            const char *name = mj_id2name(m, mjOBJ_GEOM, g);
            for (int k = 0; k < n; k++) {
                if (!(low[k] < 0))
                    continue;
                if (name)
                    printf("%.17g %s %.17g\n", t, name, -low[k]);
                else
                    printf("%.17g %s_geom%d %.17g\n", t, mj_id2name(m, mjOBJ_BODY, b), g,
                           -low[k]);
            }
        }
    }
    mj_deleteData(d);
    return rc < 0 ? 2 : 0;
}

/* The rest mode (the top): MuJoCo's run of T seconds; 0. */
static int
rest(const mjModel *m, double T)
{
    mjData *d = mj_makeData(m);
    while (d->time < T)
        mj_step(m, d);
    for (int i = 0; i < m->nq; i++)
        printf("%.17g%c", d->qpos[i], i + 1 < m->nq ? ' ' : '\n');
    mj_deleteData(d);
    return 0;
}

/* The kinetic mode (the top): 0, or 2 on a short line. */
static int
kinetic(mjModel *m)
{
    m->opt.enableflags |= mjENBL_ENERGY; /* else mj_energyVel leaves 0 */
    mjData *d = mj_makeData(m);
    double t;
    int rc = 0;
    while (scanf("%lf", &t) == 1) {
        for (int i = 0; i < m->nq + m->nv; i++) /* eomc's speeds are MuJoCo's qvel */
            if (scanf("%lf", i < m->nq ? &d->qpos[i] : &d->qvel[i - m->nq]) != 1) {
                fprintf(stderr, "mj_accel: a row has fewer than nq + nv = %d numbers\n",
                        m->nq + m->nv);
                rc = 2;
                goto done;
            }
        mj_fwdPosition(m, d);
        mj_energyVel(m, d);
        printf("%.17g %.17g\n", t, d->energy[1]);
    }
done:
    mj_deleteData(d);
    return rc;
}

/* Is joint j's limit one the import keeps (a hinge's or a slide's, where
 * the model's own flags compute limits)?  Its range, less the margin,
 * into lo and hi. */
static int
limited(const mjModel *m, int j, int flags, double *lo, double *hi)
{
    *lo = m->jnt_range[2 * j] + m->jnt_margin[j];
    *hi = m->jnt_range[2 * j + 1] - m->jnt_margin[j];
    return m->jnt_limited[j] && !(flags & (mjDSBL_LIMIT | mjDSBL_CONSTRAINT)) &&
           (m->jnt_type[j] == mjJNT_HINGE || m->jnt_type[j] == mjJNT_SLIDE);
}

/* Is every limited joint of the state inside its range (flags: the
 * model's own)? */
static int
inside(const mjModel *m, const mjData *d, int flags)
{
    double lo, hi;
    for (int j = 0; j < m->njnt; j++) {
        double q = d->qpos[m->jnt_qposadr[j]];
        if (limited(m, j, flags, &lo, &hi) && !(q > lo && q < hi))
            return 0;
    }
    return 1;
}

/* Does MuJoCo clamp an actuator's control or force at state d (after
 * mj_forward; flags: the model's own)?  Its force unclamped is gain*u +
 * bias of the control clamped, for the fixed or affine gains and biases
 * that eomc imports. */
static int
clamping(const mjModel *m, const mjData *d, int flags)
{
    for (int i = 0; i < m->nu; i++) {
        const double *g = m->actuator_gainprm + mjNGAIN * i, *b = m->actuator_biasprm + mjNBIAS * i;
        const double *cr = m->actuator_ctrlrange + 2 * i, *fr = m->actuator_forcerange + 2 * i;
        double u = d->ctrl[i], L = d->actuator_length[i], V = d->actuator_velocity[i];
        if (m->actuator_ctrllimited[i] && !(flags & mjDSBL_CLAMPCTRL)) {
            if (u < cr[0] || u > cr[1])
                return 1;
        }
        double gain = g[0] + (m->actuator_gaintype[i] == mjGAIN_AFFINE ? g[1] * L + g[2] * V : 0);
        double f = gain * u + (m->actuator_biastype[i] == mjBIAS_AFFINE ? b[0] + b[1] * L + b[2] * V : 0);
        if (m->actuator_forcelimited[i] && (f < fr[0] || f > fr[1]))
            return 1;
    }
    return 0;
}

/* Joint j's dofs (qvel entries). */
static int
dofs(const mjModel *m, int j)
{
    return m->jnt_type[j] == mjJNT_FREE ? 6 : m->jnt_type[j] == mjJNT_BALL ? 3 : 1;
}

/* The states where MuJoCo clamps a control or a force (said at the end). */
static long clamped_states;

/* The state of one seed and MuJoCo's q'' there, printed; 3 if no state
 * drawn meets the constraints inside the limits.  flags: the model's own
 * disableflags; joint_inputs: forces drawn on the joints' dofs too. */
static int
one_state(mjModel *m, mjData *d, uint64_t seed, int flags, int joint_inputs)
{
    mj_resetData(m, d); /* as a new one: nothing warm-started from the last */
    /* the model's own <flag>s may disable them (docs/import.md) */
    int equalities = m->neq && !(m->opt.disableflags & (mjDSBL_EQUALITY | mjDSBL_CONSTRAINT));
    /* with constraints, a draw whose Newton steps do not reach them (a
     * closed loop that cannot close there) is drawn again */
    for (int draw = 0;; draw++) {
        for (int i = 0; i < m->nq; i++)
            d->qpos[i] = uniform(&seed);
        for (int i = 0; i < m->nv; i++)
            d->qvel[i] = uniform(&seed);
        for (int i = 0; i < m->nu; i++)
            d->ctrl[i] = uniform(&seed);
        for (int j = 0; j < m->njnt && joint_inputs; j++)
            for (int k = 0; m->jnt_type[j] != mjJNT_FREE && k < dofs(m, j); k++)
                d->qfrc_applied[m->jnt_dofadr[j] + k] = uniform(&seed);
        for (int j = 0; j < m->njnt; j++) { /* unit quaternions; limits' ranges */
            int type = m->jnt_type[j];
            double lo, hi, *q = d->qpos + m->jnt_qposadr[j];
            if (type == mjJNT_BALL || type == mjJNT_FREE)
                mju_normalize4(q + (type == mjJNT_FREE ? 3 : 0));
            if (limited(m, j, flags, &lo, &hi))
                *q = lo + (*q + 1.5) / 3 * (hi - lo);
        }
        mj_forward(m, d);
        if ((!equalities || constrained(m, d) == 0) && inside(m, d, flags))
            break;
        if (draw == DRAWS_MAX) {
            fprintf(stderr, "mj_accel: no state of %d drawn converges onto the constraints "
                    "inside the limits\n", DRAWS_MAX);
            return 3;
        }
    }
    clamped_states += clamping(m, d, flags);
    for (int i = 0; i < m->nq; i++)
        printf("%.17g%c", d->qpos[i], i + 1 < m->nq ? ' ' : '\n');
    for (int i = 0; i < m->nv; i++)
        printf("%.17g%c", d->qvel[i], i + 1 < m->nv ? ' ' : '\n');
    const char *sep = "";
    for (int i = 0; i < m->nu; i++, sep = " ")
        printf("%s%.17g", sep, d->ctrl[i]);
    for (int j = 0; j < m->njnt && joint_inputs; j++) /* in eomc's order: tau_J by joint */
        for (int k = 0; m->jnt_type[j] != mjJNT_FREE && k < dofs(m, j); k++, sep = " ")
            printf("%s%.17g", sep, d->qfrc_applied[m->jnt_dofadr[j] + k]);
    printf("\n");
    for (int i = 0; i < m->nv; i++)
        printf("%.17g\n", d->qacc[i]);
    return 0;
}

int
main(int argc, char **argv)
{
    char err[1000] = "";
    mjModel *m = argc == 3 || argc == 4 ? mj_loadXML(argv[1], NULL, err, sizeof err) : NULL;
    if (!m) {
        fprintf(stderr, "mj_accel: %s\n",
                argc == 3 || argc == 4 ? err : "usage: mj_accel MODEL SEED [COUNT]");
        return 2;
    }
    if (!strcmp(argv[2], "sinks") || (!strcmp(argv[2], "rest") && argc == 4)) {
        int rc = argv[2][0] == 's' ? sinks(m) : rest(m, strtod(argv[3], NULL));
        mj_deleteModel(m);
        return rc;
    }
    if (!strcmp(argv[2], "com") || !strcmp(argv[2], "kinetic") || !strcmp(argv[2], "lowest")) {
        int rc = argv[2][0] == 'c' ? centre_of_mass(m) : argv[2][0] == 'k' ? kinetic(m) : lowest(m);
        mj_deleteModel(m);
        return rc;
    }
    int flags = m->opt.disableflags;
    m->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_FRICTIONLOSS |
                           (m->neq ? 0 : mjDSBL_EQUALITY);
    m->opt.jacobian = mjJAC_DENSE;
    gsl_set_error_handler_off(); /* a singular draw is drawn again */
    mjData *d = mj_makeData(m);
    uint64_t seed = strtoull(argv[2], NULL, 10);
    long count = argc == 4 ? strtol(argv[3], NULL, 10) : 1;
    const char *ji = getenv("MJ_ACCEL_JOINT_INPUTS");
    int rc = 0, joint_inputs = ji && !strcmp(ji, "1");
    for (long k = 0; k < count && rc == 0; k++)
        rc = one_state(m, d, seed + (uint64_t)k, flags, joint_inputs);
    if (rc == 0 && m->nu)
        fprintf(stderr, "mj_accel: a control or force clamped at %ld of %ld states\n",
                clamped_states, count);
    mj_deleteData(d);
    mj_deleteModel(m);
    return rc;
}

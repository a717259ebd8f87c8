/*
 * Models whose speeds are not their coordinates' rates (freebody.c: a free
 * body's unit quaternion and its angular velocity in its own axes), through
 * the API, each figure against one computed here apart from the runtime:
 *  - the state's size nq + nv and the speeds' names (eomc_model_count "v");
 *  - v' of the free body: (0, 0, -g) and Euler's -In^-1 (w x In w);
 *  - dx'/dx (eomc_sim_jacobian: [dq'/dq, W(q)] over -M^-1 dE/dx, and the
 *    KKT solve's for the top) against central differences of q' and v';
 *  - a symmetric body (I1 = I2) by every method, adaptive and in fixed
 *    steps, against its closed form (the centre's parabola, the turn
 *    Rot(L, |L| t / I1) R0 Rot(z, (1 - I3/I1) wz t), (wx, wy) turning at
 *    (I3 - I1) wz / I1): every row within its bound, its quaternion of
 *    length 1 to rounding;
 *  - the asymmetric body (I1 < I2 < I3): its energy, its world angular
 *    momentum R(e) In w and its centre's parabola;
 *  - the heavy symmetric top, a free body whose tip is held at the origin
 *    by three holonomic constraints (KKT, and unit loads), with and
 *    without projection: its energy, the vertical component of its angular
 *    momentum about the tip, and the one along its axis (C wz), conserved;
 *    its tip at the origin; the KKT and the unit loads the same motion;
 *  - a state off the top's constraints projected onto them (its quaternion
 *    renormalized), and with its turn held (only the centre moves); with
 *    its centre held (the rows then dependent) and a quaternion held in
 *    part, refused;
 *  - an event's `set` of a speed (the body bouncing on the floor) and an
 *    output of v': the parabolas between bounces, Euler's v';
 *  - one step at a time (eomc_sim_step): the ends on the closed form, the
 *    dense output inside renormalized;
 *  - the reference solution (extended precision) against the closed form:
 *    its estimated error bounds its true one.
 */
#include "../unit/check.h"
#include "rtest.h"

#include <float.h>

enum { NQ = 7, NV = 6, NX = NQ + NV };
/* A quaternion renormalized is of length 1 to a few units of rounding
 * (the runtime leaves one within 4 as it is; computing the length here
 * adds its own). */
enum { UNIT_ROUNDING = 8 };

/* | |e| - 1 | largest over the rows (e = q[3..6]). */
static double
unit_error(const Rows *r)
{
    double worst = 0;
    for (int i = 0; i < r->n; i++) {
        const double *e = rows_x(r, i) + 3;
        double len = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
        worst = fmax(worst, fabs(len - 1));
    }
    return worst;
}

/* The largest error of the rows against the symmetric body's closed form
 * from x0 (its parameters p), every component. */
static double
exact_error(const Rows *r, const double *p, const double *x0)
{
    double worst = 0, ex[NX];
    for (int i = 0; i < r->n; i++) {
        freebody_exact(p, x0, x0 + NQ, r->t[i], ex, ex + NQ);
        for (int j = 0; j < NX; j++)
            worst = fmax(worst, fabs(rows_x(r, i)[j] - ex[j]));
    }
    return worst;
}

/* The body's parameters as the simulator has them (the derived none). */
static void
params(const eomc_sim *s, double *p)
{
    memcpy(p, eomc_sim_params(s), (size_t)eomc_sim_model(s)->np * sizeof *p);
}

static void
names_and_sizes(void)
{
    const eomc_model *m = &freebody_model;
    CHECK(eomc_nv(m) == NV && eomc_nx(m) == NX, "freebody: nv = 6, nx = 13 (got %d, %d)",
          eomc_nv(m), eomc_nx(m));
    CHECK(eomc_model_count(m, "v") == NV && !strcmp(eomc_model_name(m, "v", 3), "root_wx") &&
              !strcmp(eomc_model_name(m, "v", 0), "root_x'"),
          "eomc_model_count/name \"v\": 6 speeds, root_x' .. root_wx ..");
    CHECK(eomc_model_count(&osc_model, "v") == 0 && eomc_nv(&osc_model) == 1,
          "a model whose speeds are its rates: no \"v\" names, nv = nq = 1");
}

/* v' = (0, 0, -g, -In^-1 (w x In w)) at the start and at another state. */
static void
accel_closed_form(const eomc_model *m)
{
    eomc_sim *s = sim_new(m);
    double x[NX], a[NV], p[5];
    sim_x0(s, x);
    params(s, p);
    for (int trial = 0; trial < 2; trial++) {
        if (trial) /* another turn and spin */
            x[3] = 0.5, x[4] = -0.5, x[5] = 0.5, x[6] = 0.5, x[10] = -1.3, x[11] = 0.2,
            x[12] = 0.9;
        int rc = eomc_sim_accel(s, 0, x, x + NQ, a);
        const double *w = x + NQ + 3, *In = p + 1;
        double want[NV] = {0, 0, -p[4], -(In[2] - In[1]) * w[1] * w[2] / In[0],
                           -(In[0] - In[2]) * w[0] * w[2] / In[1],
                           -(In[1] - In[0]) * w[0] * w[1] / In[2]};
        double err = 0, scale = 0;
        for (int i = 0; i < NV; i++) {
            err = fmax(err, fabs(a[i] - want[i]));
            scale = fmax(scale, fabs(want[i]));
        }
        CHECK(rc == EOMC_OK && err <= 4 * DBL_EPSILON * scale, "%s: v' is Euler's and "
              "gravity's (state %d, error %.2g of %.3g)", m->name, trial, err, scale);
    }
    eomc_sim_free(s);
}

/* x' = (q', v') at x, by the model's qdot and the runtime's v'. */
static int
rates(eomc_sim *s, const double *x, double *f)
{
    eomc_sim_model(s)->qdot(x, x + NQ, f);
    return eomc_sim_accel(s, 0, x, x + NQ, f + NQ);
}

/* eomc_sim_jacobian against central differences of x'. */
static void
jacobian_fd(const eomc_model *m)
{
    eomc_sim *s = sim_new(m);
    double x[NX], J[NX * NX], fp[NX], fm[NX], y[NX];
    sim_x0(s, x);
    x[NQ + 3] += 0.7, x[NQ + 4] -= 0.4; /* no symmetry to hide a wrong entry */
    int rc = eomc_sim_jacobian(s, 0, x, J, NULL), bad = rc != EOMC_OK;
    double worst = 0;
    for (int j = 0; j < NX && !bad; j++) {
        double h = 1e-6 * fmax(1, fabs(x[j]));
        memcpy(y, x, sizeof y);
        y[j] = x[j] + h;
        bad |= rates(s, y, fp) != EOMC_OK;
        y[j] = x[j] - h;
        bad |= rates(s, y, fm) != EOMC_OK;
        for (int i = 0; i < NX; i++) {
            double row = 1;
            for (int k = 0; k < NX; k++)
                row = fmax(row, fabs(J[i * NX + k]));
            worst = fmax(worst, fabs(J[i * NX + j] - (fp[i] - fm[i]) / (2 * h)) / row);
        }
    }
    CHECK(!bad && worst < 1e-7, "%s: dx'/dx (%d x %d) is the central differences' of x' "
          "(largest difference %.2g of its row)", m->name, NX, NX, worst);
    eomc_sim_free(s);
}

/* One run of the symmetric free body (I2 = I1): its error against the
 * closed form, the quaternion's length in the rows, the drift. */
typedef struct Case {
    const char *method;
    double tol, h;   /* adaptive at tol, or fixed steps h */
    double bound;    /* the error allowed against the closed form */
} Case;

static void
symmetric_run(const eomc_model *m, const Case *c)
{
    eomc_sim *s = sim_new(m);
    eomc_sim_set(s, "I2", FREEBODY_I1);
    double x[NX], x0[NX], p[5];
    sim_x0(s, x);
    memcpy(x0, x, sizeof x);
    params(s, p);
    eomc_run_opts o = opts_for(m, 2.0, 0.05, c->method, c->tol, c->tol);
    o.h_fixed = c->h;
    Rows r;
    eomc_stats st;
    rows_init_model(&r, m);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    double err = exact_error(&r, p, x0), unit = unit_error(&r);
    CHECK(rc == EOMC_OK && r.n == 41 && err <= c->bound,
          "%s %s %s %g: the closed form to %.2g (bound %g)%s%s", m->name, c->method,
          c->h > 0 ? "fixed steps" : "tolerance", c->h > 0 ? c->h : c->tol, err, c->bound,
          rc ? ": " : "", rc ? eomc_sim_error(s) : "");
    CHECK(r.n == 41 && unit <= UNIT_ROUNDING * DBL_EPSILON && st.quat_drift > 0 &&
              st.quat_drift < 1e-3 &&
              !strcmp(st.quat_name, "root_e0"),
          "... every row's quaternion of length 1 to rounding (%.2g), the drift before "
          "renormalizing measured (%.2g, %s)", unit, st.quat_drift,
          st.quat_name ? st.quat_name : "none");
    rows_free(&r);
    eomc_sim_free(s);
}

static const Case cases[] = {
    {"rk2", 1e-9, 0, 1e-6},      {"rk4", 1e-10, 0, 1e-7},    {"rkf45", 1e-10, 0, 1e-7},
    {"rkck", 1e-10, 0, 1e-7},    {"rk8pd", 1e-12, 0, 1e-9},  {"rk1imp", 1e-6, 0, 1e-2},
    {"rk2imp", 1e-9, 0, 1e-6},   {"rk4imp", 1e-10, 0, 1e-7}, {"bsimp", 1e-11, 0, 1e-8},
    {"msadams", 1e-11, 0, 1e-7}, {"msbdf", 1e-9, 0, 1e-5},
    /* fixed steps (tol: their Newton iterations'): the error the method's
     * order gives */
    {"rk4", 1e-12, 1e-3, 1e-9},  {"rk8pd", 1e-12, 2e-2, 1e-9}, {"rk2imp", 1e-12, 1e-3, 1e-4},
    {"rk4imp", 1e-12, 1e-2, 1e-7}, {"bsimp", 1e-12, 5e-2, 1e-7},
};

/* The asymmetric body: energy, world angular momentum, centre; at most
 * max_side of its 31 rows (every 0.1 over 3 s) by side steps. */
static void
asymmetric_run(const char *method, double tol, double h, double bound, long max_side)
{
    const eomc_model *m = &freebody_model;
    eomc_sim *s = sim_new(m);
    double x[NX], x0[NX], p[5];
    sim_x0(s, x);
    memcpy(x0, x, sizeof x);
    params(s, p);
    eomc_run_opts o = opts_for(m, 3.0, 0.1, method, tol, tol);
    o.h_fixed = h;
    Rows r;
    eomc_stats st;
    rows_init_model(&r, m);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    double L0[3] = {0, 0, 0}, dE = 0, dL = 0, dc = 0, E0 = 0, Lmag = 0, T = 0;
    for (int i = 0; i < r.n; i++) {
        const double *y = rows_x(&r, i), *w = y + NQ + 3;
        double R[9], L[3] = {0, 0, 0}, Lb[3] = {p[1] * w[0], p[2] * w[1], p[3] * w[2]};
        quat_rotation(y + 3, R);
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
                L[a] += R[3 * a + b] * Lb[b];
        double Ti = 0.5 * p[0] * (y[7] * y[7] + y[8] * y[8] + y[9] * y[9]) +
                    0.5 * (p[1] * w[0] * w[0] + p[2] * w[1] * w[1] + p[3] * w[2] * w[2]);
        double E = Ti + p[0] * p[4] * y[2];
        if (i == 0) {
            memcpy(L0, L, sizeof L0);
            E0 = E, T = Ti;
            Lmag = sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2]);
        }
        dE = fmax(dE, fabs(E - E0));
        for (int a = 0; a < 3; a++)
            dL = fmax(dL, fabs(L[a] - L0[a]));
        double t = r.t[i], c[3] = {x0[0] + x0[7] * t, x0[1] + x0[8] * t,
                                   x0[2] + x0[9] * t - p[4] * t * t / 2};
        for (int a = 0; a < 3; a++)
            dc = fmax(dc, fabs(y[a] - c[a]));
    }
    CHECK(rc == EOMC_OK && dE <= bound * T && dL <= bound * Lmag && dc <= bound,
          "freebody (I1 < I2 < I3) %s %s %g: E to %.2g of T, R(e) In w to %.2g of |L|, the "
          "centre's parabola to %.2g (bound %g)", method, h > 0 ? "fixed steps" : "tolerance",
          h > 0 ? h : tol, dE / T, dL / Lmag, dc, bound);
    CHECK(r.n == 31 && unit_error(&r) <= UNIT_ROUNDING * DBL_EPSILON &&
              st.side_steps <= max_side,
          "... its quaternion of length 1 in every row, %ld rows by side steps (at most %ld: "
          "the others interpolated, speeds included)", st.side_steps, max_side);
    rows_free(&r);
    eomc_sim_free(s);
}

/* The top's invariants at a row: E, the vertical angular momentum about
 * the tip, the one along its axis; the tip's distance from the origin. */
static void
top_invariants(const double *p, const double *y, double *E, double *Lz, double *La,
               double *tip)
{
    const double *w = y + NQ + 3, *xd = y + NQ;
    double R[9], Lb[3] = {p[1] * w[0], p[1] * w[1], p[2] * w[2]}, L[3] = {0, 0, 0};
    quat_rotation(y + 3, R);
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            L[a] += R[3 * a + b] * Lb[b];
    double mx[3] = {p[0] * (y[1] * xd[2] - y[2] * xd[1]), p[0] * (y[2] * xd[0] - y[0] * xd[2]),
                    p[0] * (y[0] * xd[1] - y[1] * xd[0])};
    *E = 0.5 * p[0] * (xd[0] * xd[0] + xd[1] * xd[1] + xd[2] * xd[2]) +
         0.5 * (p[1] * (w[0] * w[0] + w[1] * w[1]) + p[2] * w[2] * w[2]) + p[0] * p[4] * y[2];
    *Lz = L[2] + mx[2];
    *La = 0;
    for (int a = 0; a < 3; a++) /* along the body's axis R e_z */
        *La += R[3 * a + 2] * (L[a] + mx[a]);
    *tip = 0;
    for (int a = 0; a < 3; a++)
        *tip = fmax(*tip, fabs(y[a] - p[3] * R[3 * a + 2]));
}

static void
top_run(const eomc_model *m, const char *method, double tol, double h, int project,
        double bound, Rows *keep)
{
    eomc_sim *s = sim_new(m);
    double x[NX], p[5];
    sim_x0(s, x);
    params(s, p);
    if (project)
        eomc_sim_stabilize(s, EOMC_STABILIZE_PROJECT, 0, 0);
    eomc_run_opts o = opts_for(m, 2.0, 0.05, method, tol, tol);
    o.h_fixed = h;
    Rows r;
    eomc_stats st;
    rows_init_model(&r, m);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    double E0 = 0, Lz0 = 0, La0 = 0, dE = 0, dLz = 0, dLa = 0, tip = 0, dwz = 0, T = 0;
    for (int i = 0; i < r.n; i++) {
        const double *y = rows_x(&r, i);
        double E, Lz, La, d;
        top_invariants(p, y, &E, &Lz, &La, &d);
        if (i == 0) {
            E0 = E, Lz0 = Lz, La0 = La;
            T = E - p[0] * p[4] * y[2];
        }
        dE = fmax(dE, fabs(E - E0)), dLz = fmax(dLz, fabs(Lz - Lz0));
        dLa = fmax(dLa, fabs(La - La0)), tip = fmax(tip, d);
        dwz = fmax(dwz, fabs(y[NQ + 5] - TOP_SPIN));
    }
    double La_scale = p[2] * TOP_SPIN;
    CHECK(rc == EOMC_OK && r.n == 41 && dE <= bound * T && dLz <= bound * La_scale &&
              dLa <= bound * La_scale && dwz <= bound * TOP_SPIN,
          "%s %s%s %s %g: E to %.2g of T, L_z to %.2g and L along the axis to %.2g of C wz, "
          "wz to %.2g (bound %g)%s%s", m->name, method, project ? " projected" : "",
          h > 0 ? "fixed steps" : "tolerance", h > 0 ? h : tol, dE / T, dLz / La_scale,
          dLa / La_scale, dwz / TOP_SPIN, bound, rc ? ": " : "", rc ? eomc_sim_error(s) : "");
    double tip_bound = project ? 1e-14 : bound;
    CHECK(r.n == 41 && tip <= tip_bound * p[3] && unit_error(&r) <= UNIT_ROUNDING * DBL_EPSILON,
          "... the tip at the origin to %.2g of l (bound %g), the quaternion of length 1",
          tip / p[3], tip_bound);
    if (keep)
        *keep = r;
    else
        rows_free(&r);
    eomc_sim_free(s);
}

/* The KKT solve and the unit loads: the same motion. */
static void
top_same(void)
{
    Rows a, b;
    top_run(&top_model, "rk8pd", 1e-12, 0, 0, 1e-9, &a);
    top_run(&top_loads_model, "rk8pd", 1e-12, 0, 0, 1e-9, &b);
    double d = 0;
    for (int i = 0; i < a.n && i < b.n; i++)
        for (int j = 0; j < NX; j++)
            d = fmax(d, fabs(rows_x(&a, i)[j] - rows_x(&b, i)[j]));
    CHECK(a.n == b.n && d <= 1e-9, "top by KKT and by unit loads: the same rows to %.2g", d);
    rows_free(&a);
    rows_free(&b);
}

/* The top's constraints at (q, v): the largest |g_k| / l, |g'_k| / (l |w|). */
static double
top_residual(const double *p, const double *x)
{
    double R[9], l = p[3], worst = 0;
    const double *v = x + NQ, *w = v + 3;
    quat_rotation(x + 3, R);
    double wn = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int k = 0; k < 3; k++) {
        worst = fmax(worst, fabs(x[k] - l * R[3 * k + 2]) / l);
        worst = fmax(worst, fabs(v[k] + l * (w[0] * R[3 * k + 1] - w[1] * R[3 * k])) / (l * wn));
    }
    return worst;
}

static void
projection(void)
{
    const eomc_model *m = &top_model;
    eomc_sim *s = sim_new(m);
    double x[NX], y[NX], p[5];
    sim_x0(s, x);
    params(s, p);
    /* turned off its tip: the orientation moved (a unit quaternion still),
     * the centre kept */
    x[4] += 0.05, x[5] -= 0.03;
    double len0 = sqrt(x[3] * x[3] + x[4] * x[4] + x[5] * x[5] + x[6] * x[6]);
    for (int i = 3; i < 7; i++)
        x[i] /= len0;
    x[NQ] += 0.1;
    memcpy(y, x, sizeof x);
    int rc = eomc_sim_project(s, 0, y, y + NQ);
    double len = sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]);
    CHECK(rc == EOMC_OK && top_residual(p, x) > 1e-2 && top_residual(p, y) <= 1e-14 &&
              fabs(len - 1) <= UNIT_ROUNDING * DBL_EPSILON,
          "top off its constraints (%.2g) projected onto them (%.2g), its quaternion of "
          "length 1 (%.2g)", top_residual(p, x), top_residual(p, y), len - 1);
    /* its turn held, the quaternion's four coordinates: only the centre
     * (x', y', z' at positions) moves */
    unsigned char hold[NX] = {0, 0, 0, 1, 1, 1, 1};
    memcpy(y, x, sizeof x);
    rc = eomc_sim_project_held(s, 0, y, y + NQ, hold);
    CHECK(rc == EOMC_OK && !memcmp(y + 3, x + 3, 4 * sizeof *x) && y[0] != x[0] &&
              top_residual(p, y) <= 1e-14,
          "... with its turn held: the quaternion as it was to the bit, the centre moved onto "
          "the tip (%.2g)%s%s", top_residual(p, y), rc ? ": " : "", rc ? eomc_sim_error(s) : "");
    /* its centre held: the three rows leave the turn two directions (none
     * about the axis moves the tip), so they cannot all be met */
    unsigned char centre[NX] = {1, 1, 1};
    memcpy(y, x, sizeof x);
    rc = eomc_sim_project_held(s, 0, y, y + NQ, centre);
    CHECK(rc == EOMC_ENUMERIC && strstr(eomc_sim_error(s), "cannot all be met") &&
              y[0] == x[0] && y[1] == x[1] && y[2] == x[2],
          "... with its centre held: refused, the centre as it was (%s)", eomc_sim_error(s));
    /* a quaternion held in part: refused, naming it */
    unsigned char part[NX] = {0, 0, 0, 1};
    memcpy(y, x, sizeof x);
    rc = eomc_sim_project_held(s, 0, y, y + NQ, part);
    CHECK(rc == EOMC_EUSAGE && strstr(eomc_sim_error(s), "root_e0") &&
              strstr(eomc_sim_error(s), "four together") && !memcmp(x, y, sizeof x),
          "root_e0 held alone: refused (%s), nothing moved", eomc_sim_error(s));
    eomc_sim_free(s);
}

/* Without c_scale, the positions' residuals are measured against g's terms
 * dg/dq_i q_i (c_levels_jacobian's gradient), as B's where the speeds are
 * the rates: a residual of 1e-6 of l is about that against the terms
 * (|z| + 2 l here), not 1, and the projection is as good. */
static void
no_scale(void)
{
    eomc_sim *a = sim_new(&top_model), *b = sim_new(&top_noscale_model);
    double x[NX], y[NX], p[5];
    sim_x0(a, x);
    params(a, p);
    x[2] += 1e-6 * p[3]; /* the centre off the tip by 1e-6 of l, up */
    int wa, wb, la, lb;
    double ea = eomc_sim_inconsistency(a, 0, x, x + NQ, &wa, &la);
    double eb = eomc_sim_inconsistency(b, 0, x, x + NQ, &wb, &lb);
    memcpy(y, x, sizeof x);
    int rc = eomc_sim_project(b, 0, y, y + NQ);
    CHECK(ea > 1e-6 / 8 && ea < 1e-6 && eb > 1e-6 / 8 && eb < 1e-6 && wa == 2 && wb == 2 &&
              la == 0 && lb == 0 &&
              rc == EOMC_OK && top_residual(p, y) <= 1e-14,
          "top without c_scale: tip_z off by 1e-6 of l measured %.2g (with c_scale %.2g), "
          "projected onto the tip (%.2g)", eb, ea, top_residual(p, y));
    eomc_sim_free(a);
    eomc_sim_free(b);
}

/* The reference of the symmetric body: its estimate bounds its error. */
static void
reference(void)
{
    const eomc_model *m = &freebody_model;
    eomc_sim *s = sim_new(m);
    eomc_sim_set(s, "I2", FREEBODY_I1);
    double x0[NX], p[5], ex[NX];
    sim_x0(s, x0);
    params(s, p);
    eomc_run_opts o = opts_for(m, 2.0, 0.1, "rk8pd", 1e-10, 1e-10);
    eomc_reference ref;
    int rc = eomc_reference_compute(s, &freebody_model_ext, &o, x0, &ref);
    double err = 0, unit = 0;
    for (long k = 0; rc == EOMC_OK && k < ref.nrows; k++) {
        const double *y = ref.x + (size_t)k * (size_t)ref.nx;
        freebody_exact(p, x0, x0 + NQ, ref.t[k], ex, ex + NQ);
        for (int j = 0; j < NX; j++)
            err = fmax(err, fabs(y[j] - ex[j]));
        unit = fmax(unit, fabs(sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6]) - 1));
    }
    CHECK(rc == EOMC_OK && ref.nx == NX && ref.nrows == 21 && err <= ref.error &&
              ref.error < 1e-13 && unit <= UNIT_ROUNDING * DBL_EPSILON,
          "the reference (%s): the closed form to %.2g, within its estimate %.2g; "
          "quaternion of length 1 (%.2g)%s%s", rc ? "failed" : ref.method, err,
          rc ? NAN : ref.error, unit, rc ? ": " : "", rc ? eomc_sim_error(s) : "");
    if (rc == EOMC_OK)
        eomc_reference_free(&ref);
    /* the twin's v' with the doubles' */
    double a[NV], ae[NV];
    rc = eomc_sim_accel(s, 0, x0, x0 + NQ, a);
    int rce = eomc_reference_accel(s, &freebody_model_ext, 0, x0, ae, NULL);
    double d = 0;
    for (int i = 0; i < NV; i++)
        d = fmax(d, fabs(a[i] - ae[i]));
    CHECK(rc == EOMC_OK && rce == EOMC_OK && d <= 1e-14, "eomc_reference_accel: the twin's "
          "v' [6] the doubles' to %.2g", d);
    eomc_sim_free(s);
}

/* The symmetric body bouncing on the floor: its centre's height the
 * parabolas between elastic bounces, its turn the closed form's (the
 * bounce sets the speed root_z' alone); the output wz_rate, v' [6]'s
 * last, Euler's at each row. */
static void
bounce(void)
{
    const eomc_model *m = &freebody_bounce_model;
    eomc_sim *s = sim_new(m);
    eomc_sim_set(s, "I2", FREEBODY_I1);
    double x[NX], x0[NX], p[5], ex[NX];
    sim_x0(s, x);
    memcpy(x0, x, sizeof x);
    params(s, p);
    eomc_run_opts o = opts_for(m, 2.0, 0.05, "rk8pd", 1e-12, 1e-12);
    Rows r;
    eomc_stats st;
    rows_init_model(&r, m);
    int rc = eomc_sim_integrate(s, &o, x, rows_add, &r, &st);
    double g = p[4], err = 0, out_err = 0;
    for (int i = 0; i < r.n; i++) {
        const double *y = rows_x(&r, i);
        double t = r.t[i], tb = 0, z = x0[2], vz = x0[NQ + 2];
        /* the bounces before t: each where the parabola reaches 0 */
        for (;;) {
            double hit = tb + (vz + sqrt(vz * vz + 2 * g * z)) / g;
            if (hit > t)
                break;
            vz = -(vz - g * (hit - tb)), z = 0, tb = hit;
        }
        freebody_exact(p, x0, x0 + NQ, t, ex, ex + NQ);
        ex[2] = z + vz * (t - tb) - g * (t - tb) * (t - tb) / 2;
        ex[NQ + 2] = vz - g * (t - tb);
        for (int j = 0; j < NX; j++)
            err = fmax(err, fabs(y[j] - ex[j]));
    }
    /* the output at the rows' states, of the asymmetric body (wz' not 0) */
    eomc_sim_set(s, "I2", FREEBODY_I2);
    for (int i = 0; i < r.n; i++) {
        const double *y = rows_x(&r, i);
        double out, want = -(FREEBODY_I2 - FREEBODY_I1) * y[NQ + 3] * y[NQ + 4] / FREEBODY_I3;
        eomc_sim_outputs(s, r.t[i], y, y + NQ, &out);
        out_err = fmax(out_err, fabs(out - want));
    }
    CHECK(rc == EOMC_OK && r.n == 41 && st.events == 2 && err < 1e-9 &&
              out_err <= 4 * DBL_EPSILON,
          "freebody bouncing: 2 bounces, the rows on the parabolas and the turn's closed form "
          "(%.2g), the output wz_rate Euler's (%.2g)", err, out_err);
    rows_free(&r);
    eomc_sim_free(s);
}

/* One step at a time: each step's ends and its dense output inside on the
 * symmetric body's closed form (the cubic to its O(h^4)), the quaternion
 * inside renormalized. */
static void
steps(void)
{
    const eomc_model *m = &freebody_model;
    eomc_sim *s = sim_new(m);
    eomc_sim_set(s, "I2", FREEBODY_I1);
    double x0[NX], x[NX], ex[NX], p[5];
    sim_x0(s, x0);
    params(s, p);
    eomc_run_opts o = opts_for(m, 2.0, 0.1, "rk8pd", 1e-12, 1e-12);
    eomc_evolve *e = eomc_evolve_alloc(s, &o, x0);
    eomc_step d = {0};
    double ends = 0, inside = 0, unit = 0;
    int rc = e ? EOMC_OK : EOMC_ENUMERIC, n = 0;
    while (e && (rc = eomc_sim_step(s, e, &d)) == EOMC_OK) {
        n++;
        freebody_exact(p, x0, x0 + NQ, d.t1, ex, ex + NQ);
        for (int j = 0; j < NX; j++)
            ends = fmax(ends, fabs(d.x1[j] - ex[j]));
        double t = 0.5 * (d.t0 + d.t1);
        eomc_step_eval(&d, t, x);
        freebody_exact(p, x0, x0 + NQ, t, ex, ex + NQ);
        for (int j = 0; j < NX; j++)
            inside = fmax(inside, fabs(x[j] - ex[j]));
        unit = fmax(unit, fabs(sqrt(x[3] * x[3] + x[4] * x[4] + x[5] * x[5] + x[6] * x[6]) - 1));
        if (d.last)
            break;
    }
    CHECK(rc == EOMC_OK && n > 5 && d.nx == NX && ends < 1e-9 && inside < 1e-5 &&
              unit <= UNIT_ROUNDING * DBL_EPSILON,
          "eomc_sim_step: %d steps of nx = 13, their ends on the closed form (%.2g), the cubic "
          "inside to %.2g, its quaternion of length 1 (%.2g)", n, ends, inside, unit);
    eomc_evolve_free(e);
    eomc_sim_free(s);
}

/* The eigenvalue of (re, im) [n] nearest (wr, wi): its distance. */
static double
nearest_eig(const double *re, const double *im, int n, double wr, double wi)
{
    double best = HUGE_VAL;
    for (int k = 0; k < n; k++)
        best = fmin(best, hypot(re[k] - wr, im[k] - wi));
    return best;
}

/* The torque-free body spinning at w about principal axis a, linearized
 * in the tangent space, against the closed form: the rotation's error
 * dtheta' = dw - w0 x dtheta (eigenvalues 0, +-i w), Euler's equations
 * about the spin (0 and lambda^2 = w^2 (Ia - Ib)(Ic - Ia) / (Ib Ic), b
 * and c the other axes: a pair on the imaginary axis about the major and
 * the minor axis, a real pair about the middle one), the centre's
 * translation (0).  Gravity moves only the centre: it is on. */
static void
spin_linearized(int a, double w)
{
    enum { NL = 12 };
    const eomc_model *m = &freebody_model;
    eomc_sim *s = sim_new(m);
    double x[NX], A[NL * NL], re[NL], im[NL], p[5];
    params(s, p);
    const double *In = p + 1;
    /* a turned start (e not 1: the frame P, Q at a general e), moving */
    double e[4] = {0.8, 0.2, -0.4, 0.4};
    memset(x, 0, sizeof x);
    x[0] = 0.3, x[1] = -1, x[2] = 2;
    memcpy(x + 3, e, sizeof e);
    x[NQ] = 0.5, x[NQ + 1] = -0.2, x[NQ + 2] = 1;
    x[NQ + 3 + a] = w;
    int rc = eomc_sim_linearize(s, 0, x, A, NULL), nl = eomc_sim_linear_size(s);
    int erc = rc == EOMC_OK ? eomc_sim_eigenvalues(s, A, NL, re, im) : rc;
    int b = (a + 1) % 3, c = (a + 2) % 3;
    double lam2 = w * w * (In[a] - In[b]) * (In[c] - In[a]) / (In[b] * In[c]);
    double lam = sqrt(fabs(lam2)), lr = lam2 > 0 ? lam : 0, li = lam2 > 0 ? 0 : lam;
    double far = fmax(fmax(nearest_eig(re, im, NL, 0, w), nearest_eig(re, im, NL, 0, -w)),
                      fmax(nearest_eig(re, im, NL, lr, li), nearest_eig(re, im, NL, -lr, -li)));
    int zeros = 0;
    for (int k = 0; k < NL; k++)
        zeros += hypot(re[k], im[k]) <= 1e-12 * w;
    /* the rotation's rows: -[w0 x] and the identity, exactly */
    double rot = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            /* -[w0 x]'s entry: w0 along a, so 0 in a's row and column
             * (and on the diagonal, where there is no third axis) */
            double wx = i == j || i == a || j == a
                            ? 0
                            : (j == (i + 1) % 3 ? 1 : -1) * x[NQ + 3 + 3 - i - j];
            rot = fmax(rot, fabs(A[(3 + i) * NL + 3 + j] - wx));
            rot = fmax(rot, fabs(A[(3 + i) * NL + 9 + j] - (i == j)));
        }
    int coord, order;
    eomc_sim_linear_state(s, 3 + a, &coord, &order);
    CHECK(rc == EOMC_OK && erc == EOMC_OK && nl == NL && order == 2 && coord == 3 + a &&
              far <= 1e-12 * w && zeros == NL - 4 && rot <= 1e-15 * w,
          "linearized spinning about axis %d (w = %g): z = (root_x.., root_r%c.., v) of 12, "
          "eigenvalues +-%gi and %s%g (lambda^2 = %.6g) to %.2g, %d zeros, dtheta' = dw - "
          "w0 x dtheta to %.2g", a + 1, w, "xyz"[a], w, lam2 > 0 ? "+-" : "+-i", lam, lam2,
          far, zeros, rot);
    eomc_sim_free(s);
}

/* The test for rest and the equilibrium search in the tangent space: a
 * body spinning about a principal axis without gravity is a steady
 * motion (v' = 0 exactly), with gravity it falls; and nothing holds a
 * free body, so it has no equilibrium: refused, saying so. */
static void
rest_and_equilibrium(void)
{
    eomc_sim *s = sim_new(&freebody_model);
    double x[NX], acc[NV];
    int worst, its;
    memset(x, 0, sizeof x);
    x[3] = 0.8, x[4] = 0.2, x[5] = -0.4, x[6] = 0.4, x[NQ + 5] = 2;
    double falling = eomc_sim_accel_residual(s, 0, x, acc, &worst);
    int fell = worst;
    eomc_sim_set(s, "g", 0);
    double steady = eomc_sim_accel_residual(s, 0, x, acc, &worst);
    CHECK(steady == 0 && falling > EOMC_ACCEL_ZERO && fell == 2,
          "eomc_sim_accel_residual: spinning about axis 3 without gravity %g (a steady "
          "motion), with gravity %g (v'[%d], root_z'')", steady, falling, fell);
    eomc_sim_set(s, "g", FREEBODY_G);
    int rc = eomc_sim_equilibrium(s, 0, x, &its);
    CHECK(rc == EOMC_ENUMERIC && strstr(eomc_sim_error(s), "no equilibrium"),
          "a free body under gravity has no equilibrium: %s", eomc_sim_error(s));
    eomc_sim_free(s);
}

/* The top held at its tip (three holonomic constraints: the centre's
 * coordinates and speeds dependent), started tilted 2.8 rad from upright
 * at rest: the equilibrium search turns its quaternion until it hangs
 * (its axis R(e) z down, |e| = 1), and there the reduced linearization
 * (the rotations and angular velocities, 6) has the pendulum's +-i
 * sqrt(m g l / (A + m l^2)) about both horizontal axes and 0 for the
 * spin. */
static void
top_hanging(const eomc_model *m)
{
    enum { NL = 6 };
    eomc_sim *s = sim_new(m);
    double x[NX] = {0}, A[NL * NL], re[NL], im[NL], R[9];
    x[3] = cos(1.4), x[4] = sin(1.4);
    quat_rotation(x + 3, R);
    for (int i = 0; i < 3; i++) /* the centre, l along the axis from the tip */
        x[i] = R[3 * i + 2] * TOP_L;
    int its, rc = eomc_sim_equilibrium(s, 0, x, &its);
    quat_rotation(x + 3, R);
    double down = fabs(R[8] + 1) + fabs(R[2]) + fabs(R[5]);
    double unit = fabs(sqrt(x[3] * x[3] + x[4] * x[4] + x[5] * x[5] + x[6] * x[6]) - 1);
    int lrc = rc == EOMC_OK ? eomc_sim_linearize(s, 0, x, A, NULL) : rc;
    int erc = lrc == EOMC_OK ? eomc_sim_eigenvalues(s, A, NL, re, im) : lrc;
    double w = sqrt(TOP_M * TOP_G * TOP_L / (TOP_A + TOP_M * TOP_L * TOP_L)), far = 0;
    int zeros = 0, names = 1;
    for (int k = 0; k < NL; k++) {
        zeros += hypot(re[k], im[k]) <= 1e-12 * w;
        int c, o;
        eomc_sim_linear_state(s, k, &c, &o);
        names &= k < 3 ? o == 2 && c == 3 + k : o == 1 && c == k;
    }
    for (int sgn = -1; sgn <= 1; sgn += 2) { /* each of +-iw twice */
        int count = 0;
        for (int k = 0; k < NL; k++)
            if (hypot(re[k], im[k] - sgn * w) <= 1e-12 * w)
                count++;
        far = fmax(far, count == 2 ? fmax(nearest_eig(re, im, NL, 0, sgn * w), 0) : HUGE_VAL);
    }
    CHECK(rc == EOMC_OK && down <= 8 * DBL_EPSILON && unit <= UNIT_ROUNDING * DBL_EPSILON &&
              erc == EOMC_OK && eomc_sim_linear_size(s) == NL && names && far <= 1e-12 * w &&
              zeros == 2,
          "%s: the equilibrium from a tilt of 2.8 hangs (its axis down to %.2g, |e| = 1 to "
          "%.2g, %d steps); linearized in (root_rx.., root_wx..): +-%.6gi twice to %.2g, "
          "%d zeros", m->name, down, unit, its, w, far, zeros);
    eomc_sim_free(s);
}

/* Taylor's method refuses a model with speeds whose series lack q' = W(q)
 * v (taylor_qd), naming a speed. */
static void
refusals(void)
{
    eomc_sim *s;
    double x[NX];
    /* a model that has series (a compiler's mistake): refused all the same */
    s = sim_new(&freebody_series_model);
    sim_x0(s, x);
    eomc_run_opts o = opts_for(&freebody_series_model, 1.0, 0.1, "taylor", 1e-10, 1e-10);
    int rc = eomc_sim_integrate(s, &o, x, NULL, NULL, NULL);
    CHECK(rc == EOMC_EUSAGE && strstr(eomc_sim_error(s), "not its coordinates' rates") &&
              strstr(eomc_sim_error(s), "taylor_qd") && strstr(eomc_sim_error(s), "root_wx"),
          "--method taylor refuses a model with speeds whose series lack q' = W(q) v: %s",
          eomc_sim_error(s));
    eomc_sim_free(s);
}

int
main(void)
{
    names_and_sizes();
    accel_closed_form(&freebody_model);
    jacobian_fd(&freebody_model);
    jacobian_fd(&top_model);
    jacobian_fd(&top_loads_model);
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
        symmetric_run(&freebody_model, &cases[k]);
    symmetric_run(&freebody_accel_model, &cases[4]);
    asymmetric_run("rk8pd", 1e-12, 0, 1e-9, 0);
    asymmetric_run("rk8pd", 1e-8, 0, 1e-6, 0);
    asymmetric_run("bsimp", 1e-11, 0, 1e-8, 31);
    asymmetric_run("rk4", 1e-12, 1e-3, 1e-8, 0);
    top_run(&top_model, "rk4imp", 1e-10, 0, 0, 1e-7, NULL);
    top_run(&top_model, "bsimp", 1e-11, 0, 0, 1e-8, NULL);
    top_run(&top_model, "rk8pd", 1e-10, 0, 1, 1e-7, NULL);
    top_run(&top_loads_model, "rk4", 1e-12, 1e-3, 1, 1e-6, NULL);
    top_same();
    bounce();
    steps();
    projection();
    no_scale();
    reference();
    refusals();
    for (int a = 0; a < 3; a++)
        spin_linearized(a, 0.7);
    rest_and_equilibrium();
    top_hanging(&top_model);
    top_hanging(&top_loads_model);
    return check_done();
}

/*
 * mech: sum up T, V, S and Q over particles, explicit terms and the
 * effects that the scene turns on.  Disabled effects contribute nothing,
 * so no code for them is ever derived or emitted.
 */
#include "mech.h"

#include "contact.h"

#include <stdlib.h>
#include <string.h>

static ExprId
dot_product(ExprPool *P, int dim, const ExprId *x, const ExprId *y)
{
    ExprId s = EXPR_ZERO;
    for (int k = 0; k < dim; k++)
        s = expr_add(P, s, expr_mul(P, x[k], y[k]));
    return s;
}

/* 1/2 m |d^order r/dt^order|^2 for one particle. */
static ExprId
particle_square(ExprPool *P, Diff *D, const SpecParticle *pt, int order)
{
    ExprId w[3];
    for (int k = 0; k < pt->dim; k++) {
        w[k] = pt->pos[k];
        for (int o = 0; o < order; o++)
            w[k] = diff_time(D, w[k]);
    }
    ExprId half_m = expr_mul(P, expr_const(P, 0.5), pt->mass);
    return expr_mul(P, half_m, dot_product(P, pt->dim, w, w));
}

/* Body-frame w x (I w). */
static void
gyroscopic(ExprPool *P, const SpecBody *b, ExprId out[3])
{
    ExprId Iw[3];
    for (int i = 0; i < 3; i++)
        Iw[i] = dot_product(P, 3, &b->inertia[3 * i], b->omega);
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3, k = (i + 2) % 3;
        ExprId kj = expr_mul(P, b->omega[k], Iw[j]);
        ExprId jk = expr_mul(P, b->omega[j], Iw[k]);
        out[i] = expr_sub(P, jk, kj);
    }
}

/* 1/2 m |c'|^2 + 1/2 w.I w (order 1), or the acceleration energy
 * 1/2 m |c''|^2 + 1/2 w'.I w' + w'.(w x I w), less terms free of q''
 * (order 2). */
static ExprId
body_energy(ExprPool *P, Diff *D, const SpecBody *b, int order)
{
    SpecParticle centre = {b->name, b->loc, b->mass, b->dim, {0}, {0}, 0, -1};
    int vel = b->has_center_vel; /* the order-1 form frames give */
    for (int k = 0; k < b->dim; k++)
        centre.pos[k] = vel ? b->center_vel[k] : b->center[k];
    ExprId e = particle_square(P, D, &centre, order - vel), half = expr_const(P, 0.5);
    int nw = b->dim == 2 ? 1 : 3;
    ExprId w[3], Iw[3];
    for (int i = 0; i < nw; i++)
        w[i] = order == 1 ? b->omega[i] : diff_time(D, b->omega[i]);
    for (int i = 0; i < nw; i++)
        Iw[i] = nw == 1 ? expr_mul(P, b->inertia[0], w[0])
                        : dot_product(P, 3, &b->inertia[3 * i], w);
    e = expr_add(P, e, expr_mul(P, half, dot_product(P, nw, w, Iw)));
    if (order == 2 && nw == 3) {
        ExprId g[3];
        gyroscopic(P, b, g);
        e = expr_add(P, e, dot_product(P, 3, w, g));
    }
    if (b->quat[0] >= 0 && b->quat_speed < 0 && b->dim == 3) {
        /* w = 2 L e' leaves e' along e without inertia: the mass matrix
         * would be singular (in that direction only the unit constraint
         * decides).  1/2 c (e.e')^2, with c = 4 tr(I)/3 (the mean of the
         * other directions' 4 A, 4 B, 4 C), gives it inertia and is zero,
         * with every derivative the motion sees, where the constraint
         * holds (e.e' = 0 and its rate e.e'' + e'.e' = 0).  Its
         * acceleration energy is 1/2 c (e.e'' + e'.e')^2. */
        ExprId y = EXPR_ZERO; /* (e.e)/2, whose rate is e.e' */
        for (int k = 0; k < 4; k++)
            y = expr_add(P, y, expr_powi(P, expr_var(P, b->quat[k], 0), 2));
        y = expr_mul(P, half, y);
        ExprId rate = diff_time(D, y);
        if (order == 2)
            rate = diff_time(D, rate);
        ExprId tr = expr_add(P, expr_add(P, b->inertia[0], b->inertia[4]), b->inertia[8]);
        ExprId c = expr_mul(P, expr_const(P, 4.0 / 3.0), tr);
        e = expr_add(P, e, expr_mul(P, half, expr_mul(P, c, expr_powi(P, rate, 2))));
    }
    return e;
}

/* Qq_i += F . dr/dq_i for a force at a point r(t, q). */
static void
add_point_force(const ExprId *r, int dim, const SpecForce *f, Mech *m, ExprPool *P,
                Diff *D, ExprId *Qq)
{
    for (int i = 0; i < m->nq; i++) {
        ExprId J[3];
        for (int k = 0; k < dim; k++)
            J[k] = diff_partial(D, r[k], m->q[0][i]);
        Qq[i] = expr_add(P, Qq[i], dot_product(P, dim, f->vec, J));
    }
}

/* Q_j += tau . dw/dv_j: the virtual rotation of the body is
 * (dw/dv) delta v, in any speeds. */
static void
add_torque(const SpecBody *b, const SpecForce *f, Mech *m, ExprPool *P, Diff *D)
{
    int nw = b->dim == 2 ? 1 : 3;
    for (int i = 0; i < m->n; i++) {
        ExprId J[3];
        for (int k = 0; k < nw; k++)
            J[k] = diff_partial(D, b->omega[k], m->q[1][i]);
        m->Q[i] = expr_add(P, m->Q[i], dot_product(P, nw, f->vec, J));
    }
}

/* V -= sum_k m_k g . r_k over all particles and bodies' centres */
static ExprId
gravity_potential(const Spec *s, const SpecForce *f, ExprPool *P)
{
    ExprId V = EXPR_ZERO;
    for (int k = 0; k < s->npart; k++) {
        const SpecParticle *pt = &s->part[k];
        ExprId gr = dot_product(P, pt->dim, f->vec, pt->pos);
        V = expr_sub(P, V, expr_mul(P, pt->mass, gr));
    }
    for (int k = 0; k < s->nbody; k++) {
        const SpecBody *b = &s->body[k];
        ExprId gr = dot_product(P, b->dim, f->vec, b->center);
        V = expr_sub(P, V, expr_mul(P, b->mass, gr));
    }
    return V;
}

static void
add_effect(const Spec *s, const SpecEffect *e, Mech *m, Arena *A, ExprPool *P, Diff *D,
           ExprId *Qq)
{
    for (int j = 0; j < e->nforce; j++) {
        const SpecForce *f = &e->force[j];
        switch (f->kind) {
        case FORCE_GRAVITY:
            m->V = expr_add(P, m->V, gravity_potential(s, f, P));
            if (f->dim == 3 && m->gravity[0] != EXPR_NONE) {
                for (int i = 0; i < 3; i++)
                    m->gravity[i] = expr_add(P, m->gravity[i], f->vec[i]);
            } else {
                m->gravity[0] = EXPR_NONE;
            }
            break;
        case FORCE_POTENTIAL:
            m->V = expr_add(P, m->V, f->expr);
            m->V_rest = expr_add(P, m->V_rest, f->expr);
            break;
        case FORCE_VECTOR:
            if (f->particle >= 0)
                add_point_force(s->part[f->particle].pos, f->dim, f, m, P, D, Qq);
            else
                add_point_force(s->body[f->body].center, f->dim, f, m, P, D, Qq);
            break;
        case FORCE_TORQUE:
            add_torque(&s->body[f->body], f, m, P, D);
            break;
        case FORCE_KINETIC: /* in T (mech_build) */
            break;
        case FORCE_CONTACT:
            contact_add(s, e, f, P, D,
                        &(ContactQ){m->nq, m->n, m->q[0], m->q[1], Qq, m->Q, A, &m->fric});
            break;
        case FORCE_WORK: /* W = sum_i Q_i delta(q_i), linear (spec/effects.c checked) */
            for (int i = 0; i < m->nq; i++)
                Qq[i] = expr_add(P, Qq[i], diff_partial(D, f->expr, expr_seed(P, i, 0)));
            for (int j = 0; m->speeds && j < m->n; j++) /* and delta(w), a speed's own */
                if (s->vcoord[j] >= m->nq)
                    m->Q[j] = expr_add(P, m->Q[j], diff_partial(D, f->expr,
                                                                 expr_seed(P, s->vcoord[j], 0)));
            break;
        }
    }
}

Mech *
mech_build(const Spec *s, Arena *A, ExprPool *P, Diff *D)
{
    Mech *m = arena_alloc(A, sizeof *m);
    m->n = s->nv;
    m->nq = s->nq;
    m->speeds = s->nspeed > 0;
    m->q[0] = arena_new_array(A, ExprId, s->nq);
    for (int i = 0; i < s->nq; i++)
        m->q[0][i] = expr_var(P, i, 0);
    for (int k = 1; k <= EXPR_MAX_ORDER; k++) {
        m->q[k] = arena_new_array(A, ExprId, s->nv);
        for (int j = 0; j < s->nv; j++)
            m->q[k][j] = expr_var(P, s->vcoord[j], k);
    }
    m->rate = arena_new_array(A, ExprId, s->nq);
    for (int i = 0; i < s->nq; i++)
        m->rate[i] = diff_time(D, m->q[0][i]);
    m->T = m->V = m->S = m->T_joint = EXPR_ZERO;
    for (int k = 0; k < s->npart; k++) {
        SpecParticle at = s->part[k]; /* at a point: its velocity as frames give it */
        int vel = at.has_vel;
        for (int i = 0; vel && i < at.dim; i++)
            at.pos[i] = at.vel[i];
        m->T = expr_add(P, m->T, particle_square(P, D, &at, 1 - vel));
        m->S = expr_add(P, m->S, particle_square(P, D, &at, 2 - vel));
    }
    for (int k = 0; k < s->nbody; k++) {
        m->T = expr_add(P, m->T, body_energy(P, D, &s->body[k], 1));
        m->S = expr_add(P, m->S, body_energy(P, D, &s->body[k], 2));
    }
    /* kinetic-energy terms no mass carries: the spec's own, and those of
     * the effects that are on (a rotor's inertia) */
    int nkin = s->nkinetic;
    for (int e = 0; e < s->neffect; e++)
        for (int j = 0; s->effect[e].enabled && j < s->effect[e].nforce; j++)
            nkin += s->effect[e].force[j].kind == FORCE_KINETIC;
    ExprId *kin = arena_new_array(A, ExprId, nkin + 1);
    nkin = 0;
    for (int k = 0; k < s->nkinetic; k++)
        kin[nkin++] = s->kinetic[k].expr;
    for (int e = 0; e < s->neffect; e++)
        for (int j = 0; s->effect[e].enabled && j < s->effect[e].nforce; j++)
            if (s->effect[e].force[j].kind == FORCE_KINETIC)
                kin[nkin++] = s->effect[e].force[j].expr;
    for (int k = 0; k < nkin; k++) {
        m->T = expr_add(P, m->T, kin[k]);
        m->T_joint = expr_add(P, m->T_joint, kin[k]);
    }
    m->in_kinetic = arena_new_array(A, unsigned char, s->nq + 1);
    {
        unsigned char *mark = calloc(expr_pool_size(P), 1);
        expr_mark(P, nkin, kin, mark);
        for (int i = 0; i < s->nq; i++)
            m->in_kinetic[i] = mark[m->q[0][i]] || (s->vslot[i] >= 0 && mark[m->q[1][s->vslot[i]]]);
        free(mark);
    }
    if (nkin > 0)
        m->S = EXPR_NONE;
    ExprId T0 = m->T;
    /* the coordinates that are no quaternion's parameters, and zeros */
    ExprId *rest = NULL, *zeros = NULL;
    int nrest = 0;
    if (s->nfquat) {
        rest = arena_new_array(A, ExprId, s->nq);
        zeros = arena_new_array(A, ExprId, s->nq);
        for (int i = 0; i < s->nq; i++) {
            int quat = 0;
            for (int k = 0; k < s->nfquat; k++)
                for (int d = 0; d < 4; d++)
                    quat |= s->fquat[k].q[d] == i;
            if (!quat)
                rest[nrest] = m->q[0][i], zeros[nrest++] = EXPR_ZERO;
        }
        if (!nrest)
            rest = NULL;
    }
    for (int k = 0; k < s->nfquat; k++) {
        if (s->fquat[k].speed >= 0) /* turned by its speeds: no e' along e */
            continue;
        /* a frame turned by Euler parameters e: as for a body's
         * (body_energy), e' along e moves nothing, and 1/2 c (e.e')^2
         * gives it inertia where the unit constraint alone decides.  c is
         * the mean inertia of the other directions, a third of the trace
         * of d2T/de'2 (4 tr(I) for one body on the frame), so that it
         * scales with the model's units. */
        const int *q = s->fquat[k].q;
        ExprId tr = EXPR_ZERO, y = EXPR_ZERO, half = expr_const(P, 0.5);
        for (int i = 0; i < 4; i++) {
            ExprId v = m->q[1][q[i]];
            tr = expr_add(P, tr, diff_partial(D, diff_partial(D, T0, v), v));
            y = expr_add(P, y, expr_powi(P, m->q[0][q[i]], 2));
        }
        /* at the other coordinates' zeros (a quaternion's own kept): on a
         * tree the trace is a function of every joint below, whose terms
         * would cost more than the motion's own, and any positive c serves */
        if (rest) {
            ExprId trz;
            expr_subst_many(P, 1, &tr, nrest, rest, zeros, &trz);
            tr = trz;
        }
        ExprId c = expr_mul(P, expr_const(P, 1.0 / 3.0), tr);
        y = expr_mul(P, half, y); /* its rate is e.e' */
        ExprId rate = diff_time(D, y);
        ExprId Tq = expr_mul(P, half, expr_mul(P, c, expr_powi(P, rate, 2)));
        m->T = expr_add(P, m->T, Tq);
        m->T_joint = expr_add(P, m->T_joint, Tq);
        if (m->S != EXPR_NONE)
            m->S = expr_add(P, m->S, expr_mul(P, half, expr_mul(P, c, expr_powi(P,
                                                                      diff_time(D, rate), 2))));
    }
    for (int k = 0; k < s->npotential; k++)
        m->V = expr_add(P, m->V, s->potential[k].expr);
    m->V_rest = m->V;
    m->gravity[0] = m->gravity[1] = m->gravity[2] = EXPR_ZERO;
    m->Q = arena_new_array(A, ExprId, s->nv);
    for (int j = 0; j < s->nv; j++)
        m->Q[j] = EXPR_ZERO;
    /* forces by the coordinates' virtual displacements, then in the
     * speeds: Q_j = sum_i Qq_i dq_i'/dv_j (the same array without speeds) */
    ExprId *Qq = m->Q;
    if (m->speeds) {
        Qq = arena_new_array(A, ExprId, s->nq);
        for (int i = 0; i < s->nq; i++)
            Qq[i] = EXPR_ZERO;
    }
    for (int e = 0; e < s->neffect; e++)
        if (s->effect[e].enabled)
            add_effect(s, &s->effect[e], m, A, P, D, Qq);
    for (int i = 0; m->speeds && i < s->nq; i++)
        for (int j = 0; Qq[i] != EXPR_ZERO && j < s->nv; j++)
            m->Q[j] = expr_add(P, m->Q[j], expr_mul(P, Qq[i], diff_partial(D, m->rate[i],
                                                                         m->q[1][j])));
    /* A coordinate whose velocity is not in T has a zero row in M: the
     * spec is wrong, and saying so beats a singular matrix at run time. */
    /* (by the leaves T reaches, once: a derivative per coordinate would
     * cost n times T's size) */
    /* (in the arena: diag_error may end the compilation here) */
    size_t npool = expr_pool_size(P);
    unsigned char *in_T = arena_alloc(A, npool + 1);
    memset(in_T, 0, npool + 1);
    expr_mark(P, 1, &m->T, in_T);
    for (int j = 0; j < m->n; j++) {
        int c = s->vcoord[j];
        if (in_T[m->q[1][j]])
            continue;
        if (c < s->nq)
            diag_error(s->coord[c].loc, "coordinate '%s' does not appear in the kinetic "
                       "energy: it has no inertia, so its row of the mass matrix is zero",
                       s->coord[c].name);
        diag_error(s->speed[c - s->nq].loc, "speed '%s' does not appear in the kinetic energy: "
                   "it has no inertia, so its row of the mass matrix is zero",
                   s->speed[c - s->nq].name);
    }
    for (int i = 0; m->gravity[0] != EXPR_NONE && i < 3; i++)
        if (diff_time(D, m->gravity[i]) != EXPR_ZERO) /* not uniform at every instant */
            m->gravity[0] = EXPR_NONE;
    if (m->gravity[0] == EXPR_NONE)
        m->V_rest = m->V;
    m->tree = tree_build(s, m->q[1], nkin, kin, A, P, D, &m->tree_why);
    return m;
}

/*
 * mech: sum up T, V, S and Q over particles, explicit terms and the
 * effects that the scene turns on.  Disabled effects contribute nothing,
 * so no code for them is ever derived or emitted.
 */
#include "mech.h"

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

/* Q_i += F . dr/dq_i */
static void
add_vector_force(const Spec *s, const SpecForce *f, Mech *m, ExprPool *P,
                 Diff *D)
{
    const SpecParticle *pt = &s->part[f->particle];
    for (int i = 0; i < m->n; i++) {
        ExprId J[3];
        for (int k = 0; k < pt->dim; k++)
            J[k] = diff_partial(D, pt->pos[k], m->q[0][i]);
        m->Q[i] = expr_add(P, m->Q[i], dot_product(P, pt->dim, f->vec, J));
    }
}

/* V -= sum_k m_k g . r_k over all particles */
static ExprId
gravity_potential(const Spec *s, const SpecForce *f, ExprPool *P)
{
    ExprId V = EXPR_ZERO;
    for (int k = 0; k < s->npart; k++) {
        const SpecParticle *pt = &s->part[k];
        ExprId gr = dot_product(P, pt->dim, f->vec, pt->pos);
        V = expr_sub(P, V, expr_mul(P, pt->mass, gr));
    }
    return V;
}

static void
add_effect(const Spec *s, const SpecEffect *e, Mech *m, ExprPool *P, Diff *D)
{
    for (int j = 0; j < e->nforce; j++) {
        const SpecForce *f = &e->force[j];
        switch (f->kind) {
        case FORCE_GRAVITY:
            m->V = expr_add(P, m->V, gravity_potential(s, f, P));
            break;
        case FORCE_POTENTIAL:
            m->V = expr_add(P, m->V, f->expr);
            break;
        case FORCE_VECTOR:
            add_vector_force(s, f, m, P, D);
            break;
        case FORCE_WORK: /* delta W = sum_i dW/dq_i delta q_i */
            for (int i = 0; i < m->n; i++)
                m->Q[i] = expr_add(P, m->Q[i],
                                   diff_partial(D, f->expr, m->q[0][i]));
            break;
        }
    }
}

Mech *
mech_build(const Spec *s, Arena *A, ExprPool *P, Diff *D)
{
    Mech *m = arena_alloc(A, sizeof *m);
    m->n = s->nq;
    for (int k = 0; k <= EXPR_MAX_ORDER; k++) {
        m->q[k] = arena_new_array(A, ExprId, s->nq);
        for (int i = 0; i < s->nq; i++)
            m->q[k][i] = expr_var(P, i, k);
    }
    m->T = m->V = m->S = EXPR_ZERO;
    for (int k = 0; k < s->npart; k++) {
        m->T = expr_add(P, m->T, particle_square(P, D, &s->part[k], 1));
        m->S = expr_add(P, m->S, particle_square(P, D, &s->part[k], 2));
    }
    for (int k = 0; k < s->nkinetic; k++)
        m->T = expr_add(P, m->T, s->kinetic[k].expr);
    if (s->nkinetic > 0)
        m->S = EXPR_NONE;
    for (int k = 0; k < s->npotential; k++)
        m->V = expr_add(P, m->V, s->potential[k].expr);
    m->Q = arena_new_array(A, ExprId, s->nq);
    for (int i = 0; i < s->nq; i++)
        m->Q[i] = EXPR_ZERO;
    for (int e = 0; e < s->neffect; e++)
        if (s->effect[e].enabled)
            add_effect(s, &s->effect[e], m, P, D);
    /* A coordinate whose velocity is not in T has a zero row in M: the
     * spec is wrong, and saying so beats a singular matrix at run time. */
    for (int i = 0; i < m->n; i++)
        if (diff_partial(D, m->T, m->q[1][i]) == EXPR_ZERO)
            diag_error(s->coord[i].loc, "coordinate '%s' does not appear in the kinetic "
                       "energy: it has no inertia, so its row of the mass matrix is zero",
                       s->coord[i].name);
    return m;
}

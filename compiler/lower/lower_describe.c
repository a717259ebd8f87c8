/*
 * lower_describe: the lowered model's own copy of what the emitter prints
 * besides the functions (lowered.h's LowModel), so that emit reads neither
 * the spec nor the form, the constraints or the invariant.
 */
#include "lower_describe.h"

#include <string.h>

static const char *
dup(Arena *A, const char *s)
{
    return s ? arena_strdup(A, s) : NULL;
}

/* The spec's file name without directories. */
static const char *
base_name(const char *path)
{
    const char *base = strrchr(path, '/');
    return base ? base + 1 : path;
}

void
lower_describe(Lowered *L, const Spec *s, const Eom *e, const Constraints *c,
               const Invariant *inv, Arena *A)
{
    LowModel *md = &L->model;
    const SpecScene *sc = &s->scene;
    md->name = dup(A, s->name);
    md->spec = dup(A, base_name(s->path));
    md->form = dup(A, e->form->name);
    md->formula = dup(A, e->form->formula);
    md->nq = s->nq, md->np = s->np, md->nu = s->nu, md->neffect = s->neffect;
    md->coord = arena_new_array(A, const char *, s->nq + s->nspeed);
    for (int i = 0; i < s->nq; i++)
        md->coord[i] = dup(A, s->coord[i].name);
    for (int k = 0; k < s->nspeed; k++)
        md->coord[s->nq + k] = dup(A, s->speed[k].name);
    md->nv = s->nv, md->nspeed = s->nspeed;
    md->vslot = arena_new_array(A, int, s->nq + s->nspeed);
    memcpy(md->vslot, s->vslot, (size_t)(s->nq + s->nspeed) * sizeof *md->vslot);
    md->vcoord = arena_new_array(A, int, s->nv);
    memcpy(md->vcoord, s->vcoord, (size_t)s->nv * sizeof *md->vcoord);
    md->v_names = arena_new_array(A, const char *, s->nv);
    for (int j = 0; j < s->nv; j++)
        md->v_names[j] = s->vcoord[j] < s->nq ? arena_printf(A, "%s'", md->coord[s->vcoord[j]])
                                              : md->coord[s->vcoord[j]];
    md->quat = arena_new_array(A, int, 4 * (s->nfquat + s->nbody) + 1);
    for (int k = 0; k < s->nfquat + s->nbody; k++) {
        const int *q = k < s->nfquat ? s->fquat[k].q : s->body[k - s->nfquat].quat;
        int sp = k < s->nfquat ? s->fquat[k].speed : s->body[k - s->nfquat].quat_speed;
        if (q[0] < 0 || sp < 0)
            continue;
        memcpy(md->quat + 4 * md->nquat++, q, 4 * sizeof *q);
    }
    md->param = arena_new_array(A, LowParam, s->np);
    for (int i = 0; i < s->np; i++)
        md->param[i] = (LowParam){dup(A, s->param[i].name), s->param[i].value,
                                  s->param[i].fixed};
    md->input = arena_new_array(A, const char *, s->nu);
    for (int i = 0; i < s->nu; i++)
        md->input[i] = dup(A, s->input[i].name);
    md->effect = arena_new_array(A, LowEffect, s->neffect);
    for (int k = 0; k < s->neffect; k++)
        md->effect[k] = (LowEffect){dup(A, s->effect[k].name), s->effect[k].enabled};

    md->scene = dup(A, sc->name);
    md->t_end = sc->t_end, md->dt = sc->dt, md->rtol = sc->rtol, md->atol = sc->atol;
    md->h_fixed = sc->h_fixed;
    md->method = dup(A, sc->method);
    md->noutput = sc->noutput;
    md->output = arena_new_array(A, const char *, sc->noutput);
    for (int k = 0; k < sc->noutput; k++)
        md->output[k] = dup(A, sc->output[k].name);
    md->nevent = sc->nevent;
    md->event = arena_new_array(A, LowEvent, sc->nevent);
    for (int k = 0; k < sc->nevent; k++)
        md->event[k] = (LowEvent){dup(A, sc->event[k].name), sc->event[k].direction,
                                  sc->event[k].action};
    md->assemble = sc->assemble;
    if (sc->hold) {
        md->hold = arena_new_array(A, unsigned char, s->nq + s->nv);
        memcpy(md->hold, sc->hold, (size_t)(s->nq + s->nv));
    }
    md->ncheck = s->ncheck;
    md->check = arena_new_array(A, LowCheck, s->ncheck);
    for (int i = 0; i < s->ncheck; i++)
        md->check[i] = (LowCheck){dup(A, s->check[i].what), dup(A, s->check[i].params),
                                  s->check[i].strict};

    md->constrained = c != NULL;
    md->affine = c ? c->affine : 1;
    md->nc = s->nconstraint;
    md->constraint = arena_new_array(A, LowConstraint, s->nconstraint);
    for (int k = 0; k < s->nconstraint; k++) {
        int order = s->constraint[k].order;
        md->constraint[k] = (LowConstraint){dup(A, s->constraint[k].name), order,
                                            constraint_order_name(order),
                                            c ? c->dependent[k] : -1};
    }
    md->invariant = inv->h != EXPR_NONE ? dup(A, inv->name) : NULL;
    md->invariant_note = dup(A, inv->note);
    if (e->mass_parent && !c) { /* (one entry per speed: M is nv x nv) */
        md->mass_parent = arena_new_array(A, int, e->n);
        memcpy(md->mass_parent, e->mass_parent, (size_t)e->n * sizeof *md->mass_parent);
    }
    const SpecView *v = &s->view;
    md->ndraw = v->nitem;
    md->draw_item = arena_new_array(A, LowDrawItem, v->nitem + 1);
    for (int k = 0; k < v->nitem; k++) /* SPEC_DRAW_* is EOMC_DRAW_*'s order */
        md->draw_item[k] = (LowDrawItem){dup(A, v->item[k].name),
                                         v->item[k].kind == SPEC_DRAW_GROUND ? SPEC_DRAW_BODY
                                                                             : v->item[k].kind,
                                         v->item[k].dim, v->item[k].unturned};
    md->nplace = s->nplace;
    md->place = arena_new_array(A, LowDrawItem, s->nplace + 1);
    for (int k = 0; k < s->nplace; k++)
        md->place[k] = (LowDrawItem){dup(A, s->place[k].name), s->place[k].kind,
                                     s->place[k].dim, s->place[k].unturned};
    md->shape = arena_new_array(A, LowShape, s->nshape + 1);
    md->nshape = 0;
    for (int k = 0; v->nitem && k < s->nshape; k++) /* a plane is the page's floor, no shape */
        if (s->shape[k].type != SPEC_SHAPE_PLANE)
            md->shape[md->nshape++] = s->shape[k];
    md->nlink = v->nlink, md->ntrace = v->ntrace, md->view_frames = v->frames;
    md->view_link = arena_new_array(A, int, 2 * v->nlink + 1);
    if (v->nlink)
        memcpy(md->view_link, v->link, 2 * (size_t)v->nlink * sizeof *md->view_link);
    md->view_trace = arena_new_array(A, int, v->ntrace + 1);
    if (v->ntrace)
        memcpy(md->view_trace, v->trace, (size_t)v->ntrace * sizeof *md->view_trace);
    md->has_camera = v->has_camera;
    memcpy(md->camera, v->camera, sizeof md->camera);
    md->view_follow = v->follow;
    md->view_floor = v->floor;
}

/*
 * project: move a state back onto its holonomic and velocity-level
 * constraints, as a pure function of (t, q, v, p, u) that returns a
 * status; sim.c says what it means.  The mathematics is in project.c;
 * n below is the number of speeds, nv (eomc.h).
 */
#ifndef EOMC_PROJECT_H
#define EOMC_PROJECT_H

#include "eomc_model.h"

typedef struct Proj Proj;

enum {
    PROJ_OK,
    PROJ_NOT_PD,    /* the mass matrix is not positive definite */
    PROJ_SINGULAR,  /* G M^-1 G^T is singular at the level */
    PROJ_NO_CONVERGENCE,
    PROJ_HOLD,      /* a held coordinate moves with a speed not held
                     * (proj_hold_conflict) */
};
/* Gauss-Newton corrections per level, at most. */
enum { PROJ_MAX = 20 };

/* NULL when memory runs out; proj_free is NULL-safe. */
Proj *proj_alloc(const eomc_model *m);
void proj_free(Proj *j);
/* Rows left out of the projections (drop [nc], 1: dropped; NULL: none),
 * still measured by proj_residual and proj_inconsistencies; 0, or -1 when
 * memory runs out. */
int proj_set_dropped(Proj *j, const unsigned char *drop);
/* The rows a level's projection uses (0: holonomic, 1: velocity), their
 * count into *nr. */
const int *proj_rows(const Proj *j, int level, int *nr);
/* Whether the model has constraints below acceleration level. */
int proj_levels(const Proj *j);
/* The largest |g| and |g'| or |phi| at (t, q, v), in the constraints'
 * own units. */
double proj_residual(Proj *j, double t, const double *q, const double *v,
                     const double *p, const double *u);
/* The largest residual of a constraint at position or velocity level
 * relative to the magnitude of its terms (0 when all hold exactly, 1 or
 * more when one is nowhere near), that constraint's index into *worst
 * (-1 when there are none) and its level into *level.  Unlike proj_residual, it does not
 * depend on the model's units. */
double proj_inconsistency(Proj *j, double t, const double *q, const double *v,
                          const double *p, const double *u, int *worst, int *level);
/* The same, with each constraint's into each [nc] (for a holonomic one the
 * larger of its two levels', g and g'; 0 for a second-order one) and its level
 * into each_level [nc] (0: g, 1: g' or phi), either NULL if not wanted. */
double proj_inconsistencies(Proj *j, double t, const double *q, const double *v,
                            const double *p, const double *u, int *worst, int *level,
                            double *each, int *each_level);
/* (q, v) onto the holonomic and velocity-level constraints, in place.
 * On failure *level is 0 (positions) or 1 (velocities). */
int proj_apply(Proj *j, double t, double *q, double *v, const double *p,
               const double *u, int *level);
/* The same keeping the coordinates and speeds hold [nq + nv] marks (q_i
 * at i, speed k at nq + k) as they are: the others move, by the smallest
 * change in the mass matrix's metric restricted to them (project.c). */
int proj_apply_held(Proj *j, double t, double *q, double *v, const double *p,
                    const double *u, const unsigned char *hold, int *level);
/* After PROJ_HOLD: the held coordinate and the speed not held that moves
 * it. */
void proj_hold_conflict(const Proj *j, int *coord, int *speed);
/* The constraints a level's projection uses (0: holonomic, 1: velocity),
 * for messages. */
const char *proj_names(const Proj *j, int level);

#endif

/*
 * state: the layout of a model's first-order state x = (q, v), nq
 * coordinates and then nv speeds (eomc.h): the names of its components
 * and of the speeds' rates, a component found by name, the kinematic
 * equation q' = W(q) v, and the unit quaternions the steps renormalize.
 * Pure functions of the model (state.c).
 */
#ifndef EOMC_STATE_H
#define EOMC_STATE_H

#include "eomc.h"

#include <stddef.h>

/* The longest name these functions write, with its quotes. */
enum { STATE_NAME_MAX = 256 };

/* Component k of the state (k < nq + nv): "x", then the speeds "x'" (the
 * coordinates' rates, model->nv = 0) or model->v_names ("root_wx"). */
const char *state_name(const eomc_model *m, int k, char *buf, size_t len);
/* Switch k's name (k < nmode, eomc_model.h's sw_names: floor.max), as
 * --events and the messages name it; "switch K" where the model has none. */
const char *state_switch_name(const eomc_model *m, int k, char *buf, size_t len);
/* Speed k's own name (k < nv): "x'" or "root_wx" (state_name's nq + k). */
const char *state_speed(const eomc_model *m, int k, char *buf, size_t len);
/* The rate of speed k, as --accel names it: "x''" or "root_wx'". */
const char *state_rate(const eomc_model *m, int k, char *buf, size_t len);
/* The first speed not named as a coordinate's rate ("root_wx", not
 * "root_x'"): what a message names to say the speeds are not the rates
 * (model->nv > 0). */
const char *state_own_speed(const eomc_model *m);
/* What a speed is called in messages, "velocity" or "speed", and its
 * plural. */
const char *state_speed_word(const eomc_model *m, int plural);
/* The index in the state of the component named name, or -1; *rate (unless
 * NULL) 1 when name is a speed's rate instead (state_rate's name: an
 * acceleration), its index then nq + k. */
int state_find(const eomc_model *m, const char *name, int *rate);

/* q' = W(q) v into qd [nq]: v itself when the speeds are the rates. */
void state_qdot(const eomc_model *m, const double *q, const double *v, double *qd);

/* Each unit quaternion of q (model->quat) divided by its length, in
 * place; returns the largest ||e| - 1| before (0 without quaternions),
 * and that quaternion's index into *which (-1: none).  One within a few
 * units of rounding of length 1 is left to the bit (state.c), and one
 * whose length is 0 or not finite is left as it is (the right-hand side
 * then says why the state fails). */
double state_normalize(const eomc_model *m, double *q, int *which);
/* The same for quaternion j alone: its ||e| - 1| before. */
double state_normalize_quat(const eomc_model *m, double *q, int j);
/* The same in extended precision (the reference). */
eomc_ext state_normalize_ext(const eomc_model *m, eomc_ext *q);
/* Quaternion j's length in q. */
double state_quat_norm(const eomc_model *m, const double *q, int j);

/* The tangent space's components, one per speed: slot[k] (k < nv) is the
 * coordinate whose rate speed k is, or STATE_ROTATION(j, a) (< 0) when
 * speed k is component a (0 x, 1 y, 2 z) of unit quaternion j's angular
 * velocity in its body's axes.  Read off the kinematic equation (state.c);
 * 0, or -1 when it is not of that form (a speed that is neither, or a
 * coordinate or an axis given by two speeds).  nv = 0: slot[k] = k. */
int state_tangent(const eomc_model *m, int *slot);
#define STATE_ROTATION(j, a) (-1 - 3 * (j) - (a))
#define STATE_ROT_QUAT(slot) ((-1 - (slot)) / 3)
#define STATE_ROT_AXIS(slot) ((-1 - (slot)) % 3)
/* The name of the small rotation about the axis of angular velocity
 * speed k: its speed's name with the w of its axis a (..."wx") an r
 * ("root_rx"), or "rot_" before it when it does not end so. */
const char *state_rotation_name(const eomc_model *m, int k, char *buf, size_t len);

#endif

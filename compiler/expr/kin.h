/*
 * kin: frames and points, as expressions.
 *
 * A frame is an orientation: its rotation matrix R (row-major; column k
 * is its k-th axis in world components) and its angular velocity relative
 * to the world, kept in its own components, where a rotation sequence's
 * rates add up without trigonometry (the recursive formula of multibody
 * codes: w_new = Rk^T w + a angle').  A point is a position in world
 * components.  Frame 0 is the world and point 0 its origin.  Everything
 * is exact: the derivatives are the DAG's (diff_time), never numerical.
 */
#ifndef EOMC_KIN_H
#define EOMC_KIN_H

#include "base/arena.h"
#include "diff.h"

typedef struct Kin Kin;

/* C = A B, 3 x 3 row-major (C may be A or B). */
void kin_mat3_mul(ExprPool *P, const ExprId *A, const ExprId *B, ExprId *C);
/* a x b and a . b of world-component vectors (out may be a or b). */
void kin_cross(ExprPool *P, const ExprId *a, const ExprId *b, ExprId *out);
ExprId kin_dot(ExprPool *P, const ExprId *a, const ExprId *b);

/* Room for nframes and npoints besides the world and its origin. */
Kin *kin_new(Arena *A, ExprPool *P, Diff *D, int nframes, int npoints);

enum { KIN_WORLD = 0, KIN_ORIGIN = 0 };

/* A new frame oriented as parent, to be turned by kin_turn*. */
int kin_frame(Kin *K, int parent);
/* The recursion by which turns add up to an angular velocity:
 * w = Rk^T w + own, w in the axes before the turn on entry and in those
 * after it on return, own the turn's own angular velocity in the axes
 * after it (a th', or 2 L e').  Frames turn by it (kin_turn*), and so do
 * bodies turned by a rotation sequence, which have no frame (spec/). */
void kin_rate_turn(ExprPool *P, const ExprId Rk[9], const ExprId own[3], ExprId w[3]);
/* Rk and unit axis a of a turn by th about coordinate axis k (0 x, 1 y,
 * 2 z), with Rk's zeros and ones written in. */
void kin_axis_turn(ExprPool *P, int k, ExprId th, ExprId Rk[9], ExprId a[3]);
/* Turn frame f by angle about its own axis k (0 x, 1 y, 2 z) as built so
 * far, or about the unit vector a in those components (a constant of the
 * parameters). */
void kin_turn_axis(Kin *K, int f, int k, ExprId angle);
void kin_turn(Kin *K, int f, const ExprId a[3], ExprId angle);
/* Turn frame f by the Euler parameters e = (e0, e1, e2, e3), scalar
 * first: the rotation (e0^2 - |v|^2) I + 2 v v^T + 2 e0 [v x], v = (e1,
 * e2, e3), whose angular velocity 2 L e' (in the turned axes) is exact
 * where |e| = 1, which a unit constraint must keep (spec/constraints.c adds it). */
void kin_turn_quaternion(Kin *K, int f, const ExprId e[4]);
/* The same turn whose angular velocity is the speeds w (in the turned
 * axes), and the Euler parameters' rates e' = 1/2 e (x) (0, w)
 * (kin_quat_rates, expr_set_rate): nothing to keep, |e| is constant. */
void kin_turn_quaternion_speeds(Kin *K, int f, const ExprId e[4], const ExprId w[3]);
/* ed = 1/2 e (x) (0, w) = 1/2 L^T w: the rates of the Euler parameters e
 * turning at w in the turned axes; L e' = w/2 and e.e' = 0 for any e. */
void kin_quat_rates(ExprPool *P, const ExprId e[4], const ExprId w[3], ExprId ed[4]);
/* w = 2 L(e) e': the angular velocity, in the turned axes, of Euler
 * parameters e turning at rates ed (exact where |e| = 1). */
void kin_quat_omega(ExprPool *P, const ExprId e[4], const ExprId ed[4], ExprId w[3]);
/* The rotation matrix of the Euler parameters e (scalar first), row-major:
 * (e0^2 - |v|^2) I + 2 v v^T + 2 e0 [v x], v = (e1, e2, e3).  A frame's
 * turn (kin_turn_quaternion) and a body's own quaternion share it. */
void kin_quat_matrix(ExprPool *P, const ExprId e[4], ExprId R[9]);
/* The point from + R_f at. */
int kin_point(Kin *K, int from, int f, const ExprId at[3]);
/* A frame's origin: the point whose motion, with the frame's rotation,
 * gives the velocity of any point moving with the frame (the world's is
 * point 0); -1 until set. */
void kin_set_origin(Kin *K, int f, int p);
int kin_origin(const Kin *K, int f);

/* World components: of frame f's axis k, of f's angular velocity, of
 * point p's position, and of a vector whose components in f are v. */
void kin_axis(const Kin *K, int f, int k, ExprId out[3]);
void kin_omega(const Kin *K, int f, ExprId out[3]);
void kin_pos(const Kin *K, int p, ExprId out[3]);
void kin_to_world(const Kin *K, int f, const ExprId v[3], ExprId out[3]);
/* f's components of a vector given in world components. */
void kin_to_frame(const Kin *K, int f, const ExprId w[3], ExprId out[3]);
/* f's angular velocity in its own components: a body's omega. */
void kin_omega_local(const Kin *K, int f, ExprId out[3]);
/* Point p's velocity, by the links' structure: v_from + w_f x (R_f at) +
 * R_f at', each w a sum of rates along axes (equal to the time derivative
 * of kin_pos, and built without differentiating a rotation matrix). */
void kin_vel(const Kin *K, int p, ExprId out[3]);
/* omega(f) - omega(g) in world components, summed from the turns on the
 * way between them in the tree of frames (nothing that cancels). */
void kin_omega_rel(const Kin *K, int f, int g, ExprId out[3]);
/* The same in g's own axes when g is an ancestor of f (1), from the turns
 * between them alone: 0 otherwise. */
int kin_omega_rel_in(const Kin *K, int f, int g, ExprId out[3]);
/* Point p's link: the point it is offset from (-1 for the origin), the
 * frame of the offset, and the offset in that frame's and the world's
 * axes. */
int kin_point_link(const Kin *K, int p, int *f, ExprId at[3], ExprId off[3]);

/* The tree's structure, for the recursive form (forms/newton_euler.c).
 * Frames are numbered after their parents; the world is frame 0, its
 * parent -1.  kin_is_ancestor counts f as its own ancestor. */
int kin_nframes(const Kin *K);
int kin_npoints(const Kin *K);
int kin_parent(const Kin *K, int f);
int kin_is_ancestor(const Kin *K, int a, int f);
/* Frame f's own turn k (0 the first): its rate (the angle's time
 * derivative) and its axis in world components; 0 past the last turn.
 * A turn by a quaternion has no axis: rate EXPR_NONE, axis zero. */
int kin_turn_of(const Kin *K, int f, int k, ExprId *rate, ExprId axis[3]);
/* The same turn as it turns f: its angle, unit axis a in the axes before
 * it (which the turn leaves where it is, so also in the axes after it),
 * and Rk, the axes after it in the axes before it (row-major, columns the
 * axes).  A quaternion's turn has angle EXPR_NONE and axis zero. */
int kin_turn_local(const Kin *K, int f, int k, ExprId *angle, ExprId a[3], ExprId Rk[9]);
/* The same turn's own angular velocity in the axes after it: a th' for
 * an angle, 2 L e' for a quaternion (kin_turn_quaternion). */
int kin_turn_omega(const Kin *K, int f, int k, ExprId wa[3]);
/* f's rotation matrix, row-major (columns its axes in the world's). */
void kin_rotation(const Kin *K, int f, ExprId R[9]);

#endif

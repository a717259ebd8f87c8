/*
 * animate: a run's motion as a self-contained HTML page (--animate
 * FILE.html).  The rows the CSV gets are kept as they are written (the
 * scene's outputs with them), each with the poses of the model's draw
 * items (eomc_model.draw), decimated to stay within the page's budget;
 * at the end the page is written: three.js and its OrbitControls
 * (Debian's libjs-three, read from $EOMC_THREE_DIR or
 * /usr/share/javascript/three) inlined, the scene and the trajectory as
 * JSON, and the page's own script (animate_page.js, built in).  It is
 * written to FILE.tmp and renamed: never a partial page.
 */
#ifndef EOMC_ANIMATE_H
#define EOMC_ANIMATE_H

#include "eomc.h"

/* The page's budget: at most ANIM_MAX_FRAMES frames, and at most
 * ANIM_MAX_TEXT bytes of trajectory text (numbers written %.6g); rows
 * beyond it are thinned evenly (every 2nd, 4th, ... row kept), the last
 * row always kept. */
#define ANIM_MAX_FRAMES 20000
#define ANIM_MAX_TEXT (4L << 20)

typedef struct Anim Anim;

/* The directory three.js is read from: $EOMC_THREE_DIR, else Debian's. */
const char *anim_three_dir(void);
/* NULL when the page can be written for m, else why not (a usage error:
 * nothing to draw, or libjs-three missing). */
const char *anim_cannot(const eomc_model *m, char *buf, size_t len);
/* A collector of sim's rows for the page at path; NULL when out of memory. */
Anim *anim_new(eomc_sim *sim, const char *path);
/* One row as written to the CSV: (t, x) and the scene's outputs [nout].
 * EOMC_OK, or EOMC_EUSAGE when out of memory. */
int anim_row(Anim *a, double t, const double *x, const double *out);
/* The page, from the rows kept (none: no page).  EOMC_OK, or EOMC_EUSAGE
 * after saying why on stderr (prog: the simulator's name). */
int anim_write(Anim *a, const char *prog);
void anim_free(Anim *a);
/* The uniform solid of mass mass and inertia I [9] (about its centre,
 * symmetric) that a body without shapes is drawn as: a cylinder when two
 * principal moments are equal and the third is not (a disk, a wheel, a
 * rod; also a planar body's moment about z alone: a disk in the plane),
 * else a box.  half [3]: the box's half-sizes along the columns of R [9]
 * (row-major, a rotation), or the cylinder's radius, radius and
 * half-length along R's third column.  EOMC_SHAPE_BOX or
 * EOMC_SHAPE_CYLINDER; -1 when I is not physical (half all 0). */
int anim_equivalent_solid(double mass, const double *I, double *half, double *R);

#endif

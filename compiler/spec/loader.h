/*
 * loader: the state of one spec_load (spec.h), which the files of spec/
 * share; nothing outside spec/ includes this.
 *
 * The loader works in phases, so that every name is known before any
 * expression is parsed: names (parameters, coordinates, inputs, defines),
 * then the defines in dependency order (found by lexing their texts, so
 * that a cycle is reported as one, and no define expansion recurses),
 * then everything else.  Each expression is parsed with the DEP_ bits
 * of what it may depend on; parse.c rejects the rest at the right column.
 *
 * Errors go through diag_error, which longjmps back to spec_load_buffer:
 * everything the loader allocates lives in the arena or the pool, so
 * nothing leaks when it unwinds, except the libyaml document, which the
 * catch point deletes.
 */
#ifndef EOMC_SPEC_LOADER_H
#define EOMC_SPEC_LOADER_H

#include "expr/kin.h"
#include "expr/parse.h"
#include "spec.h"

#include <yaml.h>

typedef struct Name Name;           /* names.h */
typedef struct Define Define;       /* names.h */
typedef struct AxisCheck AxisCheck; /* checks.h */

typedef struct Loader {
    ParseScope sc; /* first: parser callbacks receive the Loader */
    const char *path, *text;
    size_t len;
    size_t *line_start; /* byte offset of each line */
    size_t nlines;
    yaml_document_t doc;
    int have_doc;
    Arena *A;
    ExprPool *P;
    Spec *s;
    Name *names;
    int nnames;
    Define *def; /* the items: defines, then frames, then points */
    int ndef, nitem_defs, nframes, npoints;
    Kin *K;
    double *pdef;  /* the parameters' defaults, once loaded (spec_defaults()) */
    char *bad_param; /* per parameter: its value had an error */
    char *bad_part, *bad_body; /* per particle and body: it had an error */
    int *body_frame;           /* per body: the frame it is placed by, or -1 */
    int stop;      /* no use going on: SPEC_MAX_ERRORS reached, or a limit */
    const SpecOptions *opt; /* never NULL */
    yaml_node_t *scene;     /* the scene compiled: its map, or NULL */
    SpecScene *scene_into;  /* the scene being read: Spec.scene or a scratch copy */
    int scene_live;         /* it is the scene compiled */
    AxisCheck *axes;        /* fixed axes of parameters, checked once they are loaded */
    const char **quat_of;   /* per coordinate: whose Euler parameter it is, or NULL */
    int capfquat;           /* room in Spec.fquat */
    int shape_body;         /* the draw item whose shapes are being read */
    yaml_node_t **shape_node; /* per shape (Spec.shape): its map */
    int bad_shapes;         /* a shape had an error (it is not in Spec.shape) */
    int floor_plane;        /* the ground's plane that is the page's floor, or -1 */
} Loader;

#endif

/*
 * yaml: the spec's YAML through libyaml's document API, and the source
 * map from a node, or a byte of a scalar's value, back to the line and
 * column of the file.  Every accessor reports a node of the wrong kind at
 * that node (diag_error), so callers read the document as if it were
 * right.
 */
#ifndef EOMC_SPEC_YAML_H
#define EOMC_SPEC_YAML_H

#include "loader.h"

#define PAIRS(map) (map)->data.mapping.pairs.start
#define NPAIRS(map) ((int)((map)->data.mapping.pairs.top - (map)->data.mapping.pairs.start))
#define ITEMS(seq) (seq)->data.sequence.items.start
#define NITEMS(seq) ((int)((seq)->data.sequence.items.top - (seq)->data.sequence.items.start))

/* A scalar being parsed as an expression: where() maps its bytes back. */
typedef struct Scalar {
    ParseSrc src; /* first */
    const Loader *L;
    const yaml_node_t *node;
    /* where spec_scalar_where last stopped: value byte k is source byte
     * i, at line and col (0-based; all 0 with k 0: not yet asked) */
    size_t k, i, line, col;
} Scalar;

/* Read L->text into L->doc: one document, not nested too deep, no
 * expression split at its commas by a flow collection.  Its root. */
yaml_node_t *spec_read(Loader *L);

/* Where node n starts, and where byte off of a scalar's value is. */
SrcLoc spec_loc(const Loader *L, const yaml_node_t *n);
SrcLoc spec_scalar_where(const ParseSrc *src, size_t off);
/* Scalar n as a source for the parser (parse.h), located by the above. */
void spec_scalar_src(Loader *L, Scalar *sc, const yaml_node_t *n, const char *what);

/* Node id of the document. */
yaml_node_t *spec_node(Loader *L, int id);
/* An empty plain scalar (nothing, ~, null). */
int spec_is_null(const yaml_node_t *n);
/* n is of type (a scalar: not null), or an error naming `what`. */
void spec_expect(Loader *L, const yaml_node_t *n, yaml_node_type_t type, const char *what);
/* A scalar's text (no NUL inside), a key's, a mapping with unique keys. */
const char *spec_scalar(Loader *L, const yaml_node_t *n, const char *what);
const char *spec_key(Loader *L, const yaml_node_pair_t *p);
void spec_unique_keys(Loader *L, yaml_node_t *map, const char *what);
yaml_node_t *spec_map(Loader *L, yaml_node_t *n, const char *what);
/* Key i of map, or every key of it, is one of `allowed` (NULL-terminated),
 * or an error that says what was meant, in `where`. */
void spec_check_key(Loader *L, yaml_node_t *map, int i, const char *const *allowed,
                    const char *where);
void spec_check_keys(Loader *L, yaml_node_t *map, const char *const *allowed, const char *where);
/* The value of `key` in map, or NULL; spec_section: NULL also if it is
 * empty, and a mapping if map is set. */
yaml_node_t *spec_lookup(Loader *L, yaml_node_t *map, const char *key);
yaml_node_t *spec_section(Loader *L, yaml_node_t *root, const char *key, int map);
/* Where `key` of map is written (map's place if it is not). */
SrcLoc spec_key_loc(Loader *L, yaml_node_t *map, const char *key);

/* Going on after an error: f(L, map, i) reads one entry of a section; an
 * error in it is reported and spec_checked returns 0, so that the next
 * entry is read (past SPEC_MAX_ERRORS, the load is abandoned). */
typedef void EntryFn(Loader *L, yaml_node_t *map, int i);
int spec_checked(Loader *L, EntryFn *f, yaml_node_t *map, int i);
/* Abandon the load if anything so far failed: what follows depends on it. */
void spec_stop_if_failed(void);

#endif

/*
 * import_where: where in an MJCF or URDF file an error of `eomc import` is,
 * from MuJoCo's loader message or from the element the importer refuses
 * (import_where.c says which forms of MuJoCo's it reads).
 */
#ifndef EOMC_IMPORT_WHERE_H
#define EOMC_IMPORT_WHERE_H

#include "base/diag.h"

/* Where an import error points, for its file:line:column.  A loader
 * error: the line MuJoCo's message names, its column where it gives one
 * (else 0), and the element it names (elem, MuJoCo's "Element 'joint',
 * line 9") or the name of the object (name, "Object name = hip, id = 1,
 * line = 9"), to put the caret at that element's `<`.  A refusal: no line, the name of the element at fault, and
 * the tags it may have (tags, "motor general ...") inside which section
 * (section, "actuator"; NULL: anywhere), so that a site and a motor of one
 * name are told apart; the caret goes to the value of its `name="..."`.
 * All 0, "" and NULL where nothing is known (an unnamed element). */
typedef struct ImportWhere {
    int line, col;
    char elem[32];
    char name[128];
    const char *tags, *section;
} ImportWhere;

/* MuJoCo's loader message msg read for where it points, into *at. */
void import_where_parse(const char *msg, ImportWhere *at);

/* Where *at is in the model file at path: a location for diag, the file's
 * text registered with diag so that the error quotes it; the file alone
 * where the place is not known or not in this file. */
SrcLoc import_where_find(const char *path, const ImportWhere *at);

#endif

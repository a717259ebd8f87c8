/*
 * import_contact: a MuJoCo model's contacts as eomc's contact pairs
 * (docs/import.md "Contacts"): the geom pairs MuJoCo's filters let touch,
 * each with the stiffness and damping of eomc's law that its solref
 * gives, and the pairs eomc's contact cannot take, each with why.
 */
#ifndef EOMC_IMPORT_CONTACT_H
#define EOMC_IMPORT_CONTACT_H

#ifdef EOMC_HAVE_MUJOCO /* (import.c's MuJoCo part, as it is built with it) */
#include <mujoco/mujoco.h>

/* A pair eomc takes: geoms g1 and g2 (g1's type first in MuJoCo's order:
 * a plane before the shape on it), its law's k and c, and MuJoCo's
 * friction of it: condim, mu its sliding friction (friction[0] of the
 * contact's five), mu2 its second sliding direction's (friction[1]: a
 * <pair>'s own, else mu), as MuJoCo mixes them (import_contact.c). */
typedef struct ImportPair {
    int g1, g2;
    double k, c;
    int condim;
    double mu, mu2;
    int friction; /* eomc writes `friction: mu`: condim > 1, g1 a plane, no equality
                   * constraint (import_contacts' constrained) */
    int margin;   /* MuJoCo gives it a margin or gap */
} ImportPair;

/* A pair MuJoCo collides that eomc's contact cannot take, and why. */
typedef struct ImportSkip {
    int g1, g2;
    const char *why;
} ImportSkip;

typedef struct ImportContacts {
    ImportPair *pair;
    int npair;
    ImportSkip *skip;
    int nskip;
} ImportContacts;

/* The contacts of m where contacts are on (its flags), into *ic (zeros
 * where off); written[g]: geom g is a shape of the spec; constrained: the
 * spec has equality constraints (a run refuses contact friction with
 * them, so no pair's friction is written). */
void import_contacts(const mjModel *m, const unsigned char *written, int constrained,
                     ImportContacts *ic);
void import_contacts_free(ImportContacts *ic);

#endif
#endif

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
 * a plane before the shape on it), its law's k and c. */
typedef struct ImportPair {
    int g1, g2;
    double k, c;
    int friction, margin; /* MuJoCo gives it friction (condim > 1), a margin or gap */
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
 * where off); written[g]: geom g is a shape of the spec. */
void import_contacts(const mjModel *m, const unsigned char *written, ImportContacts *ic);
void import_contacts_free(ImportContacts *ic);

#endif
#endif

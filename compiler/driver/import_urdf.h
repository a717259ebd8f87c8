/*
 * import_urdf: a URDF's text as the importer hands it to MuJoCo's loader
 * (through its virtual file system), edited where MuJoCo's URDF reader
 * would do otherwise than asked: its visuals kept (MuJoCo discards them by
 * default) and, for --floating, its root links given free joints (MuJoCo
 * welds them to the world).  Each edit adds no line break, so MuJoCo's
 * line numbers stay the file's.  Plain text, no MuJoCo.
 */
#ifndef EOMC_IMPORT_URDF_H
#define EOMC_IMPORT_URDF_H

#include <stddef.h>

/* Whether an XML text's root element is a URDF's <robot>. */
int urdf_is(const char *text);

/* The URDF's text with MuJoCo told to keep its <visual>s (its compiler's
 * discardvisual="false"); NULL where the file says discardvisual itself
 * or the tags are not found.  malloc'd, its length in *outlen. */
char *urdf_keep_visuals(const char *text, size_t len, size_t *outlen);

/* The URDF's text with each root link (a link no joint has for its child)
 * joined to MuJoCo's world by a joint of type floating, a free joint to
 * MuJoCo, named after the link; malloc'd, its length in *outlen.  NULL
 * with the reason in err where there is no root to free (no link, or the
 * root is the link `world`, which MuJoCo takes for the world itself). */
char *urdf_floating(const char *text, size_t len, size_t *outlen, char *err, size_t errlen);

/* Each joint of the URDF with a <mimic> (which MuJoCo's URDF reader
 * ignores), by name, to each(ctx, name); how many. */
int urdf_mimics(const char *text, void (*each)(void *ctx, const char *joint), void *ctx);

#endif

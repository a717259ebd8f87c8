/*
 * import_urdf: a URDF's text edited for MuJoCo's loader (import_urdf.h).
 * A light reading of the XML (tags, their names and attributes, comments,
 * CDATA and declarations skipped): MuJoCo parses the file itself, and
 * what this misreads MuJoCo reports at the file's own lines.
 */
#include "import_urdf.h"

#include "base/arena.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The end of the tag that starts at lt ('<'): its '>', quoted values
 * skipped; NULL if it has none. */
static const char *
tag_end(const char *lt)
{
    for (const char *c = lt; *c; c++) {
        if (*c == '"' || *c == '\'') {
            const char *q = strchr(c + 1, *c);
            if (!q)
                return NULL;
            c = q;
        } else if (*c == '>') {
            return c;
        }
    }
    return NULL;
}

/* Does the tag at lt ('<') have this name (not a longer one)? */
static int
tag_is(const char *lt, const char *name)
{
    size_t n = strlen(name);
    char after = lt[1 + n];
    return !strncmp(lt + 1, name, n) &&
           (after == '>' || after == '/' || after == ' ' || after == '\t' || after == '\n' ||
            after == '\r');
}

/* The root element's start tag: its '<' past the XML declaration,
 * comments and a doctype; NULL if there is none. */
static const char *
root_tag(const char *text)
{
    const char *c = text;
    for (;;) {
        c += strspn(c, " \t\r\n");
        if (!strncmp(c, "\xef\xbb\xbf", 3)) /* a UTF-8 byte-order mark */
            c += 3;
        else if (!strncmp(c, "<?", 2))
            c = (c = strstr(c, "?>")) ? c + 2 : NULL;
        else if (!strncmp(c, "<!--", 4))
            c = (c = strstr(c, "-->")) ? c + 3 : NULL;
        else if (!strncmp(c, "<!", 2))
            c = (c = tag_end(c)) ? c + 1 : NULL;
        else
            return *c == '<' ? c : NULL;
        if (!c)
            return NULL;
    }
}

/* A URDF's text with MuJoCo told to keep its <visual>s: MuJoCo's own
 * compiler option discardvisual="false", which its URDF reader takes from
 * a <mujoco><compiler .../></mujoco> in the <robot> (URDF's default is to
 * discard them).  Put in the file's own <mujoco> element where it has
 * one (MuJoCo reads the first only), else as a new one first in <robot>,
 * without a line break: MuJoCo's line numbers stay the file's.  NULL
 * where the file says discardvisual itself (its choice stands) or the
 * tags are not found.  malloc'd, its length in *outlen. */
int
urdf_is(const char *text)
{
    const char *root = root_tag(text);
    return root && tag_is(root, "robot");
}

/* A URDF's text with MuJoCo told to keep its <visual>s: MuJoCo's own
 * compiler option discardvisual="false", which its URDF reader takes from
 * a <mujoco><compiler .../></mujoco> in the <robot> (URDF's default is to
 * discard them).  Put in the file's own <mujoco> element where it has
 * one (MuJoCo reads the first only), else as a new one first in <robot>,
 * without a line break: MuJoCo's line numbers stay the file's.  NULL
 * where the file says discardvisual itself (its choice stands) or the
 * tags are not found.  malloc'd, its length in *outlen. */
char *
urdf_keep_visuals(const char *text, size_t len, size_t *outlen)
{
    static const char *const attr = " discardvisual=\"false\"";
    static const char *const compiler = "<compiler discardvisual=\"false\"/>";
    static const char *const element = "<mujoco><compiler discardvisual=\"false\"/></mujoco>";
    const char *root = root_tag(text);
    const char *re = root ? tag_end(root) : NULL, *at = NULL, *ins = NULL;
    if (!re || re[-1] == '/' || strstr(text, "discardvisual"))
        return NULL;
    for (const char *c = re; !at && (c = strstr(c, "<mujoco")); c++) {
        const char *e = tag_is(c, "mujoco") ? tag_end(c) : NULL;
        if (!e || e[-1] == '/')
            continue; /* <mujoco/>: nothing in it, one of ours goes first */
        const char *close = strstr(e, "</mujoco");
        const char *cp = strstr(e, "<compiler");
        if (cp && (!close || cp < close) && tag_is(cp, "compiler"))
            at = cp + strlen("<compiler"), ins = attr;
        else
            at = e + 1, ins = compiler;
    }
    if (!at)
        at = re + 1, ins = element;
    size_t head = (size_t)(at - text), n = strlen(ins);
    char *out = xmalloc(len + n + 1);
    memcpy(out, text, head);
    memcpy(out + head, ins, n);
    memcpy(out + head + n, at, len - head + 1);
    *outlen = len + n;
    return out;
}


/* The next tag at or after c, a start or an end tag: its '<' (comments,
 * CDATA, processing instructions and declarations skipped); NULL at the
 * end. */
static const char *
next_tag(const char *c)
{
    while ((c = strchr(c, '<'))) {
        const char *past;
        if (!strncmp(c, "<!--", 4))
            past = (past = strstr(c + 4, "-->")) ? past + 3 : NULL;
        else if (!strncmp(c, "<![CDATA[", 9))
            past = (past = strstr(c + 9, "]]>")) ? past + 3 : NULL;
        else if (c[1] == '?')
            past = (past = strstr(c + 2, "?>")) ? past + 2 : NULL;
        else if (c[1] == '!')
            past = (past = tag_end(c)) ? past + 1 : NULL;
        else
            return c;
        if (!past)
            return NULL;
        c = past;
    }
    return NULL;
}

/* A walk through a text's tags: each start or end tag in turn, with the
 * depth of its element (the root's 0). */
typedef struct Walk {
    const char *lt, *gt; /* the tag's '<' and '>' */
    int depth;
    int empty; /* a start tag that ends itself, <x/> */
    int open;  /* elements open after it */
} Walk;

/* The next tag into *w (zeroed to start at text); 0 at the end. */
static int
walk(Walk *w, const char *text)
{
    const char *c = next_tag(w->lt ? w->gt + 1 : text);
    if (!c || !(w->gt = tag_end(c)))
        return 0;
    w->lt = c;
    if (c[1] == '/') {
        w->depth = --w->open, w->empty = 0;
    } else {
        w->depth = w->open, w->empty = w->gt[-1] == '/';
        w->open += !w->empty;
    }
    return 1;
}

/* The value of attribute key of the tag from lt to its end gt into buf
 * (as written, entities and all, truncated to len); 1, or 0 if it has
 * none. */
static int
tag_attr(const char *lt, const char *gt, const char *key, char *buf, size_t len)
{
    size_t n = strlen(key);
    for (const char *c = lt + 1; c < gt; c++) {
        if (*c == '"' || *c == '\'') { /* a value: not where a name starts */
            const char *q = strchr(c + 1, *c);
            if (!q || q > gt)
                return 0;
            c = q;
            continue;
        }
        if (!isspace((unsigned char)c[-1]) || strncmp(c, key, n))
            continue;
        const char *v = c + n;
        v += strspn(v, " \t\r\n");
        if (*v != '=')
            continue;
        v += 1 + strspn(v + 1, " \t\r\n");
        const char *q = *v == '"' || *v == '\'' ? strchr(v + 1, *v) : NULL;
        if (!q || q > gt)
            return 0;
        snprintf(buf, len, "%.*s", (int)(q - v - 1), v + 1);
        return 1;
    }
    return 0;
}

/* A list of names. */
typedef struct NameList {
    char **s;
    int n, cap;
} NameList;

static void
add(NameList *l, const char *s)
{
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 16;
        l->s = xrealloc(l->s, (size_t)l->cap * sizeof *l->s);
    }
    l->s[l->n++] = strcpy(xmalloc(strlen(s) + 1), s);
}

static int
has(const NameList *l, const char *s)
{
    for (int i = 0; i < l->n; i++)
        if (!strcmp(l->s[i], s))
            return 1;
    return 0;
}

static void
names_free(NameList *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->s[i]);
    free(l->s);
}

enum { NAME_MAX_LEN = 256 };

char *
urdf_floating(const char *text, size_t len, size_t *outlen, char *err, size_t errlen)
{
    /* <robot>'s links and joints (depth 1), the joints' <child link=...>
     * (depth 2), and where </robot> is */
    NameList links = {0}, joints = {0}, children = {0};
    const char *end = NULL;
    int in_joint = 0;
    char name[NAME_MAX_LEN];
    for (Walk w = {0}; walk(&w, text);) {
        const char *c = w.lt;
        if (c[1] == '/') {
            if (w.depth == 0 && tag_is(c + 1, "robot"))
                end = c;
            in_joint &= w.depth > 1;
            continue;
        }
        if (w.depth == 1 && tag_is(c, "link") && tag_attr(c, w.gt, "name", name, sizeof name))
            add(&links, name);
        if (w.depth == 1 && tag_is(c, "joint")) {
            if (tag_attr(c, w.gt, "name", name, sizeof name))
                add(&joints, name);
            in_joint = !w.empty;
        }
        if (w.depth == 2 && in_joint && tag_is(c, "child") &&
            tag_attr(c, w.gt, "link", name, sizeof name))
            add(&children, name);
    }
    /* each root, joined to the world; the joint named after its link, or
     * LINK_floating (LINK_floating_2, ...) where a joint has that name */
    char *ins = NULL;
    size_t insn = 0;
    FILE *f = open_memstream(&ins, &insn);
    int roots = 0, world = 0;
    fputs("<link name=\"world\"/>", f);
    for (int i = 0; i < links.n; i++) {
        const char *l = links.s[i];
        if (has(&children, l))
            continue;
        world |= !strcmp(l, "world");
        snprintf(name, sizeof name, "%s", l);
        for (int k = 1; has(&joints, name); k++)
            snprintf(name, sizeof name, k == 1 ? "%s_floating" : "%s_floating_%d", l, k);
        add(&joints, name);
        fprintf(f, "<joint name=\"%s\" type=\"floating\"><parent link=\"world\"/>"
                "<child link=\"%s\"/></joint>", name, l);
        roots++;
    }
    fclose(f);
    char *out = NULL;
    if (!end)
        snprintf(err, errlen, "--floating: no </robot> closes the URDF");
    else if (world)
        snprintf(err, errlen, "--floating: the URDF's root link is 'world', which MuJoCo takes for "
                 "the world itself, holding the robot by its joints; remove the link 'world' and "
                 "its joints, and --floating frees the links they held");
    else if (!roots)
        snprintf(err, errlen, "--floating: the URDF has no root link (a <link> that no joint "
                 "has for its child) to free");
    else { /* before </robot> */
        size_t head = (size_t)(end - text);
        out = xmalloc(len + insn + 1);
        memcpy(out, text, head);
        memcpy(out + head, ins, insn);
        memcpy(out + head + insn, end, len - head + 1);
        *outlen = len + insn;
    }
    free(ins);
    names_free(&links);
    names_free(&joints);
    names_free(&children);
    return out;
}

int
urdf_mimics(const char *text, void (*each)(void *ctx, const char *joint), void *ctx)
{
    char name[NAME_MAX_LEN] = "";
    int n = 0, in_joint = 0;
    for (Walk w = {0}; walk(&w, text);) {
        if (w.lt[1] == '/') {
            in_joint &= w.depth > 1;
            continue;
        }
        if (w.depth == 1 && tag_is(w.lt, "joint")) {
            in_joint = !w.empty;
            if (!tag_attr(w.lt, w.gt, "name", name, sizeof name))
                name[0] = '\0';
        }
        if (w.depth == 2 && in_joint && tag_is(w.lt, "mimic"))
            each(ctx, name), n++;
    }
    return n;
}

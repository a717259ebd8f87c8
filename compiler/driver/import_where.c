/*
 * import_where: where in an MJCF or URDF file an import error is
 * (import_where.h), from MuJoCo's message or the name of the element the
 * importer refuses.
 *
 * MuJoCo (2.2.2, and the versions after it) writes a position in these
 * forms, which are all read:
 *   - its XML reader's errors (mjXError): "Element 'joint', line 9";
 *   - its compiler's errors (mjCError): "Object name = hip, id = 1, line =
 *     9, column = -1" (2.2.2; the column is always -1 there, and an object
 *     of a URDF has no line: "Object name = link1, id = 2"), and "Element
 *     name 'hip', id 1, line 9" or "..., line = 9" (3.x);
 *   - tinyxml2's parse errors: "Line number=4" (0 where there is no line,
 *     as for a file it cannot open).
 * The column, where MuJoCo gives none, is that of the element's `<` on the
 * line (an element is on the line its `<` is on), else the line's first
 * character that is not a blank.
 *
 * This reads text, never the XML: no element is parsed, the names and tags
 * are found as the file spells them.
 */
#include "import_where.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

/* Is c a character of an XML name (a tag's or an attribute's)? */
static int
namechar(int c)
{
    return isalnum(c) || c == '_' || c == '-' || c == ':' || c == '.';
}

/* The number after "line" at p (its blanks and an '=' skipped), or 0. */
static int
number_after(const char *p, const char **end)
{
    while (*p == ' ' || *p == '=')
        p++;
    if (!isdigit((unsigned char)*p))
        return 0;
    char *e;
    long n = strtol(p, &e, 10);
    *end = e;
    return n > 0 && n < 1000000000 ? (int)n : 0;
}

/* The text between start and the first of stop after it, into out. */
static void
copy_until(char *out, size_t len, const char *start, const char *stop)
{
    const char *e = strstr(start, stop);
    size_t n = e ? (size_t)(e - start) : strlen(start);
    snprintf(out, len, "%.*s", (int)(n < len ? n : len - 1), start);
}

void
import_where_parse(const char *msg, ImportWhere *at)
{
    const char *p, *e;
    /* the line: "line 9", "line = 9", "Line number=9"; the first that
     * names one (the word alone: not "spline") */
    for (p = msg; (p = strstr(p, "ine")) != NULL; p += 3) {
        if (p == msg || (p[-1] != 'l' && p[-1] != 'L') ||
            (p - 1 > msg && namechar((unsigned char)p[-2])))
            continue;
        const char *q = p + 3;
        if (!strncmp(q, " number", 7))
            q += 7;
        if (!(at->line = number_after(q, &e)))
            continue;
        while (*e == ' ' || *e == ',')
            e++;
        if (!strncmp(e, "column", 6)) { /* -1 (or none) stays 0: not given */
            const char *c = e + 6;
            int col = number_after(c, &c);
            at->col = col;
        }
        break;
    }
    /* the element: "Element 'joint'" (not "Element name 'hip'") */
    if ((p = strstr(msg, "Element '")))
        copy_until(at->elem, sizeof at->elem, p + 9, "'");
    /* the object's name */
    if ((p = strstr(msg, "Object name = ")))
        copy_until(at->name, sizeof at->name, p + 14, ", id");
    else if ((p = strstr(msg, "Element name '")))
        copy_until(at->name, sizeof at->name, p + 14, "'");
}

/* Is the tag of the element that starts at lt ('<') one of the list's
 * (space-separated; NULL: any)? */
static int
tag_in(const char *lt, const char *tags)
{
    if (!tags)
        return 1;
    size_t n = 0;
    while (namechar((unsigned char)lt[1 + n]))
        n++;
    for (const char *t = tags; *t;) {
        size_t k = strcspn(t, " ");
        if (k == n && !strncmp(t, lt + 1, n))
            return 1;
        t += k + (t[k] == ' ');
    }
    return 0;
}

/* Is p inside the section's element: is the last `<section` before p
 * after the last `</section`?  (section NULL: yes) */
static int
inside(const char *text, const char *p, const char *section)
{
    if (!section)
        return 1;
    size_t n = strlen(section);
    const char *open = NULL, *close = NULL;
    for (const char *c = text; c < p && (c = strchr(c, '<')) && c < p; c++) {
        if (!strncmp(c + 1, section, n) && !namechar((unsigned char)c[1 + n]))
            open = c;
        else if (c[1] == '/' && !strncmp(c + 2, section, n) &&
                 !namechar((unsigned char)c[2 + n]))
            close = c;
    }
    return open && (!close || close < open);
}

/* The `<` of the element whose attribute is at p, or NULL. */
static const char *
element_of(const char *text, const char *p)
{
    while (p > text && *p != '<' && *p != '>')
        p--;
    return *p == '<' ? p : NULL;
}

/* The value of `name="NAME"` (or 'NAME') on an element whose tag is one of
 * tags, inside section; failing that, of one whose tag is; failing that,
 * the first anywhere; NULL where there is none.  Within [from, to). */
static const char *
find_name(const char *text, const char *from, const char *to, const char *name,
          const char *tags, const char *section)
{
    const char *best[3] = {NULL, NULL, NULL};
    for (int q = 0; q < 2; q++) {
        char want[200];
        snprintf(want, sizeof want, q ? "name='%s'" : "name=\"%s\"", name);
        for (const char *h = from; (h = strstr(h, want)) && h < to; h++) {
            if (h > text && namechar((unsigned char)h[-1])) /* "classname=" */
                continue;
            const char *lt = element_of(text, h);
            int rank = !lt || !tag_in(lt, tags) ? 2 : inside(text, h, section) ? 0 : 1;
            if (!best[rank] || h < best[rank])
                best[rank] = h;
        }
    }
    for (int r = 0; r < 3; r++)
        if (best[r])
            return best[r] + 6; /* the value's first character */
    return NULL;
}

/* line:col of p in text, into loc. */
static void
place(SrcLoc *loc, const char *text, const char *p)
{
    loc->line = 1, loc->col = 1;
    for (const char *c = text; c < p; c++)
        if (*c == '\n')
            loc->line++, loc->col = 1;
        else
            loc->col++;
}

/* Where on its line (text from line to eol) the error MuJoCo placed there
 * is: the column it gave; the `<` of the element it named (NULL where the
 * line does not have it: the line is not this file's, as one of an
 * included file's); of the element whose name it gave; the line's first
 * `<`; its first character that is not a blank. */
static const char *
on_line(const char *line, const char *eol, const ImportWhere *at)
{
    if (at->col > 0)
        return at->col - 1 <= eol - line ? line + at->col - 1 : eol;
    if (at->elem[0]) {
        size_t n = strlen(at->elem);
        for (const char *c = line; c < eol && (c = memchr(c, '<', (size_t)(eol - c))); c++)
            if (!strncmp(c + 1, at->elem, n) && !namechar((unsigned char)c[1 + n]))
                return c;
        return NULL;
    }
    if (at->name[0]) {
        const char *v = find_name(line, line, eol, at->name, NULL, NULL);
        const char *lt = v ? element_of(line, v - 6) : NULL;
        if (lt)
            return lt;
    }
    const char *lt = memchr(line, '<', (size_t)(eol - line));
    if (lt)
        return lt;
    while (line < eol && (*line == ' ' || *line == '\t'))
        line++;
    return line;
}

static char *
read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, n = 0, k;
    char *buf = malloc(cap);
    while (buf && (k = fread(buf + n, 1, cap - n - 1, f)) > 0)
        if ((n += k) == cap - 1) {
            char *b = realloc(buf, cap *= 2);
            if (!b)
                free(buf);
            buf = b;
        }
    fclose(f);
    if (buf)
        buf[n] = '\0', *len = n;
    return buf;
}

SrcLoc
import_where_find(const char *path, const ImportWhere *at)
{
    SrcLoc loc = {path, 0, 0};
    size_t len;
    char *text = (at->line > 0 || at->name[0]) ? read_all(path, &len) : NULL;
    if (!text)
        return loc;
    diag_add_source(path, text, len); /* (kept: the error that follows quotes it) */
    if (at->line > 0) {
        const char *line = text;
        for (int l = 1; l < at->line && line; l++)
            if ((line = strchr(line, '\n')))
                line++;
        if (!line || !*line)
            return loc; /* past the file's end: not this file's line */
        const char *eol = line + strcspn(line, "\n");
        const char *c = on_line(line, eol, at);
        if (c)
            place(&loc, text, c);
        return loc;
    }
    const char *v = find_name(text, text, text + len, at->name, at->tags, at->section);
    if (v)
        place(&loc, text, v);
    return loc;
}

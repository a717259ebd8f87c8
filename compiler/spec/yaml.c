/*
 * yaml: the spec's YAML and its source map (yaml.h).
 *
 * libyaml's marks give a node's line and column; a byte of a scalar's
 * value is found by walking the scalar's source beside it (quotes,
 * escapes and folded lines are in the one, not the other), so that an
 * error inside an expression points at its column in the file.
 */
#include "yaml.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- locations ---- */

SrcLoc
spec_loc(const Loader *L, const yaml_node_t *n)
{
    return (SrcLoc){L->path, (int)n->start_mark.line + 1, (int)n->start_mark.column + 1};
}

static int is_cont(unsigned char c) { return (c & 0xC0) == 0x80; }

/* Byte offset of (line, column), both 0-based, column in characters. */
static size_t
byte_at(const Loader *L, size_t line, size_t col)
{
    if (line >= L->nlines)
        return L->len;
    size_t i = L->line_start[line];
    while (i < L->len && col > 0) {
        i++;
        while (i < L->len && is_cont((unsigned char)L->text[i]))
            i++;
        col--;
    }
    return i;
}

static size_t
escape_len(const char *s, size_t i, size_t end)
{
    if (i + 1 >= end)
        return 1;
    switch (s[i + 1]) {
    case 'x': return 4;
    case 'u': return 6;
    case 'U': return 10;
    case '\n': return 2;
    }
    return 2;
}

/* A node's mark is at its anchor (&a) or tag (!t) when it has one: the
 * byte where its text starts, past them and the blanks after them. */
static size_t
skip_properties(const char *s, size_t i, size_t end, size_t *line, size_t *col)
{
    while (i < end && (s[i] == '&' || s[i] == '!')) {
        for (; i < end && s[i] != ' ' && s[i] != '\t' && s[i] != '\n' && s[i] != '\r'; i++)
            *col += !is_cont((unsigned char)s[i]);
        while (i < end && (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')) {
            if (s[i] == '\n')
                (*line)++, *col = 0;
            else if (s[i] != '\r')
                (*col)++;
            i++;
        }
    }
    return i;
}

/* Walk the source of a scalar and its value side by side up to byte `off`
 * of the value: line folding, quotes and escapes are skipped in the
 * source. */
SrcLoc
spec_scalar_where(const ParseSrc *src, size_t off)
{
    /* The parser asks for every name's place as it reads, left to right:
     * going on from the last answer (the Scalar is the loader's, not
     * const; only the parser's view of it is) keeps reading an
     * expression linear in its length, where starting over each time
     * was quadratic (a 10 000-term sum: 0.23 s, 6 s instrumented). */
    Scalar *sc = (Scalar *)src;
    const Loader *L = sc->L;
    const yaml_node_t *n = sc->node;
    size_t line = n->start_mark.line, col = n->start_mark.column;
    size_t i = byte_at(L, line, col), end = L->len, k = 0;
    const char *s = L->text, *v = src->text;
    yaml_scalar_style_t style = n->data.scalar.style;
    if (sc->k > 0 && sc->k <= off) {
        k = sc->k, i = sc->i, line = sc->line, col = sc->col;
    } else {
        i = skip_properties(s, i, end, &line, &col);
        if (style == YAML_SINGLE_QUOTED_SCALAR_STYLE ||
            style == YAML_DOUBLE_QUOTED_SCALAR_STYLE) {
            i++, col++;
        } else if (style == YAML_LITERAL_SCALAR_STYLE || style == YAML_FOLDED_SCALAR_STYLE) {
            while (i < end && s[i] != '\n')
                i++;
            i++, line++, col = 0;
        }
    }
    while (k < off && k < src->len && i < end) {
        unsigned char c = (unsigned char)s[i], vc = (unsigned char)v[k];
        size_t step = 1, vstep = 1;
        if (style == YAML_DOUBLE_QUOTED_SCALAR_STYLE && c == '\\') {
            step = escape_len(s, i, end);
            while (k + vstep < src->len && is_cont((unsigned char)v[k + vstep]))
                vstep++;
        } else if (style == YAML_SINGLE_QUOTED_SCALAR_STYLE && c == '\'' && vc == '\'') {
            step = 2;
        } else if (c != vc) {
            if (c != ' ' && c != '\t' && c != '\n' && c != '\r')
                break; /* lost track: report what we have */
            vstep = 0;   /* folded whitespace: source only */
        }
        for (size_t j = 0; j < step && i < end; j++, i++) {
            if (s[i] == '\n')
                line++, col = 0;
            else if (!is_cont((unsigned char)s[i]))
                col++;
        }
        k += vstep;
    }
    sc->k = k, sc->i = i, sc->line = line, sc->col = col;
    return (SrcLoc){L->path, (int)line + 1, (int)col + 1};
}

/* ---- YAML node access ---- */

yaml_node_t *
spec_node(Loader *L, int id)
{
    yaml_node_t *n = yaml_document_get_node(&L->doc, id);
    if (!n)
        diag_unreachable();
    return n;
}

static const char *
kind_name(const yaml_node_t *n)
{
    switch (n->type) {
    case YAML_SCALAR_NODE: return "a scalar";
    case YAML_SEQUENCE_NODE: return "a sequence";
    case YAML_MAPPING_NODE: return "a mapping";
    default: return "nothing";
    }
}

int
spec_is_null(const yaml_node_t *n)
{
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
        return 0;
    const char *v = (const char *)n->data.scalar.value;
    return !*v || !strcmp(v, "~") || !strcmp(v, "null") || !strcmp(v, "Null") ||
           !strcmp(v, "NULL");
}

void
spec_expect(Loader *L, const yaml_node_t *n, yaml_node_type_t type, const char *what)
{
    if (n->type == type && !(type == YAML_SCALAR_NODE && spec_is_null(n)))
        return;
    const char *want = type == YAML_SCALAR_NODE ? "a value"
                     : type == YAML_SEQUENCE_NODE ? "a sequence [...]" : "a mapping";
    diag_error(spec_loc(L, n), "%s must be %s, not %s", what, want,
               spec_is_null(n) ? "empty" : kind_name(n));
}

const char *
spec_scalar(Loader *L, const yaml_node_t *n, const char *what)
{
    spec_expect(L, n, YAML_SCALAR_NODE, what);
    if (strlen((const char *)n->data.scalar.value) != n->data.scalar.length)
        diag_error(spec_loc(L, n), "%s contains a NUL character", what);
    return (const char *)n->data.scalar.value;
}

const char *
spec_key(Loader *L, const yaml_node_pair_t *p)
{
    return spec_scalar(L, spec_node(L, p->key), "a key");
}

typedef struct KeyRef {
    const char *key;
    int index;
} KeyRef;

static int
cmp_key(const void *a, const void *b)
{
    const KeyRef *x = a, *y = b;
    int c = strcmp(x->key, y->key);
    return c ? c : (x->index > y->index) - (x->index < y->index);
}

/* Keys are scalars, each at most once (sorted: no quadratic scan); a
 * repeated one is reported where it repeats, naming the first. */
void
spec_unique_keys(Loader *L, yaml_node_t *map, const char *what)
{
    int n = NPAIRS(map);
    if (n < 2)
        return;
    KeyRef *k = arena_new_array(L->A, KeyRef, n);
    for (int i = 0; i < n; i++)
        k[i] = (KeyRef){spec_key(L, &PAIRS(map)[i]), i};
    qsort(k, (size_t)n, sizeof *k, cmp_key);
    for (int i = 1; i < n; i++) {
        if (strcmp(k[i].key, k[i - 1].key))
            continue;
        SrcLoc first = spec_loc(L, spec_node(L, PAIRS(map)[k[i - 1].index].key));
        diag_error(spec_loc(L, spec_node(L, PAIRS(map)[k[i].index].key)),
                   "duplicate key '%s' in %s (first at line %d, column %d)", k[i].key, what,
                   first.line, first.col);
    }
}

yaml_node_t *
spec_map(Loader *L, yaml_node_t *n, const char *what)
{
    spec_expect(L, n, YAML_MAPPING_NODE, what);
    spec_unique_keys(L, n, what);
    return n;
}

/* Where each key of the format belongs, for a key found elsewhere. */
static const struct {
    const char *key, *where;
} key_homes[] = {
    {"mass", "in a particle or a body"}, {"position", "in a particle"},
    {"center", "in a body"}, {"inertia", "in a body"}, {"rotation", "in a body"},
    {"omega", "in a body"}, {"angle", "in a body"}, {"gravity", "in an effect"},
    {"force", "in an effect"}, {"torque", "in an effect"}, {"work", "in an effect"},
    {"on", "in an effect"}, {"expr", "in a constraint"}, {"dependent", "in a constraint"},
    {"t_end", "in a scene"}, {"dt", "in a scene"}, {"method", "in a scene"},
    {"rtol", "in a scene"}, {"atol", "in a scene"}, {"fixed_step", "in a scene"},
    {"fix", "in a scene"}, {"outputs", "in a scene"}, {"events", "in a scene"},
    {"assemble", "in a scene"}, {"hold", "in a scene's `assemble:`"},
    {"quaternion", "in a body's rotation or a frame's turns"},
    {"when", "in an event"}, {"direction", "in an event"}, {"action", "in an event"},
    {"coordinates", "at the top level"}, {"parameters", "at the top level"},
    {"particles", "at the top level"}, {"bodies", "at the top level"},
    {"ground", "at the top level"},
    {"define", "at the top level"}, {"inputs", "at the top level"},
    {"kinetic", "at the top level"}, {"initial", "at the top level"},
    {"constraints", "at the top level"}, {"scene", "at the top level"},
    {"scenes", "at the top level"},
};

static const char *
key_home(const char *key)
{
    for (size_t i = 0; i < sizeof key_homes / sizeof key_homes[0]; i++)
        if (!strcmp(key_homes[i].key, key))
            return key_homes[i].where;
    return NULL;
}

/* Key i of map must be one of `allowed` (NULL-terminated).  An unknown
 * key gets the nearest allowed ones, or where it belongs if it is a key of
 * another part of the spec, or the list of allowed keys. */
void
spec_check_key(Loader *L, yaml_node_t *map, int i, const char *const *allowed, const char *where)
{
    int nallowed = 0;
    while (allowed[nallowed])
        nallowed++;
    const char *k = spec_key(L, &PAIRS(map)[i]);
    for (int j = 0; j < nallowed; j++)
        if (!strcmp(k, allowed[j]))
            return;
    const char *near = diag_nearest(k, allowed, nallowed);
    SrcLoc at = spec_loc(L, spec_node(L, PAIRS(map)[i].key));
    if (near)
        diag_error(at, "unknown key '%s' in %s; did you mean %s?", k, where, near);
    const char *home = key_home(k);
    if (home)
        diag_error(at, "'%s' is not a key of %s: it belongs %s", k, where, home);
    char list[512] = "";
    for (int j = 0; j < nallowed; j++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", j ? ", " : "",
                 allowed[j]);
    diag_error(at, "unknown key '%s' in %s; expected one of: %s", k, where, list);
}

/* Only `allowed` keys may appear in map: the first that is not is the
 * error. */
void
spec_check_keys(Loader *L, yaml_node_t *map, const char *const *allowed, const char *where)
{
    for (int i = 0; i < NPAIRS(map); i++)
        spec_check_key(L, map, i, allowed, where);
}

yaml_node_t *
spec_lookup(Loader *L, yaml_node_t *map, const char *key)
{
    for (int i = 0; i < NPAIRS(map); i++)
        if (!strcmp(spec_key(L, &PAIRS(map)[i]), key))
            return spec_node(L, PAIRS(map)[i].value);
    return NULL;
}

void
spec_scalar_src(Loader *L, Scalar *sc, const yaml_node_t *n, const char *what)
{
    const char *text = spec_scalar(L, n, what);
    sc->src = (ParseSrc){text, n->data.scalar.length, spec_scalar_where, NULL};
    sc->L = L;
    sc->node = n;
    sc->k = sc->i = sc->line = sc->col = 0;
}

/* ---- going on after an error ---- */

/* Past this many errors a spec is not worth reading further: later
 * messages grow likelier to follow from earlier ones (clang's default
 * -ferror-limit is the same). */
enum { SPEC_MAX_ERRORS = 20 };

/* f(L, map, i), one entry of a section, so that an error in it is
 * reported and loading goes on with the next entry: a spec's independent
 * mistakes are found in one run.  0 if it failed.  What depends on a
 * failed entry is marked by the caller, and its uses are abandoned
 * without a second message (diag_abandon). */
/* After an entry's error: stop reading past SPEC_MAX_ERRORS.  (Its own
 * function: no temporary of it lives in spec_checked's frame across longjmp.) */
static void
count_error(Loader *L)
{
    if (diag_error_count() >= SPEC_MAX_ERRORS && !L->stop) {
        diag_note((SrcLoc){L->path, 0, 0}, "stopping after %d errors", SPEC_MAX_ERRORS);
        L->stop = 1;
    }
    if (L->stop)
        diag_abandon();
}

int
spec_checked(Loader *L, EntryFn *f, yaml_node_t *map, int i)
{
    jmp_buf jb;
    jmp_buf *outer = diag_set_jump(&jb);
    if (setjmp(jb)) {
        diag_set_jump(outer);
        count_error(L);
        return 0;
    }
    f(L, map, i);
    diag_set_jump(outer);
    return 1;
}

/* Stop here if anything so far failed: what follows depends on it. */
void
spec_stop_if_failed(void)
{
    if (diag_error_count())
        diag_abandon();
}

yaml_node_t *
spec_section(Loader *L, yaml_node_t *root, const char *key, int map)
{
    yaml_node_t *n = spec_lookup(L, root, key);
    if (!n || spec_is_null(n))
        return NULL;
    return map ? spec_map(L, n, key) : n;
}

/* Where `key` of map is written. */
SrcLoc
spec_key_loc(Loader *L, yaml_node_t *map, const char *key)
{
    for (int i = 0; i < NPAIRS(map); i++)
        if (!strcmp(spec_key(L, &PAIRS(map)[i]), key))
            return spec_loc(L, spec_node(L, PAIRS(map)[i].key));
    return spec_loc(L, map);
}

static void
index_lines(Loader *L)
{
    size_t n = 1;
    for (size_t i = 0; i < L->len; i++)
        n += L->text[i] == '\n';
    L->line_start = arena_new_array(L->A, size_t, n);
    L->nlines = 0;
    L->line_start[L->nlines++] = 0;
    for (size_t i = 0; i < L->len; i++)
        if (L->text[i] == '\n')
            L->line_start[L->nlines++] = i + 1;
}

/* Line and column of a byte offset (libyaml's reader errors give one). */
static SrcLoc
loc_of_byte(const Loader *L, size_t off)
{
    size_t line = 0;
    while (line + 1 < L->nlines && L->line_start[line + 1] <= off)
        line++;
    int col = 1;
    for (size_t i = L->line_start[line]; i < off && i < L->len; i++)
        col += !is_cont((unsigned char)L->text[i]);
    return (SrcLoc){L->path, (int)line + 1, col};
}

/* Where a reader error is: libyaml gives the byte after a truncated
 * UTF-8 sequence; the sequence starts at its lead byte. */
static size_t
reader_offset(const Loader *L, const yaml_parser_t *yp)
{
    size_t off = yp->problem_offset;
    if (!yp->problem || strcmp(yp->problem, "invalid trailing UTF-8 octet") || off > L->len)
        return off;
    while (off > 0 && is_cont((unsigned char)L->text[off - 1]))
        off--;
    return off > 0 ? off - 1 : off;
}

/* libyaml's reader errors, with the byte they are about: a spec is UTF-8
 * text without control characters. */
static void
reader_problem(const Loader *L, const yaml_parser_t *yp, char *msg, size_t len)
{
    const char *p = yp->problem ? yp->problem : "";
    int v = yp->problem_value;
    size_t off = reader_offset(L, yp);
    if (!strcmp(p, "invalid trailing UTF-8 octet") && off < L->len)
        snprintf(msg, len, "incomplete UTF-8 sequence (byte 0x%02x without the bytes that "
                 "follow it): a spec must be UTF-8 text", (unsigned char)L->text[off]);
    else if (strstr(p, "UTF-8") && v >= 0)
        snprintf(msg, len, "%s (byte 0x%02x): a spec must be UTF-8 text", p, v & 0xff);
    else if (strstr(p, "UTF-8") || strstr(p, "Unicode"))
        snprintf(msg, len, "%s: a spec must be UTF-8 text", p);
    else if (strstr(p, "control characters") && v >= 0)
        snprintf(msg, len, "control character (U+%04X) in the text: a spec cannot contain "
                 "control characters other than tab and line breaks", (unsigned)v);
    else
        snprintf(msg, len, "%s", p);
}

/* libyaml's own errors, with its marks; the parser is deleted first. */
static _Noreturn void
yaml_failure(Loader *L, yaml_parser_t *yp)
{
    SrcLoc at = {L->path, (int)yp->problem_mark.line + 1, (int)yp->problem_mark.column + 1};
    if (yp->error == YAML_READER_ERROR)
        at = loc_of_byte(L, reader_offset(L, yp));
    char msg[512];
    const char *problem = yp->problem ? yp->problem : "cannot parse the YAML";
    if (yp->context)
        snprintf(msg, sizeof msg, "%s %s that started at line %d, column %d", problem,
                 yp->context, (int)yp->context_mark.line + 1, (int)yp->context_mark.column + 1);
    else
        snprintf(msg, sizeof msg, "%s", problem);
    size_t b = byte_at(L, yp->problem_mark.line, yp->problem_mark.column);
    if (yp->error != YAML_READER_ERROR && b < L->len && L->text[b] == '\t')
        snprintf(msg, sizeof msg, "a tab character: YAML indents with spaces only");
    else if (yp->error == YAML_READER_ERROR)
        reader_problem(L, yp, msg, sizeof msg);
    else if (yp->error != YAML_READER_ERROR && b < L->len &&
             (L->text[b] == '[' || L->text[b] == ']') && yp->context &&
             strstr(yp->context, "flow"))
        snprintf(msg + strlen(msg), sizeof msg - strlen(msg),
                 " (inside { } or [ ], quote an expression with brackets: \"lambda[c]\")");
    else if (yp->problem && !strcmp(yp->problem, "did not find expected key") && yp->context &&
             strstr(yp->context, "block mapping"))
        snprintf(msg + strlen(msg), sizeof msg - strlen(msg),
                 " (is this line indented like the keys of that mapping?)");
    yaml_parser_delete(yp);
    diag_error(at, "%s", msg);
}

/* libyaml's scanner slows down quadratically with flow nesting, and a
 * deep document would make every later walk deep: refuse one nested
 * deeper than SPEC_MAX_DEPTH, reading events (which stops at the first
 * offending level instead of scanning the whole file), before loading. */
enum { SPEC_MAX_DEPTH = 64 };

static void
check_depth(Loader *L)
{
    yaml_parser_t yp;
    yaml_event_t ev;
    if (!yaml_parser_initialize(&yp))
        diag_error((SrcLoc){L->path, 0, 0}, "out of memory");
    yaml_parser_set_input_string(&yp, (const unsigned char *)L->text, L->len);
    for (int depth = 0, done = 0; !done;) {
        if (!yaml_parser_parse(&yp, &ev))
            yaml_failure(L, &yp);
        int type = ev.type;
        SrcLoc at = {L->path, (int)ev.start_mark.line + 1, (int)ev.start_mark.column + 1};
        yaml_event_delete(&ev);
        if (type == YAML_SEQUENCE_START_EVENT || type == YAML_MAPPING_START_EVENT)
            depth++;
        else if (type == YAML_SEQUENCE_END_EVENT || type == YAML_MAPPING_END_EVENT)
            depth--;
        done = type == YAML_STREAM_END_EVENT;
        if (depth > SPEC_MAX_DEPTH) {
            yaml_parser_delete(&yp);
            diag_error(at, "the YAML is nested more than %d levels deep", SPEC_MAX_DEPTH);
        }
    }
    yaml_parser_delete(&yp);
}

static void
load_document(Loader *L)
{
    yaml_parser_t yp;
    check_depth(L);
    if (!yaml_parser_initialize(&yp))
        diag_error((SrcLoc){L->path, 0, 0}, "out of memory");
    yaml_parser_set_input_string(&yp, (const unsigned char *)L->text, L->len);
    if (!yaml_parser_load(&yp, &L->doc))
        yaml_failure(L, &yp);
    L->have_doc = 1;
    /* a second document would be ignored silently: refuse it */
    yaml_document_t extra;
    if (!yaml_parser_load(&yp, &extra))
        yaml_failure(L, &yp);
    int more = yaml_document_get_root_node(&extra) != NULL;
    SrcLoc at = {L->path, (int)extra.start_mark.line + 1, (int)extra.start_mark.column + 1};
    yaml_document_delete(&extra);
    yaml_parser_delete(&yp);
    if (more)
        diag_error(at, "a spec is one YAML document; this is a second one");
}

/* ---- expressions that YAML split ---- */

/* Inside { } and [ ], YAML reads a comma as a separator, also in
 * dot(a, b): the expression arrives in pieces, and the errors that follow
 * (an unknown key 'b)', a vector of 6 components) describe only the
 * symptom.  A piece that opens a parenthesis which a later piece closes
 * can only be such an expression: it is reported first, quoted as it
 * should be written, and nothing is read from a document whose structure
 * is not the one meant. */

/* The parentheses a plain scalar opens and does not close, or 0 for any
 * other node (a quoted scalar's are the parser's to judge). */
static int
paren_balance(const yaml_node_t *n)
{
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
        return 0;
    int b = 0;
    for (size_t i = 0; i < n->data.scalar.length; i++)
        b += (n->data.scalar.value[i] == '(') - (n->data.scalar.value[i] == ')');
    return b;
}

/* A flow collection's pieces in the order written: a sequence's items, a
 * mapping's keys and values. */
static int
flow_pieces(const yaml_node_t *c)
{
    return c->type == YAML_SEQUENCE_NODE ? NITEMS(c) : 2 * NPAIRS(c);
}

static yaml_node_t *
flow_piece(Loader *L, const yaml_node_t *c, int k)
{
    if (c->type == YAML_SEQUENCE_NODE)
        return spec_node(L, ITEMS(c)[k]);
    const yaml_node_pair_t *p = &PAIRS(c)[k / 2];
    return spec_node(L, k % 2 ? p->value : p->key);
}

/* The piece that closes what piece i of c opens, or -1; *last, the last
 * piece looked at (a later search starts after it: one pass over c). */
static int
split_end(Loader *L, const yaml_node_t *c, int i, int *last)
{
    int b = paren_balance(flow_piece(L, c, i));
    *last = i;
    if (b <= 0)
        return -1;
    for (int j = i + 1; j < flow_pieces(c); j++) {
        yaml_node_t *n = flow_piece(L, c, j);
        *last = j;
        if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
            return -1;
        if ((b += paren_balance(n)) <= 0)
            return b == 0 ? j : -1;
    }
    return -1;
}

enum { SPLIT_SHOWN = 240 }; /* a longer expression is shown cut short */

static int is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

/* Pieces i .. split_end of flow collection c are one expression: an error
 * at its start, with its source text quoted (line breaks and comments
 * between the pieces dropped). */
static void
split_expression(Loader *L, yaml_node_t *c, int i)
{
    int last;
    const yaml_node_t *a = flow_piece(L, c, i), *z = flow_piece(L, c, split_end(L, c, i, &last));
    size_t from = byte_at(L, a->start_mark.line, a->start_mark.column);
    size_t to = byte_at(L, z->end_mark.line, z->end_mark.column);
    char q[SPLIT_SHOWN + 8];
    size_t n = 0;
    for (size_t k = from; k < to && n < SPLIT_SHOWN; k++) {
        char ch = L->text[k];
        if (ch == '#' && k > from && is_blank(L->text[k - 1])) {
            while (k + 1 < to && L->text[k + 1] != '\n')
                k++;
            continue;
        }
        if (is_blank(ch)) { /* a run of blanks is one space */
            if (n > 0 && q[n - 1] != ' ')
                q[n++] = ' ';
            continue;
        }
        if (ch == '"' || ch == '\\')
            q[n++] = '\\';
        q[n++] = ch;
    }
    while (n > 0 && q[n - 1] == ' ')
        n--;
    q[n] = '\0';
    diag_error(spec_loc(L, a), "an expression with commas inside %s must be quoted: \"%s%s\" "
               "(YAML splits it at its commas)", c->type == YAML_SEQUENCE_NODE ? "[ ]" : "{ }",
               q, n >= SPLIT_SHOWN ? "..." : "");
}

/* Every split expression of the document, each node once (the node list,
 * not a walk: aliases share nodes). */
static void
check_splits(Loader *L)
{
    for (yaml_node_t *c = L->doc.nodes.start; c < L->doc.nodes.top; c++) {
        int flow = c->type == YAML_SEQUENCE_NODE
                       ? c->data.sequence.style == YAML_FLOW_SEQUENCE_STYLE
                       : c->type == YAML_MAPPING_NODE &&
                             c->data.mapping.style == YAML_FLOW_MAPPING_STYLE;
        for (int i = 0, last; flow && i < flow_pieces(c) && !L->stop; i = last + 1)
            if (split_end(L, c, i, &last) >= 0)
                spec_checked(L, split_expression, c, i);
    }
    spec_stop_if_failed();
}

/* The whole document, checked before anything is read from it. */
yaml_node_t *
spec_read(Loader *L)
{
    index_lines(L);
    load_document(L);
    yaml_node_t *root = yaml_document_get_root_node(&L->doc);
    if (!root)
        diag_error((SrcLoc){L->path, 1, 1}, "the spec is empty");
    check_splits(L);
    return root;
}

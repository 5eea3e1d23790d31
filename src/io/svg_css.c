/* svg_css.c - the SVG reader's style sheets (src/io): the text of <style>
 * elements parsed into rules (selector lists and declarations), and the
 * match of one selector against an element of the document tree.
 *
 * Selectors: type, '*', .class, #id, attribute tests ([a], [a=v], [a~=v],
 * [a|=v], [a^=v], [a$=v], [a*=v]), :first-child, compounds of them,
 * descendant (blank), child ('>'), next-sibling ('+') and later-sibling
 * ('~') combinators.  A selector with anything else (other pseudo-classes,
 * pseudo-elements, namespaces) never matches and the caller is told once.
 * At-rules are skipped whole. */
#include "io/svg.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *skip_blank(const char *s, const char *e)
{
    while (s < e && isspace((unsigned char)*s)) {
        s++;
    }
    return s;
}

static char *dup_range(const char *s, const char *e)
{
    while (s < e && isspace((unsigned char)*s)) {
        s++;
    }
    while (e > s && isspace((unsigned char)e[-1])) {
        e--;
    }
    char *d = malloc((size_t)(e - s) + 1);
    if (d) {
        memcpy(d, s, (size_t)(e - s));
        d[e - s] = 0;
    }
    return d;
}

static bool is_ident(char c)
{
    return isalnum((unsigned char)c) || c == '-' || c == '_' || (unsigned char)c >= 0x80;
}

/* An attribute test "[name op value]" at s (s < e, *s == '['), added to c;
 * the end of the test, or NULL when it is malformed. */
static const char *parse_attr_test(const char *s, const char *e, svg_css_compound *c)
{
    s = skip_blank(s + 1, e);
    const char *n = s;
    while (s < e && (is_ident(*s) || *s == ':')) {
        s++;
    }
    if (s == n) {
        return NULL;
    }
    svg_css_attr a = { .name = dup_range(n, s) };
    s = skip_blank(s, e);
    if (s < e && strchr("~|^$*", *s) && s + 1 < e && s[1] == '=') {
        a.op = *s;
        s += 2;
    } else if (s < e && *s == '=') {
        a.op = '=';
        s++;
    }
    if (a.op) {
        s = skip_blank(s, e);
        const char *v = s, *ve;
        if (s < e && (*s == '"' || *s == '\'')) {
            const char *q = memchr(s + 1, *s, (size_t)(e - s - 1));
            if (!q) {
                free(a.name);
                return NULL;
            }
            v = s + 1;
            ve = q;
            s = q + 1;
        } else {
            while (s < e && is_ident(*s)) {
                s++;
            }
            ve = s;
            if (ve == v) {
                free(a.name);
                return NULL;
            }
        }
        a.value = malloc((size_t)(ve - v) + 1);
        if (a.value) {
            memcpy(a.value, v, (size_t)(ve - v));
            a.value[ve - v] = 0;
        }
    }
    s = skip_blank(s, e);
    if (s == e || *s != ']' || !a.name || (a.op && !a.value)) {
        free(a.name);
        free(a.value);
        return NULL;
    }
    c->attrs[c->n_attrs++] = a;
    return s + 1;
}

/* One selector of a list, s..e; false when it uses what is not supported. */
static bool parse_selector(const char *s, const char *e, svg_css_selector *sel)
{
    memset(sel, 0, sizeof *sel);
    char comb = 0;
    s = skip_blank(s, e);
    while (s < e) {
        if (sel->n == SVG_CSS_MAX_COMPOUNDS) {
            return false;
        }
        svg_css_compound *c = &sel->parts[sel->n++];
        c->combinator = comb;
        bool any = false;
        if (*s == '*') {
            s++;
            any = true;
        } else if (is_ident(*s)) {
            const char *t = s;
            while (s < e && is_ident(*s)) {
                s++;
            }
            c->type = dup_range(t, s);
            any = true;
        }
        while (s < e && (*s == '.' || *s == '#' || *s == '[' || *s == ':')) {
            if (*s == '[') {
                if (c->n_attrs == SVG_CSS_MAX_ATTRS || !(s = parse_attr_test(s, e, c))) {
                    return false;
                }
                sel->specificity += 100;
                any = true;
                continue;
            }
            if (*s == ':') {
                if ((size_t)(e - s) < 12 || strncmp(s, ":first-child", 12) != 0 ||
                    (s + 12 < e && is_ident(s[12]))) {
                    return false;
                }
                s += 12;
                c->first_child = true;
                sel->specificity += 100;
                any = true;
                continue;
            }
            char kind = *s++;
            const char *t = s;
            while (s < e && is_ident(*s)) {
                s++;
            }
            if (s == t) {
                return false;
            }
            if (kind == '#') {
                free(c->id);
                c->id = dup_range(t, s);
                sel->specificity += 10000;
            } else {
                if (c->n_classes == SVG_CSS_MAX_CLASSES) {
                    return false;
                }
                c->classes[c->n_classes++] = dup_range(t, s);
                sel->specificity += 100;
            }
            any = true;
        }
        if (!any) {
            return false;
        }
        if (c->type) {
            sel->specificity += 1;
        }
        const char *t = skip_blank(s, e);
        if (t == e) {
            break;
        }
        if (*t == '>' || *t == '+' || *t == '~') {
            comb = *t;
            s = skip_blank(t + 1, e);
        } else if (t > s) {
            comb = ' ';
            s = t;
        } else {
            return false; /* '|', ',' inside and the like */
        }
    }
    return sel->n > 0;
}

static void free_selector(svg_css_selector *sel)
{
    for (int i = 0; i < sel->n; i++) {
        free(sel->parts[i].type);
        free(sel->parts[i].id);
        for (int k = 0; k < sel->parts[i].n_classes; k++) {
            free(sel->parts[i].classes[k]);
        }
        for (int k = 0; k < sel->parts[i].n_attrs; k++) {
            free(sel->parts[i].attrs[k].name);
            free(sel->parts[i].attrs[k].value);
        }
    }
}

/* The declarations "name: value [!important]; ..." of s..e. */
bool svg_css_parse_decls(const char *s, const char *e, svg_css_rule *rule)
{
    while (s < e) {
        const char *semi = memchr(s, ';', (size_t)(e - s));
        const char *end = semi ? semi : e;
        const char *colon = memchr(s, ':', (size_t)(end - s));
        if (colon) {
            svg_css_decl d = { 0 };
            const char *vend = end;
            /* "!important" at the value's end */
            const char *bang = memchr(colon, '!', (size_t)(vend - colon));
            if (bang) {
                const char *k = skip_blank(bang + 1, vend);
                if ((size_t)(vend - k) >= 9 && strncasecmp(k, "important", 9) == 0) {
                    d.important = true;
                    vend = bang;
                }
            }
            d.name = dup_range(s, colon);
            d.value = dup_range(colon + 1, vend);
            svg_css_decl *grown = realloc(rule->decls, (size_t)(rule->n_decls + 1) * sizeof *grown);
            if (!d.name || !d.value || !grown) {
                free(d.name);
                free(d.value);
                if (grown) {
                    rule->decls = grown;
                }
                return false;
            }
            rule->decls = grown;
            rule->decls[rule->n_decls++] = d;
        }
        s = semi ? semi + 1 : e;
    }
    return true;
}

/* Comments out, in place. */
static void strip_comments(char *t)
{
    char *w = t;
    for (char *r = t; *r;) {
        if (r[0] == '/' && r[1] == '*') {
            char *end = strstr(r + 2, "*/");
            r = end ? end + 2 : r + strlen(r);
            *w++ = ' ';
        } else {
            *w++ = *r++;
        }
    }
    *w = 0;
}

/* Where the block opened at s ('{') closes, nested blocks included. */
static const char *block_end(const char *s)
{
    int depth = 0;
    for (; *s; s++) {
        depth += *s == '{';
        depth -= *s == '}';
        if (depth == 0) {
            return s;
        }
    }
    return s;
}

static bool add_rule(svg_css_sheet *sheet, svg_css_rule *rule)
{
    svg_css_rule *grown = realloc(sheet->rules, (size_t)(sheet->n_rules + 1) * sizeof *grown);
    if (!grown) {
        return false;
    }
    sheet->rules = grown;
    sheet->rules[sheet->n_rules++] = *rule;
    return true;
}

bool svg_css_parse(svg_css_sheet *sheet, const char *text, int *unsupported)
{
    char *t = strdup(text);
    if (!t) {
        return false;
    }
    strip_comments(t);
    bool ok = true;
    const char *s = t;
    while (ok && *(s = skip_blank(s, s + strlen(s)))) {
        if (*s == '@') { /* an at-rule: up to ';' or its whole block */
            const char *semi = strchr(s, ';'), *open = strchr(s, '{');
            if (semi && (!open || semi < open)) {
                s = semi + 1;
            } else if (open) {
                const char *close = block_end(open);
                s = *close ? close + 1 : close;
            } else {
                break;
            }
            (*unsupported)++;
            continue;
        }
        if (strncmp(s, "<!--", 4) == 0 || strncmp(s, "-->", 3) == 0) {
            s += s[0] == '<' ? 4 : 3;
            continue;
        }
        const char *open = strchr(s, '{');
        if (!open) {
            break;
        }
        const char *close = strchr(open, '}');
        if (!close) {
            close = open + strlen(open);
        }
        svg_css_rule proto = { 0 };
        ok = svg_css_parse_decls(open + 1, close, &proto);
        /* One rule per selector of the list, sharing nothing. */
        const char *sel = s;
        while (ok && sel < open) {
            const char *comma = memchr(sel, ',', (size_t)(open - sel));
            const char *end = comma ? comma : open;
            svg_css_rule r = { .order = sheet->n_rules };
            if (parse_selector(sel, end, &r.selector)) {
                r.n_decls = proto.n_decls;
                r.decls = calloc((size_t)(proto.n_decls ? proto.n_decls : 1), sizeof *r.decls);
                ok = r.decls != NULL;
                for (int i = 0; ok && i < proto.n_decls; i++) {
                    r.decls[i] = (svg_css_decl){ strdup(proto.decls[i].name),
                                                 strdup(proto.decls[i].value),
                                                 proto.decls[i].important };
                    ok = r.decls[i].name && r.decls[i].value;
                }
                ok = ok && add_rule(sheet, &r);
                if (!ok) {
                    r.n_decls = r.decls ? r.n_decls : 0;
                    svg_css_free_rule(&r);
                }
            } else {
                free_selector(&r.selector);
                (*unsupported)++;
            }
            sel = end + 1;
        }
        svg_css_free_rule(&proto);
        s = *close ? close + 1 : close;
    }
    free(t);
    return ok;
}

void svg_css_free_rule(svg_css_rule *r)
{
    free_selector(&r->selector);
    for (int i = 0; i < r->n_decls; i++) {
        free(r->decls[i].name);
        free(r->decls[i].value);
    }
    free(r->decls);
}

void svg_css_free(svg_css_sheet *sheet)
{
    for (int i = 0; i < sheet->n_rules; i++) {
        svg_css_free_rule(&sheet->rules[i]);
    }
    free(sheet->rules);
    *sheet = (svg_css_sheet){ 0 };
}

/* Whether the class attribute's list holds the name. */
static bool has_class(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = list; s && *s;) {
        while (isspace((unsigned char)*s)) {
            s++;
        }
        const char *t = s;
        while (*t && !isspace((unsigned char)*t)) {
            t++;
        }
        if ((size_t)(t - s) == n && strncmp(s, name, n) == 0) {
            return true;
        }
        s = t;
    }
    return false;
}

/* Whether the value v passes the attribute test a. */
static bool attr_matches(const svg_css_attr *a, const char *v)
{
    size_t n = a->value ? strlen(a->value) : 0, m = strlen(v);
    switch (a->op) {
    case 0:
        return true;
    case '=':
        return strcmp(v, a->value) == 0;
    case '~':
        return n > 0 && !strpbrk(a->value, " \t\n\r\f") && has_class(v, a->value);
    case '|':
        return strncmp(v, a->value, n) == 0 && (v[n] == 0 || v[n] == '-');
    case '^':
        return n > 0 && strncmp(v, a->value, n) == 0;
    case '$':
        return n > 0 && m >= n && strcmp(v + m - n, a->value) == 0;
    default: /* '*' */
        return n > 0 && strstr(v, a->value) != NULL;
    }
}

static const char *node_attr(const svg_node *node, const char *name)
{
    for (int i = 0; node->atts[i]; i += 2) {
        if (strcmp(node->atts[i], name) == 0) {
            return node->atts[i + 1];
        }
    }
    return NULL;
}

/* Character data of a text is kept as nodes named "#text" among the
 * elements: selectors see elements only. */
static bool is_element(const svg_node *n)
{
    return n->name[0] != '#';
}

/* The element before node among its parent's children, or NULL. */
static const svg_node *previous_sibling(const svg_node *node, long *work)
{
    const svg_node *prev = NULL;
    for (const svg_node *c = node->parent ? node->parent->first : NULL; c && c != node;
         c = c->next) {
        ++*work;
        prev = is_element(c) ? c : prev;
    }
    return prev;
}

static bool compound_matches(const svg_css_compound *c, const svg_node *node)
{
    if (!is_element(node)) {
        return false;
    }
    if (c->first_child && node->parent) {
        const svg_node *first = node->parent->first;
        while (first && !is_element(first)) {
            first = first->next;
        }
        if (first != node) {
            return false;
        }
    }
    for (int i = 0; i < c->n_attrs; i++) {
        const char *v = node_attr(node, c->attrs[i].name);
        if (!v || !attr_matches(&c->attrs[i], v)) {
            return false;
        }
    }
    if (c->type && strcmp(c->type, node->name) != 0) {
        return false;
    }
    if (c->id && (!node->id || strcmp(c->id, node->id) != 0)) {
        return false;
    }
    for (int i = 0; i < c->n_classes; i++) {
        if (!has_class(node->cls, c->classes[i])) {
            return false;
        }
    }
    return true;
}

/* parts[0..k] against node and its ancestors, right to left. */
static bool match_from(const svg_css_selector *sel, int k, const svg_node *node, long *work)
{
    if (++*work > SVG_CSS_MAX_WORK) {
        return false; /* the caller reports the document as too costly */
    }
    if (!compound_matches(&sel->parts[k], node)) {
        return false;
    }
    if (k == 0) {
        return true;
    }
    char comb = sel->parts[k].combinator;
    if (comb == '+') {
        const svg_node *p = previous_sibling(node, work);
        return p && match_from(sel, k - 1, p, work);
    }
    if (comb == '~') {
        for (const svg_node *p = node->parent ? node->parent->first : NULL; p && p != node;
             p = p->next) {
            if (match_from(sel, k - 1, p, work)) {
                return true;
            }
        }
        return false;
    }
    for (const svg_node *p = node->parent; p; p = p->parent) {
        if (match_from(sel, k - 1, p, work)) {
            return true;
        }
        if (comb == '>') {
            return false;
        }
    }
    return false;
}

bool svg_css_matches(const svg_css_selector *sel, const svg_node *node, long *work)
{
    return sel->n > 0 && match_from(sel, sel->n - 1, node, work);
}

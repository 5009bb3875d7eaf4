/* reader.c - INI case files with units -> mc_scene (see case.h).
 *
 * Three passes: inih reads the text through our own line reader (which counts lines, enforces
 * inih's line limit and UTF-8, and knows which lines are continuations) and every [section]
 * header and key = value pair is collected; --set overrides replace or add entries; then the
 * entries are validated against the one key table (keys.c), written into a scene, and the scene
 * is checked (mc_scene_check_key: the table's bounds and the cross-key rules), the failing key
 * named with its line.
 */
#include <ctype.h>
#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "case/datafiles.h"
#include "case/keys.h"
#include "core/alloc.h"
#include "io/file.h"
#include "surface/surface.h"

#define MAX_FILE_BYTES (16L << 20) /* a case file is a few kB; refuse to slurp devices */

/* ---- collecting entries: the line reader and the inih handler -------------------------------- */

typedef struct {
    char *section;
    char *name; /* NULL: a [section] header line */
    char *value;
    size_t vlen, vcap;
    int line;        /* line of the key (or header) in the file; 0 for an override */
    int cont_line;   /* first continuation line of the value; 0 if none */
    const char *ovr; /* the --set text when the value comes from an override */
} entry;

typedef struct {
    const char *name;     /* for messages */
    const char *base_dir; /* for relative paths in the file */
    const char *text;
    mc_error *err;

    /* reader state */
    const char *p;
    int line;      /* lines handed to inih so far = the handler's line number */
    int cont;      /* the current line continues the previous key's value */
    int have_prev; /* mirror of inih's "previous key" (continuations need one) */
    int stop, nomem;
    int bad_line; /* first line the reader refused, with its reason */
    char bad[200];
    int unterminated; /* first "[section" line without ']' */
    int mesh_from_file; /* [mesh] nx, ny (dx, dy) come from the [roughness] file */

    entry *e;
    int n, cap;
    int slot[MC_MAX_KEYS]; /* entry index of each key, -1 if not given */
    mc_scene sc;
} ctx;

static char *dup_range(const char *s, size_t n)
{
    char *d = mc_malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

static int set_value(entry *e, const char *v)
{
    size_t n = strlen(v);
    char *d = dup_range(v, n);
    if (!d)
        return 0;
    mc_free(e->value);
    e->value = d;
    e->vlen = n;
    e->vcap = n + 1;
    return 1;
}

static int append_value(entry *e, const char *v)
{
    size_t n = strlen(v), need = e->vlen + 1 + n + 1;
    if (need > e->vcap) {
        size_t cap = 2 * e->vcap > need ? 2 * e->vcap : need;
        char *d = mc_malloc(cap);
        if (!d)
            return 0;
        memcpy(d, e->value, e->vlen);
        mc_free(e->value);
        e->value = d;
        e->vcap = cap;
    }
    e->value[e->vlen++] = '\n';
    memcpy(e->value + e->vlen, v, n + 1);
    e->vlen += n;
    return 1;
}

/* Append an entry (name NULL: a header); NULL when out of memory. */
static entry *add_entry(ctx *c, const char *section, size_t seclen, const char *name,
                        const char *value, int line)
{
    if (c->n == c->cap) {
        int cap = c->cap ? 2 * c->cap : 32;
        entry *e = mc_calloc((size_t)cap, sizeof *e);
        if (!e)
            return NULL;
        if (c->n)
            memcpy(e, c->e, sizeof *e * (size_t)c->n);
        mc_free(c->e);
        c->e = e;
        c->cap = cap;
    }
    entry *e = &c->e[c->n];
    memset(e, 0, sizeof *e);
    e->line = line;
    e->section = dup_range(section, seclen);
    if (!e->section)
        return NULL;
    if (name) {
        e->name = dup_range(name, strlen(name));
        if (!e->name || !set_value(e, value)) {
            mc_free(e->name);
            mc_free(e->section);
            return NULL;
        }
    }
    c->n++;
    return e;
}

static void free_entries(ctx *c)
{
    for (int i = 0; i < c->n; i++) {
        mc_free(c->e[i].section);
        mc_free(c->e[i].name);
        mc_free(c->e[i].value);
    }
    mc_free(c->e);
    c->e = NULL;
    c->n = c->cap = 0;
}

/* inih's find_chars_or_comment: first of chars, or an inline ';' after whitespace. */
static const char *chars_or_comment(const char *s, const char *chars)
{
    int was_space = 0;
    while (*s && !strchr(chars, *s) && !(was_space && *s == ';')) {
        was_space = isspace((unsigned char)*s);
        s++;
    }
    return s;
}

/* Classify the line the way inih will (multiline on, ';' and '#' comments): continuation,
 * section header, key line. Records headers, which inih does not report. */
static void classify(ctx *c, const char *line)
{
    const char *s = line;
    c->cont = 0;
    if (c->line == 1 && (unsigned char)s[0] == 0xEF && (unsigned char)s[1] == 0xBB &&
        (unsigned char)s[2] == 0xBF)
        s += 3;
    while (isspace((unsigned char)*s))
        s++;
    if (!*s || *s == ';' || *s == '#')
        return;
    if (c->have_prev && s > line) {
        c->cont = 1;
        return;
    }
    if (*s == '[') {
        const char *end = chars_or_comment(s + 1, "]");
        if (*end == ']') {
            c->have_prev = 0;
            if (!add_entry(c, s + 1, (size_t)(end - s - 1), NULL, NULL, c->line))
                c->nomem = c->stop = 1;
        } else if (!c->unterminated)
            c->unterminated = c->line;
        return;
    }
    const char *end = chars_or_comment(s, "=:");
    if ((*end == '=' || *end == ':') && end > s)
        c->have_prev = 1;
}

/* fgets-like reader over the text: one line per call (without its line break). */
static char *read_line(char *str, int num, void *stream)
{
    ctx *c = stream;
    if (c->stop || !*c->p || num < 2)
        return NULL;
    const char *s = c->p;
    size_t len = strcspn(s, "\n");
    const char *next = s[len] ? s + len + 1 : s + len;
    size_t clen = len;
    if (clen && s[clen - 1] == '\r')
        clen--;
    c->line++;
    size_t bad_at;
    if (clen > (size_t)(num - 1)) {
        c->bad_line = c->line;
        mc_key_fmt(c->bad, sizeof c->bad,
            "line %d is longer than %d characters (the INI reader's limit); continue a long "
            "list on indented lines",
            c->line, num - 1);
        c->stop = 1;
        return NULL;
    }
    if (!mc_utf8_check(s, clen, &bad_at)) {
        c->bad_line = c->line;
        mc_key_fmt(c->bad, sizeof c->bad, "line %d is not UTF-8 text (byte 0x%02X at column %zu)", c->line,
            (unsigned char)s[bad_at], bad_at + 1);
        c->stop = 1;
        return NULL;
    }
    memcpy(str, s, clen);
    str[clen] = '\0';
    c->p = next;
    classify(c, str);
    return c->stop ? NULL : str;
}

static int on_pair(void *user, const char *section, const char *name, const char *value)
{
    ctx *c = user;
    if (c->stop)
        return 1;
    if (c->cont && c->n > 0 && c->e[c->n - 1].name) {
        entry *e = &c->e[c->n - 1];
        if (!e->cont_line)
            e->cont_line = c->line;
        if (append_value(e, value))
            return 1;
    } else if (add_entry(c, section, strlen(section), name, value, c->line))
        return 1;
    c->nomem = c->stop = 1;
    return 0;
}

/* ---- messages -------------------------------------------------------------------------------- */

/* "--set mesh.nx=0: " for an override entry, else "x.ini:12: ", or "x.ini: " without a line. */
static void prefix(const ctx *c, const entry *e, int line, char *buf, size_t len)
{
    char q[96];
    if (e && e->ovr) {
        mc_case_quote(e->ovr, q, sizeof q);
        mc_key_fmt(buf, len, "--set %s: ", q);
    } else if (line > 0)
        mc_key_fmt(buf, len, "%s:%d: ", c->name, line);
    else
        mc_key_fmt(buf, len, "%s: ", c->name);
}

static int fail_at(const ctx *c, const entry *e, int line, const char *f, ...)
    __attribute__((format(printf, 4, 5)));
static int fail_at(const ctx *c, const entry *e, int line, const char *f, ...)
{
    char head[MC_ERROR_MSG_MAX], body[MC_ERROR_MSG_MAX];
    prefix(c, e, line, head, sizeof head);
    va_list ap;
    va_start(ap, f);
    vsnprintf(body, sizeof body, f, ap);
    va_end(ap);
    return mc_fail(c->err, MC_ERR_INPUT, "%s%s", head, body);
}

/* Where another entry is, seen from a message about e: "on line 8", "on line 8 of x.ini",
 * "given by --set load.force=3 N". */
static void where(const ctx *c, const entry *from, const entry *other, char *buf, size_t len)
{
    char q[96];
    if (other->ovr) {
        mc_case_quote(other->ovr, q, sizeof q);
        mc_key_fmt(buf, len, "given by --set %s", q);
    } else if (from && from->ovr)
        mc_key_fmt(buf, len, "on line %d of %s", other->line, c->name);
    else
        mc_key_fmt(buf, len, "on line %d", other->line);
}

static void known_sections(char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = '\0';
    for (int s = 0; s < mc_nsections && o < len; s++) {
        mc_key_fmt(buf + o, len - o, "%s%s", s ? ", " : "", mc_key_sections[s].name);
        o += strlen(buf + o);
    }
}

static void keys_of(const char *section, char *buf, size_t len)
{
    size_t o = 0;
    buf[0] = '\0';
    for (int k = 0; k < mc_nkeys && o < len; k++) {
        if (strcmp(mc_keys[k].section, section) != 0)
            continue;
        mc_key_fmt(buf + o, len - o, "%s%s", o ? ", " : "", mc_keys[k].name);
        o += strlen(buf + o);
    }
}

/* ---- validation ------------------------------------------------------------------------------ */

/* The effective value of an enum or bool key as text ("sphere", "yes"). */
static void value_text(const ctx *c, int k, char *buf, size_t len)
{
    int v = mc_key_get_int(&c->sc, mc_keys[k].off);
    if (mc_keys[k].kind == K_BOOL)
        mc_key_fmt(buf, len, "%s", v ? "yes" : "no");
    else if (!mc_key_choice(&mc_keys[k], v, buf, len))
        mc_key_fmt(buf, len, "%d", v);
}

static int used(const ctx *c, int k)
{
    const case_key *key = &mc_keys[k];
    if (key->use == USE_ALWAYS)
        return 1;
    int sel = mc_key_selector(k);
    if (key->use == USE_UNLESS)
        return c->slot[sel] < 0;
    char v[64];
    value_text(c, sel, v, sizeof v);
    /* a selector that is itself unused selects nothing (hardening under criterion = pressure_cap) */
    return mc_key_word_index(key->use_values, v) >= 0 && used(c, sel);
}

/* The section's requirements apply (its switch key, if any, is on). */
static int section_active(const ctx *c, const char *section)
{
    const case_section *s = mc_key_section(section);
    if (!s->switch_key)
        return 1;
    return mc_key_get_int(&c->sc, mc_keys[mc_key_find(section, s->switch_key)].off) != 0;
}

/* "force, force_per_length, approach, pressure_file": the used keys of k's group. */
static int group_members(const ctx *c, int k, char *buf, size_t len)
{
    size_t o = 0;
    int n = 0;
    buf[0] = '\0';
    for (int j = 0; j < mc_nkeys && o < len; j++) {
        if (!mc_keys[j].group || strcmp(mc_keys[j].group, mc_keys[k].group) != 0 ||
            strcmp(mc_keys[j].section, mc_keys[k].section) != 0 || !used(c, j))
            continue;
        mc_key_fmt(buf + o, len - o, "%s%s", n++ ? ", " : "", mc_keys[j].name);
        o += strlen(buf + o);
    }
    return n;
}

/* " for shape = sphere" when k is conditional on a selector. */
static void condition_text(const ctx *c, int k, char *buf, size_t len)
{
    buf[0] = '\0';
    if (mc_keys[k].use == USE_WHEN) {
        char v[64];
        value_text(c, mc_key_selector(k), v, sizeof v);
        mc_key_fmt(buf, len, " for %s = %s", mc_keys[k].use_key, v);
    }
}

static int check_structure(ctx *c)
{
    char list[512], q[96], qv[96];
    for (int i = 0; i < c->n; i++) {
        entry *e = &c->e[i];
        mc_case_quote(e->section, q, sizeof q);
        if (!e->name) {
            if (!mc_key_section(e->section)) {
                known_sections(list, sizeof list);
                return fail_at(c, e, e->line, "unknown section [%s]; known sections: %s", q, list);
            }
            continue;
        }
        char qn[96];
        mc_case_quote(e->name, qn, sizeof qn);
        if (!e->section[0]) {
            known_sections(list, sizeof list);
            mc_key_show(e->value, qv, sizeof qv);
            return fail_at(c, e, e->line, "%s = %s comes before any [section]; known sections: %s",
                           qn, qv, list);
        }
        if (!mc_key_section(e->section)) {
            known_sections(list, sizeof list);
            return fail_at(c, e, e->line, "unknown section [%s]; known sections: %s", q, list);
        }
        int k = mc_key_find(e->section, e->name);
        if (k < 0) {
            keys_of(e->section, list, sizeof list);
            return fail_at(c, e, e->line, "[%s] unknown key '%s'; keys of [%s]: %s", q, qn, q,
                           list);
        }
        if (c->slot[k] >= 0) {
            char w[160];
            where(c, e, &c->e[c->slot[k]], w, sizeof w);
            return fail_at(c, e, e->line, "[%s] %s given twice (first %s)", q, qn, w);
        }
        c->slot[k] = i;
    }
    return MC_OK;
}

static int key_of_entry(const entry *e) { return e->name ? mc_key_find(e->section, e->name) : -1; }

static int convert_entries(ctx *c)
{
    char why[MC_KEY_DESCRIBE_MAX + 64], qv[96];
    for (int i = 0; i < c->n; i++) {
        const entry *e = &c->e[i];
        int k = key_of_entry(e);
        if (k < 0)
            continue;
        const case_key *key = &mc_keys[k];
        mc_key_show(e->value, qv, sizeof qv);
        if (e->cont_line && key->kind != K_LENGTHS && key->kind != K_LIST) /* lists continue */
            return fail_at(c, e, e->cont_line,
                           "[%s] %s: this line starts with whitespace, so it continues %s from "
                           "line %d, but %s takes a single value (remove the indentation)",
                           key->section, key->name, key->name, e->line, key->name);
        if (mc_key_convert(key, e->value, e->ovr ? NULL : c->base_dir, &c->sc, why, sizeof why))
            return fail_at(c, e, e->line, "[%s] %s = %s: %s", key->section, key->name, qv, why);
    }
    return MC_OK;
}

static int check_use(ctx *c)
{
    char w[160], v[64], members[256];
    for (int i = 0; i < c->n; i++) {
        const entry *e = &c->e[i];
        int k = key_of_entry(e);
        if (k < 0)
            continue;
        const case_key *key = &mc_keys[k];
        if (!used(c, k)) {
            int sel = mc_key_selector(k);
            if (key->use == USE_WHEN) {
                value_text(c, sel, v, sizeof v);
                return fail_at(c, e, e->line, "[%s] %s is not used by %s = %s", key->section,
                               key->name, key->use_key, v);
            }
            where(c, e, &c->e[c->slot[sel]], w, sizeof w);
            return fail_at(c, e, e->line, "[%s] %s cannot be combined with %s (%s)", key->section,
                           key->name, key->use_key, w);
        }
        if (!key->group)
            continue;
        for (int j = 0; j < mc_nkeys; j++) {
            if (j == k || !mc_keys[j].group || strcmp(mc_keys[j].group, key->group) != 0 ||
                strcmp(mc_keys[j].section, key->section) != 0 || c->slot[j] < 0 || c->slot[j] >= i ||
                !used(c, j))
                continue;
            group_members(c, k, members, sizeof members);
            where(c, e, &c->e[c->slot[j]], w, sizeof w);
            return fail_at(c, e, e->line, "[%s] %s: give exactly one of %s (%s is %s)",
                           key->section, key->name, members, mc_keys[j].name, w);
        }
    }
    return MC_OK;
}

static int check_required(ctx *c)
{
    char range[MC_KEY_DESCRIBE_MAX], cond[96], members[256];
    for (int k = 0; k < mc_nkeys; k++) {
        const case_key *key = &mc_keys[k];
        if (c->slot[k] >= 0 || !used(c, k) || !section_active(c, key->section))
            continue;
        if (c->mesh_from_file && strcmp(key->section, "mesh") == 0)
            continue; /* the grid came from the height map */
        condition_text(c, k, cond, sizeof cond);
        mc_key_describe(key, 1, range, sizeof range);
        if (key->required)
            return fail_at(c, NULL, 0, "[%s] %s is required%s (%s)", key->section, key->name, cond,
                           range);
        if (!key->group)
            continue;
        int n = group_members(c, k, members, sizeof members), given = 0, first = -1;
        for (int j = 0; j < mc_nkeys; j++) {
            if (!mc_keys[j].group || strcmp(mc_keys[j].group, key->group) != 0 ||
                strcmp(mc_keys[j].section, key->section) != 0 || !used(c, j))
                continue;
            if (first < 0)
                first = j;
            given |= c->slot[j] >= 0 || mc_keys[j].def; /* a defaulted member stands in */
        }
        if (given || first != k)
            continue;
        if (n == 1)
            return fail_at(c, NULL, 0, "[%s] %s is required%s (%s)", key->section, key->name, cond,
                           range);
        return fail_at(c, NULL, 0, "[%s] give exactly one of %s%s: none is given", key->section,
                       members, cond);
    }
    return MC_OK;
}

/* [roughness] type = file without nx and ny in [mesh]: the mesh is the file's (its size, and its
 * spacing unless [mesh] gives dx, dy). The map is read here (errors name the line of [roughness]
 * file); the run reads it again. */
static int mesh_from_file(ctx *c)
{
    if (c->sc.roughness.type != MC_ROUGH_FILE)
        return MC_OK;
    const int knx = mc_key_find("mesh", "nx"), kny = mc_key_find("mesh", "ny"),
              kdx = mc_key_find("mesh", "dx"), kdy = mc_key_find("mesh", "dy");
    const int given = (c->slot[knx] >= 0) + (c->slot[kny] >= 0);
    const int kfile = mc_key_find("roughness", "file");
    if (given == 2 || c->slot[kfile] < 0)
        return MC_OK; /* the run reads the map onto the given mesh; no file: check_required */
    const entry *fe = &c->e[c->slot[kfile]];
    if (given == 1)
        return fail_at(c, &c->e[c->slot[c->slot[knx] >= 0 ? knx : kny]],
                       c->e[c->slot[c->slot[knx] >= 0 ? knx : kny]].line,
                       "[mesh] give both nx and ny, or neither (then the mesh is the height "
                       "map's of [roughness] file)");
    mc_measured_spec ms;
    mc_measured m;
    mc_surface_measured_spec(&c->sc.roughness, &ms);
    int rc = mc_measured_load(&ms, &m, c->err);
    if (rc != MC_OK) {
        char head[MC_ERROR_MSG_MAX];
        prefix(c, fe, fe->line, head, sizeof head);
        if (c->err)
            mc_error_prefix(c->err, "%s[roughness] file: ", head);
        return rc;
    }
    mc_grid *g = &c->sc.grid;
    g->nx = m.grid.nx;
    g->ny = m.grid.ny;
    if (c->slot[kdx] < 0) {
        if (!(m.grid.dx > 0)) {
            char format[sizeof m.format];
            memcpy(format, m.format, sizeof format); /* mc_measured_free zeroes m */
            mc_measured_free(&m);
            return fail_at(c, fe, fe->line,
                           "[roughness] file: this %s file states no lateral spacing: give "
                           "[mesh] dx (and dy)",
                           format);
        }
        g->dx = m.grid.dx;
        if (c->slot[kdy] < 0)
            g->dy = m.grid.dy;
    }
    mc_measured_free(&m);
    c->mesh_from_file = 1;
    const int kres = mc_key_find("roughness", "resample");
    if (c->slot[kdx] < 0 && c->slot[kdy] < 0 && c->slot[kres] >= 0 &&
        c->sc.roughness.resample != MC_RESAMPLE_NONE) /* the mesh is the file's own grid */
        return fail_at(c, &c->e[c->slot[kres]], c->e[c->slot[kres]].line,
                       "[roughness] resample has no effect when the mesh comes from the file "
                       "(no nx, ny, dx, dy in [mesh]: nothing to resample onto): remove it");
    return MC_OK;
}

static int parse_override(ctx *c, const char *ovr)
{
    char q[96];
    mc_case_quote(ovr, q, sizeof q);
    const char *eq = strchr(ovr, '=');
    const char *dot = eq ? memchr(ovr, '.', (size_t)(eq - ovr)) : NULL;
    if (!eq || !dot)
        return mc_fail(c->err, MC_ERR_INPUT, "--set %s: expected section.key=value", q);
    const char *s0 = ovr, *s1 = dot, *k0 = dot + 1, *k1 = eq, *v0 = eq + 1;
    while (s0 < s1 && isspace((unsigned char)*s0))
        s0++;
    while (s1 > s0 && isspace((unsigned char)s1[-1]))
        s1--;
    while (k0 < k1 && isspace((unsigned char)*k0))
        k0++;
    while (k1 > k0 && isspace((unsigned char)k1[-1]))
        k1--;
    while (isspace((unsigned char)*v0))
        v0++;
    size_t vn = strlen(v0);
    while (vn > 0 && isspace((unsigned char)v0[vn - 1]))
        vn--;
    if (s0 == s1 || k0 == k1)
        return mc_fail(c->err, MC_ERR_INPUT, "--set %s: expected section.key=value", q);
    char *key = dup_range(k0, (size_t)(k1 - k0)), *val = dup_range(v0, vn);
    entry *e = NULL;
    int ok = key && val;
    for (int i = 0; ok && i < c->n && !e; i++)
        if (c->e[i].name && strcmp(c->e[i].name, key) == 0 &&
            strlen(c->e[i].section) == (size_t)(s1 - s0) &&
            memcmp(c->e[i].section, s0, (size_t)(s1 - s0)) == 0)
            e = &c->e[i];
    if (ok && vn == 0 && e) {
        /* "section.key=" removes the key (e.g. --set load.force= --set load.approach=1um):
         * the entry goes, as if the file never had it; its section header stays */
        mc_free(e->section);
        mc_free(e->name);
        mc_free(e->value);
        size_t i = (size_t)(e - c->e);
        memmove(e, e + 1, sizeof *e * ((size_t)c->n - i - 1));
        c->n--;
        mc_free(key);
        mc_free(val);
        return MC_OK;
    }
    if (ok && vn == 0) { /* a known key the file does not give: nothing to remove */
        char *sec = dup_range(s0, (size_t)(s1 - s0));
        int known = sec && mc_key_find(sec, key) >= 0;
        ok = sec != NULL;
        mc_free(sec);
        if (known) {
            mc_free(key);
            mc_free(val);
            return MC_OK;
        }
    }
    if (ok && e) {
        ok = set_value(e, val);
        e->line = e->cont_line = 0;
    } else if (ok)
        ok = (e = add_entry(c, s0, (size_t)(s1 - s0), key, val, 0)) != NULL;
    if (ok)
        e->ovr = ovr;
    mc_free(key);
    mc_free(val);
    if (!ok)
        return mc_fail(c->err, MC_ERR_NOMEM, "out of memory reading --set %s", q);
    return MC_OK;
}

/* The text of line n (1-based) of c->text, quoted. */
static void line_text(const ctx *c, int n, char *buf, size_t len)
{
    const char *p = c->text;
    for (int l = 1; l < n && *p; l++) {
        p += strcspn(p, "\n");
        if (*p)
            p++;
    }
    char raw[128];
    size_t k = strcspn(p, "\r\n");
    mc_key_fmt(raw, sizeof raw, "%.*s", (int)(k < sizeof raw ? k : sizeof raw - 1), p);
    mc_case_quote(raw, buf, len);
}

static int parse_and_check(ctx *c, int noverrides, const char *const *overrides)
{
    int rc = ini_parse_stream(read_line, c, on_pair, c);
    if (c->nomem || rc == -2)
        return mc_fail(c->err, MC_ERR_NOMEM, "%s: out of memory while reading", c->name);
    if (rc > 0 && (!c->bad_line || rc < c->bad_line)) {
        char t[96];
        line_text(c, rc, t, sizeof t);
        if (rc == c->unterminated)
            return fail_at(c, NULL, rc, "section header '%s' lacks its closing ']'", t);
        return fail_at(c, NULL, rc,
                       "cannot parse this line (expected key = value or [section]): '%s'", t);
    }
    if (c->bad_line)
        return fail_at(c, NULL, c->bad_line, "%s", c->bad);
    if (c->n == 0)
        return mc_fail(c->err, MC_ERR_INPUT, "%s: empty case file (no sections and no keys)",
                       c->name);
    for (int i = 0; i < noverrides; i++)
        if ((rc = parse_override(c, overrides[i])))
            return rc;

    for (int k = 0; k < mc_nkeys; k++)
        c->slot[k] = -1;
    if ((rc = check_structure(c)) || (rc = convert_entries(c)))
        return rc;

    for (int k = 0; k < mc_nkeys; k++) {
        const case_key *key = &mc_keys[k];
        if (key->def_from && c->slot[k] < 0) {
            size_t from = mc_keys[mc_key_find(key->section, key->def_from)].off;
            memcpy((char *)&c->sc + key->off, (const char *)&c->sc + from, sizeof(double));
        }
        if (key->tagged && c->slot[k] >= 0)
            mc_key_put_int(&c->sc, key->tag_off, key->tag);
    }
    /* a section with a switch key ([stress], [lubrication]) is on when it is present */
    for (int s = 0; s < mc_nsections; s++) {
        const case_section *sec = &mc_key_sections[s];
        if (!sec->switch_key)
            continue;
        int present = 0;
        for (int i = 0; i < c->n; i++)
            present |= strcmp(c->e[i].section, sec->name) == 0;
        int k = mc_key_find(sec->name, sec->switch_key);
        if (present && c->slot[k] < 0)
            mc_key_put_int(&c->sc, mc_keys[k].off, 1);
    }

    if ((rc = check_use(c)) || (rc = mesh_from_file(c)) || (rc = check_required(c)))
        return rc;

    if (c->slot[mc_key_find("output", "dir")] < 0) {
        char dir[MC_PATH_MAX];
        if ((rc = mc_scene_output_dir(&c->sc, dir, sizeof dir, c->err))) {
            if (c->err)
                mc_error_prefix(c->err, "%s: [output] dir: ", c->name);
            return rc;
        }
        memcpy(c->sc.output.dir, dir, sizeof dir);
    }

    const char *sec = NULL, *key = NULL;
    if ((rc = mc_scene_check_key(&c->sc, c->err, &sec, &key)) ||
        (rc = mc_case_check_datafiles(&c->sc, c->err, &sec, &key))) {
        int k = sec && key ? mc_key_find(sec, key) : -1;
        const entry *e = k >= 0 && c->slot[k] >= 0 ? &c->e[c->slot[k]] : NULL;
        char head[MC_ERROR_MSG_MAX];
        prefix(c, e, e ? e->line : 0, head, sizeof head);
        if (c->err)
            mc_error_prefix(c->err, "%s", head);
        return rc;
    }
    return MC_OK;
}

int mc_case_parse_text(const char *text, const char *name, const char *base_dir, int noverrides,
                       const char *const *overrides, mc_scene *scene, mc_error *err)
{
    if (!text)
        return mc_fail(err, MC_ERR_INPUT, "%s: no case text", name ? name : "<case>");
    ctx *c = mc_calloc(1, sizeof *c);
    if (!c)
        return mc_fail(err, MC_ERR_NOMEM, "out of memory reading a case");
    c->name = name ? name : "<case>";
    c->base_dir = base_dir ? base_dir : "";
    c->text = c->p = text;
    c->err = err;
    mc_scene_defaults(&c->sc);
    int rc = MC_OK;
    if (strlen(c->name) >= sizeof c->sc.path)
        rc = mc_fail(err, MC_ERR_INPUT, "case file name is longer than %d bytes", MC_PATH_MAX - 1);
    else {
        memcpy(c->sc.path, c->name, strlen(c->name) + 1);
        rc = parse_and_check(c, noverrides, overrides);
    }
    if (rc == MC_OK && mc_nkeys > MC_SCENE_KEYS_MAX)
        rc = mc_fail(err, MC_ERR_INTERNAL, "the key table has %d rows, MC_SCENE_KEYS_MAX is %d",
                     mc_nkeys, MC_SCENE_KEYS_MAX);
    if (rc == MC_OK) {
        for (int k = 0; k < mc_nkeys; k++) /* where each key was given (mc_scene_where) */
            c->sc.key_line[k] = c->slot[k] < 0 ? 0 : c->e[c->slot[k]].ovr ? -1 : c->e[c->slot[k]].line;
        *scene = c->sc;
    }
    free_entries(c);
    mc_free(c);
    return rc;
}

int mc_case_load(const char *path, int noverrides, const char *const *overrides, mc_scene *scene,
                 mc_error *err)
{
    unsigned char *buf = NULL;
    size_t n = 0;
    int rc = mc_io_read_limited(path, (size_t)MAX_FILE_BYTES, "a case file", &buf, &n, err);
    char *text = (char *)buf;
    if (rc == MC_OK) {
        const char *nul = memchr(text, '\0', n);
        if (nul) {
            int line = 1;
            for (const char *q = text; q < nul; q++)
                line += *q == '\n';
            rc = mc_fail(err, MC_ERR_INPUT, "%s:%d: contains a NUL byte (not a text file)", path,
                         line);
        }
    }
    char *dir = NULL;
    if (rc == MC_OK) {
        const char *slash = strrchr(path, '/');
        size_t dlen = slash ? (slash == path ? 1 : (size_t)(slash - path)) : 0;
        dir = dup_range(path, dlen);
        if (!dir)
            rc = mc_fail(err, MC_ERR_NOMEM, "%s: out of memory", path);
    }
    if (rc == MC_OK)
        rc = mc_case_parse_text(text, path, dir, noverrides, overrides, scene, err);
    mc_free(dir);
    mc_free(text);
    return rc;
}
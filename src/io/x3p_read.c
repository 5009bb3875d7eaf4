/* x3p_read.c - X3P reader, ISO 25178-72 (the ISO 5436-2 XML container), see surface_file.h.
 *
 * An X3P file is a zip archive holding main.xml (root ISO5436_2, namespace
 * http://www.opengps.eu/2008/ISO5436_2, child elements unqualified):
 *   Record1: FeatureType SUR; Axes CX, CY incremental (AxisType I, Increment = spacing [m],
 *            Offset [m]); CZ absolute (AxisType A) with DataType I (int16), L (int32),
 *            F (float32) or D (float64), Increment and Offset: z = Offset + Increment * stored
 *            value (both optional, 1 and 0) for the integer types, z = Offset + stored value
 *            for F and D (the reference implementation, openGPS, and x3ptools ignore the
 *            Increment of float heights; another one is reported in out->warning);
 *   Record3: MatrixDimension SizeX SizeY SizeZ (= 1); DataLink with PointDataLink (the binary
 *            member, little-endian, x fastest), MD5ChecksumPointData, and optionally
 *            ValidPointsLink (one bit per point, least significant bit first, 1 = valid) and
 *            MD5ChecksumValidPoints; or DataList, the points inside main.xml, one Datum element
 *            each (x fastest; an empty Datum is a point not measured);
 *   Record4: ChecksumFile, a member whose first token is the MD5 of main.xml (md5sum style).
 * Record2 (date, creator, instrument, calibration) is not needed to read the heights. The members
 * may sit at the archive's root or under one top-level folder (NAME/main.xml, NAME/bindata/...,
 * as x3ptools writes them); links are looked up beside main.xml first.
 *
 * Checksums that the file declares are verified when opt->verify_checksum is set (MD5 by
 * nettle); absent ones are not required. The zip's own CRC-32 of every member is always checked
 * (libzip, when a member is read to its end). main.xml is parsed by libxml2 with network access
 * off, no entity substitution, no DTD loading; a DTD that declares entities or names an external
 * subset is refused before use. A member may not claim more compressed bytes than the archive
 * has, nor to inflate beyond deflate's ratio bound, so a small file cannot make the reader
 * allocate gigabytes.
 */
#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <libxml/globals.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include <nettle/md5.h>
#include <zip.h>

#include "core/alloc.h"
#include "io/surface_formats.h"

#define XML_MAX_BYTES (16L << 20) /* main.xml of a surface is a few kB */
#define DEFLATE_RATIO 1032        /* deflate's largest expansion factor */
#define TEXT_MAX 256              /* longest element text used (links, numbers, names) */

void mc_md5_hex(const unsigned char *buf, size_t len, char hex[33])
{
    struct md5_ctx c;
    uint8_t d[MD5_DIGEST_SIZE];
    md5_init(&c);
    md5_update(&c, len, buf);
    md5_digest(&c, MD5_DIGEST_SIZE, d);
    for (int k = 0; k < MD5_DIGEST_SIZE; k++)
        snprintf(hex + 2 * k, 3, "%02x", d[k]);
}

/* A printable copy of text taken from the file (element text, member names), for messages. */
#define SHOWN_MAX 72
static const char *shown(const char *s, char buf[SHOWN_MAX])
{
    mc_surface_quote(buf, SHOWN_MAX, (const unsigned char *)s, strlen(s));
    return buf;
}

/* ---- zip members ------------------------------------------------------------------------- */

typedef struct {
    zip_t *za;
    const char *what;
    size_t len; /* bytes of the whole archive */
} archive;

/* Read member name into *data (mc_malloc'ed). expect > 0: the member must have exactly that many
 * bytes (exact) or at least that many (!exact); checked before anything is allocated. Returns
 * MC_OK, an error, or -1 (no error raised) when the archive has no such member. */
static int member(const archive *a, const char *name, size_t expect, int exact,
                  unsigned char **data, size_t *len, mc_error *err)
{
    *data = NULL;
    *len = 0;
    zip_int64_t idx = zip_name_locate(a->za, name, 0);
    if (idx < 0)
        return -1;
    char qn[SHOWN_MAX];
    shown(name, qn);
    zip_stat_t st;
    if (zip_stat_index(a->za, (zip_uint64_t)idx, 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
        return mc_fail(err, MC_ERR_INPUT, "%s: corrupt zip archive: no size for member %s",
                       a->what, qn);
    if (expect > 0 && (exact ? st.size != expect : st.size < expect))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: member %s has %llu bytes, main.xml's sizes need %s%zu (sizes do not "
                       "match the data)",
                       a->what, qn, (unsigned long long)st.size, exact ? "" : "at least ",
                       expect);
    if (st.size > (zip_uint64_t)MC_SURFACE_MAX_POINTS * 8)
        return mc_fail(err, MC_ERR_INPUT, "%s: member %s claims %llu bytes: absurd", a->what,
                       qn, (unsigned long long)st.size);
    if (!(st.valid & ZIP_STAT_COMP_SIZE) || st.comp_size > a->len ||
        ((st.valid & ZIP_STAT_COMP_METHOD) &&
         (st.comp_method == ZIP_CM_STORE || st.comp_method == ZIP_CM_DEFLATE) &&
         st.size > st.comp_size * DEFLATE_RATIO + 64))
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: corrupt zip archive: member %s claims %llu bytes from %llu "
                       "compressed",
                       a->what, qn, (unsigned long long)st.size,
                       (unsigned long long)st.comp_size);
    size_t n = (size_t)st.size;
    unsigned char *b = mc_malloc(n ? n : 1);
    if (!b)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for member %s (%zu bytes)", a->what,
                       qn, n);
    zip_file_t *f = zip_fopen_index(a->za, (zip_uint64_t)idx, 0);
    if (!f) {
        mc_free(b);
        return mc_fail(err, MC_ERR_INPUT, "%s: cannot open member %s: %s", a->what, qn,
                       zip_strerror(a->za));
    }
    size_t got = 0;
    unsigned char extra;
    zip_int64_t r = 1;
    while (got < n && (r = zip_fread(f, b + got, n - got)) > 0)
        got += (size_t)r;
    if (r > 0) /* one more read reaches the end, where libzip checks the CRC */
        r = zip_fread(f, &extra, 1);
    if (r != 0 || got != n) {
        int st2 = mc_fail(err, MC_ERR_INPUT, "%s: truncated or corrupt zip archive: member %s: %s",
                          a->what, qn,
                          r < 0 ? zip_file_strerror(f)
                                : got != n ? "shorter than its size" : "longer than its size");
        zip_fclose(f);
        mc_free(b);
        return st2;
    }
    zip_fclose(f);
    *data = b;
    *len = n;
    return MC_OK;
}

/* The folder prefix of main.xml: "" when the archive has main.xml at its root, "NAME/" when its
 * members sit under one top-level folder (NAME/main.xml, as x3ptools writes them). Returns
 * MC_OK, -1 (no main.xml anywhere) or an error (several folders hold one). */
static int find_main(const archive *a, char prefix[TEXT_MAX], mc_error *err)
{
    prefix[0] = '\0';
    if (zip_name_locate(a->za, "main.xml", 0) >= 0)
        return MC_OK;
    static const char tail[] = "/main.xml";
    const size_t nt = sizeof tail - 1;
    zip_int64_t n = zip_get_num_entries(a->za, 0);
    int found = 0;
    for (zip_int64_t k = 0; k < n; k++) {
        const char *name = zip_get_name(a->za, (zip_uint64_t)k, 0);
        size_t len = name ? strlen(name) : 0;
        if (len <= nt || len - nt + 1 >= TEXT_MAX || strcmp(name + len - nt, tail) != 0 ||
            memchr(name, '/', len - nt) != NULL)
            continue; /* only FOLDER/main.xml, one level down */
        if (found++) {
            char q1[SHOWN_MAX], q2[SHOWN_MAX];
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: main.xml in two folders of the zip archive (%s and %s): not one "
                           "X3P surface",
                           a->what, shown(prefix, q1), shown(name, q2));
        }
        memcpy(prefix, name, len - nt + 1);
        prefix[len - nt + 1] = '\0';
    }
    return found ? MC_OK : -1;
}

/* member() of a name main.xml gives (a link), looked up beside main.xml first. */
static int member_at(const archive *a, const char *prefix, const char *name, size_t expect,
                     int exact, unsigned char **data, size_t *len, mc_error *err)
{
    if (prefix[0]) {
        char full[2 * TEXT_MAX];
        snprintf(full, sizeof full, "%s%s", prefix, name);
        int st = member(a, full, expect, exact, data, len, err);
        if (st != -1)
            return st;
    }
    return member(a, name, expect, exact, data, len, err);
}

/* ---- main.xml ---------------------------------------------------------------------------- */

/* First element child of n called name (local name; any namespace). */
static xmlNodePtr child(xmlNodePtr n, const char *name)
{
    for (xmlNodePtr c = n ? n->children : NULL; c; c = c->next)
        if (c->type == XML_ELEMENT_NODE && strcmp((const char *)c->name, name) == 0)
            return c;
    return NULL;
}

/* The element at a '/'-separated path below n, or NULL. */
static xmlNodePtr at(xmlNodePtr n, const char *path)
{
    char part[64];
    while (n && *path) {
        size_t k = strcspn(path, "/");
        if (k >= sizeof part)
            return NULL;
        memcpy(part, path, k);
        part[k] = '\0';
        n = child(n, part);
        path += k + (path[k] == '/');
    }
    return n;
}

/* Trimmed text of the element at path into out (TEXT_MAX). 1 found, 0 absent, -1 too long. */
static int text_at(xmlNodePtr root, const char *path, char *out)
{
    xmlNodePtr n = at(root, path);
    if (!n)
        return 0;
    xmlChar *c = xmlNodeGetContent(n);
    const char *s = c ? (const char *)c : "";
    size_t len = strlen(s);
    while (len > 0 && isspace((unsigned char)*s))
        s++, len--;
    while (len > 0 && isspace((unsigned char)s[len - 1]))
        len--;
    int ok = len < TEXT_MAX;
    if (ok) {
        memcpy(out, s, len);
        out[len] = '\0';
    }
    xmlFree(c);
    return ok ? 1 : -1;
}

typedef struct {
    const char *what;
    xmlNodePtr root;
    mc_error *err;
} xml_ctx;

/* Required text at path: MC_OK, or an error naming the element. */
static int need_text(const xml_ctx *x, const char *path, char *out)
{
    int r = text_at(x->root, path, out);
    if (r == 1)
        return MC_OK;
    return mc_fail(x->err, MC_ERR_INPUT, "%s: main.xml: %s %s", x->what, path,
                   r == 0 ? "missing" : "too long");
}

static int number_at(const xml_ctx *x, const char *path, int required, double dflt, double *v)
{
    char t[TEXT_MAX];
    int r = text_at(x->root, path, t);
    if (r == 0 && !required) {
        *v = dflt;
        return MC_OK;
    }
    if (r != 1 || !mc_surface_number(t, strlen(t), v))
        return mc_fail(x->err, MC_ERR_INPUT, "%s: main.xml: %s %s", x->what, path,
                       r == 0 ? "missing" : "is not a finite number");
    return MC_OK;
}

/* Refuse DTDs that could expand entities or point outside the file, before libxml2 sees them. */
static int refuse_dtd(const unsigned char *xml, size_t n, const char *what, mc_error *err)
{
    static const char ent[] = "<!ENTITY";
    for (size_t k = 0; k + sizeof ent - 1 <= n; k++)
        if (xml[k] == '<' && memcmp(xml + k, ent, sizeof ent - 1) == 0)
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: main.xml declares XML entities (<!ENTITY ...>): refused (an X3P "
                           "needs no DTD)",
                           what);
    return MC_OK;
}

/* libxml2 reports some problems (encoding errors, I/O) through its per-thread global handlers,
 * which print to stderr by default: while parsing, those are replaced by these two, which only
 * keep the first error's text (library code never prints). */
typedef struct {
    char msg[160];
    int line;
} xml_report;

static void xml_quiet(void *ctx, const char *fmt, ...)
{
    (void)ctx;
    (void)fmt;
}

static void xml_record(void *ctx, xmlErrorPtr e)
{
    xml_report *r = ctx;
    if (r->msg[0] == '\0' && e && e->level >= XML_ERR_ERROR && e->message) {
        mc_surface_quote(r->msg, sizeof r->msg, (const unsigned char *)e->message,
                         strcspn(e->message, "\n"));
        r->line = e->line;
    }
}

static int parse_xml(const unsigned char *xml, size_t n, const char *what, xmlDocPtr *doc,
                     mc_error *err)
{
    *doc = NULL;
    if (n > (size_t)XML_MAX_BYTES)
        return mc_fail(err, MC_ERR_INPUT, "%s: main.xml has %zu bytes; at most %ld accepted", what,
                       n, XML_MAX_BYTES);
    int st = refuse_dtd(xml, n, what, err);
    if (st != MC_OK)
        return st;
    xml_report rep = {"", 0};
    xmlGenericErrorFunc old_generic = xmlGenericError;
    void *old_generic_ctx = xmlGenericErrorContext;
    xmlStructuredErrorFunc old_structured = xmlStructuredError;
    void *old_structured_ctx = xmlStructuredErrorContext;
    xmlSetGenericErrorFunc(NULL, xml_quiet);
    xmlSetStructuredErrorFunc(&rep, xml_record);
    xmlParserCtxtPtr ctxt = xmlNewParserCtxt();
    /* NONET: no network; no NOENT (entities are not substituted), no DTDLOAD/DTDVALID (no
     * external subset is fetched); NOERROR/NOWARNING: no reports through the context. */
    if (ctxt)
        *doc = xmlCtxtReadMemory(ctxt, (const char *)xml, (int)n, "main.xml", NULL,
                                 XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING);
    if (ctxt && !*doc && rep.msg[0] == '\0') {
        xmlErrorPtr e = xmlCtxtGetLastError(ctxt);
        xml_record(&rep, e);
    }
    if (ctxt)
        xmlFreeParserCtxt(ctxt);
    xmlSetGenericErrorFunc(old_generic_ctx, old_generic);
    xmlSetStructuredErrorFunc(old_structured_ctx, old_structured);
    if (!ctxt)
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory for the XML parser", what);
    if (!*doc)
        return mc_fail(err, MC_ERR_INPUT, "%s: main.xml is not well-formed XML (line %d): %s",
                       what, rep.line, rep.msg[0] ? rep.msg : "no document");
    xmlDtdPtr dtd = (*doc)->intSubset;
    if ((*doc)->extSubset || (dtd && (dtd->ExternalID || dtd->SystemID || dtd->entities))) {
        xmlFreeDoc(*doc);
        *doc = NULL;
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: main.xml has a DTD with entities or an external subset: refused (an "
                       "X3P needs no DTD)",
                       what);
    }
    return MC_OK;
}

/* ---- checksums ----------------------------------------------------------------------------- */

static int hex_equal(const char *a, const char *b)
{
    for (int k = 0; k < 32; k++)
        if (tolower((unsigned char)a[k]) != tolower((unsigned char)b[k]))
            return 0;
    return 1;
}

/* The MD5 hex at the start of s[0..n) (md5sum style: digest, blank, name), or NULL. */
static const char *md5_token(const unsigned char *s, size_t n, char hex[33])
{
    size_t k = 0;
    while (k < n && isspace(s[k]))
        k++;
    if (n - k < 32)
        return NULL;
    for (int q = 0; q < 32; q++) {
        if (!isxdigit(s[k + (size_t)q]))
            return NULL;
        hex[q] = (char)s[k + (size_t)q];
    }
    if (n - k > 32 && !isspace(s[k + 32]))
        return NULL;
    hex[32] = '\0';
    return hex;
}

static int check_md5(const char *what, const char *name, const unsigned char *b, size_t n,
                     const char *declared, const char *where, mc_error *err)
{
    char got[33];
    mc_md5_hex(b, n, got);
    if (strlen(declared) != 32 || !hex_equal(got, declared)) {
        char q[SHOWN_MAX], qn[SHOWN_MAX], qw[SHOWN_MAX];
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: MD5 mismatch: %s has MD5 %s, %s says '%s' (corrupt file; set "
                       "verify_checksum = no to read it anyway)",
                       what, shown(name, qn), got, shown(where, qw), shown(declared, q));
    }
    return MC_OK;
}

/* ---- the surface ------------------------------------------------------------------------- */

typedef struct {
    double dx, dy, x0, y0, zinc, zoff;
    char type;
    long long nx, ny;
    char data_link[TEXT_MAX], data_md5[TEXT_MAX], valid_link[TEXT_MAX], valid_md5[TEXT_MAX];
    int have_data_md5, have_valid, have_valid_md5;
    xmlNodePtr data_list; /* Record3/DataList: the points inside main.xml (no binary member) */
} x3p_layout;

static int read_layout(const xml_ctx *x, x3p_layout *L)
{
    char t[TEXT_MAX], q[SHOWN_MAX];
    const char *what = x->what;
    if (strcmp((const char *)x->root->name, "ISO5436_2") != 0)
        return mc_fail(x->err, MC_ERR_INPUT,
                       "%s: main.xml root element is '%s', not ISO5436_2 (not an X3P file)", what,
                       shown((const char *)x->root->name, q));
    int st = need_text(x, "Record1/FeatureType", t);
    if (st != MC_OK)
        return st;
    if (strcmp(t, "SUR") != 0)
        return mc_fail(x->err, MC_ERR_INPUT,
                       "%s: X3P feature type '%s' not supported; need SUR (an areal surface)",
                       what, shown(t, q));
    static const char *const ax[2] = {"Record1/Axes/CX", "Record1/Axes/CY"};
    for (int a = 0; a < 2; a++) {
        char p[64];
        snprintf(p, sizeof p, "%s/AxisType", ax[a]);
        if ((st = need_text(x, p, t)) != MC_OK)
            return st;
        if (strcmp(t, "I") != 0)
            return mc_fail(x->err, MC_ERR_INPUT,
                           "%s: X3P axis %s has AxisType '%s'; need I (incremental: a regular "
                           "grid)",
                           what, ax[a] + 13, shown(t, q));
        snprintf(p, sizeof p, "%s/Increment", ax[a]);
        double *inc = a ? &L->dy : &L->dx, *off = a ? &L->y0 : &L->x0;
        if ((st = number_at(x, p, 1, 0, inc)) != MC_OK)
            return st;
        if (!(*inc > 0))
            return mc_fail(x->err, MC_ERR_INPUT, "%s: main.xml: %s = %g; need a spacing > 0",
                           what, p, *inc);
        snprintf(p, sizeof p, "%s/Offset", ax[a]);
        if ((st = number_at(x, p, 0, 0.0, off)) != MC_OK)
            return st;
    }
    if ((st = need_text(x, "Record1/Axes/CZ/AxisType", t)) != MC_OK)
        return st;
    if (strcmp(t, "A") != 0)
        return mc_fail(x->err, MC_ERR_INPUT, "%s: X3P axis CZ has AxisType '%s'; need A", what,
                       shown(t, q));
    if ((st = need_text(x, "Record1/Axes/CZ/DataType", t)) != MC_OK)
        return st;
    if (strlen(t) != 1 || !strchr("ILFD", t[0]))
        return mc_fail(x->err, MC_ERR_INPUT,
                       "%s: X3P CZ DataType '%s' not supported; need I, L, F or D", what,
                       shown(t, q));
    L->type = t[0];
    if ((st = number_at(x, "Record1/Axes/CZ/Increment", 0, 1.0, &L->zinc)) != MC_OK ||
        (st = number_at(x, "Record1/Axes/CZ/Offset", 0, 0.0, &L->zoff)) != MC_OK)
        return st;
    if (L->zinc == 0.0)
        return mc_fail(x->err, MC_ERR_INPUT, "%s: main.xml: CZ Increment is 0", what);

    static const char *const dims[3] = {"Record3/MatrixDimension/SizeX",
                                        "Record3/MatrixDimension/SizeY",
                                        "Record3/MatrixDimension/SizeZ"};
    long long size[3];
    for (int d = 0; d < 3; d++) {
        if ((st = need_text(x, dims[d], t)) != MC_OK)
            return st;
        if (!mc_surface_integer(t, strlen(t), &size[d]))
            return mc_fail(x->err, MC_ERR_INPUT, "%s: main.xml: %s '%s' is not an integer",
                           what, dims[d], shown(t, q));
    }
    if (size[2] != 1)
        return mc_fail(x->err, MC_ERR_INPUT,
                       "%s: X3P SizeZ = %lld (several layers) not supported; need 1", what,
                       size[2]);
    if ((st = mc_surface_check_dims(size[0], size[1], what, x->err)) != MC_OK)
        return st;
    L->nx = size[0];
    L->ny = size[1];
    if (!at(x->root, "Record3/DataLink")) {
        /* ISO 5436-2 allows the points inside main.xml, one Datum each (openGPS's samples) */
        L->data_list = at(x->root, "Record3/DataList");
        if (!L->data_list)
            return mc_fail(x->err, MC_ERR_INPUT,
                           "%s: main.xml has neither Record3/DataLink (binary points) nor "
                           "Record3/DataList (points in main.xml): no heights",
                           what);
        return MC_OK;
    }
    if ((st = need_text(x, "Record3/DataLink/PointDataLink", L->data_link)) != MC_OK)
        return st;
    L->have_data_md5 = text_at(x->root, "Record3/DataLink/MD5ChecksumPointData", L->data_md5) == 1;
    L->have_valid = text_at(x->root, "Record3/DataLink/ValidPointsLink", L->valid_link) == 1 &&
                    L->valid_link[0];
    L->have_valid_md5 =
        text_at(x->root, "Record3/DataLink/MD5ChecksumValidPoints", L->valid_md5) == 1;
    return MC_OK;
}

static double stored_value(const unsigned char *b, char type)
{
    switch (type) {
    case 'I':
        return (double)(int16_t)(uint16_t)(b[0] | b[1] << 8);
    case 'L':
        return (double)(int32_t)((uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                                 (uint32_t)b[3] << 24);
    case 'F': {
        uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 |
                     (uint32_t)b[3] << 24;
        float f;
        memcpy(&f, &u, sizeof f);
        return (double)f;
    }
    default: {
        uint64_t u = 0;
        for (int k = 7; k >= 0; k--)
            u = (u << 8) | b[k];
        double d;
        memcpy(&d, &u, sizeof d);
        return d;
    }
    }
}

/* The points of Record3/DataList: one Datum element per point, x fastest, holding the stored z
 * value (an empty Datum is a point not measured). */
static int read_data_list(const x3p_layout *L, double zinc, const char *what,
                          mc_surface_data *out, mc_error *err)
{
    const size_t n = (size_t)(L->nx * L->ny);
    size_t count = 0;
    for (xmlNodePtr c = L->data_list->children; c; c = c->next)
        count += c->type == XML_ELEMENT_NODE && strcmp((const char *)c->name, "Datum") == 0;
    if (count != n)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: main.xml: Record3/DataList has %zu Datum elements, MatrixDimension "
                       "%lld x %lld needs %zu (sizes do not match the data)",
                       what, count, L->nx, L->ny, n);
    int st = mc_surface_alloc(out, L->nx, L->ny, what, err);
    if (st != MC_OK)
        return st;
    size_t k = 0;
    for (xmlNodePtr c = L->data_list->children; c; c = c->next) {
        if (c->type != XML_ELEMENT_NODE || strcmp((const char *)c->name, "Datum") != 0)
            continue;
        xmlChar *t = xmlNodeGetContent(c);
        const char *s = t ? (const char *)t : "";
        size_t len = strlen(s), b = strspn(s, " \t\r\n");
        double v = NAN;
        int ok = b == len || mc_surface_number(s, len, &v);
        if (!ok) {
            char q[SHOWN_MAX];
            mc_surface_quote(q, sizeof q, (const unsigned char *)s, len);
            xmlFree(t);
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: main.xml: Record3/DataList Datum %zu (row %zu, column %zu) is "
                           "'%s', not a number",
                           what, k + 1, k / (size_t)L->nx, k % (size_t)L->nx, q);
        }
        xmlFree(t);
        if (L->type == 'F')
            v = (double)(float)v; /* the stored type's precision */
        else if ((L->type == 'I' || L->type == 'L') && isfinite(v) && v != nearbyint(v))
            return mc_fail(err, MC_ERR_INPUT,
                           "%s: main.xml: Record3/DataList Datum %zu is %g, not an integer "
                           "(DataType %c)",
                           what, k + 1, v, L->type);
        out->z[k++] = isfinite(v) && !(zinc == 1.0 && L->zoff == 0.0) ? L->zoff + zinc * v : v;
    }
    out->dx = L->dx;
    out->dy = L->dy;
    out->x0 = L->x0;
    out->y0 = L->y0;
    return MC_OK;
}

/* Everything after the archive is open; frees what it takes except *out. */
static int read_x3p(const archive *a, const mc_surface_read_options *opt, mc_surface_data *out,
                    mc_error *err)
{
    const char *what = a->what;
    unsigned char *xml = NULL, *sum = NULL, *data = NULL, *mask = NULL;
    size_t xml_len, sum_len, data_len, mask_len;
    xmlDocPtr doc = NULL;
    char q[SHOWN_MAX];
    char prefix[TEXT_MAX];
    int st = find_main(a, prefix, err);
    if (st == MC_OK)
        st = member_at(a, prefix, "main.xml", 0, 0, &xml, &xml_len, err);
    if (st == -1)
        return mc_fail(err, MC_ERR_INPUT,
                       "%s: no main.xml in the zip archive, neither at its root nor in one "
                       "top-level folder (not an X3P file)",
                       what);
    if (st != MC_OK)
        return st;
    if ((st = parse_xml(xml, xml_len, what, &doc, err)) != MC_OK)
        goto done;
    xml_ctx x = {what, xmlDocGetRootElement(doc), err};
    if (!x.root) {
        st = mc_fail(err, MC_ERR_INPUT, "%s: main.xml has no root element", what);
        goto done;
    }
    x3p_layout L;
    memset(&L, 0, sizeof L);
    if ((st = read_layout(&x, &L)) != MC_OK)
        goto done;

    char sum_name[TEXT_MAX];
    if (opt->verify_checksum && text_at(x.root, "Record4/ChecksumFile", sum_name) == 1 &&
        sum_name[0]) {
        st = member_at(a, prefix, sum_name, 0, 0, &sum, &sum_len, err);
        if (st == -1)
            st = mc_fail(err, MC_ERR_INPUT,
                         "%s: checksum file %s named in Record4 is not in the archive", what,
                         shown(sum_name, q));
        if (st != MC_OK)
            goto done;
        char hex[33];
        if (!md5_token(sum, sum_len, hex)) {
            st = mc_fail(err, MC_ERR_INPUT, "%s: %s does not start with an MD5 digest", what,
                         shown(sum_name, q));
            goto done;
        }
        if ((st = check_md5(what, "main.xml", xml, xml_len, hex, sum_name, err)) != MC_OK)
            goto done;
    }

    size_t n = (size_t)(L.nx * L.ny), elem = L.type == 'I' ? 2 : L.type == 'D' ? 8 : 4;
    /* Float heights are the heights: ISO 5436-2's reference implementation (openGPS) and
     * x3ptools use the CZ Increment only to scale integer types; a file that states another one
     * for F or D is read that way too, with a warning naming it (a factor of 1e6 between two
     * readers must not pass silently). */
    const int is_float = L.type == 'F' || L.type == 'D';
    if (is_float && L.zinc != 1.0)
        snprintf(out->warning, sizeof out->warning,
                 "%s: main.xml: CZ Increment = %g with float heights (DataType %c) ignored, as "
                 "ISO 5436-2's reference reader does; if the heights need it, give [roughness] "
                 "scale = %g",
                 what, L.zinc, L.type, L.zinc);
    const double zinc = is_float ? 1.0 : L.zinc;
    if (L.data_list) {
        st = read_data_list(&L, zinc, what, out, err);
        goto done;
    }
    st = member_at(a, prefix, L.data_link, n * elem, 1, &data, &data_len, err);
    if (st == -1)
        st = mc_fail(err, MC_ERR_INPUT, "%s: point data %s named in Record3 is not in the "
                     "archive", what, shown(L.data_link, q));
    if (st != MC_OK)
        goto done;
    if (opt->verify_checksum && L.have_data_md5 &&
        (st = check_md5(what, L.data_link, data, data_len, L.data_md5, "MD5ChecksumPointData",
                        err)) != MC_OK)
        goto done;
    if (L.have_valid) {
        st = member_at(a, prefix, L.valid_link, (n + 7) / 8, 0, &mask, &mask_len, err);
        if (st == -1)
            st = mc_fail(err, MC_ERR_INPUT, "%s: valid-points mask %s named in Record3 is not "
                         "in the archive", what, shown(L.valid_link, q));
        if (st != MC_OK)
            goto done;
        if (opt->verify_checksum && L.have_valid_md5 &&
            (st = check_md5(what, L.valid_link, mask, mask_len, L.valid_md5,
                            "MD5ChecksumValidPoints", err)) != MC_OK)
            goto done;
    }

    if ((st = mc_surface_alloc(out, L.nx, L.ny, what, err)) != MC_OK)
        goto done;
    if (mask) {
        out->valid = mc_malloc(n);
        if (!out->valid) {
            st = mc_fail(err, MC_ERR_NOMEM, "%s: no memory for the valid-point mask", what);
            goto done;
        }
        for (size_t k = 0; k < n; k++)
            out->valid[k] = (mask[k >> 3] >> (k & 7)) & 1;
    }
    /* Increment 1, offset 0 (what the writer uses): the stored double itself, bit for bit. */
    int identity = zinc == 1.0 && L.zoff == 0.0;
    for (size_t k = 0; k < n; k++) {
        double v = stored_value(data + k * elem, L.type);
        out->z[k] = identity || !isfinite(v) ? v : L.zoff + zinc * v;
    }
    out->dx = L.dx;
    out->dy = L.dy;
    out->x0 = L.x0;
    out->y0 = L.y0;
done:
    if (doc)
        xmlFreeDoc(doc);
    mc_free(xml);
    mc_free(sum);
    mc_free(data);
    mc_free(mask);
    return st;
}

int mc_x3p_parse(const unsigned char *buf, size_t len, const char *what,
                 const mc_surface_read_options *opt, mc_surface_data *out, mc_error *err)
{
    zip_error_t ze;
    zip_error_init(&ze);
    zip_source_t *src = zip_source_buffer_create(buf, len, 0, &ze);
    if (!src) {
        zip_error_fini(&ze);
        return mc_fail(err, MC_ERR_NOMEM, "%s: no memory to open the zip archive", what);
    }
    zip_t *za = zip_open_from_source(src, ZIP_RDONLY | ZIP_CHECKCONS, &ze);
    if (!za) {
        zip_source_free(src);
        int zip_like = len >= 4 && buf[0] == 'P' && buf[1] == 'K';
        int st;
        if (zip_like)
            st = mc_fail(err, MC_ERR_INPUT, "%s: truncated or corrupt zip archive (%s)", what,
                         zip_error_strerror(&ze));
        else
            st = mc_fail(err, MC_ERR_INPUT, "%s: not an X3P file (not a zip archive)", what);
        zip_error_fini(&ze);
        return st;
    }
    zip_error_fini(&ze);
    archive a = {za, what, len};
    int st = read_x3p(&a, opt, out, err);
    zip_discard(za);
    return st;
}

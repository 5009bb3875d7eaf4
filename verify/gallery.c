/* gallery.c - writes <reports>/index.md from the suites' result.json files and the figure
 * manifest (gallery_manifest.c); see gallery.h. */
#include "gallery.h"

#include <jansson.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "harness.h"

#define PATHLEN 2048

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

/* <dir>/<suite>/result.json, or NULL when the suite has not been run into dir. */
static json_t *load_result(const char *dir, const char *suite)
{
    char path[PATHLEN];
    snprintf(path, sizeof path, "%s/%s/result.json", dir, suite);
    return json_load_file(path, 0, NULL);
}

static int is_registered(const char *suite)
{
    int n;
    const vf_suite *all = vf_suites(&n);
    for (int k = 0; k < n; k++)
        if (!strcmp(all[k].name, suite))
            return 1;
    return 0;
}

/* ---- caption placeholders ----------------------------------------------------------------- */

/* The field of line at column col (comma separated, no quoting: the suites write plain CSV) into
 * out; 0 if there is no such column. */
static int csv_field(const char *line, int col, char *out, size_t len)
{
    for (int c = 0; c < col; c++) {
        line = strchr(line, ',');
        if (!line)
            return 0;
        line++;
    }
    size_t n = strcspn(line, ",\r\n");
    snprintf(out, len, "%.*s", (int)n, line);
    return 1;
}

static int csv_column(const char *header, const char *name)
{
    char f[128];
    for (int c = 0; csv_field(header, c, f, sizeof f); c++)
        if (!strcmp(f, name))
            return c;
    return -1;
}

/* spec = "FILE:K=V,K2=V2:COL" in <dir>/<suite>/: the value, or NAN. Lines starting with '#'
 * are comments; the first other line is the header. */
static double csv_lookup(const char *dir, const char *suite, const char *spec)
{
    char file[256], conds[512], col[128];
    if (sscanf(spec, "%255[^:]:%511[^:]:%127s", file, conds, col) != 3)
        return NAN;
    char path[PATHLEN];
    snprintf(path, sizeof path, "%s/%s/%s", dir, suite, file);
    FILE *f = fopen(path, "r");
    if (!f)
        return NAN;
    char header[4096] = "", line[4096];
    double v = NAN;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#')
            continue;
        if (!header[0]) {
            snprintf(header, sizeof header, "%s", line);
            continue;
        }
        int match = 1;
        char buf[512];
        snprintf(buf, sizeof buf, "%s", conds);
        for (char *save = NULL, *c = strtok_r(buf, ",", &save); c && match;
             c = strtok_r(NULL, ",", &save)) {
            char *eq = strchr(c, '='), fv[128];
            if (eq)
                *eq = '\0';
            int k = eq ? csv_column(header, c) : -1;
            match = k >= 0 && csv_field(line, k, fv, sizeof fv) && !strcmp(fv, eq + 1);
        }
        if (!match)
            continue;
        char fv[128];
        int k = csv_column(header, col);
        if (k >= 0 && csv_field(line, k, fv, sizeof fv)) {
            char *end;
            double d = strtod(fv, &end);
            if (end != fv)
                v = d;
        }
        break;
    }
    fclose(f);
    return v;
}

/* A measured value from result.json of suite (loaded on demand). */
static double result_value(const char *dir, const char *suite, const char *id)
{
    json_t *r = load_result(dir, suite);
    double v = NAN;
    if (r) {
        json_t *x = json_object_get(json_object_get(r, "values"), id);
        if (json_is_number(x))
            v = json_number_value(x);
        json_decref(r);
    }
    return v;
}

/* Whether fmt is one printf conversion for a double (flags, width, precision, then e f g E G)
 * with nothing but literal text (and %%) around it. */
static int safe_format(const char *fmt)
{
    int conv = 0;
    for (const char *p = fmt; *p; p++) {
        if (*p != '%')
            continue;
        if (p[1] == '%') {
            p++;
            continue;
        }
        p++;
        p += strspn(p, "-+ #0");
        p += strspn(p, "0123456789");
        if (*p == '.')
            p += 1 + strspn(p + 1, "0123456789");
        if (!*p || !strchr("efgEG", *p))
            return 0;
        conv++;
    }
    return conv == 1;
}

/* Expand the placeholders of text (gallery.h) for the row of suite into f. */
static void expand(FILE *f, const char *dir, const char *suite, const char *text)
{
    for (const char *p = text; *p; p++) {
        const char *end = *p == '{' ? strchr(p, '}') : NULL;
        if (!end || end - p > 600) {
            fputc(*p, f);
            continue;
        }
        char spec[608], fmt[32] = "%.4g";
        snprintf(spec, sizeof spec, "%.*s", (int)(end - p - 1), p + 1);
        int pct = 0, has_fmt = 0;
        char *bar = strchr(spec, '|');
        if (bar)
            *bar = '\0';
        while (bar) { /* options after '|': pct (x 100) and/or a printf conversion */
            char *opt = bar + 1;
            bar = strchr(opt, '|');
            if (bar)
                *bar = '\0';
            if (!strcmp(opt, "pct"))
                pct = 1;
            else if (safe_format(opt)) {
                snprintf(fmt, sizeof fmt, "%s", opt);
                has_fmt = 1;
            }
        }
        if (pct && !has_fmt)
            snprintf(fmt, sizeof fmt, "%%.1f");
        double v;
        if (!strncmp(spec, "csv:", 4))
            v = csv_lookup(dir, suite, spec + 4);
        else {
            char *colon = strchr(spec, ':');
            if (colon) {
                *colon = '\0';
                v = result_value(dir, spec, colon + 1);
            } else
                v = result_value(dir, suite, spec);
        }
        if (isnan(v))
            fputs("n/a", f);
        else
            fprintf(f, fmt, pct ? 100 * v : v);
        p = end;
    }
}

/* ---- the suite table --------------------------------------------------------------------- */

typedef struct {
    int runs, checks, failed, info;
    double seconds;
} totals;

static void suite_row(FILE *f, const char *dir, const char *name, const char *title, totals *t)
{
    json_t *r = load_result(dir, name);
    if (!r) {
        fprintf(f, "| `%s` | %s | not run | | | | | | `microcontact verify %s` |\n", name, title,
                name);
        return;
    }
    int checks = (int)json_integer_value(json_object_get(r, "checks"));
    int failed = (int)json_integer_value(json_object_get(r, "failed"));
    int info = (int)json_integer_value(json_object_get(r, "info"));
    double sec = json_number_value(json_object_get(r, "seconds"));
    const char *variant = json_string_value(json_object_get(r, "variant"));
    json_t *g = json_object_get(r, "regression");
    char gate[160] = "no gate";
    if (json_is_true(json_object_get(g, "blessed_by_this_run")))
        snprintf(gate, sizeof gate, "blessed by this run");
    else if (json_is_true(json_object_get(g, "blessed")))
        snprintf(gate, sizeof gate, "%d compared, %s%d drifted%s",
                 (int)json_integer_value(json_object_get(g, "compared")),
                 json_integer_value(json_object_get(g, "drifted")) ? "**" : "",
                 (int)json_integer_value(json_object_get(g, "drifted")),
                 json_integer_value(json_object_get(g, "drifted")) ? "**" : "");
    else if (json_is_string(json_object_get(g, "baseline")))
        snprintf(gate, sizeof gate, "not blessed");
    fprintf(f, "| `%s` | %s | %s | %d | %s%d%s | %d | %s | %.1f s | [report](%s/report.md) |\n",
            name, title, variant ? variant : "?", checks, failed ? "**" : "", failed,
            failed ? "**" : "", info, gate, sec, name);
    t->runs++;
    t->checks += checks;
    t->failed += failed;
    t->info += info;
    t->seconds += sec;
    json_decref(r);
}

static void suite_table(FILE *f, const char *dir)
{
    int n;
    const vf_suite *all = vf_suites(&n);
    totals t = {0};
    fprintf(f, "## Suites\n\n"
               "| suite | what | variant | checks | failed | info rows | regression gate | "
               "run time | report |\n|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < n; k++)
        suite_row(f, dir, all[k].name, all[k].title, &t);
    /* the benchmark writes through the same harness (`microcontact bench`), when present; its
     * targets are speed goals, not physics: a row of its own, outside the suites' totals */
    char path[PATHLEN];
    snprintf(path, sizeof path, "%s/bench/result.json", dir);
    totals tb = {0};
    if (exists(path))
        suite_row(f, dir, "bench", "Benchmarks (`microcontact bench`; targets, not physics)", &tb);
    fprintf(f, "\n%d of %d suites found in this directory: %d checks, %d failed, %d information "
               "rows; %.0f s of suite run time in all.",
            t.runs, n, t.checks, t.failed, t.info, t.seconds);
    if (tb.runs)
        fprintf(f, " The benchmark (not counted above): %d of %d targets met.",
                tb.checks - tb.failed, tb.checks);
    fprintf(f, "\n\n");
}

/* ---- the gallery ------------------------------------------------------------------------- */

static void figure(FILE *f, const char *dir, const vf_gallery_row *g)
{
    char png[PATHLEN];
    snprintf(png, sizeof png, "%s/%s/%s", dir, g->suite, g->png);
    fprintf(f, "### %s: %s\n\n", g->figure, g->title);
    json_t *r = exists(png) ? load_result(dir, g->suite) : NULL;
    if (!exists(png)) {
        json_t *any = load_result(dir, g->suite);
        if (!is_registered(g->suite))
            fprintf(f, "*Pending: the suite `%s` is not part of this build yet; it is to draw "
                       "`%s/%s` from `%s`.*\n\n",
                    g->suite, g->suite, g->png, g->csv);
        else if (!any)
            fprintf(f, "*Pending: `microcontact verify %s --reports %s` has not been run into "
                       "this directory.*\n\n",
                    g->suite, dir);
        else {
            fprintf(f, "*Pending: the suite `%s` ran but did not draw `%s` (the manifest row in "
                       "verify/gallery_manifest.c names it). Its figures:",
                    g->suite, g->png);
            json_t *figs = json_object_get(any, "figures");
            size_t i;
            json_t *fg;
            json_array_foreach(figs, i, fg)
                fprintf(f, " [%s](%s/%s)", json_string_value(json_object_get(fg, "file")),
                        g->suite, json_string_value(json_object_get(fg, "file")));
            fprintf(f, ".*\n\n");
        }
        json_decref(any);
        fprintf(f, "**Paper.** %s\n\n", g->paper);
        return;
    }
    const char *variant = json_string_value(json_object_get(r, "variant"));
    int fast = variant && !strcmp(variant, "fast");
    fprintf(f, "![%s](%s/%s)\n\n", g->title, g->suite, g->png);
    fprintf(f, "**Paper.** %s\n\n**microcontact.** ", g->paper);
    expand(f, dir, g->suite, g->ours);
    fprintf(f, "%s\n\n**Difference.** ", fast ? " *(fast variant of the suite)*" : "");
    expand(f, dir, g->suite, g->differ);
    fprintf(f, "\n\nData: [%s](%s/%s) · report: [%s](%s/report.md) · regenerate: "
               "`microcontact verify %s%s --reports %s` (the suite), or "
               "`cd %s/%s && gnuplot %s.gp` (the figure alone, from the CSV)\n\n",
            g->csv, g->suite, g->csv, g->suite, g->suite, fast ? "--fast " : "", g->suite, dir,
            dir, g->suite, g->png);
    json_decref(r);
}

int vf_gallery_write(const char *reports_dir, char *msg, size_t msglen)
{
    char path[PATHLEN], tmp[PATHLEN + 8];
    snprintf(path, sizeof path, "%s/index.md", reports_dir);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        snprintf(msg, msglen, "cannot write %s", tmp);
        return -1;
    }
    fprintf(f,
            "# Verification reports and the paper's figures\n\n"
            "Regenerate everything with `make reports` (= `microcontact verify --all --reports "
            "%s`); one suite with `microcontact verify SUITE --reports %s`. This page is "
            "rewritten by every `microcontact verify` run from the reports found in this "
            "directory. Each suite compares its numbers with analytic or published references "
            "(the physics tolerance) and, where a baseline is blessed "
            "(`verify/baselines/`), with its blessed values (the regression gate).\n\n"
            "Coordinates: microcontact's x is the rolling direction, y transverse, z the depth "
            "into the body. **The paper writes x for the depth** and y, z in the surface: paper "
            "x = our z, paper sigma_x = our sigma_zz, and the paper's mesh \"dy = dz = 0.8 um\" "
            "is our dx = dy = 0.8 um. Stresses are tension positive (sigma_zz = -p at the "
            "loaded surface).\n\n",
            reports_dir, reports_dir);
    suite_table(f, reports_dir);
    fprintf(f, "## Figure gallery, in the paper's order\n\n"
               "Mevissen, Sklenak, Brecher, Bergs, *Elastic-plastic micro contact calculation for "
               "large scale, lubricated rolling-sliding contacts*, Tribologie und "
               "Schmierungstechnik 72(1) 2025. Each figure is drawn by gnuplot from the CSV "
               "beside it; the caption says what the paper shows, what we get, and where and "
               "why the two differ. What the paper shows is summarised from the project's "
               "brief and physics dossier (plastic-lubrication.md), not copied from the paper. "
               "Numbers in the captions are read from this directory's results when the page "
               "is written. A figure whose suite has not produced it yet is marked "
               "pending.\n\n");
    int n;
    const vf_gallery_row *rows = vf_gallery_manifest(&n);
    const char *last = "";
    for (int k = 0; k < n; k++) {
        if (strcmp(rows[k].figure, last) != 0)
            fprintf(f, "---\n\n");
        last = rows[k].figure;
        figure(f, reports_dir, &rows[k]);
    }
    int bad = ferror(f) | (fclose(f) != 0);
    if (bad || rename(tmp, path) != 0) {
        remove(tmp);
        snprintf(msg, msglen, "cannot write %s", path);
        return -1;
    }
    return 0;
}

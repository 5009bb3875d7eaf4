/* harness.c - runs verification suites and writes their reports (see harness.h). */
#include "harness.h"

#include <errno.h>
#include <fnmatch.h>
#include <jansson.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "pipeline/pipeline.h"

#define MAX_TEXT 65536
#define MAX_FIGS 32
#define MAX_OPEN 16

typedef struct {
    char id[64], quantity[160], reference[160];
    double expected, measured, tol, error;
    vf_kind kind;
    int pass;
    int info; /* an information row (vf_info): shown, never fails, not counted as a check */
    /* regression gate */
    double err_tol; /* physics tolerance of a row whose value is an error (vf_tier_tol), else 0 */
    int counts;     /* the row can hold a count (vf_tier_auto) */
    vf_tier tier;   /* declared by the suite (vf_regress); VF_TIER_AUTO: none declared */
    int gate;       /* GATE_* */
    double blessed, reg_tol, drift;
} vf_row;

enum {
    GATE_OFF,     /* no baseline for this suite (or no gate in this run) */
    GATE_NEW,     /* the baseline has no entry for this id: not blessed yet */
    GATE_OK,      /* within the regression tolerance */
    GATE_DRIFT,   /* beyond it: the row fails (unless the run blesses) */
    GATE_UNGATED, /* tier none: recorded, not compared */
    GATE_MISSING  /* a blessed id this run did not produce (a row added by the harness) */
};

struct vf_ctx {
    const vf_suite *suite;
    char dir[1024];
    int fast;
    vf_row *rows; /* grown as needed (the full stability matrix records over a thousand) */
    int nrows, cap_rows, nfail, ninfo;
    int lost_rows; /* rows that could not be stored (out of memory): the suite fails */
    char text[MAX_TEXT];
    size_t ntext;
    char figs[MAX_FIGS][2][256];
    int nfigs;
    FILE *open_f[MAX_OPEN];
    char open_name[MAX_OPEN][1536];
    int gnuplot_missing;
    /* regression gate */
    const vf_options *opt;
    char base_path[1280];
    int has_base;     /* the baseline file exists and was read */
    vf_baseline base;
    int mismatch;     /* blessed on another configuration: the tol_other tolerances apply */
    vf_config config; /* this run's configuration */
    int ndrift, nnew, nmissing; /* drifted rows, rows not blessed yet, blessed ids not produced */
    int blessed_now;  /* this run wrote (or confirmed) the baseline */
};

int vf_fast(const vf_ctx *ctx) { return ctx->fast; }

static double row_error(vf_kind kind, double expected, double measured)
{
    switch (kind) {
    case VF_REL: return expected != 0 ? fabs(measured - expected) / fabs(expected) : fabs(measured);
    case VF_ABS: return fabs(measured - expected);
    case VF_MAX: return measured;
    }
    return NAN;
}

/* Compare row r (index k) with its blessed value; returns 0 when it drifted beyond the
 * regression tolerance (the row then fails unless the run blesses). */
static int gate_row(vf_ctx *ctx, vf_row *r, int k)
{
    if (!ctx->has_base)
        return 1;
    vf_blessed *e = vf_baseline_find(&ctx->base, r->id, k);
    if (!e || e->seen) { /* (seen: a repeated id, which vf_check forbids: not gated) */
        r->gate = GATE_NEW;
        ctx->nnew++;
        return 1;
    }
    e->seen = 1;
    r->blessed = e->value;
    /* on the blessing configuration the suites repeat bit for bit; on another one FFTW plans and
     * the order of threaded sums change the last digits (baseline.h) */
    r->reg_tol = ctx->mismatch ? e->tol_other : e->tol;
    r->drift = isfinite(r->measured) && isfinite(e->value) ? fabs(r->measured - e->value)
               : isfinite(r->measured) == isfinite(e->value) ? 0
                                                             : INFINITY;
    if (isnan(r->reg_tol)) {
        r->gate = GATE_UNGATED;
        return 1;
    }
    if (vf_blessed_ok(e, r->reg_tol, r->measured)) {
        r->gate = GATE_OK;
        return 1;
    }
    r->gate = GATE_DRIFT;
    ctx->ndrift++;
    return ctx->opt && ctx->opt->bless;
}

/* The tail of a PASS/FAIL line for a drifted row: names the blessed and the new value. */
static const char *drift_text(const vf_ctx *ctx, const vf_row *r, char *buf, size_t len)
{
    if (r->gate != GATE_DRIFT) {
        buf[0] = '\0';
        return buf;
    }
    snprintf(buf, len,
             " - regression: blessed %.15g, new %.15g, drift %.3g > regression tolerance %.3g "
             "(%s)%s",
             r->blessed, r->measured, r->drift, r->reg_tol, ctx->base_path,
             ctx->opt && ctx->opt->bless ? "; re-blessed" : "");
    return buf;
}

/* The tier the registry gives id (vf_suite_tiers), or VF_TIER_AUTO. */
static vf_tier suite_tier(const vf_suite *suite, const char *id)
{
    for (const char *p = vf_suite_tiers(suite->name); p && *p;) {
        p += strspn(p, " ");
        size_t n = strcspn(p, " ");
        char pair[160];
        snprintf(pair, sizeof pair, "%.*s", (int)n, p);
        p += n;
        char *eq = strrchr(pair, '=');
        if (!eq)
            continue;
        *eq = '\0';
        if (fnmatch(pair, id, 0) == 0)
            return vf_tier_from_name(eq + 1);
    }
    return VF_TIER_AUTO;
}

static int add_row(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
                   double expected, double measured, double tol, double e, vf_kind kind, int pass,
                   int info)
{
    if (ctx->nrows == ctx->cap_rows) {
        int cap = ctx->cap_rows ? 2 * ctx->cap_rows : 256;
        vf_row *grown = realloc(ctx->rows, (size_t)cap * sizeof *grown);
        if (!grown) {
            ctx->lost_rows++;
            return 0;
        }
        ctx->rows = grown;
        ctx->cap_rows = cap;
    }
    vf_row *r = &ctx->rows[ctx->nrows++];
    snprintf(r->id, sizeof r->id, "%s", id);
    snprintf(r->quantity, sizeof r->quantity, "%s", quantity);
    snprintf(r->reference, sizeof r->reference, "%s", reference);
    r->expected = expected;
    r->measured = measured;
    r->tol = tol;
    r->error = e;
    r->kind = kind;
    r->pass = pass;
    r->info = info;
    /* an error that must stay small: VF_MAX, or VF_ABS against 0 */
    r->err_tol = !info && (kind == VF_MAX || (kind == VF_ABS && expected == 0)) ? tol : 0;
    r->counts = info || (kind != VF_REL && expected == rint(expected) && tol == rint(tol));
    r->tier = suite_tier(ctx->suite, id);
    r->gate = GATE_OFF;
    r->blessed = r->reg_tol = r->drift = NAN;
    return 1;
}

double vf_worst(double worst, double v)
{
    return isnan(worst) || isnan(v) ? NAN : v > worst ? v : worst;
}

double vf_least(double least, double v)
{
    return isnan(least) || isnan(v) ? NAN : v < least ? v : least;
}

int vf_check(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
             double expected, double measured, double tol, vf_kind kind)
{
    double e = row_error(kind, expected, measured);
    /* an infinite (or NaN) tolerance would make a check that cannot fail */
    int pass = isfinite(e) && isfinite(tol) && e <= tol;
    int gated = 1;
    char tail[1600] = "";
    if (add_row(ctx, id, quantity, reference, expected, measured, tol, e, kind, pass, 0)) {
        vf_row *r = &ctx->rows[ctx->nrows - 1];
        gated = gate_row(ctx, r, ctx->nrows - 1);
        r->pass = pass && gated;
        drift_text(ctx, r, tail, sizeof tail);
    }
    if (!pass || !gated)
        ctx->nfail++;
    printf("%s %s.%s: %s = %.6g (reference %.6g, %s %.3g, tolerance %.3g)%s%s\n",
           pass && gated ? "PASS" : "FAIL", ctx->suite->name, id, quantity, measured, expected,
           kind == VF_REL ? "rel. error" : kind == VF_ABS ? "abs. error" : "value", e, tol,
           isfinite(tol) ? "" : " - a check that cannot fail: record it with vf_info", tail);
    fflush(stdout);
    return pass && gated;
}

void vf_info(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
             double expected, double measured)
{
    int gated = 1;
    char tail[1600] = "";
    if (add_row(ctx, id, quantity, reference, expected, measured, NAN, NAN, VF_MAX, 0, 1)) {
        ctx->ninfo++;
        vf_row *r = &ctx->rows[ctx->nrows - 1];
        gated = gate_row(ctx, r, ctx->nrows - 1);
        drift_text(ctx, r, tail, sizeof tail);
    }
    /* an information row has no physics tolerance, but a drift from its blessed value fails it:
     * this is what guards numbers without a reference (a running-in curve, an iteration count) */
    if (!gated)
        ctx->nfail++;
    char ref[48] = "";
    if (!isnan(expected))
        snprintf(ref, sizeof ref, " against %.6g", expected);
    printf("%s %s.%s: %s = %.6g%s (%s; information, not a check)%s\n", gated ? "INFO" : "FAIL",
           ctx->suite->name, id, quantity, measured, ref, reference, tail);
    fflush(stdout);
}

void vf_regress(vf_ctx *ctx, const char *id, vf_tier tier)
{
    for (int k = ctx->nrows - 1; k >= 0; k--)
        if (!strcmp(ctx->rows[k].id, id)) {
            ctx->rows[k].tier = tier;
            return;
        }
}

void vf_fail(vf_ctx *ctx, const char *id, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    vf_check(ctx, id, msg, "must run", 0, NAN, 0, VF_ABS);
}

void vf_text(vf_ctx *ctx, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int w = vsnprintf(ctx->text + ctx->ntext, MAX_TEXT - ctx->ntext, fmt, ap);
    va_end(ap);
    if (w > 0)
        ctx->ntext += (size_t)w < MAX_TEXT - ctx->ntext ? (size_t)w : MAX_TEXT - ctx->ntext - 1;
}

const char *vf_path(vf_ctx *ctx, const char *file)
{
    static char buf[8][2048];
    static int k;
    k = (k + 1) % 8;
    snprintf(buf[k], sizeof buf[k], "%s/%s", ctx->dir, file);
    return buf[k];
}

FILE *vf_open(vf_ctx *ctx, const char *file)
{
    for (int k = 0; k < MAX_OPEN; k++) {
        if (ctx->open_f[k])
            continue;
        char tmp[1600];
        snprintf(ctx->open_name[k], sizeof ctx->open_name[k], "%s/%s", ctx->dir, file);
        snprintf(tmp, sizeof tmp, "%s.tmp", ctx->open_name[k]);
        ctx->open_f[k] = fopen(tmp, "w");
        return ctx->open_f[k];
    }
    return NULL;
}

int vf_close(vf_ctx *ctx, FILE *f)
{
    for (int k = 0; k < MAX_OPEN; k++) {
        if (ctx->open_f[k] != f)
            continue;
        char tmp[1600];
        snprintf(tmp, sizeof tmp, "%s.tmp", ctx->open_name[k]);
        int bad = ferror(f) | (fclose(f) != 0);
        ctx->open_f[k] = NULL;
        if (bad || rename(tmp, ctx->open_name[k]) != 0) {
            remove(tmp);
            return -1;
        }
        return 0;
    }
    return -1;
}

int vf_plot(vf_ctx *ctx, const char *png, const char *caption, const char *script)
{
    char gp[300];
    snprintf(gp, sizeof gp, "%s.gp", png);
    FILE *f = vf_open(ctx, gp);
    if (!f)
        return -1;
    fprintf(f, "set terminal pngcairo size 900,600 font 'sans,11'\nset output '%s'\n%s\n", png,
            script);
    if (vf_close(ctx, f) != 0)
        return -1;
    if (ctx->nfigs < MAX_FIGS) {
        snprintf(ctx->figs[ctx->nfigs][0], 256, "%s", png);
        snprintf(ctx->figs[ctx->nfigs][1], 256, "%s", caption);
        ctx->nfigs++;
    }
    if (system("command -v gnuplot >/dev/null 2>&1") != 0) {
        ctx->gnuplot_missing = 1;
        return 0;
    }
    char cmd[1600];
    snprintf(cmd, sizeof cmd, "cd '%s' && gnuplot '%s' 2>gnuplot.log && rm -f gnuplot.log", ctx->dir,
             gp);
    return system(cmd) == 0 ? 0 : -1;
}

static int mkdirs(const char *path)
{
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", path);
    for (char *p = buf + 1; *p; p++) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST)
            return -1;
        *p = '/';
    }
    return mkdir(buf, 0777) != 0 && errno != EEXIST ? -1 : 0;
}

static void fmt_num(char *out, size_t len, double v)
{
    if (isnan(v))
        snprintf(out, len, "n/a");
    else
        snprintf(out, len, "%.6g", v);
}

static const char *gate_text(const vf_row *r, char *buf, size_t len)
{
    char b[32], t[32];
    fmt_num(b, sizeof b, r->blessed);
    fmt_num(t, sizeof t, r->reg_tol);
    switch (r->gate) {
    case GATE_OFF: snprintf(buf, len, "- | -"); break;
    case GATE_NEW: snprintf(buf, len, "- | not blessed"); break;
    case GATE_OK: snprintf(buf, len, "%s | %.2g <= %s", b, r->drift, t); break;
    case GATE_DRIFT: snprintf(buf, len, "%s | **%.3g > %s**", b, r->drift, t); break;
    case GATE_UNGATED: snprintf(buf, len, "%s | not gated", b); break;
    case GATE_MISSING: snprintf(buf, len, "%s | **not produced**", b); break;
    }
    return buf;
}

static void write_gate_summary(vf_ctx *ctx, FILE *f)
{
    if (!ctx->opt || !ctx->opt->baselines)
        return;
    const vf_config *c = &ctx->config;
    if (!ctx->has_base && ctx->blessed_now) {
        fprintf(f, "Regression gate: this run created the baseline `%s` (blessed with %d "
                   "thread%s, %s, %s).\n\n",
                ctx->base_path, c->threads, c->threads == 1 ? "" : "s", c->fftw,
                c->cpu[0] ? c->cpu : "CPU unknown");
        return;
    }
    if (!ctx->has_base) {
        fprintf(f, "Regression gate: **no baseline `%s`**: the suite fails (check `baseline`) "
                   "until one is blessed deliberately (`microcontact verify %s--bless %s` "
                   "writes one).\n\n",
                ctx->base_path, ctx->fast ? "--fast " : "", ctx->suite->name);
        return;
    }
    int gated = 0;
    for (int k = 0; k < ctx->nrows; k++)
        gated += ctx->rows[k].gate == GATE_OK || ctx->rows[k].gate == GATE_DRIFT;
    const vf_config *b = &ctx->base.config;
    fprintf(f,
            "Regression gate: `%s`, blessed with %d thread%s, %s, %s; %s. %d rows compared, %d "
            "beyond their regression tolerance, %d not blessed yet, %d blessed but not "
            "produced%s.\n\n",
            ctx->base_path, b->threads, b->threads == 1 ? "" : "s", b->fftw,
            b->cpu[0] ? b->cpu : "CPU unknown",
            ctx->mismatch ? "this run is on another configuration, so the wider tolerances "
                            "(tol_other) apply"
                          : "this run is on the same configuration, so the round-off "
                            "tolerances apply",
            gated, ctx->ndrift, ctx->nnew, ctx->nmissing,
            ctx->opt->bless ? " (this run re-blessed the baseline)" : "");
}

/* s for a Markdown table cell: '|' escaped (quantities such as "max |p - p_ref|") */
static const char *cell(const char *s, char *buf, size_t len)
{
    size_t k = 0;
    for (; *s && k + 3 < len; s++) {
        if (*s == '|')
            buf[k++] = '\\';
        buf[k++] = *s;
    }
    buf[k] = '\0';
    return buf;
}

static int write_report(vf_ctx *ctx, double seconds)
{
    FILE *f = vf_open(ctx, "report.md");
    if (!f)
        return -1;
    int npass = 0;
    for (int k = 0; k < ctx->nrows; k++)
        npass += ctx->rows[k].pass;
    char info[96] = "";
    if (ctx->ninfo)
        snprintf(info, sizeof info, "; %d information row%s, shown but not counted as checks",
                 ctx->ninfo, ctx->ninfo == 1 ? "" : "s");
    fprintf(f, "# %s\n\n", ctx->suite->title);
    fprintf(f, "Suite `%s`%s: **%d of %d checks pass** (%s%s). Run time %.1f s.\n",
            ctx->suite->name, ctx->fast ? " (fast variant)" : "", npass, ctx->nrows - ctx->ninfo,
            ctx->nfail ? "FAIL" : "PASS", info, seconds);
    if (ctx->suite->regenerate)
        fprintf(f, "Regenerate with `%s`.\n\n", ctx->suite->regenerate);
    else
        fprintf(f, "Regenerate with `microcontact verify %s%s` (or `make verify`).\n\n",
                ctx->fast ? "--fast " : "", ctx->suite->name);
    write_gate_summary(ctx, f);
    fputs(ctx->text, f);
    fprintf(f, "\n## Checks\n\n");
    if (ctx->ninfo)
        fprintf(f, "Rows marked *info* show a measured value for information: no tolerance, never "
                   "a failure, not counted among the checks%s.\n\n",
                ctx->has_base ? " (but compared with their blessed value like every row)" : "");
    int gate_cols = ctx->opt && ctx->opt->baselines;
    fprintf(f, "| id | quantity | reference | expected | measured | error | tolerance | result |%s"
               "\n|---|---|---|---|---|---|---|---|%s\n",
            gate_cols ? " blessed | drift <= regression tol. |" : "", gate_cols ? "---|---|" : "");
    for (int k = 0; k < ctx->nrows; k++) {
        const vf_row *r = &ctx->rows[k];
        char e[32], m[32], er[32], t[32], g[128] = "";
        fmt_num(e, sizeof e, r->expected);
        fmt_num(m, sizeof m, r->measured);
        fmt_num(er, sizeof er, r->error);
        fmt_num(t, sizeof t, r->tol);
        if (gate_cols) {
            char gt[112];
            snprintf(g, sizeof g, " %s |", gate_text(r, gt, sizeof gt));
        }
        const char *res = r->pass ? "PASS" : "**FAIL**";
        char qb[2 * sizeof r->quantity], rb[2 * sizeof r->reference];
        const char *q = cell(r->quantity, qb, sizeof qb), *rf = cell(r->reference, rb, sizeof rb);
        if (r->info) {
            fprintf(f, "| %s | %s | %s | %s | %s | - | - | %s |%s\n", r->id, q, rf,
                    isnan(r->expected) ? "-" : e, m,
                    r->gate == GATE_DRIFT && !ctx->opt->bless ? "info, **FAIL**" : "info", g);
            continue;
        }
        if (r->gate == GATE_MISSING) {
            fprintf(f, "| %s | %s | %s | - | - | - | - | **FAIL** |%s\n", r->id, q, rf, g);
            continue;
        }
        fprintf(f, "| %s | %s | %s | %s | %s | %s %s | %s | %s |%s\n", r->id, q, rf, e, m, er,
                r->kind == VF_REL ? "(rel.)" : r->kind == VF_ABS ? "(abs.)" : "(value)", t, res, g);
    }
    if (ctx->nfigs) {
        fprintf(f, "\n## Figures\n\n");
        if (ctx->gnuplot_missing)
            fprintf(f, "gnuplot was not found: the figure scripts (`*.png.gp`) are written but not "
                       "rendered.\n\n");
        for (int k = 0; k < ctx->nfigs; k++)
            fprintf(f, "![%s](%s)\n\n*%s*\n\n", ctx->figs[k][1], ctx->figs[k][0], ctx->figs[k][1]);
    }
    return vf_close(ctx, f);
}

static json_t *jnum(double v) { return isfinite(v) ? json_real(v) : json_null(); }

/* <dir>/result.json: the suite's counts, figures and measured values, for the gallery
 * (verify/gallery.h). */
static int write_result(vf_ctx *ctx, double seconds)
{
    json_t *o = json_object(), *vals = json_object(), *figs = json_array();
    if (!o || !vals || !figs) {
        json_decref(o);
        json_decref(vals);
        json_decref(figs);
        return -1;
    }
    int gated = 0;
    for (int k = 0; k < ctx->nrows; k++) {
        const vf_row *r = &ctx->rows[k];
        gated += r->gate == GATE_OK || r->gate == GATE_DRIFT;
        if (r->gate != GATE_MISSING)
            json_object_set_new(vals, r->id, jnum(r->measured));
    }
    for (int k = 0; k < ctx->nfigs; k++) {
        json_t *fg = json_object();
        json_object_set_new(fg, "file", json_string(ctx->figs[k][0]));
        json_object_set_new(fg, "caption", json_string(ctx->figs[k][1]));
        json_array_append_new(figs, fg);
    }
    json_object_set_new(o, "suite", json_string(ctx->suite->name));
    json_object_set_new(o, "title", json_string(ctx->suite->title));
    json_object_set_new(o, "variant", json_string(ctx->fast ? "fast" : "full"));
    json_object_set_new(o, "checks", json_integer(ctx->nrows - ctx->ninfo));
    json_object_set_new(o, "failed", json_integer(ctx->nfail + ctx->lost_rows));
    json_object_set_new(o, "info", json_integer(ctx->ninfo));
    json_object_set_new(o, "seconds", json_real(seconds));
    json_t *g = json_object();
    if (g) {
        json_object_set_new(g, "baseline", ctx->opt && ctx->opt->baselines
                                               ? json_string(ctx->base_path)
                                               : json_null());
        json_object_set_new(g, "blessed", json_boolean(ctx->has_base || ctx->blessed_now));
        json_object_set_new(g, "blessed_by_this_run", json_boolean(ctx->blessed_now));
        json_object_set_new(g, "compared", json_integer(gated));
        json_object_set_new(g, "drifted", json_integer(ctx->ndrift));
        json_object_set_new(g, "not_blessed", json_integer(ctx->nnew));
        json_object_set_new(g, "missing", json_integer(ctx->nmissing));
        json_object_set_new(o, "regression", g);
    }
    json_object_set_new(o, "figures", figs);
    json_object_set_new(o, "values", vals);
    char tmp[1200];
    snprintf(tmp, sizeof tmp, "%s/result.json.tmp", ctx->dir);
    int rc = json_dump_file(o, tmp, JSON_INDENT(1) | JSON_PRESERVE_ORDER | JSON_REAL_PRECISION(17));
    json_decref(o);
    if (rc == 0 && rename(tmp, vf_path(ctx, "result.json")) == 0)
        return 0;
    remove(tmp);
    return -1;
}

/* Blessed ids this run did not produce: a row each, failed (a check that disappears changes
 * what is verified; re-bless if deliberate). */
static void add_missing_rows(vf_ctx *ctx)
{
    if (!ctx->has_base)
        return;
    for (int k = 0; k < ctx->base.n; k++) {
        const vf_blessed *e = &ctx->base.v[k];
        if (e->seen)
            continue;
        ctx->nmissing++;
        if (add_row(ctx, e->id, "blessed check not produced by this run", "baseline", e->value,
                    NAN, NAN, NAN, VF_ABS, 0, 0)) {
            vf_row *r = &ctx->rows[ctx->nrows - 1];
            r->gate = GATE_MISSING;
            r->blessed = e->value;
            r->reg_tol = e->tol;
        }
        if (!ctx->opt->bless)
            ctx->nfail++;
        printf("%s %s.%s: blessed check not produced by this run (blessed value %.15g; %s)\n",
               ctx->opt->bless ? "GONE" : "FAIL", ctx->suite->name, e->id, e->value,
               ctx->opt->bless ? "removed from the baseline" : "re-bless if deliberate");
    }
}

/* Rewrite the baseline from the rows of this run (values, tolerances and this configuration) and
 * print the diff: each value that moved beyond the tolerance that applies to this run, each
 * added, removed or re-tiered row, and the count of values that moved within it. A bless that
 * would change nothing leaves the file alone. Returns 0, or 1 when refused or not written. */
static int bless(vf_ctx *ctx)
{
    const char *name = ctx->suite->name;
    int physics_fail = 0;
    for (int k = 0; k < ctx->nrows; k++) {
        const vf_row *r = &ctx->rows[k];
        physics_fail += !r->info && r->gate != GATE_MISSING &&
                        !(isfinite(r->error) && isfinite(r->tol) && r->error <= r->tol);
    }
    if (physics_fail || ctx->lost_rows) {
        printf("bless %s: refused, %d check%s fail against the reference; %s is unchanged\n",
               name, physics_fail, physics_fail == 1 ? "" : "s", ctx->base_path);
        return 1;
    }
    vf_baseline nb;
    memset(&nb, 0, sizeof nb);
    snprintf(nb.suite, sizeof nb.suite, "%s", name);
    nb.fast = ctx->fast;
    nb.config = ctx->config;
    int same = ctx->has_base && !ctx->mismatch;
    int changed = 0, moved = 0, added = 0, retiered = 0, unchanged = 0;
    int tiers[VF_TIER_FIXED + 1] = {0};
    printf("bless %s%s: %s\n", name, ctx->fast ? " (fast)" : "", ctx->base_path);
    for (int k = 0; k < ctx->nrows; k++) {
        const vf_row *r = &ctx->rows[k];
        if (r->gate == GATE_MISSING || vf_baseline_find(&nb, r->id, -1))
            continue;
        const vf_blessed *old = ctx->has_base ? vf_baseline_find(&ctx->base, r->id, k) : NULL;
        vf_tier tier = r->tier != VF_TIER_AUTO ? r->tier
                       : old && old->tier != VF_TIER_AUTO
                           ? old->tier
                           : vf_tier_auto(r->id, r->measured, r->counts);
        double value = isfinite(r->measured) ? r->measured : NAN;
        double tol = vf_tier_tol(tier, value, r->err_tol, 0);
        double tol_other = vf_tier_tol(tier, value, r->err_tol, 1);
        if (tier == VF_TIER_FIXED) {
            tol = old ? old->tol : NAN;
            tol_other = old ? old->tol_other : NAN;
        }
        if (old) {
            if (old->tier != tier) {
                printf("  %s: tier %s -> %s\n", r->id, vf_tier_name(old->tier), vf_tier_name(tier));
                retiered++;
            }
            /* the diff lists what moved beyond the tolerance that applies to this run */
            double app = same ? tol : tol_other;
            if (old->value == value || (isnan(old->value) && isnan(value)))
                unchanged++;
            else if (vf_blessed_ok(old, app, value))
                moved++;
            else {
                printf("  %s: %.15g -> %.15g (drift %.3g, regression tolerance %.3g)\n", r->id,
                       old->value, value, fabs(value - old->value), app);
                changed++;
            }
        } else {
            if (ctx->has_base)
                printf("  + %s = %.15g (tier %s, tolerance %.3g)\n", r->id, value,
                       vf_tier_name(tier), tol);
            added++;
        }
        tiers[tier]++;
        if (!vf_baseline_add(&nb, r->id, value, tol, tol_other, tier)) {
            vf_baseline_free(&nb);
            printf("bless %s: out of memory; %s is unchanged\n", name, ctx->base_path);
            return 1;
        }
    }
    int removed = ctx->nmissing;
    if (ctx->has_base && same && !changed && !moved && !added && !retiered && !removed) {
        printf("bless %s: no change (%d rows, the same values on the same configuration)\n", name,
               unchanged);
        vf_baseline_free(&nb);
        ctx->blessed_now = 1;
        return 0;
    }
    char msg[1400];
    if (vf_baseline_save(ctx->base_path, &nb, msg, sizeof msg) != 0) {
        printf("bless %s: %s\n", name, msg);
        vf_baseline_free(&nb);
        return 1;
    }
    printf("bless %s: %s %s: %d rows (%d exact, %d iter, %d roundoff, %d plan, %d noise, %d none, "
           "%d fixed); %d values beyond their tolerance, %d added, %d removed, %d re-tiered, %d "
           "moved within their tolerance (not listed)\n",
           name, ctx->has_base ? "rewrote" : "created", ctx->base_path, nb.n,
           tiers[VF_TIER_EXACT], tiers[VF_TIER_ITER], tiers[VF_TIER_ROUNDOFF], tiers[VF_TIER_PLAN],
           tiers[VF_TIER_NOISE], tiers[VF_TIER_NONE], tiers[VF_TIER_FIXED], changed, added,
           removed, retiered, moved);
    vf_baseline_free(&nb);
    ctx->blessed_now = 1;
    return 0;
}

/* Open the suite's baseline (ctx->opt->baselines set). Returns 0, or -1 on a malformed file. */
static int open_baseline(vf_ctx *ctx)
{
    if (vf_baseline_path(ctx->base_path, sizeof ctx->base_path, ctx->opt->baselines,
                         ctx->suite->name, ctx->fast) != 0) {
        fprintf(stderr, "microcontact: baseline path too long\n");
        return -1;
    }
    char msg[1400];
    int rc = vf_baseline_load(ctx->base_path, &ctx->base, msg, sizeof msg);
    if (rc < 0) {
        fprintf(stderr, "microcontact: baseline %s\n", msg);
        return -1;
    }
    ctx->has_base = rc == 0;
    ctx->mismatch = ctx->has_base && !vf_config_same(&ctx->base.config, &ctx->config);
    return 0;
}

int vf_run_suite_opts(const vf_suite *suite, const vf_options *opt)
{
    vf_ctx *ctx = calloc(1, sizeof *ctx);
    if (!ctx) {
        fprintf(stderr, "microcontact: out of memory\n");
        return -1;
    }
    ctx->suite = suite;
    ctx->fast = opt->fast;
    ctx->opt = opt;
    vf_config_current(&ctx->config);
    snprintf(ctx->dir, sizeof ctx->dir, "%s/%s", opt->reports_dir, suite->name);
    if (mkdirs(ctx->dir) != 0) {
        fprintf(stderr, "microcontact: cannot create %s: %s\n", ctx->dir, strerror(errno));
        free(ctx);
        return -1;
    }
    if (opt->baselines && open_baseline(ctx) != 0) {
        free(ctx);
        return -1;
    }
    printf("== suite %s%s: %s\n", suite->name, opt->fast ? " (fast)" : "", suite->title);
    double t0 = mc_clock();
    int rc = suite->run(ctx, opt->fast);
    if (rc != 0)
        vf_fail(ctx, "suite", "the suite stopped early (status %d)", rc);
    double dt = mc_clock() - t0;
    add_missing_rows(ctx);
    /* the gate cannot be skipped: a gated run of a suite without its baseline file fails; the
     * bless below is the explicit act that creates the file */
    if (opt->baselines && !ctx->has_base && !opt->bless)
        vf_fail(ctx, "baseline",
                "no baseline file %s: the suite is not gated; create it deliberately with "
                "make bless SUITES=%s",
                ctx->base_path, suite->name);
    int failures = ctx->nfail + ctx->lost_rows;
    if (ctx->lost_rows)
        fprintf(stderr, "microcontact: out of memory: %d rows of suite %s are missing from its "
                        "report\n", ctx->lost_rows, suite->name);
    if (opt->bless && opt->baselines)
        failures += bless(ctx);
    if (write_report(ctx, dt) != 0) {
        fprintf(stderr, "microcontact: cannot write %s/report.md\n", ctx->dir);
        failures++;
    }
    if (write_result(ctx, dt) != 0) {
        fprintf(stderr, "microcontact: cannot write %s/result.json\n", ctx->dir);
        failures++;
    }
    char gate[1536] = "";
    if (opt->baselines && !ctx->has_base && ctx->blessed_now)
        snprintf(gate, sizeof gate, ", baseline %s created", ctx->base_path);
    else if (opt->baselines && !ctx->has_base)
        snprintf(gate, sizeof gate, ", FAILED: no baseline %s", ctx->base_path);
    else if (opt->baselines)
        snprintf(gate, sizeof gate, ", %d drifted from the baseline, %d not blessed, %d missing",
                 ctx->ndrift, ctx->nnew, ctx->nmissing);
    printf("== suite %s: %d checks, %d failed, %d information rows%s, %.1f s -> %s/report.md\n",
           suite->name, ctx->nrows - ctx->ninfo, ctx->nfail, ctx->ninfo, gate, dt, ctx->dir);
    vf_baseline_free(&ctx->base);
    free(ctx->rows);
    free(ctx);
    return failures;
}

int vf_run_suite(const vf_suite *suite, const char *reports_dir, int fast)
{
    vf_options opt = {.reports_dir = reports_dir, .fast = fast};
    return vf_run_suite_opts(suite, &opt);
}

int vf_run_opts(const vf_options *opt, int nnames, char **names)
{
    int count;
    const vf_suite *all = vf_suites(&count);
    for (int a = 0; a < nnames; a++) {
        int found = 0;
        for (int k = 0; k < count; k++)
            found |= strcmp(all[k].name, names[a]) == 0;
        if (!found) {
            fprintf(stderr, "microcontact verify: unknown suite '%s'; known suites:", names[a]);
            for (int k = 0; k < count; k++)
                fprintf(stderr, " %s", all[k].name);
            fprintf(stderr, "\n");
            return -1;
        }
    }
    int failures = 0;
    for (int k = 0; k < count; k++) {
        int wanted = nnames == 0;
        for (int a = 0; a < nnames; a++)
            wanted |= strcmp(all[k].name, names[a]) == 0;
        if (!wanted)
            continue;
        int f = vf_run_suite_opts(&all[k], opt);
        if (f < 0)
            return -1;
        failures += f;
    }
    return failures;
}

int vf_run(const char *reports_dir, int nnames, char **names, int fast, int list_only)
{
    if (list_only) {
        int count;
        const vf_suite *all = vf_suites(&count);
        for (int k = 0; k < count; k++)
            printf("%-24s %s\n", all[k].name, all[k].title);
        return 0;
    }
    vf_options opt = {.reports_dir = reports_dir, .fast = fast};
    return vf_run_opts(&opt, nnames, names);
}

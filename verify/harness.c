/* harness.c - runs verification suites and writes their reports (see harness.h). */
#include "harness.h"

#include <errno.h>
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
} vf_row;

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
    return 1;
}

int vf_check(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
             double expected, double measured, double tol, vf_kind kind)
{
    double e = row_error(kind, expected, measured);
    /* an infinite (or NaN) tolerance would make a check that cannot fail */
    int pass = isfinite(e) && isfinite(tol) && e <= tol;
    add_row(ctx, id, quantity, reference, expected, measured, tol, e, kind, pass, 0);
    if (!pass)
        ctx->nfail++;
    printf("%s %s.%s: %s = %.6g (reference %.6g, %s %.3g, tolerance %.3g)%s\n",
           pass ? "PASS" : "FAIL", ctx->suite->name, id, quantity, measured, expected,
           kind == VF_REL ? "rel. error" : kind == VF_ABS ? "abs. error" : "value", e, tol,
           isfinite(tol) ? "" : " - a check that cannot fail: record it with vf_info");
    fflush(stdout);
    return pass;
}

void vf_info(vf_ctx *ctx, const char *id, const char *quantity, const char *reference,
             double expected, double measured)
{
    ctx->ninfo +=
        add_row(ctx, id, quantity, reference, expected, measured, NAN, NAN, VF_MAX, 0, 1);
    char ref[48] = "";
    if (!isnan(expected))
        snprintf(ref, sizeof ref, " against %.6g", expected);
    printf("INFO %s.%s: %s = %.6g%s (%s; information, not a check)\n", ctx->suite->name, id,
           quantity, measured, ref, reference);
    fflush(stdout);
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
    fputs(ctx->text, f);
    fprintf(f, "\n## Checks\n\n");
    if (ctx->ninfo)
        fprintf(f, "Rows marked *info* show a measured value for information: no tolerance, never "
                   "a failure, not counted among the checks.\n\n");
    fprintf(f, "| id | quantity | reference | expected | measured | error | tolerance | result "
               "|\n|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < ctx->nrows; k++) {
        const vf_row *r = &ctx->rows[k];
        char e[32], m[32], er[32], t[32];
        fmt_num(e, sizeof e, r->expected);
        fmt_num(m, sizeof m, r->measured);
        fmt_num(er, sizeof er, r->error);
        fmt_num(t, sizeof t, r->tol);
        if (r->info) {
            fprintf(f, "| %s | %s | %s | %s | %s | - | - | info |\n", r->id, r->quantity,
                    r->reference, isnan(r->expected) ? "-" : e, m);
            continue;
        }
        fprintf(f, "| %s | %s | %s | %s | %s | %s %s | %s | %s |\n", r->id, r->quantity,
                r->reference, e, m, er,
                r->kind == VF_REL ? "(rel.)" : r->kind == VF_ABS ? "(abs.)" : "(value)", t,
                r->pass ? "PASS" : "**FAIL**");
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

int vf_run_suite(const vf_suite *suite, const char *reports_dir, int fast)
{
    vf_ctx *ctx = calloc(1, sizeof *ctx);
    if (!ctx) {
        fprintf(stderr, "microcontact: out of memory\n");
        return -1;
    }
    ctx->suite = suite;
    ctx->fast = fast;
    snprintf(ctx->dir, sizeof ctx->dir, "%s/%s", reports_dir, suite->name);
    if (mkdirs(ctx->dir) != 0) {
        fprintf(stderr, "microcontact: cannot create %s: %s\n", ctx->dir, strerror(errno));
        free(ctx);
        return -1;
    }
    printf("== suite %s%s: %s\n", suite->name, fast ? " (fast)" : "", suite->title);
    double t0 = mc_clock();
    int rc = suite->run(ctx, fast);
    if (rc != 0)
        vf_fail(ctx, "suite", "the suite stopped early (status %d)", rc);
    double dt = mc_clock() - t0;
    int failures = ctx->nfail + ctx->lost_rows;
    if (ctx->lost_rows)
        fprintf(stderr, "microcontact: out of memory: %d rows of suite %s are missing from its "
                        "report\n", ctx->lost_rows, suite->name);
    if (write_report(ctx, dt) != 0) {
        fprintf(stderr, "microcontact: cannot write %s/report.md\n", ctx->dir);
        failures++;
    }
    printf("== suite %s: %d checks, %d failed, %d information rows, %.1f s -> %s/report.md\n",
           suite->name, ctx->nrows - ctx->ninfo, ctx->nfail, ctx->ninfo, dt, ctx->dir);
    free(ctx->rows);
    free(ctx);
    return failures;
}

int vf_run(const char *reports_dir, int nnames, char **names, int fast, int list_only)
{
    int count;
    const vf_suite *all = vf_suites(&count);
    if (list_only) {
        for (int k = 0; k < count; k++)
            printf("%-24s %s\n", all[k].name, all[k].title);
        return 0;
    }
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
        int f = vf_run_suite(&all[k], reports_dir, fast);
        if (f < 0)
            return -1;
        failures += f;
    }
    return failures;
}

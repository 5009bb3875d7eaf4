/* baseline.c - blessed values of the regression gate (see baseline.h). */
#include "baseline.h"

#include <ctype.h>
#include <fftw3.h>
#include <jansson.h>
#include <omp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Tier tolerances: |new - blessed| <= REL |blessed| + FLOOR err (err: the physics tolerance of a
 * check whose value is an error that must stay small; 0 for quantities, see baseline.h).
 * Same configuration (threads, FFTW, CPU): measured, every fast suite repeats bit for bit - two
 *   runs, and an -O1 AddressSanitizer build against the -O2 one, differ in no value. SAME_REL
 *   1e-12 (a few thousand eps) and SAME_FLOOR 1e-6 leave a margin for a compiler that contracts
 *   or reorders differently, and nothing more: any change of the code that moves a number is
 *   seen.
 * Another configuration: PLAN_REL 1e-9 and PLAN_FLOOR 1e-3. Measured: 1 against 2 threads moves
 *   only the OpenMP reductions of min_eval_depth, by <= 2.4e-13 relative on quantities and by
 *   <= 2e-4 of PLAN_FLOOR err on errors near round-off; a perturbed iteration path (seen while
 *   the contact solver was being changed elsewhere) moved p_max, approaches and loads of the
 *   stability scenes by < 1e-9 relative. 1e-9 is also below every solver tolerance of the
 *   suites (1e-8 .. 1e-11 on the load), so a converged value moved by a different FFT rounding
 *   stays inside it, while a change of the method does not.
 * NOISE on another configuration: NOISE_FLOOR 0.5. The same perturbed iteration path moved the
 *   stopping residuals (KKT measures) of the stability scenes by up to 0.19 of their physics
 *   tolerance, round-off consistency measures by up to 0.01 and differences of two converged
 *   solves by up to 0.04: half the tolerance keeps a 2.6x margin and still catches a jump by an
 *   order of magnitude. NOISE_REL 1e-6 for a quantity (not an error) declared noise.
 * ROUNDOFF: no FFT or thread touches the value, so the same tolerance everywhere.
 * ITER: exact on the same configuration; ITER_OTHER 1 on another (the last digits move the
 *   iterate at which the stopping test passes by at most one, for a test not sitting on its
 *   threshold). */
#define SAME_REL 1e-12
#define SAME_FLOOR 1e-6
#define PLAN_REL 1e-9
#define PLAN_FLOOR 1e-3
#define NOISE_REL 1e-6
#define NOISE_FLOOR 0.5
#define ITER_OTHER 1.0

static const char *tier_names[] = {"auto",  "exact", "iter", "roundoff",
                                   "plan",  "noise", "none", "fixed"};

const char *vf_tier_name(vf_tier tier)
{
    return tier >= VF_TIER_AUTO && tier <= VF_TIER_FIXED ? tier_names[tier] : "?";
}

vf_tier vf_tier_from_name(const char *s)
{
    for (int t = VF_TIER_EXACT; t <= VF_TIER_FIXED; t++)
        if (!strcmp(s, tier_names[t]))
            return (vf_tier)t;
    return VF_TIER_AUTO;
}

double vf_tier_tol(vf_tier tier, double v, double err, int other)
{
    double a = isfinite(v) ? fabs(v) : 0, f = isfinite(err) ? fabs(err) : 0;
    double same = SAME_REL * a + SAME_FLOOR * f;
    switch (tier) {
    case VF_TIER_EXACT: return 0;
    case VF_TIER_ITER: return other ? ITER_OTHER : 0;
    case VF_TIER_ROUNDOFF: return same;
    case VF_TIER_AUTO: /* callers resolve auto first; treat as plan */
    case VF_TIER_PLAN: return other ? PLAN_REL * a + PLAN_FLOOR * f : same;
    case VF_TIER_NOISE: return other ? NOISE_REL * a + NOISE_FLOOR * f : same;
    case VF_TIER_NONE: return NAN;
    case VF_TIER_FIXED: return NAN; /* the file's own tolerances: callers keep them */
    }
    return NAN;
}

static int is_integer(double v) { return isfinite(v) && fabs(v) < 2147483648.0 && v == rint(v); }

/* case-insensitive "iter" in s (iterations, iters, outer_iter) */
static int names_iterations(const char *s)
{
    static const char key[] = "iter";
    for (; s && *s; s++) {
        size_t k = 0;
        while (key[k] && s[k] && tolower((unsigned char)s[k]) == key[k])
            k++;
        if (!key[k])
            return 1;
    }
    return 0;
}

vf_tier vf_tier_auto(const char *id, double v, int counts)
{
    if (!counts || !is_integer(v))
        return VF_TIER_PLAN;
    const char *last = strrchr(id, '.'); /* ids like "iter_limit.fft.cg.finite": the last part */
    return names_iterations(last ? last + 1 : id) ? VF_TIER_ITER : VF_TIER_EXACT;
}

int vf_blessed_ok(const vf_blessed *e, double tol, double value)
{
    if (isnan(tol))
        return 1;
    if (!isfinite(e->value) || !isfinite(value))
        return !isfinite(e->value) && !isfinite(value);
    return fabs(value - e->value) <= tol;
}

void vf_config_current(vf_config *c)
{
    memset(c, 0, sizeof *c);
    c->threads = omp_get_max_threads();
    snprintf(c->fftw, sizeof c->fftw, "%s", fftw_version);
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        const char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) != 0 || !colon)
            continue;
        colon += 1 + strspn(colon + 1, " \t");
        snprintf(c->cpu, sizeof c->cpu, "%.*s", (int)strcspn(colon, "\r\n"), colon);
        break;
    }
    fclose(f);
}

int vf_config_same(const vf_config *a, const vf_config *b)
{
    return a->threads == b->threads && !strcmp(a->fftw, b->fftw) && !strcmp(a->cpu, b->cpu);
}

int vf_baseline_path(char *buf, size_t len, const char *dir, const char *suite, int fast)
{
    int w = snprintf(buf, len, "%s/%s%s.json", dir, suite, fast ? ".fast" : "");
    return w < 0 || (size_t)w >= len ? -1 : 0;
}

vf_blessed *vf_baseline_find(vf_baseline *b, const char *id, int hint)
{
    if (hint >= 0 && hint < b->n && !strcmp(b->v[hint].id, id))
        return &b->v[hint];
    for (int k = 0; k < b->n; k++)
        if (!strcmp(b->v[k].id, id))
            return &b->v[k];
    return NULL;
}

vf_blessed *vf_baseline_add(vf_baseline *b, const char *id, double value, double tol,
                            double tol_other, vf_tier tier)
{
    if (b->n == b->cap) {
        int cap = b->cap ? 2 * b->cap : 64;
        vf_blessed *grown = realloc(b->v, (size_t)cap * sizeof *grown);
        if (!grown)
            return NULL;
        b->v = grown;
        b->cap = cap;
    }
    vf_blessed *e = &b->v[b->n++];
    memset(e, 0, sizeof *e);
    snprintf(e->id, sizeof e->id, "%s", id);
    e->value = isfinite(value) ? value : NAN;
    e->tol = tol;
    e->tol_other = tol_other;
    e->tier = tier;
    return e;
}

void vf_baseline_free(vf_baseline *b)
{
    free(b->v);
    memset(b, 0, sizeof *b);
}

static double json_num(const json_t *j)
{
    return json_is_number(j) ? json_number_value(j) : NAN;
}

int vf_baseline_load(const char *path, vf_baseline *b, char *msg, size_t msglen)
{
    memset(b, 0, sizeof *b);
    FILE *f = fopen(path, "r");
    if (!f)
        return 1;
    json_error_t jerr;
    json_t *root = json_loadf(f, 0, &jerr);
    fclose(f);
    if (!root) {
        snprintf(msg, msglen, "%s:%d: %s", path, jerr.line, jerr.text);
        return -1;
    }
    json_t *checks = json_object_get(root, "checks");
    if (!json_is_object(checks)) {
        snprintf(msg, msglen, "%s: no \"checks\" object", path);
        json_decref(root);
        return -1;
    }
    snprintf(b->suite, sizeof b->suite, "%s",
             json_is_string(json_object_get(root, "suite"))
                 ? json_string_value(json_object_get(root, "suite"))
                 : "");
    const json_t *var = json_object_get(root, "variant");
    b->fast = json_is_string(var) && !strcmp(json_string_value(var), "fast");
    b->config.threads = (int)json_integer_value(json_object_get(root, "threads"));
    const json_t *fw = json_object_get(root, "fftw"), *cpu = json_object_get(root, "cpu");
    snprintf(b->config.fftw, sizeof b->config.fftw, "%s",
             json_is_string(fw) ? json_string_value(fw) : "");
    snprintf(b->config.cpu, sizeof b->config.cpu, "%s",
             json_is_string(cpu) ? json_string_value(cpu) : "");
    /* json_object_foreach visits keys in file order (jansson keeps insertion order) */
    const char *key;
    json_t *val;
    json_object_foreach(checks, key, val)
    {
        const json_t *tier = json_object_get(val, "tier");
        if (!json_is_object(val) || !json_object_get(val, "value") ||
            !json_object_get(val, "tol")) {
            snprintf(msg, msglen, "%s: check \"%s\" needs \"value\" and \"tol\"", path, key);
            json_decref(root);
            vf_baseline_free(b);
            return -1;
        }
        double tol = json_num(json_object_get(val, "tol"));
        const json_t *jo = json_object_get(val, "tol_other");
        double tol_other = jo ? json_num(jo) : tol;
        if ((!isnan(tol) && !(tol >= 0)) || (!isnan(tol_other) && !(tol_other >= 0))) {
            snprintf(msg, msglen, "%s: check \"%s\": tol and tol_other must be >= 0 or null",
                     path, key);
            json_decref(root);
            vf_baseline_free(b);
            return -1;
        }
        vf_tier t = json_is_string(tier) ? vf_tier_from_name(json_string_value(tier)) : VF_TIER_AUTO;
        if (!vf_baseline_add(b, key, json_num(json_object_get(val, "value")), tol, tol_other, t)) {
            snprintf(msg, msglen, "%s: out of memory", path);
            json_decref(root);
            vf_baseline_free(b);
            return -1;
        }
    }
    json_decref(root);
    return 0;
}

/* A JSON string (ids and names are plain ASCII; escape what JSON requires anyway). */
static void put_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

/* %.17g round-trips a double; non-finite values are null. */
static void put_number(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.17g", v);
    else
        fputs("null", f);
}

int vf_baseline_save(const char *path, const vf_baseline *b, char *msg, size_t msglen)
{
    char tmp[2048];
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *f = fopen(tmp, "w");
    if (!f) {
        snprintf(msg, msglen, "cannot write %s", tmp);
        return -1;
    }
    fputs("{\"suite\": ", f);
    put_string(f, b->suite);
    fprintf(f, ", \"variant\": \"%s\", \"threads\": %d, \"fftw\": ", b->fast ? "fast" : "full",
            b->config.threads);
    put_string(f, b->config.fftw);
    fputs(",\n \"cpu\": ", f);
    put_string(f, b->config.cpu);
    fputs(",\n \"checks\": {\n", f);
    for (int k = 0; k < b->n; k++) {
        const vf_blessed *e = &b->v[k];
        fputs("  ", f);
        put_string(f, e->id);
        fputs(": {\"value\": ", f);
        put_number(f, e->value);
        fputs(", \"tol\": ", f);
        put_number(f, e->tol);
        fputs(", \"tol_other\": ", f);
        put_number(f, e->tol_other);
        fprintf(f, ", \"tier\": \"%s\"}%s\n", vf_tier_name(e->tier), k + 1 < b->n ? "," : "");
    }
    fputs(" }}\n", f);
    int bad = ferror(f) | (fclose(f) != 0);
    if (bad || rename(tmp, path) != 0) {
        remove(tmp);
        snprintf(msg, msglen, "cannot write %s", path);
        return -1;
    }
    return 0;
}

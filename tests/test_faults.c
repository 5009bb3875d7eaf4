/* test_faults.c - robustness: injected allocation failures through a whole run, into the contact
 * solver and the operator plan directly, and regressions of bad-input bugs. (Inputs that crash a
 * fuzzer are replayed by test_fuzz_replay.c from tests/fuzz/regressions/.)
 *
 * Fault injection (alloc.h, after SQLite's sqlite3FaultSim): for n = 1, 2, ... the nth allocation
 * from the start of the attempt fails (only that one). Every attempt must end in MC_ERR_NOMEM at
 * the stage that owned the allocation - never a crash, never MC_OK or a later stage after a
 * failed allocation - free everything it took (the suite runs under ASan/LSan in `make
 * check-sanitize`) and leave the output directory without result files, staging directories or
 * probe files. The first n that does not fail is the attempt in which no allocation was refused:
 * it must reproduce, file for file, a reference run made without injection, and it must come
 * exactly after the last allocation of that reference run (so every allocation was tried).
 * Runs use solver threads = 1, which makes them deterministic (bitwise equal results).
 */
#include <check.h>
#include <dirent.h>
#include <jansson.h>
#include <math.h>
#include <malloc.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"
#include "core/threads.h"
#include "case/case.h"
#include "contact/contact.h"
#include "io/npy.h"
#include "operator/operator.h"
#include "pipeline/output.h"
#include "pipeline/pipeline.h"
#include "test_util.h"

/* A loop that tries every allocation must end; runs of these small scenes allocate a few
 * hundred times (a guard against an injection that never stops failing). */
#define MAX_ATTEMPTS 20000L

/* ---- small file helpers ------------------------------------------------------------------- */

static char *path_join(const char *a, const char *b)
{
    static char buf[4][1024];
    static int k;
    char *p = buf[k++ % 4];
    snprintf(p, sizeof buf[0], "%s/%s", a, b);
    return p;
}

/* Names in dir, sorted, each followed by '\n' ("" for an empty directory, NULL if it does not
 * exist). Caller frees. */
static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

static char *listing(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return NULL;
    char *names[256];
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        ck_assert_int_lt(n, 256);
        names[n++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], cmp_str);
    size_t len = 1;
    for (int i = 0; i < n; i++)
        len += strlen(names[i]) + 1;
    char *s = malloc(len);
    ck_assert_ptr_nonnull(s);
    s[0] = '\0';
    for (int i = 0; i < n; i++) {
        strcat(s, names[i]);
        strcat(s, "\n");
        free(names[i]);
    }
    return s;
}

static unsigned char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    ck_assert_msg(f != NULL, "cannot open %s", path);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)n + 1);
    ck_assert_ptr_nonnull(b);
    ck_assert_uint_eq(fread(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *len = (size_t)n;
    return b;
}

/* summary.json of two runs agree in everything but the timings (wall-clock). */
static void assert_same_summary(const char *a, const char *b)
{
    json_error_t je;
    json_t *ja = json_load_file(a, 0, &je);
    ck_assert_msg(ja != NULL, "%s: %s", a, je.text);
    json_t *jb = json_load_file(b, 0, &je);
    ck_assert_msg(jb != NULL, "%s: %s", b, je.text);
    json_object_del(ja, "timing");
    json_object_del(jb, "timing");
    ck_assert_msg(json_equal(ja, jb), "%s and %s differ beyond the timings", a, b);
    json_decref(ja);
    json_decref(jb);
}

/* Every file of dir equals the reference directory's (bytes; summary.json without timings). */
static void assert_same_output(const char *dir, const char *ref)
{
    char *l = listing(dir), *lr = listing(ref);
    ck_assert_ptr_nonnull(l);
    ck_assert_ptr_nonnull(lr);
    ck_assert_str_eq(l, lr);
    for (char *p = l; *p;) {
        char *nl = strchr(p, '\n');
        *nl = '\0';
        if (!strcmp(p, "summary.json")) {
            assert_same_summary(path_join(dir, p), path_join(ref, p));
        } else {
            size_t na, nb;
            unsigned char *a = slurp(path_join(dir, p), &na), *b = slurp(path_join(ref, p), &nb);
            ck_assert_msg(na == nb && memcmp(a, b, na) == 0, "%s differs from the reference", p);
            free(a);
            free(b);
        }
        p = nl + 1;
    }
    free(l);
    free(lr);
}

/* ---- the whole run under injection -------------------------------------------------------- */

enum { STAGE_PARSE, STAGE_PREPARE, STAGE_PIPELINE, STAGE_OUTPUT, NSTAGES };
static const char *const stage_name[NSTAGES] = {"case parse", "output prepare", "pipeline",
                                                "output write"};

/* What `microcontact run` does: parse, prepare DIR, run, write. *stage = the last stage entered.
 * Returns the first error, or the pipeline's status (MC_OK or MC_NOT_CONVERGED). */
static int run_case(const char *text, const char *base, const char *dir, mc_results *res,
                    mc_error *err, int *stage)
{
    static mc_scene sc;
    *stage = STAGE_PARSE;
    int rc = mc_case_parse_text(text, "faults.ini", base, 0, NULL, &sc, err);
    if (rc != MC_OK)
        return rc;
    *stage = STAGE_PREPARE;
    if ((rc = mc_output_prepare(dir, err)) != MC_OK)
        return rc;
    *stage = STAGE_PIPELINE;
    rc = mc_pipeline_run(&sc, res, err);
    if (rc != MC_OK && rc != MC_NOT_CONVERGED)
        return rc;
    *stage = STAGE_OUTPUT;
    int wrc = mc_output_write(dir, &sc, res, err);
    return wrc != MC_OK ? wrc : rc;
}

typedef struct {
    const char *name;
    const char *text; /* case text; relative paths resolve against the fixture directory */
    int stages;       /* bit mask of the stages that must have seen an injected failure */
    int stress;       /* the stress stage runs: the results include von_mises.npy */
} fault_case;

#define MESH16 "[mesh]\nnx = 16\nny = 12\ndx = 2 um\ndy = 3 um\n"
#define ALL_STAGES ((1 << STAGE_PARSE) | (1 << STAGE_PIPELINE) | (1 << STAGE_OUTPUT))

static const fault_case fault_cases[] = {
    {"sphere, gaussian roughness, cg, fft, vtk",
     MESH16 "[geometry]\nshape = sphere\nradius = 5 mm\n"
            "[roughness]\ntype = gaussian\nrq = 0.05 um\ncorrelation_x = 6 um\nseed = 3\n"
            "[load]\nforce = 0.5 N\n[solver]\nmethod = cg\noperator = fft\nthreads = 1\n"
            "[output]\nvtk = yes\n",
     ALL_STAGES, 0},
    {"ellipsoid, self-affine roughness, pk, direct, lubricant and cap",
     MESH16 "[geometry]\nshape = ellipsoid\nradius_x = 4 mm\nradius_y = 8 mm\n"
            "[roughness]\ntype = self_affine\nrq = 0.02 um\nhurst = 0.7\n"
            "[body2]\nrigid = yes\n"
            "[load]\nforce = 0.3 N\nlubricant_pressure = 5 MPa\npressure_cap = 4 GPa\n"
            "[solver]\nmethod = pk\noperator = direct\nthreads = 1\n",
     ALL_STAGES, 0},
    {"cylinder, periodic y, force per length, active-set, roughness file",
     "[mesh]\nnx = 12\nny = 6\ndx = 3 um\nperiodic_y = yes\n"
     "[geometry]\nshape = cylinder\nradius = 5 mm\n"
     "[roughness]\ntype = file\nfile = heights.txt\n"
     "[load]\nforce_per_length = 50 N/mm\n[solver]\nmethod = active-set\nthreads = 1\n",
     ALL_STAGES, 0},
    {"approach control, periodic x, cg",
     "[mesh]\nnx = 16\nny = 8\ndx = 2 um\nperiodic_x = yes\n"
     "[geometry]\nshape = sphere\nradius = 5 mm\n"
     "[load]\napproach = 0.05 um\n[solver]\nthreads = 1\n",
     ALL_STAGES, 0},
    {"prescribed pressure from .npy, with [stress]",
     MESH16 "[load]\npressure_file = pressure.npy\n[solver]\nthreads = 1\n"
            "[stress]\ndepth_max = 20 um\nlayers = 4\n[output]\nvtk = yes\n",
     ALL_STAGES, 1},
    {"sphere, gaussian roughness, [stress] with friction",
     MESH16 "[geometry]\nshape = sphere\nradius = 5 mm\n"
            "[roughness]\ntype = gaussian\nrq = 0.05 um\ncorrelation_x = 6 um\n"
            "[load]\nforce = 0.5 N\n[solver]\nthreads = 1\n"
            "[stress]\ndepths = 0.5 um, 2 um, 8 um\nfriction = 0.1\nkernel = patch\n",
     ALL_STAGES, 1},
    {"coarse start and contact box (100 x 96, small contact), roughness, [stress]",
     "[mesh]\nnx = 100\nny = 96\ndx = 1 um\n[geometry]\nshape = sphere\nradius = 5 mm\n"
     "[roughness]\ntype = gaussian\nrq = 0.01 um\ncorrelation_x = 4 um\n"
     "[load]\nforce = 0.05 N\n[solver]\nthreads = 1\n"
     "[stress]\ndepth_max = 10 um\nlayers = 3\n",
     ALL_STAGES, 1},
};
#define NFAULT_CASES ((int)(sizeof fault_cases / sizeof fault_cases[0]))

/* The fixtures the cases read, written once (without injection) into a fresh directory. */
static const char *fixtures(void)
{
    static char dir[256];
    if (dir[0])
        return dir;
    snprintf(dir, sizeof dir, "%s", test_tmpdir());
    FILE *f = fopen(path_join(dir, "heights.txt"), "w");
    ck_assert_ptr_nonnull(f);
    for (int j = 0; j < 6; j++) {
        for (int i = 0; i < 12; i++)
            fprintf(f, "%s%.3e", i ? " " : "", 1e-8 * ((i * 7 + j * 3) % 5));
        fputc('\n', f);
    }
    ck_assert_int_eq(fclose(f), 0);
    double p[16 * 12];
    for (int j = 0; j < 12; j++)
        for (int i = 0; i < 16; i++) {
            double x = (i - 7.5) / 6.0, y = (j - 5.5) / 4.0, r2 = x * x + y * y;
            p[j * 16 + i] = r2 < 1 ? 1e9 * sqrt(1 - r2) : 0.0; /* a Hertz-like dome, Pa */
        }
    size_t shape[2] = {12, 16};
    mc_error err = {0};
    ck_assert_msg(mc_npy_write(path_join(dir, "pressure.npy"), p, 2, shape, &err) == MC_OK, "%s",
                  err.msg);
    return dir;
}

START_TEST(test_whole_run)
{
    const fault_case *fc = &fault_cases[_i];
    const char *base = fixtures();
    const char *tmp = test_tmpdir();
    char ref[512], out[512];
    snprintf(ref, sizeof ref, "%s/ref", tmp);
    snprintf(out, sizeof out, "%s/out", tmp);

    /* the reference: no injection */
    mc_results res;
    memset(&res, 0, sizeof res);
    mc_error err = {0};
    int stage;
    long allocs0 = mc_alloc_count();
    int rc = run_case(fc->text, base, ref, &res, &err, &stage);
    long ref_allocs = mc_alloc_count() - allocs0;
    ck_assert_msg(rc == MC_OK, "%s: reference run failed in %s: %s", fc->name, stage_name[stage],
                  err.msg);
    ck_assert_msg((res.nlayers > 0) == fc->stress, "%s: %d stress layers", fc->name, res.nlayers);
    mc_results_free(&res);

    int seen = 0; /* stages that met an injected failure */
    long n;
    for (n = 1; n <= MAX_ATTEMPTS; n++) {
        memset(&res, 0, sizeof res);
        mc_error e = {0};
        long injected = mc_alloc_injected();
        mc_alloc_fail_at(n);
        rc = run_case(fc->text, base, out, &res, &e, &stage);
        mc_alloc_fail_at(0);
        int fired = mc_alloc_injected() != injected;
        mc_results_free(&res);
        if (!fired) {
            ck_assert_msg(rc == MC_OK, "%s: n = %ld, no injected failure, yet %s failed: %s",
                          fc->name, n, stage_name[stage], e.msg);
            break;
        }
        ck_assert_msg(rc == MC_ERR_NOMEM, "%s: allocation %ld failed in %s, status %s: %s",
                      fc->name, n, stage_name[stage], mc_status_name((mc_status)rc), e.msg);
        ck_assert_msg(e.code == MC_ERR_NOMEM && e.msg[0] != '\0', "%s: n = %ld: no message",
                      fc->name, n);
        seen |= 1 << stage;
        char *l = listing(out);
        ck_assert_msg(l == NULL || l[0] == '\0',
                      "%s: allocation %ld failed in %s and left in the output directory:\n%s",
                      fc->name, n, stage_name[stage], l);
        free(l);
    }
    ck_assert_msg(n == ref_allocs + 1,
                  "%s: the first attempt without a failure is n = %ld, but the reference run "
                  "allocated %ld times",
                  fc->name, n, ref_allocs);
    ck_assert_msg((seen & fc->stages) == fc->stages, "%s: stages that met a failure: mask %d",
                  fc->name, seen);
    assert_same_output(out, ref);
}
END_TEST

/* ---- the contact solver and the operator plan, directly ------------------------------------ */

/* Sphere-on-flat problems for the solver tests: small grids for every method, and a grid large
 * enough (both axes >= MC_COARSEN_MIN) with a small contact, so that cg starts from the coarse
 * grid's solution and then solves on the contact's bounding box (contact.h), both of which plan
 * operators and solvers of their own. */
typedef struct {
    mc_contact_method method;
    int nx, ny;
    double load; /* N; with R = 5 mm, E* = 115 GPa: contact radius ~ 19 um at 0.2 N */
    double d;    /* cell size, m */
} contact_case;

static const contact_case contact_cases[] = {
    {MC_METHOD_CG, 24, 20, 0.2, 2e-6},
    {MC_METHOD_PK, 24, 20, 0.2, 2e-6},
    {MC_METHOD_ACTIVE_SET, 24, 20, 0.2, 2e-6},
    {MC_METHOD_CG, MC_COARSEN_MIN + 4, MC_COARSEN_MIN, 0.05, 1e-6},
};
#define NCONTACT_CASES ((int)(sizeof contact_cases / sizeof contact_cases[0]))
#define CONTACT_ESTAR 1.15e11 /* Pa, steel on steel */

static char sentinel; /* an address a failed create must overwrite with NULL */

/* Operator, gap and options of contact case k; h has nx*ny values (caller frees). */
static void contact_setup(int k, mc_operator **K, double **h, mc_contact_options *opt)
{
    const contact_case *cc = &contact_cases[k];
    mc_grid g = {cc->nx, cc->ny, cc->d, cc->d, 0, 0};
    mc_error err = {0};
    ck_assert_msg(mc_operator_plan_love(&g, CONTACT_ESTAR, MC_BACKEND_FFT, K, &err) == MC_OK, "%s",
                  err.msg);
    *h = malloc(sizeof **h * mc_grid_cells(&g));
    ck_assert_ptr_nonnull(*h);
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++) {
            double x = mc_grid_x(&g, i), y = mc_grid_y(&g, j);
            (*h)[j * g.nx + i] = (x * x + y * y) / (2 * 5e-3);
        }
    *opt = (mc_contact_options){.method = cc->method, .tolerance = 1e-9, .max_iterations = 500,
                                .estar = CONTACT_ESTAR};
}

START_TEST(test_contact_create)
{
    /* Every allocation of mc_contact_create (workspaces, preconditioner, the coarse grid's
     * operator and solver for cg) fails in turn: NOMEM, *out NULL, nothing leaked; then the
     * solver made without a failure solves exactly as one made before. */
    mc_threads_scope threads;
    mc_threads_begin(1, &threads);
    const contact_case *cc = &contact_cases[_i];
    const size_t n = (size_t)cc->nx * (size_t)cc->ny;
    mc_operator *K;
    double *h;
    mc_contact_options opt;
    contact_setup(_i, &K, &h, &opt);
    double *p_ref = calloc(n, sizeof *p_ref), *p = calloc(n, sizeof *p);
    ck_assert(p_ref && p);
    mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                               .load = cc->load};
    mc_contact_summary sum_ref, sum;
    mc_error err = {0};

    mc_contact_solver *s = NULL;
    long allocs0 = mc_alloc_count();
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    long ref_allocs = mc_alloc_count() - allocs0;
    ck_assert_msg(mc_contact_solve(s, &prob, p_ref, NULL, NULL, &sum_ref, &err) == MC_OK, "%s",
                  err.msg);
    mc_contact_destroy(&s);
    ck_assert_ptr_null(s);

    long k;
    for (k = 1; k <= MAX_ATTEMPTS; k++) {
        mc_error e = {0};
        long injected = mc_alloc_injected();
        s = (mc_contact_solver *)(void *)&sentinel;
        mc_alloc_fail_at(k);
        int rc = mc_contact_create(K, &opt, &s, &e);
        mc_alloc_fail_at(0);
        if (mc_alloc_injected() == injected) {
            ck_assert_int_eq(rc, MC_OK);
            break;
        }
        ck_assert_msg(rc == MC_ERR_NOMEM, "%s %d x %d: allocation %ld: status %d: %s",
                      mc_contact_method_name(opt.method), cc->nx, cc->ny, k, rc, e.msg);
        ck_assert_ptr_null(s);
    }
    ck_assert_int_eq(k, ref_allocs + 1);
    ck_assert_int_gt(ref_allocs, 2); /* the loop went through several allocations */
    ck_assert_msg(mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(sum.iterations, sum_ref.iterations);
    ck_assert_mem_eq(p, p_ref, n * sizeof *p);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    free(h);
    free(p);
    free(p_ref);
    mc_threads_end(&threads);
}
END_TEST

START_TEST(test_contact_solve)
{
    /* A solve allocates too (contact.h says the solver "allocates every workspace once"): the cg
     * and pk preconditioner plans and caches an FFT for each new size of the contact's bounding
     * box (precond.c plan_for), and cg plans a box-sized operator when it restricts the solve to
     * the contact's box. Every allocation of a first solve fails in turn, on a fresh solver each
     * time: NOMEM, and the same solver then solves again (without injection) exactly as the
     * reference, so a failed solve leaves it usable. */
    mc_threads_scope threads;
    mc_threads_begin(1, &threads);
    const contact_case *cc = &contact_cases[_i];
    const size_t n = (size_t)cc->nx * (size_t)cc->ny;
    mc_operator *K;
    double *h;
    mc_contact_options opt;
    contact_setup(_i, &K, &h, &opt);
    double *p_ref = calloc(n, sizeof *p_ref), *p = calloc(n, sizeof *p);
    double *u = calloc(n, sizeof *u), *gap = calloc(n, sizeof *gap);
    ck_assert(p_ref && p && u && gap);
    mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                               .load = cc->load};
    mc_contact_summary sum_ref, sum;
    mc_error err = {0};
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    long allocs0 = mc_alloc_count();
    ck_assert_msg(mc_contact_solve(s, &prob, p_ref, NULL, NULL, &sum_ref, &err) == MC_OK, "%s",
                  err.msg);
    long ref_allocs = mc_alloc_count() - allocs0;
    if (cc->nx >= MC_COARSEN_MIN && cc->ny >= MC_COARSEN_MIN) /* the paths this case is for */
        ck_assert_msg(mc_contact_last_coarse_applies(s) > 0 && mc_contact_last_box_cells(s) > 0,
                      "no coarse start (%ld applies) or no box (%ld cells)",
                      mc_contact_last_coarse_applies(s), mc_contact_last_box_cells(s));
    mc_contact_destroy(&s);

    long k;
    for (k = 1; k <= MAX_ATTEMPTS; k++) {
        mc_error e = {0};
        ck_assert_int_eq(mc_contact_create(K, &opt, &s, &e), MC_OK);
        long injected = mc_alloc_injected();
        mc_alloc_fail_at(k);
        int rc = mc_contact_solve(s, &prob, p, u, gap, &sum, &e);
        mc_alloc_fail_at(0);
        int fired = mc_alloc_injected() != injected;
        if (fired) {
            ck_assert_msg(rc == MC_ERR_NOMEM, "%s %d x %d: allocation %ld of the solve: "
                          "status %d: %s", mc_contact_method_name(opt.method), cc->nx, cc->ny,
                          k, rc, e.msg);
            mc_error_clear(&e);
            rc = mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &e);
        }
        ck_assert_msg(rc == MC_OK, "%s: k = %ld: %s", mc_contact_method_name(opt.method), k,
                      e.msg);
        ck_assert_int_eq(sum.iterations, sum_ref.iterations);
        ck_assert_mem_eq(p, p_ref, n * sizeof *p);
        mc_contact_destroy(&s);
        if (!fired)
            break;
    }
    ck_assert_int_eq(k, ref_allocs + 1);
    mc_operator_destroy(&K);
    free(h);
    free(p);
    free(p_ref);
    free(u);
    free(gap);
    mc_threads_end(&threads);
}
END_TEST

static const struct {
    mc_backend b;
    int px, py;
} plans[] = {{MC_BACKEND_FFT, 0, 0},    {MC_BACKEND_FFT, 1, 0},    {MC_BACKEND_FFT, 0, 1},
             {MC_BACKEND_FFT, 1, 1},    {MC_BACKEND_DIRECT, 0, 0}, {MC_BACKEND_DIRECT, 1, 1}};

START_TEST(test_operator_plan)
{
    /* Every allocation of mc_operator_plan_love (conv engine, buffers, kernel table, spectra)
     * fails in turn: NOMEM and *out NULL; the plan made without a failure applies exactly as a
     * plan made before. */
    mc_threads_scope threads;
    mc_threads_begin(1, &threads);
    mc_grid g = {17, 10, 1e-6, 1.5e-6, plans[_i].px, plans[_i].py};
    size_t ncell = mc_grid_cells(&g);
    double in[17 * 10], u_ref[17 * 10], u[17 * 10];
    test_random_field(in, ncell, 42);
    mc_error err = {0};
    mc_operator *op = NULL;
    long allocs0 = mc_alloc_count();
    ck_assert_int_eq(mc_operator_plan_love(&g, 1e11, plans[_i].b, &op, &err), MC_OK);
    long ref_allocs = mc_alloc_count() - allocs0;
    mc_operator_apply(op, in, u_ref);
    mc_operator_destroy(&op);

    long n;
    for (n = 1; n <= MAX_ATTEMPTS; n++) {
        mc_error e = {0};
        long injected = mc_alloc_injected();
        op = (mc_operator *)(void *)&sentinel;
        mc_alloc_fail_at(n);
        int rc = mc_operator_plan_love(&g, 1e11, plans[_i].b, &op, &e);
        mc_alloc_fail_at(0);
        if (mc_alloc_injected() == injected) {
            ck_assert_int_eq(rc, MC_OK);
            break;
        }
        ck_assert_msg(rc == MC_ERR_NOMEM, "allocation %ld: status %d: %s", n, rc, e.msg);
        ck_assert_ptr_null(op);
    }
    ck_assert_int_eq(n, ref_allocs + 1);
    ck_assert_int_gt(ref_allocs, 2);
    mc_operator_apply(op, in, u);
    ck_assert_mem_eq(u, u_ref, sizeof u);
    mc_operator_destroy(&op);
    mc_threads_end(&threads);
}
END_TEST

/* ---- regressions ---------------------------------------------------------------------------- */

START_TEST(test_negative_pressure_map)
{
    /* A prescribed pressure map with a negative value is refused (MC_ERR_INPUT) with a message
     * naming the value and its place. Found by tests/cli/bad_input.sh under ASan: run_prescribed
     * (pipeline.c) freed the map before formatting the message from it (heap-use-after-free),
     * which only a sanitizer build shows; check-sanitize runs this test under ASan. */
    const char *dir = test_tmpdir();
    double p[4 * 3];
    for (int k = 0; k < 12; k++)
        p[k] = 1e6;
    p[1 * 4 + 2] = -2.5e6; /* row 1, column 2 */
    size_t shape[2] = {3, 4};
    mc_error err = {0};
    ck_assert_int_eq(mc_npy_write(path_join(dir, "p.npy"), p, 2, shape, &err), MC_OK);
    mc_scene sc;
    ck_assert_int_eq(mc_case_parse_text("[mesh]\nnx = 4\nny = 3\ndx = 1 um\n"
                                        "[load]\npressure_file = p.npy\n",
                                        "neg.ini", dir, 0, NULL, &sc, &err),
                     MC_OK);
    mc_results res;
    int rc = mc_pipeline_run(&sc, &res, &err);
    mc_results_free(&res);
    ck_assert_int_eq(rc, MC_ERR_INPUT);
    ck_assert_msg(strstr(err.msg, "p.npy") && strstr(err.msg, "-2.5e+06 Pa at row 1, column 2"),
                  "%s", err.msg);
}
END_TEST

START_TEST(test_null_error_keeps_status)
{
    /* err may be NULL (error.h): the status must stay what the failure was. output.c's
     * check_results returned mc_error_prefix(err, ...), which is MC_ERR_INTERNAL for err = NULL,
     * instead of the grid check's MC_ERR_INPUT. */
    const char *dir = test_tmpdir();
    mc_results r;
    memset(&r, 0, sizeof r); /* a 0 x 0 grid: invalid */
    mc_scene sc;
    mc_scene_defaults(&sc);
    ck_assert_int_eq(mc_output_write(dir, &sc, &r, NULL), MC_ERR_INPUT);
    mc_error err = {0};
    ck_assert_int_eq(mc_output_write(dir, &sc, &r, &err), MC_ERR_INPUT);
    ck_assert_msg(strncmp(err.msg, "output: ", 8) == 0, "%s", err.msg);
    char *l = listing(dir);
    ck_assert_str_eq(l, "");
    free(l);
}
END_TEST

START_TEST(test_alloc_alignment)
{
    /* alloc.c: every block 64-byte aligned; blocks of >= 4 MiB aligned to 2 MiB (huge page
     * candidates) unless mc_alloc_huge_pages(0); every byte usable either way */
    const size_t big = (size_t)5 << 20;
    for (int on = 1; on >= 0; on--) {
        mc_alloc_huge_pages(on);
        unsigned char *a = mc_malloc(100), *b = mc_malloc(big);
        ck_assert_ptr_nonnull(a);
        ck_assert_ptr_nonnull(b);
        ck_assert_uint_eq((uintptr_t)a % 64, 0);
        ck_assert_uint_eq((uintptr_t)b % 64, 0);
        if (on)
            ck_assert_uint_eq((uintptr_t)b % ((size_t)2 << 20), 0);
        memset(b, 0xA5, big);
        ck_assert_uint_eq(b[big - 1], 0xA5);
        mc_free(a);
        mc_free(b);
    }
    mc_alloc_huge_pages(1);
    double *z = mc_zeros((size_t)1 << 20); /* 8 MiB: the huge path of calloc */
    ck_assert_ptr_nonnull(z);
    ck_assert(z[0] == 0.0 && z[((size_t)1 << 20) - 1] == 0.0);
    mc_free(z);
}
END_TEST

START_TEST(test_calloc_zeroes_large)
{
    /* alloc.c: arrays of >= 4 MiB are zeroed by the run's threads a huge page at a time; every
     * byte, the last partial page included. glibc hands large blocks out by mmap (zero already),
     * so the heap is forced here (M_MMAP_MAX 0, and no trimming of its top): a freed dirty block
     * comes back */
    mc_threads_scope scope;
    mc_threads_begin(2, &scope);
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    const size_t sizes[] = {((size_t)4 << 20) + 8, ((size_t)9 << 20) + 24};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        unsigned char *d = mc_malloc(sizes[k]);
        ck_assert_ptr_nonnull(d);
        memset(d, 0xFF, sizes[k]);
        mc_free(d);
        unsigned char *z = mc_calloc(1, sizes[k]);
        ck_assert_ptr_nonnull(z);
        size_t nonzero = 0;
        for (size_t i = 0; i < sizes[k]; i++)
            nonzero += z[i] != 0;
        ck_assert_msg(nonzero == 0, "%zu of %zu bytes not zeroed (%s)", nonzero, sizes[k],
                      z == d ? "the dirty block reused" : "another block");
        mc_free(z);
    }
    mallopt(M_MMAP_MAX, 65536); /* glibc's defaults */
    mallopt(M_TRIM_THRESHOLD, 128 * 1024);
    mc_threads_end(&scope);
}
END_TEST

Suite *suite_faults(void);
Suite *suite_faults(void)
{
    Suite *s = suite_create("faults");
    TCase *tc = tcase_create("injection");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_whole_run, 0, NFAULT_CASES);
    tcase_add_loop_test(tc, test_contact_create, 0, NCONTACT_CASES);
    tcase_add_loop_test(tc, test_contact_solve, 0, NCONTACT_CASES);
    tcase_add_loop_test(tc, test_operator_plan, 0, (int)(sizeof plans / sizeof plans[0]));
    suite_add_tcase(s, tc);
    TCase *reg = tcase_create("regressions");
    tcase_add_test(reg, test_negative_pressure_map);
    tcase_add_test(reg, test_null_error_keeps_status);
    tcase_add_test(reg, test_alloc_alignment);
    tcase_add_test(reg, test_calloc_zeroes_large);
    suite_add_tcase(s, reg);
    return s;
}

/* test_faults.c - robustness: injected allocation failures through a whole run, into the contact
 * solver and the operator plan directly, and regressions found by the fuzzers (tests/fuzz/).
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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "alloc.h"
#include "case.h"
#include "contact.h"
#include "npy.h"
#include "operator.h"
#include "output.h"
#include "pipeline.h"
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
} fault_case;

#define MESH16 "[mesh]\nnx = 16\nny = 12\ndx = 2 um\ndy = 3 um\n"
#define ALL_STAGES ((1 << STAGE_PARSE) | (1 << STAGE_PIPELINE) | (1 << STAGE_OUTPUT))

static const fault_case fault_cases[] = {
    {"sphere, gaussian roughness, cg, fft, vtk",
     MESH16 "[geometry]\nshape = sphere\nradius = 5 mm\n"
            "[roughness]\ntype = gaussian\nrq = 0.05 um\ncorrelation_x = 6 um\nseed = 3\n"
            "[load]\nforce = 0.5 N\n[solver]\nmethod = cg\noperator = fft\nthreads = 1\n"
            "[output]\nvtk = yes\n",
     ALL_STAGES},
    {"ellipsoid, self-affine roughness, pk, direct, lubricant and cap",
     MESH16 "[geometry]\nshape = ellipsoid\nradius_x = 4 mm\nradius_y = 8 mm\n"
            "[roughness]\ntype = self_affine\nrq = 0.02 um\nhurst = 0.7\n"
            "[body2]\nrigid = yes\n"
            "[load]\nforce = 0.3 N\nlubricant_pressure = 5 MPa\npressure_cap = 4 GPa\n"
            "[solver]\nmethod = pk\noperator = direct\nthreads = 1\n",
     ALL_STAGES},
    {"cylinder, periodic y, force per length, active-set, roughness file",
     "[mesh]\nnx = 12\nny = 6\ndx = 3 um\nperiodic_y = yes\n"
     "[geometry]\nshape = cylinder\nradius = 5 mm\n"
     "[roughness]\ntype = file\nfile = heights.txt\n"
     "[load]\nforce_per_length = 50 N/mm\n[solver]\nmethod = active-set\nthreads = 1\n",
     ALL_STAGES},
    {"approach control, periodic x, cg",
     "[mesh]\nnx = 16\nny = 8\ndx = 2 um\nperiodic_x = yes\n"
     "[geometry]\nshape = sphere\nradius = 5 mm\n"
     "[load]\napproach = 0.05 um\n[solver]\nthreads = 1\n",
     ALL_STAGES},
    {"prescribed pressure from .npy, with [stress]",
     MESH16 "[load]\npressure_file = pressure.npy\n[solver]\nthreads = 1\n"
            "[stress]\ndepth_max = 20 um\nlayers = 4\n[output]\nvtk = yes\n",
     ALL_STAGES},
    {"sphere, gaussian roughness, [stress] with friction",
     MESH16 "[geometry]\nshape = sphere\nradius = 5 mm\n"
            "[roughness]\ntype = gaussian\nrq = 0.05 um\ncorrelation_x = 6 um\n"
            "[load]\nforce = 0.5 N\n[solver]\nthreads = 1\n"
            "[stress]\ndepths = 0.5 um, 2 um, 8 um\nfriction = 0.1\nkernel = patch\n",
     ALL_STAGES},
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
    mc_set_threads(0);
}
END_TEST

/* ---- the contact solver and the operator plan, directly ------------------------------------ */

enum { CNX = 24, CNY = 20 };

static char sentinel; /* an address a failed create must overwrite with NULL */

static const mc_grid cgrid = {CNX, CNY, 2e-6, 2.5e-6, 0, 0};

static void hertz_gap(double *h)
{
    for (int j = 0; j < CNY; j++)
        for (int i = 0; i < CNX; i++) {
            double x = mc_grid_x(&cgrid, i), y = mc_grid_y(&cgrid, j);
            h[j * CNX + i] = (x * x + y * y) / (2 * 5e-3);
        }
}

static const mc_contact_method methods[] = {MC_METHOD_CG, MC_METHOD_PK, MC_METHOD_ACTIVE_SET};

START_TEST(test_contact_create)
{
    /* Every allocation of mc_contact_create (workspaces, preconditioner, the coarse grid's
     * operator and solver for cg) fails in turn: NOMEM, *out NULL, nothing leaked; then the
     * solver made without a failure solves exactly as one made before. */
    mc_set_threads(1);
    mc_error err = {0};
    mc_operator *K = NULL;
    double Estar = 1.15e11;
    ck_assert_int_eq(mc_operator_plan_love(&cgrid, Estar, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options opt = {.method = methods[_i], .tolerance = 1e-9, .max_iterations = 500};
    double h[CNX * CNY], p_ref[CNX * CNY], p[CNX * CNY];
    hertz_gap(h);
    mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                               .load = 0.2};
    mc_contact_summary sum_ref, sum;

    mc_contact_solver *s = NULL;
    long allocs0 = mc_alloc_count();
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    long ref_allocs = mc_alloc_count() - allocs0;
    ck_assert_msg(mc_contact_solve(s, &prob, p_ref, NULL, NULL, &sum_ref, &err) == MC_OK, "%s",
                  err.msg);
    mc_contact_destroy(&s);
    ck_assert_ptr_null(s);

    long n;
    for (n = 1; n <= MAX_ATTEMPTS; n++) {
        mc_error e = {0};
        long injected = mc_alloc_injected();
        s = (mc_contact_solver *)(void *)&sentinel;
        mc_alloc_fail_at(n);
        int rc = mc_contact_create(K, &opt, &s, &e);
        mc_alloc_fail_at(0);
        if (mc_alloc_injected() == injected) {
            ck_assert_int_eq(rc, MC_OK);
            break;
        }
        ck_assert_msg(rc == MC_ERR_NOMEM, "%s: allocation %ld: status %d: %s",
                      mc_contact_method_name(opt.method), n, rc, e.msg);
        ck_assert_ptr_null(s);
    }
    ck_assert_int_eq(n, ref_allocs + 1);
    ck_assert_int_gt(ref_allocs, 2); /* the loop went through several allocations */
    ck_assert_msg(mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &err) == MC_OK, "%s", err.msg);
    ck_assert_int_eq(sum.iterations, sum_ref.iterations);
    ck_assert_mem_eq(p, p_ref, sizeof p);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_set_threads(0);
}
END_TEST

START_TEST(test_contact_solve)
{
    /* A solve allocates too: the cg and pk preconditioner plans (and caches) an FFT for each new
     * size of the contact's bounding box (precond.c plan_for). Every allocation of a first solve
     * fails in turn, on a fresh solver each time: NOMEM, and the same solver then solves again
     * (without injection) exactly as the reference, so a failed solve leaves it usable. */
    mc_set_threads(1);
    mc_error err = {0};
    mc_operator *K = NULL;
    ck_assert_int_eq(mc_operator_plan_love(&cgrid, 1.15e11, MC_BACKEND_FFT, &K, &err), MC_OK);
    mc_contact_options opt = {.method = methods[_i], .tolerance = 1e-9, .max_iterations = 500};
    double h[CNX * CNY], p_ref[CNX * CNY], p[CNX * CNY], u[CNX * CNY], gap[CNX * CNY];
    hertz_gap(h);
    mc_contact_problem prob = {.h = h, .p_cap = INFINITY, .control = MC_CONTROL_FORCE,
                               .load = 0.2};
    mc_contact_summary sum_ref, sum;
    mc_contact_solver *s = NULL;
    ck_assert_int_eq(mc_contact_create(K, &opt, &s, &err), MC_OK);
    long allocs0 = mc_alloc_count();
    ck_assert_msg(mc_contact_solve(s, &prob, p_ref, NULL, NULL, &sum_ref, &err) == MC_OK, "%s",
                  err.msg);
    long ref_allocs = mc_alloc_count() - allocs0;
    mc_contact_destroy(&s);

    long n;
    for (n = 1; n <= MAX_ATTEMPTS; n++) {
        mc_error e = {0};
        ck_assert_int_eq(mc_contact_create(K, &opt, &s, &e), MC_OK);
        long injected = mc_alloc_injected();
        mc_alloc_fail_at(n);
        int rc = mc_contact_solve(s, &prob, p, u, gap, &sum, &e);
        mc_alloc_fail_at(0);
        int fired = mc_alloc_injected() != injected;
        if (fired) {
            ck_assert_msg(rc == MC_ERR_NOMEM, "%s: allocation %ld of the solve: status %d: %s",
                          mc_contact_method_name(opt.method), n, rc, e.msg);
            mc_error_clear(&e);
            rc = mc_contact_solve(s, &prob, p, NULL, NULL, &sum, &e);
        }
        ck_assert_msg(rc == MC_OK, "%s: n = %ld: %s", mc_contact_method_name(opt.method), n,
                      e.msg);
        ck_assert_int_eq(sum.iterations, sum_ref.iterations);
        ck_assert_mem_eq(p, p_ref, sizeof p);
        mc_contact_destroy(&s);
        if (!fired)
            break;
    }
    ck_assert_int_eq(n, ref_allocs + 1);
    mc_operator_destroy(&K);
    mc_set_threads(0);
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
    mc_set_threads(1);
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
    mc_set_threads(0);
}
END_TEST

/* ---- regressions found by the fuzzers ------------------------------------------------------ */

Suite *suite_faults(void);
Suite *suite_faults(void)
{
    Suite *s = suite_create("faults");
    TCase *tc = tcase_create("injection");
    tcase_set_timeout(tc, 600);
    tcase_add_loop_test(tc, test_whole_run, 0, NFAULT_CASES);
    tcase_add_loop_test(tc, test_contact_create, 0, (int)(sizeof methods / sizeof methods[0]));
    tcase_add_loop_test(tc, test_contact_solve, 0, (int)(sizeof methods / sizeof methods[0]));
    tcase_add_loop_test(tc, test_operator_plan, 0, (int)(sizeof plans / sizeof plans[0]));
    suite_add_tcase(s, tc);
    return s;
}

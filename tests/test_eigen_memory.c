/* test_eigen_memory.c - the memory model of the elastic-plastic stage (issue 20 item 2):
 *   - the eigenstrain operators' estimates from the sizes alone (mc_eigen_stress_estimate,
 *     mc_eigen_disp_estimate) equal the bytes of the objects create builds, part by part, on
 *     every grid type (free with a window inside the grid, line, strip, doubly periodic, graded
 *     layers), both backends, one and two threads (the workspaces are per thread): the memory
 *     guard reads the estimates, so they must be the objects' own figures, exactly;
 *   - the guard of the plastic stage (mc_memory_check_plastic) refuses a run whose volume does
 *     not fit, with a message naming the stage and the volume, before the loop allocates, and
 *     passes it when it fits. */
#include <check.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "case/case.h"
#include "core/threads.h"
#include "eigen_testkit.h"
#include "pipeline/memguard.h"
#include "pipeline/pipeline.h"

typedef struct {
    const char *name;
    int nx, ny, px, py;         /* grid */
    int i0, j0, wx, wy, nz;     /* volume */
    int graded;                 /* 1: groups 1, 1, 3, 5 */
} mcase;

static const mcase cases[] = {
    {"free, window inside", 30, 26, 0, 0, 3, 2, 21, 17, 4, 0},
    {"free, whole grid", 24, 24, 0, 0, 0, 0, 24, 24, 5, 0},
    {"line", 40, 1, 0, 1, 4, 0, 30, 1, 6, 0},
    {"strip, periodic y", 28, 16, 0, 1, 2, 0, 20, 16, 4, 0},
    {"doubly periodic", 20, 18, 1, 1, 0, 0, 20, 18, 4, 0},
    {"free, graded", 22, 20, 0, 0, 1, 1, 18, 16, 4, 1},
    {"doubly periodic, graded", 16, 16, 1, 1, 0, 0, 16, 16, 4, 1},
};
#define NCASES ((int)(sizeof cases / sizeof cases[0]))

START_TEST(estimate_is_the_objects_bytes)
{
    const mcase *c = &cases[_i % NCASES];
    const mc_backend b = (_i / NCASES) % 2 ? MC_BACKEND_DIRECT : MC_BACKEND_FFT;
    const int threads = _i / (2 * NCASES) + 1;
    mc_threads_scope scope;
    mc_threads_begin(threads, &scope);
    mc_grid g;
    memset(&g, 0, sizeof g);
    g.nx = c->nx;
    g.ny = c->ny;
    g.dx = 1e-6;
    g.dy = 1.2e-6;
    g.periodic_x = c->px;
    g.periodic_y = c->py;
    static int group[] = {1, 1, 3, 5};
    const mc_eigen_volume v = {c->i0, c->j0, c->wx, c->wy, c->nz, 0.5e-6, MC_EIG_CELL_AVERAGE,
                               c->graded ? group : NULL, MC_EIG_KERNEL_CUBOID};
    mc_eigen_stress *s = eig_stress_op(&g, &v, 0.3, b);
    mc_eigen_disp *d = eig_disp_op(&g, &v, 0.3, b);
    size_t got[MC_EIGEN_STRESS_PARTS], est[MC_EIGEN_STRESS_PARTS], sum = 0;
    mc_eigen_stress_parts(s, got);
    mc_eigen_stress_estimate(&g, &v, b, est);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++) {
        ck_assert_msg(got[k] == est[k], "%s, %s, %d threads: stress part %d: object %zu, "
                      "estimate %zu", c->name, b == MC_BACKEND_FFT ? "fft" : "direct", threads,
                      k, got[k], est[k]);
        sum += got[k];
    }
    ck_assert(sum == mc_eigen_stress_bytes(s));
    ck_assert_msg(mc_eigen_disp_bytes(d) == mc_eigen_disp_estimate(&g, &v, b),
                  "%s, %s, %d threads: displacement: object %zu, estimate %zu", c->name,
                  b == MC_BACKEND_FFT ? "fft" : "direct", threads, mc_eigen_disp_bytes(d),
                  mc_eigen_disp_estimate(&g, &v, b));
    /* a volume create refuses: nothing */
    const mc_eigen_volume bad = {0, 0, c->nx + 1, c->wy, c->nz, 0.5e-6, MC_EIG_CELL_AVERAGE, NULL, MC_EIG_KERNEL_CUBOID};
    mc_eigen_stress_estimate(&g, &bad, b, est);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        ck_assert(est[k] == 0);
    ck_assert(mc_eigen_disp_estimate(&g, &bad, b) == 0);
    mc_eigen_stress_destroy(&s);
    mc_eigen_disp_destroy(&d);
    mc_threads_end(&scope);
}
END_TEST

/* An elastic-plastic sphere (yielding at 8 um depth under 1.1 GPa) on 32^2 through the pipeline:
 * with the memory limit just above the elastic run's estimate the plastic stage refuses it once
 * its volume is known, naming the stage and the volume; without a limit it runs. */
START_TEST(plastic_stage_guard)
{
    char ini[] = "/tmp/mc_test_memguard_XXXXXX";
    const int fd = mkstemp(ini);
    ck_assert(fd >= 0);
    FILE *f = fdopen(fd, "w");
    ck_assert(f != NULL);
    fprintf(f, "[mesh]\nnx = 32\nny = 32\ndx = 1 um\n[geometry]\nshape = sphere\nradius = 2 mm\n"
               "[body2]\nrigid = yes\n[load]\nforce = 0.3 N\n[plasticity]\nhardening = perfect\n"
               "yield_stress = 450 MPa\nload_steps = 1\ndz = 0.5 um\n");
    fclose(f);
    mc_scene s;
    mc_error err = {0};
    ck_assert_msg(mc_case_load(ini, 0, NULL, &s, &err) == MC_OK, "%s", err.msg);
    unlink(ini);
    char lim[64];
    snprintf(lim, sizeof lim, "%.0f", mc_memory_estimate(&s) + 1.0);
    setenv("MC_MEMORY_LIMIT", lim, 1);
    mc_results r;
    const int rc = mc_pipeline_run(&s, &r, &err);
    unsetenv("MC_MEMORY_LIMIT");
    ck_assert_int_eq(rc, MC_ERR_NOMEM);
    ck_assert_msg(strstr(err.msg, "elastic-plastic stage needs about") &&
                      strstr(err.msg, "plastic volume"),
                  "%s", err.msg);
    mc_results_free(&r);
    ck_assert_int_eq(mc_pipeline_run(&s, &r, &err), MC_OK);
    ck_assert(r.plastic.enabled && !r.plastic.elastic_shortcut && r.plastic.volume_cells > 0);
    /* the stage's estimate grows with the volume's layers */
    const mc_eigen_volume v1 = {0, 0, 32, 32, 8, 0.5e-6, MC_EIG_CELL_AVERAGE, NULL, MC_EIG_KERNEL_CUBOID};
    mc_eigen_volume v2 = v1;
    v2.nz = 16;
    ck_assert(mc_memory_estimate_plastic(&s, &r.grid, &v2, 0) >
              mc_memory_estimate_plastic(&s, &r.grid, &v1, 0) + 8 * 32 * 32 * 264.0);
    mc_results_free(&r);
}
END_TEST

Suite *suite_eigen_memory(void);
Suite *suite_eigen_memory(void)
{
    Suite *s = suite_create("eigen_memory");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_loop_test(tc, estimate_is_the_objects_bytes, 0, 4 * NCASES);
    tcase_add_test(tc, plastic_stage_guard);
    suite_add_tcase(s, tc);
    return s;
}

/* test_stage_roughness.c - the ISO parameters of the initial surface in a run's results. */
#include <math.h>

#include "case/case.h"
#include "pipeline/pipeline.h"
#include "test_util.h"

/* A synthetic Gaussian surface is scaled to exactly rq (surface/surface.h): the areal Sq of the
 * run's roughness parameters must be rq to round-off, and Sa/Sq of Gaussian heights sqrt(2/pi)
 * within the sampling scatter of 64 x 64 correlated heights (5 %). A clipped cut-off says so. */
START_TEST(initial_parameters_of_a_run)
{
    const char *text = "[mesh]\nnx = 64\nny = 64\ndx = 1 um\nperiodic_x = yes\nperiodic_y = yes\n"
                       "[roughness]\ntype = gaussian\nrq = 0.3 um\ncorrelation_x = 3 um\n"
                       "[load]\nforce = 0.1 N\n";
    mc_scene s;
    mc_error err = {0};
    ck_assert_msg(mc_case_parse_text(text, "r.ini", "", 0, NULL, &s, &err) == MC_OK, "%s", err.msg);
    mc_results r;
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(r.has_roughness);
    const mc_roughness_params *p = &r.roughness_initial;
    ck_assert_msg(fabs(p->Sq - 0.3e-6) <= 1e-12 * 0.3e-6, "Sq = %.17g", p->Sq);
    ck_assert_msg(fabs(p->Sa / p->Sq - sqrt(2 / M_PI)) <= 0.05, "Sa/Sq = %g", p->Sa / p->Sq);
    ck_assert(p->cutoff_clipped && p->warning[0]); /* 64 um is far below the 0.8 mm of ISO 4288 */
    mc_results_free(&r);
    /* a smooth scene has no roughness parameters */
    s.roughness.type = MC_ROUGH_NONE;
    ck_assert_msg(mc_pipeline_run(&s, &r, &err) == MC_OK, "%s", err.msg);
    ck_assert(!r.has_roughness);
    mc_results_free(&r);
}
END_TEST

Suite *suite_stage_roughness(void);
Suite *suite_stage_roughness(void)
{
    Suite *s = suite_create("stage_roughness");
    TCase *t = tcase_create("stage");
    tcase_add_test(t, initial_parameters_of_a_run);
    suite_add_tcase(s, t);
    return s;
}

/* suites.c - the registry of verification suites, in report order. */
#include <string.h>

#include "harness.h"
#include "suites.h"

static const vf_suite all[] = {
    {.name = "hertz_point",
     .title = "Hertz point contact: sphere on flat (two materials)",
     .run = vf_suite_hertz_point},
    {.name = "hertz_line",
     .title = "Hertz line contact: cylinder periodic in y (plane strain)",
     .run = vf_suite_hertz_line},
    {.name = "min_eval_depth",
     .title = "Minimum evaluation depth: point forces versus patch kernels (paper Fig. 2-3)",
     .run = vf_suite_min_eval_depth},
    {.name = "neighbour_interaction",
     .title = "Neighbour interaction: Hertzian pressure cells in patterns (paper Fig. 2-2)",
     .run = vf_suite_neighbour_interaction},
    {.name = "stability",
     .title = "Numerical stability: extreme scenes x backends x solvers",
     .run = vf_suite_stability},
    {.name = "lubricant_bc",
     .title = "Lubricant boundary condition p >= p_lub on a wavy surface (paper Fig. 3-1)",
     .run = vf_suite_lubricant_bc},
};

const vf_suite *vf_suites(int *count)
{
    *count = (int)(sizeof all / sizeof all[0]);
    return all;
}

/* Regression tiers by check id (harness.h vf_suite_tiers), for suites whose rows do not declare
 * them with vf_regress. */
static const struct {
    const char *suite, *tiers;
} tiers[] = {
    /* stopping residuals, round-off consistency and differences of two converged solves: the
     * last digits of another FFT plan move them by up to 0.2 of their tolerance (baseline.c) */
    {"stability", "*.kkt=noise *.consistent=noise *.similar=noise"},
};

const char *vf_suite_tiers(const char *suite)
{
    for (size_t k = 0; k < sizeof tiers / sizeof tiers[0]; k++)
        if (!strcmp(tiers[k].suite, suite))
            return tiers[k].tiers;
    return NULL;
}

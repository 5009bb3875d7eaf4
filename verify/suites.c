/* suites.c - the registry of verification suites, in report order. */
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
};

const vf_suite *vf_suites(int *count)
{
    *count = (int)(sizeof all / sizeof all[0]);
    return all;
}

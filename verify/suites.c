/* suites.c - the registry of verification suites, in report order. */
#include "harness.h"
#include "suites.h"

static const vf_suite all[] = {
    {"hertz_point", "Hertz point contact: sphere on flat (two materials)", vf_suite_hertz_point},
    {"hertz_line", "Hertz line contact: cylinder periodic in y (plane strain)", vf_suite_hertz_line},
    {"min_eval_depth",
     "Minimum evaluation depth: point forces versus patch kernels (paper Fig. 2-3)",
     vf_suite_min_eval_depth},
    {"neighbour_interaction",
     "Neighbour interaction: Hertzian pressure cells in patterns (paper Fig. 2-2)",
     vf_suite_neighbour_interaction},
    {"stability", "Numerical stability: extreme scenes x backends x solvers", vf_suite_stability},
};

const vf_suite *vf_suites(int *count)
{
    *count = (int)(sizeof all / sizeof all[0]);
    return all;
}

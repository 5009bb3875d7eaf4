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
    {.name = "yield_criterion",
     .title = "Yield criterion: von Mises against a pressure cap on asperity patterns (paper "
              "Fig. 2-2 top)",
     .run = vf_suite_yield_criterion},
    {.name = "mesh_convergence",
     .title = "Mesh convergence of stress and plastic deformation on a rough section, 2.0 to "
              "0.4 um (paper Fig. 2-4)",
     .run = vf_suite_mesh_convergence},
    {.name = "yield_onset",
     .title = "Yield onset of a Hertz sphere and cylinder: no plastic strain at 0.99, plastic "
              "strain at the right depth at 1.01 of the onset p0",
     .run = vf_suite_yield_onset},
    {.name = "kogut_etsion",
     .title = "Elastic-perfectly plastic sphere on a rigid flat against the Kogut-Etsion fits",
     .run = vf_suite_kogut_etsion},
    {.name = "swift_sphere",
     .title = "AISI 52100 Swift sphere: regression and grid convergence of the residual dent",
     .run = vf_suite_swift_sphere},
    {.name = "stability",
     .title = "Numerical stability: extreme scenes x backends x solvers",
     .run = vf_suite_stability},
    {.name = "lubricant_bc",
     .title = "Lubricant boundary condition p >= p_lub on a wavy surface (paper Fig. 3-1)",
     .run = vf_suite_lubricant_bc},
    {.name = "ehl_film",
     .title = "EHL film thickness of the disc case: every formula against the dossier",
     .run = vf_suite_ehl_film},
    {.name = "volume_equilibrium",
     .title = "Lubricant volume equilibrium: monotone V(p_lub), load split, limits, roots",
     .run = vf_suite_volume_equilibrium},
    {.name = "runin",
     .title = "Running-in: the friction hysteresis of three forces (paper Figs. 4-1 to 4-3)",
     .run = vf_suite_runin},
    {.name = "whole_contact",
     .title = "The whole lubricated line contact: Hertz, McEwen, the patch, the running-in at "
              "the paper's pressures",
     .run = vf_suite_whole_contact},
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
    /* values through the elastic-plastic loop (outer tolerance 1e-3 on the residual
     * displacement): another FFT plan may move its stopping iterate */
    {"yield_criterion", "vm_*=noise cap_*=noise plain_*=noise"},
    {"mesh_convergence", "*_rel_*=noise *_vs_*=noise *_coarse_farther=noise *_order=noise"},
    {"yield_onset", "*_vm_factor=noise *_depth=noise *_peq_max=noise"},
    {"kogut_etsion", "w_*=noise A_*=noise"},
    {"swift_sphere", "dent_*=noise pmax_*=noise peq_*=noise"},
};

const char *vf_suite_tiers(const char *suite)
{
    for (size_t k = 0; k < sizeof tiers / sizeof tiers[0]; k++)
        if (!strcmp(tiers[k].suite, suite))
            return tiers[k].tiers;
    return NULL;
}

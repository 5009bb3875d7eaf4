/* results.c - ownership of the run results (see results.h). */
#include "pipeline/results.h"

#include <string.h>

#include "core/alloc.h"
#include "kernels/kernel.h"

/* The stress members, as a list of the owned arrays. */
static void stress_arrays(mc_results *r, double **a[MC_NSTRESS + 4])
{
    a[0] = &r->depths;
    for (int c = 0; c < MC_NSTRESS; c++)
        a[1 + c] = &r->stress[c];
    a[MC_NSTRESS + 1] = &r->von_mises;
    a[MC_NSTRESS + 2] = &r->hydrostatic;
    a[MC_NSTRESS + 3] = &r->tresca;
}

void mc_results_free_stress(mc_results *r)
{
    double **a[MC_NSTRESS + 4];
    stress_arrays(r, a);
    for (int k = 0; k < MC_NSTRESS + 4; k++) {
        mc_free(*a[k]);
        *a[k] = NULL;
    }
    r->nlayers = 0;
    memset(&r->stress_summary, 0, sizeof r->stress_summary);
    memset(&r->stress_layout, 0, sizeof r->stress_layout);
}

void mc_results_move_stress(mc_results *to, mc_results *from)
{
    mc_results_free_stress(to);
    double **a[MC_NSTRESS + 4], **b[MC_NSTRESS + 4];
    stress_arrays(to, a);
    stress_arrays(from, b);
    for (int k = 0; k < MC_NSTRESS + 4; k++) {
        *a[k] = *b[k];
        *b[k] = NULL;
    }
    to->nlayers = from->nlayers;
    to->stress_summary = from->stress_summary;
    to->stress_layout = from->stress_layout;
    from->nlayers = 0;
}

void mc_results_free(mc_results *r)
{
    if (!r)
        return;
    mc_free(r->topography);
    mc_free(r->pressure);
    mc_free(r->gap);
    mc_free(r->displacement);
    mc_results_free_stress(r);
    mc_free(r->residual_displacement);
    mc_free(r->lube_profile);
    mc_free(r->topography_final);
    mc_free(r->plastic_strain);
    mc_free(r->residual_von_mises);
    mc_free(r->plastic.steps);
    mc_free(r->plastic.group);
    mc_free(r->runin.rows);
    mc_free(r->runin.hysteresis);
    mc_free(r->surface_initial);
    mc_free(r->surface_final);
    for (int k = 0; k < 2; k++) {
        mc_free(r->body_initial[k]);
        mc_free(r->body_final[k]);
    }
    memset(r, 0, sizeof *r);
}

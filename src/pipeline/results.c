/* results.c - ownership of the run results (see results.h). */
#include "pipeline/results.h"

#include <string.h>

#include "core/alloc.h"
#include "kernels/kernel.h"

void mc_results_free(mc_results *r)
{
    if (!r)
        return;
    mc_free(r->topography);
    mc_free(r->pressure);
    mc_free(r->gap);
    mc_free(r->displacement);
    mc_free(r->depths);
    for (int c = 0; c < MC_NSTRESS; c++)
        mc_free(r->stress[c]);
    mc_free(r->von_mises);
    mc_free(r->hydrostatic);
    mc_free(r->tresca);
    memset(r, 0, sizeof *r);
}

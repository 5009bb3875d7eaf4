/* runin_checks.c - the running-in checks shared by two suites (runin_checks.h). */
#include "runin_checks.h"

#include <math.h>
#include <stdio.h>

void vf_runin_ra_checks(vf_ctx *ctx, const mc_runin_summary *ri, int f, double ra_before)
{
    const int m = ri->nspeeds;
    const mc_runin_row *first = &ri->rows[2 * m * f], *last = &ri->rows[2 * m * f + m - 1];
    int rises = 0;
    double prev = ra_before, up_dev = 0;
    for (int k = 0; k < m; k++) {
        rises += !(first[k].ra <= prev); /* a NaN Ra counts as a rise */
        prev = first[k].ra;
    }
    for (int k = m; k < 2 * m; k++)
        up_dev = vf_worst(up_dev, fabs(first[k].ra - last->ra));
    char id[64], q[200];
    snprintf(id, sizeof id, "ra_never_rises_F%d", f + 1);
    snprintf(q, sizeof q, "F_N = %.0f N: run-down steps where Ra rose", first->force);
    vf_check(ctx, id, q, "plastic smoothing only lowers the surface", 0, rises, 0, VF_MAX);
    snprintf(id, sizeof id, "ra_falls_F%d", f + 1);
    snprintf(q, sizeof q, "F_N = %.0f N: Ra after the run-down / Ra before it", first->force);
    /* strictly below: by more than the 1e-6 the roughness parameters can resolve */
    vf_check(ctx, id, q, "paper Fig. 4-1: Ra falls during the run-down", 1.0,
             last->ra / ra_before, 1 - 1e-6, VF_MAX);
    snprintf(id, sizeof id, "ra_up_unchanged_F%d", f + 1);
    snprintf(q, sizeof q, "F_N = %.0f N: max |Ra - Ra(end of run-down)| over the run-up, m",
             first->force);
    vf_check(ctx, id, q, "the run-up is elastic", 0, up_dev, 0, VF_MAX);
}

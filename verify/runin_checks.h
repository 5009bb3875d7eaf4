/* runin_checks.h - the running-in checks the suites `runin` (the patch) and `whole_contact` (the
 * whole contact) share. */
#ifndef MC_VERIFY_RUNIN_CHECKS_H
#define MC_VERIFY_RUNIN_CHECKS_H

#include "harness.h"
#include "pipeline/results.h"

/* The Ra checks of force f of a running-in (rows of ri; ra_before: Ra of the surface the run-down
 * starts from): ra_never_rises_F<f+1> (no run-down step raises Ra; a NaN counts as a rise),
 * ra_falls_F<f+1> (Ra ends the run-down below where it began, by more than the 1e-6 the roughness
 * parameters resolve) and ra_up_unchanged_F<f+1> (the elastic run-up leaves Ra exactly). */
void vf_runin_ra_checks(vf_ctx *ctx, const mc_runin_summary *ri, int f, double ra_before);

#endif

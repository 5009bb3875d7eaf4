/* suites.h - the suite entry points (one file each in verify/). */
#ifndef MC_VERIFY_SUITES_H
#define MC_VERIFY_SUITES_H

#include "harness.h"

int vf_suite_hertz_point(vf_ctx *ctx, int fast);
int vf_suite_hertz_line(vf_ctx *ctx, int fast);
int vf_suite_min_eval_depth(vf_ctx *ctx, int fast);
int vf_suite_neighbour_interaction(vf_ctx *ctx, int fast);
int vf_suite_stability(vf_ctx *ctx, int fast);
int vf_suite_lubricant_bc(vf_ctx *ctx, int fast);
int vf_suite_ehl_film(vf_ctx *ctx, int fast);
int vf_suite_volume_equilibrium(vf_ctx *ctx, int fast);
int vf_suite_runin(vf_ctx *ctx, int fast);
int vf_suite_whole_contact(vf_ctx *ctx, int fast);
int vf_suite_mesh_convergence(vf_ctx *ctx, int fast);
int vf_suite_yield_criterion(vf_ctx *ctx, int fast);
int vf_suite_yield_onset(vf_ctx *ctx, int fast);
int vf_suite_kogut_etsion(vf_ctx *ctx, int fast);
int vf_suite_swift_sphere(vf_ctx *ctx, int fast);

/* Subsurface-stress checks of the Hertz suites (verify/hertz_stress.c), called at the end of
 * vf_suite_hertz_point / vf_suite_hertz_line: they record their checks in the same report. */
int vf_hertz_point_stress(vf_ctx *ctx, int fast);
int vf_hertz_line_stress(vf_ctx *ctx, int fast);

#endif

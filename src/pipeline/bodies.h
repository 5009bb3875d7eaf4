/* bodies.h - the surfaces of the two bodies ([roughness] and [roughness2]): the initial
 * topography of a scene, each body's heights before and after the run, and their ISO roughness
 * parameters (docs/theory.md §4.11).
 *
 * Without [roughness2] the scene has one composite surface ([roughness]) and nothing here adds to
 * the results. With it, [roughness] is body 1's surface z1 and [roughness2] body 2's z2, each
 * measured outward, towards the other body; the gap's roughness is z1 + z2, so the topography is
 * shape - (z1 + z2). A body's final surface is its initial one minus its own residual dent: body 1
 * takes the residual displacement u_r of the elastic-plastic stage or running-in, body 2 takes
 * the same u_r with [plasticity] bodies = both (one material, deforming alike) and none
 * otherwise. Their sum is the composite final surface, shape - topography_final.
 */
#ifndef MC_BODIES_H
#define MC_BODIES_H

#include "case/scene.h"
#include "core/error.h"
#include "pipeline/results.h"

/* The initial topography of sc into topo (ny*nx, m): shape minus the heights of [roughness]
 * (mc_surface_topography), or with [roughness2] minus z1 + z2 (mc_surface_two_bodies), each
 * body's heights kept in res->body_initial (res->two_bodies = 1) with what its file held in
 * res->body_file. On failure *section (may be NULL) names the section at fault ("roughness" or
 * "roughness2"). Errors as mc_surface_two_bodies, MC_ERR_NOMEM. */
int mc_bodies_topography(const mc_scene *sc, mc_results *res, double *topo, const char **section,
                         mc_error *err);

/* The ISO options of a roughness section's parameters on sc's grid (spec: sc->roughness or
 * sc->roughness2): a run's (runin = 0: the standard filter, the section's cutoff or ISO 4288
 * from Ra) or a running-in's (runin = 1: filtered only with a cutoff given, else each row's mean
 * removed: a simulated window is far shorter than an ISO cut-off). */
void mc_bodies_options(const mc_scene *sc, const mc_roughness_spec *spec, int runin,
                       mc_roughness_options *opt);

/* Each body's ISO parameters before the run (res->body_roughness_initial) with
 * mc_bodies_options; nothing without res->two_bodies. On failure *section names the body's
 * section (a cutoff too short for the grid is MC_ERR_INPUT from mc_roughness_compute). */
int mc_bodies_initial_parameters(const mc_scene *sc, int runin, mc_results *res,
                                 const char **section, mc_error *err);

/* Each body's final surface (res->body_final, res->body_has_final) and its ISO parameters:
 * body_final[0] = z1 - u_r, body_final[1] = z2 - u_r with [plasticity] bodies = both, else z2
 * (u_r: ny*nx, m, positive into the body; NULL: no dent, the finals are the initials); nothing
 * without res->two_bodies. *section as above. MC_ERR_NOMEM. */
int mc_bodies_final(const mc_scene *sc, int runin, const double *u_r, mc_results *res,
                    const char **section, mc_error *err);

#endif

/* stage_plastic.h - the elastic-plastic stage: the scene's [plasticity] turned into the material
 * law, the plastic volume (its depth and columns from the elastic solution at the full load) and
 * the semi-analytical loop of plastic/loop.h; or, for criterion = pressure_cap, the capped contact
 * and its penetration. docs/theory.md §7-§9.
 */
#ifndef MC_STAGE_PLASTIC_H
#define MC_STAGE_PLASTIC_H

#include "case/scene.h"
#include "contact/contact.h"
#include "core/error.h"
#include "operator/operator.h"
#include "pipeline/results.h"
#include "plastic/hardening.h"

/* Run the stage with the contact solver (planned over K, the two-body Love operator of the
 * grid) into res: pressure, displacement, gap and contact at the full load; residual
 * displacement, final topography, plastic strain and residual von Mises fields; res->plastic.
 * Skips (measured in the bench): the columns outside the contact's box plus a margin carry no
 * plastic cells; the volume ends where the elastic von Mises stress falls below half the yield
 * stress (depth = auto); nothing yields at the full load -> no plastic loop at all.
 * MC_OK, MC_NOT_CONVERGED (results still filled, res->plastic.converged = 0) or an error. */
int mc_stage_plastic(const mc_scene *sc, mc_operator *K, mc_contact_solver *solver,
                     mc_results *res, mc_error *err);

/* The hardening law of the scene's [plasticity] (free with mc_hardening_free). MC_OK or the law's
 * errors (MC_ERR_INPUT, MC_ERR_IO for a table file). */
int mc_stage_plastic_law(const mc_scene *sc, mc_hardening *law, mc_error *err);

/* Largest von Mises stress of body 1 in each of the nz layers at depths z (m) under pressure p
 * (Pa, with the friction traction of [plasticity] where p exceeds the lubricant pressure p_lub
 * shape[i], shape NULL: uniform; stress/traction.h): vm_layer[k], Pa. */
int mc_stage_plastic_layer_maxima(const mc_scene *sc, const mc_grid *g, const double *p,
                                  double p_lub, const double *shape, const double *z, int nz,
                                  double *vm_layer, mc_error *err);

#endif

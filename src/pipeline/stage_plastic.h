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

/* Run the stage with the contact solver (planned over K, the two-body Love operator of the
 * grid) into res: pressure, displacement, gap and contact at the full load; residual
 * displacement, final topography, plastic strain and residual von Mises fields; res->plastic.
 * Skips (measured in the bench): the columns outside the contact's box plus a margin carry no
 * plastic cells; the volume ends where the elastic von Mises stress falls below half the yield
 * stress (depth = auto); nothing yields at the full load -> no plastic loop at all.
 * MC_OK, MC_NOT_CONVERGED (results still filled, res->plastic.converged = 0) or an error. */
int mc_plastic_stage(const mc_scene *sc, mc_operator *K, mc_contact_solver *solver,
                     mc_results *res, mc_error *err);

#endif

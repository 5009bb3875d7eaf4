/* output.h - the output contract of DESIGN.md: summary.json, .npy fields, .csv profiles and
 * field.vti, written atomically.
 *
 * Files are first written into a staging directory inside DIR and renamed into DIR only when all
 * of them succeeded: a failed run leaves no half-written result and no partial set. */
#ifndef MC_OUTPUT_H
#define MC_OUTPUT_H

#include "error.h"
#include "results.h"
#include "scene.h"

/* Create DIR (and parents) if needed and check that it is writable, before any computation, so
 * a bad output directory fails fast (MC_ERR_IO naming the directory). */
int mc_output_prepare(const char *dir, mc_error *err);

/* Write every file the results call for (see DESIGN.md "Output contract") into dir. The scene
 * is recorded in summary.json (case path, seed, key inputs). */
int mc_output_write(const char *dir, const mc_scene *scene, const mc_results *res, mc_error *err);

#endif

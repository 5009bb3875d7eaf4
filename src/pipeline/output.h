/* output.h - the output contract of DESIGN.md: summary.json, .npy fields, .csv profiles and
 * VTK files, written atomically.
 *
 * Files are first written into a staging directory inside DIR (DIR/.staging-XXXXXX) and renamed
 * into DIR only when all of them succeeded: a failed run leaves no half-written result and no
 * partial set. Contract files of an earlier run that this run does not produce (von_mises.npy
 * after a run without stress, field.vti without vtk, ...) are removed, so DIR never mixes two
 * runs; other files in DIR are left alone. The old summary.json is removed first and the new one
 * renamed last, so a summary.json in DIR always describes the files beside it. */
#ifndef MC_OUTPUT_H
#define MC_OUTPUT_H

#include "core/error.h"
#include "pipeline/results.h"
#include "case/scene.h"

/* Create DIR (and parents, like mkdir -p) if needed and check that it is writable by creating
 * and removing a probe file, before any computation, so a bad output directory fails fast.
 * MC_ERR_IO naming the directory and strerror; MC_ERR_INPUT for an empty or too long path. */
int mc_output_prepare(const char *dir, mc_error *err);

/* Write every file the results call for into the existing directory dir:
 *  always     summary.json, pressure.npy, gap.npy, displacement.npy, topography.npy (ny x nx,
 *             .npy 1.0 float64), profile_x.csv ("x,pressure,gap,displacement": row j of the
 *             maximum pressure, x at cell centres);
 *  res->nlayers > 0 (stress was run)
 *             von_mises.npy, hydrostatic.npy, stress_xx.npy ... stress_xz.npy (layers x ny x nx),
 *             depths.csv ("layer,z"), axis.csv ("z,sxx,syy,szz,sxy,syz,sxz,von_mises,
 *             hydrostatic,tresca" under the cell of maximum pressure);
 *  scene->output.vtk
 *             field.vti (ImageData, the four surface fields as CellData) and, with stress,
 *             stress.vtr (RectilinearGrid: x, y at cell centres, z = -depth increasing; the six
 *             stresses, von_mises, hydrostatic, tresca as PointData); raw appended
 *             little-endian Float64, header_type UInt64.
 * Ties for the maximum pressure (e.g. all zero) go to the cell nearest the grid centre. Numbers
 * in CSV and JSON carry 17 significant digits (exact round trip); JSON infinities and NaN are
 * null.
 * summary.json: format, format_version, case (scene->path), mesh, geometry, materials (E, nu,
 * rigid, estar), load (kind, value or pressure_file, lubricant_pressure, pressure_cap), roughness
 * (type; seed = res->roughness_seed, a string if above INT64_MAX; the type's parameters),
 * contact (the mc_contact_summary, plus the solver tolerance and max_iterations of the scene),
 * stress (the mc_stress_summary, when stress was run), timing (total_s, setup_s, contact_s,
 * stress_s) and files (every file written, summary.json last).
 * Returns MC_OK; MC_ERR_IO (dir missing or not writable, a write failed, a result file name in
 * DIR is taken by a directory: DIR unchanged); MC_ERR_NOMEM (DIR unchanged); MC_ERR_INTERNAL
 * (results lack a field the contract needs). Only a failing rename after the commit started
 * (practically impossible within one directory) leaves DIR without summary.json. */
int mc_output_write(const char *dir, const mc_scene *scene, const mc_results *res, mc_error *err);

#endif

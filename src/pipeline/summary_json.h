/* summary_json.h - the summary.json document of a run (the output contract: README.md, Outputs). */
#ifndef MC_SUMMARY_JSON_H
#define MC_SUMMARY_JSON_H

#include <jansson.h>

#include "case/scene.h"
#include "core/error.h"
#include "pipeline/results.h"

/* Build the document: format and version, the case, every input of the scene, the results
 * (mesh, contact, stress, timing, ...), and the list of files written (files[0..nfiles) and then
 * self, the summary's own name, if not NULL). SI units; infinities and NaN become null. *out
 * receives a new reference (json_decref it). MC_OK or MC_ERR_NOMEM. */
int mc_summary_json(const mc_scene *scene, const mc_results *res, const char *const *files,
                    int nfiles, const char *self, json_t **out, mc_error *err);

#endif

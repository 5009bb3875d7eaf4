/* case.h - INI case files (inih) with units -> mc_scene.
 *
 * Every key is declared once in a table (case.c) with its section, kind, unit, default, accepted
 * range and one line of documentation; the same table validates input and generates the case
 * reference (docs/case-format.md). Errors name the file, line, [section] key, the value and what
 * is accepted: "cases/x.ini:12: [mesh] nx = 0: must be an integer in 1..65536".
 */
#ifndef MC_CASE_H
#define MC_CASE_H

#include "error.h"
#include "scene.h"

/* Load path into *scene (defaults first), then apply overrides "section.key=value" (as from
 * --set; they replace a key of the file, they are not duplicates), then mc_scene_check.
 * Relative file paths inside the case resolve against the case file's directory.
 * Returns MC_OK, MC_ERR_IO (cannot read) or MC_ERR_INPUT (with the message described above). */
int mc_case_load(const char *path, int noverrides, const char *const *overrides, mc_scene *scene,
                 mc_error *err);

/* Same from an in-memory text; name is used in messages and base_dir for relative paths. */
int mc_case_parse_text(const char *text, const char *name, const char *base_dir, int noverrides,
                       const char *const *overrides, mc_scene *scene, mc_error *err);

/* The case-file reference as Markdown (malloc'ed, caller frees with mc_free); NULL if no memory. */
char *mc_case_reference_markdown(void);

#endif

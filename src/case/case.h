/* case.h - INI case files (inih) with units -> mc_scene.
 *
 * Every key is declared once in a table (case.c) with its section, kind, unit, default, accepted
 * range and one line of documentation; the same table validates input and generates the case
 * reference (docs/case-format.md). Errors name the file, line, [section] key, the value and what
 * is accepted: "cases/x.ini:12: [mesh] nx = 0: must be an integer in 1..65536".
 */
#ifndef MC_CASE_H
#define MC_CASE_H

#include "core/error.h"
#include "case/scene.h"

/* Load path into *scene: defaults (mc_scene_defaults), then the file's keys, then overrides
 * "section.key=value" (as from --set; an override replaces the file's key, it is not a
 * duplicate; of two overrides of one key the last wins), then the cross-key rules
 * (mc_scene_check). Relative [roughness] file and [load] pressure_file paths in the file resolve
 * against the case file's directory; in overrides they stay relative to the current directory.
 * [output] dir defaults to "out/<case file name without .ini>" (relative to the current
 * directory). scene->path = path. *scene is written only on success.
 * Returns MC_OK, MC_ERR_IO (cannot open or read: the message names path and strerror),
 * MC_ERR_INPUT (the message described above) or MC_ERR_NOMEM. */
int mc_case_load(const char *path, int noverrides, const char *const *overrides, mc_scene *scene,
                 mc_error *err);

/* Same from an in-memory, NUL-terminated text: name (NULL: "<case>") is used in messages and as
 * scene->path, base_dir (NULL or "": the current directory) for relative paths. */
int mc_case_parse_text(const char *text, const char *name, const char *base_dir, int noverrides,
                       const char *const *overrides, mc_scene *scene, mc_error *err);

/* The case-file reference as Markdown (allocated with mc_malloc, caller frees with mc_free); NULL
 * if out of memory. Its first line is an HTML comment naming this function; docs/case-format.md
 * is a hand-written introduction followed by exactly this text (a unit test compares them). */
char *mc_case_reference_markdown(void);

/* Consistency of the key table (for tests): every documented default parses to exactly the
 * value mc_scene_defaults() sets, conditions name real keys and values, groups are well formed,
 * no text breaks the Markdown table. MC_OK or MC_ERR_INTERNAL naming the key. */
int mc_case_check_table(mc_error *err);

#endif

/* datafiles.h - the data files a case names, read while the case is read: an unreadable or
 * invalid file is bad input of the case file (exit 2, naming the line of its key), found before
 * anything runs or prints. Measured surfaces ([roughness] file) are read by reader.c (the mesh
 * may come from them); this is for the others. */
#ifndef MC_CASE_DATAFILES_H
#define MC_CASE_DATAFILES_H

#include "case/scene.h"
#include "core/error.h"

/* [plasticity] table (hardening = table): read and checked by plastic/hardening.h, then freed.
 * On error *section, *keyname name the key (as mc_scene_check_key) and the message starts with
 * "[plasticity] table: ". */
int mc_case_check_datafiles(const mc_scene *s, mc_error *err, const char **section,
                            const char **keyname);

#endif

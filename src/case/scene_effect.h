/* scene_effect.h - cross-key rules of keys without effect and of documented limits the key table
 * cannot state (scene_effect.c); part of mc_scene_check. */
#ifndef MC_SCENE_EFFECT_H
#define MC_SCENE_EFFECT_H

#include "case/scene.h"
#include "core/error.h"

/* MC_OK, or MC_ERR_INPUT with *section, *keyname (when not NULL) naming the key. */
int mc_scene_effect_rules(const mc_scene *s, mc_error *err, const char **section,
                          const char **keyname);

#endif

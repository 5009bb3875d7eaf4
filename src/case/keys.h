/* keys.h - the key table of case files, shared by the reader (reader.c), the scene check
 * (scene.c) and the generated reference (docs/case-format.md). Internal to case/.
 *
 * One row per key: where it lives in mc_scene, its kind, unit, bounds, default and help. The
 * bounds are checked in one place (mc_keys_check_scene) for scenes from files and from code
 * alike; the rules that tie keys together are in scene.c (scene_rules).
 */
#ifndef MC_CASE_KEYS_H
#define MC_CASE_KEYS_H

#include <stddef.h>

#include "case/case.h"
#include "case/scene.h"
#include "case/units.h"
#include "core/error.h"

typedef enum {
    K_INT,    /* int in lo..hi */
    K_SEED,   /* uint64_t, any value */
    K_REAL,   /* double with a unit kind, in (lo|[lo, hi]|hi) */
    K_ENUM,   /* one of choices; stored as the index */
    K_BOOL,   /* yes/no; stored as 0/1 in an int */
    K_PATH,   /* char[MC_PATH_MAX] */
    K_LENGTHS, /* comma-separated lengths, strictly increasing, >= 0 */
    K_REGION,  /* x0, y0, width, height: four lengths, width and height > 0 */
    K_LIST     /* comma-separated quantities of the row's unit, each in the row's range, in the
                  row's order; a unit written once at the end applies to the bare numbers */
} key_kind;

typedef enum {
    USE_ALWAYS,
    USE_WHEN,  /* used when use_key's value is one of use_values (space-separated) */
    USE_UNLESS /* used unless use_key is given */
} key_use;

typedef struct {
    const char *section, *name;
    key_kind kind;
    mc_unit_kind unit;    /* K_REAL, K_LENGTHS */
    double lo, hi;        /* K_INT, K_REAL: accepted range */
    int lo_open, hi_open; /* K_REAL: strict bounds */
    const char *lo_text;  /* replaces the lower bound in messages: a cross-key bound */
    const char *choices;  /* K_ENUM: space-separated names (or, instead, choice:) */
    const char *(*choice)(int i); /* K_ENUM: name of choice i, NULL past the last: the table of
                                     the module that owns the choices (film formulas, ...) */
    const char *(*choice_help)(int i); /* with choice: one line of help per choice (docs) */
    const char *def;      /* documented default; NULL: none */
    int def_rule;         /* def states a rule, not a value (not checked against the scene) */
    const char *def_from; /* default: the value of this key of the same section */
    int required;         /* must be given whenever it is used */
    const char *group;    /* exactly one of the used keys of a group must be given */
    key_use use;
    const char *use_key, *use_values;
    size_t off;      /* destination in mc_scene */
    int tagged, tag; /* when given, also store tag (an enum value) at tag_off */
    size_t tag_off;
    size_t count_off; /* K_LENGTHS: int count */
    int relative;     /* K_PATH: resolved against the case file's directory */
    const char *word; /* K_REAL: a word accepted instead of a number, stored as word_value */
    double word_value;
    const char *doc;
    int order;    /* K_LIST: 1 strictly increasing, -1 strictly decreasing, 0 any order */
    int list_max; /* K_LIST: most items (the capacity at off); the count is an int at count_off */
} case_key;

typedef struct {
    const char *name;
    const char *switch_key; /* a bool key that turns the section's requirements off */
    const char *doc;
} case_section;

#define MC_MAX_KEYS 160 /* rows the reader can track (keys.c asserts the table fits) */

extern const case_key mc_keys[];
extern const int mc_nkeys;
extern const case_section mc_key_sections[];
extern const int mc_nsections;

const case_section *mc_key_section(const char *name); /* NULL when unknown */
int mc_key_find(const char *section, const char *name); /* row index, -1 when unknown */

void mc_key_fmt(char *buf, size_t len, const char *f, ...) __attribute__((format(printf, 3, 4)));
int mc_key_word(const char *list, int i, char *buf, size_t len); /* word i of a list; 0: none */
int mc_key_word_index(const char *list, const char *word);      /* -1 when absent */
void mc_key_words_joined(const char *list, const char *sep, char *buf, size_t len);
/* The choices of an enum row, from its choices string or its module's choice function. */
int mc_key_choice(const case_key *k, int i, char *buf, size_t len); /* 0: no choice i */
int mc_key_choice_index(const case_key *k, const char *word);      /* -1 when absent */
void mc_key_choices_joined(const case_key *k, const char *sep, char *buf, size_t len);
#define MC_KEY_DESCRIBE_MAX 512 /* longest "what a key accepts" text (the table check asserts it) */
void mc_key_show(const char *v, char *buf, size_t len); /* a value quoted for a message */
void mc_key_fmt_bound(double v, mc_unit_kind unit, char *buf, size_t len);

/* What a key accepts: with noun "an integer in 1..65536", without "1..65536". */
void mc_key_describe(const case_key *k, int noun, char *buf, size_t len);
int mc_key_in_range(const case_key *k, double x);

void mc_key_put_int(mc_scene *sc, size_t off, int v);
int mc_key_get_int(const mc_scene *sc, size_t off);

/* Convert the text v of key k into the scene (base: directory of relative paths, NULL for none).
 * 0 on success, else 1 with the reason in why. */
int mc_key_convert(const case_key *k, const char *v, const char *base, mc_scene *sc, char *why,
                   size_t wl);

/* Row index of key k's use_key ("key" of its own section or "section.key"); -1: none. */
int mc_key_selector(int k);

/* The effective value of an enum or bool key of the scene as text ("sphere", "yes"). */
void mc_key_value_text(const mc_scene *sc, int k, char *buf, size_t len);

/* Whether key k has an effect in scene sc: its use condition holds (a USE_WHEN selector has one
 * of the listed values; a USE_UNLESS key's tagged counterpart is not in force) and, for a tagged
 * member of a group, its tag is the one in force. */
int mc_key_used_in_scene(const mc_scene *sc, int k);

/* Check every used key's value in sc against its row (bounds, choices, list rules); only the
 * keys of section `only` when it is not NULL. On failure names the key (*section, *key) and
 * returns MC_ERR_INPUT with "[section] key = value: must be <what the row accepts>". */
int mc_keys_check_scene(const mc_scene *sc, const char *only, mc_error *err, const char **section,
                        const char **key);

/* Fill the defaults of every row that states a value (def without def_rule/def_from). */
void mc_keys_defaults(mc_scene *sc);

#endif

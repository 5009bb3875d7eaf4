/* units.h - numbers with unit suffixes, as written in case files ("0.8 um", "210 GPa",
 * "500 N/mm", "30 mPa*s"); a bare number is SI. Also the two text helpers the case reader needs
 * to report bad input safely (UTF-8 check, quoting for messages). */
#ifndef MC_UNITS_H
#define MC_UNITS_H

#include <stddef.h>

typedef enum {
    MC_UNIT_NONE,             /* dimensionless: a bare number only */
    MC_UNIT_LENGTH,           /* m, mm, um (µm), nm */
    MC_UNIT_FORCE,            /* N, kN, mN */
    MC_UNIT_PRESSURE,         /* Pa, kPa, MPa, GPa (also moduli) */
    MC_UNIT_FORCE_PER_LENGTH, /* N/m, N/mm, kN/m, kN/mm */
    MC_UNIT_VISCOSITY,        /* Pa*s, Pa.s, mPa*s, mPa.s */
    MC_UNIT_SPEED,            /* m/s, mm/s */
    MC_UNIT_ROTATION          /* rpm (-> rad/s), rad/s, 1/s (= rad/s) */
} mc_unit_kind;

/* Parse "number [unit]" into SI: a decimal number (strtod syntax without NaN, Inf or hex; finite)
 * optionally followed by spaces and a suffix of the requested kind. Suffixes are case-sensitive
 * (mN is a millinewton, MN is unknown); µm may be written with U+00B5 or U+03BC. Surrounding
 * whitespace is ignored. Returns 0 on success (*si set); otherwise non-zero, *si untouched and a
 * short reason in why (NUL-terminated, cut to whylen), e.g.
 * "unit 'N' is a force; a length is due (m, mm, um, nm)". why may be NULL. */
int mc_parse_quantity(const char *text, mc_unit_kind kind, double *si, char *why, size_t whylen);

/* Name of a unit kind ("length", "dimensionless"), its accepted suffixes ("m, mm, um, nm"; ""
 * for MC_UNIT_NONE) and its SI symbol ("m"; "" for MC_UNIT_NONE). */
const char *mc_unit_kind_name(mc_unit_kind kind);
const char *mc_unit_suffixes(mc_unit_kind kind);
const char *mc_unit_si_symbol(mc_unit_kind kind);

/* 1 if the n bytes at s are well-formed UTF-8 (no overlong forms, surrogates or code points
 * above U+10FFFF); otherwise 0 and, if bad_at is not NULL, the offset of the first bad byte. */
int mc_utf8_check(const char *s, size_t n, size_t *bad_at);

/* Copy text into buf (size len >= 8) for an error message: control bytes and bytes that are not
 * well-formed UTF-8 become \xNN, and text longer than 60 bytes is cut (at a character boundary)
 * with "...". Never fails; buf is always NUL-terminated. */
void mc_case_quote(const char *text, char *buf, size_t len);

#endif

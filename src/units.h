/* units.h - numbers with unit suffixes, as written in case files ("0.8 um", "210 GPa",
 * "500 N/mm", "30 mPa*s"); a bare number is SI. */
#ifndef MC_UNITS_H
#define MC_UNITS_H

#include <stddef.h>

typedef enum {
    MC_UNIT_NONE,             /* dimensionless: a bare number only */
    MC_UNIT_LENGTH,           /* m, mm, um (µm), nm */
    MC_UNIT_FORCE,            /* N, kN, mN */
    MC_UNIT_PRESSURE,         /* Pa, kPa, MPa, GPa (also moduli) */
    MC_UNIT_FORCE_PER_LENGTH, /* N/m, N/mm, kN/m, kN/mm */
    MC_UNIT_VISCOSITY,        /* Pa*s, mPa*s */
    MC_UNIT_SPEED,            /* m/s, mm/s */
    MC_UNIT_ROTATION          /* rpm (-> rad/s), rad/s, 1/s */
} mc_unit_kind;

/* Parse "number [unit]" into SI. Returns 0 on success; otherwise non-zero and a short reason in
 * why (e.g. "unit 'N' is a force, a length is due (m, mm, um, nm)"). Rejects NaN/Inf and
 * trailing garbage. */
int mc_parse_quantity(const char *text, mc_unit_kind kind, double *si, char *why, size_t whylen);

/* Name of a unit kind ("length") and its accepted suffixes ("m, mm, um, nm"). */
const char *mc_unit_kind_name(mc_unit_kind kind);
const char *mc_unit_suffixes(mc_unit_kind kind);

#endif

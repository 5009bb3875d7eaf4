/* units.c - numbers with unit suffixes (see units.h). */
#include "case/units.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *suffix;
    mc_unit_kind kind;
    double factor; /* SI value of one unit */
} unit_row;

/* Exact, case-sensitive matches: "mN" and "MN" must not be confused. */
static const unit_row units[] = {
    {"m", MC_UNIT_LENGTH, 1.0},
    {"mm", MC_UNIT_LENGTH, 1e-3},
    {"um", MC_UNIT_LENGTH, 1e-6},
    {"\xc2\xb5m", MC_UNIT_LENGTH, 1e-6}, /* U+00B5 MICRO SIGN */
    {"\xce\xbcm", MC_UNIT_LENGTH, 1e-6}, /* U+03BC GREEK SMALL LETTER MU (what keyboards give) */
    {"nm", MC_UNIT_LENGTH, 1e-9},
    {"N", MC_UNIT_FORCE, 1.0},
    {"kN", MC_UNIT_FORCE, 1e3},
    {"mN", MC_UNIT_FORCE, 1e-3},
    {"Pa", MC_UNIT_PRESSURE, 1.0},
    {"kPa", MC_UNIT_PRESSURE, 1e3},
    {"MPa", MC_UNIT_PRESSURE, 1e6},
    {"GPa", MC_UNIT_PRESSURE, 1e9},
    {"N/m", MC_UNIT_FORCE_PER_LENGTH, 1.0},
    {"N/mm", MC_UNIT_FORCE_PER_LENGTH, 1e3},
    {"kN/m", MC_UNIT_FORCE_PER_LENGTH, 1e3},
    {"kN/mm", MC_UNIT_FORCE_PER_LENGTH, 1e6},
    {"Pa*s", MC_UNIT_VISCOSITY, 1.0},
    {"Pa.s", MC_UNIT_VISCOSITY, 1.0},
    {"mPa*s", MC_UNIT_VISCOSITY, 1e-3},
    {"mPa.s", MC_UNIT_VISCOSITY, 1e-3},
    {"m/s", MC_UNIT_SPEED, 1.0},
    {"mm/s", MC_UNIT_SPEED, 1e-3},
    {"rpm", MC_UNIT_ROTATION, 6.283185307179586476925286766559 / 60.0},
    {"rad/s", MC_UNIT_ROTATION, 1.0},
    {"1/s", MC_UNIT_ROTATION, 1.0}, /* SI angular velocity: s^-1 is rad/s, not rev/s */
};

const char *mc_unit_kind_name(mc_unit_kind kind)
{
    switch (kind) {
    case MC_UNIT_NONE: return "dimensionless";
    case MC_UNIT_LENGTH: return "length";
    case MC_UNIT_FORCE: return "force";
    case MC_UNIT_PRESSURE: return "pressure";
    case MC_UNIT_FORCE_PER_LENGTH: return "force per length";
    case MC_UNIT_VISCOSITY: return "viscosity";
    case MC_UNIT_SPEED: return "speed";
    case MC_UNIT_ROTATION: return "rotation speed";
    }
    return "unknown";
}

const char *mc_unit_suffixes(mc_unit_kind kind)
{
    switch (kind) {
    case MC_UNIT_NONE: return "";
    case MC_UNIT_LENGTH: return "m, mm, um, nm";
    case MC_UNIT_FORCE: return "N, kN, mN";
    case MC_UNIT_PRESSURE: return "Pa, kPa, MPa, GPa";
    case MC_UNIT_FORCE_PER_LENGTH: return "N/m, N/mm, kN/m, kN/mm";
    case MC_UNIT_VISCOSITY: return "Pa*s, Pa.s, mPa*s, mPa.s";
    case MC_UNIT_SPEED: return "m/s, mm/s";
    case MC_UNIT_ROTATION: return "rpm, rad/s, 1/s";
    }
    return "";
}

const char *mc_unit_si_symbol(mc_unit_kind kind)
{
    switch (kind) {
    case MC_UNIT_NONE: return "";
    case MC_UNIT_LENGTH: return "m";
    case MC_UNIT_FORCE: return "N";
    case MC_UNIT_PRESSURE: return "Pa";
    case MC_UNIT_FORCE_PER_LENGTH: return "N/m";
    case MC_UNIT_VISCOSITY: return "Pa*s";
    case MC_UNIT_SPEED: return "m/s";
    case MC_UNIT_ROTATION: return "rad/s";
    }
    return "";
}

/* Length of the well-formed UTF-8 sequence starting at s (n bytes available), 0 if ill-formed
 * (Unicode 15, table 3-7). */
static size_t utf8_seq(const unsigned char *s, size_t n)
{
    unsigned c = s[0];
    if (c < 0x80)
        return 1;
    size_t len;
    unsigned lo = 0x80, hi = 0xBF; /* range of the second byte */
    if (c >= 0xC2 && c <= 0xDF)
        len = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        len = 3;
        if (c == 0xE0)
            lo = 0xA0; /* overlong */
        if (c == 0xED)
            hi = 0x9F; /* surrogates */
    } else if (c >= 0xF0 && c <= 0xF4) {
        len = 4;
        if (c == 0xF0)
            lo = 0x90; /* overlong */
        if (c == 0xF4)
            hi = 0x8F; /* above U+10FFFF */
    } else
        return 0;
    if (n < len || s[1] < lo || s[1] > hi)
        return 0;
    for (size_t k = 2; k < len; k++)
        if (s[k] < 0x80 || s[k] > 0xBF)
            return 0;
    return len;
}

int mc_utf8_check(const char *s, size_t n, size_t *bad_at)
{
    const unsigned char *u = (const unsigned char *)s;
    size_t i = 0;
    while (i < n) {
        size_t len = utf8_seq(u + i, n - i);
        if (len == 0) {
            if (bad_at)
                *bad_at = i;
            return 0;
        }
        i += len;
    }
    return 1;
}

void mc_case_quote(const char *text, char *buf, size_t len)
{
    enum { SHOWN = 60 };
    const unsigned char *u = (const unsigned char *)text;
    size_t n = strlen(text), i = 0, o = 0;
    if (len < 8) {
        if (len)
            buf[0] = '\0';
        return;
    }
    while (i < n) {
        char piece[8];
        size_t plen, adv;
        size_t seq = utf8_seq(u + i, n - i);
        if (seq == 0 || u[i] < 0x20 || u[i] == 0x7f) {
            snprintf(piece, sizeof piece, "\\x%02X", u[i]);
            plen = 4;
            adv = 1;
        } else {
            memcpy(piece, u + i, seq);
            plen = adv = seq;
        }
        /* keep room for "..." and the NUL */
        if (i + adv > SHOWN || o + plen + 4 > len) {
            memcpy(buf + o, "...", 3);
            o += 3;
            break;
        }
        memcpy(buf + o, piece, plen);
        o += plen;
        i += adv;
    }
    buf[o] = '\0';
}

static void say(char *why, size_t whylen, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void say(char *why, size_t whylen, const char *fmt, ...)
{
    if (why && whylen) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(why, whylen, fmt, ap);
        va_end(ap);
    }
}

/* "a length is due (m, mm, um, nm)" */
static void due(mc_unit_kind kind, char *out, size_t len)
{
    if (kind == MC_UNIT_NONE)
        snprintf(out, len, "a plain number is due (no unit)");
    else
        snprintf(out, len, "a %s is due (%s)", mc_unit_kind_name(kind), mc_unit_suffixes(kind));
}

static int starts_with_ci(const char *s, const char *word)
{
    for (; *word; s++, word++)
        if (tolower((unsigned char)*s) != *word)
            return 0;
    return 1;
}

int mc_parse_quantity(const char *text, mc_unit_kind kind, double *si, char *why, size_t whylen)
{
    char need[96], shown[96];
    due(kind, need, sizeof need);
    const char *p = text;
    while (isspace((unsigned char)*p))
        p++;
    const char *start = p;
    if (*p == '+' || *p == '-')
        p++;
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X')) {
        say(why, whylen, "hexadecimal numbers are not accepted; %s", need);
        return 1;
    }
    if (starts_with_ci(p, "nan") || starts_with_ci(p, "inf")) {
        say(why, whylen, "NaN and infinity are not accepted; %s", need);
        return 1;
    }
    /* The decimal syntax is checked here, so strtod only converts (and sees no locale-specific
     * or hexadecimal forms). */
    size_t ndigits = 0;
    while (isdigit((unsigned char)*p))
        p++, ndigits++;
    if (*p == '.') {
        p++;
        while (isdigit((unsigned char)*p))
            p++, ndigits++;
    }
    if (ndigits == 0) {
        if (*start == '\0')
            say(why, whylen, "a value is required; %s", need);
        else {
            mc_case_quote(start, shown, sizeof shown);
            say(why, whylen, "'%s' is not a number; %s", shown, need);
        }
        return 1;
    }
    if (*p == 'e' || *p == 'E') {
        const char *q = p + 1;
        if (*q == '+' || *q == '-')
            q++;
        if (isdigit((unsigned char)*q)) {
            while (isdigit((unsigned char)*q))
                q++;
            p = q;
        }
    }
    char num[128];
    size_t nlen = (size_t)(p - start);
    if (nlen >= sizeof num) {
        say(why, whylen, "the number is too long; %s", need);
        return 1;
    }
    memcpy(num, start, nlen);
    num[nlen] = '\0';
    errno = 0;
    double v = strtod(num, NULL);
    if (errno == ERANGE && !isfinite(v)) {
        say(why, whylen, "%s is out of range; %s", num, need);
        return 1;
    }

    while (*p == ' ' || *p == '\t')
        p++;
    size_t slen = strlen(p);
    while (slen > 0 && isspace((unsigned char)p[slen - 1]))
        slen--;
    if (slen == 0) {
        *si = v;
        return 0;
    }
    char suffix[64];
    if (slen >= sizeof suffix)
        slen = sizeof suffix - 1; /* longer than any unit: unknown either way */
    memcpy(suffix, p, slen);
    suffix[slen] = '\0';
    mc_case_quote(suffix, shown, sizeof shown);
    for (size_t k = 0; k < sizeof units / sizeof units[0]; k++) {
        if (strcmp(units[k].suffix, suffix) != 0)
            continue;
        if (units[k].kind != kind) {
            say(why, whylen, "unit '%s' is a %s; %s", shown, mc_unit_kind_name(units[k].kind),
                need);
            return 1;
        }
        double s = v * units[k].factor;
        if (!isfinite(s)) {
            say(why, whylen, "%s %s is out of range", num, shown);
            return 1;
        }
        *si = s;
        return 0;
    }
    if (kind == MC_UNIT_NONE)
        say(why, whylen, "unexpected '%s' after the number; %s", shown, need);
    else
        say(why, whylen, "unknown unit '%s'; %s", shown, need);
    return 1;
}

/* le.c - little-endian binary numbers (le.h). */
#include "io/le.h"

#include <string.h>

#define LE_CHUNK 512 /* doubles encoded per fwrite */

double mc_le64_get(const unsigned char *b)
{
    uint64_t u = 0;
    for (int k = 7; k >= 0; k--)
        u = (u << 8) | b[k];
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

void mc_le64_put(unsigned char *b, double d)
{
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    for (int k = 0; k < 8; k++) {
        b[k] = (unsigned char)(u & 0xff);
        u >>= 8;
    }
}

int mc_le_write_doubles(FILE *f, const double *v, size_t n)
{
    unsigned char buf[LE_CHUNK * 8];
    for (size_t k = 0; k < n; k += LE_CHUNK) {
        size_t m = n - k < LE_CHUNK ? n - k : LE_CHUNK;
        for (size_t q = 0; q < m; q++)
            mc_le64_put(buf + 8 * q, v[k + q]);
        if (fwrite(buf, 8, m, f) != m)
            return 0;
    }
    return 1;
}

int mc_le_write_u64(FILE *f, uint64_t u)
{
    unsigned char b[8];
    for (int k = 0; k < 8; k++)
        b[k] = (unsigned char)(u >> (8 * k));
    return fwrite(b, 1, 8, f) == 8;
}

/* le.h - little-endian binary numbers, independent of the host's byte order: the one encoder of
 * the .npy files, the VTK files and the X3P data. */
#ifndef MC_LE_H
#define MC_LE_H

#include <stdint.h>
#include <stdio.h>

/* The IEEE double stored little-endian at b (8 bytes), and its inverse. */
double mc_le64_get(const unsigned char *b);
void mc_le64_put(unsigned char *b, double d);

/* Write n doubles (or one uint64) little-endian to f in chunks. 1 when every byte was written,
 * 0 on a write error (ferror(f) is set; the caller reports it). */
int mc_le_write_doubles(FILE *f, const double *v, size_t n);
int mc_le_write_u64(FILE *f, uint64_t u);

#endif

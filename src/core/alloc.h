/* alloc.h - every allocation of the library goes through here.
 *
 * One place to (a) align arrays for FFTW/SIMD, (b) count allocations, and (c) inject failures:
 * a test can make the Nth allocation from now fail (SQLite's sqlite3FaultSim idea) and check
 * that every failure path frees what it took and reports MC_ERR_NOMEM cleanly.
 */
#ifndef MC_ALLOC_H
#define MC_ALLOC_H

#include <stddef.h>

/* malloc/calloc/free with fault injection. Memory is 64-byte aligned (fit for FFTW's SIMD).
 * Return NULL on failure (real or injected); mc_free(NULL) is a no-op. */
void *mc_malloc(size_t bytes);
void *mc_calloc(size_t count, size_t size);
void mc_free(void *ptr);

/* n doubles, zero-initialised; NULL on failure or overflow. */
double *mc_zeros(size_t n);

/* Large arrays (>= 4 MiB) are aligned to 2 MiB and advised as transparent huge pages (alloc.c
 * says why and what it saves); mc_alloc_huge_pages(0) turns that off for the allocations that
 * follow (the bench measures both), (1) on again. */
void mc_alloc_huge_pages(int on);

/* Fault injection: the nth allocation after this call fails (n >= 1); n = 0 disables.
 * Once triggered, injection disarms itself (only one allocation fails). */
void mc_alloc_fail_at(long n);

/* Number of successful allocations and of injected failures since start (for tests). */
long mc_alloc_count(void);
long mc_alloc_injected(void);

/* Overflow-safe size product: returns 0 and leaves *out untouched on overflow. */
int mc_size_mul(size_t a, size_t b, size_t *out);

#endif

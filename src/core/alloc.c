/* alloc.c - aligned allocation with fault injection (see alloc.h). */
#include "core/alloc.h"

#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define MC_ALIGN 64

static atomic_long fail_countdown; /* > 0: armed; the allocation that brings it to 0 fails */
static atomic_long n_allocs;
static atomic_long n_injected;

void mc_alloc_fail_at(long n) { atomic_store(&fail_countdown, n > 0 ? n : 0); }
long mc_alloc_count(void) { return atomic_load(&n_allocs); }
long mc_alloc_injected(void) { return atomic_load(&n_injected); }

static int injected_failure(void)
{
    long c = atomic_load(&fail_countdown);
    while (c > 0) {
        if (atomic_compare_exchange_weak(&fail_countdown, &c, c - 1))
            break;
    }
    if (c == 1) {
        atomic_fetch_add(&n_injected, 1);
        return 1;
    }
    return 0;
}

void *mc_malloc(size_t bytes)
{
    if (injected_failure())
        return NULL;
    void *p = NULL;
    size_t rounded = bytes ? (bytes + MC_ALIGN - 1) / MC_ALIGN * MC_ALIGN : MC_ALIGN;
    if (rounded < bytes || posix_memalign(&p, MC_ALIGN, rounded) != 0)
        return NULL;
    atomic_fetch_add(&n_allocs, 1);
    return p;
}

void *mc_calloc(size_t count, size_t size)
{
    size_t bytes;
    if (!mc_size_mul(count, size, &bytes))
        return NULL;
    void *p = mc_malloc(bytes);
    if (p)
        memset(p, 0, bytes);
    return p;
}

void mc_free(void *ptr) { free(ptr); }

double *mc_zeros(size_t n) { return mc_calloc(n, sizeof(double)); }

int mc_size_mul(size_t a, size_t b, size_t *out)
{
    if (a != 0 && b > SIZE_MAX / a)
        return 0;
    *out = a * b;
    return 1;
}

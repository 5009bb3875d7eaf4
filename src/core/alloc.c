/* alloc.c - aligned allocation with fault injection (see alloc.h). */
#include "core/alloc.h"

#include <stdatomic.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#define MC_ALIGN 64

/* Arrays of at least HUGE_MIN bytes are aligned to HUGE_PAGE and advised to the kernel as huge
 * page candidates (MADV_HUGEPAGE: transparent huge pages in their "madvise" mode, the default of
 * Debian's kernels). Why: a 4 KiB page fault costs microseconds, on a virtual machine more, and
 * the operators of the elastic-plastic stage touch ~2 GiB at 512 x 256 x 16; measured on the
 * project's machine, the residual stress operator's creation there took 9.3 s instead of
 * 10.6-11.1 s and one application 1.0-1.2 s instead of 1.5-1.7 s (one thread; fewer page faults
 * and TLB misses). The cost: up to HUGE_PAGE of address space per such array (not resident).
 * Without THP, or where madvise fails, nothing changes but the alignment. */
#define HUGE_PAGE ((size_t)2 << 20)
#define HUGE_MIN (2 * HUGE_PAGE)

static atomic_int huge_off; /* mc_alloc_huge_pages(0) */

static atomic_long fail_countdown; /* > 0: armed; the allocation that brings it to 0 fails */
static atomic_long n_allocs;
static atomic_long n_injected;

void mc_alloc_huge_pages(int on) { atomic_store(&huge_off, !on); }

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
    if (rounded < bytes)
        return NULL;
    if (rounded >= HUGE_MIN && !atomic_load(&huge_off)) {
        if (posix_memalign(&p, HUGE_PAGE, rounded) != 0)
            return NULL;
#ifdef MADV_HUGEPAGE
        (void)madvise(p, rounded, MADV_HUGEPAGE);
#endif
    } else if (posix_memalign(&p, MC_ALIGN, rounded) != 0) {
        return NULL;
    }
    atomic_fetch_add(&n_allocs, 1);
    return p;
}

void *mc_calloc(size_t count, size_t size)
{
    size_t bytes;
    if (!mc_size_mul(count, size, &bytes))
        return NULL;
    void *p = mc_malloc(bytes);
    if (!p)
        return NULL;
    if (bytes < HUGE_MIN) {
        memset(p, 0, bytes);
        return p;
    }
    /* zeroed by the run's threads, a huge page each at a time: the first touch (the page faults,
     * where the kernel clears the pages) is most of the cost and runs in parallel this way */
    const long chunks = (long)((bytes + HUGE_PAGE - 1) / HUGE_PAGE);
#pragma omp parallel for schedule(static)
    for (long c = 0; c < chunks; c++) {
        const size_t at = (size_t)c * HUGE_PAGE;
        memset((char *)p + at, 0, bytes - at < HUGE_PAGE ? bytes - at : HUGE_PAGE);
    }
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

/* increment.c - the sparse plastic strain increment (increment.h; docs/theory.md §9.9). */
#include "plastic/increment.h"

#include <stdlib.h>
#include <string.h>

#include "core/alloc.h"

#define W MC_INCR_WIDTH

int mc_incr_reserve(mc_plastic_incr *a, long n)
{
    if (n <= a->cap)
        return 1;
    long cap = a->cap ? a->cap : 1024;
    while (cap < n)
        cap *= 2;
    long *nc = mc_malloc((size_t)cap * sizeof *nc);
    double *nv = mc_malloc((size_t)cap * W * sizeof *nv);
    if (!nc || !nv) {
        mc_free(nc);
        mc_free(nv);
        return 0;
    }
    if (a->n) {
        memcpy(nc, a->cell, (size_t)a->n * sizeof *nc);
        memcpy(nv, a->val, (size_t)a->n * W * sizeof *nv);
    }
    mc_free(a->cell);
    mc_free(a->val);
    a->cell = nc;
    a->val = nv;
    a->cap = cap;
    return 1;
}

int mc_incr_push(mc_plastic_incr *a, long cell, const double v[W])
{
    if (!mc_incr_reserve(a, a->n + 1))
        return 0;
    a->cell[a->n] = cell;
    memcpy(a->val + (size_t)a->n * W, v, W * sizeof *v);
    a->n++;
    return 1;
}

int mc_incr_scaled(mc_plastic_incr *dst, const mc_plastic_incr *src, double s)
{
    dst->n = 0;
    if (!mc_incr_reserve(dst, src->n))
        return 0;
    for (long k = 0; k < src->n; k++) {
        double v[W];
        int any = 0;
        for (int q = 0; q < W; q++) {
            v[q] = s * src->val[(size_t)k * W + q];
            any |= v[q] != 0.0;
        }
        if (any)
            mc_incr_push(dst, src->cell[k], v); /* (room reserved) */
    }
    return 1;
}

void mc_incr_range(const mc_plastic_incr *a, long first, long last, long *k0, long *k1)
{
    const mc_eigen_sparse v = mc_incr_strain(a);
    mc_eigen_sparse_range(&v, first, last, k0, k1);
}

typedef struct {
    long cell, at;
} order_key;

static int by_cell(const void *x, const void *y)
{
    const long a = ((const order_key *)x)->cell, b = ((const order_key *)y)->cell;
    return (a > b) - (a < b);
}

int mc_incr_sort(mc_plastic_incr *a, mc_plastic_incr *tmp)
{
    int sorted = 1;
    for (long k = 1; k < a->n && sorted; k++)
        sorted = a->cell[k - 1] < a->cell[k];
    if (sorted)
        return 1;
    order_key *key = mc_malloc((size_t)a->n * sizeof *key);
    if (!key || !mc_incr_reserve(tmp, a->n)) {
        mc_free(key);
        return 0;
    }
    for (long k = 0; k < a->n; k++)
        key[k] = (order_key){a->cell[k], k};
    qsort(key, (size_t)a->n, sizeof *key, by_cell);
    tmp->n = 0;
    for (long k = 0; k < a->n; k++)
        mc_incr_push(tmp, key[k].cell, a->val + (size_t)key[k].at * W);
    mc_free(key);
    const mc_plastic_incr t = *a;
    *a = *tmp;
    *tmp = t;
    return 1;
}

mc_eigen_sparse mc_incr_strain(const mc_plastic_incr *a)
{
    return (mc_eigen_sparse){a->n, a->cell, a->val, W};
}

void mc_incr_scatter(const mc_plastic_incr *a, long nvol, double *d6, double *dp)
{
    for (long k = 0; k < a->n; k++) {
        const size_t v = (size_t)a->cell[k];
        for (int q = 0; q < 6; q++)
            d6[(size_t)q * (size_t)nvol + v] = a->val[(size_t)k * W + q];
        if (dp)
            dp[v] = a->val[(size_t)k * W + 6];
    }
}

int mc_incr_gather(mc_plastic_incr *a, long nvol, const double *d6, const double *dp)
{
    a->n = 0;
    for (long v = 0; v < nvol; v++) {
        double e[W];
        int any = 0;
        for (int q = 0; q < 6; q++) {
            e[q] = d6[(size_t)q * (size_t)nvol + (size_t)v];
            any |= e[q] != 0.0;
        }
        e[6] = dp[v];
        any |= e[6] != 0.0;
        if (any && !mc_incr_push(a, v, e))
            return 0;
    }
    return 1;
}

int mc_incr_any(const mc_plastic_incr *a)
{
    for (size_t i = 0; i < (size_t)a->n * W; i++)
        if (a->val[i] != 0.0)
            return 1;
    return 0;
}

void mc_incr_free(mc_plastic_incr *a)
{
    mc_free(a->cell);
    mc_free(a->val);
    memset(a, 0, sizeof *a);
}

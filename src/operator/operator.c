/* operator.c - conv + one kernel: what a solver plans, applies and destroys; (see operator.h). */
#include <fftw3.h>

#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "operator/operator.h"

struct mc_operator {
    mc_conv *conv;
    double *kspec; /* the transformed kernel (real parts only when real_kernel) */
    double *lspec; /* workspace of mc_conv_convolve (direct backend only) */
    int real_kernel;
};

/* Takes ownership of conv (destroyed on failure too). */
static int plan_with_conv(mc_conv *conv, const mc_kernel_table *t, mc_operator **out,
                          mc_error *err)
{
    const size_t n = mc_conv_spectrum_len(conv);
    mc_operator *op = mc_calloc(1, sizeof *op);
    int rc;
    const size_t nw = mc_conv_work_len(conv);
    rc = MC_OK;
    if (!op || (nw && !(op->lspec = mc_malloc(nw * sizeof *op->lspec))))
        rc = mc_fail(err, MC_ERR_NOMEM, "operator: out of memory for its workspace");
    /* an even kernel keeps only the real half of its spectrum */
    if (rc == MC_OK && mc_conv_backend(conv) == MC_BACKEND_FFT) {
        if (!(op->kspec = mc_malloc(n / 2 * sizeof *op->kspec)))
            rc = mc_fail(err, MC_ERR_NOMEM, "operator: out of memory for a %zu-double spectrum",
                         n / 2);
        else if (!(op->real_kernel = mc_conv_kernel_real(conv, t, op->kspec))) {
            mc_free(op->kspec);
            op->kspec = NULL;
        }
    }
    if (rc == MC_OK && !op->real_kernel) {
        if (!(op->kspec = mc_malloc(n * sizeof *op->kspec)))
            rc = mc_fail(err, MC_ERR_NOMEM, "operator: out of memory for %zu-double spectra", n);
        else
            rc = mc_conv_kernel(conv, t, op->kspec, err);
    }
    if (rc) {
        if (op) {
            mc_free(op->kspec);
            mc_free(op->lspec);
            mc_free(op);
        }
        mc_conv_destroy(&conv);
        return rc;
    }
    op->conv = conv;
    *out = op;
    return MC_OK;
}

int mc_operator_plan(const mc_grid *g, const mc_kernel_table *t, mc_backend b, mc_operator **out,
                     mc_error *err)
{
    *out = NULL;
    mc_conv *conv;
    int rc = mc_conv_create_distributed(g, b, &conv, err);
    return rc ? rc : plan_with_conv(conv, t, out, err);
}

/* Distributed (mc_conv_table_rows): each rank tabulates and transforms its rows of the table
 * alone (operator.h, mc_conv_kernel_rows); the same spectrum as the whole table's. Takes
 * ownership of conv. Collective. */
static int plan_love_rows(mc_conv *conv, const mc_grid *g, double Estar, int j0, int nj,
                          mc_operator **out, mc_error *err)
{
    int tx, ty;
    mc_conv_table_dims(conv, &tx, &ty);
    const size_t w = 2 * (size_t)(tx / 2 + 1), n = mc_conv_spectrum_len(conv);
    double *rows = mc_zeros((size_t)nj * w + 1);
    mc_operator *op = mc_calloc(1, sizeof *op);
    double *kspec = mc_malloc((n + 1) * sizeof *kspec);
    int rc = rows && op && kspec ? MC_OK
                                 : mc_fail(err, MC_ERR_NOMEM, "operator: out of memory for %d "
                                                              "rows of its kernel table", nj);
    if (rc == MC_OK)
        rc = mc_kernel_table_love_rows(g, tx, ty, Estar, j0, nj, rows, err);
    if (rc == MC_OK) /* the rows at the spectrum's stride, from the last (row r: r tx -> r w) */
        for (int r = nj - 1; r > 0; r--)
            memmove(rows + (size_t)r * w, rows + (size_t)r * tx, (size_t)tx * sizeof *rows);
    int any = mc_dist_max_int(rc != MC_OK); /* all ranks go on, or none */
    int real = 0;
    if (!any) {
        rc = mc_conv_kernel_rows(conv, rows, kspec, &real, err);
        any = rc != MC_OK;
    } else if (rc == MC_OK) {
        rc = mc_fail(err, MC_ERR_NOMEM, "operator: another process could not tabulate its rows");
    }
    mc_free(rows);
    if (any) {
        mc_free(kspec);
        mc_free(op);
        mc_conv_destroy(&conv);
        return rc;
    }
    if (real) { /* half the memory: the real parts are the first n / 2 doubles */
        double *k2 = mc_malloc((n / 2 + 1) * sizeof *k2);
        if (k2) {
            memcpy(k2, kspec, n / 2 * sizeof *k2);
            mc_free(kspec);
            kspec = k2;
        }
    }
    op->kspec = kspec;
    op->real_kernel = real;
    op->conv = conv;
    *out = op;
    return MC_OK;
}

int mc_operator_plan_love(const mc_grid *g, double Estar, mc_backend b, mc_operator **out,
                          mc_error *err)
{
    *out = NULL;
    mc_conv *conv;
    int rc = mc_conv_create_distributed(g, b, &conv, err);
    if (rc)
        return rc;
    int tx, ty, j0, nj;
    if (mc_conv_table_rows(conv, &j0, &nj))
        return plan_love_rows(conv, g, Estar, j0, nj, out, err);
    mc_conv_table_dims(conv, &tx, &ty);
    mc_kernel_table t;
    if ((rc = mc_kernel_table_love(g, tx, ty, Estar, &t, err))) {
        mc_conv_destroy(&conv);
        return rc;
    }
    rc = plan_with_conv(conv, &t, out, err);
    mc_kernel_table_free(&t);
    return rc;
}

void mc_operator_apply(mc_operator *op, const double *in, double *out)
{
    if (op->real_kernel)
        mc_conv_convolve_real(op->conv, op->kspec, in, out);
    else
        mc_conv_convolve(op->conv, op->kspec, in, out, op->lspec);
}

void mc_operator_apply_rows(mc_operator *op, const double *in, double *out)
{
    mc_conv_convolve_rows(op->conv, op->kspec, op->real_kernel ? op->kspec : NULL, in, out,
                          op->lspec);
}

int mc_operator_rows(const mc_operator *op, int *r0, int *nr)
{
    return mc_conv_rows(op->conv, r0, nr);
}

void mc_operator_destroy(mc_operator **op)
{
    if (!op || !*op)
        return;
    mc_conv_destroy(&(*op)->conv);
    mc_free((*op)->kspec);
    mc_free((*op)->lspec);
    mc_free(*op);
    *op = NULL;
}

const mc_grid *mc_operator_grid(const mc_operator *op) { return mc_conv_grid(op->conv); }
mc_backend mc_operator_backend(const mc_operator *op) { return mc_conv_backend(op->conv); }

/* conv.c - the transform engine: one grid, one backend, many kernels (see operator.h).
 * Backends are rows of a table chosen by name; each row owns its workspace in the engine. */
#include <fftw3.h>
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/fftsize.h"
#include "operator/operator.h"

/* Below this many values a memory-bound loop is not worth waking the thread team. */
#define PAR_MIN MC_THREADS_MIN_CELLS
/* Transforms smaller than this run on one thread (see MC_THREADS_MIN_CELLS). */
#define FFT_THREADS_MIN MC_THREADS_MIN_CELLS

typedef struct conv_ops conv_ops;

struct mc_conv {
    mc_grid g;
    const conv_ops *ops;
    int tx, ty;          /* kernel table (and transform) size */
    size_t speclen;      /* doubles per spectrum */
    double *rbuf;        /* fft: ty*tx real workspace (the padded field) */
    fftw_complex *cbuf;  /* fft: ty*(tx/2+1) half spectrum */
    fftw_plan r2c, c2r;  /* fft: rbuf -> cbuf and back (2-D plans) */
    /* fft, free y axis: the same transforms pruned of the all-zero padding rows — rows are
     * transformed only where the field has data (forward) or where output is wanted (inverse),
     * columns in full: 1/4 fewer butterflies than the 2-D pair, identical results to round-off */
    int pruned;
    fftw_plan row_r2c, col_fwd, col_bwd, row_c2r;
};

struct conv_ops {
    const char *name;
    mc_backend id;
    int (*create)(mc_conv *c, mc_error *err); /* sets speclen, takes the workspace */
    void (*kernel)(mc_conv *c, const double *table, double *kspec);
    void (*load)(mc_conv *c, const double *field, double *lspec);
    void (*apply)(mc_conv *c, int nterms, const double *const *kspec, const double *const *lspec,
                  double *out);
    void (*convolve)(mc_conv *c, const double *kspec, const double *field, double *out,
                     double *work);
    void (*destroy)(mc_conv *c); /* frees what create took; safe on a half-built engine */
};

/* ---- fft: DC-FFT (elastic.md 5.1) and cyclic FFT (5.2) ------------------------------------- */

static size_t half_len(const mc_conv *c) { return (size_t)c->ty * (size_t)(c->tx / 2 + 1); }

static int fft_create(mc_conv *c, mc_error *err)
{
    int rc = mc_fftw_prepare(err);
    if (rc)
        return rc;
    size_t nr, nc = half_len(c);
    if (!mc_size_mul((size_t)c->tx, (size_t)c->ty, &nr) ||
        !(c->rbuf = mc_malloc(nr * sizeof *c->rbuf)) ||
        !(c->cbuf = mc_malloc(nc * sizeof *c->cbuf)))
        return mc_fail(err, MC_ERR_NOMEM, "fft engine %d x %d: out of memory", c->tx, c->ty);
    if ((size_t)c->tx * c->ty < FFT_THREADS_MIN)
        fftw_plan_with_nthreads(1);
    /* row-major (ty, tx) with x fastest; ESTIMATE: no trial runs, the same plan every time */
    c->r2c = fftw_plan_dft_r2c_2d(c->ty, c->tx, c->rbuf, c->cbuf, FFTW_ESTIMATE);
    c->c2r = fftw_plan_dft_c2r_2d(c->ty, c->tx, c->cbuf, c->rbuf, FFTW_ESTIMATE);
    if (!c->r2c || !c->c2r)
        return mc_fail(err, MC_ERR_NOMEM, "fft engine: FFTW could not plan %d x %d", c->tx, c->ty);
    c->pruned = c->ty > c->g.ny;
    if (c->pruned) {
        const int hx = c->tx / 2 + 1, ny = c->g.ny;
        int nrow[1] = {c->tx}, ncol[1] = {c->ty};
        c->row_r2c = fftw_plan_many_dft_r2c(1, nrow, ny, c->rbuf, NULL, 1, c->tx, c->cbuf, NULL, 1,
                                            hx, FFTW_ESTIMATE);
        c->row_c2r = fftw_plan_many_dft_c2r(1, nrow, ny, c->cbuf, NULL, 1, hx, c->rbuf, NULL, 1,
                                            c->tx, FFTW_ESTIMATE);
        c->col_fwd = fftw_plan_many_dft(1, ncol, hx, c->cbuf, NULL, hx, 1, c->cbuf, NULL, hx, 1,
                                        FFTW_FORWARD, FFTW_ESTIMATE);
        c->col_bwd = fftw_plan_many_dft(1, ncol, hx, c->cbuf, NULL, hx, 1, c->cbuf, NULL, hx, 1,
                                        FFTW_BACKWARD, FFTW_ESTIMATE);
        if (!c->row_r2c || !c->row_c2r || !c->col_fwd || !c->col_bwd)
            return mc_fail(err, MC_ERR_NOMEM, "fft engine: FFTW could not plan the pruned %d x %d",
                           c->tx, c->ty);
    }
    c->speclen = 2 * nc;
    return MC_OK;
}

static void fft_destroy(mc_conv *c)
{
    fftw_plan plans[] = {c->r2c, c->c2r, c->row_r2c, c->row_c2r, c->col_fwd, c->col_bwd};
    for (size_t k = 0; k < sizeof plans / sizeof plans[0]; k++)
        if (plans[k])
            fftw_destroy_plan(plans[k]);
    mc_free(c->rbuf);
    mc_free(c->cbuf);
}

static void fft_kernel(mc_conv *c, const double *table, double *kspec)
{
    const size_t nc = half_len(c);
    const double scale = 1.0 / ((double)c->tx * (double)c->ty); /* FFTW does not normalise */
    memcpy(c->rbuf, table, (size_t)c->tx * (size_t)c->ty * sizeof *table);
    fftw_execute(c->r2c);
    const double *s = (const double *)c->cbuf;
    for (size_t q = 0; q < 2 * nc; q++)
        kspec[q] = scale * s[q];
}

/* The zero-padded field into rbuf (the padding is rewritten each time: c2r leaves it dirty);
 * the pruned transform reads only the first ny rows. */
static void fft_fill(mc_conv *c, const double *field)
{
    const int nx = c->g.nx, ny = c->g.ny, tx = c->tx, ty = c->pruned ? c->g.ny : c->ty;
    double *r = c->rbuf;
#pragma omp parallel for schedule(static) if ((size_t)tx * ty > PAR_MIN)
    for (int j = 0; j < ty; j++) {
        double *row = r + (size_t)j * tx;
        if (j < ny) {
            memcpy(row, field + (size_t)j * nx, (size_t)nx * sizeof *row);
            memset(row + nx, 0, (size_t)(tx - nx) * sizeof *row);
        } else {
            memset(row, 0, (size_t)tx * sizeof *row);
        }
    }
}

/* The first ny rows and nx columns of rbuf into out. */
static void fft_crop(mc_conv *c, double *out)
{
    const int nx = c->g.nx, ny = c->g.ny, tx = c->tx;
#pragma omp parallel for schedule(static) if ((size_t)nx * ny > PAR_MIN)
    for (int j = 0; j < ny; j++)
        memcpy(out + (size_t)j * nx, c->rbuf + (size_t)j * tx, (size_t)nx * sizeof *out);
}

/* rbuf (field rows) -> cbuf (half spectrum) */
static void fft_forward(mc_conv *c)
{
    if (!c->pruned) {
        fftw_execute(c->r2c);
        return;
    }
    const size_t hx = (size_t)(c->tx / 2 + 1);
    fftw_execute(c->row_r2c);
    memset(c->cbuf + (size_t)c->g.ny * hx, 0, (size_t)(c->ty - c->g.ny) * hx * sizeof *c->cbuf);
    fftw_execute(c->col_fwd);
}

/* cbuf -> rbuf (at least the first ny rows); destroys cbuf */
static void fft_inverse(mc_conv *c)
{
    if (!c->pruned) {
        fftw_execute(c->c2r);
        return;
    }
    fftw_execute(c->col_bwd);
    fftw_execute(c->row_c2r);
}

static void fft_load(mc_conv *c, const double *field, double *lspec)
{
    fft_fill(c, field);
    fft_forward(c);
    const long n = 2 * (long)half_len(c);
    const double *s = (const double *)c->cbuf;
#pragma omp parallel for schedule(static) if (n > 2 * PAR_MIN)
    for (long q = 0; q < n; q++)
        lspec[q] = s[q];
}

static void fft_apply(mc_conv *c, int nterms, const double *const *kspec,
                      const double *const *lspec, double *out)
{
    const long nc = (long)half_len(c);
    double *s = (double *)c->cbuf;
#pragma omp parallel for schedule(static) if (nc > PAR_MIN)
    for (long q = 0; q < nc; q++) {
        double re = 0.0, im = 0.0;
        for (int t = 0; t < nterms; t++) {
            const double kr = kspec[t][2 * q], ki = kspec[t][2 * q + 1];
            const double lr = lspec[t][2 * q], li = lspec[t][2 * q + 1];
            re += kr * lr - ki * li;
            im += kr * li + ki * lr;
        }
        s[2 * q] = re;
        s[2 * q + 1] = im;
    }
    fft_inverse(c); /* destroys cbuf: it is ours */
    fft_crop(c, out);
}

/* One kernel, one load, without the intermediate load spectrum: the operator's hot path. */
static void fft_convolve(mc_conv *c, const double *kspec, const double *field, double *out,
                         double *work)
{
    (void)work;
    fft_fill(c, field);
    fft_forward(c);
    const long nc = (long)half_len(c);
    double *s = (double *)c->cbuf;
#pragma omp parallel for schedule(static) if (nc > PAR_MIN)
    for (long q = 0; q < nc; q++) {
        const double kr = kspec[2 * q], ki = kspec[2 * q + 1];
        const double lr = s[2 * q], li = s[2 * q + 1];
        s[2 * q] = kr * lr - ki * li;
        s[2 * q + 1] = kr * li + ki * lr;
    }
    fft_inverse(c);
    fft_crop(c, out);
}

/* ---- direct: the O(N^2) reference ----------------------------------------------------------- */

static int direct_create(mc_conv *c, mc_error *err)
{
    (void)err;
    c->speclen = (size_t)c->tx * (size_t)c->ty; /* >= nx*ny: holds a table or a field */
    return MC_OK;
}

static void direct_destroy(mc_conv *c) { (void)c; }

static void direct_kernel(mc_conv *c, const double *table, double *kspec)
{
    memcpy(kspec, table, (size_t)c->tx * (size_t)c->ty * sizeof *kspec);
}

static void direct_load(mc_conv *c, const double *field, double *lspec)
{
    memcpy(lspec, field, mc_grid_cells(&c->g) * sizeof *lspec);
}

/* Table index of offset o in (-len, len) (field minus source): the wrap-around layout. */
static inline int wrap(int o, int len) { return o >= 0 ? o : o + len; }

static void direct_apply(mc_conv *c, int nterms, const double *const *kspec,
                         const double *const *lspec, double *out)
{
    const int nx = c->g.nx, ny = c->g.ny, tx = c->tx, ty = c->ty;
#pragma omp parallel for schedule(static)
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double u = 0.0;
            for (int t = 0; t < nterms; t++)
                for (int js = 0; js < ny; js++) {
                    const double *krow = kspec[t] + (size_t)wrap(j - js, ty) * tx;
                    const double *frow = lspec[t] + (size_t)js * nx;
                    for (int is = 0; is < nx; is++)
                        u += krow[wrap(i - is, tx)] * frow[is];
                }
            out[(size_t)j * nx + i] = u;
        }
}

/* work holds the load, so field may be out */
static void direct_convolve(mc_conv *c, const double *kspec, const double *field, double *out,
                            double *work)
{
    direct_load(c, field, work);
    const double *k = kspec, *l = work;
    direct_apply(c, 1, &k, &l, out);
}

/* ---- the backend table ---------------------------------------------------------------------- */

static const conv_ops backends[] = {
    {"fft", MC_BACKEND_FFT, fft_create, fft_kernel, fft_load, fft_apply, fft_convolve,
     fft_destroy},
    {"direct", MC_BACKEND_DIRECT, direct_create, direct_kernel, direct_load, direct_apply,
     direct_convolve, direct_destroy},
};
#define N_BACKENDS ((int)(sizeof backends / sizeof backends[0]))

static const conv_ops *find_backend(mc_backend b)
{
    for (int i = 0; i < N_BACKENDS; i++)
        if (backends[i].id == b)
            return &backends[i];
    return NULL;
}

const char *mc_backend_name(mc_backend b)
{
    const conv_ops *ops = find_backend(b);
    return ops ? ops->name : "?";
}

int mc_backend_from_name(const char *name, mc_backend *out)
{
    for (int i = 0; name && i < N_BACKENDS; i++)
        if (strcmp(name, backends[i].name) == 0) {
            *out = backends[i].id;
            return MC_OK;
        }
    return MC_ERR_INPUT;
}


/* ---- the engine ------------------------------------------------------------------------------ */

int mc_conv_create(const mc_grid *g, mc_backend b, mc_conv **out, mc_error *err)
{
    *out = NULL;
    int rc = mc_grid_check(g, err);
    if (rc)
        return rc;
    const conv_ops *ops = find_backend(b);
    if (!ops)
        return mc_fail(err, MC_ERR_INPUT, "unknown operator backend %d (accepted: fft, direct)",
                       (int)b);
    mc_conv *c = mc_calloc(1, sizeof *c);
    if (!c)
        return mc_fail(err, MC_ERR_NOMEM, "convolution engine: out of memory");
    c->g = *g;
    c->ops = ops;
    c->tx = g->periodic_x ? g->nx : mc_fft_good_size(2 * g->nx - 1);
    c->ty = g->periodic_y ? g->ny : mc_fft_good_size(2 * g->ny - 1);
    if ((rc = ops->create(c, err))) {
        ops->destroy(c);
        mc_free(c);
        return rc;
    }
    *out = c;
    return MC_OK;
}

void mc_conv_destroy(mc_conv **c)
{
    if (!c || !*c)
        return;
    (*c)->ops->destroy(*c);
    mc_free(*c);
    *c = NULL;
}

void mc_conv_table_dims(const mc_conv *c, int *tx, int *ty)
{
    *tx = c->tx;
    *ty = c->ty;
}

size_t mc_conv_spectrum_len(const mc_conv *c) { return c->speclen; }

/* A table is usable only with the grid and sizes it was built for. */
static int table_matches(const mc_conv *c, const mc_kernel_table *t, mc_error *err)
{
    const mc_grid *a = &c->g, *b = &t->grid;
    if (!t->k || t->tx != c->tx || t->ty != c->ty || a->nx != b->nx || a->ny != b->ny ||
        a->dx != b->dx || a->dy != b->dy || a->periodic_x != b->periodic_x ||
        a->periodic_y != b->periodic_y)
        return mc_fail(err, MC_ERR_INPUT,
                       "kernel table %d x %d (grid %d x %d, dx %g m, dy %g m, periodic %d/%d) does "
                       "not match the engine's %d x %d (grid %d x %d, dx %g m, dy %g m, periodic "
                       "%d/%d)",
                       t->tx, t->ty, b->nx, b->ny, b->dx, b->dy, b->periodic_x, b->periodic_y,
                       c->tx, c->ty, a->nx, a->ny, a->dx, a->dy, a->periodic_x, a->periodic_y);
    return MC_OK;
}

int mc_conv_kernel(mc_conv *c, const mc_kernel_table *t, double *kspec, mc_error *err)
{
    int rc = table_matches(c, t, err);
    if (rc == MC_OK)
        c->ops->kernel(c, t->k, kspec);
    return rc;
}

void mc_conv_load(mc_conv *c, const double *field, double *lspec)
{
    c->ops->load(c, field, lspec);
}

void mc_conv_apply(mc_conv *c, int nterms, const double *const *kspec, const double *const *lspec,
                   double *out)
{
    c->ops->apply(c, nterms, kspec, lspec, out);
}

void mc_conv_convolve(mc_conv *c, const double *kspec, const double *field, double *out,
                      double *work)
{
    c->ops->convolve(c, kspec, field, out, work);
}

size_t mc_conv_work_len(const mc_conv *c)
{
    return c->ops->id == MC_BACKEND_DIRECT ? mc_grid_cells(&c->g) : 0;
}

int mc_conv_kernel_real(mc_conv *c, const mc_kernel_table *t, double *kre)
{
    if (c->ops->id != MC_BACKEND_FFT || table_matches(c, t, NULL) != MC_OK)
        return 0; /* mc_conv_kernel then reports the mismatch */
    const size_t nc = half_len(c);
    memcpy(c->rbuf, t->k, (size_t)c->tx * (size_t)c->ty * sizeof *t->k);
    fftw_execute(c->r2c);
    const double *s = (const double *)c->cbuf;
    double re = 0, im = 0;
    for (size_t q = 0; q < nc; q++) {
        re = fmax(re, fabs(s[2 * q]));
        im = fmax(im, fabs(s[2 * q + 1]));
    }
    if (!(im <= 1e-13 * re))
        return 0;
    const double scale = 1.0 / ((double)c->tx * (double)c->ty);
    for (size_t q = 0; q < nc; q++)
        kre[q] = scale * s[2 * q];
    return 1;
}

void mc_conv_convolve_real(mc_conv *c, const double *kre, const double *field, double *out)
{
    fft_fill(c, field);
    fft_forward(c);
    const long nc = (long)half_len(c);
    double *s = (double *)c->cbuf;
#pragma omp parallel for schedule(static) if (nc > PAR_MIN)
    for (long q = 0; q < nc; q++) {
        s[2 * q] *= kre[q];
        s[2 * q + 1] *= kre[q];
    }
    fft_inverse(c);
    fft_crop(c, out);
}

mc_backend mc_conv_backend(const mc_conv *c) { return c->ops->id; }
const mc_grid *mc_conv_grid(const mc_conv *c) { return &c->g; }

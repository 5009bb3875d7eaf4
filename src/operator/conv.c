/* conv.c - the transform engine: one grid, one backend, many kernels (see operator.h).
 * Backends are rows of a table chosen by name; each row owns its workspace in the engine. */
#include <math.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/fftsize.h"
#include "operator/dfft.h"
#include "operator/operator.h"
#include "operator/padfft.h"

/* Below this many values a memory-bound loop is not worth waking the thread team. */
#define PAR_MIN MC_THREADS_MIN_CELLS

typedef struct conv_ops conv_ops;

struct mc_conv {
    mc_grid g;
    const conv_ops *ops;
    int tx, ty;     /* kernel table (and transform) size */
    size_t speclen; /* doubles per spectrum */
    mc_padfft fft;  /* fft: the padded transforms (2-D pair for tables, pruned for fields) */
    int distribute; /* fft: asked to distribute its transforms over the run's ranks */
    mc_dfft *dfft;  /* fft over the ranks (dfft.h) instead of fft; NULL serially */
    int rows_only;  /* dfft: field and out are this rank's rows only (mc_conv_convolve_rows) */
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

/* ---- fft: DC-FFT (theory.md §3.1) and cyclic FFT (§3.2) ---------------------------------- */

/* Complex values of this process's spectrum (all of it serially, its columns over ranks). */
static size_t half_len(const mc_conv *c) { return c->speclen / 2; }

/* The engine's own spectrum, and the transform pair into and out of it: serial (padfft.h) or
 * over the run's ranks (dfft.h; the spectrum is then this rank's slab of columns). */
static fftw_complex *work_spec(mc_conv *c)
{
    return c->dfft ? mc_dfft_spectrum(c->dfft) : c->fft.cbuf;
}

static void forward(mc_conv *c, const double *field)
{
    if (c->dfft)
        mc_dfft_forward(c->dfft, field, mc_dfft_spectrum(c->dfft), c->rows_only);
    else
        mc_padfft_forward(&c->fft, field, c->fft.cbuf);
}

static void inverse(mc_conv *c, double *out)
{
    if (c->dfft)
        mc_dfft_inverse(c->dfft, out, c->rows_only);
    else
        mc_padfft_inverse(&c->fft, out);
}

/* A whole kernel table forward into the engine's spectrum. */
static void table_forward(mc_conv *c, const double *table)
{
    if (c->dfft)
        mc_dfft_table(c->dfft, table, mc_dfft_spectrum(c->dfft));
    else
        mc_padfft_table(&c->fft, table);
}

static int fft_create(mc_conv *c, mc_error *err)
{
    if (c->distribute) {
        int rc = mc_dfft_create(c->g.nx, c->g.ny, c->tx, c->ty, &c->dfft, err);
        if (rc == MC_OK)
            c->speclen = mc_dfft_spectrum_len(c->dfft);
        return rc;
    }
    int rc = mc_padfft_create(&c->fft, c->g.nx, c->g.ny, c->tx, c->ty, 1, err);
    if (rc == MC_OK)
        c->speclen = mc_padfft_spectrum_len(&c->fft);
    return rc;
}

static void fft_destroy(mc_conv *c)
{
    mc_padfft_destroy(&c->fft);
    mc_dfft_destroy(&c->dfft);
}

static void fft_kernel(mc_conv *c, const double *table, double *kspec)
{
    const size_t nc = half_len(c);
    const double scale = 1.0 / ((double)c->tx * (double)c->ty); /* FFTW does not normalise */
    table_forward(c, table);
    const double *s = (const double *)work_spec(c);
    for (size_t q = 0; q < 2 * nc; q++)
        kspec[q] = scale * s[q];
}

static void fft_load(mc_conv *c, const double *field, double *lspec)
{
    forward(c, field);
    const long n = 2 * (long)half_len(c);
    const double *s = (const double *)work_spec(c);
#pragma omp parallel for schedule(static) if (n > 2 * PAR_MIN)
    for (long q = 0; q < n; q++)
        lspec[q] = s[q];
}

static void fft_apply(mc_conv *c, int nterms, const double *const *kspec,
                      const double *const *lspec, double *out)
{
    const long nc = (long)half_len(c);
    double *s = (double *)work_spec(c);
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
    inverse(c, out); /* destroys the spectrum: it is ours */
}

/* One kernel, one load, without the intermediate load spectrum: the operator's hot path. The
 * kernel's spectrum is complex (kspec) or, for an even kernel, its real parts (kre). */
static void fft_convolve_one(mc_conv *c, const double *kspec, const double *kre,
                             const double *field, double *out)
{
    forward(c, field);
    const long nc = (long)half_len(c);
    double *s = (double *)work_spec(c);
    if (kre) {
#pragma omp parallel for schedule(static) if (nc > PAR_MIN)
        for (long q = 0; q < nc; q++) {
            s[2 * q] *= kre[q];
            s[2 * q + 1] *= kre[q];
        }
    } else {
#pragma omp parallel for schedule(static) if (nc > PAR_MIN)
        for (long q = 0; q < nc; q++) {
            const double kr = kspec[2 * q], ki = kspec[2 * q + 1];
            const double lr = s[2 * q], li = s[2 * q + 1];
            s[2 * q] = kr * lr - ki * li;
            s[2 * q + 1] = kr * li + ki * lr;
        }
    }
    inverse(c, out);
}

static void fft_convolve(mc_conv *c, const double *kspec, const double *field, double *out,
                         double *work)
{
    (void)work;
    fft_convolve_one(c, kspec, NULL, field, out);
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

static int create(const mc_grid *g, mc_backend b, int distribute, mc_conv **out, mc_error *err)
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
    c->distribute = distribute && b == MC_BACKEND_FFT && mc_dist_active();
    c->tx = g->periodic_x ? g->nx : mc_fftsize_good(2 * g->nx - 1);
    c->ty = g->periodic_y ? g->ny : mc_fftsize_good(2 * g->ny - 1);
    if ((rc = ops->create(c, err))) {
        ops->destroy(c);
        mc_free(c);
        return rc;
    }
    *out = c;
    return MC_OK;
}

int mc_conv_create(const mc_grid *g, mc_backend b, mc_conv **out, mc_error *err)
{
    return create(g, b, 0, out, err);
}

int mc_conv_create_distributed(const mc_grid *g, mc_backend b, mc_conv **out, mc_error *err)
{
    return create(g, b, 1, out, err);
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
    table_forward(c, t->k);
    const double *s = (const double *)work_spec(c);
    double m[2] = {0, 0}; /* max |Re|, max |Im| */
    for (size_t q = 0; q < nc; q++) {
        m[0] = fmax(m[0], fabs(s[2 * q]));
        m[1] = fmax(m[1], fabs(s[2 * q + 1]));
    }
    if (c->dfft) /* over all ranks: they must all take the same path */
        mc_dist_max(m, 2);
    const double re = m[0], im = m[1];
    if (!(im <= 1e-13 * re))
        return 0;
    const double scale = 1.0 / ((double)c->tx * (double)c->ty);
    for (size_t q = 0; q < nc; q++)
        kre[q] = scale * s[2 * q];
    return 1;
}

void mc_conv_convolve_real(mc_conv *c, const double *kre, const double *field, double *out)
{
    fft_convolve_one(c, NULL, kre, field, out);
}

void mc_conv_convolve_rows(mc_conv *c, const double *kspec, const double *kre,
                           const double *field, double *out, double *work)
{
    c->rows_only = 1;
    if (kre)
        fft_convolve_one(c, NULL, kre, field, out);
    else
        c->ops->convolve(c, kspec, field, out, work);
    c->rows_only = 0;
}

int mc_conv_rows(const mc_conv *c, int *r0, int *nr)
{
    *r0 = 0;
    *nr = c->g.ny;
    if (c->dfft)
        mc_dfft_rows(c->dfft, r0, nr);
    return c->dfft != NULL;
}

mc_backend mc_conv_backend(const mc_conv *c) { return c->ops->id; }
const mc_grid *mc_conv_grid(const mc_conv *c) { return &c->g; }

int mc_conv_table_rows(const mc_conv *c, int *j0, int *nj)
{
    *j0 = 0;
    *nj = c->ty;
    if (!c->dfft || c->ops->id != MC_BACKEND_FFT)
        return 0;
    mc_dfft_table_split(c->dfft, j0, nj);
    return 1;
}

int mc_conv_kernel_rows(mc_conv *c, double *rows, double *kspec, int *real, mc_error *err)
{
    *real = 0;
    if (!c->dfft || c->ops->id != MC_BACKEND_FFT)
        return mc_fail(err, MC_ERR_INTERNAL, "kernel rows: not a distributed fft engine");
    if (mc_dfft_table_rows(c->dfft, rows, mc_dfft_spectrum(c->dfft)) != MC_OK)
        return mc_fail(err, MC_ERR_NOMEM, "kernel rows: out of memory for the exchange");
    /* as mc_conv_kernel_real, then fft_kernel: the same test, the same scaling */
    const size_t nc = half_len(c);
    const double *s = (const double *)work_spec(c);
    double m[2] = {0, 0}; /* max |Re|, max |Im| */
    for (size_t q = 0; q < nc; q++) {
        m[0] = fmax(m[0], fabs(s[2 * q]));
        m[1] = fmax(m[1], fabs(s[2 * q + 1]));
    }
    mc_dist_max(m, 2);
    const double scale = 1.0 / ((double)c->tx * (double)c->ty);
    *real = m[1] <= 1e-13 * m[0];
    if (*real)
        for (size_t q = 0; q < nc; q++)
            kspec[q] = scale * s[2 * q];
    else
        for (size_t q = 0; q < 2 * nc; q++)
            kspec[q] = scale * s[q];
    return MC_OK;
}

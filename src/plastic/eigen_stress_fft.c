/* eigen_stress_fft.c - the fft backend of the residual stress operator (see eigen_op.h,
 * eigen_stress_op.c for the sums it evaluates, eigen_internal.h for the quadrant spectra).
 *
 * Laterally: DC-FFT, each layer and column zero-padded to 2mx x 2my (m >= the window) and
 * transformed once; the kernels are kept as real quadrant spectra.
 * In depth: per lateral frequency the S1 + S2 sum over source layers is a convolution along z of
 * the infinite-space kernel with the source extended by its mirror (layer -(k'+1) carries
 * r_c eps(k'), r_c = -1 for yz, xz). With period L = 2 Nz, Nz >= 2 nz (depth offsets run from
 * -(nz - 1) to 2 nz - 1 and must not meet their images), the kernel table is filled symmetrically
 * (offsets |m| <= Nz, by its parity in z), so its DFT is real (even pairs) or -i times real (odd
 * pairs): DCT-I of planes 0..Nz or DST-I of planes 1..Nz-1 (FFTW REDFT00 / RODFT00), kept for
 * kz = 0..Nz. The source is a complex DFT of length L of the mirrored sequence (FFTW's complex
 * transforms are ~2x faster here than its DCT-II/III); the extended source and the output are
 * half-sample symmetric, y(-q-1) = s y(q), so Y(L - kz) = s w^kz Y(kz), w = e^(-2 pi i / L):
 * the 6 x 6 products are formed for kz = 0..Nz only and the rest follows by that twiddle. This
 * replaces the O(nz^2) pair sum by O(nz log nz) per frequency, with 21 x (Nz + 1) real kernel
 * values per lateral frequency of the quadrant (the signs of eigen_internal.h folded in, and
 * (-i)^(a XOR b) = (-i)^a (-i)^b (-1)^(a b) again for the parities a, b in z; times w_i of the
 * row, which makes the stored matrix symmetric). They are stored in blocks of ch kx values of
 * one quadrant row holding every depth frequency and pair, so the depth step of a block reads
 * one contiguous run (and a spectrum row and its mirror, which share the kernel, run together).
 * S3: p3 = sum of P_k'c E_c is formed per frequency, inverted, cut to the window (p3 lives on the
 * window), transformed again and added with Love's spectra before the layers' inverse transforms.
 * Graded volumes (eigen_op.h, theory.md §8.8): the depth step above runs on the fine lattice; the
 * coarse step (depth_step_coarse) sums instead over the nz + 1 layer boundaries with the prefix
 * sums of the real tables (2 nzf + 1 planes of 21 values per lateral frequency, about the count
 * of the depth spectra), (nz + 1) nz terms per lateral frequency against 12 DFTs of length L;
 * coarse_pays chooses by that count (uniform volumes: always the DFTs, unchanged).
 */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "core/alloc.h"
#include "core/fftsize.h"
#include "core/dist.h"
#include "core/threads.h"
#include "operator/dfft.h"
#include "operator/operator.h"
#include "plastic/eigen_internal.h"

/* The depth step is most of an application and its loops run over contiguous kx: on x86-64 a
 * second copy for AVX2 is chosen at load time when the processor has it (same operations in the
 * same order, -std=c11 does not contract to FMA: the same results). */
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define DEPTH_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DEPTH_CLONES
#endif

/* kx values per block at most */
#define CHUNK_TARGET 64

/* Distributed: layers per batch of the lateral transforms (mc_dfft_create_many): a 128^2 x 16
 * stress apply makes 2 x 6 x 16 + 2 transposes and 6 x 16 + 1 gathers one at a time, 26 + 13
 * in batches of 8; the batch's buffers cost 2 x 8 / (6 nz) of E per rank */
#define DIST_BATCH 8

/* the cost model of coarse_pays, relative units (flops of the loops, scaled by measurement) */
#define COARSE_PAIR 115.0
#define FINE_DFT 2.5
#define FINE_PROD 200.0

typedef struct {
    mc_eig_fft fft;       /* 2mx x 2my; forward and inverse on the window's rows */
    int coarse;           /* 1: the coarse depth step (graded volumes; file comment) */
    int Nz, L;            /* depth half period and period (fine lattice step) */
    int np;               /* depth planes per block of V: Nz + 1 (fine) or 2 nzf + 1 (coarse) */
    int ch, nch;          /* kx per block, blocks per quadrant row (nch ch >= nk) */
    int k0, nk;           /* this rank's lateral frequencies kx = k0 .. k0 + nk - 1 (serial: 0, hx;
                           * distributed: mc_dfft_columns). E, P, V, P3 and Love hold them alone */
    mc_dfft *d;           /* distributed (mc_dist_active at create): the lateral transforms, in
                           * batches of bm layers of a component */
    int bm;               /* layers per batch (min(nz, DIST_BATCH)) */
    fftw_complex *bs;     /* bm spectra in mc_dfft's layout, nk x ty each */
    int lrow;             /* Love's spectra: row stride (qx serial, nk distributed) */
    size_t lql;           /* Love's spectra: doubles per quadrant */
    size_t dbytes;        /* the bytes of d */
    int cs;               /* buffer stride: ch rounded up to whole cache lines, off powers of 2 */
    int nthr;             /* workspaces */
    double *V;            /* S1 + S2 spectra, blocked: [(b np + kz) 21 + n] ch + x; coarse: the
                           * prefix sums of the real tables at plane m (m = 0 .. 2 nzf) */
    double *P3;           /* p3 kernel spectra, blocked: [(b nz + k) 6 + c] ch + x */
    fftw_complex *E;      /* 6 nz spectra [c * nz + k]: eps, then the stresses / 2G; each ty rows
                           * of nk values [ky * nk + kx - k0] */
    fftw_complex *P;      /* p3 spectrum */
    fftw_complex *PL;     /* the folded loads' spectra / 2G (op->nloads, E's layout; §8.9) */
    double *rows;         /* nthr x (wy x tx) (serial only) */
    fftw_complex *zb;     /* nthr x zlen: source and output (6 x L x cs each), planar scratch;
                           * coarse: the boundary jumps (2 x (nz + 1) x 12 cs doubles), output */
    size_t zlen;
    fftw_complex *tw;     /* w^kz, kz = 0..Nz, w = e^(-2 pi i / L) */
    fftw_plan zf, zi;     /* depth DFTs of length L, cs sequences at a time */
} sfft;

/* Half the lateral transform sizes: a free axis padded to 2 m >= 2 window; a periodic axis
 * (mc_eig_per_x / _y) transformed over its period n, unpadded, m = n / 2. */
static int half_x(const mc_eigen_stress *op)
{
    return mc_eig_per_x(&op->g) ? op->g.nx / 2 : mc_fftsize_good(op->v.nx < 2 ? 2 : op->v.nx);
}
static int half_y(const mc_eigen_stress *op)
{
    return mc_eig_per_y(&op->g) ? op->g.ny / 2 : mc_fftsize_good(op->v.ny < 2 ? 2 : op->v.ny);
}
static int size_x(const mc_eigen_stress *op)
{
    return mc_eig_per_x(&op->g) ? op->g.nx : 2 * half_x(op);
}
static int size_y(const mc_eigen_stress *op)
{
    return mc_eig_per_y(&op->g) ? op->g.ny : 2 * half_y(op);
}

void mc_eig_stress_fft_size(mc_eigen_stress *op)
{
    op->qx = half_x(op) + 1;
    op->qy = half_y(op) + 1;
}

/* Per component c: the quarter turns rot[c] of its lateral parities and the sign sy[c] of its
 * y-mirrored row (-1 for the components odd in y when the row is a mirror). */
static void component_signs(int mirror, int rot[6], double sy[6])
{
    for (int c = 0; c < 6; c++) {
        rot[c] = mc_eig_odd_x(c) + mc_eig_odd_y(c);
        sy[c] = (mirror && mc_eig_odd_y(c)) ? -1.0 : 1.0;
    }
}

/* the sign (-1)^(a b) of the parities in z of the pair (i, c) */
static double zsign(int i, int c)
{
    return (mc_eig_odd_z(i) && mc_eig_odd_z(c)) ? -1.0 : 1.0;
}

/* the lateral sign (-1)^(a b) of eigen_internal.h for the pair (i, c) */
static double xysign(int i, int c)
{
    const int n = (mc_eig_odd_x(i) & mc_eig_odd_x(c)) + (mc_eig_odd_y(i) & mc_eig_odd_y(c));
    return (n & 1) ? -1.0 : 1.0;
}

/* Quadrants q[0..n) (lateral spectra) into planes plane0 .. plane0 + n - 1 of the blocked array
 * dst of nplanes planes per block. */
static void scatter_blocks(const mc_eigen_stress *op, const sfft *f, double *const *q, int n,
                           int plane0, int nplanes, double *dst)
{
    const int qx = op->qx, ch = f->ch, k0 = f->k0;
#pragma omp parallel for schedule(static)
    for (int ky = 0; ky < op->qy; ky++)
        for (int kx = 0; kx < f->nk; kx++) { /* this rank's frequencies, local index kx */
            const size_t b = (size_t)ky * f->nch + kx / ch;
            for (int p = 0; p < n; p++)
                dst[(b * nplanes + plane0 + p) * ch + kx % ch] = q[p][(size_t)ky * qx + k0 + kx];
        }
}

/* The lateral quadrant transforms of the operator's sizes. */
static int make_quad(const mc_eigen_stress *op, mc_eig_quad *quad, mc_error *err)
{
    int rc = mc_eig_periodic(&op->g)
                 ? mc_eig_quad_create_full(quad, size_x(op), size_y(op), op->qx, op->qy, err)
                 : mc_eig_quad_create(quad, op->qx - 1, op->qy - 1, err);
    if (rc)
        mc_eig_quad_destroy(quad);
    return rc;
}

/* Quadrant tables *arr (ntab of op->qlen, parity par(op, t) each) into their spectra, in place;
 * distributed, then cut to this rank's columns (rows of nk values, Love's layout f->lrow,
 * f->lql; *arr replaced). */
static int quad_spectra(mc_eigen_stress *op, sfft *f, double **arr, int ntab,
                        int (*par)(const mc_eigen_stress *, int), mc_error *err)
{
    const size_t ql = op->qlen;
    mc_eig_quad quad;
    int rc = make_quad(op, &quad, err);
    if (rc)
        return rc;
    double *a = *arr;
#pragma omp parallel for schedule(dynamic, 1)
    for (int t = 0; t < ntab; t++)
        mc_eig_quad_transform(&quad, par(op, t), a + (size_t)t * ql);
    mc_eig_quad_destroy(&quad);
    if (!f->d)
        return MC_OK;
    double *mine = mc_malloc(((size_t)ntab * f->lql + 1) * sizeof *mine);
    if (!mine)
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for %d spectra", ntab);
    for (int t = 0; t < ntab; t++)
        for (int ky = 0; ky < op->qy; ky++)
            memcpy(mine + (size_t)t * f->lql + (size_t)ky * f->nk,
                   a + (size_t)t * ql + (size_t)ky * op->qx + f->k0, (size_t)f->nk * sizeof *mine);
    mc_free(a);
    *arr = mine;
    return MC_OK;
}

/* the layout of the quadrant spectra: whole quadrants (serial), this rank's columns (distributed) */
static void spectra_layout(const mc_eigen_stress *op, sfft *f, int dist)
{
    f->lrow = dist ? f->nk : op->qx;
    f->lql = dist ? ((size_t)op->qy * f->nk + 7) / 8 * 8 : op->qlen;
}

static int love_par(const mc_eigen_stress *op, int t)
{
    (void)op;
    return mc_eig_par(t % 6);
}

static int load_par(const mc_eigen_stress *op, int t)
{
    const int per = 6 * op->v.nz;
    return op->load_par[t / per][t % 6];
}

/* Love's tables into their spectra (before the kernel spectra are allocated: the whole tables
 * and V are never held together). */
static int love_spectra(mc_eigen_stress *op, sfft *f, mc_error *err)
{
    spectra_layout(op, f, f->d != NULL);
    int rc = quad_spectra(op, f, &op->love, 6 * op->v.nz, love_par, err);
    if (rc == MC_OK && f->d)
        op->part[3] = 6 * (size_t)op->v.nz * f->lql * sizeof(double);
    return rc;
}

/* The folded loads (theory.md §8.9): their tables op->lk into spectra, and the loads' spectra. */
int mc_eig_stress_fft_loads(mc_eigen_stress *op, mc_error *err)
{
    sfft *f = op->fft;
    const int ntab = op->nloads * 6 * op->v.nz;
    int rc = quad_spectra(op, f, &op->lk, ntab, load_par, err);
    if (rc)
        return rc;
    const size_t sl = f->fft.speclen;
    if (!(f->PL = mc_calloc((size_t)op->nloads * sl + 1, sizeof *f->PL)))
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for the loads' spectra");
    op->part[3] += (size_t)ntab * f->lql * sizeof(double);
    op->part[1] += (size_t)op->nloads * sl * sizeof(fftw_complex);
    return MC_OK;
}

/* One job of the kernel tables: kind 0 the S1 family at fine depth offset idx (MC_EIG_NSYM
 * tables), kind 1 p3's tables of layer idx (6), filled and transformed laterally into q. */
static void table_job(const mc_eigen_stress *op, mc_eig_quad *quad, mc_eig_corners *cc,
                      const int par[MC_EIG_NSYM], int kind, int idx, double *const *q)
{
    if (kind == 0) {
        mc_eig_s1_fill(op, idx, cc, q);
#pragma omp parallel for schedule(dynamic, 1)
        for (int n = 0; n < MC_EIG_NSYM; n++)
            mc_eig_quad_transform(quad, par[n], q[n]);
    } else {
        mc_eig_p3_fill(op, idx, cc, q);
#pragma omp parallel for schedule(dynamic, 1)
        for (int c = 0; c < 6; c++)
            mc_eig_quad_transform(quad, mc_eig_par(c), q[c]);
    }
}

/* The S1 family's planes and p3's layers into V and P3 (this rank's frequencies), job by job in
 * q (a scratch of MC_EIG_NSYM tables). Over P > 1 ranks the jobs are split (issue 22: they were
 * filled whole on every rank): the jobs of each kind in P contiguous blocks (consecutive depth
 * offsets keep the corner lattice's planes in use), in rounds - in round i rank r makes its i-th
 * job, then every job of the round is broadcast from its maker and each rank scatters its own
 * frequencies. The same fills and transforms as on one rank: the same bits
 * (tests/mpi/mpi_eigen.c: a wrong plane of the scatter is 1.6-2 of the largest stress off). Per
 * round one job's tables are held twice (the own and the one received); every rank receives
 * every job whole (P times its own share of V). With one rank: every job in order, no copy.
 * Collective. */
static int fill_tables(const mc_eigen_stress *op, sfft *f, mc_eig_quad *quad, mc_eig_corners *cc,
                       const int par[MC_EIG_NSYM], double *const *q, mc_error *err)
{
    const int P = f->d ? mc_dist_size() : 1, me = P > 1 ? mc_dist_rank() : 0;
    const int np = f->np * MC_EIG_NSYM;
    const size_t ql = op->qlen;
    double *rbuf = P > 1 ? mc_malloc((size_t)MC_EIG_NSYM * ql * sizeof *rbuf) : NULL;
    if (P > 1 && mc_dist_max_int(rbuf ? MC_OK : MC_ERR_NOMEM) != MC_OK) {
        mc_free(rbuf);
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for the shared tables");
    }
    double *r[MC_EIG_NSYM] = {NULL};
    for (int n = 0; rbuf && n < MC_EIG_NSYM; n++)
        r[n] = rbuf + (size_t)n * ql;
    for (int kind = 0; kind < 2; kind++) {
        const int njobs = kind ? op->v.nz : 2 * op->nzf, ntab = kind ? 6 : MC_EIG_NSYM;
        const int per = (njobs + P - 1) / P;
        for (int i = 0; i < per; i++) {
            if (me * per + i < njobs)
                table_job(op, quad, cc, par, kind, me * per + i, q);
            for (int src = 0; src < P; src++) {
                const int job = src * per + i;
                if (job >= njobs)
                    continue;
                double *const *t = src == me ? q : r;
                if (P > 1)
                    mc_dist_bcast(t[0], (size_t)ntab * ql, src); /* the tables are contiguous */
                if (kind == 0)
                    scatter_blocks(op, f, t, ntab, job * MC_EIG_NSYM, np, f->V);
                else
                    scatter_blocks(op, f, t, ntab, 6 * job, 6 * op->v.nz, f->P3);
            }
        }
    }
    mc_free(rbuf);
    return MC_OK;
}

/* The kernel spectra: lateral r2r of each table (quadrant by quadrant through a scratch of 21),
 * scattered into blocks (this rank's frequencies); then, block by block, the depth r2r of the S1
 * family and the folded signs. */
static int build_spectra(mc_eigen_stress *op, sfft *f, mc_error *err)
{
    const int Nz = f->Nz, ch = f->ch, np = f->np * MC_EIG_NSYM;
    const size_t ql = op->qlen, nblk = (size_t)op->qy * f->nch;
    mc_eig_quad quad;
    int rc = make_quad(op, &quad, err);
    if (rc)
        return rc;
    double *scr = mc_malloc((size_t)MC_EIG_NSYM * ql * sizeof *scr);
    mc_eig_corners cc;
    if (!scr || (rc = mc_eig_corners_init(op, &cc, err))) {
        mc_free(scr);
        mc_eig_quad_destroy(&quad);
        return scr ? rc : mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for table scratch");
    }
    double *q[MC_EIG_NSYM];
    for (int n = 0; n < MC_EIG_NSYM; n++)
        q[n] = scr + (size_t)n * ql;
    int par[MC_EIG_NSYM], oddz[MC_EIG_NSYM];
    double sign[MC_EIG_NSYM], signc[MC_EIG_NSYM];
    for (int i = 0; i < 6; i++)
        for (int c = i; c < 6; c++) {
            const int n = mc_eig_sym(i, c);
            par[n] = mc_eig_pair_par(i, c);
            oddz[n] = mc_eig_odd_z(i) ^ mc_eig_odd_z(c);
            /* times w_min(i,c): the stored matrix is then symmetric, S_ic = V_ic / w_i */
            sign[n] = xysign(i, c) * zsign(i, c) * mc_eig_weight(i);
            signc[n] = xysign(i, c) * mc_eig_weight(i);
        }
    /* the fine lattice's offsets (planes m >= 2 nzf stay zero: calloc), then p3's layers; with
     * several ranks each fills and transforms its share (fill_tables) */
    rc = fill_tables(op, f, &quad, &cc, par, q, err);
    mc_eig_corners_free(&cc);
    mc_eig_quad_destroy(&quad);
    mc_free(scr);
    if (rc)
        return rc;
    if (f->coarse) {
        /* the real tables at m dz times the lateral signs and w_min(i,c) (the same factors as
         * below, without the depth DFT's (-i) parities), summed: plane m holds
         * S(m) = sum of K(m') for m' < m; K(0) of a pair odd in z is 0 (the DST's convention) */
#pragma omp parallel for schedule(static)
        for (size_t b = 0; b < nblk; b++)
            for (int n = 0; n < MC_EIG_NSYM; n++) {
                double *base = f->V + b * (size_t)np * ch + (size_t)n * ch;
                const double s = signc[n];
                for (int x = 0; x < ch; x++) {
                    double acc = 0.0;
                    for (int m = 0; m < f->np; m++) {
                        double *v = base + (size_t)m * MC_EIG_NSYM * ch + x;
                        const double k = (m == 0 && oddz[n]) ? 0.0 : s * *v;
                        *v = acc;
                        acc += k;
                    }
                }
            }
        return MC_OK;
    }

    /* depth: within a block, planes kz of pair n are MC_EIG_NSYM ch apart */
    int n0[1] = {Nz + 1}, n1[1] = {Nz - 1};
    fftw_r2r_kind k0[1] = {FFTW_REDFT00}, k1[1] = {FFTW_RODFT00};
    const int stride = MC_EIG_NSYM * ch;
    fftw_plan zp[2];
    fftw_plan_with_nthreads(1);
    zp[0] = fftw_plan_many_r2r(1, n0, ch, f->V, NULL, stride, 1, f->V, NULL, stride, 1, k0,
                               FFTW_ESTIMATE | FFTW_UNALIGNED);
    zp[1] = fftw_plan_many_r2r(1, n1, ch, f->V + stride, NULL, stride, 1, f->V + stride, NULL,
                               stride, 1, k1, FFTW_ESTIMATE | FFTW_UNALIGNED);
    if (!zp[0] || !zp[1]) {
        for (int p = 0; p < 2; p++)
            if (zp[p])
                fftw_destroy_plan(zp[p]);
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: FFTW could not plan the depth kernels");
    }
#pragma omp parallel for schedule(static)
    for (size_t b = 0; b < nblk; b++)
        for (int n = 0; n < MC_EIG_NSYM; n++) {
            double *base = f->V + b * (size_t)np * ch + (size_t)n * ch;
            if (oddz[n]) {
                fftw_execute_r2r(zp[1], base + stride, base + stride);
                /* DST-I: kz = 0 and kz = Nz vanish */
                memset(base, 0, (size_t)ch * sizeof *base);
                memset(base + (size_t)Nz * stride, 0, (size_t)ch * sizeof *base);
            } else {
                fftw_execute_r2r(zp[0], base, base);
            }
            for (int kz = 0; kz <= Nz; kz++)
                for (int x = 0; x < ch; x++)
                    base[(size_t)kz * stride + x] *= sign[n];
        }
    for (int p = 0; p < 2; p++)
        fftw_destroy_plan(zp[p]);
    return MC_OK;
}

/* Whether the coarse depth step costs less than the fine lattice's, per lateral frequency:
 * COARSE_PAIR x (nz + 1) nz pair terms against FINE_DFT x 12 L log2 L (depth DFTs) + FINE_PROD x
 * (L / 2 + 1) products. The constants are measured costs (theory.md §8.8, bench plastic). */
static int coarse_pays(int nz, int nzf, int L)
{
    if (nz == nzf)
        return 0; /* uniform: the fine step is the coarse one's lattice, same bits as before */
    const double pair = COARSE_PAIR * (nz + 1.0) * nz;
    const double fine = FINE_DFT * 12.0 * L * log2((double)L) + FINE_PROD * (L / 2 + 1.0);
    return pair < fine;
}

/* The sizes of prepare, without planning (the transform sizes and spectrum length as
 * mc_eig_fft_create sets them): shared by prepare and the estimate of the bytes. ranks = 0: the
 * serial operator; ranks >= 1: distributed, rank `rank`'s frequencies (FFTW-MPI's default
 * blocks of kx, mc_dfft_split; the blocks of ch kx split rank 0's share, the same on every
 * rank: the same depth plans). */
static void plan_sizes(const mc_eigen_stress *op, sfft *f, int ranks, int rank)
{
    const int nz = op->v.nz;
    /* depth half period: offsets up to 2 nzf - 1 of the fine lattice must not meet their images
     * (file comment) */
    f->Nz = mc_fftsize_good(2 * op->nzf);
    f->L = 2 * f->Nz;
    f->coarse = op->depth == MC_EIG_DEPTH_COARSE ||
                (op->depth == MC_EIG_DEPTH_AUTO && coarse_pays(nz, op->nzf, f->L));
    f->np = f->coarse ? 2 * op->nzf + 1 : f->Nz + 1;
    f->fft.tx = size_x(op);
    f->fft.ty = size_y(op);
    f->fft.hx = f->fft.tx / 2 + 1; /* = qx */
    const int hx = f->fft.hx;
    f->k0 = 0;
    f->nk = hx;
    if (ranks > 0)
        mc_dfft_split(hx, ranks, rank, &f->k0, &f->nk);
    f->fft.speclen = ((size_t)f->fft.ty * f->nk + 3) / 4 * 4;
    /* blocks of at most CHUNK_TARGET kx splitting evenly the serial hx or, distributed, the
     * largest rank's share (rank 0's; the others' shorter last blocks pad with zeros) */
    const int share = ranks > 0 ? (hx + ranks - 1) / ranks : hx;
    const int nch = (share + CHUNK_TARGET - 1) / CHUNK_TARGET;
    f->ch = (share + nch - 1) / nch;
    f->nch = (f->nk + f->ch - 1) / f->ch;
    f->bm = ranks > 0 ? (nz < DIST_BATCH ? nz : DIST_BATCH) : 0;
    f->dbytes = ranks > 0 ? mc_dfft_estimate_many(op->v.nx, op->v.ny, f->fft.tx, f->fft.ty, f->bm,
                                                  ranks, rank) +
                                (size_t)f->bm * f->nk * f->fft.ty * sizeof(fftw_complex)
                          : 0;
    f->cs = (f->ch + 3) / 4 * 4;
    if (f->cs % 16 == 0) /* a power-of-2 stride between depth planes thrashes the cache */
        f->cs += 4;
    f->nthr = mc_eig_threads(12 * (size_t)nz * (size_t)f->fft.tx * (size_t)f->fft.ty);
    f->zlen = f->coarse ? (size_t)(24 * (nz + 1) + 12) * f->cs / 2 + 1
                        : (size_t)(12 * f->L + 12) * f->cs;
}

/* Bytes of what prepare takes, by part (mc_eigen_stress_parts): [0] kernel spectra V, [1] layer
 * spectra E and P, [2] p3 kernel spectra, [4] workspaces (rows, depth scratch, twiddles). */
static void fft_parts(const mc_eigen_stress *op, const sfft *f, size_t parts[MC_EIGEN_STRESS_PARTS])
{
    const int nz = op->v.nz;
    const size_t blk = (size_t)op->qy * f->nch * f->ch; /* doubles per blocked plane */
    const size_t sl = f->fft.speclen, rl = f->dbytes ? 0 : (size_t)op->v.ny * f->fft.tx;
    parts[0] = (size_t)f->np * MC_EIG_NSYM * blk * sizeof(double);
    parts[1] = (6 * (size_t)nz + 1) * sl * sizeof(fftw_complex);
    parts[2] = 6 * (size_t)nz * blk * sizeof(double);
    parts[3] = 0;
    parts[4] = sizeof *f + ((size_t)f->nthr * f->zlen + f->Nz + 1) * sizeof(fftw_complex) +
               (size_t)f->nthr * rl * sizeof(double) + f->dbytes;
}

/* Love's spectra (part 3) when distributed: rows of this rank's nk frequencies. */
static size_t love_bytes(const mc_eigen_stress *op, const sfft *f)
{
    return 6 * (size_t)op->v.nz * (((size_t)op->qy * f->nk + 7) / 8 * 8) * sizeof(double);
}

size_t mc_eig_stress_fft_loads_bytes(const mc_eigen_stress *op, int ranks, int nloads)
{
    sfft f;
    memset(&f, 0, sizeof f);
    plan_sizes(op, &f, ranks, 0);
    const size_t tabs = ranks > 0 ? love_bytes(op, &f) : 6 * (size_t)op->v.nz * op->qlen * sizeof(double);
    return (size_t)nloads * (tabs + f.fft.speclen * sizeof(fftw_complex));
}

void mc_eig_stress_fft_estimate(const mc_eigen_stress *op, int ranks,
                                size_t parts[MC_EIGEN_STRESS_PARTS])
{
    sfft f;
    memset(&f, 0, sizeof f);
    plan_sizes(op, &f, ranks, 0); /* rank 0 holds the most frequencies */
    size_t add[MC_EIGEN_STRESS_PARTS];
    fft_parts(op, &f, add);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        parts[k] += add[k];
    if (ranks > 0)
        parts[3] = love_bytes(op, &f);
}

int mc_eig_stress_fft_prepare(mc_eigen_stress *op, mc_error *err)
{
    sfft *f = mc_calloc(1, sizeof *f);
    if (!f)
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory");
    op->fft = f;
    const int nz = op->v.nz, wy = op->v.ny;
    /* under mpirun (any number of ranks, one included: the same path, the same bits for every
     * P) the lateral transforms are distributed and this rank keeps its frequencies alone */
    const int dist = mc_dist_active() && !op->replicated;
    plan_sizes(op, f, dist ? mc_dist_size() : 0, mc_dist_rank());
    int rc;
    if (dist) {
        const mc_eig_fft sz = f->fft; /* the sizes plan_sizes set */
        if ((rc = mc_dfft_create_many(op->v.nx, wy, sz.tx, sz.ty, f->bm, &f->d, err)))
            return rc;
        int k0, nk;
        mc_dfft_columns(f->d, &k0, &nk);
        if (k0 != f->k0 || nk != f->nk)
            return mc_fail(err, MC_ERR_INTERNAL,
                           "eigen stress: FFTW-MPI gave columns %d + %d, expected %d + %d", k0, nk,
                           f->k0, f->nk);
        const size_t nb = (size_t)f->bm * f->nk * sz.ty;
        if (!(f->bs = mc_malloc((nb + 1) * sizeof *f->bs)))
            return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory");
        f->dbytes = mc_dfft_bytes(f->d) + nb * sizeof *f->bs;
    } else if ((rc = mc_eig_fft_create(&f->fft, size_x(op), size_y(op), 0, wy, wy, err))) {
        return rc;
    }
    if ((rc = love_spectra(op, f, err)))
        return rc;
    const size_t sl = f->fft.speclen, rl = dist ? 0 : (size_t)wy * f->fft.tx;
    const size_t blk = (size_t)op->qy * f->nch * f->ch; /* doubles per blocked plane */
    const size_t nv = (size_t)f->np * MC_EIG_NSYM * blk, np3 = 6 * (size_t)nz * blk;
    f->V = mc_calloc(nv + 1, sizeof *f->V);
    f->P3 = mc_calloc(np3 + 1, sizeof *f->P3);
    f->E = mc_malloc((6 * (size_t)nz * sl + 1) * sizeof *f->E);
    f->P = mc_malloc((sl + 1) * sizeof *f->P);
    f->rows = mc_malloc(((size_t)f->nthr * rl + 1) * sizeof *f->rows);
    f->zb = mc_calloc((size_t)f->nthr * f->zlen, sizeof *f->zb);
    f->tw = mc_malloc((size_t)(f->Nz + 1) * sizeof *f->tw);
    if (!f->V || !f->P3 || !f->E || !f->P || !f->rows || !f->zb || !f->tw)
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: out of memory for %zu spectra",
                       (size_t)f->np * MC_EIG_NSYM + 12 * (size_t)nz);
    size_t parts[MC_EIGEN_STRESS_PARTS];
    fft_parts(op, f, parts);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        op->part[k] += parts[k];
    /* touch the spectra now: the first apply should not pay the page faults */
    memset(f->E, 0, 6 * (size_t)nz * sl * sizeof *f->E);
    memset(f->P, 0, sl * sizeof *f->P);
    if ((rc = build_spectra(op, f, err)))
        return rc;
    if (f->coarse)
        return MC_OK;
    for (int kz = 0; kz <= f->Nz; kz++) {
        f->tw[kz][0] = cos(2.0 * M_PI * kz / f->L);
        f->tw[kz][1] = -sin(2.0 * M_PI * kz / f->L);
    }
    /* depth DFTs: length L with stride cs, over cs interleaved sequences (one kx each) */
    fftw_iodim dim = {f->L, f->cs, f->cs}, vec = {f->cs, 1, 1};
    /* repeated: [solver] plans (operator/operator.h); zb is scratch, filled at each apply.
     * Distributed: FFTW_ESTIMATE, the same plan on every rank (dfft.h) */
    const unsigned rep = dist ? FFTW_ESTIMATE : mc_fft_plan_flags();
    fftw_plan_with_nthreads(1);
    f->zf = fftw_plan_guru_dft(1, &dim, 1, &vec, f->zb, f->zb, FFTW_FORWARD, rep);
    f->zi = fftw_plan_guru_dft(1, &dim, 1, &vec, f->zb, f->zb, FFTW_BACKWARD, rep);
    if (!f->zf || !f->zi)
        return mc_fail(err, MC_ERR_NOMEM, "eigen stress: FFTW could not plan depth transforms");
    return MC_OK;
}

int mc_eig_stress_fft_depth(const mc_eigen_stress *op)
{
    const sfft *f = op->fft;
    return !f ? 0 : f->coarse ? MC_EIG_DEPTH_COARSE : MC_EIG_DEPTH_FINE;
}

void mc_eig_stress_fft_free(mc_eigen_stress *op)
{
    sfft *f = op->fft;
    if (!f)
        return;
    mc_eig_fft_destroy(&f->fft);
    mc_dfft_destroy(&f->d);
    mc_free(f->bs);
    if (f->zf)
        fftw_destroy_plan(f->zf);
    if (f->zi)
        fftw_destroy_plan(f->zi);
    mc_free(f->V);
    mc_free(f->P3);
    mc_free(f->E);
    mc_free(f->P);
    mc_free(f->PL);
    mc_free(f->rows);
    mc_free(f->zb);
    mc_free(f->tw);
    mc_free(f);
    op->fft = NULL;
}

/* The depth step for spectrum row ky, block chunk (kx0 = chunk ch, len values): gather with the
 * column factors (-i)^(ox + oy) s_y and the mirror layers, p3, depth DFTs, the 6 x 6 products for
 * kz = 0..Nz (on planar copies, so the loops run over contiguous kx) and the twiddle for the rest,
 * inverse DFTs, scatter with the row factors and 1 / L back into E. */
DEPTH_CLONES static void depth_step(const mc_eigen_stress *op, const sfft *f, int ky, int chunk,
                       fftw_complex *zb)
{
    const int nz = op->v.nz, nzf = op->nzf, Nz = f->Nz, L = f->L, ch = f->ch, cs = f->cs;
    const int nk = f->nk, ty = f->fft.ty, my = op->qy - 1, mirror = ky > my, kx0 = chunk * ch;
    const int len = nk - kx0 < ch ? nk - kx0 : ch;
    const size_t sl = f->fft.speclen, at = (size_t)ky * nk + kx0; /* spectrum index (local kx) */
    const size_t b = (size_t)(mirror ? ty - ky : ky) * f->nch + chunk; /* kernel block */
    const double *Vb = f->V + b * (size_t)(Nz + 1) * MC_EIG_NSYM * ch;
    const double *Pb = f->P3 + b * (size_t)nz * 6 * ch;
    const size_t cstride = (size_t)L * cs; /* complex values per component */
    fftw_complex *A = zb, *B = zb + 6 * cstride;

    int rot[6];
    double sy[6];
    component_signs(mirror, rot, sy);
    /* gather: the fine layers q < nzf and their mirrors at L - 1 - q (r_c = -1 for yz, xz),
     * each layer's spectrum repeated over its fine layers (graded layers, eigen_op.h); p3 / 2G
     * once per layer (its table is the whole layer's) */
    double pr[CHUNK_TARGET] = {0.0}, pi[CHUNK_TARGET] = {0.0};
    for (int c = 0; c < 6; c++) {
        fftw_complex *a = A + c * cstride;
        const double r = mc_eig_odd_z(c) ? -1.0 : 1.0;
        memset(a + (size_t)nzf * cs, 0, (size_t)(L - 2 * nzf) * cs * sizeof *a);
        for (int k = 0; k < nz; k++) {
            const int q0 = op->first[k], q1 = op->first[k + 1];
            fftw_complex *g = a + (size_t)q0 * cs, *gm = a + (size_t)(L - 1 - q0) * cs;
            const fftw_complex *e = f->E + (size_t)(c * nz + k) * sl + at;
            const double *P = Pb + (size_t)(k * 6 + c) * ch;
            for (int x = 0; x < len; x++) {
                double re = sy[c] * e[x][0], im = sy[c] * e[x][1];
                mc_eig_rot(&re, &im, rot[c]);
                g[x][0] = re;
                g[x][1] = im;
                gm[x][0] = r * re;
                gm[x][1] = r * im;
                pr[x] += P[x] * re;
                pi[x] += P[x] * im;
            }
            for (int x = len; x < cs; x++)
                g[x][0] = g[x][1] = gm[x][0] = gm[x][1] = 0.0;
            for (int q = q0 + 1; q < q1; q++) { /* the rest of a graded layer */
                memcpy(a + (size_t)q * cs, g, (size_t)cs * sizeof *a);
                memcpy(a + (size_t)(L - 1 - q) * cs, gm, (size_t)cs * sizeof *a);
            }
        }
        fftw_execute_dft(f->zf, a, a);
    }
    for (int x = 0; x < len; x++) {
        f->P[at + x][0] = pr[x];
        f->P[at + x][1] = pi[x];
    }
    /* products at kz = 0..Nz; the upper half by Y(L - kz) = s_i w^kz Y(kz). On planar copies
     * (contiguous runs over kx), one kx at a time with its six inputs in registers and each
     * row's sum over c = 0..5 in order; the kernel's 21 values of a frequency read once each. */
    double *pl = (double *)(zb + 12 * cstride); /* planar: 6 x (re, im) x cs, in then out */
    double *po = pl + 12 * (size_t)cs;
    for (int kz = 0; kz <= Nz; kz++) {
        for (int c = 0; c < 6; c++) {
            const fftw_complex *a = A + c * cstride + (size_t)kz * cs;
            double *ar = pl + (size_t)c * 2 * cs, *ai = ar + cs;
            const int odd = mc_eig_odd_z(c); /* (-i)^oz(c) */
            for (int x = 0; x < len; x++) {
                ar[x] = odd ? a[x][1] : a[x][0];
                ai[x] = odd ? -a[x][0] : a[x][1];
            }
        }
        const double *V = Vb + (size_t)kz * MC_EIG_NSYM * ch;
        const double *r0 = pl, *i0 = pl + cs, *r1 = pl + 2 * cs, *i1 = pl + 3 * cs;
        const double *r2 = pl + 4 * cs, *i2 = pl + 5 * cs, *r3 = pl + 6 * cs, *i3 = pl + 7 * cs;
        const double *r4 = pl + 8 * cs, *i4 = pl + 9 * cs, *r5 = pl + 10 * cs, *i5 = pl + 11 * cs;
        /* ROW(i, ...): the stored pairs mc_eig_sym(i, c) for c = 0..5 */
#define KV(n) V[(size_t)(n) * ch + x]
#define ROW(i, n0, n1, n2, n3, n4, n5)                                                            \
    do {                                                                                          \
        const double v0 = KV(n0), v1 = KV(n1), v2 = KV(n2), v3 = KV(n3), v4 = KV(n4), v5 = KV(n5); \
        po[(size_t)(2 * (i)) * cs + x] =                                                          \
            v0 * a0r + v1 * a1r + v2 * a2r + v3 * a3r + v4 * a4r + v5 * a5r;                      \
        po[(size_t)(2 * (i) + 1) * cs + x] =                                                      \
            v0 * a0i + v1 * a1i + v2 * a2i + v3 * a3i + v4 * a4i + v5 * a5i;                      \
    } while (0)
#pragma omp simd
        for (int x = 0; x < len; x++) {
            const double a0r = r0[x], a0i = i0[x], a1r = r1[x], a1i = i1[x], a2r = r2[x];
            const double a2i = i2[x], a3r = r3[x], a3i = i3[x], a4r = r4[x], a4i = i4[x];
            const double a5r = r5[x], a5i = i5[x];
            ROW(0, 0, 1, 2, 3, 4, 5);
            ROW(1, 1, 6, 7, 8, 9, 10);
            ROW(2, 2, 7, 11, 12, 13, 14);
            ROW(3, 3, 8, 12, 15, 16, 17);
            ROW(4, 4, 9, 13, 16, 18, 19);
            ROW(5, 5, 10, 14, 17, 19, 20);
        }
#undef ROW
#undef KV
        const double twr = f->tw[kz][0], twi = f->tw[kz][1];
        for (int i = 0; i < 6; i++) {
            const double *yr = po + (size_t)(2 * i) * cs, *yi = yr + cs;
            fftw_complex *y = B + i * cstride + (size_t)kz * cs;
            fftw_complex *ym = B + i * cstride + (size_t)(L - kz) * cs;
            const int odd = mc_eig_odd_z(i);
            const double s = odd ? -1.0 : 1.0;
            for (int x = 0; x < len; x++) {
                /* (-i)^oz(i) */
                const double re = odd ? yi[x] : yr[x], im = odd ? -yr[x] : yi[x];
                y[x][0] = re;
                y[x][1] = im;
                if (kz > 0 && kz < Nz) {
                    ym[x][0] = s * (twr * re - twi * im);
                    ym[x][1] = s * (twr * im + twi * re);
                }
            }
        }
    }
    for (int i = 0; i < 6; i++) {
        fftw_complex *g = B + i * cstride;
        const double scale = 1.0 / (L * mc_eig_weight(i)); /* the DFT pair; V's weight */
        fftw_execute_dft(f->zi, g, g);
        for (int k = 0; k < nz; k++) { /* read at each layer's centre */
            fftw_complex *e = f->E + (size_t)(i * nz + k) * sl + at;
            const fftw_complex *y = g + (size_t)op->centre[k] * cs;
            for (int x = 0; x < len; x++) {
                double re = scale * sy[i] * y[x][0], im = scale * sy[i] * y[x][1];
                mc_eig_rot(&re, &im, rot[i]);
                e[x][0] = re;
                e[x][1] = im;
            }
        }
    }
}

/* The coarse depth step for spectrum row ky, block chunk (graded volumes; theory.md §8.8). With
 * S(m) the prefix sums of the real table K (plane m of V), the fine-lattice sum over the fine
 * layers q' = f_j .. f_(j+1) - 1 of source layer j, seen at the fine centre c of the target,
 *   sum K(c - q') + r_c K(c + q' + 1) = Q(c - f_j + 1) - Q(c - f_(j+1) + 1)
 *                                      + r_c (S(c + f_(j+1) + 1) - S(c + f_j + 1)),
 * Q the prefix sum over signed offsets (Q(m) = S(m) for m >= 0, s (S(1) - S(1 - m)) below, s the
 * pair's parity in z; Q and S are defined up to a constant, which the jumps cancel). Summed by
 * parts over the layers, each boundary f_j (j = 0..nz) contributes once with the jump
 * d_j = e_j - e_(j-1) of the eigenstrain (e_(-1) = e_nz = 0):
 *   y_i(c) = sum_j sum_c' [Q(c - f_j + 1) - r_c' S(c + f_j + 1)] d_j,c'.
 * Per target layer and boundary: two planes of 21 values and the 6 x 6 products; (nz + 1) nz
 * terms against the fine step's 12 depth DFTs of length L. Gather and scatter as depth_step (the
 * real-space kernel has no DFT parity factors and no 1 / L). */
DEPTH_CLONES static void depth_step_coarse(const mc_eigen_stress *op, const sfft *f, int ky,
                                           int chunk, fftw_complex *zb)
{
    const int nz = op->v.nz, ch = f->ch, cs = f->cs, np = f->np;
    const int nk = f->nk, ty = f->fft.ty, my = op->qy - 1, mirror = ky > my, kx0 = chunk * ch;
    const int len = nk - kx0 < ch ? nk - kx0 : ch;
    const size_t sl = f->fft.speclen, at = (size_t)ky * nk + kx0;
    const size_t b = (size_t)(mirror ? ty - ky : ky) * f->nch + chunk;
    const double *Sb = f->V + b * (size_t)np * MC_EIG_NSYM * ch;
    const double *Pb = f->P3 + b * (size_t)nz * 6 * ch;
    const size_t bs = 12 * (size_t)cs; /* doubles per boundary: 6 x (re, im) planar */
    double *D = (double *)zb, *Dr = D + (size_t)(nz + 1) * bs, *Y = Dr + (size_t)(nz + 1) * bs;

    int rot[6];
    double sy[6];
    component_signs(mirror, rot, sy);
    /* gather each layer's spectrum into slot k, p3 / 2G; then the jumps in place, top down */
    double pr[CHUNK_TARGET] = {0.0}, pi[CHUNK_TARGET] = {0.0};
    for (int c = 0; c < 6; c++) {
        for (int k = 0; k < nz; k++) {
            double *gr = D + (size_t)k * bs + (size_t)(2 * c) * cs, *gi = gr + cs;
            const fftw_complex *e = f->E + (size_t)(c * nz + k) * sl + at;
            const double *P = Pb + (size_t)(k * 6 + c) * ch;
            for (int x = 0; x < len; x++) {
                double re = sy[c] * e[x][0], im = sy[c] * e[x][1];
                mc_eig_rot(&re, &im, rot[c]);
                gr[x] = re;
                gi[x] = im;
                pr[x] += P[x] * re;
                pi[x] += P[x] * im;
            }
            for (int x = len; x < cs; x++)
                gr[x] = gi[x] = 0.0;
        }
    }
    memset(D + (size_t)nz * bs, 0, bs * sizeof *D);
    for (int j = nz; j > 0; j--)
        for (size_t t = 0; t < bs; t++)
            D[(size_t)j * bs + t] -= D[(size_t)(j - 1) * bs + t];
    for (int j = 0; j <= nz; j++) /* r_c d_j: the mirror layers' sign */
        for (int c = 0; c < 6; c++) {
            const double r = mc_eig_odd_z(c) ? -1.0 : 1.0;
            for (int t = 0; t < 2 * cs; t++)
                Dr[(size_t)j * bs + (size_t)(2 * c) * cs + t] =
                    r * D[(size_t)j * bs + (size_t)(2 * c) * cs + t];
        }
    for (int x = 0; x < len; x++) {
        f->P[at + x][0] = pr[x];
        f->P[at + x][1] = pi[x];
    }
    const size_t pl = (size_t)MC_EIG_NSYM * ch; /* doubles per plane of S */
    for (int k = 0; k < nz; k++) {
        const int c0 = op->centre[k];
        memset(Y, 0, bs * sizeof *Y);
        for (int j = 0; j <= nz; j++) {
            const int fj = op->first[j], md = c0 - fj + 1;
            /* Q(md) = so (A - B): A = S(md), B = S(0) = 0 for md >= 0; else A = S(1),
             * B = S(1 - md) and so = the pair's parity in z (-1 for the pairs odd in z) */
            const double *restrict A = Sb + (size_t)(md >= 0 ? md : 1) * pl;
            const double *restrict B = Sb + (size_t)(md >= 0 ? 0 : 1 - md) * pl;
            const double *restrict I = Sb + (size_t)(c0 + fj + 1) * pl; /* the mirror's S */
            const double so = md >= 0 ? 1.0 : -1.0;
            const double *restrict d = D + (size_t)j * bs, *restrict dr = Dr + (size_t)j * bs;
            double *restrict Yr = Y;
#define QD(n) (md >= 0 ? A[(size_t)(n) * ch + x] : A[(size_t)(n) * ch + x] - B[(size_t)(n) * ch + x])
#define SI(n) I[(size_t)(n) * ch + x]
#define DC(c) d[(size_t)(c) * cs + x]
#define DR(c) dr[(size_t)(c) * cs + x]
/* row i of the 6 x 6 products: pairs n0..n5 of columns 0..5, their parities in z p0..p5 */
#define ROWX(i, n0, n1, n2, n3, n4, n5, p0, p1, p2, p3, p4, p5)                                   \
    do {                                                                                          \
        const double q0 = so##p0 * QD(n0), q1 = so##p1 * QD(n1), q2 = so##p2 * QD(n2);            \
        const double q3 = so##p3 * QD(n3), q4 = so##p4 * QD(n4), q5 = so##p5 * QD(n5);            \
        const double s0 = SI(n0), s1 = SI(n1), s2 = SI(n2), s3 = SI(n3), s4 = SI(n4);             \
        const double s5 = SI(n5);                                                                 \
        Yr[(size_t)(2 * (i)) * cs + x] += q0 * DC(0) + q1 * DC(2) + q2 * DC(4) + q3 * DC(6) +      \
                                         q4 * DC(8) + q5 * DC(10) - s0 * DR(0) - s1 * DR(2) -     \
                                         s2 * DR(4) - s3 * DR(6) - s4 * DR(8) - s5 * DR(10);      \
        Yr[(size_t)(2 * (i) + 1) * cs + x] += q0 * DC(1) + q1 * DC(3) + q2 * DC(5) + q3 * DC(7) +  \
                                             q4 * DC(9) + q5 * DC(11) - s0 * DR(1) - s1 * DR(3) - \
                                             s2 * DR(5) - s3 * DR(7) - s4 * DR(9) - s5 * DR(11);  \
    } while (0)
            /* the parity factor of a pair: 1 where even in z, so where odd */
            const double soE = 1.0, soO = so;
#define ROWS                                                                                      \
    do {                                                                                          \
        ROWX(0, 0, 1, 2, 3, 4, 5, E, E, E, E, O, O);                                              \
        ROWX(1, 1, 6, 7, 8, 9, 10, E, E, E, E, O, O);                                             \
        ROWX(2, 2, 7, 11, 12, 13, 14, E, E, E, E, O, O);                                          \
        ROWX(3, 3, 8, 12, 15, 16, 17, E, E, E, E, O, O);                                          \
        ROWX(4, 4, 9, 13, 16, 18, 19, O, O, O, O, E, E);                                          \
        ROWX(5, 5, 10, 14, 17, 19, 20, O, O, O, O, E, E);                                         \
    } while (0)
            /* two loops, so that the one above the target (md >= 0) reads no B */
            if (md >= 0) {
#pragma omp simd
                for (int x = 0; x < len; x++)
                    ROWS;
            } else {
#pragma omp simd
                for (int x = 0; x < len; x++)
                    ROWS;
            }
#undef ROWS
#undef ROWX
#undef DR
#undef DC
#undef SI
#undef QD
        }
        for (int i = 0; i < 6; i++) { /* the row factors, V's weight */
            fftw_complex *e = f->E + (size_t)(i * nz + k) * sl + at;
            const double *yr = Y + (size_t)(2 * i) * cs, *yi = yr + cs;
            const double scale = sy[i] / mc_eig_weight(i);
            for (int x = 0; x < len; x++) {
                double re = scale * yr[x], im = scale * yi[x];
                mc_eig_rot(&re, &im, rot[i]);
                e[x][0] = re;
                e[x][1] = im;
            }
        }
    }
}

/* The depth steps of every quadrant row and block of this rank's frequencies (and the mirror
 * rows, which share the kernel), threads over the tasks. */
static void depth_all(const mc_eigen_stress *op, const sfft *f, int me)
{
    const int ty = f->fft.ty, my = op->qy - 1, ntask = op->qy * f->nch;
    fftw_complex *zb = f->zb + (size_t)me * f->zlen;
    void (*step)(const mc_eigen_stress *, const sfft *, int, int, fftw_complex *) =
        f->coarse ? depth_step_coarse : depth_step;
#pragma omp for schedule(dynamic, 1)
    for (int t = 0; t < ntask; t++) {
        const int ky = t / f->nch, chunk = t % f->nch;
        step(op, f, ky, chunk, zb);
        if (ky > 0 && ty - ky > my) /* its mirror row (an odd period has no Nyquist row) */
            step(op, f, ty - ky, chunk, zb);
    }
}

/* A quadrant spectrum L (Love's layout; lateral parity par) times the spectrum P, into e. */
static void quad_add(const mc_eigen_stress *op, const sfft *f, const double *L, int par,
                     const fftw_complex *P, fftw_complex *e)
{
    const int ty = f->fft.ty, nk = f->nk, my = op->qy - 1;
    const int rot = (par & 1) + (par >> 1 & 1), oy = par >> 1 & 1;
    for (int ky = 0; ky < ty; ky++) {
        const int mirror = ky > my;
        const double s = (mirror && oy) ? -1.0 : 1.0;
        const double *l = L + (size_t)(mirror ? ty - ky : ky) * f->lrow;
        for (int kx = 0; kx < nk; kx++) {
            const size_t q = (size_t)ky * nk + kx;
            double re = s * l[kx] * P[q][0], im = s * l[kx] * P[q][1];
            mc_eig_rot(&re, &im, rot);
            e[q][0] += re;
            e[q][1] += im;
        }
    }
}

/* S3 into the stress spectrum e (component i, layer k): Love's spectra times p3's. */
static void love_add(const mc_eigen_stress *op, const sfft *f, int i, int k, fftw_complex *e)
{
    quad_add(op, f, op->love + (size_t)(k * 6 + i) * f->lql, mc_eig_par(i), f->P, e);
}

/* The folded loads' stresses into e (component i, layer k; theory.md §8.9): with eps the
 * spectrum holds S eps already, else it starts from zero. */
static void loads_add(const mc_eigen_stress *op, const sfft *f, const double *const *loads,
                      int i, int k, fftw_complex *e)
{
    const size_t sl = f->fft.speclen;
    for (int l = 0; l < op->nloads; l++)
        if (loads[l])
            quad_add(op, f, op->lk + (size_t)((l * op->v.nz + k) * 6 + i) * f->lql,
                     op->load_par[l][i], f->PL + (size_t)l * sl, e);
}

/* The load spectra / 2G (the stresses leave the apply times 2G, as S eps). */
static void scale_spectrum(fftw_complex *P, size_t n, double w)
{
    for (size_t q = 0; q < n; q++) {
        P[q][0] *= w;
        P[q][1] *= w;
    }
}

/* The distributed spectrum ([kx - k0][ky], mc_dfft_spectrum) into E's layout ([ky][kx - k0])
 * and back. */
static void from_dfft(const sfft *f, const fftw_complex *d, fftw_complex *e)
{
    const int ty = f->fft.ty, nk = f->nk;
    for (int k = 0; k < nk; k++)
        for (int ky = 0; ky < ty; ky++) {
            e[(size_t)ky * nk + k][0] = d[(size_t)k * ty + ky][0];
            e[(size_t)ky * nk + k][1] = d[(size_t)k * ty + ky][1];
        }
}
static void to_dfft(const sfft *f, const fftw_complex *e, fftw_complex *d)
{
    const int ty = f->fft.ty, nk = f->nk;
    for (int k = 0; k < nk; k++)
        for (int ky = 0; ky < ty; ky++) {
            d[(size_t)k * ty + ky][0] = e[(size_t)ky * nk + k][0];
            d[(size_t)k * ty + ky][1] = e[(size_t)ky * nk + k][1];
        }
}

/* Every layer and component forward by the distributed transforms, into E (and shown to visit,
 * when given). Collective. */
static void dist_forward(const mc_eigen_stress *op, sfft *f, const double *const eps[6],
                         const mc_eig_forward_visit *visit)
{
    const int nz = op->v.nz, bm = f->bm;
    const size_t sl = f->fft.speclen, wc = (size_t)op->v.nx * op->v.ny;
    const size_t dl = (size_t)f->nk * f->fft.ty;
    for (int c = 0; c < 6; c++) /* a component's layers are contiguous: batches of bm */
        for (int k0 = 0; k0 < nz; k0 += bm) {
            const int m = nz - k0 < bm ? nz - k0 : bm;
            mc_dfft_forward_many(f->d, eps[c] + k0 * wc, wc, m, f->bs, dl);
            for (int q = 0; q < m; q++) {
                fftw_complex *e = f->E + (size_t)(c * nz + k0 + q) * sl;
                from_dfft(f, f->bs + q * dl, e);
                if (visit)
                    visit->layer(visit->ctx, -1, k0 + q, c, e);
            }
        }
}

/* Every layer and component forward into E (serial: threads over the layers; with a visitor
 * over its sum blocks, each block's layers in task order on one thread: eigen_internal.h). */
static void serial_forward(const mc_eigen_stress *op, sfft *f, const double *const eps[6],
                           const mc_eig_forward_visit *visit)
{
    const int nz = op->v.nz, wx = op->v.nx, wy = op->v.ny, tx = f->fft.tx;
    const size_t sl = f->fft.speclen, wc = (size_t)wx * wy, rl = (size_t)wy * tx;
#pragma omp parallel num_threads(f->nthr)
    {
        const int me = omp_get_thread_num();
        double *rows = f->rows + (size_t)me * rl;
        if (visit) {
            const int nb = visit->blocks;
#pragma omp for schedule(dynamic, 1)
            for (int b = 0; b < nb; b++)
                for (int t = mc_eig_block_first(b, nb, nz); t < mc_eig_block_first(b + 1, nb, nz);
                     t++) {
                    const int c = t / nz, k = t % nz;
                    mc_eig_fill_rows(rows, tx, eps[c] + k * wc, wx, wy, 0);
                    mc_eig_fft_forward(&f->fft, rows, f->E + (size_t)t * sl);
                    visit->layer(visit->ctx, b, k, c, f->E + (size_t)t * sl);
                }
        } else {
#pragma omp for schedule(dynamic, 1)
            for (int t = 0; t < 6 * nz; t++) {
                const int c = t / nz, k = t % nz;
                mc_eig_fill_rows(rows, tx, eps[c] + k * wc, wx, wy, 0);
                mc_eig_fft_forward(&f->fft, rows, f->E + (size_t)t * sl);
            }
        }
    }
}

void mc_eig_stress_fft_forward(mc_eigen_stress *op, const double *const eps[6],
                               const mc_eig_forward_visit *visit)
{
    sfft *f = op->fft;
    if (f->d)
        dist_forward(op, f, eps, visit);
    else
        serial_forward(op, f, eps, visit);
}

void mc_eig_stress_fft_spectra(const mc_eigen_stress *op, mc_eig_layer_spectra *out)
{
    const sfft *f = op->fft;
    *out = (mc_eig_layer_spectra){f->E, f->fft.speclen, f->fft.tx, f->fft.ty, f->k0, f->nk,
                                  f->d != NULL};
}

/* The distributed apply (theory.md §8.4): the lateral transforms by mc_dfft (each rank its rows,
 * then its columns), the depth step on this rank's frequencies, p3 and the stresses gathered
 * whole on every rank by the inverse transforms. Collective. */
static void dist_apply(mc_eigen_stress *op, const double *const eps[6], double G,
                       const double *const *loads, double *const sig[6])
{
    sfft *f = op->fft;
    const int nz = op->v.nz, wx = op->v.nx, wy = op->v.ny, bm = f->bm;
    const size_t sl = f->fft.speclen, wc = (size_t)wx * wy, dl = (size_t)f->nk * f->fft.ty;
    const double scale = 1.0 / ((double)f->fft.tx * f->fft.ty); /* FFTW does not normalise */
    for (int l = 0; loads && l < op->nloads; l++)
        if (loads[l]) {
            mc_dfft_forward_many(f->d, loads[l], wc, 1, f->bs, dl);
            from_dfft(f, f->bs, f->PL + (size_t)l * sl);
            scale_spectrum(f->PL + (size_t)l * sl, sl, 0.5 / G);
        }
    if (eps) {
        if (!op->fwd) /* (else E holds them: mc_eigen_stress_forward) */
            dist_forward(op, f, eps, NULL);
#pragma omp parallel num_threads(f->nthr)
        depth_all(op, f, omp_get_thread_num());
        /* p3 on the window only: back to space (whole on every rank), cut, forward again */
        to_dfft(f, f->P, f->bs);
        mc_dfft_inverse_many(f->d, f->bs, dl, 1, op->work, wc);
        for (size_t q = 0; q < wc; q++) {
            const double p = scale * op->work[q];
            op->work[q] = p;
            op->p3[q] = 2.0 * G * p;
        }
        mc_dfft_forward_many(f->d, op->work, wc, 1, f->bs, dl);
        from_dfft(f, f->bs, f->P);
    } else {
        memset(op->p3, 0, wc * sizeof *op->p3);
    }
    for (int i = 0; i < 6; i++)
        for (int k0 = 0; k0 < nz; k0 += bm) {
            const int m = nz - k0 < bm ? nz - k0 : bm;
            for (int q = 0; q < m; q++) {
                fftw_complex *e = f->E + (size_t)(i * nz + k0 + q) * sl;
                if (eps)
                    love_add(op, f, i, k0 + q, e);
                else
                    memset(e, 0, sl * sizeof *e);
                if (loads)
                    loads_add(op, f, loads, i, k0 + q, e);
                to_dfft(f, e, f->bs + q * dl);
            }
            double *out = sig[i] + k0 * wc;
            if (!op->keep_rows) {
                mc_dfft_inverse_many(f->d, f->bs, dl, m, out, wc);
                for (size_t q = 0; q < (size_t)m * wc; q++)
                    out[q] *= 2.0 * G * scale;
                continue;
            }
            /* this rank's rows alone (mc_eigen_stress_keep_rows): no gather */
            int r0, nr;
            mc_dfft_rows(f->d, &r0, &nr);
            mc_dfft_inverse_many_rows(f->d, f->bs, dl, m, out, wc);
            for (int q = 0; q < m; q++)
                for (size_t x = (size_t)r0 * wx; x < (size_t)(r0 + nr) * wx; x++)
                    out[q * wc + x] *= 2.0 * G * scale;
        }
}

int mc_eig_stress_fft_rows(const mc_eigen_stress *op, int *r0, int *nr)
{
    const sfft *f = op->fft;
    *r0 = 0;
    *nr = op->v.ny;
    if (!f || !f->d)
        return 0;
    mc_dfft_rows(f->d, r0, nr);
    return 1;
}

void mc_eig_stress_fft_apply(mc_eigen_stress *op, const double *const eps[6], double G,
                             const double *const *loads, double *const sig[6])
{
    sfft *f = op->fft;
    if (f->d) {
        dist_apply(op, eps, G, loads, sig);
        return;
    }
    const int nz = op->v.nz, wx = op->v.nx, wy = op->v.ny, tx = f->fft.tx, ty = f->fft.ty;
    const int nl = loads ? op->nloads : 0;
    const int nf = eps && !op->fwd ? 6 * nz : 0; /* forward transforms (none: E holds them) */
    const size_t sl = f->fft.speclen, wc = (size_t)wx * wy, rl = (size_t)wy * tx;
    const double scale = 1.0 / ((double)tx * ty); /* FFTW does not normalise */
#pragma omp parallel num_threads(f->nthr)
    {
        const int me = omp_get_thread_num();
        double *rows = f->rows + (size_t)me * rl;
        /* every layer and column forward, and the folded loads */
#pragma omp for schedule(dynamic, 1)
        for (int t = 0; t < nf + nl; t++) {
            if (t >= nf) {
                const int l = t - nf;
                if (!loads[l])
                    continue;
                mc_eig_fill_rows(rows, tx, loads[l], wx, wy, 0);
                mc_eig_fft_forward(&f->fft, rows, f->PL + (size_t)l * sl);
                scale_spectrum(f->PL + (size_t)l * sl, sl, 0.5 / G);
                continue;
            }
            const int c = t / nz, k = t % nz;
            mc_eig_fill_rows(rows, tx, eps[c] + k * wc, wx, wy, 0);
            mc_eig_fft_forward(&f->fft, rows, f->E + (size_t)t * sl);
        }
        if (eps) {
            /* depth coupling, frequency by frequency */
            depth_all(op, f, me);
#pragma omp single
            {
                /* p3 on the window only: back to space, cut, forward again */
                mc_eig_fft_inverse(&f->fft, f->P, rows);
                for (int j = 0; j < wy; j++)
                    for (int i = 0; i < wx; i++) {
                        const double p = scale * rows[(size_t)j * tx + i];
                        op->work[(size_t)j * wx + i] = p;
                        op->p3[(size_t)j * wx + i] = 2.0 * G * p;
                    }
                mc_eig_fill_rows(rows, tx, op->work, wx, wy, 0);
                mc_eig_fft_forward(&f->fft, rows, f->P);
            }
        } else {
#pragma omp single
            memset(op->p3, 0, wc * sizeof *op->p3);
        }
        /* S3 and the loads in, and every stress layer back */
#pragma omp for schedule(dynamic, 1)
        for (int t = 0; t < 6 * nz; t++) {
            const int i = t / nz, k = t % nz;
            fftw_complex *e = f->E + (size_t)t * sl;
            if (eps)
                love_add(op, f, i, k, e);
            else
                memset(e, 0, sl * sizeof *e);
            if (nl)
                loads_add(op, f, loads, i, k, e);
            mc_eig_fft_inverse(&f->fft, e, rows);
            double *out = sig[i] + k * wc;
            for (int j = 0; j < wy; j++)
                for (int x = 0; x < wx; x++)
                    out[(size_t)j * wx + x] = 2.0 * G * scale * rows[(size_t)j * tx + x];
        }
    }
}

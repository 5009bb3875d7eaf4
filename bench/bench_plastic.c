/* bench_plastic.c - the elastic-plastic stage's costs (issue 11 item 8):
 *   1. each eigenstrain operator (plastic/eigen_op.h, fft backend) against the bare transforms
 *      it cannot avoid, at several sizes up to 256^2 x 32, and its bytes per volume cell; the
 *      direct (reference) and fft backends' agreement at a small size;
 *   2. the Kogut-Etsion sphere at P/P_c = 10 against grid size, with its error against the KE
 *      fit (work against precision);
 *   3. what each skip of the stage saves: the column window, depth = auto, the elastic shortcut.
 * The KE case is the dossier's (plastic-lubrication §2.6): E = 210 GPa, nu = 0.3, Y = 1 GPa,
 * R = 15 mm on a rigid flat, square domain of 24 a_c / 2.7 (its 24-cell grid has 2.7 cells per
 * contact radius a_c). */
#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <stdlib.h>
#include <fcntl.h>
#include <unistd.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include "bench.h"
#include "core/alloc.h"
#include "core/fftsize.h"
#include "core/threads.h"
#include "operator/operator.h"
#include "case/case.h"
#include "pipeline/memguard.h"
#include "pipeline/pipeline.h"
#include "plastic/eigen_op.h"
#include "plastic/loop.h"
#include "vutil.h"

#define KE_E 210e9
#define KE_NU 0.3
#define KE_Y 1e9
#define KE_R 15e-3
#define KE_TOL_W 0.03    /* w/w_c within 3 % of the KE fit (issue 11 item 7) */
#define KE_TOL_A 0.05    /* A/A_c within 5 % of the KE fit (issue 11 item 7) */
#define KE_TIME_MAX 60.0 /* s: the KE point at 10 P_c within KE_TOL_W (issue 11 item 8) */
#define OP_RATIO_MAX 3.0 /* apply / FFT bound at 256^2 x 32 (issue 11 item 8) */
#define BYTES_MAX 400.0  /* bytes per volume cell (issue 11 item 8) */
/* direct and fft backends sum the same tables in another order: round-off only (issue 11 item 3
 * asks 1e-10 relative of the largest value) */
#define AGREE_TOL 1e-10

/* ---- the Kogut-Etsion case ------------------------------------------------------------------- */

typedef struct {
    double wc, pc, ac; /* critical interference (m), load (N), contact radius (m) */
} ke_crit;

/* KE's critical values with C = 1.295 exp(0.736 nu), E_H = E / (1 - nu^2) (rigid flat):
 * w_c = (pi C Y / (2 E_H))^2 R, P_c = (4/3) R^2 (pi C Y / 2)^3 / E_H^2, a_c = sqrt(R w_c). */
static ke_crit ke_critical(void)
{
    const double EH = KE_E / (1 - KE_NU * KE_NU), C = 1.295 * exp(0.736 * KE_NU);
    const double t = M_PI * C * KE_Y / 2;
    ke_crit k;
    k.wc = pow(t / EH, 2) * KE_R;
    k.pc = 4.0 / 3.0 * KE_R * KE_R * t * t * t / (EH * EH);
    k.ac = sqrt(KE_R * k.wc);
    return k;
}

/* The KE fits: w/w_c from P/P_c = 1.03 (w/w_c)^1.425 (1 <= w/w_c <= 6) or 1.40 (w/w_c)^1.263
 * (6 .. 110); A/A_c = 0.93 (w/w_c)^1.136 or 0.94 (w/w_c)^1.146. */
static double ke_w(double p)
{
    const double w = pow(p / 1.03, 1 / 1.425);
    return w <= 6 ? w : pow(p / 1.40, 1 / 1.263);
}
static double ke_a(double w) { return w <= 6 ? 0.93 * pow(w, 1.136) : 0.94 * pow(w, 1.146); }

#define KE_MAX_STEPS 32 /* per-step counts kept of a run */

typedef struct {
    /* in: 0 = the default */
    double margin, depth, yield; /* [plasticity] margin, depth (m), yield_stress (Pa) */
    double side;                 /* domain side, m (0: 24 a_c / 2.7) */
    int load_steps;              /* [plasticity] load_steps (0: the default) */
    int cuboid;                  /* 1: [plasticity] kernel = cuboid (the default: spectral) */
    /* out */
    double cpu;                  /* process CPU time of the run (all threads), s */
    int st_outer[KE_MAX_STEPS], st_sweeps[KE_MAX_STEPS], st_applies[KE_MAX_STEPS];
    int ok, converged, shortcut, steps, outer, sweeps, nz, wnx, wny;
    long volume_cells;
    double w, a, err_w, err_a, t, dz, vm_max;
} ke_run;

/* The KE sphere at p_pc P_c on an n x n grid through mc_pipeline_run, every other setting the
 * default. Fills r (r->ok = 0 when the run failed). */
static void ke_solve(int n, double p_pc, ke_run *r)
{
    const ke_crit k = ke_critical();
    const double side = r->side > 0 ? r->side : 24 * k.ac / 2.7;
    mc_scene sc;
    vu_scene(&sc, n, n, side / n, side / n);
    sc.geometry.shape = MC_SHAPE_SPHERE;
    sc.geometry.radius = KE_R;
    sc.body1.E = KE_E;
    sc.body1.nu = KE_NU;
    sc.body2.rigid = 1;
    sc.load.kind = MC_LOAD_FORCE;
    sc.load.value = p_pc * k.pc;
    sc.plasticity.enabled = 1;
    sc.plasticity.criterion = MC_CRITERION_VON_MISES;
    sc.plasticity.hardening = MC_HARDENING_PERFECT;
    sc.plasticity.yield_stress = r->yield > 0 ? r->yield : KE_Y;
    if (r->margin > 0)
        sc.plasticity.margin = r->margin;
    if (r->depth > 0)
        sc.plasticity.depth = r->depth;
    if (r->load_steps > 0)
        sc.plasticity.load_steps = r->load_steps;
    if (r->cuboid)
        sc.plasticity.kernel = MC_EIG_KERNEL_CUBOID;
    mc_results res;
    mc_error err = {0};
    const double t0 = mc_clock(), c0 = mc_bench_cpu();
    const int rc = mc_pipeline_run(&sc, &res, &err);
    r->t = mc_clock() - t0;
    r->cpu = mc_bench_cpu() - c0;
    r->ok = rc == MC_OK || rc == MC_NOT_CONVERGED;
    if (r->ok) {
        const mc_stage_plastic_summary *pl = &res.plastic;
        r->converged = rc == MC_OK && pl->converged;
        r->w = res.contact.approach / k.wc;
        r->a = res.contact.area / (M_PI * k.ac * k.ac);
        r->err_w = r->w / ke_w(p_pc) - 1;
        r->err_a = r->a / ke_a(ke_w(p_pc)) - 1;
        r->steps = pl->steps_done;
        r->outer = pl->outer_iterations;
        r->sweeps = 0;
        for (int s = 0; s < pl->steps_done && pl->steps; s++) {
            r->sweeps += pl->steps[s].plastic_iterations;
            if (s < KE_MAX_STEPS) {
                r->st_outer[s] = pl->steps[s].outer_iterations;
                r->st_sweeps[s] = pl->steps[s].plastic_iterations;
                r->st_applies[s] = pl->steps[s].stress_applies;
            }
        }
        r->nz = pl->nz;
        r->wnx = pl->wnx;
        r->wny = pl->wny;
        r->volume_cells = pl->volume_cells;
        r->shortcut = pl->elastic_shortcut;
        r->dz = pl->dz;
        r->vm_max = pl->vm_elastic_max;
    }
    mc_results_free(&res);
}

/* Peak resident memory of this process so far (VmHWM), bytes; NAN if unknown. */
static double peak_rss(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    double kb = NAN;
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "VmHWM:", 6))
            sscanf(line + 6, "%lf", &kb);
    if (f)
        fclose(f);
    return 1024 * kb;
}

/* ---- the operators --------------------------------------------------------------------------- */

/* CPU time of the calling thread, s: the operator timings run on one thread, and on a machine
 * shared with other work its CPU time is what the code costs (the wall clock swung by 3x between
 * runs here). */
static double thread_cpu(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Median thread CPU time of reps calls of fn(arg) after one warm-up call, s. */
static double cpu_time(void (*fn)(void *), void *arg, int reps)
{
    double t[16];
    reps = reps < 1 ? 1 : reps > 16 ? 16 : reps;
    fn(arg);
    for (int k = 0; k < reps; k++) {
        const double t0 = thread_cpu();
        fn(arg);
        t[k] = thread_cpu() - t0;
    }
    for (int a = 1; a < reps; a++) /* insertion sort: a handful of values */
        for (int b = a; b > 0 && t[b] < t[b - 1]; b--) {
            const double x = t[b];
            t[b] = t[b - 1];
            t[b - 1] = x;
        }
    return t[reps / 2];
}

/* One bare r2c + c2r pair of tx x ty on ONE thread (the operators run their transforms on one
 * thread each, layers in parallel), FFTW_ESTIMATE as they plan: median CPU time of reps, s. */
static double pair_time(int tx, int ty, int reps)
{
    double *r = fftw_malloc(sizeof(double) * (size_t)tx * ty);
    fftw_complex *c = fftw_malloc(sizeof(fftw_complex) * (size_t)ty * (tx / 2 + 1));
    double t = NAN;
    if (r && c) {
        mc_fftw_prepare(NULL);
        fftw_plan_with_nthreads(1);
        mc_bench_pair p = {fftw_plan_dft_r2c_2d(ty, tx, r, c, FFTW_ESTIMATE),
                      fftw_plan_dft_c2r_2d(ty, tx, c, r, FFTW_ESTIMATE)};
        for (size_t i = 0; i < (size_t)tx * ty; i++)
            r[i] = (double)(i % 17);
        t = cpu_time(mc_bench_pair_run, &p, reps);
        fftw_destroy_plan(p.f);
        fftw_destroy_plan(p.b);
        mc_fftw_prepare(NULL); /* the planner's count back to the run's */
    }
    fftw_free(r);
    fftw_free(c);
    return t;
}

typedef struct {
    double stress_s, disp_s;         /* one apply, s */
    double stress_b, disp_b;         /* bytes per volume cell */
    double stress_create, disp_create; /* s */
} op_cost;

/* Both operators (fft) on a volume of nz layers under the whole n x n grid. 0 on success. */
/* per: 0 free axes, 1 periodic y (a strip), 2 both periodic (theory.md §8.6) */
static int op_measure(int n, int nz, int per, int reps, op_cost *c)
{
    mc_grid g = {n, n, 1e-6, 1e-6, per == 2, per >= 1};
    const mc_eigen_volume v = mc_eigen_volume_full(&g, nz, 1e-6);
    const size_t nv = (size_t)n * n * nz;
    double *blk = mc_zeros(12 * nv), *uz = mc_zeros((size_t)n * n);
    mc_bench_eig a;
    memset(&a, 0, sizeof a);
    mc_error err = {0};
    int rc = blk && uz ? MC_OK : MC_ERR_NOMEM;
    if (rc == MC_OK) {
        for (int k = 0; k < 6; k++)
            a.e[k] = blk + k * nv, a.sg[k] = blk + (6 + k) * nv;
        a.uz = uz;
        for (size_t i = 0; i < 6 * nv; i++)
            blk[i] = 1e-3 * cos(0.91 * (double)i);
        double t0 = mc_clock();
        rc = mc_eigen_disp_create(&g, &v, KE_NU, MC_BACKEND_FFT, &a.d, &err);
        c->disp_create = mc_clock() - t0;
    }
    if (rc == MC_OK) {
        c->disp_b = (double)mc_eigen_disp_bytes(a.d) / (double)nv;
        c->disp_s = cpu_time(mc_bench_eig_disp, &a, reps);
        mc_eigen_disp_destroy(&a.d);
        const double t0 = mc_clock();
        rc = mc_eigen_stress_create(&g, &v, KE_NU, MC_BACKEND_FFT, &a.s, &err);
        c->stress_create = mc_clock() - t0;
    }
    if (rc == MC_OK) {
        c->stress_b = (double)mc_eigen_stress_bytes(a.s) / (double)nv;
        c->stress_s = cpu_time(mc_bench_eig_stress, &a, reps);
    }
    mc_eigen_stress_destroy(&a.s);
    mc_eigen_disp_destroy(&a.d);
    mc_free(blk);
    mc_free(uz);
    return rc;
}

/* Largest |fft - direct| / largest |direct| of both operators on a random eigenstrain in a window
 * of an odd-by-even grid with dx != dy. */
static void op_agree(double *dev_s, double *dev_d)
{
    mc_grid g = {13, 10, 1.0e-6, 1.3e-6, 0, 0};
    const mc_eigen_volume v = {2, 1, 9, 8, 5, 0.8e-6, MC_EIG_CELL_AVERAGE, NULL, MC_EIG_KERNEL_CUBOID};
    const size_t nv = (size_t)v.nx * v.ny * v.nz, ns = (size_t)g.nx * g.ny;
    double *blk = mc_zeros(18 * nv + 2 * ns);
    *dev_s = *dev_d = NAN;
    if (!blk)
        return;
    const double *e[6];
    double *s[2][6], *uz[2] = {blk + 18 * nv, blk + 18 * nv + ns};
    for (int k = 0; k < 6; k++)
        e[k] = blk + k * nv, s[0][k] = blk + (6 + k) * nv, s[1][k] = blk + (12 + k) * nv;
    unsigned long long x = 88172645463325252ULL; /* xorshift: a fixed pseudo-random field */
    for (size_t i = 0; i < 6 * nv; i++) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        blk[i] = 1e-3 * ((double)(x >> 11) / 9007199254740992.0 - 0.5);
    }
    const mc_backend b[2] = {MC_BACKEND_DIRECT, MC_BACKEND_FFT};
    int ok = 1;
    for (int m = 0; m < 2 && ok; m++) {
        mc_eigen_stress *so = NULL;
        mc_eigen_disp *d = NULL;
        mc_error err = {0};
        ok = mc_eigen_stress_create(&g, &v, KE_NU, b[m], &so, &err) == MC_OK &&
             mc_eigen_disp_create(&g, &v, KE_NU, b[m], &d, &err) == MC_OK;
        if (ok) {
            mc_eigen_stress_apply(so, e, 80e9, s[m]);
            mc_eigen_disp_apply(d, e, uz[m]);
        }
        mc_eigen_stress_destroy(&so);
        mc_eigen_disp_destroy(&d);
    }
    if (ok) {
        double ms = 0, ds = 0, md = 0, dd = 0;
        for (int k = 0; k < 6; k++)
            for (size_t i = 0; i < nv; i++) {
                ms = vf_worst(ms, fabs(s[0][k][i]));
                ds = vf_worst(ds, fabs(s[1][k][i] - s[0][k][i]));
            }
        for (size_t i = 0; i < ns; i++) {
            md = vf_worst(md, fabs(uz[0][i]));
            dd = vf_worst(dd, fabs(uz[1][i] - uz[0][i]));
        }
        *dev_s = ds / ms;
        *dev_d = dd / md;
    }
    mc_free(blk);
}

static void section_operators(vf_ctx *ctx, int quick, double *ratio256, double *bytes256)
{
    static const int on[] = {64, 128, 256}, onz[] = {8, 16, 32};
    const int nop = quick ? 2 : 3;
    *ratio256 = *bytes256 = NAN;
    vf_text(ctx, "## Elastic-plastic stage\n\n### Eigenstrain operators against their FFT bound\n\n"
                 "One application (median CPU time of repeated calls) of each operator "
                 "(plastic/eigen_op.h, fft backend, ONE thread) on a volume of n x n x nz cells under the whole grid, "
                 "against the bare one-thread FFTW transforms it cannot avoid, timed here on the "
                 "padded size (2m)², m = the 7-smooth size >= n: residual stress, 6 nz r2c + "
                 "6 nz c2r = 6 nz pairs; residual displacement, 6 nz r2c + one c2r = "
                 "(6 nz + 1) / 2 pairs. Bytes: the operator's own count (tables, spectra, "
                 "workspaces) per volume cell. Create: tables, their spectra and plans (once per "
                 "volume). The operators skip the all-zero rows of the padding (a pruned 2-D transform), so a "
                 "ratio can fall below 1. Not counted in the bytes: the loop's own volume arrays "
                 "(plastic strain, stresses, return-mapping state).\n\n"
                 "| volume | pair (ms) | stress apply (s) | bound (s) | ratio | B / cell | create (s) "
                 "| displacement apply (s) | bound (s) | ratio | B / cell | create (s) |\n"
                 "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    FILE *f = vf_open(ctx, "plastic_operators.csv");
    if (f)
        fprintf(f, "n,nz,pair_s,stress_s,stress_bound_s,stress_bytes_per_cell,stress_create_s,"
                   "disp_s,disp_bound_s,disp_bytes_per_cell,disp_create_s\n");
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    int last_n = 0, last_nz = 0;
    for (int k = 0; k < nop; k++) {
        const int n = on[k], nz = onz[k], m = mc_fftsize_good(n);
        const double pair = pair_time(2 * m, 2 * m, n <= 128 ? 20 : 7);
        op_cost c = {NAN, NAN, NAN, NAN, NAN, NAN};
        if (op_measure(n, nz, 0, n <= 128 ? 7 : 3, &c) != MC_OK) {
            vf_text(ctx, "| %d² x %d | could not create the operators (memory?) |\n", n, nz);
            continue;
        }
        const double bs = 6.0 * nz * pair, bd = (6.0 * nz + 1) / 2 * pair;
        vf_text(ctx,
                "| %d² x %d | %.3f | %.4f | %.4f | %.2f | %.0f | %.2f | %.4f | %.4f | %.2f | %.0f "
                "| %.2f |\n",
                n, nz, 1e3 * pair, c.stress_s, bs, c.stress_s / bs, c.stress_b, c.stress_create,
                c.disp_s, bd, c.disp_s / bd, c.disp_b, c.disp_create);
        if (f)
            fprintf(f, "%d,%d,%.6g,%.6g,%.6g,%.1f,%.4g,%.6g,%.6g,%.1f,%.4g\n", n, nz, pair,
                    c.stress_s, bs, c.stress_b, c.stress_create, c.disp_s, bd, c.disp_b,
                    c.disp_create);
        char id[48], q[96];
        snprintf(id, sizeof id, "eigen_disp_ratio_%d", n);
        snprintf(q, sizeof q, "residual displacement apply / FFT bound at %d² x %d", n, nz);
        vf_info(ctx, id, q, "ideal 1", 1, c.disp_s / bd);
        if (n != 256) {
            snprintf(id, sizeof id, "eigen_stress_ratio_%d", n);
            snprintf(q, sizeof q, "residual stress apply / FFT bound at %d² x %d", n, nz);
            vf_info(ctx, id, q, "ideal 1; the target <= 3 binds at 256² x 32", 1,
                    c.stress_s / bs);
        }
        *ratio256 = fmax(c.stress_s / bs, c.disp_s / bd); /* the last (largest) size */
        *bytes256 = c.stress_b + c.disp_b;
        last_n = n;
        last_nz = nz;
    }
    /* periodic axes at the largest size: unpadded transforms, smaller spectra (theory.md §8.6) */
    if (last_n) {
        const int n = last_n, nz = last_nz;
        const double pair = pair_time(n, n, n <= 128 ? 20 : 7);
        vf_text(ctx, "\nPeriodic axes (theory.md §8.6) at %d² x %d: a strip periodic along y (x "
                     "free, padded) and a doubly periodic volume, whose periodic axes are "
                     "transformed unpadded; bound: the bare pairs of the unpadded %d² (the free "
                     "row above is read against the padded size). Create includes the image sums "
                     "of the periodic tables.\n\n"
                     "| grid | stress apply (s) | ratio to %d² pairs | B / cell | create (s) | "
                     "displacement apply (s) | B / cell | create (s) |\n"
                     "|---|---|---|---|---|---|---|---|\n",
                n, nz, n, n);
        for (int per = 1; per <= 2; per++) {
            op_cost c = {NAN, NAN, NAN, NAN, NAN, NAN};
            if (op_measure(n, nz, per, n <= 128 ? 7 : 3, &c) != MC_OK)
                continue;
            vf_text(ctx, "| %s | %.4f | %.2f | %.0f | %.2f | %.4f | %.0f | %.2f |\n",
                    per == 1 ? "strip (periodic y)" : "doubly periodic", c.stress_s,
                    c.stress_s / (6.0 * nz * pair), c.stress_b, c.stress_create, c.disp_s,
                    c.disp_b, c.disp_create);
            char id[48], q[120];
            snprintf(id, sizeof id, "eigen_bytes_%s", per == 1 ? "strip" : "doubly");
            snprintf(q, sizeof q, "eigen operators (stress + displacement), bytes per volume "
                     "cell, %s %d² x %d", per == 1 ? "strip" : "doubly periodic", n, nz);
            vf_info(ctx, id, q, "the free grid's row above for comparison", NAN,
                    c.stress_b + c.disp_b);
            vf_regress(ctx, id, VF_TIER_NONE);
        }
    }
    mc_threads_end(&scope);
    if (f)
        vf_close(ctx, f);
    if (last_n) { /* the largest volume held its stress operator, the eigenstrain and 6 stress
                   * fields (96 B per cell) at once: the process's peak is that plus the code */
        const double cells = (double)last_n * last_n * last_nz, rss = peak_rss();
        vf_text(ctx, "\nPeak resident memory of this process after these: %.0f MiB, %.0f bytes per "
                     "volume cell of the %d² x %d volume (its stress operator, the eigenstrain and "
                     "the six stress fields, 96 bytes per cell, plus the program).\n",
                rss / 1048576.0, rss / cells, last_n, last_nz);
        vf_info(ctx, "plastic_peak_rss_per_cell", "peak RSS per volume cell, largest operator volume",
                "operator bytes + 96 (eps, sigma)", 0, rss / cells);
    }
    double dev_s, dev_d;
    op_agree(&dev_s, &dev_d);
    vf_text(ctx, "\nDirect (O(N²) reference) against fft on a 9 x 8 x 5 window of a 13 x 10 grid, "
                 "dx = 1 um, dy = 1.3 um, random eigenstrain: largest difference / largest "
                 "value %.1e (stress), %.1e (displacement).\n\n",
            dev_s, dev_d);
    vf_check(ctx, "eigen_stress_direct_fft", "residual stress: |fft - direct| / max |direct|",
             "round-off (issue 11: <= 1e-10)", 0, dev_s, AGREE_TOL, VF_MAX);
    vf_check(ctx, "eigen_disp_direct_fft", "residual displacement: |fft - direct| / max |direct|",
             "round-off (issue 11: <= 1e-10)", 0, dev_d, AGREE_TOL, VF_MAX);
}

/* ---- the KE sphere against grid size ---------------------------------------------------------- */

static void section_ke(vf_ctx *ctx, int quick)
{
    const ke_crit kc = ke_critical();
    /* 20^2 takes ~2 minutes on the loaded 2-core machine (its volume is above the eigen
     * operators' threads cutoff): left out to keep the section near 2 minutes */
    static const int kn[] = {10, 12, 16};
    const int k0 = quick ? 1 : 0, nke = quick ? 2 : 3; /* --quick: 12^2 alone */
    vf_text(ctx, "### Kogut-Etsion sphere at P/P_c = 10: work against precision\n\n"
                 "Dossier plastic-lubrication §2.6: elastic-perfectly plastic half-space (E = 210 "
                 "GPa, nu = 0.3, Y = 1 GPa) under a rigid sphere R = 15 mm: w_c = %.3f um, "
                 "P_c = %.2f N, a_c = %.1f um; square domain of side 24 a_c / 2.7 = %.0f um; every "
                 "other setting the default (%s threads, load steps, tolerances, depth and column "
                 "window auto). The target row takes the fastest converged grid with w/w_c within "
                 "3 %% and A/A_c within 5 %% (the kogut_etsion acceptance); the error need not fall "
                 "monotonically with the grid (contact area is grid-quantised). KE fit at 10 P_c: w/w_c = %.3f, A/A_c = %.2f. Time: the whole "
                 "pipeline run (no output files). Sweeps: plastic fixed-point iterations, one "
                 "residual stress application each.\n\n"
                 "| grid | volume | w/w_c | error | A/A_c | error | time (s) | outer it. | sweeps "
                 "| per sweep (ms) | converged |\n|---|---|---|---|---|---|---|---|---|---|---|\n",
            kc.wc * 1e6, kc.pc, kc.ac * 1e6, 24 * kc.ac / 2.7 * 1e6, "the run's", ke_w(10),
            ke_a(ke_w(10)));
    FILE *f = vf_open(ctx, "ke_work_precision.csv");
    if (f)
        fprintf(f, "n,nz,volume_cells,w_wc,err_w,a_ac,err_a,time_s,outer,sweeps,converged\n");
    int best_n = 0;
    double best_t = NAN, best_err = NAN;
    for (int k = k0; k < nke; k++) {
        ke_run r;
        memset(&r, 0, sizeof r);
        ke_solve(kn[k], 10.0, &r);
        if (!r.ok) {
            vf_text(ctx, "| %d² | the run failed |\n", kn[k]);
            continue;
        }
        vf_text(ctx, "| %d² | %d x %d x %d | %.3f | %+.1f %% | %.2f | %+.1f %% | %.1f | %d | %d | "
                     "%.2f | %s |\n",
                kn[k], r.wnx, r.wny, r.nz, r.w, 100 * r.err_w, r.a, 100 * r.err_a, r.t, r.outer,
                r.sweeps, r.sweeps ? 1e3 * r.t / r.sweeps : NAN, r.converged ? "yes" : "NO");
        if (f)
            fprintf(f, "%d,%d,%ld,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%d\n", kn[k], r.nz,
                    r.volume_cells, r.w, r.err_w, r.a, r.err_a, r.t, r.outer, r.sweeps,
                    r.converged);
        if (fabs(r.err_w) <= KE_TOL_W && fabs(r.err_a) <= KE_TOL_A && r.converged &&
            !(best_t <= r.t)) {
            best_n = kn[k];
            best_t = r.t;
            best_err = r.err_w;
        }
    }
    if (f)
        vf_close(ctx, f);
    vf_plot(ctx, "ke_work_precision.png",
            "Kogut-Etsion sphere at 10 P_c: error against the KE fit against run time, per grid",
            "set datafile separator ','\nset logscale x\nset key top right\n"
            "set xlabel 'run time (s)'\nset ylabel 'error against the KE fit (%)'\nset grid\n"
            "plot 'ke_work_precision.csv' using 8:(100*$5) with linespoints pt 7 "
            "title 'w/w_c', '' using 8:(100*$7) with linespoints pt 5 title 'A/A_c'");
    vf_text(ctx, "\n");
    if (best_n) {
        char q[160];
        snprintf(q, sizeof q,
                 "KE at 10 P_c: fastest converged grid with w/w_c within 3 %% and A/A_c within "
                 "5 %% (%d², w/w_c %+.1f %%), run time (s)",
                 best_n, 100 * best_err);
        vf_check(ctx, "plastic_ke_time", q, "target <= 60 s (issue 11)", KE_TIME_MAX, best_t,
                 KE_TIME_MAX, VF_MAX);
    } else {
        vf_fail(ctx, "plastic_ke_time",
                "no converged grid of the study has w/w_c within 3 %% and A/A_c within 5 %% of "
                "the KE fit");
    }
}

/* ---- the KE sphere at 8 P_c on 64^2 (issue 20 item 3) ---------------------------------------- */

/* The scene of issue 20: 8 P_c in 16 load steps on the bench's square (24 a_c / 2.7, so a_c is
 * about 7 cells of 64^2 and the contact radius at 8 P_c about 15), every other setting the
 * default; its time against the target, its error against the KE fit, and the per-step counts on
 * two grids (where the work of a step grows with N). */
static void section_ke64(vf_ctx *ctx, int quick)
{
    static const int kn[] = {32, 64};
    const int k0 = 0, nk = quick ? 1 : 2; /* --quick: 32^2 alone */
    ke_run r[2];
    memset(r, 0, sizeof r);
    for (int k = k0; k < nk; k++) {
        r[k].load_steps = 16;
        ke_solve(kn[k], 8.0, &r[k]);
    }
    vf_text(ctx, "### Kogut-Etsion sphere at 8 P_c in 16 load steps (issue 20)\n\n"
                 "The scene of issue 20 item 3: the square above, 8 P_c in 16 load steps, every "
                 "other setting the default (%d threads; dz = dx / 2, depth and window auto). "
                 "Wall: the whole pipeline run; CPU: the process's CPU time, all threads (the "
                 "measure that does not depend on what else the machine runs). KE fit at 8 P_c: "
                 "w/w_c = %.4f, A/A_c = %.2f.\n\n"
                 "| grid | volume | w/w_c | error | A/A_c (cells in contact) | error | wall (s) | CPU (s) | outer | "
                 "sweeps | stress applies | converged |\n|---|---|---|---|---|---|---|---|---|---|"
                 "---|---|\n",
            mc_threads_count(), ke_w(8), ke_a(ke_w(8)));
    for (int k = k0; k < nk; k++) {
        if (!r[k].ok) {
            vf_text(ctx, "| %d² | the run failed |\n", kn[k]);
            continue;
        }
        int applies = 0;
        for (int s = 0; s < r[k].steps && s < KE_MAX_STEPS; s++)
            applies += r[k].st_applies[s];
        vf_text(ctx, "| %d² | %d x %d x %d | %.4f | %+.2f %% | %.2f | %+.1f %% | %.1f | %.1f | %d "
                     "| %d | %d | %s |\n",
                kn[k], r[k].wnx, r[k].wny, r[k].nz, r[k].w, 100 * r[k].err_w, r[k].a,
                100 * r[k].err_a, r[k].t, r[k].cpu, r[k].outer, r[k].sweeps, applies,
                r[k].converged ? "yes" : "NO");
    }
    vf_text(ctx, "\nPer load step (outer iterations / sweeps; one contact solve and one elastic "
                 "stress field per outer iteration):\n\n| step |");
    for (int k = k0; k < nk; k++)
        vf_text(ctx, " %d² |", kn[k]);
    vf_text(ctx, "\n|---|");
    for (int k = k0; k < nk; k++)
        vf_text(ctx, "---|");
    vf_text(ctx, "\n");
    for (int s = 0; s < 16; s++) {
        vf_text(ctx, "| %d |", s + 1);
        for (int k = k0; k < nk; k++)
            vf_text(ctx, " %d / %d |", r[k].st_outer[s], r[k].st_sweeps[s]);
        vf_text(ctx, "\n");
    }
    vf_text(ctx, "\n");
    FILE *f = vf_open(ctx, "ke8_steps.csv");
    if (f) {
        fprintf(f, "n,step,outer,sweeps,stress_applies\n");
        for (int k = k0; k < nk; k++)
            for (int s = 0; s < r[k].steps && s < KE_MAX_STEPS; s++)
                fprintf(f, "%d,%d,%d,%d,%d\n", kn[k], s + 1, r[k].st_outer[s], r[k].st_sweeps[s],
                        r[k].st_applies[s]);
        vf_close(ctx, f);
    }
    const ke_run *big = &r[nk - 1];
    char q[200];
    snprintf(q, sizeof q, "KE sphere at 8 P_c, 16 load steps, %d²: |w/w_c error| against the KE "
             "fit", kn[nk - 1]);
    vf_check(ctx, "plastic_ke8_error", q, "within 3 % (issue 20 item 3)", KE_TOL_W,
             big->ok && big->converged ? fabs(big->err_w) : NAN, KE_TOL_W, VF_MAX);
    vf_regress(ctx, "plastic_ke8_error", VF_TIER_NONE);
    snprintf(q, sizeof q, "KE sphere at 8 P_c, 16 load steps, %d²: wall time of the run, s "
             "(%d threads)", kn[nk - 1], mc_threads_count());
    vf_check(ctx, "plastic_ke8_time", q, "target <= 60 s (issue 20 item 3)", KE_TIME_MAX,
             big->ok ? big->t : NAN, KE_TIME_MAX, VF_MAX);
    vf_regress(ctx, "plastic_ke8_time", VF_TIER_NONE);
    vf_info(ctx, "plastic_ke8_cpu", "KE sphere at 8 P_c, 16 load steps: process CPU time, s", "",
            NAN, big->ok ? big->cpu : NAN);
    vf_regress(ctx, "plastic_ke8_cpu", VF_TIER_NONE);
}

/* ---- graded against uniform layers (issue 20 item 4) ---------------------------------------- */

/* Graded layers against the uniform fine volume must give the residual dent and the plastic
 * volume within 1 % (issue 20 item 4). */
#define GRADED_TOL 0.01

typedef struct {
    int ok, converged, nz;
    double dent, vp, cpu, depth;
} graded_run;

/* A rough sphere at p_H ~ 1.5 GPa (R = 2 mm, 5.2 N, steel on steel: a = 41 um), Gaussian
 * roughness of 0.1 um rms and 6 um correlation (asperity pressures ~4.6 GPa), linear hardening
 * from 800 MPa, 4 load steps, depth and window auto; layering graded (the default with
 * depth = auto) or uniform. */
static void graded_solve(int n, int uniform, graded_run *r)
{
    mc_scene sc;
    const double side = 112e-6;
    vu_scene(&sc, n, n, side / n, side / n);
    sc.geometry.shape = MC_SHAPE_SPHERE;
    sc.geometry.radius = 2e-3;
    sc.roughness.type = MC_ROUGH_GAUSSIAN;
    sc.roughness.rq = 0.1e-6;
    sc.roughness.correlation_x = sc.roughness.correlation_y = 6e-6;
    sc.roughness.seed = 7;
    sc.load.kind = MC_LOAD_FORCE;
    sc.load.value = 5.2;
    sc.plasticity.enabled = 1;
    sc.plasticity.criterion = MC_CRITERION_VON_MISES;
    sc.plasticity.hardening = MC_HARDENING_LINEAR;
    sc.plasticity.yield_stress = 800e6;
    sc.plasticity.tangent_modulus = 20e9;
    sc.plasticity.load_steps = 4;
    sc.plasticity.layering = uniform ? MC_LAYERING_UNIFORM : MC_LAYERING_GRADED;
    mc_results res;
    mc_error err = {0};
    const double c0 = mc_bench_cpu();
    const int rc = mc_pipeline_run(&sc, &res, &err);
    r->cpu = mc_bench_cpu() - c0;
    r->ok = rc == MC_OK || rc == MC_NOT_CONVERGED;
    if (r->ok) {
        r->converged = rc == MC_OK && res.plastic.converged;
        r->dent = res.plastic.residual_max;
        r->vp = res.plastic.plastic_volume;
        r->nz = res.plastic.nz;
        r->depth = res.plastic.depth;
    }
    mc_results_free(&res);
}

static void section_graded(vf_ctx *ctx, int quick)
{
    const int n = quick ? 40 : 56;
    graded_run g, u;
    memset(&g, 0, sizeof g);
    memset(&u, 0, sizeof u);
    graded_solve(n, 0, &g);
    graded_solve(n, 1, &u);
    const double ed = g.ok && u.ok ? g.dent / u.dent - 1 : NAN;
    const double ev = g.ok && u.ok ? g.vp / u.vp - 1 : NAN;
    vf_text(ctx, "### Graded against uniform layers (issue 20 item 4)\n\n"
                 "A rough sphere at p_H ~ 1.5 GPa (R = 2 mm, 5.2 N, steel on steel; Gaussian "
                 "roughness 0.1 um rms, 6 um correlation; linear hardening from 800 MPa; 4 load "
                 "steps; %d² cells of %.2f um, dz = dx / 2, depth and window auto): layering = "
                 "graded (dz down to 8 dx, then odd groups of at most 0.25 x depth) against "
                 "uniform layers of dz. CPU: the process's CPU time (%d threads). The graded "
                 "volume's stress operator takes the coarse depth step when it costs less than "
                 "the fine lattice's DFTs (docs/theory.md §8.8).\n\n"
                 "| layering | layers | depth (um) | residual dent (nm) | plastic volume (um³) "
                 "| CPU (s) | converged |\n|---|---|---|---|---|---|---|\n",
            n, 1e6 * 112e-6 / n, mc_threads_count());
    const graded_run *rr[2] = {&g, &u};
    static const char *const name[2] = {"graded", "uniform"};
    for (int k = 0; k < 2; k++)
        if (rr[k]->ok)
            vf_text(ctx, "| %s | %d | %.1f | %.3f | %.4g | %.1f | %s |\n", name[k], rr[k]->nz,
                    1e6 * rr[k]->depth, 1e9 * rr[k]->dent, 1e18 * rr[k]->vp, rr[k]->cpu,
                    rr[k]->converged ? "yes" : "NO");
        else
            vf_text(ctx, "| %s | the run failed |\n", name[k]);
    vf_text(ctx, "\nGraded against uniform: dent %+.3f %%, plastic volume %+.3f %%, CPU %.2f of "
                 "the uniform run's.\n\n",
            100 * ed, 100 * ev, g.ok && u.ok ? g.cpu / u.cpu : NAN);
    vf_check(ctx, "plastic_graded_dent", "graded against uniform layers: |residual dent "
             "difference| (rough sphere, p_H ~ 1.5 GPa)", "within 1 % (issue 20 item 4)",
             GRADED_TOL, g.converged && u.converged ? fabs(ed) : NAN, GRADED_TOL, VF_MAX);
    vf_check(ctx, "plastic_graded_volume", "graded against uniform layers: |plastic volume "
             "difference| (rough sphere, p_H ~ 1.5 GPa)", "within 1 % (issue 20 item 4)",
             GRADED_TOL, g.converged && u.converged ? fabs(ev) : NAN, GRADED_TOL, VF_MAX);
    vf_info(ctx, "plastic_graded_cpu_fraction", "graded against uniform layers: CPU fraction", "",
            NAN, g.ok && u.ok ? g.cpu / u.cpu : NAN);
    vf_regress(ctx, "plastic_graded_cpu_fraction", VF_TIER_NONE);
}

/* ---- the skips ------------------------------------------------------------------------------- */

static void section_skips(vf_ctx *ctx, int quick)
{
    const ke_crit kc = ke_critical();
    const int n = quick ? 10 : 12;
    const double side = 24 * kc.ac / 2.7;
    vf_text(ctx, "### What the stage's skips save (KE sphere, %d² grid, whole runs)\n\n"
                 "| skip | with (s) | without (s) | saved | volume with / without |\n"
                 "|---|---|---|---|---|\n",
            n);
    /* the column window: at 2 P_c on a domain twice as wide (2n cells of the same size) the
     * contact's box plus its margin covers a part of the grid */
    ke_run w0, w1;
    memset(&w0, 0, sizeof w0);
    memset(&w1, 0, sizeof w1);
    w0.side = w1.side = 2 * side;
    w0.cuboid = w1.cuboid = 1; /* (the default spectral kernel's volume is the whole grid) */
    ke_solve(2 * n, 2.0, &w0);
    w1.margin = 2 * side; /* the window grows to the whole grid */
    ke_solve(2 * n, 2.0, &w1);
    vf_text(ctx, "| column window (kernel = cuboid; 2 P_c, %d² grid of the same cells on a domain "
                 "twice as wide: "
                 "plastic cells under the contact's box plus a margin, against every column) | "
                 "%.2f | %.2f | %.0f %% | %d x %d x %d / %d x %d x %d |\n",
            2 * n, w0.t, w1.t, 100 * (1 - w0.t / w1.t), w0.wnx, w0.wny, w0.nz, w1.wnx, w1.wny,
            w1.nz);
    /* depth = auto against twice the depth it chose */
    ke_run d0, d1;
    memset(&d0, 0, sizeof d0);
    memset(&d1, 0, sizeof d1);
    ke_solve(n, 5.0, &d0);
    d1.depth = 2 * d0.nz * d0.dz;
    ke_solve(n, 5.0, &d1);
    vf_text(ctx, "| depth = auto (5 P_c; against twice the depth auto chose) | %.2f | %.2f | "
                 "%.0f %% | %d x %d x %d / %d x %d x %d |\n",
            d0.t, d1.t, 100 * (1 - d0.t / d1.t), d0.wnx, d0.wny, d0.nz, d1.wnx, d1.wny, d1.nz);
    /* the elastic shortcut: at 0.5 P_c nothing yields; without the shortcut the loop would run
     * every load step for nothing. Its cost is measured on the same scene with the yield stress
     * set just below the elastic von Mises maximum, so the loop runs and (almost) nothing
     * yields. */
    ke_run e0, e1;
    memset(&e0, 0, sizeof e0);
    memset(&e1, 0, sizeof e1);
    ke_solve(n, 0.5, &e0);
    e1.yield = 0.999 * e0.vm_max;
    if (e0.ok && e1.yield > 0)
        ke_solve(n, 0.5, &e1);
    vf_text(ctx, "| elastic shortcut (0.5 P_c, shortcut %s; without: the same scene with Y = "
                 "0.999 of the elastic von Mises maximum, the loop runs %d outer iterations) | "
                 "%.3f | %.3f | %.0f %% | - / %d x %d x %d |\n\n",
            e0.shortcut ? "taken" : "NOT taken", e1.outer, e0.t, e1.t, 100 * (1 - e0.t / e1.t),
            e1.wnx, e1.wny, e1.nz);
    vf_info(ctx, "skip_window_saving", "column window: time saved at 2 P_c (fraction)", "", 0,
            1 - w0.t / w1.t);
    vf_info(ctx, "skip_depth_saving", "depth auto: time saved against twice the depth (fraction)",
            "", 0, 1 - d0.t / d1.t);
    vf_info(ctx, "skip_shortcut_saving", "elastic shortcut: time saved (fraction)", "", 0,
            1 - e0.t / e1.t);
}

/* ---- the peak memory of a whole run --------------------------------------------------------- */

/* Peak resident memory (bytes, getrusage ru_maxrss of the child through wait4) of a fresh
 * `microcontact run` (this executable, one thread) of `ini` with up to 8 --set overrides;
 * -1 on failure (exit 1, not converged with results, counts as run). */
static double child_peak(const char *self, const char *ini, const char *out, int nset,
                         const char *const *set)
{
    const char *argv[32];
    int a = 0;
    argv[a++] = self;
    argv[a++] = "run";
    argv[a++] = ini;
    argv[a++] = "--out";
    argv[a++] = out;
    argv[a++] = "--quiet";
    for (int k = 0; k < nset && k < 8; k++) {
        argv[a++] = "--set";
        argv[a++] = set[k];
    }
    argv[a] = NULL;
    const pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        const int fd = open("/dev/null", O_WRONLY);
        if (fd >= 0) {
            dup2(fd, 1);
            dup2(fd, 2);
        }
        setenv("OMP_NUM_THREADS", "1", 1);
        execv(self, (char *const *)argv);
        _exit(127);
    }
    int status = 0;
    struct rusage ru;
    if (wait4(pid, &status, 0, &ru) != pid || !WIFEXITED(status) || WEXITSTATUS(status) > 1)
        return -1; /* exit 1: not converged, with results */
    return 1024.0 * (double)ru.ru_maxrss; /* Linux: kilobytes */
}

/* The case file of an elastic-plastic sphere whose plastic volume is n x n x 32 cells under the
 * whole grid (dz = 0.5 um on dx = 1 um, depth 16 um), free (per 0), a strip periodic along y (1)
 * or doubly periodic (2). One load step, one outer iteration of at most 5 sweeps: every array of
 * the loop and the operators is allocated and written by then (the run ends not converged, exit
 * 1, by design). 0, or -1 when the file cannot be written. */
static int whole_run_case(const char *ini, int n, int per, int spectral)
{
    FILE *f = fopen(ini, "w");
    if (!f)
        return -1;
    fprintf(f, "[mesh]\nnx = %d\nny = %d\ndx = 1 um\nperiodic_x = %s\nperiodic_y = %s\n"
               "[geometry]\nshape = sphere\nradius = 2 mm\n[body2]\nrigid = yes\n"
               "[load]\nforce = 0.5 N\n[plasticity]\nhardening = perfect\n"
               "yield_stress = 450 MPa\nload_steps = 1\ndz = 0.5 um\ndepth = 16 um\n%s"
               "max_outer = 1\nmax_plastic = 5\n%s",
            n, n, per == 2 ? "yes" : "no", per >= 1 ? "yes" : "no",
            per == 2 || spectral ? "" : "margin = 1 mm\n",
            spectral ? "kernel = spectral\n" : "kernel = cuboid\n");
    fclose(f);
    return 0;
}

/* The memory model's parts for the volume of whole_run_case (window = grid, 32 uniform layers),
 * bytes: [0..4] the stress operator's (mc_eigen_stress_estimate), [5] the displacement
 * operator, [6] the loop's dense arrays (mc_plastic_loop_bytes without yielding cells), [7] the
 * memory guard's whole estimate (mc_memory_estimate + mc_memory_estimate_plastic). */
static void whole_run_model(const char *ini, int spectral, double m[8])
{
    for (int k = 0; k < 8; k++)
        m[k] = NAN;
    mc_scene sc;
    mc_error err = {0};
    if (mc_case_load(ini, 0, NULL, &sc, &err) != MC_OK)
        return;
    const mc_grid *g = &sc.grid;
    const mc_eigen_volume v = {0,    0,    g->nx, g->ny, 32, 0.5e-6, MC_EIG_CELL_AVERAGE, NULL,
                               spectral ? MC_EIG_KERNEL_SPECTRAL : MC_EIG_KERNEL_CUBOID};
    size_t parts[MC_EIGEN_STRESS_PARTS];
    mc_eigen_stress_estimate(g, &v, sc.solver.backend, parts);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        m[k] = (double)parts[k];
    if (spectral) /* the loads' plan (mc_eigen_stress_loads, the pressure) in part 3 */
        m[3] = (double)mc_eigen_stress_loads_estimate(g, &v, sc.solver.backend, 0, MC_TRACTION_P);
    m[5] = (double)mc_eigen_disp_estimate(g, &v, sc.solver.backend);
    m[6] = mc_plastic_loop_bytes(g, &v, 4, sc.plasticity.near_field, 0, 0);
    m[7] = mc_memory_estimate(&sc) + mc_memory_estimate_plastic(&sc, g, &v, 0);
}

static const char *const WHOLE_NAME[] = {"free", "strip (periodic y)", "doubly periodic"};
static const char *const WHOLE_KEY[] = {"free", "strip", "doubly"};

/* This executable's path into self (1024 bytes) and a fresh directory from the template dir; 0 when
 * either fails. */
static int whole_run_dir(char *dir, char *self)
{
    const ssize_t len = readlink("/proc/self/exe", self, 1023);
    if (len <= 0 || !mkdtemp(dir))
        return 0;
    self[len] = '\0';
    return 1;
}

/* One whole run of whole_run_case(n, per, spectral) in dir: its peak (*rss, bytes; -1 when it
 * failed), wall time (*t, s) and memory model (m, as whole_run_model). */
static void whole_run_measure(const char *self, const char *dir, int n, int per, int spectral,
                              double *rss, double *t, double m[8])
{
    char ini[512], out[512];
    snprintf(ini, sizeof ini, "%s/%s%d_%d.ini", dir, spectral ? "spec" : "peak", n, per);
    snprintf(out, sizeof out, "%s/out%s%d_%d", dir, spectral ? "s" : "", n, per);
    *rss = -1;
    *t = NAN;
    for (int k = 0; k < 8; k++)
        m[k] = NAN;
    if (whole_run_case(ini, n, per, spectral) != 0)
        return;
    const double t0 = mc_clock();
    *rss = child_peak(self, ini, out, 0, NULL);
    *t = mc_clock() - t0;
    whole_run_model(ini, spectral, m);
}

static void section_whole_peak(vf_ctx *ctx, int quick)
{
    char dir[] = "/tmp/mc_bench_peak_XXXXXX", self[1024];
    if (!whole_run_dir(dir, self))
        return;
    const char *const *name = WHOLE_NAME, *const *key = WHOLE_KEY;
    const int n = quick ? 128 : 256, nper = quick ? 1 : 3;
    vf_text(ctx, "\n### Peak memory of a whole run with kernel = cuboid (opt-in)\n\n"
                 "Peak resident memory (getrusage ru_maxrss of a child `microcontact run`, one "
                 "thread) of an elastic-plastic sphere, [plasticity] kernel = cuboid (the default "
                 "spectral kernel's rows follow in the next section), whose plastic volume is %d² "
                 "x 32 cells under "
                 "the whole grid (one load step, one outer iteration: every array of the loop and "
                 "the operators allocated and written), divided by the volume cells; the program "
                 "itself (code, libraries, FFTW, surface fields) is included. Target of issue 20: "
                 "<= 200 bytes per volume cell at 256² x 32. Beside it, bytes per volume cell of "
                 "the memory model (the sizes the objects take, computed without building them: "
                 "mc_eigen_stress_estimate, mc_eigen_disp_estimate, mc_plastic_loop_bytes; a unit "
                 "test holds them to the built objects): the stress operator's kernel spectra V "
                 "(21 reals per depth and lateral frequency of a quadrant), its 6 nz layer spectra "
                 "E, its p3 and Love spectra, its workspaces; the displacement operator; the "
                 "loop's dense volume arrays (sig_r, d_eps, tot, dp, dp_new, the result's "
                 "eps_p and peq, Anderson's cell map, the near field's index); the rest of the "
                 "peak is the program, the elastic stages, the arrays of the yielding cells and "
                 "the folded loads' tables (theory §8.9: 48 bytes per volume cell for the pressure "
                 "on a free grid). The loop's model leaves out the arrays a fallback to the nested "
                 "iteration makes (sig_e, 48), which a folded joint run never makes. "
                 "Last, the memory guard's estimate of the whole run (pipeline/memguard.h) against "
                 "the measured peak.\n\n"
                 "| volume | peak (MiB) | peak B/cell | V | E | p3 + Love | stress rest | disp | "
                 "loop | rest of the peak | guard's estimate / peak |\n"
                 "|---|---|---|---|---|---|---|---|---|---|---|\n",
            n);
    for (int per = 0; per < nper; per++) {
        double rss, t, m[8];
        whole_run_measure(self, dir, n, per, 0, &rss, &t, m);
        const double cells = (double)n * n * 32, bpc = rss > 0 ? rss / cells : NAN;
        const double model = m[0] + m[1] + m[2] + m[3] + m[4] + m[5] + m[6];
        vf_text(ctx, "| %s %d² x 32 | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | "
                     "%.2f |\n",
                name[per], n, rss / 1048576.0, bpc, m[0] / cells, m[1] / cells,
                (m[2] + m[3]) / cells, m[4] / cells, m[5] / cells, m[6] / cells,
                (rss - model) / cells, m[7] / rss);
        char id[64], q[160];
        snprintf(id, sizeof id, "plastic_run_peak_bytes_%s", key[per]);
        snprintf(q, sizeof q, "peak bytes per volume cell of a whole elastic-plastic run, "
                 "kernel = cuboid, %s %d² x 32 (child ru_maxrss)", name[per], n);
        vf_info(ctx, id, q, "issue 20 target <= 200 at 256² x 32 (for the default)", 200, bpc);
        vf_regress(ctx, id, VF_TIER_NONE);
        snprintf(id, sizeof id, "plastic_guard_ratio_%s", key[per]);
        snprintf(q, sizeof q, "memory guard's estimate / measured peak, %s %d² x 32", name[per],
                 n);
        vf_info(ctx, id, q, ">= 1: the guard does not pass what does not fit", 1, m[7] / rss);
    }
    /* the running-in step of issue 20 (the default scene's first force at 350 rpm, 16 layers of
     * 0.1875 um over 3 um) at 512 x 256 */
    char path[1100], out[512];
    snprintf(out, sizeof out, "%s/runin", dir);
    if (!quick && mc_bench_default_case(path, sizeof path) == 0) {
        static const char *const set[] = {"mesh.nx=512",          "mesh.ny=256",
                                          "runin.forces=1086 N",  "runin.speeds=350 rpm",
                                          "lubrication.rpm=350 rpm", "plasticity.dz=0.1875 um",
                                          "plasticity.depth=3 um"};
        const double rss = child_peak(self, path, out, 7, set);
        const double cells = 512.0 * 256 * 16;
        /* the memory guard's estimate of it (pipeline/memguard.h: mc_memory_check_runin) */
        double guard = NAN;
        mc_scene sc;
        mc_error err = {0};
        if (mc_case_load(path, 7, set, &sc, &err) == MC_OK) {
            mc_eigen_volume v = mc_eigen_volume_full(&sc.grid, 16, 0.1875e-6);
            v.stress_points = sc.plasticity.stress_points;
            v.kernel = sc.plasticity.kernel;
            guard = mc_memory_estimate(&sc) + mc_memory_estimate_runin(&sc, &sc.grid, &v);
        }
        vf_text(ctx, "\nThe running-in of the default scene's first force at 350 rpm (down and up, "
                     "16 layers of 0.1875 um over 3 um under the whole grid) on 512 x 256 x 16: "
                     "peak %.0f MiB, %.0f bytes per cell of 512 x 256 x 16 (its state, eps_p, peq "
                     "and sig_r, and the yield check's elastic stresses are lent to the loop in "
                     "place); the memory guard's estimate / peak %.2f.\n",
                rss / 1048576.0, rss / cells, guard / rss);
        vf_info(ctx, "runin_peak_bytes_512", "peak bytes per volume cell of the running-in on "
                "512 x 256 x 16 (child ru_maxrss)", "(issue 20's 200 is the whole run's, above; "
                "the running-in carries its state and Anderson's history)", 200, rss / cells);
        vf_regress(ctx, "runin_peak_bytes_512", VF_TIER_NONE);
        vf_info(ctx, "runin_guard_ratio_512", "memory guard's estimate / measured peak, "
                "running-in on 512 x 256 x 16", ">= 1: the guard does not pass what does not fit",
                1, guard / rss);
    }
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        vf_text(ctx, "(could not remove %s)\n", dir);
}

/* ---- the spectral kernel (theory.md §8.10; issue 20 item 2) -------------------------------- */

static double median_of(double *t, int n)
{
    for (int i = 1; i < n; i++) /* (a handful of values) */
        for (int j = i; j > 0 && t[j] < t[j - 1]; j--) {
            const double x = t[j];
            t[j] = t[j - 1];
            t[j - 1] = x;
        }
    return t[n / 2];
}

static void section_spectral(vf_ctx *ctx, int quick)
{
    static const int on[] = {64, 128, 256}, onz[] = {8, 16, 32};
    const int nop = quick ? 2 : 3;
    vf_text(ctx, "\n### The spectral kernel (the default [plasticity] kernel, theory §8.10)\n\n"
                 "The default lateral discretisation: the plastic strain a sampled trigonometric "
                 "field, the half-space kernel evaluated per lateral Fourier mode when used, the "
                 "layers streamed in two passes (no kernel spectra, no layer spectra kept). One "
                 "application (ONE thread, median of repeated calls) of the stress operator (its "
                 "surface displacement comes with it) and of the displacement operator alone, on "
                 "the volumes of the table above, and their bytes per volume cell (the objects' "
                 "own count). The cuboid rows above for comparison.\n\n"
                 "| volume | grid | stress apply (s) | B / cell | displacement apply (s) | B / cell | "
                 "create (s) |\n|---|---|---|---|---|---|---|\n");
    mc_threads_scope scope;
    mc_threads_begin(1, &scope);
    for (int k = 0; k < nop + (quick ? 0 : 2); k++) {
        const int big = k >= nop, n = big ? on[nop - 1] : on[k], nz = big ? onz[nop - 1] : onz[k];
        const int per = big ? k - nop + 1 : 0;
        mc_grid g = {n, n, 1e-6, 1e-6, per == 2, per >= 1};
        mc_eigen_volume v = mc_eigen_volume_full(&g, nz, 0.5e-6);
        v.kernel = MC_EIG_KERNEL_SPECTRAL;
        const size_t nv = (size_t)n * n * nz;
        double *blk = mc_zeros(12 * nv), *u = mc_zeros((size_t)n * n);
        mc_eigen_stress *os = NULL;
        mc_eigen_disp *od = NULL;
        mc_error err = {0};
        const double t0 = mc_clock();
        if (!blk || !u || mc_eigen_stress_create(&g, &v, 0.3, MC_BACKEND_FFT, &os, &err) ||
            mc_eigen_disp_create(&g, &v, 0.3, MC_BACKEND_FFT, &od, &err)) {
            vf_text(ctx, "| %d² x %d | could not create the operators (memory?) |\n", n, nz);
            mc_eigen_stress_destroy(&os);
            mc_eigen_disp_destroy(&od);
            mc_free(blk), mc_free(u);
            continue;
        }
        const double create = mc_clock() - t0;
        const double *e[6];
        double *sg[6];
        for (int c = 0; c < 6; c++) {
            e[c] = blk + c * nv;
            sg[c] = blk + (6 + c) * nv;
            for (size_t i = 0; i < nv; i++)
                blk[c * nv + i] = 1e-3 * sin(0.001 * (double)i + c);
        }
        const int reps = n <= 128 ? 5 : 3;
        double ts[8], td[8];
        for (int r = 0; r < reps; r++) {
            double c0 = mc_bench_cpu();
            mc_eigen_stress_apply(os, e, 80e9, sg);
            ts[r] = mc_bench_cpu() - c0;
            c0 = mc_bench_cpu();
            mc_eigen_disp_apply(od, e, u);
            td[r] = mc_bench_cpu() - c0;
        }
        const double ms = median_of(ts, reps), md = median_of(td, reps);
        const double bs = (double)mc_eigen_stress_bytes(os) / nv, bd = (double)mc_eigen_disp_bytes(od) / nv;
        static const char *const gname[] = {"free", "strip", "doubly periodic"};
        vf_text(ctx, "| %d² x %d | %s | %.3f | %.0f | %.3f | %.0f | %.3f |\n", n, nz, gname[per], ms,
                bs, md, bd, create);
        if (n == on[nop - 1]) {
            char id[64], q[160];
            snprintf(id, sizeof id, "spectral_bytes_%s", per == 0 ? "free" : per == 1 ? "strip" : "doubly");
            snprintf(q, sizeof q, "spectral eigen operators (stress + displacement), bytes per "
                     "volume cell, %s %d² x %d", gname[per], n, nz);
            vf_info(ctx, id, q, "the cuboid operators' rows above", NAN, bs + bd);
            vf_regress(ctx, id, VF_TIER_NONE);
            snprintf(id, sizeof id, "spectral_apply_%s", per == 0 ? "free" : per == 1 ? "strip" : "doubly");
            snprintf(q, sizeof q, "spectral stress apply (with u_z), s, one thread, %s %d² x %d",
                     gname[per], n, nz);
            vf_info(ctx, id, q, "", NAN, ms);
        }
        mc_eigen_stress_destroy(&os);
        mc_eigen_disp_destroy(&od);
        mc_free(blk), mc_free(u);
    }
    mc_threads_end(&scope);
    /* whole runs: the peak of the sphere of section_whole_peak with kernel = spectral */
    char dir[] = "/tmp/mc_bench_spec_XXXXXX", self[1024];
    if (!whole_run_dir(dir, self))
        return;
    const char *const *name = WHOLE_NAME, *const *key = WHOLE_KEY;
    const int n = quick ? 128 : 256, nper = quick ? 1 : 3;
    vf_text(ctx, "\nPeak memory of a whole run with kernel = spectral (the default): the sphere "
                 "of \"Peak memory of a whole run\" above (%d² x 32 under the whole grid, one "
                 "thread, child ru_maxrss), "
                 "its model's parts per volume cell: the stress operator (its mode states and one "
                 "layer's spectra; the loads' plan of the stress module, whose kernel spectra it "
                 "keeps only below 64 MB), the displacement operator (the object alone; in the loop "
                 "it borrows the stress operator's workspaces, theory §9.9: the rest is lower by "
                 "that), the loop's arrays (the sparse increment of theory §9.9: sig_r, eps_p, peq, "
                 "Anderson's map, one layer; the dense arrays of a fallback to the nested "
                 "iteration, which this run does not make, left out).\n\n"
                 "| volume | peak (MiB) | peak B/cell | stress operator | loads' plan | disp | loop "
                 "| rest | wall (s) |\n|---|---|---|---|---|---|---|---|---|\n",
            n);
    for (int per = 0; per < nper; per++) {
        double rss, t, m[8];
        whole_run_measure(self, dir, n, per, 1, &rss, &t, m);
        const double cells = (double)n * n * 32, bpc = rss > 0 ? rss / cells : NAN;
        const double loop = m[6];
        const double model = m[0] + m[1] + m[2] + m[4] + m[5] + loop + m[3];
        vf_text(ctx, "| %s %d² x 32 | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.1f |\n",
                name[per], n, rss / 1048576.0, bpc, (m[0] + m[1] + m[2] + m[4]) / cells,
                m[3] / cells, m[5] / cells, loop / cells, (rss - model) / cells, t);
        char id[64], q[160];
        snprintf(id, sizeof id, "spectral_run_peak_bytes_%s", key[per]);
        snprintf(q, sizeof q, "peak bytes per volume cell of a whole elastic-plastic run, kernel = "
                 "spectral, %s %d² x 32 (child ru_maxrss)", name[per], n);
        if (per == 0 && !quick) /* the target's grid (issue 20 item 2) */
            vf_check(ctx, id, q, "issue 20 target <= 200 at 256² x 32", 200, bpc, 200, VF_MAX);
        else
            vf_info(ctx, id, q, "issue 20 target <= 200 at 256² x 32", 200, bpc);
        vf_regress(ctx, id, VF_TIER_NONE);
    }
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        vf_text(ctx, "(could not remove %s)\n", dir);
    /* the Kogut-Etsion sphere at 8 P_c on 64^2 with the cuboid kernel (opt-in) */
    if (!quick) {
        ke_run r;
        memset(&r, 0, sizeof r);
        r.load_steps = 16;
        r.cuboid = 1;
        ke_solve(64, 8.0, &r);
        vf_text(ctx, "\nThe Kogut-Etsion sphere at 8 P_c in 16 load steps on 64² (the scene of the "
                     "section below) with kernel = cuboid (opt-in; its volume a window of "
                     "columns): w/w_c %.4f (%+.2f %% against the KE fit), A/A_c %.2f (%+.1f %%), volume %d x "
                     "%d x %d, wall %.1f s, CPU %.1f s, %d outer iterations, %d sweeps, %s.\n",
                r.w, 100 * r.err_w, r.a, 100 * r.err_a, r.wnx, r.wny, r.nz, r.t, r.cpu, r.outer,
                r.sweeps, r.converged ? "converged" : "NOT converged");
        vf_info(ctx, "cuboid_ke8_error", "KE sphere at 8 P_c, 64², kernel = cuboid: |w/w_c "
                "error| against the KE fit", "within 3 % (issue 20 item 3, for the default)",
                KE_TOL_W, r.ok && r.converged ? fabs(r.err_w) : NAN);
        vf_info(ctx, "cuboid_ke8_time", "KE sphere at 8 P_c, 64², kernel = cuboid: wall, s",
                "<= 60 s (issue 20 item 3, for the default)", KE_TIME_MAX, r.ok ? r.t : NAN);
    }
    vf_text(ctx, "\n");
}

int mc_bench_plastic(vf_ctx *ctx, int quick)
{
    double ratio256 = NAN, bytes256 = NAN;
    section_operators(ctx, quick, &ratio256, &bytes256);
    const char *at = quick ? "128² x 16 (--quick)" : "256² x 32";
    char q[128];
    snprintf(q, sizeof q, "eigen operators: worse apply / FFT bound at %s", at);
    vf_check(ctx, "plastic_apply_ratio", q, "target <= 3 (issue 11)", OP_RATIO_MAX, ratio256,
             OP_RATIO_MAX, VF_MAX);
    snprintf(q, sizeof q, "eigen operators (stress + displacement): bytes per volume cell at %s",
             at);
    vf_check(ctx, "plastic_bytes_per_cell", q, "target <= 400 (issue 11)", BYTES_MAX, bytes256,
             BYTES_MAX, VF_MAX);
    section_whole_peak(ctx, quick);
    section_spectral(ctx, quick);
    section_ke(ctx, quick);
    section_ke64(ctx, quick);
    section_graded(ctx, quick);
    section_skips(ctx, quick);
    return 0;
}

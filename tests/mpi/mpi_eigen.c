/* mpi_eigen.c - the eigenstrain operators' fft backend distributed over MPI ranks
 * (plastic/eigen_op.h, theory.md §8.4), run under mpirun by tests/cli/mpi.sh with 1, 2 and 3
 * processes.
 *
 * On every grid type the operators accept (free x and y, a window smaller than the grid, the
 * strip: y periodic, doubly periodic with odd periods, the line contact's bars, a graded volume
 * on both depth steps): the residual stress (and its p3) and the residual surface displacement
 * of a random eigenstrain through the distributed operators against the serial fft operators
 * built in the same process (mc_dist_set(MPI_COMM_NULL) around their creation). Rank 0 prints
 * one line per check and, per grid, hashes of the results' bits: the script requires the same
 * hashes for every process count.
 *
 * The plastic loop's split (issue 22; plastic/loop.c sweep_split_join, stress.h
 * mc_stress_field_split): the elastic stress layers of one plan split over the ranks give the
 * bits of mc_stress_field; a whole elastic-plastic run (a sphere that yields over several rows
 * of every rank, the joint iteration (Anderson) and the nested one (plain sweeps), the volume
 * whole and a window) through the
 * distributed operators, contact solve, stress layers and sweeps against the same run built
 * serially in the same process, with hashes of its plastic fields for the script's same-bits
 * test. Closes with "N passed, N failed"; exit 1 on a failure. */
#include <fftw3-mpi.h>
#include <math.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "core/alloc.h"
#include "core/dist.h"
#include "core/threads.h"
#include "contact/contact.h"
#include "kernels/kernel.h"
#include "operator/operator.h"
#include "plastic/eigen_internal.h"
#include "plastic/eigen_op.h"
#include "plastic/hardening.h"
#include "plastic/loop.h"
#include "stress/stress.h"
#include "surface/surface.h"
#include "mpi_check.h"

/* Round-off tier: both sides evaluate the same sums over the same kernel spectra; they differ
 * only in the lateral transforms (one-line plans of operator/dfft.c against padfft-style plans
 * over many lines), each a relative error of a few eps log2 n of the largest value, carried
 * through the depth step's 6 x 6 products (~1e-15 measured). 1e-12, the brief's figure, leaves
 * two orders of magnitude and catches any wrong column, block or row (errors of O(1)). */
#define TOL_ROUNDOFF 1e-12

/* the same value on every rank (0 when so) */
static double same_on_ranks(const double *v, size_t n)
{
    double mine = (double)(hash_bits(v, n) >> 12), lo = mine, hi = mine;
    MPI_Allreduce(MPI_IN_PLACE, &lo, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    MPI_Allreduce(MPI_IN_PLACE, &hi, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return lo == hi ? 0.0 : 1.0;
}

/* sig (6 nv), p3 (window) and uz (grid) through operators built serially or distributed. */
/* bytes of the built operators against the estimates from the sizes (exact, serial as
 * distributed: the memory guard's figures), on every rank (a rank with fewer columns holds no
 * more than rank 0's estimate) */
static double bytes_off(const mc_grid *g, const mc_eigen_volume *v, const mc_eigen_stress *s,
                        const mc_eigen_disp *d)
{
    size_t parts[MC_EIGEN_STRESS_PARTS], est = 0;
    mc_eigen_stress_estimate(g, v, MC_BACKEND_FFT, parts);
    for (int k = 0; k < MC_EIGEN_STRESS_PARTS; k++)
        est += parts[k];
    const size_t sb = mc_eigen_stress_bytes(s), db = mc_eigen_disp_bytes(d);
    const size_t de = mc_eigen_disp_estimate(g, v, MC_BACKEND_FFT);
    double off = rank == 0 ? (sb != est) + (db != de) : (sb > est) + (db > de);
    MPI_Allreduce(MPI_IN_PLACE, &off, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return off;
}

static double bytes_state; /* the last distributed create's bytes_off */

static int apply(const mc_grid *g, const mc_eigen_volume *v, int depth, int distributed,
                 const double *eps, double *sig, double *p3, double *uz)
{
    MPI_Comm saved = mc_dist_comm();
    if (!distributed)
        mc_dist_set(MPI_COMM_NULL);
    mc_eigen_stress *s = NULL;
    mc_eigen_disp *d = NULL;
    mc_error err = {0};
    int rc = mc_eig_stress_create_depth(g, v, 0.3, MC_BACKEND_FFT, depth, &s, &err);
    if (rc == MC_OK)
        rc = mc_eigen_disp_create(g, v, 0.3, MC_BACKEND_FFT, &d, &err);
    if (rc == MC_OK && distributed && depth == MC_EIG_DEPTH_AUTO)
        bytes_state = bytes_off(g, v, s, d);
    if (rc == MC_OK) {
        const size_t nv = (size_t)v->nz * v->ny * v->nx;
        const double *e[6];
        double *o[6];
        for (int c = 0; c < 6; c++) {
            e[c] = eps + c * nv;
            o[c] = sig + c * nv;
        }
        mc_eigen_stress_apply(s, e, 80e9, o);
        mc_eigen_stress_p3(s, p3);
        mc_eigen_disp_apply(d, e, uz);
    } else if (rank == 0) {
        printf("FAIL create: %s\n", err.msg);
    }
    mc_eigen_stress_destroy(&s);
    mc_eigen_disp_destroy(&d);
    mc_dist_set(saved);
    return rc;
}

static void one_case(const char *name, mc_grid g, mc_eigen_volume v, int depth)
{
    const size_t nv = (size_t)v.nz * v.ny * v.nx, nw = (size_t)v.ny * v.nx;
    const size_t ng = mc_grid_cells(&g);
    double *eps = mc_malloc(6 * nv * sizeof *eps);
    double *sd = mc_malloc(6 * nv * sizeof *sd), *ss = mc_malloc(6 * nv * sizeof *ss);
    double *pd = mc_malloc(nw * sizeof *pd), *ps = mc_malloc(nw * sizeof *ps);
    double *ud = mc_malloc(ng * sizeof *ud), *us = mc_malloc(ng * sizeof *us);
    uint64_t r = 987654321; /* the same field on every rank */
    for (size_t i = 0; i < 6 * nv; i++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        eps[i] = 1e-3 * ((double)(r >> 11) / 9007199254740992.0 - 0.3);
    }
    char what[160];
    if (apply(&g, &v, depth, 1, eps, sd, pd, ud) || apply(&g, &v, depth, 0, eps, ss, ps, us)) {
        failed++;
    } else {
        snprintf(what, sizeof what, "%s: residual stress, distributed vs serial fft", name);
        check(what, rel_diff(sd, ss, 6 * nv), TOL_ROUNDOFF);
        snprintf(what, sizeof what, "%s: p3, distributed vs serial fft", name);
        check(what, rel_diff(pd, ps, nw), TOL_ROUNDOFF);
        snprintf(what, sizeof what, "%s: residual u_z, distributed vs serial fft", name);
        check(what, rel_diff(ud, us, ng), TOL_ROUNDOFF);
        if (depth == MC_EIG_DEPTH_AUTO) {
            snprintf(what, sizeof what, "%s: bytes of the distributed operators = estimates", name);
            check(what, bytes_state, 0.0);
        }
        snprintf(what, sizeof what, "%s: the same stress and u_z on every rank", name);
        check(what, same_on_ranks(sd, 6 * nv) + same_on_ranks(ud, ng), 0.0);
        if (rank == 0)
            printf("hash %s %016llx %016llx\n", name, (unsigned long long)hash_bits(sd, 6 * nv),
                   (unsigned long long)hash_bits(ud, ng));
    }
    mc_free(eps);
    mc_free(sd);
    mc_free(ss);
    mc_free(pd);
    mc_free(ps);
    mc_free(ud);
    mc_free(us);
}

/* ---- surface loads folded into the residual stress operator (theory.md §8.9) ------------- */

/* S eps + the stresses of p and q_x, and the loads alone, through one operator built serially or
 * distributed; *bytes_bad (distributed) 1 when the bytes the folding took differ from
 * mc_eigen_stress_loads_estimate on rank 0 or exceed it on another rank. */
static double shared_off; /* the last apply_loaded's shared forward against the plain applies */
static int shared_used;   /* and whether the operators shared it */

static int apply_loaded(const mc_grid *g, const mc_eigen_volume *v, int distributed,
                        const double *eps, const double *p, const double *qx, double *sig,
                        double *alone, double *bytes_bad)
{
    MPI_Comm saved = mc_dist_comm();
    if (!distributed)
        mc_dist_set(MPI_COMM_NULL);
    mc_eigen_stress *s = NULL;
    mc_error err = {0};
    const int loads = MC_TRACTION_P | MC_TRACTION_QX;
    int rc = mc_eigen_stress_create(g, v, 0.3, MC_BACKEND_FFT, &s, &err);
    const size_t b0 = rc == MC_OK ? mc_eigen_stress_bytes(s) : 0;
    if (rc == MC_OK)
        rc = mc_eigen_stress_loads(s, loads, &err);
    if (rc == MC_OK && distributed) {
        const size_t took = mc_eigen_stress_bytes(s) - b0;
        const size_t est = mc_eigen_stress_loads_estimate(g, v, MC_BACKEND_FFT, mc_dist_size(), loads);
        *bytes_bad = rank == 0 ? took != est : took > est;
        MPI_Allreduce(MPI_IN_PLACE, bytes_bad, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    }
    if (rc == MC_OK) {
        const size_t nv = (size_t)v->nz * v->ny * v->nx;
        const double *e[6];
        double *o[6], *a[6];
        for (int c = 0; c < 6; c++) {
            e[c] = eps + c * nv;
            o[c] = sig + c * nv;
            a[c] = alone + c * nv;
        }
        mc_eigen_stress_apply_loaded(s, e, 80e9, p, qx, o);
        mc_eigen_stress_apply_loaded(s, NULL, 80e9, p, qx, a);
        /* the forward shared with the displacement operator: u_z as its own, the stresses the
         * same bits */
        mc_eigen_disp *d = NULL;
        const size_t ng = mc_grid_cells(g);
        double *u1 = mc_malloc(ng * sizeof *u1), *u2 = mc_malloc(ng * sizeof *u2);
        double *s2 = mc_malloc(6 * nv * sizeof *s2);
        if (mc_eigen_disp_create(g, v, 0.3, MC_BACKEND_FFT, &d, &err) == MC_OK && u1 && u2 && s2) {
            double *o2[6];
            for (int c = 0; c < 6; c++)
                o2[c] = s2 + c * nv;
            mc_eigen_disp_apply(d, e, u1);
            mc_eigen_disp_apply_shared(d, s, e, u2);
            mc_eigen_stress_apply_forwarded(s, 80e9, p, qx, o2);
            shared_off = fmax(rel_diff(u2, u1, ng), memcmp(s2, sig, 6 * nv * sizeof *s2) != 0);
            shared_used = mc_eigen_disp_shares(d, s);
            MPI_Allreduce(MPI_IN_PLACE, &shared_off, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        } else {
            shared_off = 1.0;
        }
        mc_eigen_disp_destroy(&d);
        mc_free(u1);
        mc_free(u2);
        mc_free(s2);
    } else if (rank == 0) {
        printf("FAIL create or fold: %s\n", err.msg);
    }
    mc_eigen_stress_destroy(&s);
    mc_dist_set(saved);
    return rc;
}

static void loads_case(const char *name, mc_grid g, mc_eigen_volume v)
{
    const size_t nv = (size_t)v.nz * v.ny * v.nx, ng = mc_grid_cells(&g);
    double *eps = mc_malloc(6 * nv * sizeof *eps), *p = mc_malloc(ng * sizeof *p);
    double *qx = mc_malloc(ng * sizeof *qx);
    double *sd = mc_malloc(6 * nv * sizeof *sd), *ss = mc_malloc(6 * nv * sizeof *ss);
    double *ad = mc_malloc(6 * nv * sizeof *ad), *as = mc_malloc(6 * nv * sizeof *as);
    uint64_t r = 123456789; /* the same fields on every rank */
    for (size_t i = 0; i < 6 * nv + 2 * ng; i++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        const double u = (double)(r >> 11) / 9007199254740992.0;
        if (i < 6 * nv)
            eps[i] = 1e-3 * (u - 0.3);
        else if (i < 6 * nv + ng)
            p[i - 6 * nv] = 1e9 * u;
        else
            qx[i - 6 * nv - ng] = 1e8 * (u - 0.5);
    }
    double bytes_bad = 0.0;
    char what[160];
    /* (the distributed one last: shared_off and shared_used are its) */
    if (apply_loaded(&g, &v, 0, eps, p, qx, ss, as, &bytes_bad) ||
        apply_loaded(&g, &v, 1, eps, p, qx, sd, ad, &bytes_bad)) {
        failed++;
    } else {
        snprintf(what, sizeof what, "%s: S eps + folded loads, distributed vs serial fft", name);
        check(what, rel_diff(sd, ss, 6 * nv), TOL_ROUNDOFF);
        snprintf(what, sizeof what, "%s: folded loads alone, distributed vs serial fft", name);
        check(what, rel_diff(ad, as, 6 * nv), TOL_ROUNDOFF);
        snprintf(what, sizeof what, "%s: shared forward: u_z and the stresses as the plain applies", name);
        check(what, shared_off, TOL_ROUNDOFF);
        snprintf(what, sizeof what, "%s: the displacement operator shares the forward", name);
        check(what, shared_used ? 0.0 : 1.0, 0.0);
        snprintf(what, sizeof what, "%s: bytes of the folded loads = estimate", name);
        check(what, bytes_bad, 0.0);
        snprintf(what, sizeof what, "%s: the same folded stresses on every rank", name);
        check(what, same_on_ranks(sd, 6 * nv) + same_on_ranks(ad, 6 * nv), 0.0);
        if (rank == 0)
            printf("hash %s %016llx %016llx\n", name, (unsigned long long)hash_bits(sd, 6 * nv),
                   (unsigned long long)hash_bits(ad, 6 * nv));
    }
    mc_free(eps);
    mc_free(p);
    mc_free(qx);
    mc_free(sd);
    mc_free(ss);
    mc_free(ad);
    mc_free(as);
}

/* ---- the plastic loop split over the ranks ----------------------------------------------- */

/* The elastic stresses of a random pressure (and friction traction) on a 17 x 13 grid with 7
 * layers, split by layers over the ranks: the same bits as the whole field on one process (each
 * layer is computed by one rank with the same plan and loads; the gather moves bits). */
static void stress_split_case(void)
{
    const mc_grid g = {17, 13, 1e-6, 1.2e-6, 0, 0};
    const int nl = 7;
    const size_t n = mc_grid_cells(&g), nv = n * nl;
    double depths[7], *p = mc_malloc(n * sizeof *p), *q = mc_malloc(n * sizeof *q);
    double *sd = mc_malloc(6 * nv * sizeof *sd), *ss = mc_malloc(6 * nv * sizeof *ss);
    for (int k = 0; k < nl; k++)
        depths[k] = (0.25 + k) * 0.6e-6;
    uint64_t r = 12345;
    for (size_t i = 0; i < n; i++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        p[i] = 1e9 * (double)(r >> 11) / 9007199254740992.0;
        q[i] = -0.2 * p[i];
    }
    const mc_stress_options so = {.kernel = MC_STRESS_PATCH, .nu = 0.3, .nlayers = nl,
                                  .depths = depths, .backend = MC_BACKEND_FFT,
                                  .loads = MC_TRACTION_P | MC_TRACTION_QX};
    mc_stress_plan *plan = NULL;
    mc_error err = {0};
    int rc = mc_stress_create(&g, &so, &plan, &err);
    double *const od[6] = {sd, sd + nv, sd + 2 * nv, sd + 3 * nv, sd + 4 * nv, sd + 5 * nv};
    double *const os[6] = {ss, ss + nv, ss + 2 * nv, ss + 3 * nv, ss + 4 * nv, ss + 5 * nv};
    for (size_t i = 0; i < 6 * nv; i++)
        sd[i] = NAN; /* a layer the gather missed stays NaN and fails the comparison */
    if (rc == MC_OK)
        rc = mc_stress_field_split(plan, p, q, NULL, od, &err);
    if (rc == MC_OK)
        rc = mc_stress_field(plan, p, q, NULL, os, &err);
    if (rc != MC_OK) {
        failed++;
        if (rank == 0)
            printf("FAIL stress split: %s\n", err.msg);
    } else {
        double off = 0;
        for (size_t i = 0; i < 6 * nv; i++)
            off += !(sd[i] == ss[i]);
        /* the same bits: a count of differing values, to be 0 */
        check("elastic stress layers split over the ranks: values differing from the whole "
              "field (count)", off, 0.0);
        check("elastic stress layers split: the same on every rank", same_on_ranks(sd, 6 * nv),
              0.0);
        if (rank == 0)
            printf("hash stress-split %016llx\n", (unsigned long long)hash_bits(sd, 6 * nv));
    }
    mc_stress_destroy(&plan);
    mc_free(p);
    mc_free(q);
    mc_free(sd);
    mc_free(ss);
}

/* Kogut-Etsion's sphere of tests/test_plastic_loop.c (R = 15 mm, E = 210 GPa, nu = 0.3,
 * elastic-perfectly plastic Y = 1 GPa, P_c = 91.96 N) at 4 P_c in two load steps, on 20 x 18
 * cells of 40 um with 6 layers: its plastic zone (a_c ~ 165 um, ~4 cells) spans about 8 rows
 * of y, every rank's rows for P <= 3 (checked below). One run, built and solved with the
 * communicator given (distributed) or none (serial); eps_p (6 nv), peq (nv), u_r and p out. */
static int plastic_run(int distributed, mc_plastic_iteration it, int window, double *eps,
                       double *peq, double *ur, double *p, int *steps)
{
    MPI_Comm saved = mc_dist_comm();
    if (!distributed)
        mc_dist_set(MPI_COMM_NULL);
    const mc_grid g = {.nx = 20, .ny = 18, .dx = 40e-6, .dy = 40e-6};
    const size_t n = mc_grid_cells(&g);
    double *h = mc_zeros(n), *u = mc_zeros(n), *gap = mc_zeros(n);
    mc_shape_spec shape = {.shape = MC_SHAPE_SPHERE, .radius = 15e-3};
    mc_surface_shape(&g, &shape, h);
    /* tilted along y, so that the contact spot lies off the grid's centre by about a cell: two
     * ranks' rows then do not hold mirror images of each other, whose sums (Anderson's dot
     * products in rows mode, plastic/anderson.h) would be equal halves of the whole */
    for (int j = 0; j < g.ny; j++)
        for (int i = 0; i < g.nx; i++)
            h[(size_t)j * g.nx + i] += 2.5e-3 * (j - 0.5 * (g.ny - 1)) * g.dy;
    mc_error err = {0};
    mc_operator *K = NULL;
    mc_contact_solver *s = NULL;
    mc_hardening law;
    int rc = mc_hardening_perfect(1e9, &law, &err);
    const double estar = mc_combined_modulus(210e9, 0.3, 0, 0, 1);
    if (rc == MC_OK)
        rc = mc_operator_plan_love(&g, estar, MC_BACKEND_FFT, &K, &err);
    mc_contact_options o = {.method = MC_METHOD_CG, .tolerance = 1e-10, .max_iterations = 5000};
    if (rc == MC_OK)
        rc = mc_contact_create(K, &o, &s, &err);
    mc_eigen_volume v = mc_eigen_volume_full(&g, 6, 40e-6);
    if (window) /* 14 x 13 columns from (3, 2): the layer-by-layer elastic stresses */
        v = (mc_eigen_volume){3, 2, 14, 13, 6, 40e-6, MC_EIG_CELL_AVERAGE, NULL, MC_EIG_KERNEL_CUBOID};
    const mc_plastic_problem pb = {.h = h, .load = 4 * 91.96, .load_steps = 2, .E = 210e9,
                                   .nu = 0.3, .law = &law, .volume = v,
                                   .backend = MC_BACKEND_FFT, .relaxation = 0.7,
                                   .tol_outer = 1e-3, .max_outer = 30, .tol_plastic = 1e-4,
                                   .max_plastic = 200, .iteration = it,
                                   /* the joint iteration mixes (Anderson, as the scenes'
                                    * default); the nested one here the plain relaxed sweeps */
                                   .anderson = it == MC_PLASTIC_JOINT ? 4 : 0};
    mc_plastic_result res;
    memset(&res, 0, sizeof res);
    mc_contact_summary cs;
    if (rc == MC_OK)
        rc = mc_plastic_run(&g, K, s, &pb, p, u, gap, &cs, &res, &err);
    if (rc == MC_OK) {
        memcpy(eps, res.eps_p, 6 * (size_t)res.nvol * sizeof *eps);
        memcpy(peq, res.peq, (size_t)res.nvol * sizeof *peq);
        memcpy(ur, res.u_r, n * sizeof *ur);
        *steps = 0;
        for (int k = 0; k < res.steps_done; k++)
            *steps += res.steps[k].plastic_iterations;
    } else if (rank == 0) {
        printf("FAIL plastic run (%s): %s\n", distributed ? "distributed" : "serial", err.msg);
    }
    mc_plastic_result_free(&res);
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_hardening_free(&law);
    mc_free(h);
    mc_free(u);
    mc_free(gap);
    mc_dist_set(saved);
    return rc;
}

/* The plastic fields' tier of issue 22: 1e-10. The distributed run differs from the serial one
 * by the round-off of the distributed transforms (operator, eigenstrain operators: 1e-15, the
 * checks above) and the row-wise sums of the contact solve, carried through a fixed point whose
 * iterates stop where their tests (tol_outer 1e-3, tol_plastic 1e-4) are first met: as long as
 * the iteration counts are the same (checked) the difference stays at round-off times the
 * iteration's amplification (measured 2e-15 on the CLI's 24^2 case); 1e-10 is the issue's
 * bound, and a cell whose return map is lost is off by O(1). */
#define TOL_PLASTIC 1e-10

static void plastic_case(const char *name, mc_plastic_iteration it, int window, int size)
{
    const size_t n = 20 * 18, nv = window ? 14 * 13 * 6 : n * 6;
    const int nwy = window ? 13 : 18;
    double *ed = mc_malloc(6 * nv * sizeof *ed), *es = mc_malloc(6 * nv * sizeof *es);
    double *qd = mc_malloc(nv * sizeof *qd), *qs = mc_malloc(nv * sizeof *qs);
    double *ud = mc_malloc(n * sizeof *ud), *us = mc_malloc(n * sizeof *us);
    double *pd = mc_malloc(n * sizeof *pd), *ps = mc_malloc(n * sizeof *ps);
    int nd = 0, ns = 0;
    char what[200];
    if (plastic_run(1, it, window, ed, qd, ud, pd, &nd) ||
        plastic_run(0, it, window, es, qs, us, ps, &ns)) {
        failed++;
    } else {
        snprintf(what, sizeof what, "%s: plastic strain, distributed vs serial", name);
        check(what, rel_diff(ed, es, 6 * nv), TOL_PLASTIC);
        snprintf(what, sizeof what, "%s: equivalent plastic strain, distributed vs serial", name);
        check(what, rel_diff(qd, qs, nv), TOL_PLASTIC);
        snprintf(what, sizeof what, "%s: residual u_z, distributed vs serial", name);
        check(what, rel_diff(ud, us, n), TOL_PLASTIC);
        snprintf(what, sizeof what, "%s: pressure, distributed vs serial", name);
        check(what, rel_diff(pd, ps, n), TOL_PLASTIC);
        snprintf(what, sizeof what, "%s: sweeps %d distributed, %d serial (difference)", name,
                 nd, ns);
        check(what, fabs((double)(nd - ns)), 0.0);
        snprintf(what, sizeof what, "%s: the same plastic fields on every rank", name);
        check(what, same_on_ranks(ed, 6 * nv) + same_on_ranks(qd, nv), 0.0);
        /* the split is exercised: every rank's rows (those of mc_dist_share, as the loop's)
         * hold yielded cells */
        int r0, nr, mine = 0;
        mc_dist_share(nwy, &r0, &nr);
        const size_t nwx = nv / 6 / (size_t)nwy;
        for (int k = 0; k < 6; k++)
            for (int j = r0; j < r0 + nr; j++)
                for (size_t i = 0; i < nwx; i++)
                    mine |= qd[((size_t)k * nwy + j) * nwx + i] > 0;
        int ranks_yielding = mine;
        MPI_Allreduce(MPI_IN_PLACE, &ranks_yielding, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
        snprintf(what, sizeof what, "%s: ranks without yielded cells in their rows (of %d)",
                 name, size);
        check(what, (double)(size - ranks_yielding), 0.0);
        if (rank == 0)
            printf("hash %s %016llx %016llx %016llx\n", name,
                   (unsigned long long)hash_bits(ed, 6 * nv), (unsigned long long)hash_bits(qd, nv),
                   (unsigned long long)hash_bits(ud, n));
    }
    mc_free(ed);
    mc_free(es);
    mc_free(qd);
    mc_free(qs);
    mc_free(ud);
    mc_free(us);
    mc_free(pd);
    mc_free(ps);
}

int main(int argc, char **argv)
{
    int size;
    mc_threads_scope ts;
    if (mpi_test_begin(&argc, &argv, "distributed eigenstrain operators", &ts, &size))
        return 1;
    const double d = 1e-6;
    static const int group[4] = {1, 1, 3, 5};
    const mc_grid free_g = {20, 14, d, 1.3 * d, 0, 0}, big = {26, 18, d, d, 0, 0};
    const mc_grid strip = {18, 12, d, d, 0, 1}, per = {15, 11, d, 1.2 * d, 1, 1};
    const mc_grid line = {30, 1, d, d, 0, 1};
    mc_eigen_volume vf = mc_eigen_volume_full(&free_g, 4, 0.5 * d);
    mc_eigen_volume vw = {5, 3, 13, 9, 3, 0.7 * d, MC_EIG_CELL_AVERAGE, NULL, MC_EIG_KERNEL_CUBOID}; /* a window */
    mc_eigen_volume vs = {3, 0, 11, 12, 3, 0.5 * d, MC_EIG_CELL_CENTRE, NULL, MC_EIG_KERNEL_CUBOID}; /* strip: all y */
    mc_eigen_volume vp = mc_eigen_volume_full(&per, 3, 0.6 * d);
    mc_eigen_volume vl = mc_eigen_volume_full(&line, 5, 0.5 * d);
    mc_eigen_volume vg = mc_eigen_volume_full(&free_g, 4, 0.3 * d);
    vg.group = group;
    one_case("free 20x14x4", free_g, vf, MC_EIG_DEPTH_AUTO);
    const mc_grid small = {12, 10, d, d, 0, 0}; /* 11 layers: batches of 8 and 3 */
    one_case("free 12x10x11", small, mc_eigen_volume_full(&small, 11, 0.4 * d), MC_EIG_DEPTH_AUTO);
    one_case("free 26x18, window 13x9x3 at (5,3)", big, vw, MC_EIG_DEPTH_AUTO);
    one_case("strip 18x12 (periodic y), window 11 at 3, centre", strip, vs, MC_EIG_DEPTH_AUTO);
    one_case("doubly periodic 15x11x3", per, vp, MC_EIG_DEPTH_AUTO);
    one_case("line 30x1 (bars)", line, vl, MC_EIG_DEPTH_AUTO);
    one_case("graded 20x14 (1,1,3,5) fine depth step", free_g, vg, MC_EIG_DEPTH_FINE);
    one_case("graded 20x14 (1,1,3,5) coarse depth step", free_g, vg, MC_EIG_DEPTH_COARSE);
    loads_case("loads: free 20x14x4", free_g, vf);
    loads_case("loads: strip 18x12x3", strip, mc_eigen_volume_full(&strip, 3, 0.5 * d));
    loads_case("loads: doubly periodic 15x11x3", per, vp);
    loads_case("loads: line 30x1", line, vl);
    loads_case("loads: graded 20x14 (1,1,3,5)", free_g, vg);
    stress_split_case();
    plastic_case("plastic sphere 20x18x6, joint", MC_PLASTIC_JOINT, 0, size);
    plastic_case("plastic sphere 20x18x6, nested", MC_PLASTIC_NESTED, 0, size);
    plastic_case("plastic sphere, window 14x13x6 at (3,2), joint", MC_PLASTIC_JOINT, 1, size);
    if (rank == 0)
        printf("%d passed, %d failed\n", passed, failed);
    mc_dist_set(MPI_COMM_NULL);
    fftw_mpi_cleanup();
    MPI_Finalize();
    return failed ? 1 : 0;
}

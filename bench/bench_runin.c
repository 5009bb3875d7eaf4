/* bench_runin.c - the running-in costs (issue 13 item 4): the default running-in scene
 * (cases/default.ini) step by step (time, contact solves per lubricant volume root, outer
 * iterations and plastic sweeps of its elastic-plastic steps, in FFT pairs of its padded grid);
 * the warm start of a volume equilibrium from the previous step's pressure (lube/volume.h
 * p_start) against a cold one; one elastic-plastic step on grids growing towards the issue's
 * 512 x 256 x 16 (extrapolated where it does not fit); the runin suite's committed run time. */
#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h"
#include "case/case.h"
#include "core/alloc.h"
#include "core/threads.h"
#include "operator/operator.h"
#include "pipeline/pipeline.h"
#include "pipeline/runin.h"
#include "pipeline/stage_lube.h"
#include "surface/surface.h"

#define STEP_MAX_S 30.0    /* a running-in step on 512 x 256 x 16 (issue 13 item 4) */
#define SUITE_MAX_S 600.0  /* the three-force runin suite (issue 13 item 4) */
#define GROWTH_MAX 1.2     /* exponent in N of a step's time at fixed nz (issue 20 item 3) */
#define STEP_NZ 16         /* the layers of that step (issue 20 item 3: 512 x 256 x 16) */
/* The largest step tried (predicted). The step time is irregular: before the inexact inner
 * solves (theory §9.4) a 256 x 128 x 16 step predicted at 50 s took 562 s (its first fixed point
 * diverged and the step was split); now 38 s. */
#define TRY_BUDGET_S 30.0

/* The default scene, its steps. */
static void section_default(vf_ctx *ctx, const mc_scene *sc)
{
    mc_results res;
    mc_error err = {0};
    memset(&res, 0, sizeof res);
    const double t0 = mc_clock();
    const int rc = mc_runin_run(sc, NULL, &res, &err);
    const double total = mc_clock() - t0;
    if (rc != MC_OK && rc != MC_NOT_CONVERGED) {
        vf_fail(ctx, "runin_default", "the default running-in scene failed: %s", err.msg);
        mc_results_free(&res);
        return;
    }
    mc_conv *c = NULL;
    int tx = 2 * sc->grid.nx, ty = 2 * sc->grid.ny;
    if (mc_conv_create(&sc->grid, MC_BACKEND_FFT, &c, &err) == MC_OK) {
        mc_conv_table_dims(c, &tx, &ty);
        mc_conv_destroy(&c);
    }
    const double P = mc_bench_pair_time(tx, ty, 31, FFTW_ESTIMATE, NULL);
    const mc_runin_summary *r = &res.runin;
    /* per kind: plastic run-down steps, elastic run-down steps, run-up steps */
    double sec[3] = {0}, solves[3] = {0}, roots[3] = {0};
    int cnt[3] = {0};
    long outer = 0, sweeps = 0;
    int eps = 0;
    for (int s = 0; s < r->done; s++) {
        const mc_runin_row *w = &r->rows[s];
        const int kind = w->up ? 2 : w->plastic ? 0 : 1;
        sec[kind] += w->seconds;
        solves[kind] += w->solves;
        roots[kind] += w->roots;
        cnt[kind]++;
    }
    for (int s = 0; s < res.plastic.steps_done && res.plastic.steps; s++)
        if (res.plastic.steps[s].outer_iterations > 0) {
            outer += res.plastic.steps[s].outer_iterations;
            sweeps += res.plastic.steps[s].plastic_iterations;
            eps++;
        }
    FILE *f = vf_open(ctx, "runin_steps.csv");
    if (f) {
        fprintf(f, "step,force,up,speed_rad_s,plastic,seconds,solves,roots,p_lub\n");
        for (int s = 0; s < r->done; s++) {
            const mc_runin_row *w = &r->rows[s];
            fprintf(f, "%d,%.6g,%d,%.6g,%d,%.6g,%d,%d,%.6g\n", s + 1, w->force, w->up, w->speed,
                    w->plastic, w->seconds, w->solves, w->roots, w->p_lub);
        }
        vf_close(ctx, f);
    }
    vf_text(ctx,
            "## Running-in costs\n\n### The default running-in scene, step by step\n\n"
            "cases/default.ini as shipped (%d x %d cells of %.1f um, %d forces x %d speeds, "
            "run-down elastic-plastic where something yields, run-up elastic): %d steps in "
            "%.2f s (%d threads). A pair is one bare FFTW r2c + c2r of the padded %d x %d "
            "(%.3f ms, measured here). Per-step figures from runin.csv's rows (solves: contact "
            "solves; roots: lubricant volume equilibria, in the elastic-plastic loop a root or one "
            "secant step of it, theory.md §9.8); the elastic-plastic loop's outer "
            "iterations and plastic sweeps (one residual stress application each, 6 nz pairs "
            "of the padded grid at most) from its step records.\n\n"
            "| steps | count | mean time (s) | mean time (pairs) | contact solves per step | "
            "solves per p_lub root |\n|---|---|---|---|---|---|\n",
            sc->grid.nx, sc->grid.ny, sc->grid.dx * 1e6, sc->runin.nforces, sc->runin.nspeeds,
            r->done, total, mc_threads_count(), tx, ty, 1e3 * P);
    static const char *kname[3] = {"run-down, elastic-plastic (something yielded)",
                                   "run-down, nothing yielded", "run-up (elastic)"};
    for (int k = 0; k < 3; k++)
        if (cnt[k])
            vf_text(ctx, "| %s | %d | %.3f | %.0f | %.1f | %.1f |\n", kname[k], cnt[k],
                    sec[k] / cnt[k], sec[k] / cnt[k] / P, solves[k] / cnt[k],
                    roots[k] > 0 ? solves[k] / roots[k] : NAN);
    vf_text(ctx, "\nElastic-plastic steps: %d, %.1f outer iterations and %.1f plastic sweeps "
                 "per step (each outer iteration one volume equilibrium: a p_lub root, or one secant "
                 "step of it with one contact solve); "
                 "one elastic-plastic step = %.0f FFT pairs of the padded grid in time.\n\n",
            eps, eps ? (double)outer / eps : NAN, eps ? (double)sweeps / eps : NAN,
            cnt[0] ? sec[0] / cnt[0] / P : NAN);
    const double tot_solves = solves[0] + solves[1] + solves[2];
    const double tot_roots = roots[0] + roots[1] + roots[2];
    vf_info(ctx, "runin_default_total_s", "default running-in scene: whole run, s", "", NAN,
            total);
    vf_regress(ctx, "runin_default_total_s", VF_TIER_NONE);
    vf_info(ctx, "runin_solves_per_root", "default scene: contact solves per p_lub root (or secant step)", "",
            NAN, tot_roots > 0 ? tot_solves / tot_roots : NAN);
    vf_regress(ctx, "runin_solves_per_root", VF_TIER_NONE);
    vf_info(ctx, "runin_outer_per_ep_step", "default scene: outer iterations per elastic-plastic "
            "step", "", NAN, eps ? (double)outer / eps : NAN);
    vf_regress(ctx, "runin_outer_per_ep_step", VF_TIER_NONE);
    vf_info(ctx, "runin_ep_step_pairs", "default scene: one elastic-plastic step in FFT pairs "
            "of its padded grid", "", NAN, cnt[0] ? sec[0] / cnt[0] / P : NAN);
    vf_regress(ctx, "runin_ep_step_pairs", VF_TIER_NONE);
    mc_results_free(&res);
}

/* The volume equilibrium at 350 rpm on the default scene's initial surface, cold and warm
 * started from the equilibrium at 500 rpm (the run-down step before). */
static void section_warm(vf_ctx *ctx, const mc_scene *sc0)
{
    mc_scene sc = *sc0;
    const mc_grid *g = &sc.grid;
    const size_t n = mc_grid_cells(g);
    mc_results res;
    memset(&res, 0, sizeof res);
    res.grid = *g;
    mc_error err = {0};
    mc_operator *K = NULL;
    mc_contact_solver *s = NULL;
    double *prev = mc_zeros(n);
    double t[2] = {NAN, NAN};
    int nsolves[2] = {0, 0}, ok = 0;
    double plub[2] = {NAN, NAN};
    if (prev && (res.topography = mc_zeros(n)) && (res.pressure = mc_zeros(n)) &&
        (res.gap = mc_zeros(n)) && (res.displacement = mc_zeros(n)) &&
        mc_surface_topography(g, &sc.geometry, &sc.roughness, res.topography, &err) == MC_OK &&
        mc_operator_plan_love(g, mc_scene_estar(&sc), sc.solver.backend, &K, &err) == MC_OK) {
        mc_contact_options opt = {.method = sc.solver.method,
                                  .tolerance = sc.solver.tolerance,
                                  .max_iterations = sc.solver.max_iterations,
                                  .estar = mc_scene_estar(&sc)};
        if (mc_contact_create(K, &opt, &s, &err) == MC_OK) {
            sc.lubrication.rpm = 500 * 2 * M_PI / 60; /* rad/s */
            int rc = mc_stage_lube(&sc, K, s, NULL, NULL, &res, &err);
            ok = rc == MC_OK;
            memcpy(prev, res.pressure, n * sizeof *prev);
            sc.lubrication.rpm = 350 * 2 * M_PI / 60;
            for (int w = 0; w < 2 && ok; w++) {
                const double t0 = mc_clock();
                rc = mc_stage_lube(&sc, K, s, NULL, w ? prev : NULL, &res, &err);
                t[w] = mc_clock() - t0;
                nsolves[w] = res.lube.solves;
                plub[w] = res.lube.p_lub;
                ok = rc == MC_OK;
            }
        }
    }
    vf_text(ctx, "### Warm start of the volume equilibrium\n\n");
    if (!ok) {
        vf_text(ctx, "Could not run: %s\n\n", err.msg);
    } else {
        vf_text(ctx,
                "The running-in driver starts every step's equilibrium cold (pipeline/runin.c: "
                "steps are a deterministic function of the carried state, for checkpoints); it "
                "has no switch for a warm start, so the saving is measured beside it with the "
                "public stage call (mc_stage_lube, p_start): the default scene's first force on "
                "its initial surface (without the nominal-deflection bowl the driver removes), "
                "the equilibrium at 350 rpm cold and warm-started from the one at 500 rpm.\n\n"
                "| start | contact solves | time (s) | p_lub (MPa) |\n|---|---|---|---|\n"
                "| cold | %d | %.3f | %.3f |\n| warm (500 rpm pressure) | %d | %.3f | %.3f |\n\n",
                nsolves[0], t[0], plub[0] * 1e-6, nsolves[1], t[1], plub[1] * 1e-6);
        vf_info(ctx, "runin_warm_saving", "volume equilibrium: time saved by the warm start "
                "(fraction of the cold time)", "", NAN, 1 - t[1] / t[0]);
        vf_regress(ctx, "runin_warm_saving", VF_TIER_NONE);
    }
    mc_contact_destroy(&s);
    mc_operator_destroy(&K);
    mc_results_free(&res);
    mc_free(prev);
}

/* Least-squares exponent of log y on log x over m points (NAN for fewer than 2). */
static double fit_exp(const double *x, const double *y, int m)
{
    if (m < 2)
        return NAN;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < m; k++) {
        const double a = log(x[k]), b = log(y[k]);
        sx += a, sy += b, sxx += a * a, sxy += a * b;
    }
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

/* One elastic-plastic step (350 rpm) on 2:1 grids of the default cells with 16 layers, growing
 * while the predicted time fits; extrapolated to 512 x 256 x 16 when that does not fit. With its
 * counts (issue 20 items 3 and 7): where the work of a step grows with N. */
static void section_big(vf_ctx *ctx, int quick)
{
    static const int nxs[] = {64, 96, 128, 192, 256, 384, 512};
    enum { NB = 7 };
    double N[NB], t[NB], cpu[NB];
    mc_bench_step st[NB];
    int nxr[NB], m = 0; /* the sizes run, in order, and their cells Nr */
    double Nr[NB];
    for (int k = 0; k < NB; k++)
        N[k] = (double)nxs[k] * nxs[k] / 2;
    /* 16 layers of 0.1875 um down to 3 um (default.ini's depth is 6.4 um: 35 layers); the
     * layer count each run really had is read back from its results and checked */
    const char *dz = "plasticity.dz=0.1875um plasticity.depth=3um";
    double spent = 0;
    for (int k = 0; k < NB; k++) {
        if (m >= 2) { /* predicted from the CPU time: the wall time of a shared machine swings */
            const double grow = log(cpu[m - 1] / cpu[m - 2]) / log(N[m - 1] / N[m - 2]);
            const double pred = cpu[m - 1] * pow(N[k] / N[m - 1], fmax(grow, 1.0));
            if (pred > (quick ? 10 : TRY_BUDGET_S) || spent + pred > (quick ? 20 : 120))
                break;
        }
        const double c0 = mc_bench_cpu();
        const int rc = mc_bench_runin_step_counts(nxs[k], nxs[k] / 2, "350 rpm", dz, 0, &st[k]);
        spent += mc_bench_cpu() - c0;
        t[k] = st[k].wall_s;
        cpu[k] = st[k].cpu_s;
        if (rc != 0 || !(t[k] > 0) || !st[k].plastic) /* a step where nothing yields is not the
                                                          cost asked */
            break;
        if (st[k].nz != STEP_NZ) {
            vf_fail(ctx, "runin_step_nz", "the step on %d x %d has %d layers, not %d", nxs[k],
                    nxs[k] / 2, st[k].nz, STEP_NZ);
            break;
        }
        nxr[m] = nxs[k];
        Nr[m] = N[k];
        m++;
    }
    /* the scene always (not in the quick bench): 512 x 256 x 16, measured, not
     * extrapolated; the sizes between it and the ladder's last are skipped when they do not fit */
    if (!quick && m >= 1 && nxr[m - 1] != nxs[NB - 1]) {
        const int k = m;
        const int rc = mc_bench_runin_step_counts(nxs[NB - 1], nxs[NB - 1] / 2, "350 rpm", dz, 0,
                                                  &st[k]);
        t[k] = st[k].wall_s;
        cpu[k] = st[k].cpu_s;
        if (rc == 0 && t[k] > 0 && st[k].plastic && st[k].nz == STEP_NZ) {
            nxr[m] = nxs[NB - 1];
            Nr[m] = N[NB - 1];
            m++;
        }
    }
    vf_text(ctx, "### One elastic-plastic step against the grid\n\n"
                 "The default scene's first force at 350 rpm (mixed lubrication, the asperities "
                 "yield) on nx x nx/2 cells of 0.8 um with 16 layers (dz = 0.1875 um down to a "
                 "depth of 3 um, both set here: default.ini's 6.4 um would give 35 layers; the "
                 "layer count is read back from each run's results): the wall time of the run-down step (%d threads), the "
                 "process CPU time (all threads) from the start of the run to the end of that step "
                 "(set-up, the operators' creation and the initial volume equilibrium included: "
                 "the measure that does not depend on what else the machine runs), and the "
                 "counts of the elastic-plastic loop (one load step): outer iterations (each one "
                 "volume equilibrium, one elastic stress field and one residual displacement), "
                 "plastic sweeps (global sweeps of the whole volume), residual stress applications "
                 "(the costly global operator: one per sweep, fewer with the local-global fixed "
                 "point of theory §9.7, which iterates with the near field between them), its "
                 "near-field sweeps, volume equilibria and contact solves of the step (with the first, "
                 "before the loop). Each size runs while its CPU time predicted from the two "
                 "before (at least linear in N) fits %.0f s and the step yields; 512 x 256 x 16, "
                 "the scene of issue 20, always runs (the sizes between skipped if they do not "
                 "fit).\n\n"
                 "| grid | wall (s) | CPU (s) | outer | sweeps | global applies | near-field "
                 "sweeps | equilibria | contact solves | CPU / sweeps (ms) |\n"
                 "|---|---|---|---|---|---|---|---|---|---|\n",
            mc_threads_count(), quick ? 10.0 : TRY_BUDGET_S);
    FILE *f = vf_open(ctx, "runin_step_counts.csv");
    if (f)
        fprintf(f, "nx,ny,nz,cells,wall_s,cpu_s,outer,sweeps,stress_applies,local_sweeps,"
                   "equilibria,solves\n");
    for (int k = 0; k < m; k++) {
        vf_text(ctx, "| %d x %d x %d | %.2f | %.2f | %d | %d | %d | %d | %d | %d | %.1f |\n",
                nxr[k], nxr[k] / 2, st[k].nz, t[k], cpu[k], st[k].outer, st[k].sweeps, st[k].applies,
                st[k].local_sweeps, st[k].equilibria, st[k].solves,
                st[k].sweeps > 0 ? 1e3 * cpu[k] / st[k].sweeps : NAN);
        if (f)
            fprintf(f, "%d,%d,%d,%.0f,%.6g,%.6g,%d,%d,%d,%d,%d,%d\n", nxr[k], nxr[k] / 2,
                    st[k].nz, Nr[k] * st[k].nz, t[k], cpu[k], st[k].outer, st[k].sweeps, st[k].applies,
                    st[k].local_sweeps, st[k].equilibria, st[k].solves);
    }
    if (f)
        vf_close(ctx, f);
    const double e_wall = fit_exp(Nr, t, m), e_cpu = fit_exp(Nr, cpu, m);
    double sweeps[NB], outer[NB], applies[NB];
    for (int k = 0; k < m; k++)
        sweeps[k] = fmax(st[k].sweeps, 1), outer[k] = fmax(st[k].outer, 1),
        applies[k] = fmax(st[k].applies, 1);
    const double e_sweeps = fit_exp(Nr, sweeps, m), e_outer = fit_exp(Nr, outer, m);
    const double e_applies = fit_exp(Nr, applies, m);
    vf_text(ctx, "\nFitted exponents in N over the %d sizes (least squares of the logarithms): "
                 "wall %.2f, CPU %.2f; outer iterations %.2f, sweeps %.2f, global applications "
                 "%.2f (the rest of the CPU exponent is the cost of one sweep: FFTs of N log N "
                 "and the operators' creation).\n",
            m, e_wall, e_cpu, e_outer, e_sweeps, e_applies);
    double at512 = NAN;
    const char *how = "measured";
    if (m >= 1 && nxr[m - 1] == nxs[NB - 1]) {
        at512 = t[m - 1];
    } else if (m >= 2) {
        at512 = t[m - 1] * pow(N[NB - 1] / Nr[m - 1], e_wall);
        how = "EXTRAPOLATED";
        vf_text(ctx, "\n512 x 256 x 16 did not fit: EXTRAPOLATED from the largest grid run with "
                     "the least-squares exponent of all sizes (%.2f in N): %.0f s.\n",
                e_wall, at512);
    }
    vf_text(ctx, "\n");
    char q[200];
    snprintf(q, sizeof q, "one running-in (elastic-plastic) step on 512 x 256 x 16, s (%s)", how);
    vf_check(ctx, "runin_step_512x256x16", q, "target <= 30 s (issue 13)", STEP_MAX_S, at512,
             STEP_MAX_S, VF_MAX);
    vf_regress(ctx, "runin_step_512x256x16", VF_TIER_NONE);
    if (!quick) { /* the same step with the opt-in cuboid discretisation (theory §8.10) */
        mc_bench_step sp;
        char extra[160];
        snprintf(extra, sizeof extra, "%s plasticity.kernel=cuboid", dz);
        const int rc = mc_bench_runin_step_counts(nxs[NB - 1], nxs[NB - 1] / 2, "350 rpm", extra,
                                                  0, &sp);
        const int okk = rc == 0 && sp.plastic && sp.nz == STEP_NZ;
        vf_text(ctx, "The same step on 512 x 256 x 16 with [plasticity] kernel = cuboid (opt-in; "
                     "the default is spectral, issue 20 item 2): wall %.2f s, CPU %.2f s, "
                     "%d outer iterations (joint evaluations), %d stress applications.\n\n",
                okk ? sp.wall_s : NAN, okk ? sp.cpu_s : NAN, okk ? sp.outer : 0,
                okk ? sp.applies : 0);
        vf_info(ctx, "runin_step_512_cuboid", "one running-in step on 512 x 256 x 16 with kernel "
                "= cuboid, wall s", "target <= 30 s for the default (issue 20 item 3)",
                STEP_MAX_S, okk ? sp.wall_s : NAN);
        vf_regress(ctx, "runin_step_512_cuboid", VF_TIER_NONE);
    }
    /* The work's growth: the same ladder on ONE thread. At the default thread count the small
     * grids run on one thread (below MC_THREADS_MIN_CELLS values a team costs more than it
     * saves) and the large ones on two, whose CPU time adds what two threads lose to each other
     * (the mode arithmetic is memory bound: 1.7 CPU seconds per wall second at 512 x 256); so the
     * default run's CPU exponent mixes two machines, its wall exponent too (the other way). One
     * thread at every size measures the growth of the work alone (theory §9.8). */
    double t1[NB];
    int m1 = 0;
    for (int k = 0; k < m; k++) {
        mc_bench_step s1;
        if (mc_bench_runin_step_counts(nxr[k], nxr[k] / 2, "350 rpm", dz, 1, &s1) != 0 ||
            !s1.plastic || !(s1.wall_s > 0))
            break;
        t1[m1++] = s1.wall_s;
    }
    const double e_one = m1 == m ? fit_exp(Nr, t1, m) : NAN;
    vf_text(ctx, "One thread at every size (the work's growth), step wall time, s:");
    for (int k = 0; k < m1; k++)
        vf_text(ctx, " %d x %d %.2f%s", nxr[k], nxr[k] / 2, t1[k], k + 1 < m1 ? ";" : "");
    vf_text(ctx, ". Fitted exponent %.3f (default threads: wall %.2f, CPU %.2f).\n\n", e_one,
            e_wall, e_cpu);
    vf_check(ctx, "runin_step_exponent_one_thread", "one running-in step on one thread: fitted "
             "exponent of its time in N at 16 layers, 64 x 32 .. 512 x 256",
             "target <= 1.2 (issue 20 item 3)", GROWTH_MAX, e_one, GROWTH_MAX, VF_MAX);
    vf_regress(ctx, "runin_step_exponent_one_thread", VF_TIER_NONE);
    vf_info(ctx, "runin_step_exponent_cpu", "one running-in step at the default threads: fitted "
            "exponent of its CPU time in N at 16 layers", "(one thread on the small grids, two on "
            "the large: the row above measures the work)", GROWTH_MAX, e_cpu);
    vf_regress(ctx, "runin_step_exponent_cpu", VF_TIER_NONE);
    vf_info(ctx, "runin_step_exponent_wall", "one running-in step at the default threads: fitted "
            "exponent of its wall time in N at 16 layers", "", NAN, e_wall);
    vf_regress(ctx, "runin_step_exponent_wall", VF_TIER_NONE);
    vf_info(ctx, "runin_step_exponent_sweeps", "one running-in step: fitted exponent of its "
            "plastic sweeps in N", "", NAN, e_sweeps);
    vf_regress(ctx, "runin_step_exponent_sweeps", VF_TIER_NONE);
    vf_info(ctx, "runin_step_exponent_applies", "one running-in step: fitted exponent of its "
            "global residual stress applications in N (issue 20 item 3: not to grow)", "", NAN,
            e_applies);
    vf_regress(ctx, "runin_step_exponent_applies", VF_TIER_NONE);
}

int mc_bench_runin(vf_ctx *ctx, int quick)
{
    char path[1100];
    mc_scene sc;
    mc_error err = {0};
    if (mc_bench_default_case(path, sizeof path) || mc_case_load(path, 0, NULL, &sc, &err)) {
        vf_fail(ctx, "runin_case", "cannot read cases/default.ini: %s", err.msg);
        return 0;
    }
    section_default(ctx, &sc);
    section_warm(ctx, &sc);
    section_big(ctx, quick);
    /* the suite's run time from its committed report ("Run time X s."), beside cases/ */
    double suite_s = NAN;
    char rep[1200];
    char *slash = strstr(path, "cases/default.ini");
    if (slash) {
        *slash = '\0';
        snprintf(rep, sizeof rep, "%sreports/runin/report.md", path);
        FILE *f = fopen(rep, "r");
        char line[1024];
        while (f && fgets(line, sizeof line, f) && isnan(suite_s)) {
            const char *p = strstr(line, "Run time ");
            if (p)
                suite_s = strtod(p + 9, NULL);
        }
        if (f)
            fclose(f);
    }
    vf_text(ctx, "The three-force `runin` verification suite: %.1f s (read from "
                 "reports/runin/report.md as committed, not re-run here).\n\n",
            suite_s);
    vf_check(ctx, "runin_suite_time", "the three-force runin verification suite, s (read from "
             "reports/runin/report.md, not measured in this run)", "target <= 10 minutes "
             "(issue 13)", SUITE_MAX_S, suite_s, SUITE_MAX_S, VF_MAX);
    vf_regress(ctx, "runin_suite_time", VF_TIER_NONE);
    return 0;
}

/* bench_mpi.c - the MPI executable (README "Running on a cluster", issue 22 item 4): strong
 * scaling 1 -> 2 processes of the elastic contact of the Hertz case at 1024^2 (512^2 quick), one
 * thread per process, beside the serial program on one thread; whole runs as child processes
 * (`mpirun ... bin/microcontact-mpi run`), wall time fork to exit, the CPU seconds of all the
 * run's processes (getrusage of the waited-for children), the run's own summary.json timings and
 * the communication seconds it prints ("MPI: ... spent X s communicating"). Then the flank model:
 * the time and memory of the paper's 10 mm x 1 mm gear flank at 0.8 um on N machines of this
 * size, from the measured per-cell cost, the all-to-all volume of FFTW-MPI's transposes and a
 * stated network. Beside it the elastic-plastic running-in step of the default scene on
 * 256 x 128 x 16 (plastic_step): the same runs, its eigenstrain operators, elastic stress layers
 * and the sweeps' return maps distributed, the MPI results checked against the serial one. */
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bench.h"
#include "case/scene.h"
#include "core/fftsize.h"
#include "core/threads.h"
#include "pipeline/memguard.h"
#include "pipeline/pipeline.h"

#define TARGET_SPEEDUP 1.6 /* issue 22 item 4: 1 -> 2 ranks */
#define ROUNDS 3          /* runs of the 1- and 2-process rows (interleaved; 1 quick) */

/* The number after key in the text file path (first occurrence), NAN if absent. */
static double number_after(const char *path, const char *key)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return NAN;
    char line[1024];
    double v = NAN;
    while (isnan(v) && fgets(line, sizeof line, f)) {
        const char *p = strstr(line, key);
        if (p)
            v = strtod(p + strlen(key), NULL);
    }
    fclose(f);
    return v;
}

/* The two numbers after key in "KEY X s, Y s of it in communication" of a run's log (the MPI
 * executable's last line, the last such line if several): "contact stage CPU " gives the
 * contact stage's CPU seconds of rank 0 and those in communication, "its CPU " rank 0's CPU of
 * the whole run (mc_dist_cpu_seconds, mc_dist_comm_cpu_seconds); NAN if absent. */
static void cpu_pair(const char *path, const char *key, double *cpu, double *comm)
{
    *cpu = *comm = NAN;
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    char line[1024];
    while (fgets(line, sizeof line, f)) {
        const char *p = strstr(line, key);
        if (!p)
            continue;
        char *end;
        *cpu = strtod(p + strlen(key), &end);
        const char *q = strstr(end, "s, ");
        if (q)
            *comm = strtod(q + 3, NULL);
    }
    fclose(f);
}

typedef struct {
    const char *name;
    int ranks; /* 0: the serial program */
    double wall, total, contact, comm, mib, cpu;
    double ccpu, ccomm; /* the contact stage's CPU on rank 0, and of it in communication */
    int iterations, ok;
    int fftw; /* 1: MC_TRANSPOSES=fftw, FFTW-MPI's transposes instead of the shared ones */
} mpi_run;

/* CPU seconds (user + system) of the terminated, waited-for children so far. */
static double children_cpu(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_CHILDREN, &ru) != 0)
        return NAN;
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
           (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

/* ---- the flank model ------------------------------------------------------------------------
 * The paper's gear flank: 10 mm x 1 mm at 0.8 um cells (12500 x 1250 = 15.6 million cells),
 * 16 stress layers. Assumptions, each stated in the output:
 *  - a machine is this one (2 cores, its RAM), 2 ranks per machine (one thread each);
 *  - the contact solve takes FLANK_ITERATIONS cg iterations (rough contacts took 22-27 at
 *    512^2-1024^2, contact_cg.c), FLANK_APPLIES operator applications each (K d, plus K q after a
 *    clipped step);
 *  - per cell and iteration it costs what the measured one-process run cost per cell and
 *    iteration (coarse levels included), times the ratio of log2 of the padded transform sizes
 *    (FFT work ~ n log n);
 *  - a share FLANK_REPLICATED of that work is replicated on every rank (the problem's O(N)
 *    passes, the coarse start's restriction; the preconditioner's transform is distributed since
 *    issue 22's second round): Amdahl's serial part, from the measured work speed-up s of 1 -> 2
 *    processes (f = 2/s - 1: 1.8-1.9x gave 0.05-0.11);
 *  - network: NET_BYTES_S per machine and direction (10 Gbit/s Ethernet), NET_LATENCY_S per
 *    message; per operator application two transposes of 16 ny (tx/2 + 1) bytes, of which each
 *    machine sends and receives (N - 1)/N^2; per iteration the preconditioner's transform over
 *    the contact's box (at most the grid): the box's rows to the transform's and back (2 x 8
 *    bytes a cell) and its two transposes (2 x 16 bytes a cell of half spectrum, about 16 a
 *    cell), (N - 1)/N^2 of them per machine; inside a
 *    machine the ranks share memory (its cost is in the measured per-cell figure);
 *  - the set-up scales with the padded cells and divides over the ranks (the kernel table by
 *    slabs, operator.c) but for a share FLANK_REPLICATED;
 *  - memory: the memory guard's model (pipeline/memguard.c) for P ranks, twice per machine: a
 *    replicated part plus the operators' slabs and the solvers' work arrays over P (the shape
 *    measured by memory_per_rank). */
#define FLANK_NX 12500
#define FLANK_NY 1250
#define FLANK_DX 0.8e-6
#define FLANK_LAYERS 16
#define FLANK_ITERATIONS 30
#define FLANK_APPLIES 1.2
#define FLANK_REPLICATED 0.10
#define NET_BYTES_S 1.25e9
#define NET_LATENCY_S 50e-6
#define RANKS_PER_MACHINE 2

static void flank_model(vf_ctx *ctx, const mpi_run *one, int N)
{
    const double n = (double)FLANK_NX * FLANK_NY, nb = (double)N * N;
    const double tx = mc_fftsize_good(2 * FLANK_NX - 1), ty = mc_fftsize_good(2 * FLANK_NY - 1);
    const double tb = (double)mc_fftsize_good(2 * N - 1) * mc_fftsize_good(2 * N - 1);
    const double per_cell_it = one->contact / (one->iterations * nb);
    const double c = per_cell_it * log2(tx * ty) / log2(tb); /* s per cell and iteration */
    const double setup1 = (one->total - one->contact) * (tx * ty) / tb;
    const double vt = 16.0 * FLANK_NY * (tx / 2 + 1); /* bytes of one transpose, all ranks */
    const double ram = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
    const double GiB = 1073741824.0;
    mc_scene sc;
    memset(&sc, 0, sizeof sc);
    sc.grid = (mc_grid){FLANK_NX, FLANK_NY, FLANK_DX, FLANK_DX, 0, 0};
    sc.roughness.type = sc.roughness2.type = MC_ROUGH_NONE;
    sc.load.kind = MC_LOAD_FORCE;
    sc.solver.backend = MC_BACKEND_FFT;
    sc.solver.method = MC_METHOD_CG;
    vf_text(ctx,
            "### The flank model\n\n"
            "The paper's gear flank, 10 mm x 1 mm at 0.8 um cells: %d x %d = %.1f million cells "
            "(padded transforms %.0f x %.0f), %d stress layers, on N machines of this size (%d "
            "cores, %.1f GiB), %d ranks per machine. Measured: %.3g us per cell and cg iteration "
            "(the 1-process run above: contact time / (iterations x cells), coarse levels "
            "included, under today's load), scaled by log2 of the padded sizes to %.3g us; the "
            "set-up %.3g s scaled by the padded cells to %.3g s on one rank (the kernel table "
            "by slabs: it divides but for the replicated share). "
            "Assumed: %d iterations (rough contacts took 22-27 at 512²-1024²), %.1f operator "
            "applications each, %.0f %% of the work replicated on every rank (the problem's O(N) "
            "passes, the coarse start's restriction: f = 2/s - 1 from the measured work speed-up "
            "s of 1 -> 2 processes, 1.8-1.9x; the preconditioner's transform is distributed), a "
            "network of %.2g GB/s per "
            "machine and direction (10 Gbit/s Ethernet) and %.0f us per message. Per operator "
            "application two transposes of 16 ny (tx/2 + 1) = %.0f MB, of which each "
            "machine sends and receives (N - 1)/N²; per iteration the preconditioner's transform "
            "over the contact's box (at most the grid): its rows to the transform's and back and "
            "its two transposes (about 32 bytes a cell, %.0f MB), of which each machine sends and "
            "receives (N - 1)/N². Memory: the memory guard's model "
            "(pipeline/memguard.c) for P ranks, per machine: per rank a replicated part (the "
            "surface fields, the coarse start's whole arrays, the corner lattice of the kernel "
            "table while it is built) plus the operators' slabs, the preconditioner's and the "
            "contact solvers' work arrays divided by P - the shape measured above (R + S/P), the "
            "guard's figures erring high.\n\n"
            "| machines | ranks | compute / iteration (s) | network / iteration (s) | contact "
            "solve (s) | set-up (s) | memory / machine, elastic (GiB) | with %d stress layers "
            "(GiB) | fits |\n|---|---|---|---|---|---|---|---|---|\n",
            FLANK_NX, FLANK_NY, n / 1e6, tx, ty, FLANK_LAYERS, RANKS_PER_MACHINE, ram / GiB,
            RANKS_PER_MACHINE, 1e6 * per_cell_it, 1e6 * c, one->total - one->contact, setup1,
            FLANK_ITERATIONS, FLANK_APPLIES, 100 * FLANK_REPLICATED, NET_BYTES_S / 1e9,
            1e6 * NET_LATENCY_S, vt / 1e6, 32 * n / 1e6, FLANK_LAYERS);
    FILE *f = vf_open(ctx, "mpi_flank.csv");
    if (f)
        fprintf(f, "machines,ranks,compute_it_s,network_it_s,contact_s,setup_s,elastic_gib,"
                   "stress_gib\n");
    for (int m = 1; m <= 64; m *= 2) {
        const int P = RANKS_PER_MACHINE * m;
        const double comp = c * n * ((1 - FLANK_REPLICATED) / P + FLANK_REPLICATED);
        const double net = m == 1 ? 0.0
                                  : (FLANK_APPLIES * 2 * vt * (m - 1) / ((double)m * m) +
                                     32 * n * (m - 1) / ((double)m * m)) / NET_BYTES_S +
                                        (FLANK_APPLIES * 2 + 10) * (P - 1) * NET_LATENCY_S;
        const double contact = FLANK_ITERATIONS * (comp + net);
        const double setup = setup1 * ((1 - FLANK_REPLICATED) / P + FLANK_REPLICATED);
        sc.stress.enabled = 0;
        const double el = RANKS_PER_MACHINE * mc_memory_estimate_ranks(&sc, P);
        sc.stress.enabled = 1;
        sc.stress.layers = FLANK_LAYERS;
        sc.stress.spacing = MC_SPACING_LINEAR;
        const double st = RANKS_PER_MACHINE * mc_memory_estimate_ranks(&sc, P);
        vf_text(ctx, "| %d | %d | %.2f | %.3f | %.0f | %.0f | %.1f | %.1f | %s |\n", m, P, comp,
                net, contact, setup, el / GiB, st / GiB,
                st <= ram ? "yes" : (el <= ram ? "elastic only" : "no"));
        if (f)
            fprintf(f, "%d,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", m, P, comp, net, contact, setup,
                    el / GiB, st / GiB);
    }
    if (f)
        vf_close(ctx, f);
    vf_text(ctx,
            "\nRead: the elastic flank fits on one machine; its contact solve gains over "
            "machines until the replicated share (the O(N) passes; the preconditioner's transform "
            "and the kernel table are distributed) of 1/%.0f of the work bounds it (Amdahl: at "
            "most %.0fx); the network is a small part at 10 Gbit/s. The %d stress layers do not divide: every rank "
            "keeps every layer (9 fields of 8 bytes a cell each, %.1f GiB a rank), so the "
            "stresses need them kept on the rank that computed them (not done) before the flank "
            "with stresses fits any number of these machines.\n\n",
            1 / FLANK_REPLICATED, 1 / FLANK_REPLICATED, FLANK_LAYERS,
            9.0 * 8 * n * FLANK_LAYERS / GiB);
}

/* One run of the Hertz case ini into out, its stderr and stdout to log: the serial program self
 * (ranks 0) or mpirun -np ranks of the MPI program mpi, one thread per process; waiting ranks yield
 * their core (the machine is shared, README). Wall seconds as mc_bench_run_child_to. */
static double run_hertz(const char *self, const char *mpi, const char *ini, const char *out,
                        const char *log, int ranks)
{
    char np[16];
    snprintf(np, sizeof np, "%d", ranks);
    const char *serial[] = {self, "run", ini, "--out", out, "--quiet",
                            "--set", "solver.threads=1", NULL};
    const char *par[] = {"mpirun", "--allow-run-as-root", "--oversubscribe",
                         "--mca", "mpi_yield_when_idle", "1", "-np", np,
                         mpi, "run", ini, "--out", out, "--quiet",
                         "--set", "solver.threads=1", NULL};
    return mc_bench_run_child_to(ranks ? par : serial, log);
}

/* ---- memory per rank -------------------------------------------------------------------------
 * The peak resident memory (VmHWM) of rank 0 (it holds the most rows: FFTW-MPI's blocks are
 * ceil(ny/P)) of the Hertz case at 1024^2 and 2048^2 (512^2 and 1024^2 quick), P = 1, 2, 3, one
 * run each, beside the serial program; and the fit peak = R + S/P through P = 2 and 3 (R: what
 * every rank holds whole, S: what divides). */
static void memory_per_rank(vf_ctx *ctx, const char *self, const char *mpi, int quick)
{
    char dir[] = "/tmp/mc_bench_mpimem_XXXXXX";
    if (!mkdtemp(dir))
        return;
    vf_text(ctx,
            "### Memory per rank\n\n"
            "Peak resident memory (VmHWM) of rank 0 - the rank with the most rows - of the Hertz "
            "case (one run each, one thread per process), and the fit peak = R + S / P through "
            "P = 2 and 3: R is held whole by every rank (the surface fields of the pipeline, the "
            "coarse start's whole arrays, the kernel table's corner lattice while it is built, "
            "the process), S divides (the operators' spectra and transform buffers, the kernel "
            "table's rows while they are transformed and the kernel spectrum, the "
            "preconditioner's transform over the contact's box, the contact solvers' work "
            "arrays: each rank its slab of rows).\n\n"
            "| grid | serial (MiB) | P = 1 | P = 2 | P = 3 | R (MiB) | S (MiB) | R + S (MiB) | "
            "R per cell (bytes) | S per cell (bytes) |\n|---|---|---|---|---|---|---|---|---|---|\n");
    FILE *f = vf_open(ctx, "mpi_memory.csv");
    if (f)
        fprintf(f, "n,serial_mib,p1_mib,p2_mib,p3_mib,replicated_mib,sliced_mib\n");
    for (int N = quick ? 512 : 1024; N <= (quick ? 1024 : 2048); N *= 2) {
        char ini[200];
        snprintf(ini, sizeof ini, "%s/hertz%d.ini", dir, N);
        if (mc_bench_hertz_case(ini, N))
            break;
        double mib[4] = {NAN, NAN, NAN, NAN};
        for (int P = 0; P <= 3; P++) {
            char out[300], log[300];
            snprintf(out, sizeof out, "%s/out%d_%d", dir, N, P);
            snprintf(log, sizeof log, "%s/log%d_%d", dir, N, P);
            if (run_hertz(self, mpi, ini, out, log, P) > 0)
                mib[P] = number_after(log, "peak memory ");
            mc_bench_remove_tree(out);
        }
        const double S = 6 * (mib[2] - mib[3]), R = mib[2] - S / 2, cells = (double)N * N;
        vf_text(ctx, "| %d² | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f | %.0f |\n", N,
                mib[0], mib[1], mib[2], mib[3], R, S, R + S, R * 1048576 / cells,
                S * 1048576 / cells);
        if (f)
            fprintf(f, "%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", N, mib[0], mib[1], mib[2], mib[3], R,
                    S);
        char id[64];
        snprintf(id, sizeof id, "mpi_memory_p2_over_p1_%d", N);
        vf_info(ctx, id, "peak memory per rank, 2 processes / 1", "", NAN, mib[2] / mib[1]);
        vf_regress(ctx, id, VF_TIER_NONE);
    }
    if (f)
        vf_close(ctx, f);
    vf_text(ctx, "\n");
    mc_bench_remove_tree(dir);
}

/* ---- the elastic-plastic step ------------------------------------------------------------------
 * The running-in step of the default scene on 256 x 128 x 16 (one force, one speed: one
 * elastic-plastic run-down step and one elastic run-up step), serial and P = 1, 2, 3. The
 * eigenstrain operators are distributed (theory §8.4: their lateral transforms are mc_dfft
 * batches, each rank its columns' spectra), so are the elastic stresses (each rank its block of
 * layers) and the sweeps' return maps (each rank its rows of y in every layer, the increments
 * gathered whole); the plastic loop's volume arrays, its whole-volume passes and Anderson's
 * mixing stay replicated on every rank. That is [plasticity] kernel = cuboid, set here: the
 * default spectral kernel's operators are replicated on every rank (the same bits, no speed-up
 * of their work; docs/architecture.md "MPI"). */
static const char *const plastic_sets[] = {
    "mesh.nx=256",          "mesh.ny=128",           "runin.forces=1086N",
    "runin.speeds=350rpm",  "lubrication.rpm=350rpm", "plasticity.dz=0.1875um",
    "plasticity.depth=3um", "solver.threads=1",      "plasticity.kernel=cuboid"};
#define NSETS ((int)(sizeof plastic_sets / sizeof plastic_sets[0]))

/* The value in column name of the first data row of the CSV file path, NAN if absent. */
static double csv_first_row(const char *path, const char *name)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return NAN;
    char head[2048], row[4096];
    double v = NAN;
    if (fgets(head, sizeof head, f) && fgets(row, sizeof row, f)) {
        head[strcspn(head, "\r\n")] = '\0';
        int col = -1, k = 0;
        for (char *s = head, *tok; (tok = strsep(&s, ",")); k++)
            if (!strcmp(tok, name))
                col = k;
        k = 0;
        for (char *s = row, *tok; col >= 0 && (tok = strsep(&s, ",")); k++)
            if (k == col)
                v = strtod(tok, NULL);
    }
    fclose(f);
    return v;
}

static double run_plastic(const char *self, const char *mpi, const char *ini, const char *out,
                          const char *log, int ranks)
{
    char np[16];
    snprintf(np, sizeof np, "%d", ranks);
    const char *argv[48];
    int n = 0;
    if (ranks) {
        const char *pre[] = {"mpirun", "--allow-run-as-root", "--oversubscribe", "--mca",
                             "mpi_yield_when_idle", "1", "-np", np, mpi};
        for (size_t k = 0; k < sizeof pre / sizeof pre[0]; k++)
            argv[n++] = pre[k];
    } else
        argv[n++] = self;
    argv[n++] = "run";
    argv[n++] = ini;
    argv[n++] = "--out";
    argv[n++] = out;
    argv[n++] = "--quiet";
    for (int k = 0; k < NSETS; k++) {
        argv[n++] = "--set";
        argv[n++] = plastic_sets[k];
    }
    argv[n] = NULL;
    return mc_bench_run_child_to(argv, log);
}

typedef struct {
    const char *name;
    int ranks, rounds;
    double wall, cpu, r0cpu, r0comm, mib, step_s;
    int outer, sweeps, solves, ok;
    double fig[3]; /* summary.json: peq_max, plastic_volume, residual_max */
} plastic_run;

static const char *const plastic_figs[3] = {"peq_max", "plastic_volume", "residual_max"};

static void plastic_step(vf_ctx *ctx, const char *self, const char *mpi, int quick)
{
    char ini[1024], dir[] = "/tmp/mc_bench_mpipl_XXXXXX";
    vf_text(ctx, "### The elastic-plastic step\n\n");
    if (mc_bench_default_case(ini, sizeof ini) || !mkdtemp(dir)) {
        vf_fail(ctx, "mpi_plastic_case", "cannot read cases/default.ini");
        return;
    }
    /* ROUNDS rounds (1 quick), each running every row once in turn; P = 3 once: the whole
     * row set within about 2 minutes. Per row the run with the least step time is kept. */
    const int rounds = quick ? 1 : ROUNDS;
    plastic_run runs[] = {
        {.name = "bin/microcontact, 1 thread", .ranks = 0, .rounds = rounds},
        {.name = "bin/microcontact-mpi, 1 process", .ranks = 1, .rounds = rounds},
        {.name = "bin/microcontact-mpi, 2 processes", .ranks = 2, .rounds = rounds},
        {.name = "bin/microcontact-mpi, 3 processes", .ranks = 3, .rounds = 1}};
    const int nruns = (int)(sizeof runs / sizeof runs[0]);
    for (int k = 0; k < nruns; k++)
        runs[k].step_s = INFINITY;
    for (int round = 0; round < rounds; round++)
    for (int k = 0; k < nruns; k++) {
        plastic_run *r = &runs[k];
        if (round >= r->rounds || (round > 0 && !r->ok))
            continue;
        {
            char out[300], log[300], js[400], pl[400], ri[400];
            snprintf(out, sizeof out, "%s/out%d_%d", dir, k, round);
            snprintf(log, sizeof log, "%s/log%d_%d", dir, k, round);
            const double cpu0 = children_cpu();
            const double t = run_plastic(self, mpi, ini, out, log, r->ranks);
            const double cpu = children_cpu() - cpu0;
            if (!(t > 0)) {
                char id[64];
                snprintf(id, sizeof id, "mpi_plastic_run_p%d", r->ranks);
                vf_fail(ctx, id, "%s: the run of %s failed", r->name, ini);
                r->ok = 0;
                mc_bench_remove_tree(out);
                continue;
            }
            snprintf(ri, sizeof ri, "%s/runin.csv", out);
            const double step = csv_first_row(ri, "seconds");
            if (step < r->step_s) {
                snprintf(js, sizeof js, "%s/summary.json", out);
                snprintf(pl, sizeof pl, "%s/plastic.csv", out);
                r->wall = t;
                r->cpu = cpu;
                if (r->ranks)
                    cpu_pair(log, "its CPU ", &r->r0cpu, &r->r0comm);
                else /* the serial program: its CPU is the run's, none in communication */
                    r->r0cpu = cpu, r->r0comm = 0.0;
                r->mib = number_after(log, "peak memory ");
                r->step_s = step;
                r->solves = (int)csv_first_row(ri, "contact_solves");
                r->outer = (int)csv_first_row(pl, "outer_iterations");
                r->sweeps = (int)csv_first_row(pl, "plastic_iterations");
                for (int q = 0; q < 3; q++)
                    r->fig[q] = mc_bench_json_number(js, plastic_figs[q]);
                r->ok = 1;
            }
            mc_bench_remove_tree(out);
        }
    }
    mc_bench_remove_tree(dir);

    vf_text(ctx,
            "The running-in step of the default scene on 256 x 128 cells x 16 layers: "
            "cases/default.ini with `--set` mesh.nx=256, mesh.ny=128, runin.forces=1086N, "
            "runin.speeds=350rpm, lubrication.rpm=350rpm, plasticity.dz=0.1875um, "
            "plasticity.depth=3um, solver.threads=1 (one force, one speed: the elastic-plastic "
            "run-down step, then the elastic run-up step), run as the Hertz rows above: the "
            "serial program and `mpirun ... -np P bin/microcontact-mpi run`, %d round%s, each "
            "running every row once in turn (P = 3 in the first only), and per row the run with "
            "the least step time (runin.csv seconds of the elastic-plastic row: the step the "
            "target is about, without the process's start, set-up, elastic steps and output): its "
            "wall time, fork to exit, its CPU seconds (all its "
            "processes, mpirun included), rank 0's CPU seconds and those of it in communication "
            "(mc_dist_cpu_seconds and mc_dist_comm_cpu_seconds at the end of the run, printed "
            "by the MPI executable; the running-in does not record the wall seconds of "
            "communication, so its share is of rank 0's CPU), rank 0's peak memory, the step's "
            "seconds and contact solves (runin.csv, the elastic-plastic row) and its outer "
            "iterations and plastic sweeps (plastic.csv). Distributed (docs/theory.md §8.4): "
            "the contact solves, the eigenstrain operators (their lateral transforms are "
            "mc_dfft batches, each rank keeps its columns' spectra; the elastic stresses of the "
            "pressure are folded into the residual stress operator, §8.9) and the joint "
            "iteration's volume work: each rank keeps to its rows of y in every layer (the sums "
            "eps_p + increment, the residual stresses, the return maps and Anderson's mixing, its "
            "dot products summed row by row over the ranks), the increment gathered whole once "
            "per load increment; replicated on every rank: the volume arrays, the passes once "
            "per increment (warm start, commit, the result's residual stress), Love's tables of "
            "the operators, which bound the speed-up. The host's speed varies from one minute "
            "to the next: rank 0's CPU outside communication is the steadier figure.\n\n"
            "| run | wall (s) | CPU, all processes (s) | rank 0 CPU (s) | of it communication "
            "(s) | communication / rank 0 CPU | rank 0 CPU outside communication (s) | peak "
            "MiB | step (s) | contact solves | outer iterations | plastic sweeps |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|\n",
            rounds, rounds > 1 ? "s" : "");
    FILE *f = vf_open(ctx, "mpi_plastic.csv");
    if (f)
        fprintf(f, "run,processes,wall_s,cpu_s,rank0_cpu_s,rank0_comm_cpu_s,peak_mib,step_s,"
                   "contact_solves,outer_iterations,plastic_sweeps,peq_max,plastic_volume,"
                   "residual_max\n");
    for (int k = 0; k < nruns; k++) {
        const plastic_run *r = &runs[k];
        if (!r->ok)
            continue;
        vf_text(ctx,
                "| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f | %.2f | %d | %d | %d |\n",
                r->name, r->wall, r->cpu, r->r0cpu, r->r0comm, r->r0comm / r->r0cpu,
                r->r0cpu - r->r0comm, r->mib, r->step_s, r->solves, r->outer, r->sweeps);
        if (f)
            fprintf(f, "%s,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%d,%d,%.17g,%.17g,%.17g\n",
                    r->name, r->ranks, r->wall, r->cpu, r->r0cpu, r->r0comm, r->mib, r->step_s,
                    r->solves, r->outer, r->sweeps, r->fig[0], r->fig[1], r->fig[2]);
    }
    if (f)
        vf_close(ctx, f);

    /* The same answer: issue 22 item 2 asks <= 1e-10 relative in the plastic fields of P ranks
     * against the serial run (the distributed transforms sum in another order; the split
     * per-cell work is the serial code's, cell by cell). A bench row that measured a wrong answer would be
     * worthless, so the agreement is checked before any speed-up is read. */
    if (runs[0].ok) {
        for (int k = 1; k < nruns; k++) {
            const plastic_run *r = &runs[k];
            if (!r->ok)
                continue;
            double worst = 0.0;
            for (int q = 0; q < 3; q++)
                worst = vf_worst(worst, fabs(r->fig[q] - runs[0].fig[q]) / fabs(runs[0].fig[q]));
            if (r->outer != runs[0].outer || r->sweeps != runs[0].sweeps)
                worst = vf_worst(worst, INFINITY); /* another iteration path: not the same run */
            char id[64], quant[160];
            snprintf(id, sizeof id, "mpi_plastic_agreement_p%d", r->ranks);
            snprintf(quant, sizeof quant,
                     "elastic-plastic step, %d process%s: worst relative difference of "
                     "summary.json peq_max, plastic_volume, residual_max from the serial run "
                     "(the same counts)",
                     r->ranks, r->ranks > 1 ? "es" : "");
            vf_check(ctx, id, quant, "serial bin/microcontact, issue 22: <= 1e-10", 0.0, worst,
                     1e-10, VF_MAX);
            vf_regress(ctx, id, VF_TIER_NONE);
        }
    }
    if (runs[1].ok && runs[2].ok) {
        const double s = runs[1].step_s / runs[2].step_s, sw = runs[1].wall / runs[2].wall;
        const double w1 = runs[1].r0cpu - runs[1].r0comm, w2 = runs[2].r0cpu - runs[2].r0comm;
        vf_text(ctx,
                "\nElastic-plastic step, 1 -> 2 processes: %.2fx in the step's time (target "
                "%.1fx: %s), %.2fx in the whole process's wall time; "
                "rank 0's CPU outside communication %.2f s -> %.2f s, %.2fx; communication "
                "%.0f %% of rank 0's CPU with two processes (%.0f %% with one: the local "
                "transposes). The replicated volume passes of the plastic loop do not divide: "
                "read by Amdahl's law, the work speed-up s gives f = 2/s - 1 = %.2f of rank 0's "
                "work done whole on every rank, which bounds the speed-up at 1/f = %.1fx on any "
                "number of ranks; and on this 2-core machine, shared with other jobs, a second "
                "process competes with them for the cores.\n\n",
                s, TARGET_SPEEDUP, s >= TARGET_SPEEDUP ? "met" : "not met on this machine", sw,
                w1, w2, w1 / w2, 100 * runs[2].r0comm / runs[2].r0cpu,
                100 * runs[1].r0comm / runs[1].r0cpu, 2 * w2 / w1 - 1, 1 / (2 * w2 / w1 - 1));
        /* the target, checked as the step time ratio 2 processes / 1 <= 1 / 1.6 (as
         * the contact's, the stage's own time) */
        vf_check(ctx, "mpi_speedup_plastic",
                 "elastic-plastic step: step time 2 processes / 1 process (speed-up 1.6x: <= "
                 "0.625)",
                 "issue 22 item 4: target 1.6x", 1.0 / TARGET_SPEEDUP, 1.0 / s,
                 1.0 / TARGET_SPEEDUP, VF_MAX);
        vf_regress(ctx, "mpi_speedup_plastic", VF_TIER_NONE);
        vf_info(ctx, "mpi_wall_speedup_plastic",
                "elastic-plastic step: whole process wall time, 1 -> 2 processes (start, "
                "set-up, elastic steps and output included)", "", NAN, sw);
        vf_regress(ctx, "mpi_wall_speedup_plastic", VF_TIER_NONE);
        vf_info(ctx, "mpi_work_speedup_plastic",
                "elastic-plastic step: rank 0 CPU outside communication, 1 -> 2 processes", "",
                NAN, w1 / w2);
        vf_regress(ctx, "mpi_work_speedup_plastic", VF_TIER_NONE);
        vf_info(ctx, "mpi_comm_share_plastic",
                "elastic-plastic step: communication / rank 0 CPU, 2 processes", "", NAN,
                runs[2].r0comm / runs[2].r0cpu);
        vf_regress(ctx, "mpi_comm_share_plastic", VF_TIER_NONE);
        vf_info(ctx, "mpi_memory_plastic_p2_over_p1",
                "elastic-plastic step: peak memory of rank 0, 2 processes / 1", "", NAN,
                runs[2].mib / runs[1].mib);
        vf_regress(ctx, "mpi_memory_plastic_p2_over_p1", VF_TIER_NONE);
    }
}

int mc_bench_mpi(vf_ctx *ctx, int quick)
{
    char self[1024], mpi[1100], dir[] = "/tmp/mc_bench_mpi_XXXXXX";
    const ssize_t sl = readlink("/proc/self/exe", self, sizeof self - 1);
    if (sl <= 0 || !mkdtemp(dir))
        return 1;
    self[sl] = '\0';
    snprintf(mpi, sizeof mpi, "%s-mpi", self); /* bin/microcontact-mpi beside bin/microcontact */
    vf_text(ctx, "## MPI: strong scaling of the elastic contact and an elastic-plastic step\n\n");
    if (access(mpi, X_OK) != 0) {
        vf_text(ctx, "`%s` is not built (`make mpi` needs mpicc and FFTW-MPI): not measured.\n\n",
                mpi);
        mc_bench_remove_tree(dir);
        return 0;
    }
    const int N = quick ? 512 : 1024;
    char ini[1200];
    snprintf(ini, sizeof ini, "%s/hertz%d.ini", dir, N);
    if (mc_bench_hertz_case(ini, N)) {
        vf_fail(ctx, "mpi_case", "cannot write %s", ini);
        mc_bench_remove_tree(dir);
        return 1;
    }
    mpi_run runs[] = {
        {"bin/microcontact, 1 thread", 0, 0, 0, 0, 0, 0, 0, NAN, NAN, 0, 0, 0},
        {"bin/microcontact-mpi, 1 process", 1, 0, 0, 0, 0, 0, 0, NAN, NAN, 0, 0, 0},
        {"bin/microcontact-mpi, 2 processes", 2, 0, 0, 0, 0, 0, 0, NAN, NAN, 0, 0, 0},
        {"bin/microcontact-mpi, 3 processes", 3, 0, 0, 0, 0, 0, 0, NAN, NAN, 0, 0, 0},
        {"bin/microcontact-mpi, 2 processes, FFTW-MPI's transposes (MC_TRANSPOSES=fftw)", 2, 0,
         0, 0, 0, 0, 0, NAN, NAN, 0, 0, 1}};
    /* ROUNDS rounds, each running every row once in turn (a slow spell of the host falls on
     * all rows alike); per row the run with the least contact time is kept */
    const int nruns = (int)(sizeof runs / sizeof runs[0]), rounds = ROUNDS;
    for (int k = 0; k < nruns; k++)
        runs[k].contact = INFINITY;
    for (int round = 0; round < rounds; round++)
    for (int k = 0; k < nruns; k++) {
        mpi_run *r = &runs[k];
        if (round > 0 && !r->ok)
            continue; /* (a failed run is not repeated) */
        {
            char out[1300], log[1300], js[1400];
            snprintf(out, sizeof out, "%s/out%d_%d", dir, k, round);
            snprintf(log, sizeof log, "%s/log%d_%d", dir, k, round);
            const double cpu0 = children_cpu();
            if (r->fftw)
                setenv("MC_TRANSPOSES", "fftw", 1); /* (mpirun's local ranks inherit it) */
            const double t = run_hertz(self, mpi, ini, out, log, r->ranks);
            unsetenv("MC_TRANSPOSES");
            const double cpu = children_cpu() - cpu0;
            snprintf(js, sizeof js, "%s/summary.json", out);
            if (!(t > 0)) {
                vf_fail(ctx, "mpi_run", "%s: the run of %s failed", r->name, ini);
                r->ok = 0;
                continue;
            }
            const double contact = mc_bench_json_number(js, "contact_s");
            if (contact < r->contact) {
                r->wall = t;
                r->cpu = cpu;
                r->total = mc_bench_json_number(js, "total_s");
                r->contact = contact;
                r->iterations = (int)mc_bench_json_number(js, "iterations");
                r->comm = r->ranks ? number_after(log, "spent ") : 0.0;
                r->mib = number_after(log, "peak memory ");
                if (r->ranks)
                    cpu_pair(log, "contact stage CPU ", &r->ccpu, &r->ccomm);
                r->ok = 1;
            }
            mc_bench_remove_tree(out);
        }
    }
    mc_bench_remove_tree(dir);

    FILE *f = vf_open(ctx, "mpi.csv");
    if (f)
        fprintf(f, "run,processes,wall_s,cpu_s,total_s,contact_s,comm_s,peak_mib,iterations\n");
    vf_text(ctx,
            "The Hertz point case of the whole-run section at %d² (the defaults, one thread per "
            "process: `--set solver.threads=1`), run as a child process: the serial program, and "
            "`mpirun --allow-run-as-root --oversubscribe -np P bin/microcontact-mpi run` with "
            "P = 1, 2 and 3 (3 on 2 cores: oversubscribed, for its memory; "
            "`--mca mpi_yield_when_idle 1`: a waiting rank gives its core away), and P = 2 "
            "again with FFTW-MPI's transposes instead of the shared ones (`MC_TRANSPOSES=fftw`); "
            "%d rounds, each running every row once in turn, and per row the run with the "
            "least contact time (summary.json contact_s: the stage the target is about, without "
            "the process's start, input and output): its wall time, fork to exit, its CPU "
            "seconds (user + system of all its processes, mpirun included), summary.json timings "
            "(total, contact) and the seconds rank 0 spent in communication (transposes, "
            "gathers, the row sums: MPI_Wtime around them, waiting for the other rank "
            "included). Distributed "
            "(README \"Running on a cluster\"): the operator's FFT and the contact solvers' "
            "iterations (each rank its slab of rows, sums row by row over the ranks), the "
            "preconditioner's transform over the contact's box (its rows exchanged all-to-all), "
            "the kernel table (each rank tabulates and transforms its rows of it); replicated on "
            "every rank: the problem's O(N) passes and the coarse start's restriction, which "
            "bound the speed-up. The peak memory is rank 0's. The host's speed varies by up to a third "
            "from one minute to the next on this virtual machine (first touches of memory the "
            "host has not backed yet cost 1-2 s per GB, reused memory 0.1 s): read the ratios "
            "with that in mind (the CPU seconds are the steadier figure). The elastic-plastic "
            "step: the next subsection.\n\n"
            "| run | wall (s) | CPU (s) | total (s) | contact (s) | communication (s) | "
            "communication / total | contact speed-up vs 1 process | peak MiB | iterations |\n"
            "|---|---|---|---|---|---|---|---|---|---|\n",
            N, rounds);
    const double c1 = runs[1].contact;
    for (int k = 0; k < nruns; k++) {
        const mpi_run *r = &runs[k];
        if (!r->ok)
            continue;
        vf_text(ctx, "| %s | %.3f | %.2f | %.3f | %.3f | %.3f | %.2f | %.2f | %.0f | %d |\n",
                r->name, r->wall, r->cpu, r->total, r->contact, r->comm, r->comm / r->total,
                r->ranks ? c1 / r->contact : NAN, r->mib, r->iterations);
        if (f)
            fprintf(f, "%s,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d\n", r->name, r->ranks, r->wall,
                    r->cpu, r->total, r->contact, r->comm, r->mib, r->iterations);
    }
    if (f)
        vf_close(ctx, f);
    if (runs[1].ok && runs[2].ok) {
        const double s = runs[1].contact / runs[2].contact;
        /* the work a rank did in the contact stage: its CPU outside communication */
        const double w1 = runs[1].ccpu - runs[1].ccomm, w2 = runs[2].ccpu - runs[2].ccomm;
        vf_text(ctx,
                "\nContact solve, 1 -> 2 processes: %.2fx in wall time (target %.1fx: %s); "
                "communication %.0f %% of the 2-process run's total. The contact stage's CPU on "
                "rank 0: %.3f s with one process (%.3f s of it in communication: the local "
                "transposes), %.3f s with two (%.3f s in communication: its half of the "
                "transposes, copied straight from the other rank's shared buffers (operator/"
                "dfft.h; FFTW-MPI's all-to-all across machines), the barriers around them and "
                "the row sums, waiting for the other rank included, which shares the cores with "
                "other jobs): its work outside communication %.3f s -> %.3f s, %.2fx.\n\n",
                s, TARGET_SPEEDUP, s >= TARGET_SPEEDUP ? "met" : "not met",
                100 * runs[2].comm / runs[2].total, runs[1].ccpu, runs[1].ccomm, runs[2].ccpu,
                runs[2].ccomm, w1, w2, w1 / w2);
        vf_info(ctx, "mpi_work_speedup_contact",
                "contact stage CPU outside communication, 1 -> 2 processes", "", NAN, w1 / w2);
        vf_regress(ctx, "mpi_work_speedup_contact", VF_TIER_NONE);
        /* the target, checked as the plastic step's: wall time 2 processes / 1 */
        vf_check(ctx, "mpi_speedup_contact",
                 "contact solve: wall time 2 processes / 1 process (speed-up 1.6x: <= 0.625)",
                 "issue 22 item 4: target 1.6x", 1.0 / TARGET_SPEEDUP, 1.0 / s,
                 1.0 / TARGET_SPEEDUP, VF_MAX);
        vf_regress(ctx, "mpi_speedup_contact", VF_TIER_NONE);
        vf_info(ctx, "mpi_comm_share", "communication / total, 2 processes", "", NAN,
                runs[2].comm / runs[2].total);
        vf_regress(ctx, "mpi_comm_share", VF_TIER_NONE);
    }
    if (runs[1].ok && runs[2].ok && runs[4].ok) { /* what the shared transposes save */
        vf_text(ctx,
                "The same two processes with FFTW-MPI's transposes (`MC_TRANSPOSES=fftw`, the "
                "last row; what runs across machines): contact stage %.3f s (rank 0 %.3f s in "
                "communication), %.2fx over one process; the transposes through shared memory "
                "(operator/dfft.h: each element copied once, straight out of the other rank's "
                "buffers) save %.3f s of it.\n\n",
                runs[4].contact, runs[4].comm, runs[1].contact / runs[4].contact,
                runs[4].contact - runs[2].contact);
        vf_info(ctx, "mpi_speedup_contact_fftw_transposes",
                "contact solve, 1 -> 2 processes with FFTW-MPI's transposes (MC_TRANSPOSES=fftw)",
                "", NAN, runs[1].contact / runs[4].contact);
        vf_regress(ctx, "mpi_speedup_contact_fftw_transposes", VF_TIER_NONE);
    }
    plastic_step(ctx, self, mpi, quick);
    memory_per_rank(ctx, self, mpi, quick);
    if (runs[1].ok && runs[1].iterations > 0)
        flank_model(ctx, &runs[1], N);
    return 0;
}

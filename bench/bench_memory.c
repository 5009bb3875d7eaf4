/* bench_memory.c - peak memory per cell of an elastic run, measured on a fresh process (this
 * executable re-run on a generated case, its peak RSS from wait4), and the largest grid that
 * fits this machine. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <unistd.h>

#include "bench.h"

/* Peak resident memory (bytes) of `microcontact run` on an N x N Hertz case, as the run itself
 * reports it (VmHWM of its own process image: a fork's copy of this process does not count);
 * -1 on failure. */
static double peak_rss(const char *self, int N, const char *dir)
{
    char ini[512], out[512], cmd[2048];
    snprintf(ini, sizeof ini, "%s/mem%d.ini", dir, N);
    snprintf(out, sizeof out, "%s/out%d", dir, N);
    FILE *f = fopen(ini, "w");
    if (!f)
        return -1;
    fprintf(f, "[mesh]\nnx = %d\nny = %d\ndx = %.17g\n[geometry]\nshape = sphere\nradius = 10 mm\n"
               "[load]\nforce = 100 N\n[solver]\ntolerance = 1e-6\n",
            N, N, 560e-6 / N);
    fclose(f);
    snprintf(cmd, sizeof cmd, "'%s' run '%s' --out '%s' 2>/dev/null", self, ini, out);
    FILE *p = popen(cmd, "r");
    if (!p)
        return -1;
    char line[512];
    double mib = -1;
    while (fgets(line, sizeof line, p)) {
        const char *at = strstr(line, "peak memory ");
        if (at)
            sscanf(at, "peak memory %lf MiB", &mib);
    }
    if (pclose(p) != 0)
        return -1;
    return mib * 1048576.0;
}

int mc_bench_memory(vf_ctx *ctx, int quick)
{
    char dir[] = "/tmp/mc_bench_mem_XXXXXX", self[1024];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0 || !mkdtemp(dir))
        return 1;
    self[len] = '\0';
    static const int sizes[] = {512, 1024, 2048};
    int nsizes = quick ? 2 : 3;
    double base = peak_rss(self, 16, dir);
    double phys = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
    FILE *f = vf_open(ctx, "memory.csv");
    vf_text(ctx, "## Memory\n\n"
                 "Peak resident memory of a fresh `microcontact run` of the Hertz case (cg, fft, "
                 "no stress, outputs written; the peak the run reports for its own process) minus "
                 "that of a 16 x 16 run (%.0f MiB: code, libraries, FFTW), per cell.\n\n| N | peak (MiB) | bytes per cell |\n|---|---|---|\n",
            base / 1048576.0);
    if (f)
        fprintf(f, "N,peak_bytes,bytes_per_cell\n");
    double bpc_last = NAN;
    for (int k = 0; k < nsizes; k++) {
        double rss = peak_rss(self, sizes[k], dir);
        double cells = (double)sizes[k] * sizes[k];
        double bpc = rss > 0 && base > 0 ? (rss - base) / cells : NAN;
        if (f)
            fprintf(f, "%d,%.0f,%.1f\n", sizes[k], rss, bpc);
        vf_text(ctx, "| %d² | %.0f | %.0f |\n", sizes[k], rss / 1048576.0, bpc);
        bpc_last = bpc;
    }
    if (f)
        vf_close(ctx, f);
    vf_check(ctx, "bytes_per_cell", "peak memory per cell of an elastic solve (bytes)",
             "target <= 300", 300, bpc_last, 300, VF_MAX);
    double nmax = sqrt(0.9 * phys / bpc_last);
    vf_text(ctx, "\nThis machine has %.1f GiB: at %.0f bytes per cell, the largest square grid an "
                 "elastic solve fits in (90 %% of it) is about %.0f x %.0f cells (%.0f million).\n\n",
            phys / 1073741824.0, bpc_last, nmax, nmax, nmax * nmax * 1e-6);
    if (!quick) { /* show it: a 4096 x 4096 elastic solve on this machine */
        double rss = peak_rss(self, 4096, dir);
        vf_text(ctx, "A 4096 x 4096 Hertz solve (16.8 million cells) ran here with a peak of %.1f "
                     "GiB (%.0f bytes per cell).\n\n",
                rss / 1073741824.0, (rss - base) / (4096.0 * 4096.0));
    }
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        vf_text(ctx, "(could not remove %s)\n", dir);
    return 0;
}

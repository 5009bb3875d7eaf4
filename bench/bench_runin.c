#include "bench.h"
int mc_bench_runin(vf_ctx *ctx, int quick) { (void)ctx; (void)quick; return 0; }

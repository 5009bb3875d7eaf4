#include "bench.h"
int mc_bench_growth(vf_ctx *ctx, int quick) { (void)ctx; (void)quick; return 0; }

/* fuzz_npy_any.c - libFuzzer target: the general .npy reader of measured surfaces
 * (mc_npy_parse_any: every float and integer dtype, both byte orders, C and Fortran order),
 * through mc_surface_parse_buffer "npy". The buffer is exactly `size` bytes. Contracts: those of
 * fuzz_surface.h, with at most one point per input byte (the smallest dtype has one byte). */
#include <stddef.h>
#include <stdint.h>

#include "fuzz_surface.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    long fail_at = fuzz_alloc_prefix(&data, &size);
    fuzz_surface_parse("npy", data, size, NULL, fail_at, (double)size);
    return 0;
}

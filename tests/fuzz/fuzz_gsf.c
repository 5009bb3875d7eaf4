/* fuzz_gsf.c - libFuzzer target: the Gwyddion Simple Field reader, through
 * mc_surface_parse_buffer "gsf". The buffer is exactly `size` bytes. Contracts: those of
 * fuzz_surface.h, with exactly 4 bytes of data per point, so at most size/4 points. */
#include <stddef.h>
#include <stdint.h>

#include "fuzz_surface.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    long fail_at = fuzz_alloc_prefix(&data, &size);
    fuzz_surface_parse("gsf", data, size, NULL, fail_at, (double)size / 4);
    return 0;
}

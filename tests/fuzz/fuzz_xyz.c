/* fuzz_xyz.c - libFuzzer target: the x y z triplet reader and its grid detection, through
 * mc_surface_parse_buffer "xyz". The buffer is exactly `size` bytes. Contracts: those of
 * fuzz_surface.h; the grid holds at most twice as many points as the file has lines, and a line
 * takes at least 5 bytes, so at most 2*size/5 + 2 points. */
#include <stddef.h>
#include <stdint.h>

#include "fuzz_surface.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    long fail_at = fuzz_alloc_prefix(&data, &size);
    fuzz_surface_parse("xyz", data, size, NULL, fail_at, 2.0 * (double)size / 5 + 2);
    return 0;
}

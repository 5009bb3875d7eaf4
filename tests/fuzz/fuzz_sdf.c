/* fuzz_sdf.c - libFuzzer target: the SDF reader (ISO 25178-71, ASCII and binary), through
 * mc_surface_parse_buffer "sdf". The buffer is exactly `size` bytes, so AddressSanitizer catches
 * any read past it. Contracts: those of fuzz_surface.h, with at most one point per input byte
 * (a binary value takes at least one byte, an ASCII value a character and a separator). */
#include <stddef.h>
#include <stdint.h>

#include "fuzz_surface.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    long fail_at = fuzz_alloc_prefix(&data, &size);
    fuzz_surface_parse("sdf", data, size, NULL, fail_at, (double)size);
    return 0;
}

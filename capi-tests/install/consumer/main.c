/* Installed-package consumer: built by capi-tests/install/check.sh with pkg-config's flags and with CMake. */
#include <dnsr.h>
#include <inttypes.h>
#include <stdio.h>

int main(void) {
    uint32_t v = dnsr_version();
    printf("dnsr_version() = %u.%u.%u (0x%08" PRIx32 ")\n", v >> 22, (v >> 12) & 0x3FFu, v & 0xFFFu, v);
    if (v != DNSR_VERSION) {
        fprintf(stderr, "library version 0x%08" PRIx32 " != header DNSR_VERSION 0x%08" PRIx32 "\n", v,
                (uint32_t)DNSR_VERSION);
        return 1;
    }
    uint64_t bytes = 0;
    DnsrResult r = dnsr_get_memory_requirements(1920, 1080, DNSR_PRECISION_FP32, 3, 1, &bytes);
    if (r != DNSR_SUCCESS || bytes == 0) {
        fprintf(stderr, "dnsr_get_memory_requirements failed: %d (bytes %" PRIu64 ")\n", (int)r, bytes);
        return 1;
    }
    printf("dnsr_get_memory_requirements(1920x1080, FP32, 3 passes, 1 light) = %" PRIu64 " bytes\n", bytes);
    return 0;
}

/*
 * dnsr.h compiles as C11 under -pedantic -Wall -Wextra -Werror, and generated/layout.h (static asserts of the
 * size, alignment and every field offset of each public struct, generated from the Rust definitions) holds:
 * a layout mismatch fails the build, not a run. At run time: the library's version equals the header's, and
 * dnsr_result_to_string names codes.
 */
#include "dnsr.h"
#include "generated/layout.h"

#include <stdio.h>
#include <string.h>

static int failures;

static void expect_name(int32_t code, const char *want)
{
    const char *got = dnsr_result_to_string(code);
    if (got == NULL || strcmp(got, want) != 0) {
        fprintf(stderr, "dnsr_result_to_string(%d) = \"%s\", want \"%s\"\n", (int)code, got ? got : "(null)", want);
        failures++;
    }
}

int main(void)
{
    printf("C11 sizes: DnsrContextCreateInfo %zu, DnsrShadowsDispatch %zu, DnsrSettings %zu, DnsrHostImage %zu, "
           "DnsrPassTimings %zu, DnsrDeviceRequirements %zu, DnsrGpuMemoryCallbacks %zu, DnsrResult %zu\n",
           sizeof(DnsrContextCreateInfo), sizeof(DnsrShadowsDispatch), sizeof(DnsrSettings), sizeof(DnsrHostImage),
           sizeof(DnsrPassTimings), sizeof(DnsrDeviceRequirements), sizeof(DnsrGpuMemoryCallbacks),
           sizeof(DnsrResult));

    uint32_t version = dnsr_version();
    printf("library version %u.%u.%u, header version %u.%u.%u\n", version >> 22, (version >> 12) & 0x3ffu,
           version & 0xfffu, DNSR_VERSION_MAJOR, DNSR_VERSION_MINOR, DNSR_VERSION_PATCH);
    if (version != DNSR_VERSION) {
        fprintf(stderr, "dnsr_version() = 0x%x but DNSR_VERSION = 0x%x\n", version, DNSR_VERSION);
        failures++;
    }

    expect_name(DNSR_SUCCESS, "DNSR_SUCCESS");
    expect_name(DNSR_NOT_READY, "DNSR_NOT_READY");
    expect_name(DNSR_ERROR_INVALID_ARGUMENT, "DNSR_ERROR_INVALID_ARGUMENT");
    expect_name(DNSR_ERROR_NON_FINITE, "DNSR_ERROR_NON_FINITE");
    expect_name(DNSR_ERROR_INTERNAL, "DNSR_ERROR_INTERNAL");
    expect_name(DNSR_ERROR_INVALID_QUEUE_FAMILY, "DNSR_ERROR_INVALID_QUEUE_FAMILY");
    expect_name(DNSR_ERROR_CLASSIFIER_NOT_ENABLED, "DNSR_ERROR_CLASSIFIER_NOT_ENABLED");
    expect_name(DNSR_ERROR_OUT_OF_HOST_MEMORY, "DNSR_ERROR_OUT_OF_HOST_MEMORY");
    expect_name(-25, "DNSR_RESULT_UNKNOWN");
    expect_name(2, "DNSR_RESULT_UNKNOWN");
    expect_name(DNSR_RESULT_MAX_ENUM, "DNSR_RESULT_UNKNOWN");
    expect_name(INT32_MIN, "DNSR_RESULT_UNKNOWN");

    /* A pure query needs no device: the default settings come back tagged. */
    DnsrSettings s;
    memset(&s, 0, sizeof s);
    if (dnsr_settings_init_default(&s) != DNSR_SUCCESS || s.sType != DNSR_STRUCTURE_TYPE_SETTINGS || s.filterPasses != 2) {
        fprintf(stderr, "dnsr_settings_init_default: sType %u, filterPasses %u\n", s.sType, s.filterPasses);
        failures++;
    }

    /* Presets: Quality is the default (two passes, stable history, the moving-shadow test); Balanced the FidelityFX values
       (three passes, none of the run features); Fast Quality in one pass. */
    DnsrSettings fast, balanced, quality;
    if (dnsr_settings_init_preset(DNSR_PRESET_FAST, &fast) != DNSR_SUCCESS || fast.filterPasses != 1
        || fast.stableHistorySamples != 8.0f
        || dnsr_settings_init_preset(DNSR_PRESET_QUALITY, &quality) != DNSR_SUCCESS || memcmp(&quality, &s, sizeof s) != 0
        || quality.filterPasses != 2 || quality.stableHistorySamples != 8.0f || quality.movingShadowSigmas != 3.0f || quality.sType != DNSR_STRUCTURE_TYPE_SETTINGS
        || dnsr_settings_init_preset(DNSR_PRESET_BALANCED, &balanced) != DNSR_SUCCESS || balanced.filterPasses != 3
        || balanced.stableHistorySamples != 0.0f || balanced.outputContrast != 1.2f
        || balanced.movingShadowSigmas != 0.0f) {
        fprintf(stderr, "dnsr_settings_init_preset: fast %u passes, quality %u passes, stable %g, balanced stable %g\n",
                fast.filterPasses, quality.filterPasses, (double)quality.stableHistorySamples,
                (double)balanced.stableHistorySamples);
        failures++;
    }
    if (DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS != (1u << 30)) {
        fprintf(stderr, "DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS moved\n");
        failures++;
    }

    printf("%s\n", failures ? "header_c11: FAILED" : "header_c11: ok");
    return failures ? 1 : 0;
}

// dnsr.h compiles as C++17 under -pedantic -Wall -Wextra -Werror (DnsrResult is then a real enum with a fixed
// int32_t underlying type), and generated/layout.h's static asserts hold for the C++ view of every struct.
#include "dnsr.h"
#include "generated/layout.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <type_traits>

static_assert(std::is_same<std::underlying_type<DnsrResult>::type, int32_t>::value, "DnsrResult is 32-bit");
static_assert(sizeof(DnsrResult) == 4, "DnsrResult is 32-bit");
static_assert(std::is_trivially_copyable<DnsrShadowsDispatch>::value, "plain C struct");
static_assert(std::is_standard_layout<DnsrContextCreateInfo>::value, "plain C struct");

static int failures = 0;

static void expect_name(int32_t code, const char *want)
{
    const char *got = dnsr_result_to_string(code);
    if (got == nullptr || std::strcmp(got, want) != 0) {
        std::fprintf(stderr, "dnsr_result_to_string(%d) = \"%s\", want \"%s\"\n", static_cast<int>(code),
                     got ? got : "(null)", want);
        failures++;
    }
}

int main()
{
    std::printf("C++17 sizes: DnsrContextCreateInfo %zu, DnsrShadowsDispatch %zu, DnsrSettings %zu, DnsrHostImage %zu, "
                "DnsrPassTimings %zu, DnsrDeviceRequirements %zu, DnsrGpuMemoryCallbacks %zu, DnsrResult %zu\n",
                sizeof(DnsrContextCreateInfo), sizeof(DnsrShadowsDispatch), sizeof(DnsrSettings), sizeof(DnsrHostImage),
                sizeof(DnsrPassTimings), sizeof(DnsrDeviceRequirements), sizeof(DnsrGpuMemoryCallbacks),
                sizeof(DnsrResult));

    const uint32_t version = dnsr_version();
    if (version != DNSR_VERSION) {
        std::fprintf(stderr, "dnsr_version() = 0x%x but DNSR_VERSION = 0x%x\n", version, DNSR_VERSION);
        failures++;
    }

    expect_name(DNSR_SUCCESS, "DNSR_SUCCESS");
    expect_name(DNSR_ERROR_INVALID_STRUCTURE, "DNSR_ERROR_INVALID_STRUCTURE");
    expect_name(DNSR_ERROR_INVALID_HOST_SYNC, "DNSR_ERROR_INVALID_HOST_SYNC");
    expect_name(-15, "DNSR_RESULT_UNKNOWN"); // retired DNSR_ERROR_DESCRIPTOR_CACHE_FULL
    expect_name(DNSR_ERROR_VULKAN, "DNSR_ERROR_VULKAN");
    expect_name(12345, "DNSR_RESULT_UNKNOWN");
    expect_name(-100, "DNSR_RESULT_UNKNOWN");

    // In C++ a DnsrResult is returned as the enum type and compares with the enumerators directly.
    DnsrSettings s{};
    const DnsrResult r = dnsr_settings_init_default(&s);
    if (r != DNSR_SUCCESS || s.sType != DNSR_STRUCTURE_TYPE_SETTINGS) {
        std::fprintf(stderr, "dnsr_settings_init_default: %s\n", dnsr_result_to_string(r));
        failures++;
    }

    std::printf("%s\n", failures ? "header_cxx17: FAILED" : "header_cxx17: ok");
    return failures ? 1 : 0;
}

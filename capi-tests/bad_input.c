/*
 * bad_input: every misuse of the C API gets its specific DnsrResult and a dnsr_last_error_message() that names
 * the offending field (with the library's spelling of it), and a refused dnsr_shadows_record records nothing.
 *
 * "Records nothing" is proven on the GPU, not assumed: each refused record happens inside a pipeline statistics
 * query that must count zero compute shader invocations (when the device has pipelineStatisticsQuery), and the
 * output image, filled by a good all-lit frame (1.0 everywhere), must still hold 1.0 after the command buffer ran,
 * although the inputs uploaded meanwhile are all-shadow (any dnsr pass that ran would write 0).
 *
 * The validation layer (with synchronization validation) runs throughout; any message fails the test.
 */
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 32u
#define H 16u
#define TILES_X ((W + 7u) / 8u)
#define TILES_Y ((H + 3u) / 4u)
#define MIN_CASES 45u

static Host host;
static unsigned cases;

/* ------------------------------------------------------------------------------------------------------------- */
/* Checking one refused call                                                                                     */
/* ------------------------------------------------------------------------------------------------------------- */

/* Checks the result of a call that just returned `got` (no dnsr call may happen in between: the message is this
 * thread's last call's). `mention` is a substring the message must contain (NULL: any non-empty message). */
static void expect(const char *name, DnsrResult got, DnsrResult want, const char *mention)
{
    const char *msg = dnsr_last_error_message();
    cases++;
    CHECK(msg != NULL, "%s: dnsr_last_error_message() returned NULL", name);
    CHECK(got == want, "%s: got %s, want %s (message: \"%s\")", name, dnsr_result_to_string(got),
          dnsr_result_to_string(want), msg);
    CHECK(msg[0] != '\0', "%s: %s with an empty dnsr_last_error_message()", name, dnsr_result_to_string(got));
    CHECK(mention == NULL || strstr(msg, mention) != NULL, "%s: message \"%s\" does not mention \"%s\"", name, msg,
          mention);
    host_expect_clean(&host, name);
    printf("  %-46s %-35s %s\n", name, dnsr_result_to_string(got), msg);
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Calls that need no device                                                                                     */
/* ------------------------------------------------------------------------------------------------------------- */

static void device_free_calls(void)
{
    DnsrDeviceRequirements req;
    memset(&req, 0, sizeof req);
    req.sType = DNSR_STRUCTURE_TYPE_SETTINGS;
    expect("requirements: wrong sType", dnsr_get_device_requirements(&req), DNSR_ERROR_INVALID_STRUCTURE,
           "pRequirements->sType");
    expect("requirements: NULL", dnsr_get_device_requirements(NULL), DNSR_ERROR_INVALID_ARGUMENT, "pRequirements");
    req.sType = DNSR_STRUCTURE_TYPE_DEVICE_REQUIREMENTS;
    DNSR_CHECK(dnsr_get_device_requirements(&req));
    CHECK(req.minApiVersion == VK_API_VERSION_1_1, "minApiVersion 0x%x", req.minApiVersion);
    CHECK(req.optionalExtensionCount >= 1 && strcmp(req.ppOptionalExtensionNames[0], "VK_KHR_push_descriptor") == 0,
          "optional extensions: %u", req.optionalExtensionCount);

    uint64_t bytes = 0;
    expect("memory requirements: width 0", dnsr_get_memory_requirements(0, H, DNSR_PRECISION_FP32, 3, 1, &bytes),
           DNSR_ERROR_INVALID_EXTENT, "zero width");
    expect("memory requirements: filterPasses 9", dnsr_get_memory_requirements(W, H, DNSR_PRECISION_FP32, 9, 1, &bytes),
           DNSR_ERROR_INVALID_SETTING, "filterPasses");
    expect("memory requirements: precision 7", dnsr_get_memory_requirements(W, H, 7, 3, 1, &bytes),
           DNSR_ERROR_INVALID_ARGUMENT, "precision 7");
    expect("memory requirements: NULL pBytes", dnsr_get_memory_requirements(W, H, DNSR_PRECISION_FP32, 3, 1, NULL),
           DNSR_ERROR_INVALID_ARGUMENT, "pBytes");
    expect("settings init: NULL", dnsr_settings_init_default(NULL), DNSR_ERROR_INVALID_ARGUMENT, "pSettings");
    expect("preset init: NULL", dnsr_settings_init_preset(DNSR_PRESET_QUALITY, NULL), DNSR_ERROR_INVALID_ARGUMENT,
           "pSettings");
    DnsrSettings untouched;
    memset(&untouched, 0xAB, sizeof untouched);
    expect("preset init: preset 3", dnsr_settings_init_preset(3, &untouched), DNSR_ERROR_INVALID_ARGUMENT,
           "preset 3");
    CHECK(untouched.filterPasses == 0xABABABABu, "preset init: preset 3 wrote the settings");
}

/* ------------------------------------------------------------------------------------------------------------- */
/* dnsr_context_create                                                                                           */
/* ------------------------------------------------------------------------------------------------------------- */

static DnsrContextCreateInfo good_info;
static DnsrSettings default_settings;

static VkResult gpu_allocate_never(void *user, const VkMemoryRequirements *req, DnsrResourceKind kind,
                                   DnsrGpuAllocation *out)
{
    (void)user, (void)req, (void)kind, (void)out;
    return VK_ERROR_OUT_OF_DEVICE_MEMORY;
}

static void gpu_free_never(void *user, const DnsrGpuAllocation *a)
{
    (void)user, (void)a;
}

static VKAPI_ATTR void *VKAPI_CALL cpu_allocate_never(void *user, size_t size, size_t align, VkSystemAllocationScope scope)
{
    (void)user, (void)size, (void)align, (void)scope;
    return NULL;
}

static VKAPI_ATTR void *VKAPI_CALL cpu_reallocate_never(void *user, void *orig, size_t size, size_t align,
                                                       VkSystemAllocationScope scope)
{
    (void)user, (void)orig, (void)size, (void)align, (void)scope;
    return NULL;
}

static void expect_create(const char *name, const DnsrContextCreateInfo *info, DnsrResult want, const char *mention)
{
    DnsrContext context = (DnsrContext)(uintptr_t)0x5eed; /* must be overwritten with NULL */
    DnsrResult r = dnsr_context_create(info, &context);
    expect(name, r, want, mention);
    CHECK(context == NULL, "%s: a refused dnsr_context_create must write NULL to *pContext", name);
}

/* Edits a copy of the good create info (statements after `mention`, which may also edit `settings`, the initial
 * settings the copy points to) and expects dnsr_context_create to refuse it. */
#define CREATE_CASE(name, want, mention, ...)                                                                     \
    do {                                                                                                          \
        DnsrContextCreateInfo info = good_info;                                                                   \
        DnsrSettings settings = default_settings;                                                                 \
        info.pSettings = &settings;                                                                               \
        __VA_ARGS__;                                                                                              \
        expect_create(name, &info, want, mention);                                                                \
    } while (0)

/* The physical device's Vulkan version, patch dropped. */
static uint32_t device_api_version(const Host *h)
{
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(h->physicalDevice, &props);
    return VK_MAKE_API_VERSION(0, VK_API_VERSION_MAJOR(props.apiVersion), VK_API_VERSION_MINOR(props.apiVersion), 0);
}

static void create_calls(void)
{
    expect_create("create: NULL pCreateInfo", NULL, DNSR_ERROR_INVALID_ARGUMENT, "pCreateInfo is NULL");
    expect("create: NULL pContext", dnsr_context_create(&good_info, NULL), DNSR_ERROR_INVALID_ARGUMENT, "pContext");

    CREATE_CASE("create: wrong sType", DNSR_ERROR_INVALID_STRUCTURE, "pCreateInfo->sType",
                info.sType = DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH);
    CREATE_CASE("create: non-NULL pNext", DNSR_ERROR_INVALID_STRUCTURE, "pCreateInfo->pNext", info.pNext = &settings);
    CREATE_CASE("create: null instance", DNSR_ERROR_NULL_HANDLE, "instance", info.instance = VK_NULL_HANDLE);
    CREATE_CASE("create: null physicalDevice", DNSR_ERROR_NULL_HANDLE, "physicalDevice",
                info.physicalDevice = VK_NULL_HANDLE);
    CREATE_CASE("create: null device", DNSR_ERROR_NULL_HANDLE, "device", info.device = VK_NULL_HANDLE);
    CREATE_CASE("create: null vkGetInstanceProcAddr", DNSR_ERROR_NULL_HANDLE, "vulkanFunctions.vkGetInstanceProcAddr",
                info.vulkanFunctions.vkGetInstanceProcAddr = NULL);
    CREATE_CASE("create: null vkGetDeviceProcAddr", DNSR_ERROR_NULL_HANDLE, "vulkanFunctions.vkGetDeviceProcAddr",
                info.vulkanFunctions.vkGetDeviceProcAddr = NULL);
    CREATE_CASE("create: apiVersion 1.0", DNSR_ERROR_UNSUPPORTED_API_VERSION, "apiVersion 1.0",
                info.apiVersion = VK_API_VERSION_1_0);
    CREATE_CASE("create: apiVersion 0", DNSR_ERROR_UNSUPPORTED_API_VERSION, "apiVersion", info.apiVersion = 0);
    /* A patch number does not lift 1.0 to 1.1. */
    CREATE_CASE("create: apiVersion 1.0.999", DNSR_ERROR_UNSUPPORTED_API_VERSION, "apiVersion 1.0",
                info.apiVersion = VK_MAKE_API_VERSION(0, 1, 0, 999));
    /* Versions the device does not have, and values that are no Vulkan version at all. */
    CREATE_CASE("create: apiVersion 9.0", DNSR_ERROR_UNSUPPORTED_API_VERSION, "apiVersion 9.0",
                info.apiVersion = VK_MAKE_API_VERSION(0, 9, 0, 0));
    CREATE_CASE("create: apiVersion 2.0", DNSR_ERROR_UNSUPPORTED_API_VERSION, "apiVersion 2.0",
                info.apiVersion = VK_MAKE_API_VERSION(0, 2, 0, 0));
    CREATE_CASE("create: apiVersion variant 1", DNSR_ERROR_UNSUPPORTED_API_VERSION, "apiVersion",
                info.apiVersion = VK_MAKE_API_VERSION(1, 1, 1, 0));
    CREATE_CASE("create: apiVersion 0xFFFFFFFF", DNSR_ERROR_UNSUPPORTED_API_VERSION, "apiVersion",
                info.apiVersion = 0xFFFFFFFFu);
    CREATE_CASE("create: apiVersion one minor above the device", DNSR_ERROR_UNSUPPORTED_API_VERSION,
                "the device supports", info.apiVersion = device_api_version(&host) + VK_MAKE_API_VERSION(0, 0, 1, 0));
    CREATE_CASE("create: queueFamilyIndex 99", DNSR_ERROR_INVALID_QUEUE_FAMILY, "queueFamilyIndex 99",
                info.queueFamilyIndex = 99);
    CREATE_CASE("create: lightCount 65", DNSR_ERROR_INVALID_ARGUMENT, "lightCount is 65", info.lightCount = 65);
    CREATE_CASE("create: lightCount 100000", DNSR_ERROR_INVALID_ARGUMENT, "DNSR_MAX_LIGHT_COUNT",
                info.lightCount = 100000);
    CREATE_CASE("create: lightCount 0xFFFFFFFF", DNSR_ERROR_INVALID_ARGUMENT, "lightCount",
                info.lightCount = 0xFFFFFFFFu);
    CREATE_CASE("create: 64 lights at 16384x16384", DNSR_ERROR_OUT_OF_DEVICE_MEMORY, "MiB of device memory",
                info.lightCount = DNSR_MAX_LIGHT_COUNT;
                info.width = 16384; info.height = 16384);
    CREATE_CASE("create: maxFramesInFlight 17", DNSR_ERROR_INVALID_ARGUMENT, "maxFramesInFlight is 17",
                info.maxFramesInFlight = DNSR_MAX_FRAMES_IN_FLIGHT + 1);
    CREATE_CASE("create: zero width", DNSR_ERROR_INVALID_EXTENT, "zero width", info.width = 0);
    CREATE_CASE("create: zero height", DNSR_ERROR_INVALID_EXTENT, "zero width or height", info.height = 0);
    CREATE_CASE("create: width 1<<20", DNSR_ERROR_INVALID_EXTENT, "exceeds the device limit", info.width = 1u << 20);
    CREATE_CASE("create: lightCount 0", DNSR_ERROR_INVALID_ARGUMENT, "lightCount is 0", info.lightCount = 0);
    /* Known bits are set next to the unknown one on purpose: the message must name only the unknown bits. */
    CREATE_CASE("create: unknown flag bits", DNSR_ERROR_INVALID_ARGUMENT, "pCreateInfo->flags has unknown bits 0x100",
                info.flags = DNSR_CONTEXT_CREATE_DEPTH_INVERTED | (1u << 8));
    CREATE_CASE("create: host previous G-buffer with a visibility input", DNSR_ERROR_INVALID_ARGUMENT,
                "DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER) is true with shadow input Visibility",
                (info.flags = DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER, info.shadowInput = DNSR_SHADOW_INPUT_VISIBILITY));
    CREATE_CASE("create: aliased transient memory without pGpuMemoryCallbacks", DNSR_ERROR_INVALID_ARGUMENT,
                "DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY) is true; it needs hooks.gpuMemory (pGpuMemoryCallbacks)",
                info.flags = DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY);
    CREATE_CASE("create: unknown feature bits", DNSR_ERROR_INVALID_ARGUMENT,
                "pCreateInfo->enabledFeatures has unknown bits 0x200", info.enabledFeatures |= 1u << 9);
    CREATE_CASE("create: precision 7", DNSR_ERROR_INVALID_ARGUMENT, "precision 7", info.precision = 7);
    CREATE_CASE("create: shadowInput 5", DNSR_ERROR_INVALID_ARGUMENT, "shadowInput 5", info.shadowInput = 5);
    CREATE_CASE("create: FP16 without DNSR_FEATURE_FLOAT16", DNSR_ERROR_MISSING_FEATURE, "DNSR_FEATURE_FLOAT16",
                info.precision = DNSR_PRECISION_FP16;
                info.enabledFeatures &= ~(DnsrFeatureFlags)DNSR_FEATURE_FLOAT16);
    CREATE_CASE("create: BGRA8 output", DNSR_ERROR_UNSUPPORTED_FORMAT, "output image format B8G8R8A8_UNORM",
                info.outputFormat = VK_FORMAT_B8G8R8A8_UNORM);
    CREATE_CASE("create: UNDEFINED output format", DNSR_ERROR_UNSUPPORTED_FORMAT, "output image format",
                info.outputFormat = VK_FORMAT_UNDEFINED);
    /* Shader overrides: checked before anything is created. */
    static const uint32_t not_spirv[4] = {0x6e697323u, 0x6564756cu, 0u, 0u};
    DnsrShaderOverride overrides[2] = {{"filter_final_r32f", not_spirv, sizeof not_spirv},
                                       {"filter_final_r99", not_spirv, sizeof not_spirv}};
    CREATE_CASE("create: shader override that is not SPIR-V", DNSR_ERROR_SHADER_INTERFACE, "is not SPIR-V",
                info.shaderOverrideCount = 1; info.pShaderOverrides = &overrides[0]);
    CREATE_CASE("create: shader override of an unknown variant", DNSR_ERROR_SHADER_INTERFACE, "filter_final_r99",
                info.shaderOverrideCount = 1; info.pShaderOverrides = &overrides[1]);
    CREATE_CASE("create: shaderOverrideCount without pShaderOverrides", DNSR_ERROR_INVALID_ARGUMENT, "pShaderOverrides",
                info.shaderOverrideCount = 2);
    DnsrShaderOverride odd = {"filter_final_r32f", not_spirv, 6};
    CREATE_CASE("create: shader override of 6 bytes", DNSR_ERROR_INVALID_ARGUMENT, "codeSize",
                info.shaderOverrideCount = 1; info.pShaderOverrides = &odd);
    DnsrShaderOverride huge = {"filter_final_r32f", not_spirv, DNSR_MAX_SHADER_OVERRIDE_CODE_SIZE + 4};
    CREATE_CASE("create: shader override over DNSR_MAX_SHADER_OVERRIDE_CODE_SIZE", DNSR_ERROR_INVALID_ARGUMENT,
                "DNSR_MAX_SHADER_OVERRIDE_CODE_SIZE", info.shaderOverrideCount = 1; info.pShaderOverrides = &huge);
    {
        /* A 100,000-byte name: refused, and the message does not echo it whole. */
        char *name = (char *)malloc(100001);
        memset(name, 'x', 100000);
        name[100000] = 0;
        DnsrShaderOverride long_name = {name, not_spirv, sizeof not_spirv};
        CREATE_CASE("create: shader override named by 100000 bytes", DNSR_ERROR_INVALID_ARGUMENT,
                    "DNSR_MAX_SHADER_VARIANT_NAME_LENGTH", info.shaderOverrideCount = 1; info.pShaderOverrides = &long_name);
        CHECK(strlen(dnsr_last_error_message()) < 512, "a 100000-byte name echoed in a %zu-byte message",
              strlen(dnsr_last_error_message()));
        free(name);
    }
    {
        uint32_t n = 0;
        expect("dnsr_get_shader_variants: NULL count", dnsr_get_shader_variants(NULL, NULL), DNSR_ERROR_INVALID_ARGUMENT, "pCount");
        CHECK(dnsr_get_shader_variants(&n, NULL) == DNSR_SUCCESS && n > 10, "dnsr_get_shader_variants count %u", n);
        DnsrShaderVariantInfo first;
        n = 1;
        CHECK(dnsr_get_shader_variants(&n, &first) == DNSR_SUCCESS && n == 1 && strcmp(first.pName, "prepare") == 0 &&
                  strcmp(first.pSource, "prepare.comp") == 0,
              "dnsr_get_shader_variants first entry");
    }
    CREATE_CASE("create: filterPasses 0", DNSR_ERROR_INVALID_SETTING, "filterPasses", settings.filterPasses = 0);
    CREATE_CASE("create: filterPasses 5", DNSR_ERROR_INVALID_SETTING, "filterPasses", settings.filterPasses = 5);
    CREATE_CASE("create: NaN disocclusion threshold", DNSR_ERROR_INVALID_SETTING, "disocclusionThresholdFacing",
                settings.disocclusionThresholdFacing = NAN);
    CREATE_CASE("create: minCurrentWeight 0", DNSR_ERROR_INVALID_SETTING, "minCurrentWeight",
                settings.minCurrentWeight = 0.0f);
    CREATE_CASE("create: settings wrong sType", DNSR_ERROR_INVALID_STRUCTURE, "pCreateInfo->pSettings->sType",
                settings.sType = 0);
    CREATE_CASE("create: settings non-NULL pNext", DNSR_ERROR_INVALID_STRUCTURE, "pCreateInfo->pSettings->pNext",
                settings.pNext = &info);

    DnsrLogCallback no_log = {NULL, NULL};
    CREATE_CASE("create: pLogCallback with NULL log", DNSR_ERROR_INVALID_ARGUMENT, "pCreateInfo->pLogCallback->log",
                info.pLogCallback = &no_log);
    DnsrGpuMemoryCallbacks no_free = {NULL, gpu_allocate_never, NULL};
    CREATE_CASE("create: pGpuMemoryCallbacks with NULL free", DNSR_ERROR_INVALID_ARGUMENT, "pGpuMemoryCallbacks",
                info.pGpuMemoryCallbacks = &no_free);
    DnsrGpuMemoryCallbacks no_allocate = {NULL, NULL, gpu_free_never};
    CREATE_CASE("create: pGpuMemoryCallbacks with NULL allocate", DNSR_ERROR_INVALID_ARGUMENT, "pGpuMemoryCallbacks",
                info.pGpuMemoryCallbacks = &no_allocate);
    DnsrDebugNameCallback no_name = {NULL, NULL};
    CREATE_CASE("create: pDebugNameCallback with NULL setName", DNSR_ERROR_INVALID_ARGUMENT,
                "pDebugNameCallback->setName", info.pDebugNameCallback = &no_name);
    VkAllocationCallbacks no_cpu_free = {NULL, cpu_allocate_never, cpu_reallocate_never, NULL, NULL, NULL};
    CREATE_CASE("create: pAllocationCallbacks without pfnFree", DNSR_ERROR_INVALID_ARGUMENT, "pAllocationCallbacks",
                info.pAllocationCallbacks = &no_cpu_free);
    CREATE_CASE("create: timestamps, queueFamilyIndex 99", DNSR_ERROR_INVALID_QUEUE_FAMILY, "no queue family",
                info.flags = DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS;
                info.queueFamilyIndex = 99);
    /* The host's GPU allocator failing is reported as a Vulkan error, with the allocator named. */
    DnsrGpuMemoryCallbacks failing = {NULL, gpu_allocate_never, gpu_free_never};
    CREATE_CASE("create: GPU allocator fails", DNSR_ERROR_VULKAN, "host GPU memory allocator",
                info.pGpuMemoryCallbacks = &failing);
}

/* ------------------------------------------------------------------------------------------------------------- */
/* A live context, its images, and the probe that proves a command buffer recorded nothing                       */
/* ------------------------------------------------------------------------------------------------------------- */

static DnsrContext ctx;
static HostImage mask, depth, velocity, normals, output;
static HostBuffer readback;
static VkQueryPool stats;       /* VK_NULL_HANDLE without pipelineStatisticsQuery */
static float sentinel;          /* what the output holds since the last good frame */
static DnsrShadowsDispatch good;

static void upload_inputs(uint32_t mask_bits)
{
    static uint32_t mask_data[TILES_X * TILES_Y];
    static float depth_data[W * H], velocity_data[W * H * 2], normal_data[W * H * 4];
    for (uint32_t i = 0; i < TILES_X * TILES_Y; i++) mask_data[i] = mask_bits;
    for (uint32_t i = 0; i < W * H; i++) {
        depth_data[i] = 0.5f;
        velocity_data[2 * i] = velocity_data[2 * i + 1] = 0.0f;
        normal_data[4 * i] = normal_data[4 * i + 1] = normal_data[4 * i + 3] = 0.0f;
        normal_data[4 * i + 2] = 1.0f;
    }
    host_upload(&host, &mask, mask_data, sizeof mask_data);
    host_upload(&host, &depth, depth_data, sizeof depth_data);
    host_upload(&host, &velocity, velocity_data, sizeof velocity_data);
    host_upload(&host, &normals, normal_data, sizeof normal_data);
}

static void live_context_setup(void)
{
    DNSR_CHECK(dnsr_context_create(&good_info, &ctx));
    host_image_create(&host, &mask, VK_FORMAT_R32_UINT, TILES_X, TILES_Y, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    host_image_create(&host, &depth, VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    host_image_create(&host, &velocity, VK_FORMAT_R32G32_SFLOAT, W, H, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    host_image_create(&host, &normals, VK_FORMAT_R32G32B32A32_SFLOAT, W, H, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    /* Resting in TRANSFER_SRC_OPTIMAL: dnsr moves it to GENERAL and back. */
    host_image_create(&host, &output, VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    host_buffer_create(&host, &readback, host_image_bytes(&output));
    if (host.pipelineStatistics) {
        VkQueryPoolCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
            .queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS,
            .queryCount = 1,
            .pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT,
        };
        VK_CHECK(vkCreateQueryPool(host.device, &info, NULL, &stats));
    }

    memset(&good, 0, sizeof good);
    good.sType = DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH;
    good.hitMaskConvention = DNSR_HIT_MASK_OCCLUDED_BITS;
    good.hitMask = host_image_desc(&mask);
    good.depth = host_image_desc(&depth);
    good.velocity = host_image_desc(&velocity);
    good.normals = host_image_desc(&normals);
    good.output = host_image_desc(&output);
    host_dispatch_neutral(&good);
}

static void live_context_teardown(void)
{
    DNSR_CHECK(dnsr_context_destroy(ctx));
    if (stats) vkDestroyQueryPool(host.device, stats, NULL);
    host_buffer_destroy(&host, &readback);
    HostImage *images[] = {&mask, &depth, &velocity, &normals, &output};
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++) host_image_destroy(&host, images[i]);
}

/* A command buffer whose compute work between probe_begin and probe_end is counted. */
static VkCommandBuffer probe_begin(void)
{
    VkCommandBuffer cmd = host_begin(&host);
    host_cmd_full_barrier(cmd);
    if (stats) {
        vkCmdResetQueryPool(cmd, stats, 0, 1);
        vkCmdBeginQuery(cmd, stats, 0, 0);
    }
    return cmd;
}

/* Submits the probe and checks what ran: with `expect_work`, some compute work and an output of `value`
 * everywhere (which then becomes the sentinel); without, zero compute invocations and the sentinel untouched. */
static void probe_end(VkCommandBuffer cmd, const char *name, bool expect_work, float value)
{
    if (stats) vkCmdEndQuery(cmd, stats, 0);
    host_cmd_copy(cmd, &output, &readback, 0, false);
    host_cmd_host_read_barrier(cmd);
    host_submit(&host, cmd);
    if (stats) {
        uint64_t invocations = 0;
        VK_CHECK(vkGetQueryPoolResults(host.device, stats, 0, 1, sizeof invocations, &invocations, sizeof invocations,
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        if (expect_work)
            CHECK(invocations > 0, "%s: a good frame ran no compute shader invocation", name);
        else
            CHECK(invocations == 0, "%s: %llu compute shader invocations after a refused record", name,
                  (unsigned long long)invocations);
    }
    float want = expect_work ? value : sentinel;
    const float *out = (const float *)readback.mapped;
    for (uint32_t i = 0; i < W * H; i++)
        CHECK(out[i] == want, "%s: output[%u] = %g, want %g%s", name, i, out[i], want,
              expect_work ? "" : " (something ran)");
    sentinel = want;
    host_expect_clean(&host, name);
}

static void good_frame(const char *name, float value)
{
    DnsrShadowsDispatch d = good;
    d.commandBuffer = probe_begin();
    DNSR_CHECK(dnsr_shadows_record(ctx, &d));
    probe_end(d.commandBuffer, name, true, value);
}

/* Records a copy of the good dispatch after the edit statements (which may change `d`, or point `pd` elsewhere)
 * into a probe with `context`; the record must be refused with `want` and the probe must show nothing ran. */
#define RECORD_CASE(name, context, want, mention, ...)                                                            \
    do {                                                                                                          \
        DnsrShadowsDispatch d = good;                                                                             \
        const DnsrShadowsDispatch *pd = &d;                                                                       \
        VkCommandBuffer probe = probe_begin();                                                                    \
        d.commandBuffer = probe;                                                                                  \
        __VA_ARGS__;                                                                                              \
        expect(name, dnsr_shadows_record(context, pd), want, mention);                                           \
        probe_end(probe, name, false, 0.0f);                                                                      \
    } while (0)

#define DISPATCH_CASE(name, want, mention, ...) RECORD_CASE(name, ctx, want, mention, __VA_ARGS__)

/* The good dispatch split into what lights share and one light's fields, for dnsr_lights_record. */
static DnsrShadowsDispatch shared_part(DnsrShadowsDispatch d)
{
    d.hitMask = (DnsrHostImage){0};
    d.output = (DnsrHostImage){0};
    d.lightIndex = 0;
    return d;
}

static DnsrLightDispatch light_part(const DnsrShadowsDispatch *d)
{
    DnsrLightDispatch l = {.sType = DNSR_STRUCTURE_TYPE_LIGHT_DISPATCH, .lightIndex = d->lightIndex, .hitMask = d->hitMask,
                           .output = d->output};
    return l;
}

/* Like RECORD_CASE for dnsr_lights_record: the edit statements may change the shared dispatch `d`, the light
 * list `lights` (one good light, then a copy of it), `count` or point `pl` elsewhere. */
#define LIGHTS_CASE(name, want, mention, ...)                                                                     \
    do {                                                                                                          \
        DnsrShadowsDispatch d = shared_part(good);                                                                \
        DnsrLightDispatch lights[DNSR_MAX_LIGHTS_PER_RECORD + 1];                                                  \
        for (uint32_t i = 0; i <= DNSR_MAX_LIGHTS_PER_RECORD; i++) lights[i] = light_part(&good);                \
        const DnsrLightDispatch *pl = lights;                                                                     \
        uint32_t count = 1;                                                                                       \
        VkCommandBuffer probe = probe_begin();                                                                    \
        d.commandBuffer = probe;                                                                                  \
        __VA_ARGS__;                                                                                              \
        expect(name, dnsr_lights_record(ctx, &d, count, pl), want, mention);                                      \
        probe_end(probe, name, false, 0.0f);                                                                      \
    } while (0)

static void lights_calls(void)
{
    LIGHTS_CASE("lights: lightCount 0", DNSR_ERROR_INVALID_ARGUMENT, "lightCount is 0", count = 0);
    LIGHTS_CASE("lights: lightCount 9", DNSR_ERROR_INVALID_ARGUMENT, "lightCount is 9", count = 9);
    LIGHTS_CASE("lights: NULL pLights", DNSR_ERROR_INVALID_ARGUMENT, "pLights is NULL", pl = NULL);
    LIGHTS_CASE("lights: wrong sType", DNSR_ERROR_INVALID_STRUCTURE, "pLights[0]",
                lights[0].sType = DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH);
    LIGHTS_CASE("lights: unknown light flags", DNSR_ERROR_INVALID_ARGUMENT, "pLights[0].flags has unknown bits 0x10",
                lights[0].flags = 1u << 4);
    LIGHTS_CASE("lights: light 0 twice", DNSR_ERROR_INVALID_ARGUMENT, "pLights[1]: lightIndex is 0 (as pLights[0])",
                count = 2);
    LIGHTS_CASE("lights: lightIndex 1", DNSR_ERROR_INVALID_LIGHT_INDEX, "pLights[0]: light index 1",
                lights[0].lightIndex = 1);
    LIGHTS_CASE("lights: null output view", DNSR_ERROR_NULL_HANDLE, "pLights[0]: output.view",
                lights[0].output.view = VK_NULL_HANDLE);
    LIGHTS_CASE("lights: output in the shared dispatch", DNSR_ERROR_INVALID_ARGUMENT, "shared dispatch of dnsr_lights_record",
                d.output = good.output);
    LIGHTS_CASE("lights: reset in the shared dispatch", DNSR_ERROR_INVALID_ARGUMENT, "reset is true",
                d.flags |= DNSR_DISPATCH_RESET);
    /* The same light, as it should be, records. */
    DnsrShadowsDispatch d = shared_part(good);
    DnsrLightDispatch light = light_part(&good);
    d.commandBuffer = probe_begin();
    DNSR_CHECK(dnsr_lights_record(ctx, &d, 1, &light));
    probe_end(d.commandBuffer, "good one-light dnsr_lights_record", true, 0.0f);
}

static void dispatch_calls(void)
{
    RECORD_CASE("record: NULL pDispatch", ctx, DNSR_ERROR_INVALID_ARGUMENT, "pDispatch is NULL", pd = NULL);
    DISPATCH_CASE("record: wrong sType", DNSR_ERROR_INVALID_STRUCTURE, "pDispatch->sType",
                  d.sType = DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO);
    DISPATCH_CASE("record: non-NULL pNext", DNSR_ERROR_INVALID_STRUCTURE, "pDispatch->pNext", d.pNext = &good);
    DISPATCH_CASE("record: null commandBuffer", DNSR_ERROR_NULL_HANDLE, "commandBuffer", d.commandBuffer = NULL);
    DISPATCH_CASE("record: unknown flags", DNSR_ERROR_INVALID_ARGUMENT, "pDispatch->flags has unknown bits 0x20",
                  d.flags = DNSR_DISPATCH_RESET | (1u << 5));
    DISPATCH_CASE("record: NaN light position", DNSR_ERROR_NON_FINITE, "lightPosition",
                  (d.flags |= DNSR_DISPATCH_USE_LIGHT_POSITION, d.lightPosition[1] = NAN));
    DISPATCH_CASE("record: light position with w 2", DNSR_ERROR_INVALID_ARGUMENT, "w 0",
                  (d.flags |= DNSR_DISPATCH_USE_LIGHT_POSITION, d.lightPosition[1] = 1.0f, d.lightPosition[3] = 2.0f));
    DISPATCH_CASE("record: hitMaskConvention 9", DNSR_ERROR_INVALID_ARGUMENT, "hitMaskConvention 9",
                  d.hitMaskConvention = 9);
    DISPATCH_CASE("record: lightIndex 1", DNSR_ERROR_INVALID_LIGHT_INDEX, "light index 1", d.lightIndex = 1);
    /* The shadow input the context does not take is refused, not ignored; a visibility context needs visibility. */
    DISPATCH_CASE("record: visibility given to a hit-mask context", DNSR_ERROR_INVALID_ARGUMENT,
                  "the context takes a hit mask", d.visibility = d.depth);
    {
        DnsrContextCreateInfo vinfo = good_info;
        vinfo.shadowInput = DNSR_SHADOW_INPUT_VISIBILITY;
        DnsrContext vctx = NULL;
        DNSR_CHECK(dnsr_context_create(&vinfo, &vctx));
        RECORD_CASE("record: visibility context without visibility", vctx, DNSR_ERROR_NULL_HANDLE, "visibility.image",
                    (void)0);
        RECORD_CASE("record: visibility context given a hit mask too", vctx, DNSR_ERROR_INVALID_ARGUMENT,
                    "the context takes per-pixel visibility", d.visibility = d.depth);
        RECORD_CASE("record: integer visibility", vctx, DNSR_ERROR_UNSUPPORTED_FORMAT, "visibility image format",
                    d.visibility = d.depth; d.visibility.format = VK_FORMAT_R32_UINT; d.hitMask = (DnsrHostImage){0});
        dnsr_context_destroy(vctx);
    }
    /* Lights recorded together share one depth copy: every record holds every light of the context. */
    {
        DnsrContextCreateInfo tinfo = good_info;
        tinfo.lightCount = 2;
        tinfo.flags |= DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER;
        DnsrContext tctx = NULL;
        DNSR_CHECK(dnsr_context_create(&tinfo, &tctx));
        RECORD_CASE("record: one of two lights recorded together", tctx, DNSR_ERROR_INVALID_ARGUMENT,
                    "records every light in each record", (void)0);
        dnsr_context_destroy(tctx);
    }
    /* A checkerboard phase is 0 or 1, and only a checkerboard context takes a nonzero one. */
    DISPATCH_CASE("record: checkerboardPhase for a hit-mask context", DNSR_ERROR_INVALID_ARGUMENT,
                  "checkerboardPhase is 1", d.checkerboardPhase = 1);
    {
        DnsrContextCreateInfo cinfo = good_info;
        cinfo.shadowInput = DNSR_SHADOW_INPUT_CHECKERBOARD;
        DnsrContext cctx = NULL;
        DNSR_CHECK(dnsr_context_create(&cinfo, &cctx));
        RECORD_CASE("record: checkerboardPhase 2", cctx, DNSR_ERROR_INVALID_ARGUMENT, "checkerboardPhase is 2",
                    d.checkerboardPhase = 2);
        dnsr_context_destroy(cctx);
    }

    DISPATCH_CASE("record: null hitMask view", DNSR_ERROR_NULL_HANDLE, "hitMask.view", d.hitMask.view = VK_NULL_HANDLE);
    DISPATCH_CASE("record: null depth view", DNSR_ERROR_NULL_HANDLE, "depth.view", d.depth.view = VK_NULL_HANDLE);
    DISPATCH_CASE("record: null velocity view", DNSR_ERROR_NULL_HANDLE, "velocity.view",
                  d.velocity.view = VK_NULL_HANDLE);
    DISPATCH_CASE("record: null normals view", DNSR_ERROR_NULL_HANDLE, "normals.view", d.normals.view = VK_NULL_HANDLE);
    DISPATCH_CASE("record: null output view", DNSR_ERROR_NULL_HANDLE, "output.view", d.output.view = VK_NULL_HANDLE);
    DISPATCH_CASE("record: null output image", DNSR_ERROR_NULL_HANDLE, "output.image", d.output.image = VK_NULL_HANDLE);
    DISPATCH_CASE("record: null hitMask image", DNSR_ERROR_NULL_HANDLE, "hitMask.image",
                  d.hitMask.image = VK_NULL_HANDLE);

    DISPATCH_CASE("record: float hit mask", DNSR_ERROR_UNSUPPORTED_FORMAT, "hitMask image format R32_SFLOAT",
                  d.hitMask.format = VK_FORMAT_R32_SFLOAT);
    DISPATCH_CASE("record: RGBA8 depth", DNSR_ERROR_UNSUPPORTED_FORMAT, "depth image format",
                  d.depth.format = VK_FORMAT_R8G8B8A8_UNORM);
    DISPATCH_CASE("record: one-channel velocity", DNSR_ERROR_UNSUPPORTED_FORMAT, "velocity image format",
                  d.velocity.format = VK_FORMAT_R32_SFLOAT);
    DISPATCH_CASE("record: integer normals", DNSR_ERROR_UNSUPPORTED_FORMAT, "normals image format",
                  d.normals.format = VK_FORMAT_R32G32B32A32_UINT);
    DISPATCH_CASE("record: output format differs from create", DNSR_ERROR_UNSUPPORTED_FORMAT, "differs from the context's outputFormat",
                  d.output.format = VK_FORMAT_R16_SFLOAT);

    DISPATCH_CASE("record: UNDEFINED hitMask layout", DNSR_ERROR_UNSUPPORTED_LAYOUT, "hitMask image layout UNDEFINED",
                  d.hitMask.layout = VK_IMAGE_LAYOUT_UNDEFINED);
    DISPATCH_CASE("record: UNDEFINED depth layout", DNSR_ERROR_UNSUPPORTED_LAYOUT, "depth image layout",
                  d.depth.layout = VK_IMAGE_LAYOUT_UNDEFINED);
    DISPATCH_CASE("record: UNDEFINED velocity layout", DNSR_ERROR_UNSUPPORTED_LAYOUT, "velocity image layout",
                  d.velocity.layout = VK_IMAGE_LAYOUT_UNDEFINED);
    DISPATCH_CASE("record: UNDEFINED normals layout", DNSR_ERROR_UNSUPPORTED_LAYOUT, "normals image layout",
                  d.normals.layout = VK_IMAGE_LAYOUT_UNDEFINED);
    DISPATCH_CASE("record: UNDEFINED output layout", DNSR_ERROR_UNSUPPORTED_LAYOUT, "output image layout",
                  d.output.layout = VK_IMAGE_LAYOUT_UNDEFINED);
    DISPATCH_CASE("record: output in attachment layout", DNSR_ERROR_UNSUPPORTED_LAYOUT, "output image layout",
                  d.output.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);

    DISPATCH_CASE("record: hitMask extent", DNSR_ERROR_IMAGE_EXTENT_MISMATCH, "hitMask image is 5x4 but must be 4x4",
                  d.hitMask.width += 1);
    DISPATCH_CASE("record: depth extent", DNSR_ERROR_IMAGE_EXTENT_MISMATCH, "depth image is 33x16",
                  d.depth.width += 1);
    DISPATCH_CASE("record: velocity extent", DNSR_ERROR_IMAGE_EXTENT_MISMATCH, "velocity image",
                  d.velocity.height += 1);
    DISPATCH_CASE("record: normals extent", DNSR_ERROR_IMAGE_EXTENT_MISMATCH, "normals image", d.normals.width -= 1);
    DISPATCH_CASE("record: output extent", DNSR_ERROR_IMAGE_EXTENT_MISMATCH, "output image", d.output.height = 0);

    /* Penumbra guidance: its inputs are checked only with its flag, and then like the others. */
    DISPATCH_CASE("record: hit distance flag without an image", DNSR_ERROR_NULL_HANDLE, "hitDistance.image",
                  d.flags |= DNSR_DISPATCH_USE_HIT_DISTANCE);
    DISPATCH_CASE("record: integer hit distance", DNSR_ERROR_UNSUPPORTED_FORMAT, "hitDistance image format",
                  d.flags |= DNSR_DISPATCH_USE_HIT_DISTANCE, d.hitDistance = d.hitMask);
    DISPATCH_CASE("record: output is the depth image", DNSR_ERROR_INVALID_ARGUMENT, "output is the depth image",
                  d.output.image = d.depth.image);
    DISPATCH_CASE("record: NaN lightAngularSize", DNSR_ERROR_NON_FINITE, "lightAngularSize",
                  d.flags |= DNSR_DISPATCH_USE_HIT_DISTANCE, d.hitDistance = d.output, d.hitDistance.layout = VK_IMAGE_LAYOUT_GENERAL, d.lightAngularSize = NAN);
    DISPATCH_CASE("record: negative lightAngularSize", DNSR_ERROR_INVALID_ARGUMENT, "lightAngularSize",
                  d.flags |= DNSR_DISPATCH_USE_HIT_DISTANCE, d.hitDistance = d.output, d.hitDistance.layout = VK_IMAGE_LAYOUT_GENERAL, d.lightAngularSize = -0.5f);

    DISPATCH_CASE("record: NaN projectionInverse", DNSR_ERROR_NON_FINITE, "projectionInverse",
                  d.projectionInverse[5] = NAN);
    DISPATCH_CASE("record: NaN reprojectionMatrix", DNSR_ERROR_NON_FINITE, "reprojectionMatrix",
                  d.reprojectionMatrix[15] = NAN);
    DISPATCH_CASE("record: NaN viewProjectionInverse", DNSR_ERROR_NON_FINITE, "viewProjectionInverse",
                  d.viewProjectionInverse[0] = NAN);
    DISPATCH_CASE("record: Inf reprojectionMatrix", DNSR_ERROR_NON_FINITE, "reprojectionMatrix",
                  d.reprojectionMatrix[3] = -INFINITY);
    DISPATCH_CASE("record: Inf eye", DNSR_ERROR_NON_FINITE, "eye", d.eye[1] = INFINITY);
    DISPATCH_CASE("record: NaN motionVectorScale", DNSR_ERROR_NON_FINITE, "motionVectorScale",
                  d.motionVectorScale[0] = NAN);
    DISPATCH_CASE("record: NaN normalsUnpackAdd", DNSR_ERROR_NON_FINITE, "normalsUnpack",
                  d.normalsUnpackAdd = NAN);
    DISPATCH_CASE("record: depthSimilaritySigma 0", DNSR_ERROR_INVALID_ARGUMENT, "depthSimilaritySigma is 0",
                  d.depthSimilaritySigma = 0.0f);
    DISPATCH_CASE("record: depthSimilaritySigma NaN", DNSR_ERROR_NON_FINITE, "depthSimilaritySigma contains NaN",
                  d.depthSimilaritySigma = NAN);

    /* HostSync: dnsr turns it into barriers, so everything the validation layer would reject is refused first. */
    DISPATCH_CASE("record: unknown input stage bit", DNSR_ERROR_INVALID_HOST_SYNC, "sync.inputSrcStages: unknown",
                  d.sync.inputSrcStages = 1u << 30);
    DISPATCH_CASE("record: unknown output access bit", DNSR_ERROR_INVALID_HOST_SYNC, "sync.outputDstAccess: unknown",
                  d.sync.outputDstStages = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
                  d.sync.outputDstAccess = 1u << 29);
    DISPATCH_CASE("record: COLOR_ATTACHMENT_WRITE from FRAGMENT_SHADER", DNSR_ERROR_INVALID_HOST_SYNC,
                  "COLOR_ATTACHMENT_WRITE is not performed by any stage",
                  d.sync.inputSrcStages = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
                  d.sync.inputSrcAccess = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_SHADER_READ_BIT);
    DISPATCH_CASE("record: SHADER_READ by TRANSFER", DNSR_ERROR_INVALID_HOST_SYNC, "sync.outputDstAccess",
                  d.sync.outputDstStages = VK_PIPELINE_STAGE_TRANSFER_BIT;
                  d.sync.outputDstAccess = VK_ACCESS_SHADER_READ_BIT);
    DISPATCH_CASE("record: access without stage", DNSR_ERROR_INVALID_HOST_SYNC, "inputSrcStages is empty",
                  d.sync.inputSrcStages = 0;
                  d.sync.inputSrcAccess = VK_ACCESS_SHADER_WRITE_BIT);
    DnsrEngineImage engine_images[2] = {{DNSR_ENGINE_BINDING_BASE + DNSR_MAX_ENGINE_IMAGES, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL},
                                        {DNSR_ENGINE_BINDING_BASE, VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL}};
    DISPATCH_CASE("record: engine image count without array", DNSR_ERROR_INVALID_ARGUMENT, "pEngineImages is NULL",
                  d.engineImageCount = 1);
    DISPATCH_CASE("record: engine image past the range", DNSR_ERROR_INVALID_ARGUMENT, "engine images are bindings 32..39",
                  d.engineImageCount = 1; d.pEngineImages = &engine_images[0]);
    DnsrEngineImage twice[2] = {engine_images[1], engine_images[1]};
    DISPATCH_CASE("record: engine image given twice", DNSR_ERROR_INVALID_ARGUMENT, "given twice",
                  d.engineImageCount = 2; d.pEngineImages = twice);
    DISPATCH_CASE("record: mesh shader stage", DNSR_ERROR_INVALID_HOST_SYNC, "sync.outputDstStages",
                  d.sync.outputDstStages = VK_PIPELINE_STAGE_MESH_SHADER_BIT_EXT);

    DISPATCH_CASE("record: render rect misaligned x", DNSR_ERROR_INVALID_RENDER_RECT, "x must be a multiple of 8",
                  d.flags = DNSR_DISPATCH_USE_RENDER_RECT;
                  d.renderRect = (DnsrRect){3, 0, 8, 4});
    DISPATCH_CASE("record: render rect misaligned y", DNSR_ERROR_INVALID_RENDER_RECT, "y of 4",
                  d.flags = DNSR_DISPATCH_USE_RENDER_RECT;
                  d.renderRect = (DnsrRect){8, 2, 8, 4});
    DISPATCH_CASE("record: render rect outside", DNSR_ERROR_INVALID_RENDER_RECT, "outside the render size",
                  d.flags = DNSR_DISPATCH_USE_RENDER_RECT;
                  d.renderRect = (DnsrRect){8, 4, W, 4});
    DISPATCH_CASE("record: render rect far outside (overflow)", DNSR_ERROR_INVALID_RENDER_RECT,
                  "outside the render size", d.flags = DNSR_DISPATCH_USE_RENDER_RECT;
                  d.renderRect = (DnsrRect){0xfffffff8u, 0, 16, 4});
    DISPATCH_CASE("record: render rect empty", DNSR_ERROR_INVALID_RENDER_RECT, "zero width or height",
                  d.flags = DNSR_DISPATCH_USE_RENDER_RECT;
                  d.renderRect = (DnsrRect){0, 0, 0, 4});
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Settings and the other calls on a live context                                                                */
/* ------------------------------------------------------------------------------------------------------------- */

#define SETTINGS_CASE(name, want, mention, ...)                                                                   \
    do {                                                                                                          \
        DnsrSettings s = default_settings;                                                                        \
        __VA_ARGS__;                                                                                              \
        expect(name, dnsr_context_set_settings(ctx, &s), want, mention);                                         \
    } while (0)

static void live_context_calls(void)
{
    SETTINGS_CASE("set_settings: filterPasses 0", DNSR_ERROR_INVALID_SETTING, "filterPasses", s.filterPasses = 0);
    SETTINGS_CASE("set_settings: filterPasses 5", DNSR_ERROR_INVALID_SETTING, "filterPasses", s.filterPasses = 5);
    SETTINGS_CASE("set_settings: NaN threshold", DNSR_ERROR_INVALID_SETTING, "disocclusionThresholdFacing",
                  s.disocclusionThresholdFacing = NAN);
    SETTINGS_CASE("set_settings: minCurrentWeight 0", DNSR_ERROR_INVALID_SETTING, "minCurrentWeight",
                  s.minCurrentWeight = 0.0f);
    SETTINGS_CASE("set_settings: negative normalPower", DNSR_ERROR_INVALID_SETTING, "normalPower",
                  s.normalPower = -1.0f);
    SETTINGS_CASE("set_settings: wrong sType", DNSR_ERROR_INVALID_STRUCTURE, "pSettings->sType",
                  s.sType = DNSR_STRUCTURE_TYPE_PASS_TIMINGS);
    SETTINGS_CASE("set_settings: non-NULL pNext", DNSR_ERROR_INVALID_STRUCTURE, "pSettings->pNext", s.pNext = &s);
    expect("set_settings: NULL pSettings", dnsr_context_set_settings(ctx, NULL), DNSR_ERROR_INVALID_ARGUMENT,
           "pSettings is NULL");
    expect("get_settings: NULL pSettings", dnsr_context_get_settings(ctx, NULL), DNSR_ERROR_INVALID_ARGUMENT,
           "pSettings is NULL");

    /* A refused change keeps the old settings. */
    DnsrSettings now;
    memset(&now, 0, sizeof now);
    DNSR_CHECK(dnsr_context_get_settings(ctx, &now));
    CHECK(now.sType == DNSR_STRUCTURE_TYPE_SETTINGS && now.pNext == NULL, "get_settings tags its output");
    CHECK(now.filterPasses == default_settings.filterPasses &&
              now.disocclusionThresholdFacing == default_settings.disocclusionThresholdFacing &&
              now.minCurrentWeight == default_settings.minCurrentWeight &&
              now.normalPower == default_settings.normalPower,
          "refused set_settings changed the settings (filterPasses %u)", now.filterPasses);

    DnsrPassTimings timings;
    memset(&timings, 0, sizeof timings);
    expect("get_timings: wrong sType", dnsr_context_get_timings(ctx, &timings), DNSR_ERROR_INVALID_STRUCTURE,
           "pTimings->sType");
    expect("get_timings: NULL pTimings", dnsr_context_get_timings(ctx, NULL), DNSR_ERROR_INVALID_ARGUMENT, "pTimings");
    timings.sType = DNSR_STRUCTURE_TYPE_PASS_TIMINGS;
    DnsrResult r = dnsr_context_get_timings(ctx, &timings);
    CHECK(r == DNSR_NOT_READY, "get_timings without timestamps: %s", dnsr_result_to_string(r));

    expect("get_memory_usage: NULL pBytes", dnsr_context_get_memory_usage(ctx, NULL), DNSR_ERROR_INVALID_ARGUMENT,
           "pBytes is NULL");
    expect("reset_history: lightIndex 1", dnsr_context_reset_history(ctx, 1), DNSR_ERROR_INVALID_LIGHT_INDEX,
           "light index 1");
    expect("resize: width 0", dnsr_context_resize(ctx, 0, H), DNSR_ERROR_INVALID_EXTENT, "zero width or height");
    expect("resize: height 1<<20", dnsr_context_resize(ctx, W, 1u << 20), DNSR_ERROR_INVALID_EXTENT,
           "exceeds the device limit");
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Handles that are not live contexts                                                                            */
/* ------------------------------------------------------------------------------------------------------------- */

static void handle_calls(void)
{
    const char *dead_msg = "not a live DnsrContext";
    DnsrContext dead = NULL;
    DNSR_CHECK(dnsr_context_create(&good_info, &dead));
    CHECK(dead != NULL, "create returned a NULL context");
    DNSR_CHECK(dnsr_context_destroy(dead));

    RECORD_CASE("destroyed context: record", dead, DNSR_ERROR_INVALID_HANDLE, dead_msg, (void)0);
    expect("destroyed context: resize", dnsr_context_resize(dead, W, H), DNSR_ERROR_INVALID_HANDLE, dead_msg);
    DnsrSettings s = default_settings;
    expect("destroyed context: get_settings", dnsr_context_get_settings(dead, &s), DNSR_ERROR_INVALID_HANDLE, dead_msg);
    expect("destroyed context: set_settings", dnsr_context_set_settings(dead, &s), DNSR_ERROR_INVALID_HANDLE, dead_msg);
    expect("destroyed context: reset_history", dnsr_context_reset_history(dead, 0), DNSR_ERROR_INVALID_HANDLE,
           dead_msg);
    uint64_t bytes = 0;
    expect("destroyed context: get_memory_usage", dnsr_context_get_memory_usage(dead, &bytes),
           DNSR_ERROR_INVALID_HANDLE, dead_msg);
    DnsrPassTimings t;
    memset(&t, 0, sizeof t);
    t.sType = DNSR_STRUCTURE_TYPE_PASS_TIMINGS;
    expect("destroyed context: get_timings", dnsr_context_get_timings(dead, &t), DNSR_ERROR_INVALID_HANDLE, dead_msg);
    expect("destroyed context: destroy again", dnsr_context_destroy(dead), DNSR_ERROR_INVALID_HANDLE, dead_msg);

    DnsrContext made_up = (DnsrContext)(uintptr_t)0xdeadbeefu;
    RECORD_CASE("made-up handle: record", made_up, DNSR_ERROR_INVALID_HANDLE, dead_msg, (void)0);
    expect("made-up handle: destroy", dnsr_context_destroy(made_up), DNSR_ERROR_INVALID_HANDLE, dead_msg);

    /* destroy(NULL) is a no-op success, and a success clears the last error. */
    DnsrResult r = dnsr_context_destroy(NULL);
    const char *msg = dnsr_last_error_message();
    cases++;
    CHECK(r == DNSR_SUCCESS, "destroy(NULL): %s", dnsr_result_to_string(r));
    CHECK(msg != NULL && msg[0] == '\0', "destroy(NULL) left the message \"%s\"", msg ? msg : "(null)");
    printf("  %-46s %-35s (message cleared)\n", "destroy(NULL)", dnsr_result_to_string(r));
}

/* ------------------------------------------------------------------------------------------------------------- */

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    host_create(&host);
    good_info = host_create_info(&host, W, H);
    DNSR_CHECK(dnsr_settings_init_default(&default_settings));

    device_free_calls();
    create_calls();

    live_context_setup();
    upload_inputs(0u); /* all lit (OCCLUDED_BITS convention: no bit set) */
    good_frame("good lit frame", 1.0f);
    /* From here on the inputs say "all shadow": any pass that runs writes 0 and breaks the sentinel 1.0. */
    upload_inputs(0xffffffffu);
    dispatch_calls();
    lights_calls();
    live_context_calls();
    handle_calls();
    /* After all that, the same context still works. */
    good_frame("good shadow frame after the refusals", 0.0f);
    bool proven_by_statistics = stats != VK_NULL_HANDLE;
    live_context_teardown();

    host_expect_clean(&host, "teardown");
    host_destroy(&host);
    printf("bad_input: %u cases run (minimum %u), %s\n", cases, MIN_CASES,
           proven_by_statistics ? "empty command buffers proven by pipeline statistics and the output sentinel"
                 : "empty command buffers proven by the output sentinel");
    CHECK(cases >= MIN_CASES, "only %u cases ran", cases);
    return 0;
}

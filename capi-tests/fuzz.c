/*
 * fuzz: randomized calls of the C API, legal and illegal values mixed, with fixed seeds (printed; rerun one
 * with `fuzz --seed S`).
 *
 * Every call is built from a legal one (real images of the pool below, truthfully described; legal flags,
 * rectangles, floats and DnsrHostSync bits built from Vulkan's "supported access types" table) and then, for
 * most calls, mutated: wrong sType/pNext, null handles, formats and layouts dnsr does not accept for that image,
 * extents other than the render size, images of the wrong format or size, NaN/Inf, out-of-range enums and flag
 * bits, bad render rectangles and light indices, garbage HostSync bits, and legal variations as well. Mutations
 * only lie in ways the header says dnsr must detect: a host that lies undetectably (a format dnsr accepts but
 * that is not the view's) is the host's bug, not dnsr's.
 *
 * Checked for every call:
 *   - no crash (ASan), and the result is DNSR_SUCCESS with an empty dnsr_last_error_message(), or a negative
 *     DnsrResult with a non-empty one (DNSR_NOT_READY from dnsr_context_get_timings only); a refused
 *     dnsr_context_create writes NULL;
 *   - a call with a mutation the header says is an error is refused, and a call the fuzz built legal succeeds;
 *   - a refused dnsr_shadows_record recorded nothing: every record sits in its own pipeline-statistics query,
 *     which must count zero compute invocations for a refused call and some for a successful one;
 *   - a successful record is submitted and executed (records are batched into one command buffer, a full
 *     barrier before each, at most maxFramesInFlight frames of a light per batch), and produces no validation
 *     message (validation layer with synchronization validation; every message fails the test at once, naming
 *     the call that caused it, or the batch if it came at submit).
 * Between records: dnsr_context_create (legal and illegal create infos), resize, set/get_settings,
 * reset_history, get_timings, get_memory_usage and destroy, on live, destroyed and made-up handles.
 * At least MIN_SUCCESS_PERCENT of the records must succeed, so that the fuzz does not only test the front door.
 */
#define _POSIX_C_SOURCE 200809L

#include "host.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* CMakeLists.txt reads this line and runs each seed as a test of its own. */
#define DEFAULT_SEEDS {0x00c0ffeeu, 0x5eed0002u, 0xfa11b4c3u}
#define DEFAULT_RECORDS_PER_SEED 1200u
#define MIN_SUCCESS_PERCENT 20u
#define MAX_CONTEXTS 4
#define MAX_LIGHTS 4u
#define BATCH 64u /* records (and pipeline-statistics queries) per command buffer */
#define DESC_BYTES 512

#ifdef DNSR_MAX_FRAMES_IN_FLIGHT
#define NEW_API 1
#define MAX_FIF DNSR_MAX_FRAMES_IN_FLIGHT
#define DEFAULT_FIF DNSR_DEFAULT_MAX_FRAMES_IN_FLIGHT
#else
#define NEW_API 0
#define MAX_FIF 16u
#define DEFAULT_FIF 3u
#endif

static Host host;
static VkPhysicalDeviceProperties device_props;
static uint32_t queue_family_count;
static bool queue_graphics;

/* ------------------------------------------------------------------------------------------------------------- */
/* Random numbers and bookkeeping                                                                                */
/* ------------------------------------------------------------------------------------------------------------- */

static uint64_t rng_state;

static uint64_t rnd64(void)
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static uint32_t rnd32(void)
{
    return (uint32_t)(rnd64() >> 32);
}

/* Uniform in [0, n). */
static uint32_t rnd(uint32_t n)
{
    return n ? (uint32_t)((rnd64() >> 11) % n) : 0;
}

static bool chance(unsigned percent)
{
    return rnd(100) < percent;
}

static float rnd_unit(void)
{
    return (float)(rnd64() >> 40) / (float)(1u << 24);
}

#define PICK(array) ((array)[rnd((uint32_t)(sizeof(array) / sizeof((array)[0])))])
#define COUNT(array) ((uint32_t)(sizeof(array) / sizeof((array)[0])))

/* What the current call is (for failure messages; '!' marks an illegal value) and whether the header says it
 * must be refused (decided on the final values by the *_legal checks below, not by the mutations applied, since a
 * later legal mutation may undo an earlier illegal one). */
typedef struct Call {
    char desc[DESC_BYTES];
    size_t len;
    bool mustRefuse;
} Call;

static void note(Call *c, bool illegal, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

static void note(Call *c, bool illegal, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    if (c->len + 4 < DESC_BYTES) {
        int n = vsnprintf(c->desc + c->len, DESC_BYTES - c->len, fmt, args);
        if (n > 0) c->len = c->len + (size_t)n < DESC_BYTES ? c->len + (size_t)n : DESC_BYTES - 1;
    }
    va_end(args);
    if (illegal) {
        if (c->len + 2 < DESC_BYTES) {
            c->desc[c->len++] = '!';
            c->desc[c->len] = '\0';
        }
    }
    if (c->len + 2 < DESC_BYTES) {
        c->desc[c->len++] = ' ';
        c->desc[c->len] = '\0';
    }
}

/* note() for calls whose legality is the union of their notes (no later value can undo an earlier one). */
#define NOTE_MUST(c, illegal, ...)                                                                              \
    do {                                                                                                        \
        bool illegal_ = (illegal);                                                                              \
        note((c), illegal_, __VA_ARGS__);                                                                       \
        if (illegal_) (c)->mustRefuse = true;                                                                   \
    } while (0)

static uint32_t current_seed;
/* --lenient: skip the header-oracle checks (accepted illegal calls, refused legal ones) and keep only the
 * invariants (result contract, nothing recorded on refusal, no validation message). */
static bool lenient;
static unsigned calls, successes, refusals, records, record_successes, unexpected_refusals, creates, create_successes;
static unsigned refused_by_code[64];

/* Checks the result contract of the call that just returned (no dnsr call in between: the message is this
 * thread's last). Returns true on success. */
static bool check_result(const Call *c, DnsrResult r, bool not_ready_ok)
{
    const char *msg = dnsr_last_error_message();
    calls++;
    CHECK(msg != NULL, "seed 0x%x: %s: dnsr_last_error_message() returned NULL", current_seed, c->desc);
    if (r == DNSR_SUCCESS || (not_ready_ok && r == DNSR_NOT_READY)) {
        CHECK(msg[0] == '\0', "seed 0x%x: %s: %s left the message \"%s\"", current_seed, c->desc,
              dnsr_result_to_string(r), msg);
        CHECK(lenient || !c->mustRefuse, "seed 0x%x: %s: accepted, but a mutation (marked !) is an error by the header",
              current_seed, c->desc);
        successes++;
        return true;
    }
    CHECK(r < 0, "seed 0x%x: %s: result %d is neither DNSR_SUCCESS nor an error", current_seed, c->desc, (int)r);
    CHECK(msg[0] != '\0', "seed 0x%x: %s: %s with an empty dnsr_last_error_message()", current_seed, c->desc,
          dnsr_result_to_string(r));
    CHECK(strcmp(dnsr_result_to_string(r), "DNSR_RESULT_UNKNOWN") != 0, "seed 0x%x: %s: unknown result %d",
          current_seed, c->desc, (int)r);
    refusals++;
    refused_by_code[-r < 64 ? -r : 63]++;
    if (!c->mustRefuse && !lenient) {
        unexpected_refusals++;
        host_fail(__FILE__, __LINE__, "legal call refused", "seed 0x%x: %s: the fuzz built this call legal, dnsr said %s: %s",
                  current_seed, c->desc, dnsr_result_to_string(r), msg);
    }
    return false;
}

/* Any validation message fails at once, naming the call. */
static void check_clean(const char *what, const char *desc)
{
    if (host.validationMessages != 0)
        host_fail(__FILE__, __LINE__, "no validation message", "seed 0x%x: %u validation message(s) (printed above) %s: %s",
                  current_seed, host.validationMessages, what, desc);
}

/* ------------------------------------------------------------------------------------------------------------- */
/* What the header accepts                                                                                       */
/* ------------------------------------------------------------------------------------------------------------- */

enum Role { MASK, DEPTH, VELOCITY, NORMALS, OUTPUT, ROLES };
static const char *const role_name[ROLES] = {"hitMask", "depth", "velocity", "normals", "output"};

static const VkFormat depth_formats[] = {
    VK_FORMAT_D32_SFLOAT, VK_FORMAT_D16_UNORM, VK_FORMAT_X8_D24_UNORM_PACK32, VK_FORMAT_D24_UNORM_S8_UINT,
    VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_D16_UNORM_S8_UINT, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R16_SFLOAT,
    VK_FORMAT_R16_UNORM,
};
static const VkFormat velocity_formats[] = {
    VK_FORMAT_R16G16_SFLOAT, VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R16G16_SNORM, VK_FORMAT_R16G16B16A16_SFLOAT,
    VK_FORMAT_R32G32B32A32_SFLOAT,
};
static const VkFormat normal_formats[] = {
    VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_SNORM, VK_FORMAT_B8G8R8A8_UNORM,
    VK_FORMAT_A2B10G10R10_UNORM_PACK32, VK_FORMAT_A2R10G10B10_UNORM_PACK32, VK_FORMAT_B10G11R11_UFLOAT_PACK32,
    VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R16G16B16A16_UNORM, VK_FORMAT_R16G16B16A16_SNORM,
    VK_FORMAT_R32G32B32A32_SFLOAT,
};
static const VkFormat output_formats[] = {VK_FORMAT_R8_UNORM, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R32_SFLOAT};
/* Every output format a context takes (the header's DnsrContextCreateInfo::outputFormat); the pool's outputs above
 * are the single-channel ones. */
static const VkFormat accepted_output_formats[] = {VK_FORMAT_R8_UNORM, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R32_SFLOAT,
                                                   VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT};

static bool in_list(VkFormat f, const VkFormat *list, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        if (list[i] == f) return true;
    return false;
}

/* Whether dnsr may accept format f for role r (for the output: the context's format only). */
static bool format_accepted(enum Role r, VkFormat f, VkFormat context_output)
{
    switch (r) {
    case MASK: return f == VK_FORMAT_R32_UINT;
    case DEPTH: return in_list(f, depth_formats, COUNT(depth_formats));
    case VELOCITY: return in_list(f, velocity_formats, COUNT(velocity_formats));
    case NORMALS: return in_list(f, normal_formats, COUNT(normal_formats));
    default: return f == context_output;
    }
}

static bool layout_accepted(enum Role r, VkImageLayout l)
{
    if (l == VK_IMAGE_LAYOUT_GENERAL || l == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL ||
        l == VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL)
        return true;
    if (r == DEPTH)
        return l == VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL || l == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL ||
               l == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL;
    if (r == OUTPUT) return l == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    return false;
}

/* A format value dnsr must refuse for role r: other real formats, and values no format has. */
static VkFormat lie_format(enum Role r, VkFormat context_output)
{
    static const VkFormat candidates[] = {
        VK_FORMAT_UNDEFINED, VK_FORMAT_R8_UNORM, VK_FORMAT_R16_SFLOAT, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32_UINT,
        VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R32G32B32A32_UINT, VK_FORMAT_D32_SFLOAT,
        VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_BC1_RGB_UNORM_BLOCK, VK_FORMAT_R64_SFLOAT, VK_FORMAT_S8_UINT,
        VK_FORMAT_G8_B8_R8_3PLANE_420_UNORM, (VkFormat)1000, (VkFormat)0x7fffffff, (VkFormat)-1,
        (VkFormat)1000156000 /* a YCbCr format */,
    };
    for (;;) {
        VkFormat f = chance(80) ? PICK(candidates) : (VkFormat)rnd32();
        if (!format_accepted(r, f, context_output)) return f;
    }
}

static VkImageLayout lie_layout(enum Role r)
{
    static const VkImageLayout candidates[] = {
        VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_PREINITIALIZED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
        VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
        VK_IMAGE_LAYOUT_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, (VkImageLayout)9,
        (VkImageLayout)0x7fffffff, (VkImageLayout)-5,
    };
    for (;;) {
        VkImageLayout l = chance(85) ? PICK(candidates) : (VkImageLayout)rnd32();
        if (!layout_accepted(r, l)) return l;
    }
}

/* Synchronization-1 stage and access bits (Vulkan 1.0). */
#define CORE_STAGES 0x1ffffu
#define CORE_ACCESS 0x1ffffu
#define SHADER_STAGES                                                                                           \
    (VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT |                 \
     VK_PIPELINE_STAGE_TESSELLATION_EVALUATION_SHADER_BIT | VK_PIPELINE_STAGE_GEOMETRY_SHADER_BIT |            \
     VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT)
#define GRAPHICS_STAGES                                                                                         \
    (VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_VERTEX_INPUT_BIT | VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | \
     VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT | VK_PIPELINE_STAGE_TESSELLATION_EVALUATION_SHADER_BIT |     \
     VK_PIPELINE_STAGE_GEOMETRY_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |                               \
     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |                      \
     VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT)

/* Stages a barrier of this device and queue may name (those whose features the host enabled). */
static VkPipelineStageFlags usable_stages(void)
{
    VkPipelineStageFlags s = CORE_STAGES;
    if (!host.geometryShader) s &= ~(VkPipelineStageFlags)VK_PIPELINE_STAGE_GEOMETRY_SHADER_BIT;
    if (!host.tessellationShader)
        s &= ~(VkPipelineStageFlags)(VK_PIPELINE_STAGE_TESSELLATION_CONTROL_SHADER_BIT |
                                     VK_PIPELINE_STAGE_TESSELLATION_EVALUATION_SHADER_BIT);
    if (!queue_graphics) s &= ~(VkPipelineStageFlags)GRAPHICS_STAGES;
    return s;
}

/* Access bits some stage of `stages` performs (ALL_GRAPHICS/ALL_COMMANDS expanded; TOP/BOTTOM_OF_PIPE none). */
static VkAccessFlags supported_access(VkPipelineStageFlags stages)
{
    VkPipelineStageFlags usable = usable_stages();
    if (stages & VK_PIPELINE_STAGE_ALL_COMMANDS_BIT) stages |= usable;
    if (stages & VK_PIPELINE_STAGE_ALL_GRAPHICS_BIT) stages |= usable & GRAPHICS_STAGES;
    VkAccessFlags a = 0;
    if (stages & VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT) a |= VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    if (stages & VK_PIPELINE_STAGE_VERTEX_INPUT_BIT) a |= VK_ACCESS_INDEX_READ_BIT | VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT;
    if (stages & SHADER_STAGES) a |= VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
    if (stages & VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT) a |= VK_ACCESS_INPUT_ATTACHMENT_READ_BIT;
    if (stages & (VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT))
        a |= VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    if (stages & VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT)
        a |= VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    if (stages & VK_PIPELINE_STAGE_TRANSFER_BIT) a |= VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    if (stages & VK_PIPELINE_STAGE_HOST_BIT) a |= VK_ACCESS_HOST_READ_BIT | VK_ACCESS_HOST_WRITE_BIT;
    if (stages & ~(VkPipelineStageFlags)(VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT | VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT))
        a |= VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
    return a;
}

static bool sync_half_legal(VkPipelineStageFlags stages, VkAccessFlags access)
{
    if (stages & ~usable_stages()) return false;
    if (access & ~(VkAccessFlags)CORE_ACCESS) return false;
    return (access & ~supported_access(stages)) == 0;
}

static bool sync_legal(const DnsrHostSync *s)
{
    return sync_half_legal(s->inputSrcStages, s->inputSrcAccess) &&
           sync_half_legal(s->outputDstStages, s->outputDstAccess);
}

/* A legal (stages, access) pair: a few usable stages, then some of the access bits they support. */
static void legal_sync_half(VkPipelineStageFlags *stages, VkAccessFlags *access)
{
    *stages = 0;
    *access = 0;
    if (chance(15)) return;
    VkPipelineStageFlags usable = usable_stages();
    unsigned n = 1 + rnd(3);
    for (unsigned i = 0; i < n; i++) {
        VkPipelineStageFlags bit = 1u << rnd(17);
        if (usable & bit) *stages |= bit;
    }
    if (*stages == 0) *stages = VK_PIPELINE_STAGE_TRANSFER_BIT;
    VkAccessFlags supported = supported_access(*stages);
    for (unsigned b = 0; b < 17; b++)
        if ((supported & (1u << b)) && chance(30)) *access |= 1u << b;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* The image pool                                                                                                */
/* ------------------------------------------------------------------------------------------------------------- */

typedef struct Size {
    uint32_t width, height;
} Size;

static const Size sizes[] = {{32, 16}, {37, 23}};

typedef struct PoolImage {
    HostImage img;
    enum Role role;
    uint32_t size; /* index into sizes */
} PoolImage;

#define POOL_MAX 64
static PoolImage pool[POOL_MAX];
static uint32_t pool_count;

static void pool_add(enum Role role, uint32_t size, VkFormat format, VkImageLayout layout)
{
    CHECK(pool_count < POOL_MAX, "image pool full");
    uint32_t w = sizes[size].width, h = sizes[size].height;
    if (role == MASK) w = (w + 7) / 8, h = (h + 3) / 4;
    PoolImage *p = &pool[pool_count++];
    host_image_create(&host, &p->img, format, w, h, layout);
    p->role = role;
    p->size = size;
}

/* Few formats per role on purpose: lavapipe compiles a shader variant per combination of image formats a
 * pipeline sees (hundreds of milliseconds each under ASan), while layouts cost nothing. The formats dnsr refuses
 * are covered by the descriptions (lie_format) and by the R32G32B32A32_UINT image below. */
static void pool_create(void)
{
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, general = VK_IMAGE_LAYOUT_GENERAL;
    for (uint32_t s = 0; s < COUNT(sizes); s++) {
        pool_add(MASK, s, VK_FORMAT_R32_UINT, read);
        pool_add(MASK, s, VK_FORMAT_R32_UINT, general);
        pool_add(DEPTH, s, VK_FORMAT_R32_SFLOAT, read);
        pool_add(DEPTH, s, VK_FORMAT_R32_SFLOAT, general);
        pool_add(DEPTH, s, VK_FORMAT_D32_SFLOAT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
        pool_add(VELOCITY, s, VK_FORMAT_R32G32_SFLOAT, read);
        pool_add(VELOCITY, s, VK_FORMAT_R32G32_SFLOAT, general);
        pool_add(NORMALS, s, VK_FORMAT_R32G32B32A32_SFLOAT, read);
        pool_add(NORMALS, s, VK_FORMAT_R32G32B32A32_SFLOAT, general);
        pool_add(OUTPUT, s, VK_FORMAT_R32_SFLOAT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        pool_add(OUTPUT, s, VK_FORMAT_R32_SFLOAT, general);
        pool_add(OUTPUT, s, VK_FORMAT_R32_SFLOAT, read);
        pool_add(OUTPUT, s, VK_FORMAT_R16_SFLOAT, read);
        pool_add(OUTPUT, s, VK_FORMAT_R16_SFLOAT, general);
        pool_add(OUTPUT, s, VK_FORMAT_R8_UNORM, general);
    }
    /* A format no role accepts. */
    pool_add(NORMALS, 0, VK_FORMAT_R32G32B32A32_UINT, read);
}

static bool pool_fits(const PoolImage *p, enum Role role, uint32_t size, VkFormat output_format)
{
    return p->role == role && p->size == size && format_accepted(role, p->img.format, output_format);
}

/* A random pool image that is legal for the role at that size, or NULL if there is none. */
static const PoolImage *pool_pick(enum Role role, uint32_t size, VkFormat output_format)
{
    const PoolImage *fits[POOL_MAX];
    uint32_t n = 0;
    for (uint32_t i = 0; i < pool_count; i++)
        if (pool_fits(&pool[i], role, size, output_format)) fits[n++] = &pool[i];
    return n ? fits[rnd(n)] : NULL;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Contexts and batches                                                                                          */
/* ------------------------------------------------------------------------------------------------------------- */

typedef struct FuzzContext {
    DnsrContext handle;
    uint32_t width, height, lights, fif;
    VkFormat outputFormat;
    DnsrFeatureFlags features;
    uint32_t flags;
    unsigned pending[MAX_LIGHTS]; /* records of each light in the open batch */
} FuzzContext;

static FuzzContext contexts[MAX_CONTEXTS];
static DnsrContext dead_handles[8];
static uint32_t dead_count;
static DnsrSettings default_settings;
static VkQueryPool stats_pool;

typedef struct Batch {
    VkCommandBuffer cmd;
    uint32_t count;
    bool succeeded[BATCH];
    char desc[BATCH][DESC_BYTES];
} Batch;

static Batch batch;

static int size_index(uint32_t w, uint32_t h)
{
    for (uint32_t i = 0; i < COUNT(sizes); i++)
        if (sizes[i].width == w && sizes[i].height == h) return (int)i;
    return -1;
}

static void flush(void)
{
    if (!batch.cmd) return;
    VkCommandBuffer cmd = batch.cmd;
    batch.cmd = VK_NULL_HANDLE;
    host_submit(&host, cmd);
    if (host.validationMessages) {
        for (uint32_t i = 0; i < batch.count; i++)
            fprintf(stderr, "  batch call %u (%s): %s\n", i, batch.succeeded[i] ? "succeeded" : "refused", batch.desc[i]);
        check_clean("at the submit of the batch of these calls", "see above");
    }
    if (batch.count) {
        uint64_t invocations[BATCH];
        VK_CHECK(vkGetQueryPoolResults(host.device, stats_pool, 0, batch.count, sizeof invocations, invocations,
                                       sizeof invocations[0], VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        for (uint32_t i = 0; i < batch.count; i++) {
            if (batch.succeeded[i])
                CHECK(invocations[i] > 0, "seed 0x%x: %s: succeeded but ran no compute shader invocation", current_seed,
                      batch.desc[i]);
            else
                CHECK(invocations[i] == 0, "seed 0x%x: %s: refused but %llu compute shader invocations ran",
                      current_seed, batch.desc[i], (unsigned long long)invocations[i]);
        }
    }
    batch.count = 0;
    for (int i = 0; i < MAX_CONTEXTS; i++) memset(contexts[i].pending, 0, sizeof contexts[i].pending);
}

static VkCommandBuffer batch_cmd(void)
{
    if (!batch.cmd) {
        batch.cmd = host_begin(&host);
        vkCmdResetQueryPool(batch.cmd, stats_pool, 0, BATCH);
        batch.count = 0;
    }
    return batch.cmd;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* dnsr_shadows_record                                                                                           */
/* ------------------------------------------------------------------------------------------------------------- */

static void rnd_matrix(float m[16])
{
    if (chance(50)) {
        for (int i = 0; i < 16; i++) m[i] = (i % 5 == 0) ? 1.0f : 0.0f;
        return;
    }
    for (int i = 0; i < 16; i++) m[i] = (rnd_unit() - 0.5f) * 20.0f;
}

static float rnd_finite_extreme(void)
{
    static const float values[] = {0.0f, -0.0f, 1e-38f, -1e-38f, 1e-45f, 3.4e38f, -3.4e38f, 1e30f, 1.0f, -1.0f};
    return PICK(values);
}

static float rnd_non_finite(void)
{
    static const float values[] = {NAN, -NAN, INFINITY, -INFINITY};
    return PICK(values);
}

static DnsrHostImage desc_of(const PoolImage *p)
{
    return host_image_desc(&p->img);
}

/* Replaces the image of `role` with a pool image of the wrong format or size (described truthfully). */
static bool swap_wrong_image(DnsrShadowsDispatch *d, enum Role role, const FuzzContext *c, Call *call)
{
    int size = size_index(c->width, c->height);
    const PoolImage *cands[POOL_MAX];
    uint32_t n = 0;
    for (uint32_t i = 0; i < pool_count; i++) {
        const PoolImage *p = &pool[i];
        if (p->role == OUTPUT && role != OUTPUT) continue; /* never an output image as an input (aliasing) */
        if (role == OUTPUT && p->role != OUTPUT) continue; /* nor an input as the output */
        bool wrong_format = !format_accepted(role, p->img.format, c->outputFormat);
        bool wrong_size = (int)p->size != size || (role == MASK) != (p->role == MASK);
        if (wrong_format || wrong_size) cands[n++] = p;
    }
    if (n == 0) return false;
    const PoolImage *p = cands[rnd(n)];
    DnsrHostImage *slot = role == MASK ? &d->hitMask
                          : role == DEPTH ? &d->depth
                          : role == VELOCITY ? &d->velocity
                          : role == NORMALS ? &d->normals
                                            : &d->output;
    /* An image already used in another role of this dispatch would alias: only input roles may share. */
    if (role != OUTPUT && p->img.image == d->output.image) return false;
    *slot = desc_of(p);
    note(call, true, "%s=wrong image (%s fmt %d %ux%u)", role_name[role],
         format_accepted(role, p->img.format, c->outputFormat) ? "size" : "format", (int)p->img.format,
         p->img.width, p->img.height);
    return true;
}

static DnsrHostImage *role_slot(DnsrShadowsDispatch *d, enum Role r)
{
    switch (r) {
    case MASK: return &d->hitMask;
    case DEPTH: return &d->depth;
    case VELOCITY: return &d->velocity;
    case NORMALS: return &d->normals;
    default: return &d->output;
    }
}

/* The extent the header requires of a role's image (width or height). */
static uint32_t required_extent(const FuzzContext *c, enum Role r, bool width)
{
    if (r == MASK) return width ? (c->width + 7) / 8 : (c->height + 3) / 4;
    return width ? c->width : c->height;
}

static bool all_finite(const float *v, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(v[i])) return false;
    return true;
}

/* Whether the header allows this record on context c (the images themselves are described truthfully or with
 * values the header refuses). */
static bool dispatch_legal(const DnsrShadowsDispatch *d, const FuzzContext *c)
{
    if (d->sType != DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH || d->pNext != NULL || d->commandBuffer == VK_NULL_HANDLE)
        return false;
    if (d->lightIndex >= c->lights) return false;
    if (d->flags & ~(DnsrDispatchFlags)(DNSR_DISPATCH_RESET | DNSR_DISPATCH_USE_RENDER_RECT | DNSR_DISPATCH_HARD_LIGHT))
        return false;
    if (d->hitMaskConvention > DNSR_HIT_MASK_LIT_BITS || d->debugView > DNSR_DEBUG_VIEW_SAMPLE_RUN) return false;
    for (int r = 0; r < ROLES; r++) {
        const DnsrHostImage *img = role_slot((DnsrShadowsDispatch *)d, (enum Role)r);
        if (img->image == VK_NULL_HANDLE || img->view == VK_NULL_HANDLE) return false;
        if (!format_accepted((enum Role)r, img->format, c->outputFormat) || !layout_accepted((enum Role)r, img->layout))
            return false;
        if (img->width != required_extent(c, (enum Role)r, true) || img->height != required_extent(c, (enum Role)r, false))
            return false;
    }
    if (!all_finite(d->projectionInverse, 16) || !all_finite(d->reprojectionMatrix, 16) ||
        !all_finite(d->viewProjectionInverse, 16) || !all_finite(d->eye, 3) || !all_finite(d->motionVectorScale, 2) ||
        !isfinite(d->normalsUnpackMul) || !isfinite(d->normalsUnpackAdd))
        return false;
    if (!(isfinite(d->depthSimilaritySigma) && d->depthSimilaritySigma > 0)) return false;
    if (d->flags & DNSR_DISPATCH_USE_RENDER_RECT) {
        const DnsrRect *r = &d->renderRect;
        if (r->x % 8 || r->y % 4 || r->width == 0 || r->height == 0) return false;
        if ((uint64_t)r->x + r->width > c->width || (uint64_t)r->y + r->height > c->height) return false;
    }
    return sync_legal(&d->sync);
}

/* One mutation; returns without change when it does not apply. */
static void mutate_dispatch(DnsrShadowsDispatch *d, const FuzzContext *c, Call *call, const DnsrShadowsDispatch **pd)
{
    static DnsrSettings not_a_dispatch;
    enum Role role = (enum Role)rnd(ROLES);
    DnsrHostImage *img = role_slot(d, role);
    uint32_t kind = rnd(40);
    switch (kind) {
    case 0: d->sType = chance(50) ? DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO : rnd32() | 8u; note(call, true, "sType=%u", d->sType); break;
    case 1: d->pNext = &not_a_dispatch; note(call, true, "pNext"); break;
    case 2: d->commandBuffer = VK_NULL_HANDLE; note(call, true, "commandBuffer=NULL"); break;
    case 3: d->lightIndex = c->lights + rnd(chance(50) ? 4 : 0x7fffffffu); note(call, true, "lightIndex=%u", d->lightIndex); break;
    case 4: {
        /* An unknown bit, or USE_HIT_DISTANCE without a hit-distance image (never DNSR_DISPATCH_HARD_LIGHT: legal). */
        uint32_t bit = 2 + rnd(29);
        d->flags |= 1u << (bit >= 3 ? bit + 1 : bit);
        note(call, true, "flags=0x%x", d->flags);
        break;
    }
    case 5: d->hitMaskConvention = 2 + rnd(chance(50) ? 8 : 0x7ffffff0u); note(call, true, "hitMaskConvention=%u", d->hitMaskConvention); break;
    case 6: d->debugView = DNSR_DEBUG_VIEW_SAMPLE_RUN + 1 + rnd(chance(50) ? 8 : 0x7ffffff0u); note(call, true, "debugView=%u", d->debugView); break;
    case 7: img->view = VK_NULL_HANDLE; note(call, true, "%s.view=NULL", role_name[role]); break;
    case 8: img->image = VK_NULL_HANDLE; note(call, true, "%s.image=NULL", role_name[role]); break;
    case 9: case 10: img->format = lie_format(role, c->outputFormat); note(call, true, "%s.format=%d", role_name[role], (int)img->format); break;
    case 11: case 12: img->layout = lie_layout(role); note(call, true, "%s.layout=%d", role_name[role], (int)img->layout); break;
    case 13: {
        bool width = chance(50);
        uint32_t *field = width ? &img->width : &img->height;
        uint32_t want = required_extent(c, role, width);
        do {
            *field = chance(60) ? want + rnd(5) - 2 : rnd32() >> rnd(32);
        } while (*field == want);
        note(call, true, "%s.extent=%ux%u", role_name[role], img->width, img->height);
        break;
    }
    case 14: case 15: swap_wrong_image(d, role, c, call); break;
    case 16: {
        float *m = PICK(((float *[]){d->projectionInverse, d->reprojectionMatrix, d->viewProjectionInverse}));
        m[rnd(16)] = rnd_non_finite();
        note(call, true, "matrix NaN/Inf");
        break;
    }
    case 17: d->eye[rnd(3)] = rnd_non_finite(); note(call, true, "eye NaN/Inf"); break;
    case 18: d->motionVectorScale[rnd(2)] = rnd_non_finite(); note(call, true, "motionVectorScale NaN/Inf"); break;
    case 19: *(chance(50) ? &d->normalsUnpackMul : &d->normalsUnpackAdd) = rnd_non_finite(); note(call, true, "normalsUnpack NaN/Inf"); break;
    case 20: {
        static const float bad[] = {0.0f, -0.0f, -1.0f, -1e-30f, NAN, INFINITY, -INFINITY};
        d->depthSimilaritySigma = PICK(bad);
        note(call, true, "depthSimilaritySigma=%g", d->depthSimilaritySigma);
        break;
    }
    case 21: case 22: {
        /* An illegal render rectangle, used. */
        DnsrRect r = {8 * rnd(c->width / 8 + 1), 4 * rnd(c->height / 4 + 1), 1 + rnd(c->width), 1 + rnd(c->height)};
        switch (rnd(5)) {
        case 0: r.x += 1 + rnd(7); break;
        case 1: r.y += 1 + rnd(3); break;
        case 2: if (chance(50)) r.width = 0; else r.height = 0; break;
        case 3: r.width = c->width - r.x + 1 + rnd(64); break;
        default: r.x = 0xfffffff8u; r.width = 16; break;
        }
        d->renderRect = r;
        d->flags |= DNSR_DISPATCH_USE_RENDER_RECT;
        note(call, true, "renderRect=%u,%u %ux%u", r.x, r.y, r.width, r.height);
        break;
    }
    case 23: case 24: case 25: {
        /* Garbage HostSync: random bits anywhere, or legal stages with accesses they do not perform, or access
         * without stages. Illegal exactly when the table says so. */
        DnsrHostSync s = d->sync;
        VkFlags *fields[] = {&s.inputSrcStages, &s.inputSrcAccess, &s.outputDstStages, &s.outputDstAccess};
        switch (rnd(4)) {
        case 0: *fields[rnd(4)] = rnd32() >> rnd(32); break;
        case 1: *fields[rnd(4)] ^= 1u << rnd(32); break;
        case 2:
            if (chance(50)) s.inputSrcStages = 0, s.inputSrcAccess |= 1u << rnd(17);
            else s.outputDstStages = 0, s.outputDstAccess |= 1u << rnd(17);
            break;
        default: {
            static const VkAccessFlags typical[] = {VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT,
                                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                                                    VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT,
                                                    VK_ACCESS_INDIRECT_COMMAND_READ_BIT};
            static const VkPipelineStageFlags stages[] = {VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                                                          VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
                                                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                                          VK_PIPELINE_STAGE_TRANSFER_BIT,
                                                          VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                                                          VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT};
            s.inputSrcStages = PICK(stages) | (chance(30) ? PICK(stages) : 0);
            s.inputSrcAccess = PICK(typical) | (chance(30) ? PICK(typical) : 0);
            break;
        }
        }
        d->sync = s;
        note(call, !sync_legal(&s), "sync={0x%x,0x%x,0x%x,0x%x}", s.inputSrcStages, s.inputSrcAccess, s.outputDstStages,
             s.outputDstAccess);
        break;
    }
    /* Legal variations from here on. */
    case 26: case 27: legal_sync_half(&d->sync.inputSrcStages, &d->sync.inputSrcAccess);
        legal_sync_half(&d->sync.outputDstStages, &d->sync.outputDstAccess);
        note(call, false, "sync={0x%x,0x%x,0x%x,0x%x}", d->sync.inputSrcStages, d->sync.inputSrcAccess,
             d->sync.outputDstStages, d->sync.outputDstAccess);
        break;
    case 28: d->renderRect = (DnsrRect){rnd32(), rnd32(), rnd32(), rnd32()};
        d->flags &= ~(DnsrDispatchFlags)DNSR_DISPATCH_USE_RENDER_RECT;
        note(call, false, "unused garbage renderRect");
        break;
    case 29: {
        float *f = PICK(((float *[]){&d->projectionInverse[rnd(16)], &d->reprojectionMatrix[rnd(16)],
                                     &d->viewProjectionInverse[rnd(16)], &d->eye[rnd(3)], &d->motionVectorScale[rnd(2)],
                                     &d->normalsUnpackMul, &d->normalsUnpackAdd}));
        *f = rnd_finite_extreme();
        note(call, false, "extreme finite %g", *f);
        break;
    }
    case 30: { static const float good[] = {1e-30f, 1e-6f, 0.01f, 1.0f, 1e6f, 3.4e38f}; d->depthSimilaritySigma = PICK(good); note(call, false, "depthSimilaritySigma=%g", d->depthSimilaritySigma); break; }
    case 31: d->frameIndex = rnd32(); note(call, false, "frameIndex=%u", d->frameIndex); break;
    case 32: d->hitMaskConvention ^= 1u; note(call, false, "hitMaskConvention=%u", d->hitMaskConvention); break;
    case 33: d->flags ^= DNSR_DISPATCH_RESET; note(call, false, "flags=0x%x", d->flags); break;
    case 34: d->debugView = rnd(DNSR_DEBUG_VIEW_SAMPLE_RUN + 1); note(call, false, "debugView=%u", d->debugView); break;
    case 35: { const PoolImage *p = pool_pick(role, (uint32_t)size_index(c->width, c->height), c->outputFormat);
        if (p && (role == OUTPUT || p->img.image != d->output.image)) { *img = desc_of(p); note(call, false, "%s=fmt %d layout %d", role_name[role], (int)p->img.format, (int)p->img.layout); }
        break; }
    case 36: *pd = NULL; note(call, true, "pDispatch=NULL"); break;
    case 37: d->sync = (DnsrHostSync){0, 0, 0, 0}; note(call, false, "sync=0"); break;
    default: /* no change */ break;
    }
}

/* A legal dispatch for context c (its size has pool images). */
static DnsrShadowsDispatch legal_dispatch(const FuzzContext *c, VkCommandBuffer cmd, Call *call)
{
    uint32_t size = (uint32_t)size_index(c->width, c->height);
    DnsrShadowsDispatch d;
    memset(&d, 0, sizeof d);
    d.sType = DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH;
    d.commandBuffer = cmd;
    d.lightIndex = rnd(c->lights);
    d.flags = (chance(20) ? DNSR_DISPATCH_RESET : 0) | (chance(20) ? DNSR_DISPATCH_HARD_LIGHT : 0);
    d.hitMaskConvention = chance(50) ? DNSR_HIT_MASK_OCCLUDED_BITS : DNSR_HIT_MASK_LIT_BITS;
    for (int r = 0; r < ROLES; r++) {
        const PoolImage *p = pool_pick((enum Role)r, size, c->outputFormat);
        CHECK(p != NULL, "no pool image for %s at %ux%u", role_name[r], c->width, c->height);
        *role_slot(&d, (enum Role)r) = desc_of(p);
    }
    d.motionVectorScale[0] = chance(50) ? 1.0f : rnd_unit() * 4 - 2;
    d.motionVectorScale[1] = chance(50) ? 1.0f : rnd_unit() * 4 - 2;
    d.normalsUnpackMul = chance(50) ? 1.0f : 2.0f;
    d.normalsUnpackAdd = d.normalsUnpackMul == 2.0f ? -1.0f : 0.0f;
    for (int i = 0; i < 3; i++) d.eye[i] = rnd_unit() * 10 - 5;
    d.frameIndex = rnd32();
    rnd_matrix(d.projectionInverse);
    rnd_matrix(d.reprojectionMatrix);
    rnd_matrix(d.viewProjectionInverse);
    d.depthSimilaritySigma = chance(70) ? 1.0f : 0.01f + rnd_unit() * 10;
    if (chance(25)) {
        uint32_t x = 8 * rnd((c->width + 7) / 8), y = 4 * rnd((c->height + 3) / 4);
        d.flags |= DNSR_DISPATCH_USE_RENDER_RECT;
        d.renderRect = (DnsrRect){x, y, 1 + rnd(c->width - x), 1 + rnd(c->height - y)};
    }
    if (chance(10)) d.debugView = rnd(DNSR_DEBUG_VIEW_SAMPLE_RUN + 1);
    if (chance(60)) {
        d.sync.inputSrcStages = VK_PIPELINE_STAGE_TRANSFER_BIT;
        d.sync.inputSrcAccess = VK_ACCESS_TRANSFER_WRITE_BIT;
        d.sync.outputDstStages = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
        d.sync.outputDstAccess = VK_ACCESS_SHADER_READ_BIT;
    } else {
        legal_sync_half(&d.sync.inputSrcStages, &d.sync.inputSrcAccess);
        legal_sync_half(&d.sync.outputDstStages, &d.sync.outputDstAccess);
    }
    note(call, false, "light %u flags 0x%x conv %u sync={0x%x,0x%x,0x%x,0x%x}%s;", d.lightIndex, d.flags,
         d.hitMaskConvention, d.sync.inputSrcStages, d.sync.inputSrcAccess, d.sync.outputDstStages,
         d.sync.outputDstAccess, d.flags & DNSR_DISPATCH_USE_RENDER_RECT ? " rect" : "");
    return d;
}

static FuzzContext *random_live_context(void)
{
    FuzzContext *live[MAX_CONTEXTS];
    uint32_t n = 0;
    for (int i = 0; i < MAX_CONTEXTS; i++)
        if (contexts[i].handle) live[n++] = &contexts[i];
    return n ? live[rnd(n)] : NULL;
}

static void record_call(uint32_t iteration)
{
    FuzzContext *c = random_live_context();
    CHECK(c != NULL, "no live context");
    /* A context whose size has no pool images can only be refused: give it a good size first. */
    if (size_index(c->width, c->height) < 0) {
        flush();
        const Size *s = &sizes[rnd(COUNT(sizes))];
        DNSR_CHECK(dnsr_context_resize(c->handle, s->width, s->height));
        c->width = s->width;
        c->height = s->height;
    }
    Call call = {.len = 0};
    note(&call, false, "call %u: record ctx %ux%u fmt %d lights %u fif %u features 0x%x flags 0x%x:", iteration,
         c->width, c->height, (int)c->outputFormat, c->lights, c->fif, c->features, c->flags);

    /* Built with a placeholder command buffer (the batch may have to be flushed first, see below). */
    VkCommandBuffer placeholder = (VkCommandBuffer)(uintptr_t)&call;
    DnsrShadowsDispatch d = legal_dispatch(c, placeholder, &call);
    const DnsrShadowsDispatch *pd = &d;
    DnsrContext handle = c->handle;
    if (chance(55)) {
        unsigned n = 1 + (chance(70) ? 0 : rnd(3));
        for (unsigned i = 0; i < n; i++) mutate_dispatch(&d, c, &call, &pd);
    }
    bool dead = chance(2);
    if (dead) {
        handle = dead_count && chance(50) ? dead_handles[rnd(dead_count)] : (DnsrContext)(uintptr_t)(rnd64() | 1u);
        note(&call, true, "dead/made-up context handle");
    }
    call.mustRefuse = dead || pd == NULL || !dispatch_legal(&d, c);
    /* The contract: at most maxFramesInFlight frames of a light per batch (the batch completes as a whole). */
    if (batch.count == BATCH || c->pending[d.lightIndex < c->lights ? d.lightIndex : 0] >= c->fif) flush();
    VkCommandBuffer cmd = batch_cmd();
    if (d.commandBuffer == placeholder) d.commandBuffer = cmd;

    host_cmd_full_barrier(cmd);
    uint32_t q = batch.count;
    vkCmdBeginQuery(cmd, stats_pool, q, 0);
    DnsrResult r = dnsr_shadows_record(handle, pd);
    bool ok = check_result(&call, r, false);
    vkCmdEndQuery(cmd, stats_pool, q);
    check_clean("recording", call.desc);
    records++;
    if (ok) {
        record_successes++;
        c->pending[d.lightIndex]++;
    }
    batch.succeeded[q] = ok;
    note(&call, false, "-> %s", dnsr_result_to_string(r));
    memcpy(batch.desc[q], call.desc, DESC_BYTES);
    batch.count++;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Settings                                                                                                      */
/* ------------------------------------------------------------------------------------------------------------- */

typedef struct Range {
    const char *name;
    size_t offset;
    float lo, hi;
} Range;

#define RANGE(field, lo, hi) {#field, offsetof(DnsrSettings, field), lo, hi}
static const Range ranges[] = {
    RANGE(disocclusionThresholdFacing, 0, 10), RANGE(disocclusionThresholdGrazing, 0, 10),
    RANGE(disocclusionAngleExponent, 0, 64),   RANGE(spatialFalloff, 0, 100),
    RANGE(historyClampSigmas, 0, 16),          RANGE(historyRejectionFalloff, 1e-3f, 1e6f),
    RANGE(historyRejectionMinSigma, 1e-6f, 1), RANGE(varianceBoostSamples, 0, 1024),
    RANGE(fullHistorySamples, 1, 1024),        RANGE(minCurrentWeight, 1e-3f, 1),
    RANGE(maxHistorySamples, 2, 128),          RANGE(kernelCrossWeight, 0, 1),
    RANGE(normalPower, 0, 256),                RANGE(outputContrast, 1, 4),
    RANGE(minShadowSigma, 1e-6f, 1),
};

static bool settings_legal(const DnsrSettings *s)
{
    if (s->sType != DNSR_STRUCTURE_TYPE_SETTINGS || s->pNext != NULL) return false;
    if (s->filterPasses < 1 || s->filterPasses > 4) return false;
    for (uint32_t i = 0; i < COUNT(ranges); i++) {
        float v;
        memcpy(&v, (const char *)s + ranges[i].offset, sizeof v);
        if (!(v >= ranges[i].lo && v <= ranges[i].hi)) return false;
    }
    return true;
}

/* Settings from the defaults with a few fields changed, legal or not (the header's ranges). */
static DnsrSettings fuzz_settings(Call *call)
{
    DnsrSettings s = default_settings;
    unsigned n = rnd(4);
    for (unsigned i = 0; i < n; i++) {
        uint32_t k = rnd(COUNT(ranges) + 3);
        if (k == COUNT(ranges)) {
            s.filterPasses = chance(70) ? 1 + rnd(4) : (chance(50) ? 0 : 5 + rnd(1000));
            note(call, s.filterPasses < 1 || s.filterPasses > 4, "filterPasses=%u", s.filterPasses);
            continue;
        }
        if (k == COUNT(ranges) + 1) {
            s.sType = chance(50) ? DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH : rnd32();
            note(call, s.sType != DNSR_STRUCTURE_TYPE_SETTINGS, "settings.sType=%u", s.sType);
            continue;
        }
        if (k == COUNT(ranges) + 2) {
            s.pNext = &default_settings;
            note(call, true, "settings.pNext");
            continue;
        }
        const Range *r = &ranges[k];
        float v;
        switch (rnd(6)) {
        case 0: v = r->lo; break;
        case 1: v = r->hi; break;
        case 2: v = r->lo + (r->hi - r->lo) * rnd_unit(); break;
        case 3: v = rnd_non_finite(); break;
        case 4: v = r->lo - (r->lo != 0 ? fabsf(r->lo) * 0.5f : 1e-3f) - rnd_unit(); break;
        default: v = r->hi * (1.5f + rnd_unit()) + 1.0f; break;
        }
        memcpy((char *)&s + r->offset, &v, sizeof v);
        note(call, !(v >= r->lo && v <= r->hi), "%s=%g", r->name, v);
    }
    return s;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* dnsr_context_create and the other context calls                                                               */
/* ------------------------------------------------------------------------------------------------------------- */

static unsigned log_messages;

static void on_log(void *user, DnsrLogLevel level, const char *message)
{
    (void)user, (void)level;
    CHECK(message != NULL, "log callback with a NULL message");
    log_messages++;
}

/* The memory a context of these parameters needs, or UINT64_MAX if dnsr cannot say (illegal parameters). */
static uint64_t memory_need(uint32_t w, uint32_t h, DnsrPrecision p, uint32_t passes, uint32_t lights)
{
    uint64_t bytes = 0;
    if (dnsr_get_memory_requirements(w, h, p, passes, lights, &bytes) != DNSR_SUCCESS) return UINT64_MAX;
    return bytes;
}

static void destroy_context(FuzzContext *c)
{
    flush();
    DNSR_CHECK(dnsr_context_destroy(c->handle));
    if (dead_count < COUNT(dead_handles)) dead_handles[dead_count++] = c->handle;
    else dead_handles[rnd(dead_count)] = c->handle;
    memset(c, 0, sizeof *c);
}

static VkQueueFamilyProperties families[32];
static VkDeviceSize largest_device_heap;

/* Whether the header allows this create info (pSettings and callbacks included) on this device. */
static bool create_legal(const DnsrContextCreateInfo *i)
{
    if (i->sType != DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO || i->pNext != NULL) return false;
    if (!i->instance || !i->physicalDevice || !i->device || !i->vulkanFunctions.vkGetInstanceProcAddr ||
        !i->vulkanFunctions.vkGetDeviceProcAddr)
        return false;
    uint32_t dev = device_props.apiVersion;
    if (VK_API_VERSION_VARIANT(i->apiVersion) != 0 || i->apiVersion < VK_API_VERSION_1_1 ||
        VK_MAKE_API_VERSION(0, VK_API_VERSION_MAJOR(i->apiVersion), VK_API_VERSION_MINOR(i->apiVersion), 0) >
            VK_MAKE_API_VERSION(0, VK_API_VERSION_MAJOR(dev), VK_API_VERSION_MINOR(dev), 0))
        return false;
    if (i->queueFamilyIndex >= queue_family_count || !(families[i->queueFamilyIndex].queueFlags & VK_QUEUE_COMPUTE_BIT))
        return false;
    uint32_t max_dim = device_props.limits.maxImageDimension2D;
    if (i->width == 0 || i->height == 0 || i->width > max_dim || i->height > max_dim) return false;
    if (i->lightCount == 0) return false;
#if NEW_API
    if (i->lightCount > DNSR_MAX_LIGHT_COUNT || i->maxFramesInFlight > DNSR_MAX_FRAMES_IN_FLIGHT) return false;
#endif
    if (i->flags & ~(DnsrContextCreateFlags)(DNSR_CONTEXT_CREATE_DEPTH_INVERTED |
                                              DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS))
        return false;
    if ((i->flags & DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS) && families[i->queueFamilyIndex].timestampValidBits == 0)
        return false;
    if (i->enabledFeatures & ~host.features) return false;
    if (i->precision > DNSR_PRECISION_FP16) return false;
    if (i->precision == DNSR_PRECISION_FP16 && !(i->enabledFeatures & DNSR_FEATURE_FLOAT16)) return false;
    if (!in_list(i->outputFormat, accepted_output_formats, COUNT(accepted_output_formats))) return false;
    if (i->pSettings && !settings_legal(i->pSettings)) return false;
    if (i->pLogCallback && !i->pLogCallback->log) return false;
    uint64_t need = memory_need(i->width, i->height, i->precision, i->pSettings ? i->pSettings->filterPasses : 3,
                                i->lightCount);
    return need <= largest_device_heap;
}

static void create_call(uint32_t iteration, bool must_succeed)
{
    Call call = {.len = 0};
    note(&call, false, "call %u: create", iteration);
    DnsrContextCreateInfo info = host_create_info(&host, 32, 16);
    static DnsrSettings settings;
    static DnsrLogCallback log = {NULL, on_log};
    const Size *s = &sizes[rnd(COUNT(sizes))];
    info.width = s->width;
    info.height = s->height;
    info.enabledFeatures = host.features & rnd32();
    info.outputFormat = chance(80) ? VK_FORMAT_R32_SFLOAT : PICK(output_formats); /* see pool_create */
    info.precision = (info.enabledFeatures & DNSR_FEATURE_FLOAT16) && chance(40) ? DNSR_PRECISION_FP16 : DNSR_PRECISION_FP32;
    info.flags = rnd32() & (DNSR_CONTEXT_CREATE_DEPTH_INVERTED |
                            (chance(30) ? DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS : 0u));
    info.lightCount = 1 + rnd(MAX_LIGHTS);
    if (chance(30)) info.apiVersion = VK_API_VERSION_1_1 + rnd(100); /* 1.1.x: legal, below the host's 1.2 */
#if NEW_API
    info.maxFramesInFlight = chance(30) ? 0 : 1 + rnd(MAX_FIF);
#endif
    if (chance(30)) info.pLogCallback = &log;
    info.pSettings = NULL;
    note(&call, false, "%ux%u features 0x%x fmt %d precision %u flags 0x%x lights %u api 0x%x;", info.width,
         info.height, info.enabledFeatures, (int)info.outputFormat, info.precision, info.flags, info.lightCount,
         info.apiVersion);

    DnsrContextCreateInfo *pinfo = &info;
    DnsrContext *pcontext_out = NULL;
    if (!must_succeed && chance(88)) {
        unsigned n = 1 + (chance(70) ? 0 : rnd(3));
        for (unsigned i = 0; i < n; i++) {
            switch (rnd(27)) {
            case 0: info.sType = DNSR_STRUCTURE_TYPE_SETTINGS; note(&call, true, "sType"); break;
            case 1: info.pNext = &settings; note(&call, true, "pNext"); break;
            case 2: info.instance = VK_NULL_HANDLE; note(&call, true, "instance=NULL"); break;
            case 3: info.physicalDevice = VK_NULL_HANDLE; note(&call, true, "physicalDevice=NULL"); break;
            case 4: info.device = VK_NULL_HANDLE; note(&call, true, "device=NULL"); break;
            case 5: if (chance(50)) info.vulkanFunctions.vkGetInstanceProcAddr = NULL; else info.vulkanFunctions.vkGetDeviceProcAddr = NULL;
                note(&call, true, "vulkanFunctions NULL"); break;
            case 6: {
                uint32_t dev = device_props.apiVersion;
                switch (rnd(4)) {
                case 0: info.apiVersion = VK_MAKE_API_VERSION(0, 1, 0, rnd(1000)); break;
                case 1: info.apiVersion = VK_MAKE_API_VERSION(1 + rnd(7), 1, 2, 0); break;
                case 2: info.apiVersion = VK_MAKE_API_VERSION(0, VK_API_VERSION_MAJOR(dev), VK_API_VERSION_MINOR(dev) + 1 + rnd(5), 0); break;
                default: info.apiVersion = VK_MAKE_API_VERSION(0, VK_API_VERSION_MAJOR(dev) + 1 + rnd(3), 0, 0); break;
                }
                note(&call, true, "apiVersion=0x%x", info.apiVersion);
                break;
            }
            case 7: info.queueFamilyIndex = queue_family_count + rnd(chance(50) ? 4 : 0x7fffffffu);
                note(&call, true, "queueFamilyIndex=%u", info.queueFamilyIndex); break;
            case 8: if (chance(50)) info.width = 0; else info.height = 0; note(&call, true, "extent 0"); break;
            case 9: *(chance(50) ? &info.width : &info.height) = device_props.limits.maxImageDimension2D + 1 + rnd(1u << 20);
                note(&call, true, "extent %ux%u", info.width, info.height); break;
            case 10: info.lightCount = 0; note(&call, true, "lightCount=0"); break;
#if NEW_API
            case 11: info.lightCount = DNSR_MAX_LIGHT_COUNT + 1 + rnd(chance(50) ? 10 : 0x7fffff00u);
                note(&call, true, "lightCount=%u", info.lightCount); break;
            case 12: info.maxFramesInFlight = DNSR_MAX_FRAMES_IN_FLIGHT + 1 + rnd(chance(50) ? 10 : 0x7fffff00u);
                note(&call, true, "maxFramesInFlight=%u", info.maxFramesInFlight); break;
            case 13: /* Far more memory than any device has: refused before allocating. */
                info.width = info.height = device_props.limits.maxImageDimension2D;
                info.lightCount = DNSR_MAX_LIGHT_COUNT;
                note(&call, true, "huge %ux%u x %u lights", info.width, info.height, info.lightCount); break;
#endif
            case 14: info.flags |= 1u << (3 + rnd(29)); note(&call, true, "flags=0x%x", info.flags); break;
            case 15: info.enabledFeatures |= 1u << (3 + rnd(29)); note(&call, true, "features=0x%x", info.enabledFeatures); break;
            case 16: info.precision = 2 + rnd(0x7ffffff0u); note(&call, true, "precision=%u", info.precision); break;
            case 17: if (!(info.enabledFeatures & DNSR_FEATURE_FLOAT16)) { info.precision = DNSR_PRECISION_FP16; note(&call, true, "FP16 without FLOAT16"); } break;
            case 18: info.outputFormat = lie_format(OUTPUT, VK_FORMAT_UNDEFINED);
                if (!in_list(info.outputFormat, accepted_output_formats, COUNT(accepted_output_formats))) note(&call, true, "outputFormat=%d", (int)info.outputFormat);
                else note(&call, false, "outputFormat=%d", (int)info.outputFormat);
                break;
            case 19: case 20: settings = fuzz_settings(&call); info.pSettings = &settings; break;
            case 21: { static DnsrLogCallback no_log = {NULL, NULL}; info.pLogCallback = &no_log; note(&call, true, "log=NULL fn"); break; }
            case 22: pinfo = NULL; note(&call, true, "pCreateInfo=NULL"); break;
            case 25: pcontext_out = (DnsrContext *)&call; note(&call, true, "pContext=NULL"); break;
            case 23: { const Size *t = &sizes[rnd(COUNT(sizes))]; info.width = t->width; info.height = t->height; note(&call, false, "%ux%u", info.width, info.height); break; }
            case 24: info.width = 1 + rnd(64); info.height = 1 + rnd(64); note(&call, false, "%ux%u", info.width, info.height); break;
            default: info.apiVersion = host.apiVersion | rnd(4096); note(&call, false, "apiVersion=0x%x", info.apiVersion); break;
            }
        }
    }
    call.mustRefuse = pinfo == NULL || pcontext_out != NULL || !create_legal(&info);
    /* Never let a create that may succeed allocate much: a legal create of more than 64 MiB is not made. */
    uint32_t passes = info.pSettings ? info.pSettings->filterPasses : 3;
    uint64_t need = memory_need(info.width, info.height, info.precision, passes >= 1 && passes <= 4 ? passes : 3,
                                info.lightCount ? info.lightCount : 1);
    if (!call.mustRefuse && need > (64u << 20)) return;

    /* A free slot (destroying a random context when all are taken, unless the call cannot succeed). */
    int slot = -1;
    for (int i = 0; i < MAX_CONTEXTS && slot < 0; i++)
        if (!contexts[i].handle) slot = i;
    if (slot < 0 && call.mustRefuse) slot = -2;
    if (slot == -1) {
        slot = (int)rnd(MAX_CONTEXTS);
        destroy_context(&contexts[slot]);
    }

    DnsrContext handle = (DnsrContext)(uintptr_t)0x5eed;
    DnsrResult r = dnsr_context_create(pinfo, pcontext_out ? NULL : &handle);
    if (pcontext_out) handle = NULL;
    bool ok = check_result(&call, r, false);
    creates++;
    create_successes += ok;
    check_clean("in dnsr_context_create", call.desc);
    if (!ok) {
        CHECK(handle == NULL, "seed 0x%x: %s: a refused dnsr_context_create must write NULL", current_seed, call.desc);
        return;
    }
    CHECK(slot >= 0 && handle != NULL, "created a context with no slot");
    FuzzContext *c = &contexts[slot];
    memset(c, 0, sizeof *c);
    c->handle = handle;
    c->width = info.width;
    c->height = info.height;
    c->lights = info.lightCount;
    c->outputFormat = info.outputFormat;
    c->features = info.enabledFeatures;
    c->flags = info.flags;
#if NEW_API
    c->fif = info.maxFramesInFlight ? info.maxFramesInFlight : DEFAULT_FIF;
#else
    c->fif = DEFAULT_FIF;
#endif
    /* The pool holds single-channel outputs only: a context writing RGBA (created and checked above) records nothing. */
    if (!in_list(c->outputFormat, output_formats, COUNT(output_formats))) destroy_context(c);
}

static void other_call(uint32_t iteration)
{
    FuzzContext *c = random_live_context();
    Call call = {.len = 0};
    NOTE_MUST(&call, false, "call %u:", iteration);
    DnsrContext handle = c ? c->handle : NULL;
    bool dead = false;
    if (!c || chance(8)) {
        handle = dead_count && chance(60) ? dead_handles[rnd(dead_count)] : (DnsrContext)(uintptr_t)(rnd64() | 1u);
        dead = true;
        NOTE_MUST(&call, true, "dead/made-up handle");
    }
    switch (rnd(7)) {
    case 0: { /* resize */
        uint32_t w, h;
        bool illegal = false;
        if (chance(70)) {
            const Size *s = &sizes[rnd(COUNT(sizes))];
            w = s->width, h = s->height;
        } else if (chance(50)) {
            w = 1 + rnd(64), h = 1 + rnd(64);
        } else {
            w = chance(50) ? 0 : device_props.limits.maxImageDimension2D + 1 + rnd(1000);
            h = 1 + rnd(16);
            if (chance(50)) { uint32_t t = w; w = h; h = t; }
            illegal = true;
        }
        NOTE_MUST(&call, illegal, "resize %ux%u", w, h);
        flush();
        DnsrResult r = dnsr_context_resize(handle, w, h);
        if (check_result(&call, r, false) && !dead) c->width = w, c->height = h;
        break;
    }
    case 1: { /* set_settings */
        NOTE_MUST(&call, false, "set_settings");
        DnsrSettings s = fuzz_settings(&call);
        call.mustRefuse = dead || !settings_legal(&s);
        flush();
        if (chance(5)) {
            NOTE_MUST(&call, true, "NULL");
            call.mustRefuse = true;
            check_result(&call, dnsr_context_set_settings(handle, NULL), false);
        } else {
            check_result(&call, dnsr_context_set_settings(handle, &s), false);
        }
        break;
    }
    case 2: { /* reset_history */
        uint32_t light = chance(80) && c ? rnd(c->lights) : rnd32();
        NOTE_MUST(&call, !c || light >= c->lights, "reset_history %u", light);
        check_result(&call, dnsr_context_reset_history(handle, light), false);
        break;
    }
    case 3: { /* get_settings */
        DnsrSettings s;
        memset(&s, 0, sizeof s);
        bool null = chance(10);
        NOTE_MUST(&call, null, "get_settings%s", null ? " NULL" : "");
        if (check_result(&call, dnsr_context_get_settings(handle, null ? NULL : &s), false))
            CHECK(s.sType == DNSR_STRUCTURE_TYPE_SETTINGS && s.filterPasses >= 1 && s.filterPasses <= 4,
                  "get_settings returned sType %u filterPasses %u", s.sType, s.filterPasses);
        break;
    }
    case 4: { /* get_timings */
        DnsrPassTimings t;
        memset(&t, 0, sizeof t);
        t.sType = chance(90) ? DNSR_STRUCTURE_TYPE_PASS_TIMINGS : rnd32() | 0x100u;
        NOTE_MUST(&call, t.sType != DNSR_STRUCTURE_TYPE_PASS_TIMINGS, "get_timings");
        flush();
        DnsrResult r = dnsr_context_get_timings(handle, &t);
        if (check_result(&call, r, true) && r == DNSR_SUCCESS)
            CHECK(isfinite(t.totalMs) && t.totalMs >= 0, "timings total %g", t.totalMs);
        break;
    }
    case 5: { /* get_memory_usage */
        uint64_t bytes = 0;
        bool null = chance(10);
        NOTE_MUST(&call, null, "get_memory_usage%s", null ? " NULL" : "");
        if (check_result(&call, dnsr_context_get_memory_usage(handle, null ? NULL : &bytes), false))
            CHECK(bytes > 0, "memory usage 0");
        break;
    }
    default: { /* destroy (and a replacement later), or destroy of a dead handle */
        if (dead || !c || chance(60)) {
            if (!dead) {
                handle = dead_count ? dead_handles[rnd(dead_count)] : (DnsrContext)(uintptr_t)0xdeadbeefu;
                NOTE_MUST(&call, true, "dead handle");
            }
            NOTE_MUST(&call, true, "destroy");
            check_result(&call, dnsr_context_destroy(handle), false);
        } else {
            NOTE_MUST(&call, false, "destroy live");
            calls++, successes++;
            destroy_context(c);
        }
        break;
    }
    }
    check_clean("in a context call", call.desc);
}

/* ------------------------------------------------------------------------------------------------------------- */

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void run_seed(uint32_t seed, uint32_t record_count)
{
    current_seed = seed;
    rng_state = seed;
    unsigned records_before = records, successes_before = record_successes, calls_before = calls;
    double start = seconds_now();
    /* Two known-good contexts to start with (push descriptors on and off where the device has them). */
    for (int i = 0; i < 2; i++) create_call(0, true);
    uint32_t iteration = 0;
    while (records - records_before < record_count) {
        iteration++;
        bool any = random_live_context() != NULL;
        uint32_t dice = rnd(100);
        if (!any || dice < 6) create_call(iteration, !any);
        else if (dice < 12) other_call(iteration);
        else record_call(iteration);
    }
    flush();
    for (int i = 0; i < MAX_CONTEXTS; i++)
        if (contexts[i].handle) destroy_context(&contexts[i]);
    dead_count = 0;
    printf("seed 0x%08x: %u calls, %u records of which %u succeeded, %.1f s\n", seed, calls - calls_before,
           records - records_before, record_successes - successes_before, seconds_now() - start);
}

int main(int argc, char **argv)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    uint32_t seeds[16] = DEFAULT_SEEDS;
    uint32_t seed_count = 3, per_seed = DEFAULT_RECORDS_PER_SEED;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
            if (seed_count == 3 && seeds[0] == 0x00c0ffeeu) seed_count = 0;
            if (seed_count < 16) seeds[seed_count++] = (uint32_t)strtoul(argv[++i], NULL, 0);
        } else if (strcmp(argv[i], "--lenient") == 0) {
            lenient = true;
        } else if (strcmp(argv[i], "--records") == 0 && i + 1 < argc) {
            per_seed = (uint32_t)strtoul(argv[++i], NULL, 0);
        } else {
            fprintf(stderr, "usage: fuzz [--seed S]... [--records N] [--lenient]\n");
            return 2;
        }
    }

    HostOptions options;
    memset(&options, 0, sizeof options);
    options.allShaderStages = true; /* every stage the device has may then appear in a legal HostSync */
    host_create_with(&host, &options);
    CHECK(host.pipelineStatistics, "the fuzz proves refused records empty with pipeline statistics queries; %s has no "
          "pipelineStatisticsQuery", host.deviceName);
    vkGetPhysicalDeviceProperties(host.physicalDevice, &device_props);
    vkGetPhysicalDeviceQueueFamilyProperties(host.physicalDevice, &queue_family_count, NULL);
    uint32_t n = queue_family_count < 32 ? queue_family_count : 32;
    vkGetPhysicalDeviceQueueFamilyProperties(host.physicalDevice, &n, families);
    queue_family_count = n;
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(host.physicalDevice, &memory);
    for (uint32_t i = 0; i < memory.memoryHeapCount; i++)
        if ((memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) && memory.memoryHeaps[i].size > largest_device_heap)
            largest_device_heap = memory.memoryHeaps[i].size;
    queue_graphics = (families[host.queueFamily].queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0;
    DNSR_CHECK(dnsr_settings_init_default(&default_settings));
    VkQueryPoolCreateInfo qinfo = {
        .sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
        .queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS,
        .queryCount = BATCH,
        .pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT,
    };
    VK_CHECK(vkCreateQueryPool(host.device, &qinfo, NULL, &stats_pool));
    pool_create();
    host_expect_clean(&host, "setup");

    printf("fuzz: seeds");
    for (uint32_t i = 0; i < seed_count; i++) printf(" 0x%08x", seeds[i]);
    printf(", %u records each (rerun one with: fuzz --seed S)\n", per_seed);
    double start = seconds_now();
    for (uint32_t i = 0; i < seed_count; i++) run_seed(seeds[i], per_seed);

    vkDestroyQueryPool(host.device, stats_pool, NULL);
    for (uint32_t i = 0; i < pool_count; i++) host_image_destroy(&host, &pool[i].img);
    host_destroy(&host);

    printf("fuzz: %u calls, %u succeeded, %u refused (by code:", calls, successes, refusals);
    for (int i = 1; i < 64; i++)
        if (refused_by_code[i]) printf(" %s %u", dnsr_result_to_string(-i), refused_by_code[i]);
    printf("); %u records, %u succeeded (%u%%), all executed; %u creates, %u succeeded; %u log messages; %.1f s\n",
           records, record_successes, records ? 100u * record_successes / records : 0u, creates, create_successes,
           log_messages, seconds_now() - start);
    CHECK(records > 0 && 100u * record_successes >= MIN_SUCCESS_PERCENT * records,
          "only %u of %u records succeeded (want at least %u%%): the fuzz would only test the front door",
          record_successes, records, MIN_SUCCESS_PERCENT);
    return 0;
}

/*
 * full_frame: whole frames through the C API, with every host hook installed.
 *
 * A 37x23 context (odd size: partial 8x4 tiles on both edges), FP32, R32_SFLOAT output, timestamps on:
 *   - an all-lit mask (no bit set in the FidelityFX OCCLUDED_BITS convention), depth 0.5, normals (0,0,1), zero
 *     velocity and identity matrices must give exactly 1.0 everywhere after 3 frames; then an all-shadow mask
 *     exactly 0.0 after 3 more;
 *   - dnsr_context_get_timings: DNSR_NOT_READY before any frame completed, then DNSR_SUCCESS with finite,
 *     non-negative times of the most recent frame;
 *   - dnsr_context_get_memory_usage >= dnsr_get_memory_requirements for the same parameters, and likewise their
 *     persistent parts (dnsr_context_get_persistent_memory_usage, dnsr_get_persistent_memory_requirements), and
 *     dnsr_get_context_memory_requirements of the create info equal to those two;
 *   - pGpuMemoryCallbacks: a tiny allocator (vkAllocateMemory per request) whose live allocations return to 0 at
 *     destroy, with DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY: the persistent images come as
 *     DNSR_RESOURCE_KIND_IMAGE (their bytes are dnsr_context_get_persistent_memory_usage's), the others as
 *     DNSR_RESOURCE_KIND_TRANSIENT_IMAGE; pAllocationCallbacks: counting CPU callbacks that balance by destroy; pLogCallback: a refused call
 *     logs exactly one error with the text of dnsr_last_error_message(); pDebugNameCallback: every name starts
 *     with "dnsr." (and is forwarded to vkSetDebugUtilsObjectNameEXT, as the header suggests).
 * The callback structs live on the stack of the function that creates the context and are wiped right after
 * dnsr_context_create: the header says they are copied.
 * No validation message may appear.
 */
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 37u
#define H 23u
#define TILES_X ((W + 7u) / 8u)
#define TILES_Y ((H + 3u) / 4u)
#define FRAMES_PER_PHASE 3

static Host host;

/* ------------------------------------------------------------------------------------------------------------- */
/* Host hooks                                                                                                    */
/* ------------------------------------------------------------------------------------------------------------- */

/* GPU memory: one vkAllocateMemory per request. */
typedef struct GpuAllocator {
    int live;
    unsigned images, buffers, transientImages;
    uint64_t nextHandle;
    VkDeviceSize bytes, imageBytes;
} GpuAllocator;

static VkResult gpu_allocate(void *user, const VkMemoryRequirements *req, DnsrResourceKind kind,
                             DnsrGpuAllocation *out)
{
    GpuAllocator *a = (GpuAllocator *)user;
    CHECK(kind == DNSR_RESOURCE_KIND_IMAGE || kind == DNSR_RESOURCE_KIND_BUFFER || kind == DNSR_RESOURCE_KIND_TRANSIENT_IMAGE,
          "unknown resource kind %u", kind);
    VkMemoryAllocateInfo info = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = req->size,
        .memoryTypeIndex = host_memory_type(&host, req->memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
    };
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkResult r = vkAllocateMemory(host.device, &info, NULL, &memory);
    if (r != VK_SUCCESS) return r;
    out->memory = memory;
    out->offset = 0;
    out->userHandle = ++a->nextHandle;
    a->live++;
    a->bytes += req->size;
    if (kind == DNSR_RESOURCE_KIND_IMAGE) a->images++, a->imageBytes += req->size;
    else if (kind == DNSR_RESOURCE_KIND_TRANSIENT_IMAGE) a->transientImages++;
    else a->buffers++;
    return VK_SUCCESS;
}

static void gpu_free(void *user, const DnsrGpuAllocation *allocation)
{
    GpuAllocator *a = (GpuAllocator *)user;
    CHECK(allocation->userHandle != 0 && allocation->userHandle <= a->nextHandle, "free of unknown handle %llu",
          (unsigned long long)allocation->userHandle);
    vkFreeMemory(host.device, allocation->memory, NULL);
    a->live--;
}

/* CPU memory for Vulkan objects: malloc with a header in front of the aligned block, counting live blocks. */
typedef struct CpuAllocator {
    long live;
    unsigned long total;
} CpuAllocator;

typedef struct BlockHeader {
    void *raw;
    size_t size;
} BlockHeader;

static void *cpu_block(CpuAllocator *a, size_t size, size_t align)
{
    if (size == 0) return NULL;
    if (align < 16) align = 16; /* keeps the 16-byte header in front of the block aligned */
    char *raw = (char *)malloc(size + align + sizeof(BlockHeader));
    if (raw == NULL) return NULL;
    uintptr_t p = ((uintptr_t)raw + sizeof(BlockHeader) + align - 1) & ~(uintptr_t)(align - 1);
    BlockHeader *h = (BlockHeader *)p - 1;
    h->raw = raw;
    h->size = size;
    a->live++;
    a->total++;
    return (void *)p;
}

static void cpu_release(CpuAllocator *a, void *p)
{
    if (p == NULL) return;
    BlockHeader *h = (BlockHeader *)p - 1;
    free(h->raw);
    a->live--;
}

static VKAPI_ATTR void *VKAPI_CALL cpu_allocate(void *user, size_t size, size_t align, VkSystemAllocationScope scope)
{
    (void)scope;
    return cpu_block((CpuAllocator *)user, size, align);
}

static VKAPI_ATTR void *VKAPI_CALL cpu_reallocate(void *user, void *orig, size_t size, size_t align,
                                                  VkSystemAllocationScope scope)
{
    CpuAllocator *a = (CpuAllocator *)user;
    (void)scope;
    if (orig == NULL) return cpu_block(a, size, align);
    if (size == 0) {
        cpu_release(a, orig);
        return NULL;
    }
    void *p = cpu_block(a, size, align);
    if (p == NULL) return NULL;
    size_t old = ((BlockHeader *)orig - 1)->size;
    memcpy(p, orig, old < size ? old : size);
    cpu_release(a, orig);
    return p;
}

static VKAPI_ATTR void VKAPI_CALL cpu_free(void *user, void *p)
{
    cpu_release((CpuAllocator *)user, p);
}

typedef struct LogCapture {
    unsigned count;
    DnsrLogLevel level;
    char text[1024];
} LogCapture;

static void on_log(void *user, DnsrLogLevel level, const char *message)
{
    LogCapture *l = (LogCapture *)user;
    l->count++;
    l->level = level;
    snprintf(l->text, sizeof l->text, "%s", message ? message : "(null)");
}

typedef struct Names {
    unsigned count;
    unsigned bad;
    char example[128];
    char firstBad[128];
} Names;

static void on_name(void *user, VkObjectType type, uint64_t handle, const char *name)
{
    Names *n = (Names *)user;
    n->count++;
    if (name == NULL || strncmp(name, "dnsr.", 5) != 0 || handle == 0 || type == VK_OBJECT_TYPE_UNKNOWN) {
        if (n->bad++ == 0) snprintf(n->firstBad, sizeof n->firstBad, "%s (type %d)", name ? name : "(null)", (int)type);
        return;
    }
    if (n->count == 1) snprintf(n->example, sizeof n->example, "%s", name);
    if (host.setObjectName) {
        VkDebugUtilsObjectNameInfoEXT info = {
            .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT,
            .objectType = type,
            .objectHandle = handle,
            .pObjectName = name,
        };
        VK_CHECK(host.setObjectName(host.device, &info));
    }
}

static GpuAllocator gpu_allocator;
static CpuAllocator cpu_allocator;
static LogCapture log_capture;
static Names names;
/* The CPU callbacks must outlive the context (the header says so); the other callback structs are copied. */
static VkAllocationCallbacks cpu_callbacks;

/* What dnsr_get_context_memory_requirements said of the create info, before the context existed. */
static uint64_t create_info_required, create_info_kept;

static DnsrContext create_context(void)
{
    cpu_callbacks = (VkAllocationCallbacks){
        .pUserData = &cpu_allocator,
        .pfnAllocation = cpu_allocate,
        .pfnReallocation = cpu_reallocate,
        .pfnFree = cpu_free,
    };
    DnsrGpuMemoryCallbacks gpu = {&gpu_allocator, gpu_allocate, gpu_free};
    DnsrLogCallback log = {&log_capture, on_log};
    DnsrDebugNameCallback namer = {&names, on_name};

    DnsrContextCreateInfo info = host_create_info(&host, W, H);
    /* The host may alias the transient images' memory: they come as DNSR_RESOURCE_KIND_TRANSIENT_IMAGE. */
    info.flags = DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS | DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY;
    info.pAllocationCallbacks = &cpu_callbacks;
    info.pGpuMemoryCallbacks = &gpu;
    info.pLogCallback = &log;
    info.pDebugNameCallback = &namer;

    DNSR_CHECK(dnsr_get_context_memory_requirements(&info, &create_info_required, &create_info_kept));
    DnsrContext ctx = NULL;
    DNSR_CHECK(dnsr_context_create(&info, &ctx));
    CHECK(ctx != NULL, "dnsr_context_create succeeded with a NULL context");
    /* Copied at creation: wiping them must not matter. */
    memset(&gpu, 0, sizeof gpu);
    memset(&log, 0, sizeof log);
    memset(&namer, 0, sizeof namer);
    memset(&info, 0, sizeof info);
    return ctx;
}

/* ------------------------------------------------------------------------------------------------------------- */
/* Frames                                                                                                        */
/* ------------------------------------------------------------------------------------------------------------- */

static HostImage mask, depth, velocity, normals, output;
static HostBuffer readback;

static void create_images(void)
{
    VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    host_image_create(&host, &mask, VK_FORMAT_R32_UINT, TILES_X, TILES_Y, read);
    host_image_create(&host, &depth, VK_FORMAT_R32_SFLOAT, W, H, read);
    host_image_create(&host, &velocity, VK_FORMAT_R32G32_SFLOAT, W, H, read);
    host_image_create(&host, &normals, VK_FORMAT_R32G32B32A32_SFLOAT, W, H, read);
    /* Resting in TRANSFER_SRC_OPTIMAL: dnsr moves it to GENERAL and back. */
    host_image_create(&host, &output, VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    host_buffer_create(&host, &readback, host_image_bytes(&output));

    static float depth_data[W * H], velocity_data[W * H * 2], normal_data[W * H * 4];
    for (uint32_t i = 0; i < W * H; i++) {
        depth_data[i] = 0.5f;
        normal_data[4 * i + 2] = 1.0f; /* (0, 0, 1, 0); the rest stays 0 like the velocity */
    }
    host_upload(&host, &depth, depth_data, sizeof depth_data);
    host_upload(&host, &velocity, velocity_data, sizeof velocity_data);
    host_upload(&host, &normals, normal_data, sizeof normal_data);
}

static void destroy_images(void)
{
    host_buffer_destroy(&host, &readback);
    HostImage *images[] = {&mask, &depth, &velocity, &normals, &output};
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++) host_image_destroy(&host, images[i]);
}

static void upload_mask(uint32_t bits)
{
    static uint32_t data[TILES_X * TILES_Y];
    for (uint32_t i = 0; i < TILES_X * TILES_Y; i++) data[i] = bits;
    host_upload(&host, &mask, data, sizeof data);
}

static DnsrShadowsDispatch dispatch(VkCommandBuffer cmd, uint32_t frame)
{
    DnsrShadowsDispatch d = host_dispatch(cmd, &mask, &depth, &velocity, &normals, &output);
    d.frameIndex = frame;
    return d;
}

/* Records one frame, submits it, waits, and returns the output (W*H floats, in `out`). */
static void run_frame(DnsrContext ctx, uint32_t frame, float *out)
{
    VkCommandBuffer cmd = host_begin(&host);
    host_cmd_full_barrier(cmd);
    DnsrShadowsDispatch d = dispatch(cmd, frame);
    DNSR_CHECK(dnsr_shadows_record(ctx, &d));
    host_cmd_copy(cmd, &output, &readback, 0, false);
    host_cmd_host_read_barrier(cmd);
    host_submit(&host, cmd);
    memcpy(out, readback.mapped, W * H * sizeof(float));
}

static void expect_everywhere(const float *out, float want, const char *phase)
{
    float lo = out[0], hi = out[0];
    for (uint32_t i = 0; i < W * H; i++) {
        lo = out[i] < lo ? out[i] : lo;
        hi = out[i] > hi ? out[i] : hi;
    }
    printf("%s: output in [%g, %g]\n", phase, lo, hi);
    for (uint32_t i = 0; i < W * H; i++)
        CHECK(out[i] == want, "%s: output at (%u, %u) = %.9g, want exactly %g", phase, i % W, i / W, out[i], want);
}

static void check_timings(DnsrContext ctx, uint64_t frames)
{
    DnsrPassTimings t;
    memset(&t, 0, sizeof t);
    t.sType = DNSR_STRUCTURE_TYPE_PASS_TIMINGS;
    DNSR_CHECK(dnsr_context_get_timings(ctx, &t));
    printf("timings of frame %llu: prepare %.3f ms, tile classification %.3f ms, filter %.3f/%.3f/%.3f/%.3f ms (%u "
           "passes), total %.3f ms\n",
           (unsigned long long)t.frame, t.prepareMs, t.tileClassificationMs, t.filterMs[0], t.filterMs[1],
           t.filterMs[2], t.filterMs[3], t.filterPasses, t.totalMs);
    CHECK(t.frame == frames, "timings of frame %llu, want the latest completed frame %llu", (unsigned long long)t.frame,
          (unsigned long long)frames);
    DnsrSettings s;
    DNSR_CHECK(dnsr_context_get_settings(ctx, &s));
    CHECK(t.filterPasses == s.filterPasses && t.filterPasses == 2, "filterPasses %u (the default's: %u)", t.filterPasses,
          s.filterPasses);
    double all[] = {t.prepareMs, t.tileClassificationMs, t.filterMs[0], t.filterMs[1], t.filterMs[2], t.filterMs[3],
                    t.totalMs};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        CHECK(isfinite(all[i]) && all[i] >= 0.0, "timing %zu is %g", i, all[i]);
    CHECK(t.filterMs[2] == 0.0 && t.filterMs[3] == 0.0, "unused filter passes timed %g and %g ms", t.filterMs[2],
          t.filterMs[3]);
}

/* ------------------------------------------------------------------------------------------------------------- */

/* A refused call logs exactly one error, with the text dnsr_last_error_message() gives. */
static void check_log_of_refused_call(const char *what, DnsrResult r, DnsrResult want, unsigned before)
{
    const char *msg = dnsr_last_error_message();
    CHECK(r == want, "%s: %s, want %s", what, dnsr_result_to_string(r), dnsr_result_to_string(want));
    CHECK(log_capture.count == before + 1, "%s: %u log messages, want exactly 1", what, log_capture.count - before);
    CHECK(log_capture.level == DNSR_LOG_LEVEL_ERROR, "%s: log level %u", what, log_capture.level);
    CHECK(strcmp(log_capture.text, msg) == 0, "%s: logged \"%s\" but dnsr_last_error_message() is \"%s\"", what,
          log_capture.text, msg);
    printf("%s: logged \"%s\"\n", what, log_capture.text);
}

int main(void)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    host_create(&host);

    DnsrContext ctx = create_context();
    printf("created %ux%u: %u debug names (e.g. %s), %u GPU allocations (%u images, %u buffers, %llu bytes), %lu CPU "
           "allocations\n",
           W, H, names.count, names.example, gpu_allocator.live >= 0 ? (unsigned)gpu_allocator.live : 0u,
           gpu_allocator.images, gpu_allocator.buffers, (unsigned long long)gpu_allocator.bytes, cpu_allocator.total);
    CHECK(names.count > 0, "pDebugNameCallback was never called");
    CHECK(names.bad == 0, "%u debug names do not start with \"dnsr.\" (first: %s)", names.bad, names.firstBad);
    CHECK(gpu_allocator.images > 0 && gpu_allocator.buffers > 0, "GPU allocator saw %u images, %u buffers",
          gpu_allocator.images, gpu_allocator.buffers);
    CHECK(cpu_allocator.total > 0, "pAllocationCallbacks were never used");
    CHECK(log_capture.count == 0, "a successful create logged \"%s\"", log_capture.text);

    DnsrPassTimings early;
    memset(&early, 0, sizeof early);
    early.sType = DNSR_STRUCTURE_TYPE_PASS_TIMINGS;
    DnsrResult r = dnsr_context_get_timings(ctx, &early);
    CHECK(r == DNSR_NOT_READY, "timings before any frame: %s", dnsr_result_to_string(r));

    uint64_t usage = 0, required = 0;
    DNSR_CHECK(dnsr_context_get_memory_usage(ctx, &usage));
    DNSR_CHECK(dnsr_get_memory_requirements(W, H, DNSR_PRECISION_FP32, 3, 1, &required));
    printf("memory: usage %llu bytes >= requirements %llu bytes (GPU allocator handed out %llu)\n",
           (unsigned long long)usage, (unsigned long long)required, (unsigned long long)gpu_allocator.bytes);
    CHECK(usage >= required, "usage %llu < requirements %llu", (unsigned long long)usage, (unsigned long long)required);
    CHECK(gpu_allocator.bytes >= usage, "the allocator handed out %llu bytes, dnsr reports %llu",
          (unsigned long long)gpu_allocator.bytes, (unsigned long long)usage);
    uint64_t kept = 0, keptRequired = 0;
    DNSR_CHECK(dnsr_context_get_persistent_memory_usage(ctx, &kept));
    DNSR_CHECK(dnsr_get_persistent_memory_requirements(W, H, DNSR_PRECISION_FP32, 1, &keptRequired));
    printf("memory kept between records: %llu bytes (requirements %llu)\n", (unsigned long long)kept,
           (unsigned long long)keptRequired);
    CHECK(kept >= keptRequired && kept < usage, "persistent %llu (requirements %llu) of %llu", (unsigned long long)kept,
          (unsigned long long)keptRequired, (unsigned long long)usage);
    /* One light, a hit mask: the create info's requirements are the size's. */
    CHECK(create_info_required == required && create_info_kept == keptRequired,
          "dnsr_get_context_memory_requirements: %llu and %llu kept, the size's %llu and %llu",
          (unsigned long long)create_info_required, (unsigned long long)create_info_kept, (unsigned long long)required,
          (unsigned long long)keptRequired);
    CHECK(gpu_allocator.imageBytes == kept && gpu_allocator.transientImages > 0,
          "the allocator saw %llu bytes of persistent images (dnsr keeps %llu) and %u transient images",
          (unsigned long long)gpu_allocator.imageBytes, (unsigned long long)kept, gpu_allocator.transientImages);

    create_images();
    static float out[W * H];
    uint32_t frame = 0;

    upload_mask(0u); /* no occluded bit: all lit */
    for (int i = 0; i < FRAMES_PER_PHASE; i++) run_frame(ctx, ++frame, out);
    expect_everywhere(out, 1.0f, "all lit, 3 frames");
    check_timings(ctx, frame);

    upload_mask(0xffffffffu); /* every ray occluded */
    for (int i = 0; i < FRAMES_PER_PHASE; i++) run_frame(ctx, ++frame, out);
    expect_everywhere(out, 0.0f, "all shadow, 3 more frames");
    check_timings(ctx, frame);

    /* Logging: each refused call logs once; a successful one logs nothing. */
    unsigned before = log_capture.count;
    DnsrSettings s;
    DNSR_CHECK(dnsr_context_get_settings(ctx, &s));
    s.filterPasses = 0;
    r = dnsr_context_set_settings(ctx, &s);
    check_log_of_refused_call("refused set_settings", r, DNSR_ERROR_INVALID_SETTING, before);
    before = log_capture.count;
    VkCommandBuffer cmd = host_begin(&host);
    DnsrShadowsDispatch d = dispatch(cmd, ++frame);
    d.lightIndex = 1;
    r = dnsr_shadows_record(ctx, &d);
    check_log_of_refused_call("refused record", r, DNSR_ERROR_INVALID_LIGHT_INDEX, before);
    host_submit(&host, cmd); /* empty */
    before = log_capture.count;
    DNSR_CHECK(dnsr_context_reset_history(ctx, 0));
    CHECK(log_capture.count == before, "a successful call logged \"%s\"", log_capture.text);

    DNSR_CHECK(dnsr_context_destroy(ctx));
    printf("after destroy: %d live GPU allocations, %ld live CPU allocations (of %lu)\n", gpu_allocator.live,
           cpu_allocator.live, cpu_allocator.total);
    CHECK(gpu_allocator.live == 0, "%d GPU allocations still live after destroy", gpu_allocator.live);
    CHECK(cpu_allocator.live == 0, "%ld CPU allocations still live after destroy", cpu_allocator.live);

    destroy_images();
    host_expect_clean(&host, "full_frame");
    host_destroy(&host);
    printf("full_frame: ok\n");
    return 0;
}

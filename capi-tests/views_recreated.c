/*
 * views_recreated: the host's image views live for one frame only, without push descriptors.
 *
 * A render graph with transient resources creates its images and views for a frame and destroys them once the
 * GPU is done with that frame; the driver may then hand back the same handle values for the next frame's new
 * objects. dnsr must not keep descriptor sets keyed on those handle values (a set written for a destroyed view
 * is stale even when a new view has the same value), nor run out of sets: the header's contract is that the
 * host may destroy its views once the command buffer that used them completed, and create fresh ones every
 * frame, forever, as long as frame N of a light completed before frame N + maxFramesInFlight is recorded.
 *
 * 10,000 frames of a 16x8 context (one light, DNSR_FEATURE_PUSH_DESCRIPTOR off). Every frame has its own fresh
 * VkDeviceMemory, VkImages and VkImageViews (hit mask, depth, velocity, normals, output), filled by clears: the
 * hit mask is all-lit or all-shadowed (a fixed pseudo-random sequence), the output starts at a sentinel 0.25.
 * Every frame is recorded with DNSR_DISPATCH_RESET, so its output must be exactly 1 (lit) or 0 (shadowed)
 * everywhere; every frame's output is read back and checked. Frames go in batches of maxFramesInFlight per
 * command buffer (each frame with its own objects); after the batch completed, its objects are destroyed.
 *
 * Modes (argv[1]), one CTest entry each:
 *   validation  the validation layer with synchronization validation (host.c's default); the layer wraps
 *               handles, so values never repeat here, but it sees every use of a destroyed view.
 *   no-layers   no layer at all: the application sees lavapipe's handles (heap addresses), and the test
 *               prints how often a new view or image got a handle value seen before.
 *   planted     the views are created with VkAllocationCallbacks that hand out a fixed set of static blocks,
 *               first free block first. lavapipe allocates its view objects through pAllocator and uses the
 *               object's address as the handle, so every view of a batch gets the handle value of the view in
 *               the same position of the previous batch, which was destroyed just before. The validation layer
 *               runs with its unique-handle wrapping off, so it sees those repeated values too, and reports any
 *               descriptor set that still points at a destroyed view. The test fails if the values did not
 *               actually repeat (the planting must not silently stop working).
 * Options after the mode: --frames N (default 10000), --frames-in-flight N (maxFramesInFlight; default 0, i.e.
 * DNSR_DEFAULT_MAX_FRAMES_IN_FLIGHT; the batch size is the effective value).
 */
#define _POSIX_C_SOURCE 200809L /* posix_memalign, clock_gettime */

#include "host.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define W 16u
#define H 8u
#define TILES_X ((W + 7u) / 8u)
#define TILES_Y ((H + 3u) / 4u)
#define IMAGES_PER_FRAME 5u
#define SENTINEL 0.25f

#ifdef DNSR_MAX_FRAMES_IN_FLIGHT
#define MAX_BATCH DNSR_MAX_FRAMES_IN_FLIGHT
#define DEFAULT_FRAMES_IN_FLIGHT DNSR_DEFAULT_MAX_FRAMES_IN_FLIGHT
#else
/* A header from before DnsrContextCreateInfo.maxFramesInFlight: batches of 3 (what the default will be). */
#define MAX_BATCH 16u
#define DEFAULT_FRAMES_IN_FLIGHT 3u
#endif

enum Role { MASK, DEPTH, VELOCITY, NORMALS, OUTPUT };

static const VkFormat role_format[IMAGES_PER_FRAME] = {
    VK_FORMAT_R32_UINT, VK_FORMAT_R32_SFLOAT, VK_FORMAT_R32G32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT,
    VK_FORMAT_R32_SFLOAT,
};

static Host host;

/* ------------------------------------------------------------------------------------------------------------- */
/* Handle values seen so far (an open-addressing set of uint64)                                                  */
/* ------------------------------------------------------------------------------------------------------------- */

typedef struct HandleSet {
    uint64_t *slots;
    size_t capacity, count;
} HandleSet;

static size_t hash_handle(uint64_t v)
{
    v ^= v >> 33;
    v *= 0xff51afd7ed558ccdull;
    v ^= v >> 33;
    return (size_t)v;
}

/* Adds v; returns true if it was already there. */
static bool handle_set_add(HandleSet *s, uint64_t v)
{
    if (2 * (s->count + 1) > s->capacity) {
        HandleSet bigger = {calloc(s->capacity ? 2 * s->capacity : 1024, sizeof(uint64_t)),
                            s->capacity ? 2 * s->capacity : 1024, 0};
        CHECK(bigger.slots != NULL, "out of memory");
        for (size_t i = 0; i < s->capacity; i++)
            if (s->slots[i]) handle_set_add(&bigger, s->slots[i]);
        free(s->slots);
        *s = bigger;
    }
    for (size_t i = hash_handle(v) & (s->capacity - 1);; i = (i + 1) & (s->capacity - 1)) {
        if (s->slots[i] == v) return true;
        if (s->slots[i] == 0) {
            s->slots[i] = v;
            s->count++;
            return false;
        }
    }
}

/* ------------------------------------------------------------------------------------------------------------- */
/* The planted allocator: static blocks, first free block first                                                  */
/* ------------------------------------------------------------------------------------------------------------- */

#define PLANTED_BLOCKS (IMAGES_PER_FRAME * MAX_BATCH)
#define PLANTED_BLOCK_BYTES 4096u
#define PLANTED_ALIGN 64u

typedef struct Planted {
    _Alignas(PLANTED_ALIGN) unsigned char blocks[PLANTED_BLOCKS][PLANTED_BLOCK_BYTES];
    bool used[PLANTED_BLOCKS];
    unsigned long planted;  /* allocations served from a block */
    unsigned long fallback; /* allocations that did not fit (too big, too aligned, or every block in use) */
    long liveFallback;
} Planted;

static Planted planted;

static int planted_block_of(const void *p)
{
    uintptr_t c = (uintptr_t)p, base = (uintptr_t)planted.blocks;
    if (c < base || c >= base + sizeof planted.blocks) return -1;
    return (int)((c - base) / PLANTED_BLOCK_BYTES);
}

/* Fallback blocks carry their size in a header in front of the aligned pointer. */
static void *fallback_alloc(size_t size, size_t align)
{
    size_t header = align < 16 ? 16 : align;
    unsigned char *raw = NULL;
    if (posix_memalign((void **)&raw, header, header + size) != 0) return NULL;
    memcpy(raw + header - sizeof(size_t), &size, sizeof size);
    memcpy(raw + header - 2 * sizeof(size_t), &header, sizeof header);
    planted.fallback++;
    planted.liveFallback++;
    return raw + header;
}

static size_t fallback_size(const void *p)
{
    size_t size;
    memcpy(&size, (const unsigned char *)p - sizeof(size_t), sizeof size);
    return size;
}

static void fallback_free(void *p)
{
    size_t header;
    memcpy(&header, (unsigned char *)p - 2 * sizeof(size_t), sizeof header);
    free((unsigned char *)p - header);
    planted.liveFallback--;
}

static VKAPI_ATTR void *VKAPI_CALL planted_allocate(void *user, size_t size, size_t align, VkSystemAllocationScope scope)
{
    (void)user, (void)scope;
    if (size <= PLANTED_BLOCK_BYTES && align <= PLANTED_ALIGN)
        for (unsigned i = 0; i < PLANTED_BLOCKS; i++)
            if (!planted.used[i]) {
                planted.used[i] = true;
                planted.planted++;
                memset(planted.blocks[i], 0xab, PLANTED_BLOCK_BYTES);
                return planted.blocks[i];
            }
    return fallback_alloc(size, align);
}

static VKAPI_ATTR void VKAPI_CALL planted_free(void *user, void *p)
{
    (void)user;
    if (p == NULL) return;
    int block = planted_block_of(p);
    if (block < 0) {
        fallback_free(p);
        return;
    }
    CHECK(planted.used[block], "planted block %d freed twice", block);
    /* Scribble over it: whatever still reads the destroyed object reads garbage. */
    memset(planted.blocks[block], 0xcd, PLANTED_BLOCK_BYTES);
    planted.used[block] = false;
}

static VKAPI_ATTR void *VKAPI_CALL planted_reallocate(void *user, void *old, size_t size, size_t align,
                                                     VkSystemAllocationScope scope)
{
    if (old == NULL) return planted_allocate(user, size, align, scope);
    if (size == 0) {
        planted_free(user, old);
        return NULL;
    }
    size_t old_size = planted_block_of(old) >= 0 ? PLANTED_BLOCK_BYTES : fallback_size(old);
    void *p = planted_allocate(user, size, align, scope);
    if (p == NULL) return NULL;
    memcpy(p, old, old_size < size ? old_size : size);
    planted_free(user, old);
    return p;
}

static const VkAllocationCallbacks planted_callbacks = {
    .pfnAllocation = planted_allocate,
    .pfnReallocation = planted_reallocate,
    .pfnFree = planted_free,
};

/* ------------------------------------------------------------------------------------------------------------- */
/* One frame's objects                                                                                           */
/* ------------------------------------------------------------------------------------------------------------- */

typedef struct Frame {
    uint32_t index;
    bool lit;
    VkDeviceMemory memory;
    VkImage image[IMAGES_PER_FRAME];
    VkImageView view[IMAGES_PER_FRAME];
} Frame;

typedef struct Stats {
    HandleSet views, images;
    unsigned long viewsCreated, viewsReused, viewsReusedAfterFirstBatch, imagesReused;
} Stats;

static const VkAllocationCallbacks *view_allocator;
static Stats stats;

static VkExtent2D role_extent(enum Role r)
{
    return r == MASK ? (VkExtent2D){TILES_X, TILES_Y} : (VkExtent2D){W, H};
}

static void frame_create(Frame *f, uint32_t index, bool lit, bool first_batch)
{
    memset(f, 0, sizeof *f);
    f->index = index;
    f->lit = lit;
    VkMemoryRequirements req[IMAGES_PER_FRAME];
    VkDeviceSize offset[IMAGES_PER_FRAME], size = 0;
    uint32_t type_bits = ~0u;
    for (unsigned r = 0; r < IMAGES_PER_FRAME; r++) {
        VkExtent2D e = role_extent((enum Role)r);
        VkImageCreateInfo info = {
            .sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
            .imageType = VK_IMAGE_TYPE_2D,
            .format = role_format[r],
            .extent = {e.width, e.height, 1},
            .mipLevels = 1,
            .arrayLayers = 1,
            .samples = VK_SAMPLE_COUNT_1_BIT,
            .tiling = VK_IMAGE_TILING_OPTIMAL,
            .usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                     (r == OUTPUT ? VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT
                                  : VK_IMAGE_USAGE_SAMPLED_BIT),
            .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
        };
        VK_CHECK(vkCreateImage(host.device, &info, NULL, &f->image[r]));
        if (handle_set_add(&stats.images, (uint64_t)(uintptr_t)f->image[r])) stats.imagesReused++;
        vkGetImageMemoryRequirements(host.device, f->image[r], &req[r]);
        size = (size + req[r].alignment - 1) / req[r].alignment * req[r].alignment;
        offset[r] = size;
        size += req[r].size;
        type_bits &= req[r].memoryTypeBits;
    }
    VkMemoryAllocateInfo alloc = {
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = size,
        .memoryTypeIndex = host_memory_type(&host, type_bits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
    };
    VK_CHECK(vkAllocateMemory(host.device, &alloc, NULL, &f->memory));
    for (unsigned r = 0; r < IMAGES_PER_FRAME; r++) {
        VK_CHECK(vkBindImageMemory(host.device, f->image[r], f->memory, offset[r]));
        VkImageViewCreateInfo view = {
            .sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
            .image = f->image[r],
            .viewType = VK_IMAGE_VIEW_TYPE_2D,
            .format = role_format[r],
            .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1},
        };
        VK_CHECK(vkCreateImageView(host.device, &view, view_allocator, &f->view[r]));
        stats.viewsCreated++;
        if (handle_set_add(&stats.views, (uint64_t)(uintptr_t)f->view[r])) {
            stats.viewsReused++;
            if (!first_batch) stats.viewsReusedAfterFirstBatch++;
        }
    }
}

static void frame_destroy(Frame *f)
{
    for (unsigned r = 0; r < IMAGES_PER_FRAME; r++) {
        vkDestroyImageView(host.device, f->view[r], view_allocator);
        vkDestroyImage(host.device, f->image[r], NULL);
    }
    vkFreeMemory(host.device, f->memory, NULL);
    memset(f, 0, sizeof *f);
}

static DnsrHostImage frame_desc(const Frame *f, enum Role r, VkImageLayout layout)
{
    VkExtent2D e = role_extent(r);
    DnsrHostImage d = {f->image[r], f->view[r], role_format[r], layout, e.width, e.height};
    return d;
}

/* ------------------------------------------------------------------------------------------------------------- */

static double seconds_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Records, runs and checks one batch of `count` frames starting at frame `first`, then destroys its objects. */
static void run_batch(DnsrContext ctx, Frame *frames, uint32_t count, uint32_t first, const HostBuffer *readback,
                      uint32_t *rng)
{
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkImageLayout out_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    for (uint32_t i = 0; i < count; i++) {
        *rng = *rng * 1664525u + 1013904223u;
        frame_create(&frames[i], first + i, (*rng >> 16) & 1u, first == 0);
    }

    VkCommandBuffer cmd = host_begin(&host);
    VkImageMemoryBarrier b[MAX_BATCH * IMAGES_PER_FRAME];
    for (uint32_t i = 0; i < count; i++)
        for (unsigned r = 0; r < IMAGES_PER_FRAME; r++)
            b[i * IMAGES_PER_FRAME + r] =
                host_transition(frames[i].image[r], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    host_cmd_full_barrier_with(cmd, b, count * IMAGES_PER_FRAME);
    const VkImageSubresourceRange color = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    for (uint32_t i = 0; i < count; i++) {
        const Frame *f = &frames[i];
        /* DNSR_HIT_MASK_OCCLUDED_BITS: no bit set = every ray reached the light. */
        VkClearColorValue mask = {.uint32 = {f->lit ? 0u : 0xffffffffu, 0, 0, 0}};
        VkClearColorValue depth = {.float32 = {0.5f, 0, 0, 0}};
        VkClearColorValue zero = {.float32 = {0, 0, 0, 0}};
        VkClearColorValue normal = {.float32 = {0, 0, 1, 0}};
        VkClearColorValue sentinel = {.float32 = {SENTINEL, 0, 0, 0}};
        const VkImageLayout dst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
        vkCmdClearColorImage(cmd, f->image[MASK], dst, &mask, 1, &color);
        vkCmdClearColorImage(cmd, f->image[DEPTH], dst, &depth, 1, &color);
        vkCmdClearColorImage(cmd, f->image[VELOCITY], dst, &zero, 1, &color);
        vkCmdClearColorImage(cmd, f->image[NORMALS], dst, &normal, 1, &color);
        vkCmdClearColorImage(cmd, f->image[OUTPUT], dst, &sentinel, 1, &color);
        for (unsigned r = 0; r < IMAGES_PER_FRAME; r++)
            b[i * IMAGES_PER_FRAME + r] =
                host_transition(f->image[r], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, r == OUTPUT ? out_layout : read);
    }
    host_cmd_full_barrier_with(cmd, b, count * IMAGES_PER_FRAME);

    for (uint32_t i = 0; i < count; i++) {
        const Frame *f = &frames[i];
        DnsrShadowsDispatch d;
        memset(&d, 0, sizeof d);
        d.sType = DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH;
        d.commandBuffer = cmd;
        d.flags = DNSR_DISPATCH_RESET;
        d.hitMaskConvention = DNSR_HIT_MASK_OCCLUDED_BITS;
        d.hitMask = frame_desc(f, MASK, read);
        d.depth = frame_desc(f, DEPTH, read);
        d.velocity = frame_desc(f, VELOCITY, read);
        d.normals = frame_desc(f, NORMALS, read);
        d.output = frame_desc(f, OUTPUT, out_layout);
        host_dispatch_neutral(&d);
        d.frameIndex = f->index;
        DnsrResult r = dnsr_shadows_record(ctx, &d);
        CHECK(r == DNSR_SUCCESS, "frame %u (%lu views created so far): dnsr_shadows_record: %s: %s", f->index,
              stats.viewsCreated, dnsr_result_to_string(r), dnsr_last_error_message());
    }

    host_cmd_full_barrier_with(cmd, NULL, 0);
    for (uint32_t i = 0; i < count; i++) {
        VkBufferImageCopy region = {
            .bufferOffset = (VkDeviceSize)i * W * H * sizeof(float),
            .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
            .imageExtent = {W, H, 1},
        };
        vkCmdCopyImageToBuffer(cmd, frames[i].image[OUTPUT], out_layout, readback->buffer, 1, &region);
    }
    host_cmd_host_read_barrier(cmd);
    host_submit(&host, cmd);

    char where[64];
    snprintf(where, sizeof where, "frames %u..%u", first, first + count - 1);
    host_expect_clean(&host, where);
    for (uint32_t i = 0; i < count; i++) {
        const float *out = (const float *)readback->mapped + (size_t)i * W * H;
        float want = frames[i].lit ? 1.0f : 0.0f;
        for (uint32_t p = 0; p < W * H; p++)
            CHECK(out[p] == want, "frame %u (%s): output[%u] = %g, want %g%s", frames[i].index,
                  frames[i].lit ? "all lit" : "all shadowed", p, out[p], want,
                  out[p] == SENTINEL ? " (the output was never written: stale descriptor set?)" : "");
    }
    /* The batch's command buffer completed (host_submit waited): its objects may go. */
    for (uint32_t i = 0; i < count; i++) frame_destroy(&frames[i]);
}

static void usage(void)
{
    fprintf(stderr, "usage: views_recreated validation|no-layers|planted [--frames N] [--frames-in-flight N]\n");
    exit(2);
}

int main(int argc, char **argv)
{
    setvbuf(stdout, NULL, _IOLBF, 0);
    if (argc < 2) usage();
    const char *mode = argv[1];
    HostOptions options;
    memset(&options, 0, sizeof options);
    bool plant = false;
    if (strcmp(mode, "validation") == 0) {
    } else if (strcmp(mode, "no-layers") == 0) {
        options.noLayers = true;
    } else if (strcmp(mode, "planted") == 0) {
        options.rawHandles = true;
        plant = true;
    } else {
        usage();
    }
    uint32_t frames = 10000, frames_in_flight = 0;
    for (int i = 2; i < argc; i++) {
        if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc)
            frames = (uint32_t)strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--frames-in-flight") == 0 && i + 1 < argc)
            frames_in_flight = (uint32_t)strtoul(argv[++i], NULL, 10);
        else
            usage();
    }
    uint32_t batch = frames_in_flight ? frames_in_flight : DEFAULT_FRAMES_IN_FLIGHT;
    CHECK(batch >= 1 && batch <= MAX_BATCH, "--frames-in-flight %u: at most %u", frames_in_flight, MAX_BATCH);
    view_allocator = plant ? &planted_callbacks : NULL;

    host_create_with(&host, &options);
    DnsrContextCreateInfo info = host_create_info(&host, W, H);
    info.enabledFeatures &= ~(DnsrFeatureFlags)DNSR_FEATURE_PUSH_DESCRIPTOR;
#ifdef DNSR_MAX_FRAMES_IN_FLIGHT
    info.maxFramesInFlight = frames_in_flight;
#else
    printf("note: dnsr.h has no maxFramesInFlight yet (built against the old header)\n");
#endif
    DnsrContext ctx = NULL;
    DNSR_CHECK(dnsr_context_create(&info, &ctx));
    HostBuffer readback;
    host_buffer_create(&host, &readback, (VkDeviceSize)MAX_BATCH * W * H * sizeof(float));
    printf("views_recreated (%s): %u frames of %ux%u, push descriptors off, maxFramesInFlight %u (batches of %u)\n",
           mode, frames, W, H, frames_in_flight, batch);

    double start = seconds_now();
    uint32_t rng = 0x5eed1234u;
    Frame batch_frames[MAX_BATCH];
    for (uint32_t first = 0; first < frames; first += batch) {
        uint32_t count = frames - first < batch ? frames - first : batch;
        run_batch(ctx, batch_frames, count, first, &readback, &rng);
    }
    double elapsed = seconds_now() - start;

    DNSR_CHECK(dnsr_context_destroy(ctx));
    host_buffer_destroy(&host, &readback);
    char host_device_name_copy[sizeof host.deviceName];
    memcpy(host_device_name_copy, host.deviceName, sizeof host_device_name_copy);
    host_destroy(&host);

    printf("views_recreated (%s): %u frames checked in %.1f s (%.2f ms/frame); %lu views created, %lu got a handle "
           "value seen before (%lu after the first batch), %lu images did\n",
           mode, frames, elapsed, 1e3 * elapsed / (frames ? frames : 1), stats.viewsCreated, stats.viewsReused,
           stats.viewsReusedAfterFirstBatch, stats.imagesReused);
    if (options.noLayers) {
        /* lavapipe's handles are heap addresses, and the heap reuses them (ASan's quarantine only delays it): if
         * that stops, this mode no longer tests reuse. Other drivers may never reuse; the planted mode covers it. */
        if (strstr(host_device_name_copy, "llvmpipe"))
            CHECK(stats.viewsReused > 0, "no view handle value repeated on lavapipe without layers: the mode lost its point");
        else if (stats.viewsReused == 0)
            printf("note: this driver never reused a view handle value here\n");
    }
    if (plant) {
        printf("planted allocator: %lu view allocations from static blocks, %lu elsewhere\n", planted.planted,
               planted.fallback);
        /* Every view after the first batch must have reused the value of a destroyed view: otherwise the planting
         * did not work (the driver does not allocate views through pAllocator, or not at the object's address)
         * and this mode proves nothing. */
        unsigned long after_first = stats.viewsCreated - (unsigned long)(frames < batch ? frames : batch) * IMAGES_PER_FRAME;
        CHECK(stats.viewsReusedAfterFirstBatch == after_first,
              "planted reuse did not happen: %lu of %lu views after the first batch reused a handle value",
              stats.viewsReusedAfterFirstBatch, after_first);
        CHECK(planted.liveFallback == 0, "%ld fallback allocations still live", planted.liveFallback);
    }
    free(stats.views.slots);
    free(stats.images.slots);
    return 0;
}

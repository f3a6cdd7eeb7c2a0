/*
 * classify: the hybrid-shadows classifier through the C API, end to end on a scene whose answer is known. A flat
 * receiver faces the light; the shadow map has a blocker over its left half. The classifier must prefill the hit
 * mask with "occluded" on the left and "lit" on the right, list only the tiles on the blocker's edge (with
 * indirect-dispatch counts), and refuse bad input (no cascades, a NaN cascade matrix, tap count 7, a context
 * without the classifier) with specific errors. Validation and synchronization validation on throughout.
 */
#include "host.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define W 64u
#define H 16u
#define TILES_X (W / 8u)
#define TILES_Y (H / 4u)
#define MAP 64u

static Host host;

static void expect_refused(const char *name, DnsrResult got, DnsrResult want, const char *mention)
{
    const char *msg = dnsr_last_error_message();
    CHECK(got == want, "%s: got %s, want %s (%s)", name, dnsr_result_to_string(got), dnsr_result_to_string(want), msg);
    CHECK(strstr(msg, mention) != NULL, "%s: message \"%s\" does not mention \"%s\"", name, msg, mention);
    printf("  %-34s %-36s %s\n", name, dnsr_result_to_string(got), msg);
}

int main(void)
{
    host_create(&host);
    DnsrContextCreateInfo info = host_create_info(&host, W, H);
    DnsrContext plain = NULL, ctx = NULL;
    DNSR_CHECK(dnsr_context_create(&info, &plain));
    info.flags |= DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER | DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS;
    DNSR_CHECK(dnsr_context_create(&info, &ctx));

    HostImage depth, normals, mask, cascade;
    host_image_create(&host, &depth, VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    host_image_create(&host, &normals, VK_FORMAT_R32G32B32A32_SFLOAT, W, H, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    host_image_create(&host, &mask, VK_FORMAT_R32_UINT, TILES_X, TILES_Y, VK_IMAGE_LAYOUT_GENERAL);
    host_image_create(&host, &cascade, VK_FORMAT_R32_SFLOAT, MAP, MAP, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    /* World = clip space (identity viewProjectionInverse): the receiver is the plane z = 0.5 facing +z, the light. */
    static float depth_data[W * H], normal_data[W * H * 4], map_data[MAP * MAP];
    for (uint32_t i = 0; i < W * H; i++) {
        depth_data[i] = 0.5f;
        normal_data[4 * i + 2] = 1.0f;
    }
    /* The cascade maps x, y in [-1, 1] to u, v and depth = 0.5 - 0.5 z (growing away from the light): the
     * receiver sits at 0.25, the blocker over u < 0.5 at 0.1. */
    for (uint32_t y = 0; y < MAP; y++)
        for (uint32_t x = 0; x < MAP; x++) map_data[y * MAP + x] = x < MAP / 2 ? 0.1f : 0.25f;
    host_upload(&host, &depth, depth_data, sizeof depth_data);
    host_upload(&host, &normals, normal_data, sizeof normal_data);
    host_upload(&host, &cascade, map_data, sizeof map_data);

    DnsrClassifyDispatch d;
    memset(&d, 0, sizeof d);
    d.sType = DNSR_STRUCTURE_TYPE_CLASSIFY_DISPATCH;
    d.flags = DNSR_CLASSIFY_REJECT_LIT_PIXELS | DNSR_CLASSIFY_BOUND_RAY_INTERVAL;
    d.hitMaskConvention = DNSR_HIT_MASK_OCCLUDED_BITS;
    d.hitMask = host_image_desc(&mask);
    d.depth = host_image_desc(&depth);
    d.normals = host_image_desc(&normals);
    d.normalsUnpackMul = 1.0f;
    for (int i = 0; i < 4; i++) d.viewProjectionInverse[i * 5] = 1.0f;
    d.lightDirection[2] = 1.0f;
    d.lightAngularSize = 0.0093f;
    d.cascadeCount = 1;
    /* Column-major: u = 0.5 x + 0.5, v = 0.5 y + 0.5, depth = 0.5 - 0.5 z. */
    float m[16] = {0.5f, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, -0.5f, 0, 0.5f, 0.5f, 0.5f, 1};
    memcpy(d.cascadeWorldToShadow[0], m, sizeof m);
    d.cascadeImages[0] = host_image_desc(&cascade);
    d.blockerOffset = 0.05f;
    d.tapCount = 24;
    d.sync.outputDstStages = VK_PIPELINE_STAGE_TRANSFER_BIT;
    d.sync.outputDstAccess = VK_ACCESS_TRANSFER_READ_BIT;

    DnsrClassifierBuffers buffers;
    memset(&buffers, 0, sizeof buffers);
    expect_refused("buffers: wrong sType", dnsr_context_get_classifier_buffers(ctx, &buffers), DNSR_ERROR_INVALID_STRUCTURE, "pBuffers");
    buffers.sType = DNSR_STRUCTURE_TYPE_CLASSIFIER_BUFFERS;
    DNSR_CHECK(dnsr_context_get_classifier_buffers(ctx, &buffers));
    CHECK(buffers.tiles != VK_NULL_HANDLE && buffers.counts != VK_NULL_HANDLE, "null classifier buffers");
    CHECK(buffers.tileCapacity == TILES_X * TILES_Y, "tile capacity %u", buffers.tileCapacity);

    HostBuffer readback;
    host_buffer_create(&host, &readback, DNSR_CLASSIFY_COUNTS_BYTES + (VkDeviceSize)TILES_X * TILES_Y * DNSR_CLASSIFY_TILE_BYTES);
    VkCommandBuffer cmd = host_begin(&host);
    d.commandBuffer = cmd;
    DNSR_CHECK(dnsr_classify_record(ctx, &d));
    VkBufferCopy counts = {0, 0, DNSR_CLASSIFY_COUNTS_BYTES};
    VkBufferCopy tiles = {0, DNSR_CLASSIFY_COUNTS_BYTES, (VkDeviceSize)TILES_X * TILES_Y * DNSR_CLASSIFY_TILE_BYTES};
    vkCmdCopyBuffer(cmd, buffers.counts, readback.buffer, 1, &counts);
    vkCmdCopyBuffer(cmd, buffers.tiles, readback.buffer, 1, &tiles);
    host_cmd_host_read_barrier(cmd);
    host_submit(&host, cmd);
    host_expect_clean(&host, "classify");

    const uint32_t *words = (const uint32_t *)readback.mapped;
    uint32_t listed = words[0];
    CHECK(words[1] == 1 && words[2] == 1 && words[3] == listed && words[4] == 32 * listed, "counts %u %u %u %u %u",
          words[0], words[1], words[2], words[3], words[4]);
    /* The blocker's edge is at x = W / 2: the column of tiles on each side of it holds the pixels to trace. */
    CHECK(listed >= TILES_Y && listed <= 2 * TILES_Y, "%u tiles listed, expected the %u to %u on the edge", listed, TILES_Y, 2 * TILES_Y);
    for (uint32_t i = 0; i < listed; i++) {
        const uint32_t *r = words + 8 + 4 * i;
        uint32_t tx = r[0] & 0xFFFF;
        float min_t, max_t;
        memcpy(&min_t, &r[2], 4);
        memcpy(&max_t, &r[3], 4);
        CHECK(tx == TILES_X / 2 - 1 || tx == TILES_X / 2, "tile %u listed, away from the edge", tx);
        CHECK(r[1] != 0 && min_t == 0.0f && max_t > 0.0f && isfinite(max_t), "tile %u: mask %#x, interval %g..%g", tx, r[1], min_t, max_t);
    }
    static uint32_t mask_words[TILES_X * TILES_Y];
    host_download(&host, &mask, mask_words, sizeof mask_words);
    for (uint32_t ty = 0; ty < TILES_Y; ty++) {
        CHECK(mask_words[ty * TILES_X] == 0xFFFFFFFFu, "left tile row %u: %#x, want all occluded", ty, mask_words[ty * TILES_X]);
        CHECK(mask_words[ty * TILES_X + TILES_X - 1] == 0u, "right tile row %u: %#x, want all lit", ty, mask_words[ty * TILES_X + TILES_X - 1]);
    }
    printf("classify: %u of %u tiles listed\n", listed, TILES_X * TILES_Y);

    /* The classifier's GPU time (the context records timestamps). */
    DnsrClassifierTimings timings;
    memset(&timings, 0, sizeof timings);
    expect_refused("timings: wrong sType", dnsr_context_get_classifier_timings(ctx, &timings), DNSR_ERROR_INVALID_STRUCTURE, "pTimings");
    expect_refused("timings: NULL pTimings", dnsr_context_get_classifier_timings(ctx, NULL), DNSR_ERROR_INVALID_ARGUMENT, "pTimings");
    timings.sType = DNSR_STRUCTURE_TYPE_CLASSIFIER_TIMINGS;
    expect_refused("timings: no classifier", dnsr_context_get_classifier_timings(plain, &timings), DNSR_ERROR_CLASSIFIER_NOT_ENABLED,
                   "classifier");
    DNSR_CHECK(dnsr_context_get_classifier_timings(ctx, &timings));
    CHECK(timings.dispatch == 1 && timings.classifyMs > 0.0 && isfinite(timings.classifyMs), "classifier timings: dispatch %llu, %g ms",
          (unsigned long long)timings.dispatch, timings.classifyMs);
    printf("classify: %.4f ms of GPU time (dispatch %llu)\n", timings.classifyMs, (unsigned long long)timings.dispatch);

    cmd = host_begin(&host);
    DnsrClassifyDispatch bad = d;
    bad.commandBuffer = cmd;
    bad.cascadeCount = 0;
    expect_refused("no cascades", dnsr_classify_record(ctx, &bad), DNSR_ERROR_INVALID_ARGUMENT, "cascadeCount");
    bad = d;
    bad.commandBuffer = cmd;
    bad.cascadeWorldToShadow[0][5] = NAN;
    expect_refused("cascade matrix with NaN", dnsr_classify_record(ctx, &bad), DNSR_ERROR_NON_FINITE, "cascades[0]");
    bad = d;
    bad.commandBuffer = cmd;
    bad.projectionInverse[10] = INFINITY;
    expect_refused("projection inverse with infinity", dnsr_classify_record(ctx, &bad), DNSR_ERROR_NON_FINITE, "projectionInverse");
    bad = d;
    bad.commandBuffer = cmd;
    bad.tapCount = 7;
    expect_refused("tap count 7", dnsr_classify_record(ctx, &bad), DNSR_ERROR_INVALID_ARGUMENT, "tapCount");
    bad = d;
    bad.commandBuffer = cmd;
    bad.flags |= 1u << 20;
    expect_refused("unknown flag", dnsr_classify_record(ctx, &bad), DNSR_ERROR_INVALID_ARGUMENT, "flags");
    bad = d;
    bad.commandBuffer = cmd;
    expect_refused("context without classifier", dnsr_classify_record(plain, &bad), DNSR_ERROR_CLASSIFIER_NOT_ENABLED, "DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER");
    expect_refused("NULL dispatch", dnsr_classify_record(ctx, NULL), DNSR_ERROR_INVALID_ARGUMENT, "pDispatch");
    host_submit(&host, cmd);

    host_buffer_destroy(&host, &readback);
    HostImage *images[] = {&depth, &normals, &mask, &cascade};
    for (size_t i = 0; i < sizeof images / sizeof images[0]; i++) host_image_destroy(&host, images[i]);
    DNSR_CHECK(dnsr_context_destroy(ctx));
    DNSR_CHECK(dnsr_context_destroy(plain));
    host_destroy(&host);
    printf("classify: ok\n");
    return 0;
}

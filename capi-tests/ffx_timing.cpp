/*
 * ffx_timing: GPU time of one frame through the FidelityFX SDK 1.1.4 API (dnsr's include/ffx, as an integration
 * calls it) against the same frame through dnsr.h, on the same inputs, measured with GPU timestamps around each
 * recorded dispatch. The inputs are the worst case for the denoiser: every 8x4 tile holds both lit and shadowed
 * pixels (nothing is cleared), the camera is still.
 *
 *   ffx_timing [--size WxH] [--frames N] [--no-layers]
 *
 * `make test` runs it at 64x48 under the validation layer (it must run cleanly); docs/migrating-from-ffx.md
 * quotes it at 3840x2160 on the device (--no-layers: no validation layer installed there).
 */
#include <FidelityFX/host/backends/vk/ffx_vk.h>
#include <FidelityFX/host/ffx_denoiser.h>

#include "ffx_host.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

static Host host;

struct Timer {
    VkQueryPool pool = VK_NULL_HANDLE;
    double periodNs = 1;
};

static double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// Records `record` between two timestamps `frames` times (one submit each) and returns the median GPU ms.
template <typename F> static double time_frames(Timer &t, int frames, F record)
{
    std::vector<double> ms;
    for (int frame = 0; frame < frames; frame++) {
        VkCommandBuffer cmd = host_begin(&host);
        vkCmdResetQueryPool(cmd, t.pool, 0, 2);
        host_cmd_full_barrier(cmd);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, t.pool, 0);
        record(cmd, (uint32_t)frame);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, t.pool, 1);
        host_submit(&host, cmd);
        uint64_t stamps[2];
        VK_CHECK(vkGetQueryPoolResults(host.device, t.pool, 0, 2, sizeof stamps, stamps, sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        if (frame >= frames / 4) ms.push_back(double(stamps[1] - stamps[0]) * t.periodNs * 1e-6); /* warm-up */
    }
    return median(ms);
}

int main(int argc, char **argv)
{
    uint32_t w = 64, h = 48;
    int frames = 40;
    HostOptions options = {};
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "--size") && i + 1 < argc) {
            CHECK(std::sscanf(argv[++i], "%ux%u", &w, &h) == 2 && w && h, "--size wants WxH");
        } else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) {
            frames = std::atoi(argv[++i]);
            CHECK(frames >= 4, "--frames wants at least 4");
        } else if (!std::strcmp(argv[i], "--no-layers")) {
            options.noLayers = true;
        } else {
            CHECK(false, "unknown argument %s", argv[i]);
        }
    }
    host_create_with(&host, &options);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(host.physicalDevice, &props);
    Timer timer;
    timer.periodNs = props.limits.timestampPeriod;
    VkQueryPoolCreateInfo qi = {};
    qi.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO;
    qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qi.queryCount = 2;
    VK_CHECK(vkCreateQueryPool(host.device, &qi, nullptr, &timer.pool));

    uint32_t tx = (w + 7) / 8, ty = (h + 3) / 4;
    HostImage mask, depth, velocity, normals, outFfx, outNative;
    VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    host_image_create(&host, &mask, VK_FORMAT_R32_UINT, tx, ty, VK_IMAGE_LAYOUT_GENERAL);
    host_image_create(&host, &depth, VK_FORMAT_R32_SFLOAT, w, h, read);
    host_image_create(&host, &velocity, VK_FORMAT_R16G16_SFLOAT, w, h, read);
    host_image_create(&host, &normals, VK_FORMAT_R8G8B8A8_UNORM, w, h, read);
    host_image_create(&host, &outFfx, VK_FORMAT_R8G8B8A8_UNORM, w, h, VK_IMAGE_LAYOUT_GENERAL);
    host_image_create(&host, &outNative, VK_FORMAT_R8G8B8A8_UNORM, w, h, VK_IMAGE_LAYOUT_GENERAL);
    {
        std::vector<uint32_t> bits(size_t(tx) * ty);
        uint32_t s = 1;
        for (auto &b : bits) s = s * 1664525u + 1013904223u, b = (s ^ (s >> 15)) | 1u; /* mixed in every tile */
        host_upload(&host, &mask, bits.data(), bits.size() * 4);
        std::vector<float> d(size_t(w) * h, 0.5f);
        host_upload(&host, &depth, d.data(), d.size() * 4);
        std::vector<uint16_t> v(size_t(w) * h * 2, 0);
        host_upload(&host, &velocity, v.data(), v.size() * 2);
        std::vector<uint8_t> n(size_t(w) * h * 4);
        for (size_t i = 0; i < n.size(); i += 4) n[i] = n[i + 1] = 128, n[i + 2] = 255, n[i + 3] = 0;
        host_upload(&host, &normals, n.data(), n.size());
    }

    // The FFX integration, as the SDK's sample sets it up.
    VkDeviceContext dc = {host.device, host.physicalDevice, vkGetDeviceProcAddr};
    size_t scratchSize = ffxGetScratchMemorySizeVK(host.physicalDevice, 1);
    std::vector<unsigned char> scratch(scratchSize);
    FfxInterface iface;
    CHECK(ffxGetInterfaceVK(&iface, ffxGetDeviceVK(&dc), scratch.data(), scratchSize, 1) == FFX_OK, "%s", dnsr_last_error_message());
    FfxDenoiserContextDescription desc = {};
    desc.flags = FFX_DENOISER_SHADOWS;
    desc.windowSize = {w, h};
    desc.backendInterface = iface;
    std::vector<FfxDenoiserContext> ffx(1);
    CHECK(ffxDenoiserContextCreate(ffx.data(), &desc) == FFX_OK, "%s", dnsr_last_error_message());
    double ffxMs = time_frames(timer, frames, [&](VkCommandBuffer cmd, uint32_t frame) {
        FfxDenoiserShadowsDispatchDescription d = sample_dispatch(cmd, frame, mask, depth, velocity, normals, outFfx);
        CHECK(ffxDenoiserContextDispatchShadows(ffx.data(), &d) == FFX_OK, "%s", dnsr_last_error_message());
    });
    CHECK(ffxDenoiserContextDestroy(ffx.data()) == FFX_OK, "%s", dnsr_last_error_message());

    // The same frames through dnsr.h, with and without push descriptors (the FFX layer cannot know whether the
    // engine enabled VK_KHR_push_descriptor, so it uses descriptor sets).
    double nativeMs[2] = {0, 0};
    for (int push = 0; push < 2; push++) {
        DnsrContextCreateInfo info = host_create_info(&host, w, h);
        info.outputFormat = VK_FORMAT_R8G8B8A8_UNORM;
        if (!push) info.enabledFeatures &= ~(DnsrFeatureFlags)DNSR_FEATURE_PUSH_DESCRIPTOR;
        else if (!(info.enabledFeatures & DNSR_FEATURE_PUSH_DESCRIPTOR)) continue;
        DnsrContext ctx = nullptr;
        DNSR_CHECK(dnsr_context_create(&info, &ctx));
        nativeMs[push] = time_frames(timer, frames, [&](VkCommandBuffer cmd, uint32_t frame) {
            DnsrShadowsDispatch d = host_dispatch(cmd, &mask, &depth, &velocity, &normals, &outNative);
            d.normalsUnpackMul = 2.0f, d.normalsUnpackAdd = -1.0f;
            d.sync.inputSrcStages = d.sync.outputDstStages = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
            d.sync.inputSrcAccess = VK_ACCESS_MEMORY_WRITE_BIT;
            d.sync.outputDstAccess = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
            d.frameIndex = frame;
            DNSR_CHECK(dnsr_shadows_record(ctx, &d));
        });
        DNSR_CHECK(dnsr_context_destroy(ctx));
    }
    std::printf("ffx_timing: %s, %ux%u, every tile mixed, default settings, RGBA8 output, median of %d frames:\n",
                host.deviceName, w, h, frames - frames / 4);
    std::printf("  FFX API (include/ffx):                  %.3f ms\n", ffxMs);
    std::printf("  dnsr.h, descriptor sets:                %.3f ms\n", nativeMs[0]);
    if (nativeMs[1] > 0) std::printf("  dnsr.h, push descriptors:               %.3f ms\n", nativeMs[1]);

    vkDestroyQueryPool(host.device, timer.pool, nullptr);
    for (HostImage *img : {&mask, &depth, &velocity, &normals, &outFfx, &outNative}) host_image_destroy(&host, img);
    host_destroy(&host);
    return 0;
}

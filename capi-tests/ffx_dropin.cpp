/*
 * ffx_dropin: an integration of the FidelityFX SDK 1.1.4 shadow denoiser, written as the SDK's sample writes it
 * (C++17, <FidelityFX/host/ffx_denoiser.h> and <FidelityFX/host/backends/vk/ffx_vk.h>), built against dnsr's
 * include/ffx headers and linked with libdnsr only.
 *
 *   - layout: every size and offset the SDK's headers give on Linux x86-64 (a mismatch here means an integration
 *     compiled against the SDK's headers would pass garbage), and the enum values integrations switch on;
 *   - versions: the asserts the SDK's sample makes (SDK 1.1.4 through fpGetSDKVersion, denoiser 1.3.0);
 *   - frames: six frames of a 37x23 mask (four noisy, two all lit) through the FFX API equal, bit for bit, the same
 *     frames through dnsr.h with a fresh context's settings (dnsr's default, the Quality preset); a second FFX
 *     context writing the sample's RGBA8 output holds the same values, rounded, in every channel; with
 *     DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS in the description's flags, the same against dnsr.h with
 *     DNSR_PRESET_BALANCED (the FidelityFX settings), and those frames differ from the default's; told the light
 *     through dnsr_ffx_context_set_light (its position behind the receivers, or that it has no size), the same
 *     against dnsr.h dispatches with those bits, after a refused call that must not change the context's light;
 *     given hit distances and the light's size through dnsr_ffx_context_set_penumbra_guidance, the same against
 *     dnsr.h dispatches with DNSR_DISPATCH_USE_HIT_DISTANCE, after a refused call that must not change them; with
 *     DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER and the previous depth and normals given before every dispatch but the
 *     first (dnsr_ffx_context_set_previous_gbuffer), the same against dnsr.h with
 *     DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER, after a dispatch without them that must be refused;
 *   - the depth buffer itself (D32_SFLOAT, reverse-Z, FFX_DENOISER_ENABLE_DEPTH_INVERTED) equals dnsr.h with
 *     DNSR_CONTEXT_CREATE_DEPTH_INVERTED on it;
 *   - misuse the SDK does not catch (NULL pointers, a destroyed or never-created context, a create into a live
 *     one, the reflections flag, an output format dnsr cannot write, a NULL image, a scratch buffer too small, an
 *     interface not from ffxGetInterfaceVK): each a specific FfxErrorCode with a message, nothing recorded;
 *     dnsr_ffx_context_set_light's (NULL, dead or destroyed context, unknown bits, a missing, zero, non-finite or
 *     non-homogeneous position) and dnsr_ffx_context_set_penumbra_guidance's (NULL, dead or destroyed context,
 *     a null image or view, a non-finite or out-of-range angle) and dnsr_ffx_context_set_previous_gbuffer's (NULL,
 *     dead, destroyed or flagless context, a NULL description, a null image or view): each a specific DnsrResult
 *     with a message;
 *   - no validation message from any of it.
 */
#include <FidelityFX/host/backends/vk/ffx_vk.h>
#include <FidelityFX/host/ffx_denoiser.h>

#include "ffx_host.h"

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

// ---- Layout (SDK 1.1.4 on Linux x86-64, 4-byte wchar_t) ----
static_assert(sizeof(wchar_t) == 4, "these offsets are Linux's");
static_assert(sizeof(FfxResourceDescription) == 32, "");
static_assert(offsetof(FfxResourceDescription, mipCount) == 20 && offsetof(FfxResourceDescription, usage) == 28, "");
static_assert(sizeof(FfxResource) == 304 && offsetof(FfxResource, description) == 8, "");
static_assert(offsetof(FfxResource, state) == 40 && offsetof(FfxResource, name) == 44, "");
static_assert(sizeof(FfxInterface) == 232 && offsetof(FfxInterface, fpRegisterConstantBufferAllocator) == 200, "");
static_assert(offsetof(FfxInterface, scratchBuffer) == 208 && offsetof(FfxInterface, scratchBufferSize) == 216, "");
static_assert(offsetof(FfxInterface, device) == 224, "");
static_assert(sizeof(FfxDenoiserContextDescription) == 248, "");
static_assert(offsetof(FfxDenoiserContextDescription, normalsHistoryBufferFormat) == 12, "");
static_assert(offsetof(FfxDenoiserContextDescription, backendInterface) == 16, "");
using Dispatch = FfxDenoiserShadowsDispatchDescription;
static_assert(sizeof(Dispatch) == 1760, "");
static_assert(offsetof(Dispatch, hitMaskResults) == 8 && offsetof(Dispatch, depth) == 312, "");
static_assert(offsetof(Dispatch, velocity) == 616 && offsetof(Dispatch, normal) == 920, "");
static_assert(offsetof(Dispatch, shadowMaskOutput) == 1224 && offsetof(Dispatch, motionVectorScale) == 1528, "");
static_assert(offsetof(Dispatch, normalsUnpackMul) == 1536 && offsetof(Dispatch, normalsUnpackAdd) == 1540, "");
static_assert(offsetof(Dispatch, eye) == 1544 && offsetof(Dispatch, frameIndex) == 1556, "");
static_assert(offsetof(Dispatch, projectionInverse) == 1560 && offsetof(Dispatch, reprojectionMatrix) == 1624, "");
static_assert(offsetof(Dispatch, viewProjectionInverse) == 1688, "");
static_assert(offsetof(Dispatch, depthSimilaritySigma) == 1752, "");
static_assert(sizeof(FfxDenoiserReflectionsDispatchDescription) == 3592, "");
static_assert(sizeof(FfxDenoiserContext) == 292392, "");
static_assert(sizeof(VkDeviceContext) == 24 && sizeof(FfxDeviceCapabilities) == 20, "");
static_assert(uint32_t(FFX_ERROR_INVALID_VERSION) == 0x8000000fu && uint32_t(FFX_ERROR_ACCESS_DENIED) == 0x80000010u, "");
// The error types as the SDK declares them: FfxErrorCode a signed 32-bit integer, FfxErrorCodes an enum whose values
// from 0x80000000 up make its underlying type unsigned. So a switch on FfxErrorCodes takes these labels without
// narrowing, and `code < FFX_OK` compares as unsigned and is false for every code, as with the SDK.
static_assert(std::is_same<FfxErrorCode, int32_t>::value, "FfxErrorCode");
static_assert(std::is_unsigned<std::underlying_type<FfxErrorCodes>::type>::value, "FfxErrorCodes' underlying type");
static constexpr const char *ffx_error_name(FfxErrorCodes code)
{
    switch (code) {
    case FFX_OK: return "FFX_OK";
    case FFX_ERROR_INVALID_POINTER: return "FFX_ERROR_INVALID_POINTER";
    case FFX_ERROR_INVALID_ARGUMENT: return "FFX_ERROR_INVALID_ARGUMENT";
    default: return "another FfxErrorCodes";
    }
}
static_assert(ffx_error_name(FFX_ERROR_INVALID_ARGUMENT)[10] == 'I', "a switch on FfxErrorCodes");
static_assert(FFX_SURFACE_FORMAT_R32_FLOAT == 28 && FFX_SURFACE_FORMAT_R32_TYPELESS == 37, "");
static_assert(FFX_RESOURCE_STATE_GENERIC_READ == 20 && FFX_RESOURCE_STATE_DEPTH_ATTACHEMENT == 512, "");
static_assert(FFX_DENOISER_ENABLE_DEPTH_INVERTED == 4 && FFX_EFFECT_DENOISER == 9, "");
static_assert(FFX_SDK_MAKE_VERSION(1, 1, 4) == 0x401004, "");

#define W 37u
#define H 23u
#define TILES_X ((W + 7u) / 8u)
#define TILES_Y ((H + 3u) / 4u)

static Host host;
static HostImage mask, depth, depthBuffer, velocity, velocityVarying, normals, outFfx, outFfx8, outNative, hitDistance;
static HostBuffer readback;

// FFX_OK, or fail the test with the call, the code and dnsr's message.
#define FFX_CHECK(call)                                                                                          \
    do {                                                                                                         \
        FfxErrorCode ffx_check_ = (call);                                                                        \
        if (ffx_check_ != FFX_OK) host_fail(__FILE__, __LINE__, #call, "FfxErrorCode 0x%08x: %s", (unsigned)ffx_check_, \
                                            dnsr_last_error_message());                                          \
    } while (0)

// `call` returns `want` and leaves a message.
#define EXPECT_FFX(want, call)                                                                                   \
    do {                                                                                                         \
        FfxErrorCode ffx_got_ = (call);                                                                          \
        CHECK(ffx_got_ == FfxErrorCode(want), "%s gave 0x%08x, want %s", #call, (unsigned)ffx_got_, #want);                 \
        CHECK(dnsr_last_error_message()[0] != 0, "%s: no message", #call);                                      \
        std::printf("refused as %s: %s\n", #want, dnsr_last_error_message());                                    \
        cases++;                                                                                                 \
    } while (0)
// `call` returns the DnsrResult `want` and leaves a message.
#define EXPECT_DNSR(want, call)                                                                                  \
    do {                                                                                                         \
        DnsrResult dnsr_got_ = (call);                                                                           \
        CHECK(dnsr_got_ == (want), "%s gave %s, want %s", #call, dnsr_result_to_string(dnsr_got_), #want);       \
        CHECK(dnsr_last_error_message()[0] != 0, "%s: no message", #call);                                      \
        std::printf("refused as %s: %s\n", #want, dnsr_last_error_message());                                   \
        cases++;                                                                                                 \
    } while (0)
static int cases = 0;

static Dispatch ffx_dispatch(VkCommandBuffer cmd, uint32_t frame, const HostImage &out = outFfx)
{
    return sample_dispatch(cmd, frame, mask, depth, velocity, normals, out);
}

// The same frame through dnsr.h (the settings are the context's).
static DnsrShadowsDispatch native_dispatch(VkCommandBuffer cmd, uint32_t frame)
{
    DnsrShadowsDispatch d = host_dispatch(cmd, &mask, &depth, &velocity, &normals, &outNative);
    d.normalsUnpackMul = 2.0f;
    d.normalsUnpackAdd = -1.0f;
    d.frameIndex = frame;
    return d;
}

static void upload_mask(uint32_t seed, bool allLit)
{
    std::vector<uint32_t> data(TILES_X * TILES_Y);
    uint32_t s = seed * 2654435761u + 1u;
    for (auto &word : data) {
        s = s * 1664525u + 1013904223u;
        word = allLit ? 0u : (s ^ (s >> 13)) & 0x0F0FF0F0u; /* occluded bits: about half the pixels */
    }
    host_upload(&host, &mask, data.data(), data.size() * sizeof(uint32_t));
}

static void read_output(const HostImage &img, std::vector<float> &out)
{
    VkCommandBuffer cmd = host_begin(&host);
    host_cmd_copy(cmd, &img, &readback, 0, false);
    host_cmd_host_read_barrier(cmd);
    host_submit(&host, cmd);
    if (img.format == VK_FORMAT_R8G8B8A8_UNORM) {
        const uint8_t *texels = (const uint8_t *)readback.mapped;
        out.resize(W * H);
        for (uint32_t i = 0; i < W * H; i++) {
            const uint8_t *t = texels + 4 * i;
            CHECK(t[1] == t[0] && t[2] == t[0] && t[3] == t[0], "RGBA8 output channels differ at %u", i);
            out[i] = t[0] / 255.0f;
        }
        return;
    }
    out.assign((const float *)readback.mapped, (const float *)readback.mapped + W * H);
}

struct Integration {
    VkDeviceContext deviceContext;
    std::unique_ptr<unsigned char, void (*)(void *)> scratch{nullptr, std::free};
    FfxInterface iface;
    std::unique_ptr<FfxDenoiserContext> context{new FfxDenoiserContext};
};

// fpGetDeviceCapabilities reports the device as the SDK's Vulkan backend does: wave lanes from the subgroup size
// control properties where the device has that extension (32 otherwise), fp16 from shaderFloat16 where it has
// VK_KHR_shader_float16_int8, shader model 5.1.
static void check_capabilities(FfxInterface &iface)
{
    FfxDeviceCapabilities caps;
    std::memset(&caps, 0xff, sizeof caps);
    FFX_CHECK(iface.fpGetDeviceCapabilities(&iface, &caps));
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(host.physicalDevice, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(host.physicalDevice, nullptr, &count, extensions.data());
    auto has = [&](const char *name) {
        for (const VkExtensionProperties &e : extensions)
            if (std::strcmp(e.extensionName, name) == 0) return true;
        return false;
    };
    VkPhysicalDeviceSubgroupSizeControlProperties sizes = {};
    sizes.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_PROPERTIES;
    VkPhysicalDeviceProperties2 properties = {};
    properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    properties.pNext = &sizes;
    VkPhysicalDeviceShaderFloat16Int8Features fp16 = {};
    fp16.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_FLOAT16_INT8_FEATURES;
    VkPhysicalDeviceFeatures2 features = {};
    features.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2;
    features.pNext = &fp16;
    vkGetPhysicalDeviceProperties2(host.physicalDevice, &properties);
    vkGetPhysicalDeviceFeatures2(host.physicalDevice, &features);
    bool control = has(VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME);
    uint32_t lanesMin = control ? sizes.minSubgroupSize : 32, lanesMax = control ? sizes.maxSubgroupSize : 32;
    bool half = has(VK_KHR_SHADER_FLOAT16_INT8_EXTENSION_NAME) && fp16.shaderFloat16;
    CHECK(caps.waveLaneCountMin == lanesMin && caps.waveLaneCountMax == lanesMax, "wave lanes %u..%u, want %u..%u",
          caps.waveLaneCountMin, caps.waveLaneCountMax, lanesMin, lanesMax);
    CHECK(caps.fp16Supported == half, "fp16Supported %d, want %d", int(caps.fp16Supported), int(half));
    CHECK(caps.maximumSupportedShaderModel == FFX_SHADER_MODEL_5_1, "shader model %d", int(caps.maximumSupportedShaderModel));
    CHECK(caps.dedicatedAllocationSupported == has(VK_KHR_DEDICATED_ALLOCATION_EXTENSION_NAME), "dedicatedAllocationSupported");
    EXPECT_FFX(FFX_ERROR_INVALID_POINTER, iface.fpGetDeviceCapabilities(&iface, nullptr));
    std::printf("fpGetDeviceCapabilities: wave lanes %u..%u, fp16 %d, ray tracing %d, synchronization2 %d\n",
                caps.waveLaneCountMin, caps.waveLaneCountMax, int(caps.fp16Supported), int(caps.raytracingSupported),
                int(caps.extendedSynchronizationSupported));
}

// What the SDK's sample does at start-up, with its version asserts.
static void integrate(Integration &in, uint32_t flags)
{
    in.deviceContext = VkDeviceContext{host.device, host.physicalDevice, vkGetDeviceProcAddr};
    size_t size = ffxGetScratchMemorySizeVK(host.physicalDevice, FFX_DENOISER_CONTEXT_COUNT);
    in.scratch.reset((unsigned char *)std::calloc(size, 1));
    FFX_CHECK(ffxGetInterfaceVK(&in.iface, ffxGetDeviceVK(&in.deviceContext), in.scratch.get(), size,
                                FFX_DENOISER_CONTEXT_COUNT));
    CHECK(in.iface.fpGetSDKVersion(&in.iface) == FFX_SDK_MAKE_VERSION(1, 1, 4), "fpGetSDKVersion");
    CHECK(ffxDenoiserGetEffectVersion() == FFX_SDK_MAKE_VERSION(1, 3, 0), "ffxDenoiserGetEffectVersion");
    check_capabilities(in.iface);
    in.iface.fpRegisterConstantBufferAllocator(&in.iface, nullptr);
    FfxDenoiserContextDescription desc = {};
    desc.flags = flags;
    desc.windowSize = {W, H};
    desc.backendInterface = in.iface;
    FFX_CHECK(ffxDenoiserContextCreate(in.context.get(), &desc));
}

// Returns the last noisy frame's output. fidelityfx: the FFX contexts get DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS and
// the dnsr.h context DNSR_PRESET_BALANCED; else both run dnsr's default settings. lightFlags (DNSR_DISPATCH_HARD_LIGHT,
// DNSR_DISPATCH_USE_LIGHT_POSITION) and lightPosition: told to the FFX contexts by dnsr_ffx_context_set_light (after
// which a refused call must leave them as they were), to the dnsr.h context in each dispatch. guided: the hit
// distances and lightAngle, told to the FFX contexts by dnsr_ffx_context_set_penumbra_guidance (after which a
// refused call must leave them as they were), to the dnsr.h context in each dispatch. hostPrevious: the FFX contexts
// get DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER and the (static) depth and normals as last frame's before every dispatch
// but the first, after one dispatch without them that must be refused; the dnsr.h context
// DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER and the same images in each dispatch.
static std::vector<float> frames_match_native(bool fidelityfx, uint32_t lightFlags = 0, const float *lightPosition = nullptr,
                                              bool guided = false, float lightAngle = 0.0f, bool hostPrevious = false)
{
    Integration in, in8;
    uint32_t settings = (fidelityfx ? DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS : 0u) | (hostPrevious ? DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER : 0u);
    // The sample's flags: shadows, plus the classifier's depth-inverted bit (1 << 3) the denoiser ignores.
    integrate(in, FFX_DENOISER_SHADOWS | (1u << 3) | settings);
    integrate(in8, FFX_DENOISER_SHADOWS | settings);
    DnsrContextCreateInfo info = host_create_info(&host, W, H);
    DnsrSettings balanced;
    DNSR_CHECK(dnsr_settings_init_preset(DNSR_PRESET_BALANCED, &balanced));
    if (fidelityfx) info.pSettings = &balanced;
    if (hostPrevious) info.flags |= DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER;
    DnsrContext native = nullptr;
    DNSR_CHECK(dnsr_context_create(&info, &native));
    if (lightFlags) {
        const float behind[4] = {0.0f, 0.0f, NAN, 0.0f};
        for (Integration *i : {&in, &in8}) {
            DNSR_CHECK(dnsr_ffx_context_set_light(i->context.get(), lightFlags, lightPosition, lightAngle));
            EXPECT_DNSR(DNSR_ERROR_NON_FINITE, dnsr_ffx_context_set_light(i->context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, behind, 0.0f));
        }
    }
    const DnsrHostImage hits = host_image_desc(&hitDistance);
    if (guided) {
        for (Integration *i : {&in, &in8}) {
            DNSR_CHECK(dnsr_ffx_context_set_penumbra_guidance(i->context.get(), &hits, lightAngle));
            EXPECT_DNSR(DNSR_ERROR_NON_FINITE, dnsr_ffx_context_set_penumbra_guidance(i->context.get(), &hits, NAN));
        }
    }

    std::vector<float> a, b, c, lastNoisy;
    for (uint32_t frame = 0; frame < 6; frame++) {
        bool allLit = frame >= 4;
        upload_mask(frame, allLit);
        VkCommandBuffer cmd = host_begin(&host);
        host_cmd_full_barrier(cmd);
        Dispatch fd = ffx_dispatch(cmd, frame);
        const DnsrHostImage previousDepth = host_image_desc(&depth), previousNormals = host_image_desc(&normals);
        if (hostPrevious && frame > 0) {
            if (frame == 1) EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchShadows(in.context.get(), &fd));
            for (Integration *i : {&in, &in8})
                DNSR_CHECK(dnsr_ffx_context_set_previous_gbuffer(i->context.get(), &previousDepth, &previousNormals));
        }
        FFX_CHECK(ffxDenoiserContextDispatchShadows(in.context.get(), &fd));
        Dispatch fd8 = ffx_dispatch(cmd, frame, outFfx8);
        FFX_CHECK(ffxDenoiserContextDispatchShadows(in8.context.get(), &fd8));
        DnsrShadowsDispatch nd = native_dispatch(cmd, frame);
        nd.flags |= lightFlags;
        if (hostPrevious) nd.previousDepth = previousDepth, nd.previousNormals = previousNormals;
        if (lightPosition) std::memcpy(nd.lightPosition, lightPosition, sizeof nd.lightPosition);
        nd.lightAngularSize = lightAngle;  // read with the light's position or hit distances
        if (guided) {
            nd.flags |= DNSR_DISPATCH_USE_HIT_DISTANCE;
            nd.hitDistance = hits;
        }
        DNSR_CHECK(dnsr_shadows_record(native, &nd));
        host_submit(&host, cmd);
        read_output(outFfx, a);
        read_output(outNative, b);
        read_output(outFfx8, c);
        for (uint32_t i = 0; i < W * H; i++) {
            CHECK(a[i] == b[i], "frame %u: FFX API %.9g, dnsr.h %.9g at (%u, %u)", frame, a[i], b[i], i % W, i / W);
            CHECK(std::fabs(c[i] - b[i]) <= 0.5f / 255.0f + 1e-6f, "frame %u: RGBA8 %.9g, dnsr.h %.9g at (%u, %u)", frame,
                  c[i], b[i], i % W, i / W);
        }
        float lo = a[0], hi = a[0];
        for (float v : a) lo = v < lo ? v : lo, hi = v > hi ? v : hi;
        std::printf("frame %u (%s settings, light flags 0x%x%s%s): FFX API == dnsr.h on all %u pixels, output in [%g, %g]\n",
                    frame, fidelityfx ? "FidelityFX" : "default", lightFlags, guided ? ", hit distances" : "",
                    hostPrevious ? ", host's previous G-buffer" : "", W * H, lo, hi);
        if (frame < 4) CHECK(hi > lo, "frame %u: a noisy mask gave a flat output", frame);
        if (frame == 3) lastNoisy = a;
    }
    // Two all-lit frames after noise: the history takes time, so only check the value is in range.
    for (float v : a) CHECK(v >= 0.0f && v <= 1.0f, "output %g outside [0, 1]", v);
    host_expect_clean(&host, "frames");
    FFX_CHECK(ffxDenoiserContextDestroy(in.context.get()));
    FFX_CHECK(ffxDenoiserContextDestroy(in8.context.get()));
    DNSR_CHECK(dnsr_context_destroy(native));
    return lastNoisy;
}

// ---- A pitching camera: the SDK's clip space has y up ----

// Column-major 4x4 matrices for column vectors, in double.
struct Mat4 {
    double m[16];
    double &at(int row, int col) { return m[col * 4 + row]; }
    double at(int row, int col) const { return m[col * 4 + row]; }
};
static Mat4 mul(const Mat4 &a, const Mat4 &b)
{
    Mat4 r = {};
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < 4; k++) r.at(i, j) += a.at(i, k) * b.at(k, j);
    return r;
}
static Mat4 inverse(Mat4 a)
{
    Mat4 r = {};
    for (int i = 0; i < 4; i++) r.at(i, i) = 1.0;
    for (int c = 0; c < 4; c++) {
        int p = c;
        for (int i = c + 1; i < 4; i++)
            if (std::fabs(a.at(i, c)) > std::fabs(a.at(p, c))) p = i;
        for (int j = 0; j < 4; j++) std::swap(a.at(c, j), a.at(p, j)), std::swap(r.at(c, j), r.at(p, j));
        double d = a.at(c, c);
        for (int j = 0; j < 4; j++) a.at(c, j) /= d, r.at(c, j) /= d;
        for (int i = 0; i < 4; i++) {
            if (i == c) continue;
            double f = a.at(i, c);
            for (int j = 0; j < 4; j++) a.at(i, j) -= f * a.at(c, j), r.at(i, j) -= f * r.at(c, j);
        }
    }
    return r;
}
static void store(float out[16], const Mat4 &m)
{
    for (int i = 0; i < 16; i++) out[i] = float(m.m[i]);
}

// Vulkan's clip space (y down, depth 0..1): a 60-degree perspective; the camera at the origin looking down -z,
// pitched by `degrees` about x.
static Mat4 vulkan_projection()
{
    double f = 1.0 / std::tan(M_PI / 6.0), n = 0.1, far = 100.0;
    Mat4 p = {};
    p.at(0, 0) = f * H / W;
    p.at(1, 1) = -f;
    p.at(2, 2) = far / (n - far);
    p.at(2, 3) = n * far / (n - far);
    p.at(3, 2) = -1.0;
    return p;
}
static Mat4 pitch(double degrees)
{
    double a = degrees * M_PI / 180.0;
    Mat4 v = {};
    v.at(0, 0) = v.at(3, 3) = 1.0;
    v.at(1, 1) = v.at(2, 2) = std::cos(a);
    v.at(1, 2) = -std::sin(a);
    v.at(2, 1) = std::sin(a);
    return v;
}

// SDK-style matrices (y-up clip space, what an integration of the SDK passes) through the FFX API give the same
// output, bit for bit, as the same camera's Vulkan-convention matrices through dnsr.h, over frames of a camera
// pitched 30 degrees and pitching 0.5 degrees more per frame, facing a wall 5 units away (its depth recomputed every frame); the Vulkan-
// convention matrices through the FFX API do not (they would mirror the reprojection and lose the history).
static void pitching_camera(void)
{
    Integration sdk, vulkan;
    integrate(sdk, FFX_DENOISER_SHADOWS);
    integrate(vulkan, FFX_DENOISER_SHADOWS);
    DnsrContextCreateInfo info = host_create_info(&host, W, H);
    DnsrContext native = nullptr;
    DNSR_CHECK(dnsr_context_create(&info, &native));
    Mat4 flip = {};
    flip.at(0, 0) = flip.at(2, 2) = flip.at(3, 3) = 1.0;
    flip.at(1, 1) = -1.0;
    Mat4 p = vulkan_projection(), pi = inverse(p);
    std::vector<float> a, b, c, depthData(W * H);
    uint32_t differing = 0;
    for (uint32_t frame = 0; frame < 6; frame++) {
        Mat4 vp = mul(p, pitch(30.0 + 0.5 * frame)), vpPrev = mul(p, pitch(30.0 + 0.5 * (frame ? frame - 1 : 0)));
        Mat4 vpi = inverse(vp), reprojection = mul(vpPrev, vpi);
        // The wall z = -5 seen through each pixel centre.
        for (uint32_t y = 0; y < H; y++) {
            for (uint32_t x = 0; x < W; x++) {
                double ndc[4] = {2.0 * (x + 0.5) / W - 1.0, 2.0 * (y + 0.5) / H - 1.0, 1.0, 1.0}, w[4] = {};
                for (int i = 0; i < 4; i++)
                    for (int k = 0; k < 4; k++) w[i] += vpi.at(i, k) * ndc[k];
                double t = -5.0 / (w[2] / w[3]);
                double world[4] = {t * w[0] / w[3], t * w[1] / w[3], -5.0, 1.0}, clip[4] = {};
                for (int i = 0; i < 4; i++)
                    for (int k = 0; k < 4; k++) clip[i] += vp.at(i, k) * world[k];
                depthData[y * W + x] = float(clip[2] / clip[3]);
            }
        }
        host_upload(&host, &depth, depthData.data(), depthData.size() * sizeof(float));
        upload_mask(100 + frame, false);
        VkCommandBuffer cmd = host_begin(&host);
        host_cmd_full_barrier(cmd);
        Dispatch fs = ffx_dispatch(cmd, frame);
        store(fs.projectionInverse, mul(pi, flip));
        store(fs.viewProjectionInverse, mul(vpi, flip));
        store(fs.reprojectionMatrix, mul(flip, mul(reprojection, flip)));
        FFX_CHECK(ffxDenoiserContextDispatchShadows(sdk.context.get(), &fs));
        Dispatch fv = ffx_dispatch(cmd, frame, outFfx8);
        store(fv.projectionInverse, pi);
        store(fv.viewProjectionInverse, vpi);
        store(fv.reprojectionMatrix, reprojection);
        FFX_CHECK(ffxDenoiserContextDispatchShadows(vulkan.context.get(), &fv));
        DnsrShadowsDispatch nd = native_dispatch(cmd, frame);
        store(nd.projectionInverse, pi);
        store(nd.viewProjectionInverse, vpi);
        store(nd.reprojectionMatrix, reprojection);
        DNSR_CHECK(dnsr_shadows_record(native, &nd));
        host_submit(&host, cmd);
        read_output(outFfx, a);
        read_output(outNative, b);
        read_output(outFfx8, c);
        differing = 0;
        for (uint32_t i = 0; i < W * H; i++) {
            CHECK(a[i] == b[i], "pitch frame %u: FFX API (SDK matrices) %.9g, dnsr.h %.9g at (%u, %u)", frame, a[i], b[i],
                  i % W, i / W);
            differing += std::fabs(c[i] - b[i]) > 1.0f / 255.0f;
        }
    }
    CHECK(differing > W * H / 10, "Vulkan-convention matrices through the FFX API differ on only %u pixels", differing);
    std::printf("pitching camera: SDK-style matrices through the FFX API == dnsr.h with Vulkan's on all %u pixels of 6 "
                "frames; Vulkan's through the FFX API differ on %u pixels of the last\n", W * H, differing);
    host_expect_clean(&host, "pitching camera");
    FFX_CHECK(ffxDenoiserContextDestroy(sdk.context.get()));
    FFX_CHECK(ffxDenoiserContextDestroy(vulkan.context.get()));
    DNSR_CHECK(dnsr_context_destroy(native));
}

// The depth buffer itself (D32_SFLOAT, described by ffxGetImageResourceDescriptionVK with DEPTHTARGET usage, where
// the SDK needed an R32_FLOAT copy), reverse-Z, with FFX_DENOISER_ENABLE_DEPTH_INVERTED: equal to dnsr.h with
// DNSR_CONTEXT_CREATE_DEPTH_INVERTED on the same image. Odd columns move 2 px, even ones stay: each 2x2 quad takes
// the motion of its closest pixel, which only the depth-inverted flag identifies (without it the outputs differ).
static void depth_buffer_reverse_z(void)
{
    Integration in;
    integrate(in, FFX_DENOISER_SHADOWS | FFX_DENOISER_ENABLE_DEPTH_INVERTED);
    DnsrContextCreateInfo info = host_create_info(&host, W, H);
    info.flags |= DNSR_CONTEXT_CREATE_DEPTH_INVERTED;
    DnsrContext native = nullptr;
    DNSR_CHECK(dnsr_context_create(&info, &native));
    std::vector<float> a, b;
    for (uint32_t frame = 0; frame < 3; frame++) {
        upload_mask(frame + 10, false);
        VkCommandBuffer cmd = host_begin(&host);
        host_cmd_full_barrier(cmd);
        Dispatch fd = ffx_dispatch(cmd, frame);
        fd.depth = resource(depthBuffer, FFX_RESOURCE_STATE_PIXEL_COMPUTE_READ, L"depth buffer");
        fd.velocity = resource(velocityVarying, FFX_RESOURCE_STATE_PIXEL_COMPUTE_READ, L"velocity");
        CHECK(fd.depth.description.usage & FFX_RESOURCE_USAGE_DEPTHTARGET, "D32_SFLOAT not described as a depth target");
        FFX_CHECK(ffxDenoiserContextDispatchShadows(in.context.get(), &fd));
        DnsrShadowsDispatch nd = native_dispatch(cmd, frame);
        nd.depth = host_image_desc(&depthBuffer);
        nd.velocity = host_image_desc(&velocityVarying);
        DNSR_CHECK(dnsr_shadows_record(native, &nd));
        host_submit(&host, cmd);
        read_output(outFfx, a);
        read_output(outNative, b);
        for (uint32_t i = 0; i < W * H; i++) {
            CHECK(a[i] == b[i], "reverse-Z frame %u: FFX API %.9g, dnsr.h %.9g at (%u, %u)", frame, a[i], b[i], i % W, i / W);
        }
    }
    std::printf("depth buffer, reverse-Z: FFX API == dnsr.h on 3 frames\n");
    host_expect_clean(&host, "reverse-Z");
    FFX_CHECK(ffxDenoiserContextDestroy(in.context.get()));
    DNSR_CHECK(dnsr_context_destroy(native));
}

static void misuse(void)
{
    Integration in;
    integrate(in, FFX_DENOISER_SHADOWS);
    FfxDenoiserContextDescription desc = {};
    desc.flags = FFX_DENOISER_SHADOWS;
    desc.windowSize = {W, H};
    desc.backendInterface = in.iface;
    FfxDenoiserContext *other = new FfxDenoiserContext;
    std::memset(other, 0, sizeof *other);

    EXPECT_FFX(FFX_ERROR_INVALID_POINTER, ffxDenoiserContextCreate(nullptr, &desc));
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextCreate(in.context.get(), &desc)); /* live: not orphaned */
    EXPECT_FFX(FFX_ERROR_INVALID_POINTER, ffxDenoiserContextCreate(other, nullptr));
    desc.flags = FFX_DENOISER_SHADOWS | FFX_DENOISER_REFLECTIONS;
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextCreate(other, &desc));
    desc.flags = FFX_DENOISER_SHADOWS;
    desc.windowSize = {0, H};
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextCreate(other, &desc));
    desc.windowSize = {W, H};
    FfxInterface handmade = {};
    desc.backendInterface = handmade;
    EXPECT_FFX(FFX_ERROR_INCOMPLETE_INTERFACE, ffxDenoiserContextCreate(other, &desc));
    desc.backendInterface = in.iface;

    FfxInterface iface;
    unsigned char small[4];
    EXPECT_FFX(FFX_ERROR_INSUFFICIENT_MEMORY,
               ffxGetInterfaceVK(&iface, ffxGetDeviceVK(&in.deviceContext), small, sizeof small, 1));
    EXPECT_FFX(FFX_ERROR_INVALID_POINTER, ffxGetInterfaceVK(nullptr, ffxGetDeviceVK(&in.deviceContext), small, 4, 1));
    EXPECT_FFX(FFX_ERROR_INVALID_POINTER, ffxGetInterfaceVK(&iface, nullptr, small, sizeof small, 1));

    // Dispatch misuse: nothing may be recorded (the command buffer is submitted and must stay valid and empty).
    VkCommandBuffer cmd = host_begin(&host);
    Dispatch d = ffx_dispatch(cmd, 0);
    EXPECT_FFX(FFX_ERROR_INVALID_POINTER, ffxDenoiserContextDispatchShadows(nullptr, &d));
    EXPECT_FFX(FFX_ERROR_INVALID_POINTER, ffxDenoiserContextDispatchShadows(in.context.get(), nullptr));
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchShadows(other, &d)); /* never created */
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchReflections(in.context.get(), nullptr));
    Dispatch bad = d;
    bad.depth.resource = nullptr;
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchShadows(in.context.get(), &bad));
    bad = d;
    bad.shadowMaskOutput.description.format = FFX_SURFACE_FORMAT_B8G8R8A8_UNORM;
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchShadows(in.context.get(), &bad));
    bad = d;
    bad.velocity.state = FFX_RESOURCE_STATE_INDIRECT_ARGUMENT;
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchShadows(in.context.get(), &bad));
    bad = d;
    bad.viewProjectionInverse[3] = NAN;
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchShadows(in.context.get(), &bad));
    host_submit(&host, cmd);

    // dnsr_ffx_context_set_light: the context, the bits, the position and the light's size.
    const float sun[4] = {0.3f, 0.8f, 0.2f, 0.0f}, zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, half[4] = {1.0f, 2.0f, 3.0f, 0.5f};
    const float inf[4] = {INFINITY, 0.0f, 1.0f, 1.0f};
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(nullptr, DNSR_DISPATCH_HARD_LIGHT, nullptr, 0.0f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(other, DNSR_DISPATCH_HARD_LIGHT, nullptr, 0.0f)); /* never created */
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_RESET, nullptr, 0.0f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(in.context.get(), 1u << 31, nullptr, 0.0f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, nullptr, 0.0f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, zero, 0.0f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, half, 0.0f));
    EXPECT_DNSR(DNSR_ERROR_NON_FINITE, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, inf, 0.0f));
    EXPECT_DNSR(DNSR_ERROR_NON_FINITE, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, sun, NAN));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, sun, -0.1f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, sun, 4.0f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT,
                dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION | DNSR_DISPATCH_HARD_LIGHT, sun, 0.01f));
    DNSR_CHECK(dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION | DNSR_DISPATCH_HARD_LIGHT, sun, 0.0f));
    DNSR_CHECK(dnsr_ffx_context_set_light(in.context.get(), 0, nullptr, 0.0f));

    // dnsr_ffx_context_set_penumbra_guidance: the context, the image's handles and the angle.
    DnsrHostImage hits = host_image_desc(&hitDistance), noImage = hits, noView = hits;
    noImage.image = VK_NULL_HANDLE;
    noView.view = VK_NULL_HANDLE;
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_penumbra_guidance(nullptr, &hits, 0.01f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_penumbra_guidance(other, &hits, 0.01f)); /* never created */
    EXPECT_DNSR(DNSR_ERROR_NULL_HANDLE, dnsr_ffx_context_set_penumbra_guidance(in.context.get(), &noImage, 0.01f));
    EXPECT_DNSR(DNSR_ERROR_NULL_HANDLE, dnsr_ffx_context_set_penumbra_guidance(in.context.get(), &noView, 0.01f));
    EXPECT_DNSR(DNSR_ERROR_NON_FINITE, dnsr_ffx_context_set_penumbra_guidance(in.context.get(), &hits, INFINITY));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_penumbra_guidance(in.context.get(), &hits, -0.01f));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_penumbra_guidance(in.context.get(), &hits, 3.5f));
    DNSR_CHECK(dnsr_ffx_context_set_penumbra_guidance(in.context.get(), &hits, 0.01f));
    // One light, one size: a dispatch refuses two different ones from the two calls, and records nothing.
    DNSR_CHECK(dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_USE_LIGHT_POSITION, sun, 0.02f));
    cmd = host_begin(&host);
    d = ffx_dispatch(cmd, 1);
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchShadows(in.context.get(), &d));
    host_submit(&host, cmd);
    DNSR_CHECK(dnsr_ffx_context_set_light(in.context.get(), 0, nullptr, 0.0f));
    DNSR_CHECK(dnsr_ffx_context_set_penumbra_guidance(in.context.get(), nullptr, NAN)); /* off: the angle is not read */

    // dnsr_ffx_context_set_previous_gbuffer: the context (and its flag), the descriptions and their handles.
    DnsrHostImage prevDepth = host_image_desc(&depth), prevNormals = host_image_desc(&normals), noDepthView = prevDepth;
    noDepthView.view = VK_NULL_HANDLE;
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_previous_gbuffer(nullptr, &prevDepth, &prevNormals));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_previous_gbuffer(other, &prevDepth, &prevNormals)); /* never created */
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_previous_gbuffer(in.context.get(), &prevDepth, &prevNormals)); /* no flag */
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_previous_gbuffer(in.context.get(), nullptr, &prevNormals));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_previous_gbuffer(in.context.get(), &prevDepth, nullptr));
    EXPECT_DNSR(DNSR_ERROR_NULL_HANDLE, dnsr_ffx_context_set_previous_gbuffer(in.context.get(), &noDepthView, &prevNormals));
    EXPECT_DNSR(DNSR_ERROR_NULL_HANDLE, dnsr_ffx_context_set_previous_gbuffer(in.context.get(), &prevDepth, &noImage));

    FFX_CHECK(ffxDenoiserContextDestroy(in.context.get()));
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_light(in.context.get(), DNSR_DISPATCH_HARD_LIGHT, nullptr, 0.0f)); /* destroyed */
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_penumbra_guidance(in.context.get(), nullptr, 0.0f)); /* destroyed */
    EXPECT_DNSR(DNSR_ERROR_INVALID_ARGUMENT, dnsr_ffx_context_set_previous_gbuffer(in.context.get(), &prevDepth, &prevNormals)); /* destroyed */
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDestroy(in.context.get())); /* twice */
    cmd = host_begin(&host);
    d = ffx_dispatch(cmd, 1);
    EXPECT_FFX(FFX_ERROR_INVALID_ARGUMENT, ffxDenoiserContextDispatchShadows(in.context.get(), &d)); /* destroyed */
    host_submit(&host, cmd);
    EXPECT_FFX(FFX_ERROR_INVALID_POINTER, ffxDenoiserContextDestroy(nullptr));
    delete other;
    host_expect_clean(&host, "misuse");
}

int main(void)
{
    host_create(&host);
    VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    host_image_create(&host, &mask, VK_FORMAT_R32_UINT, TILES_X, TILES_Y, VK_IMAGE_LAYOUT_GENERAL);
    host_image_create(&host, &depth, VK_FORMAT_R32_SFLOAT, W, H, read);
    host_image_create(&host, &depthBuffer, VK_FORMAT_D32_SFLOAT, W, H, read);
    host_image_create(&host, &velocityVarying, VK_FORMAT_R32G32_SFLOAT, W, H, read);
    host_image_create(&host, &velocity, VK_FORMAT_R16G16_SFLOAT, W, H, read);
    host_image_create(&host, &normals, VK_FORMAT_R8G8B8A8_UNORM, W, H, read);
    host_image_create(&host, &outFfx, VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_LAYOUT_GENERAL);
    host_image_create(&host, &outNative, VK_FORMAT_R32_SFLOAT, W, H, VK_IMAGE_LAYOUT_GENERAL);
    host_image_create(&host, &outFfx8, VK_FORMAT_R8G8B8A8_UNORM, W, H, VK_IMAGE_LAYOUT_GENERAL);
    host_image_create(&host, &hitDistance, VK_FORMAT_R32_SFLOAT, W, H, read);
    host_buffer_create(&host, &readback, W * H * sizeof(float));
    std::vector<float> depthData(W * H);
    std::vector<uint16_t> velocityData(W * H * 2, 0);
    std::vector<uint8_t> normalData(W * H * 4);
    for (uint32_t i = 0; i < W * H; i++) {
        depthData[i] = 0.4f + 0.2f * float(i % W) / W;
        normalData[4 * i + 0] = normalData[4 * i + 1] = 128; /* (0, 0, 1) packed as rgb * 2 - 1 */
        normalData[4 * i + 2] = 255;
    }
    host_upload(&host, &depth, depthData.data(), depthData.size() * sizeof(float));
    for (float &d : depthData) d = 1.0f - d; /* the same surfaces in reverse-Z */
    std::vector<float> varying(W * H * 2, 0.0f);
    for (uint32_t i = 0; i < W * H; i++) varying[2 * i] = (i % W) % 2 ? 2.0f / W : 0.0f;
    host_upload(&host, &velocityVarying, varying.data(), varying.size() * sizeof(float));
    host_upload(&host, &depthBuffer, depthData.data(), depthData.size() * sizeof(float));
    host_upload(&host, &velocity, velocityData.data(), velocityData.size() * sizeof(uint16_t));
    host_upload(&host, &normals, normalData.data(), normalData.size());
    // Hit distances from contact (a penumbra far under a pixel: the ray is the output) to far blockers.
    std::vector<float> hitData(W * H);
    for (uint32_t i = 0; i < W * H; i++) hitData[i] = 0.001f + 2.0f * float(i % W) / W;
    host_upload(&host, &hitDistance, hitData.data(), hitData.size() * sizeof(float));

    {
        std::vector<float> quality = frames_match_native(false), fidelityfx = frames_match_native(true);
        size_t differ = 0;
        for (size_t i = 0; i < quality.size(); i++) differ += quality[i] != fidelityfx[i];
        CHECK(differ > 0, "DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS changed no pixel of frame 3");
        std::printf("DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS: %zu of %u pixels of frame 3 differ from the default's\n",
                    differ, W * H);
        // The light through dnsr_ffx_context_set_light: behind every receiver (their normals face +z), so that each
        // shadowed ray is its receiver's output; then a light of no size.
        const float behind[4] = {0.2f, -0.1f, -1.0f, 0.0f};
        for (uint32_t flags : {DNSR_DISPATCH_USE_LIGHT_POSITION, DNSR_DISPATCH_HARD_LIGHT}) {
            std::vector<float> told = frames_match_native(false, flags, behind);
            differ = 0;
            for (size_t i = 0; i < quality.size(); i++) differ += quality[i] != told[i];
            CHECK(differ > 0, "dnsr_ffx_context_set_light(0x%x) changed no pixel of frame 3", flags);
            std::printf("dnsr_ffx_context_set_light(0x%x): %zu of %u pixels of frame 3 differ from the untold default's\n",
                        flags, differ, W * H);
        }
        // Hit distances through dnsr_ffx_context_set_penumbra_guidance, a light of about 3 degrees.
        std::vector<float> guided = frames_match_native(false, 0, nullptr, true, 0.05f);
        differ = 0;
        for (size_t i = 0; i < quality.size(); i++) differ += quality[i] != guided[i];
        CHECK(differ > 0, "dnsr_ffx_context_set_penumbra_guidance changed no pixel of frame 3");
        std::printf("dnsr_ffx_context_set_penumbra_guidance: %zu of %u pixels of frame 3 differ from the unguided default's\n",
                    differ, W * H);
        // The host's previous depth and normals instead of the context's depth copy (the same images every frame:
        // a still camera).
        std::vector<float> hostPrevious = frames_match_native(false, 0, nullptr, false, 0.0f, true);
        differ = 0;
        for (size_t i = 0; i < quality.size(); i++) differ += quality[i] != hostPrevious[i];
        std::printf("DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER: %zu of %u pixels of frame 3 differ from the depth copy's\n",
                    differ, W * H);
    }
    depth_buffer_reverse_z();
    misuse();
    pitching_camera();

    host_buffer_destroy(&host, &readback);
    for (HostImage *img : {&mask, &depth, &depthBuffer, &velocity, &velocityVarying, &normals, &outFfx, &outFfx8, &outNative, &hitDistance}) host_image_destroy(&host, img);
    host_destroy(&host);
    std::printf("ffx_dropin: layout, versions, 6 frames equal to dnsr.h (R32F and RGBA8 outputs; untold, told the light's "
                "position, told it has no size, given hit distances, given the previous G-buffer), %d misuse cases refused\n", cases);
    return 0;
}

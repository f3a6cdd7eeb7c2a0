// renderer.h: the viewer's frame, recorded into one command buffer the way an engine would:
//
//   primary.comp    camera rays -> G-buffer (depth, normal, motion vectors, albedo, shadow-ray origin)
//   shadow.comp     per light, one jittered shadow ray per pixel (with --checkerboard, for half the pixels) -> the
//                   light's 8x4-tile hit mask (and, for dnsr's penumbra guidance, the distance to the nearest
//                   occluder per pixel)
//   or, in hybrid mode (--hybrid, key C; one directional light):
//     cascade.comp        the sun's cascaded shadow maps (cascades.h), traced since the viewer has no rasteriser
//     dnsr classifier     (denoiser.h) dnsr_classify_record: G-buffer + cascades -> the hit mask prefilled where
//                         the cascades decide, and the list of tiles whose other pixels need a ray
//     shadow_listed.comp  one workgroup per listed tile (vkCmdDispatchIndirect on the classifier's counts): the
//                         listed pixels' shadow rays, within the interval the cascades bound, ORed into the mask
//   reference.comp  (when asked) per light, many shadow rays per pixel -> the ground truth, for error measurements
//   dnsr            (denoiser.h) dnsr_shadows_record (one light) or dnsr_lights_record (all lights in one call):
//                   hit masks + G-buffer -> one denoised shadow per light
//   composite.comp  albedo * (ambient + sum over the lights of N.L * shadow), or a debug view of one light -> the
//                   display image
//
// Every image stays in layout GENERAL. The renderer never submits: the caller submits the command buffer and
// waits for it before calling afterFrame() and recording the next frame (one frame in flight keeps the sample
// simple; an engine would keep a few, with one set of per-frame resources each).
#pragma once

#include <vector>

#include "bvh.h"
#include "cascades.h"
#include "denoiser.h"
#include "scene_gltf.h"
#include "vk_context.h"

// At most this many lights (shaders/common.glsl's kMaxLights, with their own bindings for each light's images).
constexpr uint32_t kMaxLights = 2;

// Views 5..8 and 11 ask dnsr itself for a debug view of its internal state (DnsrShadowsDispatch::debugView),
// shown like the denoised shadow.
enum class View : uint32_t {
    Noisy = 0,
    Denoised = 1,
    Reference = 2,
    Composite = 3,
    TileDensity = 4,
    DnsrTiles = 5,
    DnsrSampleCount = 6,
    DnsrVariance = 7,
    DnsrDisocclusion = 8,
    Hybrid = 9,       // what decided each pixel: the cascades or a ray (hybrid mode)
    TracedTiles = 10, // the fraction of each tile's pixels traced this frame
    DnsrSampleRun = 11, // dnsr's debug view of each pixel's run of identical samples
};

// dnsr's debug views in DnsrDebugView order from DNSR_DEBUG_VIEW_TILE_CLASSIFICATION: the name --debug-view and
// report.json's "debug_view" give each, and the view that shows it.
struct DnsrViewName {
    const char *name;
    View view;
};
constexpr DnsrViewName kDnsrViews[] = {{"classification", View::DnsrTiles}, {"samples", View::DnsrSampleCount},
                                       {"variance", View::DnsrVariance},     {"disocclusion", View::DnsrDisocclusion},
                                       {"run", View::DnsrSampleRun}};
constexpr uint32_t kDnsrViewCount = sizeof(kDnsrViews) / sizeof(kDnsrViews[0]);

// The DnsrDebugView that view v asks dnsr for (DNSR_DEBUG_VIEW_NONE for the viewer's own views).
inline DnsrDebugView dnsrDebugView(View v) {
    for (uint32_t i = 0; i < kDnsrViewCount; ++i) {
        if (kDnsrViews[i].view == v) return DNSR_DEBUG_VIEW_TILE_CLASSIFICATION + i;
    }
    return DNSR_DEBUG_VIEW_NONE;
}

// Hybrid shadows: the cascades, dnsr's classifier and the trace of the pixels it lists.
struct HybridSettings {
    bool enabled = false;      // create what hybrid mode needs (FrameInput::hybrid then picks the mode per frame)
    uint32_t cascades = 2;     // 1..kMaxCascades
    uint32_t cascadeSize = 0;  // texels per side; 0: the render size's larger side rounded up to a power of two
    uint32_t taps = 24;        // the classifier's blocker-search taps: 8, 16, 24 or 32
    uint32_t tileCutoff = 0;   // a tile is listed with more pixels to trace than this (0..31)
    float blockerOffset = -1;  // world units a cascade depth must be in front of the receiver to block it;
                               // negative: two texels of the finest cascade (it moves with the camera)
    bool reverseRays = false;  // trace from the light's end of the classifier's interval (not with guidance)
};

struct RendererSettings {
    uint32_t width = 0, height = 0;
    float sceneRadius = 1.0f;  // sets the shadow-ray offset
    float ambient = 0.2f;
    DnsrPreset preset = DNSR_PRESET_QUALITY;  // dnsr's settings (dnsr_settings_init_preset)
    std::vector<std::pair<std::string, double>> settingOverrides;  // then these (DenoiserSettings::overrides)
    // Linear depth and octahedral normals, read by dnsr through custom callbacks (examples-c/custom_gbuffer).
    bool packedGbuffer = false;
    // Normal-map-like detail (--normal-detail): the shading normal tilted by up to this x 60 degrees in a world-space
    // pattern whose period is 4% of the scene's radius; 0 keeps the interpolated normal.
    float normalDetail = 0.0f;
    bool normalDetailDnsrOnly = false;  // the detail in dnsr's packed normals alone (packedGbuffer)
    // Shadow rays per pixel: 1 packs them into the hit mask; more go to dnsr as per-pixel visibility.
    uint32_t rays = 1;
    // Half a ray per pixel (DNSR_SHADOW_INPUT_CHECKERBOARD, with rays 1): each frame only the pixels with
    // (x + y) % 2 == frame index % 2 are traced.
    bool checkerboard = false;
    // 1..kMaxLights lights, each with its own shadow rays, dnsr history (DnsrContextCreateInfo::lightCount) and output.
    uint32_t lights = 1;
    Vec3 sceneCenter;  // with sceneRadius, the sphere the cascades cover
    HybridSettings hybrid;
};

struct FrameInput {
    Mat4 viewMatrix, projection;
    Vec3 eye;
    // The lights (RendererSettings::lights of them, all of one kind and size): a direction towards each
    // (directional) or its position (point), and their size: tan of the angular radius (directional) or the sphere
    // radius (point).
    bool pointLight = false;
    Vec3 lights[kMaxLights];
    float lightSize = 0.05f;
    // Penumbra guidance (DNSR_DISPATCH_USE_HIT_DISTANCE): the shadow pass also writes the distance to the nearest
    // occluder, and dnsr narrows its filter to the penumbra that distance and the light's angular diameter
    // (radians, as seen from the receivers) imply.
    bool hitDistance = false;
    float lightAngularSize = 0.0f;
    // The light has no size and dnsr is told so (DNSR_DISPATCH_HARD_LIGHT): its rays are the output.
    bool hardLight = false;
    // dnsr is told where each light is (DNSR_DISPATCH_USE_LIGHT_POSITION): `lights` as homogeneous points.
    bool lightPosition = false;
    bool cameraCut = false;          // discard dnsr's history (first frame, view reset)
    // Hybrid mode (needs RendererSettings::hybrid.enabled): rays only where dnsr's classifier cannot decide from
    // the cascades. With penumbra guidance, only the traced pixels have a hit distance (the others 0: unknown).
    bool hybrid = false;
    View display = View::Composite;  // what composite.comp writes to the display image
    uint32_t shownLight = 0;         // the light the views other than the composite show (dnsr's included)
    bool resetReference = false;     // restart the reference accumulation (camera or light changed)
    uint32_t referenceSamples = 0;   // reference samples per pixel to add this frame
};

// GPU time of the viewer's own passes in the last completed frame, in milliseconds.
// cascades and classify are 0 outside hybrid mode; shadow is then the trace of the listed pixels only.
struct ViewerTimings {
    double primary = 0, cascades = 0, classify = 0, shadow = 0, reference = 0, dnsr = 0, composite = 0;
};

class Renderer {
public:
    void create(VulkanContext &ctx, const Scene &scene, const RendererSettings &settings);
    void destroy();

    // Records one frame into `cmd` (being recorded). Throws VulkanError when dnsr refuses the dispatch.
    void recordFrame(VkCommandBuffer cmd, const FrameInput &input);
    // After the GPU finished the frame: fetch the timings (the viewer's timestamps and dnsr's).
    void afterFrame();
    // Copies the G-buffer, each light's hit mask, denoised shadow and reference sum, and the display image to host
    // memory (after a recordFrame in the same command buffer); read them with the accessors below once the GPU is
    // done.
    void recordReadback(VkCommandBuffer cmd);

    const float *readDepth() const { return at<float>(depthOffset_); }
    const uint32_t *readHitMask(uint32_t light) const { return at<uint32_t>(lights_[light].maskOffset); }
    const float *readDenoised(uint32_t light) const { return at<float>(lights_[light].denoisedOffset); }
    const float *readReferenceSum(uint32_t light) const { return at<float>(lights_[light].referenceOffset); }
    const uint8_t *readDisplay() const { return at<uint8_t>(displayOffset_); }
    // Per tile, the pixels whose shadow ray the frame traced (bit as in the hit mask): in hybrid mode the ones the
    // classifier listed, otherwise tracedBits() (sky pixels included, though no ray is cast for them).
    const uint32_t *readTraced() const { return at<uint32_t>(tracedOffset_); }
    // RGBA16F texels (raw half floats), for checking the G-buffer against dnsr's CPU reference.
    const uint16_t *readNormals() const { return at<uint16_t>(normalsOffset_); }
    const uint16_t *readVelocity() const { return at<uint16_t>(velocityOffset_); }

    const GpuImage &displayImage() const { return display_; }
    uint32_t referenceCount() const { return referenceCount_; }
    uint32_t tilesX() const { return (settings_.width + 7) / 8; }
    uint32_t tilesY() const { return (settings_.height + 3) / 4; }
    uint32_t lightCount() const { return settings_.lights; }
    // The hit-mask bits the last recorded frame traced, the same word for every tile (tiles start at even x and
    // y): all of them, or with --checkerboard those of the pixels with (x + y) % 2 == the frame's phase.
    uint32_t tracedBits() const { return tracedBits_; }
    uint64_t dnsrMemoryBytes() const { return denoiser_.memoryBytes(); }
    uint32_t cascadeSize() const { return cascadeSize_; }

    DnsrPassTimings dnsrTimings{};  // dnsr's per-pass GPU times (valid when haveDnsrTimings)
    bool haveDnsrTimings = false;
    double dnsrClassifyMs = 0.0;  // dnsr's own GPU time of its classifier (hybrid mode; 0 until one completed)
    ViewerTimings viewerTimings;
    uint32_t bvhNodes = 0, bvhDepth = 0, triangles = 0;

private:
    // What each light has of its own: the shadow pass's outputs, dnsr's output and the reference, and where the
    // readback puts them.
    struct LightResources {
        GpuImage hitMask, hitDistance, visibility, denoised, reference;
        VkDeviceSize maskOffset = 0, denoisedOffset = 0, referenceOffset = 0;
    };

    template <typename T> const T *at(VkDeviceSize offset) const
    {
        return reinterpret_cast<const T *>(static_cast<const uint8_t *>(readback_.mapped) + offset);
    }
    void createDescriptors();
    std::vector<GpuImage *> images();  // every image, for the initial clear and destroy()
    void bind(VkCommandBuffer cmd, VkPipeline pipeline, uint32_t mode = 0, uint32_t sampleBase = 0,
              uint32_t sampleCount = 0, uint32_t light = 0);
    void dispatch(VkCommandBuffer cmd, VkPipeline pipeline, uint32_t groupsX, uint32_t groupsY, uint32_t mode = 0,
                  uint32_t sampleBase = 0, uint32_t sampleCount = 0, uint32_t light = 0);
    // Hybrid mode: cascades, classifier, the listed pixels' rays (instead of shadow.comp).
    void recordHybridShadows(VkCommandBuffer cmd, const FrameInput &in, const DenoiserFrame &frame);

    VulkanContext *ctx_ = nullptr;
    RendererSettings settings_;
    Denoiser denoiser_;
    uint32_t frameIndex_ = 0;
    uint32_t referenceCount_ = 0;
    uint32_t tracedBits_ = ~0u;
    Mat4 prevViewProj_;

    GpuBuffer frameConstants_, nodes_, triGeometry_, triShading_, readback_;
    GpuImage rayOrigin_, depth_, normals_, velocity_, albedo_, display_;
    GpuImage linearDepth_, octNormals_;  // --gbuffer packed
    LightResources lights_[kMaxLights];  // the first settings_.lights are created
    // Hybrid mode: the cascades (1x1 placeholders without it), the traced pixels per tile, dnsr's tile list and
    // counts (its classifier's buffers), where the cascades lie this frame.
    GpuImage cascades_[kMaxCascades], traced_;
    VkBuffer tileList_ = VK_NULL_HANDLE, tileCounts_ = VK_NULL_HANDLE;
    CascadeSet cascadeSet_;
    uint32_t cascadeSize_ = 0;
    VkDeviceSize depthOffset_ = 0, displayOffset_ = 0, normalsOffset_ = 0, velocityOffset_ = 0, tracedOffset_ = 0;

    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkDescriptorPool descriptorPool_ = VK_NULL_HANDLE;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
    VkPipeline primary_ = VK_NULL_HANDLE, shadow_ = VK_NULL_HANDLE, reference_pipeline_ = VK_NULL_HANDLE,
               composite_ = VK_NULL_HANDLE, cascade_ = VK_NULL_HANDLE, shadowListed_ = VK_NULL_HANDLE;
    VkQueryPool timestamps_ = VK_NULL_HANDLE;
};

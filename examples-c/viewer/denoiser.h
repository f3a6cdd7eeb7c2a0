// denoiser.h: how to integrate dnsr. Every dnsr_* call of the viewer is in denoiser.cpp, in the order an engine
// makes them; this is the part to copy. The rest of the viewer only plays the engine around it: it owns the
// Vulkan device, the G-buffer and the shadow rays, and hands dnsr their images.
//
//   1. device creation   addDenoiserDeviceExtensions: the extensions dnsr needs (dnsr_get_device_requirements)
//   2. once              Denoiser::create: the context (dnsr_context_create) and its settings (a preset)
//   3. every frame       Denoiser::recordDenoise, after the shadow rays: dnsr_shadows_record, or dnsr_lights_record
//                        for several lights in one call. In hybrid mode, before the rays: Denoiser::recordClassify
//                        (dnsr_classify_record) prefills the hit mask from the cascaded shadow maps and lists the
//                        tiles still to trace (Denoiser::classifierBuffers: dnsr_context_get_classifier_buffers)
//   4. after the frame   Denoiser::fetchTimings: dnsr's per-pass GPU times (dnsr_context_get_timings), and in
//                        hybrid mode Denoiser::fetchClassifierTimings (dnsr_context_get_classifier_timings)
//   5. at the end        Denoiser::destroy, once the GPU is idle (dnsr_context_destroy)
//
// Another dnsr dispatch of the frame (one recorded before the shadow rays, say) goes next to recordDenoise: it
// takes the same DenoiserFrame, whose G-buffer and camera every dispatch reads.
#pragma once

#include <dnsr.h>

#include <string>
#include <utility>
#include <vector>

#include "cascades.h"
#include "vec_math.h"
#include "vk_context.h"

// Before vkCreateDevice: appends the device extensions dnsr needs to `extensions` (VulkanError when the device
// lacks one or is too old), and VK_KHR_push_descriptor when the device has it. Returns whether it added that one:
// the context is then told (DNSR_FEATURE_PUSH_DESCRIPTOR) and keeps its descriptors in the command buffer.
bool addDenoiserDeviceExtensions(VkPhysicalDevice physicalDevice, uint32_t apiVersion,
                                 std::vector<const char *> &extensions);

struct DenoiserSettings {
    uint32_t width = 0, height = 0;
    uint32_t lights = 1;  // each light keeps its own history in the one context
    // DNSR_SHADOW_INPUT_HIT_MASK (one ray per pixel in an 8x4-tile bit mask), _VISIBILITY (several rays per pixel,
    // their lit fraction) or _CHECKERBOARD (half a ray per pixel in the hit mask).
    uint32_t shadowInput = DNSR_SHADOW_INPUT_HIT_MASK;
    // The engine's own G-buffer encoding (linear depth, octahedral normals): dnsr runs its passes compiled against
    // the engine's callbacks (examples-c/custom_gbuffer) instead of reading the default formats.
    bool packedGbuffer = false;
    DnsrPreset preset = DNSR_PRESET_QUALITY;
    // Single settings changed after the preset filled them (--set), by their DnsrSettings field names:
    // dnsr_context_set_settings checks the values.
    std::vector<std::pair<std::string, double>> overrides;
    bool classifier = false;  // hybrid shadows: recordClassify (DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER)
};

// Whether `name` is a DnsrSettings field that DenoiserSettings::overrides may set; every such name, for messages.
bool isDenoiserSetting(const std::string &name);
std::string denoiserSettingNames();

// What every dnsr dispatch of one frame reads: the G-buffer, the camera and where the frame is in the sequence.
struct DenoiserFrame {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    const GpuImage *depth = nullptr, *velocity = nullptr, *normals = nullptr;
    Mat4 projectionInverse, viewProjectionInverse;
    Mat4 reprojection;  // current clip -> previous clip (reprojection() in vec_math.h: double precision matters)
    Vec3 eye;
    uint32_t frameIndex = 0;
    uint32_t checkerboardPhase = 0;  // DNSR_SHADOW_INPUT_CHECKERBOARD: the (x + y) % 2 this frame traced
    bool cameraCut = false;          // the history no longer matches the view: dnsr restarts it
};

// One light's images: what the shadow pass wrote for it, and where dnsr writes its shadow.
struct DenoiserLight {
    const GpuImage *hitMask = nullptr;      // DNSR_SHADOW_INPUT_HIT_MASK and _CHECKERBOARD
    const GpuImage *visibility = nullptr;   // DNSR_SHADOW_INPUT_VISIBILITY
    const GpuImage *hitDistance = nullptr;  // penumbra guidance; null: off
    float lightAngularSize = 0.0f;          // with hitDistance or useLightPosition: the light's angular diameter, radians
    bool hardLight = false;                 // the light has no size: its rays are exact (DNSR_DISPATCH_HARD_LIGHT)
    bool useLightPosition = false;          // lightPosition is given (DNSR_DISPATCH_USE_LIGHT_POSITION)
    float lightPosition[4] = {};            // world space: {direction to the light, 0} or {centre, 1}
    const GpuImage *output = nullptr;
};

// Hybrid shadows: what the classifier reads besides the frame's G-buffer, and the hit mask it prefills.
struct DenoiserClassify {
    const GpuImage *hitMask = nullptr;  // the one light's mask: prefilled here, completed by the trace, denoised
    Vec3 toLight;                       // the sun (a directional light)
    float lightAngularSize = 0.0f;      // its angular diameter, radians: how far the blocker search reaches
    const CascadeSet *cascades = nullptr;
    const GpuImage *cascadeImages[kMaxCascades] = {};  // the first cascades->count
    float blockerOffset = 0.0f;         // world units (the shadow maps' bias)
    uint32_t taps = 24, tileCutoff = 0;
};

class Denoiser {
public:
    // VulkanError with dnsr's own message when it refuses.
    void create(const VulkanContext &ctx, const DenoiserSettings &settings);
    void destroy();

    // Records the denoising of `lights` (one per light of the context) into frame.cmd, behind the shadow pass.
    // debugView: DNSR_DEBUG_VIEW_NONE, or one of dnsr's views of its internal state, written to every output.
    void recordDenoise(const DenoiserFrame &frame, const std::vector<DenoiserLight> &lights, uint32_t debugView);

    // Hybrid shadows, behind the G-buffer and the cascades and before the trace: prefills c.hitMask where the
    // cascades decide and lists the tiles to trace in classifierBuffers(), their count as indirect dispatch
    // arguments (one workgroup per tile). The barriers after it cover a compute trace sized by those counts.
    void recordClassify(const DenoiserFrame &frame, const DenoiserClassify &c);
    // dnsr's tile list and counts (context created with DenoiserSettings::classifier): fixed until a resize.
    void classifierBuffers(VkBuffer &tiles, VkBuffer &counts) const;

    // After the GPU finished a frame: dnsr's per-pass GPU times. False until a frame's timings are available.
    bool fetchTimings(DnsrPassTimings &timings);
    // The GPU time of dnsr's most recent completed classifier dispatch (dnsr_context_get_classifier_timings;
    // the context must have the classifier); false before one has completed.
    bool fetchClassifierTimings(double &classifyMs);
    uint64_t memoryBytes() const;

private:
    DnsrShadowsDispatch frameDispatch(const DenoiserFrame &frame) const;

    DnsrContext context_ = nullptr;
};

// denoiser.cpp: see denoiser.h. dnsr's C API (include/dnsr.h), called as an engine calls it.
#include "denoiser.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

namespace {

// dnsr's passes compiled against examples-c/custom_gbuffer/engine_callbacks.glsl by its build_shaders.sh (CMake),
// for --gbuffer packed: an engine whose G-buffer dnsr cannot read as is compiles dnsr's shader sources with its
// own read functions and hands the SPIR-V over at context creation.
const uint32_t kDnsrClassification[] =
#include "dnsr_engine/tile_classification_r32f.inc"
    ;
const uint32_t kDnsrFilter[] =
#include "dnsr_engine/filter.inc"
    ;
const uint32_t kDnsrFilterLater[] =
#include "dnsr_engine/filter_later.inc"
    ;
const uint32_t kDnsrFilterFinal[] =
#include "dnsr_engine/filter_final_r32f.inc"
    ;
const uint32_t kDnsrFilterLaterFinal[] =
#include "dnsr_engine/filter_later_final_r32f.inc"
    ;
const uint32_t kDnsrClassify[] =
#include "dnsr_engine/classify.inc"
    ;
const DnsrShaderOverride kPackedOverrides[] = {
    {"tile_classification_r32f", kDnsrClassification, sizeof kDnsrClassification},
    {"filter", kDnsrFilter, sizeof kDnsrFilter},
    {"filter_later", kDnsrFilterLater, sizeof kDnsrFilterLater},
    {"filter_final_r32f", kDnsrFilterFinal, sizeof kDnsrFilterFinal},
    {"filter_later_final_r32f", kDnsrFilterLaterFinal, sizeof kDnsrFilterLaterFinal},
    {"classify", kDnsrClassify, sizeof kDnsrClassify},  // --hybrid: the classifier reads the packed G-buffer too
};

// Every dnsr call returns a DnsrResult; dnsr_last_error_message() says which field was wrong and why.
// DnsrSettings' fields by name, for --set: every one but filterPasses is a float.
struct SettingField {
    const char *name;
    float DnsrSettings::*field;
};
#define DNSR_VIEWER_SETTING(f) SettingField{#f, &DnsrSettings::f}
const SettingField kSettingFields[] = {
    DNSR_VIEWER_SETTING(disocclusionThresholdFacing), DNSR_VIEWER_SETTING(disocclusionThresholdGrazing),
    DNSR_VIEWER_SETTING(disocclusionAngleExponent),   DNSR_VIEWER_SETTING(spatialFalloff),
    DNSR_VIEWER_SETTING(historyClampSigmas),          DNSR_VIEWER_SETTING(historyRejectionFalloff),
    DNSR_VIEWER_SETTING(historyRejectionMinSigma),    DNSR_VIEWER_SETTING(varianceBoostSamples),
    DNSR_VIEWER_SETTING(fullHistorySamples),          DNSR_VIEWER_SETTING(minCurrentWeight),
    DNSR_VIEWER_SETTING(maxHistorySamples),           DNSR_VIEWER_SETTING(kernelCrossWeight),
    DNSR_VIEWER_SETTING(normalPower),                 DNSR_VIEWER_SETTING(outputContrast),
    DNSR_VIEWER_SETTING(minShadowSigma),              DNSR_VIEWER_SETTING(stableHistorySamples),
    DNSR_VIEWER_SETTING(historyFlipSamples),          DNSR_VIEWER_SETTING(convergedSamples),
    DNSR_VIEWER_SETTING(hardPenumbraPixels),          DNSR_VIEWER_SETTING(movingShadowSigmas),
    DNSR_VIEWER_SETTING(movingHistoryClampSigmas),    DNSR_VIEWER_SETTING(hardTileFrames),
    DNSR_VIEWER_SETTING(geometricNormalDegrees),
};
#undef DNSR_VIEWER_SETTING

void applySetting(DnsrSettings &s, const std::string &name, double value)
{
    if (name == "filterPasses") {
        // A whole number (--set checks it); one out of range reaches dnsr, which says its range.
        s.filterPasses = uint32_t(std::min(value, 1e9));
        return;
    }
    for (const SettingField &f : kSettingFields)
        if (name == f.name) s.*f.field = float(value);
}

[[noreturn]] void dnsrFail(const char *call, DnsrResult r)
{
    throw VulkanError(std::string(call) + " failed: " + dnsr_result_to_string(r) + ": " + dnsr_last_error_message());
}

// dnsr borrows the engine's images for the frame; the viewer keeps all of them in layout GENERAL.
DnsrHostImage hostImage(const GpuImage &img)
{
    return DnsrHostImage{img.image, img.view, img.format, VK_IMAGE_LAYOUT_GENERAL, img.width, img.height};
}

DnsrHostImage hostImage(const GpuImage *img) { return img ? hostImage(*img) : DnsrHostImage{}; }

}  // namespace

bool isDenoiserSetting(const std::string &name)
{
    if (name == "filterPasses") return true;
    for (const SettingField &f : kSettingFields)
        if (name == f.name) return true;
    return false;
}

std::string denoiserSettingNames()
{
    std::string names = "filterPasses";
    for (const SettingField &f : kSettingFields) names += std::string(", ") + f.name;
    return names;
}

bool addDenoiserDeviceExtensions(VkPhysicalDevice physicalDevice, uint32_t apiVersion,
                                 std::vector<const char *> &extensions)
{
    DnsrDeviceRequirements req{};
    req.sType = DNSR_STRUCTURE_TYPE_DEVICE_REQUIREMENTS;
    if (dnsr_get_device_requirements(&req) != DNSR_SUCCESS)
        throw VulkanError(std::string("dnsr_get_device_requirements: ") + dnsr_last_error_message());
    if (apiVersion < req.minApiVersion) throw VulkanError("the device's Vulkan version is too old for dnsr");
    for (uint32_t i = 0; i < req.requiredExtensionCount; i++) {
        const char *name = req.ppRequiredExtensionNames[i];
        if (!hasDeviceExtension(physicalDevice, name))
            throw VulkanError(std::string("the device lacks ") + name + ", which dnsr needs");
        extensions.push_back(name);
    }
    // The optional ones only help: the viewer takes the one it knows (push descriptors) where the device has it.
    bool pushDescriptor = false;
    for (uint32_t i = 0; i < req.optionalExtensionCount; i++) {
        const char *name = req.ppOptionalExtensionNames[i];
        if (std::strcmp(name, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME) == 0 && hasDeviceExtension(physicalDevice, name)) {
            extensions.push_back(name);
            pushDescriptor = true;
        }
    }
    return pushDescriptor;
}

void Denoiser::create(const VulkanContext &ctx, const DenoiserSettings &settings)
{
    // A header built for another library version would misread every structure: check first.
    if (dnsr_version() != DNSR_VERSION)
        throw VulkanError("dnsr.h is version " + std::to_string(DNSR_VERSION) + " but libdnsr is " +
                          std::to_string(dnsr_version()));
    DnsrContextCreateInfo info{};
    info.sType = DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO;
    info.instance = ctx.instance;
    info.physicalDevice = ctx.physicalDevice;
    info.device = ctx.device;
    info.vulkanFunctions = {vkGetInstanceProcAddr, vkGetDeviceProcAddr};  // dnsr never links the loader
    info.apiVersion = ctx.apiVersion;
    info.queueFamilyIndex = ctx.queueFamily;
    info.enabledFeatures = ctx.pushDescriptorEnabled ? DNSR_FEATURE_PUSH_DESCRIPTOR : 0;
    info.width = settings.width;
    info.height = settings.height;
    info.flags = DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS;  // standard depth (sky = 1), finite far plane
    if (settings.classifier) info.flags |= DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER;
    // Every frame records every light in one call (recordDenoise): the lights then share one depth copy.
    info.flags |= DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER;
    info.precision = DNSR_PRECISION_FP32;
    info.outputFormat = VK_FORMAT_R32_SFLOAT;
    info.lightCount = settings.lights;
    info.shadowInput = settings.shadowInput;
    if (settings.packedGbuffer) {
        info.shaderOverrideCount = sizeof kPackedOverrides / sizeof kPackedOverrides[0];
        info.pShaderOverrides = kPackedOverrides;
    }
    DnsrResult r = dnsr_context_create(&info, &context_);
    if (r != DNSR_SUCCESS) dnsrFail("dnsr_context_create", r);
    // A preset fills every setting; an engine would tweak single fields of it before setting it.
    DnsrSettings dnsrSettings;
    r = dnsr_settings_init_preset(settings.preset, &dnsrSettings);
    for (const auto &[name, value] : settings.overrides) applySetting(dnsrSettings, name, value);
    if (r == DNSR_SUCCESS) r = dnsr_context_set_settings(context_, &dnsrSettings);
    if (r != DNSR_SUCCESS) dnsrFail("dnsr_settings_init_preset / dnsr_context_set_settings", r);
}

// The fields of a dispatch that describe the frame rather than a light: any dnsr dispatch of the frame starts
// from these.
DnsrShadowsDispatch Denoiser::frameDispatch(const DenoiserFrame &f) const
{
    DnsrShadowsDispatch d{};
    d.sType = DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH;
    d.commandBuffer = f.cmd;
    d.hitMaskConvention = DNSR_HIT_MASK_OCCLUDED_BITS;  // bit = 1: the ray hit an occluder
    d.depth = hostImage(f.depth);
    d.velocity = hostImage(f.velocity);
    d.normals = hostImage(f.normals);
    d.motionVectorScale[0] = d.motionVectorScale[1] = 1.0f;  // velocity = prev_uv - uv, in uv units
    d.normalsUnpackMul = 1.0f;  // float normals, stored as is
    d.normalsUnpackAdd = 0.0f;
    d.eye[0] = f.eye.x, d.eye[1] = f.eye.y, d.eye[2] = f.eye.z;
    d.frameIndex = f.frameIndex;
    d.checkerboardPhase = f.checkerboardPhase;  // shared by every light of dnsr_lights_record: traced alike
    std::memcpy(d.projectionInverse, f.projectionInverse.m, sizeof d.projectionInverse);
    std::memcpy(d.reprojectionMatrix, f.reprojection.m, sizeof d.reprojectionMatrix);
    std::memcpy(d.viewProjectionInverse, f.viewProjectionInverse.m, sizeof d.viewProjectionInverse);
    d.depthSimilaritySigma = 1.0f;
    // dnsr emits the barriers around its work: the engine's compute passes' writes (G-buffer, shadow rays) before
    // its reads, its output write before the engine's compute pass that reads it (the composite here).
    d.sync.inputSrcStages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    d.sync.inputSrcAccess = VK_ACCESS_SHADER_WRITE_BIT;
    d.sync.outputDstStages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    d.sync.outputDstAccess = VK_ACCESS_SHADER_READ_BIT;
    return d;
}

void Denoiser::recordDenoise(const DenoiserFrame &frame, const std::vector<DenoiserLight> &lights, uint32_t debugView)
{
    // What differs from light to light: its inputs from the shadow pass, its output and its flags. Exactly one of
    // hit mask and visibility is set, as the context's shadowInput says; the other stays all zero.
    std::vector<DnsrLightDispatch> perLight(lights.size());
    for (uint32_t i = 0; i < lights.size(); i++) {
        DnsrLightDispatch &l = perLight[i];
        l.sType = DNSR_STRUCTURE_TYPE_LIGHT_DISPATCH;
        l.lightIndex = i;
        l.flags = (frame.cameraCut ? DNSR_LIGHT_DISPATCH_RESET : 0) |
                  (lights[i].hitDistance ? DNSR_LIGHT_DISPATCH_USE_HIT_DISTANCE : 0) |
                  (lights[i].hardLight ? DNSR_LIGHT_DISPATCH_HARD_LIGHT : 0) |
                  (lights[i].useLightPosition ? DNSR_LIGHT_DISPATCH_USE_LIGHT_POSITION : 0);
        std::memcpy(l.lightPosition, lights[i].lightPosition, sizeof l.lightPosition);
        l.hitMask = hostImage(lights[i].hitMask);
        l.visibility = hostImage(lights[i].visibility);
        l.output = hostImage(lights[i].output);
        // Written by the shadow pass like the hit mask: the same input barrier (sync) covers it.
        if (lights[i].hitDistance) l.hitDistance = hostImage(lights[i].hitDistance);
        // Read with hit distances or the light's position (receivers turned away from the whole light are final).
        if (lights[i].hitDistance || lights[i].useLightPosition) l.lightAngularSize = lights[i].lightAngularSize;
    }
    DnsrShadowsDispatch d = frameDispatch(frame);
    d.debugView = debugView;  // one setting for the whole call: every light's output gets the debug view
    if (perLight.size() == 1) {
        // One light: the single-light call, with the light's own fields in the dispatch itself.
        const DnsrLightDispatch &l = perLight[0];
        d.lightIndex = l.lightIndex;
        d.flags = (l.flags & DNSR_LIGHT_DISPATCH_RESET ? DNSR_DISPATCH_RESET : 0) |
                  (l.flags & DNSR_LIGHT_DISPATCH_USE_HIT_DISTANCE ? DNSR_DISPATCH_USE_HIT_DISTANCE : 0) |
                  (l.flags & DNSR_LIGHT_DISPATCH_HARD_LIGHT ? DNSR_DISPATCH_HARD_LIGHT : 0) |
                  (l.flags & DNSR_LIGHT_DISPATCH_USE_LIGHT_POSITION ? DNSR_DISPATCH_USE_LIGHT_POSITION : 0);
        std::memcpy(d.lightPosition, l.lightPosition, sizeof d.lightPosition);
        d.hitMask = l.hitMask, d.visibility = l.visibility, d.output = l.output;
        d.hitDistance = l.hitDistance, d.lightAngularSize = l.lightAngularSize;
        DnsrResult r = dnsr_shadows_record(context_, &d);
        if (r != DNSR_SUCCESS) dnsrFail("dnsr_shadows_record", r);
    } else {
        // Several lights in one call, all of them (the context was created with
        // DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER): they share their transient images and the depth copy. The
        // dispatch keeps its per-light fields zero.
        DnsrResult r = dnsr_lights_record(context_, &d, uint32_t(perLight.size()), perLight.data());
        if (r != DNSR_SUCCESS) dnsrFail("dnsr_lights_record", r);
    }
}

void Denoiser::recordClassify(const DenoiserFrame &f, const DenoiserClassify &c)
{
    DnsrClassifyDispatch d{};
    d.sType = DNSR_STRUCTURE_TYPE_CLASSIFY_DISPATCH;
    d.commandBuffer = f.cmd;
    // Pixels no blocker-search tap finds a blocker for are lit without a ray; a listed tile's rays only cover the
    // stretch of the light direction where the cascades saw its blockers.
    d.flags = DNSR_CLASSIFY_REJECT_LIT_PIXELS | DNSR_CLASSIFY_BOUND_RAY_INTERVAL;
    d.hitMaskConvention = DNSR_HIT_MASK_OCCLUDED_BITS;  // as the trace and recordDenoise
    d.hitMask = hostImage(c.hitMask);
    d.depth = hostImage(f.depth);
    d.normals = hostImage(f.normals);
    d.normalsUnpackMul = 1.0f;
    d.normalsUnpackAdd = 0.0f;
    std::memcpy(d.viewProjectionInverse, f.viewProjectionInverse.m, sizeof d.viewProjectionInverse);
    // The packed G-buffer's callbacks turn linear depth back into hardware depth with it.
    std::memcpy(d.projectionInverse, f.projectionInverse.m, sizeof d.projectionInverse);
    d.lightDirection[0] = c.toLight.x, d.lightDirection[1] = c.toLight.y, d.lightDirection[2] = c.toLight.z;
    d.lightAngularSize = c.lightAngularSize;
    d.cascadeCount = c.cascades->count;
    for (uint32_t i = 0; i < c.cascades->count; i++) {
        std::memcpy(d.cascadeWorldToShadow[i], c.cascades->cascades[i].worldToShadow.m, sizeof d.cascadeWorldToShadow[i]);
        d.cascadeImages[i] = hostImage(c.cascadeImages[i]);
    }
    d.blockerOffset = c.blockerOffset;
    d.tapCount = c.taps;
    d.tileCutoff = c.tileCutoff;
    // The G-buffer and the cascades come from compute passes; the trace after it is a compute dispatch that reads
    // its size from the counts, the tile list and the mask, and ORs its rays into the mask.
    d.sync.inputSrcStages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    d.sync.inputSrcAccess = VK_ACCESS_SHADER_WRITE_BIT;
    d.sync.outputDstStages = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT;
    d.sync.outputDstAccess = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
    DnsrResult r = dnsr_classify_record(context_, &d);
    if (r != DNSR_SUCCESS) dnsrFail("dnsr_classify_record", r);
}

void Denoiser::classifierBuffers(VkBuffer &tiles, VkBuffer &counts) const
{
    DnsrClassifierBuffers b{};
    b.sType = DNSR_STRUCTURE_TYPE_CLASSIFIER_BUFFERS;
    DnsrResult r = dnsr_context_get_classifier_buffers(context_, &b);
    if (r != DNSR_SUCCESS) dnsrFail("dnsr_context_get_classifier_buffers", r);
    tiles = b.tiles;
    counts = b.counts;
}

bool Denoiser::fetchTimings(DnsrPassTimings &timings)
{
    DnsrPassTimings t{};
    t.sType = DNSR_STRUCTURE_TYPE_PASS_TIMINGS;
    DnsrResult r = dnsr_context_get_timings(context_, &t);
    if (r == DNSR_NOT_READY) return false;  // no recorded frame has completed yet
    if (r != DNSR_SUCCESS) dnsrFail("dnsr_context_get_timings", r);
    timings = t;
    return true;
}

bool Denoiser::fetchClassifierTimings(double &classifyMs)
{
    DnsrClassifierTimings t{};
    t.sType = DNSR_STRUCTURE_TYPE_CLASSIFIER_TIMINGS;
    DnsrResult r = dnsr_context_get_classifier_timings(context_, &t);
    if (r == DNSR_NOT_READY) return false;  // no classifier dispatch has completed yet
    if (r != DNSR_SUCCESS) dnsrFail("dnsr_context_get_classifier_timings", r);
    classifyMs = t.classifyMs;
    return true;
}

uint64_t Denoiser::memoryBytes() const
{
    uint64_t bytes = 0;
    if (context_) dnsr_context_get_memory_usage(context_, &bytes);
    return bytes;
}

void Denoiser::destroy()
{
    // The caller waits for the GPU first: dnsr's resources are in command buffers until they complete.
    if (context_) dnsr_context_destroy(context_);
    context_ = nullptr;
}

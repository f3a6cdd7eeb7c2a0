// renderer.cpp: see renderer.h.
#include "renderer.h"

#include <cstring>

namespace {

// SPIR-V compiled from shaders/*.comp by glslc at build time (CMake), embedded so the viewer runs from anywhere.
const uint32_t kPrimarySpv[] =
#include "primary.comp.inc"
    ;
const uint32_t kShadowSpv[] =
#include "shadow.comp.inc"
    ;
const uint32_t kShadowR32fSpv[] =  // the same, writing an R32F hit distance (no shaderStorageImageExtendedFormats)
#include "shadow_r32f.comp.inc"
    ;
const uint32_t kReferenceSpv[] =
#include "reference.comp.inc"
    ;
const uint32_t kCompositeSpv[] =
#include "composite.comp.inc"
    ;
const uint32_t kPrimaryPackedSpv[] =  // also writes the packed G-buffer (--gbuffer packed)
#include "primary_packed.comp.inc"
    ;
const uint32_t kCascadeSpv[] =
#include "cascade.comp.inc"
    ;
const uint32_t kShadowListedSpv[] =
#include "shadow_listed.comp.inc"
    ;
const uint32_t kShadowListedR32fSpv[] =  // R32F hit distance, as shadow_r32f
#include "shadow_listed_r32f.comp.inc"
    ;
// Host copy of shaders/common.glsl's FrameConstants (std140: vec4-aligned members only, so no padding rules).
struct FrameConstants {
    Mat4 viewProj, invViewProj, prevViewProj;
    float eye[4];
    float lights[kMaxLights][4];
    float lightParams[4];
    uint32_t size[4];
    uint32_t info[4];
    float skyColor[4];
    float cascadeOrigin[kMaxCascades][4], cascadeAxisU[kMaxCascades][4], cascadeAxisV[kMaxCascades][4];
    float cascadeParams[4];
    float surfaceDetail[4];
};

// The shaders' binding numbers (shaders/common.glsl).
enum Binding : uint32_t {
    kFrameConstants = 0,
    kBvhNodes,
    kTriGeometry,
    kTriShading,
    kRayOrigin,
    kDepth,
    kNormals,
    kVelocity,
    kAlbedo,
    kHitMask,
    kDenoised,
    kReference,
    kDisplay,
    kHitDistance,  // declared in shadow.comp only (its format depends on the device)
    kLinearDepth,  // these two in primary.comp's packed variant only
    kOctNormals,
    kVisibility,   // shadow.comp, with --rays k > 1
    kHitMask1,     // light 1's images, as light 0's above
    kDenoised1,
    kReference1,
    kHitDistance1,
    kVisibility1,
    kCascade0,     // cascade.comp (hybrid mode), one binding per cascade
    kCascade1,
    kCascade2,
    kCascade3,
    kTileList,     // dnsr's tile list (shadow_listed.comp)
    kTraced,       // pixels traced per tile (shadow_listed.comp writes, composite.comp reads)
    kBindingCount
};

VkDescriptorType descriptorType(uint32_t binding)
{
    if (binding == kFrameConstants) return VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    if (binding <= kTriShading || binding == kTileList) return VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    return VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
}

// Each light's bindings (common.glsl, shadow.comp).
struct LightBindings {
    Binding hitMask, hitDistance, visibility, denoised, reference;
};
constexpr LightBindings kLightBindings[kMaxLights] = {
    {kHitMask, kHitDistance, kVisibility, kDenoised, kReference},
    {kHitMask1, kHitDistance1, kVisibility1, kDenoised1, kReference1},
};

enum Timestamp : uint32_t {
    kStart,
    kAfterPrimary,
    kAfterCascades,
    kAfterClassify,
    kAfterShadow,
    kAfterReference,
    kAfterDnsr,
    kAfterComposite,
    kCount
};

constexpr uint32_t kReferenceChunk = 32;  // samples per reference dispatch: keeps each dispatch short

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkAccessFlags srcAccess, VkPipelineStageFlags dst,
                   VkAccessFlags dstAccess)
{
    auto b = vkStruct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    b.srcAccessMask = srcAccess;
    b.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, src, dst, 0, 1, &b, 0, nullptr, 0, nullptr);
}

uint32_t divUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

uint32_t powerOfTwoAtLeast(uint32_t v)
{
    uint32_t p = 1;
    while (p < v) p *= 2;
    return p;
}

}  // namespace

void Renderer::create(VulkanContext &ctx, const Scene &scene, const RendererSettings &settings)
{
    ctx_ = &ctx;
    settings_ = settings;
    const uint32_t w = settings.width, h = settings.height;

    // Scene -> BVH -> GPU buffers. Triangles are stored in BVH leaf order: v0, e1, e2 for the intersection test,
    // then the three vertex normals with the packed albedo in the first one's w.
    Bvh bvh = buildBvh(scene.positions);
    bvhNodes = static_cast<uint32_t>(bvh.nodes.size());
    bvhDepth = bvh.depth;
    triangles = static_cast<uint32_t>(scene.triangleCount());
    std::vector<float> geometry, shading;
    geometry.reserve(bvh.triangleOrder.size() * 12);
    shading.reserve(bvh.triangleOrder.size() * 12);
    for (uint32_t t : bvh.triangleOrder) {
        Vec3 v0 = scene.positions[3 * t], v1 = scene.positions[3 * t + 1], v2 = scene.positions[3 * t + 2];
        for (Vec3 v : {v0, v1 - v0, v2 - v0}) geometry.insert(geometry.end(), {v.x, v.y, v.z, 0.0f});
        for (int k = 0; k < 3; k++) {
            Vec3 n = scene.normals[3 * t + k];
            float w4 = 0.0f;
            if (k == 0) std::memcpy(&w4, &scene.albedo[t], 4);
            shading.insert(shading.end(), {n.x, n.y, n.z, w4});
        }
    }
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    nodes_ = ctx.createBuffer(bvh.nodes.size() * sizeof(BvhNode), storage, false);
    ctx.upload(nodes_, bvh.nodes.data(), nodes_.size);
    triGeometry_ = ctx.createBuffer(geometry.size() * sizeof(float), storage, false);
    ctx.upload(triGeometry_, geometry.data(), triGeometry_.size);
    triShading_ = ctx.createBuffer(shading.size() * sizeof(float), storage, false);
    ctx.upload(triShading_, shading.data(), triShading_.size);
    frameConstants_ = ctx.createBuffer(sizeof(FrameConstants), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);

    // Images. SAMPLED because dnsr reads its inputs through samplers, STORAGE because our passes write them,
    // TRANSFER for the initial clear and for readback / the blit to the window.
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    rayOrigin_ = ctx.createImage(VK_FORMAT_R32G32B32A32_SFLOAT, w, h, usage);
    depth_ = ctx.createImage(VK_FORMAT_R32_SFLOAT, w, h, usage);  // dnsr accepts R32_SFLOAT depth
    normals_ = ctx.createImage(VK_FORMAT_R16G16B16A16_SFLOAT, w, h, usage);  // unpack: mul 1, add 0
    velocity_ = ctx.createImage(VK_FORMAT_R16G16B16A16_SFLOAT, w, h, usage);
    albedo_ = ctx.createImage(VK_FORMAT_R8G8B8A8_UNORM, w, h, usage);
    display_ = ctx.createImage(VK_FORMAT_R8G8B8A8_UNORM, w, h, usage);
    for (uint32_t i = 0; i < settings.lights; i++) {
        LightResources &l = lights_[i];
        l.hitMask = ctx.createImage(VK_FORMAT_R32_UINT, tilesX(), tilesY(), usage);
        l.denoised = ctx.createImage(VK_FORMAT_R32_SFLOAT, w, h, usage);
        l.reference = ctx.createImage(VK_FORMAT_R32_SFLOAT, w, h, usage);
        // Penumbra guidance: distance to the nearest occluder. Half floats are plenty (dnsr averages them per
        // tile), but writing R16F from a shader needs shaderStorageImageExtendedFormats; R32F otherwise.
        l.hitDistance = ctx.createImage(ctx.storageImageExtendedFormats ? VK_FORMAT_R16_SFLOAT : VK_FORMAT_R32_SFLOAT,
                                        w, h, usage);
        // --rays k: each pixel's lit fraction, R16F like the hit distance (dnsr accepts R8/R16 UNORM, R16F, R32F).
        l.visibility = ctx.createImage(ctx.storageImageExtendedFormats ? VK_FORMAT_R16_SFLOAT : VK_FORMAT_R32_SFLOAT,
                                       w, h, usage);
    }
    // Hybrid mode's cascades (R32F depth, which dnsr's classifier samples) and traced pixels per tile. Without it
    // 1x1 stand-ins keep every binding valid.
    const HybridSettings &hybrid = settings.hybrid;
    cascadeSize_ = !hybrid.enabled       ? 1
                   : hybrid.cascadeSize ? hybrid.cascadeSize
                                         : std::min(powerOfTwoAtLeast(std::max(w, h)), 8192u);
    for (uint32_t i = 0; i < kMaxCascades; i++) {
        uint32_t size = hybrid.enabled && i < hybrid.cascades ? cascadeSize_ : 1;
        cascades_[i] = ctx.createImage(VK_FORMAT_R32_SFLOAT, size, size, usage);
    }
    traced_ = ctx.createImage(VK_FORMAT_R32_UINT, tilesX(), tilesY(), usage);
    if (settings.packedGbuffer && !ctx.storageImageExtendedFormats)
        throw VulkanError("--gbuffer packed writes RG16_SNORM normals, which needs shaderStorageImageExtendedFormats");
    linearDepth_ = ctx.createImage(VK_FORMAT_R32_SFLOAT, w, h, usage);
    octNormals_ = ctx.createImage(ctx.storageImageExtendedFormats ? VK_FORMAT_R16G16_SNORM : VK_FORMAT_R32G32_SFLOAT, w,
                                  h, usage);

    // Readback buffer: one section per image, each starting at a multiple of 16 bytes (a buffer-image copy's
    // offset must be a multiple of the texel size, up to 16 for RGBA32F; odd render sizes break 4-byte sections).
    VkDeviceSize pixels = VkDeviceSize(w) * h, offset = 0;
    auto section = [&](VkDeviceSize bytes) {
        VkDeviceSize start = offset;
        offset = (offset + bytes + 15) & ~VkDeviceSize(15);
        return start;
    };
    depthOffset_ = section(pixels * 4);
    for (uint32_t i = 0; i < settings.lights; i++) {
        lights_[i].maskOffset = section(VkDeviceSize(tilesX()) * tilesY() * 4);
        lights_[i].denoisedOffset = section(pixels * 4);
        lights_[i].referenceOffset = section(pixels * 4);
    }
    displayOffset_ = section(pixels * 4);
    tracedOffset_ = section(VkDeviceSize(tilesX()) * tilesY() * 4);
    normalsOffset_ = section(pixels * 8);
    velocityOffset_ = section(pixels * 8);
    readback_ = ctx.createBuffer(offset, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);

    // Every image to GENERAL once, cleared so that nothing undefined is ever read.
    VkCommandBuffer cmd = ctx.beginOneTimeCommands();
    std::vector<VkImageMemoryBarrier> toGeneral;
    for (const GpuImage *img : images()) {
        auto b = vkStruct<VkImageMemoryBarrier>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER);
        b.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        b.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = img->image;
        b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        toGeneral.push_back(b);
    }
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0,
                         nullptr, static_cast<uint32_t>(toGeneral.size()), toGeneral.data());
    VkClearColorValue zero{};
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    for (const VkImageMemoryBarrier &b : toGeneral)
        vkCmdClearColorImage(cmd, b.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT);
    ctx.submitAndWait(cmd);

    // The context after the images: an engine creates it once it knows the render size, with its G-buffer's encoding
    // and how its shadow rays are handed over.
    DenoiserSettings ds;
    ds.width = w, ds.height = h;
    ds.lights = settings.lights;
    // --rays k > 1: several rays per pixel, handed over as per-pixel visibility instead of the hit mask;
    // --checkerboard: half a ray per pixel in the hit mask.
    ds.shadowInput = settings.rays > 1        ? DNSR_SHADOW_INPUT_VISIBILITY
                     : settings.checkerboard ? DNSR_SHADOW_INPUT_CHECKERBOARD
                                             : DNSR_SHADOW_INPUT_HIT_MASK;
    ds.packedGbuffer = settings.packedGbuffer;
    ds.preset = settings.preset;
    ds.overrides = settings.settingOverrides;
    ds.classifier = hybrid.enabled;
    denoiser_.create(ctx, ds);
    if (hybrid.enabled) denoiser_.classifierBuffers(tileList_, tileCounts_);

    createDescriptors();
    primary_ = settings.packedGbuffer ? ctx.createComputePipeline(pipelineLayout_, kPrimaryPackedSpv, sizeof kPrimaryPackedSpv)
                                      : ctx.createComputePipeline(pipelineLayout_, kPrimarySpv, sizeof kPrimarySpv);
    shadow_ = ctx.storageImageExtendedFormats
                  ? ctx.createComputePipeline(pipelineLayout_, kShadowSpv, sizeof kShadowSpv)
                  : ctx.createComputePipeline(pipelineLayout_, kShadowR32fSpv, sizeof kShadowR32fSpv);
    reference_pipeline_ = ctx.createComputePipeline(pipelineLayout_, kReferenceSpv, sizeof kReferenceSpv);
    composite_ = ctx.createComputePipeline(pipelineLayout_, kCompositeSpv, sizeof kCompositeSpv);
    if (hybrid.enabled) {
        cascade_ = ctx.createComputePipeline(pipelineLayout_, kCascadeSpv, sizeof kCascadeSpv);
        shadowListed_ = ctx.storageImageExtendedFormats
                            ? ctx.createComputePipeline(pipelineLayout_, kShadowListedSpv, sizeof kShadowListedSpv)
                            : ctx.createComputePipeline(pipelineLayout_, kShadowListedR32fSpv, sizeof kShadowListedR32fSpv);
    }

    auto queryInfo = vkStruct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = kCount;
    VK_CHECK(vkCreateQueryPool(ctx.device, &queryInfo, nullptr, &timestamps_));

}

// One descriptor set layout for all four passes: each shader uses the subset of bindings it needs.
void Renderer::createDescriptors()
{
    VkDevice dev = ctx_->device;
    std::vector<VkDescriptorSetLayoutBinding> bindings(kBindingCount);
    for (uint32_t i = 0; i < kBindingCount; i++) {
        bindings[i].binding = i;
        bindings[i].descriptorType = descriptorType(i);
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    auto layoutInfo = vkStruct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    layoutInfo.bindingCount = kBindingCount;
    layoutInfo.pBindings = bindings.data();
    VK_CHECK(vkCreateDescriptorSetLayout(dev, &layoutInfo, nullptr, &setLayout_));

    VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 4 * sizeof(uint32_t)};
    auto pipelineInfo = vkStruct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    pipelineInfo.setLayoutCount = 1;
    pipelineInfo.pSetLayouts = &setLayout_;
    pipelineInfo.pushConstantRangeCount = 1;
    pipelineInfo.pPushConstantRanges = &push;
    VK_CHECK(vkCreatePipelineLayout(dev, &pipelineInfo, nullptr, &pipelineLayout_));

    VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4},
                                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kBindingCount - 5}};
    auto poolInfo = vkStruct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 3;
    poolInfo.pPoolSizes = sizes;
    VK_CHECK(vkCreateDescriptorPool(dev, &poolInfo, nullptr, &descriptorPool_));
    auto alloc = vkStruct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    alloc.descriptorPool = descriptorPool_;
    alloc.descriptorSetCount = 1;
    alloc.pSetLayouts = &setLayout_;
    VK_CHECK(vkAllocateDescriptorSets(dev, &alloc, &set_));

    // Without hybrid mode the tile list's binding gets a stand-in (the BVH nodes): declared, never read.
    VkDescriptorBufferInfo buffers[kBindingCount] = {};
    buffers[kFrameConstants] = {frameConstants_.buffer, 0, VK_WHOLE_SIZE};
    buffers[kBvhNodes] = {nodes_.buffer, 0, VK_WHOLE_SIZE};
    buffers[kTriGeometry] = {triGeometry_.buffer, 0, VK_WHOLE_SIZE};
    buffers[kTriShading] = {triShading_.buffer, 0, VK_WHOLE_SIZE};
    buffers[kTileList] = {tileList_ ? tileList_ : nodes_.buffer, 0, VK_WHOLE_SIZE};
    const GpuImage *images[kBindingCount] = {};
    images[kRayOrigin] = &rayOrigin_, images[kDepth] = &depth_, images[kNormals] = &normals_;
    images[kVelocity] = &velocity_, images[kAlbedo] = &albedo_, images[kDisplay] = &display_;
    images[kLinearDepth] = &linearDepth_, images[kOctNormals] = &octNormals_;
    for (uint32_t i = 0; i < kMaxCascades; i++) images[kCascade0 + i] = &cascades_[i];
    images[kTraced] = &traced_;
    // With one light, light 1's bindings get light 0's images: the shaders declare them (so they must be valid)
    // but use them only when there is a second light.
    for (uint32_t i = 0; i < kMaxLights; i++) {
        const LightResources &l = lights_[std::min(i, settings_.lights - 1)];
        const LightBindings &b = kLightBindings[i];
        images[b.hitMask] = &l.hitMask, images[b.hitDistance] = &l.hitDistance, images[b.visibility] = &l.visibility;
        images[b.denoised] = &l.denoised, images[b.reference] = &l.reference;
    }
    VkDescriptorImageInfo imageInfos[kBindingCount] = {};
    std::vector<VkWriteDescriptorSet> writes(kBindingCount,
                                             vkStruct<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET));
    for (uint32_t i = 0; i < kBindingCount; i++) {
        writes[i].dstSet = set_;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = bindings[i].descriptorType;
        if (bindings[i].descriptorType != VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
            writes[i].pBufferInfo = &buffers[i];
        } else {
            imageInfos[i] = {VK_NULL_HANDLE, images[i]->view, VK_IMAGE_LAYOUT_GENERAL};
            writes[i].pImageInfo = &imageInfos[i];
        }
    }
    vkUpdateDescriptorSets(dev, kBindingCount, writes.data(), 0, nullptr);
}

std::vector<GpuImage *> Renderer::images()
{
    std::vector<GpuImage *> all = {&rayOrigin_, &depth_,       &normals_,    &velocity_, &albedo_,
                                   &display_,   &linearDepth_, &octNormals_, &traced_};
    for (GpuImage &c : cascades_) all.push_back(&c);
    for (uint32_t i = 0; i < settings_.lights; i++) {
        LightResources &l = lights_[i];
        all.insert(all.end(), {&l.hitMask, &l.hitDistance, &l.visibility, &l.denoised, &l.reference});
    }
    return all;
}

void Renderer::bind(VkCommandBuffer cmd, VkPipeline pipeline, uint32_t mode, uint32_t sampleBase,
                    uint32_t sampleCount, uint32_t light)
{
    const uint32_t push[4] = {mode, sampleBase, sampleCount, light};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &set_, 0, nullptr);
    vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, push);
}

void Renderer::dispatch(VkCommandBuffer cmd, VkPipeline pipeline, uint32_t groupsX, uint32_t groupsY, uint32_t mode,
                        uint32_t sampleBase, uint32_t sampleCount, uint32_t light)
{
    bind(cmd, pipeline, mode, sampleBase, sampleCount, light);
    vkCmdDispatch(cmd, groupsX, groupsY, 1);
}

void Renderer::recordHybridShadows(VkCommandBuffer cmd, const FrameInput &in, const DenoiserFrame &frame)
{
    // The cascades (an engine renders its shadow maps here), then dnsr's classifier reads them with the G-buffer.
    for (uint32_t c = 0; c < cascadeSet_.count; c++)
        dispatch(cmd, cascade_, divUp(cascadeSize_, 8), divUp(cascadeSize_, 8), 0, 0, 0, c);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterCascades);

    const HybridSettings &h = settings_.hybrid;
    DenoiserClassify c;
    c.hitMask = &lights_[0].hitMask;
    c.toLight = in.lights[0];
    c.lightAngularSize = in.lightAngularSize;
    c.cascades = &cascadeSet_;
    for (uint32_t i = 0; i < cascadeSet_.count; i++) c.cascadeImages[i] = &cascades_[i];
    // A scene-sized offset hides low blockers in a large scene (the city's rails at 0.005 scene radii); a texel-sized
    // one follows the cascade's own precision.
    const Cascade &finest = cascadeSet_.cascades[0];
    c.blockerOffset = h.blockerOffset >= 0 ? h.blockerOffset : 2.0f * length(finest.axisU) / float(cascadeSize_);
    c.taps = h.taps;
    c.tileCutoff = h.tileCutoff;
    denoiser_.recordClassify(frame, c);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterClassify);

    // One workgroup per listed tile: the classifier wrote the group count into its counts buffer (word 0..2).
    // Mode bit 0: reversed rays; bit 1: penumbra guidance (forward rays to the nearest occluder, its distance).
    bind(cmd, shadowListed_, (h.reverseRays ? 1u : 0u) | (in.hitDistance ? 2u : 0u));
    vkCmdDispatchIndirect(cmd, tileCounts_, 0);
}

void Renderer::recordFrame(VkCommandBuffer cmd, const FrameInput &in)
{
    const uint32_t w = settings_.width, h = settings_.height;
    Mat4 viewProj = in.projection * in.viewMatrix;
    if (frameIndex_ == 0 || in.cameraCut) prevViewProj_ = viewProj;  // no previous frame: no motion
    Mat4 invViewProj, invProjection, reprojection;
    if (!inverse(viewProj, invViewProj) || !inverse(in.projection, invProjection) ||
        !::reprojection(prevViewProj_, viewProj, reprojection))
        throw VulkanError("the camera matrices are singular");
    if (in.resetReference) referenceCount_ = 0;
    uint32_t referenceAfter = referenceCount_ + in.referenceSamples;
    // --checkerboard: the phases alternate, so every pixel is traced every other frame. Bit (y % 4) * 8 + x % 8
    // of 0xAA55AA55 is set where x + y is even.
    const uint32_t phase = settings_.checkerboard ? frameIndex_ % 2 : 0;
    tracedBits_ = !settings_.checkerboard ? ~0u : phase == 0 ? 0xAA55AA55u : 0x55AA55AAu;
    if (in.hybrid && !settings_.hybrid.enabled) throw VulkanError("hybrid mode was not enabled at creation");
    const bool hybrid = in.hybrid;
    const bool guidance = in.hitDistance;
    if (hybrid)
        cascadeSet_ = fitCascades(invViewProj, in.eye, in.lights[0], settings_.sceneCenter, settings_.sceneRadius,
                                  settings_.hybrid.cascades, cascadeSize_);

    // What every dnsr dispatch of this frame reads (its G-buffer once primary.comp has written it, the camera):
    // described once, up front, so that a dispatch recorded before the shadow rays could take it as well.
    DenoiserFrame frame;
    frame.cmd = cmd;
    // --gbuffer packed: dnsr reads the engine's own encoding through the passes the context was created with.
    frame.depth = settings_.packedGbuffer ? &linearDepth_ : &depth_;
    frame.velocity = &velocity_;
    frame.normals = settings_.packedGbuffer ? &octNormals_ : &normals_;
    frame.projectionInverse = invProjection;
    frame.viewProjectionInverse = invViewProj;
    frame.reprojection = reprojection;
    frame.eye = in.eye;
    frame.frameIndex = frameIndex_;
    frame.checkerboardPhase = phase;
    frame.cameraCut = in.cameraCut;

    // Per-frame constants. The buffer is host-coherent and the previous frame has completed (one frame in
    // flight), so writing it now is safe.
    FrameConstants c{};
    c.viewProj = viewProj;
    c.invViewProj = invViewProj;
    c.prevViewProj = prevViewProj_;
    c.eye[0] = in.eye.x, c.eye[1] = in.eye.y, c.eye[2] = in.eye.z;
    for (uint32_t i = 0; i < kMaxLights; i++) {
        const Vec3 &l = in.lights[i];
        c.lights[i][0] = l.x, c.lights[i][1] = l.y, c.lights[i][2] = l.z, c.lights[i][3] = in.pointLight ? 1.f : 0.f;
    }
    c.lightParams[0] = in.lightSize;
    c.lightParams[1] = settings_.ambient;
    c.lightParams[2] = 2e-4f * settings_.sceneRadius;
    c.lightParams[3] = settings_.sceneRadius;
    c.size[0] = w, c.size[1] = h, c.size[2] = tilesX(), c.size[3] = tilesY();
    c.info[0] = frameIndex_, c.info[1] = referenceAfter, c.info[2] = settings_.lights, c.info[3] = tracedBits_;
    c.skyColor[0] = 0.55f, c.skyColor[1] = 0.70f, c.skyColor[2] = 0.90f, c.skyColor[3] = 1.0f;
    for (uint32_t i = 0; i < cascadeSet_.count; i++) {
        const Cascade &k = cascadeSet_.cascades[i];
        const Vec3 *v[3] = {&k.origin, &k.axisU, &k.axisV};
        float(*dst[3])[4] = {c.cascadeOrigin, c.cascadeAxisU, c.cascadeAxisV};
        for (int j = 0; j < 3; j++) dst[j][i][0] = v[j]->x, dst[j][i][1] = v[j]->y, dst[j][i][2] = v[j]->z;
    }
    c.cascadeParams[0] = cascadeSet_.depthRange;
    c.cascadeParams[1] = float(cascadeSize_);
    c.surfaceDetail[0] = settings_.normalDetail;
    c.surfaceDetail[1] = 0.04f * settings_.sceneRadius;
    c.surfaceDetail[2] = settings_.normalDetailDnsrOnly ? 1.0f : 0.0f;
    std::memcpy(frameConstants_.mapped, &c, sizeof c);

    vkCmdResetQueryPool(cmd, timestamps_, 0, kCount);
    // The previous frame's passes, readback and blit (same queue, earlier submission) before this frame
    // overwrites what they read or wrote.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                      VK_ACCESS_TRANSFER_WRITE_BIT);
    // Which pixels this frame traces, per tile: shadow_listed.comp fills in the listed tiles in hybrid mode.
    VkClearColorValue traced{};
    traced.uint32[0] = hybrid ? 0u : tracedBits_;
    VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdClearColorImage(cmd, traced_.image, VK_IMAGE_LAYOUT_GENERAL, &traced, 1, &range);
    // Hybrid mode with penumbra guidance: only the traced pixels get a hit distance; the others' stay 0, which dnsr
    // reads as unknown (it averages the known ones around each tile).
    if (hybrid && guidance) {
        VkClearColorValue zero{};
        vkCmdClearColorImage(cmd, lights_[0].hitDistance.image, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
    }
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps_, kStart);

    dispatch(cmd, primary_, divUp(w, 8), divUp(h, 8));
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterPrimary);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);

    if (hybrid) {
        recordHybridShadows(cmd, in, frame);
    } else {
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterCascades);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterClassify);
        // Mode 1: the rays find their nearest occluder and write its distance (penumbra guidance); mode 0: any
        // occluder ends a ray, and the hit-distance image is left alone. The hit mask is the same either way. The
        // lights' dispatches write different images: no barrier between them.
        for (uint32_t i = 0; i < settings_.lights; i++)
            dispatch(cmd, shadow_, divUp(tilesX(), 8), divUp(tilesY(), 8), guidance ? 1u : 0u, 0, settings_.rays, i);
    }
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterShadow);

    // Reference samples, in chunks; each chunk adds to the sum the previous one wrote.
    for (uint32_t done = 0; done < in.referenceSamples; done += kReferenceChunk) {
        if (done > 0)
            memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        uint32_t n = std::min(kReferenceChunk, in.referenceSamples - done);
        for (uint32_t i = 0; i < settings_.lights; i++)
            dispatch(cmd, reference_pipeline_, divUp(w, 8), divUp(h, 8), 0, referenceCount_ + done, n, i);
    }
    referenceCount_ = referenceAfter;
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterReference);

    // ---- dnsr (denoiser.cpp): the shadow pass's outputs of each light -> its denoised shadow ----
    std::vector<DenoiserLight> lights(settings_.lights);
    for (uint32_t i = 0; i < settings_.lights; i++) {
        DenoiserLight &l = lights[i];
        if (settings_.rays > 1) l.visibility = &lights_[i].visibility;
        else l.hitMask = &lights_[i].hitMask;
        if (guidance) l.hitDistance = &lights_[i].hitDistance;
        l.lightAngularSize = in.lightAngularSize;  // read with hit distances or the light's position
        l.hardLight = in.hardLight;
        if (in.lightPosition) {
            l.useLightPosition = true;
            Vec3 v = in.lights[i];
            l.lightPosition[0] = v.x, l.lightPosition[1] = v.y, l.lightPosition[2] = v.z;
            l.lightPosition[3] = in.pointLight ? 1.0f : 0.0f;  // a point light's centre, or the direction to the sun
        }
        l.output = &lights_[i].denoised;
    }
    bool dnsrView = dnsrDebugView(in.display) != DNSR_DEBUG_VIEW_NONE;
    denoiser_.recordDenoise(frame, lights, dnsrDebugView(in.display));
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterDnsr);

    // dnsr's debug views land in its output images: shown like the denoised shadow (composite mode 1).
    uint32_t mode = dnsrView ? uint32_t(View::Denoised) : static_cast<uint32_t>(in.display);
    dispatch(cmd, composite_, divUp(w, 8), divUp(h, 8), mode, 0, 0, in.shownLight);
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, timestamps_, kAfterComposite);
    // The display image is read next by a blit (window) or a copy (readback).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT);

    prevViewProj_ = viewProj;
    frameIndex_++;
}

void Renderer::afterFrame()
{
    uint64_t ticks[kCount];
    VkResult r = vkGetQueryPoolResults(ctx_->device, timestamps_, 0, kCount, sizeof ticks, ticks, sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    if (r == VK_SUCCESS) {
        double ms = ctx_->properties.limits.timestampPeriod * 1e-6;
        auto span = [&](int a, int b) { return ticks[b] > ticks[a] ? double(ticks[b] - ticks[a]) * ms : 0.0; };
        viewerTimings = {span(kStart, kAfterPrimary),      span(kAfterPrimary, kAfterCascades),
                         span(kAfterCascades, kAfterClassify), span(kAfterClassify, kAfterShadow),
                         span(kAfterShadow, kAfterReference), span(kAfterReference, kAfterDnsr),
                         span(kAfterDnsr, kAfterComposite)};
    }
    if (denoiser_.fetchTimings(dnsrTimings)) haveDnsrTimings = true;
    if (tileList_ != VK_NULL_HANDLE) denoiser_.fetchClassifierTimings(dnsrClassifyMs);  // the classifier exists
}

void Renderer::recordReadback(VkCommandBuffer cmd)
{
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT);
    auto copy = [&](const GpuImage &img, VkDeviceSize offset) {
        VkBufferImageCopy region{};
        region.bufferOffset = offset;
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {img.width, img.height, 1};
        vkCmdCopyImageToBuffer(cmd, img.image, VK_IMAGE_LAYOUT_GENERAL, readback_.buffer, 1, &region);
    };
    copy(depth_, depthOffset_);
    for (uint32_t i = 0; i < settings_.lights; i++) {
        copy(lights_[i].hitMask, lights_[i].maskOffset);
        copy(lights_[i].denoised, lights_[i].denoisedOffset);
        copy(lights_[i].reference, lights_[i].referenceOffset);
    }
    copy(display_, displayOffset_);
    copy(traced_, tracedOffset_);
    copy(normals_, normalsOffset_);
    copy(velocity_, velocityOffset_);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                  VK_ACCESS_HOST_READ_BIT);
}

void Renderer::destroy()
{
    if (!ctx_) return;
    VkDevice dev = ctx_->device;
    vkDeviceWaitIdle(dev);
    // The context goes first, once the GPU has finished every command buffer it recorded into.
    denoiser_.destroy();
    for (VkPipeline p : {primary_, shadow_, reference_pipeline_, composite_, cascade_, shadowListed_})
        if (p) vkDestroyPipeline(dev, p, nullptr);
    if (pipelineLayout_) vkDestroyPipelineLayout(dev, pipelineLayout_, nullptr);
    if (descriptorPool_) vkDestroyDescriptorPool(dev, descriptorPool_, nullptr);
    if (setLayout_) vkDestroyDescriptorSetLayout(dev, setLayout_, nullptr);
    if (timestamps_) vkDestroyQueryPool(dev, timestamps_, nullptr);
    for (GpuImage *img : images()) ctx_->destroyImage(*img);
    for (GpuBuffer *b : {&frameConstants_, &nodes_, &triGeometry_, &triShading_, &readback_}) ctx_->destroyBuffer(*b);
    ctx_ = nullptr;
}

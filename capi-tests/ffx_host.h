/*
 * What the FFX drop-in tests share: host.h, plus a host image as an FFX integration describes it
 * (ffxGetImageResourceDescriptionVK of its create info, then ffxGetResourceVK).
 */
#ifndef DNSR_CAPI_TESTS_FFX_HOST_H
#define DNSR_CAPI_TESTS_FFX_HOST_H

#include <FidelityFX/host/backends/vk/ffx_vk.h>
#include <FidelityFX/host/ffx_denoiser.h>

#include "host.h"

static inline FfxResource resource(const HostImage &img, FfxResourceStates state, const wchar_t *name)
{
    VkImageCreateInfo info = {};
    info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = img.format;
    info.extent = {img.width, img.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
    return ffxGetResourceVK((void *)img.image, ffxGetImageResourceDescriptionVK(img.image, info), name, state);
}

/* A still-camera dispatch as the SDK's sample fills it: its resource states and names, motion vectors in uv with
 * scale 1, UNORM normals (unpack 2, -1), identity matrices, depth similarity sigma 1. */
static inline FfxDenoiserShadowsDispatchDescription sample_dispatch(VkCommandBuffer cmd, uint32_t frame, const HostImage &mask,
                                                                    const HostImage &depth, const HostImage &velocity,
                                                                    const HostImage &normals, const HostImage &output)
{
    FfxDenoiserShadowsDispatchDescription d = {};
    d.commandList = ffxGetCommandListVK(cmd);
    d.hitMaskResults = resource(mask, FFX_RESOURCE_STATE_GENERIC_READ, L"FidelityFX_ShadowDenoiser_RayHit");
    d.depth = resource(depth, FFX_RESOURCE_STATE_PIXEL_COMPUTE_READ, L"FidelityFX_ShadowDenoiser_InputDepth");
    d.velocity = resource(velocity, FFX_RESOURCE_STATE_PIXEL_COMPUTE_READ, L"FidelityFX_ShadowDenoiser_InputVelocity");
    d.normal = resource(normals, FFX_RESOURCE_STATE_PIXEL_COMPUTE_READ, L"FidelityFX_ShadowDenoiser_InputNormals");
    d.shadowMaskOutput = resource(output, FFX_RESOURCE_STATE_UNORDERED_ACCESS, L"FidelityFX_ShadowDenoiser_ShadowMaskOutput");
    d.motionVectorScale[0] = d.motionVectorScale[1] = 1.0f;
    d.normalsUnpackMul = 2.0f;
    d.normalsUnpackAdd = -1.0f;
    for (int i = 0; i < 16; i++) {
        float v = (i % 5 == 0) ? 1.0f : 0.0f;
        d.projectionInverse[i] = d.reprojectionMatrix[i] = d.viewProjectionInverse[i] = v;
    }
    d.frameIndex = frame;
    d.depthSimilaritySigma = 1.0f;
    return d;
}

#endif

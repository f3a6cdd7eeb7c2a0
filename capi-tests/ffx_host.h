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

#endif

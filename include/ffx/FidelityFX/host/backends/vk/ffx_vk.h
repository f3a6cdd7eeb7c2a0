/*
 * dnsr's FidelityFX SDK 1.1.4 compatibility headers: the Vulkan backend functions a shadow-denoiser integration
 * calls. C and C++ (the default arguments exist in C++ only, as in the SDK). See ffx_denoiser.h.
 */
#ifndef FFX_VK_H
#define FFX_VK_H

#include <vulkan/vulkan.h>

#include "../../ffx_interface.h"

#ifdef __cplusplus
#define FFX_DNSR_DEFAULT_ARGUMENT(value) = value
extern "C" {
#else
#define FFX_DNSR_DEFAULT_ARGUMENT(value)
#endif

/* The device an integration hands to the backend. vkDeviceProcAddr may be NULL (dnsr then takes the loader's). */
typedef struct VkDeviceContext {
    VkDevice vkDevice;
    VkPhysicalDevice vkPhysicalDevice;
    PFN_vkGetDeviceProcAddr vkDeviceProcAddr;
} VkDeviceContext;

/* Bytes of scratch memory ffxGetInterfaceVK needs (the same for any device and any maxContexts >= 1). */
FFX_API size_t ffxGetScratchMemorySizeVK(VkPhysicalDevice physicalDevice, size_t maxContexts);

/* Copies *vkDeviceContext into process-wide storage and returns it as an FfxDevice (as the SDK does: one device
 * per process; a later call replaces it for later ffxGetInterfaceVK calls). NULL gives NULL. */
FFX_API FfxDevice ffxGetDeviceVK(VkDeviceContext *vkDeviceContext);

/* Fills backendInterface for the denoiser (see ffx_interface.h for which entries). FFX_ERROR_INVALID_POINTER for
 * a NULL interface, scratch buffer or device; FFX_ERROR_INSUFFICIENT_MEMORY when scratchBufferSize is below
 * ffxGetScratchMemorySizeVK; FFX_ERROR_INVALID_ARGUMENT for maxContexts 0. */
FFX_API FfxErrorCode ffxGetInterfaceVK(FfxInterface *backendInterface, FfxDevice device, void *scratchBuffer,
                                       size_t scratchBufferSize, size_t maxContexts);

FFX_API FfxCommandList ffxGetCommandListVK(VkCommandBuffer cmdBuf);

/* An FfxResource for a VkImage (vkResource) in `state`; the name is copied (truncated to 63 characters). */
FFX_API FfxResource ffxGetResourceVK(void *vkResource, FfxResourceDescription ffxResDescription,
                                     const wchar_t *ffxResName,
                                     FfxResourceStates state FFX_DNSR_DEFAULT_ARGUMENT(FFX_RESOURCE_STATE_COMPUTE_READ));

/* The FfxSurfaceFormat of a VkFormat (depth formats give their colour twin; unknown ones FFX_SURFACE_FORMAT_UNKNOWN). */
FFX_API FfxSurfaceFormat ffxGetSurfaceFormatVK(VkFormat format);

/* The description of an image from its create info: format, extent, mip count, array layers as depth, usage
 * DEPTHTARGET for a depth format, UAV for a storage image, plus additionalUsages. A null image gives zeros. */
FFX_API FfxResourceDescription ffxGetImageResourceDescriptionVK(
    const VkImage image, const VkImageCreateInfo createInfo,
    FfxResourceUsage additionalUsages FFX_DNSR_DEFAULT_ARGUMENT(FFX_RESOURCE_USAGE_READ_ONLY));

/* The description of a buffer from its create info: FFX_RESOURCE_TYPE_BUFFER, size createInfo.size (truncated to
 * 32 bits, as in the SDK), stride 0, format unknown, usage UAV for a storage buffer and INDIRECT for an indirect
 * one, plus additionalUsages. A null buffer gives zeros. (dnsr reads no buffers; for integrations' own glue.) */
FFX_API FfxResourceDescription ffxGetBufferResourceDescriptionVK(
    const VkBuffer buffer, const VkBufferCreateInfo createInfo,
    FfxResourceUsage additionalUsages FFX_DNSR_DEFAULT_ARGUMENT(FFX_RESOURCE_USAGE_READ_ONLY));

/* A VkQueue as an FfxCommandQueue, and a VkPipeline as an FfxPipeline (the handles themselves). */
FFX_API FfxCommandQueue ffxGetCommandQueueVK(VkQueue commandQueue);
FFX_API FfxPipeline ffxGetPipelineVK(VkPipeline pipeline);

#ifdef __cplusplus
}
#endif

#undef FFX_DNSR_DEFAULT_ARGUMENT

#endif

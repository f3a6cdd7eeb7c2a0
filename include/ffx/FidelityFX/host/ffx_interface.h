/*
 * dnsr's FidelityFX SDK 1.1.4 compatibility headers: the backend interface.
 *
 * In the SDK, FfxInterface is the table through which an effect drives its graphics backend. dnsr records its own
 * passes and does not go through the table: ffxGetInterfaceVK fills fpGetSDKVersion (it answers 1.1.4, which
 * integrations assert), fpGetDeviceCapabilities and fpRegisterConstantBufferAllocator (accepted and ignored: dnsr
 * keeps its constants itself), the scratch memory and the device. Every other entry is NULL: code that calls one
 * of them directly (to run another FFX effect through this table) needs the SDK's own backend, which cannot be
 * linked next to libdnsr (both export ffxGetInterfaceVK).
 */
#ifndef FFX_INTERFACE_H
#define FFX_INTERFACE_H

#include "ffx_error.h"
#include "ffx_types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FFX_SDK_VERSION_MAJOR (1)
#define FFX_SDK_VERSION_MINOR (1)
#define FFX_SDK_VERSION_PATCH (4)
#define FFX_SDK_MAKE_VERSION(major, minor, patch) FFX_MAKE_VERSION(major, minor, patch)

typedef struct FfxInterface FfxInterface;
typedef uint32_t FfxPass;

typedef FfxVersionNumber (*FfxGetSDKVersionFunc)(FfxInterface *backendInterface);
typedef FfxErrorCode (*FfxGetEffectGpuMemoryUsageFunc)(FfxInterface *backendInterface, FfxUInt32 effectContextId,
                                                       FfxEffectMemoryUsage *outVramUsage);
typedef FfxErrorCode (*FfxCreateBackendContextFunc)(FfxInterface *backendInterface, FfxEffect effect,
                                                    FfxEffectBindlessConfig *bindlessConfig, FfxUInt32 *effectContextId);
typedef FfxErrorCode (*FfxGetDeviceCapabilitiesFunc)(FfxInterface *backendInterface,
                                                     FfxDeviceCapabilities *outDeviceCapabilities);
typedef FfxErrorCode (*FfxDestroyBackendContextFunc)(FfxInterface *backendInterface, FfxUInt32 effectContextId);
typedef FfxErrorCode (*FfxCreateResourceFunc)(FfxInterface *backendInterface,
                                              const FfxCreateResourceDescription *createResourceDescription,
                                              FfxUInt32 effectContextId, FfxResourceInternal *outResource);
typedef FfxErrorCode (*FfxRegisterResourceFunc)(FfxInterface *backendInterface, const FfxResource *inResource,
                                                FfxUInt32 effectContextId, FfxResourceInternal *outResource);
typedef FfxResource (*FfxGetResourceFunc)(FfxInterface *backendInterface, FfxResourceInternal resource);
typedef FfxErrorCode (*FfxUnregisterResourcesFunc)(FfxInterface *backendInterface, FfxCommandList commandList,
                                                   FfxUInt32 effectContextId);
typedef FfxErrorCode (*FfxRegisterStaticResourceFunc)(FfxInterface *backendInterface,
                                                      const FfxStaticResourceDescription *desc,
                                                      FfxUInt32 effectContextId);
typedef FfxResourceDescription (*FfxGetResourceDescriptionFunc)(FfxInterface *backendInterface,
                                                                FfxResourceInternal resource);
typedef FfxErrorCode (*FfxDestroyResourceFunc)(FfxInterface *backendInterface, FfxResourceInternal resource,
                                               FfxUInt32 effectContextId);
typedef FfxErrorCode (*FfxMapResourceFunc)(FfxInterface *backendInterface, FfxResourceInternal resource, void **ptr);
typedef FfxErrorCode (*FfxUnmapResourceFunc)(FfxInterface *backendInterface, FfxResourceInternal resource);
typedef FfxErrorCode (*FfxStageConstantBufferDataFunc)(FfxInterface *backendInterface, void *data, FfxUInt32 size,
                                                       FfxConstantBuffer *constantBuffer);
typedef FfxErrorCode (*FfxCreatePipelineFunc)(FfxInterface *backendInterface, FfxEffect effect, FfxPass pass,
                                              uint32_t permutationOptions,
                                              const FfxPipelineDescription *pipelineDescription,
                                              FfxUInt32 effectContextId, FfxPipelineState *outPipeline);
typedef FfxErrorCode (*FfxGetPermutationBlobByIndexFunc)(FfxEffect effectId, FfxPass passId, FfxBindStage bindStage,
                                                         uint32_t permutationOptions, FfxShaderBlob *outBlob);
typedef FfxErrorCode (*FfxDestroyPipelineFunc)(FfxInterface *backendInterface, FfxPipelineState *pipeline,
                                               FfxUInt32 effectContextId);
typedef FfxErrorCode (*FfxScheduleGpuJobFunc)(FfxInterface *backendInterface, const FfxGpuJobDescription *job);
typedef FfxErrorCode (*FfxExecuteGpuJobsFunc)(FfxInterface *backendInterface, FfxCommandList commandList,
                                              FfxUInt32 effectContextId);
typedef FfxErrorCode (*FfxSwapChainConfigureFrameGenerationFunc)(FfxFrameGenerationConfig const *config);
typedef FfxErrorCode (*FfxBreadcrumbsAllocBlockFunc)(FfxInterface *backendInterface, uint64_t blockBytes,
                                                     FfxBreadcrumbsBlockData *blockData);
typedef void (*FfxBreadcrumbsFreeBlockFunc)(FfxInterface *backendInterface, FfxBreadcrumbsBlockData *blockData);
typedef void (*FfxBreadcrumbsWriteFunc)(FfxInterface *backendInterface, FfxCommandList commandList, uint32_t value,
                                        uint64_t gpuLocation, void *gpuBuffer, bool isBegin);
typedef void (*FfxBreadcrumbsPrintDeviceInfoFunc)(FfxInterface *backendInterface, FfxAllocationCallbacks *allocs,
                                                  bool extendedInfo, char **printBuffer, size_t *printSize);
typedef void (*FfxRegisterConstantBufferAllocatorFunc)(FfxInterface *backendInterface,
                                                       FfxConstantBufferAllocator constantAllocator);

/* The backend table (see the top of this file for which entries dnsr fills). */
struct FfxInterface {
    FfxGetSDKVersionFunc fpGetSDKVersion;
    FfxGetEffectGpuMemoryUsageFunc fpGetEffectGpuMemoryUsage;
    FfxCreateBackendContextFunc fpCreateBackendContext;
    FfxGetDeviceCapabilitiesFunc fpGetDeviceCapabilities;
    FfxDestroyBackendContextFunc fpDestroyBackendContext;
    FfxCreateResourceFunc fpCreateResource;
    FfxRegisterResourceFunc fpRegisterResource;
    FfxGetResourceFunc fpGetResource;
    FfxUnregisterResourcesFunc fpUnregisterResources;
    FfxRegisterStaticResourceFunc fpRegisterStaticResource;
    FfxGetResourceDescriptionFunc fpGetResourceDescription;
    FfxDestroyResourceFunc fpDestroyResource;
    FfxMapResourceFunc fpMapResource;
    FfxUnmapResourceFunc fpUnmapResource;
    FfxStageConstantBufferDataFunc fpStageConstantBufferDataFunc;
    FfxCreatePipelineFunc fpCreatePipeline;
    FfxDestroyPipelineFunc fpDestroyPipeline;
    FfxScheduleGpuJobFunc fpScheduleGpuJob;
    FfxExecuteGpuJobsFunc fpExecuteGpuJobs;
    FfxBreadcrumbsAllocBlockFunc fpBreadcrumbsAllocBlock;
    FfxBreadcrumbsFreeBlockFunc fpBreadcrumbsFreeBlock;
    FfxBreadcrumbsWriteFunc fpBreadcrumbsWrite;
    FfxBreadcrumbsPrintDeviceInfoFunc fpBreadcrumbsPrintDeviceInfo;
    FfxGetPermutationBlobByIndexFunc fpGetPermutationBlobByIndex;
    FfxSwapChainConfigureFrameGenerationFunc fpSwapChainConfigureFrameGeneration;
    FfxRegisterConstantBufferAllocatorFunc fpRegisterConstantBufferAllocator;
    /* The caller's scratch memory (ffxGetScratchMemorySizeVK bytes or more) and its size; ffxGetInterfaceVK
     * writes the device description there and ffxDenoiserContextCreate reads it (a context keeps a copy, so the
     * memory may be freed once the contexts are created). */
    void *scratchBuffer;
    size_t scratchBufferSize;
    /* From ffxGetDeviceVK. */
    FfxDevice device;
};

#ifdef __cplusplus
}
#endif

#endif

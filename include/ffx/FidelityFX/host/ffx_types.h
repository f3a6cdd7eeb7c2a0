/*
 * dnsr's FidelityFX SDK 1.1.4 compatibility headers: the types the shadow denoiser's Vulkan interface uses.
 *
 * Written for dnsr from the SDK's interface: names, values and layouts match SDK 1.1.4 so that an integration
 * compiles unchanged and its structures have the SDK's sizes (wchar_t names make FfxResource 304 bytes on Linux,
 * 176 on Windows, as in the SDK). Unlike the SDK's headers these compile as C11 as well as C++.
 * Only what the shadow denoiser and its Vulkan backend functions need is declared; the SDK's other effects,
 * its GPU job and pipeline structures are declared by name only (they appear in FfxInterface's function types).
 */
#ifndef FFX_TYPES_H
#define FFX_TYPES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <wchar.h>

/* Export decoration of the API functions: none (libdnsr exports them with default visibility). */
#ifndef FFX_API
#define FFX_API
#endif

/* Packs a version: major 10 bits, minor 10 bits, patch 12 bits (as the SDK's FFX_SDK_MAKE_VERSION). */
#define FFX_MAKE_VERSION(major, minor, patch) ((((uint32_t)(major)) << 22) | (((uint32_t)(minor)) << 12) | ((uint32_t)(patch)))

/* Length of FfxResource::name, in wchar_t. */
#define FFX_RESOURCE_NAME_SIZE 64
/* Frames the SDK's backend keeps per-frame objects for; dnsr keeps the image views it creates for a dispatch
 * alive for this many later dispatches of the same context. */
#define FFX_MAX_QUEUED_FRAMES (4)

/* The SDK's backend limits (SDK 1.1.4's values), for glue code that sizes its own tables by them; dnsr's
 * backend has none of these tables. */
#define FFX_MAX_NUM_SRVS 64
#define FFX_MAX_NUM_UAVS 64
#define FFX_MAX_NUM_CONST_BUFFERS 3
#define FFX_MAX_RESOURCE_COUNT (512)
#define FFX_MAX_PASS_COUNT (50)
#define FFX_MAX_BARRIERS (128)
#define FFX_MAX_GPU_JOBS (256)
#define FFX_MAX_SAMPLERS (16)
/* One constant-buffer entry of the SDK backend's ring, in bytes, and the ring descriptors and bytes it derives. */
#define FFX_BUFFER_SIZE (4096)
#define FFX_RING_BUFFER_DESCRIPTOR_COUNT (FFX_MAX_QUEUED_FRAMES * FFX_MAX_PASS_COUNT * FFX_MAX_RESOURCE_COUNT)
#define FFX_CONSTANT_BUFFER_RING_BUFFER_SIZE (FFX_MAX_QUEUED_FRAMES * FFX_MAX_PASS_COUNT * FFX_BUFFER_SIZE)

#ifdef __cplusplus
extern "C" {
#endif

typedef uint32_t FfxVersionNumber;
typedef bool FfxBoolean;
typedef uint8_t FfxUInt8;
typedef uint16_t FfxUInt16;
typedef uint32_t FfxUInt32;
typedef uint64_t FfxUInt64;
typedef int8_t FfxInt8;
typedef int16_t FfxInt16;
typedef int32_t FfxInt32;
typedef int64_t FfxInt64;
typedef float FfxFloat32;
typedef float FfxFloat32x2[2];
typedef float FfxFloat32x3[3];
typedef float FfxFloat32x4[4];
typedef float FfxFloat32x4x4[16];
typedef uint32_t FfxUInt32x2[2];
typedef uint32_t FfxUInt32x3[3];
typedef uint32_t FfxUInt32x4[4];
typedef int32_t FfxInt32x2[2];
typedef int32_t FfxInt32x3[3];
typedef int32_t FfxInt32x4[4];

/* Opaque API handles. With the Vulkan functions of ffx_vk.h: FfxDevice points at a VkDeviceContext copy,
 * FfxCommandList is a VkCommandBuffer, FfxPipeline a VkPipeline. */
typedef void *FfxDevice;
typedef void *FfxCommandQueue;
typedef void *FfxSwapchain;
typedef void *FfxCommandList;
typedef void *FfxRootSignature;
typedef void *FfxCommandSignature;
typedef void *FfxPipeline;

/* Message types (ffx_message.h) and the callback that receives them. */
typedef enum FfxMsgType {
    FFX_MESSAGE_TYPE_ERROR = 0,
    FFX_MESSAGE_TYPE_WARNING = 1,
    FFX_MESSAGE_TYPE_COUNT
} FfxMsgType;
typedef void (*ffxMessageCallback)(uint32_t type, const wchar_t *message);

/* Texel formats. A depth image is described by its colour twin (D32_SFLOAT as R32_FLOAT, D16_UNORM as R16_UNORM)
 * plus FFX_RESOURCE_USAGE_DEPTHTARGET. */
typedef enum FfxSurfaceFormat {
    FFX_SURFACE_FORMAT_UNKNOWN = 0,
    FFX_SURFACE_FORMAT_R32G32B32A32_TYPELESS = 1,
    FFX_SURFACE_FORMAT_R32G32B32A32_UINT = 2,
    FFX_SURFACE_FORMAT_R32G32B32A32_FLOAT = 3,
    FFX_SURFACE_FORMAT_R16G16B16A16_FLOAT = 4,
    FFX_SURFACE_FORMAT_R32G32B32_FLOAT = 5,
    FFX_SURFACE_FORMAT_R32G32_FLOAT = 6,
    FFX_SURFACE_FORMAT_R8_UINT = 7,
    FFX_SURFACE_FORMAT_R32_UINT = 8,
    FFX_SURFACE_FORMAT_R8G8B8A8_TYPELESS = 9,
    FFX_SURFACE_FORMAT_R8G8B8A8_UNORM = 10,
    FFX_SURFACE_FORMAT_R8G8B8A8_SNORM = 11,
    FFX_SURFACE_FORMAT_R8G8B8A8_SRGB = 12,
    FFX_SURFACE_FORMAT_B8G8R8A8_TYPELESS = 13,
    FFX_SURFACE_FORMAT_B8G8R8A8_UNORM = 14,
    FFX_SURFACE_FORMAT_B8G8R8A8_SRGB = 15,
    FFX_SURFACE_FORMAT_R11G11B10_FLOAT = 16,
    FFX_SURFACE_FORMAT_R10G10B10A2_UNORM = 17,
    FFX_SURFACE_FORMAT_R16G16_FLOAT = 18,
    FFX_SURFACE_FORMAT_R16G16_UINT = 19,
    FFX_SURFACE_FORMAT_R16G16_SINT = 20,
    FFX_SURFACE_FORMAT_R16_FLOAT = 21,
    FFX_SURFACE_FORMAT_R16_UINT = 22,
    FFX_SURFACE_FORMAT_R16_UNORM = 23,
    FFX_SURFACE_FORMAT_R16_SNORM = 24,
    FFX_SURFACE_FORMAT_R8_UNORM = 25,
    FFX_SURFACE_FORMAT_R8G8_UNORM = 26,
    FFX_SURFACE_FORMAT_R8G8_UINT = 27,
    FFX_SURFACE_FORMAT_R32_FLOAT = 28,
    FFX_SURFACE_FORMAT_R9G9B9E5_SHAREDEXP = 29,
    FFX_SURFACE_FORMAT_R16G16B16A16_TYPELESS = 30,
    FFX_SURFACE_FORMAT_R32G32_TYPELESS = 31,
    FFX_SURFACE_FORMAT_R10G10B10A2_TYPELESS = 32,
    FFX_SURFACE_FORMAT_R16G16_TYPELESS = 33,
    FFX_SURFACE_FORMAT_R16_TYPELESS = 34,
    FFX_SURFACE_FORMAT_R8_TYPELESS = 35,
    FFX_SURFACE_FORMAT_R8G8_TYPELESS = 36,
    FFX_SURFACE_FORMAT_R32_TYPELESS = 37
} FfxSurfaceFormat;

/* How a resource may be used (bits). */
typedef enum FfxResourceUsage {
    FFX_RESOURCE_USAGE_READ_ONLY = 0,
    FFX_RESOURCE_USAGE_RENDERTARGET = (1 << 0),
    FFX_RESOURCE_USAGE_UAV = (1 << 1),
    FFX_RESOURCE_USAGE_DEPTHTARGET = (1 << 2),
    FFX_RESOURCE_USAGE_INDIRECT = (1 << 3),
    FFX_RESOURCE_USAGE_ARRAYVIEW = (1 << 4),
    FFX_RESOURCE_USAGE_STENCILTARGET = (1 << 5),
    FFX_RESOURCE_USAGE_DCC_RENDERTARGET = (1 << 15)
} FfxResourceUsage;

/* The state a resource is in when the recorded commands execute (dnsr maps it to a Vulkan image layout; it
 * leaves every image in the state it was passed in). */
typedef enum FfxResourceStates {
    FFX_RESOURCE_STATE_COMMON = (1 << 0),
    FFX_RESOURCE_STATE_UNORDERED_ACCESS = (1 << 1),
    FFX_RESOURCE_STATE_COMPUTE_READ = (1 << 2),
    FFX_RESOURCE_STATE_PIXEL_READ = (1 << 3),
    FFX_RESOURCE_STATE_PIXEL_COMPUTE_READ = (FFX_RESOURCE_STATE_PIXEL_READ | FFX_RESOURCE_STATE_COMPUTE_READ),
    FFX_RESOURCE_STATE_COPY_SRC = (1 << 4),
    FFX_RESOURCE_STATE_COPY_DEST = (1 << 5),
    FFX_RESOURCE_STATE_GENERIC_READ = (FFX_RESOURCE_STATE_COPY_SRC | FFX_RESOURCE_STATE_COMPUTE_READ),
    FFX_RESOURCE_STATE_INDIRECT_ARGUMENT = (1 << 6),
    FFX_RESOURCE_STATE_PRESENT = (1 << 7),
    FFX_RESOURCE_STATE_RENDER_TARGET = (1 << 8),
    FFX_RESOURCE_STATE_DEPTH_ATTACHEMENT = (1 << 9)
} FfxResourceStates;

typedef enum FfxResourceType {
    FFX_RESOURCE_TYPE_BUFFER = 0,
    FFX_RESOURCE_TYPE_TEXTURE1D = 1,
    FFX_RESOURCE_TYPE_TEXTURE2D = 2,
    FFX_RESOURCE_TYPE_TEXTURE_CUBE = 3,
    FFX_RESOURCE_TYPE_TEXTURE3D = 4
} FfxResourceType;

typedef enum FfxResourceFlags {
    FFX_RESOURCE_FLAGS_NONE = 0,
    FFX_RESOURCE_FLAGS_ALIASABLE = (1 << 0),
    FFX_RESOURCE_FLAGS_UNDEFINED = (1 << 1)
} FfxResourceFlags;

typedef enum FfxShaderModel {
    FFX_SHADER_MODEL_5_1 = 0,
    FFX_SHADER_MODEL_6_0 = 1,
    FFX_SHADER_MODEL_6_1 = 2,
    FFX_SHADER_MODEL_6_2 = 3,
    FFX_SHADER_MODEL_6_3 = 4,
    FFX_SHADER_MODEL_6_4 = 5,
    FFX_SHADER_MODEL_6_5 = 6,
    FFX_SHADER_MODEL_6_6 = 7,
    FFX_SHADER_MODEL_6_7 = 8
} FfxShaderModel;

typedef enum FfxEffect {
    FFX_EFFECT_FSR2 = 0,
    FFX_EFFECT_FSR1 = 1,
    FFX_EFFECT_SPD = 2,
    FFX_EFFECT_BLUR = 3,
    FFX_EFFECT_BREADCRUMBS = 4,
    FFX_EFFECT_BRIXELIZER = 5,
    FFX_EFFECT_BRIXELIZER_GI = 6,
    FFX_EFFECT_CACAO = 7,
    FFX_EFFECT_CAS = 8,
    FFX_EFFECT_DENOISER = 9,
    FFX_EFFECT_LENS = 10,
    FFX_EFFECT_PARALLEL_SORT = 11,
    FFX_EFFECT_SSSR = 12,
    FFX_EFFECT_VARIABLE_SHADING = 13,
    FFX_EFFECT_LPM = 14,
    FFX_EFFECT_DOF = 15,
    FFX_EFFECT_CLASSIFIER = 16,
    FFX_EFFECT_FSR3UPSCALER = 17,
    FFX_EFFECT_FRAMEINTERPOLATION = 18,
    FFX_EFFECT_OPTICALFLOW = 19,
    FFX_EFFECT_SHAREDRESOURCES = 127,
    FFX_EFFECT_SHAREDAPIBACKEND = 128
} FfxEffect;

typedef enum FfxBindStage {
    FFX_BIND_PIXEL_SHADER_STAGE = (1 << 0),
    FFX_BIND_VERTEX_SHADER_STAGE = (1 << 1),
    FFX_BIND_COMPUTE_SHADER_STAGE = (1 << 2)
} FfxBindStage;

typedef struct FfxDimensions2D {
    uint32_t width;
    uint32_t height;
} FfxDimensions2D;

typedef struct FfxIntCoords2D {
    int32_t x;
    int32_t y;
} FfxIntCoords2D;

typedef struct FfxFloatCoords2D {
    float x;
    float y;
} FfxFloatCoords2D;

typedef struct FfxRect2D {
    int32_t left;
    int32_t top;
    int32_t width;
    int32_t height;
} FfxRect2D;

/* What a resource is. For an image: type FFX_RESOURCE_TYPE_TEXTURE2D, its format, width and height of mip 0,
 * depth = array layers, its mip count, usage bits (DEPTHTARGET for a depth format). */
typedef struct FfxResourceDescription {
    FfxResourceType type;
    FfxSurfaceFormat format;
    union {
        uint32_t width;
        uint32_t size;
    };
    union {
        uint32_t height;
        uint32_t stride;
    };
    union {
        uint32_t depth;
        uint32_t alignment;
    };
    uint32_t mipCount;
    FfxResourceFlags flags;
    FfxResourceUsage usage;
} FfxResourceDescription;

/* One resource as a dispatch names it: the API handle (a VkImage for dnsr), its description, its current state
 * and an optional name (dnsr does not read it). */
typedef struct FfxResource {
    void *resource;
    FfxResourceDescription description;
    FfxResourceStates state;
    wchar_t name[FFX_RESOURCE_NAME_SIZE];
} FfxResource;

typedef struct FfxResourceInternal {
    int32_t internalIndex;
} FfxResourceInternal;

typedef struct FfxDeviceCapabilities {
    FfxShaderModel maximumSupportedShaderModel;
    uint32_t waveLaneCountMin;
    uint32_t waveLaneCountMax;
    bool fp16Supported;
    bool raytracingSupported;
    bool deviceCoherentMemorySupported;
    bool dedicatedAllocationSupported;
    bool bufferMarkerSupported;
    bool extendedSynchronizationSupported;
    bool shaderStorageBufferArrayNonUniformIndexing;
} FfxDeviceCapabilities;

typedef struct FfxEffectBindlessConfig {
    uint32_t maxTextureSrvs;
    uint32_t maxBufferSrvs;
    uint32_t maxTextureUavs;
    uint32_t maxBufferUavs;
} FfxEffectBindlessConfig;

typedef struct FfxEffectMemoryUsage {
    uint64_t totalUsageInBytes;
    uint64_t aliasableUsageInBytes;
} FfxEffectMemoryUsage;

typedef struct FfxConstantBuffer {
    uint32_t num32BitEntries;
    uint32_t *data;
} FfxConstantBuffer;

typedef struct FfxBreadcrumbsBlockData {
    void *memory;
    void *heap;
    void *buffer;
    uint64_t baseAddress;
    uint32_t nextMarker;
} FfxBreadcrumbsBlockData;

typedef void *(*FfxAllocFunc)(size_t size);
typedef void *(*FfxReallocFunc)(void *ptr, size_t size);
typedef void (*FfxFreeFunc)(void *ptr);

typedef struct FfxAllocationCallbacks {
    FfxAllocFunc fpAlloc;
    FfxReallocFunc fpRealloc;
    FfxFreeFunc fpFree;
} FfxAllocationCallbacks;

typedef struct FfxConstantAllocation {
    FfxResource resource;
    FfxUInt64 handle;
} FfxRootConstantAllocation;

typedef struct FfxConstantAllocation (*FfxConstantBufferAllocator)(void *data, const FfxUInt64 dataSize);

/* How a backend fills a resource it creates: with a copy of a buffer, with one byte value, or not at all. */
typedef enum FfxResourceInitDataType {
    FFX_RESOURCE_INIT_DATA_TYPE_INVALID = 0,
    FFX_RESOURCE_INIT_DATA_TYPE_UNINITIALIZED = 1,
    FFX_RESOURCE_INIT_DATA_TYPE_BUFFER = 2,
    FFX_RESOURCE_INIT_DATA_TYPE_VALUE = 3
} FfxResourceInitDataType;

/* A resource's initial contents (24 bytes on 64-bit targets, as in the SDK). */
typedef struct FfxResourceInitData {
    FfxResourceInitDataType type;
    /* Bytes to initialise. */
    size_t size;
    union {
        /* FFX_RESOURCE_INIT_DATA_TYPE_BUFFER: the bytes to copy. */
        void *buffer;
        /* FFX_RESOURCE_INIT_DATA_TYPE_VALUE: the byte every byte is set to. */
        unsigned char value;
    };
#ifdef __cplusplus
    /* The SDK's C++ helpers building a value- or buffer-initialised description. */
    static FfxResourceInitData FfxResourceInitValue(size_t dataSize, uint8_t initVal)
    {
        FfxResourceInitData d = {FFX_RESOURCE_INIT_DATA_TYPE_VALUE, dataSize, {nullptr}};
        d.value = initVal;
        return d;
    }
    static FfxResourceInitData FfxResourceInitBuffer(size_t dataSize, void *pInitData)
    {
        FfxResourceInitData d = {FFX_RESOURCE_INIT_DATA_TYPE_BUFFER, dataSize, {pInitData}};
        return d;
    }
#endif
} FfxResourceInitData;

/* Structures that appear in FfxInterface's function types only; dnsr neither defines nor uses them. */
typedef struct FfxCreateResourceDescription FfxCreateResourceDescription;
typedef struct FfxStaticResourceDescription FfxStaticResourceDescription;
typedef struct FfxPipelineDescription FfxPipelineDescription;
typedef struct FfxPipelineState FfxPipelineState;
typedef struct FfxGpuJobDescription FfxGpuJobDescription;
typedef struct FfxShaderBlob FfxShaderBlob;
typedef struct FfxFrameGenerationConfig FfxFrameGenerationConfig;

#ifdef __cplusplus
}
#endif

#endif

/*
 * dnsr's FidelityFX SDK 1.1.4 compatibility headers: the denoiser.
 *
 * An integration of the SDK 1.1.x shadow denoiser on Vulkan builds against these headers unchanged (add
 * <dnsr>/include/ffx to the include path ahead of the SDK's, link libdnsr instead of ffx_denoiser_x64 and
 * ffx_backend_vk_x64) and runs dnsr with its default settings (the Quality preset: docs/do-no-harm.md); with
 * DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS (dnsr.h) in FfxDenoiserContextDescription.flags, with the FidelityFX settings
 * (DNSR_PRESET_BALANCED: the SDK's output). docs/migrating-from-ffx.md says what changes, what dnsr fixes, and how to
 * move on to dnsr.h step by step.
 *
 * What is supported, function by function (every failure also sets dnsr_last_error_message()):
 *   ffxDenoiserContextCreate: FFX_DENOISER_SHADOWS, optionally FFX_DENOISER_ENABLE_DEPTH_INVERTED and dnsr's
 *     DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS (1 << 30); other unknown bits are ignored, as the SDK does. FFX_DENOISER_REFLECTIONS: FFX_ERROR_INVALID_ARGUMENT (dnsr has no
 *     reflections denoiser), nothing created. The backend interface must come from ffxGetInterfaceVK (else
 *     FFX_ERROR_INCOMPLETE_INTERFACE). A NULL pointer gives FFX_ERROR_INVALID_POINTER, a zero window size
 *     FFX_ERROR_INVALID_ARGUMENT.
 *   ffxDenoiserContextDispatchShadows: records dnsr's passes into commandList. The first dispatch after create
 *     starts from empty history (there is no reset field: to reset, destroy and create, or use dnsr.h's
 *     DNSR_DISPATCH_RESET). Resources are VkImages in the states they are in; dnsr creates the views it needs
 *     (kept for FFX_MAX_QUEUED_FRAMES later dispatches) and leaves every image in its state. Depth may be a depth
 *     image (DEPTHTARGET usage) or an R32_FLOAT colour copy. The output must be R8_UNORM, R16_FLOAT, R32_FLOAT,
 *     R8G8B8A8_UNORM or R16G16B16A16_FLOAT (the shadow in every channel) and the same format on every dispatch of
 *     a context (else FFX_ERROR_INVALID_ARGUMENT). velocity is read in
 *     the SDK's convention: history uv = uv + motionVectorScale * v. frameIndex is accepted and not needed (dnsr
 *     keeps its own history ping-pong). Bad input (a NULL image, an image smaller than the window, non-finite
 *     matrices) is refused with FFX_ERROR_INVALID_ARGUMENT and nothing is recorded, where the SDK returns FFX_OK.
 *     Barriers: dnsr waits for all earlier commands' writes to the inputs and makes its output visible to all
 *     later commands (the FFX interface does not say which stages produced or consume them).
 *   ffxDenoiserContextDispatchReflections: FFX_ERROR_INVALID_ARGUMENT, nothing recorded.
 *   ffxDenoiserContextDestroy: FFX_OK; the GPU must have finished the command buffers the context recorded into.
 *     A context that is not live (never created, or destroyed) gives FFX_ERROR_INVALID_ARGUMENT, where the SDK
 *     crashes or frees twice.
 *   ffxDenoiserGetEffectVersion: 1.3.0, the version SDK 1.1.4's denoiser reports.
 */
#ifndef FFX_DENOISER_H
#define FFX_DENOISER_H

#include "ffx_interface.h"

#define FFX_DENOISER_VERSION_MAJOR (1)
#define FFX_DENOISER_VERSION_MINOR (3)
#define FFX_DENOISER_VERSION_PATCH (0)
#define FFX_DENOISER_CONTEXT_COUNT 1
/* Size of FfxDenoiserContext in uint32_t (dnsr keeps a handle to its own context in it). */
#define FFX_DENOISER_CONTEXT_SIZE (73098)

#ifdef __cplusplus
extern "C" {
#endif

typedef enum FfxDenoiserPass {
    FFX_DENOISER_PASS_PREPARE_SHADOW_MASK = 0,
    FFX_DENOISER_PASS_SHADOWS_TILE_CLASSIFICATION = 1,
    FFX_DENOISER_PASS_FILTER_SOFT_SHADOWS_0 = 2,
    FFX_DENOISER_PASS_FILTER_SOFT_SHADOWS_1 = 3,
    FFX_DENOISER_PASS_FILTER_SOFT_SHADOWS_2 = 4,
    FFX_DENOISER_PASS_REPROJECT_REFLECTIONS = 5,
    FFX_DENOISER_PASS_PREFILTER_REFLECTIONS = 6,
    FFX_DENOISER_PASS_RESOLVE_TEMPORAL_REFLECTIONS = 7,
    FFX_DENOISER_PASS_COUNT
} FfxDenoiserPass;

typedef enum FfxDenoiserInitializationFlagBits {
    FFX_DENOISER_SHADOWS = (1 << 0),
    FFX_DENOISER_REFLECTIONS = (1 << 1),
    FFX_DENOISER_ENABLE_DEPTH_INVERTED = (1 << 2)
} FfxDenoiserInitializationFlagBits;

typedef struct FfxDenoiserContextDescription {
    /* FfxDenoiserInitializationFlagBits. */
    uint32_t flags;
    /* Render size in pixels (the size of depth, velocity, normal and the output). */
    FfxDimensions2D windowSize;
    /* Reflections only; not read. */
    FfxSurfaceFormat normalsHistoryBufferFormat;
    /* From ffxGetInterfaceVK. */
    FfxInterface backendInterface;
} FfxDenoiserContextDescription;

/* One frame. Matrices are column-major float[16] mapping column vectors, as in the SDK. */
typedef struct FfxDenoiserShadowsDispatchDescription {
    /* From ffxGetCommandListVK. */
    FfxCommandList commandList;
    /* R32_UINT, one word per 8x4 tile, a bit set where the shadow ray hit an occluder. */
    FfxResource hitMaskResults;
    /* Hardware depth (0..1; 1 = far, or near with FFX_DENOISER_ENABLE_DEPTH_INVERTED). */
    FfxResource depth;
    /* Motion in uv units (RG16F/RG32F): history uv = uv + motionVectorScale * v. */
    FfxResource velocity;
    /* World-space normals, decoded as rgb * normalsUnpackMul + normalsUnpackAdd. */
    FfxResource normal;
    /* The denoised visibility (1 = lit): an R8_UNORM, R16_FLOAT, R32_FLOAT, R8G8B8A8_UNORM or R16G16B16A16_FLOAT
     * storage image (4-channel formats get the visibility in every channel). */
    FfxResource shadowMaskOutput;
    FfxFloat32x2 motionVectorScale;
    FfxFloat32 normalsUnpackMul;
    FfxFloat32 normalsUnpackAdd;
    /* Camera position in world space. */
    FfxFloat32x3 eye;
    uint32_t frameIndex;
    /* Clip space is the SDK's: y up (NDC = (2 uv - 1) * (1, -1)), depth 0..1; column-major, column vectors. dnsr
     * flips y for its own API, which reads Vulkan's convention. Clip space -> view space. */
    FfxFloat32 projectionInverse[16];
    /* Current clip space -> previous frame's clip space. */
    FfxFloat32 reprojectionMatrix[16];
    FfxFloat32 viewProjectionInverse[16];
    /* Depth edge stop of the filter (the SDK's sample passes 1). */
    FfxFloat32 depthSimilaritySigma;
} FfxDenoiserShadowsDispatchDescription;

/* The SDK's reflections dispatch, declared so that code naming it compiles; dnsr refuses it. */
typedef struct FfxDenoiserReflectionsDispatchDescription {
    FfxCommandList commandList;
    FfxResource depthHierarchy;
    FfxResource motionVectors;
    FfxResource normal;
    FfxResource radianceA;
    FfxResource radianceB;
    FfxResource varianceA;
    FfxResource varianceB;
    FfxResource extractedRoughness;
    FfxResource denoiserTileList;
    FfxResource indirectArgumentsBuffer;
    FfxResource output;
    FfxDimensions2D renderSize;
    FfxFloatCoords2D motionVectorScale;
    float invProjection[16];
    float invView[16];
    float prevViewProjection[16];
    float normalsUnpackMul;
    float normalsUnpackAdd;
    bool isRoughnessPerceptual;
    uint32_t roughnessChannel;
    float temporalStabilityFactor;
    float roughnessThreshold;
    uint32_t frameIndex;
    bool reset;
} FfxDenoiserReflectionsDispatchDescription;

/* Caller-allocated storage of a context (zeroing it is not needed). */
typedef struct FfxDenoiserContext {
    uint32_t data[FFX_DENOISER_CONTEXT_SIZE];
} FfxDenoiserContext;

FFX_API FfxErrorCode ffxDenoiserContextCreate(FfxDenoiserContext *pContext,
                                              const FfxDenoiserContextDescription *pContextDescription);
FFX_API FfxErrorCode ffxDenoiserContextDispatchShadows(FfxDenoiserContext *context,
                                                       const FfxDenoiserShadowsDispatchDescription *dispatchDescription);
FFX_API FfxErrorCode ffxDenoiserContextDispatchReflections(
    FfxDenoiserContext *context, const FfxDenoiserReflectionsDispatchDescription *dispatchDescription);
FFX_API FfxErrorCode ffxDenoiserContextDestroy(FfxDenoiserContext *context);
FFX_API FfxVersionNumber ffxDenoiserGetEffectVersion(void);

#ifdef __cplusplus
}
#endif

#endif

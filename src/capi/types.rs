//! The C types of include/dnsr.h. Field docs say: required or optional, lifetime, units, default.
//!
//! Enumerations that the host writes are `uint32_t` typedefs with `#define` values (a Rust enum must never
//! receive an out-of-range value from C); each family ends with a `_MAX_ENUM` = 0x7FFFFFFF value.
#![allow(non_camel_case_types)]

use ash::vk;
use std::ffi::{c_char, c_void};

// Vulkan types come from <vulkan/vulkan.h>; cbindgen is told not to emit these aliases.
/// `VkInstance`.
pub type VkInstance = vk::Instance;
/// `VkPhysicalDevice`.
pub type VkPhysicalDevice = vk::PhysicalDevice;
/// `VkDevice`.
pub type VkDevice = vk::Device;
/// `VkCommandBuffer`.
pub type VkCommandBuffer = vk::CommandBuffer;
/// `VkImage`.
pub type VkImage = vk::Image;
/// `VkImageView`.
pub type VkImageView = vk::ImageView;
/// `VkBuffer`.
pub type VkBuffer = vk::Buffer;
/// `VkFormat`.
pub type VkFormat = vk::Format;
/// `VkImageLayout`.
pub type VkImageLayout = vk::ImageLayout;
/// `VkPipelineStageFlags`.
pub type VkPipelineStageFlags = vk::PipelineStageFlags;
/// `VkAccessFlags`.
pub type VkAccessFlags = vk::AccessFlags;
/// `VkDeviceMemory`.
pub type VkDeviceMemory = vk::DeviceMemory;
/// `VkDeviceSize`.
pub type VkDeviceSize = vk::DeviceSize;
/// `VkMemoryRequirements`.
pub type VkMemoryRequirements = vk::MemoryRequirements;
/// `VkAllocationCallbacks`.
pub type VkAllocationCallbacks = vk::AllocationCallbacks<'static>;
/// `VkObjectType`.
pub type VkObjectType = vk::ObjectType;
/// `VkResult`.
pub type VkResult = vk::Result;
/// `PFN_vkGetInstanceProcAddr` (nullable).
pub type PFN_vkGetInstanceProcAddr = Option<vk::PFN_vkGetInstanceProcAddr>;
/// `PFN_vkGetDeviceProcAddr` (nullable).
pub type PFN_vkGetDeviceProcAddr = Option<vk::PFN_vkGetDeviceProcAddr>;

/// Result of every dnsr function. Negative values are errors; `dnsr_last_error_message` says what was wrong.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DnsrResult {
    /// The call succeeded.
    DNSR_SUCCESS = 0,
    /// Nothing to report yet (e.g. no recorded frame has completed for `dnsr_context_get_timings`).
    DNSR_NOT_READY = 1,
    /// A required pointer argument is NULL, or an argument is out of range.
    DNSR_ERROR_INVALID_ARGUMENT = -1,
    /// A structure's `sType` is wrong.
    DNSR_ERROR_INVALID_STRUCTURE = -2,
    /// The context handle is not a live context (never created, or already destroyed).
    DNSR_ERROR_INVALID_HANDLE = -3,
    /// A required Vulkan handle or function pointer in a structure is null.
    DNSR_ERROR_NULL_HANDLE = -4,
    /// The declared Vulkan API version is too old or newer than the device.
    DNSR_ERROR_UNSUPPORTED_API_VERSION = -5,
    /// A requested feature was not declared enabled, or the device lacks it.
    DNSR_ERROR_MISSING_FEATURE = -6,
    /// A width or height is zero or larger than the device supports.
    DNSR_ERROR_INVALID_EXTENT = -7,
    /// A host image's extent does not match the render size.
    DNSR_ERROR_IMAGE_EXTENT_MISMATCH = -8,
    /// A format dnsr cannot read or write for that image, or the device cannot use that way.
    DNSR_ERROR_UNSUPPORTED_FORMAT = -9,
    /// A host image layout dnsr cannot use.
    DNSR_ERROR_UNSUPPORTED_LAYOUT = -10,
    /// A matrix or vector contains NaN or infinity.
    DNSR_ERROR_NON_FINITE = -11,
    /// The render rectangle is empty, misaligned or outside the images.
    DNSR_ERROR_INVALID_RENDER_RECT = -12,
    /// A setting is out of range.
    DNSR_ERROR_INVALID_SETTING = -13,
    /// The light index is not below the context's light count.
    DNSR_ERROR_INVALID_LIGHT_INDEX = -14,
    // -15 was DNSR_ERROR_DESCRIPTOR_CACHE_FULL (dnsr 0.1.0); descriptor sets are now rewritten every frame.
    /// Timestamps were requested but the queue family cannot write them.
    DNSR_ERROR_TIMESTAMPS_UNSUPPORTED = -16,
    /// A shader override is not valid SPIR-V for the device, or does not match dnsr's binding interface.
    DNSR_ERROR_SHADER_INTERFACE = -17,
    /// A Vulkan call (or the host's GPU memory allocator) failed.
    DNSR_ERROR_VULKAN = -18,
    /// A bug in dnsr (a caught panic). The context that reported it should be destroyed.
    DNSR_ERROR_INTERNAL = -19,
    /// The context would need more device memory than the device has (checked before anything is allocated:
    /// the largest device-local heap's budget with VK_EXT_memory_budget, else its size).
    DNSR_ERROR_OUT_OF_DEVICE_MEMORY = -20,
    /// `sync` names unknown bits, a stage the device or queue family does not support, or an access that no
    /// given stage performs (Vulkan's "supported access types").
    DNSR_ERROR_INVALID_HOST_SYNC = -21,
    /// `queueFamilyIndex` does not exist on the physical device, or the family cannot run compute work.
    DNSR_ERROR_INVALID_QUEUE_FAMILY = -22,
    /// The classifier was used on a context created without DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER.
    DNSR_ERROR_CLASSIFIER_NOT_ENABLED = -23,
    /// A host allocation failed (the CPU reference's per-pixel buffers for a large frame): nothing was written.
    DNSR_ERROR_OUT_OF_HOST_MEMORY = -24,
    /// Forces a 32-bit enum.
    DNSR_RESULT_MAX_ENUM = 0x7FFF_FFFF,
}

/// Structure type tags (`sType`).
pub type DnsrStructureType = u32;
/// `DnsrContextCreateInfo`.
pub const DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO: DnsrStructureType = 1;
/// `DnsrShadowsDispatch`.
pub const DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH: DnsrStructureType = 2;
/// `DnsrSettings`.
pub const DNSR_STRUCTURE_TYPE_SETTINGS: DnsrStructureType = 3;
/// `DnsrPassTimings`.
pub const DNSR_STRUCTURE_TYPE_PASS_TIMINGS: DnsrStructureType = 4;
/// `DnsrDeviceRequirements`.
pub const DNSR_STRUCTURE_TYPE_DEVICE_REQUIREMENTS: DnsrStructureType = 5;
/// `DnsrLightDispatch`.
pub const DNSR_STRUCTURE_TYPE_LIGHT_DISPATCH: DnsrStructureType = 6;
/// `DnsrClassifyDispatch`.
pub const DNSR_STRUCTURE_TYPE_CLASSIFY_DISPATCH: DnsrStructureType = 7;
/// `DnsrClassifierBuffers`.
pub const DNSR_STRUCTURE_TYPE_CLASSIFIER_BUFFERS: DnsrStructureType = 8;
/// `DnsrClassifierTimings`.
pub const DNSR_STRUCTURE_TYPE_CLASSIFIER_TIMINGS: DnsrStructureType = 9;
/// `DnsrReferenceFrameInfo` (the CPU reference from C).
pub const DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO: DnsrStructureType = 10;
/// Forces 32 bits.
pub const DNSR_STRUCTURE_TYPE_MAX_ENUM: DnsrStructureType = 0x7FFF_FFFF;

/// Optional device features the host enabled (bit flags).
pub type DnsrFeatureFlags = u32;
/// `shaderFloat16` and `storageBuffer16BitAccess` are enabled (needed by `DNSR_PRECISION_FP16`).
pub const DNSR_FEATURE_FLOAT16: DnsrFeatureFlags = 1 << 0;
/// VK_KHR_push_descriptor is enabled.
pub const DNSR_FEATURE_PUSH_DESCRIPTOR: DnsrFeatureFlags = 1 << 1;
// 1 << 2 was DNSR_FEATURE_SUBGROUP_SIZE_CONTROL (dnsr 0.1.0): the shaders are subgroup-size agnostic.
/// Forces 32 bits.
pub const DNSR_FEATURE_MAX_ENUM: DnsrFeatureFlags = 0x7FFF_FFFF;

/// Context creation flags.
pub type DnsrContextCreateFlags = u32;
/// Reverse-Z: depth 1 is near, 0 is far (sky).
pub const DNSR_CONTEXT_CREATE_DEPTH_INVERTED: DnsrContextCreateFlags = 1 << 0;
// 1 << 1 was DNSR_CONTEXT_CREATE_INFINITE_FAR (dnsr 0.1.0): an infinite far plane needs no flag.
/// Record GPU timestamps around each pass and the classifier's dispatch (read with `dnsr_context_get_timings`,
/// `dnsr_context_get_classifier_timings`).
pub const DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS: DnsrContextCreateFlags = 1 << 2;
/// Create the hybrid-shadows classifier (`dnsr_classify_record`): its pipelines and its tile list and counts
/// buffers (16 B per 8x4 tile, about 0.5 B/px, plus 1 KiB).
pub const DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER: DnsrContextCreateFlags = 1 << 3;
/// The host aliases dnsr's transient memory (needs pGpuMemoryCallbacks). The images whose contents do not outlive
/// one record (tile state, the temporal result, the filter's intermediates, the reconstructed visibility:
/// dnsr_context_get_memory_usage less dnsr_context_get_persistent_memory_usage, the constants buffer aside) are
/// allocated with DNSR_RESOURCE_KIND_TRANSIENT_IMAGE, and every record moves them out of VK_IMAGE_LAYOUT_UNDEFINED.
/// The host may bind that memory to its own resources too, provided its use of them has finished before a record
/// of dnsr's begins (dnsr's first barrier waits for the stages and accesses the dispatch's sync names as
/// inputSrcStages / inputSrcAccess, and for earlier compute and transfer work) and begins after it ends (order it
/// after the stages named as outputDstStages). Costs one layout transition per transient image on every record.
pub const DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY: DnsrContextCreateFlags = 1 << 4;
/// Each light keeps its own transient images instead of every light sharing one set. Shared (the default), a
/// record of several lights records each light's passes in a row and only the persistent images grow with the light
/// count (dnsr_get_persistent_memory_requirements: 10.4 B/px per light after the first with a hit mask instead of
/// 18.7; 4 lights 49.8 instead of 74.9 B/px). With this flag dnsr_lights_record records pass by pass for every light
/// and runs the later filter passes four lights per dispatch, which measured faster where every tile is active (4
/// lights at 3840x2160 on an H200: Quality 4.97 instead of 5.17 ms, Balanced 3.75 instead of 4.21; the typical scene's
/// Quality the same; BENCHMARKS.md, "Several lights"). dnsr_get_memory_requirements does
/// not count it: each light after the first adds the difference between a one-light context's
/// dnsr_get_memory_requirements and its dnsr_get_persistent_memory_requirements, the constants aside. No effect
/// with one light.
pub const DNSR_CONTEXT_CREATE_TRANSIENT_MEMORY_PER_LIGHT: DnsrContextCreateFlags = 1 << 5;
/// Every record holds every light of the context (one dnsr_lights_record call with all lightCount lights;
/// dnsr_shadows_record only where the context has one light; a record with fewer is refused with
/// DNSR_ERROR_INVALID_ARGUMENT): the lights then share one depth copy (this frame's depth and normal, kept for the next
/// frame's reprojection), which only the record's last light writes; the others write theirs to a transient image,
/// for their own later filter passes. Each light after the first keeps 4 B/px less (with a hit mask 6.25 B/px
/// instead of 10.25; dnsr_get_memory_requirements and dnsr_get_persistent_memory_requirements do not count it), with
/// outputs bit for bit the same. At most DNSR_MAX_LIGHTS_PER_RECORD lights. No effect with one light.
pub const DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER: DnsrContextCreateFlags = 1 << 6;
/// The host gives dnsr its previous frame's depth and normals with every dispatch (DnsrShadowsDispatch::previousDepth
/// and previousNormals, required then), so that dnsr keeps no depth copy of its own: 4 B/px less persistent memory
/// per light (6.25 B/px kept instead of 10.25 with a hit mask; dnsr_get_memory_requirements counts the same bytes,
/// moved to the transient part, which DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY hands to the host). Where the
/// previous images hold exactly what the host gave as depth and normals last frame (and the projection's depth
/// mapping did not change), the output is the one without this flag but where the depth copy's rounding (16-bit
/// depth, 8-bit octahedral normals) would have decided a test the other way: as accurate, and no slower. Hit-mask
/// input only
/// (DNSR_ERROR_INVALID_ARGUMENT otherwise).
pub const DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER: DnsrContextCreateFlags = 1 << 7;
/// Forces 32 bits.
pub const DNSR_CONTEXT_CREATE_MAX_ENUM: DnsrContextCreateFlags = 0x7FFF_FFFF;

/// Filter precision.
pub type DnsrPrecision = u32;
/// 32-bit floats everywhere.
pub const DNSR_PRECISION_FP32: DnsrPrecision = 0;
/// float16 filter arithmetic and 16-bit intermediates (needs `DNSR_FEATURE_FLOAT16`).
pub const DNSR_PRECISION_FP16: DnsrPrecision = 1;
/// Forces 32 bits.
pub const DNSR_PRECISION_MAX_ENUM: DnsrPrecision = 0x7FFF_FFFF;

/// What the engine's shadow rays deliver per pixel (DnsrContextCreateInfo::shadowInput).
pub type DnsrShadowInput = u32;
/// One ray per pixel, packed into the 8x4-tile hit mask (DnsrShadowsDispatch::hitMask), as FidelityFX.
pub const DNSR_SHADOW_INPUT_HIT_MASK: DnsrShadowInput = 0;
/// The fraction of the pixel's rays that reached the light, in [0, 1] (DnsrShadowsDispatch::visibility): for
/// engines tracing several rays per pixel, sampling area lights, or mixing analytic and traced shadows. Only exact
/// 0 and 1 count as uniform or extend runs of identical samples; the temporal moments are those of the per-frame
/// values, so k rays per pixel give the variance of a mean of k samples. 12 B/px more device memory per light than
/// dnsr_get_memory_requirements says (the moments keep the samples' sum of squared deviations, and the filter's
/// signal between passes takes an image of its own).
pub const DNSR_SHADOW_INPUT_VISIBILITY: DnsrShadowInput = 1;
/// Half a ray per pixel: hitMask (in its hitMaskConvention) holds this frame's rays for the pixels with
/// (x + y) % 2 == DnsrShadowsDispatch::checkerboardPhase only (x, y in image pixels); alternate the phase every
/// frame. dnsr keeps each traced pixel's sample, gives every other pixel the mean of its four traced neighbours and
/// denoises that as a visibility input. 16 B/px more device memory per light than dnsr_get_memory_requirements says.
pub const DNSR_SHADOW_INPUT_CHECKERBOARD: DnsrShadowInput = 2;
/// Forces 32 bits.
pub const DNSR_SHADOW_INPUT_MAX_ENUM: DnsrShadowInput = 0x7FFF_FFFF;

/// Named settings (`dnsr_settings_init_preset`), chosen from the accuracy measurements in docs/accuracy.md.
pub type DnsrPreset = u32;
/// Quality's values with one filter pass: the cheapest setting with Quality's do-no-harm features (runs,
/// converged pixels, hard penumbrae); docs/do-no-harm.md measures both.
pub const DNSR_PRESET_FAST: DnsrPreset = 0;
/// The FidelityFX shadow denoiser's values: its output, for engines that need the old look (3 filter passes, 5%
/// current-frame weight, output contrast 1.2, cross-tap weight 2/3, none of the run-based features).
pub const DNSR_PRESET_BALANCED: DnsrPreset = 1;
/// The default (same as `dnsr_settings_init_default`): the measured best knobs combined. 2 filter passes, 10%
/// current-frame weight, no output contrast, cross-tap weight 0.5, stable history after 8 identical samples,
/// restarted after 3 samples of the other value, converged after 8 identical samples (unfiltered among converged
/// neighbours), a shadow that moved over a still surface clamped to its new samples, with penumbra guidance pixels
/// under a penumbra narrower than a quarter pixel output as sampled.
pub const DNSR_PRESET_QUALITY: DnsrPreset = 2;
/// Forces 32 bits.
pub const DNSR_PRESET_MAX_ENUM: DnsrPreset = 0x7FFF_FFFF;

/// A bit of `FfxDenoiserContextDescription.flags` that dnsr's FidelityFX layer (include/ffx) reads: the context runs
/// the FidelityFX shadow denoiser's settings (DNSR_PRESET_BALANCED, its output) instead of dnsr's default (the
/// Quality preset). The SDK's own denoiser ignores bits it does not know, so an integration may set it and still
/// build against either library.
pub const DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS: u32 = 1 << 30;
/// A bit of `FfxDenoiserContextDescription.flags` that dnsr's FidelityFX layer (include/ffx) reads: the engine gives
/// the context its previous frame's depth and normals before every dispatch (dnsr_ffx_context_set_previous_gbuffer),
/// so that it keeps no depth copy of its own (DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER: 4 B/px less persistent
/// memory, as accurate and no slower). The SDK's own denoiser ignores bits it does not know; an integration that sets
/// it must call dnsr_ffx_context_set_previous_gbuffer, which only dnsr's layer has.
pub const DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER: u32 = 1 << 29;

/// Bit convention of the hit mask.
pub type DnsrHitMaskConvention = u32;
/// FidelityFX SDK: bit = 1 means the shadow ray hit an occluder (classification inverts it as it reads it).
pub const DNSR_HIT_MASK_OCCLUDED_BITS: DnsrHitMaskConvention = 0;
/// bit = 1 means lit. Either convention is read as it is, without a prepare pass.
pub const DNSR_HIT_MASK_LIT_BITS: DnsrHitMaskConvention = 1;
/// Forces 32 bits.
pub const DNSR_HIT_MASK_MAX_ENUM: DnsrHitMaskConvention = 0x7FFF_FFFF;

/// Per-dispatch flags.
pub type DnsrDispatchFlags = u32;
/// Camera cut: discard this light's history before this frame.
pub const DNSR_DISPATCH_RESET: DnsrDispatchFlags = 1 << 0;
/// Denoise only `renderRect` (otherwise the whole render size).
pub const DNSR_DISPATCH_USE_RENDER_RECT: DnsrDispatchFlags = 1 << 1;
/// Penumbra guidance: `hitDistance` and `lightAngularSize` are read.
pub const DNSR_DISPATCH_USE_HIT_DISTANCE: DnsrDispatchFlags = 1 << 2;
/// The light has no size (a point light, or a directional light of angular size 0): every receiver's output is its
/// own ray's result, with or without hit distances, and only the first filter pass runs for it
/// (ShadowsDispatch::hard_light in the Rust API). With DNSR_DISPATCH_USE_HIT_DISTANCE, `lightAngularSize` must be 0.
pub const DNSR_DISPATCH_HARD_LIGHT: DnsrDispatchFlags = 1 << 3;
/// `lightPosition` and `lightAngularSize` are read: receivers turned away from the light keep their shadowed rays'
/// result (ShadowsDispatch::light_position in the Rust API).
pub const DNSR_DISPATCH_USE_LIGHT_POSITION: DnsrDispatchFlags = 1 << 4;
/// Forces 32 bits.
pub const DNSR_DISPATCH_MAX_ENUM: DnsrDispatchFlags = 0x7FFF_FFFF;

/// What the output shows (DebugView in the Rust API).
pub type DnsrDebugView = u32;
/// The denoised shadow.
pub const DNSR_DEBUG_VIEW_NONE: DnsrDebugView = 0;
/// Tile classification: 1 cleared lit, 0 cleared shadowed, 0.5 filtered, 0.75 sky.
pub const DNSR_DEBUG_VIEW_TILE_CLASSIFICATION: DnsrDebugView = 1;
/// Temporal sample count / maxHistorySamples.
pub const DNSR_DEBUG_VIEW_SAMPLE_COUNT: DnsrDebugView = 2;
/// Standard deviation of the filtered estimate, clamped to [0, 1].
pub const DNSR_DEBUG_VIEW_VARIANCE: DnsrDebugView = 3;
/// 1 where the history restarted this frame (disocclusion, reset or rejection), else 0.
pub const DNSR_DEBUG_VIEW_DISOCCLUSION: DnsrDebugView = 4;
/// The current run of identical samples / maxHistorySamples, clamped to [0, 1] (1 in cleared tiles, 0 on sky):
/// where it reaches stableHistorySamples the input is taken to resolve the pixel.
pub const DNSR_DEBUG_VIEW_SAMPLE_RUN: DnsrDebugView = 5;
/// Forces 32 bits.
pub const DNSR_DEBUG_VIEW_MAX_ENUM: DnsrDebugView = 0x7FFF_FFFF;

/// What a GPU allocation is for.
pub type DnsrResourceKind = u32;
/// An internal image.
pub const DNSR_RESOURCE_KIND_IMAGE: DnsrResourceKind = 0;
/// The constants buffer.
pub const DNSR_RESOURCE_KIND_BUFFER: DnsrResourceKind = 1;
/// An internal image whose contents do not outlive one record, with DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY only
/// (otherwise such images come as DNSR_RESOURCE_KIND_IMAGE): its memory may be aliased, as that flag says.
pub const DNSR_RESOURCE_KIND_TRANSIENT_IMAGE: DnsrResourceKind = 2;
/// Forces 32 bits.
pub const DNSR_RESOURCE_KIND_MAX_ENUM: DnsrResourceKind = 0x7FFF_FFFF;

/// Severity of a log message.
pub type DnsrLogLevel = u32;
/// A call failed; the message says why.
pub const DNSR_LOG_LEVEL_ERROR: DnsrLogLevel = 0;
/// Something worth knowing at creation (device, path chosen).
pub const DNSR_LOG_LEVEL_INFO: DnsrLogLevel = 1;
/// Forces 32 bits.
pub const DNSR_LOG_LEVEL_MAX_ENUM: DnsrLogLevel = 0x7FFF_FFFF;

/// Opaque context object (never dereferenced: handles are ids).
pub struct DnsrContext_T {
    _private: [u8; 0],
}
/// A denoiser context. NULL is never a valid context.
pub type DnsrContext = *mut DnsrContext_T;

/// The host's Vulkan loader entry points; dnsr loads every function through them and never links libvulkan.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct DnsrVulkanFunctions {
    /// Required. The host's `vkGetInstanceProcAddr`.
    pub vk_get_instance_proc_addr: PFN_vkGetInstanceProcAddr,
    /// Required. The host's `vkGetDeviceProcAddr`.
    pub vk_get_device_proc_addr: PFN_vkGetDeviceProcAddr,
}

/// Device memory the host's allocator hands to dnsr.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct DnsrGpuAllocation {
    /// Memory to bind the resource to. Must not be VK_NULL_HANDLE.
    pub memory: VkDeviceMemory,
    /// Byte offset within `memory`; a multiple of the requirement's alignment.
    pub offset: VkDeviceSize,
    /// The host's own handle (e.g. a VmaAllocation), given back to `free`.
    pub user_handle: u64,
}

/// Optional: the host's GPU memory allocator (e.g. VMA) creates the memory of dnsr's images and buffers.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct DnsrGpuMemoryCallbacks {
    /// Optional. Passed to both callbacks.
    pub user_data: *mut c_void,
    /// Required. Allocate device-local memory satisfying `*pRequirements`; fill `*pAllocation`; return
    /// VK_SUCCESS or an error. Called during create and resize only.
    pub allocate: Option<
        unsafe extern "C" fn(
            user_data: *mut c_void,
            requirements: *const VkMemoryRequirements,
            kind: DnsrResourceKind,
            allocation: *mut DnsrGpuAllocation,
        ) -> VkResult,
    >,
    /// Required. Free an allocation from `allocate`, after dnsr destroyed the resource bound to it.
    pub free: Option<unsafe extern "C" fn(user_data: *mut c_void, allocation: *const DnsrGpuAllocation)>,
}

/// Optional: receives dnsr's log messages (errors, with the same text as `dnsr_last_error_message`).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct DnsrLogCallback {
    /// Optional. Passed to `log`.
    pub user_data: *mut c_void,
    /// Required. `message` is valid only during the call.
    pub log: Option<unsafe extern "C" fn(user_data: *mut c_void, level: DnsrLogLevel, message: *const c_char)>,
}

/// Optional: receives a name for every Vulkan object dnsr creates (forward it to vkSetDebugUtilsObjectNameEXT).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct DnsrDebugNameCallback {
    /// Optional. Passed to `set_name`.
    pub user_data: *mut c_void,
    /// Required. `name` is valid only during the call.
    pub set_name:
        Option<unsafe extern "C" fn(user_data: *mut c_void, object_type: VkObjectType, handle: u64, name: *const c_char)>,
}

/// Every constant of the algorithm. Initialise with `dnsr_settings_init_default` (the Quality preset) or
/// `dnsr_settings_init_preset` (DNSR_PRESET_BALANCED: the FidelityFX values, given below where they differ). Each
/// field is checked against its range (NaN and infinities are refused) by dnsr_context_create and
/// dnsr_context_set_settings: DNSR_ERROR_INVALID_SETTING names the field, the value and the range.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrSettings {
    /// Must be DNSR_STRUCTURE_TYPE_SETTINGS.
    pub s_type: DnsrStructureType,
    /// Must be NULL (reserved for extensions).
    pub p_next: *const c_void,
    /// Filter passes (a-trous steps 1, 2, 4, 8 px). Range [1, 4]. Default 2 (the Balanced preset: 3).
    pub filter_passes: u32,
    /// Relative depth change counted as disocclusion where the surface faces the camera, |prev - cur| / cur.
    /// Range [0, 10]. Default 0.01.
    pub disocclusion_threshold_facing: f32,
    /// The same at grazing angles. Range [0, 10]. Default 0.1.
    pub disocclusion_threshold_grazing: f32,
    /// Exponent of (1 - N.V) blending the two thresholds. Range [0, 64]. Default 8.
    pub disocclusion_angle_exponent: f32,
    /// Local-moment Gaussian falloff: w(i) = exp(-falloff i^2 / 81). Range [0, 100]. Default 3.
    pub spatial_falloff: f32,
    /// History clamp half-width in local standard deviations. Range [0, 16]. Default 0.5.
    pub history_clamp_sigmas: f32,
    /// Sample count multiplied by exp(-d^2 / falloff) for a history d clamp widths away. Range [1e-3, 1e6].
    /// Default 20.
    pub history_rejection_falloff: f32,
    /// Floor of the clamp width in the rejection distance. Range [1e-6, 1]. Default 0.001.
    pub history_rejection_min_sigma: f32,
    /// Variance boost below this many samples (not on pixels whose run is stable). Range [0, 1024]. Default 16.
    pub variance_boost_samples: f32,
    /// Sample count of full history trust. Range [1, 1024]. Default 8.
    pub full_history_samples: f32,
    /// Current-frame weight with full history trust. Range [1e-3, 1]. Default 0.1 (FidelityFX 0.05).
    pub min_current_weight: f32,
    /// Bound on the temporal sample count. Range [2, 128]. Default 32.
    pub max_history_samples: f32,
    /// Cross-tap weight of the 3x3 kernel (corners get its square). Range [0, 1]. Default 0.5 (FidelityFX 2/3).
    pub kernel_cross_weight: f32,
    /// Normal edge-stop exponent. Range [0, 256]. Default 32.
    pub normal_power: f32,
    /// Output pow(mean, max(contrast - variance, 1)). Range [1, 4]; 1 disables. Default 1 (FidelityFX 1.2).
    pub output_contrast: f32,
    /// Floor of the shadow edge-stop sigma. Range [1e-6, 1]. Default 1e-4.
    pub min_shadow_sigma: f32,
    /// A pixel whose last n >= this-many samples were identical is clamped to within 3/n of them instead of to the
    /// local distribution (hard shadow edges the input resolves stay sharp). Range [0, 127]; 0 disables (the
    /// FidelityFX behaviour). Default 8 (FidelityFX 0).
    pub stable_history_samples: f32,
    /// After a stable run, this many samples of the other value in a row (or the first, where the local mean is
    /// within 0.5 of it) restart the pixel's history at the local mean (a shadow moved over it). Range [0, 16];
    /// 0 disables; needs stableHistorySamples > 0. Default 3 (FidelityFX 0).
    pub history_flip_samples: f32,
    /// A stable pixel whose last n >= this-many samples were identical (each exactly 0 or 1), with no other sample
    /// in its history, is converged; where at least half of its 3x3 receivers are converged too, the filter passes
    /// it through as its run's value (its 1-spp input resolves it: hard shadows, faces turned from the light,
    /// creases, thin stripes); not where movingShadowSigmas finds that the shadow moved over a still pixel (a
    /// short run there is as often a penumbra's). Under a moving camera, a receiver beside the sky whose neighbours
    /// of last frame held the other value for this many samples or more, and two of whose 8 neighbours share its
    /// sample, takes its sample as it is (a resolved silhouette; this part needs no stable history). Range [0, 127]; 0
    /// disables; converged pixels need stableHistorySamples > 0. Default 8 (FidelityFX 0).
    pub converged_samples: f32,
    /// With penumbra guidance (DNSR_DISPATCH_USE_HIT_DISTANCE) only: where the blockers near a tile cast a penumbra
    /// narrower than this many pixels either side of its edge and lie at least two pixel footprints away, a
    /// receiver's output is its sample of this frame, neither accumulated nor filtered (one ray resolves it: a
    /// hard light; where the estimate errs, the output is the input). Range [0, 16]; 0 disables (the FidelityFX
    /// behaviour). Default 0.25 (FidelityFX 0).
    pub hard_penumbra_pixels: f32,
    /// A shadow that moved over a still surface (an occluder moving without motion vectors on the receiver): where
    /// a pixel's motion vector is under 0.01 px and this frame's samples around its 8x4 tile (24x20 px) lie more
    /// than this many standard deviations (plus two samples) from last frame's accumulated means, its history is
    /// clamped to movingHistoryClampSigmas instead of historyClampSigmas. 3 takes a moving occluder's error to
    /// about two thirds for 0.07 ms more at 4K on an H200 (docs/do-no-harm.md); 0 in DNSR_PRESET_BALANCED. Needs
    /// stableHistorySamples or convergedSamples > 0.
    /// Range [0, 16]; 0 disables (the pipelines compile it out). Default 3 (FidelityFX 0).
    pub moving_shadow_sigmas: f32,
    /// The history clamp's width in local standard deviations where the shadow moved (movingShadowSigmas).
    /// Range [0, 16]. Default 0.1.
    pub moving_history_clamp_sigmas: f32,
    /// Without penumbra guidance: each 8x4 tile counts the frames since one of its receivers' samples contradicted
    /// last frame's (a world point in a penumbra changes its value at random, one in a hard shadow keeps it); where
    /// the 3x3 tiles around a receiver's tile all counted this many frames, a receiver that does not contradict
    /// (disoccluded or not) outputs its sample (hard and nearly hard shadows under a moving camera stay exact; where a
    /// penumbra shows no contradiction the output is the input, never worse). Needs stableHistorySamples or
    /// convergedSamples > 0. Range [0, 255]; 0 disables (the FidelityFX behaviour). Default 6 (FidelityFX 0).
    pub hard_tile_frames: f32,
    /// The first filter pass weighs its taps by each receiver's geometric normal (the plane through its nearer
    /// neighbour along each axis, from the depth and DnsrShadowsDispatch::viewProjectionInverse) where it lies within
    /// this many degrees of your normal: a normal map's tilt would otherwise stop the normal edge stop on one plane.
    /// Past it (a feature of 1-2 px, a crease), and where an axis has no receiver neighbour, your normal stays.
    /// Needs stableHistorySamples or convergedSamples > 0. Range [0, 89]; 0 disables (the FidelityFX behaviour).
    /// Default 53 (FidelityFX 0).
    pub geometric_normal_degrees: f32,
}

/// Everything needed to create a context. Read during `dnsr_context_create` only (callback structs are copied;
/// the function pointers and user data they hold must stay valid until the context is destroyed).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct DnsrContextCreateInfo {
    /// Must be DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO.
    pub s_type: DnsrStructureType,
    /// Must be NULL (reserved for extensions).
    pub p_next: *const c_void,
    /// Required. The host's instance; must outlive the context.
    pub instance: VkInstance,
    /// Required. The physical device of `device`.
    pub physical_device: VkPhysicalDevice,
    /// Required. The host's device; must outlive the context.
    pub device: VkDevice,
    /// Required. Loader entry points.
    pub vulkan_functions: DnsrVulkanFunctions,
    /// The Vulkan version dnsr may use: the apiVersion the host created its instance with, or the device's
    /// version if that is lower (VK_MAKE_API_VERSION, variant 0). At least 1.1 and at most the device's
    /// major.minor (patch ignored); anything else is DNSR_ERROR_UNSUPPORTED_API_VERSION.
    pub api_version: u32,
    /// Queue family of the command buffers dnsr records into. Must exist and support compute
    /// (DNSR_ERROR_INVALID_QUEUE_FAMILY); timestamp support and the stages `DnsrShadowsDispatch::sync` may name
    /// are checked against it.
    pub queue_family_index: u32,
    /// DNSR_FEATURE_* bits the host enabled on `device`. 0 is valid.
    pub enabled_features: DnsrFeatureFlags,
    /// Render width in pixels, 1..maxImageDimension2D.
    pub width: u32,
    /// Render height in pixels, 1..maxImageDimension2D.
    pub height: u32,
    /// DNSR_CONTEXT_CREATE_* bits. 0 = standard depth, finite far plane, no timestamps.
    pub flags: DnsrContextCreateFlags,
    /// DNSR_PRECISION_FP32 (default) or DNSR_PRECISION_FP16.
    pub precision: DnsrPrecision,
    /// Output image format: VK_FORMAT_R8_UNORM, VK_FORMAT_R16_SFLOAT or VK_FORMAT_R32_SFLOAT, or a 4-channel
    /// VK_FORMAT_R8G8B8A8_UNORM / VK_FORMAT_R16G16B16A16_SFLOAT (the shadow in every channel, as FidelityFX's sample
    /// output). The device must support storage images of it.
    pub output_format: VkFormat,
    /// Number of lights with independent histories, 1..DNSR_MAX_LIGHT_COUNT (64). Device memory grows linearly
    /// with it (see dnsr_get_memory_requirements); a context that would not fit in the device's memory is refused
    /// with DNSR_ERROR_OUT_OF_DEVICE_MEMORY before anything is allocated.
    pub light_count: u32,
    /// How many recorded frames of one light may be in flight on the GPU at once, 1..DNSR_MAX_FRAMES_IN_FLIGHT
    /// (16); 0 = DNSR_DEFAULT_MAX_FRAMES_IN_FLIGHT (3). Contract: the command buffer holding frame N of a light
    /// must have completed before frame N + maxFramesInFlight of that light is recorded. Without push
    /// descriptors dnsr rewrites one of this many descriptor-set slots per light on every record, so it never
    /// holds a host image view past that frame.
    pub max_frames_in_flight: u32,
    /// Optional (NULL = dnsr_settings_init_default's: the Quality preset). Initial settings.
    pub p_settings: *const DnsrSettings,
    /// Optional. CPU allocation callbacks for every Vulkan object dnsr creates; must outlive the context.
    pub p_allocation_callbacks: *const VkAllocationCallbacks,
    /// Optional (NULL = dnsr calls vkAllocateMemory). The host's GPU memory allocator.
    pub p_gpu_memory_callbacks: *const DnsrGpuMemoryCallbacks,
    /// Optional. Log messages.
    pub p_log_callback: *const DnsrLogCallback,
    /// Optional. Debug names of dnsr's Vulkan objects.
    pub p_debug_name_callback: *const DnsrDebugNameCallback,
    /// Number of entries in pShaderOverrides (0: dnsr's embedded SPIR-V for every pass).
    pub shader_override_count: u32,
    /// Optional (with shaderOverrideCount 0). Pass variants the engine compiled against its own callbacks file
    /// (docs/callbacks.md; dnsr_get_shader_variants lists the variants, their entry files and definitions). Read
    /// during dnsr_context_create only. Each is checked against the interface dnsr relies on; a mismatch is
    /// DNSR_ERROR_SHADER_INTERFACE naming the variant and what differs, and nothing is created. With overrides of
    /// every classification and filter variant the context runs (docs/callbacks.md), the dispatch's depth,
    /// velocity, normals and hit distances may have any format the device can sample (the engine's callbacks
    /// decode them); otherwise they must be in dnsr's formats, which its own decode reads.
    pub p_shader_overrides: *const DnsrShaderOverride,
    /// DNSR_SHADOW_INPUT_HIT_MASK (0, default), DNSR_SHADOW_INPUT_VISIBILITY or DNSR_SHADOW_INPUT_CHECKERBOARD:
    /// which of hitMask / visibility every dispatch of this context passes, and how many of the pixels it traced.
    pub shadow_input: DnsrShadowInput,
}

/// Largest `DnsrShaderOverride::codeSize` accepted, in bytes (dnsr's own modules are under 100 KiB): a larger one is
/// refused with DNSR_ERROR_INVALID_ARGUMENT before anything is read.
pub const DNSR_MAX_SHADER_OVERRIDE_CODE_SIZE: usize = 16 << 20;
/// Longest `DnsrShaderOverride::pVariantName` accepted, in bytes without the terminator (dnsr's names are under 40):
/// a longer one is refused with DNSR_ERROR_INVALID_ARGUMENT, and no more of it is read or echoed.
pub const DNSR_MAX_SHADER_VARIANT_NAME_LENGTH: usize = 255;

/// One pass variant's SPIR-V, compiled by the engine.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrShaderOverride {
    /// Required. The variant it replaces, e.g. "tile_classification_r16f" (NUL-terminated, at most
    /// DNSR_MAX_SHADER_VARIANT_NAME_LENGTH bytes before the terminator).
    pub p_variant_name: *const c_char,
    /// Required. The SPIR-V module (SPIR-V 1.3: glslc --target-env=vulkan1.1). Before anything else reads it, it
    /// must pass Khronos's validator (SPIRV-Tools, compiled into dnsr) for Vulkan 1.1, have an id bound no larger
    /// than its word count, and ask only for the capabilities, extensions and instruction sets docs/callbacks.md
    /// lists; otherwise DNSR_ERROR_SHADER_INTERFACE with the validator's message. Malformed SPIR-V never reaches
    /// the driver.
    pub p_code: *const u32,
    /// Size of pCode in bytes (a multiple of 4, at most DNSR_MAX_SHADER_OVERRIDE_CODE_SIZE).
    pub code_size: usize,
}

/// A pass variant an engine may compile (dnsr_get_shader_variants). The strings are static.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrShaderVariantInfo {
    /// The name a DnsrShaderOverride gives.
    pub p_name: *const c_char,
    /// Its entry file under dnsr's shader sources (installed in share/dnsr/shaders).
    pub p_source: *const c_char,
    /// Its preprocessor definitions, space-separated, each passed to glslc as -D<definition>.
    pub p_defines: *const c_char,
}

/// One of the host's images, as used by one dispatch.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct DnsrHostImage {
    /// Required. The image (used for the output's layout transitions and for validation).
    pub image: VkImage,
    /// Required. A 2D view of mip 0, layer 0 (depth aspect only for depth/stencil formats).
    pub view: VkImageView,
    /// The view's format.
    pub format: VkFormat,
    /// The layout the image is in when the commands execute; it is left in this layout.
    pub layout: VkImageLayout,
    /// Width of mip 0 in pixels.
    pub width: u32,
    /// Height of mip 0 in pixels.
    pub height: u32,
}

/// A pixel rectangle.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct DnsrRect {
    /// Left edge, a multiple of 8.
    pub x: u32,
    /// Top edge, a multiple of 4.
    pub y: u32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

/// Barriers dnsr emits for the host around its work. All zero = the host emits them itself. Synchronization-1
/// bits only: Vulkan 1.0 stages (plus VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR where the device supports
/// ray-tracing pipelines) that the device and the context's queue family support, and access bits that one of
/// the given stages performs (Vulkan's "supported access types" table; MEMORY_READ/WRITE with any stage but
/// TOP/BOTTOM_OF_PIPE). Anything else is DNSR_ERROR_INVALID_HOST_SYNC and nothing is recorded. Name only
/// stages whose features you enabled (dnsr can check support, not enablement).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct DnsrHostSync {
    /// Stages that wrote the input images.
    pub input_src_stages: VkPipelineStageFlags,
    /// Accesses that wrote the input images.
    pub input_src_access: VkAccessFlags,
    /// Stages that will use the output.
    pub output_dst_stages: VkPipelineStageFlags,
    /// Accesses that will use the output.
    pub output_dst_access: VkAccessFlags,
}

/// One frame of one light: the FidelityFX dispatch description plus dnsr's additions. Matrices are column-major
/// float[16] mapping column vectors; clip space is Vulkan's (uv (0,0) top-left = NDC (-1,-1), depth 0..1).
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrShadowsDispatch {
    /// Must be DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH.
    pub s_type: DnsrStructureType,
    /// Must be NULL (reserved for extensions).
    pub p_next: *const c_void,
    /// Required. The command buffer the host is recording (outside a render pass).
    pub command_buffer: VkCommandBuffer,
    /// Which light's history, below the context's light count.
    pub light_index: u32,
    /// DNSR_DISPATCH_* bits.
    pub flags: DnsrDispatchFlags,
    /// DNSR_HIT_MASK_OCCLUDED_BITS (FidelityFX) or DNSR_HIT_MASK_LIT_BITS.
    pub hit_mask_convention: DnsrHitMaskConvention,
    /// Required. VK_FORMAT_R32_UINT, ceil(W/8) x ceil(H/4); bit (y%4)*8 + (x%8) of texel (x/8, y/4).
    /// Sampled; layout GENERAL, SHADER_READ_ONLY_OPTIMAL or READ_ONLY_OPTIMAL.
    pub hit_mask: DnsrHostImage,
    /// Required. W x H depth: D32_SFLOAT, D16_UNORM, X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT,
    /// D32_SFLOAT_S8_UINT, D16_UNORM_S8_UINT (depth-aspect view), R32_SFLOAT, R16_SFLOAT or R16_UNORM. Receivers
    /// have 0 < depth < 1. Layout GENERAL, SHADER_READ_ONLY_OPTIMAL, READ_ONLY_OPTIMAL,
    /// DEPTH_STENCIL_READ_ONLY_OPTIMAL, DEPTH_READ_ONLY_OPTIMAL or DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL.
    /// The history is kept where the linear (view-space) depth that projectionInverse gives lies within 2^-16 to
    /// 2^48 view units (any scene scale): dnsr keeps last frame's depth in that range, and a receiver outside it
    /// starts afresh every frame.
    pub depth: DnsrHostImage,
    /// Required. W x H motion vectors, first two channels used: R16G16_SFLOAT, R32G32_SFLOAT, R16G16_SNORM,
    /// R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT. prev_uv = uv + value.xy * motionVectorScale. Sampled layouts
    /// as for the hit mask.
    pub velocity: DnsrHostImage,
    /// Required. W x H world-space normals, rgb * normalsUnpackMul + normalsUnpackAdd: R8G8B8A8_UNORM/SNORM,
    /// B8G8R8A8_UNORM, A2B10G10R10/A2R10G10B10_UNORM_PACK32, B10G11R11_UFLOAT_PACK32, R16G16B16A16_SFLOAT/UNORM/
    /// SNORM or R32G32B32A32_SFLOAT. Sampled layouts as for the hit mask.
    pub normals: DnsrHostImage,
    /// Required. W x H output (1 = lit) in the context's output format, written as a storage image. Layout
    /// GENERAL, or SHADER_READ_ONLY_OPTIMAL / READ_ONLY_OPTIMAL / TRANSFER_SRC_OPTIMAL (moved to GENERAL and back).
    pub output: DnsrHostImage,
    /// Motion vector multiplier (FidelityFX motionVectorScale).
    pub motion_vector_scale: [f32; 2],
    /// Normal decode multiplier (2 for UNORM normals).
    pub normals_unpack_mul: f32,
    /// Normal decode offset (-1 for UNORM normals).
    pub normals_unpack_add: f32,
    /// Camera position in the space `viewProjectionInverse` maps to.
    pub eye: [f32; 3],
    /// Frame counter; informational only.
    pub frame_index: u32,
    /// Current clip -> view space.
    pub projection_inverse: [f32; 16],
    /// Current clip -> previous clip.
    pub reprojection_matrix: [f32; 16],
    /// Current clip -> world. Classification takes receivers' world positions from it (their view direction and
    /// their side of the light), and the first filter pass their geometric normals (from neighbouring depths).
    pub view_projection_inverse: [f32; 16],
    /// Depth edge stop of the filter: a tap's weight is multiplied by exp(-|z_center - z_tap| / sigma), z the
    /// linear view-space depth from projectionInverse, in your view-space units (metres if your world is in
    /// metres). Smaller keeps contact shadows sharper across depth steps; larger blurs across them. Finite and
    /// > 0 (NaN/Inf: DNSR_ERROR_NON_FINITE; <= 0: DNSR_ERROR_INVALID_ARGUMENT). FidelityFX default 1.
    pub depth_similarity_sigma: f32,
    /// Region to denoise when DNSR_DISPATCH_USE_RENDER_RECT is set.
    pub render_rect: DnsrRect,
    /// Optional barriers on the host's behalf.
    pub sync: DnsrHostSync,
    /// DNSR_DEBUG_VIEW_NONE (0, the shadow) or a debug view of dnsr's internal state written to the output.
    pub debug_view: DnsrDebugView,
    /// Read when DNSR_DISPATCH_USE_HIT_DISTANCE is set (penumbra guidance). W x H, R16_SFLOAT or R32_SFLOAT: per
    /// pixel, the distance along the shadow ray from the receiver to the first occluder it hit, in view-space
    /// units (those projectionInverse maps depth to). Read only where the hit mask says the ray hit; a value
    /// there that is not finite and > 0 counts as unknown, so a tracer may write anything (0, say) on a miss.
    /// The filter narrows its kernel to the penumbra width the blockers imply: contact shadows stay sharp, wide
    /// penumbrae are filtered as without guidance, and under penumbrae narrower than
    /// DnsrSettings::hardPenumbraPixels the output is the ray's own result, as it is where no pixel within +-8 px
    /// of a tile has a known distance (its shadowed pixels face away from the light): write every hit's distance.
    /// Sampled layouts as for the hit mask.
    pub hit_distance: DnsrHostImage,
    /// Read when DNSR_DISPATCH_USE_HIT_DISTANCE or DNSR_DISPATCH_USE_LIGHT_POSITION is set. The light's angular
    /// diameter seen from the receivers, in radians, in [0, pi) (the sun: about 0.0093; a sphere light of radius r at
    /// distance D: 2 asin(r / D)); 0 is a point light (with hit distances: hard shadows, no spatial filtering; with
    /// the light's position: a receiver turned away from its centre sees none of it). NaN/Inf:
    /// DNSR_ERROR_NON_FINITE; out of range: DNSR_ERROR_INVALID_ARGUMENT.
    pub light_angular_size: f32,
    /// Number of entries in pEngineImages (0 without engine-compiled shader variants).
    pub engine_image_count: u32,
    /// Optional (with engineImageCount 0). The engine's own images its shader variants (pShaderOverrides) declare
    /// at bindings DNSR_ENGINE_BINDING_BASE.. of set 0; each such binding of this frame's passes must be given.
    /// Views are borrowed for the frame, like the other images.
    pub p_engine_images: *const DnsrEngineImage,
    /// Required with DNSR_SHADOW_INPUT_VISIBILITY, all zero otherwise (and hitMask all zero with it). W x H, per
    /// pixel the fraction of its shadow rays that reached the light (1 lit, 0 shadowed): VK_FORMAT_R8_UNORM,
    /// R16_UNORM, R16_SFLOAT or R32_SFLOAT, sampled layouts as for the hit mask. Values are clamped to [0, 1] and
    /// NaN reads as 0. With k rays per pixel store hits / k (R8_UNORM stores 1/2, 1/4 ... only approximately,
    /// which is harmless: only exact 0 and 1 are treated specially). hitMaskConvention is ignored.
    pub visibility: DnsrHostImage,
    /// DNSR_SHADOW_INPUT_CHECKERBOARD: this frame's rays were traced for the pixels with (x + y) % 2 ==
    /// checkerboardPhase (x, y in image pixels), 0 or 1; alternate it every frame. 0 for the other inputs.
    pub checkerboard_phase: u32,
    /// Read when DNSR_DISPATCH_USE_LIGHT_POSITION is set. Where the light is, in world space (the space
    /// viewProjectionInverse maps to), as a homogeneous point: {x, y, z, 0} the direction toward a directional
    /// light (any non-zero length), {x, y, z, 1} a point or sphere light's centre. With it, a receiver whose
    /// normal faces away from the light (N.L < 0, the normals as decoded) and whose ray hit keeps that result as
    /// its output: it cannot see the light, and the history and the filter would only blend it with the lit face
    /// beside it (a pole's or a sphere's dark side against the sky, the far face of a fin). A ray that reached the
    /// light is filtered as any other (a normal-mapped face may see it); so is one that hit where a normal map tilts
    /// the normal past the light inside a plane that faces it, in a 16x16 group where such a receiver's ray reached
    /// the light (the rays do not test the mapped normals, so the hit is a penumbra's). Where the normal is turned
    /// away from the whole light (N.L below -sin(lightAngularSize / 2): give the light's size, or a large light's
    /// penumbrae on faces turned just past its centre are lost), that output is final: no filter pass blends it
    /// with its neighbours or them with it, so a shadowed dot a pixel wide (a bump turned away, where the rays test
    /// the mapped normals) stays one. Fast and Quality only (Balanced keeps the FidelityFX behaviour). NaN/Inf: DNSR_ERROR_NON_FINITE; w other than 0 or 1, or a direction of length 0:
    /// DNSR_ERROR_INVALID_ARGUMENT.
    pub light_position: [f32; 4],
    /// Required with DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER, all zero otherwise: the image the host gave as depth
    /// last frame (its previous depth buffer, which engines keep for temporal anti-aliasing), in one of depth's
    /// formats and layouts, W x H. Linearised with this frame's projectionInverse; not read after a reset.
    pub previous_depth: DnsrHostImage,
    /// Required with DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER, all zero otherwise: last frame's normals, in one of
    /// normals' formats, W x H, decoded with this frame's normalsUnpackMul and normalsUnpackAdd.
    pub previous_normals: DnsrHostImage,
}

/// Per-light flags of `DnsrLightDispatch`.
pub type DnsrLightDispatchFlags = u32;
/// Discard this light's history before this frame (the other lights of the call keep theirs).
pub const DNSR_LIGHT_DISPATCH_RESET: DnsrLightDispatchFlags = 1 << 0;
/// Penumbra guidance for this light: `hitDistance` and `lightAngularSize` are read.
pub const DNSR_LIGHT_DISPATCH_USE_HIT_DISTANCE: DnsrLightDispatchFlags = 1 << 1;
/// This light has no size, as DNSR_DISPATCH_HARD_LIGHT.
pub const DNSR_LIGHT_DISPATCH_HARD_LIGHT: DnsrLightDispatchFlags = 1 << 2;
/// `lightPosition` is read for this light, as DNSR_DISPATCH_USE_LIGHT_POSITION.
pub const DNSR_LIGHT_DISPATCH_USE_LIGHT_POSITION: DnsrLightDispatchFlags = 1 << 3;
/// Forces 32 bits.
pub const DNSR_LIGHT_DISPATCH_MAX_ENUM: DnsrLightDispatchFlags = 0x7FFF_FFFF;

/// Most lights one `dnsr_lights_record` call denoises.
pub const DNSR_MAX_LIGHTS_PER_RECORD: u32 = 8;
const _: () = assert!(DNSR_MAX_LIGHTS_PER_RECORD as usize == crate::MAX_LIGHTS_PER_RECORD);

/// What differs from light to light in `dnsr_lights_record`; each field as its namesake in
/// `DnsrShadowsDispatch`, which there holds what the lights share.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrLightDispatch {
    /// Must be DNSR_STRUCTURE_TYPE_LIGHT_DISPATCH.
    pub s_type: DnsrStructureType,
    /// Must be NULL (reserved for extensions).
    pub p_next: *const c_void,
    /// Which light's history, below the context's light count; each light at most once per call.
    pub light_index: u32,
    /// DNSR_LIGHT_DISPATCH_* bits.
    pub flags: DnsrLightDispatchFlags,
    /// This light's hit mask (required with DNSR_SHADOW_INPUT_HIT_MASK, all zero otherwise). Its bit convention
    /// is the shared dispatch's hitMaskConvention.
    pub hit_mask: DnsrHostImage,
    /// This light's visibility (required with DNSR_SHADOW_INPUT_VISIBILITY, all zero otherwise).
    pub visibility: DnsrHostImage,
    /// Required. This light's output; every light of the call writes its own image.
    pub output: DnsrHostImage,
    /// Read with DNSR_LIGHT_DISPATCH_USE_HIT_DISTANCE: this light's hit distances.
    pub hit_distance: DnsrHostImage,
    /// Read with DNSR_LIGHT_DISPATCH_USE_HIT_DISTANCE or DNSR_LIGHT_DISPATCH_USE_LIGHT_POSITION: this light's angular
    /// diameter in radians, in [0, pi).
    pub light_angular_size: f32,
    /// Read with DNSR_LIGHT_DISPATCH_USE_LIGHT_POSITION: where this light is, as DnsrShadowsDispatch::lightPosition.
    pub light_position: [f32; 4],
}

/// First binding number of an engine's own images in dnsr's set 0 (see DnsrShadowsDispatch::pEngineImages).
pub const DNSR_ENGINE_BINDING_BASE: u32 = 32;
/// How many engine images one dispatch can bind.
pub const DNSR_MAX_ENGINE_IMAGES: u32 = 8;
const _: () = assert!(DNSR_ENGINE_BINDING_BASE == crate::ENGINE_BINDING_BASE && DNSR_MAX_ENGINE_IMAGES as usize == crate::MAX_ENGINE_IMAGES);

/// One of the engine's images, bound for its own shader variants.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct DnsrEngineImage {
    /// The binding its shader declares, DNSR_ENGINE_BINDING_BASE .. DNSR_ENGINE_BINDING_BASE + 7.
    pub binding: u32,
    /// Required. A 2D view, as the shader declares it (sampled texture2D or storage image2D).
    pub view: VkImageView,
    /// Its layout while the commands execute: GENERAL, SHADER_READ_ONLY_OPTIMAL or READ_ONLY_OPTIMAL when sampled,
    /// GENERAL for a storage image.
    pub layout: VkImageLayout,
}

/// GPU time of each pass of one completed frame, in milliseconds.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrPassTimings {
    /// Must be DNSR_STRUCTURE_TYPE_PASS_TIMINGS (set it before the call).
    pub s_type: DnsrStructureType,
    /// Must be NULL.
    pub p_next: *mut c_void,
    /// Which recorded frame (counting record calls from 1).
    pub frame: u64,
    /// prepare: visibility and checkerboard inputs only (otherwise the empty interval between its two timestamps).
    pub prepare_ms: f64,
    /// tile classification.
    pub tile_classification_ms: f64,
    /// Each filter pass; entries beyond `filterPasses` are 0.
    pub filter_ms: [f64; 4],
    /// Filter passes that ran.
    pub filter_passes: u32,
    /// From before the first pass to after the last.
    pub total_ms: f64,
}

/// GPU time of one completed hybrid-shadows classifier dispatch (`dnsr_classify_record`), in milliseconds.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrClassifierTimings {
    /// Must be DNSR_STRUCTURE_TYPE_CLASSIFIER_TIMINGS (set it before the call).
    pub s_type: DnsrStructureType,
    /// Must be NULL.
    pub p_next: *mut c_void,
    /// Which classifier dispatch (counting dnsr_classify_record calls from 1).
    pub dispatch: u64,
    /// From before the classifier's first command (its counters' reset) to after its dispatch.
    pub classify_ms: f64,
}

/// What the host must create its instance and device with.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrDeviceRequirements {
    /// Must be DNSR_STRUCTURE_TYPE_DEVICE_REQUIREMENTS (set it before the call).
    pub s_type: DnsrStructureType,
    /// Must be NULL.
    pub p_next: *mut c_void,
    /// Lowest apiVersion dnsr works with.
    pub min_api_version: u32,
    /// Device extensions dnsr requires (none today).
    pub required_extension_count: u32,
    /// Their names (static storage).
    pub pp_required_extension_names: *const *const c_char,
    /// Device extensions dnsr uses when enabled (declare them in `enabledFeatures`).
    pub optional_extension_count: u32,
    /// Their names (static storage): "VK_KHR_push_descriptor" (-> DNSR_FEATURE_PUSH_DESCRIPTOR). FLOAT16 needs
    /// no extension on Vulkan 1.2+ (VK_KHR_shader_float16_int8 + VK_KHR_16bit_storage before).
    pub pp_optional_extension_names: *const *const c_char,
    /// DNSR_FEATURE_* bits dnsr can use: FLOAT16 = shaderFloat16 + storageBuffer16BitAccess (for
    /// DNSR_PRECISION_FP16) and PUSH_DESCRIPTOR.
    pub optional_features: DnsrFeatureFlags,
}

/// Flags of `DnsrClassifyDispatch`.
pub type DnsrClassifyFlags = u32;
/// Pixels no blocker-search tap finds a blocker for are decided lit (recommended). Without it only shadowed
/// pixels are decided and every other receiver is traced.
pub const DNSR_CLASSIFY_REJECT_LIT_PIXELS: DnsrClassifyFlags = 1 << 0;
/// A listed tile's ray interval is bounded by the blockers its pixels' taps found (recommended); without it,
/// from 0 (the receiver: the engine's own ray offset keeps its rays off their surface) to infinity.
pub const DNSR_CLASSIFY_BOUND_RAY_INTERVAL: DnsrClassifyFlags = 1 << 1;
/// The shadow maps hold 1 at the light's near plane and 0 at its far plane (reverse-Z cascades).
pub const DNSR_CLASSIFY_CASCADES_DEPTH_INVERTED: DnsrClassifyFlags = 1 << 2;
/// Classify only `renderRect`.
pub const DNSR_CLASSIFY_USE_RENDER_RECT: DnsrClassifyFlags = 1 << 3;
/// The cascades are the layers of `cascadeArray` (a 2D-array view) instead of `pCascadeImages`' images.
pub const DNSR_CLASSIFY_CASCADE_ARRAY: DnsrClassifyFlags = 1 << 4;
/// Forces 32 bits.
pub const DNSR_CLASSIFY_MAX_ENUM: DnsrClassifyFlags = 0x7FFF_FFFF;

/// Most shadow-map cascades one classify dispatch reads.
pub const DNSR_MAX_CASCADES: u32 = 4;
const _: () = assert!(DNSR_MAX_CASCADES as usize == crate::MAX_CASCADES);
/// Bytes of one record of the classifier's tile list: uint32 x (tile x | tile y << 16), mask of the tile's
/// pixels to trace (bit (y % 4) * 8 + (x % 8)), minT and maxT (float bits, world units). minT is 0 (kept for the
/// FidelityFX record layout): rays start at their receiver, since blockers nearer than the blocker offset or
/// between the blocker-search taps are invisible to the cascades.
pub const DNSR_CLASSIFY_TILE_BYTES: u32 = 16;
/// Bytes of the classifier's counts: uint32 words 0..3 VkDispatchIndirectCommand (tiles, 1, 1) and the tile count;
/// words 4..7 (32 x tiles, 1, 1, 0), one invocation per pixel of every listed tile.
pub const DNSR_CLASSIFY_COUNTS_BYTES: u32 = 32;

/// One frame of the hybrid-shadows classifier (`dnsr_classify_record`): from the engine's cascaded shadow maps it
/// prefills the hit mask with the pixels they decide (surely lit, surely shadowed, facing away from the light)
/// and lists the 8x4 tiles whose other pixels need a shadow ray. Then the engine traces the listed pixels (ORing
/// its bit into the mask: occluded with DNSR_HIT_MASK_OCCLUDED_BITS, lit with DNSR_HIT_MASK_LIT_BITS; they are
/// prefilled 0) and records the denoiser with that mask. Conventions as `DnsrShadowsDispatch`.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrClassifyDispatch {
    /// Must be DNSR_STRUCTURE_TYPE_CLASSIFY_DISPATCH.
    pub s_type: DnsrStructureType,
    /// Must be NULL (reserved for extensions).
    pub p_next: *const c_void,
    /// Required. The command buffer the host is recording (outside a render pass).
    pub command_buffer: VkCommandBuffer,
    /// DNSR_CLASSIFY_* bits (DNSR_CLASSIFY_REJECT_LIT_PIXELS | DNSR_CLASSIFY_BOUND_RAY_INTERVAL recommended).
    pub flags: DnsrClassifyFlags,
    /// The convention of the engine's trace and of the denoiser's dispatch (DnsrShadowsDispatch).
    pub hit_mask_convention: DnsrHitMaskConvention,
    /// Required. The hit mask the classifier prefills: VK_FORMAT_R32_UINT, ceil(W/8) x ceil(H/4), created with
    /// STORAGE usage, layout GENERAL; the same image the engine's trace completes and the denoiser reads.
    pub hit_mask: DnsrHostImage,
    /// Required. W x H depth in the context's convention (formats and layouts as DnsrShadowsDispatch::depth).
    pub depth: DnsrHostImage,
    /// Required. W x H world-space normals (formats as DnsrShadowsDispatch::normals): a pixel facing away from the
    /// light is shadowed without a ray; an unusable (zero) normal leaves the decision to the cascades.
    pub normals: DnsrHostImage,
    /// Normal decode multiplier (2 for UNORM normals).
    pub normals_unpack_mul: f32,
    /// Normal decode offset (-1 for UNORM normals).
    pub normals_unpack_add: f32,
    /// Current clip -> world (the space the cascades' matrices take).
    pub view_projection_inverse: [f32; 16],
    /// Optional (zero if unused). Current clip -> view (as DnsrShadowsDispatch::projection_inverse). dnsr's own
    /// classifier does not read it; an engine's classifier variant (pShaderOverrides) whose callbacks decode depth
    /// with dnsr_get_projection_inverse() does. Must be finite.
    pub projection_inverse: [f32; 16],
    /// World-space direction from the surfaces toward the light (the sun); any non-zero length.
    pub light_direction: [f32; 3],
    /// The light's angular diameter in radians, in [0, pi) (the sun: about 0.0093): the blocker search radius
    /// is the widest penumbra a blocker between the receiver and the cascade's near plane can cast.
    pub light_angular_size: f32,
    /// Cascades used, 1..DNSR_MAX_CASCADES (0: DNSR_ERROR_INVALID_ARGUMENT). The first one containing a pixel
    /// decides it; a pixel in none is traced.
    pub cascade_count: u32,
    /// Per cascade (finest first) a column-major float[16]: world position (w = 1) to (u, v, depth) of its
    /// shadow map, u, v in [0, 1] across the image (0, 0 the top-left texel corner), depth as stored. Affine
    /// (last row 0 0 0 1; orthographic sun cascades). A "shadow matrix plus per-cascade scale and offset"
    /// setup (FidelityFX) passes translate(offset) * scale(scale) * shadowMatrix. NaN/Inf: DNSR_ERROR_NON_FINITE.
    pub cascade_world_to_shadow: [[f32; 16]; 4],
    /// Without DNSR_CLASSIFY_CASCADE_ARRAY: cascade i's shadow map (a 2D depth-aspect view of a depth format as
    /// DnsrShadowsDispatch::depth, any size, a depth read-only or shader read-only layout); the first
    /// cascadeCount are read.
    pub cascade_images: [DnsrHostImage; 4],
    /// With DNSR_CLASSIFY_CASCADE_ARRAY: the cascades as layers of one image (a 2D-array view, layer i cascade
    /// i); cascadeImages stay zero. The view must be of type VK_IMAGE_VIEW_TYPE_2D_ARRAY: dnsr cannot query a
    /// view's type, so a 2D view of a layered image is recorded as given and the validation layer reports
    /// VUID-vkCmdDispatch-viewType-07752 at the dispatch.
    pub cascade_array: DnsrHostImage,
    /// Layers of cascadeArray's view (at least cascadeCount).
    pub cascade_array_layers: u32,
    /// World distance along the light direction a shadow-map depth must be in front of the receiver to count as
    /// a blocker (the shadow maps' bias), >= 0. Each tap is compared with the receiver's tangent plane (from its
    /// normal) under it, so a sloping receiver needs no larger offset than a flat one: texel size and depth
    /// precision set it.
    pub blocker_offset: f32,
    /// Blocker-search taps per pixel: 8, 16, 24 (recommended) or 32; anything else is
    /// DNSR_ERROR_INVALID_ARGUMENT.
    pub tap_count: u32,
    /// A tile is listed only with more pixels to trace than this, 0..31 (0: every tile with one). The pixels to
    /// trace of a tile that is not listed get the verdict most of their taps give.
    pub tile_cutoff: u32,
    /// Region to classify with DNSR_CLASSIFY_USE_RENDER_RECT.
    pub render_rect: DnsrRect,
    /// Optional barriers: the writes of depth, normals and shadow maps before; the host's use of the hit mask,
    /// tile list and counts after (its trace: e.g. DRAW_INDIRECT | RAY_TRACING_SHADER_KHR with
    /// INDIRECT_COMMAND_READ | SHADER_READ | SHADER_WRITE). dnsr's own prepare pass is always covered.
    pub sync: DnsrHostSync,
}

/// The buffers the classifier writes (`dnsr_context_get_classifier_buffers`). dnsr owns them; they change only
/// with `dnsr_context_resize`. Usage STORAGE_BUFFER | STORAGE_TEXEL_BUFFER | INDIRECT_BUFFER | TRANSFER_SRC |
/// TRANSFER_DST.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct DnsrClassifierBuffers {
    /// Must be DNSR_STRUCTURE_TYPE_CLASSIFIER_BUFFERS.
    pub s_type: DnsrStructureType,
    /// Must be NULL.
    pub p_next: *mut c_void,
    /// The tile list: tileCapacity records of DNSR_CLASSIFY_TILE_BYTES; the last classify dispatch wrote the
    /// first (counts word 3) of them, in no particular order.
    pub tiles: VkBuffer,
    /// Records `tiles` holds (every 8x4 tile of the render size).
    pub tile_capacity: u32,
    /// DNSR_CLASSIFY_COUNTS_BYTES of counts, reset by every classify dispatch; word 0 is the indirect dispatch
    /// of one workgroup per listed tile.
    pub counts: VkBuffer,
}

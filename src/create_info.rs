//! What the host hands dnsr to create a context.

use crate::host::HostHooks;
use crate::settings::Settings;
use ash::vk;

/// Optional device features the host enabled on its `VkDevice`. dnsr uses only what is declared here and
/// checks at creation that the physical device supports it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EnabledFeatures {
    /// `shaderFloat16` (VK 1.2 / VK_KHR_shader_float16_int8) and `storageBuffer16BitAccess`
    /// (VK 1.1 / VK_KHR_16bit_storage) are enabled. Required for `Precision::Fp16`.
    pub float16: bool,
    /// VK_KHR_push_descriptor is enabled. Without it dnsr keeps a cache of descriptor sets per distinct set of
    /// host image views.
    pub push_descriptor: bool,
}

/// Depth conventions of the host's depth buffer. An infinite far plane needs no flag: sky is still depth 1 (0
/// with `inverted`), and the infinite linear depth it has counts as disoccluded wherever it is compared.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DepthFlags {
    /// Depth 1 is near and 0 is far (reverse-Z).
    pub inverted: bool,
}

/// Arithmetic precision of the filter passes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Precision {
    /// 32-bit floats everywhere.
    #[default]
    Fp32,
    /// float16 filter arithmetic and 16-bit intermediate images; needs `EnabledFeatures::float16`.
    Fp16,
}

/// What the engine's shadow rays deliver per pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ShadowInput {
    /// One ray per pixel, packed into the 8x4-tile hit mask (`ShadowsDispatch::hit_mask`), as FidelityFX.
    #[default]
    HitMask,
    /// The fraction of the pixel's rays that reached the light, in [0, 1] (`ShadowsDispatch::visibility`): for
    /// engines tracing several rays per pixel, sampling area lights, or mixing analytic and traced shadows. Only
    /// exact 0 and 1 count as uniform (cleared tiles) or extend runs of identical samples; the temporal moments
    /// are those of the per-frame values, so k rays per pixel give the variance of a mean of k samples. Costs 12
    /// B/px more per light (the moments keep the samples' sum of squared deviations, which 0/1 samples imply, and
    /// the filter's signal between passes needs an image of its own instead of the frame moments' memory).
    Visibility,
    /// Half a ray per pixel: the hit mask (`ShadowsDispatch::hit_mask`, in its `hit_mask_convention`) holds this
    /// frame's rays for the pixels with (x + y) % 2 == `ShadowsDispatch::checkerboard_phase` only (x, y in image
    /// pixels); the host alternates the phase every frame. dnsr keeps each traced pixel's sample and gives every
    /// other pixel the mean of its four traced neighbours, then denoises that as a visibility input. Costs 16 B/px
    /// more per light (the reconstructed visibility, and what a visibility input costs).
    Checkerboard,
}

/// Most lights one context denoises (`ContextCreateInfo::light_count`).
pub const MAX_LIGHT_COUNT: u32 = 64;
/// Most frames of one light that may be in flight on the GPU at once (`ContextCreateInfo::max_frames_in_flight`).
pub const MAX_FRAMES_IN_FLIGHT: u32 = 16;
/// `max_frames_in_flight` of `ContextCreateInfo::new` (and of a C create info that leaves it 0).
pub const DEFAULT_MAX_FRAMES_IN_FLIGHT: u32 = 3;

/// Everything needed to create a `Context`. Vulkan handles are borrowed: they must outlive the context.
#[derive(Clone, Debug)]
pub struct ContextCreateInfo {
    /// The host's instance. Required.
    pub instance: vk::Instance,
    /// The physical device the host's device was created from. Required.
    pub physical_device: vk::PhysicalDevice,
    /// The host's device. Required.
    pub device: vk::Device,
    /// The host's `vkGetInstanceProcAddr`; dnsr never links the Vulkan loader. Required.
    pub get_instance_proc_addr: Option<vk::PFN_vkGetInstanceProcAddr>,
    /// The host's `vkGetDeviceProcAddr`; every device function dnsr calls is loaded through it. Required.
    pub get_device_proc_addr: Option<vk::PFN_vkGetDeviceProcAddr>,
    /// The `apiVersion` the host created its instance/device with (`vk::make_api_version`). At least 1.1.
    pub api_version: u32,
    /// Queue family of the command buffers dnsr records into: it must support compute; timestamp support and
    /// the stages `HostSync` may name are checked against it.
    pub queue_family_index: u32,
    /// Optional features the host enabled.
    pub features: EnabledFeatures,
    /// Render width in pixels, 1..=maxImageDimension2D.
    pub width: u32,
    /// Render height in pixels, 1..=maxImageDimension2D.
    pub height: u32,
    /// Depth conventions.
    pub depth: DepthFlags,
    /// Filter precision.
    pub precision: Precision,
    /// The shadow input every dispatch of this context passes: the hit mask or per-pixel visibility.
    pub shadow_input: ShadowInput,
    /// Format of the output image: R8_UNORM, R16_SFLOAT or R32_SFLOAT, or R8G8B8A8_UNORM / R16G16B16A16_SFLOAT (the
    /// shadow in every channel). Must support storage on the device.
    pub output_format: vk::Format,
    /// Number of independently denoised lights (each gets its own history), 1..=`MAX_LIGHT_COUNT`.
    pub light_count: u32,
    /// How many recorded frames of one light may be in flight on the GPU at once, 1..=`MAX_FRAMES_IN_FLIGHT`:
    /// the command buffer holding frame N of a light must have completed before frame N + max_frames_in_flight
    /// of that light is recorded. Without push descriptors dnsr rewrites a ring of this many descriptor-set slots
    /// per light, so host image views need to live only until the command buffer that used them completes.
    pub max_frames_in_flight: u32,
    /// Record GPU timestamps around each pass and around the classifier's dispatch; read them with
    /// `Context::timings` and `Context::classifier_timings`.
    pub enable_timestamps: bool,
    /// Create the hybrid-shadows classifier (`Context::record_classify`): its pipelines and its tile list and
    /// counts buffers (16 B per 8x4 tile, about 0.5 B/px, plus 1 KiB).
    pub enable_classifier: bool,
    /// Initial settings.
    pub settings: Settings,
    /// The host aliases dnsr's transient memory: the images whose contents do not outlive one record (tile state,
    /// the temporal result, the filter's intermediates, the reconstructed visibility; the difference
    /// between `Context::memory_bytes` and `Context::persistent_memory_bytes`) are allocated through
    /// `hooks.gpu_memory` (required then) as `ResourceKind::TransientImage`, and every record moves them out of
    /// `VK_IMAGE_LAYOUT_UNDEFINED`, so their contents may be lost between records. The host may then bind that
    /// memory to its own resources as well, provided that its use of them is finished before a record of dnsr's
    /// begins (dnsr's first barrier waits for the stages and accesses a dispatch's `HostSync` names as
    /// `input_src_*`, and for earlier compute and transfer work) and starts after it ends (order it after the
    /// stages named as `output_dst_*`). Costs one layout transition per transient image on every record.
    pub alias_transient_memory: bool,
    /// Each light keeps its own transient images (tile state, the temporal result, the filter's intermediates) instead
    /// of every light sharing one set. Sharing records each light's passes in a row (its transient images are free
    /// again once its last filter pass read them), so only the persistent images (moments, depth copy, history,
    /// quiet counts: `persistent_memory_requirements`) grow with the light count: 10.4 B/px per light after the first
    /// with a hit mask instead of 18.7 (4 lights 49.8 instead of 74.9 B/px). With this flag a `record_lights` call
    /// records pass by pass for every light and runs the later filter passes four lights per dispatch, which measured
    /// faster where every tile is active (4 lights at 3840x2160 on an H200: Quality 4.97 instead of 5.17 ms, Balanced
    /// 3.75 instead of 4.21; the typical scene's Quality the same; BENCHMARKS.md, "Several lights");
    /// `memory_requirements` does not count it: each light after the first adds the difference between a
    /// one-light context's `memory_requirements` and its `persistent_memory_requirements`, the constants aside.
    /// No effect with one light.
    pub transient_memory_per_light: bool,
    /// Every record holds every light of the context (one `record_lights` call with all `light_count` lights;
    /// `record_shadows` only where the context has one light): the lights then share one depth copy (this frame's
    /// depth and normal, kept for the next frame's reprojection), which only the record's last light writes; the
    /// others write theirs to a transient image of their set, for their own later filter passes. Each light after the
    /// first keeps 4 B/px less (with a hit mask 6.25 B/px instead of 10.25: `persistent_memory_requirements` and
    /// `memory_requirements` do not count it) and its outputs are bit for bit the same. A record with fewer lights is
    /// refused, and so is a context of more lights than a record holds (`MAX_LIGHTS_PER_RECORD`). No effect with one
    /// light.
    pub lights_recorded_together: bool,
    /// The host gives dnsr its previous frame's depth and normals with every dispatch
    /// (`ShadowsDispatch::previous_depth`, `previous_normals`: required then), so that dnsr keeps no depth copy of its
    /// own: last frame's linear depth and normal come from those images, and this frame's, which the later filter
    /// passes read as their guide, go to a transient image. 4 B/px less persistent memory per light with a hit mask
    /// (6.25 B/px kept instead of 10.25; `memory_requirements` counts the same bytes, moved to the transient part).
    /// Where the host's previous images hold exactly what it gave dnsr as `depth` and `normals` last frame, and
    /// the projection's depth mapping did not change, the output is the one without this option but where the
    /// depth copy's rounding (16-bit depth, 8-bit octahedral normals) would have decided a test the other way: as
    /// accurate, and no slower (docs/performance.md, State model).
    /// Hit-mask input only (a visibility or checkerboard context is refused).
    pub host_previous_gbuffer: bool,
    /// Host allocators and debug names (all optional).
    pub hooks: HostHooks,
    /// Pass variants the engine compiled itself, against its own callbacks file (docs/callbacks.md); the
    /// embedded SPIR-V is used for every variant not named here. Each is checked against the interface dnsr
    /// relies on (entry point, workgroup size, bindings, push constants, specialization constants) before
    /// anything is created. With overrides of every classification and filter variant the context runs
    /// (docs/callbacks.md), dispatches may pass depth, velocity, normals and hit distances in any format the
    /// device can sample (the callbacks decode them); otherwise only in dnsr's formats, which its own decode reads.
    pub shader_overrides: Vec<ShaderOverride>,
}

/// One pass variant's SPIR-V, compiled by the engine (see `shader_variants` for the names, entry files and
/// definitions; compile with `SHADER_COMPILE_ARGS`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShaderOverride {
    /// The variant it replaces, e.g. `"tile_classification_r16f"`.
    pub variant: String,
    /// The SPIR-V module, as bytes (a multiple of 4, host byte order).
    pub spirv: Vec<u8>,
}

impl ContextCreateInfo {
    /// A create info with defaults for everything but the handles and size.
    pub fn new(
        instance: vk::Instance,
        physical_device: vk::PhysicalDevice,
        device: vk::Device,
        get_instance_proc_addr: vk::PFN_vkGetInstanceProcAddr,
        get_device_proc_addr: vk::PFN_vkGetDeviceProcAddr,
        width: u32,
        height: u32,
    ) -> Self {
        ContextCreateInfo {
            instance,
            physical_device,
            device,
            get_instance_proc_addr: Some(get_instance_proc_addr),
            get_device_proc_addr: Some(get_device_proc_addr),
            api_version: vk::API_VERSION_1_1,
            queue_family_index: 0,
            features: EnabledFeatures::default(),
            width,
            height,
            depth: DepthFlags::default(),
            precision: Precision::Fp32,
            shadow_input: ShadowInput::HitMask,
            output_format: vk::Format::R16_SFLOAT,
            light_count: 1,
            max_frames_in_flight: DEFAULT_MAX_FRAMES_IN_FLIGHT,
            enable_timestamps: false,
            enable_classifier: false,
            settings: Settings::default(),
            alias_transient_memory: false,
            transient_memory_per_light: false,
            lights_recorded_together: false,
            host_previous_gbuffer: false,
            hooks: HostHooks::default(),
            shader_overrides: Vec::new(),
        }
    }
}

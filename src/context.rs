//! The denoiser context: pipelines, internal state per light, and recording into the host's command buffer.

use crate::constants::{FrameConstants, FLAG_CHECKERBOARD, FLAG_DEPTH_INVERTED, FLAG_LIGHT_POSITION, FLAG_LIT_BIT_MASK, FLAG_RESET};
use crate::create_info::{ContextCreateInfo, EnabledFeatures, Precision, ShadowInput};
use crate::dispatch::{HitMaskConvention, LightDispatch, Rect, ShadowsDispatch, MAX_LIGHTS_PER_RECORD};
use crate::error::{vk_check, Error, Result};
use crate::gpu::barrier;
use crate::gpu::descriptors::{Binder, RecordSets};
use crate::gpu::image::{check_internal_format, color_range};
use crate::gpu::loader::{HostDevice, Vk};
use crate::gpu::memory::{self, Memory};
use crate::host::ResourceKind;
use crate::light::{LightState, TransientImages};
use crate::passes::bindings::{image, Binding};
use crate::passes::variants::{is_light_slot_variant, variant};
use crate::passes::{filter, prepare, tile_classification};
use crate::passes::{roles, FrameViews, Pass, Role, LIGHT_SLOTS, SPEC_HARD_LIGHT, SPEC_MOVING_SHADOWS, SPEC_PENUMBRA_GUIDED, SPEC_STABLE_HISTORY};
use crate::pipeline::PassPipeline;
use crate::settings::{check_filter_passes, Settings};
use crate::timestamps::{ClassifierTimings, PassTimings, Timestamps};
use crate::validate;
use ash::vk;

/// Bytes of device memory a context with these parameters and a hit-mask input allocates, before driver padding and
/// alignment (which `Context::memory_bytes` includes), its lights sharing one set of transient images
/// (`ContextCreateInfo::transient_memory_per_light` and `lights_recorded_together` say how they change it); other
/// inputs: `memory_requirements_for_input`. Needs no device.
pub fn memory_requirements(width: u32, height: u32, precision: Precision, filter_passes: u32, light_count: u32) -> Result<u64> {
    memory_requirements_for_input(width, height, precision, filter_passes, light_count, ShadowInput::HitMask)
}

/// `memory_requirements` for a context with shadow input `input` (a visibility input adds 12 B/px per light: the
/// second word of its kept and of its frame's moments, and the filter's signal between passes, which a hit mask
/// keeps in its frame moments' memory; a checkerboard input 16, with its reconstructed visibility). The filter
/// passes change nothing: every count uses the same images.
pub fn memory_requirements_for_input(
    width: u32,
    height: u32,
    precision: Precision,
    filter_passes: u32,
    light_count: u32,
    input: ShadowInput,
) -> Result<u64> {
    memory_requirements_with(width, height, precision, filter_passes, light_count, input, false, false, false).map(|(bytes, _)| bytes)
}

/// `memory_requirements_for_input` with each light's own transient images where `transient_per_light`
/// (`ContextCreateInfo::transient_memory_per_light`; without it the lights share one set), one depth copy for all
/// lights where `together` (`ContextCreateInfo::lights_recorded_together`) and none where `host_previous`
/// (`ContextCreateInfo::host_previous_gbuffer`); and the part of them that persists between records.
#[allow(clippy::too_many_arguments)]
fn memory_requirements_with(
    width: u32,
    height: u32,
    precision: Precision,
    filter_passes: u32,
    light_count: u32,
    input: ShadowInput,
    transient_per_light: bool,
    together: bool,
    host_previous: bool,
) -> Result<(u64, u64)> {
    validate::extent("render size", width, height, u32::MAX)?;
    check_filter_passes(filter_passes)?;
    validate::light_count(light_count)?;
    if together && light_count as usize > MAX_LIGHTS_PER_RECORD {
        return Err(Error::InvalidValue {
            field: "lights_recorded_together",
            value: format!("true with light_count {light_count}"),
            allowed: "a record holds at most 8 lights (MAX_LIGHTS_PER_RECORD), and lights recorded together are all in each record",
        });
    }
    if host_previous && input != ShadowInput::HitMask {
        return Err(Error::InvalidValue {
            field: "host_previous_gbuffer (DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER)",
            value: format!("true with shadow input {input:?}"),
            allowed: "a hit-mask input only: a visibility or checkerboard context keeps its own depth copy",
        });
    }
    use crate::state::{persistent_texel_bytes, table::Scope, texel_bytes, together_bytes};
    let extent = [width, height];
    // Which lights keep a depth copy and which sets hold a frame depth (its size): the rules the lights are made by.
    let c = crate::light::Config { extent, precision, input, together: together && light_count > 1, host_previous };
    let depth = together_bytes(extent, precision, input);
    let kept_depth = depth * (0..light_count).filter(|&l| c.keeps_depth_copy(l)).count() as u64;
    let persistent = persistent_texel_bytes(extent, precision, input);
    let transient = texel_bytes(Scope::Light, extent, precision, input) - persistent + if c.frame_depth() { depth } else { 0 };
    let sets = transient_sets(light_count, transient_per_light) as u64;
    let kept = (persistent - depth) * light_count as u64 + kept_depth;
    Ok((kept + transient * sets + texel_bytes(Scope::Context, extent, precision, input) + constants_bytes(light_count), kept))
}

/// How many transient image sets a context of `light_count` lights holds.
fn transient_sets(light_count: u32, transient_per_light: bool) -> u32 {
    if transient_per_light { light_count } else { 1 }
}

/// Bytes of device memory a context created with `info` allocates, before driver padding and alignment, and the part
/// of them that persists between records: what `Context::memory_bytes` and `Context::persistent_memory_bytes` report
/// less the padding, with every option of `info` counted (its shadow input, `transient_memory_per_light`,
/// `lights_recorded_together`, `host_previous_gbuffer`). Reads no Vulkan handle of `info`; refuses what
/// `Context::new` would refuse of its size, light count, filter passes and these options.
pub fn context_memory_requirements(info: &ContextCreateInfo) -> Result<(u64, u64)> {
    memory_requirements_with(
        info.width,
        info.height,
        info.precision,
        info.settings.filter_passes,
        info.light_count,
        info.shadow_input,
        info.transient_memory_per_light,
        info.lights_recorded_together,
        info.host_previous_gbuffer,
    )
}

/// Bytes of the part of `memory_requirements` whose contents must survive from one record of a light to the next
/// (each light's moments, depth copy and history: `state::Lifetime`), with a hit-mask input (a visibility or
/// checkerboard input adds 4 B/px per light, the kept moments' second word); the rest is written and read within
/// one record. Needs no device.
pub fn persistent_memory_requirements(width: u32, height: u32, precision: Precision, light_count: u32) -> Result<u64> {
    validate::extent("render size", width, height, u32::MAX)?;
    validate::light_count(light_count)?;
    Ok(crate::state::persistent_texel_bytes([width, height], precision, ShadowInput::HitMask) * light_count as u64)
}

/// Bytes between the constants of consecutive lights of one record: the block rounded up to 256, the largest
/// minUniformBufferOffsetAlignment Vulkan allows, so the layout needs no device query.
const CONSTANTS_STRIDE: vk::DeviceSize = (std::mem::size_of::<FrameConstants>() as vk::DeviceSize).next_multiple_of(256);

/// The constants buffer: one slot per light a record can hold.
fn constants_bytes(light_count: u32) -> u64 {
    light_count.min(MAX_LIGHTS_PER_RECORD as u32) as u64 * CONSTANTS_STRIDE
}

/// Lowest Vulkan version dnsr runs on (SPIR-V 1.3, samplerless texel fetches).
pub const MIN_API_VERSION: u32 = vk::API_VERSION_1_1;

struct Pipelines {
    /// None in a hit-mask context: classification reads the host's mask (`Context::reads_mask_directly`).
    prepare: Option<PassPipeline>,
    classification: PassPipeline,
    filter_first: PassPipeline,
    filter_later: PassPipeline,
    filter_final: PassPipeline,
    filter_only: PassPipeline,
    /// The light-slot variants of the later filter passes (intermediate, final), which filter up to LIGHT_SLOTS
    /// lights per dispatch: a context of several lights without shader overrides has them.
    filter_lights: Option<[PassPipeline; 2]>,
}

impl Pipelines {
    fn all_mut(&mut self) -> impl Iterator<Item = &mut PassPipeline> {
        [
            &mut self.classification,
            &mut self.filter_first,
            &mut self.filter_later,
            &mut self.filter_final,
            &mut self.filter_only,
        ]
        .into_iter()
        .chain(self.prepare.as_mut())
        .chain(self.filter_lights.iter_mut().flatten())
    }

    fn for_role(&self, role: Role) -> &PassPipeline {
        match role {
            // A context without prepare never records it; its descriptor ring's sets for it take classification's
            // layout.
            Role::Prepare => self.prepare.as_ref().unwrap_or(&self.classification),
            Role::Classification => &self.classification,
            Role::Filter(0) => &self.filter_first,
            Role::Filter(_) => &self.filter_later,
            Role::FilterFinal => &self.filter_final,
            Role::FilterOnly => &self.filter_only,
            // A context without them never records these roles; its descriptor ring's sets for them take the
            // later passes' layouts.
            Role::FilterLights(_) => self.filter_lights.as_ref().map_or(&self.filter_later, |l| &l[0]),
            Role::FilterLightsFinal => self.filter_lights.as_ref().map_or(&self.filter_final, |l| &l[1]),
        }
    }
}

/// A shadow denoiser bound to one host device. Not thread-safe: record from one thread at a time.
///
/// Dropping the context destroys its Vulkan objects at once: the GPU must have finished every command buffer
/// it recorded into (the same holds for `resize`, which frees the previous internal images).
pub struct Context {
    vk: Vk,
    size: [u32; 2],
    precision: Precision,
    output_format: vk::Format,
    shadow_input: ShadowInput,
    depth_inverted: bool,
    features: EnabledFeatures,
    settings: Settings,
    pipelines: Option<Pipelines>,
    binder: Option<Binder>,
    sampler: vk::Sampler,
    constants_buffer: vk::Buffer,
    constants_memory: Memory,
    lights: Vec<LightState>,
    /// The lights' transient images: one set that every light uses in turn, or one per light
    /// (`ContextCreateInfo::transient_memory_per_light`); `LightState::transient` indexes it.
    transients: Vec<TransientImages>,
    /// `ContextCreateInfo::transient_memory_per_light`.
    transient_per_light: bool,
    /// `ContextCreateInfo::lights_recorded_together`, with more than one light: the lights share the first light's
    /// depth copy, and every record holds all of them.
    together: bool,
    /// `ContextCreateInfo::host_previous_gbuffer`: classification reads last frame's depth and normals from the
    /// host's images, and no light keeps a depth copy.
    host_previous: bool,
    light_count: u32,
    /// The host aliases the transient images (`ContextCreateInfo::alias_transient_memory`): they are allocated as
    /// `ResourceKind::TransientImage`, and every record moves them out of UNDEFINED.
    alias_transient: bool,
    timestamps: Option<Timestamps>,
    frames_recorded: u64,
    /// The barrier bookkeeping of `record`, kept between records so that no record zeroes its 8 KB again.
    hazards: Box<Hazards>,
    /// `record_classify` calls recorded (numbers the classifier's timestamps).
    classify_dispatches: u64,
    /// Stages `HostSync` may name on this device and queue family.
    supported_stages: vk::PipelineStageFlags,
    /// Engine-compiled classification or filter variants decode the G-buffer: its formats are theirs to choose.
    engine_reads: bool,
    /// Some pipeline declares engine images (bindings ENGINE_BINDING_BASE..): dispatches must give them.
    engine_images_declared: bool,
    /// The hybrid-shadows classifier, with `ContextCreateInfo::enable_classifier`.
    classifier: Option<crate::classify::Classifier>,
}

/// What loading the host's device takes from the create info.
fn host_device(info: &ContextCreateInfo) -> HostDevice<'_> {
    HostDevice {
        instance: info.instance,
        physical_device: info.physical_device,
        device: info.device,
        get_instance_proc_addr: info.get_instance_proc_addr,
        get_device_proc_addr: info.get_device_proc_addr,
        push_descriptor: info.features.push_descriptor,
        hooks: &info.hooks,
    }
}

fn check_features(vk: &Vk, info: &ContextCreateInfo) -> Result<()> {
    let props = unsafe { vk.instance.get_physical_device_properties(vk.physical_device) };
    validate::api_version(info.api_version, props.api_version, MIN_API_VERSION)?;
    if info.precision == Precision::Fp16 {
        if !info.features.float16 {
            return Err(Error::MissingFeature("precision Fp16 needs features.float16 (shaderFloat16 + 16-bit storage) enabled"));
        }
        let mut f16 = vk::PhysicalDeviceShaderFloat16Int8Features::default();
        let mut s16 = vk::PhysicalDevice16BitStorageFeatures::default();
        let mut f2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut f16).push_next(&mut s16);
        unsafe { vk.instance.get_physical_device_features2(vk.physical_device, &mut f2) };
        if f16.shader_float16 == 0 || s16.storage_buffer16_bit_access == 0 {
            return Err(Error::MissingFeature("the device does not support shaderFloat16 and storageBuffer16BitAccess"));
        }
    }
    if !validate::OUTPUT_FORMATS.contains(&info.output_format)
        || !vk.format_features(info.output_format).contains(vk::FormatFeatureFlags::STORAGE_IMAGE)
    {
        return Err(Error::UnsupportedFormat { role: Some(crate::error::ImageRole::Output), format: info.output_format });
    }
    for format in crate::state::formats(info.precision) {
        check_internal_format(vk, format)?;
    }
    Ok(())
}

/// What an override's SPIR-V may use beyond every Vulkan 1.1 device's compute shaders.
fn override_offers(vk: &Vk, info: &ContextCreateInfo) -> crate::gpu::spirv_validity::DeviceOffers {
    let mut subgroup = vk::PhysicalDeviceSubgroupProperties::default();
    let mut p2 = vk::PhysicalDeviceProperties2::default().push_next(&mut subgroup);
    unsafe { vk.instance.get_physical_device_properties2(vk.physical_device, &mut p2) };
    let compute = subgroup.supported_stages.contains(vk::ShaderStageFlags::COMPUTE);
    crate::gpu::spirv_validity::DeviceOffers {
        float16: info.features.float16,
        subgroup_operations: if compute { subgroup.supported_operations } else { vk::SubgroupFeatureFlags::empty() },
    }
}

/// Every override names a variant once and fits dnsr's interface (checked before anything is created).
fn check_shader_overrides(vk: &Vk, info: &ContextCreateInfo) -> Result<()> {
    let overrides = &info.shader_overrides;
    let offers = if overrides.is_empty() { Default::default() } else { override_offers(vk, info) };
    for (i, o) in overrides.iter().enumerate() {
        if is_light_slot_variant(&o.variant) {
            return Err(Error::ShaderInterface(format!(
                "shader override {i}: \"{}\" filters several lights per dispatch and is dnsr's own; a context with overrides runs a dispatch per light instead",
                o.variant
            )));
        }
        if !crate::passes::variants::shader_variants().any(|v| v.name == o.variant) {
            // Not a variant: echo no more of the name than a variant's could be.
            let shown: String = o.variant.chars().take(64).collect();
            let more = if shown.len() < o.variant.len() { "..." } else { "" };
            return Err(Error::ShaderInterface(format!(
                "shader override {i} names \"{shown}{more}\", which is not a dnsr shader variant (shader_variants lists them)"
            )));
        }
        if overrides[..i].iter().any(|p| p.variant == o.variant) {
            return Err(Error::ShaderInterface(format!("shader override {i}: \"{}\" is overridden twice", o.variant)));
        }
        crate::interface::check_override(&o.variant, &o.spirv, offers)?;
    }
    Ok(())
}

impl Context {
    /// Creates pipelines and internal state for `info.width` x `info.height`. Every unsupported combination
    /// is reported here rather than at the first dispatch.
    pub fn new(info: &ContextCreateInfo) -> Result<Context> {
        let vk = Vk::load(&host_device(info), validate::known_formats())?;
        let props = unsafe { vk.instance.get_physical_device_properties(vk.physical_device) };
        validate::extent("render size", info.width, info.height, props.limits.max_image_dimension2_d)?;
        validate::light_count(info.light_count)?;
        validate::frames_in_flight(info.max_frames_in_flight)?;
        if info.alias_transient_memory && info.hooks.gpu_memory.is_none() {
            return Err(Error::InvalidValue {
                field: "alias_transient_memory (DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY)",
                value: "true".into(),
                allowed: "it needs hooks.gpu_memory (pGpuMemoryCallbacks): the host's allocator is what aliases the memory",
            });
        }
        info.settings.validate()?;
        check_features(&vk, info)?;
        // After the API version check: the override check queries Vulkan 1.1 properties.
        check_shader_overrides(&vk, info)?;
        let family = validate::queue_family(&vk, info.queue_family_index)?;
        let supported_stages = validate::supported_stages(&vk, &family);
        let (needed, _) = context_memory_requirements(info)?;
        memory::check_available(&vk, needed)?;

        let push = vk.push_descriptor.clone();
        let mut ctx = Context {
            vk,
            size: [info.width, info.height],
            precision: info.precision,
            output_format: info.output_format,
            shadow_input: info.shadow_input,
            depth_inverted: info.depth.inverted,
            features: info.features,
            settings: info.settings,
            pipelines: None,
            binder: None,
            sampler: vk::Sampler::null(),
            constants_buffer: vk::Buffer::null(),
            constants_memory: Memory::default(),
            lights: Vec::new(),
            transients: Vec::new(),
            transient_per_light: info.transient_memory_per_light,
            together: info.lights_recorded_together && info.light_count > 1,
            host_previous: info.host_previous_gbuffer,
            light_count: info.light_count,
            alias_transient: info.alias_transient_memory,
            timestamps: None,
            frames_recorded: 0,
            hazards: Box::default(),
            classify_dispatches: 0,
            supported_stages,
            engine_reads: false,
            engine_images_declared: false,
            classifier: None,
        };
        ctx.engine_reads = ctx.engine_decodes(&info.shader_overrides);
        // On any error below, dropping `ctx` releases what was created so far.
        let pipelines = ctx.pipelines.insert(ctx.create_pipelines(push.is_some(), &info.shader_overrides)?);
        let layouts = roles().map(|r| pipelines.for_role(r));
        ctx.engine_images_declared = layouts.iter().any(|p| p.interface.bindings.iter().any(|b| b.resource.engine_slot().is_some()));
        let push_descriptors = push.is_some();
        // One set per role in each ring slot: a pass's set is at its role's set_index.
        let set_layouts = layouts.map(|p| &p.vulkan);
        ctx.binder = Some(Binder::new(&ctx.vk, push, &set_layouts, info.light_count, info.max_frames_in_flight)?);
        ctx.create_sampler_and_constants()?;
        if info.enable_timestamps {
            ctx.timestamps = Some(Timestamps::new(&ctx.vk, info.queue_family_index)?);
        }
        ctx.allocate_lights()?;
        if info.enable_classifier {
            ctx.classifier = Some(crate::classify::Classifier::new(&ctx.vk, ctx.size, push_descriptors, info.max_frames_in_flight, &info.shader_overrides)?);
        }
        Ok(ctx)
    }

    /// The variants of the context's pipelines, in `Pipelines` order (prepare first, where the context has it).
    fn pipeline_names(&self) -> impl Iterator<Item = &'static str> {
        let prepare = (!self.reads_mask_directly()).then(|| prepare::shader(self.shadow_input));
        prepare.into_iter().chain([
            tile_classification::shader(self.precision, self.output_format, self.shadow_input, self.host_previous).expect("output format checked"),
            filter::shader(self.precision, None, false, self.shadow_input).expect("non-final variant exists"),
            filter::shader(self.precision, None, true, self.shadow_input).expect("non-final variant exists"),
            filter::shader(self.precision, Some(self.output_format), true, self.shadow_input).expect("output format checked"),
            filter::shader(self.precision, Some(self.output_format), false, self.shadow_input).expect("output format checked"),
        ])
    }

    /// Whether only engine-compiled variants decode the G-buffer, so that its formats are the engine's to choose:
    /// every pipeline of this context that reads it (all but prepare) is overridden. Where one is not, dnsr's own
    /// decode runs there and the G-buffer must be in dnsr's formats (an override set compiled for a hit-mask
    /// context leaves a checkerboard context's classification variant, say, to dnsr).
    fn engine_decodes(&self, overrides: &[crate::create_info::ShaderOverride]) -> bool {
        let prepare = prepare::shader(self.shadow_input);
        self.pipeline_names().filter(|&name| name != prepare).all(|name| overrides.iter().any(|o| o.variant == name))
    }

    fn create_pipelines(&self, push: bool, overrides: &[crate::create_info::ShaderOverride]) -> Result<Pipelines> {
        // Several lights per dispatch only with dnsr's own variants: an engine's override of the later pass would
        // not be the one that runs for several lights (and light-slot variants are never overridden); and only
        // where each light has its own transient images, which one dispatch of four lights holds at once.
        let slots = self.light_count > 1 && self.transient_per_light && overrides.is_empty();
        let light_slots = if slots { &self.light_slot_names()[..] } else { &[] };
        let names = self.pipeline_names().chain(light_slots.iter().copied());
        let mut made: Vec<PassPipeline> = Vec::with_capacity(8);
        for name in names {
            let spirv = overrides.iter().find(|o| o.variant == name).map_or(variant(name).spirv, |o| &o.spirv[..]);
            match PassPipeline::new(&self.vk, name, spirv, push) {
                Ok(p) => made.push(p),
                Err(e) => {
                    made.iter_mut().for_each(|p| p.destroy(&self.vk));
                    return Err(e);
                }
            }
        }
        let mut it = made.into_iter();
        let mut next = || it.next().expect("one pipeline per name");
        let mut pipelines = Pipelines {
            prepare: (!self.reads_mask_directly()).then(&mut next),
            classification: next(),
            filter_first: next(),
            filter_later: next(),
            filter_final: next(),
            filter_only: next(),
            filter_lights: None,
        };
        if let (Some(a), Some(b)) = (it.next(), it.next()) {
            pipelines.filter_lights = Some([a, b]);
        }
        Ok(pipelines)
    }

    /// The light-slot variants of the later filter passes (intermediate, final).
    fn light_slot_names(&self) -> [&'static str; 2] {
        [
            filter::lights_shader(self.precision, None).expect("non-final variant exists"),
            filter::lights_shader(self.precision, Some(self.output_format)).expect("output format checked"),
        ]
    }

    fn create_sampler_and_constants(&mut self) -> Result<()> {
        let d = &self.vk.device;
        let alloc = self.vk.alloc();
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(vk::Filter::LINEAR)
            .min_filter(vk::Filter::LINEAR)
            .mipmap_mode(vk::SamplerMipmapMode::NEAREST)
            .address_mode_u(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_v(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .address_mode_w(vk::SamplerAddressMode::CLAMP_TO_EDGE)
            .max_lod(0.0);
        self.sampler = vk_check("vkCreateSampler", unsafe { d.create_sampler(&info, alloc) })?;
        self.vk.name(self.sampler, "dnsr.history_sampler");
        let info = vk::BufferCreateInfo::default()
            .size(constants_bytes(self.light_count))
            .usage(vk::BufferUsageFlags::UNIFORM_BUFFER | vk::BufferUsageFlags::TRANSFER_DST);
        self.constants_buffer = vk_check("vkCreateBuffer", unsafe { d.create_buffer(&info, alloc) })?;
        self.vk.name(self.constants_buffer, "dnsr.constants");
        let req = unsafe { d.get_buffer_memory_requirements(self.constants_buffer) };
        self.constants_memory = memory::allocate(&self.vk, req, ResourceKind::Buffer)?;
        let m = self.constants_memory;
        vk_check("vkBindBufferMemory", unsafe { d.bind_buffer_memory(self.constants_buffer, m.memory, m.offset) })
    }

    /// Every light's persistent images and the transient sets. On an error what was made stays in `lights` and
    /// `transients` (the caller destroys them).
    fn allocate_lights(&mut self) -> Result<()> {
        let sets = transient_sets(self.light_count, self.transient_per_light);
        let c = crate::light::Config {
            extent: self.size,
            precision: self.precision,
            input: self.shadow_input,
            together: self.together,
            host_previous: self.host_previous,
        };
        for set in 0..sets {
            let owner = if sets == 1 { "lights".to_string() } else { format!("light{set}") };
            self.transients.push(TransientImages::new(&self.vk, &owner, c, self.alias_transient)?);
        }
        for index in 0..self.light_count {
            self.lights.push(LightState::new(&self.vk, index, c, (index % sets) as usize)?);
        }
        Ok(())
    }

    fn destroy_lights(&mut self) {
        let vk = &self.vk;
        self.lights.iter_mut().for_each(|l| l.destroy(vk));
        self.lights.clear();
        self.transients.iter_mut().for_each(|t| t.destroy(vk));
        self.transients.clear();
    }

    /// Reallocates internal state for a new render size; histories restart. The GPU must have finished every
    /// command buffer dnsr recorded before (their resources are freed).
    pub fn resize(&mut self, width: u32, height: u32) -> Result<()> {
        let props = unsafe { self.vk.instance.get_physical_device_properties(self.vk.physical_device) };
        validate::extent("render size", width, height, props.limits.max_image_dimension2_d)?;
        let (needed, _) = memory_requirements_with(
            width,
            height,
            self.precision,
            self.settings.filter_passes,
            self.light_count,
            self.shadow_input,
            self.transient_per_light,
            self.together,
            self.host_previous,
        )?;
        memory::check_available(&self.vk, needed.saturating_sub(self.memory_bytes()))?;
        self.destroy_lights();
        self.size = [width, height];
        let mut allocated = self.allocate_lights();
        if let (Ok(()), Some(c)) = (&allocated, self.classifier.as_mut()) {
            c.free_buffers(&self.vk);
            allocated = c.allocate(&self.vk, self.size);
        }
        if allocated.is_err() {
            // Leave no half-allocated state: record refuses until a resize succeeds.
            self.destroy_lights();
            if let Some(c) = self.classifier.as_mut() {
                c.free_buffers(&self.vk);
            }
        }
        allocated
    }

    /// Current render size.
    pub fn size(&self) -> [u32; 2] {
        self.size
    }

    /// Current settings.
    pub fn settings(&self) -> Settings {
        self.settings
    }

    /// Replaces the settings from the next recorded frame on. Allocates nothing: every filter pass count uses the
    /// same images.
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        settings.validate()?;
        self.settings = settings;
        Ok(())
    }

    /// Discards the history of `light_index` before its next frame (same as `ShadowsDispatch::reset`).
    pub fn reset_history(&mut self, light_index: u32) -> Result<()> {
        let count = self.light_count;
        let light = self.lights.get_mut(light_index as usize).ok_or(Error::InvalidLightIndex { index: light_index, count })?;
        light.pending_reset = true;
        Ok(())
    }

    /// Bytes of device memory dnsr allocated (internal images and the constants buffer).
    pub fn memory_bytes(&self) -> u64 {
        let classifier = self.classifier.as_ref().map_or(0, |c| c.bytes());
        let images = self.lights.iter().flat_map(LightState::images).chain(self.transients.iter().flat_map(TransientImages::images));
        images.map(|i| i.bytes).sum::<u64>() + constants_bytes(self.light_count) + classifier
    }

    /// The part of `memory_bytes` whose contents must survive from one record of a light to the next (each light's
    /// moments, depth copy and history, driver padding included); the rest (tile state, the temporal result, the
    /// filter's intermediates, the constants, the classifier's buffers) is written and read within one
    /// record.
    pub fn persistent_memory_bytes(&self) -> u64 {
        self.lights.iter().flat_map(LightState::images).map(|i| i.bytes).sum()
    }

    /// The classifier's tile list and counts (`ContextCreateInfo::enable_classifier`), which the engine's trace
    /// reads after `record_classify`. They change only with `resize`.
    pub fn classifier_buffers(&self) -> Result<crate::passes::classify::ClassifierBuffers> {
        let c = self.classifier.as_ref().ok_or(Error::ClassifierNotEnabled)?;
        if !c.has_buffers() {
            return Err(Error::NotResized);
        }
        Ok(c.buffers())
    }

    /// Records the hybrid-shadows classifier into `cmd` (outside a render pass): it prefills `d.hit_mask` with
    /// the shadow maps' verdicts and lists the tiles with pixels left to trace in `classifier_buffers()`, with
    /// indirect-dispatch counts. The engine then traces the listed pixels (ORing its bits into the mask) and
    /// records the denoiser with that mask. On error nothing is recorded.
    pub fn record_classify(&mut self, cmd: vk::CommandBuffer, d: &crate::passes::classify::ClassifyDispatch) -> Result<()> {
        if cmd == vk::CommandBuffer::null() {
            return Err(Error::NullHandle("command_buffer"));
        }
        let classifier = self.classifier.as_ref().ok_or(Error::ClassifierNotEnabled)?;
        if !classifier.has_buffers() {
            return Err(Error::NotResized);
        }
        let engine_decodes = classifier.engine_decodes(d.cascade_array.is_some());
        let rect = validate::classify(&self.vk, d, self.size, self.supported_stages, engine_decodes)?;
        let classify = crate::passes::classify::constants(d)?;
        let shadows = ShadowsDispatch {
            depth: d.depth,
            normals: d.normals,
            normals_unpack_mul: d.normals_unpack_mul,
            normals_unpack_add: d.normals_unpack_add,
            view_projection_inverse: d.view_projection_inverse,
            projection_inverse: d.projection_inverse,
            hit_mask_convention: d.hit_mask_convention,
            ..Default::default()
        };
        let frame = self.frame_constants(&shadows, rect, false);
        let binder = binder_ref(&self.binder);
        let classifier = self.classifier.as_mut().expect("checked above");
        self.classify_dispatches += 1;
        let dev = &self.vk.device;
        let first_query = self.timestamps.as_mut().map(|t| t.begin_classify(dev, cmd, self.classify_dispatches));
        let timestamps = self.timestamps.as_ref();
        let stamp = |index: u32| {
            if let (Some(t), Some(first)) = (timestamps, first_query) {
                t.stamp(dev, cmd, first + index);
            }
        };
        stamp(0);
        classifier.record(&self.vk, binder, cmd, d, &frame, &classify, rect);
        stamp(1);
        Ok(())
    }

    /// GPU time of the most recent classifier dispatch that has completed, if timestamps are enabled and one has.
    pub fn classifier_timings(&self) -> Result<Option<ClassifierTimings>> {
        if self.classifier.is_none() {
            return Err(Error::ClassifierNotEnabled);
        }
        match &self.timestamps {
            Some(t) => t.latest_classify(&self.vk.device),
            None => Ok(None),
        }
    }

    /// Features the context was created with.
    pub fn features(&self) -> EnabledFeatures {
        self.features
    }

    /// The specialization constants of a frame's passes: with hit distances (`guided`), of a light of no size
    /// (`hard_light`), under the current settings.
    fn specialization(&self, guided: bool, hard_light: bool) -> u32 {
        (if guided { 1 << SPEC_PENUMBRA_GUIDED } else { 0 })
            | (if self.settings.uses_runs() { 1 << SPEC_STABLE_HISTORY } else { 0 })
            | (if self.settings.tells_moving_shadows() { 1 << SPEC_MOVING_SHADOWS } else { 0 })
            | (if hard_light { 1 << SPEC_HARD_LIGHT } else { 0 })
    }

    /// For dnsr-bench: the driver's statistics of each of this context's pipelines (its shader variant's name)
    /// as a frame with the current settings, with or without hit distances (`guided`), runs them: (name, value)
    /// pairs from VK_KHR_pipeline_executable_properties (on NVIDIA the register count, which sets how many
    /// invocations a multiprocessor holds). Each pipeline is compiled again with statistics captured, then
    /// destroyed. The host must have enabled the extension and its `pipelineExecutableInfo` feature
    /// (`Error::MissingFeature` without the extension). `overrides`: the SPIR-V the context was created with
    /// (`ContextCreateInfo::shader_overrides`), so that the statistics are those of the pipelines that run.
    #[doc(hidden)]
    pub fn pipeline_statistics(
        &self,
        guided: bool,
        overrides: &[crate::create_info::ShaderOverride],
    ) -> Result<Vec<(&'static str, Vec<(String, String)>)>> {
        let spec = self.specialization(guided, false);
        self.pipeline_names()
            .map(|name| {
                let spirv = overrides.iter().find(|o| o.variant == name).map_or(variant(name).spirv, |o| &o.spirv[..]);
                Ok((name, PassPipeline::statistics(&self.vk, name, spirv, spec)?))
            })
            .collect()
    }

    /// GPU timings of the most recent recorded frame that has completed, if timestamps are enabled and one has.
    pub fn timings(&self) -> Result<Option<PassTimings>> {
        match &self.timestamps {
            Some(t) => t.latest(&self.vk.device),
            None => Ok(None),
        }
    }

    /// The bindings of light `d.light_index`, whose constants are in slot `slot` of the constants buffer.
    /// `writes_depth`: the light writes the depth copy that the lights recorded together share (the record's last
    /// light); the others write this frame's depth into their transient set.
    fn frame_views(&self, d: &ShadowsDispatch, slot: usize, cur: usize, writes_depth: bool) -> FrameViews {
        let light = &self.lights[d.light_index as usize];
        let t = &self.transients[light.transient];
        let host = |h: &crate::dispatch::HostImage| image(h.view, h.layout);
        let frame_depth = || t.frame_depth.as_ref().expect("lights recorded together and host-previous contexts have a frame depth").view;
        let (depth_copy, previous_depth) = if self.host_previous {
            (frame_depth(), host(&d.previous_depth))
        } else {
            let kept_depth = self.lights[0].depth_copy.as_ref().filter(|_| self.together).or(light.depth_copy.as_ref());
            let kept_depth = kept_depth.expect("a light's own depth copy, or the first light's").view;
            let written = if self.together && !writes_depth { frame_depth() } else { kept_depth };
            (written, image(kept_depth, vk::ImageLayout::GENERAL))
        };
        FrameViews {
            constants: Binding {
                buffer: self.constants_buffer,
                offset: slot as vk::DeviceSize * CONSTANTS_STRIDE,
                range: std::mem::size_of::<FrameConstants>() as vk::DeviceSize,
                ..Default::default()
            },
            hit_mask: host(&d.hit_mask),
            visibility: t.reconstructed.as_ref().map_or(host(&d.visibility), |r| image(r.view, vk::ImageLayout::GENERAL)),
            visibility_out: t.reconstructed.as_ref().map_or(vk::ImageView::null(), |r| r.view),
            depth: host(&d.depth),
            velocity: host(&d.velocity),
            normals: host(&d.normals),
            // Without hit distances the binding takes an image of a float format that the pass only samples.
            hit_distance: d.hit_distance.as_ref().map_or(image(light.history.view, vk::ImageLayout::GENERAL), host),
            tile_blocker: t.tile_blocker.view,
            spec: self.specialization(d.hit_distance.is_some(), d.hard_light),
            output: d.output.view,
            // The other inputs' tile words are prepare's; a hit mask is read as the host gives it (its context has no
            // tile mask: the state table's `Needed::FractionInput`).
            tile_mask: t.tile_mask.as_ref().map_or(host(&d.hit_mask), |m| image(m.view, vk::ImageLayout::GENERAL)),
            tile_dark: t.tile_dark.as_ref().map_or(vk::ImageView::null(), |i| i.view),
            tile_meta: t.tile_meta.view,
            reprojection: t.reprojection.view,
            history: light.history.view,
            signal: t.signal_view(),
            depth_copy,
            previous_depth,
            previous_normals: host(&d.previous_normals),
            kept_moments: light.moments.view,
            frame_moments: t.frame_moments.view,
            previous_tile_quiet: light.tile_quiet[cur ^ 1].view,
            tile_quiet: light.tile_quiet[cur].view,
            engine: d.engine_images.map(|e| e.map_or(Binding::default(), |e| image(e.view, e.layout))),
            penumbra_tan_half_angle: penumbra_tan_half_angle(d),
        }
    }

    /// Every engine image the enabled passes' (engine-compiled) variants declare is given, in a layout its
    /// descriptor type allows. Nothing to check (and no work on the recording path) without such variants.
    /// `hard_light`: some light of the record has no size (its frame is a single filter pass).
    fn check_engine_images(&self, d: &ShadowsDispatch, views: &FrameViews, run_prepare: bool, hard_light: bool) -> Result<()> {
        // Building a frame of passes is most of a record's CPU time: only where an override declares engine images.
        if !self.engine_images_declared {
            return Ok(());
        }
        let frame = |filter_passes| crate::passes::frame(views, filter_passes, run_prepare, d.debug_view);
        let single = hard_light.then(|| frame(crate::passes::light_filter_passes(self.settings.filter_passes, true)));
        let passes = frame(self.settings.filter_passes);
        let pipelines = self.pipelines.as_ref().expect("created");
        for pass in passes.iter().chain(single.iter().flat_map(|f| f.iter())).filter(|p| p.enabled) {
            for b in &pipelines.for_role(pass.role).interface.bindings {
                if let Some(slot) = b.resource.engine_slot() {
                    let storage = b.descriptor_type == vk::DescriptorType::STORAGE_IMAGE;
                    validate::engine_image(crate::dispatch::ENGINE_BINDING_BASE + slot as u32, storage, d.engine_images[slot])?;
                }
            }
        }
        Ok(())
    }

    /// Records the denoiser for one light into `cmd`, which the host is recording (outside a render pass).
    ///
    /// Expectations on the host: the input images are in their declared layouts and their writes are available
    /// to compute-shader reads (pass `HostSync` to have dnsr emit that barrier); the output is not in use by
    /// the GPU; command buffers are submitted in the order they were recorded; and the context outlives them.
    /// A context of several lights created with `lights_recorded_together` refuses it (`record_lights` with all of
    /// them). On error nothing is recorded and no state changes.
    pub fn record_shadows(&mut self, cmd: vk::CommandBuffer, d: &ShadowsDispatch) -> Result<()> {
        self.record(cmd, std::slice::from_ref(d), false)
    }

    /// Records the denoiser for several lights that share one G-buffer and camera (`shared`; its per-light fields
    /// stay at their defaults) into `cmd`: each light reads its own hit mask (or visibility) and writes its own
    /// output, with its own history. The lights share their transient images, so each light's passes are recorded
    /// in a row. With `ContextCreateInfo::transient_memory_per_light` the lights' dispatches of each pass are
    /// recorded together instead, with one barrier between passes for all of them, and the filter passes after the
    /// first up to `LIGHT_SLOTS` (four) lights per dispatch, computing the geometric weights once per tap for all of
    /// them (a context with shader overrides runs a dispatch per light). The result for every light is the result
    /// of a `record_shadows` call for it alone. A context created with `lights_recorded_together` takes every one of
    /// its lights here and nowhere else. Expectations on the host as for `record_shadows`; on error (`Error::Light`
    /// names the light) nothing is recorded and no state changes.
    pub fn record_lights(&mut self, cmd: vk::CommandBuffer, shared: &ShadowsDispatch, lights: &[LightDispatch]) -> Result<()> {
        validate::light_list(shared, lights)?;
        let dispatches: [ShadowsDispatch; MAX_LIGHTS_PER_RECORD] =
            std::array::from_fn(|i| lights.get(i).map_or(*shared, |l| l.apply(shared)));
        self.record(cmd, &dispatches[..lights.len()], true)
    }

    /// Records the frame of every light in `ds` (1..=MAX_LIGHTS_PER_RECORD, distinct lights and outputs): light by
    /// light where they share a transient set, pass by pass otherwise. `listed`: errors name the light's position
    /// (a `record_lights` call).
    fn record(&mut self, cmd: vk::CommandBuffer, ds: &[ShadowsDispatch], listed: bool) -> Result<()> {
        if cmd == vk::CommandBuffer::null() {
            return Err(Error::NullHandle("command_buffer"));
        }
        if self.lights.len() != self.light_count as usize {
            return Err(Error::NotResized);
        }
        let rules = validate::DispatchRules {
            size: self.size,
            output_format: self.output_format,
            lights: self.light_count,
            supported_stages: self.supported_stages,
            engine_reads: self.engine_reads,
            shadow_input: self.shadow_input,
            host_previous: self.host_previous,
        };
        let in_light = |position: usize| {
            move |error: Error| if listed { Error::Light { position: position as u32, error: Box::new(error) } } else { error }
        };
        if self.together && ds.len() != self.light_count as usize {
            return Err(Error::InvalidValue {
                field: "the record's light count",
                value: format!("{} of the context's {}", ds.len(), self.light_count),
                allowed: "a context created with lights_recorded_together (DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER) records every light in each record: they share one depth copy",
            });
        }
        let mut rect = Default::default();
        for (i, d) in ds.iter().enumerate() {
            rect = validate::dispatch(&self.vk, d, &rules).map_err(in_light(i))?;
        }
        let extent = [rect.width, rect.height];
        // Shared by every light of the call: the shadow input, the mask convention, the settings, the debug view.
        let shared = &ds[0];
        let run_prepare = !self.reads_mask_directly();
        // Each light's views; its passes are built from them one at a time (a frame of passes is several KB, and
        // a record must not need eight of them on the host's stack).
        // The last light writes the depth copy that lights recorded together share: after every light's
        // classification read last frame's (in turn, it is the last round; pass by pass, every classification
        // runs before the first filter pass).
        let views: [Option<FrameViews>; MAX_LIGHTS_PER_RECORD] = std::array::from_fn(|i| {
            ds.get(i).map(|d| self.frame_views(d, i, self.lights[d.light_index as usize].parity, i + 1 == ds.len()))
        });
        let views = &views[..ds.len()];
        let (filter_passes, debug_view) = (self.settings.filter_passes, shared.debug_view);
        let light_views = |light: usize| views[light].as_ref().expect("one per dispatch");
        // The engine images are the shared dispatch's, and every light runs the same passes.
        self.check_engine_images(shared, light_views(0), run_prepare, ds.iter().any(|d| d.hard_light))?;
        // A light of no size outputs its rays, which its first filter pass writes: that pass is its last
        // (`Role::FilterOnly`), and the later filter passes (index 3 on) run for the other lights alone.
        let passes_of = |light: usize| crate::passes::light_filter_passes(filter_passes, ds[light].hard_light);
        let every: [usize; MAX_LIGHTS_PER_RECORD] = std::array::from_fn(|i| i);
        let mut filtered = [0; MAX_LIGHTS_PER_RECORD];
        let mut filtered_count = 0;
        for light in (0..ds.len()).filter(|&l| passes_of(l) > 1) {
            filtered[filtered_count] = light;
            filtered_count += 1;
        }
        let members_of = |index: usize| if index >= 3 { &filtered[..filtered_count] } else { &every[..ds.len()] };
        // The later filter passes of several lights run LIGHT_SLOTS lights per dispatch where the context has the
        // light-slot variants; every other pass runs a dispatch per light.
        let pipelines = self.pipelines.as_ref().expect("created");
        let grouped = |index: usize| index >= 3 && pipelines.filter_lights.is_some();
        // Dispatch k of pass `index`: its lights, as positions in `members_of(index)`.
        let group = |index: usize, k: usize| if grouped(index) { crate::passes::light_group(members_of(index).len(), k) } else { k..k + 1 };
        let dispatch_count = |index: usize| match members_of(index).len() {
            0 => 0,
            n if grouped(index) => crate::passes::light_group_count(n),
            n => n,
        };
        // The light whose descriptor ring slot holds dispatch k's sets: its first.
        let first_light = |index: usize, k: usize| members_of(index)[group(index, k).start];
        let build = |index: usize, k: usize| -> Pass {
            let lights = &members_of(index)[group(index, k)];
            if let [light] = *lights {
                return crate::passes::pass(light_views(light), index, passes_of(light), run_prepare, debug_view);
            }
            let members: [&FrameViews; LIGHT_SLOTS] = std::array::from_fn(|s| light_views(lights[s.min(lights.len() - 1)]));
            filter::lights_pass(&members[..lights.len()], index as u32 - 2, filter_passes, debug_view)
        };
        let pass_count = crate::passes::pass_count(filter_passes);
        // Everything that can fail was checked above. Nothing below fails. Each light takes its next ring slot, and
        // every dispatch's bindings are written into its first light's (nothing to write with push descriptors).
        let binder = self.binder.as_mut().expect("created");
        let sets: [Option<RecordSets>; MAX_LIGHTS_PER_RECORD] = std::array::from_fn(|i| ds.get(i).map(|d| binder.next_record(d.light_index)));
        if binder.writes_sets() {
            for index in 0..pass_count {
                for k in 0..dispatch_count(index) {
                    let pass = build(index, k);
                    let set = binder.set(sets[first_light(index, k)].expect("one per dispatch"), pass.role.set_index());
                    if pass.enabled {
                        binder.write(&self.vk.device, set, || pipelines.for_role(pass.role).descriptors(&pass.bindings, self.sampler));
                    }
                }
            }
        }

        // Lights that share one transient set run in turn, each light's passes in a row (a round each): the next
        // light's classification writes the images the last one's filter passes read. Otherwise one round holds
        // every light's dispatches of each pass.
        let in_turn = ds.len() > 1 && !self.transient_per_light;
        let rounds = if in_turn { ds.len() } else { 1 };
        let dev = &self.vk.device;
        self.frames_recorded += 1;
        let first_query = self.timestamps.as_mut().map(|t| t.begin(dev, cmd, self.frames_recorded, filter_passes, rounds as u32));
        let timestamps = self.timestamps.as_ref();
        let stamp = |query: u32| {
            if let (Some(t), Some(first)) = (timestamps, first_query) {
                t.stamp(dev, cmd, first + query);
            }
        };
        // The transient sets of this record's lights, each once.
        let mut transient_sets = [usize::MAX; MAX_LIGHTS_PER_RECORD];
        let mut set_count = 0;
        for d in ds {
            let set = self.lights[d.light_index as usize].transient;
            if !transient_sets[..set_count].contains(&set) {
                transient_sets[set_count] = set;
                set_count += 1;
            }
        }
        let transient_sets = &transient_sets[..set_count];

        // Internal images this frame uses for the first time: moved out of UNDEFINED and cleared.
        let new_images = || {
            let lights = ds.iter().map(|d| &self.lights[d.light_index as usize]).filter(|l| !l.initialized);
            let transients = transient_sets.iter().map(|&t| &self.transients[t]).filter(|t| !t.initialized);
            lights.flat_map(LightState::images).chain(transients.flat_map(TransientImages::images))
        };
        // Layout transitions into GENERAL: the outputs not in it yet here, with the first barrier; the internal
        // images a frame uses for the first time in barriers of their own, in chunks, on those frames alone (an
        // array for every image a record could transition took a fifth of a record's CPU time just to zero).
        let mut outputs = [vk::ImageMemoryBarrier::default(); MAX_LIGHTS_PER_RECORD];
        let mut count = 0;
        for d in ds.iter().filter(|d| d.output.layout != vk::ImageLayout::GENERAL) {
            outputs[count] = barrier::layout_transition(
                d.output.image,
                vk::ImageAspectFlags::COLOR,
                d.output.layout,
                vk::ImageLayout::GENERAL,
                vk::AccessFlags::empty(),
                vk::AccessFlags::SHADER_WRITE,
            );
            count += 1;
        }
        let mut src_stages = vk::PipelineStageFlags::TOP_OF_PIPE | vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::TRANSFER;
        let mut src_access = vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::TRANSFER_WRITE;
        for d in ds {
            src_stages |= d.sync.input_src_stages | d.sync.output_dst_stages;
            src_access |= d.sync.input_src_access;
        }
        let dst_stages = vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::TRANSFER;
        let dst_access = vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::TRANSFER_WRITE;
        // Earlier frames (dnsr's compute and the constants update), the host's input writes and its earlier use
        // of the outputs, all before anything this frame reads or writes.
        barrier::memory(dev, cmd, src_stages, src_access, dst_stages, dst_access, &outputs[..count]);
        // Aliased transient images (`alias_transient_memory`): the host may have used their memory since the last
        // record, so each record moves them out of UNDEFINED (their contents are lost, which they may be:
        // tests/transient.rs). Before the first-use clears below, which then keep their effect.
        if self.alias_transient {
            let transients = transient_sets.iter().flat_map(|&t| self.transients[t].images());
            transition_from_undefined(dev, cmd, transients, [src_stages, dst_stages], [src_access, dst_access]);
        }
        if new_images().next().is_some() {
            transition_from_undefined(dev, cmd, new_images(), [src_stages, dst_stages], [src_access, dst_access]);
        }
        // Defined contents from the first frame on: no NaN garbage can be sampled even by a bad reset path.
        let zero = vk::ClearColorValue { float32: [0.0; 4] };
        for img in new_images() {
            unsafe { dev.cmd_clear_color_image(cmd, img.image, vk::ImageLayout::GENERAL, &zero, &[color_range()]) };
        }
        // Each light's constants at its slot (one update each: no padded staging copy of every slot).
        for (i, d) in ds.iter().enumerate() {
            let light = &self.lights[d.light_index as usize];
            let c = self.frame_constants(d, rect, d.reset || light.pending_reset || !light.initialized);
            unsafe { dev.cmd_update_buffer(cmd, self.constants_buffer, i as u64 * CONSTANTS_STRIDE, bytemuck::bytes_of(&c)) };
        }
        barrier::transfer_to_compute(dev, cmd);

        // The frame's passes in order, each for every light of the round; a barrier wherever a dispatch touches what
        // an earlier one wrote, or writes what an earlier one read, since the last barrier. The lights' dispatches
        // of one pass in one round touch only their own images and run together.
        let binder = binder_ref(&self.binder);
        let record_dispatch = |index: usize, k: usize, hazards: &mut Hazards| {
            let pass = &build(index, k);
            if !pass.enabled {
                return;
            }
            let pipeline = pipelines.for_role(pass.role);
            if hazards.needs_barrier(pipeline, pass) {
                barrier::compute_to_compute(dev, cmd);
            }
            let groups = pass.group_count(extent);
            unsafe {
                dev.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline.vulkan.for_frame(pass.spec));
                if let Some(push) = &pass.push {
                    dev.cmd_push_constants(cmd, pipeline.vulkan.layout, vk::ShaderStageFlags::COMPUTE, 0, bytemuck::bytes_of(push));
                }
            }
            let set = binder.set(sets[first_light(index, k)].expect("one per dispatch"), pass.role.set_index());
            binder.bind(dev, cmd, &pipeline.vulkan, || pipeline.descriptors(&pass.bindings, self.sampler), set);
            unsafe { dev.cmd_dispatch(cmd, groups[0], groups[1], groups[2]) };
        };
        let hazards = &mut self.hazards;
        hazards.begin(transient_sets.iter().map(|&t| &self.transients[t]));
        stamp(0);
        for round in 0..rounds {
            for index in 0..pass_count {
                // In turn: the round's light alone (its dispatch k of the pass, where it has one).
                let dispatches = match in_turn {
                    true => members_of(index).iter().position(|&l| l == round).map_or(0..0, |k| k..k + 1),
                    false => 0..dispatch_count(index),
                };
                for k in dispatches {
                    record_dispatch(index, k, hazards);
                }
                stamp(Timestamps::query(filter_passes, round as u32, index as u32));
            }
        }

        let mut back = [vk::ImageMemoryBarrier::default(); MAX_LIGHTS_PER_RECORD];
        let mut count = 0;
        let mut dst_stages = vk::PipelineStageFlags::empty();
        let mut dst_access = vk::AccessFlags::empty();
        for d in ds {
            dst_stages |= d.sync.output_dst_stages;
            dst_access |= d.sync.output_dst_access;
        }
        for d in ds.iter().filter(|d| d.output.layout != vk::ImageLayout::GENERAL) {
            back[count] = barrier::layout_transition(
                d.output.image,
                vk::ImageAspectFlags::COLOR,
                vk::ImageLayout::GENERAL,
                d.output.layout,
                vk::AccessFlags::SHADER_WRITE,
                dst_access,
            );
            count += 1;
        }
        if count > 0 || !dst_stages.is_empty() {
            let dst = if dst_stages.is_empty() { vk::PipelineStageFlags::COMPUTE_SHADER } else { dst_stages };
            barrier::memory(dev, cmd, vk::PipelineStageFlags::COMPUTE_SHADER, vk::AccessFlags::SHADER_WRITE, dst, dst_access, &back[..count]);
        }

        for d in ds {
            let light = &mut self.lights[d.light_index as usize];
            light.parity ^= 1;
            light.initialized = true;
            light.pending_reset = false;
        }
        for &t in transient_sets {
            self.transients[t].initialized = true;
        }
        Ok(())
    }

    /// Classification reads the host's hit mask as it is, without prepare, in either convention (it inverts
    /// FidelityFX's occluded bits itself; visibility and checkerboard inputs always go through prepare). Prepare
    /// did nothing else for a hit mask, and cost a dispatch, a barrier and 0.005-0.007 ms (BENCHMARKS.md).
    fn reads_mask_directly(&self) -> bool {
        self.shadow_input == ShadowInput::HitMask
    }

    /// The constants of one light's frame.
    fn frame_constants(&self, d: &ShadowsDispatch, rect: Rect, reset: bool) -> FrameConstants {
        let mut c = FrameConstants {
            projection_inverse: d.projection_inverse.to_cols_array_2d(),
            reprojection: d.reprojection_matrix.to_cols_array_2d(),
            view_projection_inverse: d.view_projection_inverse.to_cols_array_2d(),
            eye_depth_sigma: [d.eye.x, d.eye.y, d.eye.z, d.depth_similarity_sigma],
            motion_normals: [d.motion_vector_scale.x, d.motion_vector_scale.y, d.normals_unpack_mul, d.normals_unpack_add],
            rect: [rect.x, rect.y, rect.width, rect.height],
            flags: [
                (if reset { FLAG_RESET } else { 0 })
                    | (if self.depth_inverted { FLAG_DEPTH_INVERTED } else { 0 })
                    | (if d.hit_mask_convention == HitMaskConvention::LitBits { FLAG_LIT_BIT_MASK } else { 0 })
                    | (if self.shadow_input == ShadowInput::Checkerboard { FLAG_CHECKERBOARD } else { 0 })
                    | (if d.light_position.is_some() { FLAG_LIGHT_POSITION } else { 0 }),
                d.checkerboard_phase,
                0,
                0,
            ],
            inv_extent: [1.0 / rect.width as f32, 1.0 / rect.height as f32, 1.0 / self.size[0] as f32, 1.0 / self.size[1] as f32],
            penumbra: penumbra_constants(d, rect.height),
            light_position: d.light_position.unwrap_or_default().to_array(),
            light_extent: [if d.light_position.is_some() { crate::reference::light_sin_radius(d.light_angular_size as f64) as f32 } else { 0.0 }, 0.0, 0.0, 0.0],
            ..Default::default()
        };
        c.set_settings(&self.settings);
        c
    }
}

#[cfg(test)]
impl Context {
    /// Whether a record of several lights runs the later filter passes for several lights per dispatch.
    pub(crate) fn has_light_slot_pipelines(&self) -> bool {
        self.pipelines.as_ref().is_some_and(|p| p.filter_lights.is_some())
    }

    /// The pipeline stages a `HostSync` may name on this context's device.
    pub(crate) fn supported_stages(&self) -> vk::PipelineStageFlags {
        self.supported_stages
    }
}

/// Moves `images` from UNDEFINED to GENERAL (their contents discarded) after the `stages[0]` / `access[0]` work, for
/// the `stages[1]` / `access[1]` work, in barriers of a few images each (no array sized for every image a record
/// could transition).
fn transition_from_undefined<'a>(
    dev: &ash::Device,
    cmd: vk::CommandBuffer,
    images: impl Iterator<Item = &'a crate::gpu::image::InternalImage>,
    stages: [vk::PipelineStageFlags; 2],
    access: [vk::AccessFlags; 2],
) {
    let mut chunk = [vk::ImageMemoryBarrier::default(); 16];
    let mut images = images.peekable();
    while images.peek().is_some() {
        let mut n = 0;
        for img in images.by_ref().take(chunk.len()) {
            chunk[n] = barrier::layout_transition(
                img.image,
                vk::ImageAspectFlags::COLOR,
                vk::ImageLayout::UNDEFINED,
                vk::ImageLayout::GENERAL,
                // An aliased image was written before (by dnsr or by the host): the transition waits for that.
                access[0],
                access[1],
            );
            n += 1;
        }
        barrier::memory(dev, cmd, stages[0], access[0], stages[1], access[1], &chunk[..n]);
    }
}

/// Internal images of one light, for tests that read dnsr's intermediate state.
#[cfg(test)]
pub(crate) struct Internals {
    /// Null with a hit-mask input (no such image).
    pub tile_mask: vk::Image,
    pub tile_dark: vk::Image,
    pub tile_meta: vk::Image,
    pub tile_blocker: vk::Image,
    pub reprojection: vk::Image,
    /// The mean alone (`history_format`).
    pub history: vk::Image,
    /// The image whose memory holds the filter's signal between passes (the frame moments' with a hit mask),
    /// in `intermediate_format`'s texels.
    pub signal: vk::Image,
    /// Written by the last recorded frame.
    pub moments: vk::Image,
    /// Written by the last recorded frame.
    pub tile_quiet: vk::Image,
    pub depth: vk::Image,
    pub intermediate_format: vk::Format,
    pub history_format: vk::Format,
}

#[cfg(test)]
impl Context {
    pub(crate) fn internals(&self, light: usize) -> Internals {
        let l = &self.lights[light];
        let t = &self.transients[l.transient];
        Internals {
            tile_mask: t.tile_mask.as_ref().map_or(vk::Image::null(), |i| i.image),
            tile_dark: t.tile_dark.as_ref().map_or(vk::Image::null(), |i| i.image),
            tile_meta: t.tile_meta.image,
            tile_blocker: t.tile_blocker.image,
            reprojection: t.reprojection.image,
            history: l.history.image,
            signal: t.signal.as_ref().map_or(t.frame_moments.image, |s| s.image),
            moments: l.moments.image,
            tile_quiet: l.tile_quiet[l.parity ^ 1].image,
            depth: self.lights[0].depth_copy.as_ref().filter(|_| self.together).or(l.depth_copy.as_ref()).or(t.frame_depth.as_ref()).expect("a depth copy").image,
            intermediate_format: crate::state::intermediate_format(self.precision),
            history_format: crate::state::history_format(self.precision),
        }
    }

    /// The shadow input the context was created for (its moments' format: `state::moments_format`).
    pub(crate) fn shadow_input(&self) -> ShadowInput {
        self.shadow_input
    }

    /// The moments image written by the last recorded frame of `light` (packed: src/reference/storage.rs; GENERAL).
    pub(crate) fn last_moments(&self, light: usize) -> vk::Image {
        self.lights[light].moments.image
    }

    /// The image of the state table's row `image` (half `copy` of a pair) that `light`'s passes use (its own, or
    /// its transient set's), or the context's own for `light` None (it holds none today: `Scope::Context`), if it
    /// has one: a test compares them with the table.
    pub(crate) fn state_image(&self, light: Option<usize>, image: crate::state::table::Image, copy: u32) -> Option<&crate::gpu::image::InternalImage> {
        let l = &self.lights[light?];
        l.image(image, copy).or_else(|| self.transients[l.transient].image(image, copy))
    }

    /// Every transient image (`state::Lifetime::Transient`, of every transient set) with its format, and the count
    /// of persistent ones: a test fills the transient ones with garbage between records.
    pub(crate) fn transient_images(&self) -> (Vec<(vk::Image, vk::Format)>, usize) {
        let images = self.transients.iter().flat_map(TransientImages::images).map(|i| (i.image, i.format)).collect();
        (images, self.lights.iter().map(|l| l.images().count()).sum())
    }

    /// How many transient image sets the context holds (one, or one per light).
    pub(crate) fn transient_set_count(&self) -> usize {
        self.transients.len()
    }

    /// Frames recorded so far and the parity of `light`: changes exactly when something was recorded.
    pub(crate) fn recording_state(&self, light: usize) -> (u64, usize, bool) {
        let l = &self.lights[light];
        (self.frames_recorded, l.parity, l.initialized)
    }
}

/// Images the passes recorded since the last barrier read and wrote (fixed capacity: no allocation). Tracked by
/// view, a second view of one memory (a hit mask's frame moments and the filter's signal,
/// `InternalImage::shared_view`) counted as its image's first (`same_memory`): where the lights take turns with one
/// transient set, the next light's classification writes the frame moments whose memory the last light's filter
/// passes read as the signal.
struct Hazards {
    read: [vk::ImageView; 2 * crate::gpu::descriptors::MAX_BINDINGS * MAX_LIGHTS_PER_RECORD],
    written: [vk::ImageView; 2 * crate::gpu::descriptors::MAX_BINDINGS * MAX_LIGHTS_PER_RECORD],
    reads: usize,
    writes: usize,
    /// (second view, first view) of each transient set of the record whose frame moments have a second view.
    same_memory: [(vk::ImageView, vk::ImageView); MAX_LIGHTS_PER_RECORD],
    same_memory_count: usize,
}

impl Default for Hazards {
    fn default() -> Self {
        let none = [vk::ImageView::null(); 2 * crate::gpu::descriptors::MAX_BINDINGS * MAX_LIGHTS_PER_RECORD];
        let no_pairs = [(vk::ImageView::null(), vk::ImageView::null()); MAX_LIGHTS_PER_RECORD];
        Hazards { read: none, written: none, reads: 0, writes: 0, same_memory: no_pairs, same_memory_count: 0 }
    }
}

impl Hazards {
    /// Forgets every access: the state after a barrier (the arrays' stale entries lie beyond the counts).
    fn clear(&mut self) {
        (self.reads, self.writes) = (0, 0);
    }

    /// Starts a record whose transient sets are `sets`: no access yet, and their second views known.
    fn begin<'a>(&mut self, sets: impl Iterator<Item = &'a TransientImages>) {
        self.clear();
        self.same_memory_count = 0;
        for t in sets.filter(|t| t.frame_moments.shared_view != vk::ImageView::null()) {
            self.same_memory[self.same_memory_count] = (t.frame_moments.shared_view, t.frame_moments.view);
            self.same_memory_count += 1;
        }
    }

    /// The view that stands for `view`'s memory, of the pairs `same_memory`.
    fn memory_of(same_memory: &[(vk::ImageView, vk::ImageView)], view: vk::ImageView) -> vk::ImageView {
        same_memory.iter().find(|p| p.0 == view).map_or(view, |p| p.1)
    }

    /// Whether `pass` must wait for the passes since the last barrier (read-after-write, write-after-write or
    /// write-after-read on one of its images); records its own accesses either way.
    fn needs_barrier(&mut self, pipeline: &PassPipeline, pass: &Pass) -> bool {
        let same_memory = self.same_memory;
        let same_memory = &same_memory[..self.same_memory_count];
        let accesses = || {
            pipeline.interface.bindings.iter().filter_map(|b| {
                let view = pass.bindings[b.resource as usize].view;
                let write = b.descriptor_type == vk::DescriptorType::STORAGE_IMAGE;
                (view != vk::ImageView::null()).then(|| (Self::memory_of(same_memory, view), write))
            })
        };
        let (new_reads, new_writes) = accesses().fold((0, 0), |(r, w), (_, write)| if write { (r, w + 1) } else { (r + 1, w) });
        let full = self.reads + new_reads > self.read.len() || self.writes + new_writes > self.written.len();
        let conflict = full
            || accesses().any(|(view, write)| {
                self.written[..self.writes].contains(&view) || (write && self.read[..self.reads].contains(&view))
            });
        if conflict {
            self.clear();
        }
        for (view, write) in accesses() {
            let (list, n) = if write { (&mut self.written, &mut self.writes) } else { (&mut self.read, &mut self.reads) };
            list[*n] = view;
            *n += 1;
        }
        conflict
    }
}

/// The penumbra guidance constants: the same conversion the CPU reference uses. Without hit distances the light's
/// size is 0 (x), but the camera's pixel footprint (yz) is kept: a dispatch of several lights reads it from its
/// first light's constants, guided or not.
fn penumbra_constants(d: &ShadowsDispatch, height: u32) -> [f32; 4] {
    let p = crate::reference::Penumbra::new(0.0, d.projection_inverse.as_dmat4(), height as i32);
    [penumbra_tan_half_angle(d), p.pixel_size as f32, p.pixel_size_per_depth as f32, crate::reference::PENUMBRA_SIGMA_SCALE as f32]
}

/// The light's part of the penumbra constants (x), which a dispatch of several lights pushes per light.
fn penumbra_tan_half_angle(d: &ShadowsDispatch) -> f32 {
    if d.hit_distance.is_some() { crate::reference::Penumbra::tan_half_angle(d.light_angular_size as f64) as f32 } else { 0.0 }
}

fn binder_ref(b: &Option<Binder>) -> &Binder {
    b.as_ref().expect("created")
}

impl Drop for Context {
    fn drop(&mut self) {
        self.destroy_lights();
        let vk = &self.vk;
        let (d, alloc) = (&vk.device, vk.alloc());
        if let Some(mut p) = self.pipelines.take() {
            p.all_mut().for_each(|p| p.destroy(vk));
        }
        if let Some(mut b) = self.binder.take() {
            b.destroy(vk);
        }
        if let Some(mut c) = self.classifier.take() {
            c.destroy(vk);
        }
        if let Some(t) = self.timestamps.take() {
            unsafe { d.destroy_query_pool(t.pool, alloc) };
        }
        unsafe {
            d.destroy_sampler(self.sampler, alloc);
            d.destroy_buffer(self.constants_buffer, alloc);
        }
        memory::free(vk, &mut self.constants_memory);
    }
}

//! C structures -> Rust API values, with a specific message for each malformed field.

use super::boundary::{check_no_next, check_type, CallError, LogSink};
use super::types::*;
use crate::create_info::{ContextCreateInfo, DepthFlags, EnabledFeatures, Precision};
use crate::dispatch::{DebugView, HitMaskConvention, HostImage, HostSync, LightDispatch, Rect, ShadowsDispatch};
use crate::host::{GpuAllocation, GpuMemoryAllocator, HostHooks, ResourceKind};
use crate::settings::Settings;
use ash::vk;
use glam::{Mat4, Vec2, Vec3, Vec4};
use std::sync::Arc;

pub(crate) fn settings_from_c(s: &DnsrSettings, what: &str) -> Result<Settings, CallError> {
    check_type(s.s_type, DNSR_STRUCTURE_TYPE_SETTINGS, "DNSR_STRUCTURE_TYPE_SETTINGS", what)?;
    check_no_next(s.p_next, what)?;
    macro_rules! from_c {
        ($($f:ident),*) => { Settings { $($f: s.$f),* } };
    }
    Ok(crate::settings::for_each_setting!(from_c))
}

/// Writes `s` into `*out` field by field over zeroed bytes, so that the struct's padding (after sType) is zero too
/// and two equal settings compare equal with memcmp, as a C host may compare them. (A whole-struct assignment
/// copies whatever a temporary held in its padding.)
pub(crate) fn write_settings(s: &Settings, out: &mut DnsrSettings) {
    // SAFETY: `out` is a valid, exclusive DnsrSettings, whose fields are plain integers, floats and a pointer: all
    // zero bytes is a valid value of each.
    unsafe { std::ptr::write_bytes(out as *mut DnsrSettings, 0, 1) };
    out.s_type = DNSR_STRUCTURE_TYPE_SETTINGS;
    out.p_next = std::ptr::null();
    macro_rules! to_c {
        ($($f:ident),*) => {{ $(out.$f = s.$f;)* }};
    }
    crate::settings::for_each_setting!(to_c);
}

pub(crate) fn settings_to_c(s: &Settings) -> DnsrSettings {
    // SAFETY: all zero bytes is a valid DnsrSettings (see write_settings), which then writes every field.
    let mut out: DnsrSettings = unsafe { std::mem::zeroed() };
    write_settings(s, &mut out);
    out
}

pub(crate) fn preset_from_c(p: DnsrPreset) -> Result<crate::Preset, CallError> {
    match p {
        DNSR_PRESET_FAST => Ok(crate::Preset::Fast),
        DNSR_PRESET_BALANCED => Ok(crate::Preset::Balanced),
        DNSR_PRESET_QUALITY => Ok(crate::Preset::Quality),
        other => Err(CallError::InvalidArgument(format!("preset {other} is not a DnsrPreset value"))),
    }
}

pub(crate) fn precision_from_c(p: DnsrPrecision) -> Result<Precision, CallError> {
    match p {
        DNSR_PRECISION_FP32 => Ok(Precision::Fp32),
        DNSR_PRECISION_FP16 => Ok(Precision::Fp16),
        other => Err(CallError::InvalidArgument(format!("precision {other} is not a DnsrPrecision value"))),
    }
}

/// The host's GPU memory callbacks as a `GpuMemoryAllocator`.
struct CGpuMemory(DnsrGpuMemoryCallbacks);
// SAFETY: the host promises its callbacks and user data may be used from the threads it calls dnsr on.
unsafe impl Send for CGpuMemory {}
unsafe impl Sync for CGpuMemory {}

impl GpuMemoryAllocator for CGpuMemory {
    fn allocate(&self, requirements: &vk::MemoryRequirements, kind: ResourceKind) -> Result<GpuAllocation, vk::Result> {
        let kind = match kind {
            ResourceKind::Image => DNSR_RESOURCE_KIND_IMAGE,
            ResourceKind::Buffer => DNSR_RESOURCE_KIND_BUFFER,
            ResourceKind::TransientImage => DNSR_RESOURCE_KIND_TRANSIENT_IMAGE,
        };
        let mut out = DnsrGpuAllocation::default();
        let allocate = self.0.allocate.expect("checked at creation");
        match unsafe { allocate(self.0.user_data, requirements, kind, &mut out) } {
            vk::Result::SUCCESS => Ok(GpuAllocation { memory: out.memory, offset: out.offset, user_handle: out.user_handle }),
            error => Err(error),
        }
    }

    fn free(&self, a: &GpuAllocation) {
        let c = DnsrGpuAllocation { memory: a.memory, offset: a.offset, user_handle: a.user_handle };
        let free = self.0.free.expect("checked at creation");
        unsafe { free(self.0.user_data, &c) };
    }
}

struct CNamer(DnsrDebugNameCallback);
// SAFETY: as for CGpuMemory.
unsafe impl Send for CNamer {}
unsafe impl Sync for CNamer {}

impl CNamer {
    fn set_name(&self, object_type: vk::ObjectType, handle: u64, name: &std::ffi::CStr) {
        if let Some(f) = self.0.set_name {
            unsafe { f(self.0.user_data, object_type, handle, name.as_ptr()) };
        }
    }
}

/// Converts a create info. Its log sink is stored in `sink` first, so that every later problem is logged.
pub(crate) fn create_info_from_c(c: &DnsrContextCreateInfo, sink: &mut Option<LogSink>) -> Result<ContextCreateInfo, CallError> {
    const WHAT: &str = "pCreateInfo";
    // The sink is read before the sType check: a caller who set one wants to hear about a wrong sType too.
    let log = match unsafe { c.p_log_callback.as_ref() } {
        Some(l) if l.log.is_none() => {
            return Err(CallError::InvalidArgument("pCreateInfo->pLogCallback->log is NULL".into()));
        }
        Some(l) => Some(LogSink(*l)),
        None => None,
    };
    *sink = log;
    check_type(c.s_type, DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO, "DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO", WHAT)?;
    check_no_next(c.p_next, WHAT)?;
    let known_features = DNSR_FEATURE_FLOAT16 | DNSR_FEATURE_PUSH_DESCRIPTOR;
    if c.enabled_features & !known_features != 0 {
        let unknown = c.enabled_features & !known_features;
        return Err(CallError::InvalidArgument(format!("pCreateInfo->enabledFeatures has unknown bits {unknown:#x}")));
    }
    let known_flags = DNSR_CONTEXT_CREATE_DEPTH_INVERTED
        | DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS
        | DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER
        | DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY
        | DNSR_CONTEXT_CREATE_TRANSIENT_MEMORY_PER_LIGHT
        | DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER
        | DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER;
    if c.flags & !known_flags != 0 {
        let unknown = c.flags & !known_flags;
        return Err(CallError::InvalidArgument(format!("pCreateInfo->flags has unknown bits {unknown:#x}")));
    }
    let settings = match unsafe { c.p_settings.as_ref() } {
        Some(s) => settings_from_c(s, "pCreateInfo->pSettings")?,
        None => Settings::default(),
    };
    let mut hooks = HostHooks::default();
    if let Some(a) = unsafe { c.p_allocation_callbacks.as_ref() } {
        if a.pfn_allocation.is_none() || a.pfn_reallocation.is_none() || a.pfn_free.is_none() {
            return Err(CallError::InvalidArgument(
                "pCreateInfo->pAllocationCallbacks needs pfnAllocation, pfnReallocation and pfnFree".into(),
            ));
        }
        hooks.allocation_callbacks = Some(*a);
    }
    if let Some(m) = unsafe { c.p_gpu_memory_callbacks.as_ref() } {
        if m.allocate.is_none() || m.free.is_none() {
            return Err(CallError::InvalidArgument("pCreateInfo->pGpuMemoryCallbacks needs both allocate and free".into()));
        }
        hooks.gpu_memory = Some(Arc::new(CGpuMemory(*m)));
    }
    if let Some(n) = unsafe { c.p_debug_name_callback.as_ref() } {
        if n.set_name.is_none() {
            return Err(CallError::InvalidArgument("pCreateInfo->pDebugNameCallback->setName is NULL".into()));
        }
        let namer = CNamer(*n);
        hooks.debug_names = Some(Arc::new(move |t, handle, name| namer.set_name(t, handle, name)));
    }
    let info = ContextCreateInfo {
        instance: c.instance,
        physical_device: c.physical_device,
        device: c.device,
        get_instance_proc_addr: c.vulkan_functions.vk_get_instance_proc_addr,
        get_device_proc_addr: c.vulkan_functions.vk_get_device_proc_addr,
        api_version: c.api_version,
        queue_family_index: c.queue_family_index,
        features: EnabledFeatures {
            float16: c.enabled_features & DNSR_FEATURE_FLOAT16 != 0,
            push_descriptor: c.enabled_features & DNSR_FEATURE_PUSH_DESCRIPTOR != 0,
        },
        width: c.width,
        height: c.height,
        depth: DepthFlags {
            inverted: c.flags & DNSR_CONTEXT_CREATE_DEPTH_INVERTED != 0,
        },
        precision: precision_from_c(c.precision)?,
        shadow_input: match c.shadow_input {
            DNSR_SHADOW_INPUT_HIT_MASK => crate::ShadowInput::HitMask,
            DNSR_SHADOW_INPUT_VISIBILITY => crate::ShadowInput::Visibility,
            DNSR_SHADOW_INPUT_CHECKERBOARD => crate::ShadowInput::Checkerboard,
            other => return Err(CallError::InvalidArgument(format!("pCreateInfo->shadowInput {other} is not a DnsrShadowInput"))),
        },
        output_format: c.output_format,
        light_count: c.light_count,
        max_frames_in_flight: match c.max_frames_in_flight {
            0 => crate::create_info::DEFAULT_MAX_FRAMES_IN_FLIGHT,
            n => n,
        },
        enable_timestamps: c.flags & DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS != 0,
        enable_classifier: c.flags & DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER != 0,
        alias_transient_memory: c.flags & DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY != 0,
        transient_memory_per_light: c.flags & DNSR_CONTEXT_CREATE_TRANSIENT_MEMORY_PER_LIGHT != 0,
        lights_recorded_together: c.flags & DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER != 0,
        host_previous_gbuffer: c.flags & DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER != 0,
        settings,
        hooks,
        shader_overrides: shader_overrides_from_c(c)?,
    };
    Ok(info)
}

fn shader_overrides_from_c(c: &DnsrContextCreateInfo) -> Result<Vec<crate::ShaderOverride>, CallError> {
    if c.shader_override_count == 0 {
        return Ok(Vec::new());
    }
    if c.p_shader_overrides.is_null() {
        return Err(CallError::InvalidArgument(format!(
            "pCreateInfo->shaderOverrideCount is {} but pShaderOverrides is NULL",
            c.shader_override_count
        )));
    }
    // SAFETY: the caller's array holds shaderOverrideCount entries.
    let all = unsafe { std::slice::from_raw_parts(c.p_shader_overrides, c.shader_override_count as usize) };
    all.iter()
        .enumerate()
        .map(|(i, o)| {
            let what = format!("pCreateInfo->pShaderOverrides[{i}]");
            if o.p_variant_name.is_null() || o.p_code.is_null() {
                return Err(CallError::InvalidArgument(format!("{what}: pVariantName and pCode are required")));
            }
            if o.code_size % 4 != 0 || o.code_size == 0 {
                return Err(CallError::InvalidArgument(format!("{what}.codeSize is {}; SPIR-V is whole 32-bit words", o.code_size)));
            }
            if o.code_size > DNSR_MAX_SHADER_OVERRIDE_CODE_SIZE {
                return Err(CallError::InvalidArgument(format!(
                    "{what}.codeSize is {}; at most DNSR_MAX_SHADER_OVERRIDE_CODE_SIZE ({DNSR_MAX_SHADER_OVERRIDE_CODE_SIZE}) bytes",
                    o.code_size
                )));
            }
            // SAFETY: a NUL-terminated name, read no further than one byte past the longest accepted.
            let length = unsafe { libc::strnlen(o.p_variant_name, DNSR_MAX_SHADER_VARIANT_NAME_LENGTH + 1) };
            // SAFETY: `length` bytes before the terminator (or the bound).
            let name = unsafe { std::slice::from_raw_parts(o.p_variant_name as *const u8, length) };
            if length > DNSR_MAX_SHADER_VARIANT_NAME_LENGTH {
                return Err(CallError::InvalidArgument(format!(
                    "{what}.pVariantName is longer than DNSR_MAX_SHADER_VARIANT_NAME_LENGTH ({DNSR_MAX_SHADER_VARIANT_NAME_LENGTH}) bytes: \"{}...\"",
                    String::from_utf8_lossy(&name[..32])
                )));
            }
            let variant = String::from_utf8_lossy(name).into_owned();
            // SAFETY: codeSize bytes of code, as the header requires.
            let spirv = unsafe { std::slice::from_raw_parts(o.p_code as *const u8, o.code_size) }.to_vec();
            Ok(crate::ShaderOverride { variant, spirv })
        })
        .collect()
}

fn image(i: &DnsrHostImage) -> HostImage {
    HostImage { image: i.image, view: i.view, format: i.format, layout: i.layout, width: i.width, height: i.height }
}

/// Converts a dispatch; returns the command buffer and the Rust dispatch.
pub(crate) fn dispatch_from_c(c: &DnsrShadowsDispatch) -> Result<(vk::CommandBuffer, ShadowsDispatch), CallError> {
    const WHAT: &str = "pDispatch";
    check_type(c.s_type, DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH, "DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH", WHAT)?;
    check_no_next(c.p_next, WHAT)?;
    let known = DNSR_DISPATCH_RESET
        | DNSR_DISPATCH_USE_RENDER_RECT
        | DNSR_DISPATCH_USE_HIT_DISTANCE
        | DNSR_DISPATCH_HARD_LIGHT
        | DNSR_DISPATCH_USE_LIGHT_POSITION;
    let unknown = c.flags & !known;
    if unknown != 0 {
        return Err(CallError::InvalidArgument(format!("pDispatch->flags has unknown bits {unknown:#x}")));
    }
    let hit_mask_convention = hit_mask_convention_from_c(c.hit_mask_convention)?;
    let debug_view = match c.debug_view {
        DNSR_DEBUG_VIEW_NONE => DebugView::None,
        DNSR_DEBUG_VIEW_TILE_CLASSIFICATION => DebugView::TileClassification,
        DNSR_DEBUG_VIEW_SAMPLE_COUNT => DebugView::SampleCount,
        DNSR_DEBUG_VIEW_VARIANCE => DebugView::Variance,
        DNSR_DEBUG_VIEW_DISOCCLUSION => DebugView::Disocclusion,
        DNSR_DEBUG_VIEW_SAMPLE_RUN => DebugView::SampleRun,
        other => return Err(CallError::InvalidArgument(format!("pDispatch->debugView {other} is not a DnsrDebugView"))),
    };
    let r = c.render_rect;
    let d = ShadowsDispatch {
        debug_view,
        light_index: c.light_index,
        hit_mask: image(&c.hit_mask),
        visibility: image(&c.visibility),
        hit_mask_convention,
        depth: image(&c.depth),
        velocity: image(&c.velocity),
        normals: image(&c.normals),
        previous_depth: image(&c.previous_depth),
        previous_normals: image(&c.previous_normals),
        output: image(&c.output),
        hit_distance: (c.flags & DNSR_DISPATCH_USE_HIT_DISTANCE != 0).then(|| image(&c.hit_distance)),
        light_angular_size: c.light_angular_size,
        hard_light: c.flags & DNSR_DISPATCH_HARD_LIGHT != 0,
        light_position: (c.flags & DNSR_DISPATCH_USE_LIGHT_POSITION != 0).then(|| Vec4::from_array(c.light_position)),
        motion_vector_scale: Vec2::from_array(c.motion_vector_scale),
        normals_unpack_mul: c.normals_unpack_mul,
        normals_unpack_add: c.normals_unpack_add,
        eye: Vec3::from_array(c.eye),
        frame_index: c.frame_index,
        projection_inverse: Mat4::from_cols_array(&c.projection_inverse),
        reprojection_matrix: Mat4::from_cols_array(&c.reprojection_matrix),
        view_projection_inverse: Mat4::from_cols_array(&c.view_projection_inverse),
        depth_similarity_sigma: c.depth_similarity_sigma,
        reset: c.flags & DNSR_DISPATCH_RESET != 0,
        render_rect: (c.flags & DNSR_DISPATCH_USE_RENDER_RECT != 0).then_some(Rect { x: r.x, y: r.y, width: r.width, height: r.height }),
        sync: sync_from_c(&c.sync),
        engine_images: engine_images_from_c(c)?,
        checkerboard_phase: c.checkerboard_phase,
    };
    Ok((c.command_buffer, d))
}

/// Converts a `DnsrClassifyDispatch`.
pub(crate) fn classify_from_c(c: &DnsrClassifyDispatch) -> Result<(vk::CommandBuffer, crate::ClassifyDispatch), CallError> {
    const WHAT: &str = "pDispatch";
    check_type(c.s_type, DNSR_STRUCTURE_TYPE_CLASSIFY_DISPATCH, "DNSR_STRUCTURE_TYPE_CLASSIFY_DISPATCH", WHAT)?;
    check_no_next(c.p_next, WHAT)?;
    let known = DNSR_CLASSIFY_REJECT_LIT_PIXELS
        | DNSR_CLASSIFY_BOUND_RAY_INTERVAL
        | DNSR_CLASSIFY_CASCADES_DEPTH_INVERTED
        | DNSR_CLASSIFY_USE_RENDER_RECT
        | DNSR_CLASSIFY_CASCADE_ARRAY;
    if c.flags & !known != 0 {
        return Err(CallError::InvalidArgument(format!("pDispatch->flags has unknown bits {:#x}", c.flags & !known)));
    }
    let r = c.render_rect;
    let d = crate::ClassifyDispatch {
        depth: image(&c.depth),
        normals: image(&c.normals),
        normals_unpack_mul: c.normals_unpack_mul,
        normals_unpack_add: c.normals_unpack_add,
        view_projection_inverse: Mat4::from_cols_array(&c.view_projection_inverse),
        projection_inverse: Mat4::from_cols_array(&c.projection_inverse),
        light_direction: Vec3::from_array(c.light_direction),
        light_angular_size: c.light_angular_size,
        cascade_count: c.cascade_count,
        cascades: c.cascade_world_to_shadow.map(|m| crate::ShadowCascade { world_to_shadow: Mat4::from_cols_array(&m) }),
        cascade_images: c.cascade_images.map(|i| image(&i)),
        cascade_array: (c.flags & DNSR_CLASSIFY_CASCADE_ARRAY != 0).then(|| image(&c.cascade_array)),
        cascade_array_layers: c.cascade_array_layers,
        cascades_depth_inverted: c.flags & DNSR_CLASSIFY_CASCADES_DEPTH_INVERTED != 0,
        blocker_offset: c.blocker_offset,
        tap_count: c.tap_count,
        tile_cutoff: c.tile_cutoff,
        reject_lit_pixels: c.flags & DNSR_CLASSIFY_REJECT_LIT_PIXELS != 0,
        cascades_bound_ray_interval: c.flags & DNSR_CLASSIFY_BOUND_RAY_INTERVAL != 0,
        hit_mask: image(&c.hit_mask),
        hit_mask_convention: hit_mask_convention_from_c(c.hit_mask_convention)?,
        render_rect: (c.flags & DNSR_CLASSIFY_USE_RENDER_RECT != 0).then_some(Rect { x: r.x, y: r.y, width: r.width, height: r.height }),
        sync: sync_from_c(&c.sync),
    };
    Ok((c.command_buffer, d))
}

fn hit_mask_convention_from_c(c: DnsrHitMaskConvention) -> Result<HitMaskConvention, CallError> {
    match c {
        DNSR_HIT_MASK_OCCLUDED_BITS => Ok(HitMaskConvention::OccludedBits),
        DNSR_HIT_MASK_LIT_BITS => Ok(HitMaskConvention::LitBits),
        other => Err(CallError::InvalidArgument(format!("pDispatch->hitMaskConvention {other} is not a DnsrHitMaskConvention"))),
    }
}

fn sync_from_c(s: &DnsrHostSync) -> HostSync {
    HostSync {
        input_src_stages: s.input_src_stages,
        input_src_access: s.input_src_access,
        output_dst_stages: s.output_dst_stages,
        output_dst_access: s.output_dst_access,
    }
}

/// Converts the light list of `dnsr_lights_record`.
pub(crate) fn lights_from_c(
    count: u32,
    p_lights: *const DnsrLightDispatch,
) -> Result<([LightDispatch; crate::MAX_LIGHTS_PER_RECORD], usize), CallError> {
    let mut out = [LightDispatch::default(); crate::MAX_LIGHTS_PER_RECORD];
    if count == 0 || count as usize > crate::MAX_LIGHTS_PER_RECORD {
        return Err(CallError::InvalidArgument(format!("lightCount is {count}; one call takes 1 to 8 lights (DNSR_MAX_LIGHTS_PER_RECORD)")));
    }
    if p_lights.is_null() {
        return Err(CallError::InvalidArgument("pLights is NULL".into()));
    }
    // SAFETY: the caller's array holds lightCount entries.
    for (i, c) in unsafe { std::slice::from_raw_parts(p_lights, count as usize) }.iter().enumerate() {
        let what = format!("pLights[{i}]");
        check_type(c.s_type, DNSR_STRUCTURE_TYPE_LIGHT_DISPATCH, "DNSR_STRUCTURE_TYPE_LIGHT_DISPATCH", &what)?;
        check_no_next(c.p_next, &what)?;
        let known = DNSR_LIGHT_DISPATCH_RESET
            | DNSR_LIGHT_DISPATCH_USE_HIT_DISTANCE
            | DNSR_LIGHT_DISPATCH_HARD_LIGHT
            | DNSR_LIGHT_DISPATCH_USE_LIGHT_POSITION;
        let unknown = c.flags & !known;
        if unknown != 0 {
            return Err(CallError::InvalidArgument(format!("{what}.flags has unknown bits {unknown:#x}")));
        }
        out[i] = LightDispatch {
            light_index: c.light_index,
            hit_mask: image(&c.hit_mask),
            visibility: image(&c.visibility),
            output: image(&c.output),
            hit_distance: (c.flags & DNSR_LIGHT_DISPATCH_USE_HIT_DISTANCE != 0).then(|| image(&c.hit_distance)),
            light_angular_size: c.light_angular_size,
            hard_light: c.flags & DNSR_LIGHT_DISPATCH_HARD_LIGHT != 0,
            light_position: (c.flags & DNSR_LIGHT_DISPATCH_USE_LIGHT_POSITION != 0).then(|| Vec4::from_array(c.light_position)),
            reset: c.flags & DNSR_LIGHT_DISPATCH_RESET != 0,
        };
    }
    Ok((out, count as usize))
}

fn engine_images_from_c(c: &DnsrShadowsDispatch) -> Result<[Option<crate::EngineImage>; crate::MAX_ENGINE_IMAGES], CallError> {
    let mut out = [None; crate::MAX_ENGINE_IMAGES];
    if c.engine_image_count == 0 {
        return Ok(out);
    }
    if c.p_engine_images.is_null() {
        return Err(CallError::InvalidArgument(format!(
            "pDispatch->engineImageCount is {} but pEngineImages is NULL",
            c.engine_image_count
        )));
    }
    // SAFETY: the caller's array holds engineImageCount entries.
    for (i, e) in unsafe { std::slice::from_raw_parts(c.p_engine_images, c.engine_image_count as usize) }.iter().enumerate() {
        let slot = e.binding.wrapping_sub(crate::ENGINE_BINDING_BASE) as usize;
        if slot >= crate::MAX_ENGINE_IMAGES {
            return Err(CallError::InvalidArgument(format!(
                "pDispatch->pEngineImages[{i}].binding is {}; engine images are bindings {}..{}",
                e.binding,
                crate::ENGINE_BINDING_BASE,
                crate::ENGINE_BINDING_BASE + crate::MAX_ENGINE_IMAGES as u32 - 1
            )));
        }
        if out[slot].is_some() {
            return Err(CallError::InvalidArgument(format!("pDispatch->pEngineImages[{i}]: binding {} is given twice", e.binding)));
        }
        out[slot] = Some(crate::EngineImage { view: e.view, layout: e.layout });
    }
    Ok(out)
}

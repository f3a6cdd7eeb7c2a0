//! The C ABI (include/dnsr.h is generated from this module by cbindgen). Validation and conversion only: every
//! export runs behind `boundary::guard`, so no panic unwinds into the host and every failure has a code and a
//! message (`dnsr_last_error_message`). On any error nothing is recorded into the command buffer.
//!
//! Conventions follow VMA: create-info + out handle + result code; destroy accepts NULL; required pointers are
//! checked; structures that may grow carry sType/pNext.

pub(crate) mod boundary;
pub(crate) mod convert;
mod handles;
pub mod reference;
pub mod types;

use boundary::{check_no_next, CallError, check_type, guard, last_error_ptr, optional_out, out, required};
use convert::{classify_from_c, create_info_from_c, dispatch_from_c, lights_from_c, precision_from_c, preset_from_c, settings_from_c, write_settings};
use std::ffi::c_char;
use types::*;

/// Largest `DnsrContextCreateInfo::lightCount`.
pub const DNSR_MAX_LIGHT_COUNT: u32 = 64;
/// Largest `DnsrContextCreateInfo::maxFramesInFlight`.
pub const DNSR_MAX_FRAMES_IN_FLIGHT: u32 = 16;
/// What `DnsrContextCreateInfo::maxFramesInFlight` = 0 means.
pub const DNSR_DEFAULT_MAX_FRAMES_IN_FLIGHT: u32 = 3;
// cbindgen needs literals; the Rust API's constants are the source.
const _: () = assert!(
    DNSR_MAX_LIGHT_COUNT == crate::create_info::MAX_LIGHT_COUNT
        && DNSR_MAX_FRAMES_IN_FLIGHT == crate::create_info::MAX_FRAMES_IN_FLIGHT
        && DNSR_DEFAULT_MAX_FRAMES_IN_FLIGHT == crate::create_info::DEFAULT_MAX_FRAMES_IN_FLIGHT
);

/// Major version of this dnsr build.
pub const DNSR_VERSION_MAJOR: u32 = 0;
/// Minor version of this dnsr build.
pub const DNSR_VERSION_MINOR: u32 = 1;
/// Patch version of this dnsr build.
pub const DNSR_VERSION_PATCH: u32 = 0;

/// The version of the loaded library, as DNSR_MAKE_VERSION(major, minor, patch). Compare with DNSR_VERSION
/// (the header's) to detect a header/library mismatch.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_version() -> u32 {
    (DNSR_VERSION_MAJOR << 22) | (DNSR_VERSION_MINOR << 12) | DNSR_VERSION_PATCH
}

/// The pass variants an engine may compile against its own callbacks file (docs/callbacks.md), for
/// DnsrContextCreateInfo::pShaderOverrides. `*pCount` is the capacity of `pVariants` on entry and the number
/// written on return; with `pVariants` NULL it receives the number of variants.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_get_shader_variants(p_count: *mut u32, p_variants: *mut DnsrShaderVariantInfo) -> DnsrResult {
    use std::ffi::CString;
    use std::sync::OnceLock;
    static STRINGS: OnceLock<Vec<[CString; 3]>> = OnceLock::new();
    guard(|_| {
        let count = out(p_count, "pCount")?;
        let all = STRINGS.get_or_init(|| {
            let c = |s: &str| CString::new(s).expect("variant strings have no NUL");
            crate::shader_variants().map(|v| [c(v.name), c(v.source), c(&v.defines.join(" "))]).collect()
        });
        if p_variants.is_null() {
            *count = all.len() as u32;
            return Ok(DnsrResult::DNSR_SUCCESS);
        }
        let written = all.len().min(*count as usize);
        for (i, [name, source, defines]) in all.iter().take(written).enumerate() {
            let info = DnsrShaderVariantInfo { p_name: name.as_ptr(), p_source: source.as_ptr(), p_defines: defines.as_ptr() };
            // SAFETY: the caller's array holds *pCount entries.
            unsafe { p_variants.add(i).write(info) };
        }
        *count = written as u32;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Creates a context. On success writes the handle to `*pContext`; on failure writes NULL (when `pContext` is
/// not NULL) and creates nothing.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_create(p_create_info: *const DnsrContextCreateInfo, p_context: *mut DnsrContext) -> DnsrResult {
    guard(|sink| {
        let out = out(p_context, "pContext")?;
        *out = std::ptr::null_mut();
        let c = required(p_create_info, "pCreateInfo")?;
        let info = create_info_from_c(c, sink)?;
        let context = crate::Context::new(&info)?;
        *out = handles::insert(context, *sink);
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Destroys a context and everything it created. NULL is accepted (DNSR_SUCCESS); a handle that is not live
/// (e.g. destroyed twice) gives DNSR_ERROR_INVALID_HANDLE. The GPU must have finished every command buffer the
/// context recorded into.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_destroy(context: DnsrContext) -> DnsrResult {
    guard(|_| {
        if context.is_null() {
            return Ok(DnsrResult::DNSR_SUCCESS);
        }
        drop(handles::remove(context)?);
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Records prepare, tile classification and the filter passes into `pDispatch->commandBuffer`. On error nothing
/// is recorded and the context's state is unchanged.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_shadows_record(context: DnsrContext, p_dispatch: *const DnsrShadowsDispatch) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        let (cmd, dispatch) = dispatch_from_c(required(p_dispatch, "pDispatch")?)?;
        entry.lock()?.record_shadows(cmd, &dispatch)?;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Records the denoiser for `lightCount` lights (1..DNSR_MAX_LIGHTS_PER_RECORD) that share one G-buffer and
/// camera into `pDispatch->commandBuffer`: `pDispatch` holds what they share and leaves its per-light fields
/// (lightIndex, hitMask, visibility, output, hitDistance, lightAngularSize, DNSR_DISPATCH_RESET and
/// DNSR_DISPATCH_USE_HIT_DISTANCE) zero; `pLights` gives each light's. Each light's output equals what
/// `dnsr_shadows_record` gives for it alone. The lights share their transient images, so each light's passes are
/// recorded in a row; with DNSR_CONTEXT_CREATE_TRANSIENT_MEMORY_PER_LIGHT the lights' work of each pass runs
/// together on the GPU instead, and the filter passes after the first filter up to four lights per dispatch,
/// fetching what the lights share once (not in a context with shader overrides, which runs a dispatch per light).
/// On error (the message names the refused entry of pLights) nothing is recorded and no light's state changes.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_lights_record(
    context: DnsrContext,
    p_dispatch: *const DnsrShadowsDispatch,
    light_count: u32,
    p_lights: *const DnsrLightDispatch,
) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        let (cmd, shared) = dispatch_from_c(required(p_dispatch, "pDispatch")?)?;
        let (lights, count) = lights_from_c(light_count, p_lights)?;
        entry.lock()?.record_lights(cmd, &shared, &lights[..count])?;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Records the hybrid-shadows classifier into `pDispatch->commandBuffer` (needs
/// DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER): prefills `pDispatch->hitMask` with the shadow maps' verdicts and lists
/// the tiles with pixels left to trace in the classifier's buffers (`dnsr_context_get_classifier_buffers`), with
/// indirect-dispatch counts. Record the engine's trace of the listed pixels after it, then the denoiser. On error
/// nothing is recorded.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_classify_record(context: DnsrContext, p_dispatch: *const DnsrClassifyDispatch) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        let (cmd, dispatch) = classify_from_c(required(p_dispatch, "pDispatch")?)?;
        entry.lock()?.record_classify(cmd, &dispatch)?;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Writes the classifier's tile list and counts buffers to `*pBuffers` (sType set by the caller).
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_get_classifier_buffers(context: DnsrContext, p_buffers: *mut DnsrClassifierBuffers) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        let out = out(p_buffers, "pBuffers")?;
        check_type(out.s_type, DNSR_STRUCTURE_TYPE_CLASSIFIER_BUFFERS, "DNSR_STRUCTURE_TYPE_CLASSIFIER_BUFFERS", "pBuffers")?;
        check_no_next(out.p_next, "pBuffers")?;
        let b = entry.lock()?.classifier_buffers()?;
        out.tiles = b.tiles;
        out.tile_capacity = b.tile_capacity;
        out.counts = b.counts;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Reallocates the internal state for a new render size; histories restart. The GPU must have finished every
/// command buffer the context recorded into.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_resize(context: DnsrContext, width: u32, height: u32) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        entry.lock()?.resize(width, height)?;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Discards the history of one light before its next frame (like DNSR_DISPATCH_RESET).
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_reset_history(context: DnsrContext, light_index: u32) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        entry.lock()?.reset_history(light_index)?;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Fills `*pSettings` with dnsr's default settings, the Quality preset (sType included; the struct's padding bytes
/// zero, as with every call that writes a DnsrSettings, so equal settings compare equal with memcmp). The
/// FidelityFX values: `dnsr_settings_init_preset(DNSR_PRESET_BALANCED, ...)`.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_settings_init_default(p_settings: *mut DnsrSettings) -> DnsrResult {
    guard(|_| {
        write_settings(&crate::Settings::default(), out(p_settings, "pSettings")?);
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Fills `*pSettings` with the settings of `preset` (sType included). An unknown preset value is
/// DNSR_ERROR_INVALID_ARGUMENT and leaves `*pSettings` untouched.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_settings_init_preset(preset: DnsrPreset, p_settings: *mut DnsrSettings) -> DnsrResult {
    guard(|_| {
        let settings = crate::Settings::preset(preset_from_c(preset)?);
        write_settings(&settings, out(p_settings, "pSettings")?);
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Writes the context's current settings to `*pSettings`.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_get_settings(context: DnsrContext, p_settings: *mut DnsrSettings) -> DnsrResult {
    query_into(context, p_settings, "pSettings", |c, out| write_settings(&c.settings(), out))
}

/// A query of a live context written to an out-parameter: the handle's lookup (its log sink from then on), the
/// NULL check and the lock in one place.
fn query<T>(context: DnsrContext, p_out: *mut T, name: &str, value: impl FnOnce(&crate::Context) -> T) -> DnsrResult {
    query_into(context, p_out, name, |c, out| *out = value(c))
}

/// `query` with a writer of its own (`write_settings`, which zeroes the padding).
fn query_into<T>(context: DnsrContext, p_out: *mut T, name: &str, write: impl FnOnce(&crate::Context, &mut T)) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        let out = out(p_out, name)?;
        write(&*entry.lock()?, out);
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Replaces the settings from the next recorded frame on; a refused change keeps the old settings. Allocates
/// nothing: every filter pass count uses the same images.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_set_settings(context: DnsrContext, p_settings: *const DnsrSettings) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        let settings = settings_from_c(required(p_settings, "pSettings")?, "pSettings")?;
        entry.lock()?.set_settings(settings)?;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Per-pass GPU times of the most recent completed frame (needs DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS).
/// Returns DNSR_NOT_READY when no recorded frame has completed yet (or timestamps are off).
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_get_timings(context: DnsrContext, p_timings: *mut DnsrPassTimings) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        let out = out(p_timings, "pTimings")?;
        check_type(out.s_type, DNSR_STRUCTURE_TYPE_PASS_TIMINGS, "DNSR_STRUCTURE_TYPE_PASS_TIMINGS", "pTimings")?;
        check_no_next(out.p_next, "pTimings")?;
        let Some(t) = entry.lock()?.timings()? else { return Ok(DnsrResult::DNSR_NOT_READY) };
        out.frame = t.frame;
        out.prepare_ms = t.prepare_ms;
        out.tile_classification_ms = t.tile_classification_ms;
        out.filter_ms = t.filter_ms;
        out.filter_passes = t.filter_passes;
        out.total_ms = t.total_ms;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// GPU time of the most recent completed classifier dispatch (needs DNSR_CONTEXT_CREATE_ENABLE_TIMESTAMPS and
/// DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER). Returns DNSR_NOT_READY when none has completed yet (or timestamps are
/// off), DNSR_ERROR_CLASSIFIER_NOT_ENABLED for a context without the classifier.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_get_classifier_timings(context: DnsrContext, p_timings: *mut DnsrClassifierTimings) -> DnsrResult {
    guard(|sink| {
        let entry = handles::get_logged(context, sink)?;
        let out = out(p_timings, "pTimings")?;
        check_type(out.s_type, DNSR_STRUCTURE_TYPE_CLASSIFIER_TIMINGS, "DNSR_STRUCTURE_TYPE_CLASSIFIER_TIMINGS", "pTimings")?;
        check_no_next(out.p_next, "pTimings")?;
        let Some(t) = entry.lock()?.classifier_timings()? else { return Ok(DnsrResult::DNSR_NOT_READY) };
        out.dispatch = t.dispatch;
        out.classify_ms = t.classify_ms;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// What a FidelityFX context's later dispatches take that the FFX interface has no field for (checked here).
#[derive(Clone, Copy, Debug)]
pub(crate) enum FfxContextSetting {
    /// `dnsr_ffx_context_set_light`: DNSR_DISPATCH_HARD_LIGHT and DNSR_DISPATCH_USE_LIGHT_POSITION bits, and the
    /// position and angular diameter that the second reads.
    Light { flags: DnsrDispatchFlags, position: [f32; 4], angular_size: f32 },
    /// `dnsr_ffx_context_set_penumbra_guidance`: the hit-distance image and the light's angular diameter; None
    /// turns guidance off.
    Guidance(Option<(DnsrHostImage, f32)>),
    /// `dnsr_ffx_context_set_previous_gbuffer`: last frame's depth and normals, for the next dispatch only.
    PreviousGbuffer { depth: DnsrHostImage, normals: DnsrHostImage },
}

/// What the `dnsr_ffx_context_set_*` functions call: the FidelityFX layer's setter of a context's setting (an error
/// where no live FFX context is, or where the context cannot take the setting). ffx builds on this module, so it registers the setter when it creates a context
/// instead of this module importing ffx; unset, no FFX context was ever created.
pub(crate) static FFX_SET: std::sync::OnceLock<FfxSet> = std::sync::OnceLock::new();
type FfxSet = fn(*mut std::ffi::c_void, FfxContextSetting) -> Result<(), CallError>;

/// The message of a `dnsr_ffx_context_set_*` call on a pointer that holds no live FFX context.
pub(crate) const FFX_NOT_LIVE: &str = "pFfxContext is not a live FfxDenoiserContext (never created, or destroyed)";

/// Gives the FFX context at `p_ffx_context` the setting that `checked` makes of the call's other arguments, or says
/// why not: a NULL context first, then what `checked` refuses, then a context that is not live.
fn set_ffx(
    p_ffx_context: *mut std::ffi::c_void,
    checked: impl FnOnce() -> Result<FfxContextSetting, CallError>,
) -> Result<DnsrResult, CallError> {
    if p_ffx_context.is_null() {
        return Err(CallError::InvalidArgument("pFfxContext is NULL".into()));
    }
    let setting = checked()?;
    match FFX_SET.get() {
        Some(set) => set(p_ffx_context, setting)?,
        None => return Err(CallError::InvalidArgument(FFX_NOT_LIVE.into())),
    }
    Ok(DnsrResult::DNSR_SUCCESS)
}

/// Tells dnsr's FidelityFX layer (include/ffx) about the light of a shadow denoiser context's later dispatches,
/// which the FFX interface has no field for: `pFfxContext` is the `FfxDenoiserContext*` that
/// ffxDenoiserContextCreate filled. `flags` holds DNSR_DISPATCH_HARD_LIGHT (the light has no size: every receiver's
/// output is its ray, which is exact) and DNSR_DISPATCH_USE_LIGHT_POSITION (where the light is, in the world space of
/// the dispatches' viewProjectionInverse: `pLightPosition` points at 4 floats, read as DnsrShadowsDispatch::
/// lightPosition, and `lightAngularSize` is the light's angular diameter in radians, read as DnsrShadowsDispatch::
/// lightAngularSize: 0 for a point light, the light's size otherwise, or faces turned just past a large light's
/// centre lose their penumbrae); every other bit is refused. 0 returns the context to knowing nothing of its light.
/// Each later ffxDenoiserContextDispatchShadows records as dnsr_shadows_record does with these bits, this position
/// and this size, so a point light or a moving sun calls it before each dispatch whose light moved; the values are
/// copied. With penumbra guidance too (`dnsr_ffx_context_set_penumbra_guidance`), both must give the same size: a
/// dispatch that finds them different refuses it with FFX_ERROR_INVALID_ARGUMENT.
///
/// What it changes (docs/do-no-harm.md): on the 100 scenes of `make viewer-accuracy`, dnsr's default settings are
/// worse than their 1-spp input on 25 scenes without it and on 11 with both bits (docs/viewer-family.md: quality+untold
/// and quality). The SDK's own denoiser has no such
/// function: call it only where dnsr's FidelityFX layer is linked.
///
/// Errors: DNSR_ERROR_INVALID_ARGUMENT for a NULL `pFfxContext`, a context that is not live (never created, or
/// destroyed), an unknown bit, or DNSR_DISPATCH_USE_LIGHT_POSITION with a NULL `pLightPosition` or a position that
/// is neither a direction (w 0, non-zero xyz) nor a point (w 1), or a `lightAngularSize` outside [0, pi) (or other
/// than 0 with DNSR_DISPATCH_HARD_LIGHT); DNSR_ERROR_NON_FINITE for a NaN or infinite coordinate or size. On error
/// the context keeps the light it had.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_ffx_context_set_light(
    p_ffx_context: *mut std::ffi::c_void,
    flags: DnsrDispatchFlags,
    p_light_position: *const f32,
    light_angular_size: f32,
) -> DnsrResult {
    guard(|_| set_ffx(p_ffx_context, || {
        const KNOWN: DnsrDispatchFlags = DNSR_DISPATCH_HARD_LIGHT | DNSR_DISPATCH_USE_LIGHT_POSITION;
        if flags & !KNOWN != 0 {
            return Err(CallError::InvalidArgument(format!(
                "flags 0x{flags:x}: a FidelityFX context's light takes DNSR_DISPATCH_HARD_LIGHT and DNSR_DISPATCH_USE_LIGHT_POSITION only"
            )));
        }
        let (mut position, mut angular_size) = ([0.0; 4], 0.0);
        if flags & DNSR_DISPATCH_USE_LIGHT_POSITION != 0 {
            let p: &[f32; 4] = required(p_light_position.cast(), "pLightPosition")?;
            crate::validate::light_position(glam::Vec4::from_array(*p))?;
            crate::validate::light_angular_size(light_angular_size)?;
            if flags & DNSR_DISPATCH_HARD_LIGHT != 0 {
                crate::validate::hard_light_size(light_angular_size)?;
            }
            position = *p;
            angular_size = light_angular_size;
        }
        Ok(FfxContextSetting::Light { flags, position, angular_size })
    }))
}

/// Gives dnsr's FidelityFX layer penumbra guidance for a shadow denoiser context's later dispatches, which the FFX
/// interface has no field for: `pFfxContext` is the `FfxDenoiserContext*` that ffxDenoiserContextCreate filled,
/// `pHitDistance` the engine's hit distances (read as DnsrShadowsDispatch::hitDistance: per pixel the distance along
/// the shadow ray to the first occluder it hit, R16_SFLOAT or R32_SFLOAT, in a sampled layout, the size of the
/// dispatches' images) and `lightAngularSize` the light's angular diameter in radians, in [0, pi) (the sun: about
/// 0.0093; 0 is a point light, as DnsrShadowsDispatch::lightAngularSize). Each later ffxDenoiserContextDispatchShadows
/// records as dnsr_shadows_record does with DNSR_DISPATCH_USE_HIT_DISTANCE and these values; the description is
/// copied, the image is borrowed by each dispatch, so an engine whose hit-distance image changes from frame to frame
/// calls this before each dispatch. NULL `pHitDistance` turns guidance off again (`lightAngularSize` is not read).
/// The image itself (its format, layout and size) is checked by each dispatch, which refuses one that does not fit
/// with FFX_ERROR_INVALID_ARGUMENT and a message; so is the pair with `dnsr_ffx_context_set_light`'s
/// DNSR_DISPATCH_HARD_LIGHT, which needs `lightAngularSize` 0, and with its DNSR_DISPATCH_USE_LIGHT_POSITION, whose
/// light's size must be this `lightAngularSize`.
///
/// What it changes (docs/do-no-harm.md): on the 100 scenes of `make viewer-accuracy`, dnsr's default settings are
/// worse than their 1-spp input on 25 scenes told nothing of the light, on 11 told where it is and whether it has a
/// size (`dnsr_ffx_context_set_light`), and on 6 given hit distances and the light's size as well: five of them
/// within 0.4% of their input's error, and one whose input is exact at RMSE 0.0039 (docs/viewer-family.md,
/// quality+guided). Where the engine's tracer can write the hit distance
/// beside its hit mask, this is the closest dnsr comes to never making a shadow worse. The SDK's own denoiser has
/// no such function: call it only where dnsr's FidelityFX layer is linked.
///
/// Errors: DNSR_ERROR_INVALID_ARGUMENT for a NULL `pFfxContext`, a context that is not live (never created, or
/// destroyed) or an angle outside [0, pi); DNSR_ERROR_NULL_HANDLE for a hit-distance image or view that is
/// VK_NULL_HANDLE; DNSR_ERROR_NON_FINITE for a NaN or infinite angle. On error the context keeps the guidance it
/// had.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_ffx_context_set_penumbra_guidance(
    p_ffx_context: *mut std::ffi::c_void,
    p_hit_distance: *const DnsrHostImage,
    light_angular_size: f32,
) -> DnsrResult {
    guard(|_| set_ffx(p_ffx_context, || {
        let guidance = match unsafe { p_hit_distance.as_ref() } {
            None => None,
            Some(image) => {
                if image.image == VkImage::null() {
                    return Err(crate::error::Error::NullHandle("pHitDistance->image").into());
                }
                if image.view == VkImageView::null() {
                    return Err(crate::error::Error::NullHandle("pHitDistance->view").into());
                }
                crate::validate::light_angular_size(light_angular_size)?;
                Some((*image, light_angular_size))
            }
        };
        Ok(FfxContextSetting::Guidance(guidance))
    }))
}

/// Gives dnsr's FidelityFX layer the engine's previous frame's depth and normals for a shadow denoiser context's
/// next dispatch, which the FFX interface has no field for: `pFfxContext` is the `FfxDenoiserContext*` that
/// ffxDenoiserContextCreate filled with DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER in the description's flags,
/// `pPreviousDepth` and `pPreviousNormals` the images the engine gave that context's last dispatch as `depth` and
/// `normal` (read as DnsrShadowsDispatch::previousDepth and previousNormals: the same formats, layouts and size, in a
/// sampled layout; the normals decoded with the dispatch's normalsUnpackMul and normalsUnpackAdd). Call it before
/// every ffxDenoiserContextDispatchShadows but the context's first (whose history is empty: nothing is read): the
/// descriptions are copied and used by the next dispatch only, so a dispatch that was not given this frame's
/// previous images is refused (FFX_ERROR_INVALID_ARGUMENT) instead of reading last frame's pair, which an engine that
/// alternates two G-buffers has overwritten by then. The images themselves are checked by that dispatch.
///
/// What it changes: the context keeps no depth copy, 6.3 instead of 10.4 B/px between frames at 4K, as accurate
/// (the outputs differ from the depth copy's only where its rounding decided a test) and no slower (docs/
/// performance.md, State model). The SDK's own denoiser has no such function: call it only where dnsr's FidelityFX
/// layer is linked.
///
/// Errors: DNSR_ERROR_INVALID_ARGUMENT for a NULL `pFfxContext`, a context that is not live (never created, or
/// destroyed) or was created without DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER, or a NULL `pPreviousDepth` or
/// `pPreviousNormals`; DNSR_ERROR_NULL_HANDLE for an image or view that is VK_NULL_HANDLE. On error the context
/// keeps what it had.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_ffx_context_set_previous_gbuffer(
    p_ffx_context: *mut std::ffi::c_void,
    p_previous_depth: *const DnsrHostImage,
    p_previous_normals: *const DnsrHostImage,
) -> DnsrResult {
    guard(|_| set_ffx(p_ffx_context, || {
        let depth: &DnsrHostImage = required(p_previous_depth, "pPreviousDepth")?;
        let normals: &DnsrHostImage = required(p_previous_normals, "pPreviousNormals")?;
        for (image, image_name, view_name) in [
            (depth, "pPreviousDepth->image", "pPreviousDepth->view"),
            (normals, "pPreviousNormals->image", "pPreviousNormals->view"),
        ] {
            if image.image == VkImage::null() {
                return Err(crate::error::Error::NullHandle(image_name).into());
            }
            if image.view == VkImageView::null() {
                return Err(crate::error::Error::NullHandle(view_name).into());
            }
        }
        Ok(FfxContextSetting::PreviousGbuffer { depth: *depth, normals: *normals })
    }))
}

/// Bytes of device memory the context allocated (driver padding included).
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_get_memory_usage(context: DnsrContext, p_bytes: *mut u64) -> DnsrResult {
    query(context, p_bytes, "pBytes", crate::Context::memory_bytes)
}

/// The part of dnsr_context_get_memory_usage's bytes whose contents must survive from one record of a light to
/// the next (each light's moments, depth copy and history); the rest is written and read within one record.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_context_get_persistent_memory_usage(context: DnsrContext, p_bytes: *mut u64) -> DnsrResult {
    query(context, p_bytes, "pBytes", crate::Context::persistent_memory_bytes)
}

/// The part of dnsr_get_memory_requirements' bytes that persists between records (as
/// dnsr_context_get_persistent_memory_usage), before driver padding, with a hit-mask input (a visibility or
/// checkerboard input adds 4 B/px per light, the kept moments' second word). Needs no device.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_get_persistent_memory_requirements(
    width: u32,
    height: u32,
    precision: DnsrPrecision,
    light_count: u32,
    p_bytes: *mut u64,
) -> DnsrResult {
    guard(|_| {
        let out = out(p_bytes, "pBytes")?;
        *out = crate::persistent_memory_requirements(width, height, precision_from_c(precision)?, light_count)?;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Bytes of device memory a context with a hit-mask input would allocate for this size, before driver padding (see
/// DNSR_SHADOW_INPUT_VISIBILITY and DNSR_SHADOW_INPUT_CHECKERBOARD for theirs), its lights sharing one set of
/// transient images (DNSR_CONTEXT_CREATE_TRANSIENT_MEMORY_PER_LIGHT and DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER
/// say how they change it). Needs no device.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_get_memory_requirements(
    width: u32,
    height: u32,
    precision: DnsrPrecision,
    filter_passes: u32,
    light_count: u32,
    p_bytes: *mut u64,
) -> DnsrResult {
    guard(|_| {
        let out = out(p_bytes, "pBytes")?;
        *out = crate::memory_requirements(width, height, precision_from_c(precision)?, filter_passes, light_count)?;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Bytes of device memory a context created with `pCreateInfo` would allocate, before driver padding, every option
/// counted (its shadow input, DNSR_CONTEXT_CREATE_TRANSIENT_MEMORY_PER_LIGHT, DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER,
/// DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER);
/// `pPersistentBytes` (optional, NULL allowed) receives the part of them that persists between records. Reads no
/// Vulkan handle of `pCreateInfo`; refuses what dnsr_context_create would refuse of its size, light count, settings
/// and flags.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_get_context_memory_requirements(
    p_create_info: *const DnsrContextCreateInfo,
    p_bytes: *mut u64,
    p_persistent_bytes: *mut u64,
) -> DnsrResult {
    guard(|sink| {
        let out = out(p_bytes, "pBytes")?;
        let c = required(p_create_info, "pCreateInfo")?;
        let (bytes, persistent) = crate::context_memory_requirements(&create_info_from_c(c, sink)?)?;
        *out = bytes;
        if let Some(p) = optional_out(p_persistent_bytes) {
            *p = persistent;
        }
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// Optional device extensions, as static C strings.
struct ExtensionNames([*const c_char; 1]);
// SAFETY: pointers to static string literals.
unsafe impl Sync for ExtensionNames {}
static OPTIONAL_EXTENSIONS: ExtensionNames =
    ExtensionNames([c"VK_KHR_push_descriptor".as_ptr()]);

/// What the host must create its instance and device with (see DnsrDeviceRequirements).
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_get_device_requirements(p_requirements: *mut DnsrDeviceRequirements) -> DnsrResult {
    guard(|_| {
        let out = out(p_requirements, "pRequirements")?;
        check_type(out.s_type, DNSR_STRUCTURE_TYPE_DEVICE_REQUIREMENTS, "DNSR_STRUCTURE_TYPE_DEVICE_REQUIREMENTS", "pRequirements")?;
        check_no_next(out.p_next, "pRequirements")?;
        out.min_api_version = crate::MIN_API_VERSION;
        out.required_extension_count = 0;
        out.pp_required_extension_names = std::ptr::null();
        out.optional_extension_count = OPTIONAL_EXTENSIONS.0.len() as u32;
        out.pp_optional_extension_names = OPTIONAL_EXTENSIONS.0.as_ptr();
        out.optional_features = DNSR_FEATURE_FLOAT16 | DNSR_FEATURE_PUSH_DESCRIPTOR;
        Ok(DnsrResult::DNSR_SUCCESS)
    })
}

/// The name of a result code ("DNSR_ERROR_NON_FINITE"), or "DNSR_RESULT_UNKNOWN". Static storage.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_result_to_string(result: i32) -> *const c_char {
    use DnsrResult::*;
    let all = [
        DNSR_SUCCESS,
        DNSR_NOT_READY,
        DNSR_ERROR_INVALID_ARGUMENT,
        DNSR_ERROR_INVALID_STRUCTURE,
        DNSR_ERROR_INVALID_HANDLE,
        DNSR_ERROR_NULL_HANDLE,
        DNSR_ERROR_UNSUPPORTED_API_VERSION,
        DNSR_ERROR_MISSING_FEATURE,
        DNSR_ERROR_INVALID_EXTENT,
        DNSR_ERROR_IMAGE_EXTENT_MISMATCH,
        DNSR_ERROR_UNSUPPORTED_FORMAT,
        DNSR_ERROR_UNSUPPORTED_LAYOUT,
        DNSR_ERROR_NON_FINITE,
        DNSR_ERROR_INVALID_RENDER_RECT,
        DNSR_ERROR_INVALID_SETTING,
        DNSR_ERROR_INVALID_LIGHT_INDEX,
        DNSR_ERROR_TIMESTAMPS_UNSUPPORTED,
        DNSR_ERROR_SHADER_INTERFACE,
        DNSR_ERROR_VULKAN,
        DNSR_ERROR_INTERNAL,
        DNSR_ERROR_OUT_OF_DEVICE_MEMORY,
        DNSR_ERROR_INVALID_HOST_SYNC,
        DNSR_ERROR_INVALID_QUEUE_FAMILY,
        DNSR_ERROR_CLASSIFIER_NOT_ENABLED,
        DNSR_ERROR_OUT_OF_HOST_MEMORY,
    ];
    let names: [&'static std::ffi::CStr; 25] = [
        c"DNSR_SUCCESS",
        c"DNSR_NOT_READY",
        c"DNSR_ERROR_INVALID_ARGUMENT",
        c"DNSR_ERROR_INVALID_STRUCTURE",
        c"DNSR_ERROR_INVALID_HANDLE",
        c"DNSR_ERROR_NULL_HANDLE",
        c"DNSR_ERROR_UNSUPPORTED_API_VERSION",
        c"DNSR_ERROR_MISSING_FEATURE",
        c"DNSR_ERROR_INVALID_EXTENT",
        c"DNSR_ERROR_IMAGE_EXTENT_MISMATCH",
        c"DNSR_ERROR_UNSUPPORTED_FORMAT",
        c"DNSR_ERROR_UNSUPPORTED_LAYOUT",
        c"DNSR_ERROR_NON_FINITE",
        c"DNSR_ERROR_INVALID_RENDER_RECT",
        c"DNSR_ERROR_INVALID_SETTING",
        c"DNSR_ERROR_INVALID_LIGHT_INDEX",
        c"DNSR_ERROR_TIMESTAMPS_UNSUPPORTED",
        c"DNSR_ERROR_SHADER_INTERFACE",
        c"DNSR_ERROR_VULKAN",
        c"DNSR_ERROR_INTERNAL",
        c"DNSR_ERROR_OUT_OF_DEVICE_MEMORY",
        c"DNSR_ERROR_INVALID_HOST_SYNC",
        c"DNSR_ERROR_INVALID_QUEUE_FAMILY",
        c"DNSR_ERROR_CLASSIFIER_NOT_ENABLED",
        c"DNSR_ERROR_OUT_OF_HOST_MEMORY",
    ];
    all.iter().position(|&r| r as i32 == result).map_or(c"DNSR_RESULT_UNKNOWN", |i| names[i]).as_ptr()
}

/// Why this thread's most recent dnsr call failed (which field, and why), or "" if it succeeded. Valid until
/// this thread's next dnsr call.
#[unsafe(no_mangle)]
pub extern "C" fn dnsr_last_error_message() -> *const c_char {
    last_error_ptr()
}

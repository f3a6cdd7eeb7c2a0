//! The FidelityFX SDK 1.1.4 shadow-denoiser API (include/ffx/), implemented on dnsr's public C API: an engine that
//! integrated the SDK's denoiser on Vulkan links libdnsr instead and keeps its code. Each export converts the FFX
//! structures and calls `dnsr_context_create` / `dnsr_shadows_record` / `dnsr_context_destroy`, so this layer
//! has no access to dnsr's internals and the native API's validation covers it.
//!
//! Where the SDK trusts its caller (a NULL context, a destroyed one, a missing image), these functions return an
//! error code and set `dnsr_last_error_message`, and never record anything half.

mod capabilities;
mod clip;
mod loader;
mod messages;
mod resources;
pub mod types;

use crate::capi::boundary::set_last_error;
use crate::capi::types::*;
use crate::capi::boundary::CallError;
use crate::capi::{dnsr_context_create, dnsr_context_destroy, dnsr_shadows_record, FfxContextSetting, FFX_NOT_LIVE};
use ash::vk;
use resources::{host_image, ViewRing};
use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Mutex, MutexGuard};
use types::*;

/// An FFX call's failure: its code, and the message (None: the dnsr call that failed has set it already).
struct Failure(FfxErrorCode, Option<String>);

fn fail<T>(code: FfxErrorCode, message: impl Into<String>) -> Result<T, Failure> {
    Err(Failure(code, Some(message.into())))
}

/// The panic boundary of every FFX export: a panic becomes FFX_ERROR_BACKEND_API_ERROR with its message.
fn guard(f: impl FnOnce() -> Result<(), Failure>) -> FfxErrorCode {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(())) => {
            set_last_error("");
            FFX_OK
        }
        Ok(Err(Failure(code, message))) => {
            if let Some(m) = message {
                set_last_error(&m);
            }
            // SAFETY: this thread's last error message, NUL-terminated (just set, or set by the dnsr call that failed).
            messages::error(&unsafe { std::ffi::CStr::from_ptr(crate::capi::boundary::last_error_ptr()) }.to_string_lossy());
            code
        }
        Err(_) => {
            set_last_error("internal error in dnsr's FidelityFX layer (please report)");
            FFX_ERROR_BACKEND_API_ERROR
        }
    }
}

/// A dnsr result as the FFX code an integration checks; the message stays dnsr's.
fn check(result: DnsrResult) -> Result<(), Failure> {
    use DnsrResult::*;
    let code = match result {
        DNSR_SUCCESS => return Ok(()),
        DNSR_ERROR_OUT_OF_DEVICE_MEMORY => FFX_ERROR_OUT_OF_MEMORY,
        DNSR_ERROR_VULKAN | DNSR_ERROR_INTERNAL => FFX_ERROR_BACKEND_API_ERROR,
        _ => FFX_ERROR_INVALID_ARGUMENT,
    };
    Err(Failure(code, None))
}

// ---- The scratch record and the device ----

/// What ffxGetInterfaceVK leaves in the caller's scratch memory for ffxDenoiserContextCreate.
#[repr(C)]
#[derive(Clone, Copy)]
struct Scratch {
    magic: u64,
    device: VkDeviceContext,
}
const SCRATCH_MAGIC: u64 = u64::from_le_bytes(*b"dnsrffx1");

/// The record ffxGetInterfaceVK wrote into `iface`'s scratch buffer.
fn scratch_of(iface: &FfxInterface) -> Result<Scratch, Failure> {
    if iface.functions[FP_GET_SDK_VERSION] != get_sdk_version as *const std::ffi::c_void || iface.scratchBuffer.is_null() {
        return fail(FFX_ERROR_INCOMPLETE_INTERFACE, "backendInterface was not filled by ffxGetInterfaceVK");
    }
    // SAFETY: ffxGetInterfaceVK checked the size and wrote the record (the caller may have moved nothing).
    let scratch = unsafe { (iface.scratchBuffer as *const Scratch).read_unaligned() };
    if scratch.magic != SCRATCH_MAGIC {
        return fail(FFX_ERROR_INCOMPLETE_INTERFACE, "backendInterface.scratchBuffer no longer holds what ffxGetInterfaceVK wrote");
    }
    Ok(scratch)
}

/// The SDK keeps the last ffxGetDeviceVK argument in process-wide storage and hands out its address.
static DEVICE: Mutex<VkDeviceContext> =
    Mutex::new(VkDeviceContext { vkDevice: vk::Device::null(), vkPhysicalDevice: vk::PhysicalDevice::null(), vkDeviceProcAddr: None });

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// ffx_vk.h: bytes of scratch memory ffxGetInterfaceVK needs.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetScratchMemorySizeVK(_physical_device: vk::PhysicalDevice, _max_contexts: usize) -> usize {
    std::mem::size_of::<Scratch>()
}

/// ffx_vk.h: the device as an FfxDevice (a process-wide copy, as in the SDK).
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetDeviceVK(device_context: *mut VkDeviceContext) -> *mut std::ffi::c_void {
    let Some(d) = (unsafe { device_context.as_ref() }) else { return std::ptr::null_mut() };
    let mut stored = lock(&DEVICE);
    *stored = *d;
    &mut *stored as *mut VkDeviceContext as *mut std::ffi::c_void
}

extern "C" fn get_sdk_version(_interface: *mut FfxInterface) -> u32 {
    FFX_SDK_VERSION
}

extern "C" fn register_constant_buffer_allocator(_interface: *mut FfxInterface, _allocator: *const std::ffi::c_void) {}

/// fpGetDeviceCapabilities: the device's, as the SDK's Vulkan backend reports them (capabilities.rs).
extern "C" fn get_device_capabilities(interface: *mut FfxInterface, out: *mut FfxDeviceCapabilities) -> FfxErrorCode {
    guard(|| {
        let Some(out) = (unsafe { out.as_mut() }) else { return fail(FFX_ERROR_INVALID_POINTER, "outDeviceCapabilities is NULL") };
        let Some(interface) = (unsafe { interface.as_ref() }) else { return fail(FFX_ERROR_INVALID_POINTER, "backendInterface is NULL") };
        let scratch = scratch_of(interface)?;
        *out = capabilities::query(scratch.device.vkPhysicalDevice);
        Ok(())
    })
}

/// ffx_vk.h: fills the backend table a context description carries.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetInterfaceVK(
    interface: *mut FfxInterface,
    device: *mut std::ffi::c_void,
    scratch: *mut std::ffi::c_void,
    scratch_size: usize,
    max_contexts: usize,
) -> FfxErrorCode {
    guard(|| {
        let Some(interface) = (unsafe { interface.as_mut() }) else { return fail(FFX_ERROR_INVALID_POINTER, "backendInterface is NULL") };
        let Some(device) = (unsafe { (device as *const VkDeviceContext).as_ref() }) else {
            return fail(FFX_ERROR_INVALID_POINTER, "device is NULL (pass ffxGetDeviceVK(&vkDeviceContext))");
        };
        if scratch.is_null() {
            return fail(FFX_ERROR_INVALID_POINTER, "scratchBuffer is NULL");
        }
        let needed = ffxGetScratchMemorySizeVK(device.vkPhysicalDevice, max_contexts);
        if scratch_size < needed {
            return fail(FFX_ERROR_INSUFFICIENT_MEMORY, format!("scratchBufferSize is {scratch_size}; ffxGetScratchMemorySizeVK says {needed}"));
        }
        if max_contexts == 0 {
            return fail(FFX_ERROR_INVALID_ARGUMENT, "maxContexts is 0");
        }
        // SAFETY: the caller's buffer holds at least `needed` bytes; it may not be aligned.
        unsafe { (scratch as *mut Scratch).write_unaligned(Scratch { magic: SCRATCH_MAGIC, device: *device }) };
        let mut functions = [std::ptr::null(); FFX_INTERFACE_FUNCTIONS];
        functions[FP_GET_SDK_VERSION] = get_sdk_version as *const std::ffi::c_void;
        functions[FP_GET_DEVICE_CAPABILITIES] = get_device_capabilities as *const std::ffi::c_void;
        functions[FP_REGISTER_CONSTANT_BUFFER_ALLOCATOR] = register_constant_buffer_allocator as *const std::ffi::c_void;
        *interface = FfxInterface { functions, scratchBuffer: scratch, scratchBufferSize: scratch_size, device: device as *const _ as *mut _ };
        Ok(())
    })
}

/// ffx_vk.h: a command buffer as an FfxCommandList.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetCommandListVK(command_buffer: vk::CommandBuffer) -> *mut std::ffi::c_void {
    use ash::vk::Handle;
    command_buffer.as_raw() as usize as *mut std::ffi::c_void
}

/// ffx_vk.h: an FfxResource for an image in a state.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetResourceVK(
    vk_resource: *mut std::ffi::c_void,
    description: FfxResourceDescription,
    name: *const libc::wchar_t,
    state: FfxResourceStates,
) -> FfxResource {
    let mut r = FfxResource { resource: vk_resource, description, state, name: [0; FFX_RESOURCE_NAME_SIZE] };
    if !name.is_null() {
        for (i, slot) in r.name.iter_mut().take(FFX_RESOURCE_NAME_SIZE - 1).enumerate() {
            // SAFETY: the caller's name is NUL-terminated; reading stops at the terminator.
            let c = unsafe { *name.add(i) };
            if c == 0 {
                break;
            }
            *slot = c;
        }
    }
    r
}

/// ffx_vk.h: the FfxSurfaceFormat of a VkFormat.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetSurfaceFormatVK(format: vk::Format) -> u32 {
    resources::surface_format(format)
}

/// ffx_vk.h: a buffer's FfxResourceDescription from its create info.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetBufferResourceDescriptionVK(buffer: vk::Buffer, info: vk::BufferCreateInfo<'static>, additional_usages: u32) -> FfxResourceDescription {
    if buffer == vk::Buffer::null() {
        return FfxResourceDescription::default();
    }
    let mut usage = additional_usages;
    if info.usage.contains(vk::BufferUsageFlags::STORAGE_BUFFER) {
        usage |= FFX_RESOURCE_USAGE_UAV;
    }
    if info.usage.contains(vk::BufferUsageFlags::INDIRECT_BUFFER) {
        usage |= FFX_RESOURCE_USAGE_INDIRECT;
    }
    // width is the size, height the stride (0: not a structured buffer), depth the alignment.
    FfxResourceDescription { type_: FFX_RESOURCE_TYPE_BUFFER, width: info.size as u32, usage, ..Default::default() }
}

/// ffx_vk.h: a queue as an FfxCommandQueue.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetCommandQueueVK(queue: vk::Queue) -> *mut std::ffi::c_void {
    use ash::vk::Handle;
    queue.as_raw() as usize as *mut std::ffi::c_void
}

/// ffx_vk.h: a pipeline as an FfxPipeline.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetPipelineVK(pipeline: vk::Pipeline) -> *mut std::ffi::c_void {
    use ash::vk::Handle;
    pipeline.as_raw() as usize as *mut std::ffi::c_void
}

/// ffx_vk.h: an image's FfxResourceDescription from its create info.
#[unsafe(no_mangle)]
pub extern "C" fn ffxGetImageResourceDescriptionVK(image: vk::Image, info: vk::ImageCreateInfo<'static>, additional_usages: u32) -> FfxResourceDescription {
    if image == vk::Image::null() {
        return FfxResourceDescription::default();
    }
    let format = info.format;
    let mut usage = additional_usages;
    if resources::is_depth(format) {
        usage |= FFX_RESOURCE_USAGE_DEPTHTARGET;
    }
    if matches!(format, vk::Format::D16_UNORM_S8_UINT | vk::Format::D24_UNORM_S8_UINT | vk::Format::D32_SFLOAT_S8_UINT | vk::Format::S8_UINT) {
        usage |= FFX_RESOURCE_USAGE_STENCILTARGET;
    }
    if info.usage.contains(vk::ImageUsageFlags::STORAGE) {
        usage |= FFX_RESOURCE_USAGE_UAV;
    }
    let (type_, depth) = match info.image_type {
        vk::ImageType::TYPE_1D => (FFX_RESOURCE_TYPE_TEXTURE1D, info.array_layers),
        vk::ImageType::TYPE_3D => (FFX_RESOURCE_TYPE_TEXTURE3D, info.extent.depth),
        _ if additional_usages & FFX_RESOURCE_USAGE_ARRAYVIEW == 0 && info.flags.contains(vk::ImageCreateFlags::CUBE_COMPATIBLE) => {
            (FFX_RESOURCE_TYPE_TEXTURE_CUBE, info.array_layers)
        }
        _ => (FFX_RESOURCE_TYPE_TEXTURE2D, info.array_layers),
    };
    FfxResourceDescription {
        type_,
        format: resources::surface_format(format),
        width: info.extent.width,
        height: info.extent.height,
        depth,
        mipCount: info.mip_levels,
        flags: 0,
        usage,
    }
}

// ---- Contexts ----

/// One FFX context: the dnsr context it drives and what a dispatch needs besides the description.
struct Denoiser {
    context: DnsrContext,
    device: resources::Device,
    output_format: Option<vk::Format>,
    /// What the description's flags asked for.
    options: Options,
    width: u32,
    height: u32,
    views: ViewRing,
    dispatches: u64,
    /// What `dnsr_ffx_context_set_light` last told of the light (none by default: the FFX dispatch has no light).
    light: FfxLight,
    /// What `dnsr_ffx_context_set_penumbra_guidance` last gave: the hit-distance image and the light's angular
    /// diameter (none by default: the FFX dispatch has no hit distances).
    guidance: Option<(DnsrHostImage, f32)>,
    /// What `dnsr_ffx_context_set_previous_gbuffer` gave for the next dispatch (taken by it): the host's previous
    /// depth and normals.
    previous: Option<(DnsrHostImage, DnsrHostImage)>,
}

/// The light of a context's dispatches (`dnsr_ffx_context_set_light`): DNSR_DISPATCH_HARD_LIGHT and
/// DNSR_DISPATCH_USE_LIGHT_POSITION bits, and the position and angular diameter that the second reads. Checked by
/// the caller.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct FfxLight {
    flags: u32,
    position: [f32; 4],
    angular_size: f32,
}

/// Gives the live context at `context` a setting of its later dispatches, or says why not (no live context there,
/// or one that cannot take the setting). `capi::FFX_SET` for the `dnsr_ffx_context_set_*` functions, which check
/// the setting itself.
fn set(context: *mut std::ffi::c_void, setting: FfxContextSetting) -> Result<(), CallError> {
    let not_live = || CallError::InvalidArgument(FFX_NOT_LIVE.into());
    // SAFETY: the caller's pointer is NULL-checked by capi; a non-NULL one points at an FfxDenoiserContext.
    let context = unsafe { (context as *const FfxDenoiserContext).as_ref() }.ok_or_else(not_live)?;
    let mut contexts = lock(&CONTEXTS);
    let d = contexts.get_mut(&context_id(context)).ok_or_else(not_live)?;
    match setting {
        FfxContextSetting::Light { flags, position, angular_size } => d.light = FfxLight { flags, position, angular_size },
        FfxContextSetting::Guidance(guidance) => d.guidance = guidance,
        FfxContextSetting::PreviousGbuffer { .. } if !d.options.host_previous => {
            return Err(CallError::InvalidArgument(
                "pFfxContext was created without DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER: it keeps last frame's depth and normals itself".into(),
            ));
        }
        FfxContextSetting::PreviousGbuffer { depth, normals } => d.previous = Some((depth, normals)),
    }
    Ok(())
}

// SAFETY: the dnsr context is used behind the registry's lock only.
unsafe impl Send for Denoiser {}

impl Drop for Denoiser {
    fn drop(&mut self) {
        self.views.clear(&self.device);
        dnsr_context_destroy(self.context);
    }
}

/// Live contexts by id; the caller's FfxDenoiserContext holds a magic and the id, so that a context that was never
/// created, or was destroyed, is recognised instead of dereferenced.
static CONTEXTS: Mutex<BTreeMap<u64, Denoiser>> = Mutex::new(BTreeMap::new());
static NEXT_ID: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
const CONTEXT_MAGIC: u32 = u32::from_le_bytes(*b"dnsr");

fn context_id(context: &FfxDenoiserContext) -> u64 {
    if context.data[0] != CONTEXT_MAGIC {
        return 0;
    }
    u64::from(context.data[1]) | (u64::from(context.data[2]) << 32)
}

fn with_context<T>(context: *mut FfxDenoiserContext, f: impl FnOnce(&mut Denoiser) -> Result<T, Failure>) -> Result<T, Failure> {
    let Some(context) = (unsafe { context.as_ref() }) else { return fail(FFX_ERROR_INVALID_POINTER, "context is NULL") };
    match lock(&CONTEXTS).get_mut(&context_id(context)) {
        Some(d) => f(d),
        None => fail(FFX_ERROR_INVALID_ARGUMENT, "context is not a live FfxDenoiserContext (never created, or destroyed)"),
    }
}

/// The dnsr create info for an FFX description: dnsr's default settings (Quality), fp32, one light, R8_UNORM output until a
/// dispatch names another, dnsr's descriptor sets (the FFX interface does not say which extensions are enabled).
fn create_info(device: &resources::Device, width: u32, height: u32, flags: DnsrContextCreateFlags, output: vk::Format) -> DnsrContextCreateInfo {
    DnsrContextCreateInfo {
        s_type: DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO,
        p_next: std::ptr::null(),
        instance: device.instance_placeholder(),
        physical_device: device.physical_device,
        device: device.device,
        vulkan_functions: DnsrVulkanFunctions {
            vk_get_instance_proc_addr: Some(loader::get_instance_proc_addr),
            vk_get_device_proc_addr: Some(device.get_device_proc_addr),
        },
        api_version: vk::API_VERSION_1_1,
        queue_family_index: device.queue_family,
        enabled_features: 0,
        width,
        height,
        flags,
        precision: DNSR_PRECISION_FP32,
        output_format: output,
        light_count: 1,
        max_frames_in_flight: FFX_MAX_QUEUED_FRAMES as u32,
        p_settings: std::ptr::null(),
        p_allocation_callbacks: std::ptr::null(),
        p_gpu_memory_callbacks: std::ptr::null(),
        p_log_callback: std::ptr::null(),
        p_debug_name_callback: std::ptr::null(),
        shader_override_count: 0,
        p_shader_overrides: std::ptr::null(),
        shadow_input: DNSR_SHADOW_INPUT_HIT_MASK,
    }
}

/// What an FFX description's flags ask of the dnsr context behind it.
#[derive(Clone, Copy)]
struct Options {
    /// FFX_DENOISER_ENABLE_DEPTH_INVERTED.
    depth_inverted: bool,
    /// DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS: Preset::Balanced instead of dnsr's default.
    fidelityfx: bool,
    /// DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER.
    host_previous: bool,
}

/// A dnsr context for an FFX context: `create_info`'s, with the options its flags ask for.
fn new_dnsr_context(device: &resources::Device, width: u32, height: u32, options: Options, output: vk::Format) -> Result<DnsrContext, Failure> {
    let settings = crate::capi::convert::settings_to_c(&crate::Settings::preset(crate::Preset::Balanced));
    let flags = (if options.depth_inverted { DNSR_CONTEXT_CREATE_DEPTH_INVERTED } else { 0 })
        | (if options.host_previous { DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER } else { 0 });
    let mut info = create_info(device, width, height, flags, output);
    if options.fidelityfx {
        info.p_settings = &settings;
    }
    let mut context = std::ptr::null_mut();
    check(dnsr_context_create(&info, &mut context))?;
    Ok(context)
}

/// ffx_denoiser.h: creates a shadow denoiser context (a dnsr context with dnsr's default settings, or the FidelityFX
/// ones under DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS).
#[unsafe(no_mangle)]
pub extern "C" fn ffxDenoiserContextCreate(context: *mut FfxDenoiserContext, description: *const FfxDenoiserContextDescription) -> FfxErrorCode {
    guard(|| {
        let Some(out) = (unsafe { context.as_mut() }) else { return fail(FFX_ERROR_INVALID_POINTER, "pContext is NULL") };
        // A second create into a live context would orphan the first (its GPU objects outlive the device).
        if lock(&CONTEXTS).contains_key(&context_id(out)) {
            return fail(FFX_ERROR_INVALID_ARGUMENT, "pContext holds a live context: destroy it first (ffxDenoiserContextDestroy)");
        }
        out.data[0] = 0;
        let Some(d) = (unsafe { description.as_ref() }) else { return fail(FFX_ERROR_INVALID_POINTER, "pContextDescription is NULL") };
        if d.flags & FFX_DENOISER_REFLECTIONS != 0 {
            return fail(FFX_ERROR_INVALID_ARGUMENT, "flags has FFX_DENOISER_REFLECTIONS: dnsr denoises shadows only");
        }
        let scratch = scratch_of(&d.backendInterface)?;
        let (width, height) = (d.windowSize.width, d.windowSize.height);
        if width == 0 || height == 0 {
            return fail(FFX_ERROR_INVALID_ARGUMENT, format!("windowSize is {width}x{height}"));
        }
        let device = resources::Device::new(&scratch.device).map_err(|m| Failure(FFX_ERROR_NULL_DEVICE, Some(m)))?;
        let options = Options {
            depth_inverted: d.flags & FFX_DENOISER_ENABLE_DEPTH_INVERTED != 0,
            fidelityfx: d.flags & DNSR_FFX_CONTEXT_FIDELITYFX_SETTINGS != 0,
            host_previous: d.flags & DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER != 0,
        };
        let dnsr = new_dnsr_context(&device, width, height, options, vk::Format::R8_UNORM)?;
        let id = NEXT_ID.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let denoiser = Denoiser {
            context: dnsr,
            device,
            output_format: None,
            options,
            width,
            height,
            views: ViewRing::default(),
            dispatches: 0,
            light: FfxLight::default(),
            guidance: None,
            previous: None,
        };
        crate::capi::FFX_SET.get_or_init(|| set);
        lock(&CONTEXTS).insert(id, denoiser);
        out.data[1] = id as u32;
        out.data[2] = (id >> 32) as u32;
        out.data[0] = CONTEXT_MAGIC;
        Ok(())
    })
}

/// ffx_denoiser.h: destroys a context.
#[unsafe(no_mangle)]
pub extern "C" fn ffxDenoiserContextDestroy(context: *mut FfxDenoiserContext) -> FfxErrorCode {
    guard(|| {
        let Some(c) = (unsafe { context.as_mut() }) else { return fail(FFX_ERROR_INVALID_POINTER, "context is NULL") };
        let removed = lock(&CONTEXTS).remove(&context_id(c));
        match removed {
            Some(denoiser) => {
                c.data[0] = 0;
                drop(denoiser);
                Ok(())
            }
            None => fail(FFX_ERROR_INVALID_ARGUMENT, "context is not a live FfxDenoiserContext (never created, or destroyed)"),
        }
    })
}

/// ffx_denoiser.h: refused (dnsr has no reflections denoiser).
#[unsafe(no_mangle)]
pub extern "C" fn ffxDenoiserContextDispatchReflections(context: *mut FfxDenoiserContext, _description: *const std::ffi::c_void) -> FfxErrorCode {
    guard(|| with_context(context, |_| fail(FFX_ERROR_INVALID_ARGUMENT, "dnsr has no reflections denoiser")))
}

/// ffx_denoiser.h: the denoiser version SDK 1.1.4 reports (1.3.0).
#[unsafe(no_mangle)]
pub extern "C" fn ffxDenoiserGetEffectVersion() -> u32 {
    FFX_DENOISER_VERSION
}

/// ffx_denoiser.h: records one frame of shadow denoising.
#[unsafe(no_mangle)]
pub extern "C" fn ffxDenoiserContextDispatchShadows(
    context: *mut FfxDenoiserContext,
    description: *const FfxDenoiserShadowsDispatchDescription,
) -> FfxErrorCode {
    guard(|| {
        with_context(context, |denoiser| {
            let Some(d) = (unsafe { description.as_ref() }) else { return fail(FFX_ERROR_INVALID_POINTER, "dispatchDescription is NULL") };
            denoiser.dispatch(d)
        })
    })
}

impl Denoiser {
    fn dispatch(&mut self, d: &FfxDenoiserShadowsDispatchDescription) -> Result<(), Failure> {
        let output_format = resources::view_format(&d.shadowMaskOutput.description)
            .map_err(|m| Failure(FFX_ERROR_INVALID_ARGUMENT, Some(format!("shadowMaskOutput: {m}"))))?;
        match self.output_format {
            Some(f) if f != output_format => {
                return fail(FFX_ERROR_INVALID_ARGUMENT, format!("shadowMaskOutput is {output_format:?}; this context's earlier dispatches wrote {f:?}"));
            }
            None if output_format != vk::Format::R8_UNORM => {
                // Created for R8_UNORM before any dispatch named the output: recreate for this one (its history is
                // empty either way).
                let replacement = new_dnsr_context(&self.device, self.width, self.height, self.options, output_format)?;
                dnsr_context_destroy(self.context);
                self.context = replacement;
            }
            _ => {}
        }
        let views = self.views.begin(&self.device);
        let device = &self.device;
        let mut image = |r: &FfxResource, what: &str| {
            host_image(device, views, r).map_err(|m| Failure(FFX_ERROR_INVALID_ARGUMENT, Some(format!("{what}: {m}"))))
        };
        let (hit_mask, depth, velocity, normals, output) = (
            image(&d.hitMaskResults, "hitMaskResults")?,
            image(&d.depth, "depth")?,
            image(&d.velocity, "velocity")?,
            image(&d.normal, "normal")?,
            image(&d.shadowMaskOutput, "shadowMaskOutput")?,
        );
        // The host's previous depth and normals: given for this dispatch, or (the first, whose history is empty:
        // dnsr reads neither) this frame's in their place.
        let (previous_depth, previous_normals) = match (self.options.host_previous, self.previous) {
            (false, _) => (DnsrHostImage::default(), DnsrHostImage::default()),
            (true, Some(previous)) => previous,
            (true, None) if self.dispatches == 0 => (depth, normals),
            (true, None) => {
                return fail(
                    FFX_ERROR_INVALID_ARGUMENT,
                    "this context was created with DNSR_FFX_CONTEXT_HOST_PREVIOUS_GBUFFER: call dnsr_ffx_context_set_previous_gbuffer before every dispatch but the first",
                );
            }
        };
        // One size for the light, whichever of dnsr_ffx_context_set_light and _set_penumbra_guidance gave it.
        let light_angular_size = match (self.guidance, self.light.flags & DNSR_DISPATCH_USE_LIGHT_POSITION != 0) {
            (Some((_, guided)), true) if guided != self.light.angular_size => {
                return fail(
                    FFX_ERROR_INVALID_ARGUMENT,
                    format!(
                        "the light's angular size differs between dnsr_ffx_context_set_light ({}) and dnsr_ffx_context_set_penumbra_guidance ({guided}): give both the same",
                        self.light.angular_size
                    ),
                );
            }
            (Some((_, guided)), _) => guided,
            (None, true) => self.light.angular_size,
            (None, false) => 0.0,
        };
        let dispatch = DnsrShadowsDispatch {
            s_type: DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH,
            p_next: std::ptr::null(),
            command_buffer: command_buffer(d.commandList),
            light_index: 0,
            flags: (if self.dispatches == 0 { DNSR_DISPATCH_RESET } else { 0 })
                | self.light.flags
                | (if self.guidance.is_some() { DNSR_DISPATCH_USE_HIT_DISTANCE } else { 0 }),
            hit_mask_convention: DNSR_HIT_MASK_OCCLUDED_BITS,
            hit_mask,
            depth,
            velocity,
            normals,
            output,
            motion_vector_scale: d.motionVectorScale,
            normals_unpack_mul: d.normalsUnpackMul,
            normals_unpack_add: d.normalsUnpackAdd,
            eye: d.eye,
            frame_index: d.frameIndex,
            projection_inverse: clip::from_sdk_clip(d.projectionInverse),
            reprojection_matrix: clip::between_sdk_clips(d.reprojectionMatrix),
            view_projection_inverse: clip::from_sdk_clip(d.viewProjectionInverse),
            depth_similarity_sigma: d.depthSimilaritySigma,
            render_rect: DnsrRect::default(),
            // The FFX interface does not say which stages wrote the inputs or read the output: all of them.
            sync: DnsrHostSync {
                input_src_stages: vk::PipelineStageFlags::ALL_COMMANDS,
                input_src_access: vk::AccessFlags::MEMORY_WRITE,
                output_dst_stages: vk::PipelineStageFlags::ALL_COMMANDS,
                output_dst_access: vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE,
            },
            debug_view: DNSR_DEBUG_VIEW_NONE,
            // Nor hit distances: only what dnsr_ffx_context_set_penumbra_guidance gave.
            hit_distance: self.guidance.map_or(DnsrHostImage::default(), |(image, _)| image),
            light_angular_size,
            engine_image_count: 0,
            p_engine_images: std::ptr::null(),
            visibility: DnsrHostImage::default(),
            checkerboard_phase: 0,
            // The FFX dispatch has no light: only what dnsr_ffx_context_set_light gave.
            light_position: self.light.position,
            // The FFX dispatch has no previous depth: only what dnsr_ffx_context_set_previous_gbuffer gave (else the
            // context keeps its own depth copy).
            previous_depth,
            previous_normals,
        };
        check(dnsr_shadows_record(self.context, &dispatch))?;
        self.previous = None;
        self.output_format = Some(output_format);
        self.views.commit();
        self.dispatches += 1;
        Ok(())
    }
}

fn command_buffer(list: *mut std::ffi::c_void) -> vk::CommandBuffer {
    use ash::vk::Handle;
    vk::CommandBuffer::from_raw(list as usize as u64)
}

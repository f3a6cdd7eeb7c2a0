//! The FidelityFX SDK 1.1.4 structures and values an integration of its Vulkan shadow denoiser passes, laid out as
//! the SDK's headers declare them (include/ffx/ has the C declarations; capi-tests/ffx_dropin.cpp checks that both
//! agree on every size and offset). Names keep the SDK's spelling so that the two sides can be compared.
#![allow(non_camel_case_types, non_snake_case, missing_docs)]

use ash::vk;
use std::ffi::c_void;

pub type FfxErrorCode = i32;
pub const FFX_OK: FfxErrorCode = 0;
/// FfxMsgType: an error message.
pub const FFX_MESSAGE_TYPE_ERROR: u32 = 0;
/// FfxShaderModel: the one the Vulkan backend reports (Vulkan has no shader models).
pub const FFX_SHADER_MODEL_5_1: u32 = 0;
pub const FFX_ERROR_INVALID_POINTER: FfxErrorCode = 0x8000_0000u32 as i32;
pub const FFX_ERROR_INVALID_SIZE: FfxErrorCode = 0x8000_0002u32 as i32;
pub const FFX_ERROR_OUT_OF_MEMORY: FfxErrorCode = 0x8000_0007u32 as i32;
pub const FFX_ERROR_INCOMPLETE_INTERFACE: FfxErrorCode = 0x8000_0008u32 as i32;
pub const FFX_ERROR_INVALID_ENUM: FfxErrorCode = 0x8000_0009u32 as i32;
pub const FFX_ERROR_INVALID_ARGUMENT: FfxErrorCode = 0x8000_000Au32 as i32;
pub const FFX_ERROR_NULL_DEVICE: FfxErrorCode = 0x8000_000Cu32 as i32;
pub const FFX_ERROR_BACKEND_API_ERROR: FfxErrorCode = 0x8000_000Du32 as i32;
pub const FFX_ERROR_INSUFFICIENT_MEMORY: FfxErrorCode = 0x8000_000Eu32 as i32;

/// FFX_SDK_MAKE_VERSION: major 10 bits, minor 10 bits, patch 12 bits.
pub const fn make_version(major: u32, minor: u32, patch: u32) -> u32 {
    (major << 22) | (minor << 12) | patch
}
/// What an SDK 1.1.4 integration checks: the SDK's version and the shadow denoiser's.
pub const FFX_SDK_VERSION: u32 = make_version(1, 1, 4);
pub const FFX_DENOISER_VERSION: u32 = make_version(1, 3, 0);

pub const FFX_DENOISER_SHADOWS: u32 = 1 << 0;
pub const FFX_DENOISER_REFLECTIONS: u32 = 1 << 1;
pub const FFX_DENOISER_ENABLE_DEPTH_INVERTED: u32 = 1 << 2;

/// Frames the SDK's backend keeps per-frame objects for (dnsr keeps a dispatch's views that many dispatches).
pub const FFX_MAX_QUEUED_FRAMES: usize = 4;

/// Size of the caller-allocated FfxDenoiserContext, in uint32_t.
pub const FFX_DENOISER_CONTEXT_SIZE: usize = 73098;

pub type FfxResourceStates = u32;
pub const FFX_RESOURCE_STATE_COMMON: FfxResourceStates = 1 << 0;
pub const FFX_RESOURCE_STATE_UNORDERED_ACCESS: FfxResourceStates = 1 << 1;
pub const FFX_RESOURCE_STATE_COMPUTE_READ: FfxResourceStates = 1 << 2;
pub const FFX_RESOURCE_STATE_PIXEL_READ: FfxResourceStates = 1 << 3;
pub const FFX_RESOURCE_STATE_PIXEL_COMPUTE_READ: FfxResourceStates = (1 << 2) | (1 << 3);
pub const FFX_RESOURCE_STATE_COPY_SRC: FfxResourceStates = 1 << 4;
pub const FFX_RESOURCE_STATE_COPY_DEST: FfxResourceStates = 1 << 5;
pub const FFX_RESOURCE_STATE_GENERIC_READ: FfxResourceStates = (1 << 2) | (1 << 4);
pub const FFX_RESOURCE_STATE_INDIRECT_ARGUMENT: FfxResourceStates = 1 << 6;
pub const FFX_RESOURCE_STATE_PRESENT: FfxResourceStates = 1 << 7;
pub const FFX_RESOURCE_STATE_RENDER_TARGET: FfxResourceStates = 1 << 8;
pub const FFX_RESOURCE_STATE_DEPTH_ATTACHEMENT: FfxResourceStates = 1 << 9;

/// FfxResourceUsage bits.
pub const FFX_RESOURCE_USAGE_READ_ONLY: u32 = 0;
pub const FFX_RESOURCE_USAGE_RENDERTARGET: u32 = 1 << 0;
pub const FFX_RESOURCE_USAGE_UAV: u32 = 1 << 1;
pub const FFX_RESOURCE_USAGE_DEPTHTARGET: u32 = 1 << 2;
pub const FFX_RESOURCE_USAGE_INDIRECT: u32 = 1 << 3;
pub const FFX_RESOURCE_USAGE_ARRAYVIEW: u32 = 1 << 4;
pub const FFX_RESOURCE_USAGE_STENCILTARGET: u32 = 1 << 5;

/// FfxResourceType.
pub const FFX_RESOURCE_TYPE_BUFFER: u32 = 0;
pub const FFX_RESOURCE_TYPE_TEXTURE1D: u32 = 1;
pub const FFX_RESOURCE_TYPE_TEXTURE2D: u32 = 2;
pub const FFX_RESOURCE_TYPE_TEXTURE_CUBE: u32 = 3;
pub const FFX_RESOURCE_TYPE_TEXTURE3D: u32 = 4;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FfxDimensions2D {
    pub width: u32,
    pub height: u32,
}

/// The unions (width/size, height/stride, depth/alignment) are one u32 each.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct FfxResourceDescription {
    pub type_: u32,
    pub format: u32,
    pub width: u32,
    pub height: u32,
    pub depth: u32,
    pub mipCount: u32,
    pub flags: u32,
    pub usage: u32,
}

/// wchar_t is 4 bytes on Linux (the SDK's FfxResource is 304 bytes there).
pub const FFX_RESOURCE_NAME_SIZE: usize = 64;

#[repr(C)]
#[derive(Clone, Copy)]
pub struct FfxResource {
    pub resource: *mut c_void,
    pub description: FfxResourceDescription,
    pub state: FfxResourceStates,
    pub name: [libc::wchar_t; FFX_RESOURCE_NAME_SIZE],
}

/// The SDK's backend table: 26 function pointers, then the scratch memory and the device. dnsr fills only
/// fpGetSDKVersion (index 0); its denoiser does not go through the table.
pub const FFX_INTERFACE_FUNCTIONS: usize = 26;
pub const FP_GET_SDK_VERSION: usize = 0;
pub const FP_GET_DEVICE_CAPABILITIES: usize = 3;
pub const FP_REGISTER_CONSTANT_BUFFER_ALLOCATOR: usize = 25;

#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct FfxDeviceCapabilities {
    pub maximumSupportedShaderModel: u32,
    pub waveLaneCountMin: u32,
    pub waveLaneCountMax: u32,
    pub fp16Supported: bool,
    pub raytracingSupported: bool,
    pub deviceCoherentMemorySupported: bool,
    pub dedicatedAllocationSupported: bool,
    pub bufferMarkerSupported: bool,
    pub extendedSynchronizationSupported: bool,
    pub shaderStorageBufferArrayNonUniformIndexing: bool,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct FfxInterface {
    pub functions: [*const c_void; FFX_INTERFACE_FUNCTIONS],
    pub scratchBuffer: *mut c_void,
    pub scratchBufferSize: usize,
    pub device: *mut c_void,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct FfxDenoiserContextDescription {
    pub flags: u32,
    pub windowSize: FfxDimensions2D,
    pub normalsHistoryBufferFormat: u32,
    pub backendInterface: FfxInterface,
}

#[repr(C)]
#[derive(Clone, Copy)]
pub struct FfxDenoiserShadowsDispatchDescription {
    pub commandList: *mut c_void,
    pub hitMaskResults: FfxResource,
    pub depth: FfxResource,
    pub velocity: FfxResource,
    pub normal: FfxResource,
    pub shadowMaskOutput: FfxResource,
    pub motionVectorScale: [f32; 2],
    pub normalsUnpackMul: f32,
    pub normalsUnpackAdd: f32,
    pub eye: [f32; 3],
    pub frameIndex: u32,
    pub projectionInverse: [f32; 16],
    pub reprojectionMatrix: [f32; 16],
    pub viewProjectionInverse: [f32; 16],
    pub depthSimilaritySigma: f32,
}

#[repr(C)]
pub struct FfxDenoiserContext {
    pub data: [u32; FFX_DENOISER_CONTEXT_SIZE],
}

/// ffx_vk.h's device description: what ffxGetDeviceVK turns into an FfxDevice (a pointer to the caller's struct).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct VkDeviceContext {
    pub vkDevice: vk::Device,
    pub vkPhysicalDevice: vk::PhysicalDevice,
    pub vkDeviceProcAddr: Option<vk::PFN_vkGetDeviceProcAddr>,
}

// The SDK's sizes on Linux x86-64 (DESIGN.md, "FidelityFX SDK 1.1.4 interface").
#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
const _: () = {
    assert!(std::mem::size_of::<FfxResourceDescription>() == 32);
    assert!(std::mem::size_of::<FfxDeviceCapabilities>() == 20);
    assert!(std::mem::size_of::<FfxResource>() == 304);
    assert!(std::mem::size_of::<FfxInterface>() == 232);
    assert!(std::mem::size_of::<FfxDenoiserContextDescription>() == 248);
    assert!(std::mem::size_of::<FfxDenoiserShadowsDispatchDescription>() == 1760);
};

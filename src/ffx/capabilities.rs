//! fpGetDeviceCapabilities: the device's capabilities, read the way the SDK's Vulkan backend reads them (SDK 1.1.4:
//! shader model 5.1 and 32 lanes unless the device says more; each other field from the device extension that
//! carries it, and that extension's feature bit where it has one), so an integration that picks its own shader
//! variants from them sees what it saw with the SDK. dnsr itself needs none of them.

use super::loader::symbol;
use super::types::{FfxDeviceCapabilities, FFX_SHADER_MODEL_5_1};
use ash::vk;
use std::ffi::CStr;

/// The loader's export `name` as a function of type F (a Vulkan PFN), or None.
fn function<F: Copy>(name: &CStr) -> Option<F> {
    let f = symbol(name.as_ptr());
    // SAFETY: a non-null loader export of a core Vulkan 1.1 command has that command's type, which F names.
    (!f.is_null()).then(|| unsafe { std::mem::transmute_copy::<*mut std::ffi::c_void, F>(&f) })
}

/// The device extensions `physical` offers.
fn extensions(physical: vk::PhysicalDevice) -> Vec<vk::ExtensionProperties> {
    let Some(enumerate) = function::<vk::PFN_vkEnumerateDeviceExtensionProperties>(c"vkEnumerateDeviceExtensionProperties")
    else {
        return Vec::new();
    };
    let mut count = 0u32;
    // SAFETY: the count query of a valid physical device; the second call fills at most `count` entries.
    unsafe {
        if enumerate(physical, std::ptr::null(), &mut count, std::ptr::null_mut()) != vk::Result::SUCCESS {
            return Vec::new();
        }
        let mut list = vec![vk::ExtensionProperties::default(); count as usize];
        let result = enumerate(physical, std::ptr::null(), &mut count, list.as_mut_ptr());
        if result != vk::Result::SUCCESS && result != vk::Result::INCOMPLETE {
            return Vec::new();
        }
        list.truncate(count as usize);
        list
    }
}

/// Fills `ext`, a structure of physical-device features, for `physical`.
fn feature<T: vk::ExtendsPhysicalDeviceFeatures2>(features2: vk::PFN_vkGetPhysicalDeviceFeatures2, physical: vk::PhysicalDevice, ext: &mut T) {
    let mut f = vk::PhysicalDeviceFeatures2::default().push_next(ext);
    // SAFETY: a valid physical device and a chain of one extending structure.
    unsafe { features2(physical, &mut f) };
}

/// `physical`'s capabilities (the SDK's defaults where it is null or the loader is missing).
pub(super) fn query(physical: vk::PhysicalDevice) -> FfxDeviceCapabilities {
    let mut caps = FfxDeviceCapabilities {
        maximumSupportedShaderModel: FFX_SHADER_MODEL_5_1,
        waveLaneCountMin: 32,
        waveLaneCountMax: 32,
        ..Default::default()
    };
    if physical == vk::PhysicalDevice::null() {
        return caps;
    }
    let (Some(properties2), Some(features2)) = (
        function::<vk::PFN_vkGetPhysicalDeviceProperties2>(c"vkGetPhysicalDeviceProperties2"),
        function::<vk::PFN_vkGetPhysicalDeviceFeatures2>(c"vkGetPhysicalDeviceFeatures2"),
    ) else {
        return caps;
    };
    for e in extensions(physical) {
        let Ok(name) = e.extension_name_as_c_str() else { continue };
        if name == vk::EXT_SUBGROUP_SIZE_CONTROL_NAME {
            let mut sizes = vk::PhysicalDeviceSubgroupSizeControlProperties::default();
            let mut p = vk::PhysicalDeviceProperties2::default().push_next(&mut sizes);
            // SAFETY: as above, for properties.
            unsafe { properties2(physical, &mut p) };
            caps.waveLaneCountMin = sizes.min_subgroup_size;
            caps.waveLaneCountMax = sizes.max_subgroup_size;
        } else if name == vk::KHR_SHADER_FLOAT16_INT8_NAME {
            let mut f = vk::PhysicalDeviceShaderFloat16Int8Features::default();
            feature(features2, physical, &mut f);
            caps.fp16Supported = f.shader_float16 != 0;
        } else if name == vk::KHR_ACCELERATION_STRUCTURE_NAME {
            let mut f = vk::PhysicalDeviceAccelerationStructureFeaturesKHR::default();
            feature(features2, physical, &mut f);
            caps.raytracingSupported = f.acceleration_structure != 0;
        } else if name == vk::AMD_DEVICE_COHERENT_MEMORY_NAME {
            let mut f = vk::PhysicalDeviceCoherentMemoryFeaturesAMD::default();
            feature(features2, physical, &mut f);
            caps.deviceCoherentMemorySupported = f.device_coherent_memory != 0;
        } else if name == vk::KHR_DEDICATED_ALLOCATION_NAME {
            caps.dedicatedAllocationSupported = true;
        } else if name == vk::AMD_BUFFER_MARKER_NAME {
            caps.bufferMarkerSupported = true;
        } else if name == vk::KHR_SYNCHRONIZATION2_NAME {
            let mut f = vk::PhysicalDeviceSynchronization2Features::default();
            feature(features2, physical, &mut f);
            caps.extendedSynchronizationSupported = f.synchronization2 != 0;
        } else if name == vk::EXT_DESCRIPTOR_INDEXING_NAME {
            let mut f = vk::PhysicalDeviceDescriptorIndexingFeatures::default();
            feature(features2, physical, &mut f);
            caps.shaderStorageBufferArrayNonUniformIndexing = f.shader_storage_buffer_array_non_uniform_indexing != 0;
        }
    }
    caps
}

//! Loads every Vulkan function dnsr uses through the host's `vkGetInstanceProcAddr` / `vkGetDeviceProcAddr`.

use crate::error::{Error, Result};
use crate::host::HostHooks;
use ash::vk;
use std::ffi::c_void;

/// The host's Vulkan objects with dnsr's function tables.
pub(crate) struct Vk {
    pub instance: ash::Instance,
    pub device: ash::Device,
    pub physical_device: vk::PhysicalDevice,
    /// `vkCmdPushDescriptorSetKHR`, when the host enabled VK_KHR_push_descriptor.
    pub push_descriptor: Option<ash::khr::push_descriptor::DeviceFn>,
    pub hooks: HostHooks,
    /// Optimal-tiling features of every format dnsr accepts or creates, queried once: validating a dispatch
    /// then makes no driver call.
    format_features: Vec<(vk::Format, vk::FormatFeatureFlags)>,
}

/// What loading takes from the host: its handles and entry points (each checked here), whether it enabled
/// VK_KHR_push_descriptor, and its hooks.
pub(crate) struct HostDevice<'a> {
    pub instance: vk::Instance,
    pub physical_device: vk::PhysicalDevice,
    pub device: vk::Device,
    pub get_instance_proc_addr: Option<vk::PFN_vkGetInstanceProcAddr>,
    pub get_device_proc_addr: Option<vk::PFN_vkGetDeviceProcAddr>,
    pub push_descriptor: bool,
    pub hooks: &'a HostHooks,
}

impl Vk {
    /// Loads the host's device; `formats`: the formats whose features are queried once, here.
    pub(crate) fn load(info: &HostDevice, formats: impl Iterator<Item = vk::Format>) -> Result<Vk> {
        if info.instance == vk::Instance::null() {
            return Err(Error::NullHandle("instance"));
        }
        if info.physical_device == vk::PhysicalDevice::null() {
            return Err(Error::NullHandle("physical_device"));
        }
        if info.device == vk::Device::null() {
            return Err(Error::NullHandle("device"));
        }
        let gipa = info.get_instance_proc_addr.ok_or(Error::NullHandle("get_instance_proc_addr"))?;
        let gdpa = info.get_device_proc_addr.ok_or(Error::NullHandle("get_device_proc_addr"))?;
        let (vk_instance, vk_device) = (info.instance, info.device);
        // SAFETY: the host guarantees the handles are valid and the entry points belong to them.
        let instance = unsafe {
            ash::Instance::load_with(
                |name| std::mem::transmute::<vk::PFN_vkVoidFunction, *const c_void>(gipa(vk_instance, name.as_ptr())),
                vk_instance,
            )
        };
        let load_device = |name: &std::ffi::CStr| unsafe {
            std::mem::transmute::<vk::PFN_vkVoidFunction, *const c_void>(gdpa(vk_device, name.as_ptr()))
        };
        let device = unsafe { ash::Device::load_with(load_device, vk_device) };
        let push_descriptor = if info.push_descriptor {
            if load_device(c"vkCmdPushDescriptorSetKHR").is_null() {
                return Err(Error::MissingFeature(
                    "features.push_descriptor is set but vkCmdPushDescriptorSetKHR is not available on the device",
                ));
            }
            Some(ash::khr::push_descriptor::DeviceFn::load(|name| load_device(name)))
        } else {
            None
        };
        let physical_device = info.physical_device;
        let format_features = formats
            .map(|f| (f, unsafe { instance.get_physical_device_format_properties(physical_device, f) }.optimal_tiling_features))
            .collect();
        Ok(Vk { instance, device, physical_device, push_descriptor, hooks: info.hooks.clone(), format_features })
    }

    /// The host's CPU allocation callbacks, for every create/destroy call.
    pub(crate) fn alloc(&self) -> Option<&vk::AllocationCallbacks<'static>> {
        self.hooks.allocation_callbacks.as_ref()
    }

    /// Hands `name` to the host's debug-name hook (creation time only).
    pub(crate) fn name<H: vk::Handle>(&self, handle: H, name: &str) {
        if let Some(namer) = &self.hooks.debug_names {
            if let Ok(c) = std::ffi::CString::new(name) {
                namer(H::TYPE, handle.as_raw(), &c);
            }
        }
    }

    /// Whether the physical device offers a device extension (creation-time queries only).
    pub(crate) fn supports_extension(&self, name: &std::ffi::CStr) -> bool {
        unsafe { self.instance.enumerate_device_extension_properties(self.physical_device) }
            .map(|exts| exts.iter().any(|e| e.extension_name_as_c_str() == Ok(name)))
            .unwrap_or(false)
    }

    pub(crate) fn format_features(&self, format: vk::Format) -> vk::FormatFeatureFlags {
        match self.format_features.iter().find(|(f, _)| *f == format) {
            Some(&(_, features)) => features,
            None => unsafe { self.instance.get_physical_device_format_properties(self.physical_device, format) }
                .optimal_tiling_features,
        }
    }
}

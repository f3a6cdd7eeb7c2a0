//! FFX resources as dnsr host images: the device functions the layer needs, FfxSurfaceFormat / usage -> VkFormat,
//! FfxResourceStates -> VkImageLayout (the SDK backend's mapping), and the views a dispatch creates.

use super::loader;
use super::types::*;
use crate::capi::types::DnsrHostImage;
use ash::vk;
use ash::vk::Handle;

/// The device an FFX context runs on, with the few functions the layer calls itself.
pub(super) struct Device {
    pub device: vk::Device,
    pub physical_device: vk::PhysicalDevice,
    pub get_device_proc_addr: vk::PFN_vkGetDeviceProcAddr,
    /// A queue family with compute: dnsr checks barrier stages against it (the FFX interface names no queue).
    pub queue_family: u32,
    create_image_view: vk::PFN_vkCreateImageView,
    destroy_image_view: vk::PFN_vkDestroyImageView,
}

impl Device {
    pub fn new(d: &VkDeviceContext) -> Result<Device, String> {
        if d.vkDevice == vk::Device::null() || d.vkPhysicalDevice == vk::PhysicalDevice::null() {
            return Err("the VkDeviceContext given to ffxGetDeviceVK has a null vkDevice or vkPhysicalDevice".into());
        }
        // The SDK takes the loader's vkGetDeviceProcAddr when the context has none.
        let gdpa = match d.vkDeviceProcAddr {
            Some(f) => f,
            None => {
                let f = loader::symbol(c"vkGetDeviceProcAddr".as_ptr());
                if f.is_null() {
                    return Err("VkDeviceContext.vkDeviceProcAddr is NULL and no Vulkan loader is loaded".into());
                }
                // SAFETY: the loader's export of that name has that type.
                unsafe { std::mem::transmute::<*mut std::ffi::c_void, vk::PFN_vkGetDeviceProcAddr>(f) }
            }
        };
        let load = |name: &std::ffi::CStr| unsafe { gdpa(d.vkDevice, name.as_ptr()) }.ok_or_else(|| format!("{name:?} is not available on the device"));
        // SAFETY: vkGetDeviceProcAddr returned these functions for their own names.
        let (create_image_view, destroy_image_view) = unsafe {
            (
                std::mem::transmute::<unsafe extern "system" fn(), vk::PFN_vkCreateImageView>(load(c"vkCreateImageView")?),
                std::mem::transmute::<unsafe extern "system" fn(), vk::PFN_vkDestroyImageView>(load(c"vkDestroyImageView")?),
            )
        };
        let queue_family = compute_queue_family(d.vkPhysicalDevice)?;
        Ok(Device { device: d.vkDevice, physical_device: d.vkPhysicalDevice, get_device_proc_addr: gdpa, queue_family, create_image_view, destroy_image_view })
    }

    /// dnsr wants an instance handle, and hands it only to the vkGetInstanceProcAddr the layer gives it, which
    /// ignores it (loader::get_instance_proc_addr): any non-null value serves.
    pub fn instance_placeholder(&self) -> vk::Instance {
        vk::Instance::from_raw(self.physical_device.as_raw())
    }

    fn destroy_view(&self, view: vk::ImageView) {
        unsafe { (self.destroy_image_view)(self.device, view, std::ptr::null()) };
    }
}

/// The first queue family with graphics and compute, else the first with compute.
fn compute_queue_family(physical_device: vk::PhysicalDevice) -> Result<u32, String> {
    let f = loader::symbol(c"vkGetPhysicalDeviceQueueFamilyProperties".as_ptr());
    if f.is_null() {
        return Err("no Vulkan loader is loaded in this process (vkGetPhysicalDeviceQueueFamilyProperties not found)".into());
    }
    // SAFETY: the loader's export of that name has that type.
    let get: vk::PFN_vkGetPhysicalDeviceQueueFamilyProperties = unsafe { std::mem::transmute(f) };
    let mut count = 0;
    unsafe { get(physical_device, &mut count, std::ptr::null_mut()) };
    let mut families = vec![vk::QueueFamilyProperties::default(); count as usize];
    unsafe { get(physical_device, &mut count, families.as_mut_ptr()) };
    families.truncate(count as usize);
    let has = |q: &vk::QueueFamilyProperties, flags| q.queue_flags.contains(flags);
    families
        .iter()
        .position(|q| has(q, vk::QueueFlags::GRAPHICS | vk::QueueFlags::COMPUTE))
        .or_else(|| families.iter().position(|q| has(q, vk::QueueFlags::COMPUTE)))
        .map(|i| i as u32)
        .ok_or_else(|| "the physical device has no compute queue family".into())
}

/// The VkFormat of an image's view, as the SDK backend derives it (a depth image is described by its colour twin
/// plus the DEPTHTARGET / STENCILTARGET usage bits).
pub(super) fn view_format(d: &FfxResourceDescription) -> Result<vk::Format, String> {
    use vk::Format as F;
    let depth = d.usage & FFX_RESOURCE_USAGE_DEPTHTARGET != 0;
    let stencil = d.usage & FFX_RESOURCE_USAGE_STENCILTARGET != 0;
    let format = match (d.format, depth, stencil) {
        (23, true, true) => F::D16_UNORM_S8_UINT,
        (23, true, false) => F::D16_UNORM,
        (28, true, true) => F::D32_SFLOAT_S8_UINT,
        (28, true, false) => F::D32_SFLOAT,
        (8, true, true) => F::D24_UNORM_S8_UINT,
        (8, true, false) => F::X8_D24_UNORM_PACK32,
        (2, ..) => F::R32G32B32A32_UINT,
        (3, ..) => F::R32G32B32A32_SFLOAT,
        (4, ..) => F::R16G16B16A16_SFLOAT,
        (5, ..) => F::R32G32B32_SFLOAT,
        (6, ..) => F::R32G32_SFLOAT,
        (7, ..) => F::R8_UINT,
        (8, ..) => F::R32_UINT,
        (10, ..) => F::R8G8B8A8_UNORM,
        (11, ..) => F::R8G8B8A8_SNORM,
        (12, ..) => F::R8G8B8A8_SRGB,
        (14, ..) => F::B8G8R8A8_UNORM,
        (15, ..) => F::B8G8R8A8_SRGB,
        (16, ..) => F::B10G11R11_UFLOAT_PACK32,
        (17, ..) => F::A2B10G10R10_UNORM_PACK32,
        (18, ..) => F::R16G16_SFLOAT,
        (19, ..) => F::R16G16_UINT,
        (20, ..) => F::R16G16_SINT,
        (21, ..) => F::R16_SFLOAT,
        (22, ..) => F::R16_UINT,
        (23, ..) => F::R16_UNORM,
        (24, ..) => F::R16_SNORM,
        (25, ..) => F::R8_UNORM,
        (26, ..) => F::R8G8_UNORM,
        (27, ..) => F::R8G8_UINT,
        (28, ..) => F::R32_SFLOAT,
        (29, ..) => F::E5B9G9R9_UFLOAT_PACK32,
        (other, ..) => return Err(format!("format {other} (FfxSurfaceFormat) has no Vulkan format dnsr can view")),
    };
    Ok(format)
}

/// The FfxSurfaceFormat of a VkFormat (ffxGetSurfaceFormatVK): the inverse of `view_format`, depth formats to their
/// colour twins; 0 (UNKNOWN) for the rest.
pub(super) fn surface_format(format: vk::Format) -> u32 {
    use vk::Format as F;
    match format {
        F::D24_UNORM_S8_UINT | F::X8_D24_UNORM_PACK32 => 8,
        F::D16_UNORM | F::D16_UNORM_S8_UINT => 23,
        F::D32_SFLOAT | F::D32_SFLOAT_S8_UINT => 28,
        F::S8_UINT => 7,
        other => (1..=29)
            .find(|&s| view_format(&FfxResourceDescription { format: s, ..Default::default() }) == Ok(other))
            .unwrap_or(0),
    }
}

pub(super) fn is_depth(format: vk::Format) -> bool {
    use vk::Format as F;
    matches!(format, F::D16_UNORM | F::D16_UNORM_S8_UINT | F::D32_SFLOAT | F::D32_SFLOAT_S8_UINT | F::D24_UNORM_S8_UINT | F::X8_D24_UNORM_PACK32)
}

/// The layout an image in `state` is in (the SDK backend's table: exact states only).
fn layout(state: FfxResourceStates) -> Result<vk::ImageLayout, String> {
    Ok(match state {
        FFX_RESOURCE_STATE_COMMON | FFX_RESOURCE_STATE_GENERIC_READ | FFX_RESOURCE_STATE_UNORDERED_ACCESS => vk::ImageLayout::GENERAL,
        FFX_RESOURCE_STATE_COMPUTE_READ | FFX_RESOURCE_STATE_PIXEL_READ | FFX_RESOURCE_STATE_PIXEL_COMPUTE_READ => {
            vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL
        }
        FFX_RESOURCE_STATE_COPY_SRC => vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
        FFX_RESOURCE_STATE_COPY_DEST => vk::ImageLayout::TRANSFER_DST_OPTIMAL,
        FFX_RESOURCE_STATE_RENDER_TARGET => vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
        FFX_RESOURCE_STATE_DEPTH_ATTACHEMENT => vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
        other => return Err(format!("state {other} is not an FfxResourceStates value an image can be read in")),
    })
}

/// A dnsr host image for an FFX image resource, with a new 2D view of mip 0, layer 0 (pushed to `views`).
pub(super) fn host_image(device: &Device, views: &mut Vec<vk::ImageView>, r: &FfxResource) -> Result<DnsrHostImage, String> {
    if r.resource.is_null() {
        return Err("resource is NULL".into());
    }
    let d = &r.description;
    if d.type_ != FFX_RESOURCE_TYPE_TEXTURE2D {
        return Err(format!("description.type is {}; dnsr reads FFX_RESOURCE_TYPE_TEXTURE2D images", d.type_));
    }
    let format = view_format(d)?;
    let layout = layout(r.state)?;
    let image = vk::Image::from_raw(r.resource as usize as u64);
    let aspect = if is_depth(format) { vk::ImageAspectFlags::DEPTH } else { vk::ImageAspectFlags::COLOR };
    let info = vk::ImageViewCreateInfo::default()
        .image(image)
        .view_type(vk::ImageViewType::TYPE_2D)
        .format(format)
        .subresource_range(vk::ImageSubresourceRange { aspect_mask: aspect, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: 1 });
    let mut view = vk::ImageView::null();
    let result = unsafe { (device.create_image_view)(device.device, &info, std::ptr::null(), &mut view) };
    if result != vk::Result::SUCCESS {
        return Err(format!("vkCreateImageView failed ({result:?})"));
    }
    views.push(view);
    Ok(DnsrHostImage { image, view, format, layout, width: d.width, height: d.height })
}

/// The views dispatches created, by dispatch: a dispatch's views are destroyed when the slot comes round again,
/// FFX_MAX_QUEUED_FRAMES dispatches later (by then the GPU has finished with them, as with the SDK's backend).
#[derive(Default)]
pub(super) struct ViewRing {
    slots: [Vec<vk::ImageView>; FFX_MAX_QUEUED_FRAMES + 1],
    next: usize,
}

impl ViewRing {
    /// The slot of the next dispatch, emptied (its views are FFX_MAX_QUEUED_FRAMES dispatches old, or from a
    /// dispatch that failed and recorded nothing).
    pub fn begin(&mut self, device: &Device) -> &mut Vec<vk::ImageView> {
        let slot = &mut self.slots[self.next];
        for view in slot.drain(..) {
            device.destroy_view(view);
        }
        slot
    }

    /// The dispatch recorded: keep its views.
    pub fn commit(&mut self) {
        self.next = (self.next + 1) % self.slots.len();
    }

    pub fn clear(&mut self, device: &Device) {
        for view in self.slots.iter_mut().flat_map(|s| s.drain(..)) {
            device.destroy_view(view);
        }
    }
}

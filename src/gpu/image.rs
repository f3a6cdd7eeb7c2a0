//! dnsr's internal images: device-local, one allocation each, always in GENERAL layout once initialised.

use crate::error::{vk_check, Error, Result};
use crate::gpu::loader::Vk;
use ash::vk;

pub(crate) const INTERNAL_USAGE: vk::ImageUsageFlags = vk::ImageUsageFlags::from_raw(
    vk::ImageUsageFlags::STORAGE.as_raw()
        | vk::ImageUsageFlags::SAMPLED.as_raw()
        | vk::ImageUsageFlags::TRANSFER_SRC.as_raw()
        | vk::ImageUsageFlags::TRANSFER_DST.as_raw(),
);

pub(crate) struct InternalImage {
    pub image: vk::Image,
    pub view: vk::ImageView,
    pub memory: vk::DeviceMemory,
    /// Bytes of device memory bound to the image.
    pub bytes: u64,
}

/// Checks that the device can sample and store `format` with optimal tiling.
pub(crate) fn check_internal_format(vk: &Vk, format: vk::Format) -> Result<()> {
    let need = vk::FormatFeatureFlags::STORAGE_IMAGE | vk::FormatFeatureFlags::SAMPLED_IMAGE;
    if vk.format_features(format).contains(need) { Ok(()) } else { Err(Error::UnsupportedFormat { role: None, format }) }
}

fn memory_type(vk: &Vk, type_bits: u32) -> Result<u32> {
    let props = unsafe { vk.instance.get_physical_device_memory_properties(vk.physical_device) };
    let types = &props.memory_types[..props.memory_type_count as usize];
    let pick = |flags: vk::MemoryPropertyFlags| {
        types.iter().enumerate().position(|(i, t)| type_bits & (1 << i) != 0 && t.property_flags.contains(flags))
    };
    pick(vk::MemoryPropertyFlags::DEVICE_LOCAL)
        .or_else(|| pick(vk::MemoryPropertyFlags::empty()))
        .map(|i| i as u32)
        .ok_or(Error::Vulkan { call: "memory type selection", result: vk::Result::ERROR_OUT_OF_DEVICE_MEMORY })
}

/// Allocates and binds device-local memory for a buffer or image with these requirements.
pub(crate) fn allocate(vk: &Vk, req: vk::MemoryRequirements) -> Result<vk::DeviceMemory> {
    let info = vk::MemoryAllocateInfo::default().allocation_size(req.size).memory_type_index(memory_type(vk, req.memory_type_bits)?);
    vk_check("vkAllocateMemory", unsafe { vk.device.allocate_memory(&info, None) })
}

impl InternalImage {
    pub(crate) fn new(vk: &Vk, format: vk::Format, extent: [u32; 2]) -> Result<InternalImage> {
        let d = &vk.device;
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(format)
            .extent(vk::Extent3D { width: extent[0], height: extent[1], depth: 1 })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(INTERNAL_USAGE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        let image = vk_check("vkCreateImage", unsafe { d.create_image(&info, None) })?;
        let req = unsafe { d.get_image_memory_requirements(image) };
        let mut out =
            InternalImage { image, view: vk::ImageView::null(), memory: vk::DeviceMemory::null(), bytes: req.size };
        let result = (|| {
            out.memory = allocate(vk, req)?;
            vk_check("vkBindImageMemory", unsafe { d.bind_image_memory(image, out.memory, 0) })?;
            let view_info = vk::ImageViewCreateInfo::default()
                .image(image)
                .view_type(vk::ImageViewType::TYPE_2D)
                .format(format)
                .subresource_range(color_range());
            out.view = vk_check("vkCreateImageView", unsafe { d.create_image_view(&view_info, None) })?;
            Ok(())
        })();
        match result {
            Ok(()) => Ok(out),
            Err(e) => {
                out.destroy(d);
                Err(e)
            }
        }
    }

    pub(crate) fn destroy(&mut self, d: &ash::Device) {
        unsafe {
            d.destroy_image_view(self.view, None);
            d.destroy_image(self.image, None);
            d.free_memory(self.memory, None);
        }
        self.view = vk::ImageView::null();
        self.image = vk::Image::null();
        self.memory = vk::DeviceMemory::null();
    }
}

pub(crate) fn color_range() -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange {
        aspect_mask: vk::ImageAspectFlags::COLOR,
        base_mip_level: 0,
        level_count: 1,
        base_array_layer: 0,
        layer_count: 1,
    }
}

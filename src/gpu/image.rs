//! dnsr's internal images: device-local, one allocation each, always in GENERAL layout once initialised.

use crate::error::{vk_check, Error, Result};
use crate::gpu::memory::{self, Memory};
use crate::host::ResourceKind;
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
    /// A second view of the same memory in another format of the same texel size (the state table's
    /// `Resource::shares`), or null.
    pub shared_view: vk::ImageView,
    pub memory: Memory,
    /// Bytes of device memory bound to the image.
    pub bytes: u64,
    /// Tests that write an image's texels need it.
    #[cfg_attr(not(test), allow(dead_code))]
    pub format: vk::Format,
    /// Width and height (a test compares them with the state table).
    #[cfg_attr(not(test), allow(dead_code))]
    pub extent: [u32; 2],
    /// Its contents must survive from one record to the next (state::Lifetime); a test compares it with the state
    /// table.
    #[cfg_attr(not(test), allow(dead_code))]
    pub persistent: bool,
}

/// Checks that the device can sample and store `format` with optimal tiling.
pub(crate) fn check_internal_format(vk: &Vk, format: vk::Format) -> Result<()> {
    let need = vk::FormatFeatureFlags::STORAGE_IMAGE | vk::FormatFeatureFlags::SAMPLED_IMAGE;
    if vk.format_features(format).contains(need) { Ok(()) } else { Err(Error::UnsupportedFormat { role: None, format }) }
}

impl InternalImage {
    /// `persistent`: its contents survive from one record to the next. The others are allocated as
    /// `ResourceKind::TransientImage` where `alias_transient` (the host aliases them), else as `Image`.
    /// `shared_format`: the format of a second view (`shared_view`; the image is then created mutable-format).
    pub(crate) fn new(
        vk: &Vk,
        format: vk::Format,
        extent: [u32; 2],
        name: &str,
        persistent: bool,
        alias_transient: bool,
        shared_format: Option<vk::Format>,
    ) -> Result<InternalImage> {
        let kind = if !persistent && alias_transient { ResourceKind::TransientImage } else { ResourceKind::Image };
        let d = &vk.device;
        let flags = if shared_format.is_some() { vk::ImageCreateFlags::MUTABLE_FORMAT } else { vk::ImageCreateFlags::empty() };
        let info = vk::ImageCreateInfo::default()
            .flags(flags)
            .image_type(vk::ImageType::TYPE_2D)
            .format(format)
            .extent(vk::Extent3D { width: extent[0], height: extent[1], depth: 1 })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(INTERNAL_USAGE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        let image = vk_check("vkCreateImage", unsafe { d.create_image(&info, vk.alloc()) })?;
        let req = unsafe { d.get_image_memory_requirements(image) };
        let mut out = InternalImage {
            image,
            view: vk::ImageView::null(),
            shared_view: vk::ImageView::null(),
            memory: Memory::default(),
            bytes: req.size,
            format,
            extent,
            persistent,
        };
        let result = (|| {
            out.memory = memory::allocate(vk, req, kind)?;
            vk_check("vkBindImageMemory", unsafe { d.bind_image_memory(image, out.memory.memory, out.memory.offset) })?;
            let view = |format| {
                let info = vk::ImageViewCreateInfo::default()
                    .image(image)
                    .view_type(vk::ImageViewType::TYPE_2D)
                    .format(format)
                    .subresource_range(color_range());
                vk_check("vkCreateImageView", unsafe { d.create_image_view(&info, vk.alloc()) })
            };
            out.view = view(format)?;
            if let Some(f) = shared_format {
                out.shared_view = view(f)?;
            }
            Ok(())
        })();
        match result {
            Ok(()) => {
                vk.name(out.image, name);
                vk.name(out.view, name);
                if out.shared_view != vk::ImageView::null() {
                    vk.name(out.shared_view, &format!("{name}.shared"));
                }
                Ok(out)
            }
            Err(e) => {
                out.destroy(vk);
                Err(e)
            }
        }
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        unsafe {
            vk.device.destroy_image_view(self.shared_view, vk.alloc());
            vk.device.destroy_image_view(self.view, vk.alloc());
            vk.device.destroy_image(self.image, vk.alloc());
        }
        memory::free(vk, &mut self.memory);
        self.view = vk::ImageView::null();
        self.shared_view = vk::ImageView::null();
        self.image = vk::Image::null();
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

//! Checks of a dispatch before anything is recorded. Each failure names the field and the reason.

use crate::dispatch::{HostImage, Rect, ShadowsDispatch};
use crate::error::{Error, ImageRole, Result};
use crate::gpu::loader::Vk;
use ash::vk;
use vk::Format as F;
use vk::ImageLayout as L;

const DEPTH_FORMATS: &[F] = &[
    F::D32_SFLOAT,
    F::D16_UNORM,
    F::X8_D24_UNORM_PACK32,
    F::D24_UNORM_S8_UINT,
    F::D32_SFLOAT_S8_UINT,
    F::D16_UNORM_S8_UINT,
    F::R32_SFLOAT,
    F::R16_SFLOAT,
    F::R16_UNORM,
];
const VELOCITY_FORMATS: &[F] =
    &[F::R16G16_SFLOAT, F::R32G32_SFLOAT, F::R16G16_SNORM, F::R16G16B16A16_SFLOAT, F::R32G32B32A32_SFLOAT];
const NORMAL_FORMATS: &[F] = &[
    F::R8G8B8A8_UNORM,
    F::R8G8B8A8_SNORM,
    F::B8G8R8A8_UNORM,
    F::A2B10G10R10_UNORM_PACK32,
    F::A2R10G10B10_UNORM_PACK32,
    F::B10G11R11_UFLOAT_PACK32,
    F::R16G16B16A16_SFLOAT,
    F::R16G16B16A16_UNORM,
    F::R16G16B16A16_SNORM,
    F::R32G32B32A32_SFLOAT,
];
/// Output formats with a compiled final-pass variant.
pub(crate) const OUTPUT_FORMATS: &[F] = &[F::R8_UNORM, F::R16_SFLOAT, F::R32_SFLOAT];

const SAMPLED_LAYOUTS: &[L] = &[L::GENERAL, L::SHADER_READ_ONLY_OPTIMAL, L::READ_ONLY_OPTIMAL];
const DEPTH_LAYOUTS: &[L] = &[
    L::GENERAL,
    L::SHADER_READ_ONLY_OPTIMAL,
    L::READ_ONLY_OPTIMAL,
    L::DEPTH_STENCIL_READ_ONLY_OPTIMAL,
    L::DEPTH_READ_ONLY_OPTIMAL,
    L::DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL,
];
/// The output is written in GENERAL; other layouts are transitioned there and back.
const OUTPUT_LAYOUTS: &[L] = &[L::GENERAL, L::SHADER_READ_ONLY_OPTIMAL, L::READ_ONLY_OPTIMAL, L::TRANSFER_SRC_OPTIMAL];

/// Checks a render size against the device limit.
pub(crate) fn extent(what: &'static str, width: u32, height: u32, limit: u32) -> Result<()> {
    if width == 0 || height == 0 {
        return Err(Error::ZeroExtent { what });
    }
    if width > limit || height > limit {
        return Err(Error::ExtentTooLarge { what, extent: [width, height], limit });
    }
    Ok(())
}

fn host_image(
    vk: &Vk,
    role: ImageRole,
    img: &HostImage,
    formats: &[F],
    layouts: &[L],
    expected: [u32; 2],
    feature: vk::FormatFeatureFlags,
) -> Result<()> {
    let name = match role {
        ImageRole::HitMask => ("hit_mask.image", "hit_mask.view"),
        ImageRole::Depth => ("depth.image", "depth.view"),
        ImageRole::Velocity => ("velocity.image", "velocity.view"),
        ImageRole::Normals => ("normals.image", "normals.view"),
        ImageRole::Output => ("output.image", "output.view"),
    };
    if img.image == vk::Image::null() {
        return Err(Error::NullHandle(name.0));
    }
    if img.view == vk::ImageView::null() {
        return Err(Error::NullHandle(name.1));
    }
    if !formats.contains(&img.format) || !vk.format_features(img.format).contains(feature) {
        return Err(Error::UnsupportedFormat { role: Some(role), format: img.format });
    }
    if !layouts.contains(&img.layout) {
        return Err(Error::UnsupportedLayout { role, layout: img.layout });
    }
    if [img.width, img.height] != expected {
        return Err(Error::ImageExtentMismatch { role, actual: [img.width, img.height], expected });
    }
    Ok(())
}

fn finite_mat(what: &'static str, m: &glam::Mat4) -> Result<()> {
    if m.is_finite() { Ok(()) } else { Err(Error::NonFinite(what)) }
}

/// Validates a dispatch for a context of `size` writing `output_format`; returns the effective render rect.
pub(crate) fn dispatch(vk: &Vk, d: &ShadowsDispatch, size: [u32; 2], output_format: F, lights: u32) -> Result<Rect> {
    if d.light_index >= lights {
        return Err(Error::InvalidLightIndex { index: d.light_index, count: lights });
    }
    let sampled = vk::FormatFeatureFlags::SAMPLED_IMAGE;
    let tiles = [size[0].div_ceil(8), size[1].div_ceil(4)];
    host_image(vk, ImageRole::HitMask, &d.hit_mask, &[F::R32_UINT], SAMPLED_LAYOUTS, tiles, sampled)?;
    host_image(vk, ImageRole::Depth, &d.depth, DEPTH_FORMATS, DEPTH_LAYOUTS, size, sampled)?;
    host_image(vk, ImageRole::Velocity, &d.velocity, VELOCITY_FORMATS, SAMPLED_LAYOUTS, size, sampled)?;
    host_image(vk, ImageRole::Normals, &d.normals, NORMAL_FORMATS, SAMPLED_LAYOUTS, size, sampled)?;
    if d.output.format != output_format && d.output.view != vk::ImageView::null() && d.output.image != vk::Image::null() {
        return Err(Error::OutputFormatMismatch { declared: d.output.format, context: output_format });
    }
    host_image(vk, ImageRole::Output, &d.output, &[output_format], OUTPUT_LAYOUTS, size, vk::FormatFeatureFlags::STORAGE_IMAGE)?;

    finite_mat("projection_inverse", &d.projection_inverse)?;
    finite_mat("reprojection_matrix", &d.reprojection_matrix)?;
    finite_mat("view_projection_inverse", &d.view_projection_inverse)?;
    if !d.eye.is_finite() {
        return Err(Error::NonFinite("eye"));
    }
    if !d.motion_vector_scale.is_finite() {
        return Err(Error::NonFinite("motion_vector_scale"));
    }
    if !d.normals_unpack_mul.is_finite() || !d.normals_unpack_add.is_finite() {
        return Err(Error::NonFinite("normals_unpack_mul/add"));
    }
    if !(d.depth_similarity_sigma.is_finite() && d.depth_similarity_sigma > 0.0) {
        return Err(Error::InvalidSetting { name: "depth_similarity_sigma", range: "finite and > 0" });
    }
    let rect = d.render_rect.unwrap_or(Rect { x: 0, y: 0, width: size[0], height: size[1] });
    if rect.width == 0 || rect.height == 0 {
        return Err(Error::InvalidRenderRect { reason: "zero width or height" });
    }
    if rect.x % 8 != 0 || rect.y % 4 != 0 {
        return Err(Error::InvalidRenderRect { reason: "x must be a multiple of 8 and y of 4 (tile grid)" });
    }
    if rect.x as u64 + rect.width as u64 > size[0] as u64 || rect.y as u64 + rect.height as u64 > size[1] as u64 {
        return Err(Error::InvalidRenderRect { reason: "reaches outside the render size" });
    }
    Ok(rect)
}

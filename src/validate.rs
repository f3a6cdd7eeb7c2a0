//! Checks of a dispatch before anything is recorded. Each failure names the field and the reason.

use crate::create_info::{ShadowInput, MAX_FRAMES_IN_FLIGHT, MAX_LIGHT_COUNT};
use crate::dispatch::{HostImage, HostSync, Rect, ShadowsDispatch};
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
const HIT_DISTANCE_FORMATS: &[F] = &[F::R16_SFLOAT, F::R32_SFLOAT];
const VISIBILITY_FORMATS: &[F] = &[F::R8_UNORM, F::R16_UNORM, F::R16_SFLOAT, F::R32_SFLOAT];
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
pub(crate) const OUTPUT_FORMATS: &[F] = &[F::R8_UNORM, F::R16_SFLOAT, F::R32_SFLOAT, F::R8G8B8A8_UNORM, F::R16G16B16A16_SFLOAT];

/// Every format a host image may have or dnsr creates (their features are queried once per context).
pub(crate) fn known_formats() -> impl Iterator<Item = F> {
    use crate::create_info::Precision;
    let internal = crate::state::formats(Precision::Fp32).chain(crate::state::formats(Precision::Fp16));
    [DEPTH_FORMATS, VELOCITY_FORMATS, NORMAL_FORMATS, OUTPUT_FORMATS, &[F::R32_UINT]]
        .into_iter()
        .flatten()
        .copied()
        .chain(internal)
}

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
        ImageRole::HitDistance => ("hit_distance.image", "hit_distance.view"),
        ImageRole::Visibility => ("visibility.image", "visibility.view"),
        ImageRole::PreviousDepth => ("previous_depth.image", "previous_depth.view"),
        ImageRole::PreviousNormals => ("previous_normals.image", "previous_normals.view"),
        ImageRole::Cascade => ("cascade_array.image", "cascade_array.view"),
    };
    if img.image == vk::Image::null() {
        return Err(Error::NullHandle(name.0));
    }
    if img.view == vk::ImageView::null() {
        return Err(Error::NullHandle(name.1));
    }
    // An empty list: any format the device supports for `feature` (the engine's callbacks decode it).
    let listed = formats.is_empty() || formats.contains(&img.format);
    if !listed || !vk.format_features(img.format).contains(feature) {
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

/// A frame's camera and decoding constants, which a dispatch and the CPU reference's frame info both carry.
pub(crate) struct Camera<'a> {
    pub projection_inverse: &'a glam::Mat4,
    pub reprojection_matrix: &'a glam::Mat4,
    pub view_projection_inverse: &'a glam::Mat4,
    pub eye: glam::Vec3,
    pub motion_vector_scale: glam::Vec2,
    pub normals_unpack: [f32; 2],
    pub depth_similarity_sigma: f32,
}

impl<'a> Camera<'a> {
    /// A dispatch's.
    pub fn of(d: &'a ShadowsDispatch) -> Camera<'a> {
        Camera {
            projection_inverse: &d.projection_inverse,
            reprojection_matrix: &d.reprojection_matrix,
            view_projection_inverse: &d.view_projection_inverse,
            eye: d.eye,
            motion_vector_scale: d.motion_vector_scale,
            normals_unpack: [d.normals_unpack_mul, d.normals_unpack_add],
            depth_similarity_sigma: d.depth_similarity_sigma,
        }
    }
}

/// Checks a frame's camera constants (the GPU dispatch and the CPU reference alike): finite, and a depth sigma > 0.
pub(crate) fn camera(c: &Camera) -> Result<()> {
    finite_mat("projection_inverse", c.projection_inverse)?;
    finite_mat("reprojection_matrix", c.reprojection_matrix)?;
    finite_mat("view_projection_inverse", c.view_projection_inverse)?;
    if !c.eye.is_finite() {
        return Err(Error::NonFinite("eye"));
    }
    if !c.motion_vector_scale.is_finite() {
        return Err(Error::NonFinite("motion_vector_scale"));
    }
    if !c.normals_unpack.iter().all(|v| v.is_finite()) {
        return Err(Error::NonFinite("normals_unpack_mul/add"));
    }
    if !c.depth_similarity_sigma.is_finite() {
        return Err(Error::NonFinite("depth_similarity_sigma"));
    }
    if c.depth_similarity_sigma <= 0.0 {
        return Err(Error::InvalidValue {
            field: "depth_similarity_sigma",
            value: c.depth_similarity_sigma.to_string(),
            allowed: "it must be > 0 (a linear-depth distance in view-space units, FidelityFX default 1)",
        });
    }
    Ok(())
}

/// What a context accepts in its dispatches.
pub(crate) struct DispatchRules {
    pub size: [u32; 2],
    pub output_format: F,
    pub lights: u32,
    pub supported_stages: vk::PipelineStageFlags,
    /// The context runs engine-compiled variants, whose callbacks decode the G-buffer, so its depth, velocity,
    /// normals and hit distances may have any format the device can sample.
    pub engine_reads: bool,
    pub shadow_input: ShadowInput,
    /// `ContextCreateInfo::host_previous_gbuffer`: the dispatch gives last frame's depth and normals.
    pub host_previous: bool,
}

/// The shadow input a context does not take is left null, so that a dispatch meant for another context (or a
/// field filled by mistake) is not silently ignored.
fn unused_input(img: &HostImage, field: &'static str, allowed: &'static str) -> Result<()> {
    if img.image != vk::Image::null() || img.view != vk::ImageView::null() {
        return Err(Error::InvalidValue { field, value: "given".into(), allowed });
    }
    Ok(())
}

/// The formats a G-buffer image may have: dnsr's `formats`, or any (an empty list) when the engine's callbacks
/// decode it.
fn decoded_formats(engine_decodes: bool, formats: &'static [F]) -> &'static [F] {
    if engine_decodes { &[] } else { formats }
}

/// Validates a dispatch for a context with `rules`; returns the effective render rect.
pub(crate) fn dispatch(vk: &Vk, d: &ShadowsDispatch, rules: &DispatchRules) -> Result<Rect> {
    let DispatchRules { size, output_format, lights, supported_stages, engine_reads, shadow_input, host_previous } = *rules;
    let decoded = |formats| decoded_formats(engine_reads, formats);
    if d.light_index >= lights {
        return Err(Error::InvalidLightIndex { index: d.light_index, count: lights });
    }
    let sampled = vk::FormatFeatureFlags::SAMPLED_IMAGE;
    let tiles = [size[0].div_ceil(8), size[1].div_ceil(4)];
    match shadow_input {
        ShadowInput::HitMask | ShadowInput::Checkerboard => {
            host_image(vk, ImageRole::HitMask, &d.hit_mask, &[F::R32_UINT], SAMPLED_LAYOUTS, tiles, sampled)?;
            unused_input(&d.visibility, "visibility", "leave it null: the context takes a hit mask (ShadowInput::HitMask or Checkerboard)")?;
        }
        ShadowInput::Visibility => {
            host_image(vk, ImageRole::Visibility, &d.visibility, decoded(VISIBILITY_FORMATS), SAMPLED_LAYOUTS, size, sampled)?;
            unused_input(&d.hit_mask, "hit_mask", "leave it null: the context takes per-pixel visibility (ShadowInput::Visibility)")?;
        }
    }
    let phases = if shadow_input == ShadowInput::Checkerboard { 0..=1 } else { 0..=0 };
    if !phases.contains(&d.checkerboard_phase) {
        return Err(Error::InvalidValue {
            field: "checkerboard_phase",
            value: d.checkerboard_phase.to_string(),
            allowed: if shadow_input == ShadowInput::Checkerboard {
                "it must be 0 or 1: the pixels with (x + y) % 2 == phase were traced this frame"
            } else {
                "leave it 0: the context does not take a checkerboard input (ShadowInput::Checkerboard)"
            },
        });
    }
    host_image(vk, ImageRole::Depth, &d.depth, decoded(DEPTH_FORMATS), DEPTH_LAYOUTS, size, sampled)?;
    host_image(vk, ImageRole::Velocity, &d.velocity, decoded(VELOCITY_FORMATS), SAMPLED_LAYOUTS, size, sampled)?;
    host_image(vk, ImageRole::Normals, &d.normals, decoded(NORMAL_FORMATS), SAMPLED_LAYOUTS, size, sampled)?;
    if host_previous {
        host_image(vk, ImageRole::PreviousDepth, &d.previous_depth, decoded(DEPTH_FORMATS), DEPTH_LAYOUTS, size, sampled)?;
        host_image(vk, ImageRole::PreviousNormals, &d.previous_normals, decoded(NORMAL_FORMATS), SAMPLED_LAYOUTS, size, sampled)?;
    } else {
        let own = "leave it null: dnsr keeps last frame's depth and normals itself unless the context was created with host_previous_gbuffer (DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER)";
        unused_input(&d.previous_depth, "previous_depth", own)?;
        unused_input(&d.previous_normals, "previous_normals", own)?;
    }
    if d.output.format != output_format && d.output.view != vk::ImageView::null() && d.output.image != vk::Image::null() {
        return Err(Error::OutputFormatMismatch { declared: d.output.format, context: output_format });
    }
    host_image(vk, ImageRole::Output, &d.output, &[output_format], OUTPUT_LAYOUTS, size, vk::FormatFeatureFlags::STORAGE_IMAGE)?;
    if let Some(hit_distance) = &d.hit_distance {
        host_image(vk, ImageRole::HitDistance, hit_distance, decoded(HIT_DISTANCE_FORMATS), SAMPLED_LAYOUTS, size, sampled)?;
    }
    // The light's size is read with either.
    if d.hit_distance.is_some() || d.light_position.is_some() {
        light_angular_size(d.light_angular_size)?;
        if d.hard_light {
            hard_light_size(d.light_angular_size)?;
        }
    }

    if let Some(light) = d.light_position {
        light_position(light)?;
    }
    camera(&Camera::of(d))?;
    host_sync(&d.sync, supported_stages)?;
    let rect = render_rect(d.render_rect, size)?;
    // Relations between fields, once each field is known to be usable.
    if let Some(role) = input_images(d).find(|(_, img)| *img == d.output.image).map(|(role, _)| role) {
        return Err(Error::InvalidValue {
            field: "output",
            value: format!("the {} image", role.field()),
            allowed: "an image of its own: dnsr writes the output while its passes read the inputs",
        });
    }
    Ok(rect)
}

/// The effective render rectangle: `rect` or the whole render size, on the tile grid and inside it.
fn render_rect(rect: Option<Rect>, size: [u32; 2]) -> Result<Rect> {
    let rect = rect.unwrap_or(Rect { x: 0, y: 0, width: size[0], height: size[1] });
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

/// Validates a classify dispatch for a context of render size `size`; returns the effective render rect.
/// A classify dispatch; `engine_decodes`: the variant it runs is an engine's, which decodes depth and normals of
/// any sampled format.
pub(crate) fn classify(vk: &Vk, d: &crate::passes::classify::ClassifyDispatch, size: [u32; 2], supported_stages: vk::PipelineStageFlags, engine_decodes: bool) -> Result<Rect> {
    use crate::passes::classify::{CLASSIFY_TAP_COUNTS, MAX_CASCADES};
    let sampled = vk::FormatFeatureFlags::SAMPLED_IMAGE;
    let tiles = [size[0].div_ceil(8), size[1].div_ceil(4)];
    let decoded = |formats| decoded_formats(engine_decodes, formats);
    host_image(vk, ImageRole::Depth, &d.depth, decoded(DEPTH_FORMATS), DEPTH_LAYOUTS, size, sampled)?;
    host_image(vk, ImageRole::Normals, &d.normals, decoded(NORMAL_FORMATS), SAMPLED_LAYOUTS, size, sampled)?;
    host_image(vk, ImageRole::HitMask, &d.hit_mask, &[F::R32_UINT], &[L::GENERAL], tiles, vk::FormatFeatureFlags::STORAGE_IMAGE)?;
    let invalid = |field: &'static str, value: String, allowed: &'static str| Err(Error::InvalidValue { field, value, allowed });
    if !(1..=MAX_CASCADES as u32).contains(&d.cascade_count) {
        return invalid(
            "cascade_count",
            d.cascade_count.to_string(),
            "it must be in [1, 4]: the classifier decides pixels from the shadow-map cascades, so it needs at least one",
        );
    }
    const NAMES: [[&str; 3]; MAX_CASCADES] = [
        ["cascade_images[0].image", "cascade_images[0].view", "cascades[0].world_to_shadow"],
        ["cascade_images[1].image", "cascade_images[1].view", "cascades[1].world_to_shadow"],
        ["cascade_images[2].image", "cascade_images[2].view", "cascades[2].world_to_shadow"],
        ["cascade_images[3].image", "cascade_images[3].view", "cascades[3].world_to_shadow"],
    ];
    for (i, [image, view, matrix]) in NAMES.iter().enumerate().take(d.cascade_count as usize) {
        let m = &d.cascades[i].world_to_shadow;
        finite_mat(matrix, m)?;
        if m.row(3) != glam::Vec4::W {
            return invalid(matrix, format!("a last row of {:?}", m.row(3).to_array()), "it must be affine (last row 0, 0, 0, 1): an orthographic sun cascade");
        }
        if d.cascade_array.is_none() {
            let img = &d.cascade_images[i];
            if img.image == vk::Image::null() {
                return Err(Error::NullHandle(image));
            }
            if img.view == vk::ImageView::null() {
                return Err(Error::NullHandle(view));
            }
            cascade_image(vk, img)?;
        }
    }
    if let Some(array) = &d.cascade_array {
        host_image(vk, ImageRole::Cascade, array, DEPTH_FORMATS, DEPTH_LAYOUTS, [array.width, array.height], sampled)?;
        cascade_image(vk, array)?;
        if d.cascade_array_layers < d.cascade_count {
            return invalid(
                "cascade_array_layers",
                d.cascade_array_layers.to_string(),
                "the array view needs a layer per cascade (at least cascade_count)",
            );
        }
        if d.cascade_images.iter().any(|c| c.image != vk::Image::null() || c.view != vk::ImageView::null()) {
            return invalid("cascade_images", "given".into(), "leave them null when cascade_array is given");
        }
    }
    if !CLASSIFY_TAP_COUNTS.contains(&d.tap_count) {
        return invalid("tap_count", d.tap_count.to_string(), "it must be 8, 16, 24 or 32 (blocker-search taps per pixel)");
    }
    if d.tile_cutoff > 31 {
        return invalid("tile_cutoff", d.tile_cutoff.to_string(), "it must be in [0, 31]: a tile is listed with more pixels to trace than this");
    }
    finite_mat("view_projection_inverse", &d.view_projection_inverse)?;
    finite_mat("projection_inverse", &d.projection_inverse)?;
    if !d.light_direction.is_finite() {
        return Err(Error::NonFinite("light_direction"));
    }
    if !d.light_direction.length_squared().is_normal() {
        return invalid("light_direction", format!("{:?}", d.light_direction.to_array()), "a direction toward the light of non-zero length");
    }
    light_angular_size(d.light_angular_size)?;
    if !d.blocker_offset.is_finite() {
        return Err(Error::NonFinite("blocker_offset"));
    }
    if d.blocker_offset < 0.0 {
        return invalid("blocker_offset", d.blocker_offset.to_string(), "it must be >= 0 (world units along the light direction)");
    }
    if !d.normals_unpack_mul.is_finite() || !d.normals_unpack_add.is_finite() {
        return Err(Error::NonFinite("normals_unpack_mul/add"));
    }
    host_sync(&d.sync, supported_stages)?;
    render_rect(d.render_rect, size)
}

/// A cascade's shadow map: a depth format the device samples, a depth or shader read-only layout, not empty.
fn cascade_image(vk: &Vk, img: &HostImage) -> Result<()> {
    if !DEPTH_FORMATS.contains(&img.format) || !vk.format_features(img.format).contains(vk::FormatFeatureFlags::SAMPLED_IMAGE) {
        return Err(Error::UnsupportedFormat { role: Some(ImageRole::Cascade), format: img.format });
    }
    if !DEPTH_LAYOUTS.contains(&img.layout) {
        return Err(Error::UnsupportedLayout { role: ImageRole::Cascade, layout: img.layout });
    }
    if img.width == 0 || img.height == 0 {
        return Err(Error::ZeroExtent { what: "cascade image" });
    }
    Ok(())
}

/// The host images a dispatch reads, by role (null ones included).
fn input_images(d: &ShadowsDispatch) -> impl Iterator<Item = (ImageRole, vk::Image)> + '_ {
    [
        (ImageRole::HitMask, d.hit_mask.image),
        (ImageRole::Visibility, d.visibility.image),
        (ImageRole::Depth, d.depth.image),
        (ImageRole::Velocity, d.velocity.image),
        (ImageRole::Normals, d.normals.image),
        (ImageRole::PreviousDepth, d.previous_depth.image),
        (ImageRole::PreviousNormals, d.previous_normals.image),
    ]
    .into_iter()
    .chain(d.hit_distance.map(|h| (ImageRole::HitDistance, h.image)))
}

/// Checks what `record_lights` adds to the single-light rules: 1..=MAX_LIGHTS_PER_RECORD lights, each light and
/// each output once, and the shared dispatch's per-light fields left at their defaults (a value there would
/// otherwise be silently ignored). Each light's own fields are checked as a single dispatch's.
pub(crate) fn light_list(shared: &ShadowsDispatch, lights: &[crate::dispatch::LightDispatch]) -> Result<()> {
    if lights.is_empty() || lights.len() > crate::dispatch::MAX_LIGHTS_PER_RECORD {
        return Err(Error::InvalidValue {
            field: "lights",
            value: format!("{} lights", lights.len()),
            allowed: "one record_lights call takes 1 to 8 lights (MAX_LIGHTS_PER_RECORD)",
        });
    }
    // The camera is the shared dispatch's: an error in it is not one light's.
    camera(&Camera::of(shared))?;
    let per_light = "leave it at its default in the shared dispatch of record_lights: each LightDispatch gives its own";
    unused_input(&shared.hit_mask, "hit_mask", per_light)?;
    unused_input(&shared.visibility, "visibility", per_light)?;
    unused_input(&shared.output, "output", per_light)?;
    let scalars = [
        ("light_index", shared.light_index != 0, shared.light_index.to_string()),
        ("hit_distance", shared.hit_distance.is_some(), "given".into()),
        ("light_angular_size", shared.light_angular_size != 0.0, shared.light_angular_size.to_string()),
        ("hard_light", shared.hard_light, "true".into()),
        ("light_position", shared.light_position.is_some(), "given".into()),
        ("reset", shared.reset, "true".into()),
    ];
    if let Some((field, _, value)) = scalars.into_iter().find(|s| s.1) {
        return Err(Error::InvalidValue { field, value, allowed: per_light });
    }
    for (i, l) in lights.iter().enumerate() {
        let earlier = &lights[..i];
        let refuse = |field, value: String, allowed| Err(Error::Light { position: i as u32, error: Box::new(Error::InvalidValue { field, value, allowed }) });
        if let Some(j) = earlier.iter().position(|e| e.light_index == l.light_index) {
            return refuse("light_index", format!("{} (as lights[{j}])", l.light_index), "each light at most once per record_lights call");
        }
        if let Some(j) = earlier.iter().position(|e| e.output.image == l.output.image && l.output.image != vk::Image::null()) {
            return refuse("output", format!("the image of lights[{j}]"), "every light writes its own output image");
        }
        // Another light's input (its own are checked with the rest of its dispatch).
        let read_by = |o: &crate::dispatch::LightDispatch| input_images(&o.apply(shared)).any(|(_, img)| img == l.output.image);
        let own = l.output.image != vk::Image::null();
        if let Some(j) = (0..lights.len()).find(|&j| own && j != i && read_by(&lights[j])) {
            return refuse("output", format!("an input image of lights[{j}]"), "every light writes an image no light reads");
        }
    }
    Ok(())
}

/// Checks one engine image at `binding` that an engine-compiled variant declares as a sampled or (`storage`) a
/// storage image: given, with a view, in a layout its descriptor type can be used in.
pub(crate) fn engine_image(binding: u32, storage: bool, image: Option<crate::dispatch::EngineImage>) -> Result<()> {
    let invalid = |value: String, allowed: &'static str| Err(Error::InvalidValue { field: "engine_images", value, allowed });
    let layouts: &[L] = if storage { &[L::GENERAL] } else { SAMPLED_LAYOUTS };
    match image {
        None => invalid(
            format!("no image at binding {binding}"),
            "an image for every engine binding the shader overrides of this frame's passes declare",
        ),
        Some(e) if e.view == vk::ImageView::null() => invalid(format!("binding {binding}: null view"), "a 2D view"),
        Some(e) if !layouts.contains(&e.layout) => invalid(
            format!("binding {binding} ({}) in layout {:?}", if storage { "storage" } else { "sampled" }, e.layout),
            "GENERAL, SHADER_READ_ONLY_OPTIMAL or READ_ONLY_OPTIMAL for a sampled image; GENERAL for a storage image",
        ),
        Some(_) => Ok(()),
    }
}

/// Checks the light's angular diameter of penumbra guidance (radians).
pub(crate) fn light_angular_size(angle: f32) -> Result<()> {
    if !angle.is_finite() {
        return Err(Error::NonFinite("light_angular_size"));
    }
    if !(0.0..std::f32::consts::PI).contains(&angle) {
        return Err(Error::InvalidValue {
            field: "light_angular_size",
            value: angle.to_string(),
            allowed: "it must be in [0, pi): the light's angular diameter in radians (the sun: about 0.0093)",
        });
    }
    Ok(())
}

/// Checks a light's homogeneous world-space position (`ShadowsDispatch::light_position`): finite, w 0 (a direction,
/// then of non-zero length) or 1 (a point).
pub(crate) fn light_position(light: glam::Vec4) -> Result<()> {
    if !light.is_finite() {
        return Err(Error::NonFinite("light_position"));
    }
    let allowed = match light.w {
        0.0 if !light.truncate().length_squared().is_normal() => "a direction toward the light (w 0) of non-zero length",
        0.0 | 1.0 => return Ok(()),
        _ => "w 0 (xyz: the direction toward a directional light) or w 1 (xyz: a point light's centre)",
    };
    Err(Error::InvalidValue { field: "light_position", value: format!("{:?}", light.to_array()), allowed })
}

/// Checks the angular size that penumbra guidance gives a light the host calls hard (`hard_light`): 0.
pub(crate) fn hard_light_size(angle: f32) -> Result<()> {
    if angle != 0.0 {
        return Err(Error::InvalidValue {
            field: "light_angular_size",
            value: angle.to_string(),
            allowed: "0 with hard_light: a light of no size has angular size 0",
        });
    }
    Ok(())
}

/// Checks `ContextCreateInfo::light_count` (and the C argument of the same name).
pub(crate) fn light_count(count: u32) -> Result<()> {
    if (1..=MAX_LIGHT_COUNT).contains(&count) {
        return Ok(());
    }
    Err(Error::InvalidValue { field: "light_count", value: count.to_string(), allowed: "it must be in [1, 64] (MAX_LIGHT_COUNT)" })
}

/// Checks `ContextCreateInfo::max_frames_in_flight`.
pub(crate) fn frames_in_flight(count: u32) -> Result<()> {
    if (1..=MAX_FRAMES_IN_FLIGHT).contains(&count) {
        return Ok(());
    }
    Err(Error::InvalidValue {
        field: "max_frames_in_flight",
        value: count.to_string(),
        allowed: "it must be in [1, 16] (MAX_FRAMES_IN_FLIGHT)",
    })
}

/// The declared API version must be a real Vulkan version (variant 0) between dnsr's minimum and what the
/// device supports (patch levels ignored).
pub(crate) fn api_version(declared: u32, device: u32, minimum: u32) -> Result<()> {
    let major_minor = |v: u32| (vk::api_version_major(v), vk::api_version_minor(v));
    let usable = vk::api_version_variant(declared) == 0
        && major_minor(declared) >= major_minor(minimum)
        && major_minor(declared) <= major_minor(device);
    if usable { Ok(()) } else { Err(Error::UnsupportedApiVersion { declared, required: minimum, device }) }
}

/// The capabilities of the queue family dnsr records for; it must exist and run compute work.
pub(crate) fn queue_family(vk: &Vk, index: u32) -> Result<vk::QueueFamilyProperties> {
    let families = unsafe { vk.instance.get_physical_device_queue_family_properties(vk.physical_device) };
    let family = families.get(index as usize).ok_or(Error::InvalidQueueFamily {
        index,
        reason: "the physical device has no queue family with this index",
    })?;
    if !family.queue_flags.contains(vk::QueueFlags::COMPUTE) {
        return Err(Error::InvalidQueueFamily { index, reason: "the queue family does not support compute" });
    }
    Ok(*family)
}

type S = vk::PipelineStageFlags;
type A = vk::AccessFlags;

/// Every Vulkan 1.0 pipeline stage bit, plus the ray-tracing shader stage that writes most hit masks.
const KNOWN_STAGES: S = S::from_raw(0x1_FFFF | S::RAY_TRACING_SHADER_KHR.as_raw());
/// Every Vulkan 1.0 access bit.
const KNOWN_ACCESS: A = A::from_raw(0x1_FFFF);
const SHADER_STAGES: S = S::from_raw(
    S::VERTEX_SHADER.as_raw()
        | S::TESSELLATION_CONTROL_SHADER.as_raw()
        | S::TESSELLATION_EVALUATION_SHADER.as_raw()
        | S::GEOMETRY_SHADER.as_raw()
        | S::FRAGMENT_SHADER.as_raw()
        | S::COMPUTE_SHADER.as_raw()
        | S::RAY_TRACING_SHADER_KHR.as_raw(),
);
/// The stages of a graphics pipeline: its shader stages and its fixed-function ones.
const GRAPHICS_STAGES: S = S::from_raw(
    (SHADER_STAGES.as_raw() & !(S::COMPUTE_SHADER.as_raw() | S::RAY_TRACING_SHADER_KHR.as_raw()))
        | S::DRAW_INDIRECT.as_raw()
        | S::VERTEX_INPUT.as_raw()
        | S::EARLY_FRAGMENT_TESTS.as_raw()
        | S::LATE_FRAGMENT_TESTS.as_raw()
        | S::COLOR_ATTACHMENT_OUTPUT.as_raw(),
);

/// The stages that can perform `access` (Vulkan's "supported access types" table, synchronization 1).
fn stages_for(access: A) -> S {
    match access {
        A::INDIRECT_COMMAND_READ => S::DRAW_INDIRECT,
        A::INDEX_READ | A::VERTEX_ATTRIBUTE_READ => S::VERTEX_INPUT,
        A::UNIFORM_READ | A::SHADER_READ | A::SHADER_WRITE => SHADER_STAGES,
        A::INPUT_ATTACHMENT_READ => S::FRAGMENT_SHADER,
        A::COLOR_ATTACHMENT_READ | A::COLOR_ATTACHMENT_WRITE => S::COLOR_ATTACHMENT_OUTPUT,
        A::DEPTH_STENCIL_ATTACHMENT_READ | A::DEPTH_STENCIL_ATTACHMENT_WRITE => {
            S::EARLY_FRAGMENT_TESTS | S::LATE_FRAGMENT_TESTS
        }
        A::TRANSFER_READ | A::TRANSFER_WRITE => S::TRANSFER,
        A::HOST_READ | A::HOST_WRITE => S::HOST,
        // MEMORY_READ / MEMORY_WRITE: any stage that does work.
        _ => KNOWN_STAGES & !(S::TOP_OF_PIPE | S::BOTTOM_OF_PIPE),
    }
}

/// The stages `HostSync` may name on this device and queue family.
pub(crate) fn supported_stages(vk: &Vk, family: &vk::QueueFamilyProperties) -> S {
    let features = unsafe { vk.instance.get_physical_device_features(vk.physical_device) };
    let mut stages = KNOWN_STAGES;
    if features.geometry_shader == 0 {
        stages &= !S::GEOMETRY_SHADER;
    }
    if features.tessellation_shader == 0 {
        stages &= !(S::TESSELLATION_CONTROL_SHADER | S::TESSELLATION_EVALUATION_SHADER);
    }
    if !vk.supports_extension(ash::khr::ray_tracing_pipeline::NAME) {
        stages &= !S::RAY_TRACING_SHADER_KHR;
    }
    if !family.queue_flags.contains(vk::QueueFlags::GRAPHICS) {
        stages &= !(GRAPHICS_STAGES | S::ALL_GRAPHICS);
    }
    stages
}

/// What `stages` expand to for the access check (ALL_COMMANDS / ALL_GRAPHICS stand for their members).
fn expand(stages: S, supported: S) -> S {
    let mut s = stages;
    if s.contains(S::ALL_COMMANDS) {
        s |= supported;
    }
    if s.contains(S::ALL_GRAPHICS) {
        s |= GRAPHICS_STAGES & supported;
    }
    s
}

fn stage_access_pair(stage_field: &'static str, stages: S, access_field: &'static str, access: A, supported: S) -> Result<()> {
    let bad = |field, reason: String| Err(Error::InvalidHostSync { field, reason });
    let unknown = stages & !KNOWN_STAGES;
    if !unknown.is_empty() {
        return bad(stage_field, format!("unknown pipeline stage bits 0x{:x}", unknown.as_raw()));
    }
    let unsupported = stages & !supported;
    if !unsupported.is_empty() {
        return bad(
            stage_field,
            format!("{unsupported:?} is not supported by this device and queue family (or not a stage dnsr accepts)"),
        );
    }
    let unknown = access & !KNOWN_ACCESS;
    if !unknown.is_empty() {
        return bad(access_field, format!("unknown access bits 0x{:x}", unknown.as_raw()));
    }
    if !access.is_empty() && stages.is_empty() {
        return bad(access_field, format!("{access:?} is given but {stage_field} is empty"));
    }
    let expanded = expand(stages, supported);
    for bit in (0..32).map(|i| A::from_raw(1 << i)).filter(|&b| access.contains(b)) {
        if (stages_for(bit) & expanded).is_empty() {
            return bad(access_field, format!("{bit:?} is not performed by any stage in {stage_field} ({stages:?})"));
        }
    }
    Ok(())
}

/// Checks that dnsr can put the host's stages and accesses into its two barriers.
pub(crate) fn host_sync(sync: &HostSync, supported: S) -> Result<()> {
    stage_access_pair("input_src_stages", sync.input_src_stages, "input_src_access", sync.input_src_access, supported)?;
    stage_access_pair("output_dst_stages", sync.output_dst_stages, "output_dst_access", sync.output_dst_access, supported)
}

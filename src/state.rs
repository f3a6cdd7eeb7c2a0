//! The image table of one light: every internal image's format, size, name and lifetime, and the byte counts that
//! follow from them. Plain data: light.rs creates the images from it.

use crate::create_info::{Precision, ShadowInput};
use crate::settings::MAX_FILTER_PASSES;
use ash::vk;

pub(crate) const TILE_FORMAT: vk::Format = vk::Format::R32_UINT;
pub(crate) const DEPTH_FORMAT: vk::Format = vk::Format::R32_SFLOAT;
/// Per tile: the blocker distance of penumbra guidance.
pub(crate) const TILE_BLOCKER_FORMAT: vk::Format = vk::Format::R32_SFLOAT;
/// Per pixel: mean (unorm16), sum of squared deviations and sample count (float16), run of identical samples
/// (int16), packed into two words (shaders/dnsr_storage.glsl, src/reference/storage.rs).
pub(crate) const MOMENTS_FORMAT: vk::Format = vk::Format::R32G32_UINT;
/// The filter's geometry per pixel (linear depth as float32, -1 for sky; octahedral unit normal, 2 x snorm16): one
/// texel per tap for the passes after the first instead of a depth and a normal fetch, each decoded again.
pub(crate) const GUIDE_FORMAT: vk::Format = vk::Format::R32G32_UINT;
// A context without a guide binds a light's moments in its place (Context::frame_views): same format.
const _: () = assert!(GUIDE_FORMAT.as_raw() == MOMENTS_FORMAT.as_raw());

/// The filter's signal (mean, variance) between passes and as history: R16G16_UNORM in the fp32 path (the mean,
/// and the standard deviation over `signal_scale`: shaders/dnsr_storage.glsl), float16 in the fp16 path.
pub(crate) fn intermediate_format(precision: Precision) -> vk::Format {
    match precision {
        Precision::Fp32 => vk::Format::R16G16_UNORM,
        Precision::Fp16 => vk::Format::R16G16_SFLOAT,
    }
}

/// Largest unorm16 code a stored signal's deviation takes: a device's unorm write may round to either neighbouring
/// code, so real values stay far from the sky's code 65535. Generated into GLSL.
pub(crate) const SIGNAL_MAX_DEVIATION_CODE: u32 = 65000;
/// A stored deviation above this code is the sky's (variance -1). Generated into GLSL.
pub(crate) const SIGNAL_SKY_CODE_ABOVE: u32 = 65500;

/// The standard deviation a stored signal's code 1.0 stands for: the variance boost multiplies a variance of at
/// most 0.5 (an unbiased estimate of 0/1 samples) by up to `variance_boost_samples`.
pub(crate) fn signal_scale(variance_boost_samples: f32) -> f32 {
    (0.5 * variance_boost_samples.max(1.0)).sqrt()
}

/// Images of a light that only some filter pass counts use, allocated when the settings first need them (and kept
/// when they no longer do).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Optional {
    /// Fourth-pass intermediate: four passes.
    Tmp,
}

impl Optional {
    pub(crate) fn needed(self, filter_passes: u32) -> bool {
        match self {
            Optional::Tmp => filter_passes == MAX_FILTER_PASSES,
        }
    }

    pub(crate) fn spec(self, precision: Precision) -> (vk::Format, &'static str) {
        match self {
            Optional::Tmp => (intermediate_format(precision), "filter_tmp"),
        }
    }
}

pub(crate) const OPTIONAL: [Optional; 1] = [Optional::Tmp];

/// The filter's guide is the same for every light (the G-buffer's linear depth and normal), so a context holds one,
/// written by each light's first filter pass where its later passes read it: two or more passes need it.
pub(crate) fn guide_needed(filter_passes: u32) -> bool {
    filter_passes > 1
}

/// The visibility prepare reconstructs from a checkerboard input.
pub(crate) const RECONSTRUCTED_FORMAT: vk::Format = vk::Format::R32_SFLOAT;

/// Bytes of one texel of the internal formats.
fn format_bytes(format: vk::Format) -> u64 {
    match format {
        vk::Format::R32G32B32A32_SFLOAT => 16,
        vk::Format::R32G32_SFLOAT | vk::Format::R32G32_UINT => 8,
        _ => 4, // R32_UINT, R32_SFLOAT, R16G16_SFLOAT
    }
}

/// Texel bytes a light's shadow input adds: the reconstructed visibility of a checkerboard input.
pub(crate) fn input_bytes(extent: [u32; 2], input: ShadowInput) -> u64 {
    let texels = extent[0] as u64 * extent[1] as u64;
    if input == ShadowInput::Checkerboard { format_bytes(RECONSTRUCTED_FORMAT) * texels } else { 0 }
}

/// Texel bytes of the context's guide (none with one filter pass).
pub(crate) fn guide_bytes(extent: [u32; 2], filter_passes: u32) -> u64 {
    if guide_needed(filter_passes) { format_bytes(GUIDE_FORMAT) * extent[0] as u64 * extent[1] as u64 } else { 0 }
}

/// Whether an image's contents must survive from one record of its light to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Lifetime {
    /// Read by a later frame: the moments, the depth copy (both halves of each ping-pong pair: the next frame reads
    /// the half this one wrote) and the history.
    Persistent,
    /// Written and read within one record (tile state, the temporal result, the filter's intermediates, the guide,
    /// the reconstructed visibility): its contents between records do not matter.
    Transient,
}

/// One internal image of a light: format, size, debug name, lifetime.
pub(crate) type ImageSpec = (vk::Format, [u32; 2], &'static str, Lifetime);

/// Every internal image of one light that `filter_passes` passes use, in the order `LightState::new` consumes
/// them (the optional ones last).
pub(crate) fn image_specs(extent: [u32; 2], precision: Precision, filter_passes: u32) -> impl Iterator<Item = ImageSpec> {
    use Lifetime::*;
    let tiles = [extent[0].div_ceil(8), extent[1].div_ceil(4)];
    let rg = intermediate_format(precision);
    let fixed: [ImageSpec; FIXED_IMAGES] = [
        (TILE_FORMAT, tiles, "tile_mask", Transient),
        (TILE_FORMAT, tiles, "tile_dark", Transient),
        (TILE_FORMAT, tiles, "tile_meta", Transient),
        (TILE_BLOCKER_FORMAT, tiles, "tile_blocker", Transient),
        (rg, extent, "reprojection", Transient),
        (rg, extent, "history", Persistent),
        (DEPTH_FORMAT, extent, "depth_copy_0", Persistent),
        (DEPTH_FORMAT, extent, "depth_copy_1", Persistent),
        (MOMENTS_FORMAT, extent, "moments_0", Persistent),
        (MOMENTS_FORMAT, extent, "moments_1", Persistent),
    ];
    fixed.into_iter().chain(OPTIONAL.into_iter().filter(move |o| o.needed(filter_passes)).map(move |o| {
        let (format, name) = o.spec(precision);
        (format, extent, name, Transient)
    }))
}

/// Texel bytes of the internal images of one light, before any driver padding or alignment.
pub(crate) fn texel_bytes(extent: [u32; 2], precision: Precision, filter_passes: u32) -> u64 {
    image_specs(extent, precision, filter_passes).map(spec_bytes).sum()
}

/// Texel bytes of one light's persistent images (`Lifetime::Persistent`); the guide and every other image of a
/// context are transient.
pub(crate) fn persistent_texel_bytes(extent: [u32; 2], precision: Precision) -> u64 {
    image_specs(extent, precision, 1).filter(|s| s.3 == Lifetime::Persistent).map(spec_bytes).sum()
}

fn spec_bytes((format, [w, h], _, _): ImageSpec) -> u64 {
    format_bytes(format) * w as u64 * h as u64
}

/// Images every light has (`image_specs`).
const FIXED_IMAGES: usize = 10;

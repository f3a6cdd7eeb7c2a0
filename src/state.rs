//! The state of a context as data: the table of its internal images and of the passes' accesses to them
//! (`table`), and what follows from it: the images a light and a context create, their byte counts, the formats to
//! check. Plain data: light.rs and context.rs create the images from it.

pub mod table;
#[cfg(test)]
pub(crate) mod tests;

use crate::create_info::{Precision, ShadowInput};
use ash::vk;
pub(crate) use table::Lifetime;
use table::{format_bytes, resource_of, Image, Per, Resource, Scope, RESOURCES};

/// The moments' format with shadow input `input` (packed: src/reference/storage.rs), for tests that read and write
/// them.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) fn moments_format(input: ShadowInput) -> vk::Format {
    resource_of(Image::Moments).format_for(Precision::Fp32, input)
}

/// The filter's signal (mean, variance) between passes (`table::Image::Signal`'s format: every intermediate of the
/// filter has it), for tests that read it.
#[cfg(test)]
pub(crate) fn intermediate_format(precision: Precision) -> vk::Format {
    resource_of(Image::Signal).format.get(precision)
}

/// The history's format (the signal's mean alone), for tests that read it.
#[cfg(test)]
pub(crate) fn history_format(precision: Precision) -> vk::Format {
    resource_of(Image::History).format.get(precision)
}

/// Largest unorm16 code a stored signal's deviation takes: a device's unorm write may round to either neighbouring
/// code, so real values stay far from the sky's code 65535. Generated into GLSL.
pub(crate) const SIGNAL_MAX_DEVIATION_CODE: u32 = 65000;
/// A stored deviation above this code is the sky's (variance -1). Generated into GLSL.
pub(crate) const SIGNAL_SKY_CODE_ABOVE: u32 = 65500;
/// The code a final receiver's deviation is stored as (variance -2: its value is exact, and the filter passes it
/// through and leaves it out of its neighbours' taps); halfway between the largest deviation and the sky's code, so
/// that a unorm write's rounding keeps the three apart. Generated into GLSL.
pub(crate) const SIGNAL_FINAL_CODE: u32 = 65250;
/// A stored deviation above this code (and not above `SIGNAL_SKY_CODE_ABOVE`) is a final receiver's. Generated into GLSL.
pub(crate) const SIGNAL_FINAL_CODE_ABOVE: u32 = 65125;
const _: () = assert!(SIGNAL_MAX_DEVIATION_CODE < SIGNAL_FINAL_CODE_ABOVE && SIGNAL_FINAL_CODE_ABOVE < SIGNAL_FINAL_CODE);
const _: () = assert!(SIGNAL_FINAL_CODE < SIGNAL_SKY_CODE_ABOVE);
/// The depth copy's depth code: its word's low this many bits; the normal takes the rest
/// (`DEPTH_COPY_NORMAL_BITS` a component). Generated into GLSL.
pub(crate) const DEPTH_CODE_BITS: u32 = 16;
const _: () = assert!(DEPTH_CODE_BITS + 2 * DEPTH_COPY_NORMAL_BITS == 32);
/// The depth code's largest value.
pub(crate) const DEPTH_CODE_MAX: u32 = (1 << DEPTH_CODE_BITS) - 1;
/// The depth copy's depth code: code 0 is no receiver; code c > 0 is a float without sign bit, 6 exponent and
/// `DEPTH_CODE_MANTISSA_BITS` mantissa bits, whose smallest exponent is 2^-DEPTH_CODE_BELOW_ONE_OCTAVES: the linear
/// depth of float32 bits (c + DEPTH_CODE_OFFSET) << DEPTH_CODE_SHIFT. Its 64 octaves (2^-16 to 2^48) hold 1024
/// codes each (docs/performance.md, "depth copy"). Generated into GLSL.
pub(crate) const DEPTH_CODE_MANTISSA_BITS: u32 = 10;
/// See `DEPTH_CODE_MANTISSA_BITS`.
pub(crate) const DEPTH_CODE_BELOW_ONE_OCTAVES: u32 = 16;
/// Octaves the depth code spans: 2 to the power of its exponent bits.
pub(crate) const DEPTH_CODE_OCTAVES: u32 = 1 << (DEPTH_CODE_BITS - DEPTH_CODE_MANTISSA_BITS);
/// The float32 bits a depth code drops. Generated into GLSL.
pub(crate) const DEPTH_CODE_SHIFT: u32 = 23 - DEPTH_CODE_MANTISSA_BITS;
/// Float32 bits >> DEPTH_CODE_SHIFT of the depth code 0's value, 2^-DEPTH_CODE_BELOW_ONE_OCTAVES. Generated into GLSL.
pub(crate) const DEPTH_CODE_OFFSET: u32 = (127 - DEPTH_CODE_BELOW_ONE_OCTAVES) << DEPTH_CODE_MANTISSA_BITS;
const _: () = assert!(DEPTH_CODE_OCTAVES == 64 && DEPTH_CODE_OFFSET == 113_664);
/// The depth copy's normal (its word's high bits): octahedral, this many bits a component, within about 1 degree:
/// enough to tell a turned surface (below) and for the later filter passes' normal edge stop. Generated into GLSL.
pub(crate) const DEPTH_COPY_NORMAL_BITS: u32 = 8;
/// A history texel whose surface's normal turned from this pixel's by more than acos(this / 100) (37 degrees) since
/// last frame holds another surface: it leaves the history footprint (docs/do-no-harm.md, "normal-agreeing
/// footprint": 37 and 60 degrees measured alike; faces meet at creases near 90). Generated into GLSL.
pub(crate) const TURNED_NORMAL_COS_PERCENT: u32 = 80;
/// A receiver lies inside a plane (classification's test of normal-mapped normals, `dnsr_plane_normal`) where its
/// neighbours on either side along each axis lie on one line through it: the squared cosine between the two steps at
/// least this / 100 (about 8 degrees). Generated into GLSL.
pub(crate) const PLANE_LINE_COS2_PERCENT: u32 = 98;
/// A history texel of this surface lies within the disocclusion test's depth range widened, per pixel of distance
/// from the history position, by this percentage of what a plane at the surface's angle to the view changes over
/// a pixel: 100 let thin fins over the ground keep the ground's history (seed 1040), 0 rejected grazing ground's
/// own texels (docs/do-no-harm.md, "Footprint texels at this depth"). Generated into GLSL.
pub(crate) const FOOTPRINT_SLOPE_PERCENT: u32 = 50;
/// The largest tan of the surface's angle to the view that the widening takes (86 degrees; beyond, the same).
/// Generated into GLSL.
pub(crate) const FOOTPRINT_MAX_SLOPE: u32 = 16;

/// The standard deviation a stored signal's code 1.0 stands for: the variance boost multiplies a variance of at
/// most 0.5 (an unbiased estimate of 0/1 samples) by up to `variance_boost_samples`.
pub(crate) fn signal_scale(variance_boost_samples: f32) -> f32 {
    (0.5 * variance_boost_samples.max(1.0)).sqrt()
}

/// Every persistent image is a light's and always allocated (`persistent_texel_bytes` relies on it).
const _: () = {
    let mut i = 0;
    while i < RESOURCES.len() {
        let r = &RESOURCES[i];
        assert!(!matches!(r.lifetime, Lifetime::Persistent) || (matches!(r.needed, table::Needed::Always) && matches!(r.scope, Scope::Light)));
        i += 1;
    }
};

/// One internal image to create: which row and copy of the table, format, size, lifetime.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ImageSpec {
    pub image: Image,
    /// Which half of a ping-pong pair (0 otherwise).
    pub copy: u32,
    pub format: vk::Format,
    pub extent: [u32; 2],
    pub lifetime: Lifetime,
    /// The format of a second view of its memory: the row that shares it (`Resource::shares`), or None.
    pub shared_format: Option<vk::Format>,
}

impl ImageSpec {
    /// Its debug name after `dnsr.light{n}.` (a transient image: `dnsr.lights.` where the lights share one set;
    /// `dnsr.` for a context's): `history`, `depth_copy_1`.
    pub(crate) fn name(&self) -> String {
        let r = resource_of(self.image);
        if r.copies > 1 { format!("{}_{}", r.name, self.copy) } else { r.name.to_string() }
    }
}

/// The size of an image of `per` for a render size `extent`.
pub(crate) fn image_extent(per: Per, extent: [u32; 2]) -> [u32; 2] {
    let tile = crate::packing::TILE;
    match per {
        Per::Pixel => extent,
        Per::Tile => [extent[0].div_ceil(tile[0]), extent[1].div_ceil(tile[1])],
    }
}

fn specs_of(r: &'static Resource, extent: [u32; 2], precision: Precision, input: ShadowInput) -> impl Iterator<Item = ImageSpec> {
    // A row that shares this one's memory (needed whenever this one is: a shared row's other image is always
    // allocated) gives it a second view.
    let shared_format = RESOURCES
        .iter()
        .find(|s| s.needed.holds(input) && s.shared_with(precision, input) == Some(r.image))
        .map(|s| s.format_for(precision, input));
    (0..r.copies).map(move |copy| ImageSpec {
        image: r.image,
        copy,
        format: r.format_for(precision, input),
        extent: image_extent(r.per, extent),
        lifetime: r.lifetime,
        shared_format,
    })
}

/// Every image of `scope` that a context with shadow input `input` creates (each light its own for
/// `Scope::Light`), in table order: the rows it needs, less those that are views of another row's memory.
pub(crate) fn image_specs(scope: Scope, extent: [u32; 2], precision: Precision, input: ShadowInput) -> impl Iterator<Item = ImageSpec> {
    RESOURCES
        .iter()
        .filter(move |r| r.scope == scope && r.needed.holds(input) && r.shared_with(precision, input).is_none())
        .flat_map(move |r| specs_of(r, extent, precision, input))
}

/// The light images that only lights recorded together have (`Needed::LightsTogether`), in table order.
pub(crate) fn together_specs(extent: [u32; 2], precision: Precision, input: ShadowInput) -> impl Iterator<Item = ImageSpec> {
    RESOURCES.iter().filter(|r| r.needed == table::Needed::LightsTogether).flat_map(move |r| specs_of(r, extent, precision, input))
}

/// Texel bytes of `together_specs`.
pub(crate) fn together_bytes(extent: [u32; 2], precision: Precision, input: ShadowInput) -> u64 {
    together_specs(extent, precision, input).map(spec_bytes).sum()
}

/// Texel bytes of the images of `scope` (of one light for `Scope::Light`), before any driver padding or alignment.
pub(crate) fn texel_bytes(scope: Scope, extent: [u32; 2], precision: Precision, input: ShadowInput) -> u64 {
    image_specs(scope, extent, precision, input).map(spec_bytes).sum()
}

/// Texel bytes of one light's persistent images (`Lifetime::Persistent`) with shadow input `input`; an image of a
/// context would be transient.
pub(crate) fn persistent_texel_bytes(extent: [u32; 2], precision: Precision, input: ShadowInput) -> u64 {
    image_specs(Scope::Light, extent, precision, input).filter(|s| s.lifetime == Lifetime::Persistent).map(spec_bytes).sum()
}

fn spec_bytes(s: ImageSpec) -> u64 {
    format_bytes(s.format) * s.extent[0] as u64 * s.extent[1] as u64
}

/// Every format of the table with `precision`, once each: the device must sample and store them.
pub(crate) fn formats(precision: Precision) -> impl Iterator<Item = vk::Format> {
    let all: Vec<vk::Format> = RESOURCES.iter().flat_map(|r| [Some(r.format.get(precision)), r.fraction_format]).flatten().collect();
    let unique: Vec<vk::Format> = all.iter().enumerate().filter(|&(i, f)| !all[..i].contains(f)).map(|(_, &f)| f).collect();
    unique.into_iter()
}

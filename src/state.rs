//! Internal state of one light: everything that carries over from frame to frame.

use crate::create_info::Precision;
use crate::error::Result;
use crate::gpu::image::InternalImage;
use crate::gpu::loader::Vk;
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
enum Optional {
    /// Fourth-pass intermediate: four passes.
    Tmp,
}

impl Optional {
    fn needed(self, filter_passes: u32) -> bool {
        match self {
            Optional::Tmp => filter_passes == MAX_FILTER_PASSES,
        }
    }

    fn spec(self, precision: Precision) -> (vk::Format, &'static str) {
        match self {
            Optional::Tmp => (intermediate_format(precision), "filter_tmp"),
        }
    }
}

const OPTIONAL: [Optional; 1] = [Optional::Tmp];

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
pub(crate) fn input_bytes(extent: [u32; 2], input: crate::ShadowInput) -> u64 {
    let texels = extent[0] as u64 * extent[1] as u64;
    if input == crate::ShadowInput::Checkerboard { format_bytes(RECONSTRUCTED_FORMAT) * texels } else { 0 }
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
type ImageSpec = (vk::Format, [u32; 2], &'static str, Lifetime);

/// Every internal image of one light that `filter_passes` passes use, in the order `LightState::new` consumes
/// them (the optional ones last).
fn image_specs(extent: [u32; 2], precision: Precision, filter_passes: u32) -> impl Iterator<Item = ImageSpec> {
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

pub(crate) struct LightState {
    pub tile_mask: InternalImage,
    /// The exactly shadowed pixels of each tile, written by prepare with a visibility input; 4 bytes per tile, so
    /// always allocated.
    pub tile_dark: InternalImage,
    pub tile_meta: InternalImage,
    /// Written and read only with penumbra guidance; 4 bytes per tile, so always allocated.
    pub tile_blocker: InternalImage,
    pub reprojection: InternalImage,
    pub history: InternalImage,
    /// None until four passes are configured.
    pub tmp: Option<InternalImage>,
    /// The visibility prepare reconstructs from a checkerboard input (None for other inputs).
    pub reconstructed: Option<InternalImage>,
    /// Ping-pong pairs indexed by `parity` (current) and `parity ^ 1` (previous frame).
    pub depth: [InternalImage; 2],
    pub moments: [InternalImage; 2],
    /// Flips once per recorded frame of this light: advances with recording, not with frameIndex.
    pub parity: usize,
    /// False until the first frame's commands (layout transitions + clears) have been recorded.
    pub initialized: bool,
    /// The next frame discards history (reset_history or a new allocation).
    pub pending_reset: bool,
}

impl LightState {
    /// A light's images; `checkerboard` adds the reconstructed visibility of a checkerboard input. `alias`: the host
    /// aliases the transient ones (`ResourceKind::TransientImage`).
    pub(crate) fn new(vk: &Vk, light: u32, extent: [u32; 2], precision: Precision, filter_passes: u32, checkerboard: bool, alias: bool) -> Result<LightState> {
        let mut made: Vec<InternalImage> = Vec::new();
        for (format, size, name, lifetime) in image_specs(extent, precision, 1) {
            match InternalImage::new(vk, format, size, &format!("dnsr.light{light}.{name}"), lifetime == Lifetime::Persistent, alias) {
                Ok(img) => made.push(img),
                Err(e) => {
                    made.iter_mut().for_each(|i| i.destroy(vk));
                    return Err(e);
                }
            }
        }
        let mut it = made.into_iter();
        let mut next = || it.next().expect("one image per spec");
        let mut state = LightState {
            tile_mask: next(),
            tile_dark: next(),
            tile_meta: next(),
            tile_blocker: next(),
            reprojection: next(),
            history: next(),
            depth: [next(), next()],
            moments: [next(), next()],
            tmp: None,
            reconstructed: None,
            parity: 0,
            initialized: false,
            pending_reset: true,
        };
        let reconstructed = || InternalImage::new(vk, RECONSTRUCTED_FORMAT, extent, &format!("dnsr.light{light}.reconstructed_visibility"), false, alias);
        let made = state.allocate_optional(vk, light, extent, precision, filter_passes, alias).and_then(|_| {
            state.reconstructed = if checkerboard { Some(reconstructed()?) } else { None };
            Ok(())
        });
        match made {
            Ok(()) => Ok(state),
            Err(e) => {
                state.destroy(vk);
                Err(e)
            }
        }
    }

    /// Allocates the optional images `filter_passes` passes need and this light lacks; true if it made any (their
    /// first frame initialises them, like a new light's).
    pub(crate) fn allocate_optional(&mut self, vk: &Vk, light: u32, extent: [u32; 2], precision: Precision, filter_passes: u32, alias: bool) -> Result<bool> {
        let mut made = false;
        for o in OPTIONAL.into_iter().filter(|o| o.needed(filter_passes)) {
            let slot = match o {
                Optional::Tmp => &mut self.tmp,
            };
            if slot.is_none() {
                let (format, name) = o.spec(precision);
                *slot = Some(InternalImage::new(vk, format, extent, &format!("dnsr.light{light}.{name}"), false, alias)?);
                made = true;
            }
        }
        Ok(made)
    }

    pub(crate) fn images(&self) -> impl Iterator<Item = &InternalImage> {
        [&self.tile_mask, &self.tile_dark, &self.tile_meta, &self.tile_blocker, &self.reprojection, &self.history]
            .into_iter()
            .chain(self.depth.iter())
            .chain(self.moments.iter())
            .chain(self.tmp.iter())
            .chain(self.reconstructed.iter())
    }

    pub(crate) fn bytes(&self) -> u64 {
        self.images().map(|i| i.bytes).sum()
    }

    /// The images whose contents the next frame reads (`Lifetime::Persistent` in `image_specs`).
    pub(crate) fn persistent_images(&self) -> impl Iterator<Item = &InternalImage> {
        self.images().filter(|i| i.persistent)
    }

    /// Every other image: written and read within one record.
    pub(crate) fn transient_images(&self) -> impl Iterator<Item = &InternalImage> {
        self.images().filter(|i| !i.persistent)
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        for img in [&mut self.tile_mask, &mut self.tile_dark, &mut self.tile_meta, &mut self.tile_blocker, &mut self.reprojection, &mut self.history]
            .into_iter()
            .chain(self.depth.iter_mut())
            .chain(self.moments.iter_mut())
            .chain(self.tmp.iter_mut())
            .chain(self.reconstructed.iter_mut())
        {
            img.destroy(vk);
        }
    }
}

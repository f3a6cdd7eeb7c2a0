//! The state model as data: every internal image dnsr keeps, declared once (`RESOURCES`: format per precision, per
//! pixel or per tile, per light or per context, persistent or transient, when it is allocated), and every access
//! the passes make to them (`ACCESSES`: which pass reads or writes which image, over which pixels, in which filter
//! passes, in which configuration). Plain data, no Vulkan object made.
//!
//! Derived from it: the images a light and a context create (src/state.rs `image_specs`, src/light.rs), the format
//! checks at context creation, `memory_requirements`, `Context::memory_bytes` (the images it sums) and the
//! persistent/transient split (`Context::persistent_memory_bytes`, the transient images a host may alias), the
//! filter's ping-pong between its intermediates (`FILTER_INPUT`, `FILTER_OUTPUT`: src/passes/filter.rs binds them)
//! and dnsr-bench's byte model (its rows for internal images are `ACCESSES` of the shadow input the bench feeds,
//! without guidance or debug view; bytes per texel from `format_bytes` of `Resource::format_for`). Barriers are not: the recorder derives them from the
//! bindings of each pass (src/context.rs).
//!
//! Public (hidden) as `dnsr::state_table` for tooling only (dnsr-bench's byte model): not a stable API.

use crate::create_info::{Precision, ShadowInput};
use crate::settings::MAX_FILTER_PASSES;
use ash::vk;

/// An internal image of the table (a ping-pong pair counts as one: `Resource::copies`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Image {
    /// The lit-bit tile mask prepare writes from the host's hit mask (or visibility).
    TileMask,
    /// The exactly shadowed pixels of each tile (a per-pixel visibility input).
    TileDark,
    /// Tile metadata (`TILE_CLEARED`, `TILE_LIT`) of tile classification, read by the filter.
    TileMeta,
    /// Each tile's blocker estimate (penumbra guidance).
    TileBlocker,
    /// The temporal result of tile classification: filter pass 0's input, later reused as an intermediate.
    Reprojection,
    /// The mean of filter pass 0's output, which the next frame's classification reads (its variance goes to the
    /// later passes only, through `Signal`).
    History,
    /// Each frame's linear depth and normal: the later filter passes' guide, and the next frame's previous depth and
    /// normal.
    DepthCopy,
    /// Each pixel's temporal moments as the last record left them: the next frame's classification reads them (at
    /// its pixels' history positions), filter pass 0 then copies this frame's (`FrameMoments`) over them.
    Moments,
    /// The filter's signal between passes: filter pass 0's output (pass 1's input) and pass 2's (pass 3's). A view
    /// of the frame moments' memory where their texels have its size (`Resource::shares`): filter pass 0 reads
    /// each pixel's frame moments before it writes that pixel's signal, and nothing reads them after it.
    Signal,
    /// The visibility prepare reconstructs from a checkerboard input.
    Reconstructed,
    /// Per tile, the frames since one of its receivers' samples contradicted last frame's (`Settings::
    /// hard_tile_frames`), read by the next frame (ping-pong pair).
    TileQuiet,
    /// This frame's moments, which classification writes while it reads last frame's (`Moments`, at other pixels
    /// than its own too, so not in place) and filter pass 0 copies into `Moments`: a transient image instead of
    /// the second half of a persistent pair. Written for the receivers of tiles not cleared only: the other
    /// pixels' moments follow from their tile's metadata, and pass 0 keeps those instead.
    FrameMoments,
    /// This frame's linear depth and normal, as the depth copy, for a light that does not write the depth copy:
    /// where the lights are recorded together (`ContextCreateInfo::lights_recorded_together`) they share the first
    /// light's depth copy, which every light's classification reads as last frame's and only the record's last light
    /// writes; the others' first filter pass writes this frame's here instead, for their later passes' guide. Bound
    /// in the depth copy's place, so it has no accesses of its own.
    FrameDepth,
}

/// The formats of an image: the fp32 path's and the fp16 path's (`Precision`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Formats {
    /// With `Precision::Fp32`.
    pub fp32: vk::Format,
    /// With `Precision::Fp16`.
    pub fp16: vk::Format,
}

impl Formats {
    const fn both(format: vk::Format) -> Formats {
        Formats { fp32: format, fp16: format }
    }

    /// The format with `precision`.
    pub const fn get(self, precision: Precision) -> vk::Format {
        match precision {
            Precision::Fp32 => self.fp32,
            Precision::Fp16 => self.fp16,
        }
    }

    /// "R32_UINT", or "R16G16_UNORM / R16G16_SFLOAT" where the paths differ; ", packed" for words that pack
    /// several values.
    pub fn label(self, packed: bool) -> String {
        let formats = if self.fp32 == self.fp16 { format!("{:?}", self.fp32) } else { format!("{:?} / {:?}", self.fp32, self.fp16) };
        if packed { format!("{formats}, packed") } else { formats }
    }
}

/// What one texel of an image covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Per {
    /// A pixel of the render size.
    Pixel,
    /// An 8x4 tile (`packing::TILE`), the render size rounded up.
    Tile,
}

/// Who owns an image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// Every light has its own (src/light.rs).
    Light,
    /// The context holds one for all its lights (src/context.rs). No row has it today: the filter's guide was one
    /// until the later passes read each light's depth copy instead.
    Context,
}

/// Whether an image's contents must survive from one record of its light to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lifetime {
    /// Read by a later frame: the moments, the depth copy, the history and the tiles' quiet counts (both halves
    /// of their ping-pong pair: the next frame reads the half this one wrote).
    Persistent,
    /// Written and read within one record (tile state, the temporal result, the filter's intermediates, the
    /// reconstructed visibility): its contents between records do not matter.
    Transient,
}

/// When an image is allocated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Needed {
    /// Always.
    Always,
    /// With `ShadowInput::Checkerboard`.
    Checkerboard,
    /// With a per-pixel visibility input, `ShadowInput::Visibility` or `Checkerboard` (prepare runs for them only).
    FractionInput,
    /// With several lights recorded together (`ContextCreateInfo::lights_recorded_together`): not in `holds`, which
    /// the byte counts and `memory_requirements` follow.
    LightsTogether,
}

impl Needed {
    /// Whether a context with shadow input `input` has the image (whatever its filter passes: since the fourth
    /// pass's intermediate went, every pass count needs the same images).
    pub fn holds(self, input: ShadowInput) -> bool {
        match self {
            Needed::Always => true,
            Needed::Checkerboard => input == ShadowInput::Checkerboard,
            Needed::FractionInput => input != ShadowInput::HitMask,
            Needed::LightsTogether => false,
        }
    }
}

/// One internal image (or ping-pong pair) of the table.
#[derive(Clone, Copy, Debug)]
pub struct Resource {
    /// Which image (`RESOURCES[image as usize]`).
    pub image: Image,
    /// Its debug-name stem (`dnsr.light{n}.{name}`, `dnsr.lights.{name}` for a transient image the lights share,
    /// `_{copy}` after it for a pair; `dnsr.{name}` per context); with spaces for underscores, its name in the byte model and docs/performance.md.
    pub name: &'static str,
    /// Its format per precision.
    pub format: Formats,
    /// Its format instead with a visibility or checkerboard input, whose samples are fractions (the moments keep
    /// their sum of squared deviations in a second word); None: `format` whatever the input.
    pub fraction_format: Option<vk::Format>,
    /// Its words pack several values (shaders/dnsr_storage.glsl, src/reference/storage.rs).
    pub packed: bool,
    /// Another image whose memory this one reuses, as a view in its own format, where the two formats' texels have
    /// one size (the other image is then created with `VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT`); an image of its own
    /// otherwise. The two are never live at once. None: always its own.
    pub shares: Option<Image>,
    /// What a texel covers.
    pub per: Per,
    /// Per light or per context.
    pub scope: Scope,
    /// Images of it: 2 for a ping-pong pair (the current frame writes one, the previous frame wrote the other).
    pub copies: u32,
    /// Persistent or transient.
    pub lifetime: Lifetime,
    /// When it is allocated.
    pub needed: Needed,
}

impl Resource {
    /// Its name in the byte model and the docs: the debug-name stem with spaces.
    pub fn display_name(&self) -> String {
        self.name.replace('_', " ")
    }

    /// Bytes of one texel with `precision` (and a hit-mask input).
    pub fn texel_bytes(&self, precision: Precision) -> u64 {
        format_bytes(self.format.get(precision))
    }

    /// Its formats with shadow input `input`.
    pub fn formats_for(&self, input: ShadowInput) -> Formats {
        match (self.fraction_format, input) {
            (Some(f), ShadowInput::Visibility | ShadowInput::Checkerboard) => Formats::both(f),
            _ => self.format,
        }
    }

    /// Its format with `precision` and shadow input `input`.
    pub fn format_for(&self, precision: Precision, input: ShadowInput) -> vk::Format {
        self.formats_for(input).get(precision)
    }

    /// The image whose memory it is a view of with `precision` and shadow input `input` (`shares`, where the texel
    /// sizes match), or None: an image of its own.
    pub fn shared_with(&self, precision: Precision, input: ShadowInput) -> Option<Image> {
        self.shares.filter(|&s| format_bytes(resource_of(s).format_for(precision, input)) == format_bytes(self.format_for(precision, input)))
    }
}

/// The filter's signal (mean and variance) between passes: R16G16_UNORM in the fp32 path (the mean, and the
/// standard deviation over `state::signal_scale`: shaders/dnsr_storage.glsl), float16 in the fp16 path.
const SIGNAL: Formats = Formats { fp32: vk::Format::R16G16_UNORM, fp16: vk::Format::R16G16_SFLOAT };
/// The history: the signal's mean alone, in the signal's number format.
const HISTORY: Formats = Formats { fp32: vk::Format::R16_UNORM, fp16: vk::Format::R16_SFLOAT };

const fn resource(
    image: Image,
    name: &'static str,
    format: Formats,
    per: Per,
    scope: Scope,
    copies: u32,
    lifetime: Lifetime,
    needed: Needed,
) -> Resource {
    Resource { image, name, format, fraction_format: None, packed: false, shares: None, per, scope, copies, lifetime, needed }
}

const fn packed(r: Resource) -> Resource {
    Resource { packed: true, ..r }
}

use Lifetime::{Persistent, Transient};
use Per::{Pixel, Tile};
use Scope::Light;

/// Every internal image, in `Image` order (which is the order a light creates them in).
pub const RESOURCES: [Resource; 13] = [
    // Written by prepare for a visibility or checkerboard input; a hit mask is read as the host gives it, so a
    // hit-mask context has neither (0.25 B/px).
    resource(Image::TileMask, "tile_mask", Formats::both(vk::Format::R32_UINT), Tile, Light, 1, Transient, Needed::FractionInput),
    resource(Image::TileDark, "tile_dark", Formats::both(vk::Format::R32_UINT), Tile, Light, 1, Transient, Needed::FractionInput),
    resource(Image::TileMeta, "tile_meta", Formats::both(vk::Format::R32_UINT), Tile, Light, 1, Transient, Needed::Always),
    // The blocker distance of penumbra guidance; 4 bytes per tile, so allocated with or without guidance.
    resource(Image::TileBlocker, "tile_blocker", Formats::both(vk::Format::R32_SFLOAT), Tile, Light, 1, Transient, Needed::Always),
    resource(Image::Reprojection, "reprojection", SIGNAL, Pixel, Light, 1, Transient, Needed::Always),
    // The mean alone: the next frame's classification blends nothing else (2 B/px kept instead of 4).
    resource(Image::History, "history", HISTORY, Pixel, Light, 1, Persistent, Needed::Always),
    // Linear depth (16-bit code) and normal (8+8 bits) in one word. One image: classification reads last frame's
    // values before the first filter pass writes this frame's, which the later passes read as their guide.
    resource(Image::DepthCopy, "depth_copy", Formats::both(vk::Format::R32_UINT), Pixel, Light, 1, Persistent, Needed::Always),
    // Per pixel: mean (unorm14), sample count (9-bit float), run of identical samples (9-bit integer) packed into
    // one word; with fractional samples their sum of squared deviations (float32) in a second. One image: filter
    // pass 0 copies this frame's (FrameMoments) into it once classification has read last frame's.
    Resource {
        fraction_format: Some(vk::Format::R32G32_UINT),
        ..packed(resource(Image::Moments, "moments", Formats::both(vk::Format::R32_UINT), Pixel, Light, 1, Persistent, Needed::Always))
    },
    // In the frame moments' memory with a hit mask (4 B texels both); an image of its own with fractional samples
    // (8 B moments), allocated whatever the passes.
    Resource {
        shares: Some(Image::FrameMoments),
        ..resource(Image::Signal, "filter_signal", SIGNAL, Pixel, Light, 1, Transient, Needed::Always)
    },
    resource(Image::Reconstructed, "reconstructed_visibility", Formats::both(vk::Format::R32_SFLOAT), Pixel, Light, 1, Transient, Needed::Checkerboard),
    // 4 bytes per tile and frame (0.25 B/px for the pair), so allocated whatever the settings.
    resource(Image::TileQuiet, "tile_quiet", Formats::both(vk::Format::R32_UINT), Tile, Light, 2, Persistent, Needed::Always),
    // As the moments.
    Resource {
        fraction_format: Some(vk::Format::R32G32_UINT),
        ..packed(resource(Image::FrameMoments, "frame_moments", Formats::both(vk::Format::R32_UINT), Pixel, Light, 1, Transient, Needed::Always))
    },
    // As the depth copy; one in each transient set.
    resource(Image::FrameDepth, "frame_depth", Formats::both(vk::Format::R32_UINT), Pixel, Light, 1, Transient, Needed::LightsTogether),
];

/// The row of `image`.
pub const fn resource_of(image: Image) -> &'static Resource {
    &RESOURCES[image as usize]
}

// `resource_of` indexes by the enum.
const _: () = {
    let mut i = 0;
    while i < RESOURCES.len() {
        assert!(RESOURCES[i].image as usize == i);
        i += 1;
    }
};

/// The image filter pass k reads (`FILTER_INPUT[k]`) and writes when it writes an intermediate
/// (`FILTER_OUTPUT[k]`; `When::WritesIntermediate`): the reprojection is free once pass 0 consumed it and the
/// signal once pass 1 did, so four passes need no image beyond them. (A fourth pass is always the last: its output
/// entry is only bound, never written.) Pass 0 also writes the history's mean (`Image::History`).
pub const FILTER_INPUT: [Image; MAX_FILTER_PASSES as usize] = [Image::Reprojection, Image::Signal, Image::Reprojection, Image::Signal];
/// See `FILTER_INPUT`.
pub const FILTER_OUTPUT: [Image; MAX_FILTER_PASSES as usize] = [Image::Signal, Image::Reprojection, Image::Signal, Image::Reprojection];

/// Bytes of one texel of the internal formats.
///
/// # Panics
/// On a format no row of `RESOURCES` has (a unit test covers every row).
pub fn format_bytes(format: vk::Format) -> u64 {
    match format {
        vk::Format::R32G32_UINT => 8,
        vk::Format::R16_UINT | vk::Format::R16_UNORM | vk::Format::R16_SFLOAT => 2,
        vk::Format::R32_UINT | vk::Format::R32_SFLOAT | vk::Format::R16G16_UNORM | vk::Format::R16G16_SFLOAT => 4,
        _ => panic!("state table: no texel size for {format:?} (add it to format_bytes)"),
    }
}

/// A pass of dnsr's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// prepare (skipped when the host's mask already holds lit bits; tile classification then reads that mask in
    /// place of the tile mask).
    Prepare,
    /// tile classification.
    TileClassification,
    /// Every filter pass (see `When`).
    Filter,
}

/// Read or write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Access {
    /// The pass samples it.
    Read,
    /// The pass stores to it.
    Write,
}

/// Which pixels an access covers. dnsr-bench measures each class on the device through the debug views; every
/// class stays measurable whether or not the table uses it today.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pixels {
    /// One unit per 8x4 tile (bytes per tile).
    Tiles,
    /// Every pixel of the render rectangle.
    All,
    /// Receivers: 0 < depth < 1 (not sky).
    Receivers,
    /// Receivers in tiles that tile classification did not clear: the temporal path
    /// (`DebugView::TileClassification` shows 0.5 there).
    Active,
    /// Active receivers that reuse last frame's history: not disoccluded, reset or rejected
    /// (`DebugView::Disocclusion` shows 0 there).
    History,
    /// Pixels of the 8x8 groups (two tiles) with at least one tile not cleared: the filter skips the other
    /// groups, tile classification writes them early.
    ActiveGroups,
    /// Receivers in those groups.
    ActiveGroupReceivers,
    /// Pixels of the other groups (both tiles cleared): tile classification writes their final output.
    ClearedGroups,
}

/// In which filter passes a filter access happens (other passes' accesses always do).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum When {
    /// Every pass.
    Always,
    /// Every pass but the last (pass 0 writes the next frame's history whatever the passes: `FirstPass`).
    WritesIntermediate,
    /// The last pass (it writes the host output).
    FinalPass,
    /// Pass 0 (step 1 from shared memory).
    FirstPass,
    /// Every pass after the first (taps read the depth copy as their guide).
    LaterPasses,
}

impl When {
    /// Whether filter pass `pass` of `passes` makes the access.
    pub fn applies(self, pass: u32, passes: u32) -> bool {
        match self {
            When::Always => true,
            When::WritesIntermediate => pass + 1 < passes,
            When::FinalPass => pass + 1 == passes,
            When::FirstPass => pass == 0,
            When::LaterPasses => pass > 0,
        }
    }
}

/// In which configuration an access happens.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Config {
    /// In every one: a hit-mask input without penumbra guidance or debug view (the byte model's configuration)
    /// and every other.
    Any,
    /// A per-pixel visibility input: `ShadowInput::Visibility` or `Checkerboard`.
    VisibilityInput,
    /// `ShadowInput::Checkerboard`.
    CheckerboardInput,
    /// Penumbra guidance (`ShadowsDispatch::hit_distance`). Tile classification writes the blocker of the tiles it
    /// did not clear only: `Pixels::Tiles` is a bound.
    PenumbraGuidance,
    /// A debug view (`ShadowsDispatch::debug_view`).
    DebugView,
}

/// What an access touches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// The image; of a ping-pong pair, the half the current frame writes.
    Image(Image),
    /// The half of a ping-pong pair that the previous frame wrote.
    Previous(Image),
    /// The moments that the final filter pass's debug views read: this frame's (`FrameMoments`) when it is pass 0,
    /// else the kept ones that pass 0 copied them into (the frame moments' memory then holds the signal).
    DebugMoments,
    /// The filter pass's input: pass k reads `FILTER_INPUT[k]`.
    FilterInput,
    /// The filter pass's intermediate output: pass k writes `FILTER_OUTPUT[k]`.
    FilterOutput,
}

impl Target {
    /// The image filter pass `pass` touches (any pass for the targets other than the filter's input and output).
    pub fn image(self, pass: u32) -> Image {
        match self {
            Target::Image(i) | Target::Previous(i) => i,
            Target::FilterInput => FILTER_INPUT[pass as usize],
            Target::FilterOutput => FILTER_OUTPUT[pass as usize],
            Target::DebugMoments => if pass == 0 { Image::FrameMoments } else { Image::Moments },
        }
    }

    /// Its name in the byte model with shadow input `input`: "previous moments (R32_UINT, packed)", "filter input
    /// (R16G16_UNORM / R16G16_SFLOAT)".
    pub fn label_for(self, input: ShadowInput) -> String {
        let r = resource_of(self.image(0));
        let name = match self {
            Target::Image(_) => r.display_name(),
            Target::Previous(_) => format!("previous {}", r.display_name()),
            Target::FilterInput => "filter input".into(),
            Target::FilterOutput => "filter output".into(),
            Target::DebugMoments => "debug moments".into(),
        };
        let packed = r.packed && matches!(self, Target::Image(_) | Target::Previous(_));
        format!("{name} ({})", r.formats_for(input).label(packed))
    }
}

/// One access of a pass to internal state. Its bytes per unit of `pixels` are those of a texel of the target's
/// format, every texel counted once per pass (perfect reuse of neighbouring taps in the caches).
#[derive(Clone, Copy, Debug)]
pub struct StateAccess {
    /// The pass.
    pub pass: Pass,
    /// What it touches.
    pub target: Target,
    /// Read or write.
    pub access: Access,
    /// Over which pixels.
    pub pixels: Pixels,
    /// In which filter passes (`When::Always` for the other passes).
    pub when: When,
    /// In which configuration.
    pub config: Config,
}

const fn a(pass: Pass, target: Target, access: Access, pixels: Pixels, when: When, config: Config) -> StateAccess {
    StateAccess { pass, target, access, pixels, when, config }
}

/// Every access of the passes to internal state, in pass order. The byte model (dnsr-bench) counts those of
/// `Config::Any` and of the shadow input it feeds, with the host images' beside them; its notes (BENCHMARKS.md "Byte model") say what it leaves out.
pub const ACCESSES: &[StateAccess] = {
    use Access::{Read, Write};
    use Image::*;
    use Pass::{Filter, Prepare, TileClassification};
    use Pixels::{Active, ActiveGroups, All, Tiles};
    use Target::{FilterInput, FilterOutput, Image as I, Previous};
    &[
        // A hit mask is read as it is, by classification (prepare does not run for it).
        a(Prepare, I(TileMask), Write, Tiles, When::Always, Config::VisibilityInput),
        a(Prepare, I(TileDark), Write, Tiles, When::Always, Config::VisibilityInput),
        a(Prepare, I(Reconstructed), Write, All, When::Always, Config::CheckerboardInput),
        a(TileClassification, I(TileMask), Read, Tiles, When::Always, Config::VisibilityInput),
        a(TileClassification, I(TileDark), Read, Tiles, When::Always, Config::VisibilityInput),
        a(TileClassification, I(Reconstructed), Read, All, When::Always, Config::CheckerboardInput),
        a(TileClassification, I(DepthCopy), Read, Active, When::Always, Config::Any),
        // Last frame's moments, at the history positions.
        a(TileClassification, I(Moments), Read, Pixels::History, When::Always, Config::Any),
        a(TileClassification, I(History), Read, Pixels::History, When::Always, Config::Any),
        // Not for the other pixels (a cleared tile's receivers, the sky): pass 0 derives theirs from the tile metadata.
        a(TileClassification, I(FrameMoments), Write, Active, When::Always, Config::Any),
        a(TileClassification, I(Reprojection), Write, All, When::Always, Config::Any),
        a(TileClassification, I(TileMeta), Write, Tiles, When::Always, Config::Any),
        a(TileClassification, I(TileBlocker), Write, Tiles, When::Always, Config::PenumbraGuidance),
        // The 3x3 tiles around each tile: each texel counted once.
        a(TileClassification, Previous(TileQuiet), Read, Tiles, When::Always, Config::Any),
        a(TileClassification, I(TileQuiet), Write, Tiles, When::Always, Config::Any),
        a(Filter, I(TileMeta), Read, Tiles, When::Always, Config::Any),
        a(Filter, I(TileBlocker), Read, Tiles, When::Always, Config::PenumbraGuidance),
        a(Filter, I(DepthCopy), Write, All, When::FirstPass, Config::Any),
        // Pass 0 keeps this frame's moments for the next: fetched for every pixel, beside its depth (a fetch that
        // waited for the depth or the tile metadata was slower).
        a(Filter, I(FrameMoments), Read, All, When::FirstPass, Config::Any),
        a(Filter, I(Moments), Write, All, When::FirstPass, Config::Any),
        a(Filter, I(History), Write, All, When::FirstPass, Config::Any),
        a(Filter, I(DepthCopy), Read, ActiveGroups, When::LaterPasses, Config::Any),
        a(Filter, FilterInput, Read, ActiveGroups, When::Always, Config::Any),
        a(Filter, FilterOutput, Write, All, When::WritesIntermediate, Config::Any),
        // The moments debug views.
        a(Filter, Target::DebugMoments, Read, All, When::FinalPass, Config::DebugView),
    ]
};

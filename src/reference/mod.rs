//! The CPU reference: every pass in f64, written for clarity against the same Get/Read/Write interface the
//! shaders call (`dnsr_get_*`, `dnsr_read_*`, `dnsr_write_*` in shaders/dnsr_callbacks_standard.glsl). It is the
//! executable specification: the GPU passes must match it within the parity tolerances.
//!
//! Coordinates handed to the interface are relative to the render rectangle, as on the GPU.

pub mod classify;
pub mod diagnostics;
pub mod filter;
pub mod memory;
pub mod prepare;
pub mod storage;
pub mod tile_classification;

use crate::settings::Settings;
use glam::{DMat4, DVec2, DVec3, DVec4};

/// Integer pixel or tile coordinate.
pub type Coord = [i32; 2];

/// The constants every pass reads (`dnsr_get_*`).
pub trait Get {
    /// Render rectangle extent in pixels.
    fn extent(&self) -> Coord;
    /// Current clip -> view.
    fn projection_inverse(&self) -> DMat4;
    /// Current clip -> previous clip.
    fn reprojection_matrix(&self) -> DMat4;
    /// Current clip -> world.
    fn view_projection_inverse(&self) -> DMat4;
    /// Eye position in world space.
    fn eye(&self) -> DVec3;
    /// Depth edge-stop sigma.
    fn depth_similarity_sigma(&self) -> f64;
    /// History discarded this frame.
    fn is_reset(&self) -> bool;
    /// Reverse-Z.
    fn is_depth_inverted(&self) -> bool;
    /// Algorithm settings.
    fn settings(&self) -> &Settings;
    /// Tap step of the current filter pass (1, 2, 4, 8).
    fn filter_step(&self) -> i32;
    /// The current filter pass writes its (mean, variance) for the next pass or the next frame's history.
    fn write_internal(&self) -> bool;
    /// The current filter pass is the last and writes the output.
    fn is_final_pass(&self) -> bool;
    /// Penumbra guidance of this frame (None without a hit-distance input).
    fn penumbra(&self) -> Option<Penumbra>;
    /// The light has no size (`ShadowsDispatch::hard_light`): every receiver's own sample is its output.
    fn hard_light(&self) -> bool;
    /// Where the light is (`ShadowsDispatch::light_position`), a homogeneous world-space point; None: not given.
    fn light_position(&self) -> Option<DVec4>;
    /// With a light position: the sine of the light's angular radius (`light_sin_radius` of
    /// `ShadowsDispatch::light_angular_size`; 0: a light of no size).
    fn light_sin_radius(&self) -> f64;
    /// The shadow input is per-pixel visibility (`read_visibility`) instead of the hit mask; a checkerboard input
    /// is one too, from prepare on (prepare writes the visibility classification reads).
    fn visibility_input(&self) -> bool;
    /// A checkerboard input: this frame traced the pixels with (x + y) % 2 == phase (None: every pixel).
    fn checkerboard_phase(&self) -> Option<u32>;
    /// The intermediates are float16 (`Precision::Fp16`).
    fn half_intermediates(&self) -> bool;
    /// Whether this frame traced pixel `p` (every pixel without a checkerboard input).
    fn is_traced(&self, p: Coord) -> bool {
        self.checkerboard_phase().is_none_or(|phase| (p[0] + p[1]) as u32 % 2 == phase)
    }
}

/// The inputs passes read (`dnsr_read_*`). Each pass reads only what it needs.
pub trait Read: Get {
    /// Host hit mask word of a tile (FidelityFX convention: 1 = occluded).
    fn read_hit_mask(&self, tile: Coord) -> u32;
    /// Internal tile mask word (1 = lit).
    fn read_tile_mask(&self, tile: Coord) -> u32;
    /// Raw depth.
    fn read_depth(&self, p: Coord) -> f64;
    /// Motion vector already scaled: prev_uv = uv + velocity.
    fn read_velocity(&self, p: Coord) -> DVec2;
    /// Decoded unit world normal, or zero when unusable.
    fn read_normal(&self, p: Coord) -> DVec3;
    /// Previous frame's linear depth (-1: no receiver), as its depth copy holds it (`depth_copy`), or as the host's
    /// previous depth gives it (`ContextCreateInfo::host_previous_gbuffer`: not rounded).
    fn read_previous_depth(&self, p: Coord) -> f64;
    /// Previous frame's normal (unit, or zero: no receiver), as its depth copy holds it (`depth_copy`), or the
    /// host's previous normal decoded (whatever it holds where there was no receiver).
    fn read_previous_normal(&self, p: Coord) -> DVec3;
    /// Previous frame's moments (mean, Welford sum, sample count).
    fn read_previous_moments(&self, p: Coord) -> DVec4;
    /// Bilinear history at a rect-relative uv (clamp to edge).
    fn read_history(&self, uv: DVec2) -> f64;
    /// One history texel.
    fn read_history_texel(&self, p: Coord) -> f64;
    /// Tile metadata word.
    fn read_tile_meta(&self, tile: Coord) -> u32;
    /// Last frame's count of quiet frames of a tile (`tile_classification::contradicts`), as stored.
    fn read_previous_tile_quiet(&self, tile: Coord) -> u32;
    /// Filter pass input (mean, variance).
    fn read_filter_input(&self, p: Coord) -> DVec2;
    /// Host hit distance (read only with penumbra guidance, where the mask says the ray hit).
    fn read_hit_distance(&self, p: Coord) -> f64;
    /// A tile's blocker distance as classification estimated it (-1: unknown).
    fn read_tile_blocker(&self, tile: Coord) -> f64;
    /// Host visibility of a pixel, as stored (read only with `visibility_input`; see `sanitize_visibility`).
    fn read_visibility(&self, p: Coord) -> f64;
    /// Internal dark mask word: the tile's exactly shadowed pixels (visibility input).
    fn read_tile_dark(&self, tile: Coord) -> u32;
}

/// The outputs passes write (`dnsr_write_*`).
pub trait Write {
    /// Internal tile mask word.
    fn write_tile_mask(&mut self, tile: Coord, lit_bits: u32);
    /// Internal dark mask word (visibility input).
    fn write_tile_dark(&mut self, tile: Coord, dark_bits: u32);
    /// A pixel's visibility reconstructed from a checkerboard input (what `read_visibility` returns after it).
    fn write_visibility(&mut self, p: Coord, v: f64);
    /// This frame's depth copy word (`depth_copy`).
    fn write_depth_copy(&mut self, p: Coord, word: u32);
    /// This frame's moments.
    fn write_moments(&mut self, p: Coord, m: DVec4);
    /// Temporal result (mean, variance).
    fn write_reprojection(&mut self, p: Coord, mean_var: DVec2);
    /// Tile metadata word.
    fn write_tile_meta(&mut self, tile: Coord, meta: u32);
    /// This frame's count of quiet frames of a tile (the next frame's `read_previous_tile_quiet`).
    fn write_tile_quiet(&mut self, tile: Coord, frames: u32);
    /// A tile's blocker distance (penumbra guidance; -1: unknown).
    fn write_tile_blocker(&mut self, tile: Coord, distance: f64);
    /// Filter pass output (mean, variance).
    fn write_filter_output(&mut self, p: Coord, mean_var: DVec2);
    /// Final shadow value.
    fn write_output(&mut self, p: Coord, shadow: f64);
    /// Routes filter pass `pass` of `passes`: its input is the previous pass's output (pass 0: the temporal
    /// result), as the GPU's intermediate images do.
    fn begin_filter_pass(&mut self, pass: u32, passes: u32);
}

// ---- helpers shared by the passes (shaders/dnsr_common.glsl) ----

/// The (mean, variance) every pass stores for sky and non-receivers: lit, with a negative variance that marks
/// "no receiver" so that the filter's variance blur needs no depth read to tell receivers apart.
pub const SKY_SIGNAL: glam::DVec2 = glam::DVec2::new(1.0, -1.0);

/// A final receiver's variance: its value is exact (turned away from the whole light, its ray hit), and every
/// filter pass returns it as it is and leaves it out of its neighbours' taps and variance blur
/// (shaders/dnsr_common.glsl, dnsr_final_signal).
pub const FINAL_VARIANCE: f64 = -2.0;

/// Whether signal `c` is a final receiver's (`FINAL_VARIANCE`).
pub fn final_signal(c: glam::DVec2) -> bool {
    c.y < -1.5
}

/// The sine of the angular radius of a light of angular diameter `angular_size` (radians): a receiver whose normal
/// is turned further than this from the light's centre (N.L below its negative) sees none of its disc.
pub fn light_sin_radius(angular_size: f64) -> f64 {
    (angular_size * 0.5).sin()
}

/// Tile size in pixels.
pub const TILE: Coord = [crate::packing::TILE[0] as i32, crate::packing::TILE[1] as i32];

/// Bit of pixel `p` within its tile word.
pub fn tile_bit(p: Coord) -> u32 {
    (p[1].rem_euclid(4) * 8 + p[0].rem_euclid(8)) as u32
}

/// Pixel inside the render rectangle.
pub fn inside<G: Get + ?Sized>(io: &G, p: Coord) -> bool {
    let e = io.extent();
    p[0] >= 0 && p[1] >= 0 && p[0] < e[0] && p[1] < e[1]
}

/// A shadow receiver has 0 < depth < 1 (NaN is sky).
pub fn is_receiver(depth: f64) -> bool {
    depth > 0.0 && depth < 1.0
}

/// Pixel center in rect-relative uv.
pub fn pixel_uv<G: Get + ?Sized>(io: &G, p: Coord) -> DVec2 {
    let e = io.extent();
    DVec2::new((p[0] as f64 + 0.5) / e[0] as f64, (p[1] as f64 + 0.5) / e[1] as f64)
}

/// Vulkan NDC of a uv.
pub fn uv_to_ndc(uv: DVec2) -> DVec2 {
    uv * 2.0 - 1.0
}

/// Distance along the view axis (infinite at an infinite far plane's far depth).
pub fn linear_depth<G: Get + ?Sized>(io: &G, ndc: DVec2, depth: f64) -> f64 {
    let v = io.projection_inverse() * DVec4::new(ndc.x, ndc.y, depth, 1.0);
    (v.z / v.w).abs()
}

/// World-space position of pixel p at device depth `depth` (`dnsr_world_position`).
pub fn world_position<G: Get + ?Sized>(io: &G, p: Coord, depth: f64) -> DVec3 {
    let h = io.view_projection_inverse() * uv_to_ndc(pixel_uv(io, p)).extend(depth).extend(1.0);
    h.truncate() / h.w
}

/// Pixel p's linear depth where `depth` (its device depth) is a receiver's, -1 elsewhere
/// (`dnsr_receiver_linear_depth`).
pub fn receiver_linear_depth<G: Get + ?Sized>(io: &G, p: Coord, depth: f64) -> f64 {
    if is_receiver(depth) { linear_depth(io, uv_to_ndc(pixel_uv(io, p)), depth) } else { -1.0 }
}

/// The depth copy of pixel p whose depth and normal are these: on a receiver its linear depth and normal (-1 and
/// zero elsewhere), what the later filter passes and the next frame compare, packed as the GPU stores them
/// (`storage::pack_depth_copy`).
pub fn depth_copy<G: Get + ?Sized>(io: &G, p: Coord, depth: f64, normal: DVec3) -> u32 {
    let normal = if is_receiver(depth) { normal } else { DVec3::ZERO };
    storage::pack_depth_copy(receiver_linear_depth(io, p, depth), normal)
}

/// What turns a blocker distance into a penumbra radius in pixels (the dispatch's penumbra guidance).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Penumbra {
    /// tan(angular diameter / 2) of the light: a blocker d away widens the shadow's edge by d * this either side.
    pub tan_half_angle: f64,
    /// World size of one pixel at linear view depth 0 (orthographic projections: at every depth) ...
    pub pixel_size: f64,
    /// ... plus this much per unit of linear view depth (perspective projections).
    pub pixel_size_per_depth: f64,
}

impl Penumbra {
    /// From the light's angular diameter (radians), the current clip -> view matrix and the render height: the
    /// pixel footprint is measured by unprojecting one pixel's height at two depths, which covers perspective
    /// and orthographic projections alike.
    pub fn new(angular_size: f64, projection_inverse: DMat4, height: i32) -> Penumbra {
        let footprint = |depth: f64| {
            let at = |y: f64| {
                let v = projection_inverse * DVec4::new(0.0, y, depth, 1.0);
                v.truncate() / v.w
            };
            let (centre, above) = (at(0.0), at(2.0 / height as f64));
            ((above - centre).length(), centre.z.abs())
        };
        let ((s0, z0), (s1, z1)) = (footprint(0.25), footprint(0.75));
        let per_depth = if (z1 - z0).abs() > 1e-12 * z1.abs().max(1.0) { (s1 - s0) / (z1 - z0) } else { 0.0 };
        let (pixel_size, pixel_size_per_depth) =
            if per_depth.is_finite() && s0.is_finite() { (s0 - per_depth * z0, per_depth) } else { (0.0, 0.0) };
        Penumbra { tan_half_angle: Self::tan_half_angle(angular_size), pixel_size, pixel_size_per_depth }
    }

    /// tan(angular diameter / 2) of a light of angular diameter `angular_size` (radians).
    pub fn tan_half_angle(angular_size: f64) -> f64 {
        (angular_size * 0.5).tan()
    }

    /// World size of a pixel at linear view depth `z` (<= 0 where the projection gives none).
    pub fn footprint(&self, z: f64) -> f64 {
        self.pixel_size + self.pixel_size_per_depth * z
    }

    /// Whether blockers `blocker` away on average cast a penumbra narrower than `radius` pixels either side on a
    /// receiver at linear depth `z` (`Settings::hard_penumbra_pixels`; 0 never) from
    /// `HARD_PENUMBRA_MIN_BLOCKER_PIXELS` pixel footprints or more: shaders/dnsr_common.glsl, dnsr_hard_penumbra
    /// and dnsr_no_blocker, compared in the same form. A light of no size casts no penumbra: blockers at any
    /// distance. No blocker known (`blocker` negative: every shadowed pixel near the tile faces away from the
    /// light) leaves no penumbra either, whatever the light.
    pub fn is_hard(&self, blocker: f64, z: f64, radius: f64) -> bool {
        let footprint = self.footprint(z);
        let narrow = footprint > 0.0
            && blocker * self.tan_half_angle < radius * footprint
            && (self.tan_half_angle == 0.0 || blocker >= crate::passes::HARD_PENUMBRA_MIN_BLOCKER_PIXELS as f64 * footprint);
        radius > 0.0 && (blocker < 0.0 || narrow)
    }

    /// Half-width in pixels of the penumbra a blocker `blocker` away casts on a receiver at linear depth `z`
    /// (infinite where the pixel footprint is degenerate: no narrowing).
    pub fn radius_px(&self, blocker: f64, z: f64) -> f64 {
        let footprint = self.footprint(z);
        if footprint > 0.0 { blocker * self.tan_half_angle / footprint } else { f64::INFINITY }
    }
}

/// The filter's penumbra kernel: a tap `distance` pixels away weighs exp(-distance^2 / (2 sigma^2)), with sigma
/// this many times the penumbra's half-width. Chosen on `make accuracy`'s hit-distance sequences (mean RMSE,
/// Balanced / Quality: 0.1: 0.0336 / 0.0283, 0.25: 0.0344 / 0.0222, 0.5: 0.0356 / 0.0204, 1: 0.0383 / 0.0214,
/// 2: 0.0392 / 0.0217; without guidance 0.0393 / 0.0215): narrower starves Quality's temporal clamp of a
/// smooth neighbourhood, wider lets contact shadows bleed.
pub const PENUMBRA_SIGMA_SCALE: f64 = 0.5;

/// Decodes a stored normal as the default callbacks do.
pub fn decode_normal(raw: DVec3, mul: f64, add: f64) -> DVec3 {
    let n = raw * mul + add;
    let len2 = n.length_squared();
    if len2 > 1e-12 && len2 < 1e30 { n / len2.sqrt() } else { DVec3::ZERO }
}

/// A stored visibility as the passes use it: clamped to [0, 1], NaN read as 0 (shadowed).
pub fn sanitize_visibility(v: f64) -> f64 {
    if v >= 0.0 { v.min(1.0) } else { 0.0 }
}

/// Runs the whole frame: prepare (unless a hit mask already holds lit bits: `run_prepare` false; a visibility input
/// always goes through it), tile classification, filter passes. `io` carries the inputs and the previous frame's
/// state and receives every output.
pub fn run_frame<Io: Read + Write>(io: &mut Io, run_prepare: bool) {
    if run_prepare || io.visibility_input() {
        prepare::run(io);
    }
    tile_classification::run(io);
    let passes = crate::passes::light_filter_passes(io.settings().filter_passes, io.hard_light());
    for pass in 0..passes {
        io.begin_filter_pass(pass, passes);
        filter::run(io);
    }
}

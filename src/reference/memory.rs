//! A plain in-memory frame implementing the reference interface: the inputs, the previous frame's state, and
//! every output, as arrays over the whole render size (render rectangle = whole image).

use super::{Coord, Get, Penumbra, Read, Write, TILE};
use crate::settings::Settings;
use std::collections::TryReserveError;
use glam::{DMat4, DVec2, DVec3, DVec4};

/// One frame of one light for the CPU reference.
#[derive(Clone, Debug)]
pub struct Frame {
    /// Width and height in pixels.
    pub extent: Coord,
    /// Settings.
    pub settings: Settings,
    /// Current clip -> view.
    pub projection_inverse: DMat4,
    /// Current clip -> previous clip.
    pub reprojection: DMat4,
    /// Current clip -> world.
    pub view_projection_inverse: DMat4,
    /// Eye in world space.
    pub eye: DVec3,
    /// Depth edge-stop sigma.
    pub depth_similarity_sigma: f64,
    /// History discarded this frame.
    pub reset: bool,
    /// Reverse-Z.
    pub depth_inverted: bool,
    /// Penumbra guidance (None: no hit-distance input).
    pub penumbra: Option<Penumbra>,
    /// The light has no size (`ShadowsDispatch::hard_light`).
    pub hard_light: bool,
    /// Where the light is (`ShadowsDispatch::light_position`); None: not given.
    pub light_position: Option<DVec4>,
    /// The light's angular diameter in radians (`ShadowsDispatch::light_angular_size`), read with a light position.
    pub light_angular_size: f64,
    /// Host hit distance per pixel (read only with penumbra guidance).
    pub hit_distance: Vec<f64>,
    /// Host hit mask (FidelityFX convention), one word per tile.
    pub hit_mask: Vec<u32>,
    /// Host visibility per pixel, as stored; `Some` makes it the shadow input instead of the hit mask. With a
    /// checkerboard input, prepare writes the reconstructed visibility here.
    pub visibility: Option<Vec<f64>>,
    /// Checkerboard input: the hit mask holds the rays of the pixels with (x + y) % 2 == phase.
    pub checkerboard_phase: Option<u32>,
    /// Depth per pixel.
    pub depth: Vec<f64>,
    /// Scaled motion vectors per pixel.
    pub velocity: Vec<DVec2>,
    /// Decoded normals per pixel (unit or zero).
    pub normals: Vec<DVec3>,
    /// Previous frame's depth copy: words as stored (`storage::pack_depth_copy`).
    pub previous_depth: Vec<u32>,
    /// The host's previous depth and decoded normals (`set_host_previous`), read instead of `previous_depth`.
    pub host_previous: Option<(Vec<f64>, Vec<DVec3>)>,
    /// Previous frame's moments.
    pub previous_moments: Vec<DVec4>,
    /// Previous frame's history (filter pass 0 mean).
    pub history: Vec<f64>,
    /// Previous frame's count of quiet frames per tile.
    pub previous_tile_quiet: Vec<u32>,
    /// Output: this frame's count of quiet frames per tile.
    pub tile_quiet: Vec<u32>,
    /// Output: lit-bit tile mask.
    pub tile_mask: Vec<u32>,
    /// Output: the exactly shadowed pixels per tile (visibility input).
    pub tile_dark: Vec<u32>,
    /// Output: tile metadata.
    pub tile_meta: Vec<u32>,
    /// Output: each tile's blocker distance (penumbra guidance).
    pub tile_blocker: Vec<f64>,
    /// Output: depth copy (words as stored).
    pub depth_copy: Vec<u32>,
    /// Output: moments.
    pub moments: Vec<DVec4>,
    /// Output: temporal result (mean, variance).
    pub reprojection_out: Vec<DVec2>,
    /// Output of each filter pass (pass 0 is the next frame's history).
    pub filter_out: Vec<Vec<DVec2>>,
    /// Output: final shadow.
    pub output: Vec<f64>,
    /// Intermediates are stored as float16 (the fp16 path's R16G16_SFLOAT images): writes round to half.
    /// Otherwise as the fp32 path's R16G16_UNORM (storage::stored_signal).
    pub half_intermediates: bool,
    pass: u32,
    passes: u32,
}

impl Frame {
    /// A frame of `w` x `h` with neutral inputs (sky, no motion) and empty history.
    pub fn new(w: i32, h: i32, settings: Settings) -> Frame {
        Frame::try_new(w, h, settings).expect("memory for a reference frame")
    }

    /// As `new`, or the allocation that failed: every per-pixel buffer, the filter passes' included, is
    /// allocated here, fallibly (the C entry points answer DNSR_ERROR_OUT_OF_HOST_MEMORY instead of aborting).
    pub fn try_new(w: i32, h: i32, settings: Settings) -> Result<Frame, TryReserveError> {
        let n = (w * h) as usize;
        let tiles = (((w + 7) / 8) * ((h + 3) / 4)) as usize;
        let mut filter_out = Vec::new();
        filter_out.try_reserve_exact(settings.filter_passes as usize)?;
        for _ in 0..settings.filter_passes {
            filter_out.push(filled(n, DVec2::ZERO)?);
        }
        Ok(Frame {
            extent: [w, h],
            settings,
            projection_inverse: DMat4::IDENTITY,
            reprojection: DMat4::IDENTITY,
            view_projection_inverse: DMat4::IDENTITY,
            eye: DVec3::ZERO,
            depth_similarity_sigma: 1.0,
            reset: false,
            depth_inverted: false,
            penumbra: None,
            hard_light: false,
            light_position: None,
            light_angular_size: 0.0,
            hit_distance: filled(n, 0.0)?,
            hit_mask: filled(tiles, 0)?,
            visibility: None,
            checkerboard_phase: None,
            depth: filled(n, 1.0)?,
            velocity: filled(n, DVec2::ZERO)?,
            normals: filled(n, DVec3::ZERO)?,
            // A new depth copy is cleared to 0: the first depth code, the normal +z.
            previous_depth: filled(n, 0)?,
            host_previous: None,
            previous_moments: filled(n, DVec4::ZERO)?,
            history: filled(n, 0.0)?,
            previous_tile_quiet: filled(tiles, 0)?,
            tile_quiet: filled(tiles, 0)?,
            tile_mask: filled(tiles, 0)?,
            tile_dark: filled(tiles, 0)?,
            tile_meta: filled(tiles, 0)?,
            tile_blocker: filled(tiles, -1.0)?,
            depth_copy: filled(n, 0)?,
            moments: filled(n, DVec4::ZERO)?,
            reprojection_out: filled(n, DVec2::ZERO)?,
            filter_out,
            output: filled(n, 0.0)?,
            half_intermediates: false,
            pass: 0,
            passes: 0,
        })
    }

    fn px(&self, p: Coord) -> usize {
        (p[1] * self.extent[0] + p[0]) as usize
    }

    fn tile(&self, t: Coord) -> usize {
        (t[1] * ((self.extent[0] + TILE[0] - 1) / TILE[0]) + t[0]) as usize
    }

    fn store(&self, v: DVec2) -> DVec2 {
        if self.half_intermediates {
            DVec2::new(round_to_half(v.x), round_to_half(v.y))
        } else {
            super::storage::stored_signal(v, crate::state::signal_scale(self.settings.variance_boost_samples) as f64)
        }
    }

    /// Takes last frame's depth and normal from the host's previous images (`ContextCreateInfo::
    /// host_previous_gbuffer`: device depth and decoded normals per pixel) instead of the previous depth copy, as
    /// classification reads them: the depth linearised with this frame's `projection_inverse`, neither rounded to a
    /// depth copy's codes. `advance` then hands this frame's depth and normals on the same way.
    pub fn set_host_previous(&mut self, depth: &[f64], normals: &[DVec3]) {
        self.host_previous = Some((depth.to_vec(), normals.to_vec()));
    }

    /// Moves this frame's outputs into the next frame's "previous" state (depth, moments, history).
    pub fn advance(&mut self) {
        self.previous_depth = self.depth_copy.clone();
        if self.host_previous.is_some() {
            self.host_previous = Some((self.depth.clone(), self.normals.clone()));
        }
        self.previous_moments = self.moments.clone();
        self.previous_tile_quiet = self.tile_quiet.clone();
        if let Some(h) = self.filter_out.first() {
            self.history = h.iter().map(|v| v.x).collect();
        }
        self.reset = false;
    }
}

impl Get for Frame {
    fn extent(&self) -> Coord {
        self.extent
    }
    fn projection_inverse(&self) -> DMat4 {
        self.projection_inverse
    }
    fn reprojection_matrix(&self) -> DMat4 {
        self.reprojection
    }
    fn view_projection_inverse(&self) -> DMat4 {
        self.view_projection_inverse
    }
    fn eye(&self) -> DVec3 {
        self.eye
    }
    fn depth_similarity_sigma(&self) -> f64 {
        self.depth_similarity_sigma
    }
    fn is_reset(&self) -> bool {
        self.reset
    }
    fn is_depth_inverted(&self) -> bool {
        self.depth_inverted
    }
    fn settings(&self) -> &Settings {
        &self.settings
    }
    fn half_intermediates(&self) -> bool {
        self.half_intermediates
    }
    fn filter_step(&self) -> i32 {
        1 << self.pass
    }
    fn write_internal(&self) -> bool {
        self.pass == 0 || !self.is_final_pass()
    }
    fn is_final_pass(&self) -> bool {
        self.pass + 1 == self.passes
    }
    fn penumbra(&self) -> Option<Penumbra> {
        self.penumbra
    }
    fn hard_light(&self) -> bool {
        self.hard_light
    }
    fn light_position(&self) -> Option<DVec4> {
        self.light_position
    }
    fn light_sin_radius(&self) -> f64 {
        super::light_sin_radius(self.light_angular_size)
    }
    fn checkerboard_phase(&self) -> Option<u32> {
        self.checkerboard_phase
    }
    fn visibility_input(&self) -> bool {
        self.visibility.is_some() || self.checkerboard_phase.is_some()
    }
}

impl Read for Frame {
    fn read_hit_mask(&self, tile: Coord) -> u32 {
        self.hit_mask[self.tile(tile)]
    }
    fn read_visibility(&self, p: Coord) -> f64 {
        self.visibility.as_ref().expect("visibility input")[self.px(p)]
    }
    fn read_tile_mask(&self, tile: Coord) -> u32 {
        self.tile_mask[self.tile(tile)]
    }
    fn read_depth(&self, p: Coord) -> f64 {
        self.depth[self.px(p)]
    }
    fn read_velocity(&self, p: Coord) -> DVec2 {
        self.velocity[self.px(p)]
    }
    fn read_normal(&self, p: Coord) -> DVec3 {
        self.normals[self.px(p)]
    }
    fn read_previous_depth(&self, p: Coord) -> f64 {
        match &self.host_previous {
            Some((depth, _)) => super::receiver_linear_depth(self, p, depth[self.px(p)]),
            None => super::storage::unpack_depth_copy(self.previous_depth[self.px(p)]).0,
        }
    }
    fn read_previous_normal(&self, p: Coord) -> DVec3 {
        match &self.host_previous {
            Some((_, normals)) => normals[self.px(p)],
            None => super::storage::unpack_depth_copy(self.previous_depth[self.px(p)]).1,
        }
    }
    fn read_previous_moments(&self, p: Coord) -> DVec4 {
        self.previous_moments[self.px(p)]
    }
    fn read_history(&self, uv: DVec2) -> f64 {
        // Bilinear with clamp to the rectangle, texel centers at integer + 0.5, float weights: as dnsr_read_history.
        let [w, h] = self.extent;
        let s = DVec2::new(uv.x * w as f64 - 0.5, uv.y * h as f64 - 0.5);
        let (x0, y0) = (s.x.floor(), s.y.floor());
        let (fx, fy) = (s.x - x0, s.y - y0);
        let at = |x: f64, y: f64| {
            let xi = (x as i32).clamp(0, w - 1);
            let yi = (y as i32).clamp(0, h - 1);
            self.history[(yi * w + xi) as usize]
        };
        let top = at(x0, y0) * (1.0 - fx) + at(x0 + 1.0, y0) * fx;
        let bottom = at(x0, y0 + 1.0) * (1.0 - fx) + at(x0 + 1.0, y0 + 1.0) * fx;
        top * (1.0 - fy) + bottom * fy
    }
    fn read_history_texel(&self, p: Coord) -> f64 {
        self.history[self.px(p)]
    }
    fn read_tile_meta(&self, tile: Coord) -> u32 {
        self.tile_meta[self.tile(tile)]
    }
    fn read_previous_tile_quiet(&self, tile: Coord) -> u32 {
        self.previous_tile_quiet[self.tile(tile)]
    }
    fn read_filter_input(&self, p: Coord) -> DVec2 {
        let i = self.px(p);
        if self.pass == 0 { self.reprojection_out[i] } else { self.filter_out[self.pass as usize - 1][i] }
    }
    fn read_hit_distance(&self, p: Coord) -> f64 {
        self.hit_distance[self.px(p)]
    }
    fn read_tile_blocker(&self, tile: Coord) -> f64 {
        self.tile_blocker[self.tile(tile)]
    }
    fn read_tile_dark(&self, tile: Coord) -> u32 {
        self.tile_dark[self.tile(tile)]
    }
}

impl Write for Frame {
    fn write_tile_mask(&mut self, tile: Coord, lit_bits: u32) {
        let i = self.tile(tile);
        self.tile_mask[i] = lit_bits;
    }
    fn write_visibility(&mut self, p: Coord, v: f64) {
        let (i, n) = (self.px(p), (self.extent[0] * self.extent[1]) as usize);
        self.visibility.get_or_insert_with(|| vec![0.0; n])[i] = v;
    }
    fn write_tile_dark(&mut self, tile: Coord, dark_bits: u32) {
        let i = self.tile(tile);
        self.tile_dark[i] = dark_bits;
    }
    fn write_depth_copy(&mut self, p: Coord, word: u32) {
        let i = self.px(p);
        self.depth_copy[i] = word;
    }
    fn write_moments(&mut self, p: Coord, m: DVec4) {
        let i = self.px(p);
        self.moments[i] = super::storage::stored_moments(m, self.visibility.is_some());
    }
    fn write_reprojection(&mut self, p: Coord, mean_var: DVec2) {
        let i = self.px(p);
        self.reprojection_out[i] = self.store(mean_var);
    }
    fn write_tile_quiet(&mut self, tile: Coord, frames: u32) {
        let i = self.tile(tile);
        self.tile_quiet[i] = frames;
    }
    fn write_tile_meta(&mut self, tile: Coord, meta: u32) {
        let i = self.tile(tile);
        self.tile_meta[i] = meta;
    }
    fn write_tile_blocker(&mut self, tile: Coord, distance: f64) {
        let i = self.tile(tile);
        self.tile_blocker[i] = distance;
    }
    fn write_filter_output(&mut self, p: Coord, mean_var: DVec2) {
        let i = self.px(p);
        self.filter_out[self.pass as usize][i] = self.store(mean_var);
    }
    fn write_output(&mut self, p: Coord, shadow: f64) {
        let i = self.px(p);
        self.output[i] = shadow;
    }
    fn begin_filter_pass(&mut self, pass: u32, passes: u32) {
        self.pass = pass;
        self.passes = passes;
        let n = self.depth.len();
        self.filter_out.resize(passes as usize, vec![DVec2::ZERO; n]);
    }
}

/// `n` copies of `value`, or the error of a failed allocation (instead of an abort).
pub(crate) fn filled<T: Clone>(n: usize, value: T) -> Result<Vec<T>, TryReserveError> {
    let mut v = Vec::new();
    v.try_reserve_exact(n)?;
    v.resize(n, value);
    Ok(v)
}

/// Rounds to the nearest IEEE half-precision value (ties to even), as a GPU stores the float32 value into a 16-bit
/// float image.
pub fn round_to_half(x: f64) -> f64 {
    if !x.is_finite() || x == 0.0 {
        return x;
    }
    super::storage::f16_to_f32(super::storage::f32_to_f16(x as f32)) as f64
}

//! One file per pass, each describing its pass once, as data: which pipeline it runs, what it binds (reads are
//! sampled images, writes storage images, as the shader declares them), its group size and what its groups
//! cover, its push constants. `frame` lists a frame's passes in order; the recorder in context.rs derives
//! bindings, barriers, dispatches and timestamps from that list, so fusing or splitting passes is a change here.

pub(crate) mod bindings;
pub(crate) mod classify;
pub(crate) mod filter;
pub(crate) mod prepare;
mod roles;
#[cfg(test)]
pub(crate) mod state_tests;
pub(crate) mod tile_classification;
pub(crate) mod variants;

use crate::dispatch::DebugView;
use crate::packing::TILE;
use crate::settings::MAX_FILTER_PASSES;
use ash::vk;
use bindings::{image, Binding, BindingTable, Resource};
use filter::FilterPush;
pub(crate) use roles::{roles, Role};

/// Invocations of every pass's workgroup, x by y: one invocation per pixel of two stacked tiles (per tile in
/// prepare). Generated into GLSL as the shaders' local size.
pub(crate) const GROUP: [u32; 2] = [8, 8];
/// Invocations of the workgroups of tile classification and the filter passes: 2x2 blocks of `GROUP` pixels.
/// Fewer, larger groups launch faster where most blocks are cleared and return at once (an H100 spent 0.08 ms per
/// 4K filter pass launching 8x8 groups that returned at once). Generated into GLSL.
pub(crate) const WIDE_GROUP: [u32; 2] = [16, 16];
/// Radius of the local-moment window (17x17) of tile classification and its uniform-tile test. Generated into
/// GLSL; the CPU reference uses the same constant.
pub(crate) const MOMENT_RADIUS: u32 = 8;
/// Classification's surface window (with the run features) keeps each window pixel's unit normal in shared memory
/// as three signed integers of this scale, 10 bits each in one word: a quarter of the float normals' bytes (a first
/// version with float normals and per-tap sums in shared memory made classification 3.3x slower on an H100 at 4K,
/// every preset: shared memory bounds its occupancy). Generated into GLSL; the CPU reference quantizes the same
/// way.
pub(crate) const SURFACE_NORMAL_SCALE: u32 = 511;
/// Two codes lie on one surface when their integer dot product reaches this: the turned-normal cosine
/// (`state::TURNED_NORMAL_COS_PERCENT` / 100) of the scale squared, rounded up. An exact integer test, so the GPU
/// and the reference decide alike wherever they quantized alike.
pub(crate) const SURFACE_DOT_MIN: u32 =
    (crate::state::TURNED_NORMAL_COS_PERCENT * SURFACE_NORMAL_SCALE * SURFACE_NORMAL_SCALE).div_ceil(100);
/// Classification's surface window keeps each window row's weighted lit count and weight over the row's surface
/// as 16-bit fixed-point numbers of this scale (a row's weight is at most the window's 17: under 32). Generated
/// into GLSL; the CPU reference rounds the same way.
pub(crate) const SURFACE_SUM_SCALE: u32 = 2048;
const _: () = assert!((2 * MOMENT_RADIUS + 1) * SURFACE_SUM_SCALE < 1 << 16);

// What the shaders' layouts assume of these sizes: a group is one tile wide and two tiles tall (classification
// decides two tiles per group, its window is one tile column either side and two tile rows above and below),
// and the moment radius is one tile width.
const _: () = assert!(GROUP[0] == TILE[0] && GROUP[1] == 2 * TILE[1] && MOMENT_RADIUS == TILE[0] && TILE[0] * TILE[1] == 32);
// The filter works on whole blocks.
const _: () = assert!(WIDE_GROUP[0] % GROUP[0] == 0 && WIDE_GROUP[1] % GROUP[1] == 0);
// Classification holds one row of its moment window, the group's width and the radius either side, in 32 bits.
const _: () = assert!(WIDE_GROUP[0] + 2 * MOMENT_RADIUS <= 32);
// Penumbra guidance in classification: each invocation sums one share of one window tile's hit distances, into
// the moment-sum rows (one slot per invocation).
const WINDOW_TILE_COUNT: u32 = (WIDE_GROUP[0] / TILE[0] + 2) * (WIDE_GROUP[1] / TILE[1] + 4);
const _: () = assert!((WIDE_GROUP[0] * WIDE_GROUP[1]) % WINDOW_TILE_COUNT == 0 && 32 % (WIDE_GROUP[0] * WIDE_GROUP[1] / WINDOW_TILE_COUNT) == 0);
// The surface window: each invocation fetches the same number of window pixel pairs (its fetch loop has no bound
// test).
const _: () = assert!(WINDOW_TILE_COUNT * TILE[0] * TILE[1] / 2 % (WIDE_GROUP[0] * WIDE_GROUP[1]) == 0);
// A moving shadow's test: each invocation sums the same number of window pixels, consecutive in one row of one
// window tile (`dnsr_sum_previous_moments`).
const MOVING_PIXELS: u32 = WINDOW_TILE_COUNT * TILE[0] * TILE[1] / (WIDE_GROUP[0] * WIDE_GROUP[1]);
/// A moving shadow's test counts samples and moment means in fixed point: this many units are one sample
/// (the moments' unorm14 mean code over 16). Generated into GLSL; the CPU reference counts the same.
pub(crate) const MOVING_SAMPLE_UNIT: u32 = 1024;
const _: () = assert!((crate::packing::MOMENTS_MEAN_MAX + 8) >> 4 == MOVING_SAMPLE_UNIT);
/// The test's margin, in samples, beyond the Bernoulli spread (a few samples' difference is no motion).
pub(crate) const MOVING_MARGIN_SAMPLES: u32 = 2;
/// A pixel counts as still for the test where its motion vector is under 1 / this many pixels.
pub(crate) const STILL_MOTION_INV_PIXELS: u32 = 100;

// Hard tiles told by time (`Settings::hard_tile_frames`, `dnsr_quiet_tiles` and `dnsr_contradicts` in
// shaders/tile_classification.glsl, `reference::tile_classification::contradicts`).
/// A footprint texel held both values when its moments count at least this many samples...
pub(crate) const MIXED_TEXEL_SAMPLES: u32 = 8;
/// ...and their mean lies within this many percent of 0.5 (between 0.25 and 0.75).
pub(crate) const MIXED_TEXEL_SPREAD_PERCENT: u32 = 25;
const _: () = assert!(WINDOW_TILE_COUNT * TILE[0] * TILE[1] % (WIDE_GROUP[0] * WIDE_GROUP[1]) == 0 && TILE[0] % MOVING_PIXELS == 0);
const _: () = assert!(1 << (MAX_FILTER_PASSES - 1) <= GROUP[0] && 1 << (MAX_FILTER_PASSES - 1) <= GROUP[1]);

/// Lights one dispatch of the filter's light-slot variants filters (a record of more lights runs several).
/// Generated into GLSL as DNSR_LIGHT_SLOTS.
pub(crate) const LIGHT_SLOTS: usize = 4;
/// Fewer lights than this left over after the full groups run a single-light dispatch each. Two lights in one
/// dispatch of the later passes were slower than two dispatches on an H100 at 4K (typical scene: 0.344 / 0.338
/// against 0.325 / 0.305 ms), three and four faster (BENCHMARKS.md "Several lights per record").
const MIN_LIGHTS_PER_GROUP: usize = 3;

/// How many dispatches a filter pass of `n` lights runs: full groups of LIGHT_SLOTS lights, then either one group
/// of the rest or, when the rest are fewer than MIN_LIGHTS_PER_GROUP, one dispatch each.
pub(crate) fn light_group_count(n: usize) -> usize {
    let rest = n % LIGHT_SLOTS;
    n / LIGHT_SLOTS + if rest >= MIN_LIGHTS_PER_GROUP { 1 } else { rest }
}

/// The lights (positions in the record's list) of dispatch `k` of `light_group_count(n)`.
pub(crate) fn light_group(n: usize, k: usize) -> std::ops::Range<usize> {
    let full = n / LIGHT_SLOTS;
    let start = if k <= full { k * LIGHT_SLOTS } else { k - full + full * LIGHT_SLOTS };
    let len = if k < full { LIGHT_SLOTS } else if n % LIGHT_SLOTS >= MIN_LIGHTS_PER_GROUP { n % LIGHT_SLOTS } else { 1 };
    start..start + len
}

/// Specialization constants (booleans) that select what a pass compiles in; their ids are generated into GLSL.
/// Features only some frames use sit behind them rather than behind runtime branches: merely present behind a
/// branch that was never taken, penumbra guidance slowed unguided classification on an H100 at 4K from 0.409 to
/// 0.513 ms (and the filter's never-executed tile-blocker fetch made lavapipe leak JIT memory every frame), and
/// the stable-run-aware history slowed Balanced, which never uses it, from 0.410 to 0.463 ms.
/// `DNSR_SPEC_PENUMBRA_GUIDED`: the dispatch has hit distances.
pub(crate) const SPEC_PENUMBRA_GUIDED: u32 = 0;
/// `DNSR_SPEC_STABLE_HISTORY`: the run features are on (`Settings::uses_runs`: stable history or converged pixels).
/// Classification and every filter pass: the filter looks for final pixels only with them, and the first pass takes
/// geometric normals only with them (Balanced, which has neither, took 1.090 ms at 4K on an H100 with both behind
/// runtime tests, 1.055 with both behind this constant: docs/bench/h100-2026-12-08-spec-gates).
pub(crate) const SPEC_STABLE_HISTORY: u32 = 1;
/// `DNSR_SPEC_HARD_LIGHT`: the light has no size (`ShadowsDispatch::hard_light`); classification and the first
/// filter pass only. A runtime test of a flag in either, in every form tried, made lavapipe (Mesa 22.3) leak JIT
/// memory on every dispatch of those passes (the minimal example's LeakSanitizer run), lights of no size or not.
pub(crate) const SPEC_HARD_LIGHT: u32 = 2;
/// `DNSR_SPEC_MOVING_SHADOWS`: classification tells a shadow that moved over a still surface
/// (`Settings::moving_shadow_sigmas` > 0, with the run features). Behind its own constant: its fetches and sums cost
/// Quality's classification 0.810 -> 0.896 ms on an H100 at 4K (docs/do-no-harm.md), which a context that does not
/// ask for it must not pay.
pub(crate) const SPEC_MOVING_SHADOWS: u32 = 3;
/// Specialization constant ids the passes set: 0..SPEC_COUNT.
pub(crate) const SPEC_COUNT: usize = 4;

/// Which specialization constants are on for one dispatch of a pass (bit i: constant id i).
pub(crate) type Specialization = u32;

/// What one invocation of a pass covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Grid {
    /// A pixel of the render rectangle.
    Pixels,
    /// A tile of the render rectangle.
    Tiles,
}

/// One compute pass of a frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pass {
    pub role: Role,
    /// Every resource the pass binds; unset entries stay null.
    pub bindings: BindingTable,
    pub grid: Grid,
    /// Invocations per workgroup, x by y (the shader's local size).
    pub group: [u32; 2],
    pub push: Option<FilterPush>,
    /// The specialization constants on for this dispatch (see `Specialization`).
    pub spec: Specialization,
    /// A disabled pass is not dispatched; its timestamp is still written, so its time reads as zero.
    pub enabled: bool,
}

impl Pass {
    /// Groups covering the render rectangle `extent` (pixels).
    pub(crate) fn group_count(&self, extent: [u32; 2]) -> [u32; 3] {
        let covered = match self.grid {
            Grid::Pixels => extent,
            Grid::Tiles => [extent[0].div_ceil(TILE[0]), extent[1].div_ceil(TILE[1])],
        };
        [covered[0].div_ceil(self.group[0]), covered[1].div_ceil(self.group[1]), 1]
    }
}

/// Most passes one frame records: prepare, classification and every filter pass.
pub(crate) const MAX_PASSES: usize = 2 + MAX_FILTER_PASSES as usize;

/// The passes of one frame, in recording order (a fixed array: the recording path allocates nothing).
pub(crate) struct FramePasses {
    passes: [Pass; MAX_PASSES],
    count: usize,
}

impl FramePasses {
    pub(crate) fn iter(&self) -> impl Iterator<Item = &Pass> {
        self.passes[..self.count].iter()
    }

}

/// The filter passes a light runs: the configured ones, or for a light of no size (`ShadowsDispatch::hard_light`)
/// only the first, which writes its output (every pixel passes through the others). The CPU reference runs the same.
pub(crate) fn light_filter_passes(configured: u32, hard_light: bool) -> u32 {
    if hard_light { 1 } else { configured }
}

/// How many passes a frame of `filter_passes` filter passes records.
pub(crate) fn pass_count(filter_passes: u32) -> usize {
    2 + filter_passes as usize
}

/// Pass `index` of the frame (see `frame`) on its own: a record of several lights builds one pass of one light
/// at a time instead of every light's whole frame.
pub(crate) fn pass(v: &FrameViews, index: usize, filter_passes: u32, run_prepare: bool, debug_view: DebugView) -> Pass {
    match index {
        0 => prepare::pass(v, run_prepare),
        1 => tile_classification::pass(v),
        _ => filter::pass(v, index as u32 - 2, filter_passes, debug_view),
    }
}

/// The frame: prepare (skipped when the host's mask already holds lit bits), tile classification, then
/// `filter_passes` a-trous passes, the last one writing the host's output (or a debug view).
pub(crate) fn frame(v: &FrameViews, filter_passes: u32, run_prepare: bool, debug_view: DebugView) -> FramePasses {
    let mut passes = [prepare::pass(v, run_prepare); MAX_PASSES];
    let count = pass_count(filter_passes);
    for (index, p) in passes.iter_mut().enumerate().take(count).skip(1) {
        *p = pass(v, index, filter_passes, run_prepare, debug_view);
    }
    FramePasses { passes, count }
}

/// A stable pixel (`Settings::stable_history_samples`) whose last n samples were identical has its history clamped
/// to within this many / n of them (the rule of three). Generated into GLSL.
pub(crate) const RUN_CLAMP_SAMPLES: u32 = 3;

/// With converged pixels on (`Settings::converged_samples`), every receiver that is not converged stores a variance
/// of at least 1 / this, so that a variance of exactly 0 marks the converged ones alone: float rounding cannot make
/// another pixel look converged to the filter (a standard deviation of 0.001, far below what the edge stop
/// resolves; f16 holds it). Generated into GLSL.
pub(crate) const UNCONVERGED_VARIANCE_INV: u32 = 1_000_000;
/// The same floor where the intermediates are float16 (`Precision::Fp16`): 2^-14, the smallest normal float16.
/// 1e-6 would be stored as a subnormal, which a device may flush to 0, and the pixel would read as converged.
pub(crate) const UNCONVERGED_VARIANCE_INV_FP16: u32 = 16_384;

/// Penumbra guidance's hard penumbrae (`Settings::hard_penumbra_pixels`) need blockers at least this many pixel
/// footprints from the receiver on average: nearer hits are mostly the receiver's own surface under a light near its
/// horizon, whose partial visibility no blocker distance describes (the scene family's 6-10 degree lights: faces
/// lit at grazing angles lost 0.02-0.03 RMSE without this; a limit of 1 kept those losses and won 0.02 on one
/// hard-shadow scene's contact shadows, 2 lost it: docs/do-no-harm.md). Generated into GLSL.
pub(crate) const HARD_PENUMBRA_MIN_BLOCKER_PIXELS: u32 = 2;

/// Tile metadata bit: the tile needs no temporal or spatial work; its value is in `TILE_LIT`.
pub(crate) const TILE_CLEARED: u32 = 1 << 0;
/// Tile metadata bit: a cleared tile is lit (1) rather than shadowed (0).
pub(crate) const TILE_LIT: u32 = 1 << 1;

const GENERAL: vk::ImageLayout = vk::ImageLayout::GENERAL;

/// Everything the passes of one frame of one light bind.
pub(crate) struct FrameViews {
    /// This light's slot of the constants buffer (its `FrameConstants`).
    pub constants: Binding,
    pub hit_mask: Binding,
    /// The host's visibility (a visibility input), the reconstructed one (a checkerboard input), or null (no
    /// pass declares it).
    pub visibility: Binding,
    /// Where prepare reconstructs the visibility of a checkerboard input (null otherwise).
    pub visibility_out: vk::ImageView,
    pub depth: Binding,
    pub velocity: Binding,
    pub normals: Binding,
    /// The host's hit distances (penumbra guidance), or an internal image of a float format standing in for them
    /// when the dispatch has none (the shader then never reads it).
    pub hit_distance: Binding,
    /// Each tile's blocker estimate (penumbra guidance).
    pub tile_blocker: vk::ImageView,
    /// The specialization constants this frame turns on (penumbra guidance, stable history).
    pub spec: Specialization,
    /// The host output, already in GENERAL when the final pass runs.
    pub output: vk::ImageView,
    /// The lit-bit tile mask: dnsr's internal image, or the host's mask when it already holds lit bits.
    pub tile_mask: Binding,
    /// The exactly shadowed pixels per tile (visibility input).
    pub tile_dark: vk::ImageView,
    pub tile_meta: vk::ImageView,
    pub reprojection: vk::ImageView,
    pub history: vk::ImageView,
    /// The filter's signal between passes (filter pass 0's and pass 2's output): a view of the frame moments'
    /// memory with a hit mask.
    pub signal: vk::ImageView,
    /// Linear depth and normal: the first filter pass writes this frame's, the later filter passes read it as their
    /// guide. The light's depth copy, or where another light of the record writes that one (lights recorded
    /// together), its transient set's frame depth.
    pub depth_copy: vk::ImageView,
    /// Last frame's linear depth and normal, which classification reads: the light's depth copy, or the one the
    /// lights recorded together share (the same view as `depth_copy` otherwise); the host's previous depth where it
    /// gives it (`ContextCreateInfo::host_previous_gbuffer`).
    pub previous_depth: Binding,
    /// The host's previous normals (`ContextCreateInfo::host_previous_gbuffer`; null otherwise, and not declared by
    /// the variant that runs then).
    pub previous_normals: Binding,
    /// Last frame's moments (classification reads them), then this frame's (filter pass 0 copies them in).
    pub kept_moments: vk::ImageView,
    /// This frame's moments, written by classification (transient).
    pub frame_moments: vk::ImageView,
    pub previous_tile_quiet: vk::ImageView,
    pub tile_quiet: vk::ImageView,
    /// The engine's own images (slot i: binding ENGINE_BINDING_BASE + i), for its shader variants.
    pub engine: [Binding; crate::dispatch::MAX_ENGINE_IMAGES],
    /// tan(light angular diameter / 2) of penumbra guidance (0 without): the one per-light filter constant.
    pub penumbra_tan_half_angle: f32,
}

impl FrameViews {
    /// The bindings every pass shares: constants, the G-buffer and the engine's images.
    fn base_table(&self) -> BindingTable {
        let mut t: BindingTable = [Binding::default(); bindings::RESOURCE_COUNT];
        t[Resource::Constants as usize] = self.constants;
        t[Resource::Depth as usize] = self.depth;
        t[Resource::Normals as usize] = self.normals;
        for (slot, &b) in self.engine.iter().enumerate() {
            t[Resource::engine(slot).expect("slot below MAX_ENGINE_IMAGES") as usize] = b;
        }
        t
    }
}

fn internal(view: vk::ImageView) -> Binding {
    image(view, GENERAL)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn light_groups_cover_every_light_once() {
        for n in 1..=crate::dispatch::MAX_LIGHTS_PER_RECORD {
            let groups: Vec<_> = (0..light_group_count(n)).map(|k| light_group(n, k)).collect();
            let lights: Vec<usize> = groups.iter().flat_map(|g| g.clone()).collect();
            assert_eq!(lights, (0..n).collect::<Vec<_>>(), "{n} lights: {groups:?}");
            assert!(groups.iter().all(|g| g.len() == 1 || (MIN_LIGHTS_PER_GROUP..=LIGHT_SLOTS).contains(&g.len())), "{n}: {groups:?}");
        }
        assert_eq!(light_group_count(2), 2);
        assert_eq!(light_group_count(7), 2);
        assert_eq!(light_group(6, 2), 5..6);
    }
}

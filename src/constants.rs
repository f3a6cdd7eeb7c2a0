//! The data the host hands every pass: one declaration, in Rust, from which the GLSL side is generated.
//!
//! `shaders/generated/dnsr_constants.glsl` is written from these definitions (`DNSR_BLESS=1 cargo test
//! generated_glsl`) and a test fails when the committed file differs, so the shader and host layouts cannot
//! drift apart. The blocks are declared with `gpu_block!` (glsl.rs); those of one pass with that pass (the filter's
//! push constants in passes/filter.rs, the classifier's constants in passes/classify), and the header gathers
//! them with the flags and sizes of every table below it.

use crate::glsl::gpu_block;
use crate::passes::classify::{ClassifyConstants, CLASSIFY_BOUND_INTERVAL, CLASSIFY_CASCADES_INVERTED, CLASSIFY_REJECT_LIT};
use crate::passes::filter::{FilterPush, PASS_SKIP_CLEARED, PASS_WRITE_INTERNAL};
use crate::settings::Settings;
use std::fmt::Write as _;

gpu_block! {
    /// Per-dispatch constants, written with `vkCmdUpdateBuffer` at the start of each recorded frame.
    pub(crate) struct FrameConstants as "DnsrFrameConstants" {
        /// Clip (Vulkan NDC + depth) to view space of the current frame.
        projection_inverse: [[f32; 4]; 4],
        /// Current clip space to previous clip space (camera motion only).
        reprojection: [[f32; 4]; 4],
        /// Current clip space to world space.
        view_projection_inverse: [[f32; 4]; 4],
        /// xyz: eye position in world space; w: depth similarity sigma (linear depth units).
        eye_depth_sigma: [f32; 4],
        /// xy: motion vector scale; z: normal unpack multiply; w: normal unpack add.
        motion_normals: [f32; 4],
        /// xy: render rectangle offset in pixels; zw: render rectangle extent in pixels.
        rect: [u32; 4],
        /// x: DNSR_FLAG_* bits; y: checkerboard phase (a checkerboard input traced the pixels with (x + y) % 2 ==
        /// phase); zw: unused (nothing depends on the host's frame index).
        flags: [u32; 4],
        /// xy: 1 / rect extent; zw: 1 / size of the internal images (the context's size).
        inv_extent: [f32; 4],
        /// x: disocclusion threshold at N.V = 1; y: at grazing; z: (1 - N.V) exponent; w: history clamp width in sigmas.
        disocclusion: [f32; 4],
        /// x: history rejection falloff; y: rejection sigma floor; z: variance boost below this many samples; w: the
        /// fp32 path's signal scale (`state::signal_scale`).
        rejection: [f32; 4],
        /// x: samples for full history trust; y: minimum current-frame blend; z: max history samples; w: spatial falloff.
        temporal: [f32; 4],
        /// x: cross tap weight; y: normal power; z: output contrast; w: shadow sigma floor.
        filtering: [f32; 4],
        /// x: identical samples in a row that make a pixel stable (0: never); y: samples of the other value after a
        /// stable run that restart its history (0: never); z: identical samples in a row that make a pixel
        /// converged (0: never); w: penumbra guidance's hard penumbra half-width in pixels (0: off).
        runs: [f32; 4],
        /// A shadow that moved over a still surface (the run features' pipelines): x: the neighbourhood's change, in
        /// standard deviations, that counts as moved (0: never); y: the history clamp's width there, in sigmas; z:
        /// the quiet frames that make a tile hard (`Settings::hard_tile_frames`, 0: never). w: the cosine within which
        /// the first filter pass takes geometric normals (`Settings::geometric_normal_min_cos`, 2: off).
        moving: [f32; 4],
        /// Penumbra guidance (the pipelines specialized with DNSR_SPEC_PENUMBRA_GUIDED): x: tan(light angular diameter / 2); yz: a pixel's
        /// world-space size at linear view depth z is y + z * z; w: the kernel's sigma in penumbra half-widths.
        penumbra: [f32; 4],
        /// With DNSR_FLAG_LIGHT_POSITION: the light as a homogeneous world-space point (xyz: direction toward it,
        /// w 0; or its centre, w 1).
        light_position: [f32; 4],
        /// With DNSR_FLAG_LIGHT_POSITION: x: sin of the light's angular radius (`ShadowsDispatch::light_angular_size`
        /// / 2; 0: a light of no size); yzw: unused.
        light_extent: [f32; 4],
    }
}

impl FrameConstants {
    /// Fills the settings part of the per-frame constants.
    pub(crate) fn set_settings(&mut self, s: &Settings) {
        self.disocclusion = [
            s.disocclusion_threshold_facing,
            s.disocclusion_threshold_grazing,
            s.disocclusion_angle_exponent,
            s.history_clamp_sigmas,
        ];
        self.rejection = [
            s.history_rejection_falloff,
            s.history_rejection_min_sigma,
            s.variance_boost_samples,
            crate::state::signal_scale(s.variance_boost_samples),
        ];
        self.runs = [s.stable_history_samples, s.history_flip_samples, s.converged_samples, s.hard_penumbra_pixels];
        self.temporal = [s.full_history_samples, s.min_current_weight, s.max_history_samples, s.spatial_falloff];
        self.filtering = [s.kernel_cross_weight, s.normal_power, s.output_contrast, s.min_shadow_sigma];
        self.moving = [s.moving_shadow_sigmas, s.moving_history_clamp_sigmas, s.hard_tile_frames, s.geometric_normal_min_cos()];
    }
}

/// Frame flag: treat every pixel as disoccluded (camera cut, first frame, resize).
pub(crate) const FLAG_RESET: u32 = 1 << 0;
/// Frame flag: depth 0 is far, closest-depth means largest depth.
pub(crate) const FLAG_DEPTH_INVERTED: u32 = 1 << 1;
/// Frame flag: the host's hit mask holds lit bits (read by the checkerboard input's prepare, which always runs).
pub(crate) const FLAG_LIT_BIT_MASK: u32 = 1 << 2;
/// Frame flag: a checkerboard input (flags.y holds the phase): classification knows which pixels were traced.
pub(crate) const FLAG_CHECKERBOARD: u32 = 1 << 3;
/// Frame flag: the host gave the light's position (`ShadowsDispatch::light_position`): receivers turned away from
/// it keep their shadowed samples.
pub(crate) const FLAG_LIGHT_POSITION: u32 = 1 << 4;

/// Binding names shared by shaders and host. The host finds each binding's number through reflection.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const GLSL_FLAGS: &[(&str, u32)] = &[
    ("DNSR_FLAG_RESET", FLAG_RESET),
    ("DNSR_FLAG_DEPTH_INVERTED", FLAG_DEPTH_INVERTED),
    ("DNSR_FLAG_LIT_BIT_MASK", FLAG_LIT_BIT_MASK),
    ("DNSR_FLAG_CHECKERBOARD", FLAG_CHECKERBOARD),
    ("DNSR_FLAG_LIGHT_POSITION", FLAG_LIGHT_POSITION),
    ("DNSR_PASS_WRITE_INTERNAL", PASS_WRITE_INTERNAL),
    ("DNSR_PASS_SKIP_CLEARED", PASS_SKIP_CLEARED),
    ("DNSR_TILE_CLEARED", crate::passes::TILE_CLEARED),
    ("DNSR_TILE_LIT", crate::passes::TILE_LIT),
    ("DNSR_DEBUG_VIEW_NONE", crate::dispatch::DebugView::None as u32),
    ("DNSR_DEBUG_VIEW_TILE_CLASSIFICATION", crate::dispatch::DebugView::TileClassification as u32),
    ("DNSR_DEBUG_VIEW_SAMPLE_COUNT", crate::dispatch::DebugView::SampleCount as u32),
    ("DNSR_DEBUG_VIEW_VARIANCE", crate::dispatch::DebugView::Variance as u32),
    ("DNSR_DEBUG_VIEW_DISOCCLUSION", crate::dispatch::DebugView::Disocclusion as u32),
    ("DNSR_DEBUG_VIEW_SAMPLE_RUN", crate::dispatch::DebugView::SampleRun as u32),
    ("DNSR_CLASSIFY_REJECT_LIT", CLASSIFY_REJECT_LIT),
    ("DNSR_CLASSIFY_BOUND_INTERVAL", CLASSIFY_BOUND_INTERVAL),
    ("DNSR_CLASSIFY_CASCADES_INVERTED", CLASSIFY_CASCADES_INVERTED),
];

/// Sizes shared by shaders and host, as plain GLSL ints (usable in `layout(local_size_x = ...)` and array sizes).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const GLSL_INTS: &[(&str, u32)] = &[
    ("DNSR_TILE_WIDTH", crate::packing::TILE[0]),
    ("DNSR_TILE_HEIGHT", crate::packing::TILE[1]),
    ("DNSR_GROUP_WIDTH", crate::passes::GROUP[0]),
    ("DNSR_GROUP_HEIGHT", crate::passes::GROUP[1]),
    ("DNSR_WIDE_GROUP_WIDTH", crate::passes::WIDE_GROUP[0]),
    ("DNSR_WIDE_GROUP_HEIGHT", crate::passes::WIDE_GROUP[1]),
    ("DNSR_CLASSIFY_TILES_PER_GROUP", crate::passes::classify::TILES_PER_GROUP),
    ("DNSR_MOMENT_RADIUS", crate::passes::MOMENT_RADIUS),
    ("DNSR_SURFACE_NORMAL_SCALE", crate::passes::SURFACE_NORMAL_SCALE),
    ("DNSR_SURFACE_DOT_MIN", crate::passes::SURFACE_DOT_MIN),
    ("DNSR_SURFACE_SUM_SCALE", crate::passes::SURFACE_SUM_SCALE),
    ("DNSR_MAX_SAMPLE_RUN", crate::settings::MAX_SAMPLE_RUN),
    ("DNSR_RUN_CLAMP_SAMPLES", crate::passes::RUN_CLAMP_SAMPLES),
    ("DNSR_UNCONVERGED_VARIANCE_INV", crate::passes::UNCONVERGED_VARIANCE_INV),
    ("DNSR_UNCONVERGED_VARIANCE_INV_FP16", crate::passes::UNCONVERGED_VARIANCE_INV_FP16),
    ("DNSR_SIGNAL_MAX_DEVIATION_CODE", crate::state::SIGNAL_MAX_DEVIATION_CODE),
    ("DNSR_SIGNAL_SKY_CODE_ABOVE", crate::state::SIGNAL_SKY_CODE_ABOVE),
    ("DNSR_SIGNAL_FINAL_CODE", crate::state::SIGNAL_FINAL_CODE),
    ("DNSR_SIGNAL_FINAL_CODE_ABOVE", crate::state::SIGNAL_FINAL_CODE_ABOVE),
    ("DNSR_DEPTH_CODE_BITS", crate::state::DEPTH_CODE_BITS),
    ("DNSR_DEPTH_CODE_MANTISSA_BITS", crate::state::DEPTH_CODE_MANTISSA_BITS),
    ("DNSR_DEPTH_CODE_SHIFT", crate::state::DEPTH_CODE_SHIFT),
    ("DNSR_DEPTH_CODE_OFFSET", crate::state::DEPTH_CODE_OFFSET),
    ("DNSR_DEPTH_COPY_NORMAL_BITS", crate::state::DEPTH_COPY_NORMAL_BITS),
    ("DNSR_TURNED_NORMAL_COS_PERCENT", crate::state::TURNED_NORMAL_COS_PERCENT),
    ("DNSR_PLANE_LINE_COS2_PERCENT", crate::state::PLANE_LINE_COS2_PERCENT),
    ("DNSR_FOOTPRINT_SLOPE_PERCENT", crate::state::FOOTPRINT_SLOPE_PERCENT),
    ("DNSR_FOOTPRINT_MAX_SLOPE", crate::state::FOOTPRINT_MAX_SLOPE),
    ("DNSR_MOMENTS_MEAN_BITS", crate::packing::MOMENTS_MEAN_BITS),
    ("DNSR_MOMENTS_COUNT_BITS", crate::packing::MOMENTS_COUNT_BITS),
    ("DNSR_MOMENTS_MEAN_MAX", crate::packing::MOMENTS_MEAN_MAX),
    ("DNSR_COUNT_MANTISSA_BITS", crate::packing::COUNT_MANTISSA_BITS),
    ("DNSR_COUNT_SUBNORMAL_SCALE", crate::packing::COUNT_SUBNORMAL_SCALE),
    ("DNSR_COUNT_CODE_OFFSET", crate::packing::COUNT_CODE_OFFSET),
    ("DNSR_COUNT_MAX", crate::packing::COUNT_MAX),
    ("DNSR_HARD_PENUMBRA_MIN_BLOCKER_PIXELS", crate::passes::HARD_PENUMBRA_MIN_BLOCKER_PIXELS),
    ("DNSR_SPEC_ID_PENUMBRA_GUIDED", crate::passes::SPEC_PENUMBRA_GUIDED),
    ("DNSR_SPEC_ID_STABLE_HISTORY", crate::passes::SPEC_STABLE_HISTORY),
    ("DNSR_SPEC_ID_MOVING_SHADOWS", crate::passes::SPEC_MOVING_SHADOWS),
    ("DNSR_MOVING_SAMPLE_UNIT", crate::passes::MOVING_SAMPLE_UNIT),
    ("DNSR_MOVING_MARGIN_SAMPLES", crate::passes::MOVING_MARGIN_SAMPLES),
    ("DNSR_STILL_MOTION_INV_PIXELS", crate::passes::STILL_MOTION_INV_PIXELS),
    ("DNSR_MAX_QUIET_FRAMES", crate::settings::MAX_QUIET_FRAMES),
    ("DNSR_MIXED_TEXEL_SAMPLES", crate::passes::MIXED_TEXEL_SAMPLES),
    ("DNSR_MIXED_TEXEL_SPREAD_PERCENT", crate::passes::MIXED_TEXEL_SPREAD_PERCENT),
    ("DNSR_SPEC_ID_HARD_LIGHT", crate::passes::SPEC_HARD_LIGHT),
    ("DNSR_LIGHT_SLOTS", crate::passes::LIGHT_SLOTS as u32),
    ("DNSR_MAX_CASCADES", crate::passes::classify::MAX_CASCADES as u32),
    ("DNSR_MAX_CLASSIFY_TAPS", crate::passes::classify::MAX_TAPS as u32),
];

/// The complete text of `shaders/generated/dnsr_constants.glsl`.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) fn generated_glsl() -> String {
    let mut s = String::from(
        "// Generated from src/constants.rs by `DNSR_BLESS=1 cargo test generated_glsl`. Do not edit.\n\
         #ifndef DNSR_CONSTANTS_GLSL\n#define DNSR_CONSTANTS_GLSL\n\n",
    );
    s += &FrameConstants::glsl();
    s.push('\n');
    s += &FilterPush::glsl();
    s.push('\n');
    s += &ClassifyConstants::glsl();
    s.push('\n');
    for (name, value) in GLSL_FLAGS {
        let _ = writeln!(s, "#define {name} {value}u");
    }
    s.push('\n');
    for (name, value) in GLSL_INTS {
        let _ = writeln!(s, "#define {name} {value}");
    }
    // The classifier's blocker-search taps: the first n of these for n taps (each prefix is spread over the disc).
    let _ = writeln!(s, "\n#define DNSR_CLASSIFY_MAX_SLOPE {:?}", crate::passes::classify::MAX_SLOPE);
    s += "const vec2 DNSR_CLASSIFY_DISC[DNSR_MAX_CLASSIFY_TAPS] = vec2[](\n";
    let disc = crate::passes::classify::blocker_disc();
    for (i, [x, y]) in disc.iter().enumerate() {
        let _ = writeln!(s, "    vec2({x:?}, {y:?}){}", if i + 1 < disc.len() { "," } else { "" });
    }
    s += ");\n";
    s.push_str("\n#endif\n");
    s
}

//! The data the host hands every pass: one declaration, in Rust, from which the GLSL side is generated.
//!
//! `shaders/generated/dnsr_constants.glsl` is written from these definitions (`DNSR_BLESS=1 cargo test
//! generated_glsl`) and a test fails when the committed file differs, so the shader and host layouts cannot
//! drift apart. Every member is a 16-byte vector or a matrix, which makes `#[repr(C)]` and std140 agree without
//! padding rules to remember.

use std::fmt::Write as _;

/// A Rust type with a GLSL spelling of identical std140 / `repr(C)` layout.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) trait GlslType {
    const GLSL: &'static str;
}
impl GlslType for [f32; 4] {
    const GLSL: &'static str = "vec4";
}
impl GlslType for [u32; 4] {
    const GLSL: &'static str = "uvec4";
}
impl GlslType for [[f32; 4]; 4] {
    const GLSL: &'static str = "mat4";
}

/// Declares a `#[repr(C)]` Pod struct and the GLSL struct of the same layout.
macro_rules! gpu_block {
    ($(#[$m:meta])* pub(crate) struct $name:ident as $glsl:literal {
        $( $(#[$fm:meta])* $f:ident : $t:ty ),* $(,)?
    }) => {
        $(#[$m])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
        pub(crate) struct $name { $( $(#[$fm])* pub $f: $t ),* }
        #[cfg_attr(not(test), allow(dead_code))]
        impl $name {
            /// The GLSL declaration of this block's struct.
            pub(crate) fn glsl() -> String {
                let mut s = format!("struct {} {{\n", $glsl);
                $( let _ = writeln!(s, "    {} {};", <$t as GlslType>::GLSL, stringify!($f)); )*
                s.push_str("};\n");
                s
            }
        }
    };
}

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
        /// Penumbra guidance (the pipelines specialized with DNSR_SPEC_PENUMBRA_GUIDED): x: tan(light angular diameter / 2); yz: a pixel's
        /// world-space size at linear view depth z is y + z * z; w: the kernel's sigma in penumbra half-widths.
        penumbra: [f32; 4],
    }
}

gpu_block! {
    /// Push constants of one filter pass.
    pub(crate) struct FilterPush as "DnsrFilterPush" {
        /// x: tap step in pixels; y: DNSR_PASS_* bits; z: pass index; w: DNSR_DEBUG_VIEW_* (final pass).
        pass: [u32; 4],
        /// The light-slot variants (several lights per dispatch; zero otherwise): x: lights in this dispatch
        /// (1..=DNSR_LIGHT_SLOTS); y: bit s set when slot s has penumbra guidance; zw: unused.
        lights: [u32; 4],
        /// The light-slot variants: slot s's tan(light angular diameter / 2) (penumbra.x of its constants; the
        /// other penumbra constants depend on the camera only and are read from slot 0's).
        light_tan_half_angle: [f32; 4],
    }
}

gpu_block! {
    /// Constants of the hybrid-shadows classifier (`Context::record_classify`), written with `vkCmdUpdateBuffer`
    /// next to the frame constants it also reads (render rectangle, camera, normal decode).
    pub(crate) struct ClassifyConstants as "DnsrClassifyConstants" {
        /// Cascade 0: world position (w = 1) to (u, v, depth) of its shadow map; affine.
        cascade0: [[f32; 4]; 4],
        /// Cascade 1, as cascade 0.
        cascade1: [[f32; 4]; 4],
        /// Cascade 2, as cascade 0.
        cascade2: [[f32; 4]; 4],
        /// Cascade 3, as cascade 0.
        cascade3: [[f32; 4]; 4],
        /// Column i, cascade i: x: its depth units per world unit along the light direction (> 0); y, z: its u and
        /// v units per world unit across the light direction; w: the blocker offset in its depth units.
        cascade_units: [[f32; 4]; 4],
        /// Column i, cascade i: the world displacement (xyz) of a unit step along its u at constant v and depth
        /// (the inverse matrix's first column): where the blocker-search taps lie in the world.
        cascade_axes_u: [[f32; 4]; 4],
        /// Column i, cascade i: as `cascade_axes_u`, along v.
        cascade_axes_v: [[f32; 4]; 4],
        /// xyz: unit world-space direction from the surfaces toward the light; w: tan(angular diameter / 2).
        light: [f32; 4],
        /// x: cascade count; y: blocker-search taps; z: tile cut-off (a tile is listed with more pixels to trace
        /// than this); w: DNSR_CLASSIFY_* bits.
        settings: [u32; 4],
    }
}

/// Classifier flag: pixels every blocker-search tap finds unoccluded are decided lit (else they are traced).
pub(crate) const CLASSIFY_REJECT_LIT: u32 = 1 << 0;
/// Classifier flag: the ray interval of a listed tile is bounded by the blockers the cascades show.
pub(crate) const CLASSIFY_BOUND_INTERVAL: u32 = 1 << 1;
/// Classifier flag: the shadow maps hold 1 at the light's near plane and 0 at its far plane.
pub(crate) const CLASSIFY_CASCADES_INVERTED: u32 = 1 << 2;

/// Frame flag: treat every pixel as disoccluded (camera cut, first frame, resize).
pub(crate) const FLAG_RESET: u32 = 1 << 0;
/// Frame flag: depth 0 is far, closest-depth means largest depth.
pub(crate) const FLAG_DEPTH_INVERTED: u32 = 1 << 1;
/// Frame flag: the host's hit mask holds lit bits (read by the checkerboard input's prepare, which always runs).
pub(crate) const FLAG_LIT_BIT_MASK: u32 = 1 << 2;
/// Frame flag: a checkerboard input (flags.y holds the phase): classification knows which pixels were traced.
pub(crate) const FLAG_CHECKERBOARD: u32 = 1 << 3;
/// Filter pass flag: write mean and variance to the internal intermediate image.
pub(crate) const PASS_WRITE_INTERNAL: u32 = 1 << 0;
/// Filter pass flag: groups whose two tiles are cleared write nothing (what the pass would write there is
/// already in place).
pub(crate) const PASS_SKIP_CLEARED: u32 = 1 << 1;
/// Filter pass flag: write the guide (linear depth and normal) that the later passes read per tap.
pub(crate) const PASS_WRITE_GUIDE: u32 = 1 << 2;
/// Filter pass flag (with PASS_WRITE_GUIDE): write the guide in every block, not only where this light's later
/// passes tap it. The first light of a record of several writes it for all of them, and the others' first passes
/// write none (the guide is the same for every light: 16 B per pixel each of them no longer writes).
pub(crate) const PASS_WRITE_GUIDE_EVERYWHERE: u32 = 1 << 3;

/// Binding names shared by shaders and host. The host finds each binding's number through reflection.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const GLSL_FLAGS: &[(&str, u32)] = &[
    ("DNSR_FLAG_RESET", FLAG_RESET),
    ("DNSR_FLAG_DEPTH_INVERTED", FLAG_DEPTH_INVERTED),
    ("DNSR_FLAG_LIT_BIT_MASK", FLAG_LIT_BIT_MASK),
    ("DNSR_FLAG_CHECKERBOARD", FLAG_CHECKERBOARD),
    ("DNSR_PASS_WRITE_INTERNAL", PASS_WRITE_INTERNAL),
    ("DNSR_PASS_SKIP_CLEARED", PASS_SKIP_CLEARED),
    ("DNSR_PASS_WRITE_GUIDE", PASS_WRITE_GUIDE),
    ("DNSR_PASS_WRITE_GUIDE_EVERYWHERE", PASS_WRITE_GUIDE_EVERYWHERE),
    ("DNSR_TILE_CLEARED", crate::passes::TILE_CLEARED),
    ("DNSR_TILE_LIT", crate::passes::TILE_LIT),
    ("DNSR_DEBUG_VIEW_NONE", crate::dispatch::DebugView::None as u32),
    ("DNSR_DEBUG_VIEW_TILE_CLASSIFICATION", crate::dispatch::DebugView::TileClassification as u32),
    ("DNSR_DEBUG_VIEW_SAMPLE_COUNT", crate::dispatch::DebugView::SampleCount as u32),
    ("DNSR_DEBUG_VIEW_VARIANCE", crate::dispatch::DebugView::Variance as u32),
    ("DNSR_DEBUG_VIEW_DISOCCLUSION", crate::dispatch::DebugView::Disocclusion as u32),
    ("DNSR_CLASSIFY_REJECT_LIT", CLASSIFY_REJECT_LIT),
    ("DNSR_CLASSIFY_BOUND_INTERVAL", CLASSIFY_BOUND_INTERVAL),
    ("DNSR_CLASSIFY_CASCADES_INVERTED", CLASSIFY_CASCADES_INVERTED),
];

/// Sizes shared by shaders and host, as plain GLSL ints (usable in `layout(local_size_x = ...)` and array sizes).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const GLSL_INTS: &[(&str, u32)] = &[
    ("DNSR_TILE_WIDTH", crate::passes::TILE[0]),
    ("DNSR_TILE_HEIGHT", crate::passes::TILE[1]),
    ("DNSR_GROUP_WIDTH", crate::passes::GROUP[0]),
    ("DNSR_GROUP_HEIGHT", crate::passes::GROUP[1]),
    ("DNSR_WIDE_GROUP_WIDTH", crate::passes::WIDE_GROUP[0]),
    ("DNSR_WIDE_GROUP_HEIGHT", crate::passes::WIDE_GROUP[1]),
    ("DNSR_CLASSIFY_TILES_PER_GROUP", crate::passes::classify::TILES_PER_GROUP),
    ("DNSR_MOMENT_RADIUS", crate::passes::MOMENT_RADIUS),
    ("DNSR_MAX_SAMPLE_RUN", crate::passes::MAX_SAMPLE_RUN),
    ("DNSR_RUN_CLAMP_SAMPLES", crate::passes::RUN_CLAMP_SAMPLES),
    ("DNSR_UNCONVERGED_VARIANCE_INV", crate::passes::UNCONVERGED_VARIANCE_INV),
    ("DNSR_UNCONVERGED_VARIANCE_INV_FP16", crate::passes::UNCONVERGED_VARIANCE_INV_FP16),
    ("DNSR_SIGNAL_MAX_DEVIATION_CODE", crate::state::SIGNAL_MAX_DEVIATION_CODE),
    ("DNSR_SIGNAL_SKY_CODE_ABOVE", crate::state::SIGNAL_SKY_CODE_ABOVE),
    ("DNSR_HARD_PENUMBRA_MIN_BLOCKER_PIXELS", crate::passes::HARD_PENUMBRA_MIN_BLOCKER_PIXELS),
    ("DNSR_SPEC_ID_PENUMBRA_GUIDED", crate::gpu::shader::SPEC_PENUMBRA_GUIDED),
    ("DNSR_SPEC_ID_STABLE_HISTORY", crate::gpu::shader::SPEC_STABLE_HISTORY),
    ("DNSR_LIGHT_SLOTS", crate::passes::LIGHT_SLOTS as u32),
    ("DNSR_MAX_CASCADES", crate::classify::MAX_CASCADES as u32),
    ("DNSR_MAX_CLASSIFY_TAPS", crate::classify::MAX_TAPS as u32),
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
    let _ = writeln!(s, "\n#define DNSR_CLASSIFY_MAX_SLOPE {:?}", crate::classify::MAX_SLOPE);
    s += "const vec2 DNSR_CLASSIFY_DISC[DNSR_MAX_CLASSIFY_TAPS] = vec2[](\n";
    let disc = crate::classify::blocker_disc();
    for (i, [x, y]) in disc.iter().enumerate() {
        let _ = writeln!(s, "    vec2({x:?}, {y:?}){}", if i + 1 < disc.len() { "," } else { "" });
    }
    s += ");\n";
    s.push_str("\n#endif\n");
    s
}

//! classify: the hybrid-shadows classifier, one workgroup per column of TILES_PER_GROUP 8x4 tiles (each tile's
//! pixels' verdicts combine into its hit-mask word and list record with shared-memory atomics, whatever the subgroup
//! width). Shader:
//! shaders/classify.comp (classify_cascade_array with the cascades as layers of one image). Recorded by
//! `Context::record_classify` on its own, before the engine's trace and the denoiser's frame, with its own
//! pipelines and descriptor sets (src/classify.rs).
//!
//! Here, as data: its group size, its tables (cascades, blocker-search taps, the tile records and counts the
//! engine reads), its constant block and how a dispatch fills it, and the dispatch description itself
//! (dispatch.rs). The reference (`reference::classify`) and the shader (through the generated GLSL) share them.

mod dispatch;

use crate::packing::TILE;
use crate::error::{Error, Result};
use crate::glsl::gpu_block;
use glam::{Mat3, Vec3, Vec4Swizzles};

pub use dispatch::{ClassifierBuffers, ClassifyDispatch, ShadowCascade};

/// Tiles per workgroup, stacked vertically: groups of one 32-pixel tile left the GPU half idle (NVIDIA runs at most
/// 32 groups per multiprocessor).
pub(crate) const TILES_PER_GROUP: u32 = 4;

/// Invocations per workgroup: one per pixel of TILES_PER_GROUP tiles.
pub(crate) const GROUP: [u32; 2] = [TILE[0], TILE[1] * TILES_PER_GROUP];

/// Groups covering a render rectangle of `extent` pixels.
pub(crate) fn group_count(extent: [u32; 2]) -> [u32; 3] {
    [extent[0].div_ceil(GROUP[0]), extent[1].div_ceil(GROUP[1]), 1]
}

/// Most shadow-map cascades one classify dispatch reads.
pub const MAX_CASCADES: usize = 4;
/// Blocker-search tap counts the classifier supports (`ClassifyDispatch::tap_count`).
pub const CLASSIFY_TAP_COUNTS: [u32; 4] = [8, 16, 24, 32];
/// Most blocker-search taps.
pub(crate) const MAX_TAPS: usize = 32;
/// Steepest receiver slope (tangent of the angle between its normal and the light) the blocker search follows
/// with the receiver's tangent plane; a steeper receiver's plane is flattened to this slope.
pub(crate) const MAX_SLOPE: f32 = 4.0;
/// Bytes of one tile record in `ClassifierBuffers::tiles`: uvec4 (x | y << 16 in tiles, mask of pixels to trace
/// with bit (y % 4) * 8 + (x % 8), min t, max t as float bits). Min t is 0 (the FidelityFX record's field): a ray
/// starts at its receiver, since blockers nearer than the blocker offset or between taps are invisible to the
/// cascades.
pub const CLASSIFY_TILE_BYTES: u64 = 16;
/// Bytes of `ClassifierBuffers::counts`: u32 words 0..3 `VkDispatchIndirectCommand` (tiles, 1, 1) and the tile
/// count; words 4..7 (32 x tiles, 1, 1, 0): one invocation per pixel of every listed tile, e.g. for
/// `vkCmdTraceRaysIndirectKHR` after a copy into a buffer with a device address.
pub const CLASSIFY_COUNTS_BYTES: u64 = 32;

/// The blocker-search taps in the unit disc: the centre, then Mitchell's best candidate from a fixed seed, so every
/// prefix (the first 8, 16, 24) is spread over the disc too; then each tap's radius r becomes r^2, so that the
/// inner disc gets more of them (of 24 taps, 10 lie within half the radius, where an even spread puts 6). The search
/// radius is the penumbra of a blocker at the cascade's near plane, the farthest one can be; a nearer blocker's
/// penumbra is narrower and only the inner taps can find it (with the taps spread evenly, the viewer's default scene
/// left 2.6 times the error on pixels decided lit at the rim of such penumbrae, 640x360, 3-degree sun, and traced 6%
/// more pixels). One table for the shader (generated GLSL) and the reference.
pub(crate) fn blocker_disc() -> [[f32; 2]; MAX_TAPS] {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f64 / (1u64 << 24) as f64
    };
    // The centre first: a thin blocker straight towards the light (a pole's umbra) is not left between taps.
    let mut points: Vec<[f64; 2]> = vec![[0.0, 0.0]];
    while points.len() < MAX_TAPS {
        let mut best = ([0.0, 0.0], -1.0);
        for _ in 0..(8 * points.len() + 1) {
            let (r, a) = (next().sqrt(), next() * std::f64::consts::TAU);
            let c = [r * a.cos(), r * a.sin()];
            let d = points.iter().map(|p| (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).fold(f64::INFINITY, f64::min);
            if d > best.1 {
                best = (c, d);
            }
        }
        points.push(best.0);
    }
    std::array::from_fn(|i| {
        let [x, y] = points[i];
        let r = (x * x + y * y).sqrt();
        [(x * r) as f32, (y * r) as f32]
    })
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

/// Names for messages about cascade i.
const CASCADE_MATRIX: [&str; MAX_CASCADES] =
    ["cascades[0].world_to_shadow", "cascades[1].world_to_shadow", "cascades[2].world_to_shadow", "cascades[3].world_to_shadow"];

/// The classifier's constants for `d` (already validated field by field), or a specific error where a cascade's
/// geometry does not fit the light: its depth must grow away from the light.
pub(crate) fn constants(d: &ClassifyDispatch) -> Result<ClassifyConstants> {
    let to_light = d.light_direction.normalize();
    let sign = if d.cascades_depth_inverted { 1.0 } else { -1.0 };
    let mut units = [[0.0f32; 4]; 4];
    let (mut axes_u, mut axes_v) = ([[0.0f32; 4]; 4], [[0.0f32; 4]; 4]);
    for (i, c) in d.cascades.iter().take(d.cascade_count as usize).enumerate() {
        let m = c.world_to_shadow.transpose();
        let (row_u, row_v, row_depth) = (m.x_axis.xyz(), m.y_axis.xyz(), m.z_axis.xyz());
        let depth_per_unit = sign * row_depth.dot(to_light);
        if !(depth_per_unit > 0.0) {
            return Err(Error::InvalidValue {
                field: CASCADE_MATRIX[i],
                value: format!("a depth that changes by {:e} per world unit toward the light", -sign * depth_per_unit),
                allowed: "its depth must grow away from the light along light_direction (decrease, with cascades_depth_inverted)",
            });
        }
        let linear = Mat3::from_mat4(c.world_to_shadow);
        let det = linear.determinant();
        if !det.is_normal() {
            return Err(Error::InvalidValue {
                field: CASCADE_MATRIX[i],
                value: format!("a 3x3 part with determinant {det:e}"),
                allowed: "u, v and depth must change independently across the world (an invertible 3x3 part)",
            });
        }
        let inverse = linear.inverse();
        axes_u[i] = inverse.x_axis.extend(0.0).to_array();
        axes_v[i] = inverse.y_axis.extend(0.0).to_array();
        let across = |row: Vec3| (row - row.dot(to_light) * to_light).length();
        units[i] = [depth_per_unit, across(row_u), across(row_v), d.blocker_offset * depth_per_unit];
    }
    let cascade = |i: usize| d.cascades[i].world_to_shadow.to_cols_array_2d();
    let flags = (if d.reject_lit_pixels { CLASSIFY_REJECT_LIT } else { 0 })
        | (if d.cascades_bound_ray_interval { CLASSIFY_BOUND_INTERVAL } else { 0 })
        | (if d.cascades_depth_inverted { CLASSIFY_CASCADES_INVERTED } else { 0 });
    Ok(ClassifyConstants {
        cascade0: cascade(0),
        cascade1: cascade(1),
        cascade2: cascade(2),
        cascade3: cascade(3),
        cascade_units: units,
        cascade_axes_u: axes_u,
        cascade_axes_v: axes_v,
        light: [to_light.x, to_light.y, to_light.z, (0.5 * d.light_angular_size).tan()],
        settings: [d.cascade_count, d.tap_count, d.tile_cutoff, flags],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocker_disc_prefixes_cover_the_disc() {
        let disc = blocker_disc();
        assert_eq!(disc[0], [0.0, 0.0], "the centre comes first");
        for n in CLASSIFY_TAP_COUNTS {
            let warped = &disc[..n as usize];
            assert!(warped.iter().all(|p| p[0] * p[0] + p[1] * p[1] <= 1.0));
            let inner = warped.iter().filter(|p| (p[0] * p[0] + p[1] * p[1]).sqrt() <= 0.5).count();
            // An even spread puts a quarter there; 8 taps are too few to favour the centre beyond itself.
            assert!(n < 16 || inner * 4 > n as usize, "{n} taps: only {inner} within half the radius");
            // Undone (radius r^2 back to r), the taps are spread evenly: every quadrant holds a share of any prefix,
            // and no two taps nearly coincide.
            let taps: Vec<[f32; 2]> = warped
                .iter()
                .map(|&[x, y]| {
                    let r = (x * x + y * y).sqrt().sqrt();
                    if r == 0.0 { [0.0, 0.0] } else { [x / r, y / r] }
                })
                .collect();
            for q in 0..4 {
                let inside = taps.iter().filter(|p| (p[0] >= 0.0) == (q & 1 == 0) && (p[1] >= 0.0) == (q & 2 == 0)).count();
                assert!(inside * 8 >= n as usize, "{n} taps: quadrant {q} holds {inside}");
            }
            let closest = (0..taps.len())
                .flat_map(|i| (0..i).map(move |j| (i, j)))
                .map(|(i, j)| ((taps[i][0] - taps[j][0]).powi(2) + (taps[i][1] - taps[j][1]).powi(2)).sqrt())
                .fold(f32::INFINITY, f32::min);
            assert!(closest > 0.5 / (n as f32).sqrt(), "{n} taps: two within {closest}");
        }
    }
}

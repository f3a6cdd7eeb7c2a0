//! tile classification: uniform-tile skip, reprojection, disocclusion, temporal moments and the history blend.
//! Shader: shaders/tile_classification.comp (core in shaders/tile_classification.glsl).

use super::bindings::Resource;
use super::{internal, FrameViews, Grid, Pass, Role};
use crate::create_info::{Precision, ShadowInput};
use ash::vk;

/// The variant for a precision, the context's output format (it writes the output of cleared tiles), its shadow
/// input (the visibility variant reads per-pixel visibility instead of the tile mask) and whether the host gives its
/// previous depth and normals (`host_previous`: hit mask only; None for another input).
pub(crate) fn shader(precision: Precision, output: vk::Format, input: ShadowInput, host_previous: bool) -> Option<&'static str> {
    let stem = match (input, host_previous) {
        (ShadowInput::HitMask, false) => "tile_classification",
        (ShadowInput::HitMask, true) => "tile_classification_host_previous",
        // A checkerboard input reaches classification as the visibility prepare reconstructed.
        (ShadowInput::Visibility | ShadowInput::Checkerboard, false) => "tile_classification_visibility",
        (_, true) => return None,
    };
    super::variants::variant_name(stem, Some(output), precision)
}

/// One invocation per pixel, groups of `WIDE_GROUP` pixels (2x2 blocks of two tiles each).
pub(crate) fn pass(v: &FrameViews) -> Pass {
    let mut t = v.base_table();
    t[Resource::TileMask as usize] = v.tile_mask;
    t[Resource::Visibility as usize] = v.visibility;
    t[Resource::TileDark as usize] = internal(v.tile_dark);
    t[Resource::Velocity as usize] = v.velocity;
    t[Resource::PreviousDepth as usize] = v.previous_depth;
    t[Resource::PreviousNormals as usize] = v.previous_normals;
    t[Resource::PreviousMoments as usize] = internal(v.kept_moments);
    t[Resource::Moments as usize] = internal(v.frame_moments);
    t[Resource::PreviousTileQuiet as usize] = internal(v.previous_tile_quiet);
    t[Resource::TileQuiet as usize] = internal(v.tile_quiet);
    t[Resource::History as usize] = internal(v.history);
    t[Resource::Reprojection as usize] = internal(v.reprojection);
    t[Resource::TileMetaOut as usize] = internal(v.tile_meta);
    t[Resource::HitDistance as usize] = v.hit_distance;
    t[Resource::TileBlockerOut as usize] = internal(v.tile_blocker);
    t[Resource::Output as usize] = internal(v.output);
    Pass { role: Role::Classification, bindings: t, grid: Grid::Pixels, group: super::WIDE_GROUP, push: None, spec: v.spec, enabled: true }
}

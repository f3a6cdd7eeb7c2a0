//! classify: the hybrid-shadows classifier, one workgroup per column of TILES_PER_GROUP 8x4 tiles (each tile's
//! pixels' verdicts combine into its hit-mask word and list record with shared-memory atomics, whatever the subgroup
//! width). Shader:
//! shaders/classify.comp (classify_cascade_array with the cascades as layers of one image). Recorded by
//! `Context::record_classify` on its own, before the engine's trace and the denoiser's frame, with its own
//! pipelines and descriptor sets (src/classify.rs).

use super::TILE;

/// Tiles per workgroup, stacked vertically: groups of one 32-pixel tile left the GPU half idle (NVIDIA runs at most
/// 32 groups per multiprocessor).
pub(crate) const TILES_PER_GROUP: u32 = 4;

/// Invocations per workgroup: one per pixel of TILES_PER_GROUP tiles.
pub(crate) const GROUP: [u32; 2] = [TILE[0], TILE[1] * TILES_PER_GROUP];

/// Groups covering a render rectangle of `extent` pixels.
pub(crate) fn group_count(extent: [u32; 2]) -> [u32; 3] {
    [extent[0].div_ceil(GROUP[0]), extent[1].div_ceil(GROUP[1]), 1]
}

//! classify: the hybrid-shadows classifier, one workgroup per 8x4 tile (its pixels' verdicts combine into the
//! tile's hit-mask word and list record with shared-memory atomics, whatever the subgroup width). Shader:
//! shaders/classify.comp (classify_cascade_array with the cascades as layers of one image). Recorded by
//! `Context::record_classify` on its own, before the engine's trace and the denoiser's frame, with its own
//! pipelines and descriptor sets (src/classify.rs).

use super::TILE;

/// Invocations per workgroup: one per pixel of a tile.
pub(crate) const GROUP: [u32; 2] = TILE;

/// Groups covering a render rectangle of `extent` pixels: one per tile.
pub(crate) fn group_count(extent: [u32; 2]) -> [u32; 3] {
    [extent[0].div_ceil(GROUP[0]), extent[1].div_ceil(GROUP[1]), 1]
}

//! prepare: FidelityFX hit mask (1 = occluded) -> internal lit-bit tile mask. Shader: shaders/prepare.comp.
//! Skipped when the host's mask already holds lit bits.

use super::bindings::{BindingTable, Resource};
use super::{groups, internal, FrameViews};

pub(crate) const SHADER: &str = "prepare";

pub(crate) fn bindings(v: &FrameViews) -> BindingTable {
    let mut t = v.base_table();
    t[Resource::HitMask as usize] = v.hit_mask;
    t[Resource::TileMaskOut as usize] = internal(v.tile_mask.view);
    t
}

/// One invocation per 8x4 tile of the render rectangle, 8x8 invocations per group.
pub(crate) fn group_count(extent: [u32; 2]) -> [u32; 3] {
    groups([extent[0].div_ceil(8), extent[1].div_ceil(4)], [8, 8])
}

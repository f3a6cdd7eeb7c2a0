//! prepare: FidelityFX hit mask (1 = occluded) -> internal lit-bit tile mask. Shader: shaders/prepare.comp.
//! Skipped when the host's mask already holds lit bits.

use super::bindings::Resource;
use super::{internal, FrameViews, Grid, Pass, Role};

pub(crate) const SHADER: &str = "prepare";

/// One invocation per tile of the render rectangle. Reads the host mask, writes the internal lit-bit mask.
pub(crate) fn pass(v: &FrameViews, enabled: bool) -> Pass {
    let mut t = v.base_table();
    t[Resource::HitMask as usize] = v.hit_mask;
    t[Resource::TileMaskOut as usize] = internal(v.tile_mask.view);
    Pass { role: Role::Prepare, bindings: t, grid: Grid::Tiles, group: super::GROUP, push: None, spec: 0, enabled }
}

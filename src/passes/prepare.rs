//! prepare: with a visibility input the tile words of exactly lit and exactly shadowed pixels (a checkerboard
//! input: the reconstructed visibility too). Shader: shaders/prepare.comp. Not run for a hit mask, which
//! classification reads as the host gives it in either convention; a hit-mask context creates no prepare pipeline
//! (the `prepare` variant, FidelityFX hit mask -> lit-bit tile mask, is what the CPU reference's prepare models).

use super::bindings::Resource;
use super::{internal, FrameViews, Grid, Pass, Role};
use crate::create_info::ShadowInput;

/// The variant for a shadow input.
pub(crate) fn shader(input: ShadowInput) -> &'static str {
    match input {
        ShadowInput::HitMask => "prepare",
        ShadowInput::Visibility => "prepare_visibility",
        ShadowInput::Checkerboard => "prepare_checkerboard",
    }
}

/// One invocation per tile of the render rectangle (per pixel for a checkerboard input, which writes the
/// reconstructed visibility too). Reads the host mask (or visibility), writes the internal tile words.
pub(crate) fn pass(v: &FrameViews, enabled: bool) -> Pass {
    let mut t = v.base_table();
    t[Resource::HitMask as usize] = v.hit_mask;
    t[Resource::Visibility as usize] = v.visibility;
    t[Resource::TileDarkOut as usize] = internal(v.tile_dark);
    t[Resource::TileMaskOut as usize] = internal(v.tile_mask.view);
    t[Resource::VisibilityOut as usize] = internal(v.visibility_out);
    let (grid, group) = if v.visibility_out == ash::vk::ImageView::null() { (Grid::Tiles, super::GROUP) } else { (Grid::Pixels, super::WIDE_GROUP) };
    Pass { role: Role::Prepare, bindings: t, grid, group, push: None, spec: 0, enabled }
}

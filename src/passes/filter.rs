//! filter: edge-avoiding a-trous passes with steps 1, 2, 4, 8. Shader: shaders/filter.comp (core in
//! shaders/filter.glsl) in two variants: the first pass (step 1 from a shared-memory apron; writes the depth copy
//! of linear depth and normals) and the later passes (DNSR_LATER_PASS; read the depth copy per tap as their guide).
//! Pass 0 writes the history (its mean) of the next frame; the final pass writes the host output.
//!
//! Intermediates (the state table's `FILTER_INPUT` and `FILTER_OUTPUT`, src/state/table.rs): pass 0 reprojection
//! -> signal, pass 1 signal -> reprojection, pass 2 reprojection -> signal, pass 3 signal -> (output only). The
//! reprojection image is free once pass 0 consumed it, and the signal (with a hit mask, a view of the frame
//! moments' memory, which pass 0 has read by then) once pass 1 did. Tile classification already wrote the cleared
//! tiles' values into the reprojection image and the output, so a later pass that writes only there skips groups
//! whose two tiles are cleared.

use super::bindings::Resource;
use super::{internal, FrameViews, Grid, Pass, Role, LIGHT_SLOTS, SPEC_PENUMBRA_GUIDED, WIDE_GROUP};
use super::variants::variant_name;
use crate::create_info::{Precision, ShadowInput};
use crate::dispatch::DebugView;
use crate::glsl::gpu_block;
use crate::state::table::{Image, FILTER_INPUT, FILTER_OUTPUT};
use ash::vk;

gpu_block! {
    /// Push constants of one filter pass.
    pub(crate) struct FilterPush as "DnsrFilterPush" {
        /// x: tap step in pixels; y: DNSR_PASS_* bits; z: pass index; w: DNSR_DEBUG_VIEW_* (final pass).
        pass: [u32; 4],
        /// The light-slot variants (several lights per dispatch; zero otherwise): x: lights in this dispatch
        /// (1..=DNSR_LIGHT_SLOTS); y: bit s set when slot s has penumbra guidance; zw: unused. (A light of no size
        /// runs no later pass.)
        lights: [u32; 4],
        /// The light-slot variants: slot s's tan(light angular diameter / 2) (penumbra.x of its constants; the
        /// other penumbra constants depend on the camera only and are read from slot 0's).
        light_tan_half_angle: [f32; 4],
    }
}

/// Filter pass flag: write mean and variance to the internal intermediate image.
pub(crate) const PASS_WRITE_INTERNAL: u32 = 1 << 0;
/// Filter pass flag: groups whose two tiles are cleared write nothing (what the pass would write there is
/// already in place).
pub(crate) const PASS_SKIP_CLEARED: u32 = 1 << 1;

/// The variant of the first pass (`later` false: step 1, shared-memory apron, writes the depth copy and keeps the
/// moments, in the format of shadow input `input`) or of a later pass (reads the depth copy as its guide),
/// intermediate or final (writing `final_output`).
pub(crate) fn shader(precision: Precision, final_output: Option<vk::Format>, later: bool, input: ShadowInput) -> Option<&'static str> {
    let fractions = input != ShadowInput::HitMask;
    let stem = match (later, final_output.is_some(), fractions) {
        (false, false, false) => "filter",
        (false, false, true) => "filter_visibility",
        (false, true, false) => "filter_final",
        (false, true, true) => "filter_final_visibility",
        (true, false, _) => "filter_later",
        (true, true, _) => "filter_later_final",
    };
    variant_name(stem, final_output, precision)
}

/// The light-slot variant of a later pass (several lights per dispatch), intermediate or final. (The first pass
/// has none: one for several lights was slower than a dispatch per light, see filter.glsl.)
pub(crate) fn lights_shader(precision: Precision, final_output: Option<vk::Format>) -> Option<&'static str> {
    let stem = if final_output.is_some() { "filter_later_lights_final" } else { "filter_later_lights" };
    variant_name(stem, final_output, precision)
}

/// The image of the filter's signal that `image` is in this frame.
fn signal(v: &FrameViews, image: Image) -> vk::ImageView {
    match image {
        Image::Reprojection => v.reprojection,
        Image::Signal => v.signal,
        other => unreachable!("{other:?} is not an image of the filter's signal"),
    }
}

fn input(v: &FrameViews, pass: u32) -> vk::ImageView {
    signal(v, FILTER_INPUT[pass as usize])
}

fn output(v: &FrameViews, pass: u32) -> vk::ImageView {
    signal(v, FILTER_OUTPUT[pass as usize])
}

pub(crate) fn is_final(pass: u32, passes: u32) -> bool {
    pass + 1 == passes
}

/// Filter pass `pass` of `passes`: one invocation per pixel.
pub(crate) fn pass(v: &FrameViews, pass: u32, passes: u32, debug_view: DebugView) -> Pass {
    let mut t = v.base_table();
    t[Resource::TileMeta as usize] = internal(v.tile_meta);
    t[Resource::TileBlocker as usize] = internal(v.tile_blocker);
    t[Resource::FilterInput as usize] = internal(input(v, pass));
    t[Resource::FilterOutput as usize] = internal(output(v, pass));
    // The first pass writes the depth copy, the later ones read it as their guide. Both variants declare the guide
    // (they share the callbacks file), so the first pass binds it too.
    t[Resource::Guide as usize] = internal(v.depth_copy);
    if pass == 0 {
        t[Resource::DepthCopy as usize] = internal(v.depth_copy);
        t[Resource::FrameMoments as usize] = internal(v.frame_moments);
        t[Resource::KeptMoments as usize] = internal(v.kept_moments);
        t[Resource::HistoryOut as usize] = internal(v.history);
    }
    if is_final(pass, passes) {
        t[Resource::Output as usize] = internal(v.output);
        // After pass 0 the frame moments' memory holds the signal: the kept moments are the same words by then.
        t[Resource::DebugMoments as usize] = internal(if pass == 0 { v.frame_moments } else { v.kept_moments });
    }
    let role = match (is_final(pass, passes), pass) {
        (true, 0) => Role::FilterOnly,
        (true, _) => Role::FilterFinal,
        (false, _) => Role::Filter(pass),
    };
    let push = Some(push_constants(v, pass, passes, debug_view));
    Pass { role, bindings: t, grid: Grid::Pixels, group: WIDE_GROUP, push, spec: v.spec, enabled: true }
}

/// Later filter pass `pass` (1..) of `lights` (1..=LIGHT_SLOTS) at once, light k in slot k:
/// slot 0's bindings are light 0's single-light ones (which also give the guide, light 0's depth copy: the same
/// G-buffer's for every light of a record, and the G-buffer and constants),
/// and slots beyond the lights repeat slot 0's images, which the shader never touches there.
pub(crate) fn lights_pass(lights: &[&FrameViews], pass: u32, passes: u32, debug_view: DebugView) -> Pass {
    debug_assert!(pass > 0 && (1..=LIGHT_SLOTS).contains(&lights.len()));
    let mut p = self::pass(lights[0], pass, passes, debug_view);
    const PER_LIGHT: [Resource; 6] =
        [Resource::TileMeta, Resource::TileBlocker, Resource::FilterInput, Resource::FilterOutput, Resource::Output, Resource::DebugMoments];
    let (mut guided, mut tan) = (0, [0.0; 4]);
    for slot in 0..LIGHT_SLOTS {
        let v = lights.get(slot).unwrap_or(&lights[0]);
        let single = self::pass(v, pass, passes, debug_view).bindings;
        for r in PER_LIGHT {
            let at = r.in_slot(slot).expect("a per-light resource") as usize;
            p.bindings[at] = single[r as usize];
        }
        if slot < lights.len() {
            p.spec |= v.spec & (1 << SPEC_PENUMBRA_GUIDED);
            if v.spec & (1 << SPEC_PENUMBRA_GUIDED) != 0 {
                guided |= 1 << slot;
                tan[slot] = v.penumbra_tan_half_angle;
            }
        }
    }
    p.role = if is_final(pass, passes) { Role::FilterLightsFinal } else { Role::FilterLights(pass) };
    if let Some(push) = p.push.as_mut() {
        push.lights = [lights.len() as u32, guided, 0, 0];
        push.light_tan_half_angle = tan;
    }
    p
}

fn push_constants(v: &FrameViews, pass: u32, passes: u32, debug_view: DebugView) -> FilterPush {
    let last = is_final(pass, passes);
    let write_internal = !last;
    // Groups of two cleared tiles can be skipped when everything the pass writes there already holds the cleared
    // value: tile classification wrote it into the reprojection image and (without a debug view) the output. Pass
    // 0 never skips them: it writes the history and the depth copy everywhere.
    let internal_in_place = pass > 0 && (!write_internal || output(v, pass) == v.reprojection);
    let output_in_place = !last || debug_view == DebugView::None;
    let flags = (if write_internal { PASS_WRITE_INTERNAL } else { 0 })
        | (if internal_in_place && output_in_place { PASS_SKIP_CLEARED } else { 0 });
    let view = if last { debug_view as u32 } else { 0 };
    FilterPush { pass: [1 << pass, flags, pass, view], ..Default::default() }
}


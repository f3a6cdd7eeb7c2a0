//! The passes' bindings against the state table (src/state/table.rs): what a frame's passes bind is what the
//! table's accesses declare. Here rather than in src/state/tests.rs because passes import state, never the reverse.

use super::bindings::{image, Binding, BindingTable, Resource as Bound, RESOURCE_COUNT};
use super::{frame, FrameViews};
use crate::dispatch::{DebugView, MAX_ENGINE_IMAGES};
use crate::settings::MAX_FILTER_PASSES;
use crate::state::table::*;
use ash::vk;
use ash::vk::Handle;

/// A distinct view per internal image (and half of a pair: copy 0 is the current frame's, copy 1 the previous
/// frame's) and per host image.
fn view(image: Image, copy: u32) -> vk::ImageView {
    vk::ImageView::from_raw(1 + 2 * image as u64 + copy as u64)
}

/// The internal image a view of `view` is of.
fn image_of(v: vk::ImageView) -> Image {
    let raw = v.as_raw() - 1;
    RESOURCES.iter().map(|r| r.image).find(|&i| i as u64 == raw / 2).expect("an internal view")
}

/// The image (and half) of a view of `view`, for messages.
fn named(v: vk::ImageView) -> String {
    format!("{:?} copy {}", image_of(v), (v.as_raw() - 1) % 2)
}

fn host(n: u64) -> Binding {
    image(vk::ImageView::from_raw(1000 + n), vk::ImageLayout::GENERAL)
}

fn views() -> FrameViews {
    let internal = |i: Image| image(view(i, 0), vk::ImageLayout::GENERAL);
    FrameViews {
        constants: Binding::default(),
        hit_mask: host(0),
        // A checkerboard input: classification reads the reconstructed visibility.
        visibility: internal(Image::Reconstructed),
        visibility_out: view(Image::Reconstructed, 0),
        depth: host(1),
        velocity: host(2),
        normals: host(3),
        hit_distance: host(4),
        tile_blocker: view(Image::TileBlocker, 0),
        spec: 0,
        output: vk::ImageView::from_raw(1005),
        tile_mask: internal(Image::TileMask),
        tile_dark: view(Image::TileDark, 0),
        tile_meta: view(Image::TileMeta, 0),
        reprojection: view(Image::Reprojection, 0),
        history: view(Image::History, 0),
        signal: view(Image::Signal, 0),
        depth_copy: view(Image::DepthCopy, 0),
        previous_depth: internal(Image::DepthCopy),
        previous_normals: Binding::default(),
        kept_moments: view(Image::Moments, 0),
        frame_moments: view(Image::FrameMoments, 0),
        previous_tile_quiet: view(Image::TileQuiet, 1),
        tile_quiet: view(Image::TileQuiet, 0),
        engine: [Binding::default(); MAX_ENGINE_IMAGES],
        penumbra_tan_half_angle: 0.0,
    }
}

/// (view, access) of every internal image one pass binds, read (sampled) or written (storage).
fn bound(bindings: &BindingTable) -> Vec<(vk::ImageView, Access)> {
    let mut out = Vec::new();
    for (i, b) in bindings.iter().enumerate() {
        let raw = b.view.as_raw();
        if raw == 0 || raw >= 1000 {
            continue;
        }
        let storage = Bound::descriptor_type_at(i) == Some(vk::DescriptorType::STORAGE_IMAGE);
        out.push((b.view, if storage { Access::Write } else { Access::Read }));
    }
    out
}

/// The accesses are the passes' bindings (src/passes/): every access a pass of a frame of 1-4 filter passes makes
/// is to an image it binds as the access needs (storage to write, sampled to read), and every internal image a pass
/// binds is in an access of that pass (the prepare pass binds the reconstructed visibility as the input of the
/// visibility variant, which a checkerboard's variant does not declare).
#[test]
fn accesses_are_what_the_passes_bind() {
    let v = views();
    for passes in 1..=MAX_FILTER_PASSES {
        let frame = frame(&v, passes, true, DebugView::None);
        for (index, p) in frame.iter().enumerate() {
            let (pass, k) = match index {
                0 => (Pass::Prepare, 0),
                1 => (Pass::TileClassification, 0),
                _ => (Pass::Filter, index as u32 - 2),
            };
            let bound = bound(&p.bindings);
            let mine = || ACCESSES.iter().filter(|a| a.pass == pass);
            for a in mine().filter(|a| pass != Pass::Filter || a.when.applies(k, passes)) {
                assert!(bound.contains(&(target_view(a.target, k), a.access)), "{a:?}: pass {k} of {passes} does not bind it so");
            }
            for &(bound_view, access) in &bound {
                let declared = mine().any(|a| {
                    a.access == access && (0..passes).any(|any| target_view(a.target, if pass == Pass::Filter { any } else { 0 }) == bound_view)
                });
                let exempt = pass == Pass::Prepare && bound_view == view(Image::Reconstructed, 0) && access == Access::Read;
                assert!(declared || exempt, "{pass:?} {k} of {passes} binds {} ({access:?}) that no access declares", named(bound_view));
            }
        }
    }
}

/// The view of what `t` touches in filter pass `k` (any pass for the other targets).
fn target_view(t: Target, k: u32) -> vk::ImageView {
    view(t.image(k), if matches!(t, Target::Previous(_)) { 1 } else { 0 })
}

/// The state images each entry of a pass's binding table holds (indexed as `BindingTable`), over the passes of every
/// filter pass count: what src/tests/interface.rs checks the shader variants' declared formats against. The frame
/// depth of lights recorded together is bound where the depth copy is written and read as the guide.
pub(crate) fn images_per_binding() -> Vec<Vec<Image>> {
    let v = views();
    let mut holds: Vec<Vec<Image>> = vec![Vec::new(); RESOURCE_COUNT];
    for passes in 1..=MAX_FILTER_PASSES {
        for p in frame(&v, passes, true, DebugView::None).iter() {
            for (index, b) in p.bindings.iter().enumerate() {
                let raw = b.view.as_raw();
                if raw == 0 || raw >= 1000 {
                    continue;
                }
                let image = image_of(b.view);
                let in_place = [Bound::DepthCopy as usize, Bound::Guide as usize].contains(&index) && image == Image::DepthCopy;
                for image in [Some(image), in_place.then_some(Image::FrameDepth)].into_iter().flatten() {
                    if !holds[index].contains(&image) {
                        holds[index].push(image);
                    }
                }
            }
        }
    }
    holds
}

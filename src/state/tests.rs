//! The state table against what it is used for: the byte counts, the passes' bindings, the filter's ping-pong and
//! docs/performance.md. (src/tests/resources.rs checks it against the images a context creates.)

use super::table::*;
use super::{formats, image_specs, persistent_texel_bytes, texel_bytes, Lifetime};
use crate::create_info::{Precision, ShadowInput};
use crate::dispatch::DebugView;
use crate::passes::bindings::{image, Binding, Resource as Bound};
use crate::passes::{frame, FrameViews};
use crate::settings::MAX_FILTER_PASSES;
use ash::vk;
use ash::vk::Handle;

const PRECISIONS: [Precision; 2] = [Precision::Fp32, Precision::Fp16];
const INPUTS: [ShadowInput; 3] = [ShadowInput::HitMask, ShadowInput::Visibility, ShadowInput::Checkerboard];

#[test]
fn every_format_has_a_size_and_is_checked() {
    for precision in PRECISIONS {
        let checked: Vec<vk::Format> = formats(precision).collect();
        for r in &RESOURCES {
            assert!(r.texel_bytes(precision) > 0, "{:?}", r.image);
            for input in INPUTS {
                assert_eq!(checked.iter().filter(|&&f| f == r.format_for(precision, input)).count(), 1, "{:?}", r.image);
            }
        }
    }
}

/// The byte counts follow the table; the numbers are those of docs/performance.md's "State model" (10 B/px kept
/// with a hit mask, 14 with fractional samples).
#[test]
fn memory_follows_the_table() {
    for [w, h] in [[64u32, 32u32], [1921, 1081]] {
        let (px, tiles) = ((w * h) as u64, (w.div_ceil(8) * h.div_ceil(4)) as u64);
        for precision in PRECISIONS {
            for input in INPUTS {
                // Per light: metadata and blocker (4 B per tile each), with a visibility or checkerboard input
                // the tile mask and dark mask too, the tiles' quiet counts (4 B per tile, two of them); the
                // reprojection (4 B), the history (2 B: the mean alone), the depth copy (4 B), the kept and this
                // frame's moments (4 B each, 8 B with fractional samples); the filter's signal between passes (4
                // B, in the frame moments' memory with a hit mask); a checkerboard input's reconstructed
                // visibility (4 B). Per context: nothing (the later filter passes' guide is each light's depth
                // copy). Whatever the filter passes.
                let reconstructed = if input == ShadowInput::Checkerboard { 4 } else { 0 };
                let moments = if input == ShadowInput::HitMask { 4 } else { 8 };
                let signal = if input == ShadowInput::HitMask { 0 } else { 4 };
                let tile_images = if input == ShadowInput::HitMask { 2 } else { 4 };
                let light = tile_images * 4 * tiles + 2 * 4 * tiles + px * (4 + 2 + 4 + 2 * moments + signal + reconstructed);
                assert_eq!(texel_bytes(Scope::Light, [w, h], precision, input), light, "{precision:?} {input:?}");
                assert_eq!(texel_bytes(Scope::Context, [w, h], precision, input), 0, "{precision:?} {input:?}");
            }
            assert_eq!(persistent_texel_bytes([w, h], precision, ShadowInput::HitMask), 10 * px + 8 * tiles);
            assert_eq!(persistent_texel_bytes([w, h], precision, ShadowInput::Visibility), 14 * px + 8 * tiles);
        }
    }
}

/// A row that shares another's memory does so exactly where their texels have one size: the signal with a hit
/// mask's frame moments, in both precisions, and never with a visibility input's two-word moments.
#[test]
fn the_signal_shares_the_frame_moments_with_a_hit_mask() {
    let signal = resource_of(Image::Signal);
    for precision in PRECISIONS {
        assert_eq!(signal.shared_with(precision, ShadowInput::HitMask), Some(Image::FrameMoments), "{precision:?}");
        for input in [ShadowInput::Visibility, ShadowInput::Checkerboard] {
            assert_eq!(signal.shared_with(precision, input), None, "{precision:?} {input:?}");
        }
        let frame_moments = image_specs(Scope::Light, [16, 8], precision, ShadowInput::HitMask).find(|s| s.image == Image::FrameMoments);
        assert_eq!(frame_moments.and_then(|s| s.shared_format), Some(signal.format.get(precision)));
        assert!(image_specs(Scope::Light, [16, 8], precision, ShadowInput::Visibility).all(|s| s.shared_format.is_none()));
    }
    // Only rows of the same lifetime and size share: the shared memory is transient, a texel per pixel.
    for r in RESOURCES.iter().filter(|r| r.shares.is_some()) {
        let other = resource_of(r.shares.unwrap());
        assert_eq!((r.lifetime, r.per, r.scope), (other.lifetime, other.per, other.scope), "{:?}", r.image);
        assert_eq!(r.lifetime, Lifetime::Transient, "{:?}", r.image);
    }
}

/// Every image an access touches exists in every configuration where the access happens: the filter's ping-pong
/// (`FILTER_INPUT`, `FILTER_OUTPUT`) stays within the images the pass count allocates, and the filter's signal is
/// one format.
#[test]
fn accesses_touch_allocated_images() {
    for a in ACCESSES {
        for passes in 1..=MAX_FILTER_PASSES {
            let input = match a.config {
                Config::VisibilityInput => ShadowInput::Visibility,
                Config::CheckerboardInput => ShadowInput::Checkerboard,
                _ => ShadowInput::HitMask,
            };
            let ks = if a.pass == Pass::Filter { 0..passes } else { 0..1 };
            for k in ks.filter(|&k| a.pass != Pass::Filter || a.when.applies(k, passes)) {
                let r = resource_of(a.target.image(k));
                assert!(r.needed.holds(input), "{a:?}: pass {k} of {passes} touches {:?}, not allocated", r.image);
                assert!(!matches!(a.target, Target::Previous(_)) || r.copies == 2, "{a:?}: no previous half");
            }
        }
    }
    for image in FILTER_INPUT.into_iter().chain(FILTER_OUTPUT) {
        let r = resource_of(image);
        assert_eq!(r.format, resource_of(Image::Signal).format, "{image:?}");
        assert_eq!((r.per, r.scope, r.copies), (Per::Pixel, Scope::Light, 1), "{image:?}");
    }
}

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
        kept_moments: view(Image::Moments, 0),
        frame_moments: view(Image::FrameMoments, 0),
        previous_tile_quiet: view(Image::TileQuiet, 1),
        tile_quiet: view(Image::TileQuiet, 0),
        engine: [Binding::default(); crate::dispatch::MAX_ENGINE_IMAGES],
        penumbra_tan_half_angle: 0.0,
    }
}

/// (view, access) of every internal image one pass binds, read (sampled) or written (storage).
fn bound(bindings: &crate::passes::bindings::BindingTable) -> Vec<(vk::ImageView, Access)> {
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

/// docs/performance.md's "State model" table is the table's: one row per image (or several images of one format
/// size), its per-pixel or per-tile size, its bytes, its lifetime, the format it names (or "as filter signal"), a pair as
/// "(x2, ping-pong)" and the context's images as "(one per context)".
#[test]
fn performance_doc_states_the_table() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/performance.md")).unwrap();
    let section = doc.split("## State model").nth(1).expect("a State model section").split("\n## ").next().unwrap();
    let table = section.split("| image | per | format | bytes | kept |").nth(1).expect("the table of images");
    let rows: Vec<Vec<&str>> = table
        .lines()
        .skip(2)
        .take_while(|l| l.starts_with("| "))
        .map(|l| l.trim_matches('|').split(" | ").map(str::trim).collect())
        .collect();
    assert!(rows.len() >= 5, "{rows:?}");
    let mut seen = Vec::new();
    for row in &rows {
        let [names, per, format, bytes, kept, ..] = row[..] else { panic!("row {row:?}") };
        let (list, note) = names.split_once(" (").map_or((names, ""), |(l, n)| (l, n));
        for name in list.split(", ") {
            let r = RESOURCES.iter().find(|r| r.display_name() == name).unwrap_or_else(|| panic!("{name}: no image of that name"));
            seen.push(r.image);
            let want_per = match r.per {
                Per::Pixel => "px",
                Per::Tile => "tile",
            };
            assert_eq!(per, want_per, "{name}");
            assert_eq!(note.contains("x2, ping-pong"), r.copies == 2, "{name}: {names}");
            assert_eq!(note.contains("one per context"), r.scope == Scope::Context, "{name}: {names}");
            let each = r.copies > 1 || list.contains(", ");
            let texel = r.texel_bytes(Precision::Fp32);
            assert_eq!(texel, r.texel_bytes(Precision::Fp16), "{name}: one byte count");
            assert_eq!(bytes, if each { format!("{texel} each") } else { texel.to_string() }, "{name}");
            let want_kept = match r.lifetime {
                Lifetime::Persistent => "persistent",
                Lifetime::Transient => "transient",
            };
            assert_eq!(kept, want_kept, "{name}");
            if format == "as filter signal" {
                assert_eq!(r.format, resource_of(Image::Signal).format, "{name}");
            } else {
                for f in [r.format.fp32, r.format.fp16].into_iter().chain(r.fraction_format) {
                    assert!(format.contains(&format!("{f:?}")), "{name}: {format} does not name {f:?}");
                }
            }
        }
    }
    for r in &RESOURCES {
        assert_eq!(seen.iter().filter(|&&i| i == r.image).count(), 1, "{:?}: one row of docs/performance.md", r.image);
    }
}

/// A light's images in table order, the order src/light.rs creates them in.
#[test]
fn specs_are_in_table_order() {
    let names: Vec<String> = image_specs(Scope::Light, [16, 8], Precision::Fp32, ShadowInput::Checkerboard).map(|s| s.name()).collect();
    assert_eq!(
        names,
        [
            "tile_mask", "tile_dark", "tile_meta", "tile_blocker", "reprojection", "history", "depth_copy", "moments",
            "filter_signal", "reconstructed_visibility", "tile_quiet_0", "tile_quiet_1", "frame_moments"
        ]
    );
}

/// The state images each entry of a pass's binding table holds (indexed as `BindingTable`), over the passes of every
/// filter pass count: what src/tests/interface.rs checks the shader variants' declared formats against.
pub(crate) fn images_per_binding() -> Vec<Vec<Image>> {
    let v = views();
    let mut holds: Vec<Vec<Image>> = vec![Vec::new(); crate::passes::bindings::RESOURCE_COUNT];
    for passes in 1..=MAX_FILTER_PASSES {
        for p in frame(&v, passes, true, DebugView::None).iter() {
            for (index, b) in p.bindings.iter().enumerate() {
                let raw = b.view.as_raw();
                if raw == 0 || raw >= 1000 {
                    continue;
                }
                let image = image_of(b.view);
                if !holds[index].contains(&image) {
                    holds[index].push(image);
                }
            }
        }
    }
    holds
}

//! The state table against what it is used for: the byte counts, the filter's ping-pong and docs/performance.md.
//! (src/tests/resources.rs checks it against the images a context creates, src/passes/state_tests.rs against the
//! passes' bindings.)

use super::table::*;
use super::{formats, image_specs, persistent_texel_bytes, texel_bytes, Lifetime};
use crate::create_info::{Precision, ShadowInput};
use crate::settings::MAX_FILTER_PASSES;
use ash::vk;

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

//! The host's previous depth and normals (`ContextCreateInfo::host_previous_gbuffer`): no depth copy kept, the same
//! output bit for bit where those images are last frame's, 4 B/px less persistent memory, and the CPU reference's
//! model of it (`reference::Frame::set_host_previous`).

use crate::reference::{self, memory::Frame};
use crate::testing::gpu::{Gpu, GpuOptions, TestImage};
use crate::testing::typical::typical_frame;
use crate::testing::Runner;
use crate::{Error, ImageRole, Preset, Settings, ShadowInput};
use ash::vk;
use glam::{DVec3, Mat4};

const W: u32 = 96;
const H: u32 = 64;
const FRAMES: usize = 8;

fn runner(g: &Gpu, preset: Preset, host_previous: bool) -> Runner<'_> {
    let mut info = g.create_info(W, H);
    info.output_format = vk::Format::R32_SFLOAT;
    info.settings = Settings::preset(preset);
    info.host_previous_gbuffer = host_previous;
    Runner::new(g, &info).unwrap()
}

/// A panning camera over boxes (faces of several normals, sky, disocclusions): the host keeps two depth and normal
/// images and swaps them every frame, as an engine with a previous depth buffer does. Quality reads last frame's
/// normals (turned texels) and Balanced its depth alone.
#[test]
fn host_previous_gbuffer_gives_the_depth_copys_output() {
    let g = Gpu::new(GpuOptions::default());
    for preset in [Preset::Quality, Preset::Balanced] {
        let mut own = runner(&g, preset, false);
        let mut host = runner(&g, preset, true);
        let mut previous_depth = g.image(host.depth.format, W, H, host.depth.layout);
        let mut previous_normals = g.image(host.normals.format, W, H, host.normals.layout);
        let mut changed = 0;
        for frame in 0..FRAMES {
            let f = typical_frame(W, H, frame, 11 + frame as u64);
            let expected = own.run(&f, &own.dispatch(&f)).expect("record with the depth copy");
            let mut d = host.dispatch(&f);
            d.previous_depth = previous_depth.host();
            d.previous_normals = previous_normals.host();
            let got = host.run(&f, &d).expect("record with the host's previous images");
            let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert!(bits(&got) == bits(&expected), "{preset:?} frame {frame}: outputs differ");
            if frame > 0 {
                // The history carried something: the output is not this frame's samples alone.
                changed += got.iter().zip(&f.visibility).filter(|(o, v)| (*o - *v).abs() > 1e-3).count();
            }
            std::mem::swap(&mut host.depth, &mut previous_depth);
            std::mem::swap(&mut host.normals, &mut previous_normals);
        }
        assert!(changed > 0, "{preset:?}: every output equals its input");
        let px = (W * H) as u64;
        let (own_kept, host_kept) = (own.ctx.persistent_memory_bytes(), host.ctx.persistent_memory_bytes());
        assert!(own_kept >= host_kept + 4 * px, "{preset:?}: kept {own_kept} B with a depth copy, {host_kept} B without");
        g.destroy_image(&previous_depth);
        g.destroy_image(&previous_normals);
    }
    g.assert_clean();
}

/// The previous images are required with the option and refused without it, each with its own field named; a
/// visibility context cannot take the option.
#[test]
fn host_previous_gbuffer_misuse_is_refused() {
    let g = Gpu::new(GpuOptions::default());
    let f = typical_frame(W, H, 1, 3);
    let mut host = runner(&g, Preset::Quality, true);
    let spare: TestImage = g.image(host.depth.format, W, H, host.depth.layout);
    let d = host.dispatch(&f);
    let e = host.run(&f, &d).unwrap_err();
    assert!(matches!(e, Error::NullHandle("previous_depth.image")), "{e:?}");
    let mut d = host.dispatch(&f);
    d.previous_depth = spare.host();
    let e = host.run(&f, &d).unwrap_err();
    assert!(matches!(e, Error::NullHandle("previous_normals.image")), "{e:?}");
    d.previous_normals = host.velocity.host();
    let e = host.run(&f, &d).unwrap_err();
    assert!(matches!(e, Error::UnsupportedFormat { role: Some(ImageRole::PreviousNormals), .. }), "{e:?}");

    let mut own = runner(&g, Preset::Quality, false);
    let mut d = own.dispatch(&f);
    d.previous_depth = spare.host();
    let e = own.run(&f, &d).unwrap_err();
    assert!(matches!(e, Error::InvalidValue { field: "previous_depth", .. }), "{e:?}");

    let mut info = g.create_info(W, H);
    info.shadow_input = ShadowInput::Visibility;
    info.host_previous_gbuffer = true;
    let e = crate::Context::new(&info).err().expect("a visibility context with host_previous_gbuffer");
    assert!(matches!(e, Error::InvalidValue { field, .. } if field.starts_with("host_previous_gbuffer")), "{e:?}");
    g.destroy_image(&spare);
    drop((host, own));
    g.assert_clean();
}

/// The reference's model: last frame's depth and normals turned into depth copy words with this frame's projection
/// are the words its own first filter pass stored last frame (the projection does not change).
#[test]
fn reference_host_previous_words_are_the_depth_copy() {
    let dmat = |m: Mat4| m.as_dmat4();
    let frame_of = |k: usize| {
        let f = typical_frame(W, H, k, 5);
        let mut cpu = Frame::new(W as i32, H as i32, Settings::preset(Preset::Quality));
        cpu.projection_inverse = dmat(f.projection_inverse);
        cpu.reprojection = dmat(f.reprojection);
        cpu.view_projection_inverse = dmat(f.view_projection_inverse);
        cpu.hit_mask = f.mask.clone();
        cpu.depth = f.depth.iter().map(|&v| v as f64).collect();
        cpu.velocity = f.velocity.iter().map(|v| glam::DVec2::new(v[0] as f64, v[1] as f64)).collect();
        cpu.normals = f.normals.iter().map(|n| reference::decode_normal(DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64), 1.0, 0.0)).collect();
        cpu
    };
    let mut last = frame_of(2);
    reference::run_frame(&mut last, true);
    let mut next = frame_of(3);
    next.set_host_previous(&last.depth, &last.normals);
    assert_eq!(next.previous_depth, last.depth_copy);
    let receivers = last.depth.iter().filter(|&&d| reference::is_receiver(d)).count();
    assert!(receivers > 0 && receivers < last.depth.len(), "receivers and sky: {receivers} of {}", last.depth.len());
}

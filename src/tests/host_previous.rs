//! The host's previous depth and normals (`ContextCreateInfo::host_previous_gbuffer`): no depth copy kept, the
//! depth copy's output but for its rounding where those images are last frame's, 4 B/px less persistent memory, and
//! the CPU reference's model of it (`reference::Frame::set_host_previous`; the GPU against it: tests::parity).

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
/// normals (turned texels) and Balanced its depth alone. The output is the depth copy's but where the copy's
/// rounding (a 16-bit depth code, 8-bit octahedral normals) would have decided a test the other way, from where the
/// filter spreads it (lavapipe: Quality 1.8% of the outputs, by up to 6/255; Balanced 5.5%, by up to 10/255), and
/// as close to the truth (the accuracy bar: within 2% of the depth copy's RMSE; lavapipe: the same to 4 digits).
#[test]
fn host_previous_gbuffer_gives_the_depth_copys_output_unrounded() {
    let g = Gpu::new(GpuOptions::default());
    for preset in [Preset::Quality, Preset::Balanced] {
        let mut own = runner(&g, preset, false);
        let mut host = runner(&g, preset, true);
        host.keep_previous_gbuffer();
        let (mut changed, mut differ, mut worst) = (0, 0, 0.0f32);
        let (mut squared, mut receivers) = ([0.0f64; 2], 0);
        for frame in 0..FRAMES {
            let f = typical_frame(W, H, frame, 11 + frame as u64);
            let expected = own.frame(&f, frame == 0);
            let got = host.frame(&f, frame == 0);
            for (a, b) in got.iter().zip(&expected) {
                differ += (a != b) as usize;
                worst = worst.max((a - b).abs());
            }
            for (k, out) in [&expected, &got].into_iter().enumerate() {
                squared[k] += out.iter().zip(&f.truth).zip(&f.receiver).filter(|(_, r)| **r).map(|((o, t), _)| ((o - t) as f64).powi(2)).sum::<f64>();
            }
            receivers += f.receiver.iter().filter(|&&r| r).count();
            if frame > 0 {
                // The history carried something: the output is not this frame's samples alone.
                changed += got.iter().zip(&f.visibility).filter(|(o, v)| (*o - *v).abs() > 1e-3).count();
            }
        }
        let px = (W * H) as usize;
        let [own_error, host_error] = squared.map(|e| (e / receivers as f64).sqrt());
        eprintln!("{preset:?}: {differ} of {} outputs differ from the depth copy's, by at most {worst}; RMSE against the truth {own_error:.5} -> {host_error:.5}", px * FRAMES);
        assert!(changed > 0, "{preset:?}: every output equals its input");
        assert!(differ * 10 <= px * FRAMES, "{preset:?}: {differ} outputs differ from the depth copy's");
        assert!(host_error <= 1.02 * own_error, "{preset:?}: error {host_error} against the depth copy's {own_error}");
        let (own_kept, host_kept) = (own.ctx.persistent_memory_bytes(), host.ctx.persistent_memory_bytes());
        assert!(own_kept >= host_kept + 4 * px as u64, "{preset:?}: kept {own_kept} B with a depth copy, {host_kept} B without");
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

/// The reference's model: last frame's depth and normals as classification reads them from the host's images are
/// the values its own first filter pass rounded into the depth copy last frame (the projection does not change).
#[test]
fn reference_host_previous_reads_are_the_depth_copy_unrounded() {
    use reference::Read;
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
    let mut receivers = 0;
    for (i, &word) in last.depth_copy.iter().enumerate() {
        let p = [i as i32 % W as i32, i as i32 / W as i32];
        let (depth, normal) = (next.read_previous_depth(p), next.read_previous_normal(p));
        let receiver = reference::is_receiver(last.depth[i]);
        receivers += receiver as usize;
        let rounded = reference::storage::pack_depth_copy(depth, if receiver { normal } else { DVec3::ZERO });
        assert_eq!(rounded, word, "pixel {p:?}: the host's previous depth {depth} and normal {normal} round to another word");
    }
    assert!(receivers > 0 && receivers < last.depth.len(), "receivers and sky: {receivers} of {}", last.depth.len());
}

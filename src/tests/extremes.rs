//! Numerical extremes: every output finite and in [0, 1], sky exactly 1, and the history not poisoned (after
//! the extreme frames, ordinary frames converge as usual and the internal state is finite).

use super::correctness::{smooth, DEFAULTS_MAE_BOUND};
use super::{gpu, mae, static_frame};
use crate::testing::gpu::Gpu;
use crate::testing::scene::{render, Camera, FrameInputs};
use crate::testing::Runner;
use crate::{ContextCreateInfo, Precision};
use ash::vk;

fn runner<'g>(g: &'g Gpu, info: &ContextCreateInfo) -> Runner<'g> {
    let mut info = info.clone();
    info.output_format = vk::Format::R32_SFLOAT;
    Runner::new(g, &info).unwrap()
}

fn assert_sane(out: &[f32], f: &FrameInputs, what: &str) {
    for (i, &o) in out.iter().enumerate() {
        assert!(o.is_finite() && (0.0..=1.0).contains(&o), "{what}: pixel {i} = {o}");
        if !f.receiver[i] && f.depth[i].is_finite() && !(f.depth[i] > 0.0 && f.depth[i] < 1.0) {
            assert_eq!(o, 1.0, "{what}: sky pixel {i}");
        }
    }
}

/// The moments written by the last frame are finite and within their bounds.
fn assert_state_finite(r: &Runner, what: &str) {
    let [w, h] = r.ctx.size();
    let max_n = r.ctx.settings().max_history_samples as f64;
    for (i, m) in crate::testing::download_moments(r.gpu, r.ctx.internals(0).moments, w, h, r.ctx.shadow_input()).iter().enumerate() {
        assert!(m[0].is_finite() && (0.0..=1.0).contains(&m[0]), "{what}: moments.mean of pixel {i} = {}", m[0]);
        assert!(m[1].is_finite() && m[1] >= 0.0 && m[1] <= max_n, "{what}: moments.sum of pixel {i} = {}", m[1]);
        assert!(m[2].is_finite() && m[2] >= 0.0 && m[2] <= max_n, "{what}: moments.n of pixel {i} = {}", m[2]);
        let run = m[3].abs();
        let longest = crate::settings::MAX_SAMPLE_RUN as f64;
        assert!(run <= longest && (run.fract() == 0.0 || run.fract() == 0.5), "{what}: sample run of pixel {i} = {}", m[3]);
    }
}

/// Runs `frames` of a camera over the smooth field, checking sanity on each and convergence at the end.
fn converge(r: &mut Runner, cam: &Camera, frames: u64, what: &str) {
    let [w, h] = r.ctx.size();
    let mut last = 0.0;
    for frame in 0..frames {
        let f = render(w, h, cam, cam, 1e9, &smooth, 500 + frame);
        let out = r.frame(&f, false);
        assert_sane(&out, &f, what);
        last = mae(&out, &f);
    }
    assert!(last < DEFAULTS_MAE_BOUND, "{what}: MAE {last} after {frames} frames");
    assert_state_finite(r, what);
}

#[test]
fn depth_conventions_and_projections() {
    let g = gpu();
    let (w, h) = (48, 32);
    let base = Camera::above(0.0, 0.0, 10.0);
    let cases: [(&str, Camera); 7] = [
        ("standard depth", base),
        ("reverse-Z", Camera { inverted: true, ..base }),
        ("infinite far", Camera { infinite_far: true, ..base }),
        ("reverse-Z infinite far", Camera { inverted: true, infinite_far: true, ..base }),
        ("orthographic", Camera { orthographic: Some(7.0), ..base }),
        ("near 1e-4 far 1e6", Camera { near: 1e-4, far: 1e6, ..base }),
        ("camera 1e5 from the origin", Camera { eye: base.eye + glam::DVec3::new(1e5, 0.0, -1e5), ..base }),
    ];
    for (what, cam) in cases {
        let mut info = g.create_info(w, h);
        info.depth.inverted = cam.inverted;
        let mut r = runner(&g, &info);
        // Sky at the sides (plane narrower than the view), then the full plane.
        let f = render(w, h, &cam, &cam, cam.eye.x.abs() + 2.0, &smooth, 1);
        let out = r.frame(&f, true);
        assert_sane(&out, &f, what);
        assert!(f.receiver.iter().any(|&x| !x), "{what}: no sky in the test frame");
        converge(&mut r, &cam, 30, what);
    }
    g.assert_clean();
}

#[test]
fn broken_gbuffer_values_do_not_poison_anything() {
    let g = gpu();
    let (w, h) = (40, 24);
    let cam = Camera::above(0.0, 0.0, 10.0);
    for precision in [Precision::Fp32, Precision::Fp16] {
        if precision == Precision::Fp16 && !g.features.float16 {
            continue;
        }
        let mut info = g.create_info(w, h);
        info.precision = precision;
        let mut r = runner(&g, &info);
        let special = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 0.0, 1.0, -0.5, 1.5, 1e30, -1e30, 5.0];
        for frame in 0..6u64 {
            let mut f = render(w, h, &cam, &cam, 1e9, &smooth, frame + 1);
            for i in 0..f.depth.len() {
                let s = special[(i + frame as usize) % special.len()];
                match i % 7 {
                    0 => f.normals[i] = [s, s, s, 0.0],       // NaN / Inf / zero-length normals
                    1 => f.normals[i] = [0.0, 0.0, 0.0, 0.0],
                    2 => f.velocity[i] = [s, -s],              // NaN / Inf / far off-screen velocities
                    3 => f.depth[i] = [0.0, 1.0, -0.25, 1.25, f32::NAN, f32::INFINITY][i % 6], // edge and invalid depth
                    _ => {}
                }
                f.receiver[i] = f.depth[i] > 0.0 && f.depth[i] < 1.0;
            }
            let out = r.frame(&f, false);
            for (i, &o) in out.iter().enumerate() {
                assert!(o.is_finite() && (0.0..=1.0).contains(&o), "{precision:?} frame {frame}: pixel {i} = {o}");
            }
        }
        assert_state_finite(&r, "after broken G-buffers");
        converge(&mut r, &cam, 40, "recovery after broken G-buffers");
    }
    g.assert_clean();
}

#[test]
fn extreme_sizes_and_masks() {
    let g = gpu();
    for (w, h) in [(8193, 5), (16384, 16), (1, 1)] {
        let mut r = runner(&g, &g.create_info(w, h));
        for frame in 0..2 {
            let f = static_frame(w, h, &|x, _| if x > 0.0 { 1.0 } else { 0.3 }, frame + 1);
            let out = r.frame(&f, false);
            assert_sane(&out, &f, &format!("{w}x{h}"));
        }
    }
    // All lit, all shadowed, 50% pixel checkerboard (never uniform: the temporal path everywhere).
    let (w, h) = (40, 24);
    let mut r = runner(&g, &g.create_info(w, h));
    for (what, v) in [("all lit", 1.0), ("all shadow", 0.0), ("checkerboard", 0.5)] {
        for frame in 0..8 {
            let mut f = static_frame(w, h, &|_, _| v, frame);
            if v == 0.5 {
                f.mask.iter_mut().for_each(|m| *m = 0x55AA_55AA);
            }
            let out = r.frame(&f, false);
            assert_sane(&out, &f, what);
            if v != 0.5 {
                assert!(out.iter().all(|&o| o == v as f32), "{what}");
            }
        }
        assert_state_finite(&r, what);
    }
    g.assert_clean();
}

/// One million recorded frames of a fixed 50% checkerboard (the temporal path on every pixel): sample counts stay
/// bounded, moments stay finite, and the output does not drift from where it settled after a thousand frames.
/// Every pixel's samples never change, so its run of identical samples reaches its bound; fp32 runs the Quality
/// preset (stable history clamped to the run) telling moving shadows, fp16 the defaults.
fn a_million_static_frames(precision: Precision) {
    let g = gpu();
    let (w, h) = (8, 8);
    if precision == Precision::Fp16 && !g.features.float16 {
        return;
    }
    let mut info = g.create_info(w, h);
    info.precision = precision;
    if precision == Precision::Fp32 {
        // With the moving shadows' test too (its first form made lavapipe leak memory frame after frame).
        info.settings = crate::Settings { moving_shadow_sigmas: 3.0, ..crate::Settings::preset(crate::Preset::Quality) };
    }
    let mut r = runner(&g, &info);
    let mut f = static_frame(w, h, &|_, _| 0.5, 1);
    f.mask.iter_mut().for_each(|m| *m = 0x55AA_55AA);
    let mut settled = Vec::new();
    for _ in 0..1000 {
        settled = r.frame(&f, false);
    }
    let d = r.dispatch(&f);
    let cmd = g.command_buffer();
    const PER_SUBMIT: usize = 20_000;
    let submits = (1_000_000 - 1000 - 1) / PER_SUBMIT + 1;
    for _ in 0..submits {
        g.submit_with(cmd, |cmd| {
            for _ in 0..PER_SUBMIT {
                r.ctx.record_shadows(cmd, &d).unwrap();
            }
        });
    }
    g.free_command_buffer(cmd);
    let out = r.frame(&f, false);
    assert_state_finite(&r, "a million frames");
    let drift = out.iter().zip(&settled).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
    assert!(drift < 1e-3, "{precision:?}: output drifted by {drift} between frame 1000 and frame 1e6");
    drop(r);
    g.assert_clean();
}

#[test]
fn a_million_static_frames_fp32() {
    a_million_static_frames(Precision::Fp32);
}

#[test]
fn a_million_static_frames_fp16() {
    a_million_static_frames(Precision::Fp16);
}

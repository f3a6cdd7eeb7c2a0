//! The checkerboard input (half a ray per pixel): the untraced half of the mask is never read, either mask
//! convention gives the same result, and the denoised shadow converges on a static scene.

use super::correctness::smooth;
use super::{gpu, mae, static_frame};
use crate::testing::scene::FrameInputs;
use crate::testing::Runner;
use crate::{HitMaskConvention, ShadowInput, ShadowsDispatch};
use ash::vk;

const W: u32 = 48;
const H: u32 = 32;

fn runner(g: &crate::testing::gpu::Gpu, input: ShadowInput) -> Runner<'_> {
    let mut info = g.create_info(W, H);
    info.output_format = vk::Format::R32_SFLOAT;
    info.shadow_input = input;
    Runner::new(g, &info).unwrap()
}

/// `f`'s mask with the bits of the pixels not traced at `phase` inverted, and then every bit (lit bits).
fn scrambled_lit_bits(f: &FrameInputs, phase: u32) -> FrameInputs {
    let mut g = f.clone();
    let tiles_x = W.div_ceil(8);
    for (t, word) in g.mask.iter_mut().enumerate() {
        let (tx, ty) = (t as u32 % tiles_x, t as u32 / tiles_x);
        let untraced = (0..32u32).filter(|b| (tx * 8 + b % 8 + ty * 4 + b / 8) % 2 != phase).fold(0u32, |m, b| m | 1 << b);
        *word = !(*word ^ untraced);
    }
    g
}

#[test]
fn untraced_bits_and_the_mask_convention_change_nothing() {
    let g = gpu();
    let (mut plain, mut scrambled) = (runner(&g, ShadowInput::Checkerboard), runner(&g, ShadowInput::Checkerboard));
    for frame in 0..4u32 {
        let phase = frame % 2;
        let f = static_frame(W, H, &smooth, frame as u64);
        plain.checkerboard_phase = phase;
        scrambled.checkerboard_phase = phase;
        let a = plain.frame(&f, false);
        let s = scrambled_lit_bits(&f, phase);
        let d = ShadowsDispatch { hit_mask_convention: HitMaskConvention::LitBits, ..scrambled.dispatch(&s) };
        let b = scrambled.run(&s, &d).expect("lit-bit checkerboard frame");
        let differing = a.iter().zip(&b).filter(|(x, y)| x.to_bits() != y.to_bits()).count();
        assert_eq!(differing, 0, "frame {frame}: {differing} pixels depend on untraced bits or on the convention");
    }
    drop((plain, scrambled));
    g.assert_clean();
}

#[test]
fn a_static_soft_shadow_converges_at_half_a_ray_per_pixel() {
    let g = gpu();
    let (mut full, mut half) = (runner(&g, ShadowInput::HitMask), runner(&g, ShadowInput::Checkerboard));
    let (mut full_err, mut half_err, mut input_err) = (0.0, 0.0, 0.0);
    for frame in 0..24u32 {
        let f = static_frame(W, H, &smooth, 100 + frame as u64);
        half.checkerboard_phase = frame % 2;
        full_err = mae(&full.frame(&f, false), &f);
        half_err = mae(&half.frame(&f, false), &f);
        let noisy: Vec<f32> = (0..(W * H) as usize)
            .map(|i| !f.hit(i as u32 % W, i as u32 / W) as u32 as f32)
            .collect();
        input_err = mae(&noisy, &f);
    }
    eprintln!("MAE after 24 frames: input {input_err:.4}, one ray per pixel {full_err:.4}, checkerboard {half_err:.4}");
    assert!(half_err < 0.25 * input_err, "checkerboard: {half_err} against the input's {input_err}");
    assert!(half_err < 2.0 * full_err, "checkerboard {half_err} against one ray per pixel {full_err}");
    drop((full, half));
    g.assert_clean();
}

//! What the denoiser computes: exact values where the answer is known, convergence where it is noisy.

use super::{gpu, mae, static_frame};
use crate::testing::scene::{render, Camera};
use crate::testing::Runner;
use crate::Precision;

#[test]
fn all_lit_is_exactly_one_and_all_shadow_exactly_zero() {
    let g = gpu();
    for precision in [Precision::Fp32, Precision::Fp16] {
        if precision == Precision::Fp16 && !g.features.float16 {
            continue;
        }
        let mut info = g.create_info(40, 24);
        info.precision = precision;
        info.output_format = ash::vk::Format::R32_SFLOAT;
        let mut r = Runner::new(&g, &info).unwrap();
        eprintln!("{} {precision:?} push={}", g.device_name, g.features.push_descriptor);
        for (v, expect) in [(1.0, 1.0f32), (0.0, 0.0f32)] {
            for frame in 0..3 {
                let f = static_frame(40, 24, &|_, _| v, frame);
                let out = r.frame(&f, false);
                assert!(out.iter().all(|&o| o == expect), "{precision:?} v={v} frame {frame}: {:?}", &out[..8]);
            }
        }
    }
    g.assert_clean();
}

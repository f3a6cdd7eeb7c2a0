//! How often the moved-shadow test fires on a still penumbra, on the CPU reference (which the GPU matches: parity
//! seeds 8 and 14). Was run as src/tests/scratch_moved.rs (`mod scratch_moved;` in src/tests/mod.rs), not committed as
//! a test (it asserts nothing). 160x96, Quality, the penumbra-heavy field, fresh masks per frame.
use crate::reference::{self, memory::Frame};
use crate::testing::scene::{render, Camera};
use crate::{Preset, Settings};
use glam::{DVec2, DVec3};

#[test]
fn scratch_moved_rate() {
    let (w, h) = (160u32, 96u32);
    let cam = Camera::above(0.0, 0.0, 10.0);
    for (name, sigmas) in [("3 sigma (Quality)", 3.0f32), ("4 sigma", 4.0), ("5 sigma", 5.0)] {
        let mut settings = Settings::preset(Preset::Quality);
        settings.moving_shadow_sigmas = sigmas;
        let mut cpu = Frame::new(w as i32, h as i32, settings);
        let mut rates = Vec::new();
        for frame in 0..32u64 {
            let f = render(w, h, &cam, &cam, 1e9, &|x, z| 0.5 + 0.3 * (0.9 * x).sin() * (0.7 * z).cos(), 100 + frame);
            cpu.projection_inverse = f.projection_inverse.as_dmat4();
            cpu.reprojection = f.reprojection.as_dmat4();
            cpu.view_projection_inverse = f.view_projection_inverse.as_dmat4();
            cpu.hit_mask = f.mask.clone();
            cpu.depth = f.depth.iter().map(|&v| v as f64).collect();
            cpu.velocity = f.velocity.iter().map(|v| DVec2::new(v[0] as f64, v[1] as f64)).collect();
            cpu.normals = f.normals.iter().map(|n| reference::decode_normal(DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64), 1.0, 0.0)).collect();
            cpu.reset = frame == 0;
            let (tw, th) = (w.div_ceil(8) as i32, h.div_ceil(4) as i32);
            reference::run_frame(&mut cpu, true);
            let moved = (0..tw * th).filter(|&i| reference::tile_classification::shadow_moved(&cpu, [i % tw, i / tw])).count();
            cpu.advance();
            if frame >= 8 { rates.push(moved as f64 / (tw * th) as f64); }
        }
        let mean = rates.iter().sum::<f64>() / rates.len() as f64;
        eprintln!("{name}: moved tiles per frame on a still penumbra, frames 8-31: mean {:.2}%, max {:.2}%", 100.0 * mean, 100.0 * rates.iter().cloned().fold(0.0, f64::max));
    }
}

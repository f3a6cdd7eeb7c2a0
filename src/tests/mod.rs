//! GPU tests on a real Vulkan device (lavapipe in CI) with validation and synchronization validation on:
//! every test ends with `assert_clean`, so any validation message fails it.

mod bad_input;
mod capi;
mod checkerboard;
mod classify;
pub(crate) mod correctness;
mod diagnostics;
mod extremes;
mod parity;
mod interface;
mod layers;
mod host_previous;
mod lights;
mod resources;
mod shader_overrides;
mod transient;

use crate::testing::gpu::{Gpu, GpuOptions};
use crate::testing::scene::{render, Camera, FrameInputs};

pub(crate) fn gpu() -> Gpu {
    let g = Gpu::new(GpuOptions::default());
    eprintln!("device: {} (push descriptors {}, float16 {})", g.device_name, g.features.push_descriptor, g.features.float16);
    g
}

/// A static view of the plane (no sky: the plane is wider than the view) with visibility `v`.
pub(crate) fn static_frame(w: u32, h: u32, v: &dyn Fn(f64, f64) -> f64, seed: u64) -> FrameInputs {
    let cam = Camera::above(0.0, 0.0, 10.0);
    render(w, h, &cam, &cam, 1e9, v, seed)
}

/// Mean absolute error between output and truth over receiver pixels.
pub(crate) fn mae(out: &[f32], f: &FrameInputs) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for i in 0..out.len() {
        if f.receiver[i] {
            sum += (out[i] as f64 - f.truth[i] as f64).abs();
            n += 1;
        }
    }
    sum / n.max(1) as f64
}

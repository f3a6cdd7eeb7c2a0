//! GPU timings of dnsr's passes on synthetic scenes, from GPU timestamps: median over many frames.
//!
//! `cargo run --release --features demo --bin dnsr-bench -- [--frames N] [--sizes 1920x1080,3840x2160] [--fp16]`
//! Prints a Markdown table: device, size, scene, per-pass and total median milliseconds.

use dnsr::ash::vk;
use dnsr::testing::gpu::{Gpu, GpuOptions};
use dnsr::testing::scene::{render, Camera};
use dnsr::testing::Runner;
use dnsr::{PassTimings, Precision};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

fn parse_size(s: &str) -> Option<(u32, u32)> {
    let (w, h) = s.split_once('x')?;
    Some((w.parse().ok()?, h.parse().ok()?))
}

fn main() {
    let mut frames = 160usize;
    let mut sizes = vec![(1920u32, 1080u32), (2560, 1440), (3840, 2160)];
    let mut precision = Precision::Fp32;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--frames" => frames = args.next().and_then(|v| v.parse().ok()).filter(|&n| n > 0).unwrap_or_else(|| usage()),
            "--sizes" => {
                sizes = args.next().unwrap_or_else(|| usage()).split(',').map(|s| parse_size(s).unwrap_or_else(|| usage())).collect()
            }
            "--fp16" => precision = Precision::Fp16,
            _ => usage(),
        }
    }
    let gpu = Gpu::new(GpuOptions { validation: false, ..Default::default() });
    if precision == Precision::Fp16 && !gpu.features.float16 {
        eprintln!("the device lacks shaderFloat16 / 16-bit storage");
        std::process::exit(1);
    }
    println!("device: {} ({:?}, push descriptors {})\n", gpu.device_name, precision, gpu.features.push_descriptor);
    println!("| size | scene | prepare | tile classification | filter 0 | filter 1 | filter 2 | total (ms, median of {frames}) |");
    println!("|---|---|---|---|---|---|---|---|");
    // Penumbra-heavy: a smooth field between 0.2 and 0.8 everywhere, so no tile is uniform.
    let penumbra = |x: f64, z: f64| 0.5 + 0.3 * (x * 0.9).sin() * (z * 0.7).cos();
    for &(w, h) in &sizes {
        let scenes: [(&str, f64, &dyn Fn(f64, f64) -> f64); 3] =
            [("penumbra-heavy", 1e9, &penumbra), ("all lit", 1e9, &|_, _| 1.0), ("90% sky", 0.6, &penumbra)];
        for (name, half_width, field) in scenes {
            let mut info = gpu.create_info(w, h);
            info.enable_timestamps = true;
            info.precision = precision;
            info.output_format = vk::Format::R16_SFLOAT;
            let mut r = Runner::new(&gpu, &info).expect("context");
            let cam = Camera::above(0.0, 0.0, 10.0);
            let f = render(w, h, &cam, &cam, half_width, field, 1);
            r.frame(&f, true);
            let d = r.dispatch(&f);
            let cmd = gpu.command_buffer();
            let mut samples: Vec<PassTimings> = Vec::with_capacity(frames);
            for _ in 0..frames + 8 {
                gpu.submit_with(cmd, |cmd| r.ctx.record_shadows(cmd, &d).expect("record"));
                samples.push(r.ctx.timings().expect("timings").expect("completed frame"));
            }
            gpu.free_command_buffer(cmd);
            let s = &samples[8..]; // warm-up frames dropped
            let m = |f: fn(&PassTimings) -> f64| median(s.iter().map(f).collect());
            println!(
                "| {w}x{h} | {name} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} |",
                m(|t| t.prepare_ms),
                m(|t| t.tile_classification_ms),
                m(|t| t.filter_ms[0]),
                m(|t| t.filter_ms[1]),
                m(|t| t.filter_ms[2]),
                m(|t| t.total_ms)
            );
            println!("<!-- internal memory {:.1} MB ({:.2} B/px) -->", r.ctx.memory_bytes() as f64 / 1e6, r.ctx.memory_bytes() as f64 / (w * h) as f64);
        }
    }
}

fn usage() -> ! {
    eprintln!("usage: dnsr-bench [--frames N] [--sizes WxH[,WxH...]] [--fp16]");
    std::process::exit(2);
}

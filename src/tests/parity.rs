//! GPU vs CPU reference (src/reference, f64) on randomized inputs at odd sizes with every tile state present:
//! each internal output of a frame is compared, from the same inputs and the same previous state.

use super::gpu;
use crate::reference::{self, memory::Frame, storage};
use crate::testing::gpu::{Gpu, TestImage};
use crate::testing::scene::{hash01, FrameInputs};
use crate::testing::{f16_to_f32, Runner};
use crate::{Precision, Settings};
use ash::vk;
use glam::{DMat4, DVec2, DVec3, Mat4};

/// A random frame: static G-buffer (random depth and unit normals, sky patches) except a block whose depth jumps
/// in frame 3 (disocclusion) and a band of other normals that slides, and a fresh mask with uniform lit and shadowed regions (cleared tiles) around
/// random noise. From 96 px wide the uniform regions hold whole cleared 8x8 groups next to filtered tiles, whose
/// pixels the later filter passes tap.
fn random_frame(w: u32, h: u32, seed: u64, frame: u64) -> FrameInputs {
    let n = (w * h) as usize;
    let (tw, th) = (w.div_ceil(8), h.div_ceil(4));
    let cam = crate::testing::scene::Camera::above(0.0, 0.0, 10.0);
    let base = crate::testing::scene::render(w, h, &cam, &cam, 1e9, &|_, _| 0.5, 0);
    let mut f = FrameInputs { mask: vec![0; (tw * th) as usize], truth: vec![0.5; n], ..base };
    for y in 0..h {
        for x in 0..w {
            let i = (y * w + x) as usize;
            let r = |k: u64| hash01(seed ^ (k * 0x9E37), x, y);
            let sky = (x / 6 + y / 5) % 7 == 3;
            let jump = frame >= 3 && x < 12 && y >= h / 2;
            // Under sub-pixel motion (below) in 4x4 blocks of one depth: a history footprint inside a block holds
            // this surface point's depth, one across a block's border other depths too (classification leaves
            // those texels out, as it does sky).
            let moving = matches!(seed, 5 | 6 | 12 | 13 | 15);
            let depth = if moving { hash01(seed ^ 0x9E37, x / 4, y / 4) } else { r(1) };
            f.depth[i] = if sky { 1.0 } else { (0.9 + 0.09 * depth) as f32 * if jump { 0.99 } else { 1.0 } };
            // A band of surfaces facing -y slides one pixel left per frame over the others: at its left edge
            // pixels turn, and under sub-pixel motion (seeds 5, 6, 12) their footprints hold texels that were in
            // the band last frame beside ones that were not. Classification leaves turned texels out, and where
            // the nearest one turned continues the heaviest one that did not.
            let left = 20 - frame as u32;
            let band = (left..left + 16).contains(&x) && y >= h / 4 && y < h / 2 + h / 4;
            let nrm = if band {
                DVec3::new(0.2 * (r(2) - 0.5), -1.0, 0.2 * (r(4) - 0.5))
            } else {
                DVec3::new(r(2) - 0.5, r(3) * 0.5 + 0.5, r(4) - 0.5)
            }
            .normalize();
            f.normals[i] = [nrm.x as f32, nrm.y as f32, nrm.z as f32, 0.0];
            f.receiver[i] = !sky;
            // Some cases move their surfaces by a fraction of a pixel: history falls between texels, where stable
            // runs pick the texel to read (seeds 5 and 6 keep stable history; 13 is a light of no size).
            if moving {
                f.velocity[i] = [0.37 / w as f32, -0.41 / h as f32];
            }
            // Hit distances for penumbra guidance, with unusable values (zero, negative, NaN, infinite) mixed in.
            // The right half of seeds 4 and 11 knows no blocker at all (faces turned from the light): its pixels
            // are hard, under a light of any size.
            let unknown = (seed == 4 || seed == 11) && x >= w / 2;
            f.hit_distance[i] = match (x * 7 + y * 3) % 29 {
                _ if unknown => f32::INFINITY,
                0 => 0.0,
                1 => -2.0,
                2 => f32::NAN,
                3 => f32::INFINITY,
                // Seed 4's blockers lie 1-10 pixel footprints from their receivers: on both sides of the nearest
                // blocker a hard penumbra allows (HARD_PENUMBRA_MIN_BLOCKER_PIXELS). Seed 11's (a light of no size)
                // lie closer than any: only the light's size makes its pixels hard.
                _ => ((0.05 + 3.0 * r(5)) * match seed { 4 => 0.2, 11 => 0.01, _ => 1.0 }) as f32,
            };
            // Regions wide enough for uniform tiles (+-8 px): top-left lit, a bottom band shadowed, the rest noise
            // with a probability that varies across the image.
            let (lit_w, lit_h, band) = if w >= 96 { (56, 44, 24) } else { (24, 12, 12) };
            // Seed 6's compared frame draws a 1-px shadow line across the lit region, whose history is resolved
            // (cleared tiles: pure, converged): under its sub-pixel motion, where the footprint also holds sky,
            // the line's samples stand alone.
            let line = seed == 6 && frame == 3 && x == 30;
            // Seeds 8 and 14's compared frame moves the shadow over the still right half (its visibility mirrored):
            // classification tells the tiles there from the left half's (dnsr_shadow_moved).
            let p = x as f64 / w as f64;
            let p = if (seed == 8 || seed == 14) && frame == 3 && x >= w / 2 { 1.0 - p } else { p };
            let lit = if x < lit_w && y < lit_h {
                !line
            } else if y + band >= h {
                false
            } else {
                hash01(seed ^ frame.wrapping_mul(0xD1B5_4A32_D192_ED03), x, y) < p
            };
            // Seed 3's host tests its rays against the normals (its light is given, 0.6 rad wide): no receiver
            // turned away from the whole light (with a margin) sees it, so no lit sample vetoes the final ones, which
            // the filter then returns as they are and leaves out of its taps. Not in the lit region, whose tiles
            // stay cleared (its lit samples there keep their own groups from final pixels).
            let to_light = DVec3::new(1.0, 0.2, -0.3);
            let away = seed == 3 && !(x < lit_w && y < lit_h) && nrm.dot(to_light) < -(0.3f64.sin() + 0.05) * to_light.length();
            let lit = lit && !away;
            if !lit {
                f.set_hit(x, y);
            }
            // A visibility input: exact where the mask regions are uniform, else the mean of 1 to 4 rays, and a
            // few stored values outside [0, 1] (clamped; NaN reads as 0).
            let uniform = (x < lit_w && y < lit_h) || y + band >= h;
            let rays = 1 + (x + 2 * y) % 4;
            let hits = (0..rays).filter(|&k| hash01(seed ^ frame ^ (k as u64 + 7) * 0x51_7CC1, x, y) < p).count();
            f.visibility[i] = match (x * 5 + y * 11) % 37 {
                _ if uniform || away => lit as u32 as f32,
                0 => f32::NAN,
                1 => -0.25,
                2 => 1.5,
                _ => hits as f32 / rays as f32,
            };
            // Seed 9 uploads half floats: the reference reads the same values.
            if seed == 9 {
                f.visibility[i] = f16_to_f32(crate::testing::f32_to_f16(f.visibility[i]));
            }
        }
    }
    f
}

fn download<T: Copy + bytemuck::Pod>(g: &Gpu, image: vk::Image, format: vk::Format, w: u32, h: u32) -> Vec<T> {
    let raw = g.download(&TestImage::borrowed(image, format, w, h, vk::ImageLayout::GENERAL));
    bytemuck::cast_slice(&raw).to_vec()
}

/// The history's means in either precision.
fn download_history(g: &Gpu, image: vk::Image, format: vk::Format, w: u32, h: u32) -> Vec<f64> {
    let raw: Vec<u16> = download(g, image, format, w, h);
    if format == vk::Format::R16_UNORM {
        raw.iter().map(|&v| v as f64 / 65535.0).collect()
    } else {
        assert_eq!(format, vk::Format::R16_SFLOAT);
        raw.iter().map(|&v| f16_to_f32(v) as f64).collect()
    }
}

/// (mean, variance) pairs of an intermediate image in either precision (`format`: the signal's, whatever the
/// format of the image whose memory holds it).
fn download_rg(g: &Gpu, image: vk::Image, format: vk::Format, w: u32, h: u32, settings: &Settings) -> Vec<DVec2> {
    if format == vk::Format::R16G16_UNORM {
        let raw: Vec<[u16; 2]> = download(g, image, format, w, h);
        let scale = crate::state::signal_scale(settings.variance_boost_samples) as f64;
        raw.iter().map(|v| storage::decode_signal([v[0] as u32, v[1] as u32], scale)).collect()
    } else if format == vk::Format::R16G16_SFLOAT {
        let raw: Vec<[u16; 2]> = download(g, image, format, w, h);
        raw.iter().map(|v| DVec2::new(f16_to_f32(v[0]) as f64, f16_to_f32(v[1]) as f64)).collect()
    } else {
        let raw: Vec<[f32; 2]> = download(g, image, format, w, h);
        raw.iter().map(|v| DVec2::new(v[0] as f64, v[1] as f64)).collect()
    }
}

fn dmat(m: Mat4) -> DMat4 {
    m.as_dmat4()
}

/// The largest difference of one compared value, and every pixel's difference.
struct Worst {
    name: &'static str,
    err: f64,
    at: usize,
    errors: Vec<f64>,
}

impl Worst {
    /// The pixels above `tolerance`.
    fn over(&self, tolerance: f64) -> usize {
        self.errors.iter().filter(|&&e| e > tolerance).count()
    }
}

fn worst(name: &'static str, gpu: impl Iterator<Item = f64>, cpu: impl Iterator<Item = f64>) -> Worst {
    let errors: Vec<f64> = gpu.zip(cpu).map(|(a, b)| if a.is_nan() || b.is_nan() { f64::INFINITY } else { (a - b).abs() }).collect();
    let (at, err) = errors.iter().copied().enumerate().fold((0, 0.0), |w, (i, e)| if e > w.1 { (i, e) } else { w });
    Worst { name, err, at, errors }
}

/// Where float rounding differs between a device and the f64 reference (a stored count one float16 step apart, an
/// approximate exp or sqrt on a steep slope), a value may move by more than the tolerance: up to this share of a
/// case's pixels may, each within `ROUNDING_BOUND` (2/255, what an 8-bit output shows). While the history was read
/// through the sampler's bilinear filter (8 sub-texel bits on NVIDIA), an NVIDIA H200 had 9 such pixels in seed 5's
/// 2560 (history up to 1.7e-4 from the reference); lavapipe none. A wrong formula moves far more pixels, or further.
const ROUNDING_SHARE: f64 = 0.005;
const ROUNDING_BOUND: f64 = 2.0 / 255.0;

/// Steps of the stored format between two values of one moments field: unorm14 for the mean, the 9-bit float's
/// step for the count (src/reference/storage.rs) and, relative to its value, for the sum (formed from the mean and
/// the count with 0/1 samples), whole codes (half samples) for the run. A visibility input stores the sum as
/// float32, where the GPU's float32 arithmetic and the reference's f64 differ in the last bits: under a hundredth
/// of that step counts as the same value.
fn moment_steps(field: usize, a: f64, b: f64) -> f64 {
    let count_step = |v: f64| if v < (-7f64).exp2() { (-12f64).exp2() } else { (v.log2().floor() - 5.0).exp2() };
    if field == 0 {
        // Whole codes (their float32 decoding is not evenly spaced to the last bit).
        return ((a * 16383.0).round() - (b * 16383.0).round()).abs();
    }
    let step = match field {
        3 => 0.5,
        _ => count_step(a.abs().max(b.abs())),
    };
    let steps = (a - b).abs() / step;
    if field == 1 && steps < 0.01 { 0.0 } else { steps }
}

/// Parity of the stored moments, per value in its format's units: the GPU rounds its float32 value and the
/// reference its f64 one, so a value may land one step apart where the two straddle a rounding boundary, and the
/// run (exact) never; nearly all stored values are identical (a reference that did not round as the GPU stores
/// would differ on most).
fn assert_stored_moments_match(gpu: &[glam::DVec4], cpu: &[glam::DVec4], case: &str) {
    for (field, name) in ["mean", "sum of squared deviations", "count", "run"].into_iter().enumerate() {
        let steps: Vec<f64> = gpu.iter().zip(cpu).map(|(g, c)| moment_steps(field, g[field], c[field])).collect();
        let (at, worst) = steps.iter().enumerate().fold((0, 0.0f64), |w, (i, &s)| if s > w.1 { (i, s) } else { w });
        let differ = steps.iter().filter(|&&s| s > 0.0).count();
        eprintln!("{case}: stored moments.{name}: {differ} of {} differ, at most {worst} steps (pixel {at})", steps.len());
        let limit = if field == 3 { 0.0 } else { 1.0 };
        assert!(worst <= limit, "{case}: stored moments.{name} of pixel {at}: gpu {} cpu {} ({worst} steps)", gpu[at][field], cpu[at][field]);
        assert!(differ * 100 <= steps.len(), "{case}: stored moments.{name} differ on {differ} of {} pixels", steps.len());
    }
}

/// Converged pixels are marked by a variance of exactly 0, and every other receiver stores at least the floor that
/// keeps it from reading as converged: 1e-6, or with float16 intermediates 2^-14 (the smallest normal float16, which
/// no store can flush to 0). The GPU and the reference must mark the same pixels.
fn assert_converged_flags_match(name: &str, gpu: &[DVec2], cpu: &[DVec2], precision: Precision, settings: &Settings) {
    let inv = if precision == Precision::Fp16 { crate::passes::UNCONVERGED_VARIANCE_INV_FP16 } else { crate::passes::UNCONVERGED_VARIANCE_INV };
    let mut floor = 1.0 / inv as f64;
    if precision == Precision::Fp32 {
        // Stored as a unorm16 deviation: the floor's code, or the code below it (a device may round either way).
        let scale = crate::state::signal_scale(settings.variance_boost_samples) as f64;
        let code = (floor.sqrt() / scale * 65535.0).round();
        assert!(code >= 2.0, "the variance floor must not round to the converged code 0");
        floor = ((code - 1.0) / 65535.0 * scale).powi(2);
    }
    for (i, (g, c)) in gpu.iter().zip(cpu).enumerate() {
        assert_eq!(g.y == 0.0, c.y == 0.0, "{precision:?} {name}: pixel {i} converged on one side only (gpu {}, cpu {})", g.y, c.y);
        if c.y > 0.0 {
            assert!(g.y >= floor * (1.0 - 1e-6), "{precision:?} {name}: pixel {i} stores variance {} below the floor {floor}", g.y);
        }
        // Where the reference stores the floor itself, the GPU stores it or a variance its float32 arithmetic put a
        // little above (variances that small differ by a few times 1e-6 between f32 and f64): a floor that differs
        // between the two (1e-6 against 2^-14) is 61 times apart.
        if c.y > 0.0 && c.y <= floor {
            assert!(g.y <= 10.0 * c.y, "{precision:?} {name}: pixel {i} at the variance floor: gpu {} cpu {}", g.y, c.y);
        }
    }
    let at_floor = cpu.iter().filter(|c| c.y > 0.0 && c.y < 1.5 * floor).count();
    eprintln!("{precision:?} {name}: {} converged pixels, {at_floor} at the variance floor", cpu.iter().filter(|c| c.y == 0.0).count());
    assert!(cpu.iter().any(|c| c.y == 0.0), "{name}: no converged pixel");
}

/// Seeds 8 and 9 take per-pixel visibility instead of the hit mask, seeds 10 and 11 a checkerboard input (half of the
/// mask's pixels traced per frame, alternating).
fn parity(g: &Gpu, precision: Precision, passes: u32, w: u32, h: u32, seed: u64) -> Vec<Worst> {
    let visibility_input = (8..10).contains(&seed);
    let checkerboard = (10..12).contains(&seed);
    let mut info = g.create_info(w, h);
    // Odd cases start from the default (Quality: its current-frame weight, no output contrast, its cross-tap
    // weight), even ones from the FidelityFX values; the run-based knobs are set per case below.
    info.settings = crate::Settings::preset(if seed % 2 == 1 { crate::Preset::Quality } else { crate::Preset::Balanced });
    info.precision = precision;
    if visibility_input {
        info.shadow_input = crate::ShadowInput::Visibility;
    }
    if checkerboard {
        info.shadow_input = crate::ShadowInput::Checkerboard;
    }
    info.output_format = vk::Format::R32_SFLOAT;
    info.settings.filter_passes = passes;
    // Seed 15 reads last frame's depth and normals from the host's images (`host_previous_gbuffer`), not rounded to a
    // depth copy's codes: under sub-pixel motion, with the sliding band's turned normals and the jump's disocclusion.
    info.host_previous_gbuffer = seed == 15;
    // Some cases clamp the history of pixels with two identical samples in a row to their run ...
    // (Seed 6 takes four: no run is stable by the compared frame 3, so under its sub-pixel motion a run continues
    // from a pure agreeing texel where the nearest one held the other value.)
    info.settings.stable_history_samples = match seed {
        1 | 5 | 8 | 10 | 12 | 14 | 15 => 2.0,
        6 => 4.0,
        _ => 0.0,
    };
    // ... and of those, two restart it after one sample of the other value, or two unless the neighbourhood agrees
    // (both possible by the compared frame 3).
    info.settings.history_flip_samples = match seed {
        1 | 8 | 10 | 15 => 1.0,
        5 => 2.0,
        _ => 0.0,
    };
    // Some cases make pixels with two (or three) identical samples in a row converged: their run's value passes
    // through the filter (reached by the compared frame 3), with stable history on or off.
    info.settings.converged_samples = match seed {
        1 | 3 | 8 | 10 | 12 | 14 | 15 => 2.0,
        6 => 3.0,
        _ => 0.0,
    };
    // Some guided cases output the sample under a penumbra narrower than a pixel or two (about half of their
    // pixels: their penumbrae are 0.3-3 px wide either side).
    info.settings.hard_penumbra_pixels = match seed {
        4 | 11 => 1.0,
        9 => 1.5,
        _ => 0.0,
    };
    // Some cases make tiles hard by time after one quiet frame (reached by the compared frame 3: Quality's 6 is not),
    // seed 12 after two (its frame 7); every case with the run features compares the tiles' counts.
    info.settings.hard_tile_frames = match seed {
        1 | 3 | 5 => 1.0,
        12 => 2.0,
        _ => info.settings.hard_tile_frames,
    };
    // Two cases from the FidelityFX values tell a shadow that moved over a still surface (Quality's cases do too).
    if seed == 8 || seed == 14 {
        info.settings.moving_shadow_sigmas = 3.0;
    }
    let mut r = Runner::new(g, &info).unwrap();
    if info.host_previous_gbuffer {
        r.keep_previous_gbuffer();
    }
    // Seed 13: a light of no size without hit distances (ShadowsDispatch::hard_light) under sub-pixel motion.
    r.hard_light = seed == 13;
    // Some cases give the light: receivers turned away from it keep their shadowed samples. Seed 3's direction
    // (a directional light) and seed 12's point light (under sub-pixel motion) leave about half of the random
    // normals turned away.
    r.light_position = match seed {
        3 => Some(glam::Vec4::new(1.0, 0.2, -0.3, 0.0)),
        12 => Some(glam::Vec4::new(3.0, 20.0, -4.0, 1.0)),
        _ => None,
    };
    // Seed 3's light has a size: the receivers turned less than its angular radius (0.3 rad) past its centre are
    // filtered, those turned further are final (its host tests its rays against the normals: random_frame). Seed
    // 12's is a point, and lit samples on its band of normals turned away keep its groups from final pixels.
    r.light_angular_size = if seed == 3 { 0.6 } else { 0.0 };
    // Some cases guide the filter by the hit distances (penumbrae from under a pixel to tens of pixels wide).
    r.guidance = match seed {
        2 | 6 => Some(0.5),
        4 => Some(0.5),
        9 => Some(0.04),
        // A light of no size (checkerboard input): every traced pixel passes through, no untraced one.
        11 => Some(0.0),
        7 => Some(1.0),
        _ => None,
    };
    // One visibility case reads 16-bit floats (random_frame rounds its values to them).
    if seed == 9 {
        r.set_visibility_format(vk::Format::R16_SFLOAT);
    }
    // Seed 12 runs six frames before the compared one under sub-pixel motion: rejected histories keep their runs
    // but not their counts, so runs of two or three times the count occur on moments that also held the other
    // value (pure or not: shaders/tile_classification.glsl, dnsr_pure).
    let frames = if seed == 12 { 7 } else { 3 };
    for frame in 1..frames {
        r.checkerboard_phase = if checkerboard { frame as u32 % 2 } else { 0 };
        r.frame(&random_frame(w, h, seed, frame), frame == 1);
    }
    r.checkerboard_phase = checkerboard as u32;
    let before = r.ctx.internals(0);
    let fmt = before.intermediate_format;
    let mut prev_moments = crate::testing::download_moments(g, before.moments, w, h, info.shadow_input);
    if seed == 12 {
        // Every fifth pixel's history replaced by moments on both sides of the purity test (dnsr_pure): counts
        // from 0.6 to 2.5 (rejected histories), runs of 1 to 5 either way, means exactly the run's value or not.
        let receivers = random_frame(w, h, seed, frames - 1).receiver;
        for (i, m) in prev_moments.iter_mut().enumerate().filter(|(i, _)| i % 5 == 0 && receivers[*i]) {
            let k = i / 5;
            let run = [1.0, 2.0, 3.0, 4.0, 5.0][k / 4 % 5] * if k % 3 == 0 { -1.0 } else { 1.0 };
            let exact = if run > 0.0 { 1.0 } else { 0.0 };
            let mean = if k / 20 % 2 == 0 { exact } else { 0.5 + 0.3 * (exact * 2.0 - 1.0) };
            *m = glam::DVec4::new(mean, if mean == exact { 0.0 } else { 0.1 }, [0.6, 1.0, 1.5, 2.5][k % 4], run);
        }
        let packed = crate::testing::pack_moments(&prev_moments, info.shadow_input);
        let format = crate::state::moments_format(info.shadow_input);
        g.upload(&TestImage::borrowed(before.moments, format, w, h, vk::ImageLayout::GENERAL), bytemuck::cast_slice(&packed));
        prev_moments = crate::testing::download_moments(g, before.moments, w, h, info.shadow_input);
    }
    let prev_depth: Vec<u32> = download(g, before.depth, vk::Format::R32_UINT, w, h);
    let (tw, th) = (w.div_ceil(8), h.div_ceil(4));
    let prev_tile_quiet: Vec<u32> = download(g, before.tile_quiet, vk::Format::R32_UINT, tw, th);
    let history = download_history(g, before.history, before.history_format, w, h);

    let f = random_frame(w, h, seed, frames);
    let d = r.dispatch(&f);
    let out = r.frame(&f, false);
    let after = r.ctx.internals(0);
    let tile_quiet: Vec<u32> = download(g, after.tile_quiet, vk::Format::R32_UINT, tw, th);
    let tile_meta: Vec<u32> = download(g, after.tile_meta, vk::Format::R32_UINT, tw, th);
    let tile_blocker: Vec<f32> = download(g, after.tile_blocker, vk::Format::R32_SFLOAT, tw, th);
    let moments = crate::testing::download_moments(g, after.moments, w, h, info.shadow_input);
    let depth_copy: Vec<u32> = download(g, after.depth, vk::Format::R32_UINT, w, h);
    let reprojection = download_rg(g, after.reprojection, fmt, w, h, &info.settings);
    let history_out = download_history(g, after.history, after.history_format, w, h);
    // The signal pass 1 read (pass 0's output; with four passes pass 3's input, pass 2's output), which pass 1
    // overwrites in no configuration. With one pass (a light of no size runs one) none is written.
    let ran = crate::passes::light_filter_passes(passes, d.hard_light);
    let signal_pass = if ran == 4 { Some(2) } else { (ran > 1).then_some(0) };
    let signal = download_rg(g, after.signal, fmt, w, h, &info.settings);

    let mut cpu = Frame::new(w as i32, h as i32, info.settings);
    cpu.projection_inverse = dmat(d.projection_inverse);
    cpu.reprojection = dmat(d.reprojection_matrix);
    cpu.view_projection_inverse = dmat(d.view_projection_inverse);
    cpu.eye = d.eye.as_dvec3();
    cpu.depth_similarity_sigma = d.depth_similarity_sigma as f64;
    cpu.hit_mask = f.mask.clone();
    if visibility_input {
        cpu.visibility = Some(f.visibility.iter().map(|&v| v as f64).collect());
    }
    cpu.checkerboard_phase = checkerboard.then_some(1);
    cpu.hit_distance = f.hit_distance.iter().map(|&v| v as f64).collect();
    cpu.hard_light = d.hard_light;
    cpu.light_position = d.light_position.map(|l| l.as_dvec4());
    cpu.light_angular_size = d.light_angular_size as f64;
    cpu.penumbra = d.hit_distance.map(|_| reference::Penumbra::new(d.light_angular_size as f64, cpu.projection_inverse, h as i32));
    cpu.depth = f.depth.iter().map(|&v| v as f64).collect();
    cpu.velocity = f.velocity.iter().map(|v| DVec2::new(v[0] as f64, v[1] as f64)).collect();
    cpu.normals = f.normals.iter().map(|n| reference::decode_normal(DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64), 1.0, 0.0)).collect();
    cpu.previous_depth = prev_depth;
    if info.host_previous_gbuffer {
        let last = random_frame(w, h, seed, frames - 1);
        let normals: Vec<DVec3> = last.normals.iter().map(|n| reference::decode_normal(DVec3::new(n[0] as f64, n[1] as f64, n[2] as f64), 1.0, 0.0)).collect();
        cpu.set_host_previous(&last.depth.iter().map(|&v| v as f64).collect::<Vec<_>>(), &normals);
    }
    cpu.previous_moments = prev_moments;
    cpu.previous_tile_quiet = prev_tile_quiet;
    cpu.history = history;
    cpu.half_intermediates = precision == Precision::Fp16;
    reference::run_frame(&mut cpu, true);
    if seed == 8 || seed == 14 {
        // Both sides of the moved-shadow test: the right half's tiles, not the left half's.
        let (tiles, columns) = ((tw * th) as i32, tw as i32);
        let moved = (0..tiles).filter(|&i| reference::tile_classification::shadow_moved(&cpu, [i % columns, i / columns])).count();
        eprintln!("seed {seed}: the shadow moved over {moved} of {tiles} tiles");
        assert!(moved > 0 && moved < tiles as usize, "seed {seed}: {moved} of {tiles} tiles moved");
    }

    // Exact integer state, and every tile state present.
    // A hit mask is read as the host gives it (no prepare): the reference's tile mask is then the lit-bit word
    // classification forms on reading it, which the GPU does not store.
    if visibility_input || checkerboard {
        let tile_mask: Vec<u32> = download(g, after.tile_mask, vk::Format::R32_UINT, tw, th);
        let tile_dark: Vec<u32> = download(g, after.tile_dark, vk::Format::R32_UINT, tw, th);
        assert_eq!(tile_mask, cpu.tile_mask, "tile mask");
        assert_eq!(tile_dark, cpu.tile_dark, "dark mask");
    }
    assert_eq!(tile_meta, cpu.tile_meta, "tile metadata");
    if info.settings.uses_runs() {
        assert_eq!(tile_quiet, cpu.tile_quiet, "seed {seed}: tiles' quiet frames");
        if info.settings.hard_tile_frames <= 2.0 && info.settings.hard_tile_frames > 0.0 {
            // Both sides: tiles hard by time, and tiles that a contradiction kept from it.
            let hard = (0..(tw * th) as i32).filter(|&i| reference::tile_classification::quiet_tiles(&cpu, [i % tw as i32, i / tw as i32])).count();
            eprintln!("seed {seed}: {hard} of {} tiles hard by time", tw * th);
            assert!(hard > 0 && cpu.tile_quiet.contains(&0), "seed {seed}: {hard} tiles hard by time, counts {:?}", cpu.tile_quiet);
        }
    }
    for state in [0, crate::passes::TILE_CLEARED, crate::passes::TILE_CLEARED | crate::passes::TILE_LIT] {
        assert!(cpu.tile_meta.contains(&state), "tile state {state} missing from the test input");
    }
    assert_stored_moments_match(&moments, &cpu.moments, &format!("{precision:?} {w}x{h} seed {seed}"));
    // The depth copy in its codes' steps: one at most for the depth and for each of the normal's two components
    // (the GPU's float32 linear depth and octahedral division against f64 here).
    for (i, (&gpu, &cpu)) in depth_copy.iter().zip(&cpu.depth_copy).enumerate() {
        let (depth, bits) = (crate::state::DEPTH_CODE_BITS, crate::state::DEPTH_COPY_NORMAL_BITS);
        let fields = [(0, depth), (depth, bits), (depth + bits, bits)];
        let steps = fields.map(|(at, width)| {
            let field = |v: u32| ((v >> at) & ((1 << width) - 1)) as i64;
            // The normal's codes are signed: compare them as such (-1 and 0 are one step apart).
            let signed = |c: i64| if at > 0 && c >= 1 << (width - 1) { c - (1 << width) } else { c };
            (signed(field(gpu)) - signed(field(cpu))).abs()
        });
        assert!(steps.iter().all(|&s| s <= 1), "depth copy at pixel {i}: {gpu:#010x}, reference {cpu:#010x} (steps {steps:?})");
    }
    if info.settings.converged_samples > 0.0 {
        let mut signals: Vec<(&str, &[DVec2], &[DVec2])> = vec![("reprojection", &reprojection, &cpu.reprojection_out)];
        if let Some(k) = signal_pass {
            signals.push((if k == 0 { "signal (filter 0)" } else { "signal (filter 2)" }, &signal, &cpu.filter_out[k]));
        }
        for (name, gpu_signal, cpu_signal) in signals {
            // Passes after the first reuse the reprojection image: its values are the temporal part's only with
            // one or two passes.
            if name == "reprojection" && passes > 2 {
                continue;
            }
            assert_converged_flags_match(name, gpu_signal, cpu_signal, precision, &info.settings);
        }
    }
    // A light of some size whose host tests the normals (seed 3): the case has final pixels to compare.
    if d.light_position.is_some() && d.light_angular_size > 0.0 {
        assert!(cpu.reprojection_out.iter().any(|&c| reference::final_signal(c)), "no final pixel");
    }
    let mut results = vec![
        worst("history (filter 0)", history_out.iter().copied(), cpu.filter_out[0].iter().map(|v| v.x)),
        worst("output", out.iter().map(|&v| v as f64), cpu.output.iter().copied()),
    ];
    if let Some(k) = signal_pass {
        let name = if k == 0 { "signal (filter 0).mean" } else { "signal (filter 2).mean" };
        results.push(worst(name, signal.iter().map(|v| v.x), cpu.filter_out[k].iter().map(|v| v.x)));
    }
    if cpu.penumbra.is_some() {
        // The blocker estimate of the tiles the filter reads it for (relative: distances up to ~3).
        let mixed: Vec<usize> = (0..tile_meta.len()).filter(|&i| tile_meta[i] == 0).collect();
        assert!(mixed.iter().any(|&i| cpu.tile_blocker[i] > 0.0), "no tile with a known blocker");
        results.push(worst(
            "tile blocker (relative)",
            mixed.iter().map(|&i| tile_blocker[i] as f64 / cpu.tile_blocker[i].abs().max(1.0)),
            mixed.iter().map(|&i| cpu.tile_blocker[i] / cpu.tile_blocker[i].abs().max(1.0)),
        ));
    }
    if passes <= 2 {
        // The temporal result survives only while no later pass reuses its image.
        results.push(worst("reprojection.mean", reprojection.iter().map(|v| v.x), cpu.reprojection_out.iter().map(|v| v.x)));
        // Variance up to ~16 while boosted: compared relative to max(1, value) (the fp32 path's unorm16 deviation
        // code at variance 4 is 4.3e-5 of it; at small variances float32 arithmetic differs more than its codes).
        results.push(worst(
            "reprojection.variance (relative)",
            reprojection.iter().zip(&cpu.reprojection_out).map(|(g, c)| g.y / c.y.abs().max(1.0)),
            cpu.reprojection_out.iter().map(|c| c.y / c.y.abs().max(1.0)),
        ));
    }
    drop(r);
    results
}

#[test]
fn gpu_matches_the_cpu_reference() {
    let g = gpu();
    let mut precisions = vec![(Precision::Fp32, 1e-4)];
    if g.features.float16 {
        precisions.push((Precision::Fp16, 2e-3));
    }
    for (precision, tolerance) in precisions {
        let mut overall: Option<(f64, String)> = None;
        for (passes, w, h, seed) in [(2, 37, 23, 1), (3, 37, 23, 2), (4, 45, 29, 3), (1, 33, 17, 4), (3, 64, 40, 5), (3, 96, 72, 6), (4, 97, 70, 7), (2, 61, 37, 8), (4, 97, 70, 9), (2, 97, 70, 10), (3, 101, 74, 11), (3, 96, 72, 12), (3, 64, 40, 13), (2, 64, 40, 14), (2, 64, 40, 15)] {
            for r in parity(&g, precision, passes, w, h, seed) {
                let over = r.over(tolerance);
                let line = format!(
                    "{precision:?} {w}x{h} {passes} passes: {} max |gpu - cpu| = {:.2e} (pixel {}), {over} of {} over {tolerance:.0e}",
                    r.name,
                    r.err,
                    r.at,
                    r.errors.len()
                );
                eprintln!("{line}");
                let allowed = (ROUNDING_SHARE * r.errors.len() as f64).floor() as usize;
                assert!(over <= allowed && r.err <= ROUNDING_BOUND, "{line}: more than {allowed} over, or beyond {ROUNDING_BOUND:.1e}");
                if overall.as_ref().is_none_or(|o| r.err > o.0) {
                    overall = Some((r.err, line));
                }
            }
        }
        eprintln!("worst case {precision:?}: {}", overall.unwrap().1);
    }
    g.assert_clean();
}

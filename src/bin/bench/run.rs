//! One configuration (size, scene, preset, precision): the byte model's pixel classes measured through dnsr's
//! debug views, the warm-up, then the timed frames.

use super::model::PixelCounts;
use super::scenes::GpuScene;
use super::stats::median;
use dnsr::ash::vk;
use dnsr::testing::f16_to_f32;
use dnsr::testing::gpu::{Gpu, TestImage};
use dnsr::{Context, DebugView, HostSync, LightDispatch, PassTimings, Precision, Preset, Settings, ShadowsDispatch};
use std::time::Instant;

/// How the bench submits frames, as the report states it.
pub const SUBMISSION: &str = "One primary command buffer per frame, reset and re-recorded (ONE_TIME_SUBMIT), holding \
only Context::record_shadows (dnsr's barriers, constants update, passes and timestamps); vkQueueSubmit to one \
queue, then vkQueueWaitIdle before the next frame is recorded, so frames never overlap. GPU times come from dnsr's \
own timestamps (Context::timings, read after each wait): per pass, and total from before the first pass to after \
the last. With --lights N > 1 the command buffer holds one Context::record_lights call for N lights instead (light k reads the hit mask of cycle frame i + k mod N, so the lights' shadows differ; one output per light), and the times are of all N. Record CPU time is the wall time around the record call. Inputs are a cycle of precomputed \
frames resident in GPU memory (uploaded once); frame i binds cycle frame i mod N, so no upload or copy runs in the \
timed command buffers. Each configuration gets a fresh Context; its first 2N frames (untimed, history reset at frame \
0) measure the byte model's pixel classes through dnsr's debug views; then the warm-up (at least --warmup frames and \
--warmup-ms of back-to-back frames, then until the median of the last 10 frames is within 2% of the 10 before, at \
most 5x --warmup-ms), then the timed frames. The output is R16_SFLOAT, resting in SHADER_READ_ONLY_OPTIMAL; HostSync \
names compute-shader writes of the inputs and compute-shader reads of the output, as an engine's would.";

/// Records frame `index` of every light into `cmd` and times the call. One light: record_shadows, as an engine with
/// one light calls it; several: record_lights, with the dispatch's per-light fields moved into the light list.
fn record(
    ctx: &mut Context,
    cmd: vk::CommandBuffer,
    d: &ShadowsDispatch,
    scene: &GpuScene,
    index: usize,
    outputs: &[TestImage],
    guidance: Option<Guidance>,
) -> (dnsr::Result<()>, std::time::Duration) {
    let mut lights = [LightDispatch::default(); dnsr::MAX_LIGHTS_PER_RECORD];
    for (k, (l, out)) in lights.iter_mut().zip(outputs).enumerate() {
        *l = light(scene, index, k, out, guidance);
    }
    let shared = ShadowsDispatch { hit_mask: Default::default(), visibility: Default::default(), output: Default::default(),
        hit_distance: None, light_angular_size: 0.0, hard_light: false, reset: false, ..*d };
    let t0 = Instant::now();
    let r = if outputs.len() == 1 { ctx.record_shadows(cmd, d) } else { ctx.record_lights(cmd, &shared, &lights[..outputs.len()]) };
    (r, t0.elapsed())
}

/// Wall microseconds of `frames` records (each submitted and waited for, as in `measure`) of a context without
/// timestamps, after as many untimed ones as `measure`'s pixel-class pass records (a context's first records
/// compile the pipelines of the specialization its frames use); then of `frames` records back to back into the
/// same command buffer, reset and never submitted (warm: caches and clocks as on a busy render thread, where the
/// first list's records each follow an idle wait for the GPU).
fn record_only(
    gpu: &Gpu,
    ctx: &mut Context,
    scene: &GpuScene,
    outputs: &[TestImage],
    cmd: vk::CommandBuffer,
    frames: usize,
    guidance: Option<Guidance>,
) -> Result<(Vec<f64>, Vec<f64>), String> {
    let mut us = Vec::with_capacity(frames);
    let skip = 2 * scene.frames.len();
    for index in 0..skip + frames {
        let d = dispatch(scene, index, &outputs[0], guidance);
        let (r, elapsed) = gpu.submit_with(cmd, |cmd| record(ctx, cmd, &d, scene, index, outputs, guidance));
        r.map_err(|e| format!("record without timestamps: {e}"))?;
        if index >= skip {
            us.push(elapsed.as_secs_f64() * 1e6);
        }
    }
    let mut warm = Vec::with_capacity(frames);
    for index in skip + frames..skip + 2 * frames {
        let d = dispatch(scene, index, &outputs[0], guidance);
        let (r, elapsed) = gpu.record_unsubmitted(cmd, |cmd| record(ctx, cmd, &d, scene, index, outputs, guidance));
        r.map_err(|e| format!("record back to back: {e}"))?;
        warm.push(elapsed.as_secs_f64() * 1e6);
    }
    Ok((us, warm))
}

const READ: vk::ImageLayout = vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL;

pub struct ConfigRun {
    /// Timings of the timed frames (warm-up dropped).
    pub timings: Vec<PassTimings>,
    /// Wall microseconds of each timed frame's record_shadows.
    pub record_us: Vec<f64>,
    /// The same, recorded by a context without timestamps.
    pub record_us_untimed: Vec<f64>,
    /// The same context's records back to back, never submitted (`record_only`).
    pub record_us_warm: Vec<f64>,
    pub counts: PixelCounts,
    pub memory_bytes: u64,
    /// Context::persistent_memory_bytes: kept between records.
    pub persistent_bytes: u64,
    pub filter_passes: u32,
    pub warmup: WarmupDone,
    /// The driver's statistics of each of the context's pipelines as the frames ran them
    /// (`Context::pipeline_statistics`; empty where the device lacks VK_KHR_pipeline_executable_properties, and
    /// after the first row of a preset and precision).
    pub pipelines: Vec<(&'static str, Vec<(String, String)>)>,
}

/// Penumbra guidance for a run: a hit-distance image (every pixel 1.0 in R16_SFLOAT) and the light's angular size.
#[derive(Clone, Copy)]
pub struct Guidance<'a> {
    pub hit_distance: &'a TestImage,
    pub light_angular_size: f32,
}

/// The shadow input of cycle frame `index` (a hit mask, or visibility).
fn shadow_input(scene: &GpuScene, index: usize) -> (dnsr::HostImage, dnsr::HostImage) {
    let f = &scene.frames[index % scene.frames.len()];
    let img = scene.masks[f.mask].host();
    if scene.visibility_input { (Default::default(), img) } else { (img, Default::default()) }
}

/// Light k of frame `index` of a several-light run: the shadow input of cycle frame index + k.
fn light(scene: &GpuScene, index: usize, k: usize, output: &TestImage, guidance: Option<Guidance>) -> LightDispatch {
    let (hit_mask, visibility) = shadow_input(scene, index + k);
    LightDispatch {
        light_index: k as u32,
        hit_mask,
        visibility,
        output: output.host(),
        hit_distance: guidance.map(|g| g.hit_distance.host()),
        light_angular_size: guidance.map_or(0.0, |g| g.light_angular_size),
        reset: index == 0,
        hard_light: scene.hard_light,
        light_position: scene.light_position,
        ..Default::default()
    }
}

fn dispatch(scene: &GpuScene, index: usize, output: &TestImage, guidance: Option<Guidance>) -> ShadowsDispatch {
    let f = &scene.frames[index % scene.frames.len()];
    let g = &scene.gbuffers[f.gbuffer];
    // Last frame's G-buffer: the previous cycle frame's (a static scene's one G-buffer is its own previous one).
    let n = scene.frames.len();
    let previous = &scene.gbuffers[scene.frames[(index + n - 1) % n].gbuffer];
    let (previous_depth, previous_normals) =
        if scene.host_previous { (previous.depth.host(), previous.normals.host()) } else { Default::default() };
    ShadowsDispatch {
        previous_depth,
        previous_normals,
        hit_distance: guidance.map(|g| g.hit_distance.host()),
        light_angular_size: guidance.map_or(0.0, |g| g.light_angular_size),
        hit_mask: shadow_input(scene, index).0,
        visibility: shadow_input(scene, index).1,
        depth: g.depth.host(),
        velocity: g.velocity.host(),
        normals: g.normals.host(),
        normals_unpack_mul: scene.host.normals_unpack().0,
        normals_unpack_add: scene.host.normals_unpack().1,
        output: output.host(),
        eye: f.eye,
        projection_inverse: f.projection_inverse,
        reprojection_matrix: f.reprojection,
        view_projection_inverse: f.view_projection_inverse,
        sync: HostSync {
            input_src_stages: vk::PipelineStageFlags::COMPUTE_SHADER,
            input_src_access: vk::AccessFlags::SHADER_WRITE,
            output_dst_stages: vk::PipelineStageFlags::COMPUTE_SHADER,
            output_dst_access: vk::AccessFlags::SHADER_READ,
        },
        reset: index == 0,
        checkerboard_phase: if scene.checkerboard { index as u32 % 2 } else { 0 },
        hard_light: scene.hard_light,
        light_position: scene.light_position,
        ..Default::default()
    }
}

#[allow(clippy::too_many_arguments)]
pub fn run(
    gpu: &Gpu,
    scene: &GpuScene,
    (w, h): (u32, u32),
    preset: Preset,
    precision: Precision,
    warmup: Warmup,
    frames: usize,
    light_angle: Option<f32>,
    lights: usize,
    pipeline_statistics: bool,
) -> Result<ConfigRun, String> {
    let mut info = gpu.create_info(w, h);
    info.enable_timestamps = true;
    info.precision = precision;
    info.output_format = vk::Format::R16_SFLOAT;
    info.settings = Settings::preset(preset);
    if scene.visibility_input {
        info.shadow_input = dnsr::ShadowInput::Visibility;
    }
    if scene.checkerboard {
        info.shadow_input = dnsr::ShadowInput::Checkerboard;
    }
    info.light_count = lights as u32;
    info.transient_memory_per_light = scene.transient_per_light;
    info.lights_recorded_together = scene.lights_together;
    info.host_previous_gbuffer = scene.host_previous;
    info.shader_overrides = scene.shader_overrides.clone();
    if scene.alias_transient {
        info.alias_transient_memory = true;
        // One allocation per image: an engine would alias the transient ones; the bench measures what aliasing
        // costs dnsr (a layout transition per transient image and record).
        info.hooks.gpu_memory = Some(std::sync::Arc::new(dnsr::testing::gpu::HostAllocator::new(gpu)));
    }
    let mut ctx = Context::new(&info).map_err(|e| format!("Context::new: {e}"))?;
    // Each pipeline compiled again with statistics captured: once per preset and precision is enough.
    let pipelines = if pipeline_statistics && gpu.pipeline_statistics {
        ctx.pipeline_statistics(light_angle.is_some(), &scene.shader_overrides).map_err(|e| format!("Context::pipeline_statistics: {e}"))?
    } else {
        Vec::new()
    };
    let outputs: Vec<TestImage> = (0..lights).map(|_| gpu.image(vk::Format::R16_SFLOAT, w, h, READ)).collect();
    let cmd = gpu.command_buffer();
    let hit_distance = light_angle.map(|_| {
        let img = gpu.image(vk::Format::R16_SFLOAT, w, h, READ);
        gpu.upload(&img, &0x3C00u16.to_le_bytes().repeat((w * h) as usize));
        img
    });
    let guidance = hit_distance.as_ref().map(|img| Guidance { hit_distance: img, light_angular_size: light_angle.unwrap_or(0.0) });
    let result = measure(gpu, &mut ctx, scene, &outputs, cmd, warmup, frames, guidance);
    // The record's CPU time without timestamps, as an engine ships: a second context, the same frames.
    let untimed = result.is_ok().then(|| {
        info.enable_timestamps = false;
        let mut quiet = Context::new(&info).map_err(|e| format!("Context::new without timestamps: {e}"))?;
        record_only(gpu, &mut quiet, scene, &outputs, cmd, frames, guidance)
    });
    unsafe { gpu.device.device_wait_idle().ok() };
    gpu.free_command_buffer(cmd);
    if let Some(img) = &hit_distance {
        gpu.destroy_image(img);
    }
    let memory_bytes = ctx.memory_bytes();
    // A light of no size runs one filter pass (the later ones record no dispatch).
    let filter_passes = if scene.hard_light { 1 } else { Settings::preset(preset).filter_passes };
    let persistent_bytes = ctx.persistent_memory_bytes();
    drop(ctx);
    outputs.iter().for_each(|o| gpu.destroy_image(o));
    let (timings, record_us, counts, warmup) = result?;
    let (record_us_untimed, record_us_warm) = untimed.transpose()?.unwrap_or_default();
    Ok(ConfigRun { timings, record_us, record_us_untimed, record_us_warm, counts, memory_bytes, persistent_bytes, filter_passes, warmup, pipelines })
}

/// How long to warm up before the timed frames.
#[derive(Clone, Copy)]
pub struct Warmup {
    /// At least this many frames.
    pub frames: usize,
    /// At least this much wall time of back-to-back frames (GPU clocks ramp up from idle over hundreds of ms);
    /// past it, until the median GPU total of the last 10 frames is within 2% of the 10 before, for at most five
    /// times this long. 0: exactly `frames` frames.
    pub min_ms: f64,
}

/// What the warm-up took.
#[derive(Clone, Copy, Default)]
pub struct WarmupDone {
    pub frames: usize,
    pub ms: f64,
    /// The stability test passed (false: the time cap or min_ms = 0 ended it).
    pub stable: bool,
}

type Measured = (Vec<PassTimings>, Vec<f64>, PixelCounts, WarmupDone);

fn measure(
    gpu: &Gpu,
    ctx: &mut Context,
    scene: &GpuScene,
    outputs: &[TestImage],
    cmd: vk::CommandBuffer,
    warmup: Warmup,
    frames: usize,
    guidance: Option<Guidance>,
) -> Result<Measured, String> {
    let mut recorded = 0u64;
    let mut frame = |ctx: &mut Context, d: &ShadowsDispatch, index: usize| -> Result<(PassTimings, f64), String> {
        let elapsed = gpu.submit_with(cmd, |cmd| record(ctx, cmd, d, scene, index, outputs, guidance));
        elapsed.0.map_err(|e| format!("record: {e}"))?;
        recorded += 1;
        let t = ctx.timings().map_err(|e| format!("timings: {e}"))?.ok_or("no timings after the frame completed")?;
        if t.frame != recorded {
            return Err(format!("timings are of frame {} instead of {recorded}", t.frame));
        }
        Ok((t, elapsed.1.as_secs_f64() * 1e6))
    };

    // Pixel classes first (they need read-backs, which leave the GPU idle): one cycle of the sequence with the
    // tile-classification view, one with the disocclusion view. Frame 0 resets the history.
    // The pixel classes are light 0's.
    let output = &outputs[0];
    let (w, h) = (output.width as usize, output.height as usize);
    let n = scene.frames.len();
    let mut counts = PixelCounts::default();
    let mut index = 0;
    for view in [DebugView::TileClassification, DebugView::Disocclusion] {
        for _ in 0..n {
            let d = ShadowsDispatch { debug_view: view, ..dispatch(scene, index, output, guidance) };
            frame(ctx, &d, index)?;
            index += 1;
            let raw = gpu.download(output);
            let px: Vec<f32> = raw.chunks_exact(2).map(|c| f16_to_f32(u16::from_le_bytes([c[0], c[1]]))).collect();
            if view == DebugView::Disocclusion {
                counts.history -= px.iter().filter(|&&v| v == 1.0).count() as f64;
                continue;
            }
            // 0.75 sky, 0.5 receiver in a tile not cleared, 0 / 1 receiver in a cleared tile.
            counts.receivers += px.iter().filter(|&&v| v != 0.75).count() as f64;
            let active = px.iter().filter(|&&v| v == 0.5).count() as f64;
            counts.active += active;
            counts.history += active;
            for gy in (0..h).step_by(8) {
                for gx in (0..w).step_by(8) {
                    let (gw, gh) = (8.min(w - gx), 8.min(h - gy));
                    let rows = || (gy..gy + gh).map(|y| &px[y * w + gx..y * w + gx + gw]);
                    if rows().any(|r| r.contains(&0.5)) {
                        counts.active_groups += (gw * gh) as f64;
                        counts.active_group_receivers += rows().flatten().filter(|&&v| v != 0.75).count() as f64;
                    }
                }
            }
        }
    }
    let scale = 1.0 / n as f64;
    counts.receivers *= scale;
    counts.active *= scale;
    counts.history = (counts.history * scale).max(0.0);
    counts.active_groups *= scale;
    counts.active_group_receivers *= scale;
    counts.all = (w * h) as f64;
    counts.tiles = (w.div_ceil(8) * h.div_ceil(4)) as f64;

    // Warm-up, continuing the sequence.
    let started = Instant::now();
    let mut totals = Vec::new();
    let mut done = WarmupDone::default();
    loop {
        let ms = started.elapsed().as_secs_f64() * 1e3;
        let enough_frames = totals.len() >= warmup.frames;
        if enough_frames && warmup.min_ms <= 0.0 {
            break;
        }
        if enough_frames && ms >= warmup.min_ms && totals.len() >= 20 {
            let k = totals.len();
            let (last, before) = (median(&totals[k - 10..]), median(&totals[k - 20..k - 10]));
            if (last - before).abs() <= 0.02 * before {
                done.stable = true;
                break;
            }
        }
        if enough_frames && ms >= 5.0 * warmup.min_ms {
            break;
        }
        let (t, _) = frame(ctx, &dispatch(scene, index, output, guidance), index)?;
        index += 1;
        totals.push(t.total_ms);
    }
    done.frames = totals.len();
    done.ms = started.elapsed().as_secs_f64() * 1e3;

    let (mut timings, mut record_us) = (Vec::with_capacity(frames), Vec::with_capacity(frames));
    for _ in 0..frames {
        let (t, us) = frame(ctx, &dispatch(scene, index, output, guidance), index)?;
        index += 1;
        timings.push(t);
        record_us.push(us);
    }
    Ok((timings, record_us, counts, done))
}


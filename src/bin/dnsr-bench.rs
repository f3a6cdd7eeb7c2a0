//! The benchmark to quote: GPU time of every dnsr pass (median and p95 from GPU timestamps), against the
//! device's copy bandwidth and a per-pass byte model, plus the CPU time to record a frame and dnsr's memory per
//! pixel, over sizes x scenes x presets x precisions. Writes bench.json and bench.md (see BENCHMARKS.md).
//!
//! `cargo run --release --features demo --bin dnsr-bench -- [options]`; `--help` lists them.

mod bench;

use bench::device::{command_line, commit, utc, DeviceInfo};
use bench::report::{precision_name, preset_name, Report, Summary};
use bench::run::Warmup;
use bench::scenes::{build, HostFormats, SceneId, ALL_SCENES};
use dnsr::testing::gpu::{Gpu, GpuOptions};
use bench::model::Fed;
use dnsr::{Precision, Preset, ShadowInput};
use std::path::PathBuf;
use std::time::Instant;

const USAGE: &str = "usage: dnsr-bench [options]

  --sizes WxH[,WxH...]        render sizes (default 1920x1080,2560x1440,3840x2160)
  --scenes a[,b...]           penumbra-heavy, typical, all-lit, sky-90 (default: all)
  --presets a[,b...]          fast, balanced, quality (default: all)
  --precisions a[,b...]       fp32, fp16 (default: both; fp16 is skipped when the device lacks it)
  --fp16                      same as --precisions fp16
  --rays K                    the shadow input is per-pixel visibility (ShadowInput::Visibility, R8_UNORM) of K
                              rays per pixel instead of the hit mask (the byte model follows)
  --checkerboard              the shadow input is a checkerboard (ShadowInput::Checkerboard): half of each
                              frame's hit mask is read, the phase alternating
  --light-angle RAD           penumbra guidance on: a hit-distance image (1.0 everywhere, R16_SFLOAT) and this
                              light angular size in radians (default: no guidance)
  --lights N[,N...]           lights denoised per frame (default 1): N > 1 records them in one
                              Context::record_lights call, each light with its own hit mask and output (N <= 8)
  --frames N                  timed frames per configuration (default 200)
  --warmup N                  at least this many warm-up frames before timing (default 20)
  --warmup-ms T               and at least T ms of back-to-back warm-up frames, then until the GPU time is stable
                              (median of the last 10 frames within 2% of the 10 before; at most 5 T); 0: exactly N
                              frames (default 1000)
  --copy-mib N                size of each buffer of the copy-bandwidth kernel in MiB (default 256)
  --copy-runs N               timed runs of the copy kernel, median reported (default 10)
  --out DIR                   where bench.json and bench.md go (default out/bench)
  --validation                enable the Vulkan validation layer; any message fails the run (exit 1)
  --no-push-descriptors       dnsr's descriptor-set path even where VK_KHR_push_descriptor is enabled (what the
                              FidelityFX layer records: it cannot know whether the engine enabled the extension)
  --float-gbuffer             feed R32_SFLOAT depth, R32G32B32A32_SFLOAT normals and R32G32_SFLOAT velocity instead
                              of what engines render (default: D32_SFLOAT depth, A2B10G10R10_UNORM_PACK32 normals,
                              R16G16_SFLOAT velocity)
  --alias-transient           the contexts let the host alias their transient memory (ContextCreateInfo::
                              alias_transient_memory, with a host allocator): every record moves the transient
                              images out of UNDEFINED
  --transient-per-light       each light keeps its own transient images (ContextCreateInfo::
                              transient_memory_per_light): several lights record pass by pass, the later filter
                              passes four lights per dispatch (default: the lights share one set, each light's
                              passes in a row)
  --lights-together           every record holds every light (ContextCreateInfo::lights_recorded_together): the
                              lights share one depth copy
  --host-previous             the host gives last frame's depth and normals (ContextCreateInfo::
                              host_previous_gbuffer): dnsr keeps no depth copy
  --hard-light                every light has no size (ShadowsDispatch::hard_light): the output is each pixel's
                              ray, and one filter pass runs (not with a non-zero --light-angle)
  --light-position X,Y,Z,W   give the light (ShadowsDispatch::light_position: a direction towards it with W 0,
                              a point with W 1): receivers turned away from it keep their shadowed samples
  --shader-override V=FILE    run the SPIR-V in FILE for shader variant V (ContextCreateInfo::shader_overrides;
                              repeatable): a shader change or an engine's callbacks timed by the same binary as
                              dnsr's own (the variants: dnsr::shader_variants; fp32 contexts with the bench's R16F
                              output run e.g. tile_classification_r16f). One light per record (overrides run a
                              dispatch per light)

The device is the first whose name contains $DNSR_DEVICE (any device when unset). The commit recorded is
$DNSR_COMMIT, else `git rev-parse HEAD` of the working directory.";

fn usage(msg: &str) -> ! {
    if !msg.is_empty() {
        eprintln!("dnsr-bench: {msg}\n");
    }
    eprintln!("{USAGE}");
    std::process::exit(2);
}

fn list<T>(value: Option<String>, flag: &str, parse: impl Fn(&str) -> Option<T>) -> Vec<T> {
    let value = value.unwrap_or_else(|| usage(&format!("{flag} needs a value")));
    let items: Vec<T> = value
        .split(',')
        .map(|s| parse(s.trim()).unwrap_or_else(|| usage(&format!("{flag}: cannot use {s:?}"))))
        .collect();
    if items.is_empty() {
        usage(&format!("{flag}: empty list"));
    }
    items
}

fn number(value: Option<String>, flag: &str, min: usize) -> usize {
    value
        .and_then(|v| v.parse().ok())
        .filter(|&n| n >= min)
        .unwrap_or_else(|| usage(&format!("{flag} needs a whole number >= {min}")))
}

fn parse_size(s: &str) -> Option<(u32, u32)> {
    let (w, h) = s.split_once('x')?;
    Some((w.parse().ok().filter(|&w| w > 0)?, h.parse().ok().filter(|&h| h > 0)?))
}

fn parse_preset(s: &str) -> Option<Preset> {
    [Preset::Fast, Preset::Balanced, Preset::Quality].into_iter().find(|&p| preset_name(p) == s)
}

fn parse_precision(s: &str) -> Option<Precision> {
    [Precision::Fp32, Precision::Fp16].into_iter().find(|&p| precision_name(p) == s)
}

struct Options {
    sizes: Vec<(u32, u32)>,
    scenes: Vec<SceneId>,
    presets: Vec<Preset>,
    precisions: Vec<Precision>,
    frames: usize,
    warmup: usize,
    warmup_ms: usize,
    copy_mib: usize,
    copy_runs: usize,
    out: PathBuf,
    validation: bool,
    light_angle: Option<f32>,
    rays: Option<u32>,
    lights: Vec<usize>,
    checkerboard: bool,
    push_descriptors: bool,
    host: HostFormats,
    alias_transient: bool,
    transient_per_light: bool,
    lights_together: bool,
    host_previous: bool,
    hard_light: bool,
    light_position: Option<glam::Vec4>,
    shader_overrides: Vec<dnsr::ShaderOverride>,
}

impl Options {
    /// What every configuration is fed, for the byte model.
    fn fed(&self) -> Fed {
        let input = match (self.rays, self.checkerboard) {
            (Some(_), _) => ShadowInput::Visibility,
            (None, true) => ShadowInput::Checkerboard,
            (None, false) => ShadowInput::HitMask,
        };
        Fed { host: self.host, input, surface_window: false, host_previous: self.host_previous }
    }
}

fn parse_args() -> Options {
    let mut o = Options {
        sizes: vec![(1920, 1080), (2560, 1440), (3840, 2160)],
        scenes: ALL_SCENES.to_vec(),
        presets: vec![Preset::Fast, Preset::Balanced, Preset::Quality],
        precisions: vec![Precision::Fp32, Precision::Fp16],
        frames: 200,
        warmup: 20,
        warmup_ms: 1000,
        copy_mib: 256,
        copy_runs: 10,
        out: PathBuf::from("out/bench"),
        validation: false,
        light_angle: None,
        rays: None,
        lights: vec![1],
        checkerboard: false,
        push_descriptors: true,
        host: HostFormats::Engine,
        alias_transient: false,
        transient_per_light: false,
        lights_together: false,
        host_previous: false,
        hard_light: false,
        light_position: None,
        shader_overrides: Vec::new(),
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--sizes" => o.sizes = list(args.next(), "--sizes", parse_size),
            "--scenes" => o.scenes = list(args.next(), "--scenes", SceneId::parse),
            "--presets" => o.presets = list(args.next(), "--presets", parse_preset),
            "--precisions" => o.precisions = list(args.next(), "--precisions", parse_precision),
            "--fp16" => o.precisions = vec![Precision::Fp16],
            "--frames" => o.frames = number(args.next(), "--frames", 1),
            "--warmup" => o.warmup = number(args.next(), "--warmup", 0),
            "--warmup-ms" => o.warmup_ms = number(args.next(), "--warmup-ms", 0),
            "--copy-mib" => o.copy_mib = number(args.next(), "--copy-mib", 1),
            "--copy-runs" => o.copy_runs = number(args.next(), "--copy-runs", 1),
            "--out" => o.out = PathBuf::from(args.next().unwrap_or_else(|| usage("--out needs a directory"))),
            "--validation" => o.validation = true,
            "--checkerboard" => o.checkerboard = true,
            "--no-push-descriptors" => o.push_descriptors = false,
            "--float-gbuffer" => o.host = HostFormats::Float,
            "--alias-transient" => o.alias_transient = true,
            "--transient-per-light" => o.transient_per_light = true,
            "--lights-together" => o.lights_together = true,
            "--host-previous" => o.host_previous = true,
            "--hard-light" => o.hard_light = true,
            "--light-position" => {
                let v: Vec<f32> = args.next().map_or(Vec::new(), |v| v.split(',').filter_map(|c| c.parse().ok()).collect());
                if v.len() != 4 || !v.iter().all(|c| c.is_finite()) {
                    usage("--light-position needs X,Y,Z,W (four finite numbers)");
                }
                o.light_position = Some(glam::Vec4::from_slice(&v));
            }
            "--shader-override" => {
                let value = args.next().unwrap_or_else(|| usage("--shader-override needs VARIANT=FILE"));
                let (variant, file) = value.split_once('=').unwrap_or_else(|| usage("--shader-override needs VARIANT=FILE"));
                let spirv = std::fs::read(file).unwrap_or_else(|e| usage(&format!("--shader-override: cannot read {file}: {e}")));
                o.shader_overrides.push(dnsr::ShaderOverride { variant: variant.to_string(), spirv });
            }
            "--lights" => {
                let max = dnsr::MAX_LIGHTS_PER_RECORD;
                o.lights = list(args.next(), "--lights", |s| s.parse().ok().filter(|n| (1..=max).contains(n)));
            }
            "--rays" => o.rays = Some(number(args.next(), "--rays", 1) as u32),
            "--light-angle" => {
                let v = args.next().and_then(|v| v.parse::<f32>().ok());
                o.light_angle = Some(v.unwrap_or_else(|| usage("--light-angle needs an angle in radians")));
            }
            "-h" | "--help" => {
                println!("{USAGE}");
                std::process::exit(0);
            }
            other => usage(&format!("unknown argument {other:?}")),
        }
    }
    if o.hard_light && o.light_angle.is_some_and(|a| a != 0.0) {
        usage("--hard-light is a light of no size: it does not go with a non-zero --light-angle");
    }
    if o.checkerboard && o.rays.is_some() {
        usage("--checkerboard reads the hit mask: it does not go with --rays");
    }
    o
}

fn fail(msg: String) -> ! {
    eprintln!("dnsr-bench: {msg}");
    std::process::exit(1);
}

fn main() {
    let opts = parse_args();
    let started = Instant::now();
    let date = utc(std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs()));
    let mut gpu = Gpu::new(GpuOptions { validation: opts.validation, pipeline_statistics: true, ..Default::default() });
    if !opts.push_descriptors {
        gpu.features.push_descriptor = false;
    }
    let device = DeviceInfo::query(&gpu);
    eprintln!("dnsr-bench: {} (Vulkan {}, driver {})", device.name, device.api_version, device.driver());

    let mut skipped = Vec::new();
    let mut precisions = opts.precisions.clone();
    if !gpu.features.float16 && precisions.contains(&Precision::Fp16) {
        precisions.retain(|&p| p != Precision::Fp16);
        skipped.push("fp16: the device lacks shaderFloat16 + storageBuffer16BitAccess".to_string());
        eprintln!("dnsr-bench: skipping fp16 (the device lacks shaderFloat16 + storageBuffer16BitAccess)");
    }

    let copy = bench::copy::measure(&gpu, (opts.copy_mib as u64) << 20, opts.copy_runs).unwrap_or_else(|e| fail(format!("copy kernel: {e}")));
    eprintln!("dnsr-bench: copy bandwidth {:.1} GB/s (read + write, median of {})", copy.gbps(copy.median_ms()), copy.runs_ms.len());

    let mut results = Vec::new();
    let mut with_statistics = Vec::new();
    for &size in &opts.sizes {
        for &scene in &opts.scenes {
            let t = Instant::now();
            let mut gpu_scene = build(&gpu, scene, size.0, size.1, opts.rays, opts.host);
            gpu_scene.checkerboard = opts.checkerboard;
            gpu_scene.alias_transient = opts.alias_transient;
            gpu_scene.transient_per_light = opts.transient_per_light;
            gpu_scene.lights_together = opts.lights_together;
            gpu_scene.host_previous = opts.host_previous;
            gpu_scene.hard_light = opts.hard_light;
            gpu_scene.light_position = opts.light_position;
            gpu_scene.shader_overrides = opts.shader_overrides.clone();
            eprintln!("dnsr-bench: {}x{} {}: {} frames generated in {:.1} s", size.0, size.1, scene.id(), gpu_scene.frames.len(), t.elapsed().as_secs_f64());
            for &precision in &precisions {
                for (&preset, &lights) in opts.presets.iter().flat_map(|p| opts.lights.iter().map(move |l| (p, l))) {
                    let warmup = Warmup { frames: opts.warmup, min_ms: opts.warmup_ms as f64 };
                    let statistics = !with_statistics.contains(&(preset, precision, lights));
                    with_statistics.push((preset, precision, lights));
                    let run = bench::run::run(&gpu, &gpu_scene, size, preset, precision, warmup, opts.frames, opts.light_angle, lights, statistics)
                        .unwrap_or_else(|e| {
                            fail(format!("{}x{} {} {} {} {lights} light(s): {e}", size.0, size.1, scene.id(), preset_name(preset), precision_name(precision)))
                        });
                    let s = Summary::new(size, scene, preset, precision, run, gpu_scene.coverage, lights, opts.fed());
                    eprintln!(
                        "dnsr-bench: {}x{} {} {} {} {lights} light(s): total {:.3} ms median, {:.3} ms p95 (warm-up {} frames, {:.0} ms{})",
                        size.0,
                        size.1,
                        scene.id(),
                        preset_name(preset),
                        precision_name(precision),
                        s.total.median_ms,
                        s.total.p95_ms,
                        s.warmup.frames,
                        s.warmup.ms,
                        if s.warmup.stable || opts.warmup_ms == 0 { "" } else { ", not stable" }
                    );
                    results.push(s);
                }
            }
            gpu_scene.destroy(&gpu);
        }
    }

    let report = Report {
        device: &device,
        commit: commit(),
        command_line: command_line(),
        date,
        warmup: opts.warmup,
        warmup_ms: opts.warmup_ms,
        frames: opts.frames,
        copy: &copy,
        results: &results,
        skipped: &skipped,
        wall_s: started.elapsed().as_secs_f64(),
        host: opts.host,
        input: opts.fed().input,
    };
    let md = report.markdown();
    std::fs::create_dir_all(&opts.out).unwrap_or_else(|e| fail(format!("cannot create {}: {e}", opts.out.display())));
    for (name, text) in [("bench.json", report.json().to_pretty()), ("bench.md", md.clone())] {
        let path = opts.out.join(name);
        std::fs::write(&path, text).unwrap_or_else(|e| fail(format!("cannot write {}: {e}", path.display())));
    }
    println!("{md}");
    eprintln!("dnsr-bench: wrote {} and {}", opts.out.join("bench.json").display(), opts.out.join("bench.md").display());
    if opts.validation {
        let messages = gpu.take_messages();
        if !messages.is_empty() {
            fail(format!("{} validation message(s):\n{}", messages.len(), messages.join("\n")));
        }
    }
}

//! dnsr-demo: denoises a built-in synthetic shadow sequence and writes what it saw.
//!
//! A camera looks straight down at a ground plane and pans slowly sideways. On the plane lies a known soft
//! shadow (the "truth"): penumbrae of several widths, a hard contact edge, thin lines and a moving disc. Each
//! frame the demo draws a fresh 1-sample-per-pixel shadow mask from that truth (what one jittered shadow ray
//! per pixel would give), hands it to dnsr, and compares dnsr's output with the truth.
//!
//! It runs on whatever Vulkan device exists (lavapipe on a machine without a GPU); `DNSR_DEVICE=<substring>`
//! picks a device by name.
//!
//! Output in `--out` (default `out/demo`): `noisy.png`, `denoised.png`, `truth.png` (last frame), `strip.png`
//! (the three side by side) and `report.md` (also printed).

use dnsr::ash::vk;
use dnsr::testing::gpu::{Gpu, GpuOptions};
use dnsr::testing::scene::{self, Camera, FrameInputs};
use dnsr::testing::fields::{band, smoothstep, soft_box};
use dnsr::testing::images::{mask_to_image, rmse, side_by_side, write_png};
use dnsr::testing::Runner;
use dnsr::{PassTimings, ShadowsDispatch};
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

const USAGE: &str = "\
usage: dnsr-demo [--frames N] [--size WxH] [--out DIR] [--validate]

  --frames N    frames to denoise (default 48)
  --size WxH    render size in pixels (default 320x192)
  --out DIR     where to write the PNGs and report.md (default out/demo)
  --validate    enable the Vulkan validation layer (with synchronization validation);
                exit with status 1 if it reports anything

  DNSR_DEVICE=<substring> picks the Vulkan device by name (e.g. llvmpipe, NVIDIA).";

/// Command-line options.
struct Args {
    frames: u32,
    width: u32,
    height: u32,
    out: PathBuf,
    validate: bool,
}

impl Args {
    /// Parses the arguments: `Ok(None)` for --help, `Err` with the message to print above the usage text.
    fn parse(mut args: impl Iterator<Item = String>) -> Result<Option<Args>, String> {
        let mut parsed = Args { frames: 48, width: 320, height: 192, out: PathBuf::from("out/demo"), validate: false };
        while let Some(arg) = args.next() {
            let mut value = || args.next().ok_or(format!("{arg} needs a value"));
            match arg.as_str() {
                "--frames" => {
                    let v = value()?;
                    parsed.frames = v.parse().ok().filter(|&n| n > 0).ok_or(format!("bad frame count '{v}'"))?;
                }
                "--size" => {
                    let v = value()?;
                    let (w, h) = parse_size(&v).ok_or(format!("bad size '{v}' (expected WxH, e.g. 320x192)"))?;
                    (parsed.width, parsed.height) = (w, h);
                }
                "--out" => parsed.out = PathBuf::from(value()?),
                "--validate" => parsed.validate = true,
                "-h" | "--help" => return Ok(None),
                other => return Err(format!("unknown argument '{other}'")),
            }
        }
        Ok(Some(parsed))
    }
}

fn parse_size(s: &str) -> Option<(u32, u32)> {
    let (w, h) = s.split_once(['x', 'X'])?;
    let (w, h) = (w.parse().ok()?, h.parse().ok()?);
    (w > 0 && h > 0 && w <= 16384 && h <= 16384).then_some((w, h))
}

fn main() -> ExitCode {
    let args = match Args::parse(std::env::args().skip(1)) {
        Ok(Some(args)) => args,
        Ok(None) => {
            println!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        Err(message) => {
            eprintln!("dnsr-demo: {message}\n\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match run(&args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("dnsr-demo: {e}");
            ExitCode::FAILURE
        }
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The scene
// ---------------------------------------------------------------------------------------------------------------

/// Camera height above the plane, in world units.
const CAMERA_HEIGHT: f64 = 10.0;
/// Camera pan per frame, in world units (about 0.4 px at the default size): the receiver that comes into view
/// each frame at the right edge, and where the plane's edge uncovers it at the left, has no history.
const PAN_PER_FRAME: f64 = 0.02;
/// The plane covers |x| < this; beyond it is sky (no receiver: depth 1).
const PLANE_HALF_WIDTH: f64 = 8.0;
/// Fraction of the view that is sky (left of the plane's edge) in the first frame.
const SKY_FRACTION: f64 = 0.12;

/// The synthetic sequence: where the camera is each frame and what the true visibility is.
struct Scene {
    width: u32,
    height: u32,
    /// Camera x in the first frame.
    start_x: f64,
    /// World units per pixel on the plane (for features meant to be about one pixel wide).
    pixel: f64,
}

impl Scene {
    fn new(width: u32, height: u32) -> Scene {
        let cam = Camera::above(0.0, 0.0, CAMERA_HEIGHT); // for its field of view
        let half_height = CAMERA_HEIGHT * (cam.fov_y * 0.5).tan();
        let half_width = half_height * width as f64 / height as f64;
        // Put the plane's left edge SKY_FRACTION of the view in from the view's left border.
        let start_x = -PLANE_HALF_WIDTH + (1.0 - 2.0 * SKY_FRACTION) * half_width;
        Scene { width, height, start_x, pixel: 2.0 * half_height / height as f64 }
    }

    fn camera(&self, frame: u32) -> Camera {
        Camera::above(self.start_x + PAN_PER_FRAME * frame as f64, 0.0, CAMERA_HEIGHT)
    }

    /// True fraction of the light visible at world (x, z) on the plane in `frame`. Independent occluders
    /// multiply. At the default size the view spans about x in [-10, 6] (x = -8 is the plane's edge) and
    /// z in [-4.8, 4.8].
    fn visibility(&self, frame: u32, x: f64, z: f64) -> f64 {
        let mut v = 1.0;
        // Lower row of the image (z < 0): three soft boxes with penumbrae 0.2, 1 and 3 units wide.
        v *= 1.0 - soft_box(x, z, [-7.6, -5.8], [-4.0, -0.8], 0.2);
        v *= 1.0 - soft_box(x, z, [-4.8, -2.2], [-4.0, -0.8], 1.0);
        v *= 1.0 - soft_box(x, z, [0.0, 4.6], [-4.0, -0.8], 3.0);
        // Upper row, left: a contact shadow. Its left edge, where the occluder touches the plane, is hard; its
        // sides soften with distance from the contact line.
        if (-7.5..=-4.0).contains(&x) {
            let width = 0.05 + 0.4 * (x + 7.5);
            v *= 1.0 - band(z, [0.8, 4.0], width);
        }
        // Upper row, middle: thin lines, 1, 1.5 and 2 pixels wide, and a 1-pixel diagonal.
        for (i, px) in [1.0, 1.5, 2.0].into_iter().enumerate() {
            let center = -3.0 + 0.6 * i as f64;
            if (z > 0.8 && z < 4.0) && (x - center).abs() < 0.5 * px * self.pixel {
                v = 0.0;
            }
        }
        let distance_to_diagonal = (x - (-1.2 + 0.5 * (z - 0.8))).abs() / 1.25f64.sqrt();
        if z > 0.8 && z < 4.0 && distance_to_diagonal < 0.5 * self.pixel {
            v = 0.0;
        }
        // Upper row, right: the shadow of a disc swinging left and right (up to ~1.6 px per frame at the default
        // size). Its motion is not in the velocity buffer, which only describes the camera's motion.
        let phase = std::f64::consts::TAU * frame as f64 / 96.0;
        let (cx, cz) = (2.8 + 1.2 * phase.sin(), 2.4);
        let r = ((x - cx).powi(2) + (z - cz).powi(2)).sqrt();
        v *= smoothstep(1.0 - 0.3, 1.0 + 0.3, r);
        v
    }

    fn render(&self, frame: u32) -> FrameInputs {
        let cam = self.camera(frame);
        let prev = self.camera(frame.saturating_sub(1));
        // A fresh 1-spp mask every frame.
        let seed = frame as u64 * 0xD1B5_4A32_D192_ED03;
        let visibility = |x: f64, z: f64| self.visibility(frame, x, z);
        scene::render(self.width, self.height, &cam, &prev, PLANE_HALF_WIDTH, &visibility, seed)
    }
}

// ---------------------------------------------------------------------------------------------------------------
// The run
// ---------------------------------------------------------------------------------------------------------------

type AnyError = Box<dyn std::error::Error>;

/// Frames (counted from 1) whose error goes into the report.
const REPORTED_FRAMES: [u32; 4] = [1, 8, 16, 32];

fn run(args: &Args) -> Result<ExitCode, AnyError> {
    let (w, h) = (args.width, args.height);
    std::fs::create_dir_all(&args.out).map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let gpu = Gpu::new(GpuOptions { validation: args.validate, ..Default::default() });

    // The engine's side: a create info for its device, and the host images the runner owns.
    let mut info = gpu.create_info(w, h);
    info.enable_timestamps = true;
    info.output_format = vk::Format::R32_SFLOAT;
    let mut runner = Runner::new(&gpu, &info)?;

    let scene = Scene::new(w, h);
    let mut errors = Vec::new(); // (frame, noisy rmse, denoised rmse)
    let mut last = None;
    for frame in 0..args.frames {
        let inputs = scene.render(frame);
        // Upload the inputs, record dnsr into a command buffer, submit, wait, read the output back.
        let dispatch = ShadowsDispatch { reset: frame == 0, frame_index: frame, ..runner.dispatch(&inputs) };
        let denoised = runner.run(&inputs, &dispatch)?;

        let noisy = mask_to_image(&inputs);
        let number = frame + 1;
        if REPORTED_FRAMES.contains(&number) || number == args.frames {
            let truth = &inputs.truth;
            errors.push((number, rmse(&noisy, truth, &inputs.receiver), rmse(&denoised, truth, &inputs.receiver)));
        }
        if number == args.frames {
            last = Some((inputs, noisy, denoised));
        }
    }
    let (inputs, noisy, denoised) = last.expect("at least one frame");

    // The runner waited for the GPU, so the last frame's timestamps are available.
    let timings = runner.ctx.timings()?;
    let memory = runner.ctx.memory_bytes();

    write_png(&args.out.join("noisy.png"), w, h, &noisy)?;
    write_png(&args.out.join("denoised.png"), w, h, &denoised)?;
    write_png(&args.out.join("truth.png"), w, h, &inputs.truth)?;
    let (sw, strip) = side_by_side(w, h, &[&noisy, &denoised, &inputs.truth]);
    write_png(&args.out.join("strip.png"), sw, h, &strip)?;

    let report = report(args, &gpu.device_name, memory, &errors, timings.as_ref());
    std::fs::write(args.out.join("report.md"), &report).map_err(|e| format!("cannot write report.md: {e}"))?;
    print!("{report}");
    println!("\nwrote {}/{{noisy,denoised,truth,strip}}.png and report.md", args.out.display());

    drop(runner); // destroys the context: validation may report on destruction too
    if args.validate {
        let messages = gpu.take_messages();
        if !messages.is_empty() {
            eprintln!("\n{} validation message(s):", messages.len());
            for m in &messages {
                eprintln!("  {m}");
            }
            return Ok(ExitCode::FAILURE);
        }
        println!("validation: no messages");
    }
    Ok(ExitCode::SUCCESS)
}

fn report(args: &Args, device: &str, memory: u64, errors: &[(u32, f64, f64)], timings: Option<&PassTimings>) -> String {
    let (w, h) = (args.width, args.height);
    let mut r = String::new();
    let _ = writeln!(r, "# dnsr demo\n");
    let _ = writeln!(r, "- device: {device}");
    let _ = writeln!(r, "- size: {w}x{h}, {} frames, camera panning {PAN_PER_FRAME} units/frame", args.frames);
    let _ = writeln!(
        r,
        "- dnsr GPU memory: {memory} bytes ({:.1} MiB, {:.1} B/px)",
        memory as f64 / (1024.0 * 1024.0),
        memory as f64 / (w as f64 * h as f64)
    );

    let _ = writeln!(r, "\n## Error against truth (RMSE over receiver pixels, frames counted from 1)\n");
    let _ = writeln!(r, "| frame | noisy 1-spp | denoised |");
    let _ = writeln!(r, "|---:|---:|---:|");
    for &(frame, noisy, denoised) in errors {
        let _ = writeln!(r, "| {frame} | {} | {} |", fmt_rmse(noisy), fmt_rmse(denoised));
    }

    let _ = writeln!(r, "\n## GPU time of the last frame\n");
    let ms = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.3} ms"));
    let _ = writeln!(r, "| pass | time |");
    let _ = writeln!(r, "|---|---:|");
    let _ = writeln!(r, "| prepare | {} |", ms(timings.map(|t| t.prepare_ms)));
    let _ = writeln!(r, "| tile classification | {} |", ms(timings.map(|t| t.tile_classification_ms)));
    let passes = timings.map_or(0, |t| t.filter_passes as usize);
    for p in 0..passes {
        let _ = writeln!(r, "| filter {p} | {} |", ms(timings.map(|t| t.filter_ms[p])));
    }
    if timings.is_none() {
        let _ = writeln!(r, "| filter | n/a |");
    }
    let _ = writeln!(r, "| total | {} |", ms(timings.map(|t| t.total_ms)));
    let lavapipe = device.contains("llvmpipe");
    let _ = writeln!(
        r,
        "\nNote: on lavapipe (llvmpipe, Mesa's CPU Vulkan driver) GPU timings are CPU-emulated and not \
         representative of a GPU.{}",
        if lavapipe { " This run was on lavapipe." } else { "" }
    );
    r
}

fn fmt_rmse(v: f64) -> String {
    if v.is_finite() { format!("{v:.4}") } else { "n/a".to_string() }
}

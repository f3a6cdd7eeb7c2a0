//! The benchmark scenes and their frames, resident in GPU memory for the whole measurement.

use dnsr::ash::vk;
use dnsr::glam::{Mat4, Vec3};
use dnsr::testing::gpu::{Gpu, TestImage};
use dnsr::testing::scene::{hash01, render, Camera, FrameInputs};
use dnsr::testing::typical::{coverage, typical_frame, TYPICAL_CYCLE};

/// Masks drawn for a static scene: a fresh 1-spp mask every frame, replayed cyclically.
pub const STATIC_CYCLE: usize = 8;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum SceneId {
    PenumbraHeavy,
    Typical,
    AllLit,
    Sky90,
}

pub const ALL_SCENES: [SceneId; 4] = [SceneId::PenumbraHeavy, SceneId::Typical, SceneId::AllLit, SceneId::Sky90];

impl SceneId {
    /// The name on the command line and in bench.json.
    pub fn id(self) -> &'static str {
        match self {
            SceneId::PenumbraHeavy => "penumbra-heavy",
            SceneId::Typical => "typical",
            SceneId::AllLit => "all-lit",
            SceneId::Sky90 => "sky-90",
        }
    }

    /// The name in the tables.
    pub fn name(self) -> &'static str {
        match self {
            SceneId::PenumbraHeavy => "penumbra-heavy",
            SceneId::Typical => "typical",
            SceneId::AllLit => "all lit",
            SceneId::Sky90 => "90% sky",
        }
    }

    pub fn description(self) -> &'static str {
        match self {
            SceneId::PenumbraHeavy => {
                "static camera straight above a ground plane filling the image; visibility 0.5 + 0.3 sin(0.9x) cos(0.7z) \
                 (0.2..0.8) everywhere, so no tile is uniform; a fresh 1-spp mask every frame (8 masks replayed)"
            }
            SceneId::Typical => {
                "src/testing/typical.rs: boxes on a ground plane under a large area light, perspective camera panning \
                 sideways every frame (about 1% of the width per frame, 16-frame back-and-forth cycle): about 10% sky, \
                 30% penumbra, lit and shadowed ground, roofs and walls; disocclusion strips at the entering image \
                 edge and behind box edges"
            }
            SceneId::AllLit => "the penumbra-heavy camera and plane, visibility 1 everywhere (every tile cleared)",
            SceneId::Sky90 => {
                "the penumbra-heavy camera and field, the plane cut to a strip (|x| < 0.6) covering about 10% of \
                 the image; the rest is sky"
            }
        }
    }

    pub fn parse(s: &str) -> Option<SceneId> {
        ALL_SCENES.into_iter().find(|sc| sc.id() == s)
    }
}

/// The G-buffer formats the bench feeds dnsr.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum HostFormats {
    /// What engines render (the default): D32_SFLOAT depth (a depth attachment), A2B10G10R10_UNORM_PACK32 normals
    /// (n * 0.5 + 0.5, decoded with unpack mul 2, add -1), R16G16_SFLOAT velocity.
    Engine,
    /// `--float-gbuffer`: R32_SFLOAT depth, R32G32B32A32_SFLOAT normals, R32G32_SFLOAT velocity (24 B/px of
    /// normals and velocity that no engine has; the bench's inputs before issue 27).
    Float,
}

impl HostFormats {
    pub fn depth(self) -> vk::Format {
        match self {
            HostFormats::Engine => vk::Format::D32_SFLOAT,
            HostFormats::Float => vk::Format::R32_SFLOAT,
        }
    }

    pub fn velocity(self) -> vk::Format {
        match self {
            HostFormats::Engine => vk::Format::R16G16_SFLOAT,
            HostFormats::Float => vk::Format::R32G32_SFLOAT,
        }
    }

    pub fn normals(self) -> vk::Format {
        match self {
            HostFormats::Engine => vk::Format::A2B10G10R10_UNORM_PACK32,
            HostFormats::Float => vk::Format::R32G32B32A32_SFLOAT,
        }
    }

    /// (mul, add) that decode the stored normals (`ShadowsDispatch::normals_unpack_*`).
    pub fn normals_unpack(self) -> (f32, f32) {
        match self {
            HostFormats::Engine => (2.0, -1.0),
            HostFormats::Float => (1.0, 0.0),
        }
    }

    /// Bytes of one texel of each host G-buffer input: (depth, velocity, normals).
    pub fn bytes(self) -> (f64, f64, f64) {
        match self {
            HostFormats::Engine => (4.0, 4.0, 4.0),
            HostFormats::Float => (4.0, 8.0, 16.0),
        }
    }
}

/// Matrices of one frame and which resident images it binds.
pub struct Frame {
    pub mask: usize,
    pub gbuffer: usize,
    pub eye: Vec3,
    pub projection_inverse: Mat4,
    pub reprojection: Mat4,
    pub view_projection_inverse: Mat4,
}

/// Depth, velocity and normals in the scene's `HostFormats`.
pub struct GBuffer {
    pub depth: TestImage,
    pub velocity: TestImage,
    pub normals: TestImage,
}

pub struct GpuScene {
    /// The shadow input of each cycle frame: a hit mask, or with `visibility_input` an R8_UNORM visibility image.
    pub masks: Vec<TestImage>,
    /// The scene was built with `--rays k`: per-pixel visibility of k rays instead of the hit mask.
    pub visibility_input: bool,
    /// `--checkerboard`: the context takes the masks as a checkerboard input (half of each mask read per frame,
    /// alternating).
    pub checkerboard: bool,
    /// `--alias-transient`: the context hands its transient images to a host allocator and moves them out of
    /// UNDEFINED on every record (`ContextCreateInfo::alias_transient_memory`).
    pub alias_transient: bool,
    /// `--transient-per-light`: each light its own transient images (`ContextCreateInfo::transient_memory_per_light`).
    pub transient_per_light: bool,
    /// `--lights-together`: every record holds every light (`ContextCreateInfo::lights_recorded_together`).
    pub lights_together: bool,
    /// `--host-previous`: each dispatch gives the previous cycle frame's depth and normals
    /// (`ContextCreateInfo::host_previous_gbuffer`).
    pub host_previous: bool,
    /// SPIR-V that replaces dnsr's own for the named variants (`ContextCreateInfo::shader_overrides`): a shader
    /// change timed against the unchanged library in one run.
    pub shader_overrides: Vec<dnsr::ShaderOverride>,
    /// `--hard-light`: every light has no size (`ShadowsDispatch::hard_light`).
    pub hard_light: bool,
    /// `--light-position`: every light's `ShadowsDispatch::light_position`.
    pub light_position: Option<glam::Vec4>,
    pub gbuffers: Vec<GBuffer>,
    /// The formats of `gbuffers`.
    pub host: HostFormats,
    pub frames: Vec<Frame>,
    /// Fractions of the pixels (mean over the frames): sky, lit, shadowed, penumbra (visibility within 0.02 of
    /// 1, of 0, in between).
    pub coverage: [f64; 4],
}

const READ: vk::ImageLayout = vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL;

fn upload(gpu: &Gpu, format: vk::Format, w: u32, h: u32, bytes: &[u8]) -> TestImage {
    let img = gpu.image(format, w, h, READ);
    gpu.upload(&img, bytes);
    img
}

fn upload_gbuffer(gpu: &Gpu, f: &FrameInputs, host: HostFormats) -> GBuffer {
    let (w, h) = (f.width, f.height);
    if host == HostFormats::Float {
        return GBuffer {
            depth: upload(gpu, vk::Format::R32_SFLOAT, w, h, bytemuck_f32(&f.depth)),
            velocity: upload(gpu, vk::Format::R32G32_SFLOAT, w, h, bytemuck_f32(f.velocity.as_flattened())),
            normals: upload(gpu, vk::Format::R32G32B32A32_SFLOAT, w, h, bytemuck_f32(f.normals.as_flattened())),
        };
    }
    let depth = gpu.image(vk::Format::D32_SFLOAT, w, h, vk::ImageLayout::DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    gpu.upload(&depth, bytemuck_f32(&f.depth));
    let velocity: Vec<u16> = f.velocity.as_flattened().iter().map(|&v| dnsr::testing::f32_to_f16(v)).collect();
    let unorm10 = |c: f32| ((c * 0.5 + 0.5).clamp(0.0, 1.0) * 1023.0).round() as u32;
    let normals: Vec<u32> = f.normals.iter().map(|n| unorm10(n[0]) | (unorm10(n[1]) << 10) | (unorm10(n[2]) << 20) | (3 << 30)).collect();
    GBuffer {
        depth,
        velocity: upload(gpu, vk::Format::R16G16_SFLOAT, w, h, bytemuck::cast_slice(&velocity)),
        normals: upload(gpu, vk::Format::A2B10G10R10_UNORM_PACK32, w, h, bytemuck::cast_slice(&normals)),
    }
}

fn upload_mask(gpu: &Gpu, w: u32, h: u32, mask: &[u32]) -> TestImage {
    upload(gpu, vk::Format::R32_UINT, w.div_ceil(8), h.div_ceil(4), bytemuck::cast_slice(mask))
}

fn bytemuck_f32(v: &[f32]) -> &[u8] {
    bytemuck::cast_slice(v)
}

/// A 1-spp hit mask of `f`'s visibility drawn with another seed (the rule of `scene::render`).
fn redraw_mask(f: &FrameInputs, seed: u64) -> Vec<u32> {
    let tw = f.width.div_ceil(8);
    let mut mask = vec![0u32; f.mask.len()];
    for y in 0..f.height {
        for x in 0..f.width {
            let i = (y * f.width + x) as usize;
            if f.receiver[i] && hash01(seed, x, y) >= f.truth[i] as f64 {
                mask[((y / 4) * tw + x / 8) as usize] |= 1 << ((y % 4) * 8 + (x % 8));
            }
        }
    }
    mask
}

fn frame_of(f: &FrameInputs, mask: usize, gbuffer: usize) -> Frame {
    Frame {
        mask,
        gbuffer,
        eye: f.eye,
        projection_inverse: f.projection_inverse,
        reprojection: f.reprojection,
        view_projection_inverse: f.view_projection_inverse,
    }
}

/// The shadow input of `f` whose hit mask is `mask`: that mask, or (`rays`) the R8_UNORM visibility of `rays` rays
/// per pixel, the first being the mask's.
fn upload_input(gpu: &Gpu, f: &FrameInputs, mask: &[u32], rays: Option<u32>, seed: u64) -> TestImage {
    let Some(k) = rays else { return upload_mask(gpu, f.width, f.height, mask) };
    let mut g = FrameInputs { mask: mask.to_vec(), visibility: vec![1.0; f.visibility.len()], ..f.clone() };
    g.trace_rays(k, seed);
    let bytes: Vec<u8> = g.visibility.iter().map(|&v| (v * 255.0).round() as u8).collect();
    upload(gpu, vk::Format::R8_UNORM, f.width, f.height, &bytes)
}

/// Generates `scene` at `w` x `h` and uploads every frame of its cycle; with `rays`, the shadow input is the
/// visibility of that many rays per pixel.
pub fn build(gpu: &Gpu, scene: SceneId, w: u32, h: u32, rays: Option<u32>, host: HostFormats) -> GpuScene {
    let penumbra = |x: f64, z: f64| 0.5 + 0.3 * (x * 0.9).sin() * (z * 0.7).cos();
    let static_scene = |half_width: f64, field: &dyn Fn(f64, f64) -> f64| {
        let cam = Camera::above(0.0, 0.0, 10.0);
        let f = render(w, h, &cam, &cam, half_width, field, 1);
        let masks = (0..STATIC_CYCLE as u64)
            .map(|k| {
                let mask = if k == 0 { f.mask.clone() } else { redraw_mask(&f, k + 1) };
                upload_input(gpu, &f, &mask, rays, 1000 + k)
            })
            .collect();
        let frames = (0..STATIC_CYCLE).map(|k| frame_of(&f, k, 0)).collect();
        let gbuffers = vec![upload_gbuffer(gpu, &f, host)];
        GpuScene { masks, visibility_input: rays.is_some(), checkerboard: false, alias_transient: false, transient_per_light: false, lights_together: false, host_previous: false, hard_light: false, light_position: None, shader_overrides: Vec::new(), gbuffers, host, frames, coverage: coverage(&f) }
    };
    match scene {
        SceneId::PenumbraHeavy => static_scene(1e9, &penumbra),
        SceneId::AllLit => static_scene(1e9, &|_, _| 1.0),
        SceneId::Sky90 => static_scene(0.6, &penumbra),
        SceneId::Typical => {
            let mut s = GpuScene {
                masks: Vec::new(),
                visibility_input: rays.is_some(),
                checkerboard: false,
                alias_transient: false, transient_per_light: false, lights_together: false, host_previous: false, hard_light: false, light_position: None, shader_overrides: Vec::new(),
                gbuffers: Vec::new(),
                host,
                frames: Vec::new(),
                coverage: [0.0; 4],
            };
            for k in 0..TYPICAL_CYCLE {
                let f = typical_frame(w, h, k, k as u64 + 1);
                s.masks.push(upload_input(gpu, &f, &f.mask, rays, 2000 + k as u64));
                s.gbuffers.push(upload_gbuffer(gpu, &f, host));
                s.frames.push(frame_of(&f, k, k));
                for (c, v) in s.coverage.iter_mut().zip(coverage(&f)) {
                    *c += v / TYPICAL_CYCLE as f64;
                }
            }
            s
        }
    }
}

impl GpuScene {
    pub fn destroy(self, gpu: &Gpu) {
        unsafe { gpu.device.device_wait_idle().ok() };
        for m in &self.masks {
            gpu.destroy_image(m);
        }
        for g in &self.gbuffers {
            for img in [&g.depth, &g.velocity, &g.normals] {
                gpu.destroy_image(img);
            }
        }
    }
}

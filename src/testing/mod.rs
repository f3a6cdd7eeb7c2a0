//! Host-side harness shared by the tests and the demo: a Vulkan device, synthetic truth-known frames, and a
//! runner that uploads a frame, records dnsr, and reads the output back. Not part of the stable API.

pub mod fields;
pub mod flip;
pub mod gpu;
pub mod images;
pub mod scene;
pub mod settings;
pub mod typical;

use crate::{Context, ContextCreateInfo, HostSync, ShadowsDispatch};
use ash::vk;
use gpu::{full_barrier, Gpu, Staging, TestImage};
use scene::FrameInputs;

const READ: vk::ImageLayout = vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL;

/// Mask, depth, velocity, normals, output, hit-distance and visibility images for one render size.
fn host_images(gpu: &Gpu, w: u32, h: u32, output_format: vk::Format, visibility_format: vk::Format) -> [TestImage; 7] {
    [
        gpu.image(vk::Format::R32_UINT, w.div_ceil(8), h.div_ceil(4), READ),
        gpu.image(vk::Format::R32_SFLOAT, w, h, READ),
        gpu.image(vk::Format::R32G32_SFLOAT, w, h, READ),
        gpu.image(vk::Format::R32G32B32A32_SFLOAT, w, h, READ),
        // Resting in TRANSFER_SRC_OPTIMAL exercises dnsr's transition to GENERAL and back.
        gpu.image(output_format, w, h, vk::ImageLayout::TRANSFER_SRC_OPTIMAL),
        gpu.image(vk::Format::R32_SFLOAT, w, h, READ),
        gpu.image(visibility_format, w, h, READ),
    ]
}

/// Staging for one frame: mask, depth, velocity (2), normals (4), hit distance, visibility, output, in 4-byte words
/// per pixel.
fn staging_bytes(w: u32, h: u32) -> u64 {
    (w * h) as u64 * 4 * 11 + 96
}

/// Host images for one render size, plus staging memory.
pub struct Runner<'g> {
    /// The host device.
    pub gpu: &'g Gpu,
    /// The context under test.
    pub ctx: Context,
    /// Hit mask (R32_UINT).
    pub mask: TestImage,
    /// Depth (R32_SFLOAT).
    pub depth: TestImage,
    /// Velocity (R32G32_SFLOAT).
    pub velocity: TestImage,
    /// Normals (R32G32B32A32_SFLOAT).
    pub normals: TestImage,
    /// Output (the context's output format).
    pub output: TestImage,
    /// Hit distance (R32_SFLOAT), uploaded every frame.
    pub hit_distance: TestImage,
    /// Visibility (R32_SFLOAT unless `set_visibility_format`), uploaded every frame; the dispatch's shadow input
    /// when the context takes visibility.
    pub visibility: TestImage,
    /// Penumbra guidance for `dispatch`: the light's angular size, or None for none.
    pub guidance: Option<f32>,
    /// `ShadowsDispatch::hard_light` of `dispatch`.
    pub hard_light: bool,
    /// `ShadowsDispatch::light_position` of `dispatch`.
    pub light_position: Option<glam::Vec4>,
    /// The light's angular diameter that `dispatch` gives with `light_position` (`guidance` gives its own).
    pub light_angular_size: f32,
    /// `ShadowsDispatch::checkerboard_phase` of `dispatch` (a checkerboard input).
    pub checkerboard_phase: u32,
    /// Last frame's depth and normals for a context created with `host_previous_gbuffer` (`keep_previous_gbuffer`):
    /// `dispatch` names them, and each run swaps them with `depth` and `normals`, as an engine with two G-buffers.
    pub previous_gbuffer: Option<(TestImage, TestImage)>,
    visibility_input: bool,
    staging: Staging,
    cmd: vk::CommandBuffer,
}

/// Visibility values in an upload format's texel bytes.
fn encode_visibility(v: &[f32], format: vk::Format) -> Vec<u8> {
    match format {
        vk::Format::R32_SFLOAT => bytemuck::cast_slice(v).to_vec(),
        vk::Format::R16_SFLOAT => v.iter().flat_map(|&x| f32_to_f16(x).to_le_bytes()).collect(),
        vk::Format::R16_UNORM => v.iter().flat_map(|&x| ((x.clamp(0.0, 1.0) * 65535.0).round() as u16).to_le_bytes()).collect(),
        vk::Format::R8_UNORM => v.iter().map(|&x| (x.clamp(0.0, 1.0) * 255.0).round() as u8).collect(),
        other => panic!("no visibility upload for {other:?}"),
    }
}

/// A light's moments image (GENERAL; its format with `input`) read back as (mean, sum of squared deviations, count,
/// run).
pub fn download_moments(gpu: &Gpu, image: vk::Image, w: u32, h: u32, input: crate::ShadowInput) -> Vec<glam::DVec4> {
    let format = crate::state::moments_format(input);
    let raw = gpu.download(&TestImage::borrowed(image, format, w, h, vk::ImageLayout::GENERAL));
    let words: &[u32] = bytemuck::cast_slice(&raw);
    if format == vk::Format::R32_UINT {
        return words.iter().map(|&m| crate::reference::storage::unpack_moments(m)).collect();
    }
    let sum = |m: &[u32]| f32::from_bits(m[1]) as f64;
    words.chunks_exact(2).map(|m| crate::reference::storage::unpack_moments(m[0]).with_y(sum(m))).collect()
}

/// Moments as a moments image of `input`'s format holds them (see `download_moments`).
pub fn pack_moments(moments: &[glam::DVec4], input: crate::ShadowInput) -> Vec<u32> {
    let pack = crate::reference::storage::pack_moments;
    if crate::state::moments_format(input) == vk::Format::R32_UINT {
        return moments.iter().map(|&m| pack(m)).collect();
    }
    moments.iter().flat_map(|&m| [pack(m), (m.y as f32).to_bits()]).collect()
}

pub use crate::reference::storage::{f16_to_f32, f32_to_f16};

impl<'g> Runner<'g> {
    /// Creates the context and the host images for `info`'s size.
    pub fn new(gpu: &'g Gpu, info: &ContextCreateInfo) -> crate::Result<Runner<'g>> {
        let ctx = Context::new(info)?;
        let [mask, depth, velocity, normals, output, hit_distance, visibility] =
            host_images(gpu, info.width, info.height, info.output_format, vk::Format::R32_SFLOAT);
        let staging = gpu.staging(staging_bytes(info.width, info.height));
        let cmd = gpu.command_buffer();
        let visibility_input = info.shadow_input == crate::ShadowInput::Visibility;
        Ok(Runner { gpu, ctx, mask, depth, velocity, normals, output, hit_distance, visibility, visibility_input, guidance: None, hard_light: false, light_position: None, light_angular_size: 0.0, checkerboard_phase: 0, previous_gbuffer: None, staging, cmd })
    }

    /// A dispatch for `f` over this runner's images (no reset; penumbra guidance as `guidance` says).
    pub fn dispatch(&self, f: &FrameInputs) -> ShadowsDispatch {
        let (hit_mask, visibility) =
            if self.visibility_input { (Default::default(), self.visibility.host()) } else { (self.mask.host(), Default::default()) };
        ShadowsDispatch {
            hit_mask,
            visibility,
            depth: self.depth.host(),
            velocity: self.velocity.host(),
            normals: self.normals.host(),
            output: self.output.host(),
            hit_distance: self.guidance.map(|_| self.hit_distance.host()),
            light_angular_size: self.guidance.unwrap_or(if self.light_position.is_some() { self.light_angular_size } else { 0.0 }),
            hard_light: self.hard_light,
            light_position: self.light_position,
            checkerboard_phase: self.checkerboard_phase,
            previous_depth: self.previous_gbuffer.as_ref().map(|(d, _)| d.host()).unwrap_or_default(),
            previous_normals: self.previous_gbuffer.as_ref().map(|(_, n)| n.host()).unwrap_or_default(),
            eye: f.eye,
            projection_inverse: f.projection_inverse,
            reprojection_matrix: f.reprojection,
            view_projection_inverse: f.view_projection_inverse,
            sync: HostSync {
                input_src_stages: vk::PipelineStageFlags::TRANSFER,
                input_src_access: vk::AccessFlags::TRANSFER_WRITE,
                output_dst_stages: vk::PipelineStageFlags::TRANSFER,
                output_dst_access: vk::AccessFlags::TRANSFER_READ,
            },
            ..Default::default()
        }
    }

    /// Uploads `f`, records `dispatch`, reads the output back as floats.
    pub fn run(&mut self, f: &FrameInputs, dispatch: &ShadowsDispatch) -> crate::Result<Vec<f32>> {
        let (result, out) = self.run_raw(f, dispatch);
        result.map(|()| out)
    }

    /// Like `run`, but reads the output back even when recording failed: the command buffer still runs the
    /// uploads and the readback, so a test can check that a refused dispatch changed nothing.
    pub fn run_raw(&mut self, f: &FrameInputs, dispatch: &ShadowsDispatch) -> (crate::Result<()>, Vec<f32>) {
        let d = *dispatch;
        self.run_with(f, |ctx, cmd| ctx.record_shadows(cmd, &d))
    }

    /// Uploads `f`, lets `record` record the denoiser into the command buffer (through any API), reads the output.
    pub fn run_with<E>(
        &mut self,
        f: &FrameInputs,
        record: impl FnOnce(&mut Context, vk::CommandBuffer) -> Result<(), E>,
    ) -> (Result<(), E>, Vec<f32>) {
        let n = (f.width * f.height) as usize;
        // RGBA8 normals are stored as n * 0.5 + 0.5 (decode with unpack mul 2, add -1).
        let packed: Vec<[u8; 4]> = if self.normals.format == vk::Format::R8G8B8A8_UNORM {
            f.normals.iter().map(|v| v.map(|c| ((c * 0.5 + 0.5).clamp(0.0, 1.0) * 255.0).round() as u8)).collect()
        } else {
            Vec::new()
        };
        let normals: &[u8] = if packed.is_empty() { bytemuck::cast_slice(&f.normals) } else { bytemuck::cast_slice(&packed) };
        let visibility = encode_visibility(&f.visibility, self.visibility.format);
        let parts: [&[u8]; 6] = [
            bytemuck::cast_slice(&f.mask),
            bytemuck::cast_slice(&f.depth),
            bytemuck::cast_slice(&f.velocity),
            normals,
            bytemuck::cast_slice(&f.hit_distance),
            &visibility,
        ];
        let mut offsets = [0u64; 7];
        for (i, p) in parts.iter().enumerate() {
            self.staging.write(offsets[i] as usize, p);
            offsets[i + 1] = (offsets[i] + p.len() as u64).next_multiple_of(16);
        }
        let out_offset = offsets[6];
        let gpu = self.gpu;
        let images = [&self.mask, &self.depth, &self.velocity, &self.normals, &self.hit_distance, &self.visibility];
        let (ctx, staging, output) = (&mut self.ctx, &self.staging, &self.output);
        let result = gpu.submit_with(self.cmd, |cmd| {
            full_barrier(&gpu.device, cmd);
            for (img, off) in images.iter().zip(offsets) {
                gpu.cmd_copy(cmd, img, staging, off, true);
            }
            let r = record(ctx, cmd);
            gpu.cmd_copy(cmd, output, staging, out_offset, false);
            full_barrier(&gpu.device, cmd);
            r
        });
        if let Some((depth, normals)) = &mut self.previous_gbuffer {
            std::mem::swap(&mut self.depth, depth);
            std::mem::swap(&mut self.normals, normals);
        }
        let raw = self.staging.read(out_offset as usize, n * self.output.texel_bytes as usize);
        let out = match self.output.format {
            vk::Format::R32_SFLOAT => bytemuck::cast_slice::<u8, f32>(&raw).to_vec(),
            vk::Format::R16_SFLOAT => raw.chunks_exact(2).map(|c| f16_to_f32(u16::from_le_bytes([c[0], c[1]]))).collect(),
            vk::Format::R8_UNORM => raw.iter().map(|&b| b as f32 / 255.0).collect(),
            // Four-channel outputs hold the shadow in every channel.
            vk::Format::R8G8B8A8_UNORM => raw
                .chunks_exact(4)
                .map(|c| {
                    assert!(c.iter().all(|&b| b == c[0]), "RGBA8 output channels differ: {c:?}");
                    c[0] as f32 / 255.0
                })
                .collect(),
            vk::Format::R16G16B16A16_SFLOAT => raw
                .chunks_exact(8)
                .map(|c| {
                    assert!(c.chunks_exact(2).all(|h| h == &c[..2]), "RGBA16F output channels differ: {c:?}");
                    f16_to_f32(u16::from_le_bytes([c[0], c[1]]))
                })
                .collect(),
            other => panic!("no readback for {other:?}"),
        };
        (result, out)
    }

    /// Replaces the depth and normal images with other formats (D32_SFLOAT depth rests in
    /// DEPTH_STENCIL_READ_ONLY_OPTIMAL; R8G8B8A8_UNORM normals are uploaded packed).
    pub fn set_gbuffer_formats(&mut self, depth: vk::Format, normals: vk::Format) {
        let g = self.gpu;
        let (w, h) = (self.depth.width, self.depth.height);
        let depth_layout = if depth == vk::Format::D32_SFLOAT { vk::ImageLayout::DEPTH_STENCIL_READ_ONLY_OPTIMAL } else { READ };
        g.destroy_image(&self.depth);
        g.destroy_image(&self.normals);
        self.depth = g.image(depth, w, h, depth_layout);
        self.normals = g.image(normals, w, h, READ);
        if self.previous_gbuffer.is_some() {
            self.keep_previous_gbuffer();
        }
    }

    /// Keeps last frame's depth and normals for a context created with `host_previous_gbuffer`: a second pair of
    /// images in the current ones' formats (see `previous_gbuffer`). Their first frame's contents are undefined, as
    /// an engine's are before its first frame: run the first frame with `reset`.
    pub fn keep_previous_gbuffer(&mut self) {
        let g = self.gpu;
        let (w, h) = (self.depth.width, self.depth.height);
        self.drop_previous_gbuffer();
        self.previous_gbuffer = Some((g.image(self.depth.format, w, h, self.depth.layout), g.image(self.normals.format, w, h, self.normals.layout)));
    }

    fn drop_previous_gbuffer(&mut self) {
        if let Some((depth, normals)) = self.previous_gbuffer.take() {
            self.gpu.destroy_image(&depth);
            self.gpu.destroy_image(&normals);
        }
    }

    /// Replaces the visibility image with another format (R8_UNORM, R16_UNORM, R16_SFLOAT or R32_SFLOAT).
    pub fn set_visibility_format(&mut self, format: vk::Format) {
        let g = self.gpu;
        let (w, h) = (self.visibility.width, self.visibility.height);
        g.destroy_image(&self.visibility);
        self.visibility = g.image(format, w, h, READ);
    }

    /// Resizes the context and recreates the host images for the new size.
    pub fn resize(&mut self, width: u32, height: u32) -> crate::Result<()> {
        let g = self.gpu;
        unsafe { g.device.device_wait_idle().ok() };
        self.ctx.resize(width, height)?;
        let format = self.output.format;
        for img in self.images() {
            g.destroy_image(img);
        }
        g.destroy_staging(&self.staging);
        [self.mask, self.depth, self.velocity, self.normals, self.output, self.hit_distance, self.visibility] =
            host_images(g, width, height, format, self.visibility.format);
        if self.previous_gbuffer.is_some() {
            self.keep_previous_gbuffer();
        }
        self.staging = g.staging(staging_bytes(width, height));
        Ok(())
    }

    fn images(&self) -> [&TestImage; 7] {
        [&self.mask, &self.depth, &self.velocity, &self.normals, &self.output, &self.hit_distance, &self.visibility]
    }

    /// Runs one frame of `f` with the default dispatch (plus `reset`).
    pub fn frame(&mut self, f: &FrameInputs, reset: bool) -> Vec<f32> {
        let d = ShadowsDispatch { reset, ..self.dispatch(f) };
        self.run(f, &d).expect("record_shadows")
    }
}

impl Drop for Runner<'_> {
    fn drop(&mut self) {
        let g = self.gpu;
        unsafe { g.device.device_wait_idle().ok() };
        g.free_command_buffer(self.cmd);
        self.drop_previous_gbuffer();
        for img in self.images() {
            g.destroy_image(img);
        }
        g.destroy_staging(&self.staging);
    }
}

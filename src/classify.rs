//! The hybrid-shadows classifier (`Context::record_classify`): from the engine's cascaded shadow maps it decides
//! which pixels are surely lit or surely shadowed, prefills the hit mask with those verdicts, and lists the 8x4
//! tiles whose other pixels need a shadow ray, with the ray interval the blockers bound. The engine then traces
//! only the listed pixels (one indirect dispatch) and runs the denoiser on the completed mask.
//!
//! Host side here: the dispatch description, the buffers dnsr owns for the tile list and its counts, and the
//! recording. The pass is shaders/classify.glsl; the CPU reference is `reference::classify`.

use crate::constants::{ClassifyConstants, FrameConstants, CLASSIFY_BOUND_INTERVAL, CLASSIFY_CASCADES_INVERTED, CLASSIFY_REJECT_LIT};
use crate::dispatch::{HitMaskConvention, HostImage, HostSync, Rect};
use crate::error::{vk_check, Error, Result};
use crate::gpu::barrier;
use crate::gpu::descriptors::Binder;
use crate::gpu::loader::Vk;
use crate::gpu::memory::{self, Memory};
use crate::gpu::shader::{variant, Pipeline};
use crate::host::ResourceKind;
use crate::passes::bindings::{Binding, BindingTable, Resource, RESOURCE_COUNT};
use ash::vk;
use glam::{Mat3, Mat4, Vec3, Vec4Swizzles};

/// Most shadow-map cascades one classify dispatch reads.
pub const MAX_CASCADES: usize = 4;
/// Blocker-search tap counts the classifier supports (`ClassifyDispatch::tap_count`).
pub const CLASSIFY_TAP_COUNTS: [u32; 4] = [8, 16, 24, 32];
/// Most blocker-search taps.
pub(crate) const MAX_TAPS: usize = 32;
/// Steepest receiver slope (tangent of the angle between its normal and the light) the blocker search follows
/// with the receiver's tangent plane; a steeper receiver's plane is flattened to this slope.
pub(crate) const MAX_SLOPE: f32 = 4.0;
/// Bytes of one tile record in `ClassifierBuffers::tiles`: uvec4 (x | y << 16 in tiles, mask of pixels to trace
/// with bit (y % 4) * 8 + (x % 8), min t, max t as float bits). Min t is 0 (the FidelityFX record's field): a ray
/// starts at its receiver, since blockers nearer than the blocker offset or between taps are invisible to the
/// cascades.
pub const CLASSIFY_TILE_BYTES: u64 = 16;
/// Bytes of `ClassifierBuffers::counts`: u32 words 0..3 `VkDispatchIndirectCommand` (tiles, 1, 1) and the tile
/// count; words 4..7 (32 x tiles, 1, 1, 0): one invocation per pixel of every listed tile, e.g. for
/// `vkCmdTraceRaysIndirectKHR` after a copy into a buffer with a device address.
pub const CLASSIFY_COUNTS_BYTES: u64 = 32;

/// One shadow-map cascade.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowCascade {
    /// World position (w = 1) to (u, v, depth) of this cascade's shadow map: u, v in [0, 1] across its image
    /// (0, 0 the top-left texel corner), depth as its shadow map stores it. Must be affine (orthographic, last
    /// row 0 0 0 1), as a sun's cascades are. Column-major, column vectors (glam). A cascade given as the
    /// FidelityFX / "shadow matrix with per-cascade scale and offset" form is `translation(offset) *
    /// scale(scale) * shadow_matrix`.
    pub world_to_shadow: Mat4,
}

impl Default for ShadowCascade {
    fn default() -> Self {
        ShadowCascade { world_to_shadow: Mat4::IDENTITY }
    }
}

/// One frame of input of the classifier. Conventions as `ShadowsDispatch` (Vulkan NDC, column-major matrices).
#[derive(Clone, Copy, Debug)]
pub struct ClassifyDispatch {
    /// Depth, render size, in the context's depth convention (a `ShadowsDispatch::depth` format). Sampled.
    pub depth: HostImage,
    /// World-space normals, render size, decoded as `rgb * normals_unpack_mul + normals_unpack_add` (a
    /// `ShadowsDispatch::normals` format). A pixel whose normal faces away from the light is shadowed without a
    /// ray; an unusable (zero, NaN) normal leaves the decision to the cascades.
    pub normals: HostImage,
    /// Normal decode multiplier.
    pub normals_unpack_mul: f32,
    /// Normal decode offset.
    pub normals_unpack_add: f32,
    /// Current clip space -> world space (the space the cascades' matrices take).
    pub view_projection_inverse: Mat4,
    /// Current clip space -> view space (`ShadowsDispatch::projection_inverse`). dnsr's own classifier does not
    /// read it; an engine's classifier variant (`ContextCreateInfo::shader_overrides`) whose callbacks decode
    /// depth with it (`dnsr_get_projection_inverse`, e.g. from linear view depth) does.
    pub projection_inverse: Mat4,
    /// World-space direction from the surfaces toward the light (the sun); any length but zero.
    pub light_direction: Vec3,
    /// The light's angular diameter in radians (the sun: about 0.0093), in [0, pi): sets the blocker search
    /// radius (the widest penumbra a blocker between the receiver and the cascade's near plane can cast).
    pub light_angular_size: f32,
    /// How many of `cascades` (and of `cascade_images` or `cascade_array`'s layers) are used, 1..=4; the
    /// first cascade containing a pixel decides it, a pixel in none is traced.
    pub cascade_count: u32,
    /// The cascades, finest first.
    pub cascades: [ShadowCascade; MAX_CASCADES],
    /// Cascade i's shadow map as its own image (a 2D view, depth aspect, a `ShadowsDispatch::depth` format, any
    /// size, a depth read-only or shader read-only layout). Leave them null when `cascade_array` is given.
    pub cascade_images: [HostImage; MAX_CASCADES],
    /// The cascades as the layers of one image instead (a 2D-array view, layer i cascade i, at least
    /// `cascade_count` layers in `cascade_array_layers`), or None.
    pub cascade_array: Option<HostImage>,
    /// Layers of `cascade_array`'s view.
    pub cascade_array_layers: u32,
    /// The shadow maps hold 1 at the light's near plane and 0 at its far plane (reverse-Z cascades).
    pub cascades_depth_inverted: bool,
    /// World distance along the light direction a shadow-map depth must be in front of the receiver to count as
    /// a blocker (the shadow maps' bias), >= 0. Each tap is compared with the receiver's tangent plane (from its
    /// normal) under it, so a sloping receiver needs no larger offset than a flat one: texel size and depth
    /// precision set it.
    pub blocker_offset: f32,
    /// Blocker-search taps per pixel: 8, 16, 24 (default) or 32.
    pub tap_count: u32,
    /// A tile is listed for tracing only with more pixels to trace than this (0..=31; default 0, every tile
    /// with one). Pixels to trace in a tile that is not listed get the verdict most of their taps give.
    pub tile_cutoff: u32,
    /// Pixels no tap finds a blocker for are decided lit (default). Off: only shadowed pixels are decided, every
    /// other receiver is traced.
    pub reject_lit_pixels: bool,
    /// A listed tile's ray interval is bounded by the blockers its pixels' taps found (default); off: from 0
    /// (the receiver: the engine's own ray offset keeps its rays off their surface) to infinity.
    pub cascades_bound_ray_interval: bool,
    /// The host's hit mask, written (prefilled) by the classifier: R32_UINT, ceil(W/8) x ceil(H/4), STORAGE
    /// usage, GENERAL layout. The same image the engine's trace completes and `ShadowsDispatch::hit_mask`
    /// reads.
    pub hit_mask: HostImage,
    /// The convention the engine's trace and the denoiser use: pixels to trace are prefilled with bit 0 in
    /// both, so the trace ORs in its bit (occluded with `OccludedBits`, lit with `LitBits`).
    pub hit_mask_convention: HitMaskConvention,
    /// Region to classify; `None` = the whole render size. Tiles outside it are not written.
    pub render_rect: Option<Rect>,
    /// Barriers dnsr should emit on the host's behalf: the writes of depth, normals and shadow maps before,
    /// and the host's use of the hit mask, tile list and counts after (its trace: e.g. DRAW_INDIRECT +
    /// RAY_TRACING_SHADER_KHR or COMPUTE_SHADER; dnsr's own prepare pass is always covered).
    pub sync: HostSync,
}

impl Default for ClassifyDispatch {
    fn default() -> Self {
        ClassifyDispatch {
            depth: HostImage::default(),
            normals: HostImage::default(),
            normals_unpack_mul: 1.0,
            normals_unpack_add: 0.0,
            view_projection_inverse: Mat4::IDENTITY,
            projection_inverse: Mat4::IDENTITY,
            light_direction: Vec3::Z,
            light_angular_size: 0.0093,
            cascade_count: 0,
            cascades: [ShadowCascade::default(); MAX_CASCADES],
            cascade_images: [HostImage::default(); MAX_CASCADES],
            cascade_array: None,
            cascade_array_layers: 0,
            cascades_depth_inverted: false,
            blocker_offset: 0.0,
            tap_count: 24,
            tile_cutoff: 0,
            reject_lit_pixels: true,
            cascades_bound_ray_interval: true,
            hit_mask: HostImage::default(),
            hit_mask_convention: HitMaskConvention::OccludedBits,
            render_rect: None,
            sync: HostSync::default(),
        }
    }
}

/// The buffers the classifier writes (dnsr owns them; they live until the context is destroyed or resized).
/// Both have STORAGE_BUFFER, STORAGE_TEXEL_BUFFER, INDIRECT_BUFFER, TRANSFER_SRC and TRANSFER_DST usage.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ClassifierBuffers {
    /// The tile list: `tile_capacity` records of `CLASSIFY_TILE_BYTES`, the first `counts` word 3 of them
    /// written by the last classify dispatch (in no particular order).
    pub tiles: vk::Buffer,
    /// Records `tiles` holds: every tile of the render size.
    pub tile_capacity: u32,
    /// `CLASSIFY_COUNTS_BYTES` of counts (see there); reset by every classify dispatch.
    pub counts: vk::Buffer,
}

/// The blocker-search taps in the unit disc: the centre, then Mitchell's best candidate from a fixed seed, so every
/// prefix (the first 8, 16, 24) is spread over the disc too; then each tap's radius r becomes r^2, so that the
/// inner disc gets more of them (of 24 taps, 10 lie within half the radius, where an even spread puts 6). The search
/// radius is the penumbra of a blocker at the cascade's near plane, the farthest one can be; a nearer blocker's
/// penumbra is narrower and only the inner taps can find it (with the taps spread evenly, the viewer's default scene
/// left 2.6 times the error on pixels decided lit at the rim of such penumbrae, 640x360, 3-degree sun, and traced 6%
/// more pixels). One table for the shader (generated GLSL) and the reference.
pub(crate) fn blocker_disc() -> [[f32; 2]; MAX_TAPS] {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f64 / (1u64 << 24) as f64
    };
    // The centre first: a thin blocker straight towards the light (a pole's umbra) is not left between taps.
    let mut points: Vec<[f64; 2]> = vec![[0.0, 0.0]];
    while points.len() < MAX_TAPS {
        let mut best = ([0.0, 0.0], -1.0);
        for _ in 0..(8 * points.len() + 1) {
            let (r, a) = (next().sqrt(), next() * std::f64::consts::TAU);
            let c = [r * a.cos(), r * a.sin()];
            let d = points.iter().map(|p| (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2)).fold(f64::INFINITY, f64::min);
            if d > best.1 {
                best = (c, d);
            }
        }
        points.push(best.0);
    }
    std::array::from_fn(|i| {
        let [x, y] = points[i];
        let r = (x * x + y * y).sqrt();
        [(x * r) as f32, (y * r) as f32]
    })
}

/// Names for messages about cascade i.
const CASCADE_MATRIX: [&str; MAX_CASCADES] =
    ["cascades[0].world_to_shadow", "cascades[1].world_to_shadow", "cascades[2].world_to_shadow", "cascades[3].world_to_shadow"];

/// The classifier's constants for `d` (already validated field by field), or a specific error where a cascade's
/// geometry does not fit the light: its depth must grow away from the light.
pub(crate) fn constants(d: &ClassifyDispatch) -> Result<ClassifyConstants> {
    let to_light = d.light_direction.normalize();
    let sign = if d.cascades_depth_inverted { 1.0 } else { -1.0 };
    let mut units = [[0.0f32; 4]; 4];
    let (mut axes_u, mut axes_v) = ([[0.0f32; 4]; 4], [[0.0f32; 4]; 4]);
    for (i, c) in d.cascades.iter().take(d.cascade_count as usize).enumerate() {
        let m = c.world_to_shadow.transpose();
        let (row_u, row_v, row_depth) = (m.x_axis.xyz(), m.y_axis.xyz(), m.z_axis.xyz());
        let depth_per_unit = sign * row_depth.dot(to_light);
        if !(depth_per_unit > 0.0) {
            return Err(Error::InvalidValue {
                field: CASCADE_MATRIX[i],
                value: format!("a depth that changes by {:e} per world unit toward the light", -sign * depth_per_unit),
                allowed: "its depth must grow away from the light along light_direction (decrease, with cascades_depth_inverted)",
            });
        }
        let linear = Mat3::from_mat4(c.world_to_shadow);
        let det = linear.determinant();
        if !det.is_normal() {
            return Err(Error::InvalidValue {
                field: CASCADE_MATRIX[i],
                value: format!("a 3x3 part with determinant {det:e}"),
                allowed: "u, v and depth must change independently across the world (an invertible 3x3 part)",
            });
        }
        let inverse = linear.inverse();
        axes_u[i] = inverse.x_axis.extend(0.0).to_array();
        axes_v[i] = inverse.y_axis.extend(0.0).to_array();
        let across = |row: Vec3| (row - row.dot(to_light) * to_light).length();
        units[i] = [depth_per_unit, across(row_u), across(row_v), d.blocker_offset * depth_per_unit];
    }
    let cascade = |i: usize| d.cascades[i].world_to_shadow.to_cols_array_2d();
    let flags = (if d.reject_lit_pixels { CLASSIFY_REJECT_LIT } else { 0 })
        | (if d.cascades_bound_ray_interval { CLASSIFY_BOUND_INTERVAL } else { 0 })
        | (if d.cascades_depth_inverted { CLASSIFY_CASCADES_INVERTED } else { 0 });
    Ok(ClassifyConstants {
        cascade0: cascade(0),
        cascade1: cascade(1),
        cascade2: cascade(2),
        cascade3: cascade(3),
        cascade_units: units,
        cascade_axes_u: axes_u,
        cascade_axes_v: axes_v,
        light: [to_light.x, to_light.y, to_light.z, (0.5 * d.light_angular_size).tan()],
        settings: [d.cascade_count, d.tap_count, d.tile_cutoff, flags],
    })
}

/// Where the classify constants start in the classifier's uniform buffer (after the frame constants, at the
/// largest alignment Vulkan allows for uniform offsets).
const CLASSIFY_CONSTANTS_OFFSET: vk::DeviceSize = (std::mem::size_of::<FrameConstants>() as vk::DeviceSize).next_multiple_of(256);
const UNIFORM_BYTES: vk::DeviceSize = CLASSIFY_CONSTANTS_OFFSET + std::mem::size_of::<ClassifyConstants>() as vk::DeviceSize;

fn tile_capacity(size: [u32; 2]) -> u32 {
    size[0].div_ceil(crate::passes::TILE[0]) * size[1].div_ceil(crate::passes::TILE[1])
}

/// One buffer, its memory and (for the texel-buffer bindings) a view.
#[derive(Default)]
struct OwnedBuffer {
    buffer: vk::Buffer,
    memory: Memory,
    view: vk::BufferView,
    bytes: u64,
}

impl OwnedBuffer {
    fn new(vk: &Vk, bytes: u64, usage: vk::BufferUsageFlags, view_format: Option<vk::Format>, name: &str) -> Result<OwnedBuffer> {
        let d = &vk.device;
        let mut out = OwnedBuffer::default();
        let result = (|| {
            let info = vk::BufferCreateInfo::default().size(bytes).usage(usage);
            out.buffer = vk_check("vkCreateBuffer", unsafe { d.create_buffer(&info, vk.alloc()) })?;
            let req = unsafe { d.get_buffer_memory_requirements(out.buffer) };
            out.bytes = req.size;
            out.memory = memory::allocate(vk, req, ResourceKind::Buffer)?;
            vk_check("vkBindBufferMemory", unsafe { d.bind_buffer_memory(out.buffer, out.memory.memory, out.memory.offset) })?;
            if let Some(format) = view_format {
                let info = vk::BufferViewCreateInfo::default().buffer(out.buffer).format(format).range(vk::WHOLE_SIZE);
                out.view = vk_check("vkCreateBufferView", unsafe { d.create_buffer_view(&info, vk.alloc()) })?;
            }
            vk.name(out.buffer, name);
            Ok(())
        })();
        match result {
            Ok(()) => Ok(out),
            Err(e) => {
                out.destroy(vk);
                Err(e)
            }
        }
    }

    fn destroy(&mut self, vk: &Vk) {
        unsafe {
            vk.device.destroy_buffer_view(self.view, vk.alloc());
            vk.device.destroy_buffer(self.buffer, vk.alloc());
        }
        memory::free(vk, &mut self.memory);
        *self = OwnedBuffer::default();
    }
}

/// The classifier's pipelines (separate cascade images, an array image), buffers and descriptor sets.
pub(crate) struct Classifier {
    /// [separate images, array image].
    pipelines: Vec<Pipeline>,
    tiles: OwnedBuffer,
    counts: OwnedBuffer,
    uniforms: OwnedBuffer,
    tile_capacity: u32,
    /// Per pipeline: an engine's variant (`ContextCreateInfo::shader_overrides`) runs, whose callbacks decode the
    /// G-buffer (its formats are the engine's).
    engine_decodes: [bool; 2],
    /// Without push descriptors: per pipeline, a ring of `max_frames_in_flight` sets.
    pool: vk::DescriptorPool,
    sets: Vec<[vk::DescriptorSet; 2]>,
    next_set: usize,
}

const PIPELINE_NAMES: [&str; 2] = ["classify", "classify_cascade_array"];

impl Classifier {
    /// The classifier of a context; `overrides` (checked) may replace either variant.
    pub(crate) fn new(vk: &Vk, size: [u32; 2], push: bool, slots: u32, overrides: &[crate::ShaderOverride]) -> Result<Classifier> {
        let mut c = Classifier {
            pipelines: Vec::new(),
            engine_decodes: [false; 2],
            tiles: OwnedBuffer::default(),
            counts: OwnedBuffer::default(),
            uniforms: OwnedBuffer::default(),
            tile_capacity: 0,
            pool: vk::DescriptorPool::null(),
            sets: Vec::new(),
            next_set: 0,
        };
        match c.create(vk, size, push, slots, overrides) {
            Ok(()) => Ok(c),
            Err(e) => {
                c.destroy(vk);
                Err(e)
            }
        }
    }

    fn create(&mut self, vk: &Vk, size: [u32; 2], push: bool, slots: u32, overrides: &[crate::ShaderOverride]) -> Result<()> {
        for (i, name) in PIPELINE_NAMES.into_iter().enumerate() {
            let engine = overrides.iter().find(|o| o.variant == name);
            self.engine_decodes[i] = engine.is_some();
            // Pipeline::new checks both constants blocks' sizes against the host's.
            self.pipelines.push(Pipeline::new(vk, name, engine.map_or(variant(name).spirv, |o| &o.spirv[..]), push)?);
        }
        self.allocate(vk, size)?;
        let uniform = vk::BufferUsageFlags::UNIFORM_BUFFER | vk::BufferUsageFlags::TRANSFER_DST;
        self.uniforms = OwnedBuffer::new(vk, UNIFORM_BYTES, uniform, None, "dnsr.classify_constants")?;
        if !push {
            let mut sizes: Vec<vk::DescriptorPoolSize> = Vec::new();
            for b in self.pipelines.iter().flat_map(|p| &p.interface.bindings) {
                match sizes.iter_mut().find(|s| s.ty == b.descriptor_type) {
                    Some(s) => s.descriptor_count += slots,
                    None => sizes.push(vk::DescriptorPoolSize { ty: b.descriptor_type, descriptor_count: slots }),
                }
            }
            let info = vk::DescriptorPoolCreateInfo::default().max_sets(2 * slots).pool_sizes(&sizes);
            self.pool = vk_check("vkCreateDescriptorPool", unsafe { vk.device.create_descriptor_pool(&info, vk.alloc()) })?;
            let layouts = [self.pipelines[0].set_layout, self.pipelines[1].set_layout];
            let info = vk::DescriptorSetAllocateInfo::default().descriptor_pool(self.pool).set_layouts(&layouts);
            for _ in 0..slots {
                let sets = vk_check("vkAllocateDescriptorSets", unsafe { vk.device.allocate_descriptor_sets(&info) })?;
                self.sets.push([sets[0], sets[1]]);
            }
        }
        Ok(())
    }

    /// The tile list and counts for a render size (a resize calls it again after `free_buffers`).
    pub(crate) fn allocate(&mut self, vk: &Vk, size: [u32; 2]) -> Result<()> {
        let capacity = tile_capacity(size);
        let limit = unsafe { vk.instance.get_physical_device_properties(vk.physical_device) }.limits.max_texel_buffer_elements;
        if capacity > limit {
            return Err(Error::InvalidValue {
                field: "render size",
                value: format!("{} x {} ({capacity} tiles)", size[0], size[1]),
                allowed: "the classifier's tile list is a texel buffer of one element per 8x4 tile; the device's maxTexelBufferElements is smaller",
            });
        }
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::STORAGE_TEXEL_BUFFER
            | vk::BufferUsageFlags::INDIRECT_BUFFER
            | vk::BufferUsageFlags::TRANSFER_SRC
            | vk::BufferUsageFlags::TRANSFER_DST;
        let bytes = capacity as u64 * CLASSIFY_TILE_BYTES;
        self.tiles = OwnedBuffer::new(vk, bytes, usage, Some(vk::Format::R32G32B32A32_UINT), "dnsr.classify_tiles")?;
        self.counts = OwnedBuffer::new(vk, CLASSIFY_COUNTS_BYTES, usage, Some(vk::Format::R32_UINT), "dnsr.classify_counts")?;
        self.tile_capacity = capacity;
        Ok(())
    }

    pub(crate) fn free_buffers(&mut self, vk: &Vk) {
        self.tiles.destroy(vk);
        self.counts.destroy(vk);
        self.tile_capacity = 0;
    }

    pub(crate) fn buffers(&self) -> ClassifierBuffers {
        ClassifierBuffers { tiles: self.tiles.buffer, tile_capacity: self.tile_capacity, counts: self.counts.buffer }
    }

    /// Bytes of device memory bound to the classifier's buffers.
    pub(crate) fn bytes(&self) -> u64 {
        self.tiles.bytes + self.counts.bytes + self.uniforms.bytes
    }

    pub(crate) fn has_buffers(&self) -> bool {
        self.tiles.buffer != vk::Buffer::null()
    }

    /// Whether the variant a dispatch with (`array`) or without a cascade array runs is an engine's, which decodes
    /// the G-buffer itself.
    pub(crate) fn engine_decodes(&self, array: bool) -> bool {
        self.engine_decodes[array as usize]
    }

    /// Records a validated dispatch (its constants from `constants`): the counters' reset and the constants, the
    /// pass, and the barriers around. Infallible: everything that can fail was checked before.
    pub(crate) fn record(
        &mut self,
        vk: &Vk,
        binder: &Binder,
        cmd: vk::CommandBuffer,
        d: &ClassifyDispatch,
        frame: &FrameConstants,
        classify: &ClassifyConstants,
        rect: Rect,
    ) {
        let array = d.cascade_array.is_some();
        let pipeline = &self.pipelines[array as usize];
        let table = self.bindings(d);
        let set = match self.sets.get(self.next_set) {
            Some(sets) => sets[array as usize],
            None => vk::DescriptorSet::null(),
        };
        if !self.sets.is_empty() {
            self.next_set = (self.next_set + 1) % self.sets.len();
        }
        let dev = &vk.device;
        binder.write(dev, set, pipeline, &table, vk::Sampler::null());
        // Earlier frames (the host's trace reading the list and counts, dnsr's prepare reading the mask, the
        // previous classify reading the constants) and the host's input writes, before this frame's writes.
        barrier::memory(
            dev,
            cmd,
            vk::PipelineStageFlags::TOP_OF_PIPE | vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::TRANSFER
                | d.sync.input_src_stages
                | d.sync.output_dst_stages,
            vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::TRANSFER_WRITE | d.sync.input_src_access,
            vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::TRANSFER,
            vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE | vk::AccessFlags::TRANSFER_WRITE,
            &[],
        );
        let mut uniforms = [0u8; UNIFORM_BYTES as usize];
        uniforms[..std::mem::size_of::<FrameConstants>()].copy_from_slice(bytemuck::bytes_of(frame));
        uniforms[CLASSIFY_CONSTANTS_OFFSET as usize..].copy_from_slice(bytemuck::bytes_of(classify));
        let counts: [u32; 8] = [0, 1, 1, 0, 0, 1, 1, 0];
        unsafe {
            dev.cmd_update_buffer(cmd, self.uniforms.buffer, 0, &uniforms);
            dev.cmd_update_buffer(cmd, self.counts.buffer, 0, bytemuck::bytes_of(&counts));
        }
        barrier::transfer_to_compute(dev, cmd);
        let groups = crate::passes::classify::group_count([rect.width, rect.height]);
        unsafe { dev.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline.for_frame(0)) };
        binder.bind(dev, cmd, pipeline, &table, vk::Sampler::null(), set);
        unsafe { dev.cmd_dispatch(cmd, groups[0], groups[1], groups[2]) };
        // The hit mask, list and counts, for dnsr's prepare pass and the host's trace (indirect arguments too).
        barrier::memory(
            dev,
            cmd,
            vk::PipelineStageFlags::COMPUTE_SHADER,
            vk::AccessFlags::SHADER_WRITE,
            vk::PipelineStageFlags::COMPUTE_SHADER | vk::PipelineStageFlags::DRAW_INDIRECT | vk::PipelineStageFlags::TRANSFER | d.sync.output_dst_stages,
            vk::AccessFlags::SHADER_READ
                | vk::AccessFlags::SHADER_WRITE
                | vk::AccessFlags::INDIRECT_COMMAND_READ
                | vk::AccessFlags::TRANSFER_READ
                | d.sync.output_dst_access,
            &[],
        );
    }

    fn bindings(&self, d: &ClassifyDispatch) -> BindingTable {
        let mut t: BindingTable = [Binding::default(); RESOURCE_COUNT];
        let uniform = |offset: vk::DeviceSize, range: usize| Binding {
            buffer: self.uniforms.buffer,
            offset,
            range: range as vk::DeviceSize,
            ..Default::default()
        };
        t[Resource::Constants as usize] = uniform(0, std::mem::size_of::<FrameConstants>());
        t[Resource::ClassifyConstants as usize] = uniform(CLASSIFY_CONSTANTS_OFFSET, std::mem::size_of::<ClassifyConstants>());
        let host = |img: &HostImage| crate::passes::bindings::image(img.view, img.layout);
        t[Resource::Depth as usize] = host(&d.depth);
        t[Resource::Normals as usize] = host(&d.normals);
        t[Resource::HitMaskOut as usize] = host(&d.hit_mask);
        t[Resource::TileList as usize] = Binding { texel: self.tiles.view, ..Default::default() };
        t[Resource::TileCount as usize] = Binding { texel: self.counts.view, ..Default::default() };
        let cascades = [Resource::Cascade0, Resource::Cascade1, Resource::Cascade2, Resource::Cascade3];
        match &d.cascade_array {
            Some(array) => t[Resource::CascadeArray as usize] = host(array),
            None => {
                // Unused cascades are bound to the first one's image and never read.
                for (i, r) in cascades.into_iter().enumerate() {
                    let img = if i < d.cascade_count as usize { &d.cascade_images[i] } else { &d.cascade_images[0] };
                    t[r as usize] = host(img);
                }
            }
        }
        t
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        for p in &mut self.pipelines {
            p.destroy(vk);
        }
        self.pipelines.clear();
        self.free_buffers(vk);
        self.uniforms.destroy(vk);
        unsafe { vk.device.destroy_descriptor_pool(self.pool, vk.alloc()) };
        self.pool = vk::DescriptorPool::null();
        self.sets.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocker_disc_prefixes_cover_the_disc() {
        let disc = blocker_disc();
        assert_eq!(disc[0], [0.0, 0.0], "the centre comes first");
        for n in CLASSIFY_TAP_COUNTS {
            let warped = &disc[..n as usize];
            assert!(warped.iter().all(|p| p[0] * p[0] + p[1] * p[1] <= 1.0));
            let inner = warped.iter().filter(|p| (p[0] * p[0] + p[1] * p[1]).sqrt() <= 0.5).count();
            // An even spread puts a quarter there; 8 taps are too few to favour the centre beyond itself.
            assert!(n < 16 || inner * 4 > n as usize, "{n} taps: only {inner} within half the radius");
            // Undone (radius r^2 back to r), the taps are spread evenly: every quadrant holds a share of any prefix,
            // and no two taps nearly coincide.
            let taps: Vec<[f32; 2]> = warped
                .iter()
                .map(|&[x, y]| {
                    let r = (x * x + y * y).sqrt().sqrt();
                    if r == 0.0 { [0.0, 0.0] } else { [x / r, y / r] }
                })
                .collect();
            for q in 0..4 {
                let inside = taps.iter().filter(|p| (p[0] >= 0.0) == (q & 1 == 0) && (p[1] >= 0.0) == (q & 2 == 0)).count();
                assert!(inside * 8 >= n as usize, "{n} taps: quadrant {q} holds {inside}");
            }
            let closest = (0..taps.len())
                .flat_map(|i| (0..i).map(move |j| (i, j)))
                .map(|(i, j)| ((taps[i][0] - taps[j][0]).powi(2) + (taps[i][1] - taps[j][1]).powi(2)).sqrt())
                .fold(f32::INFINITY, f32::min);
            assert!(closest > 0.5 / (n as f32).sqrt(), "{n} taps: two within {closest}");
        }
    }
}

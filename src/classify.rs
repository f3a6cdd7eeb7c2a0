//! The hybrid-shadows classifier (`Context::record_classify`): from the engine's cascaded shadow maps it decides
//! which pixels are surely lit or surely shadowed, prefills the hit mask with those verdicts, and lists the 8x4
//! tiles whose other pixels need a shadow ray, with the ray interval the blockers bound. The engine then traces
//! only the listed pixels (one indirect dispatch) and runs the denoiser on the completed mask.
//!
//! Host side here: the buffers dnsr owns for the tile list and its counts, the pipelines, and the recording. The
//! dispatch description, the tables and the constant block are data (`passes::classify`); the pass is
//! shaders/classify.glsl; the CPU reference is `reference::classify`.

use crate::constants::FrameConstants;
use crate::dispatch::{HostImage, Rect};
use crate::error::{vk_check, Error, Result};
use crate::gpu::barrier;
use crate::gpu::descriptors::Binder;
use crate::gpu::loader::Vk;
use crate::gpu::memory::{self, Memory};
use crate::host::ResourceKind;
use crate::passes::bindings::{Binding, BindingTable, Resource, RESOURCE_COUNT};
use crate::passes::classify::{
    group_count, ClassifierBuffers, ClassifyConstants, ClassifyDispatch, CLASSIFY_COUNTS_BYTES, CLASSIFY_TILE_BYTES,
};
use crate::passes::variants::variant;
use crate::pipeline::PassPipeline;
use ash::vk;

/// Where the classify constants start in the classifier's uniform buffer (after the frame constants, at the
/// largest alignment Vulkan allows for uniform offsets).
const CLASSIFY_CONSTANTS_OFFSET: vk::DeviceSize = (std::mem::size_of::<FrameConstants>() as vk::DeviceSize).next_multiple_of(256);
const UNIFORM_BYTES: vk::DeviceSize = CLASSIFY_CONSTANTS_OFFSET + std::mem::size_of::<ClassifyConstants>() as vk::DeviceSize;

fn tile_capacity(size: [u32; 2]) -> u32 {
    size[0].div_ceil(crate::packing::TILE[0]) * size[1].div_ceil(crate::packing::TILE[1])
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
    pipelines: Vec<PassPipeline>,
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
    pub(crate) fn new(vk: &Vk, size: [u32; 2], push: bool, slots: u32, overrides: &[crate::create_info::ShaderOverride]) -> Result<Classifier> {
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

    fn create(&mut self, vk: &Vk, size: [u32; 2], push: bool, slots: u32, overrides: &[crate::create_info::ShaderOverride]) -> Result<()> {
        for (i, name) in PIPELINE_NAMES.into_iter().enumerate() {
            let engine = overrides.iter().find(|o| o.variant == name);
            self.engine_decodes[i] = engine.is_some();
            // PassPipeline::new checks both constants blocks' sizes against the host's.
            self.pipelines.push(PassPipeline::new(vk, name, engine.map_or(variant(name).spirv, |o| &o.spirv[..]), push)?);
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
            let layouts = [self.pipelines[0].vulkan.set_layout, self.pipelines[1].vulkan.set_layout];
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
        let descriptors = || pipeline.descriptors(&table, vk::Sampler::null());
        binder.write(dev, set, descriptors);
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
        let groups = group_count([rect.width, rect.height]);
        unsafe { dev.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline.vulkan.for_frame(0)) };
        binder.bind(dev, cmd, &pipeline.vulkan, descriptors, set);
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

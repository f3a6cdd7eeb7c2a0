//! The device's copy bandwidth: shaders/bench/copy.comp copies one storage buffer into another; bytes moved
//! (read + write) over the GPU time between two timestamps, median of several runs.

use super::stats::median;
use dnsr::ash::vk;
use dnsr::testing::gpu::Gpu;

static SPIRV: &[u8] = include_bytes!("../../../shaders/bench/copy.spv");
const GROUP: u64 = 256;
const ELEMENT: u64 = 16;

pub struct CopyResult {
    /// Bytes of each buffer (the copy reads this many and writes this many).
    pub buffer_bytes: u64,
    /// Dispatches per run (the buffers are bound in chunks within maxStorageBufferRange).
    pub chunks: u64,
    /// GPU milliseconds of each timed run.
    pub runs_ms: Vec<f64>,
}

impl CopyResult {
    pub fn moved_bytes(&self) -> f64 {
        2.0 * self.buffer_bytes as f64
    }
    pub fn median_ms(&self) -> f64 {
        median(&self.runs_ms)
    }
    /// Read + write bytes per second of the median run.
    pub fn bytes_per_s(&self) -> f64 {
        self.moved_bytes() / (self.median_ms() * 1e-3)
    }
    pub fn gbps(&self, ms: f64) -> f64 {
        self.moved_bytes() / (ms * 1e-3) / 1e9
    }
}

struct Buffer {
    buffer: vk::Buffer,
    memory: vk::DeviceMemory,
}

fn device_buffer(gpu: &Gpu, bytes: u64) -> Result<Buffer, String> {
    let d = &gpu.device;
    let info = vk::BufferCreateInfo::default()
        .size(bytes)
        .usage(vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST);
    let buffer = unsafe { d.create_buffer(&info, None) }.map_err(|e| format!("vkCreateBuffer ({bytes} bytes): {e}"))?;
    let req = unsafe { d.get_buffer_memory_requirements(buffer) };
    let props = unsafe { gpu.instance.get_physical_device_memory_properties(gpu.physical_device) };
    let index = (0..props.memory_type_count)
        .find(|&i| {
            req.memory_type_bits & (1 << i) != 0
                && props.memory_types[i as usize].property_flags.contains(vk::MemoryPropertyFlags::DEVICE_LOCAL)
        })
        .ok_or("no device-local memory type for the copy buffers")?;
    let alloc = vk::MemoryAllocateInfo::default().allocation_size(req.size).memory_type_index(index);
    let memory = unsafe { d.allocate_memory(&alloc, None) }.map_err(|e| {
        unsafe { d.destroy_buffer(buffer, None) };
        format!("vkAllocateMemory ({} bytes): {e}", req.size)
    })?;
    unsafe { d.bind_buffer_memory(buffer, memory, 0) }.map_err(|e| format!("vkBindBufferMemory: {e}"))?;
    Ok(Buffer { buffer, memory })
}

/// Copies `buffer_bytes` (rounded down to whole 16-byte elements) `runs` times after one untimed run.
pub fn measure(gpu: &Gpu, buffer_bytes: u64, runs: usize) -> Result<CopyResult, String> {
    let d = &gpu.device;
    let props = unsafe { gpu.instance.get_physical_device_properties(gpu.physical_device) };
    let limits = props.limits;
    let families = unsafe { gpu.instance.get_physical_device_queue_family_properties(gpu.physical_device) };
    let valid_bits = families[gpu.queue_family as usize].timestamp_valid_bits;
    if valid_bits == 0 {
        return Err("the queue has no timestamps".into());
    }
    let valid_mask = if valid_bits >= 64 { u64::MAX } else { (1u64 << valid_bits) - 1 };

    // Chunks: within maxStorageBufferRange, offsets aligned for storage buffers, whole groups.
    let align = limits.min_storage_buffer_offset_alignment.max(GROUP * ELEMENT);
    let max_chunk = (limits.max_storage_buffer_range as u64 / align * align).max(align);
    let bytes = (buffer_bytes / align * align).max(align);
    let chunk = bytes.min(max_chunk);
    let chunks = bytes.div_ceil(chunk);

    let src = device_buffer(gpu, bytes)?;
    let dst = device_buffer(gpu, bytes)?;
    let words = ash_words(SPIRV)?;
    let module = unsafe { d.create_shader_module(&vk::ShaderModuleCreateInfo::default().code(&words), None) }
        .map_err(|e| format!("copy shader: {e}"))?;
    let storage = |b: u32| {
        vk::DescriptorSetLayoutBinding::default()
            .binding(b)
            .descriptor_type(vk::DescriptorType::STORAGE_BUFFER)
            .descriptor_count(1)
            .stage_flags(vk::ShaderStageFlags::COMPUTE)
    };
    let bindings = [storage(0), storage(1)];
    let set_layout = unsafe { d.create_descriptor_set_layout(&vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings), None) }
        .map_err(|e| format!("set layout: {e}"))?;
    let push = vk::PushConstantRange::default().stage_flags(vk::ShaderStageFlags::COMPUTE).size(4);
    let layouts = [set_layout];
    let layout = unsafe {
        d.create_pipeline_layout(
            &vk::PipelineLayoutCreateInfo::default().set_layouts(&layouts).push_constant_ranges(std::slice::from_ref(&push)),
            None,
        )
    }
    .map_err(|e| format!("pipeline layout: {e}"))?;
    let stage = vk::PipelineShaderStageCreateInfo::default().stage(vk::ShaderStageFlags::COMPUTE).module(module).name(c"main");
    let pipeline = unsafe {
        d.create_compute_pipelines(vk::PipelineCache::null(), &[vk::ComputePipelineCreateInfo::default().stage(stage).layout(layout)], None)
    }
    .map_err(|(_, e)| format!("copy pipeline: {e}"))?[0];
    let sizes = [vk::DescriptorPoolSize { ty: vk::DescriptorType::STORAGE_BUFFER, descriptor_count: 2 * chunks as u32 }];
    let pool = unsafe { d.create_descriptor_pool(&vk::DescriptorPoolCreateInfo::default().max_sets(chunks as u32).pool_sizes(&sizes), None) }
        .map_err(|e| format!("descriptor pool: {e}"))?;
    let set_layouts = vec![set_layout; chunks as usize];
    let sets = unsafe { d.allocate_descriptor_sets(&vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&set_layouts)) }
        .map_err(|e| format!("descriptor sets: {e}"))?;
    for (k, &set) in sets.iter().enumerate() {
        let offset = k as u64 * chunk;
        let range = chunk.min(bytes - offset);
        let infos = [
            vk::DescriptorBufferInfo { buffer: src.buffer, offset, range },
            vk::DescriptorBufferInfo { buffer: dst.buffer, offset, range },
        ];
        let writes = [0, 1].map(|b| {
            vk::WriteDescriptorSet::default()
                .dst_set(set)
                .dst_binding(b)
                .descriptor_type(vk::DescriptorType::STORAGE_BUFFER)
                .buffer_info(std::slice::from_ref(&infos[b as usize]))
        });
        unsafe { d.update_descriptor_sets(&writes, &[]) };
    }
    let queries = unsafe { d.create_query_pool(&vk::QueryPoolCreateInfo::default().query_type(vk::QueryType::TIMESTAMP).query_count(2), None) }
        .map_err(|e| format!("query pool: {e}"))?;

    let barrier = |cmd, src_stage, src_access| unsafe {
        let b = vk::MemoryBarrier::default()
            .src_access_mask(src_access)
            .dst_access_mask(vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE);
        d.cmd_pipeline_barrier(cmd, src_stage, vk::PipelineStageFlags::COMPUTE_SHADER, vk::DependencyFlags::empty(), &[b], &[], &[]);
    };
    let cmd = gpu.command_buffer();
    gpu.submit_with(cmd, |cmd| unsafe {
        d.cmd_fill_buffer(cmd, src.buffer, 0, vk::WHOLE_SIZE, 0x3F80_0000);
        barrier(cmd, vk::PipelineStageFlags::TRANSFER, vk::AccessFlags::TRANSFER_WRITE);
    });
    let mut runs_ms = Vec::with_capacity(runs);
    for run in 0..=runs {
        gpu.submit_with(cmd, |cmd| unsafe {
            d.cmd_reset_query_pool(cmd, queries, 0, 2);
            // The previous run's writes to the destination before this run's.
            barrier(cmd, vk::PipelineStageFlags::COMPUTE_SHADER, vk::AccessFlags::SHADER_WRITE);
            d.cmd_bind_pipeline(cmd, vk::PipelineBindPoint::COMPUTE, pipeline);
            d.cmd_write_timestamp(cmd, vk::PipelineStageFlags::BOTTOM_OF_PIPE, queries, 0);
            for (k, &set) in sets.iter().enumerate() {
                let count = (chunk.min(bytes - k as u64 * chunk) / ELEMENT) as u32;
                let groups = (count as u64).div_ceil(GROUP);
                let x = groups.min(32768);
                d.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, layout, 0, &[set], &[]);
                d.cmd_push_constants(cmd, layout, vk::ShaderStageFlags::COMPUTE, 0, &count.to_le_bytes());
                d.cmd_dispatch(cmd, x as u32, groups.div_ceil(x) as u32, 1);
            }
            d.cmd_write_timestamp(cmd, vk::PipelineStageFlags::BOTTOM_OF_PIPE, queries, 1);
        });
        let mut stamps = [0u64; 2];
        unsafe { d.get_query_pool_results(queries, 0, &mut stamps, vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT) }
            .map_err(|e| format!("copy timestamps: {e}"))?;
        let ms = (stamps[1] & valid_mask).wrapping_sub(stamps[0] & valid_mask) as f64 * limits.timestamp_period as f64 * 1e-6;
        if run > 0 {
            runs_ms.push(ms);
        }
    }
    gpu.free_command_buffer(cmd);
    unsafe {
        d.destroy_query_pool(queries, None);
        d.destroy_descriptor_pool(pool, None);
        d.destroy_pipeline(pipeline, None);
        d.destroy_pipeline_layout(layout, None);
        d.destroy_descriptor_set_layout(set_layout, None);
        d.destroy_shader_module(module, None);
        for b in [&src, &dst] {
            d.destroy_buffer(b.buffer, None);
            d.free_memory(b.memory, None);
        }
    }
    Ok(CopyResult { buffer_bytes: bytes, chunks, runs_ms })
}

fn ash_words(bytes: &[u8]) -> Result<Vec<u32>, String> {
    dnsr::ash::util::read_spv(&mut std::io::Cursor::new(bytes)).map_err(|e| format!("copy.spv: {e}"))
}

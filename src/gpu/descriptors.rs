//! Descriptor binding without per-frame allocation: push descriptors when the host enabled them, otherwise a
//! cache of immutable descriptor sets keyed by what they point at (a set is written once and never updated, so
//! it can never be changed under a command buffer still in flight).

use crate::error::{vk_check, Error, Result};
use crate::gpu::loader::Vk;
use crate::gpu::shader::Pipeline;
use crate::passes::bindings::{Binding, BindingTable, Resource};
use ash::vk;

/// Most bindings any pass declares.
pub(crate) const MAX_BINDINGS: usize = 16;
/// Descriptor sets the cache holds before it reports `Error::DescriptorCacheFull`.
pub(crate) const CACHE_CAPACITY: u32 = 256;

type Key = [Binding; MAX_BINDINGS];

struct Entry {
    set_layout: vk::DescriptorSetLayout,
    key: Key,
    set: vk::DescriptorSet,
}

pub(crate) struct Cache {
    pool: vk::DescriptorPool,
    entries: Vec<Entry>,
}

pub(crate) enum Binder {
    Push(ash::khr::push_descriptor::DeviceFn),
    Cache(Cache),
}

fn key_of(pipeline: &Pipeline, table: &BindingTable) -> Key {
    let mut key = [Binding::default(); MAX_BINDINGS];
    for (slot, b) in key.iter_mut().zip(&pipeline.interface.bindings) {
        *slot = table[b.resource as usize];
    }
    key
}

/// Calls `f` with the descriptor writes of `pipeline` for `table` (dst_set left null).
fn with_writes<R>(pipeline: &Pipeline, table: &BindingTable, sampler: vk::Sampler, f: impl FnOnce(&[vk::WriteDescriptorSet]) -> R) -> R {
    let bindings = &pipeline.interface.bindings;
    let mut images = [vk::DescriptorImageInfo::default(); MAX_BINDINGS];
    let mut buffers = [vk::DescriptorBufferInfo::default(); MAX_BINDINGS];
    for (i, b) in bindings.iter().enumerate() {
        let bound = table[b.resource as usize];
        images[i] = vk::DescriptorImageInfo { sampler, image_view: bound.view, image_layout: bound.layout };
        buffers[i] = vk::DescriptorBufferInfo { buffer: bound.buffer, offset: 0, range: vk::WHOLE_SIZE };
    }
    let mut writes = [vk::WriteDescriptorSet::default(); MAX_BINDINGS];
    for (i, b) in bindings.iter().enumerate() {
        let w = vk::WriteDescriptorSet::default().dst_binding(b.binding).descriptor_type(b.descriptor_type);
        writes[i] = if b.resource == Resource::Constants {
            w.buffer_info(std::slice::from_ref(&buffers[i]))
        } else {
            w.image_info(std::slice::from_ref(&images[i]))
        };
    }
    f(&writes[..bindings.len()])
}

impl Binder {
    pub(crate) fn new(vk: &Vk, push: Option<ash::khr::push_descriptor::DeviceFn>) -> Result<Binder> {
        if let Some(push) = push {
            return Ok(Binder::Push(push));
        }
        let sizes = [
            (vk::DescriptorType::SAMPLED_IMAGE, 8),
            (vk::DescriptorType::STORAGE_IMAGE, 6),
            (vk::DescriptorType::COMBINED_IMAGE_SAMPLER, 1),
            (vk::DescriptorType::UNIFORM_BUFFER, 1),
        ]
        .map(|(ty, per_set)| vk::DescriptorPoolSize { ty, descriptor_count: per_set * CACHE_CAPACITY });
        let info = vk::DescriptorPoolCreateInfo::default().max_sets(CACHE_CAPACITY).pool_sizes(&sizes);
        let pool = vk_check("vkCreateDescriptorPool", unsafe { vk.device.create_descriptor_pool(&info, vk.alloc()) })?;
        vk.name(pool, "dnsr.descriptor_cache");
        Ok(Binder::Cache(Cache { pool, entries: Vec::with_capacity(CACHE_CAPACITY as usize) }))
    }

    /// Everything that can fail, done before any command is recorded: returns the set to bind (null with push
    /// descriptors).
    pub(crate) fn prepare(
        &mut self,
        device: &ash::Device,
        pipeline: &Pipeline,
        table: &BindingTable,
        sampler: vk::Sampler,
    ) -> Result<vk::DescriptorSet> {
        let Binder::Cache(cache) = self else { return Ok(vk::DescriptorSet::null()) };
        let key = key_of(pipeline, table);
        if let Some(e) = cache.entries.iter().find(|e| e.set_layout == pipeline.set_layout && e.key == key) {
            return Ok(e.set);
        }
        if cache.entries.len() >= CACHE_CAPACITY as usize {
            return Err(Error::DescriptorCacheFull);
        }
        let info = vk::DescriptorSetAllocateInfo::default()
            .descriptor_pool(cache.pool)
            .set_layouts(std::slice::from_ref(&pipeline.set_layout));
        let set = match unsafe { device.allocate_descriptor_sets(&info) } {
            Ok(sets) => sets[0],
            Err(vk::Result::ERROR_OUT_OF_POOL_MEMORY | vk::Result::ERROR_FRAGMENTED_POOL) => {
                return Err(Error::DescriptorCacheFull);
            }
            Err(result) => return Err(Error::Vulkan { call: "vkAllocateDescriptorSets", result }),
        };
        with_writes(pipeline, table, sampler, |writes| {
            let writes: [vk::WriteDescriptorSet; MAX_BINDINGS] = std::array::from_fn(|i| match writes.get(i) {
                Some(w) => w.dst_set(set),
                None => vk::WriteDescriptorSet::default(),
            });
            unsafe { device.update_descriptor_sets(&writes[..pipeline.interface.bindings.len()], &[]) };
        });
        cache.entries.push(Entry { set_layout: pipeline.set_layout, key, set });
        Ok(set)
    }

    /// Records the binding of `table` (or the prepared `set`) for `pipeline`.
    pub(crate) fn bind(
        &self,
        device: &ash::Device,
        cmd: vk::CommandBuffer,
        pipeline: &Pipeline,
        table: &BindingTable,
        sampler: vk::Sampler,
        set: vk::DescriptorSet,
    ) {
        match self {
            Binder::Push(push) => with_writes(pipeline, table, sampler, |writes| unsafe {
                (push.cmd_push_descriptor_set_khr)(
                    cmd,
                    vk::PipelineBindPoint::COMPUTE,
                    pipeline.layout,
                    0,
                    writes.len() as u32,
                    writes.as_ptr(),
                )
            }),
            Binder::Cache(_) => unsafe {
                device.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, pipeline.layout, 0, &[set], &[])
            },
        }
    }

    /// Forgets every cached set. The caller guarantees the GPU no longer uses them.
    pub(crate) fn clear(&mut self, device: &ash::Device) -> Result<()> {
        if let Binder::Cache(cache) = self {
            vk_check("vkResetDescriptorPool", unsafe {
                device.reset_descriptor_pool(cache.pool, vk::DescriptorPoolResetFlags::empty())
            })?;
            cache.entries.clear();
        }
        Ok(())
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        if let Binder::Cache(cache) = self {
            unsafe { vk.device.destroy_descriptor_pool(cache.pool, vk.alloc()) };
            cache.pool = vk::DescriptorPool::null();
        }
    }
}

//! Descriptor binding that never holds a host handle past its frame: push descriptors when the host enabled them,
//! otherwise a ring of descriptor sets per light, rewritten on every record.
//!
//! Why a ring and not a cache: the host's image views are only borrowed for one frame. A render graph with
//! transient resources destroys its views after the frame and creates new ones, and the driver may hand back the
//! same handle values; a cache keyed on handles then binds sets that point at destroyed views. Writing a set is a
//! few microseconds, so every record writes the sets of one ring slot, and a slot is only rewritten after
//! `max_frames_in_flight` more records of that light, by which time the host guarantees the GPU is done with it.

use crate::error::{vk_check, Result};
use crate::gpu::loader::Vk;
use crate::gpu::shader::Pipeline;
use crate::passes::bindings::BindingTable;
use crate::passes::{Role, MAX_PASSES};
use crate::settings::MAX_FILTER_PASSES;
use ash::vk;

/// Most bindings any pass declares (the final light-slot variant: 29). At most 32, the least
/// `maxPushDescriptors` a device with push descriptors has.
pub(crate) const MAX_BINDINGS: usize = 32;

/// The descriptor sets one record writes, one per pipeline role: every pass of the longest frame, the single
/// pass of a one-pass frame, and the later passes of several lights (intermediate ones and the final one).
pub(crate) const SETS_PER_RECORD: usize = MAX_PASSES + MAX_FILTER_PASSES as usize;

/// The set of a ring slot that a pipeline role uses.
fn set_index(role: Role) -> usize {
    match role {
        Role::Prepare => 0,
        Role::Classification => 1,
        Role::Filter(pass) => 2 + pass as usize,
        Role::FilterFinal => MAX_PASSES - 1,
        Role::FilterOnly => MAX_PASSES,
        Role::FilterLights(pass) => MAX_PASSES + pass as usize,
        Role::FilterLightsFinal => SETS_PER_RECORD - 1,
    }
}

/// Every role, in set order: every filter pass but the last can be an intermediate pass, one final pass after
/// them, the single pass of a one-pass frame, then the later passes of several lights alike.
pub(crate) fn roles() -> [Role; SETS_PER_RECORD] {
    std::array::from_fn(|i| match i {
        0 => Role::Prepare,
        1 => Role::Classification,
        _ if i == MAX_PASSES - 1 => Role::FilterFinal,
        _ if i == MAX_PASSES => Role::FilterOnly,
        _ if i == SETS_PER_RECORD - 1 => Role::FilterLightsFinal,
        _ if i > MAX_PASSES => Role::FilterLights((i - MAX_PASSES) as u32),
        _ => Role::Filter(i as u32 - 2),
    })
}

/// The pipelines whose layouts the sets of one ring slot have, in `roles()` order.
pub(crate) type RoleLayouts<'a> = [&'a Pipeline; SETS_PER_RECORD];

pub(crate) struct Ring {
    pool: vk::DescriptorPool,
    /// `slots` entries per light, light-major.
    sets: Vec<[vk::DescriptorSet; SETS_PER_RECORD]>,
    slots: u32,
    /// Per light: the slot its next record writes.
    next: Vec<u32>,
}

pub(crate) enum Binder {
    Push(ash::khr::push_descriptor::DeviceFn),
    Ring(Ring),
}

/// Calls `f` with the descriptor writes of `pipeline` for `table` (dst_set left null).
fn with_writes<R>(pipeline: &Pipeline, table: &BindingTable, sampler: vk::Sampler, f: impl FnOnce(&[vk::WriteDescriptorSet]) -> R) -> R {
    let bindings = &pipeline.interface.bindings;
    let mut images = [vk::DescriptorImageInfo::default(); MAX_BINDINGS];
    let mut buffers = [vk::DescriptorBufferInfo::default(); MAX_BINDINGS];
    let mut texels = [vk::BufferView::null(); MAX_BINDINGS];
    for (i, b) in bindings.iter().enumerate() {
        let bound = table[b.resource as usize];
        images[i] = vk::DescriptorImageInfo { sampler, image_view: bound.view, image_layout: bound.layout };
        buffers[i] = vk::DescriptorBufferInfo { buffer: bound.buffer, offset: bound.offset, range: bound.range };
        texels[i] = bound.texel;
    }
    let mut writes = [vk::WriteDescriptorSet::default(); MAX_BINDINGS];
    for (i, b) in bindings.iter().enumerate() {
        let w = vk::WriteDescriptorSet::default().dst_binding(b.binding).descriptor_type(b.descriptor_type);
        writes[i] = match b.descriptor_type {
            vk::DescriptorType::UNIFORM_BUFFER => w.buffer_info(std::slice::from_ref(&buffers[i])),
            vk::DescriptorType::STORAGE_TEXEL_BUFFER => w.texel_buffer_view(std::slice::from_ref(&texels[i])),
            _ => w.image_info(std::slice::from_ref(&images[i])),
        };
    }
    f(&writes[..bindings.len()])
}

impl Ring {
    fn new(vk: &Vk, layouts: RoleLayouts, lights: u32, slots: u32) -> Result<Ring> {
        let records = lights * slots;
        // Pool sizes from the reflected interfaces, so a shader change cannot outgrow the pool.
        let mut sizes: Vec<vk::DescriptorPoolSize> = Vec::new();
        for binding in layouts.iter().flat_map(|p| &p.interface.bindings) {
            match sizes.iter_mut().find(|s| s.ty == binding.descriptor_type) {
                Some(s) => s.descriptor_count += records,
                None => sizes.push(vk::DescriptorPoolSize { ty: binding.descriptor_type, descriptor_count: records }),
            }
        }
        let max_sets = records * SETS_PER_RECORD as u32;
        let info = vk::DescriptorPoolCreateInfo::default().max_sets(max_sets).pool_sizes(&sizes);
        let pool = vk_check("vkCreateDescriptorPool", unsafe { vk.device.create_descriptor_pool(&info, vk.alloc()) })?;
        vk.name(pool, "dnsr.descriptor_ring");
        let mut ring = Ring { pool, sets: Vec::with_capacity(records as usize), slots, next: vec![0; lights as usize] };
        let set_layouts = layouts.map(|p| p.set_layout);
        let info = vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&set_layouts);
        for _ in 0..records {
            match unsafe { vk.device.allocate_descriptor_sets(&info) } {
                Ok(sets) => ring.sets.push(std::array::from_fn(|i| sets[i])),
                Err(result) => {
                    ring.destroy(vk);
                    return Err(crate::error::Error::Vulkan { call: "vkAllocateDescriptorSets", result });
                }
            }
        }
        Ok(ring)
    }

    fn destroy(&mut self, vk: &Vk) {
        unsafe { vk.device.destroy_descriptor_pool(self.pool, vk.alloc()) };
        self.pool = vk::DescriptorPool::null();
        self.sets.clear();
    }
}

/// The descriptor sets of one record (all null with push descriptors).
#[derive(Clone, Copy)]
pub(crate) struct RecordSets([vk::DescriptorSet; SETS_PER_RECORD]);

impl RecordSets {
    pub(crate) fn get(&self, role: Role) -> vk::DescriptorSet {
        self.0[set_index(role)]
    }
}

impl Binder {
    /// Push descriptors when `push` is given; otherwise `slots` ring slots for each of `lights`.
    pub(crate) fn new(
        vk: &Vk,
        push: Option<ash::khr::push_descriptor::DeviceFn>,
        layouts: RoleLayouts,
        lights: u32,
        slots: u32,
    ) -> Result<Binder> {
        match push {
            Some(push) => Ok(Binder::Push(push)),
            None => Ok(Binder::Ring(Ring::new(vk, layouts, lights, slots)?)),
        }
    }

    /// Takes the next ring slot of `light` for one record (a dispatch of several lights uses the sets of its first
    /// light's slot). Nothing is written yet; `write` fills each set the
    /// record uses. Infallible, so a record that reaches this point always completes.
    pub(crate) fn next_record(&mut self, light: u32) -> RecordSets {
        match self {
            Binder::Push(_) => RecordSets([vk::DescriptorSet::null(); SETS_PER_RECORD]),
            Binder::Ring(ring) => {
                let slot = ring.next[light as usize];
                ring.next[light as usize] = (slot + 1) % ring.slots;
                RecordSets(ring.sets[(light * ring.slots + slot) as usize])
            }
        }
    }

    /// Whether bindings are written into sets before recording (the ring), not pushed at bind time.
    pub(crate) fn writes_sets(&self) -> bool {
        matches!(self, Binder::Ring(_))
    }

    /// Writes `table` into `set` (a no-op with push descriptors, which are written at bind time).
    pub(crate) fn write(&self, device: &ash::Device, set: vk::DescriptorSet, pipeline: &Pipeline, table: &BindingTable, sampler: vk::Sampler) {
        if let Binder::Ring(_) = self {
            with_writes(pipeline, table, sampler, |writes| {
                let writes: [vk::WriteDescriptorSet; MAX_BINDINGS] = std::array::from_fn(|i| match writes.get(i) {
                    Some(w) => w.dst_set(set),
                    None => vk::WriteDescriptorSet::default(),
                });
                unsafe { device.update_descriptor_sets(&writes[..pipeline.interface.bindings.len()], &[]) };
            });
        }
    }

    /// Records the binding of `table` (or the written `set`) for `pipeline`.
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
            Binder::Ring(_) => unsafe {
                device.cmd_bind_descriptor_sets(cmd, vk::PipelineBindPoint::COMPUTE, pipeline.layout, 0, &[set], &[])
            },
        }
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        if let Binder::Ring(ring) = self {
            ring.destroy(vk);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_role_has_its_own_set() {
        for (i, role) in roles().into_iter().enumerate() {
            assert_eq!(set_index(role), i, "{role:?}");
        }
    }
}

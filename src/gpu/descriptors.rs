//! Descriptor binding that never holds a host handle past its frame: push descriptors when the host enabled them,
//! otherwise a ring of descriptor sets per light, rewritten on every record.
//!
//! Why a ring and not a cache: the host's image views are only borrowed for one frame. A render graph with
//! transient resources destroys its views after the frame and creates new ones, and the driver may hand back the
//! same handle values; a cache keyed on handles then binds sets that point at destroyed views. Writing a set is a
//! few microseconds, so every record writes the sets of one ring slot, and a slot is only rewritten after
//! `max_frames_in_flight` more records of that light, by which time the host guarantees the GPU is done with it.
//!
//! What a record's sets are for is the caller's: it gives the pipelines whose layouts one record's sets have, and
//! picks a record's set by its place in that list.

use crate::error::{vk_check, Result};
use crate::gpu::loader::Vk;
use crate::gpu::shader::Pipeline;
use ash::vk;

/// Most bindings any pass declares (the final light-slot variant: 29). At most 32, the least
/// `maxPushDescriptors` a device with push descriptors has.
pub(crate) const MAX_BINDINGS: usize = 32;

/// One descriptor of a dispatch: its binding number and type, and what it is bound to (the image for image types,
/// the buffer range for a uniform buffer, the view for a texel buffer).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Descriptor {
    pub binding: u32,
    pub descriptor_type: vk::DescriptorType,
    pub image: vk::DescriptorImageInfo,
    pub buffer: vk::DescriptorBufferInfo,
    pub texel: vk::BufferView,
}

/// The descriptors of one dispatch, in a fixed array: the recording path allocates nothing.
#[derive(Clone, Copy)]
pub(crate) struct Descriptors {
    all: [Descriptor; MAX_BINDINGS],
    count: usize,
}

impl FromIterator<Descriptor> for Descriptors {
    /// Panics beyond MAX_BINDINGS descriptors (a pipeline's layout has no more).
    fn from_iter<I: IntoIterator<Item = Descriptor>>(iter: I) -> Descriptors {
        let mut out = Descriptors { all: [Descriptor::default(); MAX_BINDINGS], count: 0 };
        for d in iter {
            out.all[out.count] = d;
            out.count += 1;
        }
        out
    }
}

impl std::ops::Deref for Descriptors {
    type Target = [Descriptor];
    fn deref(&self) -> &[Descriptor] {
        &self.all[..self.count]
    }
}

pub(crate) struct Ring {
    pool: vk::DescriptorPool,
    /// `slots` records per light, light-major, each `sets_per_record` sets.
    sets: Vec<vk::DescriptorSet>,
    sets_per_record: usize,
    slots: u32,
    /// Per light: the slot its next record writes.
    next: Vec<u32>,
}

pub(crate) enum Binder {
    Push(ash::khr::push_descriptor::DeviceFn),
    Ring(Ring),
}

/// Calls `f` with the descriptor writes of `descriptors` (dst_set left null).
fn with_writes<R>(descriptors: &[Descriptor], f: impl FnOnce(&[vk::WriteDescriptorSet]) -> R) -> R {
    let mut writes = [vk::WriteDescriptorSet::default(); MAX_BINDINGS];
    for (i, d) in descriptors.iter().enumerate() {
        let w = vk::WriteDescriptorSet::default().dst_binding(d.binding).descriptor_type(d.descriptor_type);
        writes[i] = match d.descriptor_type {
            vk::DescriptorType::UNIFORM_BUFFER => w.buffer_info(std::slice::from_ref(&d.buffer)),
            vk::DescriptorType::STORAGE_TEXEL_BUFFER => w.texel_buffer_view(std::slice::from_ref(&d.texel)),
            _ => w.image_info(std::slice::from_ref(&d.image)),
        };
    }
    f(&writes[..descriptors.len()])
}

impl Ring {
    fn new(vk: &Vk, layouts: &[&Pipeline], lights: u32, slots: u32) -> Result<Ring> {
        let records = lights * slots;
        // Pool sizes from the pipelines' layouts, so a shader change cannot outgrow the pool.
        let mut sizes: Vec<vk::DescriptorPoolSize> = Vec::new();
        for &ty in layouts.iter().flat_map(|p| &p.descriptor_types) {
            match sizes.iter_mut().find(|s| s.ty == ty) {
                Some(s) => s.descriptor_count += records,
                None => sizes.push(vk::DescriptorPoolSize { ty, descriptor_count: records }),
            }
        }
        let max_sets = records * layouts.len() as u32;
        let info = vk::DescriptorPoolCreateInfo::default().max_sets(max_sets).pool_sizes(&sizes);
        let pool = vk_check("vkCreateDescriptorPool", unsafe { vk.device.create_descriptor_pool(&info, vk.alloc()) })?;
        vk.name(pool, "dnsr.descriptor_ring");
        let sets_per_record = layouts.len();
        let capacity = records as usize * sets_per_record;
        let mut ring = Ring { pool, sets: Vec::with_capacity(capacity), sets_per_record, slots, next: vec![0; lights as usize] };
        let set_layouts: Vec<vk::DescriptorSetLayout> = layouts.iter().map(|p| p.set_layout).collect();
        let info = vk::DescriptorSetAllocateInfo::default().descriptor_pool(pool).set_layouts(&set_layouts);
        for _ in 0..records {
            match unsafe { vk.device.allocate_descriptor_sets(&info) } {
                Ok(sets) => ring.sets.extend(sets),
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

/// The descriptor sets of one record: where they start in the ring (none with push descriptors).
#[derive(Clone, Copy)]
pub(crate) struct RecordSets(Option<usize>);

impl Binder {
    /// Push descriptors when `push` is given; otherwise `slots` ring slots for each of `lights`, each slot one set
    /// per pipeline of `layouts` (with its set layout).
    pub(crate) fn new(
        vk: &Vk,
        push: Option<ash::khr::push_descriptor::DeviceFn>,
        layouts: &[&Pipeline],
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
            Binder::Push(_) => RecordSets(None),
            Binder::Ring(ring) => {
                let slot = ring.next[light as usize];
                ring.next[light as usize] = (slot + 1) % ring.slots;
                RecordSets(Some((light * ring.slots + slot) as usize * ring.sets_per_record))
            }
        }
    }

    /// Set `index` (the place of its pipeline in the `layouts` of `new`) of a record; null with push descriptors.
    pub(crate) fn set(&self, record: RecordSets, index: usize) -> vk::DescriptorSet {
        match (self, record.0) {
            (Binder::Ring(ring), Some(first)) => {
                debug_assert!(index < ring.sets_per_record);
                ring.sets[first + index]
            }
            _ => vk::DescriptorSet::null(),
        }
    }

    /// Whether bindings are written into sets before recording (the ring), not pushed at bind time.
    pub(crate) fn writes_sets(&self) -> bool {
        matches!(self, Binder::Ring(_))
    }

    /// Writes the descriptors into `set` (a no-op with push descriptors, which are written at bind time).
    /// `descriptors` is only called where they are written.
    pub(crate) fn write(&self, device: &ash::Device, set: vk::DescriptorSet, descriptors: impl FnOnce() -> Descriptors) {
        if let Binder::Ring(_) = self {
            let descriptors = descriptors();
            with_writes(&descriptors, |writes| {
                let writes: [vk::WriteDescriptorSet; MAX_BINDINGS] = std::array::from_fn(|i| match writes.get(i) {
                    Some(w) => w.dst_set(set),
                    None => vk::WriteDescriptorSet::default(),
                });
                unsafe { device.update_descriptor_sets(&writes[..descriptors.len()], &[]) };
            });
        }
    }

    /// Records the binding of the descriptors (pushed) or of the written `set` for `pipeline`. `descriptors` is
    /// only called where they are pushed.
    pub(crate) fn bind(
        &self,
        device: &ash::Device,
        cmd: vk::CommandBuffer,
        pipeline: &Pipeline,
        descriptors: impl FnOnce() -> Descriptors,
        set: vk::DescriptorSet,
    ) {
        match self {
            Binder::Push(push) => with_writes(&descriptors(), |writes| unsafe {
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

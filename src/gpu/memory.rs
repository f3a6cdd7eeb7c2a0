//! Device memory for dnsr's resources: from the host's allocator when it gave one, else vkAllocateMemory.

use crate::error::{vk_check, Error, Result};
use crate::gpu::loader::Vk;
use crate::host::{GpuAllocation, ResourceKind};
use ash::vk;

/// Memory bound to one resource.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Memory {
    pub memory: vk::DeviceMemory,
    pub offset: vk::DeviceSize,
    /// Set when the host's allocator owns the memory.
    pub host: Option<GpuAllocation>,
}

fn memory_type(vk: &Vk, type_bits: u32) -> Result<u32> {
    let props = unsafe { vk.instance.get_physical_device_memory_properties(vk.physical_device) };
    let types = &props.memory_types[..props.memory_type_count as usize];
    let pick = |flags: vk::MemoryPropertyFlags| {
        types.iter().enumerate().position(|(i, t)| type_bits & (1 << i) != 0 && t.property_flags.contains(flags))
    };
    pick(vk::MemoryPropertyFlags::DEVICE_LOCAL)
        .or_else(|| pick(vk::MemoryPropertyFlags::empty()))
        .map(|i| i as u32)
        .ok_or(Error::Vulkan { call: "memory type selection", result: vk::Result::ERROR_OUT_OF_DEVICE_MEMORY })
}

/// Allocates device-local memory satisfying `req`.
pub(crate) fn allocate(vk: &Vk, req: vk::MemoryRequirements, kind: ResourceKind) -> Result<Memory> {
    if let Some(host) = &vk.hooks.gpu_memory {
        let a = host.allocate(&req, kind).map_err(|result| Error::Vulkan { call: "host GPU memory allocator", result })?;
        if a.memory == vk::DeviceMemory::null() || a.offset % req.alignment.max(1) != 0 {
            host.free(&a);
            return Err(Error::Vulkan { call: "host GPU memory allocator (null or misaligned)", result: vk::Result::ERROR_UNKNOWN });
        }
        return Ok(Memory { memory: a.memory, offset: a.offset, host: Some(a) });
    }
    let info = vk::MemoryAllocateInfo::default().allocation_size(req.size).memory_type_index(memory_type(vk, req.memory_type_bits)?);
    let memory = vk_check("vkAllocateMemory", unsafe { vk.device.allocate_memory(&info, vk.alloc()) })?;
    Ok(Memory { memory, offset: 0, host: None })
}

/// Releases memory from `allocate` (null-tolerant).
pub(crate) fn free(vk: &Vk, m: &mut Memory) {
    match (m.host.take(), &vk.hooks.gpu_memory) {
        (Some(a), Some(host)) => host.free(&a),
        _ => unsafe { vk.device.free_memory(m.memory, vk.alloc()) },
    }
    *m = Memory::default();
}

/// Refuses a context that needs more device memory than the device has, before anything is allocated: the
/// largest device-local heap's budget (VK_EXT_memory_budget, when the device supports it) or its size.
pub(crate) fn check_available(vk: &Vk, needed: u64) -> Result<()> {
    let has_budget = vk.supports_extension(ash::ext::memory_budget::NAME);
    let mut budget = vk::PhysicalDeviceMemoryBudgetPropertiesEXT::default();
    let memory = {
        let mut props = vk::PhysicalDeviceMemoryProperties2::default();
        if has_budget {
            props = props.push_next(&mut budget);
        }
        unsafe { vk.instance.get_physical_device_memory_properties2(vk.physical_device, &mut props) };
        props.memory_properties
    };
    let heaps = memory.memory_heaps_as_slice();
    let budget_of = |i: usize| {
        if has_budget && budget.heap_budget[i] > 0 {
            budget.heap_budget[i].saturating_sub(budget.heap_usage[i])
        } else {
            heaps[i].size
        }
    };
    let device_local = |i: &usize| heaps[*i].flags.contains(vk::MemoryHeapFlags::DEVICE_LOCAL);
    let available = (0..heaps.len()).filter(device_local).map(budget_of).max().or_else(|| (0..heaps.len()).map(budget_of).max()).unwrap_or(0);
    if needed > available {
        return Err(Error::OutOfDeviceMemory { needed, available });
    }
    Ok(())
}

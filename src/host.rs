//! Hooks through which the host owns what dnsr creates: its CPU allocator for Vulkan objects
//! (`VkAllocationCallbacks`), its GPU memory allocator (e.g. VMA) for dnsr's images and buffers, and debug names.

use ash::vk;
use std::ffi::CStr;
use std::sync::Arc;

/// What a piece of device memory is for, so a host allocator can pool by kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResourceKind {
    /// An internal image (history, moments, tiles, depth copy).
    Image,
    /// An internal image whose contents do not outlive one record (`ContextCreateInfo::alias_transient_memory`
    /// only; otherwise such images come as `Image`): the host may bind the same memory to its own resources too
    /// (memory aliasing), as that field says.
    TransientImage,
    /// The per-frame constants buffer.
    Buffer,
}

/// Device memory handed out by a host allocator: dnsr binds its resource at `memory` + `offset`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GpuAllocation {
    /// Memory object to bind to.
    pub memory: vk::DeviceMemory,
    /// Offset in bytes within `memory`; must satisfy the requirement's alignment.
    pub offset: vk::DeviceSize,
    /// The host's own handle for this allocation (e.g. a `VmaAllocation`), passed back to `free`.
    pub user_handle: u64,
}

/// A host-side GPU memory allocator. dnsr asks for device-local memory for each internal image and buffer.
pub trait GpuMemoryAllocator: Send + Sync {
    /// Allocates memory satisfying `requirements` (size, alignment, memory type bits).
    fn allocate(&self, requirements: &vk::MemoryRequirements, kind: ResourceKind) -> Result<GpuAllocation, vk::Result>;
    /// Frees an allocation returned by `allocate`, after dnsr destroyed the resource bound to it.
    fn free(&self, allocation: &GpuAllocation);
}

/// Receives a name for every Vulkan object dnsr creates (for debuggers and captures).
pub type DebugNamer = Arc<dyn Fn(vk::ObjectType, u64, &CStr) + Send + Sync>;

/// The host hooks of a context. All optional; the default lets dnsr use the driver's allocators.
#[derive(Clone, Default)]
pub struct HostHooks {
    /// CPU allocation callbacks passed to every vkCreate*/vkDestroy*/vkAllocateMemory dnsr calls. The callbacks
    /// and their user data must stay valid until the context is dropped.
    pub allocation_callbacks: Option<vk::AllocationCallbacks<'static>>,
    /// The host's GPU memory allocator; `None` = dnsr calls vkAllocateMemory itself.
    pub gpu_memory: Option<Arc<dyn GpuMemoryAllocator>>,
    /// Debug names for dnsr's objects.
    pub debug_names: Option<DebugNamer>,
}

impl std::fmt::Debug for HostHooks {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HostHooks")
            .field("allocation_callbacks", &self.allocation_callbacks.is_some())
            .field("gpu_memory", &self.gpu_memory.is_some())
            .field("debug_names", &self.debug_names.is_some())
            .finish()
    }
}

// SAFETY: VkAllocationCallbacks holds function pointers and a user pointer the host promises are usable from
// the threads it calls dnsr on; dnsr only passes them back to Vulkan.
unsafe impl Send for HostHooks {}
unsafe impl Sync for HostHooks {}

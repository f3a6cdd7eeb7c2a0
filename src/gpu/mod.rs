//! Vulkan plumbing: function loading through the host's entry points, pipelines from embedded SPIR-V with
//! layouts from reflection, internal images, barriers and descriptor binding.

pub(crate) mod barrier;
pub(crate) mod descriptors;
pub(crate) mod image;
pub(crate) mod loader;
pub(crate) mod memory;
pub(crate) mod reflect;
pub(crate) mod shader;
pub(crate) mod spirv_validity;

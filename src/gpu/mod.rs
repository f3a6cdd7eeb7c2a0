//! Vulkan plumbing: function loading through the host's entry points, pipelines with the layouts their callers
//! reflected, internal images, barriers and descriptor binding. It knows nothing of the passes, the classifier or
//! the settings (the crate docs' "Layers"): what it needs of them comes as parameters.

pub(crate) mod barrier;
pub(crate) mod descriptors;
pub(crate) mod image;
pub(crate) mod loader;
pub(crate) mod memory;
pub(crate) mod reflect;
pub(crate) mod shader;
pub(crate) mod spirv_validity;

//! dnsr: a ray-traced soft-shadow denoiser for Vulkan engines.
//!
//! The engine traces one jittered shadow ray per pixel, packs hits into 8x4-tile bitmasks, and calls
//! [`Context::record_shadows`] to record dnsr's compute passes (prepare, tile classification, a-trous filter)
//! into its own `VkCommandBuffer`. dnsr never submits, waits, or owns a queue, and never links the Vulkan
//! loader: every function is loaded through the host's `vkGetInstanceProcAddr` / `vkGetDeviceProcAddr`.
//!
//! # Layers
//!
//! The modules import one way, down (`cargo test layers` fails on an import upward, and on any cycle):
//!
//! - API, on top: `capi` (the C ABI) and `ffx` (the FidelityFX API over it; `capi` reaches it only through the
//!   setter that `ffx` registers, `capi::FFX_SET`).
//! - Contexts: `context` (the denoiser: pipelines, recording), `light` (a light's images), `classify` (the
//!   classifier's buffers and recording), `pipeline` and `interface` (a pass's pipeline and its reflected
//!   interface), `validate`, `timestamps`. They may import everything below.
//! - Vulkan plumbing: `gpu` (loading, memory, images, barriers, descriptors, pipelines, SPIR-V checks). Of the
//!   data it knows `error` and `host` only; binding numbers and types, descriptors and formats come as parameters.
//! - The CPU reference, `reference`: the data layer only.
//! - Data, at the bottom: `error`, `host`, `dispatch`, `glsl` (blocks with a GLSL twin), `packing` (the hit-mask
//!   tile and the moments' word, which settings bound their knobs by), `settings`, `create_info`, `state` (the state
//!   table: every internal image and the passes' accesses to it), `passes` (each pass's bindings, roles, group sizes
//!   and variants; `passes::classify` the classifier's tables and dispatch), `constants` (the frame's constants and
//!   the generated GLSL, from every table). No Vulkan object is made there; they use `ash::vk` types and one
//!   another, in this order.
//!
//! In full, bottom first, each module imports only those before it, so no cycle can form (the test reads this list):
//! `error`, `host`, `dispatch`, `glsl`, `packing`, `settings`, `create_info`, `state`, `passes`, `constants`, `gpu`,
//! `reference`, `interface`, `validate`, `timestamps`, `light`, `pipeline`, `classify`, `context`, `capi`, `ffx`,
//! `testing`, `tests`.
#![deny(missing_docs)]

pub mod capi;
mod classify;
mod constants;
mod context;
mod create_info;
mod dispatch;
mod error;
pub mod ffx;
mod glsl;
mod gpu;
mod host;
mod interface;
mod light;
mod packing;
mod passes;
mod pipeline;
pub mod reference;
mod settings;
mod state;
mod timestamps;
mod validate;

pub use ash;
pub use passes::classify::{
    ClassifierBuffers, ClassifyDispatch, ShadowCascade, CLASSIFY_COUNTS_BYTES, CLASSIFY_TAP_COUNTS, CLASSIFY_TILE_BYTES, MAX_CASCADES,
};
pub use context::{
    context_memory_requirements, memory_requirements, memory_requirements_for_input, persistent_memory_requirements, Context, MIN_API_VERSION,
};
pub use create_info::{
    ContextCreateInfo, DepthFlags, EnabledFeatures, Precision, ShaderOverride, ShadowInput, DEFAULT_MAX_FRAMES_IN_FLIGHT, MAX_FRAMES_IN_FLIGHT,
    MAX_LIGHT_COUNT,
};
pub use passes::variants::{shader_variants, ShaderVariantInfo, SHADER_COMPILE_ARGS};
pub use dispatch::{
    DebugView, EngineImage, HitMaskConvention, HostImage, HostSync, LightDispatch, Rect, ShadowsDispatch, ENGINE_BINDING_BASE, MAX_ENGINE_IMAGES,
    MAX_LIGHTS_PER_RECORD,
};
pub use error::{Error, ImageRole, Result};
pub use glam;
pub use host::{DebugNamer, GpuAllocation, GpuMemoryAllocator, HostHooks, ResourceKind};
pub use settings::{Preset, Settings, MAX_FILTER_PASSES};
/// The state table (src/state/table.rs), for tooling only: dnsr-bench derives its byte model from it. Not a stable
/// API.
#[doc(hidden)]
pub use state::table as state_table;
pub use timestamps::{ClassifierTimings, PassTimings};

#[cfg(any(test, feature = "demo"))]
#[doc(hidden)]
pub mod testing;

#[cfg(test)]
mod tests;

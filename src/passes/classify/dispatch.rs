//! What the engine hands one classifier dispatch (`Context::record_classify`) and the buffers it reads back: the
//! public description, plain data like `ShadowsDispatch`.

use super::MAX_CASCADES;
use crate::dispatch::{HitMaskConvention, HostImage, HostSync, Rect};
use ash::vk;
use glam::{Mat4, Vec3};

/// One shadow-map cascade.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowCascade {
    /// World position (w = 1) to (u, v, depth) of this cascade's shadow map: u, v in [0, 1] across its image
    /// (0, 0 the top-left texel corner), depth as its shadow map stores it. Must be affine (orthographic, last
    /// row 0 0 0 1), as a sun's cascades are. Column-major, column vectors (glam). A cascade given as the
    /// FidelityFX / "shadow matrix with per-cascade scale and offset" form is `translation(offset) *
    /// scale(scale) * shadow_matrix`.
    pub world_to_shadow: Mat4,
}

impl Default for ShadowCascade {
    fn default() -> Self {
        ShadowCascade { world_to_shadow: Mat4::IDENTITY }
    }
}

/// One frame of input of the classifier. Conventions as `ShadowsDispatch` (Vulkan NDC, column-major matrices).
#[derive(Clone, Copy, Debug)]
pub struct ClassifyDispatch {
    /// Depth, render size, in the context's depth convention (a `ShadowsDispatch::depth` format). Sampled.
    pub depth: HostImage,
    /// World-space normals, render size, decoded as `rgb * normals_unpack_mul + normals_unpack_add` (a
    /// `ShadowsDispatch::normals` format). A pixel whose normal faces away from the light is shadowed without a
    /// ray; an unusable (zero, NaN) normal leaves the decision to the cascades.
    pub normals: HostImage,
    /// Normal decode multiplier.
    pub normals_unpack_mul: f32,
    /// Normal decode offset.
    pub normals_unpack_add: f32,
    /// Current clip space -> world space (the space the cascades' matrices take).
    pub view_projection_inverse: Mat4,
    /// Current clip space -> view space (`ShadowsDispatch::projection_inverse`). dnsr's own classifier does not
    /// read it; an engine's classifier variant (`ContextCreateInfo::shader_overrides`) whose callbacks decode
    /// depth with it (`dnsr_get_projection_inverse`, e.g. from linear view depth) does.
    pub projection_inverse: Mat4,
    /// World-space direction from the surfaces toward the light (the sun); any length but zero.
    pub light_direction: Vec3,
    /// The light's angular diameter in radians (the sun: about 0.0093), in [0, pi): sets the blocker search
    /// radius (the widest penumbra a blocker between the receiver and the cascade's near plane can cast).
    pub light_angular_size: f32,
    /// How many of `cascades` (and of `cascade_images` or `cascade_array`'s layers) are used, 1..=4; the
    /// first cascade containing a pixel decides it, a pixel in none is traced.
    pub cascade_count: u32,
    /// The cascades, finest first.
    pub cascades: [ShadowCascade; MAX_CASCADES],
    /// Cascade i's shadow map as its own image (a 2D view, depth aspect, a `ShadowsDispatch::depth` format, any
    /// size, a depth read-only or shader read-only layout). Leave them null when `cascade_array` is given.
    pub cascade_images: [HostImage; MAX_CASCADES],
    /// The cascades as the layers of one image instead (a 2D-array view, layer i cascade i, at least
    /// `cascade_count` layers in `cascade_array_layers`), or None.
    pub cascade_array: Option<HostImage>,
    /// Layers of `cascade_array`'s view.
    pub cascade_array_layers: u32,
    /// The shadow maps hold 1 at the light's near plane and 0 at its far plane (reverse-Z cascades).
    pub cascades_depth_inverted: bool,
    /// World distance along the light direction a shadow-map depth must be in front of the receiver to count as
    /// a blocker (the shadow maps' bias), >= 0. Each tap is compared with the receiver's tangent plane (from its
    /// normal) under it, so a sloping receiver needs no larger offset than a flat one: texel size and depth
    /// precision set it.
    pub blocker_offset: f32,
    /// Blocker-search taps per pixel: 8, 16, 24 (default) or 32.
    pub tap_count: u32,
    /// A tile is listed for tracing only with more pixels to trace than this (0..=31; default 0, every tile
    /// with one). Pixels to trace in a tile that is not listed get the verdict most of their taps give.
    pub tile_cutoff: u32,
    /// Pixels no tap finds a blocker for are decided lit (default). Off: only shadowed pixels are decided, every
    /// other receiver is traced.
    pub reject_lit_pixels: bool,
    /// A listed tile's ray interval is bounded by the blockers its pixels' taps found (default); off: from 0
    /// (the receiver: the engine's own ray offset keeps its rays off their surface) to infinity.
    pub cascades_bound_ray_interval: bool,
    /// The host's hit mask, written (prefilled) by the classifier: R32_UINT, ceil(W/8) x ceil(H/4), STORAGE
    /// usage, GENERAL layout. The same image the engine's trace completes and `ShadowsDispatch::hit_mask`
    /// reads.
    pub hit_mask: HostImage,
    /// The convention the engine's trace and the denoiser use: pixels to trace are prefilled with bit 0 in
    /// both, so the trace ORs in its bit (occluded with `OccludedBits`, lit with `LitBits`).
    pub hit_mask_convention: HitMaskConvention,
    /// Region to classify; `None` = the whole render size. Tiles outside it are not written.
    pub render_rect: Option<Rect>,
    /// Barriers dnsr should emit on the host's behalf: the writes of depth, normals and shadow maps before,
    /// and the host's use of the hit mask, tile list and counts after (its trace: e.g. DRAW_INDIRECT +
    /// RAY_TRACING_SHADER_KHR or COMPUTE_SHADER; dnsr's own prepare pass is always covered).
    pub sync: HostSync,
}

impl Default for ClassifyDispatch {
    fn default() -> Self {
        ClassifyDispatch {
            depth: HostImage::default(),
            normals: HostImage::default(),
            normals_unpack_mul: 1.0,
            normals_unpack_add: 0.0,
            view_projection_inverse: Mat4::IDENTITY,
            projection_inverse: Mat4::IDENTITY,
            light_direction: Vec3::Z,
            light_angular_size: 0.0093,
            cascade_count: 0,
            cascades: [ShadowCascade::default(); MAX_CASCADES],
            cascade_images: [HostImage::default(); MAX_CASCADES],
            cascade_array: None,
            cascade_array_layers: 0,
            cascades_depth_inverted: false,
            blocker_offset: 0.0,
            tap_count: 24,
            tile_cutoff: 0,
            reject_lit_pixels: true,
            cascades_bound_ray_interval: true,
            hit_mask: HostImage::default(),
            hit_mask_convention: HitMaskConvention::OccludedBits,
            render_rect: None,
            sync: HostSync::default(),
        }
    }
}

/// The buffers the classifier writes (dnsr owns them; they live until the context is destroyed or resized).
/// Both have STORAGE_BUFFER, STORAGE_TEXEL_BUFFER, INDIRECT_BUFFER, TRANSFER_SRC and TRANSFER_DST usage.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ClassifierBuffers {
    /// The tile list: `tile_capacity` records of `CLASSIFY_TILE_BYTES`, the first `counts` word 3 of them
    /// written by the last classify dispatch (in no particular order).
    pub tiles: vk::Buffer,
    /// Records `tiles` holds: every tile of the render size.
    pub tile_capacity: u32,
    /// `CLASSIFY_COUNTS_BYTES` of counts (see there); reset by every classify dispatch.
    pub counts: vk::Buffer,
}

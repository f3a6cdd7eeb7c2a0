//! Per-frame input, shaped like the FidelityFX dispatch description so integrations port mechanically.

use ash::vk;
use glam::{Mat4, Vec2, Vec3, Vec4};

/// One of the host's images. dnsr never changes its layout permanently: an output declared in another layout
/// than GENERAL is moved to GENERAL for the filter and back to `layout` before the call returns.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HostImage {
    /// The image (needed for layout transitions of the output). Required.
    pub image: vk::Image,
    /// A 2D view of mip 0, layer 0 (depth aspect only for depth/stencil formats). Required.
    pub view: vk::ImageView,
    /// The view's format.
    pub format: vk::Format,
    /// The layout the image is in when the recorded commands execute, and is left in.
    pub layout: vk::ImageLayout,
    /// Width of mip 0 in pixels.
    pub width: u32,
    /// Height of mip 0 in pixels.
    pub height: u32,
}

/// The bit convention of the hit mask.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HitMaskConvention {
    /// FidelityFX SDK: bit = 1 means the shadow ray hit an occluder. Classification inverts it as it reads it.
    #[default]
    OccludedBits,
    /// bit = 1 means lit. Either convention is read as it is, without a prepare pass.
    LitBits,
}

/// What the output image shows. Anything but `None` replaces the shadow with a visualisation of dnsr's
/// internal state, for finding out why an integration looks wrong.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DebugView {
    /// The denoised shadow.
    #[default]
    None,
    /// Tile classification: 1 cleared lit, 0 cleared shadowed, 0.5 filtered (temporal + spatial work), 0.75 sky.
    TileClassification,
    /// Temporal sample count / max_history_samples (1 in cleared tiles, 0 on sky).
    SampleCount,
    /// Standard deviation of the filtered estimate, clamped to [0, 1].
    Variance,
    /// 1 where the history restarted this frame (disocclusion, reset or rejection: sample count <= 1), else 0.
    Disocclusion,
    /// The pixel's current run of identical samples / max_history_samples, clamped to [0, 1] (1 in cleared tiles,
    /// 0 on sky). Where it reaches `Settings::stable_history_samples` the input is taken to resolve the pixel (a hard
    /// edge): its history is clamped to the run rather than to its neighbourhood; short runs along an edge that
    /// the input had exact are where the filter can soften it.
    SampleRun,
}

/// A pixel rectangle within the render size.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rect {
    /// Left edge in pixels; a multiple of 8 (tile width).
    pub x: u32,
    /// Top edge in pixels; a multiple of 4 (tile height).
    pub y: u32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

/// Pipeline stages and accesses of the host's work around a dispatch. dnsr turns them into one barrier before
/// its first pass (host writes of the inputs -> dnsr reads) and one after its last (dnsr's output write -> the
/// host's next use). Leave both zero when the host emits those barriers itself.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HostSync {
    /// Stages that wrote the input images (e.g. FRAGMENT_SHADER | LATE_FRAGMENT_TESTS).
    pub input_src_stages: vk::PipelineStageFlags,
    /// Accesses that wrote the input images (e.g. COLOR_ATTACHMENT_WRITE | DEPTH_STENCIL_ATTACHMENT_WRITE).
    pub input_src_access: vk::AccessFlags,
    /// Stages that will use the output (e.g. FRAGMENT_SHADER).
    pub output_dst_stages: vk::PipelineStageFlags,
    /// Accesses that will use the output (e.g. SHADER_READ).
    pub output_dst_access: vk::AccessFlags,
}

/// One frame of input for one light.
///
/// Conventions: matrices are column-major and map column vectors (glam). Clip space is Vulkan's: NDC xy in
/// [-1, 1] with uv (0,0) at the top-left corner mapping to NDC (-1,-1), depth in [0, 1]. A host that flips y
/// through a negative viewport height folds that flip into the matrices it passes.
#[derive(Clone, Copy, Debug)]
pub struct ShadowsDispatch {
    /// Which light's history to use, below `ContextCreateInfo::light_count`.
    pub light_index: u32,
    /// Hit mask: R32_UINT, ceil(W/8) x ceil(H/4), bit (y%4)*8 + (x%8) of tile (x/8, y/4). Sampled read.
    /// Required with `ShadowInput::HitMask` (the default); must be left null with `ShadowInput::Visibility`.
    pub hit_mask: HostImage,
    /// Per-pixel visibility, W x H: the fraction of the pixel's shadow rays that reached the light (1 lit, 0
    /// shadowed), R8_UNORM, R16_UNORM, R16_SFLOAT or R32_SFLOAT, sampled. Required with `ShadowInput::Visibility`;
    /// must be left null otherwise. Values are clamped to [0, 1] and NaN reads as 0. With k rays per pixel store
    /// hits / k (R8_UNORM represents 1/2, 1/4 ... only approximately, which is harmless: only exact 0 and 1 are
    /// treated specially).
    pub visibility: HostImage,
    /// How the hit mask bits are to be read.
    pub hit_mask_convention: HitMaskConvention,
    /// Depth, W x H: D32_SFLOAT, D16_UNORM, X8_D24_UNORM_PACK32, D24_UNORM_S8_UINT, D32_SFLOAT_S8_UINT,
    /// R32_SFLOAT, R16_SFLOAT or R16_UNORM. Receivers have 0 < depth < 1. The history is kept where the linear
    /// (view-space) depth `projection_inverse` gives lies within 2^-16 to 2^48 view units (any scene scale):
    /// dnsr keeps last frame's depth in that range, and a receiver outside it starts afresh every frame.
    pub depth: HostImage,
    /// The depth the host gave as `depth` last frame (its previous depth buffer, which engines keep for temporal
    /// anti-aliasing), in one of `depth`'s formats and at its size, sampled. Required where the context was
    /// created with `ContextCreateInfo::host_previous_gbuffer`, and must be left null otherwise. Linearised with
    /// this frame's `projection_inverse`. After a reset (or a light's first frame) it is not read.
    pub previous_depth: HostImage,
    /// Last frame's `normals`, as `previous_depth` (decoded with this frame's `normals_unpack_mul` and
    /// `normals_unpack_add`).
    pub previous_normals: HostImage,
    /// Motion vectors, W x H, two channels (R16G16_SFLOAT, R32G32_SFLOAT, R16G16_SNORM ...).
    /// `value * motion_vector_scale` is the uv offset from a pixel to where its surface was last frame:
    /// prev_uv = uv + value * scale (FidelityFX SDK convention). For "current minus previous" vectors in NDC
    /// use scale (-0.5, -0.5).
    pub velocity: HostImage,
    /// World-space normals, W x H, decoded as `rgb * normals_unpack_mul + normals_unpack_add`.
    pub normals: HostImage,
    /// Denoised shadow (1 lit, 0 shadowed), W x H, in `ContextCreateInfo::output_format`. Storage write.
    pub output: HostImage,
    /// Optional penumbra guidance: per pixel, the distance along the shadow ray from the receiver to the first
    /// occluder it hit, in view-space units (the units `projection_inverse` maps depth to), W x H, R16_SFLOAT or
    /// R32_SFLOAT, sampled. Read only where the hit mask says the ray hit; a value there that is not finite and
    /// positive counts as unknown. With it, the filter derives how wide the penumbra can be around each pixel
    /// (from `light_angular_size`, the blockers' distance and the view depth) and narrows its kernel to that:
    /// contact shadows stay sharp, wide penumbrae are filtered as without it, and under penumbrae narrower than
    /// `Settings::hard_penumbra_pixels` the output is the ray's own result, as it is where no pixel within +-8 px
    /// of a tile has a known distance (its shadowed pixels face away from the light): give every ray that hit its
    /// distance. `None`: no guidance.
    pub hit_distance: Option<HostImage>,
    /// Angular diameter of the light seen from the receivers, in radians (the sun: about 0.0093; a sphere light of
    /// radius r at distance D: 2 asin(r / D)), in [0, pi). Used only with `hit_distance` or `light_position`; 0 means
    /// a point light (with `hit_distance`: every penumbra hard, no spatial filtering; with `light_position`: a receiver
    /// turned away from the light's centre sees none of it).
    pub light_angular_size: f32,
    /// The light has no size (a point light, or a directional light of angular size 0): every shadow it casts is
    /// hard, so each pixel's ray already is that pixel's exact visibility, and no filter can make it better. With
    /// it, every receiver's output is its own sample (for a checkerboard input: on the pixels traced this frame),
    /// with or without `hit_distance`: a shadow line a pixel wide stays a pixel wide under any camera motion. It is
    /// what penumbra guidance does for a light of angular size 0, for hosts without hit distances (with
    /// `hit_distance`, `light_angular_size` must be 0). The history goes on as without it, so a light that gains a
    /// size continues from it. Only the first filter pass runs for such a light (it writes the output), whatever
    /// `Settings::filter_passes` says. Not available through the FidelityFX layer, whose dispatch has no light size.
    pub hard_light: bool,
    /// Optional: where the light is, in world space (the space `view_projection_inverse` maps to), as a
    /// homogeneous point: (direction toward the light, 0) for a directional light, (centre, 1) for a point or
    /// sphere light. With it, a receiver whose normal faces away from the light (N.L < 0, the normals as given)
    /// and whose ray hit keeps its sample as its output: it cannot see the light, and the history and the filter
    /// would only blend it with the lit face beside it (a pole's or a sphere's dark side against the sky, the far
    /// face of a fin). Its ray that missed is filtered as any other (a normal-mapped face may see the light); so is
    /// one that hit where a normal map tilts the normal past the light inside a plane that faces it, in a 16x16
    /// group where such a receiver's ray reached the light (the host's rays do not test the mapped normals there,
    /// and the hit is a penumbra's). Where the normal is turned away from the whole light (N.L below
    /// -sin(`light_angular_size` / 2): give the light's size, or its larger shadows lose their penumbrae on faces
    /// turned just past its centre), that output is final: no filter pass blends it with its neighbours or them
    /// with it, so a shadowed dot a pixel wide (a bump of a normal-mapped face turned away, where the host tests its
    /// rays against the mapped normals) stays one.
    /// Fast and Quality (the run features) only: Balanced keeps the FidelityFX behaviour. `None`: not given (the
    /// FidelityFX layer, whose dispatch has no light).
    pub light_position: Option<Vec4>,
    /// Multiplier from stored motion vectors to uv offsets.
    pub motion_vector_scale: Vec2,
    /// Normal decode multiplier (2.0 for UNORM-packed normals).
    pub normals_unpack_mul: f32,
    /// Normal decode offset (-1.0 for UNORM-packed normals).
    pub normals_unpack_add: f32,
    /// Camera position in world space (the same space `view_projection_inverse` maps to).
    pub eye: Vec3,
    /// Frame counter; informational only: nothing in dnsr depends on its value or parity.
    pub frame_index: u32,
    /// Current clip space -> view space.
    pub projection_inverse: Mat4,
    /// Current clip space -> previous frame's clip space.
    pub reprojection_matrix: Mat4,
    /// Current clip space -> world space. Classification takes receivers' world positions from it (their view
    /// direction and their side of the light), and the first filter pass their geometric normals (from
    /// neighbouring depths).
    pub view_projection_inverse: Mat4,
    /// Depth edge-stop scale: weight exp(-|z_center - z_tap| / sigma) on linear depth. FFX default 1.0.
    pub depth_similarity_sigma: f32,
    /// Camera cut: discard this light's history before this frame.
    pub reset: bool,
    /// Region to denoise; `None` = the whole render size. Pixels outside it are not written, and are treated
    /// as absent by every neighbourhood operation.
    pub render_rect: Option<Rect>,
    /// Barriers dnsr should emit on the host's behalf.
    pub sync: HostSync,
    /// What the output shows (the shadow unless a debug view is chosen).
    pub debug_view: DebugView,
    /// Checkerboard input (`ShadowInput::Checkerboard`): this frame's rays were traced for the pixels with
    /// (x + y) % 2 == phase (x, y in image pixels), 0 or 1; alternate it every frame. Must be 0 for other inputs.
    pub checkerboard_phase: u32,
    /// Images the engine's own shader variants read or write (`ContextCreateInfo::shader_overrides`): slot i is
    /// binding `ENGINE_BINDING_BASE + i` of set 0. Every binding an override of this frame's passes declares
    /// must be given; dnsr binds them without knowing what they hold. Empty without overrides.
    pub engine_images: [Option<EngineImage>; MAX_ENGINE_IMAGES],
}

/// The first binding number of an engine's own images in dnsr's set 0.
pub const ENGINE_BINDING_BASE: u32 = 32;
/// How many engine images one dispatch can bind (bindings `ENGINE_BINDING_BASE..ENGINE_BINDING_BASE + 8`).
pub const MAX_ENGINE_IMAGES: usize = 8;

/// One of the engine's images, bound for its own shader variants.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EngineImage {
    /// A view the engine's shader declares (a 2D view for `texture2D` / `image2D`).
    pub view: vk::ImageView,
    /// Its layout while the commands execute: GENERAL, SHADER_READ_ONLY_OPTIMAL or READ_ONLY_OPTIMAL for a sampled
    /// image, GENERAL for a storage image.
    pub layout: vk::ImageLayout,
}

impl Default for ShadowsDispatch {
    fn default() -> Self {
        ShadowsDispatch {
            light_index: 0,
            hit_mask: HostImage::default(),
            visibility: HostImage::default(),
            hit_mask_convention: HitMaskConvention::OccludedBits,
            depth: HostImage::default(),
            velocity: HostImage::default(),
            normals: HostImage::default(),
            previous_depth: HostImage::default(),
            previous_normals: HostImage::default(),
            output: HostImage::default(),
            hit_distance: None,
            light_angular_size: 0.0,
            hard_light: false,
            light_position: None,
            motion_vector_scale: Vec2::ONE,
            normals_unpack_mul: 1.0,
            normals_unpack_add: 0.0,
            eye: Vec3::ZERO,
            frame_index: 0,
            projection_inverse: Mat4::IDENTITY,
            reprojection_matrix: Mat4::IDENTITY,
            view_projection_inverse: Mat4::IDENTITY,
            depth_similarity_sigma: 1.0,
            reset: false,
            render_rect: None,
            sync: HostSync::default(),
            debug_view: DebugView::None,
            checkerboard_phase: 0,
            engine_images: [None; MAX_ENGINE_IMAGES],
        }
    }
}

/// Most lights one `Context::record_lights` call denoises.
pub const MAX_LIGHTS_PER_RECORD: usize = 8;

/// What differs from light to light in `Context::record_lights`: everything else (the G-buffer, the camera, the
/// settings of the frame) is the shared `ShadowsDispatch`'s, whose per-light fields stay at their defaults there.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightDispatch {
    /// Which light's history to use, below `ContextCreateInfo::light_count`; each light at most once per call.
    pub light_index: u32,
    /// This light's hit mask, as `ShadowsDispatch::hit_mask` (required with `ShadowInput::HitMask`).
    pub hit_mask: HostImage,
    /// This light's visibility, as `ShadowsDispatch::visibility` (required with `ShadowInput::Visibility`).
    pub visibility: HostImage,
    /// This light's denoised shadow, as `ShadowsDispatch::output`; a different image for every light of the call.
    pub output: HostImage,
    /// This light's penumbra guidance, as `ShadowsDispatch::hit_distance`. Optional.
    pub hit_distance: Option<HostImage>,
    /// This light's angular diameter in radians, as `ShadowsDispatch::light_angular_size` (read with `hit_distance`
    /// or `light_position`).
    pub light_angular_size: f32,
    /// This light has no size, as `ShadowsDispatch::hard_light`.
    pub hard_light: bool,
    /// Where this light is, as `ShadowsDispatch::light_position`. Optional.
    pub light_position: Option<Vec4>,
    /// Discard this light's history alone before this frame (the other lights of the call keep theirs).
    pub reset: bool,
}

impl LightDispatch {
    /// The single-light dispatch this light's passes run with: `shared` with this light's fields.
    pub(crate) fn apply(&self, shared: &ShadowsDispatch) -> ShadowsDispatch {
        ShadowsDispatch {
            light_index: self.light_index,
            hit_mask: self.hit_mask,
            visibility: self.visibility,
            output: self.output,
            hit_distance: self.hit_distance,
            light_angular_size: self.light_angular_size,
            hard_light: self.hard_light,
            light_position: self.light_position,
            reset: self.reset,
            ..*shared
        }
    }
}

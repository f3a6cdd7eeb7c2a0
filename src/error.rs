//! Every way a call can fail, each with enough detail to fix the call.

use ash::vk;
use std::fmt;

/// Which host-provided image a message is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageRole {
    /// The per-tile hit mask (R32_UINT, one bit per pixel of an 8x4 tile).
    HitMask,
    /// Scene depth.
    Depth,
    /// Screen-space motion vectors.
    Velocity,
    /// World-space normals.
    Normals,
    /// The denoised shadow written by dnsr.
    Output,
    /// The optional per-pixel distance to the first occluder (penumbra guidance).
    HitDistance,
    /// Per-pixel visibility (a context with `ShadowInput::Visibility`).
    Visibility,
    /// The host's previous frame's depth (`ContextCreateInfo::host_previous_gbuffer`).
    PreviousDepth,
    /// The host's previous frame's normals (`ContextCreateInfo::host_previous_gbuffer`).
    PreviousNormals,
    /// A shadow-map cascade of the classifier (`ClassifyDispatch::cascade_images` or `cascade_array`).
    Cascade,
}

impl ImageRole {
    /// The dispatch field this role is passed in.
    pub fn field(self) -> &'static str {
        match self {
            ImageRole::HitMask => "hit_mask",
            ImageRole::Depth => "depth",
            ImageRole::Velocity => "velocity",
            ImageRole::Normals => "normals",
            ImageRole::Output => "output",
            ImageRole::HitDistance => "hit_distance",
            ImageRole::Visibility => "visibility",
            ImageRole::PreviousDepth => "previous_depth",
            ImageRole::PreviousNormals => "previous_normals",
            ImageRole::Cascade => "cascade_images",
        }
    }
}

/// Failure of a dnsr call. When a recording call fails, nothing was recorded into the command buffer and no
/// internal state changed.
#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// A required Vulkan handle or function pointer is null.
    NullHandle(&'static str),
    /// The Vulkan API version the host created its device with is too old, or newer than the device supports.
    UnsupportedApiVersion {
        /// The version the host declared.
        declared: u32,
        /// The lowest version dnsr needs.
        required: u32,
        /// What the physical device reports.
        device: u32,
    },
    /// A feature was requested that the host did not declare enabled, or that the device does not support.
    MissingFeature(&'static str),
    /// A width or height of zero.
    ZeroExtent {
        /// The offending field.
        what: &'static str,
    },
    /// An extent larger than the device can create images for.
    ExtentTooLarge {
        /// The offending field.
        what: &'static str,
        /// The requested width and height.
        extent: [u32; 2],
        /// The device limit (maxImageDimension2D).
        limit: u32,
    },
    /// A host image's extent does not match what dnsr expects for the render size.
    ImageExtentMismatch {
        /// The image.
        role: ImageRole,
        /// The extent the dispatch declared for it.
        actual: [u32; 2],
        /// The extent required.
        expected: [u32; 2],
    },
    /// A format the shaders cannot read (or write) for this image, or one the device cannot use that way.
    UnsupportedFormat {
        /// The image (None: an internal image format the device lacks).
        role: Option<ImageRole>,
        /// The format.
        format: vk::Format,
    },
    /// The output image's format differs from the context's output format.
    OutputFormatMismatch {
        /// The format the dispatch declared.
        declared: vk::Format,
        /// The format the context was created with.
        context: vk::Format,
    },
    /// A host image layout dnsr cannot use for this image.
    UnsupportedLayout {
        /// The image.
        role: ImageRole,
        /// The layout declared.
        layout: vk::ImageLayout,
    },
    /// A matrix or vector input contains NaN or infinity.
    NonFinite(&'static str),
    /// The render rectangle is empty, misaligned or reaches outside the images.
    InvalidRenderRect {
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A setting is outside its valid range (or NaN).
    InvalidSetting {
        /// The setting's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The valid range, as an interval ("[0, 1]").
        range: &'static str,
    },
    /// A create-info, dispatch or function argument is outside its valid range.
    InvalidValue {
        /// The field or argument.
        field: &'static str,
        /// The value given, as text.
        value: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The device memory a context needs exceeds what the device has (checked before allocating anything).
    OutOfDeviceMemory {
        /// Bytes the context's images need (before driver padding).
        needed: u64,
        /// Bytes available in the largest device-local heap (its budget with VK_EXT_memory_budget).
        available: u64,
    },
    /// `HostSync` names a stage or access dnsr cannot put in a barrier on this device and queue family.
    InvalidHostSync {
        /// The field (`input_src_stages` ...).
        field: &'static str,
        /// What is wrong.
        reason: String,
    },
    /// The queue family index does not exist on the device, or the family cannot run compute work.
    InvalidQueueFamily {
        /// The index given.
        index: u32,
        /// What is wrong.
        reason: &'static str,
    },
    /// A light index at or beyond the context's light count.
    InvalidLightIndex {
        /// The index given.
        index: u32,
        /// The number of lights the context was created for.
        count: u32,
    },
    /// One light of a `record_lights` call is refused (nothing of the call was recorded).
    Light {
        /// Its position in the call's light list.
        position: u32,
        /// Why.
        error: Box<Error>,
    },
    /// An earlier `resize` failed to allocate the internal images; record refuses until a resize succeeds.
    NotResized,
    /// Timestamps were requested but the queue family cannot write them.
    TimestampsUnsupported,
    /// The classifier was used on a context created without `enable_classifier`.
    ClassifierNotEnabled,
    /// Reflection of embedded or host-supplied SPIR-V failed or does not match the binding interface.
    ShaderInterface(String),
    /// A Vulkan call failed.
    Vulkan {
        /// The call.
        call: &'static str,
        /// Its result.
        result: vk::Result,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NullHandle(what) => write!(f, "{what} is null"),
            Error::UnsupportedApiVersion { declared, required, device } => write!(
                f,
                "api_version {}.{} is not usable: dnsr needs at least {}.{} and the device supports {}.{}",
                vk::api_version_major(*declared),
                vk::api_version_minor(*declared),
                vk::api_version_major(*required),
                vk::api_version_minor(*required),
                vk::api_version_major(*device),
                vk::api_version_minor(*device)
            ),
            Error::MissingFeature(what) => write!(f, "missing feature: {what}"),
            Error::ZeroExtent { what } => write!(f, "{what} has a zero width or height"),
            Error::ExtentTooLarge { what, extent, limit } => {
                write!(f, "{what} {}x{} exceeds the device limit of {limit} pixels per side", extent[0], extent[1])
            }
            Error::ImageExtentMismatch { role, actual, expected } => write!(
                f,
                "{} image is {}x{} but must be {}x{} for this render size",
                role.field(),
                actual[0],
                actual[1],
                expected[0],
                expected[1]
            ),
            Error::UnsupportedFormat { role: Some(role), format } => {
                write!(f, "{} image format {format:?} is not supported for this use", role.field())
            }
            Error::OutputFormatMismatch { declared, context } => {
                write!(f, "output image format {declared:?} differs from the context's output_format {context:?}")
            }
            Error::UnsupportedFormat { role: None, format } => {
                write!(f, "the device cannot use internal format {format:?} as a sampled and storage image")
            }
            Error::UnsupportedLayout { role, layout } => write!(f, "{} image layout {layout:?} is not usable here", role.field()),
            Error::NonFinite(what) => write!(f, "{what} contains NaN or infinity"),
            Error::InvalidRenderRect { reason } => write!(f, "render rect: {reason}"),
            Error::InvalidSetting { name, value, range } => {
                write!(f, "setting {name} is {}; it must be in {range}", number(*value))
            }
            Error::InvalidValue { field, value, allowed } => write!(f, "{field} is {value}; {allowed}"),
            Error::OutOfDeviceMemory { needed, available } => write!(
                f,
                "the context needs {} MiB of device memory but the largest device-local heap has {} MiB available",
                needed.div_ceil(1 << 20),
                available >> 20
            ),
            Error::InvalidHostSync { field, reason } => write!(f, "sync.{field}: {reason}"),
            Error::InvalidQueueFamily { index, reason } => write!(f, "queue_family_index {index}: {reason}"),
            Error::InvalidLightIndex { index, count } => {
                write!(f, "light index {index} is out of range: the context has {count} light(s)")
            }
            Error::Light { position, error } => write!(f, "lights[{position}]: {error}"),
            Error::NotResized => write!(
                f,
                "the internal images are missing because the last resize failed; call Context::resize again before recording"
            ),
            Error::TimestampsUnsupported => write!(f, "the queue family has no timestamp support"),
            Error::ClassifierNotEnabled => {
                write!(f, "the context has no classifier: create it with enable_classifier (DNSR_CONTEXT_CREATE_ENABLE_CLASSIFIER)")
            }
            Error::ShaderInterface(msg) => write!(f, "shader interface: {msg}"),
            Error::Vulkan { call, result } => write!(f, "{call} failed: {result:?}"),
        }
    }
}

impl std::error::Error for Error {}

/// A value as a message shows it: NaN and infinities by name.
fn number(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        (if v > 0.0 { "+infinity" } else { "-infinity" }).into()
    } else {
        format!("{v}")
    }
}

/// Result of a dnsr call.
pub type Result<T> = std::result::Result<T, Error>;

/// Wraps a `vk::Result` error with the name of the call that produced it.
pub(crate) fn vk_check<T>(call: &'static str, r: std::result::Result<T, vk::Result>) -> Result<T> {
    r.map_err(|result| Error::Vulkan { call, result })
}

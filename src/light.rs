//! Internal state of the lights, created from the state table (src/state/table.rs): each light's persistent images
//! and what carries over from frame to frame (`LightState`), and the transient images their passes use within a
//! record (`TransientImages`: one set shared by every light, or one per light).

use crate::create_info::{Precision, ShadowInput};
use crate::error::Result;
use crate::gpu::image::InternalImage;
use crate::gpu::loader::Vk;
use crate::state::table::{Image, Scope, RESOURCES};
use crate::state::{image_specs, together_specs, ImageSpec, Lifetime};
use ash::vk;

/// What one light keeps from frame to frame: its persistent images (`Lifetime::Persistent` in the state table) and
/// its recording state. Its transient images are a `TransientImages` set of the context's, its own or shared with
/// every other light (`ContextCreateInfo::transient_memory_per_light`).
pub(crate) struct LightState {
    /// The filter's mean alone.
    pub history: InternalImage,
    /// Linear depth: last frame's until the first filter pass writes this frame's. None for a light after the first
    /// where the lights are recorded together: they share the first light's (`Image::FrameDepth`); and for every
    /// light where the host gives its previous depth and normals (`Config::host_previous`).
    pub depth_copy: Option<InternalImage>,
    /// Last frame's moments until filter pass 0 copies this frame's over them.
    pub moments: InternalImage,
    /// Each tile's frames without a contradiction (`Settings::hard_tile_frames`): a ping-pong pair indexed by
    /// `parity` (current) and `parity ^ 1` (previous frame).
    pub tile_quiet: [InternalImage; 2],
    /// Which of the context's transient sets this light's passes use.
    pub transient: usize,
    /// Flips once per recorded frame of this light: advances with recording, not with frameIndex.
    pub parity: usize,
    /// False until the first frame's commands (layout transitions + clears) have been recorded.
    pub initialized: bool,
    /// The next frame discards history (reset_history or a new allocation).
    pub pending_reset: bool,
}

/// The images a light writes and reads within one record (`Lifetime::Transient`): one set per light, or one that
/// every light of the context uses in turn, each light's passes recorded in a row.
pub(crate) struct TransientImages {
    /// The lit pixels of each tile, written by prepare with a visibility or checkerboard input (None with a hit
    /// mask, which classification reads as the host gives it).
    pub tile_mask: Option<InternalImage>,
    /// The exactly shadowed pixels of each tile, as `tile_mask`.
    pub tile_dark: Option<InternalImage>,
    pub tile_meta: InternalImage,
    /// Written and read only with penumbra guidance; 4 bytes per tile, so always allocated.
    pub tile_blocker: InternalImage,
    pub reprojection: InternalImage,
    /// The filter's signal between passes, an image of its own with a visibility or checkerboard input; None with
    /// a hit mask, whose frame moments' memory holds it (`frame_moments.shared_view`).
    pub signal: Option<InternalImage>,
    /// The visibility prepare reconstructs from a checkerboard input (None for other inputs).
    pub reconstructed: Option<InternalImage>,
    /// This frame's moments: classification writes them, filter pass 0 copies them into the light's `moments`.
    pub frame_moments: InternalImage,
    /// This frame's depth copy for a light that does not write a kept one (lights recorded together, but the one
    /// that writes the shared depth copy; every light where the host gives its previous depth and normals).
    pub frame_depth: Option<InternalImage>,
    /// False until a record has moved the set out of UNDEFINED and cleared it.
    pub initialized: bool,
}

fn create(vk: &Vk, owner: &str, spec: &ImageSpec, alias: bool) -> Result<InternalImage> {
    let name = format!("dnsr.{owner}.{}", spec.name());
    InternalImage::new(vk, spec.format, spec.extent, &name, spec.lifetime == Lifetime::Persistent, alias, spec.shared_format)
}

/// What a light or transient set is created for.
#[derive(Clone, Copy)]
pub(crate) struct Config {
    pub extent: [u32; 2],
    pub precision: Precision,
    pub input: ShadowInput,
    /// `ContextCreateInfo::lights_recorded_together`, with more than one light.
    pub together: bool,
    /// `ContextCreateInfo::host_previous_gbuffer`: no light keeps a depth copy, every transient set has a frame
    /// depth.
    pub host_previous: bool,
}

impl Config {
    /// Whether each transient set has a frame depth (`Image::FrameDepth`).
    pub(crate) fn frame_depth(&self) -> bool {
        self.together || self.host_previous
    }

    /// Whether light `light` keeps a depth copy: each its own, only the first where the lights are recorded together
    /// (they share it), none where the host gives its previous depth and normals.
    pub(crate) fn keeps_depth_copy(&self, light: u32) -> bool {
        !self.host_previous && (!self.together || light == 0)
    }
}

/// Creates the state table's light images of `lifetime` that `keep` keeps (every one or none: what was made is
/// destroyed on an error) and hands them to `build`, which takes each by its row and copy.
fn create_all<T>(
    vk: &Vk,
    owner: &str,
    lifetime: Lifetime,
    c: Config,
    alias: bool,
    keep: impl Fn(Image) -> bool,
    build: impl FnOnce(&mut dyn FnMut(Image, u32) -> Option<InternalImage>) -> T,
) -> Result<T> {
    let mut made: Vec<(ImageSpec, InternalImage)> = Vec::new();
    let together = c.frame_depth().then(|| together_specs(c.extent, c.precision, c.input)).into_iter().flatten();
    let specs = image_specs(Scope::Light, c.extent, c.precision, c.input).chain(together);
    for spec in specs.filter(|s| s.lifetime == lifetime && keep(s.image)) {
        match create(vk, owner, &spec, alias) {
            Ok(img) => made.push((spec, img)),
            Err(e) => {
                made.iter_mut().for_each(|(_, i)| i.destroy(vk));
                return Err(e);
            }
        }
    }
    let mut take = |image: Image, copy: u32| {
        let at = made.iter().position(|(s, _)| s.image == image && s.copy == copy)?;
        Some(made.swap_remove(at).1)
    };
    let built = build(&mut take);
    debug_assert!(made.is_empty(), "every image created is taken");
    Ok(built)
}

const ALWAYS: &str = "an image the state table always allocates";

impl LightState {
    /// A light's persistent images, every one the state table gives a light (but the depth copy of a light after
    /// the first recorded together with it); its passes use the context's transient set `transient`.
    pub(crate) fn new(vk: &Vk, light: u32, c: Config, transient: usize) -> Result<LightState> {
        let keep = |image| c.keeps_depth_copy(light) || image != Image::DepthCopy;
        create_all(vk, &format!("light{light}"), Lifetime::Persistent, c, false, keep, |take| LightState {
            history: take(Image::History, 0).expect(ALWAYS),
            depth_copy: take(Image::DepthCopy, 0),
            moments: take(Image::Moments, 0).expect(ALWAYS),
            tile_quiet: [take(Image::TileQuiet, 0).expect(ALWAYS), take(Image::TileQuiet, 1).expect(ALWAYS)],
            transient,
            parity: 0,
            initialized: false,
            pending_reset: true,
        })
    }

    /// The persistent image of the state table's row `image` (the half `copy` of a pair), if it is one.
    pub(crate) fn image(&self, image: Image, copy: u32) -> Option<&InternalImage> {
        let single = match image {
            Image::History => Some(&self.history),
            Image::DepthCopy => self.depth_copy.as_ref(),
            Image::Moments => Some(&self.moments),
            Image::TileQuiet => return self.tile_quiet.get(copy as usize),
            _ => None,
        };
        single.filter(|_| copy == 0)
    }

    /// Every image the light has, in table order: its persistent ones.
    pub(crate) fn images(&self) -> impl Iterator<Item = &InternalImage> {
        table_order(move |image, copy| self.image(image, copy))
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        for img in [&mut self.history, &mut self.moments].into_iter().chain(self.tile_quiet.iter_mut()).chain(self.depth_copy.iter_mut()) {
            img.destroy(vk);
        }
    }
}

impl TransientImages {
    /// A transient set: every transient light image of the state table that shadow input `input` needs. `owner`
    /// names it (`light3`, or `lights` for the shared set); `alias`: the host aliases them
    /// (`ResourceKind::TransientImage`).
    pub(crate) fn new(vk: &Vk, owner: &str, c: Config, alias: bool) -> Result<TransientImages> {
        create_all(vk, owner, Lifetime::Transient, c, alias, |_| true, |take| TransientImages {
            tile_mask: take(Image::TileMask, 0),
            tile_dark: take(Image::TileDark, 0),
            tile_meta: take(Image::TileMeta, 0).expect(ALWAYS),
            tile_blocker: take(Image::TileBlocker, 0).expect(ALWAYS),
            reprojection: take(Image::Reprojection, 0).expect(ALWAYS),
            frame_moments: take(Image::FrameMoments, 0).expect(ALWAYS),
            signal: take(Image::Signal, 0),
            reconstructed: take(Image::Reconstructed, 0),
            frame_depth: take(Image::FrameDepth, 0),
            initialized: false,
        })
    }

    /// The transient image of the state table's row `image`, if the set has it.
    pub(crate) fn image(&self, image: Image, copy: u32) -> Option<&InternalImage> {
        let single = match image {
            Image::TileMask => self.tile_mask.as_ref(),
            Image::TileDark => self.tile_dark.as_ref(),
            Image::TileMeta => Some(&self.tile_meta),
            Image::TileBlocker => Some(&self.tile_blocker),
            Image::Reprojection => Some(&self.reprojection),
            Image::FrameMoments => Some(&self.frame_moments),
            Image::Signal => self.signal.as_ref(),
            Image::Reconstructed => self.reconstructed.as_ref(),
            Image::FrameDepth => self.frame_depth.as_ref(),
            _ => None,
        };
        single.filter(|_| copy == 0)
    }

    /// The view of the filter's signal between passes: its own image's, or the one of the frame moments' memory.
    pub(crate) fn signal_view(&self) -> vk::ImageView {
        self.signal.as_ref().map_or(self.frame_moments.shared_view, |s| s.view)
    }

    /// Every image of the set, in table order.
    pub(crate) fn images(&self) -> impl Iterator<Item = &InternalImage> {
        table_order(move |image, copy| self.image(image, copy))
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        for img in [&mut self.tile_meta, &mut self.tile_blocker, &mut self.reprojection, &mut self.frame_moments]
            .into_iter()
            .chain(self.tile_mask.iter_mut())
            .chain(self.tile_dark.iter_mut())
            .chain(self.signal.iter_mut())
            .chain(self.reconstructed.iter_mut())
            .chain(self.frame_depth.iter_mut())
        {
            img.destroy(vk);
        }
    }
}

/// The light rows of the state table that `image` holds, in table order.
fn table_order<'a>(image: impl Fn(Image, u32) -> Option<&'a InternalImage> + Copy + 'a) -> impl Iterator<Item = &'a InternalImage> {
    RESOURCES.iter().filter(|r| r.scope == Scope::Light).flat_map(move |r| (0..r.copies).filter_map(move |c| image(r.image, c)))
}

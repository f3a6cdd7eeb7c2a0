//! Internal state of one light: its images, created from the state table (src/state/table.rs), and everything that
//! carries over from frame to frame.

use crate::create_info::{Precision, ShadowInput};
use crate::error::Result;
use crate::gpu::image::InternalImage;
use crate::gpu::loader::Vk;
use crate::state::table::{Image, Scope, RESOURCES};
use crate::state::{image_specs, ImageSpec, Lifetime};
use ash::vk;

pub(crate) struct LightState {
    /// The lit pixels of each tile, written by prepare with a visibility or checkerboard input (None with a hit
    /// mask, which classification reads as the host gives it).
    pub tile_mask: Option<InternalImage>,
    /// The exactly shadowed pixels of each tile, as `tile_mask`.
    pub tile_dark: Option<InternalImage>,
    pub tile_meta: InternalImage,
    /// Written and read only with penumbra guidance; 4 bytes per tile, so always allocated.
    pub tile_blocker: InternalImage,
    pub reprojection: InternalImage,
    /// The filter's mean alone.
    pub history: InternalImage,
    /// The filter's signal between passes, an image of its own with a visibility or checkerboard input; None with
    /// a hit mask, whose frame moments' memory holds it (`frame_moments.shared_view`).
    pub signal: Option<InternalImage>,
    /// The visibility prepare reconstructs from a checkerboard input (None for other inputs).
    pub reconstructed: Option<InternalImage>,
    /// Linear depth: last frame's until the first filter pass writes this frame's.
    pub depth_copy: InternalImage,
    /// Last frame's moments until filter pass 0 copies this frame's over them.
    pub moments: InternalImage,
    /// This frame's moments (transient): classification writes them, filter pass 0 copies them into `moments`.
    pub frame_moments: InternalImage,
    /// Each tile's frames without a contradiction (`Settings::hard_tile_frames`): a ping-pong pair indexed by
    /// `parity` (current) and `parity ^ 1` (previous frame).
    pub tile_quiet: [InternalImage; 2],
    /// Flips once per recorded frame of this light: advances with recording, not with frameIndex.
    pub parity: usize,
    /// False until the first frame's commands (layout transitions + clears) have been recorded.
    pub initialized: bool,
    /// The next frame discards history (reset_history or a new allocation).
    pub pending_reset: bool,
}

fn create(vk: &Vk, light: u32, spec: &ImageSpec, alias: bool) -> Result<InternalImage> {
    let name = format!("dnsr.light{light}.{}", spec.name());
    InternalImage::new(vk, spec.format, spec.extent, &name, spec.lifetime == Lifetime::Persistent, alias, spec.shared_format)
}

impl LightState {
    /// A light's images: every light image of the state table that shadow input `input` needs. `alias`: the host
    /// aliases the transient ones (`ResourceKind::TransientImage`).
    pub(crate) fn new(vk: &Vk, light: u32, extent: [u32; 2], precision: Precision, input: ShadowInput, alias: bool) -> Result<LightState> {
        let mut made: Vec<(ImageSpec, InternalImage)> = Vec::new();
        for spec in image_specs(Scope::Light, extent, precision, input) {
            match create(vk, light, &spec, alias) {
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
        let (tile_mask, tile_dark) = (take(Image::TileMask, 0), take(Image::TileDark, 0));
        let mut always = |image: Image, copy: u32| take(image, copy).expect("a light image the table always allocates");
        Ok(LightState {
            tile_mask,
            tile_dark,
            tile_meta: always(Image::TileMeta, 0),
            tile_blocker: always(Image::TileBlocker, 0),
            reprojection: always(Image::Reprojection, 0),
            history: always(Image::History, 0),
            depth_copy: always(Image::DepthCopy, 0),
            moments: always(Image::Moments, 0),
            frame_moments: always(Image::FrameMoments, 0),
            tile_quiet: [always(Image::TileQuiet, 0), always(Image::TileQuiet, 1)],
            signal: take(Image::Signal, 0),
            reconstructed: take(Image::Reconstructed, 0),
            parity: 0,
            initialized: false,
            pending_reset: true,
        })
    }

    /// The image of the state table's row `image` (the half `copy` of a pair), if this light has it.
    pub(crate) fn image(&self, image: Image, copy: u32) -> Option<&InternalImage> {
        let single = match image {
            Image::TileMask => self.tile_mask.as_ref(),
            Image::TileDark => self.tile_dark.as_ref(),
            Image::TileMeta => Some(&self.tile_meta),
            Image::TileBlocker => Some(&self.tile_blocker),
            Image::Reprojection => Some(&self.reprojection),
            Image::History => Some(&self.history),
            Image::DepthCopy => Some(&self.depth_copy),
            Image::Moments => Some(&self.moments),
            Image::FrameMoments => Some(&self.frame_moments),
            Image::TileQuiet => return self.tile_quiet.get(copy as usize),
            Image::Signal => self.signal.as_ref(),
            Image::Reconstructed => self.reconstructed.as_ref(),
        };
        single.filter(|_| copy == 0)
    }

    /// The view of the filter's signal between passes: its own image's, or the one of the frame moments' memory.
    pub(crate) fn signal_view(&self) -> vk::ImageView {
        self.signal.as_ref().map_or(self.frame_moments.shared_view, |s| s.view)
    }

    /// Every image this light has, in table order.
    pub(crate) fn images(&self) -> impl Iterator<Item = &InternalImage> {
        RESOURCES.iter().filter(|r| r.scope == Scope::Light).flat_map(move |r| (0..r.copies).filter_map(move |c| self.image(r.image, c)))
    }

    pub(crate) fn bytes(&self) -> u64 {
        self.images().map(|i| i.bytes).sum()
    }

    /// The images whose contents the next frame reads (`Lifetime::Persistent` in the state table).
    pub(crate) fn persistent_images(&self) -> impl Iterator<Item = &InternalImage> {
        self.images().filter(|i| i.persistent)
    }

    /// Every other image: written and read within one record.
    pub(crate) fn transient_images(&self) -> impl Iterator<Item = &InternalImage> {
        self.images().filter(|i| !i.persistent)
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        for img in [&mut self.tile_meta, &mut self.tile_blocker, &mut self.reprojection, &mut self.history, &mut self.depth_copy, &mut self.moments, &mut self.frame_moments]
            .into_iter()
            .chain(self.tile_quiet.iter_mut())
            .chain(self.tile_mask.iter_mut())
            .chain(self.tile_dark.iter_mut())
            .chain(self.signal.iter_mut())
            .chain(self.reconstructed.iter_mut())
        {
            img.destroy(vk);
        }
    }
}

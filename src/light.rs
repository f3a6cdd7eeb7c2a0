//! Internal state of one light: its images, created from the state table (src/state/table.rs), and everything that
//! carries over from frame to frame.

use crate::create_info::{Precision, ShadowInput};
use crate::error::Result;
use crate::gpu::image::InternalImage;
use crate::gpu::loader::Vk;
use crate::state::table::{Image, Needed, Scope, RESOURCES};
use crate::state::{image_specs, specs_of_image, ImageSpec, Lifetime};

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
    pub history: InternalImage,
    /// None until four passes are configured.
    pub tmp: Option<InternalImage>,
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
    InternalImage::new(vk, spec.format, spec.extent, &format!("dnsr.light{light}.{}", spec.name()), spec.lifetime == Lifetime::Persistent, alias)
}

impl LightState {
    /// A light's images: every light image of the state table that `filter_passes` passes and shadow input `input`
    /// need. `alias`: the host aliases the transient ones (`ResourceKind::TransientImage`).
    pub(crate) fn new(vk: &Vk, light: u32, extent: [u32; 2], precision: Precision, filter_passes: u32, input: ShadowInput, alias: bool) -> Result<LightState> {
        let mut made: Vec<(ImageSpec, InternalImage)> = Vec::new();
        for spec in image_specs(Scope::Light, extent, precision, filter_passes, input) {
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
            tmp: take(Image::Tmp, 0),
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
            Image::Tmp => self.tmp.as_ref(),
            Image::Reconstructed => self.reconstructed.as_ref(),
        };
        single.filter(|_| copy == 0)
    }

    /// Allocates the images `filter_passes` passes need (the table's `Needed::Passes` light images) and this light
    /// lacks; true if it made any (their first frame initialises them, like a new light's).
    pub(crate) fn allocate_optional(&mut self, vk: &Vk, light: u32, extent: [u32; 2], precision: Precision, filter_passes: u32, alias: bool) -> Result<bool> {
        let mut made = false;
        let optional = RESOURCES.iter().filter(|r| r.scope == Scope::Light && matches!(r.needed, Needed::Passes(_)));
        for r in optional.filter(|r| r.needed.holds(filter_passes, ShadowInput::HitMask)) {
            let slot = match r.image {
                Image::Tmp => &mut self.tmp,
                other => unreachable!("{other:?}: a light image allocated with the filter passes has a slot here"),
            };
            if slot.is_none() {
                for spec in specs_of_image(r.image, extent, precision) {
                    *slot = Some(create(vk, light, &spec, alias)?);
                }
                made = true;
            }
        }
        Ok(made)
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
            .chain(self.tmp.iter_mut())
            .chain(self.reconstructed.iter_mut())
        {
            img.destroy(vk);
        }
    }
}

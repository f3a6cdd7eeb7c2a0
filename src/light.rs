//! Internal state of one light: its images, created from the image table (state.rs), and everything that carries
//! over from frame to frame.

use crate::create_info::Precision;
use crate::error::Result;
use crate::gpu::image::InternalImage;
use crate::gpu::loader::Vk;
use crate::state::{image_specs, Lifetime, Optional, OPTIONAL, RECONSTRUCTED_FORMAT};

pub(crate) struct LightState {
    pub tile_mask: InternalImage,
    /// The exactly shadowed pixels of each tile, written by prepare with a visibility input; 4 bytes per tile, so
    /// always allocated.
    pub tile_dark: InternalImage,
    pub tile_meta: InternalImage,
    /// Written and read only with penumbra guidance; 4 bytes per tile, so always allocated.
    pub tile_blocker: InternalImage,
    pub reprojection: InternalImage,
    pub history: InternalImage,
    /// None until four passes are configured.
    pub tmp: Option<InternalImage>,
    /// The visibility prepare reconstructs from a checkerboard input (None for other inputs).
    pub reconstructed: Option<InternalImage>,
    /// Ping-pong pairs indexed by `parity` (current) and `parity ^ 1` (previous frame).
    pub depth: [InternalImage; 2],
    pub moments: [InternalImage; 2],
    /// Flips once per recorded frame of this light: advances with recording, not with frameIndex.
    pub parity: usize,
    /// False until the first frame's commands (layout transitions + clears) have been recorded.
    pub initialized: bool,
    /// The next frame discards history (reset_history or a new allocation).
    pub pending_reset: bool,
}

impl LightState {
    /// A light's images; `checkerboard` adds the reconstructed visibility of a checkerboard input. `alias`: the host
    /// aliases the transient ones (`ResourceKind::TransientImage`).
    pub(crate) fn new(vk: &Vk, light: u32, extent: [u32; 2], precision: Precision, filter_passes: u32, checkerboard: bool, alias: bool) -> Result<LightState> {
        let mut made: Vec<InternalImage> = Vec::new();
        for (format, size, name, lifetime) in image_specs(extent, precision, 1) {
            match InternalImage::new(vk, format, size, &format!("dnsr.light{light}.{name}"), lifetime == Lifetime::Persistent, alias) {
                Ok(img) => made.push(img),
                Err(e) => {
                    made.iter_mut().for_each(|i| i.destroy(vk));
                    return Err(e);
                }
            }
        }
        let mut it = made.into_iter();
        let mut next = || it.next().expect("one image per spec");
        let mut state = LightState {
            tile_mask: next(),
            tile_dark: next(),
            tile_meta: next(),
            tile_blocker: next(),
            reprojection: next(),
            history: next(),
            depth: [next(), next()],
            moments: [next(), next()],
            tmp: None,
            reconstructed: None,
            parity: 0,
            initialized: false,
            pending_reset: true,
        };
        let reconstructed = || InternalImage::new(vk, RECONSTRUCTED_FORMAT, extent, &format!("dnsr.light{light}.reconstructed_visibility"), false, alias);
        let made = state.allocate_optional(vk, light, extent, precision, filter_passes, alias).and_then(|_| {
            state.reconstructed = if checkerboard { Some(reconstructed()?) } else { None };
            Ok(())
        });
        match made {
            Ok(()) => Ok(state),
            Err(e) => {
                state.destroy(vk);
                Err(e)
            }
        }
    }

    /// Allocates the optional images `filter_passes` passes need and this light lacks; true if it made any (their
    /// first frame initialises them, like a new light's).
    pub(crate) fn allocate_optional(&mut self, vk: &Vk, light: u32, extent: [u32; 2], precision: Precision, filter_passes: u32, alias: bool) -> Result<bool> {
        let mut made = false;
        for o in OPTIONAL.into_iter().filter(|o| o.needed(filter_passes)) {
            let slot = match o {
                Optional::Tmp => &mut self.tmp,
            };
            if slot.is_none() {
                let (format, name) = o.spec(precision);
                *slot = Some(InternalImage::new(vk, format, extent, &format!("dnsr.light{light}.{name}"), false, alias)?);
                made = true;
            }
        }
        Ok(made)
    }

    pub(crate) fn images(&self) -> impl Iterator<Item = &InternalImage> {
        [&self.tile_mask, &self.tile_dark, &self.tile_meta, &self.tile_blocker, &self.reprojection, &self.history]
            .into_iter()
            .chain(self.depth.iter())
            .chain(self.moments.iter())
            .chain(self.tmp.iter())
            .chain(self.reconstructed.iter())
    }

    pub(crate) fn bytes(&self) -> u64 {
        self.images().map(|i| i.bytes).sum()
    }

    /// The images whose contents the next frame reads (`Lifetime::Persistent` in `image_specs`).
    pub(crate) fn persistent_images(&self) -> impl Iterator<Item = &InternalImage> {
        self.images().filter(|i| i.persistent)
    }

    /// Every other image: written and read within one record.
    pub(crate) fn transient_images(&self) -> impl Iterator<Item = &InternalImage> {
        self.images().filter(|i| !i.persistent)
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        for img in [&mut self.tile_mask, &mut self.tile_dark, &mut self.tile_meta, &mut self.tile_blocker, &mut self.reprojection, &mut self.history]
            .into_iter()
            .chain(self.depth.iter_mut())
            .chain(self.moments.iter_mut())
            .chain(self.tmp.iter_mut())
            .chain(self.reconstructed.iter_mut())
        {
            img.destroy(vk);
        }
    }
}

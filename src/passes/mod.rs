//! One file per pass: which shader variant it runs, what it binds, how many groups it dispatches.

pub(crate) mod bindings;
pub(crate) mod filter;
pub(crate) mod prepare;
pub(crate) mod tile_classification;

use ash::vk;
use bindings::{image, Binding, BindingTable, Resource};

/// Tile metadata bit: the tile needs no temporal or spatial work; its value is in `TILE_LIT`.
pub(crate) const TILE_CLEARED: u32 = 1 << 0;
/// Tile metadata bit: a cleared tile is lit (1) rather than shadowed (0).
pub(crate) const TILE_LIT: u32 = 1 << 1;

const GENERAL: vk::ImageLayout = vk::ImageLayout::GENERAL;

/// Everything the passes of one frame of one light bind.
pub(crate) struct FrameViews {
    pub constants: vk::Buffer,
    pub hit_mask: Binding,
    pub depth: Binding,
    pub velocity: Binding,
    pub normals: Binding,
    /// The host output, already in GENERAL when the final pass runs.
    pub output: vk::ImageView,
    /// The lit-bit tile mask: dnsr's internal image, or the host's mask when it already holds lit bits.
    pub tile_mask: Binding,
    pub tile_meta: vk::ImageView,
    pub reprojection: vk::ImageView,
    pub history: vk::ImageView,
    /// Fourth-pass intermediate; null unless four filter passes are configured.
    pub tmp: vk::ImageView,
    pub previous_depth: vk::ImageView,
    pub depth_copy: vk::ImageView,
    pub previous_moments: vk::ImageView,
    pub moments: vk::ImageView,
}

impl FrameViews {
    /// The bindings every pass shares: constants and the G-buffer.
    fn base_table(&self) -> BindingTable {
        let mut t = BindingTable::default();
        t[Resource::Constants as usize] = Binding { buffer: self.constants, ..Default::default() };
        t[Resource::Depth as usize] = self.depth;
        t[Resource::Normals as usize] = self.normals;
        t
    }
}

fn internal(view: vk::ImageView) -> Binding {
    image(view, GENERAL)
}

/// Number of `group`-sized groups covering `extent`.
pub(crate) fn groups(extent: [u32; 2], group: [u32; 2]) -> [u32; 3] {
    [extent[0].div_ceil(group[0]), extent[1].div_ceil(group[1]), 1]
}

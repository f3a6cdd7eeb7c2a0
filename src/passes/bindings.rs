//! The binding interface between pass shaders and the host: every resource a pass may bind, by its GLSL name.
//! Binding numbers are not repeated here; they are read from the SPIR-V by reflection.

use ash::vk;

/// A resource a pass shader can declare.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Resource {
    Constants,
    HitMask,
    TileMaskOut,
    TileMask,
    Depth,
    Velocity,
    Normals,
    PreviousDepth,
    /// The host's previous normals (`ContextCreateInfo::host_previous_gbuffer`).
    PreviousNormals,
    DepthCopy,
    PreviousMoments,
    Moments,
    History,
    Reprojection,
    TileMetaOut,
    TileMeta,
    FilterInput,
    FilterOutput,
    Output,
    DebugMoments,
    Guide,
    HitDistance,
    TileBlockerOut,
    TileBlocker,
    Visibility,
    TileDarkOut,
    TileDark,
    VisibilityOut,
    PreviousTileQuiet,
    TileQuiet,
    /// Filter pass 0's copy of this frame's moments into the kept ones.
    FrameMoments,
    KeptMoments,
    /// Filter pass 0's mean, the next frame's history.
    HistoryOut,
    /// Slots 1..LIGHT_SLOTS of the filter's light-slot variants (slot 0 is the resource without a number).
    TileMeta1,
    TileMeta2,
    TileMeta3,
    TileBlocker1,
    TileBlocker2,
    TileBlocker3,
    FilterInput1,
    FilterInput2,
    FilterInput3,
    FilterOutput1,
    FilterOutput2,
    FilterOutput3,
    Output1,
    Output2,
    Output3,
    DebugMoments1,
    DebugMoments2,
    DebugMoments3,
    /// The hybrid-shadows classifier's own.
    ClassifyConstants,
    HitMaskOut,
    TileList,
    TileCount,
    Cascade0,
    Cascade1,
    Cascade2,
    Cascade3,
    CascadeArray,
    /// An engine's own images (bindings ENGINE_BINDING_BASE.., any name), declared by engine-compiled variants.
    Engine0,
    Engine1,
    Engine2,
    Engine3,
    Engine4,
    Engine5,
    Engine6,
    Engine7,
}

pub(crate) const RESOURCE_COUNT: usize = Resource::Engine7 as usize + 1;
const NAMED_COUNT: usize = Resource::CascadeArray as usize + 1;

impl Resource {
    /// The engine image at slot `slot` (binding ENGINE_BINDING_BASE + slot).
    pub(crate) fn engine(slot: usize) -> Option<Resource> {
        use Resource::*;
        [Engine0, Engine1, Engine2, Engine3, Engine4, Engine5, Engine6, Engine7].get(slot).copied()
    }

    /// This per-light resource of the filter's light-slot variants in slot `slot` (0..LIGHT_SLOTS); None for a
    /// resource the slots do not repeat.
    pub(crate) fn in_slot(self, slot: usize) -> Option<Resource> {
        SLOTTED.iter().find(|row| row[0] == self).and_then(|row| row.get(slot).copied())
    }

    /// The slot-0 resource whose light slot this is; itself for a resource the slots do not repeat.
    #[cfg(test)]
    pub(crate) fn slot_zero(self) -> Resource {
        SLOTTED.iter().find(|row| row.contains(&self)).map_or(self, |row| row[0])
    }

    /// The engine slot of an engine resource.
    pub(crate) fn engine_slot(self) -> Option<usize> {
        (self as usize).checked_sub(Resource::Engine0 as usize)
    }
}

/// The per-light resources of the filter's light-slot variants, slot 0 (the resource without a number) first.
const SLOTTED: [[Resource; crate::passes::LIGHT_SLOTS]; 6] = {
    use Resource::*;
    [
        [TileMeta, TileMeta1, TileMeta2, TileMeta3],
        [TileBlocker, TileBlocker1, TileBlocker2, TileBlocker3],
        [FilterInput, FilterInput1, FilterInput2, FilterInput3],
        [FilterOutput, FilterOutput1, FilterOutput2, FilterOutput3],
        [Output, Output1, Output2, Output3],
        [DebugMoments, DebugMoments1, DebugMoments2, DebugMoments3],
    ]
};

/// (GLSL name, resource, descriptor type the shader must declare it as).
const TABLE: [(&str, Resource, vk::DescriptorType); NAMED_COUNT] = [
    ("DnsrConstantsBlock", Resource::Constants, vk::DescriptorType::UNIFORM_BUFFER),
    ("dnsr_hit_mask", Resource::HitMask, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_mask_out", Resource::TileMaskOut, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_tile_mask", Resource::TileMask, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_depth", Resource::Depth, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_velocity", Resource::Velocity, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_normals", Resource::Normals, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_previous_depth", Resource::PreviousDepth, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_previous_normals", Resource::PreviousNormals, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_depth_copy", Resource::DepthCopy, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_previous_moments", Resource::PreviousMoments, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_moments", Resource::Moments, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_history", Resource::History, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_reprojection", Resource::Reprojection, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_tile_meta_out", Resource::TileMetaOut, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_tile_meta", Resource::TileMeta, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_filter_input", Resource::FilterInput, vk::DescriptorType::COMBINED_IMAGE_SAMPLER),
    ("dnsr_filter_output", Resource::FilterOutput, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_output", Resource::Output, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_debug_moments", Resource::DebugMoments, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_guide", Resource::Guide, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_hit_distance", Resource::HitDistance, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_blocker_out", Resource::TileBlockerOut, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_tile_blocker", Resource::TileBlocker, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_visibility", Resource::Visibility, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_dark_out", Resource::TileDarkOut, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_tile_dark", Resource::TileDark, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_visibility_out", Resource::VisibilityOut, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_previous_tile_quiet", Resource::PreviousTileQuiet, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_quiet", Resource::TileQuiet, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_frame_moments", Resource::FrameMoments, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_kept_moments", Resource::KeptMoments, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_history_out", Resource::HistoryOut, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_tile_meta_1", Resource::TileMeta1, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_meta_2", Resource::TileMeta2, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_meta_3", Resource::TileMeta3, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_blocker_1", Resource::TileBlocker1, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_blocker_2", Resource::TileBlocker2, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_tile_blocker_3", Resource::TileBlocker3, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_filter_input_1", Resource::FilterInput1, vk::DescriptorType::COMBINED_IMAGE_SAMPLER),
    ("dnsr_filter_input_2", Resource::FilterInput2, vk::DescriptorType::COMBINED_IMAGE_SAMPLER),
    ("dnsr_filter_input_3", Resource::FilterInput3, vk::DescriptorType::COMBINED_IMAGE_SAMPLER),
    ("dnsr_filter_output_1", Resource::FilterOutput1, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_filter_output_2", Resource::FilterOutput2, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_filter_output_3", Resource::FilterOutput3, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_output_1", Resource::Output1, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_output_2", Resource::Output2, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_output_3", Resource::Output3, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_debug_moments_1", Resource::DebugMoments1, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_debug_moments_2", Resource::DebugMoments2, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_debug_moments_3", Resource::DebugMoments3, vk::DescriptorType::SAMPLED_IMAGE),
    ("DnsrClassifyBlock", Resource::ClassifyConstants, vk::DescriptorType::UNIFORM_BUFFER),
    ("dnsr_hit_mask_out", Resource::HitMaskOut, vk::DescriptorType::STORAGE_IMAGE),
    ("dnsr_tile_list", Resource::TileList, vk::DescriptorType::STORAGE_TEXEL_BUFFER),
    ("dnsr_tile_count", Resource::TileCount, vk::DescriptorType::STORAGE_TEXEL_BUFFER),
    ("dnsr_cascade_0", Resource::Cascade0, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_cascade_1", Resource::Cascade1, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_cascade_2", Resource::Cascade2, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_cascade_3", Resource::Cascade3, vk::DescriptorType::SAMPLED_IMAGE),
    ("dnsr_cascades", Resource::CascadeArray, vk::DescriptorType::SAMPLED_IMAGE),
];

impl Resource {
    pub(crate) fn from_glsl_name(name: &str) -> Option<(Resource, vk::DescriptorType)> {
        TABLE.iter().find(|(n, _, _)| *n == name).map(|&(_, r, t)| (r, t))
    }

    /// The descriptor type a shader declares the named resource at `index` of a `BindingTable` as (None for an
    /// engine image).
    #[cfg(test)]
    pub(crate) fn descriptor_type_at(index: usize) -> Option<vk::DescriptorType> {
        TABLE.iter().find(|(_, r, _)| *r as usize == index).map(|&(_, _, t)| t)
    }
}

/// What one resource is bound to for one dispatch.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Binding {
    pub view: vk::ImageView,
    pub layout: vk::ImageLayout,
    pub buffer: vk::Buffer,
    /// Where the constants of this dispatch's light start in `buffer`.
    pub offset: vk::DeviceSize,
    /// Bytes of `buffer` bound from `offset`.
    pub range: vk::DeviceSize,
    /// A texel buffer's view (the classifier's tile list and counts).
    pub texel: vk::BufferView,
}

/// Every resource's binding for one pass of one frame; unset entries stay null.
pub(crate) type BindingTable = [Binding; RESOURCE_COUNT];

pub(crate) fn image(view: vk::ImageView, layout: vk::ImageLayout) -> Binding {
    Binding { view, layout, ..Default::default() }
}

//! The catalog of the passes' compiled variants: every SPIR-V module dnsr embeds, what it is compiled from, and
//! which variant a pass runs for a precision and an output format. Plain data; pipelines are made from it above
//! (context.rs, classify.rs), and engines compile their own variants from the same list (`shader_variants`).

use crate::create_info::Precision;
use ash::vk;

/// One compiled variant of a pass entry file.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) struct ShaderVariant {
    /// File stem under shaders/spv/.
    pub name: &'static str,
    /// Entry file under shaders/.
    pub source: &'static str,
    /// Preprocessor definitions passed to glslc.
    pub defines: &'static [&'static str],
    pub spirv: &'static [u8],
}

macro_rules! variant {
    ($name:literal, $source:literal, [$($d:literal),*]) => {
        ShaderVariant {
            name: $name,
            source: $source,
            defines: &[$($d),*],
            spirv: include_bytes!(concat!("../../shaders/spv/", $name, ".spv")),
        }
    };
}

/// Every SPIR-V module dnsr embeds. `cargo test spirv_is_current` recompiles each with glslc and compares.
pub(crate) const VARIANTS: &[ShaderVariant] = &[
    variant!("prepare", "prepare.comp", []),
    variant!("prepare_visibility", "prepare.comp", ["DNSR_VISIBILITY_INPUT"]),
    variant!("prepare_checkerboard", "prepare.comp", ["DNSR_CHECKERBOARD_INPUT"]),
    variant!("tile_classification_r8", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=r8"]),
    variant!("tile_classification_r16f", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=r16f"]),
    variant!("tile_classification_r32f", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=r32f"]),
    variant!("tile_classification_rgba8", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=rgba8"]),
    variant!("tile_classification_rgba16f", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=rgba16f"]),
    variant!("tile_classification_r8_fp16", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=r8", "DNSR_FP16"]),
    variant!("tile_classification_r16f_fp16", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=r16f", "DNSR_FP16"]),
    variant!("tile_classification_r32f_fp16", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=r32f", "DNSR_FP16"]),
    variant!("tile_classification_rgba8_fp16", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=rgba8", "DNSR_FP16"]),
    variant!("tile_classification_rgba16f_fp16", "tile_classification.comp", ["DNSR_OUTPUT_FORMAT=rgba16f", "DNSR_FP16"]),
    variant!("tile_classification_host_previous_r8", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=r8"]),
    variant!("tile_classification_host_previous_r16f", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=r16f"]),
    variant!("tile_classification_host_previous_r32f", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=r32f"]),
    variant!("tile_classification_host_previous_rgba8", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=rgba8"]),
    variant!("tile_classification_host_previous_rgba16f", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=rgba16f"]),
    variant!("tile_classification_host_previous_r8_fp16", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=r8", "DNSR_FP16"]),
    variant!("tile_classification_host_previous_r16f_fp16", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=r16f", "DNSR_FP16"]),
    variant!("tile_classification_host_previous_r32f_fp16", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=r32f", "DNSR_FP16"]),
    variant!("tile_classification_host_previous_rgba8_fp16", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=rgba8", "DNSR_FP16"]),
    variant!("tile_classification_host_previous_rgba16f_fp16", "tile_classification.comp", ["DNSR_HOST_PREVIOUS_GBUFFER", "DNSR_OUTPUT_FORMAT=rgba16f", "DNSR_FP16"]),
    variant!("tile_classification_visibility_r8", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=r8"]),
    variant!("tile_classification_visibility_r16f", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=r16f"]),
    variant!("tile_classification_visibility_r32f", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=r32f"]),
    variant!("tile_classification_visibility_rgba8", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=rgba8"]),
    variant!("tile_classification_visibility_rgba16f", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=rgba16f"]),
    variant!("tile_classification_visibility_r8_fp16", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=r8", "DNSR_FP16"]),
    variant!("tile_classification_visibility_r16f_fp16", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=r16f", "DNSR_FP16"]),
    variant!("tile_classification_visibility_r32f_fp16", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=r32f", "DNSR_FP16"]),
    variant!("tile_classification_visibility_rgba8_fp16", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=rgba8", "DNSR_FP16"]),
    variant!("tile_classification_visibility_rgba16f_fp16", "tile_classification.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_OUTPUT_FORMAT=rgba16f", "DNSR_FP16"]),
    variant!("filter", "filter.comp", []),
    variant!("filter_fp16", "filter.comp", ["DNSR_FP16"]),
    variant!("filter_final_r8", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r8"]),
    variant!("filter_final_r16f", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r16f"]),
    variant!("filter_final_r32f", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r32f"]),
    variant!("filter_final_rgba8", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba8"]),
    variant!("filter_final_rgba16f", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba16f"]),
    variant!("filter_final_r8_fp16", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r8", "DNSR_FP16"]),
    variant!("filter_final_r16f_fp16", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r16f", "DNSR_FP16"]),
    variant!("filter_final_r32f_fp16", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r32f", "DNSR_FP16"]),
    variant!("filter_final_rgba8_fp16", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba8", "DNSR_FP16"]),
    variant!("filter_final_rgba16f_fp16", "filter.comp", ["DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba16f", "DNSR_FP16"]),
    variant!("filter_visibility", "filter.comp", ["DNSR_VISIBILITY_INPUT"]),
    variant!("filter_visibility_fp16", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FP16"]),
    variant!("filter_final_visibility_r8", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r8"]),
    variant!("filter_final_visibility_r16f", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r16f"]),
    variant!("filter_final_visibility_r32f", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r32f"]),
    variant!("filter_final_visibility_rgba8", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba8"]),
    variant!("filter_final_visibility_rgba16f", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba16f"]),
    variant!("filter_final_visibility_r8_fp16", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r8", "DNSR_FP16"]),
    variant!("filter_final_visibility_r16f_fp16", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r16f", "DNSR_FP16"]),
    variant!("filter_final_visibility_r32f_fp16", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r32f", "DNSR_FP16"]),
    variant!("filter_final_visibility_rgba8_fp16", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba8", "DNSR_FP16"]),
    variant!("filter_final_visibility_rgba16f_fp16", "filter.comp", ["DNSR_VISIBILITY_INPUT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba16f", "DNSR_FP16"]),
    variant!("filter_later", "filter.comp", ["DNSR_LATER_PASS"]),
    variant!("filter_later_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FP16"]),
    variant!("filter_later_final_r8", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r8"]),
    variant!("filter_later_final_r16f", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r16f"]),
    variant!("filter_later_final_r32f", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r32f"]),
    variant!("filter_later_final_rgba8", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba8"]),
    variant!("filter_later_final_rgba16f", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba16f"]),
    variant!("filter_later_final_r8_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r8", "DNSR_FP16"]),
    variant!("filter_later_final_r16f_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r16f", "DNSR_FP16"]),
    variant!("filter_later_final_r32f_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r32f", "DNSR_FP16"]),
    variant!("filter_later_final_rgba8_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba8", "DNSR_FP16"]),
    variant!("filter_later_final_rgba16f_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba16f", "DNSR_FP16"]),
    variant!("classify", "classify.comp", []),
    variant!("classify_cascade_array", "classify.comp", ["DNSR_CASCADE_ARRAY"]),
    variant!("filter_later_lights", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT"]),
    variant!("filter_later_lights_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FP16"]),
    variant!("filter_later_lights_final_r8", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r8"]),
    variant!("filter_later_lights_final_r16f", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r16f"]),
    variant!("filter_later_lights_final_r32f", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r32f"]),
    variant!("filter_later_lights_final_rgba8", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba8"]),
    variant!("filter_later_lights_final_rgba16f", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba16f"]),
    variant!("filter_later_lights_final_r8_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r8", "DNSR_FP16"]),
    variant!("filter_later_lights_final_r16f_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r16f", "DNSR_FP16"]),
    variant!("filter_later_lights_final_r32f_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=r32f", "DNSR_FP16"]),
    variant!("filter_later_lights_final_rgba8_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba8", "DNSR_FP16"]),
    variant!("filter_later_lights_final_rgba16f_fp16", "filter.comp", ["DNSR_LATER_PASS", "DNSR_LIGHT_SLOTS_VARIANT", "DNSR_FINAL_PASS", "DNSR_OUTPUT_FORMAT=rgba16f", "DNSR_FP16"]),
];

/// The compiled variant `stem`, `stem_<output format>` when an output format is given, with `_fp16` for the fp16
/// path; None for an output format no variant writes.
pub(crate) fn variant_name(stem: &str, output: Option<vk::Format>, precision: Precision) -> Option<&'static str> {
    let format = match output {
        None => "",
        Some(vk::Format::R8_UNORM) => "_r8",
        Some(vk::Format::R16_SFLOAT) => "_r16f",
        Some(vk::Format::R32_SFLOAT) => "_r32f",
        Some(vk::Format::R8G8B8A8_UNORM) => "_rgba8",
        Some(vk::Format::R16G16B16A16_SFLOAT) => "_rgba16f",
        Some(_) => return None,
    };
    let fp16 = if precision == Precision::Fp16 { "_fp16" } else { "" };
    let name = format!("{stem}{format}{fp16}");
    VARIANTS.iter().find(|v| v.name == name).map(|v| v.name)
}

/// A pass variant an engine may compile itself (`ContextCreateInfo::shader_overrides`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShaderVariantInfo {
    /// The name a `ShaderOverride` gives, e.g. `"filter_final_r16f"`.
    pub name: &'static str,
    /// Its entry file under dnsr's shader sources (installed as share/dnsr/shaders), e.g. `"filter.comp"`.
    pub source: &'static str,
    /// The preprocessor definitions to compile it with (`-D` each).
    pub defines: &'static [&'static str],
}

/// Every pass variant an engine may compile itself; a context creates the ones its precision and output format
/// select. (The light-slot variants, which filter several lights per dispatch, are dnsr's alone: see
/// docs/callbacks.md "Several lights".)
pub fn shader_variants() -> impl Iterator<Item = ShaderVariantInfo> {
    VARIANTS.iter().filter(|v| !is_light_slot_variant(v.name)).map(|v| ShaderVariantInfo { name: v.name, source: v.source, defines: v.defines })
}

/// A light-slot variant (several lights per dispatch), which no engine overrides.
pub(crate) fn is_light_slot_variant(name: &str) -> bool {
    name.starts_with("filter_later_lights")
}

/// A variant of the hybrid-shadows classifier: an engine may override it, but without engine images (its dispatch
/// has none).
pub(crate) fn is_classify_variant(name: &str) -> bool {
    name.starts_with("classify")
}

/// The glslc arguments dnsr's own variants are compiled with, besides `-I<shader dir>` and the definitions:
/// SPIR-V 1.3, which the reflection dnsr uses reads completely.
pub const SHADER_COMPILE_ARGS: &[&str] = &["--target-env=vulkan1.1"];

pub(crate) fn variant(name: &str) -> &'static ShaderVariant {
    VARIANTS.iter().find(|v| v.name == name).expect("shader variant names are compile-time constants")
}

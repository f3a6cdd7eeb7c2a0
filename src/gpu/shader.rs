//! Embedded SPIR-V, the catalog of compiled variants, and pipelines whose layouts come from reflection.

use crate::error::{vk_check, Error, Result};
use crate::gpu::loader::Vk;
use crate::passes::bindings::Resource;
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
pub(crate) fn variant_name(stem: &str, output: Option<vk::Format>, precision: crate::Precision) -> Option<&'static str> {
    let format = match output {
        None => "",
        Some(vk::Format::R8_UNORM) => "_r8",
        Some(vk::Format::R16_SFLOAT) => "_r16f",
        Some(vk::Format::R32_SFLOAT) => "_r32f",
        Some(vk::Format::R8G8B8A8_UNORM) => "_rgba8",
        Some(vk::Format::R16G16B16A16_SFLOAT) => "_rgba16f",
        Some(_) => return None,
    };
    let fp16 = if precision == crate::Precision::Fp16 { "_fp16" } else { "" };
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

/// One binding of a pass as reflected from its SPIR-V.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ReflectedBinding {
    pub binding: u32,
    pub resource: Resource,
    pub descriptor_type: vk::DescriptorType,
}

/// The binding interface of a SPIR-V module: its descriptor bindings (set 0) and push-constant size.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Interface {
    pub bindings: Vec<ReflectedBinding>,
    pub push_constant_bytes: u32,
    pub uniform_bytes: Option<u32>,
    /// The members of each uniform block and of the push constants (`None`), as the module reads them.
    pub layouts: Vec<(Option<Resource>, Vec<crate::gpu::reflect::MemberLayout>)>,
    /// The specialization constants the module declares.
    pub specializes: Specialization,
}

/// A module's instructions: (opcode, operands), after checking the header.
pub(super) fn instructions(spirv: &[u8]) -> Result<Vec<(u32, Vec<u32>)>> {
    const MAGIC: u32 = 0x0723_0203;
    if spirv.len() % 4 != 0 || spirv.len() < 20 {
        return Err(Error::ShaderInterface(format!("is not SPIR-V: {} bytes (a module is whole 32-bit words, 5 or more)", spirv.len())));
    }
    let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    if words[0] != MAGIC {
        return Err(Error::ShaderInterface(format!("is not SPIR-V: first word 0x{:08x}, not the magic number 0x{MAGIC:08x}", words[0])));
    }
    let mut out = Vec::new();
    // The header is 5 words; then instructions, each (word count << 16 | opcode) followed by its operands.
    let mut i = 5;
    while i < words.len() {
        let (count, opcode) = ((words[i] >> 16) as usize, words[i] & 0xFFFF);
        if count == 0 || i + count > words.len() {
            return Err(Error::ShaderInterface(format!("is not valid SPIR-V: instruction of {count} words at word {i}")));
        }
        out.push((opcode, words[i + 1..i + count].to_vec()));
        i += count;
    }
    Ok(out)
}

/// The specialization constant ids a module declares (OpDecorate SpecId), as a mask; an id dnsr does not set is
/// refused.
fn specialization_ids(spirv: &[u8]) -> Result<Specialization> {
    const OP_DECORATE: u32 = 71;
    const DECORATION_SPEC_ID: u32 = 1;
    let mut mask = 0;
    for (opcode, ops) in instructions(spirv)? {
        if opcode == OP_DECORATE && ops.len() >= 3 && ops[1] == DECORATION_SPEC_ID {
            let id = ops[2];
            if id >= SPEC_COUNT as u32 {
                return Err(Error::ShaderInterface(format!("specialization constant id {id}; dnsr sets ids 0..{SPEC_COUNT}")));
            }
            mask |= 1 << id;
        }
    }
    Ok(mask)
}

/// The workgroup size of the module's GLCompute entry point named "main"; an error without one.
fn entry_workgroup_size(spirv: &[u8]) -> Result<[u32; 3]> {
    const OP_ENTRY_POINT: u32 = 15;
    const OP_EXECUTION_MODE: u32 = 16;
    const GL_COMPUTE: u32 = 5;
    const LOCAL_SIZE: u32 = 17;
    let all = instructions(spirv)?;
    // OpEntryPoint: execution model, function id, then the name as a NUL-terminated string packed in words.
    let main = all.iter().find_map(|(opcode, ops)| {
        let name = crate::gpu::spirv_validity::literal_string(ops.get(2..).unwrap_or(&[]));
        (*opcode == OP_ENTRY_POINT && ops.len() >= 3 && ops[0] == GL_COMPUTE && name == "main").then(|| ops[1])
    });
    let main = main.ok_or_else(|| Error::ShaderInterface("has no GLCompute entry point named \"main\"".into()))?;
    all.iter()
        .find_map(|(opcode, ops)| {
            (*opcode == OP_EXECUTION_MODE && ops.len() == 5 && ops[0] == main && ops[1] == LOCAL_SIZE).then(|| [ops[2], ops[3], ops[4]])
        })
        .ok_or_else(|| Error::ShaderInterface("entry point \"main\" has no literal LocalSize (dnsr dispatches fixed workgroups)".into()))
}

/// Checks an engine's SPIR-V for `name` against what dnsr relies on in its own variant: the entry point and
/// workgroup size its dispatches assume, each binding it declares at the number and of the type dnsr binds
/// there (it may leave some out), the push-constant and constants-block sizes, the specialization constants.
pub(crate) fn check_override(name: &str, spirv: &[u8], offers: crate::gpu::spirv_validity::DeviceOffers) -> Result<()> {
    let fail = |what: String| Error::ShaderInterface(format!("shader override \"{name}\": {what}"));
    let wrap = |e: Error| match e {
        Error::ShaderInterface(m) => fail(m),
        other => other,
    };
    let own = variant(name);
    let version = instructions(spirv).map(|_| u32::from_le_bytes([spirv[4], spirv[5], spirv[6], spirv[7]])).map_err(wrap)?;
    // The reflection library dnsr uses aborts the process on SPIR-V 1.4 and later, and misses buffers before 1.3.
    if version != 0x0001_0300 {
        return Err(fail(format!(
            "SPIR-V {}.{}; dnsr reads SPIR-V 1.3 (compile with --target-env=vulkan1.1)",
            (version >> 16) & 0xFF,
            (version >> 8) & 0xFF
        )));
    }
    crate::gpu::spirv_validity::check(spirv, offers).map_err(fail)?;
    let (size, expected_size) = (entry_workgroup_size(spirv).map_err(wrap)?, entry_workgroup_size(own.spirv)?);
    if size != expected_size {
        return Err(fail(format!("workgroup size {size:?}; dnsr dispatches {expected_size:?}")));
    }
    let (theirs, ours) = (reflect(spirv).map_err(wrap)?, reflect(own.spirv)?);
    for b in theirs.bindings.iter().filter(|b| b.resource.engine_slot().is_none()) {
        let Some(expected) = ours.bindings.iter().find(|o| o.resource == b.resource) else {
            return Err(fail(format!("binds {:?} (binding {}), which this pass is not given", b.resource, b.binding)));
        };
        if b.binding != expected.binding {
            return Err(fail(format!("{:?} is binding {}; dnsr binds it at {}", b.resource, b.binding, expected.binding)));
        }
    }
    if let Some(b) = theirs.bindings.iter().find(|b| is_classify_variant(name) && b.resource.engine_slot().is_some()) {
        return Err(fail(format!("declares an engine image at binding {}; the classifier's dispatch has no engine images", b.binding)));
    }
    if theirs.push_constant_bytes != ours.push_constant_bytes {
        return Err(fail(format!("push constants of {} bytes; dnsr pushes {}", theirs.push_constant_bytes, ours.push_constant_bytes)));
    }
    if theirs.uniform_bytes.is_some_and(|b| Some(b) != ours.uniform_bytes) {
        return Err(fail(format!("constants block of {:?} bytes; dnsr writes {:?}", theirs.uniform_bytes, ours.uniform_bytes)));
    }
    for (block, layout) in &theirs.layouts {
        let own = ours.layouts.iter().find(|(b, _)| b == block).map(|(_, l)| l);
        if let Some(own) = own.filter(|own| !layout.is_empty() && *own != layout) {
            let what = block.map_or("push constants".to_string(), |r| format!("{r:?} block"));
            let at = layout.iter().zip(own).position(|(a, b)| a != b).unwrap_or(own.len().min(layout.len()));
            return Err(fail(format!(
                "its {what} differs from dnsr's at member {at} (offset, size or type; keep dnsr_common.glsl's declarations)"
            )));
        }
    }
    if theirs.specializes != ours.specializes {
        return Err(fail(format!(
            "declares specialization constants (mask) {:#b}; dnsr's variant declares {:#b} (keep dnsr_common.glsl's declarations)",
            theirs.specializes, ours.specializes
        )));
    }
    Ok(())
}

/// Reflects a module and checks every binding against the interface dnsr knows.
pub(crate) fn reflect(spirv: &[u8]) -> Result<Interface> {
    let (raw, push_constant_bytes, push_layout) = crate::gpu::reflect::reflect_module(spirv)?;
    let mut bindings = Vec::with_capacity(raw.len());
    let mut layouts = vec![(None, push_layout)];
    let mut uniform_bytes = None;
    for b in raw {
        let [name, type_name] = &b.names;
        let found = Resource::from_glsl_name(name).or_else(|| Resource::from_glsl_name(type_name));
        // Any other name is an engine image when it sits in the engine's binding range as an image.
        let engine = || {
            let slot = b.binding.checked_sub(crate::ENGINE_BINDING_BASE)? as usize;
            let image = matches!(b.descriptor_type, Some(vk::DescriptorType::SAMPLED_IMAGE | vk::DescriptorType::STORAGE_IMAGE));
            Some((Resource::engine(slot).filter(|_| image)?, b.descriptor_type?))
        };
        let (resource, expected) = found.or_else(engine).ok_or_else(|| {
            Error::ShaderInterface(format!(
                "unknown binding '{name}' ({type_name}) at binding {}: dnsr's own are named dnsr_*, an engine's own \
                 images go at bindings {}..{} of set 0 (sampled or storage images)",
                b.binding,
                crate::ENGINE_BINDING_BASE,
                crate::ENGINE_BINDING_BASE + crate::MAX_ENGINE_IMAGES as u32 - 1
            ))
        })?;
        if b.descriptor_type != Some(expected) || b.set != 0 || b.count != 1 {
            return Err(Error::ShaderInterface(format!(
                "binding '{name}' is set {} binding {} of type {:?} x{}; dnsr expects set 0, one {expected:?}",
                b.set, b.binding, b.descriptor_type, b.count
            )));
        }
        if resource == Resource::Constants {
            uniform_bytes = Some(b.block_bytes);
        }
        if expected == vk::DescriptorType::UNIFORM_BUFFER {
            layouts.push((Some(resource), b.block_layout));
        }
        let classify_bytes = std::mem::size_of::<crate::constants::ClassifyConstants>() as u32;
        if resource == Resource::ClassifyConstants && b.block_bytes != classify_bytes {
            return Err(Error::ShaderInterface(format!("classify constants block is {} bytes, host writes {classify_bytes}", b.block_bytes)));
        }
        if bindings.iter().any(|x: &ReflectedBinding| x.resource == resource || x.binding == b.binding) {
            return Err(Error::ShaderInterface(format!("binding '{name}' or number {} declared twice", b.binding)));
        }
        bindings.push(ReflectedBinding { binding: b.binding, resource, descriptor_type: expected });
    }
    if bindings.len() > crate::gpu::descriptors::MAX_BINDINGS {
        return Err(Error::ShaderInterface(format!("{} bindings; at most {}", bindings.len(), crate::gpu::descriptors::MAX_BINDINGS)));
    }
    bindings.sort_by_key(|b| b.binding);
    let specializes = specialization_ids(spirv)?;
    Ok(Interface { bindings, push_constant_bytes, uniform_bytes, layouts, specializes })
}

/// Specialization constants (booleans) that select what a pass compiles in; their ids are generated into GLSL.
/// Features only some frames use sit behind them rather than behind runtime branches: merely present behind a
/// branch that was never taken, penumbra guidance slowed unguided classification on an H100 at 4K from 0.409 to
/// 0.513 ms (and the filter's never-executed tile-blocker fetch made lavapipe leak JIT memory every frame), and
/// the stable-run-aware history slowed Balanced, which never uses it, from 0.410 to 0.463 ms.
/// `DNSR_SPEC_PENUMBRA_GUIDED`: the dispatch has hit distances.
pub(crate) const SPEC_PENUMBRA_GUIDED: u32 = 0;
/// `DNSR_SPEC_STABLE_HISTORY`: the run features are on (`Settings::uses_runs`: stable history or converged pixels).
pub(crate) const SPEC_STABLE_HISTORY: u32 = 1;
const SPEC_COUNT: usize = 2;

/// Which specialization constants are on for one dispatch of a pass (bit i: constant id i).
pub(crate) type Specialization = u32;

/// A compute pipeline with its reflected interface, compiled once per combination of the specialization constants
/// its pass declares.
pub(crate) struct Pipeline {
    /// Indexed by a `Specialization` restricted to `interface.specializes`; null where that combination is not
    /// compiled.
    variants: [vk::Pipeline; 1 << SPEC_COUNT],
    pub layout: vk::PipelineLayout,
    pub set_layout: vk::DescriptorSetLayout,
    pub interface: Interface,
}

impl Pipeline {
    /// One pipeline per combination of the specialization constants the module declares.
    pub(crate) fn new(vk: &Vk, name: &str, spirv: &[u8], push_descriptors: bool) -> Result<Pipeline> {
        let interface = reflect(spirv)?;
        if let Some(bytes) = interface.uniform_bytes {
            let expected = std::mem::size_of::<crate::constants::FrameConstants>() as u32;
            if bytes != expected {
                return Err(Error::ShaderInterface(format!("constants block is {bytes} bytes, host writes {expected}")));
            }
        }
        let mut p = Pipeline {
            variants: [vk::Pipeline::null(); 1 << SPEC_COUNT],
            layout: vk::PipelineLayout::null(),
            set_layout: vk::DescriptorSetLayout::null(),
            interface,
        };
        let result = p.create(vk, spirv, push_descriptors);
        match result {
            Ok(()) => {
                for (i, v) in p.variants.iter().enumerate().filter(|(_, v)| **v != vk::Pipeline::null()) {
                    vk.name(*v, &if i == 0 { format!("dnsr.{name}") } else { format!("dnsr.{name}.spec{i}") });
                }
                vk.name(p.layout, &format!("dnsr.{name}"));
                vk.name(p.set_layout, &format!("dnsr.{name}"));
                Ok(p)
            }
            Err(e) => {
                p.destroy(vk);
                Err(e)
            }
        }
    }

    fn create(&mut self, vk: &Vk, spirv: &[u8], push_descriptors: bool) -> Result<()> {
        let (device, alloc) = (&vk.device, vk.alloc());
        let layout_bindings: Vec<_> = self
            .interface
            .bindings
            .iter()
            .map(|b| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(b.binding)
                    .descriptor_type(b.descriptor_type)
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::COMPUTE)
            })
            .collect();
        let flags = if push_descriptors {
            vk::DescriptorSetLayoutCreateFlags::PUSH_DESCRIPTOR_KHR
        } else {
            vk::DescriptorSetLayoutCreateFlags::empty()
        };
        let set_info = vk::DescriptorSetLayoutCreateInfo::default().flags(flags).bindings(&layout_bindings);
        self.set_layout = vk_check("vkCreateDescriptorSetLayout", unsafe { device.create_descriptor_set_layout(&set_info, alloc) })?;
        let range = vk::PushConstantRange::default()
            .stage_flags(vk::ShaderStageFlags::COMPUTE)
            .size(self.interface.push_constant_bytes);
        let ranges = if self.interface.push_constant_bytes > 0 { std::slice::from_ref(&range) } else { &[] };
        let layout_info =
            vk::PipelineLayoutCreateInfo::default().set_layouts(std::slice::from_ref(&self.set_layout)).push_constant_ranges(ranges);
        self.layout = vk_check("vkCreatePipelineLayout", unsafe { device.create_pipeline_layout(&layout_info, alloc) })?;

        let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        let module_info = vk::ShaderModuleCreateInfo::default().code(&words);
        let module = vk_check("vkCreateShaderModule", unsafe { device.create_shader_module(&module_info, alloc) })?;
        let stage = vk::PipelineShaderStageCreateInfo::default()
            .stage(vk::ShaderStageFlags::COMPUTE)
            .module(module)
            .name(c"main");
        let specializes = self.interface.specializes;
        let ids: Vec<u32> = (0..SPEC_COUNT as u32).filter(|i| specializes & (1 << i) != 0).collect();
        let entries: Vec<vk::SpecializationMapEntry> = (0..ids.len() as u32)
            .map(|k| vk::SpecializationMapEntry { constant_id: ids[k as usize], offset: 4 * k, size: 4 })
            .collect();
        let mut result = Ok(());
        for combination in (0..1u32 << SPEC_COUNT).filter(|c| c & !specializes == 0) {
            let data: Vec<u8> = ids.iter().flat_map(|i| ((combination >> i) & 1).to_ne_bytes()).collect();
            let spec = vk::SpecializationInfo::default().map_entries(&entries).data(&data);
            let info = vk::ComputePipelineCreateInfo::default().stage(stage.specialization_info(&spec)).layout(self.layout);
            let created = unsafe { device.create_compute_pipelines(vk::PipelineCache::null(), std::slice::from_ref(&info), alloc) };
            // Keep what was created before a failure, so that destroy() releases it.
            match vk_check("vkCreateComputePipelines", created.map_err(|(_, e)| e)) {
                Ok(p) => self.variants[combination as usize] = p[0],
                Err(e) => {
                    result = Err(e);
                    break;
                }
            }
        }
        unsafe { device.destroy_shader_module(module, alloc) };
        result
    }

    /// The pipeline to bind for a dispatch with the specialization constants `spec` on (those this pass does not
    /// declare are ignored).
    pub(crate) fn for_frame(&self, spec: Specialization) -> vk::Pipeline {
        self.variants[(spec & self.interface.specializes) as usize]
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        let (device, alloc) = (&vk.device, vk.alloc());
        unsafe {
            for v in self.variants {
                device.destroy_pipeline(v, alloc);
            }
            device.destroy_pipeline_layout(self.layout, alloc);
            device.destroy_descriptor_set_layout(self.set_layout, alloc);
        }
        self.variants = [vk::Pipeline::null(); 1 << SPEC_COUNT];
        self.layout = vk::PipelineLayout::null();
        self.set_layout = vk::DescriptorSetLayout::null();
    }
}

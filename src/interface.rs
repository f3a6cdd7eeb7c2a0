//! The interface between the passes' shaders and the host, read from SPIR-V: each binding a module declares
//! resolved to the resource the passes bind there (passes::bindings), checked against the constant blocks the host
//! writes; and the check of an engine's override against dnsr's own variant of the pass.

use crate::dispatch::{ENGINE_BINDING_BASE, MAX_ENGINE_IMAGES};
use crate::error::{Error, Result};
use crate::gpu::descriptors::MAX_BINDINGS;
use crate::gpu::reflect::{reflect_module, MemberLayout};
use crate::gpu::shader::{instructions, literal_string};
use crate::gpu::spirv_validity::{self, DeviceOffers};
use crate::passes::bindings::Resource;
use crate::passes::variants::{is_classify_variant, variant};
use crate::passes::{Specialization, SPEC_COUNT};
use ash::vk;

/// One binding of a pass as reflected from its SPIR-V.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ReflectedBinding {
    pub binding: u32,
    pub resource: Resource,
    pub descriptor_type: vk::DescriptorType,
    /// The image format a storage image declares (SPIR-V's ImageFormat; 0 otherwise).
    pub format: u32,
}

/// The binding interface of a SPIR-V module: its descriptor bindings (set 0) and push-constant size.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Interface {
    pub bindings: Vec<ReflectedBinding>,
    pub push_constant_bytes: u32,
    pub uniform_bytes: Option<u32>,
    /// The members of each uniform block and of the push constants (`None`), as the module reads them.
    pub layouts: Vec<(Option<Resource>, Vec<MemberLayout>)>,
    /// The specialization constants the module declares.
    pub specializes: Specialization,
}

/// SPIR-V's OpDecorate, which the checks below read from the words.
const OP_DECORATE: u32 = 71;

/// The specialization constant ids a module declares (OpDecorate SpecId), as a mask; an id dnsr does not set is
/// refused.
fn specialization_ids(spirv: &[u8]) -> Result<Specialization> {
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

/// Every DescriptorSet decoration names set 0, the only one dnsr binds. Checked on the words, not through the
/// reflection library: SPIRV-Reflect takes set 0xFFFFFFFF for "no set" and leaves such a binding out, so a module
/// decorated so passed the binding checks and the driver met a set its layout lacks (lavapipe crashed in
/// vkCreateComputePipelines; override_fuzz's case 4).
fn only_set_zero(spirv: &[u8]) -> Result<()> {
    const DECORATION_DESCRIPTOR_SET: u32 = 34;
    for (opcode, ops) in instructions(spirv)? {
        if opcode == OP_DECORATE && ops.len() >= 3 && ops[1] == DECORATION_DESCRIPTOR_SET && ops[2] != 0 {
            return Err(Error::ShaderInterface(format!("id {} is in descriptor set {}; dnsr binds set 0 only", ops[0], ops[2])));
        }
    }
    Ok(())
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
        let name = literal_string(ops.get(2..).unwrap_or(&[]));
        (*opcode == OP_ENTRY_POINT && ops.len() >= 3 && ops[0] == GL_COMPUTE && name == "main").then(|| ops[1])
    });
    let main = main.ok_or_else(|| Error::ShaderInterface("has no GLCompute entry point named \"main\"".into()))?;
    let mode = all
        .iter()
        .find_map(|(opcode, ops)| {
            (*opcode == OP_EXECUTION_MODE && ops.len() == 5 && ops[0] == main && ops[1] == LOCAL_SIZE).then(|| [ops[2], ops[3], ops[4]])
        })
        .ok_or_else(|| Error::ShaderInterface("entry point \"main\" has no literal LocalSize (dnsr dispatches fixed workgroups)".into()))?;
    // A constant decorated BuiltIn WorkgroupSize overrides the LocalSize mode (the driver dispatches its size): it
    // must say the same (override_fuzz, seed 0xdd5eed, case 1633: a module whose composite said (8, 8, 595902102)
    // passed the mode's check and met the device limits).
    const DECORATION_BUILTIN: u32 = 11;
    const BUILTIN_WORKGROUP_SIZE: u32 = 25;
    const OP_CONSTANT: u32 = 43;
    const OP_CONSTANT_COMPOSITE: u32 = 44;
    let builtin = all.iter().find_map(|(opcode, ops)| {
        (*opcode == OP_DECORATE && ops.len() == 3 && ops[1] == DECORATION_BUILTIN && ops[2] == BUILTIN_WORKGROUP_SIZE).then(|| ops[0])
    });
    let Some(id) = builtin else { return Ok(mode) };
    let composite = |id: u32| all.iter().find_map(|(opcode, ops)| (*opcode == OP_CONSTANT_COMPOSITE && ops.len() == 5 && ops[1] == id).then(|| [ops[2], ops[3], ops[4]]));
    let value = |part: u32| all.iter().find_map(|(opcode, ops)| (*opcode == OP_CONSTANT && ops.len() == 3 && ops[1] == part).then(|| ops[2]));
    match composite(id).map(|parts| parts.map(value)) {
        Some([Some(x), Some(y), Some(z)]) if [x, y, z] == mode => Ok(mode),
        Some([Some(x), Some(y), Some(z)]) => Err(Error::ShaderInterface(format!(
            "its WorkgroupSize constant is {:?}, its LocalSize {mode:?} (the constant decides the workgroup size)",
            [x, y, z]
        ))),
        _ => Err(Error::ShaderInterface("its WorkgroupSize is not three literal constants (dnsr dispatches fixed workgroups)".into())),
    }
}

/// Checks an engine's SPIR-V for `name` against what dnsr relies on in its own variant: the entry point and
/// workgroup size its dispatches assume, each binding it declares at the number and of the type dnsr binds
/// there (it may leave out what it reads, not what it writes), the push-constant and constants-block sizes, the
/// specialization constants.
pub(crate) fn check_override(name: &str, spirv: &[u8], offers: DeviceOffers) -> Result<()> {
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
    spirv_validity::check(spirv, offers).map_err(fail)?;
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
        // dnsr creates its images in the formats its own variants declare (the state table's): a storage image
        // declared otherwise would be written in another format's bits.
        if b.format != expected.format {
            return Err(fail(format!(
                "declares {:?} (binding {}) as {}; dnsr's variant declares {} (copy the internal callbacks unchanged)",
                b.resource,
                b.binding,
                image_format_name(b.format),
                image_format_name(expected.format)
            )));
        }
    }
    // What dnsr's variant writes is state a later pass or frame reads (the moments it keeps, the depth copy, the
    // filter's signal): an override may leave out what it reads, not what it writes, or that state would go stale
    // without an error (a variant compiled from an older dnsr's sources, for one).
    let writes = |t: vk::DescriptorType| matches!(t, vk::DescriptorType::STORAGE_IMAGE | vk::DescriptorType::STORAGE_TEXEL_BUFFER);
    if let Some(o) = ours.bindings.iter().find(|o| writes(o.descriptor_type) && !theirs.bindings.iter().any(|b| b.resource == o.resource)) {
        return Err(fail(format!(
            "does not declare {:?} (binding {}), which dnsr's variant writes (compile the variant from this dnsr's shader sources)",
            o.resource, o.binding
        )));
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
            "declares specialization constants (mask) {:#b}; dnsr's variant declares {:#b} (keep dnsr_specialization.glsl's declarations)",
            theirs.specializes, ours.specializes
        )));
    }
    Ok(())
}

/// The storage image formats dnsr's shaders declare: (Vulkan format, SPIR-V ImageFormat enumerant, GLSL layout
/// qualifier). One table for the messages below and for the test that ties each declaration to the state table's
/// format (src/tests/interface.rs).
const STORAGE_FORMATS: [(vk::Format, u32, &str); 12] = [
    (vk::Format::R32G32B32A32_SFLOAT, 1, "rgba32f"),
    (vk::Format::R16G16B16A16_SFLOAT, 2, "rgba16f"),
    (vk::Format::R32_SFLOAT, 3, "r32f"),
    (vk::Format::R8G8B8A8_UNORM, 4, "rgba8"),
    (vk::Format::R16G16_SFLOAT, 7, "rg16f"),
    (vk::Format::R16_SFLOAT, 9, "r16f"),
    (vk::Format::R16G16_UNORM, 12, "rg16"),
    (vk::Format::R16_UNORM, 14, "r16"),
    (vk::Format::R8_UNORM, 15, "r8"),
    (vk::Format::R32_UINT, 33, "r32ui"),
    (vk::Format::R32G32_UINT, 35, "rg32ui"),
    (vk::Format::R16_UINT, 38, "r16ui"),
];

/// The SPIR-V ImageFormat a storage image of Vulkan format `format` is declared with (None: not one dnsr declares).
#[cfg(test)]
pub(crate) fn spirv_image_format(format: vk::Format) -> Option<u32> {
    STORAGE_FORMATS.iter().find(|(f, _, _)| *f == format).map(|&(_, code, _)| code)
}

/// A storage image format's GLSL layout qualifier, for messages (SPIR-V's ImageFormat enumerants).
fn image_format_name(format: u32) -> String {
    match STORAGE_FORMATS.iter().find(|(_, code, _)| *code == format) {
        Some((_, _, name)) => name.to_string(),
        None if format == 0 => "no format (Unknown)".to_string(),
        None => format!("SPIR-V image format {format}"),
    }
}

/// Reflects a module and checks every binding against the interface dnsr knows.
pub(crate) fn reflect(spirv: &[u8]) -> Result<Interface> {
    only_set_zero(spirv)?;
    let (raw, push_constant_bytes, push_layout) = reflect_module(spirv)?;
    let mut bindings = Vec::with_capacity(raw.len());
    let mut layouts = vec![(None, push_layout)];
    let mut uniform_bytes = None;
    for b in raw {
        let [name, type_name] = &b.names;
        let found = Resource::from_glsl_name(name).or_else(|| Resource::from_glsl_name(type_name));
        // Any other name is an engine image when it sits in the engine's binding range as an image.
        let engine = || {
            let slot = b.binding.checked_sub(ENGINE_BINDING_BASE)? as usize;
            let image = matches!(b.descriptor_type, Some(vk::DescriptorType::SAMPLED_IMAGE | vk::DescriptorType::STORAGE_IMAGE));
            Some((Resource::engine(slot).filter(|_| image)?, b.descriptor_type?))
        };
        let (resource, expected) = found.or_else(engine).ok_or_else(|| {
            Error::ShaderInterface(format!(
                "unknown binding '{name}' ({type_name}) at binding {}: dnsr's own are named dnsr_*, an engine's own \
                 images go at bindings {}..{} of set 0 (sampled or storage images)",
                b.binding,
                ENGINE_BINDING_BASE,
                ENGINE_BINDING_BASE + MAX_ENGINE_IMAGES as u32 - 1
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
        let classify_bytes = std::mem::size_of::<crate::passes::classify::ClassifyConstants>() as u32;
        if resource == Resource::ClassifyConstants && b.block_bytes != classify_bytes {
            return Err(Error::ShaderInterface(format!("classify constants block is {} bytes, host writes {classify_bytes}", b.block_bytes)));
        }
        if bindings.iter().any(|x: &ReflectedBinding| x.resource == resource || x.binding == b.binding) {
            return Err(Error::ShaderInterface(format!("binding '{name}' or number {} declared twice", b.binding)));
        }
        let format = if expected == vk::DescriptorType::STORAGE_IMAGE { b.image_format } else { 0 };
        bindings.push(ReflectedBinding { binding: b.binding, resource, descriptor_type: expected, format });
    }
    if bindings.len() > MAX_BINDINGS {
        return Err(Error::ShaderInterface(format!("{} bindings; at most {}", bindings.len(), MAX_BINDINGS)));
    }
    bindings.sort_by_key(|b| b.binding);
    let specializes = specialization_ids(spirv)?;
    Ok(Interface { bindings, push_constant_bytes, uniform_bytes, layouts, specializes })
}

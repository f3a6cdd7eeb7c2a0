//! Whether an engine's SPIR-V may be handed to the reflection library and the driver at all.
//!
//! Neither survives malformed SPIR-V: SPIRV-Reflect asserts or allocates what a corrupt count asks for, and drivers
//! crash in `vkCreateComputePipelines` on modules that break the spec's rules. So an override passes Khronos's
//! validator (SPIRV-Tools, the Vulkan 1.1 environment) first, with its id bound tied to the module's size, and
//! may only ask for capabilities, extensions and instruction sets the device is known to have.

use super::shader::{instructions, literal_string};
use spirv_tools::val::{Validator, ValidatorLimits, ValidatorOptions};

/// What the device offers beyond what every Vulkan 1.1 device does.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct DeviceOffers {
    /// The host enabled shaderFloat16 and 16-bit storage (`EnabledFeatures::float16`).
    pub float16: bool,
    /// `VkPhysicalDeviceSubgroupProperties::supportedOperations`, when compute shaders have subgroup operations.
    pub subgroup_operations: ash::vk::SubgroupFeatureFlags,
}

/// Longest validator message echoed in an error.
const MAX_MESSAGE_CHARS: usize = 300;

/// Checks a whole module (its header already read by `shader::instructions`); `Err` says what is wrong, for the
/// caller to name the override.
pub(crate) fn check(spirv: &[u8], offers: DeviceOffers) -> Result<(), String> {
    let words: Vec<u32> = spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    // The validator lets a nonzero reserved word through; Mesa's SPIR-V reader refuses it.
    if words[4] != 0 {
        return Err(format!("header word 4 (reserved, must be 0) is {:#x}", words[4]));
    }
    // The id bound sizes SPIRV-Reflect's tables: no larger than the module could use (an id needs an instruction
    // of at least two words to define it).
    let bound = words[3];
    if bound as usize > words.len() {
        return Err(format!("id bound {bound} exceeds the module's {} words", words.len()));
    }
    let validator = spirv_tools::val::create(Some(spirv_tools::TargetEnv::Vulkan_1_1));
    let options = ValidatorOptions { max_limits: vec![(ValidatorLimits::IdBound, words.len() as u32)], ..Default::default() };
    if let Err(e) = validator.validate(&words, Some(options)) {
        let what = e.diagnostic.as_ref().map_or_else(|| format!("{:?}", e.inner), |d| d.message.clone());
        return Err(format!("is not valid SPIR-V for Vulkan 1.1 (SPIRV-Tools: {})", cap(&what)));
    }
    // The validator has accepted every word count: the walk cannot fail.
    let all = instructions(spirv).map_err(|e| e.to_string())?;
    control_flow(&all)?;
    array_sizes(&all)?;
    for (opcode, operands) in &all {
        let (opcode, operands) = (*opcode, operands.as_slice());
        match opcode {
            OP_CAPABILITY => check_capability(operands[0], offers)?,
            OP_EXTENSION | OP_EXT_INST_IMPORT => {
                let name = literal_string(&operands[usize::from(opcode == OP_EXT_INST_IMPORT)..]);
                let known = match opcode {
                    OP_EXTENSION => {
                        name == "SPV_KHR_storage_buffer_storage_class" || (name == "SPV_KHR_16bit_storage" && offers.float16)
                    }
                    _ => name == "GLSL.std.450",
                };
                if !known {
                    return Err(format!("uses \"{}\", which dnsr does not enable", cap(&name)));
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Refuses a function whose blocks are not laid out as glslc lays them out, where the current SPIR-V rules and
/// older validators (the layers engines run) or drivers (Mesa's reader) disagree:
/// - a block that no branch and no merge or continue declaration reaches;
/// - a branch to a block laid out at or before the branching one that is not a loop header (a cross edge between
///   a selection's arms, say: the layer reports "Invalid back or cross-edge in the CFG" and lavapipe refuses the
///   module, leaking what it had parsed). glslc places every target but a loop's header after the branch.
fn control_flow(all: &[(u32, Vec<u32>)]) -> Result<(), String> {
    const OP_FUNCTION: u32 = 54;
    const OP_FUNCTION_END: u32 = 56;
    const OP_LABEL: u32 = 248;
    const OP_BRANCH: u32 = 249;
    const OP_BRANCH_CONDITIONAL: u32 = 250;
    const OP_SWITCH: u32 = 251;
    const OP_LOOP_MERGE: u32 = 246;
    const OP_SELECTION_MERGE: u32 = 247;
    /// One block of a function: its label, the blocks it names (branch targets, merge, continue), those it
    /// branches to, and whether it heads a loop.
    #[derive(Default)]
    struct Block {
        label: u32,
        named: Vec<u32>,
        jumps: Vec<u32>,
        loop_header: bool,
    }
    let check = |blocks: &[Block]| -> Result<(), String> {
        let index: std::collections::HashMap<u32, usize> = blocks.iter().enumerate().map(|(i, b)| (b.label, i)).collect();
        for (i, b) in blocks.iter().enumerate() {
            if let Some(&t) = b.jumps.iter().find(|t| index.get(t).is_some_and(|&j| j <= i && !blocks[j].loop_header)) {
                return Err(format!("block %{} of a function branches back to %{}, which is not a loop header", b.label, t));
            }
        }
        let mut reached = vec![false; blocks.len()];
        let mut stack = vec![0usize];
        while let Some(b) = stack.pop() {
            if !std::mem::replace(&mut reached[b], true) {
                stack.extend(blocks[b].named.iter().filter_map(|target| index.get(target)));
            }
        }
        match reached.iter().position(|r| !r) {
            Some(b) => Err(format!("block %{} of a function is never reached (not a branch target, merge or continue block)", blocks[b].label)),
            None => Ok(()),
        }
    };
    let mut blocks: Vec<Block> = Vec::new();
    for (opcode, ops) in all {
        if *opcode == OP_FUNCTION {
            blocks.clear();
        } else if *opcode == OP_LABEL {
            blocks.push(Block { label: ops[0], ..Block::default() });
        } else if *opcode == OP_FUNCTION_END && !blocks.is_empty() {
            check(&blocks)?;
        }
        match (*opcode, blocks.last_mut()) {
            (OP_LOOP_MERGE, Some(b)) => {
                b.named.extend(&ops[..2]);
                b.loop_header = true;
            }
            (OP_SELECTION_MERGE, Some(b)) => b.named.push(ops[0]),
            (OP_BRANCH, Some(b)) => {
                b.named.push(ops[0]);
                b.jumps.push(ops[0]);
            }
            (OP_BRANCH_CONDITIONAL, Some(b)) => {
                b.named.extend(&ops[1..3]);
                b.jumps.extend(&ops[1..3]);
            }
            // Selector, then the default and (literal, label) pairs: every word counts as named, since a literal
            // that happens to name a block can only make the reachability check more lenient; the default alone
            // is checked as a jump (a literal's width depends on the selector's type).
            (OP_SWITCH, Some(b)) => {
                b.named.extend(&ops[1..]);
                b.jumps.push(ops[1]);
            }
            _ => {}
        }
    }
    Ok(())
}

/// Most elements an array type of an override may hold, nested arrays multiplied: dnsr's own largest is a few
/// thousand (shared memory). Drivers allocate what a length asks for: lavapipe took 24 GB for a 9-element array
/// whose length constant a fuzzed override had turned into 635 million, and the process was killed.
const MAX_ARRAY_ELEMENTS: u64 = 1 << 20;

/// Refuses an array type (OpTypeArray) whose length, times its element arrays' lengths, exceeds
/// `MAX_ARRAY_ELEMENTS`. The validator has checked that each length is an integer constant defined before it.
fn array_sizes(all: &[(u32, Vec<u32>)]) -> Result<(), String> {
    const OP_CONSTANT: u32 = 43;
    const OP_SPEC_CONSTANT: u32 = 50;
    const OP_TYPE_ARRAY: u32 = 28;
    let mut constants = std::collections::HashMap::new();
    let mut elements = std::collections::HashMap::new();
    for (opcode, ops) in all {
        match (*opcode, ops.as_slice()) {
            // Result type, result id, value (low word first; a 64-bit constant has two).
            (OP_CONSTANT | OP_SPEC_CONSTANT, [_, id, value @ ..]) => {
                let wide = value.iter().rev().fold(0u64, |acc, &w| acc.saturating_mul(1 << 32).saturating_add(w as u64));
                constants.insert(*id, wide);
            }
            (OP_TYPE_ARRAY, [id, element, length, ..]) => {
                let inner = elements.get(element).copied().unwrap_or(1u64);
                let total = constants.get(length).copied().unwrap_or(u64::MAX).saturating_mul(inner);
                if total > MAX_ARRAY_ELEMENTS {
                    return Err(format!("declares an array type %{id} of {total} elements; dnsr allows {MAX_ARRAY_ELEMENTS}"));
                }
                elements.insert(*id, total);
            }
            _ => {}
        }
    }
    Ok(())
}

const OP_EXTENSION: u32 = 10;
const OP_EXT_INST_IMPORT: u32 = 11;
const OP_CAPABILITY: u32 = 17;

fn cap(s: &str) -> String {
    match s.char_indices().nth(MAX_MESSAGE_CHARS) {
        Some((end, _)) => format!("{}...", &s[..end]),
        None => s.to_owned(),
    }
}

/// What an override may declare a capability with.
#[derive(Clone, Copy)]
enum Needs {
    /// Every Vulkan 1.1 device has it in compute shaders (dnsr's own passes use Shader, ImageQuery,
    /// StorageImageExtendedFormats and ImageBuffer).
    Nothing,
    /// The host enabled `EnabledFeatures::float16`.
    Float16,
    /// The device reports this subgroup operation for compute shaders.
    Subgroup(ash::vk::SubgroupFeatureFlags),
}

const CAPABILITIES: &[(u32, &str, Needs)] = {
    use ash::vk::SubgroupFeatureFlags as S;
    &[
        (0, "Matrix", Needs::Nothing),
        (1, "Shader", Needs::Nothing),
        (9, "Float16", Needs::Float16),
        (43, "Sampled1D", Needs::Nothing),
        (44, "Image1D", Needs::Nothing),
        (46, "SampledBuffer", Needs::Nothing),
        (47, "ImageBuffer", Needs::Nothing),
        (49, "StorageImageExtendedFormats", Needs::Nothing),
        (50, "ImageQuery", Needs::Nothing),
        (61, "GroupNonUniform", Needs::Subgroup(S::BASIC)),
        (62, "GroupNonUniformVote", Needs::Subgroup(S::VOTE)),
        (63, "GroupNonUniformArithmetic", Needs::Subgroup(S::ARITHMETIC)),
        (64, "GroupNonUniformBallot", Needs::Subgroup(S::BALLOT)),
        (65, "GroupNonUniformShuffle", Needs::Subgroup(S::SHUFFLE)),
        (66, "GroupNonUniformShuffleRelative", Needs::Subgroup(S::SHUFFLE_RELATIVE)),
        (67, "GroupNonUniformClustered", Needs::Subgroup(S::CLUSTERED)),
        (68, "GroupNonUniformQuad", Needs::Subgroup(S::QUAD)),
        (4433, "StorageBuffer16BitAccess", Needs::Float16),
    ]
};

/// Refuses a capability dnsr does not list, or one the device does not offer.
fn check_capability(c: u32, offers: DeviceOffers) -> Result<(), String> {
    let Some(&(_, name, needs)) = CAPABILITIES.iter().find(|(id, _, _)| *id == c) else {
        return Err(format!("declares capability {c}, which dnsr does not accept in an override (docs/callbacks.md lists those it does)"));
    };
    let offered = match needs {
        Needs::Nothing => true,
        Needs::Float16 => offers.float16,
        Needs::Subgroup(op) => offers.subgroup_operations.contains(op),
    };
    if offered { Ok(()) } else { Err(format!("declares capability {name}, which the device does not offer (or the host did not enable)")) }
}

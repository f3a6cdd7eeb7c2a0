//! Reflection of descriptor bindings and push constants through SPIRV-Reflect's C API (the `spirv-reflect`
//! crate's `ffi`). The crate's safe wrapper builds slices from null pointers for empty member lists, which is
//! undefined behaviour, so only the fields dnsr needs are read here, null-checked.
//!
//! SPIRV-Reflect as shipped in the crate asserts (aborts the process) on SPIR-V 1.4+ interface variables and
//! skips StorageBuffer blocks on 1.3, so dnsr compiles for SPIR-V 1.3 and binds images and uniform blocks only;
//! anything newer is refused before it reaches the C code.

use crate::error::{Error, Result};
use ash::vk;
use spirv_reflect::ffi;
use std::ffi::CStr;

/// Highest SPIR-V version the bundled SPIRV-Reflect handles safely.
pub(crate) const MAX_SPIRV_VERSION: u32 = 0x0001_0300;
const SPIRV_MAGIC: u32 = 0x0723_0203;

/// One descriptor binding as declared in SPIR-V.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct RawBinding {
    /// Variable name, or the block's type name for an anonymous uniform block.
    pub names: [String; 2],
    pub set: u32,
    pub binding: u32,
    pub count: u32,
    pub descriptor_type: Option<vk::DescriptorType>,
    /// An image's declared format, as SPIR-V's ImageFormat enumerant (0, Unknown, for sampled images).
    pub image_format: u32,
    /// Size of a uniform block in bytes (0 otherwise).
    pub block_bytes: u32,
    /// A uniform block's members, depth first (empty otherwise).
    pub block_layout: Vec<MemberLayout>,
}

/// One member of a block as the shader reads it: where it lies and what type it is read as. Two modules whose
/// blocks list the same members read the bytes dnsr writes the same way.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct MemberLayout {
    pub offset: u32,
    pub size: u32,
    pub type_flags: u32,
    /// Scalar width and signedness, vector components, matrix columns, rows and stride.
    pub numeric: [u32; 6],
    /// Array dimensions, then the array stride.
    pub array: Vec<u32>,
}

/// Deepest block nesting read (dnsr's own blocks are flat).
const MAX_BLOCK_DEPTH: u32 = 8;

fn block_layout(block: &ffi::SpvReflectBlockVariable, depth: u32, out: &mut Vec<MemberLayout>) -> Result<()> {
    if depth > MAX_BLOCK_DEPTH {
        return Err(Error::ShaderInterface(format!("a block nests structs deeper than {MAX_BLOCK_DEPTH}")));
    }
    let members: &[ffi::SpvReflectBlockVariable] = match block.members.is_null() {
        true => &[],
        // SAFETY: SPIRV-Reflect's block holds member_count members.
        false => unsafe { std::slice::from_raw_parts(block.members, block.member_count as usize) },
    };
    for m in members {
        let (n, a) = (&m.numeric, &m.array);
        let dims = &a.dims[..(a.dims_count as usize).min(a.dims.len())];
        out.push(MemberLayout {
            offset: m.absolute_offset,
            size: m.size,
            type_flags: unsafe { m.type_description.as_ref() }.map_or(0, |t| t.type_flags),
            numeric: [n.scalar.width, n.scalar.signedness, n.vector.component_count, n.matrix.column_count, n.matrix.row_count, n.matrix.stride],
            array: dims.iter().copied().chain([a.stride]).collect(),
        });
        block_layout(m, depth + 1, out)?;
    }
    Ok(())
}

fn c_string(p: *const std::os::raw::c_char) -> String {
    if p.is_null() { String::new() } else { unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned() }
}

fn descriptor_type(t: ffi::SpvReflectDescriptorType) -> Option<vk::DescriptorType> {
    Some(match t {
        ffi::SpvReflectDescriptorType_SPV_REFLECT_DESCRIPTOR_TYPE_SAMPLED_IMAGE => vk::DescriptorType::SAMPLED_IMAGE,
        ffi::SpvReflectDescriptorType_SPV_REFLECT_DESCRIPTOR_TYPE_STORAGE_IMAGE => vk::DescriptorType::STORAGE_IMAGE,
        ffi::SpvReflectDescriptorType_SPV_REFLECT_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER => {
            vk::DescriptorType::COMBINED_IMAGE_SAMPLER
        }
        ffi::SpvReflectDescriptorType_SPV_REFLECT_DESCRIPTOR_TYPE_UNIFORM_BUFFER => vk::DescriptorType::UNIFORM_BUFFER,
        ffi::SpvReflectDescriptorType_SPV_REFLECT_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER => vk::DescriptorType::STORAGE_TEXEL_BUFFER,
        _ => return None,
    })
}

/// Reflects `spirv`: its descriptor bindings, the largest push-constant block size and the push constants' members.
pub(crate) fn reflect_module(spirv: &[u8]) -> Result<(Vec<RawBinding>, u32, Vec<MemberLayout>)> {
    if spirv.len() < 20 || spirv.len() % 4 != 0 {
        return Err(Error::ShaderInterface(format!("SPIR-V of {} bytes is not a whole module", spirv.len())));
    }
    let word = |i: usize| u32::from_le_bytes([spirv[4 * i], spirv[4 * i + 1], spirv[4 * i + 2], spirv[4 * i + 3]]);
    if word(0) != SPIRV_MAGIC {
        return Err(Error::ShaderInterface("not SPIR-V (bad magic number)".into()));
    }
    if word(1) > MAX_SPIRV_VERSION {
        return Err(Error::ShaderInterface(format!(
            "SPIR-V version {}.{} is newer than 1.3; compile with --target-env=vulkan1.1",
            word(1) >> 16,
            (word(1) >> 8) & 0xff
        )));
    }
    // The C code reads the words in place; give it a 4-byte aligned copy.
    let words: Vec<u32> = (0..spirv.len() / 4).map(word).collect();
    let mut module = std::mem::MaybeUninit::<ffi::SpvReflectShaderModule>::zeroed();
    let r = unsafe { ffi::spvReflectCreateShaderModule(spirv.len(), words.as_ptr().cast(), module.as_mut_ptr()) };
    if r != ffi::SpvReflectResult_SPV_REFLECT_RESULT_SUCCESS {
        return Err(Error::ShaderInterface(format!("SPIRV-Reflect could not parse the module (code {r})")));
    }
    let mut module = unsafe { module.assume_init() };
    let result = read(&module);
    unsafe { ffi::spvReflectDestroyShaderModule(&mut module) };
    result
}

/// SPIRV-Reflect's two-call enumeration: ask for the count, then fill that many pointers.
fn enumerate<T>(
    what: &str,
    module: &ffi::SpvReflectShaderModule,
    f: unsafe extern "C" fn(*const ffi::SpvReflectShaderModule, *mut u32, *mut *mut T) -> ffi::SpvReflectResult,
) -> Result<Vec<*mut T>> {
    let fail = |r| Error::ShaderInterface(format!("SPIRV-Reflect {what} enumeration failed (code {r})"));
    let mut count = 0u32;
    let r = unsafe { f(module, &mut count, std::ptr::null_mut()) };
    if r != ffi::SpvReflectResult_SPV_REFLECT_RESULT_SUCCESS {
        return Err(fail(r));
    }
    let mut ptrs = vec![std::ptr::null_mut::<T>(); count as usize];
    if count > 0 {
        let r = unsafe { f(module, &mut count, ptrs.as_mut_ptr()) };
        if r != ffi::SpvReflectResult_SPV_REFLECT_RESULT_SUCCESS {
            return Err(fail(r));
        }
    }
    Ok(ptrs)
}

fn read(module: &ffi::SpvReflectShaderModule) -> Result<(Vec<RawBinding>, u32, Vec<MemberLayout>)> {
    let ptrs = enumerate("binding", module, ffi::spvReflectEnumerateDescriptorBindings)?;
    let mut bindings = Vec::with_capacity(ptrs.len());
    for p in ptrs {
        // SAFETY: SPIRV-Reflect returned these pointers into the live module.
        let b = unsafe { p.as_ref() }.ok_or_else(|| Error::ShaderInterface("null binding".into()))?;
        let type_name = unsafe { b.type_description.as_ref() }.map(|t| c_string(t.type_name)).unwrap_or_default();
        let descriptor_type = descriptor_type(b.descriptor_type);
        let uniform = descriptor_type == Some(vk::DescriptorType::UNIFORM_BUFFER);
        let block_bytes = if uniform { b.block.size } else { 0 };
        let mut block_layout = Vec::new();
        if uniform {
            self::block_layout(&b.block, 0, &mut block_layout)?;
        }
        bindings.push(RawBinding {
            names: [c_string(b.name), type_name],
            set: b.set,
            binding: b.binding,
            count: b.count,
            descriptor_type,
            image_format: b.image.image_format as u32,
            block_bytes,
            block_layout,
        });
    }
    let blocks = enumerate("push constant", module, ffi::spvReflectEnumeratePushConstantBlocks)?;
    let blocks: Vec<&ffi::SpvReflectBlockVariable> = blocks.iter().filter_map(|&p| unsafe { p.as_ref() }).collect();
    let push_bytes = blocks.iter().map(|b| b.size).max().unwrap_or(0);
    let mut push_layout = Vec::new();
    for b in blocks {
        block_layout(b, 0, &mut push_layout)?;
    }
    Ok((bindings, push_bytes, push_layout))
}

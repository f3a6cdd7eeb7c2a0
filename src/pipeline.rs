//! A pass's pipeline: its module's interface, reflected against what the passes bind (interface.rs), and the Vulkan
//! pipeline made with that layout (gpu::shader). Its descriptors for a dispatch come from the pass's binding table.

use crate::constants::FrameConstants;
use crate::error::{Error, Result};
use crate::gpu::descriptors::{Descriptor, Descriptors};
use crate::gpu::loader::Vk;
use crate::gpu::shader::{Layout, Pipeline};
use crate::interface::{reflect, Interface};
use crate::passes::bindings::BindingTable;
use ash::vk;

pub(crate) struct PassPipeline {
    pub vulkan: Pipeline,
    pub interface: Interface,
}

impl PassPipeline {
    /// Reflects `spirv`, checks its constants block against the host's, and makes its pipelines (one per
    /// combination of the specialization constants it declares).
    pub(crate) fn new(vk: &Vk, name: &str, spirv: &[u8], push_descriptors: bool) -> Result<PassPipeline> {
        let interface = Self::interface(spirv)?;
        let vulkan = Self::with_layout(&interface, |layout| Pipeline::new(vk, name, spirv, layout, push_descriptors))?;
        Ok(PassPipeline { vulkan, interface })
    }

    /// The driver's statistics of `spirv`'s pipeline specialized with `spec` (gpu::shader::Pipeline::statistics).
    pub(crate) fn statistics(vk: &Vk, name: &str, spirv: &[u8], spec: u32) -> Result<Vec<(String, String)>> {
        let interface = Self::interface(spirv)?;
        Self::with_layout(&interface, |layout| Pipeline::statistics(vk, name, spirv, layout, spec))
    }

    /// Calls `f` with the pipeline layout that `interface` declares.
    fn with_layout<T>(interface: &Interface, f: impl FnOnce(&Layout) -> Result<T>) -> Result<T> {
        let bindings: Vec<(u32, vk::DescriptorType)> = interface.bindings.iter().map(|b| (b.binding, b.descriptor_type)).collect();
        f(&Layout { bindings: &bindings, push_constant_bytes: interface.push_constant_bytes, specializes: interface.specializes })
    }

    /// `spirv`'s reflected interface, its constants block checked against the host's.
    fn interface(spirv: &[u8]) -> Result<Interface> {
        let interface = reflect(spirv)?;
        if let Some(bytes) = interface.uniform_bytes {
            let expected = std::mem::size_of::<FrameConstants>() as u32;
            if bytes != expected {
                return Err(Error::ShaderInterface(format!("constants block is {bytes} bytes, host writes {expected}")));
            }
        }
        Ok(interface)
    }

    /// What `table` binds at each binding of this pipeline, images with `sampler` (which only combined image
    /// samplers read).
    pub(crate) fn descriptors(&self, table: &BindingTable, sampler: vk::Sampler) -> Descriptors {
        self.interface
            .bindings
            .iter()
            .map(|b| {
                let bound = table[b.resource as usize];
                Descriptor {
                    binding: b.binding,
                    descriptor_type: b.descriptor_type,
                    image: vk::DescriptorImageInfo { sampler, image_view: bound.view, image_layout: bound.layout },
                    buffer: vk::DescriptorBufferInfo { buffer: bound.buffer, offset: bound.offset, range: bound.range },
                    texel: bound.texel,
                }
            })
            .collect()
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        self.vulkan.destroy(vk);
    }
}

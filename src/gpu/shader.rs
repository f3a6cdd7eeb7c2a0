//! SPIR-V words and compute pipelines: a module's instructions, and pipelines with the layout their caller read
//! from the module, compiled once per combination of the specialization constants it declares.

use crate::error::{vk_check, Error, Result};
use crate::gpu::loader::Vk;
use ash::vk;

/// A module's instructions: (opcode, operands), after checking the header.
pub(crate) fn instructions(spirv: &[u8]) -> Result<Vec<(u32, Vec<u32>)>> {
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

/// A literal string operand (NUL-terminated, packed four bytes a word).
pub(crate) fn literal_string(words: &[u32]) -> String {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).take_while(|&b| b != 0).collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// What a pipeline's layout is made of, as its caller read it from the module: the descriptor bindings of set 0
/// (number and type), the push-constant bytes, and the specialization constant ids the module declares (bit i: id
/// i). A pipeline is compiled per combination of those ids, so the caller keeps them few.
pub(crate) struct Layout<'a> {
    pub bindings: &'a [(u32, vk::DescriptorType)],
    pub push_constant_bytes: u32,
    pub specializes: u32,
}

/// A compute pipeline, compiled once per combination of the specialization constants its module declares.
pub(crate) struct Pipeline {
    /// Indexed by a combination of specialization constants (bit i: id i) restricted to `specializes`; null where
    /// that combination is not compiled.
    variants: Vec<vk::Pipeline>,
    specializes: u32,
    pub layout: vk::PipelineLayout,
    pub set_layout: vk::DescriptorSetLayout,
    /// The type of each binding of the set layout, in binding order (descriptor pools are sized from them).
    pub descriptor_types: Vec<vk::DescriptorType>,
    /// Compiled with VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR (`Pipeline::statistics`).
    capture_statistics: bool,
}

impl Pipeline {
    /// One pipeline per combination of the specialization constants the module declares.
    pub(crate) fn new(vk: &Vk, name: &str, spirv: &[u8], layout: &Layout, push_descriptors: bool) -> Result<Pipeline> {
        Self::compile(vk, name, spirv, layout, push_descriptors, false)
    }

    /// What the driver reports of the pipeline compiled for specialization `spec` (VK_KHR_pipeline_executable_properties:
    /// on NVIDIA its register count, shared memory and binary size), as (name, value) pairs of each executable.
    /// The host must have enabled the extension and its `pipelineExecutableInfo` feature; without the extension
    /// this is `Error::MissingFeature`.
    pub(crate) fn statistics(vk: &Vk, name: &str, spirv: &[u8], layout: &Layout, spec: u32) -> Result<Vec<(String, String)>> {
        let get = c"vkGetPipelineExecutableStatisticsKHR";
        // A device-level command of an extension the host did not enable is null here, and ash would panic on it.
        if unsafe { vk.instance.get_device_proc_addr(vk.device.handle(), get.as_ptr()) }.is_none() {
            return Err(Error::MissingFeature("VK_KHR_pipeline_executable_properties (pipelineExecutableInfo) enabled"));
        }
        let mut p = Self::compile(vk, name, spirv, layout, false, true)?;
        let ext = ash::khr::pipeline_executable_properties::Device::new(&vk.instance, &vk.device);
        let pipeline = p.for_frame(spec);
        let executables = vk_check("vkGetPipelineExecutablePropertiesKHR", unsafe {
            ext.get_pipeline_executable_properties(&vk::PipelineInfoKHR::default().pipeline(pipeline))
        });
        let mut out = Vec::new();
        let result = executables.and_then(|executables| {
            for index in 0..executables.len() as u32 {
                let info = vk::PipelineExecutableInfoKHR::default().pipeline(pipeline).executable_index(index);
                let stats = vk_check("vkGetPipelineExecutableStatisticsKHR", unsafe { ext.get_pipeline_executable_statistics(&info) })?;
                out.extend(stats.iter().map(|s| (s.name_as_c_str().map_or(String::new(), |c| c.to_string_lossy().into_owned()), statistic_value(s))));
            }
            Ok(())
        });
        p.destroy(vk);
        result.map(|()| out)
    }

    fn compile(vk: &Vk, name: &str, spirv: &[u8], layout: &Layout, push_descriptors: bool, capture_statistics: bool) -> Result<Pipeline> {
        // Combinations up to the highest declared id: variants[c] for every c with no bit outside `specializes`.
        let combinations = 1usize << (u32::BITS - layout.specializes.leading_zeros());
        let mut p = Pipeline {
            variants: vec![vk::Pipeline::null(); combinations],
            specializes: layout.specializes,
            layout: vk::PipelineLayout::null(),
            set_layout: vk::DescriptorSetLayout::null(),
            descriptor_types: layout.bindings.iter().map(|&(_, t)| t).collect(),
            capture_statistics,
        };
        let result = p.create(vk, spirv, layout, push_descriptors);
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

    fn create(&mut self, vk: &Vk, spirv: &[u8], layout: &Layout, push_descriptors: bool) -> Result<()> {
        let (device, alloc) = (&vk.device, vk.alloc());
        let layout_bindings: Vec<_> = layout
            .bindings
            .iter()
            .map(|&(binding, descriptor_type)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(binding)
                    .descriptor_type(descriptor_type)
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
        let range = vk::PushConstantRange::default().stage_flags(vk::ShaderStageFlags::COMPUTE).size(layout.push_constant_bytes);
        let ranges = if layout.push_constant_bytes > 0 { std::slice::from_ref(&range) } else { &[] };
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
        let specializes = self.specializes;
        let ids: Vec<u32> = (0..u32::BITS).filter(|i| specializes & (1 << i) != 0).collect();
        let entries: Vec<vk::SpecializationMapEntry> = (0..ids.len() as u32)
            .map(|k| vk::SpecializationMapEntry { constant_id: ids[k as usize], offset: 4 * k, size: 4 })
            .collect();
        let mut result = Ok(());
        for combination in (0..self.variants.len() as u32).filter(|c| c & !specializes == 0) {
            let data: Vec<u8> = ids.iter().flat_map(|i| ((combination >> i) & 1).to_ne_bytes()).collect();
            let spec = vk::SpecializationInfo::default().map_entries(&entries).data(&data);
            let flags = if self.capture_statistics { vk::PipelineCreateFlags::CAPTURE_STATISTICS_KHR } else { vk::PipelineCreateFlags::empty() };
            let info = vk::ComputePipelineCreateInfo::default().flags(flags).stage(stage.specialization_info(&spec)).layout(self.layout);
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
    pub(crate) fn for_frame(&self, spec: u32) -> vk::Pipeline {
        self.variants[(spec & self.specializes) as usize]
    }

    pub(crate) fn destroy(&mut self, vk: &Vk) {
        let (device, alloc) = (&vk.device, vk.alloc());
        unsafe {
            for &v in &self.variants {
                device.destroy_pipeline(v, alloc);
            }
            device.destroy_pipeline_layout(self.layout, alloc);
            device.destroy_descriptor_set_layout(self.set_layout, alloc);
        }
        self.variants.fill(vk::Pipeline::null());
        self.layout = vk::PipelineLayout::null();
        self.set_layout = vk::DescriptorSetLayout::null();
    }
}

/// A pipeline statistic's value as text, whatever its format.
fn statistic_value(s: &vk::PipelineExecutableStatisticKHR) -> String {
    // The union's member is the one `format` names.
    unsafe {
        match s.format {
            vk::PipelineExecutableStatisticFormatKHR::BOOL32 => (s.value.b32 != 0).to_string(),
            vk::PipelineExecutableStatisticFormatKHR::INT64 => s.value.i64.to_string(),
            vk::PipelineExecutableStatisticFormatKHR::UINT64 => s.value.u64.to_string(),
            _ => s.value.f64.to_string(),
        }
    }
}

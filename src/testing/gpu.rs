//! A minimal Vulkan host: instance (validation + synchronization validation on request), one device, one queue,
//! images with staging upload/readback. Plays the engine's part in tests and the demo.

use crate::{ContextCreateInfo, EnabledFeatures};
use ash::vk;
use std::ffi::{c_void, CStr};
use std::sync::{Arc, Mutex};

/// What the host device should enable.
#[derive(Clone, Copy, Debug)]
pub struct GpuOptions {
    /// Enable VK_LAYER_KHRONOS_validation with synchronization validation; every message is collected.
    pub validation: bool,
    /// Enable VK_KHR_push_descriptor when the device has it.
    pub push_descriptor: bool,
    /// Enable shaderFloat16 + storageBuffer16BitAccess when the device has them.
    pub float16: bool,
    /// Enable VK_KHR_pipeline_executable_properties (pipelineExecutableInfo) when the device has it, for
    /// `Context::pipeline_statistics`.
    pub pipeline_statistics: bool,
}

impl Default for GpuOptions {
    fn default() -> Self {
        GpuOptions { validation: true, push_descriptor: true, float16: true, pipeline_statistics: false }
    }
}

/// The host side of a test or demo.
pub struct Gpu {
    /// Loader entry.
    pub entry: ash::Entry,
    /// Instance.
    pub instance: ash::Instance,
    /// Physical device in use.
    pub physical_device: vk::PhysicalDevice,
    /// Device.
    pub device: ash::Device,
    /// Queue (compute + transfer capable).
    pub queue: vk::Queue,
    /// Its family.
    pub queue_family: u32,
    command_pool: vk::CommandPool,
    debug: Option<(ash::ext::debug_utils::Instance, vk::DebugUtilsMessengerEXT, *mut Arc<Mutex<Vec<String>>>)>,
    /// Validation messages collected so far.
    pub messages: Arc<Mutex<Vec<String>>>,
    /// Optional features actually enabled.
    pub features: EnabledFeatures,
    /// VK_KHR_pipeline_executable_properties is enabled (`GpuOptions::pipeline_statistics` and the device has it).
    pub pipeline_statistics: bool,
    /// Device name as the driver reports it.
    pub device_name: String,
    /// Instance/device API version used.
    pub api_version: u32,
}

unsafe extern "system" fn on_message(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    _types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    let sink = unsafe { &*(user as *const Arc<Mutex<Vec<String>>>) };
    let text = unsafe { data.as_ref().and_then(|d| d.message_as_c_str()).map(|m| m.to_string_lossy().into_owned()) }
        .unwrap_or_default();
    if let Ok(mut v) = sink.lock() {
        v.push(format!("{severity:?}: {text}"));
    }
    vk::FALSE
}

/// A host image with its memory.
pub struct TestImage {
    /// Image.
    pub image: vk::Image,
    /// Its view.
    pub view: vk::ImageView,
    memory: vk::DeviceMemory,
    /// Format.
    pub format: vk::Format,
    /// Width.
    pub width: u32,
    /// Height.
    pub height: u32,
    /// Bytes per texel.
    pub texel_bytes: u32,
    /// The layout the image rests in between uses (copies move it to a transfer layout and back).
    pub layout: vk::ImageLayout,
}

impl TestImage {
    /// Wraps an image owned elsewhere (e.g. one of dnsr's internal images) for `download`. Never destroy it.
    pub fn borrowed(image: vk::Image, format: vk::Format, width: u32, height: u32, layout: vk::ImageLayout) -> TestImage {
        TestImage {
            image,
            view: vk::ImageView::null(),
            memory: vk::DeviceMemory::null(),
            format,
            width,
            height,
            texel_bytes: texel_bytes(format),
            layout,
        }
    }

    /// The image as a dnsr host image in its resting layout.
    pub fn host(&self) -> crate::HostImage {
        crate::HostImage {
            image: self.image,
            view: self.view,
            format: self.format,
            layout: self.layout,
            width: self.width,
            height: self.height,
        }
    }
}

fn texel_bytes(format: vk::Format) -> u32 {
    match format {
        vk::Format::R8_UNORM => 1,
        vk::Format::R16_SFLOAT | vk::Format::R16_UINT | vk::Format::R16_UNORM => 2,
        vk::Format::R32_UINT | vk::Format::R32_SFLOAT | vk::Format::R8G8B8A8_UNORM | vk::Format::D32_SFLOAT => 4,
        vk::Format::A2B10G10R10_UNORM_PACK32 => 4,
        vk::Format::R32G32_SFLOAT | vk::Format::R32G32_UINT | vk::Format::R16G16B16A16_SFLOAT => 8,
        vk::Format::R32G32B32A32_SFLOAT => 16,
        vk::Format::R16G16_SFLOAT | vk::Format::R16G16_UNORM => 4,
        other => panic!("test harness has no texel size for {other:?}"),
    }
}

impl Gpu {
    /// Creates instance and device. Panics with a clear message when no Vulkan device or (if requested) no
    /// validation layer is installed: tests must not silently run without them.
    pub fn new(opts: GpuOptions) -> Gpu {
        let entry = unsafe { ash::Entry::load() }.expect("Vulkan loader (libvulkan.so.1) not found: install libvulkan1");
        let api_version = vk::API_VERSION_1_2;
        let app = vk::ApplicationInfo::default().application_name(c"dnsr-host").api_version(api_version);
        let layers = [c"VK_LAYER_KHRONOS_validation".as_ptr()];
        let extensions = [ash::ext::debug_utils::NAME.as_ptr()];
        let enables = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
        let mut features = vk::ValidationFeaturesEXT::default().enabled_validation_features(&enables);
        let mut info = vk::InstanceCreateInfo::default().application_info(&app);
        if opts.validation {
            let available = unsafe { entry.enumerate_instance_layer_properties() }.unwrap_or_default();
            let has = available.iter().any(|l| l.layer_name_as_c_str().ok() == Some(c"VK_LAYER_KHRONOS_validation"));
            assert!(has, "VK_LAYER_KHRONOS_validation is not installed (apt-get install vulkan-validationlayers)");
            info = info.enabled_layer_names(&layers).enabled_extension_names(&extensions).push_next(&mut features);
        }
        let instance = unsafe { entry.create_instance(&info, None) }.expect("vkCreateInstance");
        let messages = Arc::new(Mutex::new(Vec::new()));
        let debug = opts.validation.then(|| {
            let loader = ash::ext::debug_utils::Instance::new(&entry, &instance);
            let user = Box::into_raw(Box::new(messages.clone()));
            let info = vk::DebugUtilsMessengerCreateInfoEXT::default()
                .message_severity(vk::DebugUtilsMessageSeverityFlagsEXT::WARNING | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR)
                .message_type(
                    vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
                        | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                        | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE,
                )
                .pfn_user_callback(Some(on_message))
                .user_data(user as *mut c_void);
            let messenger = unsafe { loader.create_debug_utils_messenger(&info, None) }.expect("debug messenger");
            (loader, messenger, user)
        });

        let devices = unsafe { instance.enumerate_physical_devices() }.expect("enumerate devices");
        let wanted = std::env::var("DNSR_DEVICE").ok();
        let name_of = |pd: vk::PhysicalDevice| {
            let p = unsafe { instance.get_physical_device_properties(pd) };
            p.device_name_as_c_str().map(|c| c.to_string_lossy().into_owned()).unwrap_or_default()
        };
        let physical_device = *devices
            .iter()
            .find(|&&pd| wanted.as_deref().is_none_or(|w| name_of(pd).contains(w)))
            .unwrap_or_else(|| panic!("no Vulkan device (wanted {wanted:?}); install mesa-vulkan-drivers for lavapipe"));
        let device_name = name_of(physical_device);

        let families = unsafe { instance.get_physical_device_queue_family_properties(physical_device) };
        let queue_family = families
            .iter()
            .position(|f| f.queue_flags.contains(vk::QueueFlags::COMPUTE))
            .expect("a compute queue") as u32;

        let exts = unsafe { instance.enumerate_device_extension_properties(physical_device) }.unwrap_or_default();
        let has_ext = |n: &CStr| exts.iter().any(|e| e.extension_name_as_c_str().ok() == Some(n));
        let push_descriptor = opts.push_descriptor && has_ext(ash::khr::push_descriptor::NAME);
        let mut f11 = vk::PhysicalDeviceVulkan11Features::default();
        let mut f12 = vk::PhysicalDeviceVulkan12Features::default();
        let mut f2 = vk::PhysicalDeviceFeatures2::default().push_next(&mut f11).push_next(&mut f12);
        unsafe { instance.get_physical_device_features2(physical_device, &mut f2) };
        let float16 = opts.float16 && f12.shader_float16 != 0 && f11.storage_buffer16_bit_access != 0;

        let mut e11 = vk::PhysicalDeviceVulkan11Features::default().storage_buffer16_bit_access(float16);
        let mut e12 = vk::PhysicalDeviceVulkan12Features::default().shader_float16(float16);
        let pipeline_statistics = opts.pipeline_statistics && has_ext(ash::khr::pipeline_executable_properties::NAME);
        let device_exts: Vec<*const i8> = [(push_descriptor, ash::khr::push_descriptor::NAME), (pipeline_statistics, ash::khr::pipeline_executable_properties::NAME)]
            .into_iter()
            .filter_map(|(on, name)| on.then_some(name.as_ptr()))
            .collect();
        let mut executables = vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default().pipeline_executable_info(pipeline_statistics);
        let priorities = [1.0f32];
        let queue_info = vk::DeviceQueueCreateInfo::default().queue_family_index(queue_family).queue_priorities(&priorities);
        let mut info = vk::DeviceCreateInfo::default()
            .queue_create_infos(std::slice::from_ref(&queue_info))
            .enabled_extension_names(&device_exts)
            .push_next(&mut e11)
            .push_next(&mut e12);
        // An extension's feature struct only with the extension enabled (VUID-VkDeviceCreateInfo-pNext-pNext).
        if pipeline_statistics {
            info = info.push_next(&mut executables);
        }
        let device = unsafe { instance.create_device(physical_device, &info, None) }.expect("vkCreateDevice");
        let queue = unsafe { device.get_device_queue(queue_family, 0) };
        let pool_info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(queue_family)
            .flags(vk::CommandPoolCreateFlags::RESET_COMMAND_BUFFER);
        let command_pool = unsafe { device.create_command_pool(&pool_info, None) }.expect("command pool");
        Gpu {
            entry,
            instance,
            physical_device,
            device,
            queue,
            queue_family,
            command_pool,
            debug,
            messages,
            features: EnabledFeatures { float16, push_descriptor },
            pipeline_statistics,
            device_name,
            api_version,
        }
    }

    /// A create info for this device with its enabled features.
    pub fn create_info(&self, width: u32, height: u32) -> ContextCreateInfo {
        let mut info = ContextCreateInfo::new(
            self.instance.handle(),
            self.physical_device,
            self.device.handle(),
            self.entry.static_fn().get_instance_proc_addr,
            self.instance.fp_v1_0().get_device_proc_addr,
            width,
            height,
        );
        info.api_version = self.api_version;
        info.queue_family_index = self.queue_family;
        info.features = self.features;
        info
    }

    /// Drains the collected validation messages.
    pub fn take_messages(&self) -> Vec<String> {
        std::mem::take(&mut *self.messages.lock().unwrap())
    }

    /// Panics listing every validation message collected so far.
    pub fn assert_clean(&self) {
        let m = self.take_messages();
        assert!(m.is_empty(), "{} validation message(s):\n{}", m.len(), m.join("\n"));
    }

    /// A memory type index of `bits` with `flags`.
    pub fn memory_type(&self, bits: u32, flags: vk::MemoryPropertyFlags) -> u32 {
        let props = unsafe { self.instance.get_physical_device_memory_properties(self.physical_device) };
        (0..props.memory_type_count)
            .find(|&i| bits & (1 << i) != 0 && props.memory_types[i as usize].property_flags.contains(flags))
            .expect("memory type")
    }

    /// A 2D image resting in `layout`, usable as sampled, storage (where supported) and transfer source/target.
    pub fn image(&self, format: vk::Format, width: u32, height: u32, layout: vk::ImageLayout) -> TestImage {
        let feats = unsafe { self.instance.get_physical_device_format_properties(self.physical_device, format) }.optimal_tiling_features;
        let depth = format == vk::Format::D32_SFLOAT;
        let mut usage = vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST | vk::ImageUsageFlags::TRANSFER_SRC;
        if feats.contains(vk::FormatFeatureFlags::STORAGE_IMAGE) {
            usage |= vk::ImageUsageFlags::STORAGE;
        }
        if depth {
            usage |= vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT;
        }
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(format)
            .extent(vk::Extent3D { width, height, depth: 1 })
            .mip_levels(1)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(usage);
        let d = &self.device;
        let image = unsafe { d.create_image(&info, None) }.expect("create image");
        let req = unsafe { d.get_image_memory_requirements(image) };
        let alloc = vk::MemoryAllocateInfo::default()
            .allocation_size(req.size)
            .memory_type_index(self.memory_type(req.memory_type_bits, vk::MemoryPropertyFlags::DEVICE_LOCAL));
        let memory = unsafe { d.allocate_memory(&alloc, None) }.expect("image memory");
        unsafe { d.bind_image_memory(image, memory, 0) }.expect("bind");
        let aspect = if depth { vk::ImageAspectFlags::DEPTH } else { vk::ImageAspectFlags::COLOR };
        let range = vk::ImageSubresourceRange { aspect_mask: aspect, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: 1 };
        let view_info =
            vk::ImageViewCreateInfo::default().image(image).view_type(vk::ImageViewType::TYPE_2D).format(format).subresource_range(range);
        let view = unsafe { d.create_image_view(&view_info, None) }.expect("view");
        self.submit(|cmd| unsafe {
            let b = vk::ImageMemoryBarrier::default()
                .image(image)
                .old_layout(vk::ImageLayout::UNDEFINED)
                .new_layout(layout)
                .dst_access_mask(vk::AccessFlags::TRANSFER_WRITE | vk::AccessFlags::SHADER_READ)
                .subresource_range(range);
            d.cmd_pipeline_barrier(
                cmd,
                vk::PipelineStageFlags::TOP_OF_PIPE,
                vk::PipelineStageFlags::TRANSFER | vk::PipelineStageFlags::COMPUTE_SHADER,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[b],
            );
        });
        TestImage { image, view, memory, format, width, height, texel_bytes: texel_bytes(format), layout }
    }

    /// Destroys an image made by `image`.
    pub fn destroy_image(&self, img: &TestImage) {
        unsafe {
            self.device.destroy_image_view(img.view, None);
            self.device.destroy_image(img.image, None);
            self.device.free_memory(img.memory, None);
        }
    }

    /// A host-visible buffer (buffer, memory, mapped pointer).
    pub fn staging(&self, bytes: u64) -> Staging {
        let d = &self.device;
        let info = vk::BufferCreateInfo::default()
            .size(bytes.max(4))
            .usage(vk::BufferUsageFlags::TRANSFER_SRC | vk::BufferUsageFlags::TRANSFER_DST);
        let buffer = unsafe { d.create_buffer(&info, None) }.expect("buffer");
        let req = unsafe { d.get_buffer_memory_requirements(buffer) };
        let flags = vk::MemoryPropertyFlags::HOST_VISIBLE | vk::MemoryPropertyFlags::HOST_COHERENT;
        let alloc = vk::MemoryAllocateInfo::default().allocation_size(req.size).memory_type_index(self.memory_type(req.memory_type_bits, flags));
        let memory = unsafe { d.allocate_memory(&alloc, None) }.expect("staging memory");
        unsafe { d.bind_buffer_memory(buffer, memory, 0) }.expect("bind");
        let ptr = unsafe { d.map_memory(memory, 0, vk::WHOLE_SIZE, vk::MemoryMapFlags::empty()) }.expect("map") as *mut u8;
        Staging { buffer, memory, ptr, bytes }
    }

    /// Frees a staging buffer.
    pub fn destroy_staging(&self, s: &Staging) {
        unsafe {
            self.device.destroy_buffer(s.buffer, None);
            self.device.free_memory(s.memory, None);
        }
    }

    /// Allocates a primary command buffer.
    pub fn command_buffer(&self) -> vk::CommandBuffer {
        let info = vk::CommandBufferAllocateInfo::default().command_pool(self.command_pool).command_buffer_count(1);
        unsafe { self.device.allocate_command_buffers(&info) }.expect("command buffer")[0]
    }

    /// Frees a command buffer from `command_buffer`.
    pub fn free_command_buffer(&self, cmd: vk::CommandBuffer) {
        unsafe { self.device.free_command_buffers(self.command_pool, &[cmd]) };
    }

    /// Records into a fresh command buffer, submits it and waits.
    pub fn submit<R>(&self, record: impl FnOnce(vk::CommandBuffer) -> R) -> R {
        let cmd = self.command_buffer();
        let r = self.submit_with(cmd, record);
        self.free_command_buffer(cmd);
        r
    }

    /// Records into `cmd` (reset first), submits it and waits.
    pub fn submit_with<R>(&self, cmd: vk::CommandBuffer, record: impl FnOnce(vk::CommandBuffer) -> R) -> R {
        let r = self.record_unsubmitted(cmd, record);
        let d = &self.device;
        unsafe {
            d.queue_submit(self.queue, &[vk::SubmitInfo::default().command_buffers(&[cmd])], vk::Fence::null()).expect("submit");
            d.queue_wait_idle(self.queue).expect("wait");
        }
        r
    }

    /// Resets and begins `cmd`, calls `record` on it and ends it without submitting it (the bench's back-to-back
    /// record timing).
    pub fn record_unsubmitted<R>(&self, cmd: vk::CommandBuffer, record: impl FnOnce(vk::CommandBuffer) -> R) -> R {
        let d = &self.device;
        unsafe {
            d.reset_command_buffer(cmd, vk::CommandBufferResetFlags::empty()).expect("reset");
            d.begin_command_buffer(cmd, &vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT))
                .expect("begin");
        }
        let r = record(cmd);
        unsafe { d.end_command_buffer(cmd).expect("end") };
        r
    }

    /// Records a copy between a staging buffer and an image, moving the image to the transfer layout and back to
    /// its resting layout with full barriers around it.
    pub fn cmd_copy(&self, cmd: vk::CommandBuffer, img: &TestImage, staging: &Staging, offset: u64, to_image: bool) {
        let d = &self.device;
        let aspect = if img.format == vk::Format::D32_SFLOAT { vk::ImageAspectFlags::DEPTH } else { vk::ImageAspectFlags::COLOR };
        let region = vk::BufferImageCopy::default()
            .buffer_offset(offset)
            .image_subresource(vk::ImageSubresourceLayers { aspect_mask: aspect, mip_level: 0, base_array_layer: 0, layer_count: 1 })
            .image_extent(vk::Extent3D { width: img.width, height: img.height, depth: 1 });
        let transfer = if to_image { vk::ImageLayout::TRANSFER_DST_OPTIMAL } else { vk::ImageLayout::TRANSFER_SRC_OPTIMAL };
        let transition = |old, new| {
            let (write, read) = (vk::AccessFlags::MEMORY_WRITE, vk::AccessFlags::MEMORY_READ);
            let b = crate::gpu::barrier::layout_transition(img.image, aspect, old, new, write, read | write);
            full_barrier_with(d, cmd, &[b]);
        };
        if img.layout != transfer {
            transition(img.layout, transfer);
        }
        unsafe {
            if to_image {
                d.cmd_copy_buffer_to_image(cmd, staging.buffer, img.image, transfer, &[region]);
            } else {
                d.cmd_copy_image_to_buffer(cmd, img.image, transfer, staging.buffer, &[region]);
            }
        }
        if img.layout != transfer {
            transition(transfer, img.layout);
        }
    }

    /// Uploads raw texels into an image and waits.
    pub fn upload(&self, img: &TestImage, bytes: &[u8]) {
        let s = self.staging(bytes.len() as u64);
        s.write(0, bytes);
        self.submit(|cmd| {
            self.cmd_copy(cmd, img, &s, 0, true);
            full_barrier(&self.device, cmd);
        });
        self.destroy_staging(&s);
    }

    /// Reads back raw texels of an image.
    pub fn download(&self, img: &TestImage) -> Vec<u8> {
        let n = (img.width * img.height * img.texel_bytes) as usize;
        let s = self.staging(n as u64);
        self.submit(|cmd| {
            full_barrier(&self.device, cmd);
            self.cmd_copy(cmd, img, &s, 0, false);
            full_barrier(&self.device, cmd);
        });
        let out = s.read(0, n);
        self.destroy_staging(&s);
        out
    }
}

/// An all-commands memory barrier (test plumbing only).
pub fn full_barrier(d: &ash::Device, cmd: vk::CommandBuffer) {
    full_barrier_with(d, cmd, &[]);
}

fn full_barrier_with(d: &ash::Device, cmd: vk::CommandBuffer, images: &[vk::ImageMemoryBarrier]) {
    let all = vk::PipelineStageFlags::ALL_COMMANDS;
    let (write, read) = (vk::AccessFlags::MEMORY_WRITE, vk::AccessFlags::MEMORY_READ);
    crate::gpu::barrier::memory(d, cmd, all, write, all, read | write, images);
}

/// A mapped host-visible buffer.
pub struct Staging {
    /// Buffer.
    pub buffer: vk::Buffer,
    memory: vk::DeviceMemory,
    ptr: *mut u8,
    /// Size.
    pub bytes: u64,
}

impl Staging {
    /// Copies bytes in at `offset`.
    pub fn write(&self, offset: usize, data: &[u8]) {
        assert!(offset + data.len() <= self.bytes as usize);
        unsafe { std::ptr::copy_nonoverlapping(data.as_ptr(), self.ptr.add(offset), data.len()) };
    }
    /// Copies `n` bytes out from `offset`.
    pub fn read(&self, offset: usize, n: usize) -> Vec<u8> {
        assert!(offset + n <= self.bytes as usize);
        unsafe { std::slice::from_raw_parts(self.ptr.add(offset), n) }.to_vec()
    }
}

impl Drop for Gpu {
    fn drop(&mut self) {
        unsafe {
            let _ = self.device.device_wait_idle();
            self.device.destroy_command_pool(self.command_pool, None);
            self.device.destroy_device(None);
            if let Some((loader, messenger, user)) = self.debug.take() {
                loader.destroy_debug_utils_messenger(messenger, None);
                drop(Box::from_raw(user));
            }
            self.instance.destroy_instance(None);
        }
    }
}

/// A host GPU allocator for tests and the bench: one vkAllocateMemory of device-local memory per request, each
/// request's kind and size logged.
pub struct HostAllocator {
    device: ash::Device,
    memory: vk::PhysicalDeviceMemoryProperties,
    /// (kind, bytes) of every allocation, in order.
    pub log: Mutex<Vec<(crate::ResourceKind, u64)>>,
}

impl HostAllocator {
    /// An allocator on `gpu`'s device.
    pub fn new(gpu: &Gpu) -> HostAllocator {
        let memory = unsafe { gpu.instance.get_physical_device_memory_properties(gpu.physical_device) };
        HostAllocator { device: gpu.device.clone(), memory, log: Mutex::new(Vec::new()) }
    }
}

impl crate::GpuMemoryAllocator for HostAllocator {
    fn allocate(&self, req: &vk::MemoryRequirements, kind: crate::ResourceKind) -> Result<crate::GpuAllocation, vk::Result> {
        let types = &self.memory.memory_types[..self.memory.memory_type_count as usize];
        let index = (0..types.len() as u32)
            .find(|&i| req.memory_type_bits & (1 << i) != 0 && types[i as usize].property_flags.contains(vk::MemoryPropertyFlags::DEVICE_LOCAL))
            .ok_or(vk::Result::ERROR_OUT_OF_DEVICE_MEMORY)?;
        let info = vk::MemoryAllocateInfo::default().allocation_size(req.size).memory_type_index(index);
        let memory = unsafe { self.device.allocate_memory(&info, None) }?;
        self.log.lock().unwrap().push((kind, req.size));
        Ok(crate::GpuAllocation { memory, offset: 0, user_handle: 0 })
    }
    fn free(&self, a: &crate::GpuAllocation) {
        unsafe { self.device.free_memory(a.memory, None) };
    }
}

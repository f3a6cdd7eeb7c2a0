//! The few barrier shapes dnsr records.

use ash::vk;

/// A global memory barrier: every resource, one dependency.
pub(crate) fn memory(
    device: &ash::Device,
    cmd: vk::CommandBuffer,
    src_stages: vk::PipelineStageFlags,
    src_access: vk::AccessFlags,
    dst_stages: vk::PipelineStageFlags,
    dst_access: vk::AccessFlags,
    images: &[vk::ImageMemoryBarrier],
) {
    let barrier = vk::MemoryBarrier::default().src_access_mask(src_access).dst_access_mask(dst_access);
    unsafe {
        device.cmd_pipeline_barrier(
            cmd,
            src_stages,
            dst_stages,
            vk::DependencyFlags::empty(),
            std::slice::from_ref(&barrier),
            &[],
            images,
        )
    };
}

/// After a `vkCmdUpdateBuffer` of constants or counters: the transfer's writes before the compute passes that read
/// them (uniform or storage) or write them.
pub(crate) fn transfer_to_compute(device: &ash::Device, cmd: vk::CommandBuffer) {
    memory(
        device,
        cmd,
        vk::PipelineStageFlags::TRANSFER,
        vk::AccessFlags::TRANSFER_WRITE,
        vk::PipelineStageFlags::COMPUTE_SHADER,
        vk::AccessFlags::UNIFORM_READ | vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE,
        &[],
    );
}

/// Between two of dnsr's compute passes: earlier writes become visible to later reads, and later writes wait
/// for earlier reads.
pub(crate) fn compute_to_compute(device: &ash::Device, cmd: vk::CommandBuffer) {
    memory(
        device,
        cmd,
        vk::PipelineStageFlags::COMPUTE_SHADER,
        vk::AccessFlags::SHADER_WRITE,
        vk::PipelineStageFlags::COMPUTE_SHADER,
        vk::AccessFlags::SHADER_READ | vk::AccessFlags::SHADER_WRITE,
        &[],
    );
}

/// A layout transition of mip 0 / layer 0 of a color or depth image.
pub(crate) fn layout_transition(
    image: vk::Image,
    aspect: vk::ImageAspectFlags,
    old: vk::ImageLayout,
    new: vk::ImageLayout,
    src_access: vk::AccessFlags,
    dst_access: vk::AccessFlags,
) -> vk::ImageMemoryBarrier<'static> {
    vk::ImageMemoryBarrier::default()
        .image(image)
        .old_layout(old)
        .new_layout(new)
        .src_access_mask(src_access)
        .dst_access_mask(dst_access)
        .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
        .subresource_range(vk::ImageSubresourceRange {
            aspect_mask: aspect,
            base_mip_level: 0,
            level_count: 1,
            base_array_layer: 0,
            layer_count: 1,
        })
}

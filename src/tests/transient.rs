//! What dnsr calls transient state (`state::Lifetime::Transient`, the part of the memory that
//! `Context::persistent_memory_bytes` leaves out) really is: garbage written into every transient image between
//! two records changes no output bit, in every configuration whose passes read different transient images; and a
//! host that aliases that memory (`alias_transient_memory`) gets it as `ResourceKind::TransientImage`.

use super::correctness::smooth;
use super::gpu;
use crate::gpu::barrier;
use crate::testing::scene::{render_with_blockers, Camera};
use crate::testing::Runner;
use crate::testing::gpu::HostAllocator;
use crate::{Preset, ResourceKind, Settings, ShadowInput};
use ash::vk;
use std::sync::Arc;

/// A value no pass writes: NaN in float images, a mid-range value in unorm ones (a NaN clear turns into 0 there),
/// set bits in integer ones.
fn garbage(format: vk::Format) -> vk::ClearColorValue {
    match format {
        vk::Format::R16G16_UNORM => vk::ClearColorValue { float32: [0.6172, 0.3381, 0.0, 0.0] },
        vk::Format::R32_UINT | vk::Format::R32G32_UINT => vk::ClearColorValue { uint32: [0xA5A5_A5A5; 4] },
        _ => vk::ClearColorValue { float32: [f32::NAN; 4] },
    }
}

#[test]
fn transient_images_carry_nothing_between_records() {
    let g = gpu();
    let (w, h) = (72u32, 48u32);
    let quality = Settings::default();
    // The last field: the scrambled context aliases its transient memory (allocated by the host, moved out of
    // UNDEFINED on every record).
    let configs: [(&str, Settings, ShadowInput, Option<f32>, bool); 6] = [
        ("Quality", quality, ShadowInput::HitMask, None, false),
        ("Quality, guided", quality, ShadowInput::HitMask, Some(0.05), false),
        ("Balanced, four passes", Settings { filter_passes: 4, ..Settings::preset(Preset::Balanced) }, ShadowInput::HitMask, None, false),
        ("Fast", Settings::preset(Preset::Fast), ShadowInput::HitMask, None, false),
        ("Quality, checkerboard", quality, ShadowInput::Checkerboard, None, false),
        ("Quality, aliased", quality, ShadowInput::HitMask, None, true),
    ];
    for (name, settings, input, guidance, alias) in configs {
        let allocator = Arc::new(HostAllocator::new(&g));
        let runner = |alias: bool| {
            let mut info = g.create_info(w, h);
            info.settings = settings;
            info.shadow_input = input;
            info.output_format = vk::Format::R32_SFLOAT;
            if alias {
                info.alias_transient_memory = true;
                info.hooks.gpu_memory = Some(allocator.clone());
            }
            let mut r = Runner::new(&g, &info).unwrap();
            r.guidance = guidance;
            r
        };
        let (mut plain, mut scrambled) = (runner(false), runner(alias));
        if alias {
            // The host sees every transient image as such, and every persistent one as an image.
            let log = allocator.log.lock().unwrap().clone();
            let bytes = |kind| log.iter().filter(|(k, _)| *k == kind).map(|(_, b)| b).sum::<u64>();
            let ctx = &scrambled.ctx;
            assert_eq!(bytes(ResourceKind::Image), ctx.persistent_memory_bytes(), "{name}: persistent images");
            let buffer = bytes(ResourceKind::Buffer);
            assert_eq!(bytes(ResourceKind::TransientImage), ctx.memory_bytes() - ctx.persistent_memory_bytes() - buffer, "{name}");
            assert!(bytes(ResourceKind::TransientImage) > 0);
        }
        let (images, persistent) = scrambled.ctx.transient_images();
        // Persistent: the moments, the depth copy, the history and the pair of quiet counts.
        assert!(images.len() >= 4 && persistent == 5, "{name}: {} transient, {persistent} persistent images", images.len());
        // A camera panning across a soft shadow with sky at the sides: history, disocclusion and cleared tiles.
        let cam = |frame: u32| Camera::above(0.07 * frame as f64, 0.0, 10.0);
        for frame in 0..6u32 {
            let f = render_with_blockers(w, h, &cam(frame), &cam(frame.saturating_sub(1)), 4.0, &smooth, &|_, _| 0.8, frame as u64 + 7);
            if input == ShadowInput::Checkerboard {
                plain.checkerboard_phase = frame % 2;
                scrambled.checkerboard_phase = frame % 2;
            }
            let a = plain.frame(&f, false);
            let d = scrambled.dispatch(&f);
            let (result, b) = scrambled.run_with(&f, |ctx, cmd| {
                // Before the first record the images are not initialised yet (it clears them).
                if frame > 0 {
                    fill_with_garbage(&g.device, cmd, &images);
                }
                ctx.record_shadows(cmd, &d)
            });
            result.unwrap();
            let differing = a.iter().zip(&b).filter(|(x, y)| x.to_bits() != y.to_bits()).count();
            assert_eq!(differing, 0, "{name}, frame {frame}: {differing} pixels depend on a transient image's old contents");
        }
    }
    g.assert_clean();
}

#[test]
fn aliasing_transient_memory_needs_the_hosts_allocator() {
    let g = gpu();
    let mut info = g.create_info(16, 16);
    info.alias_transient_memory = true;
    let e = crate::Context::new(&info).err().expect("aliasing without a host allocator");
    assert!(e.to_string().contains("DNSR_CONTEXT_CREATE_ALIAS_TRANSIENT_MEMORY) is true; it needs hooks.gpu_memory"), "{e}");
    g.assert_clean();
}

/// Clears every image with garbage after the earlier frames' compute work (dnsr's first barrier waits for transfers).
fn fill_with_garbage(device: &ash::Device, cmd: vk::CommandBuffer, images: &[(vk::Image, vk::Format)]) {
    barrier::memory(
        device,
        cmd,
        vk::PipelineStageFlags::COMPUTE_SHADER,
        vk::AccessFlags::SHADER_WRITE,
        vk::PipelineStageFlags::TRANSFER,
        vk::AccessFlags::TRANSFER_WRITE,
        &[],
    );
    for &(image, format) in images {
        unsafe { device.cmd_clear_color_image(cmd, image, vk::ImageLayout::GENERAL, &garbage(format), &[crate::gpu::image::color_range()]) };
    }
}

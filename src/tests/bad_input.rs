//! Misuse gets a specific error and records nothing: after each refused call the context's recording state is
//! unchanged, the output image still holds the previous frame, and the validation layer saw nothing.

use super::{gpu, static_frame};
use crate::error::{Error, ImageRole};
use crate::testing::Runner;
use crate::{Context, ContextCreateInfo, HostImage, Precision, Rect, ShadowsDispatch};
use ash::vk;
use glam::{Mat4, Vec2, Vec3};

/// The device's API version plus one minor version.
fn newer_than_device(i: &ContextCreateInfo) -> u32 {
    let instance = unsafe {
        ash::Instance::load_with(
            |name| std::mem::transmute((i.get_instance_proc_addr.unwrap())(i.instance, name.as_ptr())),
            i.instance,
        )
    };
    let v = unsafe { instance.get_physical_device_properties(i.physical_device) }.api_version;
    vk::make_api_version(0, vk::api_version_major(v), vk::api_version_minor(v) + 1, 0)
}

#[test]
fn bad_create_infos_are_refused_with_specific_errors() {
    let g = gpu();
    let good = g.create_info(32, 16);
    Context::new(&good).unwrap();
    type Edit = fn(&mut ContextCreateInfo);
    let cases: &[(&str, Edit, fn(&Error) -> bool)] = &[
        ("null instance", |i| i.instance = vk::Instance::null(), |e| *e == Error::NullHandle("instance")),
        ("null physical device", |i| i.physical_device = vk::PhysicalDevice::null(), |e| *e == Error::NullHandle("physical_device")),
        ("null device", |i| i.device = vk::Device::null(), |e| *e == Error::NullHandle("device")),
        ("no vkGetInstanceProcAddr", |i| i.get_instance_proc_addr = None, |e| *e == Error::NullHandle("get_instance_proc_addr")),
        ("no vkGetDeviceProcAddr", |i| i.get_device_proc_addr = None, |e| *e == Error::NullHandle("get_device_proc_addr")),
        ("api 1.0", |i| i.api_version = vk::API_VERSION_1_0, |e| matches!(e, Error::UnsupportedApiVersion { .. })),
        ("zero width", |i| i.width = 0, |e| matches!(e, Error::ZeroExtent { .. })),
        ("zero height", |i| i.height = 0, |e| matches!(e, Error::ZeroExtent { .. })),
        ("oversized", |i| i.width = 1 << 20, |e| matches!(e, Error::ExtentTooLarge { .. })),
        ("no lights", |i| i.light_count = 0, |e| matches!(e, Error::InvalidValue { field: "light_count", .. })),
        ("65 lights", |i| i.light_count = 65, |e| matches!(e, Error::InvalidValue { field: "light_count", .. })),
        ("u32::MAX lights", |i| i.light_count = u32::MAX, |e| matches!(e, Error::InvalidValue { field: "light_count", .. })),
        (
            "9 lights recorded together (a record holds 8)",
            |i| {
                i.light_count = 9;
                i.lights_recorded_together = true;
            },
            |e| matches!(e, Error::InvalidValue { field: "lights_recorded_together", .. }),
        ),
        (
            "64 lights of 16384x16384 (more than any device has)",
            |i| {
                i.light_count = 64;
                (i.width, i.height) = (16384, 16384);
            },
            |e| matches!(e, Error::OutOfDeviceMemory { .. }),
        ),
        ("0 frames in flight", |i| i.max_frames_in_flight = 0, |e| matches!(e, Error::InvalidValue { field: "max_frames_in_flight", .. })),
        ("17 frames in flight", |i| i.max_frames_in_flight = 17, |e| matches!(e, Error::InvalidValue { field: "max_frames_in_flight", .. })),
        ("api 9.0", |i| i.api_version = vk::make_api_version(0, 9, 0, 0), |e| matches!(e, Error::UnsupportedApiVersion { .. })),
        ("api 2.0", |i| i.api_version = vk::make_api_version(0, 2, 0, 0), |e| matches!(e, Error::UnsupportedApiVersion { .. })),
        ("api variant 1", |i| i.api_version = vk::make_api_version(1, 1, 1, 0), |e| matches!(e, Error::UnsupportedApiVersion { .. })),
        ("api 0xFFFFFFFF", |i| i.api_version = u32::MAX, |e| matches!(e, Error::UnsupportedApiVersion { .. })),
        (
            "api one minor above the device",
            |i| i.api_version = newer_than_device(i),
            |e| matches!(e, Error::UnsupportedApiVersion { .. }),
        ),
        ("queue family 99", |i| i.queue_family_index = 99, |e| matches!(e, Error::InvalidQueueFamily { index: 99, .. })),
        (
            "fp16 without the feature",
            |i| {
                i.precision = Precision::Fp16;
                i.features.float16 = false;
            },
            |e| matches!(e, Error::MissingFeature(_)),
        ),
        (
            "BGRA8 output",
            |i| i.output_format = vk::Format::B8G8R8A8_UNORM,
            |e| matches!(e, Error::UnsupportedFormat { role: Some(ImageRole::Output), .. }),
        ),
        ("0 filter passes", |i| i.settings.filter_passes = 0, |e| matches!(e, Error::InvalidSetting { name: "filter_passes", .. })),
        ("5 filter passes", |i| i.settings.filter_passes = 5, |e| matches!(e, Error::InvalidSetting { name: "filter_passes", .. })),
        (
            "NaN threshold",
            |i| i.settings.disocclusion_threshold_facing = f32::NAN,
            |e| matches!(e, Error::InvalidSetting { name: "disocclusion_threshold_facing", .. }),
        ),
        (
            "zero blend",
            |i| i.settings.min_current_weight = 0.0,
            |e| matches!(e, Error::InvalidSetting { name: "min_current_weight", .. }),
        ),
        (
            "timestamps on a missing queue family",
            |i| {
                i.enable_timestamps = true;
                i.queue_family_index = 99;
            },
            |e| matches!(e, Error::InvalidQueueFamily { index: 99, .. }),
        ),
    ];
    for (name, edit, check) in cases {
        let mut info = good.clone();
        edit(&mut info);
        match Context::new(&info) {
            Ok(_) => panic!("{name}: accepted"),
            Err(e) => {
                assert!(check(&e), "{name}: unexpected error {e:?}");
                assert!(!e.to_string().is_empty());
            }
        }
    }
    g.assert_clean();
}

type DispatchCase = (&'static str, fn(&mut ShadowsDispatch), fn(&Error) -> bool);

/// Each case's edit of `good` is refused with its error, records nothing and leaves the (all-lit) output alone.
fn refused_record_nothing(r: &mut Runner, frame: &crate::testing::scene::FrameInputs, good: &ShadowsDispatch, cases: &[DispatchCase]) {
    for (name, edit, check) in cases {
        let mut d = *good;
        edit(&mut d);
        let before = r.ctx.recording_state(0);
        let (result, out) = r.run_raw(frame, &d);
        let e = result.expect_err(name);
        assert!(check(&e), "{name}: unexpected error {e:?}");
        assert!(!e.to_string().is_empty());
        assert_eq!(r.ctx.recording_state(0), before, "{name}: state changed");
        assert!(out.iter().all(|&o| o == 1.0), "{name}: something ran");
        r.gpu.assert_clean();
    }
}

#[test]
fn bad_visibility_dispatches_record_nothing() {
    let g = gpu();
    let (w, h) = (32, 16);
    let mut info = g.create_info(w, h);
    info.output_format = vk::Format::R32_SFLOAT;
    info.shadow_input = crate::ShadowInput::Visibility;
    let mut r = Runner::new(&g, &info).unwrap();
    let mut f = static_frame(w, h, &|_, _| 1.0, 1);
    f.trace_rays(2, 1);
    assert!(r.frame(&f, false).iter().all(|&o| o == 1.0));
    let mut shadow = static_frame(w, h, &|_, _| 0.0, 2);
    shadow.trace_rays(2, 2);
    let good = r.dispatch(&shadow);
    assert!(good.hit_mask.view == vk::ImageView::null() && good.visibility.view != vk::ImageView::null());
    let cases: &[DispatchCase] = &[
        ("no visibility", |d| d.visibility = HostImage::default(), |e| *e == Error::NullHandle("visibility.image")),
        ("null visibility view", |d| d.visibility.view = vk::ImageView::null(), |e| *e == Error::NullHandle("visibility.view")),
        (
            "integer visibility",
            |d| d.visibility.format = vk::Format::R32_UINT,
            |e| matches!(e, Error::UnsupportedFormat { role: Some(ImageRole::Visibility), .. }),
        ),
        (
            "visibility of tile size",
            |d| (d.visibility.width, d.visibility.height) = (4, 4),
            |e| matches!(e, Error::ImageExtentMismatch { role: ImageRole::Visibility, .. }),
        ),
        (
            "visibility in attachment layout",
            |d| d.visibility.layout = vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            |e| matches!(e, Error::UnsupportedLayout { role: ImageRole::Visibility, .. }),
        ),
        ("hit mask given as well", |d| d.hit_mask = d.depth, |e| matches!(e, Error::InvalidValue { field: "hit_mask", .. })),
    ];
    refused_record_nothing(&mut r, &shadow, &good, cases);
    assert!(r.run(&shadow, &good).unwrap().iter().all(|&o| o == 0.0));
    g.assert_clean();
}

#[test]
fn bad_checkerboard_dispatches_record_nothing() {
    let g = gpu();
    let (w, h) = (32, 16);
    let mut info = g.create_info(w, h);
    info.output_format = vk::Format::R32_SFLOAT;
    info.shadow_input = crate::ShadowInput::Checkerboard;
    let mut r = Runner::new(&g, &info).unwrap();
    assert!(r.frame(&static_frame(w, h, &|_, _| 1.0, 1), false).iter().all(|&o| o == 1.0));
    let shadow = static_frame(w, h, &|_, _| 0.0, 2);
    let good = ShadowsDispatch { checkerboard_phase: 1, ..r.dispatch(&shadow) };
    let cases: &[DispatchCase] = &[
        ("phase 2", |d| d.checkerboard_phase = 2, |e| matches!(e, Error::InvalidValue { field: "checkerboard_phase", .. })),
        ("no hit mask", |d| d.hit_mask = HostImage::default(), |e| *e == Error::NullHandle("hit_mask.image")),
        ("visibility given", |d| d.visibility = d.depth, |e| matches!(e, Error::InvalidValue { field: "visibility", .. })),
    ];
    refused_record_nothing(&mut r, &shadow, &good, cases);
    assert!(r.run(&shadow, &good).unwrap().iter().all(|&o| o == 0.0));
    // A phase given to a context that traces every pixel is refused, not ignored.
    info.shadow_input = crate::ShadowInput::HitMask;
    let mut r = Runner::new(&g, &info).unwrap();
    let e = r.run(&shadow, &good).expect_err("phase 1 for a hit-mask context");
    assert!(matches!(e, Error::InvalidValue { field: "checkerboard_phase", .. }), "{e:?}");
    drop(r);
    g.assert_clean();
}

#[test]
fn bad_dispatches_record_nothing() {
    let g = gpu();
    let (w, h) = (32, 16);
    let mut info = g.create_info(w, h);
    info.output_format = vk::Format::R32_SFLOAT;
    let mut r = Runner::new(&g, &info).unwrap();
    let f = static_frame(w, h, &|_, _| 1.0, 1);
    let lit = r.frame(&f, false);
    assert!(lit.iter().all(|&o| o == 1.0));
    // The refused frames would write 0 everywhere if anything ran.
    let shadow = static_frame(w, h, &|_, _| 0.0, 2);
    // With penumbra guidance, so that its inputs are checked too.
    r.guidance = Some(0.01);
    let good = r.dispatch(&shadow);

    type Edit = fn(&mut ShadowsDispatch);
    fn null_view(i: &mut HostImage) {
        i.view = vk::ImageView::null();
    }
    fn wrong_size(i: &mut HostImage) {
        i.width += 1;
    }
    let cases: &[(&str, Edit, fn(&Error) -> bool)] = &[
        ("null hit mask view", |d| null_view(&mut d.hit_mask), |e| *e == Error::NullHandle("hit_mask.view")),
        ("null depth view", |d| null_view(&mut d.depth), |e| *e == Error::NullHandle("depth.view")),
        ("null velocity view", |d| null_view(&mut d.velocity), |e| *e == Error::NullHandle("velocity.view")),
        ("null normals view", |d| null_view(&mut d.normals), |e| *e == Error::NullHandle("normals.view")),
        ("null output view", |d| null_view(&mut d.output), |e| *e == Error::NullHandle("output.view")),
        ("output is the depth image", |d| d.output.image = d.depth.image, |e| matches!(e, Error::InvalidValue { field: "output", .. })),
        ("null output image", |d| d.output.image = vk::Image::null(), |e| *e == Error::NullHandle("output.image")),
        ("null depth image", |d| d.depth.image = vk::Image::null(), |e| *e == Error::NullHandle("depth.image")),
        (
            "float hit mask",
            |d| d.hit_mask.format = vk::Format::R32_SFLOAT,
            |e| matches!(e, Error::UnsupportedFormat { role: Some(ImageRole::HitMask), .. }),
        ),
        (
            "RGBA8 depth",
            |d| d.depth.format = vk::Format::R8G8B8A8_UNORM,
            |e| matches!(e, Error::UnsupportedFormat { role: Some(ImageRole::Depth), .. }),
        ),
        (
            "one-channel velocity",
            |d| d.velocity.format = vk::Format::R32_SFLOAT,
            |e| matches!(e, Error::UnsupportedFormat { role: Some(ImageRole::Velocity), .. }),
        ),
        (
            "integer normals",
            |d| d.normals.format = vk::Format::R32G32B32A32_UINT,
            |e| matches!(e, Error::UnsupportedFormat { role: Some(ImageRole::Normals), .. }),
        ),
        (
            "output format differs from creation",
            |d| d.output.format = vk::Format::R16_SFLOAT,
            |e| matches!(e, Error::OutputFormatMismatch { declared: vk::Format::R16_SFLOAT, context: vk::Format::R32_SFLOAT }),
        ),
        (
            "undefined depth layout",
            |d| d.depth.layout = vk::ImageLayout::UNDEFINED,
            |e| matches!(e, Error::UnsupportedLayout { role: ImageRole::Depth, .. }),
        ),
        (
            "output in attachment layout",
            |d| d.output.layout = vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            |e| matches!(e, Error::UnsupportedLayout { role: ImageRole::Output, .. }),
        ),
        ("hit mask size", |d| wrong_size(&mut d.hit_mask), |e| matches!(e, Error::ImageExtentMismatch { role: ImageRole::HitMask, .. })),
        ("depth size", |d| wrong_size(&mut d.depth), |e| matches!(e, Error::ImageExtentMismatch { role: ImageRole::Depth, .. })),
        ("velocity size", |d| wrong_size(&mut d.velocity), |e| matches!(e, Error::ImageExtentMismatch { role: ImageRole::Velocity, .. })),
        ("normals size", |d| wrong_size(&mut d.normals), |e| matches!(e, Error::ImageExtentMismatch { role: ImageRole::Normals, .. })),
        ("output size", |d| d.output.height = 0, |e| matches!(e, Error::ImageExtentMismatch { role: ImageRole::Output, .. })),
        (
            "null hit distance view",
            |d| null_view(d.hit_distance.as_mut().unwrap()),
            |e| *e == Error::NullHandle("hit_distance.view"),
        ),
        (
            "R8 hit distance",
            |d| d.hit_distance.as_mut().unwrap().format = vk::Format::R8_UNORM,
            |e| matches!(e, Error::UnsupportedFormat { role: Some(ImageRole::HitDistance), .. }),
        ),
        (
            "hit distance size",
            |d| wrong_size(d.hit_distance.as_mut().unwrap()),
            |e| matches!(e, Error::ImageExtentMismatch { role: ImageRole::HitDistance, .. }),
        ),
        ("NaN light angular size", |d| d.light_angular_size = f32::NAN, |e| *e == Error::NonFinite("light_angular_size")),
        (
            "negative light angular size",
            |d| d.light_angular_size = -0.01,
            |e| matches!(e, Error::InvalidValue { field: "light_angular_size", .. }),
        ),
        (
            "a hard light of non-zero angular size",
            |d| (d.hard_light, d.light_angular_size) = (true, 0.01),
            |e| matches!(e, Error::InvalidValue { field: "light_angular_size", allowed, .. } if allowed.contains("hard_light")),
        ),
        (
            "light angular size of pi",
            |d| d.light_angular_size = std::f32::consts::PI,
            |e| matches!(e, Error::InvalidValue { field: "light_angular_size", .. }),
        ),
        (
            "NaN light angular size with a light position alone",
            |d| (d.hit_distance, d.light_position, d.light_angular_size) = (None, Some(glam::Vec4::Y), f32::NAN),
            |e| *e == Error::NonFinite("light_angular_size"),
        ),
        (
            "a hard light of non-zero angular size with a light position",
            |d| (d.hit_distance, d.light_position, d.hard_light, d.light_angular_size) = (None, Some(glam::Vec4::Y), true, 0.01),
            |e| matches!(e, Error::InvalidValue { field: "light_angular_size", allowed, .. } if allowed.contains("hard_light")),
        ),
        (
            "NaN light position",
            |d| d.light_position = Some(glam::Vec4::new(0.0, f32::NAN, 1.0, 0.0)),
            |e| *e == Error::NonFinite("light_position"),
        ),
        (
            "light direction of length 0",
            |d| d.light_position = Some(glam::Vec4::ZERO),
            |e| matches!(e, Error::InvalidValue { field: "light_position", allowed, .. } if allowed.contains("non-zero length")),
        ),
        (
            "light position with w 0.5",
            |d| d.light_position = Some(glam::Vec4::new(0.0, 1.0, 0.0, 0.5)),
            |e| matches!(e, Error::InvalidValue { field: "light_position", allowed, .. } if allowed.contains("w 1")),
        ),
        (
            "NaN projection inverse",
            |d| d.projection_inverse = Mat4::from_cols_array(&[f32::NAN; 16]),
            |e| *e == Error::NonFinite("projection_inverse"),
        ),
        (
            "Inf reprojection",
            |d| d.reprojection_matrix.x_axis.x = f32::INFINITY,
            |e| *e == Error::NonFinite("reprojection_matrix"),
        ),
        (
            "NaN view-projection inverse",
            |d| d.view_projection_inverse.w_axis.z = f32::NAN,
            |e| *e == Error::NonFinite("view_projection_inverse"),
        ),
        ("Inf eye", |d| d.eye = Vec3::new(0.0, f32::INFINITY, 0.0), |e| *e == Error::NonFinite("eye")),
        ("NaN motion scale", |d| d.motion_vector_scale = Vec2::new(f32::NAN, 1.0), |e| *e == Error::NonFinite("motion_vector_scale")),
        ("NaN normal unpack", |d| d.normals_unpack_mul = f32::NAN, |e| *e == Error::NonFinite("normals_unpack_mul/add")),
        (
            "zero depth sigma",
            |d| d.depth_similarity_sigma = 0.0,
            |e| matches!(e, Error::InvalidValue { field: "depth_similarity_sigma", .. }),
        ),
        ("NaN depth sigma", |d| d.depth_similarity_sigma = f32::NAN, |e| *e == Error::NonFinite("depth_similarity_sigma")),
        (
            "unknown input stage bit",
            |d| d.sync.input_src_stages = vk::PipelineStageFlags::from_raw(1 << 30),
            |e| matches!(e, Error::InvalidHostSync { field: "input_src_stages", .. }),
        ),
        (
            "unknown output access bit",
            |d| {
                d.sync.output_dst_stages = vk::PipelineStageFlags::FRAGMENT_SHADER;
                d.sync.output_dst_access = vk::AccessFlags::from_raw(1 << 29);
            },
            |e| matches!(e, Error::InvalidHostSync { field: "output_dst_access", .. }),
        ),
        (
            "colour attachment write from the fragment shader stage",
            |d| {
                d.sync.input_src_stages = vk::PipelineStageFlags::FRAGMENT_SHADER;
                d.sync.input_src_access = vk::AccessFlags::COLOR_ATTACHMENT_WRITE | vk::AccessFlags::SHADER_READ;
            },
            |e| matches!(e, Error::InvalidHostSync { field: "input_src_access", .. }),
        ),
        (
            "shader read by the transfer stage",
            |d| {
                d.sync.output_dst_stages = vk::PipelineStageFlags::TRANSFER;
                d.sync.output_dst_access = vk::AccessFlags::SHADER_READ;
            },
            |e| matches!(e, Error::InvalidHostSync { field: "output_dst_access", .. }),
        ),
        (
            "access without a stage",
            |d| d.sync.input_src_access = vk::AccessFlags::SHADER_WRITE,
            |e| matches!(e, Error::InvalidHostSync { field: "input_src_access", .. }),
        ),
        (
            "ray-tracing stage on a device without ray-tracing pipelines",
            |d| d.sync.input_src_stages = vk::PipelineStageFlags::RAY_TRACING_SHADER_KHR,
            |e| matches!(e, Error::InvalidHostSync { field: "input_src_stages", .. }),
        ),
        (
            "mesh shader stage (not accepted)",
            |d| d.sync.output_dst_stages = vk::PipelineStageFlags::MESH_SHADER_EXT,
            |e| matches!(e, Error::InvalidHostSync { field: "output_dst_stages", .. }),
        ),
        (
            "empty render rect",
            |d| d.render_rect = Some(Rect { x: 0, y: 0, width: 0, height: 4 }),
            |e| matches!(e, Error::InvalidRenderRect { .. }),
        ),
        (
            "misaligned render rect",
            |d| d.render_rect = Some(Rect { x: 3, y: 0, width: 8, height: 4 }),
            |e| matches!(e, Error::InvalidRenderRect { .. }),
        ),
        (
            "render rect outside",
            |d| d.render_rect = Some(Rect { x: 8, y: 4, width: 32, height: 4 }),
            |e| matches!(e, Error::InvalidRenderRect { .. }),
        ),
        ("light index", |d| d.light_index = 1, |e| matches!(e, Error::InvalidLightIndex { index: 1, count: 1 })),
        (
            "visibility given to a hit-mask context",
            |d| d.visibility = d.hit_distance.unwrap(),
            |e| matches!(e, Error::InvalidValue { field: "visibility", .. }),
        ),
    ];
    // A device with ray-tracing pipelines accepts that stage (an NVIDIA H100 does; lavapipe does not).
    let rt = r.ctx.supported_stages().contains(vk::PipelineStageFlags::RAY_TRACING_SHADER_KHR);
    let cases: Vec<DispatchCase> = cases.iter().copied().filter(|c| !(rt && c.0.starts_with("ray-tracing stage"))).collect();
    refused_record_nothing(&mut r, &shadow, &good, &cases);
    // A null command buffer.
    assert_eq!(r.ctx.record_shadows(vk::CommandBuffer::null(), &good), Err(Error::NullHandle("command_buffer")));
    // Settings are validated too, and a refused change keeps the old settings.
    let mut s = r.ctx.settings();
    s.normal_power = -1.0;
    assert!(matches!(r.ctx.set_settings(s), Err(Error::InvalidSetting { name: "normal_power", .. })));
    s.normal_power = f32::NAN;
    let e = r.ctx.set_settings(s).unwrap_err();
    assert_eq!(e.to_string(), "setting normal_power is NaN; it must be in [0, 256]");
    assert_eq!(r.ctx.settings(), crate::Settings::default());
    assert!(matches!(r.ctx.reset_history(3), Err(Error::InvalidLightIndex { .. })));
    assert!(matches!(r.ctx.resize(0, 5), Err(Error::ZeroExtent { .. })));
    // After all that, the context still works.
    let out = r.run(&shadow, &good).unwrap();
    assert!(out.iter().all(|&o| o == 0.0));
    g.assert_clean();
}

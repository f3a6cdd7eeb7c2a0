//! The C ABI from the host's side: a frame through the exported C functions equals the same frame through the
//! Rust API bit for bit; handles are checked; errors carry codes and messages.

use super::{correctness::smooth, gpu, static_frame};
use crate::capi::types::*;
use crate::capi::*;
use crate::testing::Runner;
use ash::vk;
use std::ffi::CStr;

fn create_info(g: &crate::testing::gpu::Gpu, w: u32, h: u32) -> DnsrContextCreateInfo {
    DnsrContextCreateInfo {
        s_type: DNSR_STRUCTURE_TYPE_CONTEXT_CREATE_INFO,
        p_next: std::ptr::null(),
        instance: g.instance.handle(),
        physical_device: g.physical_device,
        device: g.device.handle(),
        vulkan_functions: DnsrVulkanFunctions {
            vk_get_instance_proc_addr: Some(g.entry.static_fn().get_instance_proc_addr),
            vk_get_device_proc_addr: Some(g.instance.fp_v1_0().get_device_proc_addr),
        },
        api_version: g.api_version,
        queue_family_index: g.queue_family,
        enabled_features: if g.features.push_descriptor { DNSR_FEATURE_PUSH_DESCRIPTOR } else { 0 },
        width: w,
        height: h,
        flags: 0,
        precision: DNSR_PRECISION_FP32,
        output_format: vk::Format::R32_SFLOAT,
        light_count: 1,
        max_frames_in_flight: 0,
        p_settings: std::ptr::null(),
        p_allocation_callbacks: std::ptr::null(),
        p_gpu_memory_callbacks: std::ptr::null(),
        p_log_callback: std::ptr::null(),
        p_debug_name_callback: std::ptr::null(),
        shader_override_count: 0,
        p_shader_overrides: std::ptr::null(),
        shadow_input: DNSR_SHADOW_INPUT_HIT_MASK,
    }
}

fn host(i: &crate::HostImage) -> DnsrHostImage {
    DnsrHostImage { image: i.image, view: i.view, format: i.format, layout: i.layout, width: i.width, height: i.height }
}

fn c_dispatch(d: &crate::ShadowsDispatch, cmd: vk::CommandBuffer) -> DnsrShadowsDispatch {
    DnsrShadowsDispatch {
        s_type: DNSR_STRUCTURE_TYPE_SHADOWS_DISPATCH,
        p_next: std::ptr::null(),
        command_buffer: cmd,
        light_index: d.light_index,
        flags: (if d.reset { DNSR_DISPATCH_RESET } else { 0 })
            | (if d.hit_distance.is_some() { DNSR_DISPATCH_USE_HIT_DISTANCE } else { 0 })
            | (if d.hard_light { DNSR_DISPATCH_HARD_LIGHT } else { 0 })
            | (if d.light_position.is_some() { DNSR_DISPATCH_USE_LIGHT_POSITION } else { 0 }),
        hit_mask_convention: DNSR_HIT_MASK_OCCLUDED_BITS,
        hit_mask: host(&d.hit_mask),
        depth: host(&d.depth),
        velocity: host(&d.velocity),
        normals: host(&d.normals),
        output: host(&d.output),
        motion_vector_scale: d.motion_vector_scale.to_array(),
        normals_unpack_mul: d.normals_unpack_mul,
        normals_unpack_add: d.normals_unpack_add,
        eye: d.eye.to_array(),
        frame_index: d.frame_index,
        projection_inverse: d.projection_inverse.to_cols_array(),
        reprojection_matrix: d.reprojection_matrix.to_cols_array(),
        view_projection_inverse: d.view_projection_inverse.to_cols_array(),
        depth_similarity_sigma: d.depth_similarity_sigma,
        render_rect: DnsrRect::default(),
        sync: DnsrHostSync {
            input_src_stages: d.sync.input_src_stages,
            input_src_access: d.sync.input_src_access,
            output_dst_stages: d.sync.output_dst_stages,
            output_dst_access: d.sync.output_dst_access,
        },
        debug_view: DNSR_DEBUG_VIEW_NONE,
        hit_distance: d.hit_distance.as_ref().map(host).unwrap_or_default(),
        light_angular_size: d.light_angular_size,
        engine_image_count: 0,
        p_engine_images: std::ptr::null(),
        visibility: host(&d.visibility),
        checkerboard_phase: d.checkerboard_phase,
        light_position: d.light_position.unwrap_or_default().to_array(),
        previous_depth: host(&d.previous_depth),
        previous_normals: host(&d.previous_normals),
    }
}

fn last_error() -> String {
    unsafe { CStr::from_ptr(dnsr_last_error_message()) }.to_string_lossy().into_owned()
}

#[test]
fn a_frame_through_the_c_api_equals_the_rust_api_bit_for_bit() {
    let g = gpu();
    let (w, h) = (37, 23);
    let mut info = g.create_info(w, h);
    info.output_format = vk::Format::R32_SFLOAT;
    let mut rust = Runner::new(&g, &info).unwrap();
    let mut c_side = Runner::new(&g, &info).unwrap(); // its images; its own context stays unused
    let mut ctx: DnsrContext = std::ptr::null_mut();
    assert_eq!(dnsr_context_create(&create_info(&g, w, h), &mut ctx), DnsrResult::DNSR_SUCCESS, "{}", last_error());
    for frame in 0..6 {
        let f = static_frame(w, h, &smooth, frame + 1);
        let expected = rust.frame(&f, frame == 0);
        let d = crate::ShadowsDispatch { reset: frame == 0, ..c_side.dispatch(&f) };
        let (result, got) = c_side.run_with(&f, |_, cmd| match dnsr_shadows_record(ctx, &c_dispatch(&d, cmd)) {
            DnsrResult::DNSR_SUCCESS => Ok(()),
            code => Err((code, last_error())),
        });
        result.unwrap();
        assert_eq!(got, expected, "frame {frame}");
    }
    assert_eq!(dnsr_context_destroy(ctx), DnsrResult::DNSR_SUCCESS);
    drop((rust, c_side));
    g.assert_clean();
}

/// Every call that writes a DnsrSettings leaves its padding (after sType) zero, whatever the memory held: a C host
/// may compare settings with memcmp (capi-tests/header_c11.c does).
#[test]
fn written_settings_have_zero_padding() {
    let padding = std::mem::offset_of!(DnsrSettings, p_next) - std::mem::size_of::<DnsrStructureType>();
    assert!(padding > 0, "DnsrSettings has no padding to check");
    let garbage = || {
        let mut s = std::mem::MaybeUninit::<DnsrSettings>::uninit();
        // SAFETY: every byte pattern is a valid DnsrSettings (integers, floats, a pointer that is never read).
        unsafe {
            std::ptr::write_bytes(s.as_mut_ptr(), 0xab, 1);
            s.assume_init()
        }
    };
    let bytes = |s: &DnsrSettings| -> Vec<u8> {
        // SAFETY: reads the struct's bytes, which the calls below initialised (the padding included).
        unsafe { std::slice::from_raw_parts(s as *const DnsrSettings as *const u8, std::mem::size_of::<DnsrSettings>()) }.to_vec()
    };
    let (mut default, mut quality, mut balanced) = (garbage(), garbage(), garbage());
    assert_eq!(dnsr_settings_init_default(&mut default), DnsrResult::DNSR_SUCCESS);
    assert_eq!(dnsr_settings_init_preset(DNSR_PRESET_QUALITY, &mut quality), DnsrResult::DNSR_SUCCESS);
    assert_eq!(dnsr_settings_init_preset(DNSR_PRESET_BALANCED, &mut balanced), DnsrResult::DNSR_SUCCESS);
    let at = std::mem::size_of::<DnsrStructureType>();
    for s in [&default, &quality, &balanced] {
        assert_eq!(bytes(s)[at..at + padding], vec![0u8; padding]);
    }
    assert_eq!(bytes(&default), bytes(&quality), "the default is the Quality preset, byte for byte");

    let g = gpu();
    let mut ctx: DnsrContext = std::ptr::null_mut();
    assert_eq!(dnsr_context_create(&create_info(&g, 8, 8), &mut ctx), DnsrResult::DNSR_SUCCESS);
    let mut got = garbage();
    assert_eq!(dnsr_context_get_settings(ctx, &mut got), DnsrResult::DNSR_SUCCESS);
    assert_eq!(bytes(&got), bytes(&default), "a new context's settings are the default, byte for byte");
    assert_eq!(dnsr_context_destroy(ctx), DnsrResult::DNSR_SUCCESS);
    g.assert_clean();
}

#[test]
fn handles_codes_and_messages() {
    let g = gpu();
    let mut ctx: DnsrContext = std::ptr::null_mut();
    let mut bad = create_info(&g, 8, 8);
    bad.width = 0;
    assert_eq!(dnsr_context_create(&bad, &mut ctx), DnsrResult::DNSR_ERROR_INVALID_EXTENT);
    assert!(ctx.is_null());
    assert!(last_error().contains("render size"), "{}", last_error());
    bad = create_info(&g, 8, 8);
    bad.s_type = 77;
    assert_eq!(dnsr_context_create(&bad, &mut ctx), DnsrResult::DNSR_ERROR_INVALID_STRUCTURE);
    assert!(last_error().contains("sType is 77"), "{}", last_error());
    assert_eq!(dnsr_context_create(std::ptr::null(), &mut ctx), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
    assert_eq!(last_error(), "pCreateInfo is NULL");

    assert_eq!(dnsr_context_create(&create_info(&g, 8, 8), &mut ctx), DnsrResult::DNSR_SUCCESS);
    assert_eq!(last_error(), "", "a success clears the message");
    let mut bytes = 0u64;
    assert_eq!(dnsr_context_get_memory_usage(ctx, &mut bytes), DnsrResult::DNSR_SUCCESS);
    assert!(bytes > 0);
    let mut kept = 0u64;
    assert_eq!(dnsr_context_get_persistent_memory_usage(ctx, &mut kept), DnsrResult::DNSR_SUCCESS);
    assert!(kept > 0 && kept < bytes, "persistent {kept} of {bytes}");
    assert_eq!(dnsr_context_get_persistent_memory_usage(ctx, std::ptr::null_mut()), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
    // Three lights: one transient set, or one per light with DNSR_CONTEXT_CREATE_TRANSIENT_MEMORY_PER_LIGHT (two
    // more sets, the same persistent images).
    let usage = |flags: DnsrContextCreateFlags| {
        let (mut lights, mut three) = (create_info(&g, 8, 8), std::ptr::null_mut());
        (lights.light_count, lights.flags) = (3, flags);
        assert_eq!(dnsr_context_create(&lights, &mut three), DnsrResult::DNSR_SUCCESS, "{}", last_error());
        let (mut all, mut persistent) = (0u64, 0u64);
        assert_eq!(dnsr_context_get_memory_usage(three, &mut all), DnsrResult::DNSR_SUCCESS);
        assert_eq!(dnsr_context_get_persistent_memory_usage(three, &mut persistent), DnsrResult::DNSR_SUCCESS);
        assert_eq!(dnsr_context_destroy(three), DnsrResult::DNSR_SUCCESS);
        // What dnsr_get_context_memory_requirements says of the same create info: the same, less driver padding.
        let (mut bytes, mut kept) = (0u64, 0u64);
        assert_eq!(dnsr_get_context_memory_requirements(&lights, &mut bytes, &mut kept), DnsrResult::DNSR_SUCCESS);
        assert!(bytes <= all && all - bytes < 65536 && kept <= persistent && persistent - kept < 32768, "{bytes} {all} {kept} {persistent}");
        assert_eq!(dnsr_get_context_memory_requirements(&lights, &mut bytes, std::ptr::null_mut()), DnsrResult::DNSR_SUCCESS);
        (all, persistent)
    };
    let (shared, own) = (usage(0), usage(DNSR_CONTEXT_CREATE_TRANSIENT_MEMORY_PER_LIGHT));
    let mut estimate = 0u64;
    assert_eq!(dnsr_get_context_memory_requirements(std::ptr::null(), &mut estimate, std::ptr::null_mut()), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
    assert_eq!(dnsr_get_context_memory_requirements(&create_info(&g, 8, 8), std::ptr::null_mut(), std::ptr::null_mut()), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
    let mut nine = create_info(&g, 8, 8);
    (nine.light_count, nine.flags) = (9, DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER);
    assert_eq!(dnsr_get_context_memory_requirements(&nine, &mut estimate, std::ptr::null_mut()), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
    assert!(last_error().contains("lights_recorded_together") || last_error().contains("lightsRecordedTogether"), "{}", last_error());
    assert_eq!(shared.1, 3 * kept, "each light its own persistent images");
    // Recorded together: one depth copy (at least 4 B/px) for the three.
    let together = usage(DNSR_CONTEXT_CREATE_LIGHTS_RECORDED_TOGETHER);
    assert!(together.1 + 2 * 8 * 8 * 4 <= shared.1, "one depth copy for three lights: {} of {}", together.1, shared.1);
    assert_eq!(own.1, shared.1);
    // The host's previous depth and normals: no depth copy at all, the same bytes in all (each set's frame depth).
    let host_previous = usage(DNSR_CONTEXT_CREATE_HOST_PREVIOUS_GBUFFER);
    assert!(host_previous.1 + 3 * 8 * 8 * 4 <= shared.1, "no depth copy: {} of {}", host_previous.1, shared.1);
    assert!(host_previous.0 < shared.0, "one frame depth instead of three depth copies: {} of {}", host_previous.0, shared.0);
    // Each set holds what a one-light context holds beyond its persistent images, less its constants.
    let (set, one_light_transient) = ((own.0 - shared.0) / 2, bytes - kept);
    assert!(set > 0 && set <= one_light_transient && one_light_transient - set <= 4096, "a transient set {set}, {one_light_transient}");
    let mut timings = DnsrPassTimings {
        s_type: DNSR_STRUCTURE_TYPE_PASS_TIMINGS,
        p_next: std::ptr::null_mut(),
        frame: 0,
        prepare_ms: 0.0,
        tile_classification_ms: 0.0,
        filter_ms: [0.0; 4],
        filter_passes: 0,
        total_ms: 0.0,
    };
    assert_eq!(dnsr_context_get_timings(ctx, &mut timings), DnsrResult::DNSR_NOT_READY);
    let mut s = unsafe { std::mem::zeroed::<DnsrSettings>() };
    assert_eq!(dnsr_context_get_settings(ctx, &mut s), DnsrResult::DNSR_SUCCESS);
    assert_eq!(s.filter_passes, crate::Settings::default().filter_passes);
    s.filter_passes = 9;
    assert_eq!(dnsr_context_set_settings(ctx, &s), DnsrResult::DNSR_ERROR_INVALID_SETTING);
    assert!(last_error().contains("filterPasses"), "{}", last_error());
    assert_eq!(dnsr_context_destroy(ctx), DnsrResult::DNSR_SUCCESS);
    assert_eq!(dnsr_context_destroy(ctx), DnsrResult::DNSR_ERROR_INVALID_HANDLE, "double destroy");
    assert_eq!(dnsr_context_resize(ctx, 4, 4), DnsrResult::DNSR_ERROR_INVALID_HANDLE, "use after destroy");
    assert_eq!(dnsr_context_destroy(std::ptr::null_mut()), DnsrResult::DNSR_SUCCESS);
    assert_eq!(dnsr_context_reset_history(0xdead as DnsrContext, 0), DnsrResult::DNSR_ERROR_INVALID_HANDLE);

    let mut req = unsafe { std::mem::zeroed::<DnsrDeviceRequirements>() };
    assert_eq!(dnsr_get_device_requirements(&mut req), DnsrResult::DNSR_ERROR_INVALID_STRUCTURE);
    req.s_type = DNSR_STRUCTURE_TYPE_DEVICE_REQUIREMENTS;
    assert_eq!(dnsr_get_device_requirements(&mut req), DnsrResult::DNSR_SUCCESS);
    assert_eq!(req.min_api_version, vk::API_VERSION_1_1);
    let ext = unsafe { CStr::from_ptr(*req.pp_optional_extension_names) };
    assert_eq!(ext, ash::khr::push_descriptor::NAME);
    let mut needed = 0u64;
    assert_eq!(dnsr_get_memory_requirements(1920, 1080, DNSR_PRECISION_FP32, 3, 1, &mut needed), DnsrResult::DNSR_SUCCESS);
    // At least the per-pixel texels: reprojection, depth copy and two moments, 4 B each, and the history's 2 B.
    assert!(needed > 1920 * 1080 * 18);
    assert_eq!(needed, crate::memory_requirements(1920, 1080, crate::Precision::Fp32, 3, 1).unwrap());
    assert_eq!(dnsr_get_memory_requirements(1920, 1080, 5, 3, 1, &mut needed), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
    let mut kept = 0u64;
    assert_eq!(dnsr_get_persistent_memory_requirements(1920, 1080, DNSR_PRECISION_FP32, 1, &mut kept), DnsrResult::DNSR_SUCCESS);
    assert!(kept > 0 && kept < needed, "persistent {kept} of {needed}");
    assert_eq!(dnsr_get_persistent_memory_requirements(1920, 1080, DNSR_PRECISION_FP32, 0, &mut kept), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
    assert_eq!(dnsr_get_persistent_memory_requirements(1920, 1080, DNSR_PRECISION_FP32, 1, std::ptr::null_mut()), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
    let name = |r: i32| unsafe { CStr::from_ptr(dnsr_result_to_string(r)) }.to_str().unwrap().to_owned();
    assert_eq!(name(DnsrResult::DNSR_ERROR_NON_FINITE as i32), "DNSR_ERROR_NON_FINITE");
    assert_eq!(name(12345), "DNSR_RESULT_UNKNOWN");
    assert_eq!(dnsr_version() >> 22, DNSR_VERSION_MAJOR);
    assert_eq!(
        format!("{DNSR_VERSION_MAJOR}.{DNSR_VERSION_MINOR}.{DNSR_VERSION_PATCH}"),
        env!("CARGO_PKG_VERSION"),
        "C version constants follow Cargo.toml"
    );
    g.assert_clean();
}

mod reference_table {
    use super::super::{correctness::smooth, gpu, static_frame};
    use crate::capi::reference::*;
    use crate::capi::types::{DnsrResult, DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO};
    use crate::testing::scene::FrameInputs;
    use crate::ShadowInput;
    use crate::testing::Runner;
    use ash::vk;
    use std::ffi::c_void;

    struct Data<'a> {
        f: &'a FrameInputs,
        output: Vec<f32>,
    }

    fn data<'a>(user: *mut c_void) -> &'a mut Data<'a> {
        unsafe { &mut *(user as *mut Data) }
    }
    fn idx(d: &Data, x: i32, y: i32) -> usize {
        (y as u32 * d.f.width + x as u32) as usize
    }
    unsafe extern "C" fn read_hit_mask(user: *mut c_void, tx: i32, ty: i32) -> u32 {
        let d = data(user);
        d.f.mask[(ty as u32 * d.f.width.div_ceil(8) + tx as u32) as usize]
    }
    unsafe extern "C" fn read_depth(user: *mut c_void, x: i32, y: i32) -> f32 {
        let d = data(user);
        d.f.depth[idx(d, x, y)]
    }
    unsafe extern "C" fn read_normal(user: *mut c_void, x: i32, y: i32, rgb: *mut f32) {
        let d = data(user);
        let n = d.f.normals[idx(d, x, y)];
        unsafe { std::ptr::copy_nonoverlapping(n.as_ptr(), rgb, 3) };
    }
    unsafe extern "C" fn read_velocity(user: *mut c_void, x: i32, y: i32, xy: *mut f32) {
        let d = data(user);
        let v = d.f.velocity[idx(d, x, y)];
        unsafe { std::ptr::copy_nonoverlapping(v.as_ptr(), xy, 2) };
    }
    unsafe extern "C" fn read_hit_distance(user: *mut c_void, x: i32, y: i32) -> f32 {
        let d = data(user);
        d.f.hit_distance[idx(d, x, y)]
    }
    unsafe extern "C" fn read_visibility(user: *mut c_void, x: i32, y: i32) -> f32 {
        let d = data(user);
        d.f.visibility[idx(d, x, y)]
    }
    unsafe extern "C" fn write_output(user: *mut c_void, x: i32, y: i32, value: f32) {
        let d = data(user);
        let i = idx(d, x, y);
        d.output[i] = value;
    }

    /// An engine's first frame (reset) through the C reference table equals dnsr's GPU output on the same data,
    /// without and with penumbra guidance, with a visibility or a checkerboard input, and for a light of no size.
    #[test]
    fn the_c_reference_table_reproduces_the_gpu_frame() {
        let g = gpu();
        let one_ray = reference_frame(&g, None, ShadowInput::HitMask, false);
        let four_rays = reference_frame(&g, None, ShadowInput::Visibility, false);
        assert!(one_ray.iter().zip(&four_rays).any(|(a, b)| (a - b).abs() > 1e-3), "the visibility input changed nothing");
        let half_ray = reference_frame(&g, None, ShadowInput::Checkerboard, false);
        assert!(one_ray.iter().zip(&half_ray).any(|(a, b)| (a - b).abs() > 1e-3), "the checkerboard input changed nothing");
        let mut unguided = Vec::new();
        for guidance in [None, Some(0.3f32)] {
            let out = reference_frame(&g, guidance, ShadowInput::HitMask, false);
            if guidance.is_some() {
                let changed = out.iter().zip(&unguided).map(|(a, b): (&f32, &f32)| (a - b).abs()).fold(0.0, f32::max);
                assert!(changed > 1e-3, "guidance changed nothing: the guided path is not exercised");
            }
            unguided = out;
        }
        let hard = reference_frame(&g, None, ShadowInput::HitMask, true);
        assert!(hard.iter().zip(&one_ray).any(|(a, b)| (a - b).abs() > 1e-3), "DNSR_REFERENCE_HARD_LIGHT changed nothing");
        g.assert_clean();
    }

    /// Runs the frame on the GPU and through the C reference; checks they agree and returns the GPU output.
    fn reference_frame(g: &crate::testing::gpu::Gpu, guidance: Option<f32>, input: ShadowInput, hard_light: bool) -> Vec<f32> {
        let (w, h) = (37, 23);
        let visibility = input == ShadowInput::Visibility;
        let mut info = g.create_info(w, h);
        info.output_format = vk::Format::R32_SFLOAT;
        info.shadow_input = input;
        let mut r = Runner::new(g, &info).unwrap();
        r.guidance = guidance;
        r.hard_light = hard_light;
        // A checkerboard frame of phase 1.
        r.checkerboard_phase = (input == ShadowInput::Checkerboard) as u32;
        let mut f = static_frame(w, h, &smooth, 7);
        f.trace_rays(4, 7);
        f.hit_distance = (0..w * h).map(|i| 0.2 + (i % 5) as f32 * 0.1).collect();
        let d = r.dispatch(&f);
        let gpu_out = r.frame(&f, true);

        let mut user = Data { f: &f, output: vec![f32::NAN; (w * h) as usize] };
        let frame = DnsrReferenceFrameInfo {
            s_type: DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO,
            p_next: std::ptr::null(),
            width: w,
            height: h,
            flags: DNSR_REFERENCE_RESET
                | if guidance.is_some() { DNSR_REFERENCE_USE_HIT_DISTANCE } else { 0 }
                | if visibility { DNSR_REFERENCE_VISIBILITY_INPUT } else { 0 }
                | if hard_light { DNSR_REFERENCE_HARD_LIGHT } else { 0 }
                | if input == ShadowInput::Checkerboard { DNSR_REFERENCE_CHECKERBOARD_INPUT | DNSR_REFERENCE_CHECKERBOARD_PHASE_1 } else { 0 },
            p_settings: std::ptr::null(),
            motion_vector_scale: d.motion_vector_scale.to_array(),
            normals_unpack_mul: d.normals_unpack_mul,
            normals_unpack_add: d.normals_unpack_add,
            eye: d.eye.to_array(),
            depth_similarity_sigma: d.depth_similarity_sigma,
            projection_inverse: d.projection_inverse.to_cols_array(),
            reprojection_matrix: d.reprojection_matrix.to_cols_array(),
            view_projection_inverse: d.view_projection_inverse.to_cols_array(),
            light_angular_size: guidance.unwrap_or(0.0),
            light_position: [0.0; 4],
        };
        let callbacks = DnsrReferenceCallbacks {
            user_data: &mut user as *mut Data as *mut c_void,
            read_hit_mask: if visibility { None } else { Some(read_hit_mask) },
            read_depth: Some(read_depth),
            read_normal: Some(read_normal),
            read_velocity: Some(read_velocity),
            read_previous_depth: None,
            read_previous_moments: None,
            read_history: None,
            write_output: Some(write_output),
            write_tile_meta: None,
            write_reprojection: None,
            write_moments: None,
            write_history: None,
            read_hit_distance: Some(read_hit_distance),
            read_visibility: Some(read_visibility),
            read_previous_normal: None,
            read_previous_tile_quiet: None,
            write_tile_quiet: None,
        };
        assert_eq!(dnsr_reference_run_frame(&frame, &callbacks), DnsrResult::DNSR_SUCCESS);
        let worst = gpu_out.iter().zip(&user.output).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
        assert!(worst <= 1e-4, "C reference vs GPU ({guidance:?}): {worst}");
        // What a dispatch refuses, the reference refuses too (each used to run and return SUCCESS, the first with
        // every output non-finite or outside [0, 1]).
        for (bad, want) in [
            (DnsrReferenceFrameInfo { depth_similarity_sigma: 0.0, ..frame }, DnsrResult::DNSR_ERROR_INVALID_ARGUMENT),
            (DnsrReferenceFrameInfo { depth_similarity_sigma: f32::NAN, ..frame }, DnsrResult::DNSR_ERROR_NON_FINITE),
            (DnsrReferenceFrameInfo { eye: [f32::INFINITY, 0.0, 0.0], ..frame }, DnsrResult::DNSR_ERROR_NON_FINITE),
            (DnsrReferenceFrameInfo { motion_vector_scale: [f32::NAN, 1.0], ..frame }, DnsrResult::DNSR_ERROR_NON_FINITE),
            (DnsrReferenceFrameInfo { normals_unpack_add: f32::NAN, ..frame }, DnsrResult::DNSR_ERROR_NON_FINITE),
            (DnsrReferenceFrameInfo { flags: frame.flags | 1 << 20, ..frame }, DnsrResult::DNSR_ERROR_INVALID_ARGUMENT),
        ] {
            assert_eq!(dnsr_reference_run_frame(&bad, &callbacks), want);
        }
        // A frame without RESET needs the previous-state callbacks; guidance needs its callback and a valid angle.
        let no_reset = DnsrReferenceFrameInfo { flags: 0, ..frame };
        assert_eq!(dnsr_reference_run_frame(&no_reset, &callbacks), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
        if visibility {
            let no_callback = DnsrReferenceCallbacks { read_visibility: None, ..callbacks };
            assert_eq!(dnsr_reference_run_frame(&frame, &no_callback), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
        }
        if guidance.is_some() {
            let no_callback = DnsrReferenceCallbacks { read_hit_distance: None, ..callbacks };
            assert_eq!(dnsr_reference_run_frame(&frame, &no_callback), DnsrResult::DNSR_ERROR_INVALID_ARGUMENT);
            let nan = DnsrReferenceFrameInfo { light_angular_size: f32::NAN, ..frame };
            assert_eq!(dnsr_reference_run_frame(&nan, &callbacks), DnsrResult::DNSR_ERROR_NON_FINITE);
        }
        drop(r);
        gpu_out
    }
}

/// The CPU reference's C entry points answer DNSR_ERROR_OUT_OF_HOST_MEMORY where their buffers cannot be allocated
/// (they used to abort the process: `dnsr_reference_diagnose` at 16384x16384, `dnsr_reference_run_frame` at 4096x4096
/// under a 3 GB address-space limit). The limit applies to a whole process, so the test runs itself again as a child
/// (DNSR_OOM_CHILD set) that lowers its own limit to 1 GiB and makes both calls at 16384x16384.
mod host_memory {
    use crate::capi::reference::*;
    use crate::capi::types::{DnsrResult, DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO};
    use std::ffi::c_void;

    unsafe extern "C" fn zero(_: *mut c_void, _: i32, _: i32) -> f32 {
        0.0
    }
    unsafe extern "C" fn zeros(_: *mut c_void, _: i32, _: i32, out: *mut f32) {
        unsafe { *out = 0.0 };
    }
    unsafe extern "C" fn no_hits(_: *mut c_void, _: i32, _: i32) -> u32 {
        0
    }

    fn calls() -> [DnsrResult; 2] {
        let mut identity = [0.0f32; 16];
        for i in 0..4 {
            identity[i * 5] = 1.0;
        }
        let info = DnsrReferenceFrameInfo {
            s_type: DNSR_STRUCTURE_TYPE_REFERENCE_FRAME_INFO,
            p_next: std::ptr::null(),
            width: 16384,
            height: 16384,
            flags: DNSR_REFERENCE_RESET,
            p_settings: std::ptr::null(),
            motion_vector_scale: [1.0, 1.0],
            normals_unpack_mul: 1.0,
            normals_unpack_add: 0.0,
            eye: [0.0; 3],
            depth_similarity_sigma: 1.0,
            projection_inverse: identity,
            reprojection_matrix: identity,
            view_projection_inverse: identity,
            light_angular_size: 0.0,
            light_position: [0.0; 4],
        };
        let callbacks = DnsrReferenceCallbacks {
            user_data: std::ptr::null_mut(),
            read_hit_mask: Some(no_hits),
            read_depth: Some(zero),
            read_normal: Some(zeros),
            read_velocity: Some(zeros),
            read_previous_depth: None,
            read_previous_moments: None,
            read_history: None,
            write_output: None,
            write_tile_meta: None,
            write_reprojection: None,
            write_moments: None,
            write_history: None,
            read_hit_distance: None,
            read_visibility: None,
            read_previous_normal: None,
            read_previous_tile_quiet: None,
            write_tile_quiet: None,
        };
        let mut count = 0u32;
        [
            dnsr_reference_run_frame(&info, &callbacks),
            dnsr_reference_diagnose(&info, &callbacks, &mut count, std::ptr::null_mut()),
        ]
    }

    #[test]
    fn reference_entry_points_report_out_of_host_memory() {
        if std::env::var_os("DNSR_OOM_CHILD").is_some() {
            let limit = libc::rlimit { rlim_cur: 1 << 30, rlim_max: 1 << 30 };
            // SAFETY: lowers this (child) process's own address-space limit.
            assert_eq!(unsafe { libc::setrlimit(libc::RLIMIT_AS, &limit) }, 0);
            let got = calls();
            assert_eq!(got, [DnsrResult::DNSR_ERROR_OUT_OF_HOST_MEMORY; 2]);
            return;
        }
        let out = std::process::Command::new(std::env::current_exe().unwrap())
            .args(["--exact", "tests::capi::host_memory::reference_entry_points_report_out_of_host_memory", "--nocapture", "--test-threads", "1"])
            .env("DNSR_OOM_CHILD", "1")
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success() && text.contains("1 passed"), "child: {:?}\n{text}", out.status);
    }
}

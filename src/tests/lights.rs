//! Several lights in one `record_lights` call: the same result as one `record_shadows` call per light, a light
//! reset alone, and a bad light refusing the whole call.

use super::gpu;
use crate::testing::gpu::{Gpu, GpuOptions, TestImage};
use crate::testing::scene::{render_with_blockers, Camera, FrameInputs};
use crate::testing::Runner;
use crate::{Error, HostImage, LightDispatch, ShadowInput, ShadowsDispatch};
use ash::vk;

const W: u32 = 64;
const H: u32 = 48;
/// More lights than one dispatch of the filter's light-slot variants takes (crate::passes::LIGHT_SLOTS), so that
/// the later filter passes run a full group and a partial one (three lights in four slots).
const LIGHTS: usize = 7;
const _: () = assert!(LIGHTS > crate::passes::LIGHT_SLOTS);
/// The frame at which light 1 (only) restarts its history.
const RESET_FRAME: u32 = 3;
/// Penumbra guidance for lights 2 and 4 (angular size in radians, light 4's twice light 2's); the others have none.
const GUIDED_ANGLE: f32 = 0.05;

/// The light of no size (`ShadowsDispatch::hard_light`, without hit distances): in the second group of slots.
const HARD_LIGHT: usize = 5;

fn guided(light: usize) -> bool {
    light == 2 || light == 4
}

/// Light `light`'s frame `frame`: one camera path for every light (so one G-buffer), a shadow of its own.
fn light_frame(light: usize, frame: u32) -> FrameInputs {
    let cam = |k: u32| Camera::above(0.15 * k as f64, 0.05 * k as f64, 10.0);
    let fields: [&dyn Fn(f64, f64) -> f64; LIGHTS] = [
        &|x, _| (0.5 + x / 3.0).clamp(0.0, 1.0),
        &|x, z| if x * x + z * z < 4.0 { 0.1 } else { 1.0 },
        &|x, z| if ((x + z) * 0.7).rem_euclid(2.0) < 1.0 { 0.0 } else { 0.8 },
        &|x, z| (0.5 + 0.4 * (x * 0.8).sin() * (z * 0.6).cos()).clamp(0.0, 1.0),
        &|_, z| if z < 0.5 { 0.0 } else { 1.0 },
        &|x, z| if (x - 1.0).abs() + z.abs() < 2.5 { 0.3 } else { 1.0 },
        &|x, z| (0.2 + 0.1 * x - 0.05 * z).clamp(0.0, 1.0),
    ];
    let seed = 1000 * light as u64 + frame as u64;
    render_with_blockers(W, H, &cam(frame), &cam(frame.saturating_sub(1)), 7.0, fields[light], &|x, _| 0.5 + x.abs(), seed)
}

/// `transient_per_light`: `ContextCreateInfo::transient_memory_per_light` (the light-slot variants) instead of one
/// transient set that the lights use in turn; `together`: `ContextCreateInfo::lights_recorded_together` (one depth
/// copy for all lights).
fn runner(g: &Gpu, input: ShadowInput, transient_per_light: bool, together: bool) -> Runner<'_> {
    let mut info = g.create_info(W, H);
    info.transient_memory_per_light = transient_per_light;
    info.lights_recorded_together = together;
    info.output_format = vk::Format::R32_SFLOAT;
    info.light_count = LIGHTS as u32;
    info.shadow_input = input;
    // Quality's paths (converged pixels, runs), and hard penumbrae wide enough to hold some of the guided lights'
    // pixels (their penumbrae are about 1-3 px wide either side), so that the light-slot filter takes each.
    info.settings = crate::Settings { hard_penumbra_pixels: 2.0, ..crate::Settings::preset(crate::Preset::Quality) };
    Runner::new(g, &info).unwrap()
}

fn floats(raw: &[u8]) -> Vec<f32> {
    bytemuck::cast_slice(raw).to_vec()
}

/// This light's fields of a dispatch over `mask`, `output` and the runner's hit distances.
fn light(index: usize, mask: &TestImage, output: &TestImage, hit_distance: &TestImage, frame: u32) -> LightDispatch {
    LightDispatch {
        light_index: index as u32,
        hit_mask: mask.host(),
        output: output.host(),
        hit_distance: guided(index).then(|| hit_distance.host()),
        light_angular_size: if guided(index) { GUIDED_ANGLE * (index / 2) as f32 } else { 0.0 },
        hard_light: index == HARD_LIGHT,
        // One light is given as a direction: its receivers turned away from it keep their shadowed samples.
        light_position: (index == 2).then(|| glam::Vec4::new(0.6, -0.2, 0.8, 0.0)),
        reset: index == 1 && frame == RESET_FRAME,
        ..Default::default()
    }
}

/// The shared part of a dispatch: `d` with its per-light fields at their defaults.
fn shared(d: &ShadowsDispatch) -> ShadowsDispatch {
    ShadowsDispatch {
        light_index: 0,
        hit_mask: Default::default(),
        output: Default::default(),
        hit_distance: None,
        light_angular_size: 0.0,
        light_position: None,
        reset: false,
        ..*d
    }
}

/// With push descriptors and with the descriptor-set ring (one ring per light), for a hit mask and for a
/// checkerboard input (prepare always runs, each light reconstructs into its own image); with the lights sharing
/// their transient images (each light's passes in a row), and with a set each (the light-slot variants) on two of
/// the four; the batched lights recorded together (one depth copy for all) on two of them, one each way.
#[test]
fn several_lights_in_one_record_equal_one_record_per_light() {
    for push_descriptor in [true, false] {
        for input in [ShadowInput::HitMask, ShadowInput::Checkerboard] {
            let g = Gpu::new(GpuOptions { push_descriptor, ..Default::default() });
            assert_eq!(g.features.push_descriptor, push_descriptor, "device lacks VK_KHR_push_descriptor");
            let per_light_too = push_descriptor == (input == ShadowInput::HitMask);
            for transient_per_light in [false, true].into_iter().filter(|&p| !p || per_light_too) {
                // Together: with a shared transient set on the hit mask, with a set each on the checkerboard.
                let together = per_light_too && transient_per_light == (input == ShadowInput::Checkerboard);
                eprintln!("push descriptors {push_descriptor}, {input:?}, transient images per light {transient_per_light}, together {together}");
                equal_to_one_record_per_light(&g, input, transient_per_light, together);
            }
            g.assert_clean();
        }
    }
}

fn equal_to_one_record_per_light(g: &Gpu, input: ShadowInput, transient_per_light: bool, together: bool) {
    let phase = |frame: u32| if input == ShadowInput::Checkerboard { frame % 2 } else { 0 };
    let mut single = runner(g, input, transient_per_light, false);
    let mut batched = runner(g, input, transient_per_light, together);
    assert_eq!(batched.ctx.has_light_slot_pipelines(), transient_per_light, "the later passes of several lights per dispatch");
    // The batched runner's lights but the last read and write these; the last uses the runner's own images (its
    // frame is the one the runner uploads, hit distances included).
    let last = LIGHTS - 1;
    let masks: Vec<TestImage> = (0..last).map(|_| g.image(vk::Format::R32_UINT, W / 8, H / 4, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)).collect();
    let outputs: Vec<TestImage> = (0..last).map(|_| g.image(vk::Format::R32_SFLOAT, W, H, vk::ImageLayout::GENERAL)).collect();
    let hit_distances: Vec<TestImage> =
        (0..last).map(|_| g.image(vk::Format::R32_SFLOAT, W, H, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)).collect();
    let mut reset_changed = false;
    for frame in 0..6 {
        single.checkerboard_phase = phase(frame);
        batched.checkerboard_phase = phase(frame);
        let inputs: Vec<FrameInputs> = (0..LIGHTS).map(|l| light_frame(l, frame)).collect();
        let expected: Vec<Vec<f32>> = (0..LIGHTS)
            .map(|l| {
                let d = single.dispatch(&inputs[l]);
                let ld = light(l, &single.mask, &single.output, &single.hit_distance, frame);
                single.run(&inputs[l], &ld.apply(&d)).expect("record_shadows")
            })
            .collect();

        for ((mask, hit_distance), f) in masks.iter().zip(&hit_distances).zip(&inputs) {
            g.upload(mask, bytemuck::cast_slice(&f.mask));
            g.upload(hit_distance, bytemuck::cast_slice(&f.hit_distance));
        }
        let d = shared(&batched.dispatch(&inputs[last]));
        let lights: Vec<LightDispatch> = (0..LIGHTS)
            .map(|l| match l < last {
                true => light(l, &masks[l], &outputs[l], &hit_distances[l], frame),
                false => light(l, &batched.mask, &batched.output, &batched.hit_distance, frame),
            })
            .collect();
        let (result, last_output) = batched.run_with(&inputs[last], |ctx, cmd| ctx.record_lights(cmd, &d, &lights));
        result.expect("record_lights");
        let got: Vec<Vec<f32>> = outputs.iter().map(|o| floats(&g.download(o))).chain([last_output]).collect();
        for l in 0..LIGHTS {
            let differing = got[l].iter().zip(&expected[l]).filter(|(a, b)| a.to_bits() != b.to_bits()).count();
            assert_eq!(differing, 0, "frame {frame} light {l}: {differing} pixels differ from its own record_shadows");
        }
        if frame == RESET_FRAME {
            // The reset must show: light 1 run up to here without one (its own context) ends elsewhere.
            let mut unreset = runner(g, input, transient_per_light, false);
            let mut out = Vec::new();
            for k in 0..=frame {
                unreset.checkerboard_phase = phase(k);
                let f = light_frame(1, k);
                let d = ShadowsDispatch { light_index: 1, ..unreset.dispatch(&f) };
                out = unreset.run(&f, &d).expect("record_shadows");
            }
            reset_changed = out.iter().zip(&got[1]).any(|(a, b)| a != b);
        }
    }
    assert!(reset_changed, "resetting light 1 changed nothing: the test cannot tell a reset from none");
    // Every light holds its own persistent state and nothing more (the later filter passes' guide is each light's
    // depth copy); the transient images are one set, or one per light.
    let bytes = |lights| crate::memory_requirements(W, H, crate::Precision::Fp32, 3, lights).unwrap();
    let (one, added) = (bytes(1), bytes(2) - bytes(1));
    assert_eq!(bytes(LIGHTS as u32) - bytes(1), (LIGHTS as u64 - 1) * added, "memory grows linearly with the light count");
    let kept = crate::persistent_memory_requirements(W, H, crate::Precision::Fp32, 1).unwrap();
    assert!(added > kept && added - kept <= 1024, "each light after the first adds its persistent images ({kept}) and its constants: {added}");
    assert!(one > added, "the first light also holds the transient images");
    assert_eq!(batched.ctx.transient_set_count(), if transient_per_light { LIGHTS } else { 1 }, "transient image sets");
    // Together: one depth copy (4 B/px) for all lights, a frame depth (4 B/px) in each transient set.
    let (kept_single, kept_batched) = (single.ctx.persistent_memory_bytes(), batched.ctx.persistent_memory_bytes());
    let depth = (W * H * 4) as u64;
    match together {
        true => assert!(kept_batched + (LIGHTS as u64 - 1) * depth <= kept_single && kept_batched < kept_single, "{kept_batched} of {kept_single}"),
        false => assert_eq!(kept_batched, kept_single),
    }
    if together {
        // Every record holds every light: fewer lights, or one record_shadows, are refused and record nothing.
        let f = light_frame(0, 0);
        let d = shared(&batched.dispatch(&f));
        let before: Vec<_> = (0..LIGHTS).map(|l| batched.ctx.recording_state(l)).collect();
        let some = [light(0, &batched.mask, &batched.output, &batched.hit_distance, 0)];
        let (result, _) = batched.run_with(&f, |ctx, cmd| ctx.record_lights(cmd, &d, &some));
        let e = result.expect_err("one light of seven");
        assert!(e.to_string().contains("records every light"), "{e}");
        let single_dispatch = ShadowsDispatch { output: batched.output.host(), hit_mask: batched.mask.host(), ..d };
        let (result, _) = batched.run_with(&f, |ctx, cmd| ctx.record_shadows(cmd, &single_dispatch));
        assert!(matches!(result, Err(Error::InvalidValue { field: "the record's light count", .. })), "{result:?}");
        let after: Vec<_> = (0..LIGHTS).map(|l| batched.ctx.recording_state(l)).collect();
        assert_eq!(before, after, "a refused record changed the state");
    }
    for img in masks.iter().chain(&outputs).chain(&hit_distances) {
        g.destroy_image(img);
    }
}

#[test]
fn a_bad_light_refuses_the_whole_record() {
    let g = gpu();
    let mut r = runner(&g, ShadowInput::HitMask, false, false);
    let other = g.image(vk::Format::R32_SFLOAT, W, H, vk::ImageLayout::GENERAL);
    let f = light_frame(0, 0);
    let d = shared(&r.dispatch(&f));
    let good = |index: u32, output: &TestImage| LightDispatch { light_index: index, hit_mask: r.mask.host(), output: output.host(), ..Default::default() };
    let base = [good(0, &r.output), good(1, &other)];
    type Check = fn(&Error) -> bool;
    let cases: Vec<(&str, ShadowsDispatch, Vec<LightDispatch>, Check)> = vec![
        ("no lights", d, vec![], |e| matches!(e, Error::InvalidValue { field: "lights", .. })),
        ("nine lights", d, vec![base[0]; 9], |e| matches!(e, Error::InvalidValue { field: "lights", .. })),
        ("a light twice", d, vec![base[0], LightDispatch { output: other.host(), ..base[0] }], |e| {
            matches!(e, Error::Light { position: 1, error } if matches!(**error, Error::InvalidValue { field: "light_index", .. }))
        }),
        ("one output for two lights", d, vec![base[0], LightDispatch { output: r.output.host(), ..base[1] }], |e| {
            matches!(e, Error::Light { position: 1, error } if matches!(**error, Error::InvalidValue { field: "output", .. }))
        }),
        ("an output another light reads", d, vec![base[0], LightDispatch { hit_mask: HostImage { image: r.output.image, ..r.mask.host() }, ..base[1] }], |e| {
            matches!(e, Error::Light { position: 0, error } if matches!(**error, Error::InvalidValue { field: "output", .. }))
        }),
        ("light index out of range", d, vec![base[0], LightDispatch { light_index: LIGHTS as u32, ..base[1] }], |e| {
            matches!(e, Error::Light { position: 1, error } if matches!(**error, Error::InvalidLightIndex { index, count } if index == LIGHTS as u32 && count == LIGHTS as u32))
        }),
        ("a light without its hit mask", d, vec![base[0], LightDispatch { hit_mask: Default::default(), ..base[1] }], |e| {
            matches!(e, Error::Light { position: 1, .. })
        }),
        ("a light with a NaN angular size", d, vec![base[0], LightDispatch { hit_distance: Some(r.hit_distance.host()), light_angular_size: f32::NAN, ..base[1] }], |e| {
            matches!(e, Error::Light { position: 1, error } if matches!(**error, Error::NonFinite("light_angular_size")))
        }),
        ("output in the shared dispatch", ShadowsDispatch { output: r.output.host(), ..d }, base.to_vec(), |e| {
            matches!(e, Error::InvalidValue { field: "output", .. })
        }),
        ("reset in the shared dispatch", ShadowsDispatch { reset: true, ..d }, base.to_vec(), |e| matches!(e, Error::InvalidValue { field: "reset", .. })),
        ("hard_light in the shared dispatch", ShadowsDispatch { hard_light: true, ..d }, base.to_vec(), |e| {
            matches!(e, Error::InvalidValue { field: "hard_light", .. })
        }),
        ("light_position in the shared dispatch", ShadowsDispatch { light_position: Some(glam::Vec4::Y), ..d }, base.to_vec(), |e| {
            matches!(e, Error::InvalidValue { field: "light_position", .. })
        }),
        ("a light position with w 2", d, vec![base[0], LightDispatch { light_position: Some(glam::Vec4::new(0.0, 1.0, 0.0, 2.0)), ..base[1] }], |e| {
            matches!(e, Error::Light { position: 1, error } if matches!(**error, Error::InvalidValue { field: "light_position", .. }))
        }),
        // The camera is the shared dispatch's: its error names no light.
        ("a NaN in the shared camera", ShadowsDispatch { view_projection_inverse: glam::Mat4::NAN, ..d }, base.to_vec(), |e| {
            matches!(e, Error::NonFinite("view_projection_inverse"))
        }),
        ("light index in the shared dispatch", ShadowsDispatch { light_index: 2, ..d }, base.to_vec(), |e| {
            matches!(e, Error::InvalidValue { field: "light_index", .. })
        }),
    ];
    for (name, shared, lights, check) in cases {
        let before: Vec<_> = (0..LIGHTS).map(|l| r.ctx.recording_state(l)).collect();
        let (result, _) = r.run_with(&f, |ctx, cmd| ctx.record_lights(cmd, &shared, &lights));
        let e = result.expect_err(name);
        assert!(check(&e), "{name}: unexpected error {e:?}");
        assert!(e.to_string().len() > 10, "{name}: message {e}");
        let after: Vec<_> = (0..LIGHTS).map(|l| r.ctx.recording_state(l)).collect();
        assert_eq!(before, after, "{name}: a refused call changed the state");
    }
    // The same lights, fixed, record.
    let (result, _) = r.run_with(&f, |ctx, cmd| ctx.record_lights(cmd, &d, &base));
    result.expect("two good lights");
    g.destroy_image(&other);
    drop(r);
    g.assert_clean();
}

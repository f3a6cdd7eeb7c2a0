//! The hybrid-shadows classifier against its CPU reference (reference::classify): hit-mask words, the tile list
//! and the counts, for separate cascade images and an array image, both hit-mask conventions, with push
//! descriptors and the descriptor-set ring; and its bad input.

use crate::reference::classify::{classify, orthographic_cascade, ClassifyInputs, ShadowMap};
use crate::testing::gpu::{full_barrier, Gpu, GpuOptions, TestImage};
use crate::testing::scene::FrameInputs;
use crate::{ClassifyDispatch, Context, Error, HitMaskConvention, ShaderOverride, ShadowCascade};
use ash::vk;
use glam::{DMat4, DVec3, DVec4};

const W: u32 = 72;
const H: u32 = 44;

fn to_light() -> DVec3 {
    DVec3::new(0.4, 1.0, 0.3).normalize()
}

/// (world_to_shadow, size) of the two cascades: a fine one over the middle of the view, a coarse one around it.
fn cascade_setup() -> [(DMat4, u32); 2] {
    [
        (orthographic_cascade(to_light(), DVec3::ZERO, 8.0, 10.0, 20.0), 96),
        (orthographic_cascade(to_light(), DVec3::ZERO, 24.0, 10.0, 20.0), 48),
    ]
}

/// The shadow map of `m` (size texels square): depth of the first surface along the light, a floating slab
/// (y = 1.5 over |x - 0.5| < 2, |z| < 1.5), a thin bar (y = 0.6 over |z - 2.5| < 0.2) or the ground (y = 0).
fn shadow_map(m: DMat4, size: u32, inverted: bool) -> Vec<f32> {
    let inverse = m.inverse();
    let forward = -to_light();
    let depth_of = |p: DVec3| (m * p.extend(1.0)).z;
    let mut out = Vec::with_capacity((size * size) as usize);
    for y in 0..size {
        for x in 0..size {
            let (u, v) = ((x as f64 + 0.5) / size as f64, (y as f64 + 0.5) / size as f64);
            let origin = (inverse * DVec4::new(u, v, 0.0, 1.0)).truncate();
            let at = |h: f64| origin + forward * ((origin.y - h) / -forward.y);
            let slab = at(1.5);
            let bar = at(0.6);
            let hit = if (slab.x - 0.5).abs() < 2.0 && slab.z.abs() < 1.5 {
                slab
            } else if (bar.z - 2.5).abs() < 0.2 {
                bar
            } else {
                at(0.0)
            };
            let d = depth_of(hit) as f32;
            out.push(if inverted { 1.0 - d } else { d });
        }
    }
    out
}

/// A static view of the ground, with a sky band, a band of normals facing away from the light and a column of
/// zero normals.
fn frame() -> FrameInputs {
    let mut f = super::static_frame(W, H, &|_, _| 1.0, 1);
    for y in 0..H {
        for x in 0..W {
            let i = (y * W + x) as usize;
            if y < 3 {
                f.depth[i] = 1.0;
            }
            if (40..44).contains(&x) {
                f.normals[i] = [0.0, -1.0, 0.0, 0.0];
            }
            if x == 50 {
                f.normals[i] = [0.0; 4];
            }
        }
    }
    f
}

struct Config {
    convention: HitMaskConvention,
    taps: u32,
    cutoff: u32,
    reject_lit: bool,
    bound: bool,
    inverted: bool,
    array: bool,
    /// World units. The ground slopes by 27 degrees across the light: the receiver-plane comparison must let a
    /// small offset decide it lit.
    blocker_offset: f32,
}

/// A 2D-array image of `layers` R32_SFLOAT layers of `size` texels square, filled with `data` (layer-major), in
/// SHADER_READ_ONLY_OPTIMAL; returns (image, view, memory).
fn array_image(g: &Gpu, size: u32, layers: u32, data: &[f32]) -> (vk::Image, vk::ImageView, vk::DeviceMemory) {
    let d = &g.device;
    let info = vk::ImageCreateInfo::default()
        .image_type(vk::ImageType::TYPE_2D)
        .format(vk::Format::R32_SFLOAT)
        .extent(vk::Extent3D { width: size, height: size, depth: 1 })
        .mip_levels(1)
        .array_layers(layers)
        .samples(vk::SampleCountFlags::TYPE_1)
        .tiling(vk::ImageTiling::OPTIMAL)
        .usage(vk::ImageUsageFlags::SAMPLED | vk::ImageUsageFlags::TRANSFER_DST);
    let image = unsafe { d.create_image(&info, None) }.expect("image");
    let req = unsafe { d.get_image_memory_requirements(image) };
    let memory_type = g.memory_type(req.memory_type_bits, vk::MemoryPropertyFlags::DEVICE_LOCAL);
    let memory = unsafe { d.allocate_memory(&vk::MemoryAllocateInfo::default().allocation_size(req.size).memory_type_index(memory_type), None) }
        .expect("memory");
    unsafe { d.bind_image_memory(image, memory, 0) }.expect("bind");
    let range = vk::ImageSubresourceRange { aspect_mask: vk::ImageAspectFlags::COLOR, base_mip_level: 0, level_count: 1, base_array_layer: 0, layer_count: layers };
    let view_info = vk::ImageViewCreateInfo::default()
        .image(image)
        .view_type(vk::ImageViewType::TYPE_2D_ARRAY)
        .format(vk::Format::R32_SFLOAT)
        .subresource_range(range);
    let view = unsafe { d.create_image_view(&view_info, None) }.expect("view");
    let staging = g.staging((data.len() * 4) as u64);
    staging.write(0, bytemuck::cast_slice(data));
    g.submit(|cmd| unsafe {
        let to = |old, new| {
            vk::ImageMemoryBarrier::default()
                .image(image)
                .old_layout(old)
                .new_layout(new)
                .src_access_mask(vk::AccessFlags::MEMORY_WRITE)
                .dst_access_mask(vk::AccessFlags::MEMORY_READ | vk::AccessFlags::MEMORY_WRITE)
                .subresource_range(range)
        };
        let all = vk::PipelineStageFlags::ALL_COMMANDS;
        d.cmd_pipeline_barrier(cmd, all, all, vk::DependencyFlags::empty(), &[], &[], &[to(vk::ImageLayout::UNDEFINED, vk::ImageLayout::TRANSFER_DST_OPTIMAL)]);
        let region = vk::BufferImageCopy::default()
            .image_subresource(vk::ImageSubresourceLayers { aspect_mask: vk::ImageAspectFlags::COLOR, mip_level: 0, base_array_layer: 0, layer_count: layers })
            .image_extent(vk::Extent3D { width: size, height: size, depth: 1 });
        d.cmd_copy_buffer_to_image(cmd, staging.buffer, image, vk::ImageLayout::TRANSFER_DST_OPTIMAL, &[region]);
        let back = to(vk::ImageLayout::TRANSFER_DST_OPTIMAL, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
        d.cmd_pipeline_barrier(cmd, all, all, vk::DependencyFlags::empty(), &[], &[], &[back]);
    });
    g.destroy_staging(&staging);
    (image, view, memory)
}

fn run(g: &Gpu, cfg: &Config) {
    run_with(g, cfg, None);
}

/// `run`, the classifier's variant replaced by `engine`, whose callbacks decode the normals negated (the upload
/// negates them, so the reference's decisions stand).
fn run_with(g: &Gpu, cfg: &Config, engine: Option<&ShaderOverride>) {
    let f = frame();
    let mut info = g.create_info(W, H);
    info.enable_classifier = true;
    info.enable_timestamps = true;
    info.shader_overrides = engine.into_iter().cloned().collect();
    let mut ctx = Context::new(&info).expect("context with classifier");
    let depth = g.image(vk::Format::R32_SFLOAT, W, H, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
    let normals = g.image(vk::Format::R32G32B32A32_SFLOAT, W, H, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
    let mask = g.image(vk::Format::R32_UINT, W.div_ceil(8), H.div_ceil(4), vk::ImageLayout::GENERAL);
    g.upload(&depth, bytemuck::cast_slice(&f.depth));
    let stored: Vec<[f32; 4]> = f.normals.iter().map(|n| if engine.is_some() { n.map(|c| -c) } else { *n }).collect();
    g.upload(&normals, bytemuck::cast_slice(&stored));
    let setup = cascade_setup();
    let maps: Vec<Vec<f32>> = setup.iter().map(|&(m, size)| shadow_map(m, size, cfg.inverted)).collect();
    let mut d = ClassifyDispatch {
        depth: depth.host(),
        normals: normals.host(),
        // The frame's world is camera-relative; the cascades' is the scene's (the camera is 10 above the origin).
        view_projection_inverse: glam::Mat4::from_translation(glam::Vec3::new(0.0, 10.0, 0.0)) * f.view_projection_inverse,
        light_direction: to_light().as_vec3(),
        light_angular_size: 0.1,
        cascade_count: 2,
        cascades_depth_inverted: cfg.inverted,
        blocker_offset: cfg.blocker_offset,
        tap_count: cfg.taps,
        tile_cutoff: cfg.cutoff,
        reject_lit_pixels: cfg.reject_lit,
        cascades_bound_ray_interval: cfg.bound,
        hit_mask: mask.host(),
        hit_mask_convention: cfg.convention,
        ..Default::default()
    };
    for (k, &(m, _)) in setup.iter().enumerate() {
        // Reverse-Z cascades store 1 - depth: their matrices say so.
        let flip = DMat4::from_translation(DVec3::Z) * DMat4::from_scale(DVec3::new(1.0, 1.0, -1.0));
        d.cascades[k] = ShadowCascade { world_to_shadow: if cfg.inverted { flip * m } else { m }.as_mat4() };
    }
    // Separate images of two formats (a colour and a depth one), or one array image (the coarse cascade
    // resampled to the fine one's size: an array's layers share a size).
    let mut cascade_images: Vec<TestImage> = Vec::new();
    let mut array = None;
    let mut reference_maps = maps.clone();
    let mut sizes: Vec<u32> = setup.iter().map(|s| s.1).collect();
    if cfg.array {
        let size = setup[0].1;
        let coarse = shadow_map(setup[1].0, size, cfg.inverted);
        let data: Vec<f32> = maps[0].iter().chain(&coarse).copied().collect();
        let (image, view, memory) = array_image(g, size, 2, &data);
        d.cascade_array = Some(crate::HostImage { image, view, format: vk::Format::R32_SFLOAT, layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL, width: size, height: size });
        d.cascade_array_layers = 2;
        array = Some((image, view, memory));
        reference_maps[1] = coarse;
        sizes[1] = size;
    } else {
        for (k, (&(_, size), data)) in setup.iter().zip(&maps).enumerate() {
            let (format, layout) = if k == 1 {
                (vk::Format::D32_SFLOAT, vk::ImageLayout::DEPTH_STENCIL_READ_ONLY_OPTIMAL)
            } else {
                (vk::Format::R32_SFLOAT, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)
            };
            let img = g.image(format, size, size, layout);
            g.upload(&img, bytemuck::cast_slice(data));
            d.cascade_images[k] = img.host();
            cascade_images.push(img);
        }
    }

    let buffers = ctx.classifier_buffers().expect("buffers");
    assert_eq!(buffers.tile_capacity, W.div_ceil(8) * H.div_ceil(4));
    let tile_bytes = buffers.tile_capacity as u64 * crate::CLASSIFY_TILE_BYTES;
    let staging = g.staging(tile_bytes + crate::CLASSIFY_COUNTS_BYTES);
    // Twice: the second dispatch must reset the counts the first left.
    for _ in 0..2 {
        g.submit(|cmd| {
            ctx.record_classify(cmd, &d).expect("record_classify");
            full_barrier(&g.device, cmd);
            unsafe {
                g.device.cmd_copy_buffer(cmd, buffers.tiles, staging.buffer, &[vk::BufferCopy { src_offset: 0, dst_offset: 0, size: tile_bytes }]);
                let counts = vk::BufferCopy { src_offset: 0, dst_offset: tile_bytes, size: crate::CLASSIFY_COUNTS_BYTES };
                g.device.cmd_copy_buffer(cmd, buffers.counts, staging.buffer, &[counts]);
            }
            full_barrier(&g.device, cmd);
        });
    }
    let t = ctx.classifier_timings().unwrap().expect("the classifier's timings after two completed dispatches");
    assert!(t.dispatch == 2 && t.classify_ms > 0.0 && t.classify_ms.is_finite(), "{t:?}");
    let counts: Vec<u32> = bytemuck::cast_slice(&staging.read(tile_bytes as usize, 32)).to_vec();
    let records: Vec<[u32; 4]> = bytemuck::cast_slice(&staging.read(0, tile_bytes as usize)).to_vec();
    let words: Vec<u32> = bytemuck::cast_slice(&g.download(&mask)).to_vec();

    let shadow_maps: Vec<ShadowMap> =
        reference_maps.iter().zip(&sizes).map(|(m, &s)| ShadowMap { width: s, height: s, depth: m }).collect();
    let expected = classify(&ClassifyInputs { width: W, height: H, depth: &f.depth, normals: &f.normals, cascades: &shadow_maps, dispatch: &d })
        .expect("reference");

    let n = counts[0] as usize;
    assert_eq!(counts, vec![n as u32, 1, 1, n as u32, 32 * n as u32, 1, 1, 0], "counts");
    let mut got: Vec<[u32; 4]> = records[..n].to_vec();
    got.sort_by_key(|r| r[0]);
    let tw = W.div_ceil(8);
    let fragile_tile = |t: u32| {
        let (tx, ty) = (t % tw, t / tw);
        (ty * 4..(ty * 4 + 4).min(H)).any(|y| (tx * 8..(tx * 8 + 8).min(W)).any(|x| expected.fragile[(y * W + x) as usize]))
    };
    let tiles = tw * H.div_ceil(4);
    let fragile = (0..tiles).filter(|&t| fragile_tile(t)).count();
    let fragile_pixels = expected.fragile.iter().filter(|&&x| x).count();
    eprintln!("fragile: {fragile} of {tiles} tiles, {fragile_pixels} pixels");
    assert!(fragile * 2 <= tiles as usize, "{fragile} of {tiles} tiles hold a pixel within rounding of a decision");
    for t in (0..tiles).filter(|&t| !fragile_tile(t)) {
        assert_eq!(words[t as usize], expected.hit_mask[t as usize], "hit-mask word of tile {t}");
        let key = (t % tw) | ((t / tw) << 16);
        let want = expected.tiles.iter().find(|e| e.0 == key);
        let have = got.iter().find(|r| r[0] == key);
        match (want, have) {
            (None, None) => {}
            (Some(&(_, mask, min_t, max_t)), Some(r)) => {
                assert_eq!(r[1], mask, "tile {t}: pixels to trace");
                let close = |gpu: u32, cpu: f64| {
                    let v = f32::from_bits(gpu) as f64;
                    (v.is_infinite() && cpu.is_infinite()) || (v - cpu).abs() <= 1e-3 * cpu.abs().max(1.0)
                };
                assert!(close(r[2], min_t) && close(r[3], max_t), "tile {t}: interval {:?} against {min_t}..{max_t}", (f32::from_bits(r[2]), f32::from_bits(r[3])));
            }
            (w, h) => panic!("tile {t}: listed {} on the GPU, {} in the reference", h.is_some(), w.is_some()),
        }
    }
    // The scene exercises every verdict.
    use crate::reference::classify::Verdict;
    let count = |p: &dyn Fn(&Verdict) -> bool| expected.verdicts.iter().filter(|v| p(v)).count();
    eprintln!("trace {} shadowed {} lit {}", count(&|v| matches!(v, Verdict::Trace { .. })), count(&|v| *v == Verdict::Shadowed), count(&|v| *v == Verdict::Lit));
    assert!(count(&|v| matches!(v, Verdict::Trace { .. })) > 20, "pixels to trace");
    assert!(count(&|v| *v == Verdict::Shadowed) > 20, "shadowed pixels");
    if cfg.reject_lit {
        assert!(count(&|v| *v == Verdict::Lit) > W as usize * 4, "lit pixels");
    }
    assert!(n > 0 && n < tiles as usize, "{n} of {tiles} tiles listed");
    eprintln!("{n} of {tiles} tiles listed, {fragile} fragile");

    // The G-buffer's formats are the engine's when its variant decodes it: normals dnsr's decode does not take.
    let other = g.image(vk::Format::R16G16_SFLOAT, W, H, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
    let mut with_other = d;
    with_other.normals = other.host();
    let result = g.submit(|cmd| ctx.record_classify(cmd, &with_other));
    match engine {
        Some(_) => result.expect("the engine's variant decodes RG16F normals"),
        None => assert!(matches!(result, Err(Error::UnsupportedFormat { .. })), "dnsr's decode took RG16F normals: {result:?}"),
    }
    g.destroy_image(&other);

    g.destroy_staging(&staging);
    for img in [&depth, &normals, &mask].into_iter().chain(&cascade_images) {
        g.destroy_image(img);
    }
    if let Some((image, view, memory)) = array {
        unsafe {
            g.device.destroy_image_view(view, None);
            g.device.destroy_image(image, None);
            g.device.free_memory(memory, None);
        }
    }
    drop(ctx);
}

#[test]
fn classifier_matches_reference() {
    let configs = [
        Config { convention: HitMaskConvention::OccludedBits, taps: 24, cutoff: 0, reject_lit: true, bound: true, inverted: false, array: false, blocker_offset: 0.01 },
        Config { convention: HitMaskConvention::LitBits, taps: 8, cutoff: 4, reject_lit: false, bound: false, inverted: true, array: true, blocker_offset: 0.6 },
        Config { convention: HitMaskConvention::OccludedBits, taps: 32, cutoff: 2, reject_lit: true, bound: true, inverted: false, array: true, blocker_offset: 0.1 },
    ];
    for push_descriptor in [true, false] {
        let g = Gpu::new(GpuOptions { push_descriptor, ..Default::default() });
        for (i, cfg) in configs.iter().enumerate() {
            eprintln!("push descriptors {push_descriptor}, configuration {i}");
            run(&g, cfg);
        }
        g.assert_clean();
    }
}

/// An engine's classifier variant (its callbacks compiled from dnsr's sources) is what runs, and the G-buffer's
/// formats are then its own; one that declares an engine image is refused (the dispatch has none).
#[test]
fn an_engine_classifier_variant_is_what_runs() {
    use super::shader_overrides::{compile, sources};
    let g = super::gpu();
    let decode = "vec3 n = stored * dnsr_constants.motion_normals.z + dnsr_constants.motion_normals.w;";
    let dir = sources(&|s| {
        assert!(s.contains(decode), "the standard normal decode moved");
        s.replace(decode, "vec3 n = -(stored * dnsr_constants.motion_normals.z + dnsr_constants.motion_normals.w);")
    });
    let engine = compile(&dir, "classify", &[]);
    let cfg = Config { convention: HitMaskConvention::OccludedBits, taps: 24, cutoff: 0, reject_lit: true, bound: true, inverted: false, array: false, blocker_offset: 0.01 };
    run_with(&g, &cfg, Some(&engine));
    let dir = sources(&|s| s + "\n#ifdef DNSR_PASS_CLASSIFY\nlayout(set = 0, binding = 32) uniform texture2D engine_extra;\n#endif\n");
    let with_image = compile(&dir, "classify", &[]);
    let mut info = g.create_info(W, H);
    info.enable_classifier = true;
    info.shader_overrides = vec![with_image];
    match Context::new(&info) {
        Err(Error::ShaderInterface(m)) => assert!(m.contains("engine image") && m.contains("\"classify\""), "{m}"),
        other => panic!("an engine image in the classifier's variant: {:?}", other.map(|_| ())),
    }
    g.assert_clean();
}

#[test]
fn classifier_bad_input_is_refused() {
    let g = super::gpu();
    let mut info = g.create_info(W, H);
    let mut plain = Context::new(&info).unwrap();
    info.enable_classifier = true;
    let mut ctx = Context::new(&info).unwrap();
    assert!(matches!(plain.classifier_timings(), Err(Error::ClassifierNotEnabled)));
    assert_eq!(ctx.classifier_timings().unwrap(), None, "no timestamps, no timings");
    let depth = g.image(vk::Format::R32_SFLOAT, W, H, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
    let normals = g.image(vk::Format::R32G32B32A32_SFLOAT, W, H, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
    let mask = g.image(vk::Format::R32_UINT, W.div_ceil(8), H.div_ceil(4), vk::ImageLayout::GENERAL);
    let cascade = g.image(vk::Format::R32_SFLOAT, 32, 32, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL);
    g.upload(&mask, &vec![0u8; (W.div_ceil(8) * H.div_ceil(4) * 4) as usize]);
    let good = ClassifyDispatch {
        depth: depth.host(),
        normals: normals.host(),
        hit_mask: mask.host(),
        cascade_count: 1,
        cascades: [ShadowCascade { world_to_shadow: orthographic_cascade(to_light(), DVec3::ZERO, 8.0, 10.0, 20.0).as_mat4() }; 4],
        cascade_images: [cascade.host(), Default::default(), Default::default(), Default::default()],
        light_direction: to_light().as_vec3(),
        ..Default::default()
    };
    let invalid = |field: &'static str| move |e: &Error| matches!(e, Error::InvalidValue { field: f, .. } if *f == field);
    let cases: Vec<(&str, ClassifyDispatch, Box<dyn Fn(&Error) -> bool>)> = vec![
        ("no cascades", ClassifyDispatch { cascade_count: 0, ..good }, Box::new(invalid("cascade_count"))),
        ("five cascades", ClassifyDispatch { cascade_count: 5, ..good }, Box::new(invalid("cascade_count"))),
        ("tap count 7", ClassifyDispatch { tap_count: 7, ..good }, Box::new(invalid("tap_count"))),
        ("tile cut-off 32", ClassifyDispatch { tile_cutoff: 32, ..good }, Box::new(invalid("tile_cutoff"))),
        (
            "cascade matrix with NaN",
            ClassifyDispatch { cascades: [ShadowCascade { world_to_shadow: glam::Mat4::from_cols_array(&[f32::NAN; 16]) }; 4], ..good },
            Box::new(|e: &Error| *e == Error::NonFinite("cascades[0].world_to_shadow")),
        ),
        (
            "projection inverse with infinity",
            ClassifyDispatch { projection_inverse: glam::Mat4::from_cols_array(&[f32::INFINITY; 16]), ..good },
            Box::new(|e: &Error| *e == Error::NonFinite("projection_inverse")),
        ),
        (
            "perspective cascade",
            ClassifyDispatch { cascades: [ShadowCascade { world_to_shadow: glam::Mat4::from_cols(glam::Vec4::X, glam::Vec4::Y, glam::Vec4::new(0.0, 0.0, 1.0, 1.0), glam::Vec4::ZERO) }; 4], ..good },
            Box::new(invalid("cascades[0].world_to_shadow")),
        ),
        (
            "depth decreasing away from the light",
            ClassifyDispatch { cascades_depth_inverted: true, ..good },
            Box::new(invalid("cascades[0].world_to_shadow")),
        ),
        (
            "cascade whose u does not change across the world",
            ClassifyDispatch {
                cascades: [ShadowCascade {
                    world_to_shadow: glam::Mat4::from_cols(glam::Vec4::ZERO, glam::Vec4::Y, -to_light().as_vec3().extend(0.0), glam::Vec4::W),
                }; 4],
                ..good
            },
            Box::new(invalid("cascades[0].world_to_shadow")),
        ),
        ("zero light direction", ClassifyDispatch { light_direction: glam::Vec3::ZERO, ..good }, Box::new(invalid("light_direction"))),
        ("negative blocker offset", ClassifyDispatch { blocker_offset: -1.0, ..good }, Box::new(invalid("blocker_offset"))),
        (
            "missing cascade image",
            ClassifyDispatch { cascade_count: 2, ..good },
            Box::new(|e: &Error| *e == Error::NullHandle("cascade_images[1].image")),
        ),
        (
            "hit mask not in GENERAL",
            ClassifyDispatch { hit_mask: crate::HostImage { layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL, ..mask.host() }, ..good },
            Box::new(|e: &Error| matches!(e, Error::UnsupportedLayout { role: crate::ImageRole::HitMask, .. })),
        ),
        (
            "array without layers",
            ClassifyDispatch { cascade_array: Some(cascade.host()), cascade_images: Default::default(), ..good },
            Box::new(invalid("cascade_array_layers")),
        ),
    ];
    g.submit(|cmd| {
        for (what, d, expected) in &cases {
            let e = ctx.record_classify(cmd, d).expect_err(what);
            assert!(expected(&e), "{what}: {e:?} ({e})");
        }
        assert_eq!(plain.record_classify(cmd, &good).unwrap_err(), Error::ClassifierNotEnabled);
        assert_eq!(plain.classifier_buffers().unwrap_err(), Error::ClassifierNotEnabled);
    });
    // Nothing of the refused calls was recorded (a recorded dispatch would have written the mask).
    assert!(bytemuck::cast_slice::<u8, u32>(&g.download(&mask)).iter().all(|&w| w == 0));
    for img in [&depth, &normals, &mask, &cascade] {
        g.destroy_image(img);
    }
    drop((ctx, plain));
    g.assert_clean();
}


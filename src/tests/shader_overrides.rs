//! Engine-compiled pass variants (`ContextCreateInfo::shader_overrides`): one built from an edited callbacks file
//! is what runs, and every interface mismatch is refused at creation with the variant and the difference named.

use super::{gpu, static_frame};
use crate::testing::Runner;
use crate::{Context, Error, ShaderOverride};
use ash::vk;
use std::path::{Path, PathBuf};
use std::process::Command;

/// dnsr's shader sources copied to a fresh directory, the standard callbacks edited by `edit`.
pub(super) fn sources(edit: &dyn Fn(String) -> String) -> PathBuf {
    static N: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let n = N.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("dnsr-overrides-{}-{n}", std::process::id()));
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    for sub in ["", "generated"] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
        for e in std::fs::read_dir(root.join(sub)).unwrap() {
            let path = e.unwrap().path();
            if matches!(path.extension().and_then(|x| x.to_str()), Some("glsl" | "comp")) {
                std::fs::copy(&path, dir.join(sub).join(path.file_name().unwrap())).unwrap();
            }
        }
    }
    let callbacks = dir.join("dnsr_callbacks_standard.glsl");
    std::fs::write(&callbacks, edit(std::fs::read_to_string(&callbacks).unwrap())).unwrap();
    dir
}

/// A variant compiled as an engine would: its entry file and definitions (shader_variants) and
/// SHADER_COMPILE_ARGS, plus `extra` arguments.
pub(super) fn compile(dir: &Path, name: &str, extra: &[&str]) -> ShaderOverride {
    let v = crate::shader_variants().find(|v| v.name == name).unwrap();
    let out = dir.join(format!("{name}.spv"));
    let mut cmd = Command::new("glslc");
    cmd.args(crate::SHADER_COMPILE_ARGS).args(extra).arg(format!("-I{}", dir.display()));
    for d in v.defines {
        cmd.arg(format!("-D{d}"));
    }
    let output = cmd.arg(dir.join(v.source)).arg("-o").arg(&out).output().expect("glslc (make test installs it)");
    assert!(output.status.success(), "glslc {name}: {}", String::from_utf8_lossy(&output.stderr));
    ShaderOverride { variant: name.into(), spirv: std::fs::read(&out).unwrap() }
}

#[test]
fn an_override_built_from_an_edited_callbacks_file_is_what_runs() {
    let g = gpu();
    let (w, h) = (40, 24);
    // The engine's callbacks write 1 - shadow: every output pixel must be the default's complement.
    let dir = sources(&|s| s.replace("vec4(shadow))", "vec4(1.0 - shadow))"));
    let mut info = g.create_info(w, h);
    info.output_format = vk::Format::R32_SFLOAT;
    let mut plain = Runner::new(&g, &info).unwrap();
    info.shader_overrides = ["tile_classification_r32f", "filter_later_final_r32f", "filter_final_r32f"]
        .iter()
        .map(|name| compile(&dir, name, &[]))
        .collect();
    let mut engine = Runner::new(&g, &info).unwrap();
    let field = |x: f64, z: f64| (0.5 + 0.4 * (x * 0.9).sin() * (z * 0.7).cos()).clamp(0.0, 1.0);
    for frame in 0..4 {
        let f = static_frame(w, h, &field, frame + 1);
        let (a, b) = (plain.frame(&f, frame == 0), engine.frame(&f, frame == 0));
        for (i, (a, b)) in a.iter().zip(&b).enumerate() {
            assert!((1.0 - a - b).abs() <= 1e-6, "frame {frame} pixel {i}: default {a}, override {b}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    g.assert_clean();
}

#[test]
fn mismatched_overrides_are_refused_before_anything_is_created() {
    let g = gpu();
    let dir = sources(&|s| s);
    let good = compile(&dir, "filter_final_r16f", &[]);
    let patched = |find: &[u8], replace: &[u8]| {
        let mut o = good.clone();
        let at = o.spirv.windows(find.len()).position(|w| w == find).expect("pattern in the module");
        o.spirv[at..at + find.len()].copy_from_slice(replace);
        o
    };
    // OpExecutionMode %main LocalSize x y z: 6 words, opcode 16, mode 17.
    let local_size = {
        let words: Vec<u32> = good.spirv.chunks_exact(4).map(|c| u32::from_le_bytes(c.try_into().unwrap())).collect();
        let at = words.windows(3).position(|w| w[0] == (6 << 16 | 16) && w[2] == 17).expect("LocalSize");
        let mut o = good.clone();
        let x = 4 * (at + 3);
        o.spirv[x..x + 4].copy_from_slice(&(words[at + 3] * 2).to_le_bytes());
        o
    };
    let edited = |edit: &dyn Fn(String) -> String| {
        let d = sources(edit);
        let o = compile(&d, "filter_final_r16f", &[]);
        std::fs::remove_dir_all(&d).ok();
        o
    };
    let sampler_normals = edited(&|s| s.replace("uniform texture2D dnsr_normals;", "uniform sampler2D dnsr_normals;"));
    let moved_normals = edited(&|s| s.replace("binding = 6) uniform texture2D dnsr_normals", "binding = 30) uniform texture2D dnsr_normals"));
    let extra = edited(&|s| {
        s.replace("float dnsr_read_depth(ivec2 p) { return texelFetch(dnsr_depth, p + dnsr_get_offset(), 0).r; }",
            "layout(set = 0, binding = 40) uniform texture2D engine_depth;\n\
             float dnsr_read_depth(ivec2 p) { return texelFetch(engine_depth, p, 0).r; }")
    });
    let spirv15 = compile(&dir, "filter_final_r16f", &["--target-env=vulkan1.2"]);
    // What the reflection library or a driver would not survive, and what the device does not offer.
    let with_word = |i: usize, v: u32| {
        let mut o = good.clone();
        o.spirv[4 * i..4 * i + 4].copy_from_slice(&v.to_le_bytes());
        o
    };
    let image_sampled_3 = {
        let words: Vec<u32> = good.spirv.chunks_exact(4).map(|c| u32::from_le_bytes(c.try_into().unwrap())).collect();
        let mut at = 5;
        while words[at] & 0xFFFF != 25 {
            at += (words[at] >> 16) as usize;
        }
        with_word(at + 7, 3)
    };
    // A selection's second arm branching into its first (glslc places both arms after the selection; the layer
    // reports "Invalid back or cross-edge in the CFG" and lavapipe refuses the module).
    let cross_edge = {
        let words: Vec<u32> = good.spirv.chunks_exact(4).map(|c| u32::from_le_bytes(c.try_into().unwrap())).collect();
        let instructions: Vec<usize> =
            std::iter::successors(Some(5), |&at| Some(at + (words[at] >> 16) as usize).filter(|&next| next < words.len())).collect();
        let op = |at: usize| words[at] & 0xFFFF;
        // Each OpBranchConditional's arms, then the OpBranch that ends the second arm's block (if it does).
        let found = instructions.iter().filter(|&&at| op(at) == 250).find_map(|&at| {
            let (first, second) = (words[at + 2], words[at + 3]);
            let label = instructions.iter().position(|&i| op(i) == 248 && words[i + 1] == second)?;
            let end = instructions[label + 1..].iter().copied().find(|&i| matches!(op(i), 248..=256))?;
            (op(end) == 249 && words[end + 1] != first).then_some((end + 1, first))
        });
        let (word, first) = found.expect("a selection whose second arm ends in a branch");
        with_word(word, first)
    };
    // An array's length constant turned huge (override_fuzz, seed 1, case 696: lavapipe allocated 24 GB for it).
    let huge_array = {
        let words: Vec<u32> = good.spirv.chunks_exact(4).map(|c| u32::from_le_bytes(c.try_into().unwrap())).collect();
        let instructions: Vec<usize> =
            std::iter::successors(Some(5), |&at| Some(at + (words[at] >> 16) as usize).filter(|&next| next < words.len())).collect();
        let op = |at: usize| words[at] & 0xFFFF;
        let array = instructions.iter().copied().find(|&at| op(at) == 28).expect("an array type");
        let length = instructions.iter().copied().find(|&at| op(at) == 43 && words[at + 2] == words[array + 3]).expect("its length");
        with_word(length + 3, 1 << 30)
    };
    // The depth copy written as r16ui (what a callbacks file copied before it became R32_UINT declares).
    let narrow_depth_copy = edited(&|s| s.replace("binding = 8, r32ui) uniform writeonly uimage2D dnsr_depth_copy", "binding = 8, r16ui) uniform writeonly uimage2D dnsr_depth_copy"));
    // A callbacks file from before the first filter pass kept the moments: nothing writes them.
    let moments_not_kept = edited(&|s| {
        s.replace("layout(set = 0, binding = 65, DNSR_MOMENTS_FORMAT) uniform writeonly uimage2D dnsr_kept_moments;", "")
            .replace("{ imageStore(dnsr_kept_moments, p + dnsr_get_offset(), uvec4(words, 0u, 0u)); }", "{}")
    });
    let float64 = edited(&|s| {
        s.replace("float dnsr_read_depth(ivec2 p) { return texelFetch(dnsr_depth, p + dnsr_get_offset(), 0).r; }",
            "float dnsr_read_depth(ivec2 p) { return float(double(texelFetch(dnsr_depth, p + dnsr_get_offset(), 0).r) * 1.0lf); }")
    });
    let constants = std::fs::read_to_string(dir.join("generated/dnsr_constants.glsl")).unwrap();
    let signed_rect = edited(&|s| s.replace("#include \"generated/dnsr_constants.glsl\"", &constants.replace("uvec4 rect;", "ivec4 rect;")));
    let cases: Vec<(&str, Vec<ShaderOverride>, &str)> = vec![
        ("not SPIR-V", vec![ShaderOverride { variant: "filter_final_r16f".into(), spirv: b"#version 450\nvoid main(){}".to_vec() }], "is not SPIR-V"),
        ("unknown variant", vec![ShaderOverride { variant: "filter_final_rgb9e5".into(), ..good.clone() }], "not a dnsr shader variant"),
        ("twice", vec![good.clone(), good.clone()], "overridden twice"),
        ("a light-slot variant", vec![ShaderOverride { variant: "filter_later_lights".into(), ..good.clone() }], "is dnsr's own"),
        ("SPIR-V 1.5", vec![ShaderOverride { variant: "filter_final_r16f".into(), spirv: spirv15.spirv }], "SPIR-V 1.5"),
        ("entry point renamed", vec![patched(b"main\0", b"mian\0")], "entry point named \"main\""),
        ("workgroup size", vec![local_size], "workgroup size"),
        ("normals as a combined sampler", vec![sampler_normals], "dnsr_normals"),
        ("normals at another binding", vec![moved_normals], "Normals is binding 30; dnsr binds it at"),
        ("the depth copy as r16ui", vec![narrow_depth_copy], "declares DepthCopy (binding 8) as r16ui; dnsr's variant declares r32ui"),
        ("an engine binding", vec![extra], "unknown binding 'engine_depth'"),
        ("the moments not kept", vec![moments_not_kept], "does not declare KeptMoments (binding 65), which dnsr's variant writes"),
        ("header's reserved word", vec![with_word(4, 1)], "header word 4"),
        ("id bound 2^30", vec![with_word(3, 1 << 30)], "id bound"),
        ("image Sampled 3", vec![image_sampled_3], "is not valid SPIR-V for Vulkan 1.1"),
        ("a Float64 capability", vec![float64], "capability 10,"),
        ("a cross edge", vec![cross_edge], "which is not a loop header"),
        ("an array of 2^30 elements", vec![huge_array], "elements; dnsr allows"),
        ("constants read as other types", vec![signed_rect], "Constants block differs"),
    ];
    for (what, overrides, expect) in cases {
        let mut info = g.create_info(24, 16);
        info.shader_overrides = overrides;
        match Context::new(&info) {
            Ok(_) => panic!("{what}: accepted"),
            Err(Error::ShaderInterface(m)) => {
                assert!(m.contains(expect), "{what}: message {m:?} lacks {expect:?}");
                eprintln!("{what}: {m}");
            }
            Err(e) => panic!("{what}: {e:?}"),
        }
    }
    // The embedded module itself, as an override, is accepted.
    let mut info = g.create_info(24, 16);
    info.shader_overrides = vec![good];
    Context::new(&info).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    g.assert_clean();
}

#[test]
fn engine_images_are_bound_where_the_overrides_declare_them() {
    let g = gpu();
    let (w, h) = (40, 24);
    // The engine's callbacks read depth from an image of its own at binding ENGINE_BINDING_BASE.
    let dir = sources(&|s| {
        s.replace(
            "float dnsr_read_depth(ivec2 p) { return texelFetch(dnsr_depth, p + dnsr_get_offset(), 0).r; }",
            "layout(set = 0, binding = 32) uniform texture2D engine_depth;\n\
             float dnsr_read_depth(ivec2 p) { return texelFetch(engine_depth, p + dnsr_get_offset(), 0).r; }",
        )
    });
    let mut info = g.create_info(w, h);
    info.output_format = vk::Format::R32_SFLOAT;
    let mut plain = Runner::new(&g, &info).unwrap();
    // Every variant of the context that reads the G-buffer: then its formats are the engine's to choose.
    let readers = ["tile_classification_r32f", "filter", "filter_later", "filter_later_final_r32f", "filter_final_r32f"];
    info.shader_overrides = readers.iter().map(|name| compile(&dir, name, &[])).collect();
    // Where dnsr's own decode still runs (a reader left out; a checkerboard context, which classifies with other
    // variants), the G-buffer must be in dnsr's formats: two-channel normals are refused, nothing recorded.
    let f = static_frame(w, h, &|_, _| 0.5, 3);
    for (what, input, partial) in [("one reader left out", crate::ShadowInput::HitMask, true), ("checkerboard", crate::ShadowInput::Checkerboard, false)] {
        let mut other = info.clone();
        other.shadow_input = input;
        if partial {
            other.shader_overrides.pop();
        }
        let mut r = Runner::new(&g, &other).unwrap();
        let mut d = r.dispatch(&f);
        d.normals.format = vk::Format::R16G16_SFLOAT;
        let e = r.run(&f, &d).expect_err(what);
        assert!(matches!(e, Error::UnsupportedFormat { role: Some(crate::ImageRole::Normals), .. }), "{what}: {e:?}");
    }
    let mut engine = Runner::new(&g, &info).unwrap();
    let field = |x: f64, z: f64| (0.5 + 0.4 * (x * 0.9).sin() * (z * 0.7).cos()).clamp(0.0, 1.0);
    let f = static_frame(w, h, &field, 3);
    // Bound: the engine image is the depth image itself, so the result is dnsr's own.
    let mut d = engine.dispatch(&f);
    d.engine_images[0] = Some(crate::EngineImage { view: d.depth.view, layout: d.depth.layout });
    d.reset = true;
    let a = plain.frame(&f, true);
    assert_eq!(engine.run(&f, &d).unwrap(), a);
    // Not given, or in a layout a sampled image cannot be in: refused, nothing recorded.
    let mut missing = d;
    missing.engine_images[0] = None;
    let mut wrong = d;
    wrong.engine_images[0] = Some(crate::EngineImage { view: d.depth.view, layout: vk::ImageLayout::TRANSFER_DST_OPTIMAL });
    for (what, bad, expect) in [("missing", missing, "no image at binding 32"), ("layout", wrong, "TRANSFER_DST_OPTIMAL")] {
        match engine.run(&f, &bad) {
            Err(e @ Error::InvalidValue { field: "engine_images", .. }) => {
                assert!(e.to_string().contains(expect), "{what}: {e}");
                eprintln!("{what}: {e}");
            }
            other => panic!("{what}: {other:?}"),
        }
    }
    // The context is intact: the next frame equals the plain one's.
    let f2 = static_frame(w, h, &field, 4);
    let mut d2 = engine.dispatch(&f2);
    d2.engine_images[0] = Some(crate::EngineImage { view: d2.depth.view, layout: d2.depth.layout });
    assert_eq!(engine.run(&f2, &d2).unwrap(), plain.frame(&f2, false));
    std::fs::remove_dir_all(&dir).ok();
    g.assert_clean();
}

//! The shader/host contract: committed SPIR-V and generated GLSL are current, and reflection sees exactly the
//! interface the host binds. `DNSR_BLESS=1 cargo test bless_` rewrites the committed files instead of comparing.

use crate::constants::{generated_glsl, FrameConstants};
use crate::gpu::reflect::reflect_module;
use crate::interface::reflect;
use crate::passes::bindings::Resource;
use crate::passes::filter::FilterPush;
use crate::passes::variants::VARIANTS;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn bless() -> bool {
    std::env::var("DNSR_BLESS").is_ok_and(|v| v == "1")
}

fn compare_or_bless(path: &Path, fresh: &[u8]) {
    if bless() {
        std::fs::write(path, fresh).unwrap();
        return;
    }
    let committed = std::fs::read(path).unwrap_or_default();
    assert!(committed == fresh, "{} is stale: run `make shaders` (DNSR_BLESS=1 cargo test bless_)", path.display());
}

#[test]
fn bless_generated_glsl_is_current() {
    compare_or_bless(&root().join("shaders/generated/dnsr_constants.glsl"), generated_glsl().as_bytes());
}

/// The exact glslc command line for a variant; `make shaders` and this test share it.
fn compile(source: &str, defines: &[&str], out: &Path) {
    let mut cmd = Command::new("glslc");
    cmd.current_dir(root()).args(["--target-env=vulkan1.1", "-Ishaders"]);
    for d in defines {
        cmd.arg(format!("-D{d}"));
    }
    cmd.arg(format!("shaders/{source}")).arg("-o").arg(out);
    let output = cmd.output().expect("glslc not found: install the Debian package glslc (make test does)");
    assert!(output.status.success(), "glslc {source} {defines:?}:\n{}", String::from_utf8_lossy(&output.stderr));
}

#[test]
fn bless_spirv_matches_glslc() {
    // Generated GLSL first, so blessing both in one run compiles against the fresh header.
    if bless() {
        bless_generated_glsl_is_current();
    }
    let dir = std::env::temp_dir().join(format!("dnsr-spv-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for v in VARIANTS {
        let out = dir.join(format!("{}.spv", v.name));
        compile(v.source, v.defines, &out);
        let fresh = std::fs::read(&out).unwrap();
        let committed = root().join(format!("shaders/spv/{}.spv", v.name));
        compare_or_bless(&committed, &fresh);
        if !bless() {
            assert_eq!(v.spirv, &fresh[..], "embedded {} differs from glslc output: rebuild the crate", v.name);
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// dnsr-bench's copy kernel (the copy roofline it compares every pass with) is committed next to its source.
#[test]
fn bless_bench_copy_spirv_matches_glslc() {
    let out = std::env::temp_dir().join(format!("dnsr-bench-copy-{}.spv", std::process::id()));
    compile("bench/copy.comp", &[], &out);
    let fresh = std::fs::read(&out).unwrap();
    std::fs::remove_file(&out).ok();
    compare_or_bless(&root().join("shaders/bench/copy.spv"), &fresh);
}

#[test]
fn reflected_interfaces_match_what_the_host_binds() {
    use Resource::*;
    // (variant, bindings, push-constant bytes, specialization constants declared)
    use crate::passes::{SPEC_HARD_LIGHT as HARD, SPEC_MOVING_SHADOWS as MOVING, SPEC_PENUMBRA_GUIDED as GUIDED, SPEC_STABLE_HISTORY as STABLE};
    let expect: &[(&str, &[Resource], u32, u32)] = &[
        ("prepare", &[Constants, HitMask, TileMaskOut], 0, 0),
        (
            "tile_classification_r16f",
            &[
                Constants, TileMask, Depth, Velocity, Normals, PreviousDepth, PreviousMoments, Moments, History,
                Reprojection, TileMetaOut, Output, HitDistance, TileBlockerOut, PreviousTileQuiet, TileQuiet,
            ],
            0,
            (1 << GUIDED) | (1 << STABLE) | (1 << HARD) | (1 << MOVING),
        ),
        (
            "filter",
            &[Constants, Depth, DepthCopy, Normals, TileMeta, TileBlocker, FilterInput, FilterOutput, Guide, FrameMoments, KeptMoments, HistoryOut],
            48,
            (1 << GUIDED) | (1 << STABLE) | (1 << HARD),
        ),
        (
            "filter_later",
            &[Constants, Depth, Normals, TileMeta, TileBlocker, FilterInput, FilterOutput, Guide],
            48,
            (1 << GUIDED) | (1 << STABLE),
        ),
        (
            "filter_final_r16f_fp16",
            &[
                Constants, Depth, DepthCopy, Normals, TileMeta, TileBlocker, FilterInput, FilterOutput, Output, DebugMoments, Guide,
                FrameMoments, KeptMoments, HistoryOut,
            ],
            48,
            (1 << GUIDED) | (1 << STABLE) | (1 << HARD),
        ),
        (
            "filter_later_lights_final_r16f",
            &[
                Constants, Depth, Normals, Guide, TileMeta, TileBlocker, FilterInput, FilterOutput, Output, DebugMoments,
                TileMeta1, TileBlocker1, FilterInput1, FilterOutput1, Output1, DebugMoments1, TileMeta2, TileBlocker2, FilterInput2,
                FilterOutput2, Output2, DebugMoments2, TileMeta3, TileBlocker3, FilterInput3, FilterOutput3, Output3, DebugMoments3,
            ],
            48,
            (1 << GUIDED) | (1 << STABLE),
        ),
    ];
    for (name, resources, push, specializes) in expect {
        let v = VARIANTS.iter().find(|v| v.name == *name).unwrap();
        let iface = reflect(v.spirv).unwrap();
        let mut got: Vec<Resource> = iface.bindings.iter().map(|b| b.resource).collect();
        let mut want = resources.to_vec();
        got.sort_by_key(|r| *r as usize);
        want.sort_by_key(|r| *r as usize);
        assert_eq!(got, want, "{name}");
        assert_eq!(iface.push_constant_bytes, *push, "{name} push constants");
        assert_eq!(iface.specializes, *specializes, "{name} specialization constants");
        assert_eq!(iface.uniform_bytes, Some(std::mem::size_of::<FrameConstants>() as u32), "{name} constants block");
    }
    assert_eq!(std::mem::size_of::<FilterPush>(), 48);
    // Every variant reflects cleanly.
    for v in VARIANTS {
        reflect(v.spirv).unwrap_or_else(|e| panic!("{}: {e}", v.name));
    }
}

#[test]
fn reflection_refuses_what_it_cannot_handle() {
    assert!(reflect_module(&[0u8; 3]).is_err());
    assert!(reflect_module(&[0u8; 64]).is_err(), "bad magic");
    let mut spv = VARIANTS[0].spirv.to_vec();
    spv[4..8].copy_from_slice(&0x0001_0500u32.to_le_bytes());
    let err = reflect_module(&spv).unwrap_err().to_string();
    assert!(err.contains("1.5"), "{err}");
    // A specialization constant id dnsr does not set (OpDecorate <id> SpecId 1 -> 7).
    let classification = VARIANTS.iter().find(|v| v.name == "tile_classification_r16f").unwrap();
    let mut words: Vec<u32> = classification.spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
    let at = words.windows(4).position(|w| w[0] == (4 << 16 | 71) && w[2] == 1 && w[3] == 1).expect("SpecId 1 decoration");
    words[at + 3] = 7;
    let spv: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    let err = reflect(&spv).unwrap_err().to_string();
    assert!(err.contains("specialization constant id 7"), "{err}");
    // A descriptor set of 0xFFFFFFFF (OpDecorate <id> DescriptorSet 0 -> ~0), which SPIRV-Reflect takes for "no set"
    // and leaves out; and set 1. Both refused before a pipeline is made of them.
    for set in [u32::MAX, 1] {
        let mut words: Vec<u32> = classification.spirv.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        let at = words.windows(4).position(|w| w[0] == (4 << 16 | 71) && w[2] == 34).expect("a DescriptorSet decoration");
        words[at + 3] = set;
        let spv: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
        let err = reflect(&spv).unwrap_err().to_string();
        assert!(err.contains(&format!("descriptor set {set}; dnsr binds set 0 only")), "{err}");
    }
}

/// include/dnsr.h as cbindgen generates it with cbindgen.toml from src/capi alone: only what the C API module
/// declares can reach the header, never a public item of the Rust API.
pub(crate) fn generated_header() -> Vec<u8> {
    let config = cbindgen::Config::from_file(root().join("cbindgen.toml")).expect("cbindgen.toml");
    let mut out = Vec::new();
    cbindgen::Builder::new()
        .with_src(root().join("src/capi/mod.rs"))
        .with_config(config)
        .generate()
        .expect("cbindgen could not generate the header")
        .write(&mut out);
    out
}

#[test]
fn bless_header_is_current() {
    compare_or_bless(&root().join("include/dnsr.h"), &generated_header());
}

/// snake_case Rust field -> the camelCase name cbindgen gives it in C.
fn c_field(rust: &str) -> String {
    let mut out = String::new();
    let mut upper = false;
    for ch in rust.chars() {
        if ch == '_' {
            upper = true;
        } else if upper {
            out.extend(ch.to_uppercase());
            upper = false;
        } else {
            out.push(ch);
        }
    }
    out
}

/// capi-tests/generated/layout.h: compile-time checks of sizeof/offsetof of every public C struct against what
/// Rust lays out, so a C compiler with another idea of the layout fails to build the tests.
fn generated_layout_header() -> String {
    use crate::capi::types::*;
    use std::fmt::Write as _;
    let mut s = String::from(
        "/* Generated by `DNSR_BLESS=1 cargo test bless_layout` from the Rust definitions in src/capi. Do not edit. */\n\
         #ifndef DNSR_LAYOUT_EXPECTED_H\n#define DNSR_LAYOUT_EXPECTED_H\n#include <stddef.h>\n#include \"dnsr.h\"\n\
         #ifdef __cplusplus\n#define DNSR_STATIC_ASSERT(c, m) static_assert(c, m)\n#else\n#define DNSR_STATIC_ASSERT(c, m) _Static_assert(c, m)\n#endif\n\n",
    );
    macro_rules! check {
        ($t:ident { $($f:ident),* $(,)? }) => {{
            let _ = writeln!(s, "DNSR_STATIC_ASSERT(sizeof({}) == {}, \"sizeof({})\");", stringify!($t), std::mem::size_of::<$t>(), stringify!($t));
            let _ = writeln!(s, "DNSR_STATIC_ASSERT(_Alignof({}) == {}, \"alignof({})\");", stringify!($t), std::mem::align_of::<$t>(), stringify!($t));
            $(
                let c = c_field(stringify!($f));
                let _ = writeln!(s, "DNSR_STATIC_ASSERT(offsetof({}, {c}) == {}, \"offsetof({}, {c})\");",
                    stringify!($t), std::mem::offset_of!($t, $f), stringify!($t));
            )*
            s.push('\n');
            // Every field must be listed: this pattern has no `..`, so a new field fails to compile here.
            #[allow(unused)]
            fn exhaustive(v: $t) {
                let $t { $($f: _),* } = v;
            }
        }};
    }
    check!(DnsrVulkanFunctions { vk_get_instance_proc_addr, vk_get_device_proc_addr });
    check!(DnsrGpuAllocation { memory, offset, user_handle });
    check!(DnsrGpuMemoryCallbacks { user_data, allocate, free });
    check!(DnsrLogCallback { user_data, log });
    check!(DnsrDebugNameCallback { user_data, set_name });
    check!(DnsrSettings {
        s_type, p_next, filter_passes, disocclusion_threshold_facing, disocclusion_threshold_grazing,
        disocclusion_angle_exponent, spatial_falloff, history_clamp_sigmas, history_rejection_falloff,
        history_rejection_min_sigma, variance_boost_samples, full_history_samples, min_current_weight,
        max_history_samples, kernel_cross_weight, normal_power, output_contrast, min_shadow_sigma, stable_history_samples,
        history_flip_samples, converged_samples, hard_penumbra_pixels, moving_shadow_sigmas, moving_history_clamp_sigmas,
        hard_tile_frames, geometric_normal_degrees,
    });
    check!(DnsrContextCreateInfo {
        s_type, p_next, instance, physical_device, device, vulkan_functions, api_version, queue_family_index,
        enabled_features, width, height, flags, precision, output_format, light_count, max_frames_in_flight, p_settings,
        p_allocation_callbacks, p_gpu_memory_callbacks, p_log_callback, p_debug_name_callback, shader_override_count,
        p_shader_overrides, shadow_input,
    });
    check!(DnsrShaderOverride { p_variant_name, p_code, code_size });
    check!(DnsrShaderVariantInfo { p_name, p_source, p_defines });
    check!(DnsrHostImage { image, view, format, layout, width, height });
    check!(DnsrRect { x, y, width, height });
    check!(DnsrHostSync { input_src_stages, input_src_access, output_dst_stages, output_dst_access });
    check!(DnsrShadowsDispatch {
        s_type, p_next, command_buffer, light_index, flags, hit_mask_convention, hit_mask, depth, velocity, normals,
        output, motion_vector_scale, normals_unpack_mul, normals_unpack_add, eye, frame_index, projection_inverse,
        reprojection_matrix, view_projection_inverse, depth_similarity_sigma, render_rect, sync, debug_view, hit_distance,
        light_angular_size, engine_image_count, p_engine_images, visibility, checkerboard_phase, light_position,
        previous_depth, previous_normals,
    });
    check!(DnsrEngineImage { binding, view, layout });
    check!(DnsrLightDispatch { s_type, p_next, light_index, flags, hit_mask, visibility, output, hit_distance, light_angular_size, light_position });
    check!(DnsrPassTimings { s_type, p_next, frame, prepare_ms, tile_classification_ms, filter_ms, filter_passes, total_ms });
    check!(DnsrDeviceRequirements {
        s_type, p_next, min_api_version, required_extension_count, pp_required_extension_names,
        optional_extension_count, pp_optional_extension_names, optional_features,
    });
    {
        use crate::capi::reference::*;
        check!(DnsrReferenceFrameInfo {
            s_type, p_next, width, height, flags, p_settings, motion_vector_scale, normals_unpack_mul,
            normals_unpack_add, eye, depth_similarity_sigma, projection_inverse, reprojection_matrix,
            view_projection_inverse, light_angular_size, light_position,
        });
        check!(DnsrReferenceCallbacks {
            user_data, read_hit_mask, read_depth, read_normal, read_velocity, read_previous_depth,
            read_previous_moments, read_history, write_output, write_tile_meta, write_reprojection, write_moments,
            write_history, read_hit_distance, read_visibility, read_previous_normal, read_previous_tile_quiet,
            write_tile_quiet,
        });
        check!(DnsrDiagnosis { kind, value, message });
    }
    s.push_str("#endif\n");
    s.replace("_Alignof", "DNSR_ALIGNOF").replacen(
        "#ifdef __cplusplus\n#define DNSR_STATIC_ASSERT(c, m) static_assert(c, m)\n#else\n#define DNSR_STATIC_ASSERT(c, m) _Static_assert(c, m)\n#endif\n",
        "#ifdef __cplusplus\n#define DNSR_STATIC_ASSERT(c, m) static_assert(c, m)\n#define DNSR_ALIGNOF(t) alignof(t)\n#else\n#define DNSR_STATIC_ASSERT(c, m) _Static_assert(c, m)\n#define DNSR_ALIGNOF(t) _Alignof(t)\n#endif\n",
        1,
    )
}

#[test]
fn bless_layout_header_is_current() {
    std::fs::create_dir_all(root().join("capi-tests/generated")).unwrap();
    compare_or_bless(&root().join("capi-tests/generated/layout.h"), generated_layout_header().as_bytes());
}

/// Every name include/dnsr.h declares at file scope: macros, tags, typedefs, enumerators and functions.
fn declared_names(header: &str) -> Vec<String> {
    let mut code = String::new();
    let mut rest = header;
    while let Some(start) = rest.find("/*") {
        code.push_str(&rest[..start]);
        rest = rest[start..].find("*/").map_or("", |end| &rest[start + end + 2..]);
    }
    code.push_str(rest);
    let mut names: Vec<String> = Vec::new();
    let ident = |s: &str| s.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).next().unwrap_or("").to_string();
    for line in code.lines() {
        if let Some(def) = line.trim_start().strip_prefix("#define ") {
            names.push(ident(def));
        }
    }
    // Preprocessor lines and the C++ `extern "C"` wrapper open no C scope.
    let body: String = code
        .lines()
        .map(|l| l.find("//").map_or(l, |i| &l[..i]))
        .filter(|l| !l.trim_start().starts_with('#') && l.trim() != "extern \"C\" {" && l.trim() != "}")
        .collect::<Vec<_>>()
        .join("\n");
    let (mut braces, mut parens, mut last) = (0i32, 0i32, String::new());
    let mut in_enum = false;
    let mut chars = body.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if c.is_ascii_alphabetic() || c == '_' {
            let word = ident(&body[i..]);
            for _ in 1..word.len() {
                chars.next();
            }
            if word == "enum" && braces == 0 {
                in_enum = true;
            }
            // Enumerators are file-scope names in C.
            if in_enum && braces == 1 && parens == 0 && !last.ends_with('=') && last != "=" {
                names.push(word.clone());
            }
            last = word;
            continue;
        }
        match c {
            '(' => {
                if braces == 0 && parens == 0 && !last.is_empty() {
                    names.push(last.clone());
                }
                parens += 1;
            }
            ')' => {
                parens -= 1;
                last.clear();
            }
            '{' => {
                if braces == 0 && parens == 0 && !last.is_empty() {
                    names.push(last.clone());
                }
                braces += 1;
            }
            '}' => {
                braces -= 1;
                if braces == 0 {
                    in_enum = false;
                }
            }
            ';' if braces == 0 && parens == 0 => {
                in_enum = false;
                if !last.is_empty() {
                    names.push(std::mem::take(&mut last));
                }
            }
            // Array bounds: `typedef int32_t Coord[2];` declares Coord.
            '[' => {
                for (_, c) in chars.by_ref() {
                    if c == ']' {
                        break;
                    }
                }
            }
            '=' => last = "=".into(),
            ',' => last.clear(),
            c if c.is_whitespace() => {}
            _ => last.clear(),
        }
    }
    const C_WORDS: &[&str] = &["extern", "int32_t", "uint32_t", "cplusplus", "__cplusplus"];
    names.retain(|n| !n.is_empty() && !C_WORDS.contains(&n.as_str()) && !n.chars().all(|c| c.is_ascii_digit()));
    names.sort();
    names.dedup();
    names
}

#[test]
fn header_declares_only_dnsr_names() {
    let header = String::from_utf8(generated_header()).unwrap();
    let names = declared_names(&header);
    for expected in ["DnsrContextCreateInfo", "dnsr_shadows_record", "DNSR_SUCCESS", "DNSR_MAX_LIGHT_COUNT", "DNSR_H"] {
        assert!(names.iter().any(|n| n == expected), "the name scan missed {expected}: {names:?}");
    }
    // The scan finds the kinds of leaks seen before: a macro, an array typedef, a struct tag, a function.
    let planted = "#define TILE { 8, 4, }\ntypedef int32_t Coord[2];\nstruct Settings { int x; };\nvoid helper(int a);\n";
    assert_eq!(declared_names(planted), ["Coord", "Settings", "TILE", "helper"]);
    let foreign: Vec<_> = names.iter().filter(|n| !(n.starts_with("Dnsr") || n.starts_with("DNSR_") || n.starts_with("dnsr_"))).collect();
    assert!(foreign.is_empty(), "include/dnsr.h declares names without the dnsr prefix: {foreign:?}");
}

/// Every structure type tag of the header has a value of its own: a structure tagged as another one must be
/// refused (DNSR_STRUCTURE_TYPE_LIGHT_DISPATCH and _REFERENCE_FRAME_INFO once shared 6).
#[test]
fn every_structure_type_is_distinct() {
    let header = String::from_utf8(generated_header()).unwrap();
    let mut seen = std::collections::BTreeMap::new();
    for line in header.lines() {
        let Some(rest) = line.strip_prefix("#define DNSR_STRUCTURE_TYPE_") else { continue };
        let (name, value) = rest.split_once(' ').expect("a #define with a value");
        let value = value.trim();
        let value = match value.strip_prefix("0x") {
            Some(hex) => u32::from_str_radix(hex, 16),
            None => value.parse(),
        }
        .unwrap_or_else(|_| panic!("DNSR_STRUCTURE_TYPE_{name}: value {value}"));
        if let Some(other) = seen.insert(value, name.to_string()) {
            panic!("DNSR_STRUCTURE_TYPE_{name} and DNSR_STRUCTURE_TYPE_{other} share the value {value}");
        }
    }
    assert!(seen.len() >= 11, "the scan found only {seen:?}");
}

#[test]
fn header_documents_every_setting_range() {
    let header = String::from_utf8(generated_header()).unwrap();
    let block = &header[header.find("typedef struct DnsrSettings").unwrap()..];
    let block = &block[..block.find("} DnsrSettings;").unwrap()];
    for &(name, range) in crate::settings::RANGES {
        let field = format!(" {};", c_field(name));
        let at = block.find(&field).unwrap_or_else(|| panic!("DnsrSettings has no field {field}"));
        let doc = &block[block[..at].rfind("/**").unwrap()..at];
        assert!(doc.contains(&format!("Range {range}")), "DnsrSettings.{} does not document its range {range}", c_field(name));
        assert!(doc.contains("Default "), "DnsrSettings.{} does not document its default", c_field(name));
    }
}

/// Every storage image dnsr's own variants declare is declared in the state table's format for the variant's
/// precision and input: the GLSL layout qualifiers (shaders/dnsr_precision.glsl's macros among them) and the formats
/// the images are created in (the table's) cannot drift apart. A light slot's resource holds what its slot 0 holds.
#[test]
fn variants_declare_the_state_table_formats() {
    use crate::interface::spirv_image_format;
    use crate::state::table::{resource_of, RESOURCES};
    use crate::{Precision, ShadowInput};
    let holds = crate::passes::state_tests::images_per_binding();
    let mut checked = Vec::new();
    for variant in VARIANTS {
        let precision = if variant.defines.contains(&"DNSR_FP16") { Precision::Fp16 } else { Precision::Fp32 };
        let fractions = variant.defines.iter().any(|d| matches!(*d, "DNSR_VISIBILITY_INPUT" | "DNSR_CHECKERBOARD_INPUT"));
        let input = if fractions { ShadowInput::Visibility } else { ShadowInput::HitMask };
        for b in reflect(variant.spirv).unwrap().bindings.iter().filter(|b| b.descriptor_type == ash::vk::DescriptorType::STORAGE_IMAGE) {
            for &image in &holds[b.resource.slot_zero() as usize] {
                let want = resource_of(image).format_for(precision, input);
                assert_eq!(Some(b.format), spirv_image_format(want), "{}: {:?} holds {image:?}, created as {want:?}", variant.name, b.resource);
                checked.push(image);
            }
        }
    }
    for r in &RESOURCES {
        assert!(checked.contains(&r.image), "{:?}: no variant writes it as a storage image", r.image);
    }
}

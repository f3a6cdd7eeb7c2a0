//! The one-way layers of the crate docs (src/lib.rs, "Layers"): every `crate::` path in a module names a module of
//! its own layer or of one below it. A lower module that needed a higher one's item would close a cycle; it takes
//! the item as a parameter instead, or the item moves down.

use std::path::{Path, PathBuf};

/// The data layer: plain data, no Vulkan object made. Its modules import one another only.
const DATA: &[&str] = &["error", "host", "settings", "dispatch", "create_info", "glsl", "state", "passes", "constants"];
/// What the Vulkan plumbing (gpu/) may import: itself and two data modules. What it needs of the passes, the
/// settings or the create info comes as parameters.
const GPU_MAY_IMPORT: &[&str] = &["gpu", "error", "host"];
/// The CPU reference: it may import the data layer too.
const REFERENCE: &[&str] = &["reference"];
/// The denoiser and classifier contexts, above gpu/ and the reference: they may import everything below.
const CONTEXTS: &[&str] = &["context", "light", "classify", "pipeline", "interface", "validate", "timestamps"];
/// On top, not checked: the C and FidelityFX APIs, and the tests with their support.
const UNCHECKED: &[&str] = &["capi", "ffx", "testing", "tests"];

fn src() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The .rs files of module `name` of src/: its file, and the files under its directory.
fn files(name: &str) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let file = src().join(format!("{name}.rs"));
    if file.exists() {
        out.push(file);
    }
    let mut dirs = vec![src().join(name)];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out
}

/// The first segment of every `crate::` path in `source` outside `//` comments (`{` for a grouped import, the item
/// for a re-export of the crate root: both hide the module).
fn crate_paths(source: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in source.lines() {
        let code = line.split("//").next().unwrap_or("");
        for (at, _) in code.match_indices("crate::") {
            let rest = &code[at + "crate::".len()..];
            let end = rest.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(rest.len());
            out.push(if end == 0 { rest.chars().take(1).collect() } else { rest[..end].to_string() });
        }
    }
    out
}

/// Every import of `path` that `allowed` does not list.
fn violations(path: &Path, allowed: &[&str]) -> Vec<String> {
    let source = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let name = path.strip_prefix(src()).unwrap_or(path).display().to_string();
    crate_paths(&source).into_iter().filter(|m| !allowed.contains(&m.as_str())).map(|m| format!("src/{name}: crate::{m}")).collect()
}

/// Every import against the layers in the files of `modules`, each of which may import `allowed`.
fn check(modules: &[&str], allowed: &[&[&str]]) -> Vec<String> {
    let allowed: Vec<&str> = allowed.concat();
    modules.iter().flat_map(|m| files(m)).flat_map(|f| violations(&f, &allowed)).collect()
}

#[test]
fn lower_layers_import_nothing_above_them() {
    let found = [
        check(DATA, &[DATA]),
        check(&["gpu"], &[GPU_MAY_IMPORT]),
        check(REFERENCE, &[REFERENCE, DATA]),
        check(CONTEXTS, &[CONTEXTS, &["gpu"], REFERENCE, DATA]),
    ]
    .concat();
    assert!(found.is_empty(), "imports against the layers (src/lib.rs, \"Layers\"):\n{}", found.join("\n"));
}

/// Every module lib.rs declares has its layer here, so that a new module cannot escape the check.
#[test]
fn every_module_has_a_layer() {
    let lib = std::fs::read_to_string(src().join("lib.rs")).unwrap();
    let layered = [DATA, &["gpu"], REFERENCE, CONTEXTS, UNCHECKED].concat();
    for line in lib.lines() {
        let Some(decl) = line.trim().strip_prefix("mod ").or_else(|| line.trim().strip_prefix("pub mod ")) else { continue };
        let module = decl.trim_end_matches(';');
        assert!(layered.contains(&module), "src/lib.rs declares `mod {module}`, which src/tests/layers.rs puts in no layer");
    }
}

#[test]
fn the_scan_sees_each_kind_of_import() {
    let planted = "use crate::gpu::loader::Vk; // crate::passes in a comment\nlet a = crate::Precision::Fp16;\nuse crate::{a, b};";
    assert_eq!(crate_paths(planted), ["gpu", "Precision", "{"]);
}

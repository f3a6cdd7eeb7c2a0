//! The one-way layers of the crate docs (src/lib.rs, "Layers"): every `crate::` path in a module names a module of
//! its own layer or of one below it, and every module imports only those before it in the docs' full order, so no
//! import cycle exists, within a layer either. A lower module that needed a higher one's item would close a cycle;
//! it takes the item as a parameter instead, or the item moves down.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The data layer: plain data, no Vulkan object made. Its modules import one another only.
const DATA: &[&str] = &["error", "host", "dispatch", "glsl", "packing", "settings", "create_info", "state", "passes", "constants"];
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

/// The first segment of every `crate::` path in `source` outside `//` comments, each path of a one-line group
/// (`crate::{a, b::c}`) too (the item for a re-export of the crate root: it hides the module).
fn crate_paths(source: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in source.lines() {
        let code = line.split("//").next().unwrap_or("");
        for (at, _) in code.match_indices("crate::") {
            let rest = &code[at + "crate::".len()..];
            let paths: Vec<&str> = match rest.strip_prefix('{') {
                Some(group) => group.split('}').next().unwrap_or(group).split(',').collect(),
                None => vec![rest],
            };
            for path in paths.iter().map(|p| p.trim_start()) {
                let end = path.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(path.len());
                out.push(if end == 0 { path.chars().take(1).collect() } else { path[..end].to_string() });
            }
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

fn lib() -> String {
    std::fs::read_to_string(src().join("lib.rs")).unwrap()
}

/// The modules src/lib.rs declares.
fn declared(lib: &str) -> Vec<String> {
    let decl = |l: &str| l.trim().strip_prefix("mod ").or_else(|| l.trim().strip_prefix("pub mod ")).map(|d| d.trim_end_matches(';').to_string());
    lib.lines().filter_map(decl).collect()
}

/// Every module lib.rs declares has its layer here, so that a new module cannot escape the check.
#[test]
fn every_module_has_a_layer() {
    let layered = [DATA, &["gpu"], REFERENCE, CONTEXTS, UNCHECKED].concat();
    for module in declared(&lib()) {
        assert!(layered.contains(&module.as_str()), "src/lib.rs declares `mod {module}`, which src/tests/layers.rs puts in no layer");
    }
}

/// Where src/lib.rs's "Layers" states the full order: the backquoted names from this line to the paragraph's end.
/// Read from the docs, so that the docs and the check cannot drift apart.
const ORDER_HEADING: &str = "In full, bottom first";

/// The full import order of src/lib.rs's "Layers", bottom first.
fn order(lib: &str) -> Vec<String> {
    let docs: Vec<&str> = lib.lines().filter_map(|l| l.strip_prefix("//!")).collect();
    let at = docs.iter().position(|l| l.contains(ORDER_HEADING)).unwrap_or_else(|| panic!("src/lib.rs has no \"{ORDER_HEADING}\""));
    let paragraph = docs[at..].iter().take_while(|l| !l.trim().is_empty());
    paragraph.flat_map(|l| l.split('`').skip(1).step_by(2)).map(str::to_string).collect()
}

/// The crate root's re-exports as item -> module (`pub use context::{Context, ..}`): `crate::Context` imports
/// `context`. `pub use ash;` and the like name no module of the crate.
fn reexports(lib: &str, modules: &[String]) -> BTreeMap<String, String> {
    let code: Vec<&str> = lib.lines().map(|l| l.split("//").next().unwrap_or("")).collect();
    let mut out = BTreeMap::new();
    for statement in code.join(" ").split("pub use ").skip(1) {
        let statement = statement.split(';').next().unwrap_or("");
        let Some((module, rest)) = statement.trim().split_once("::") else { continue };
        if !modules.iter().any(|m| m == module) {
            continue;
        }
        let items = rest.split_once('{').map_or(rest, |(_, group)| group.trim_end().trim_end_matches('}'));
        for item in items.split(',').map(str::trim).filter(|i| !i.is_empty()) {
            let name = item.split_once(" as ").map_or_else(|| item.rsplit("::").next().unwrap_or(item), |(_, alias)| alias);
            out.insert(name.trim().to_string(), module.to_string());
        }
    }
    out
}

/// Each declared module's imports of other modules (a crate-root item counts as its module's), over `files`.
fn import_graph(lib: &str) -> BTreeMap<String, Vec<String>> {
    let modules = declared(lib);
    let items = reexports(lib, &modules);
    let mut graph = BTreeMap::new();
    for module in &modules {
        let mut imports: Vec<String> = Vec::new();
        for file in files(module) {
            let source = std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            for name in crate_paths(&source) {
                let target = if modules.contains(&name) { Some(&name) } else { items.get(&name) };
                if let Some(t) = target.filter(|t| *t != module && !imports.contains(t)) {
                    imports.push(t.clone());
                }
            }
        }
        graph.insert(module.clone(), imports);
    }
    graph
}

/// A path of imports from `from` to `to` (both included), if any.
fn import_path(graph: &BTreeMap<String, Vec<String>>, from: &str, to: &str) -> Option<Vec<String>> {
    let mut came_from: BTreeMap<&str, &str> = BTreeMap::from([(from, from)]);
    let mut queue = std::collections::VecDeque::from([from]);
    while let Some(m) = queue.pop_front() {
        if m == to {
            let mut path = vec![to.to_string()];
            while path.last().unwrap() != from {
                path.push(came_from[path.last().unwrap().as_str()].to_string());
            }
            path.reverse();
            return Some(path);
        }
        for next in graph.get(m).into_iter().flatten() {
            if !came_from.contains_key(next.as_str()) {
                came_from.insert(next.as_str(), m);
                queue.push_back(next.as_str());
            }
        }
    }
    None
}

/// Every module imports only modules before it in the docs' order (itself too), so the import graph has no cycle.
/// An import forward is reported with the cycle it closes, if it closes one already.
#[test]
fn modules_import_in_the_documented_order() {
    let lib = lib();
    let order = order(&lib);
    let mut declared = declared(&lib);
    let mut listed = order.clone();
    declared.sort();
    listed.sort();
    assert_eq!(listed, declared, "src/lib.rs's \"{ORDER_HEADING}\" lists each declared module once");
    let graph = import_graph(&lib);
    let mut found = Vec::new();
    for (at, module) in order.iter().enumerate() {
        for target in graph[module].iter().filter(|t| !order[..at].contains(t)) {
            found.push(match import_path(&graph, target, module) {
                Some(cycle) => format!("{module} imports {target}, listed after it, in a cycle: {module} -> {}", cycle.join(" -> ")),
                None => format!("{module} imports {target}, listed after it (no cycle yet: reorder the list)"),
            });
        }
    }
    assert!(found.is_empty(), "imports against the order of src/lib.rs's \"Layers\":\n{}", found.join("\n"));
}

#[test]
fn the_scan_sees_each_kind_of_import() {
    let planted = "use crate::gpu::loader::Vk; // crate::passes in a comment\nlet a = crate::Precision::Fp16;\nuse crate::{a, b::c};";
    assert_eq!(crate_paths(planted), ["gpu", "Precision", "a", "b"]);
}

/// The order check reads the docs' list, resolves re-exports and prints a cycle.
#[test]
fn the_order_check_reads_the_docs_and_finds_a_cycle() {
    let lib = "//! In full, bottom first:\n//! `a`, `b`,\n//! `c`.\n//!\n//! `d`\nmod a;\nmod b;\npub use b::{B, x::Y as Z};\npub use ash;";
    assert_eq!(order(lib), ["a", "b", "c"]);
    let items = reexports(lib, &declared(lib));
    assert_eq!(items.into_iter().collect::<Vec<_>>(), [("B".into(), "b".into()), ("Z".into(), "b".into())]);
    let graph = BTreeMap::from([("a".to_string(), vec!["b".to_string()]), ("b".into(), vec!["c".into()]), ("c".into(), vec!["a".into()])]);
    assert_eq!(import_path(&graph, "b", "a").unwrap(), ["b", "c", "a"]);
    assert_eq!(import_path(&graph, "a", "d"), None);
}

//! The library's layers depend one way (README, Design): each module may use only modules of
//! lower layers. Read from the source: every `crate::NAME` in code (comments and the trailing
//! `#[cfg(test)]` module left out) of every file under `src/` that belongs to the library.

use std::collections::BTreeSet;
use std::path::Path;

/// The library's top-level modules by layer, lowest first. A module may use a module only
/// from a lower row: rows of one layer (the renderer and the probe, say) never use each other.
const LAYERS: &[&[&str]] = &[
    &["math", "error", "atomic", "read", "counters", "names"],
    &["texture"],
    &["height"],
    &["scene"],
    &["load", "bake"],
    &["tangent", "shading"],
    &["frame"],
    &["chain"],
    &["prepare"],
    &["render", "probe", "check"],
    // The report draws the parallax family on the GPU (render) besides its CPU studies.
    &["report"],
    &["state"],
];

/// The binary's own files and folders: above every layer, and not checked here.
const BINARY: &[&str] = &["main.rs", "app", "cli"];

fn layer_of(module: &str) -> usize {
    LAYERS.iter().position(|row| row.contains(&module)).unwrap_or_else(|| panic!("module {module} has no layer"))
}

/// The top-level modules `crate::…` names in the code of `source`.
fn uses(source: &str) -> BTreeSet<String> {
    let code = source.split("#[cfg(test)]").next().unwrap_or_default();
    let mut found = BTreeSet::new();
    for line in code.lines().map(|l| l.split("//").next().unwrap_or_default()) {
        let mut rest = line;
        while let Some(at) = rest.find("crate::") {
            rest = &rest[at + "crate::".len()..];
            let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            found.insert(name);
        }
    }
    found
}

fn library_files(dir: &Path, out: &mut Vec<(String, std::path::PathBuf)>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let relative = path.strip_prefix(Path::new(env!("CARGO_MANIFEST_DIR")).join("src")).unwrap();
        let top = relative.components().next().unwrap().as_os_str().to_string_lossy().into_owned();
        if BINARY.contains(&top.as_str()) || top == "lib.rs" {
            continue;
        }
        if path.is_dir() {
            library_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push((top.trim_end_matches(".rs").to_owned(), path));
        }
    }
}

#[test]
fn every_module_uses_only_lower_layers() {
    let mut files = vec![];
    library_files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), &mut files);
    assert!(files.len() > 40, "found only {} library files", files.len());
    let mut wrong = vec![];
    for (module, path) in &files {
        let layer = layer_of(module);
        for used in uses(&std::fs::read_to_string(path).unwrap()) {
            if used != *module && layer_of(&used) >= layer {
                wrong.push(format!(
                    "{} ({module}, layer {layer}) uses {used} (layer {})",
                    path.display(),
                    layer_of(&used)
                ));
            }
        }
    }
    assert!(wrong.is_empty(), "imports against the layers:\n{}", wrong.join("\n"));
}

/// The check can fail: a use of a higher layer, or of a module of the same layer, is found.
#[test]
fn the_layer_check_sees_upward_and_sideways_uses() {
    let found = uses("use crate::render::Renderer;\n// crate::state in a comment\nfn f() { crate::probe::pick(); }");
    assert_eq!(found, BTreeSet::from(["render".to_owned(), "probe".to_owned()]));
    assert!(layer_of("probe") == layer_of("render") && layer_of("state") > layer_of("render"));
}

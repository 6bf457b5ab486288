//! The one statement of the code's layers ([`LAYERS`]; docs/design.md draws the same table, and
//! a test here holds the two equal). Each library module may use only modules of lower rows;
//! in the binary, `cli` sits above `app` (flags become commands for the viewer; the viewer never
//! reaches back into the command line), and `app` holds no shading math.
//!
//! Read from the source, not from the compiler: every path that starts at `crate::`, `super::`
//! or (in the binary) `bumpview::`, in code only (comments and string contents blanked; a
//! `#[cfg(test)] mod` block or file left out, nothing else), grouped imports expanded.

use std::collections::BTreeSet;
use std::path::Path;

/// The library's top-level modules by layer, lowest first, each row with the design's name for
/// its layer. A module may use a module only from a lower row: modules of one row (the
/// renderer and the probe, say) never use each other.
const LAYERS: &[(&str, &[&str])] = &[
    ("data", &["math", "error", "atomic", "read", "counters", "names"]),
    ("data", &["texture"]),
    ("data", &["height"]),
    ("data", &["scene"]),
    // The shading formulas need only the data: the loaders (a glTF roughness's exponent) and
    // the bakes (a mip level's alpha) use them.
    ("methods", &["shading"]),
    ("methods", &["tangent", "load", "bake"]),
    ("frame", &["frame"]),
    ("chain", &["chain"]),
    ("prepare", &["prepare"]),
    ("consumers", &["render", "probe", "check"]),
    // The report draws the parallax family on the GPU (render) beside its CPU studies.
    ("report", &["report"]),
    ("viewer state", &["state"]),
    // The lessons: presets with a caption, drawn by the renderer and measured.
    ("lessons", &["lessons"]),
];

/// What `app` may read from the shading layer: the colour scale its legend draws and a limit
/// its panel states. Nothing that computes a shaded value.
const APP_READS_FROM_SHADING: &[&str] = &["difference_color", "OVER_TILT_LIMIT_DEG"];

/// The library modules whose code is shading math: `app` uses none of them (beyond
/// [`APP_READS_FROM_SHADING`]).
const SHADING_MATH: &[&str] = &["chain", "shading"];

/// The table as docs/design.md draws it, highest layer first.
fn drawing() -> String {
    let mut lines = vec![
        "binary        cli → app (never app → cli); app computes no shading (no chain, no shading formulas)".to_owned(),
    ];
    for (name, modules) in LAYERS.iter().rev() {
        lines.push(format!("{name:<14}{}", modules.join(" · ")));
    }
    lines.join("\n")
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|(_, row)| row.contains(&module))
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Crate {
    Library,
    Binary,
}

/// One source file as the check reads it.
struct Source {
    /// Where it is, for messages.
    name: String,
    krate: Crate,
    /// Its module path: `render/capture.rs` is `[render, capture]`, `render/mod.rs` and
    /// `render.rs` are `[render]`, `lib.rs` and `main.rs` are `[]`.
    module: Vec<String>,
    /// Its code, as [`code_only`] leaves it.
    code: String,
}

impl Source {
    fn new(name: &str, krate: Crate, text: &str) -> Source {
        let mut module: Vec<String> =
            name.trim_end_matches(".rs").split('/').filter(|s| !s.is_empty()).map(str::to_owned).collect();
        if module.last().is_some_and(|m| m == "mod" || m == "lib" || m == "main") {
            module.pop();
        }
        Source { name: name.to_owned(), krate, module, code: code_only(text) }
    }
}

/// `text` with comments removed and the contents of string and character literals blanked, so
/// that neither a path in a doc comment nor a brace in a string is read as code.
fn code_only(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < chars.len() {
        let rest = &chars[i..];
        if rest.starts_with(&['/', '/']) {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if rest.starts_with(&['/', '*']) {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i..].starts_with(&['/', '*']) {
                    depth += 1;
                    i += 2;
                } else if chars[i..].starts_with(&['*', '/']) {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(' ');
        } else if rest[0] == 'r' && rest.get(1).is_some_and(|&c| c == '"' || c == '#') && !ident_before(&chars, i) {
            // A raw string: r"…" or r#"…"#.
            let hashes = rest[1..].iter().take_while(|&&c| c == '#').count();
            if rest.get(1 + hashes) != Some(&'"') {
                out.push(chars[i]);
                i += 1;
                continue;
            }
            i += 2 + hashes;
            let close: Vec<char> = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            while i < chars.len() && !chars[i..].starts_with(&close) {
                i += 1;
            }
            i += close.len();
            out.push_str("\"\"");
        } else if rest[0] == '"' {
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if rest[0] == '\'' && (rest.get(1) == Some(&'\\') || rest.get(2) == Some(&'\'')) {
            // A character literal ('{', '\n'); a lifetime ('a) has no closing quote two on.
            i += 1;
            while i < chars.len() && chars[i] != '\'' {
                i += if chars[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("' '");
        } else {
            out.push(chars[i]);
            i += 1;
        }
    }
    out
}

fn ident_before(chars: &[char], i: usize) -> bool {
    i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_')
}

/// `code` without its `#[cfg(test)] mod NAME { … }` blocks, and the names of the test modules
/// it declares in files of their own (`#[cfg(test)] mod NAME;`).
fn without_test_modules(code: &str) -> (String, Vec<String>) {
    let mut kept = String::new();
    let mut test_files = vec![];
    let mut rest = code;
    while let Some(at) = rest.find("#[cfg(test)]") {
        let after = &rest[at + "#[cfg(test)]".len()..];
        let item = skip_attributes(after);
        let declaration = item.strip_prefix("pub ").unwrap_or(item).trim_start();
        let Some(module) = declaration.strip_prefix("mod ") else {
            kept.push_str(&rest[..at + "#[cfg(test)]".len()]);
            rest = after;
            continue;
        };
        let name: String = module.trim_start().chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        let body = module.trim_start()[name.len()..].trim_start();
        kept.push_str(&rest[..at]);
        if let Some(body) = body.strip_prefix(';') {
            test_files.push(name);
            rest = body;
        } else if body.starts_with('{') {
            rest = &body[matching_brace(body) + 1..];
        } else {
            rest = body;
        }
    }
    kept.push_str(rest);
    (kept, test_files)
}

/// `text` past its leading whitespace and attributes (`#[…]`).
fn skip_attributes(mut text: &str) -> &str {
    loop {
        text = text.trim_start();
        match text.strip_prefix("#[") {
            Some(attribute) => text = &attribute[matching_bracket(attribute) + 1..],
            None => return text,
        }
    }
}

/// The byte index of the `]` that closes an attribute whose `#[` was just cut off.
fn matching_bracket(text: &str) -> usize {
    let mut depth = 1;
    for (i, c) in text.char_indices() {
        depth += match c {
            '[' => 1,
            ']' => -1,
            _ => 0,
        };
        if depth == 0 {
            return i;
        }
    }
    text.len() - 1
}

/// The byte index of the `}` that closes the `{` that `text` starts with.
fn matching_brace(text: &str) -> usize {
    let mut depth = 0;
    for (i, c) in text.char_indices() {
        depth += match c {
            '{' => 1,
            '}' => -1,
            _ => 0,
        };
        if depth == 0 {
            return i;
        }
    }
    text.len() - 1
}

/// Where a path starts.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Root {
    /// The crate the file is in (`crate::`, `super::`).
    Own,
    /// The library, named from the binary (`bumpview::`).
    Library,
}

/// Every path in `code` that starts at `crate::`, `super::` (resolved from `module`) or
/// `bumpview::`, grouped imports expanded: `crate::{a::B, c}` is `[a, B]` and `[c]`.
fn paths(code: &str, module: &[String]) -> Vec<(Root, Vec<String>)> {
    let chars: Vec<char> = code.chars().collect();
    let mut found = vec![];
    let mut i = 0;
    while i < chars.len() {
        let starts = |word: &str| chars[i..].iter().copied().take(word.len()).eq(word.chars());
        if ident_before(&chars, i) || (i > 0 && chars[i - 1] == ':') {
            i += 1;
            continue;
        }
        let (root, mut prefix, mut at) = if starts("crate::") {
            (Root::Own, vec![], i + "crate::".len())
        } else if starts("bumpview::") {
            (Root::Library, vec![], i + "bumpview::".len())
        } else if starts("super::") {
            let mut at = i;
            let mut depth = 0;
            while chars[at..].iter().copied().take(7).eq("super::".chars()) {
                depth += 1;
                at += 7;
            }
            (Root::Own, module[..module.len().saturating_sub(depth)].to_vec(), at)
        } else {
            i += 1;
            continue;
        };
        let mut leaves = vec![];
        use_tree(&chars, &mut at, &mut prefix, &mut leaves);
        found.extend(leaves.into_iter().filter(|p| !p.is_empty()).map(|p| (root, p)));
        i = at.max(i + 1);
    }
    found
}

/// Reads a path or use tree at `chars[*at..]` below `prefix`, pushing each full path to `out`.
fn use_tree(chars: &[char], at: &mut usize, prefix: &mut Vec<String>, out: &mut Vec<Vec<String>>) {
    let skip_space = |at: &mut usize| {
        while *at < chars.len() && chars[*at].is_whitespace() {
            *at += 1;
        }
    };
    let depth = prefix.len();
    loop {
        skip_space(at);
        match chars.get(*at) {
            Some('{') => {
                *at += 1;
                loop {
                    skip_space(at);
                    match chars.get(*at) {
                        None => break,
                        Some('}') => {
                            *at += 1;
                            break;
                        }
                        Some(',') => *at += 1,
                        Some(_) => {
                            let mut inner = prefix.clone();
                            let before = *at;
                            use_tree(chars, at, &mut inner, out);
                            if *at == before {
                                *at += 1;
                            }
                        }
                    }
                }
                break;
            }
            Some('*') => {
                *at += 1;
                out.push(prefix.clone());
                break;
            }
            _ => {
                let ident: String = chars[*at..].iter().take_while(|c| c.is_alphanumeric() || **c == '_').collect();
                *at += ident.len();
                if !ident.is_empty() && ident != "self" {
                    prefix.push(ident);
                }
                if chars[*at..].starts_with(&[':', ':']) {
                    *at += 2;
                    continue;
                }
                if prefix.len() > 0 || depth == 0 {
                    out.push(prefix.clone());
                }
                break;
            }
        }
    }
}

/// The files of `sources` that are not tests, each with its code without test modules.
fn checked(sources: &[Source]) -> Vec<(&Source, String)> {
    let test_files: BTreeSet<(Crate, Vec<String>)> = sources
        .iter()
        .flat_map(|s| {
            without_test_modules(&s.code).1.into_iter().map(|name| {
                let mut module = s.module.clone();
                module.push(name);
                (s.krate, module)
            })
        })
        .collect();
    sources
        .iter()
        .filter(|s| !test_files.contains(&(s.krate, s.module.clone())))
        .map(|s| (s, without_test_modules(&s.code).0))
        .collect()
}

/// Every use in `sources` against the layers, one line each.
fn violations(sources: &[Source]) -> Vec<String> {
    let mut wrong = vec![];
    for (source, code) in checked(sources) {
        let top = source.module.first().map_or("", String::as_str);
        for (root, path) in paths(&code, &source.module) {
            let used = path[0].as_str();
            let mut complain = |why: String| wrong.push(format!("{}: {} ({why})", source.name, path.join("::")));
            match (source.krate, root) {
                (Crate::Library, _) if top.is_empty() => {}
                (Crate::Library, _) => match (layer_of(top), layer_of(used)) {
                    (Some(layer), Some(used_layer)) if used != top && used_layer >= layer => {
                        complain(format!("{top}, layer {layer}, uses {used}, layer {used_layer}"))
                    }
                    // An item the crate root re-exports (`crate::WorkCounters`) is no module.
                    (_, None) if !used.starts_with(char::is_uppercase) => complain(format!("{used} has no layer")),
                    _ => {}
                },
                (Crate::Binary, Root::Own) if top == "app" && used == "cli" => {
                    complain("app uses cli: the command line sits above the viewer".to_owned())
                }
                (Crate::Binary, Root::Library) if top == "app" && SHADING_MATH.contains(&used) => {
                    let item = path.get(1).map_or("*", String::as_str);
                    if used != "shading" || !APP_READS_FROM_SHADING.contains(&item) {
                        complain(format!("app computes no shading; {used}::{item} is shading math"));
                    }
                }
                (Crate::Binary, _) => {}
            }
        }
    }
    wrong
}

/// A module (file) of one crate: `(crate, module path)`.
type FileModule = (Crate, Vec<String>);

/// The uses between the files of each crate: file A uses file B when a path in A's code (from
/// `crate::` or `super::`) names B's module or an item in it (the longest prefix of the path
/// that is a file's module). A folder's files are one module to the outside: what a file uses
/// outside a folder it is in, that folder's `mod.rs` uses too, and a file's uses of its own
/// ancestors (`super::Item`) and descendants are no edge.
fn file_uses(sources: &[Source]) -> BTreeSet<(FileModule, FileModule)> {
    let files: BTreeSet<FileModule> = sources.iter().map(|s| (s.krate, s.module.clone())).collect();
    let mut uses = BTreeSet::new();
    for (source, code) in checked(sources) {
        let user = &source.module;
        for (_, path) in paths(&code, user).into_iter().filter(|(root, _)| *root == Root::Own) {
            let Some(used) =
                (1..=path.len()).rev().map(|n| path[..n].to_vec()).find(|m| files.contains(&(source.krate, m.clone())))
            else {
                continue;
            };
            for folder in (1..=user.len()).map(|n| &user[..n]).filter(|f| !used.starts_with(f)) {
                if !folder.starts_with(&used) && files.contains(&(source.krate, folder.to_vec())) {
                    uses.insert(((source.krate, folder.to_vec()), (source.krate, used.clone())));
                }
            }
        }
    }
    uses
}

/// Every import circle between files of `sources`, each as `a → b → … → a`.
fn circles(sources: &[Source]) -> Vec<String> {
    let uses = file_uses(sources);
    let name = |(_, module): &FileModule| if module.is_empty() { "(crate root)".to_owned() } else { module.join("::") };
    let used_by = |from: &FileModule| {
        uses.range((from.clone(), (from.0, vec![]))..)
            .take_while(|(a, _)| a == from)
            .map(|(_, b)| b.clone())
            .collect::<Vec<_>>()
    };
    // Depth first from each file; a use of a file still on the path closes a circle.
    let mut finished = BTreeSet::new();
    let mut found = vec![];
    for (start, _) in &uses {
        if finished.contains(start) {
            continue;
        }
        let mut stack: Vec<(FileModule, Vec<FileModule>)> = vec![(start.clone(), used_by(start))];
        while let Some((file, pending)) = stack.last_mut() {
            let Some(used) = pending.pop() else {
                finished.insert(file.clone());
                stack.pop();
                continue;
            };
            if let Some(at) = stack.iter().position(|(f, _)| *f == used) {
                let circle: Vec<String> = stack[at..].iter().map(|(f, _)| name(f)).chain([name(&used)]).collect();
                found.push(circle.join(" → "));
            } else if !finished.contains(&used) {
                let after = used_by(&used);
                stack.push((used, after));
            }
        }
    }
    found
}

fn read_tree(dir: &Path, root: &Path, out: &mut Vec<Source>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            read_tree(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let name = path.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
            let top = name.split('/').next().unwrap().trim_end_matches(".rs");
            let krate = if ["main", "app", "cli"].contains(&top) { Crate::Binary } else { Crate::Library };
            out.push(Source::new(&name, krate, &std::fs::read_to_string(&path).unwrap()));
        }
    }
}

fn the_tree() -> Vec<Source> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut sources = vec![];
    read_tree(&root, &root, &mut sources);
    sources
}

#[test]
fn every_module_uses_only_lower_layers() {
    let sources = the_tree();
    let library = sources.iter().filter(|s| s.krate == Crate::Library).count();
    let binary = sources.len() - library;
    assert!(library > 80 && binary > 30, "found only {library} library and {binary} binary files");
    for source in sources.iter().filter(|s| s.krate == Crate::Library && !s.module.is_empty()) {
        assert!(layer_of(&source.module[0]).is_some(), "{}: module {} has no layer", source.name, source.module[0]);
    }
    let wrong = violations(&sources);
    assert!(wrong.is_empty(), "uses against the layers:\n{}", wrong.join("\n"));
}

#[test]
fn no_import_circle_between_files() {
    let found = circles(&the_tree());
    assert!(
        found.is_empty(),
        "import circles between files (a shared piece belongs in a leaf below both):\n{}",
        found.join("\n")
    );
}

#[test]
fn the_design_page_draws_this_table() {
    let page = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/design.md")).unwrap();
    assert!(
        page.contains(&drawing()),
        "docs/design.md must draw the layers as tests/layers.rs states them:\n{}",
        drawing()
    );
}

/// Counter-tests: each way of breaking the layers that a simpler reader missed is seen.
mod the_check_sees {
    use super::*;

    fn library(name: &str, text: &str) -> Source {
        Source::new(name, Crate::Library, text)
    }

    #[test]
    fn upward_and_sideways_uses_and_not_comments_or_strings() {
        let source = library(
            "probe/pick.rs",
            "use crate::render::Renderer;\n// crate::state in a comment\nfn f() { crate::report::run(\"crate::state\"); }",
        );
        let found: Vec<_> = paths(&source.code, &source.module).into_iter().map(|(_, p)| p.join("::")).collect();
        assert_eq!(found, ["render::Renderer", "report::run"]);
        assert_eq!(violations(&[source]).len(), 2, "render beside the probe, report above it");
    }

    #[test]
    fn a_super_path_that_climbs_to_a_higher_layer() {
        let planted =
            library("chain/parallax.rs", "use super::super::probe::pick;\nfn f() { super::super::render::draw(); }");
        let wrong = violations(&[planted]);
        assert_eq!(wrong.len(), 2, "{wrong:?}");
        assert!(wrong[0].contains("probe::pick") && wrong[1].contains("render"), "{wrong:?}");
        // `super::` inside the module itself is fine.
        assert!(violations(&[library("chain/parallax.rs", "use super::{march, Step};")]).is_empty());
    }

    #[test]
    fn an_upward_use_after_a_test_module() {
        let planted = library(
            "shading/lights.rs",
            "fn a() {}\n#[cfg(test)]\nmod tests {\n    use crate::state::X; fn s() { let c = '}'; }\n}\nuse crate::state::Y;\n",
        );
        let wrong = violations(&[planted]);
        assert_eq!(wrong.len(), 1, "only the use outside the test module: {wrong:?}");
        assert!(wrong[0].contains("state::Y"), "{wrong:?}");
    }

    #[test]
    fn a_grouped_import() {
        let planted = library("probe/pick.rs", "use crate::{math::normalize_or, render::{Renderer, capture}};");
        let wrong = violations(&[planted]);
        assert_eq!(wrong.len(), 2, "{wrong:?}");
    }

    #[test]
    fn an_app_cli_app_tie() {
        let cli = Source::new("cli/viewer.rs", Crate::Binary, "use crate::app;\nfn run() { app::run(); }");
        let app = Source::new("app/controller/exports.rs", Crate::Binary, "use crate::cli::args::parse_size;");
        assert!(violations(&[cli]).is_empty(), "cli may use app");
        let wrong = violations(&[app]);
        assert_eq!(wrong.len(), 1, "{wrong:?}");
        assert!(wrong[0].contains("app uses cli"), "{wrong:?}");
    }

    #[test]
    fn shading_math_in_the_app() {
        let app = Source::new(
            "app/view/legend.rs",
            Crate::Binary,
            "use bumpview::shading::{difference_color, blinn_phong};\nuse bumpview::chain::shade;",
        );
        let wrong = violations(&[app]);
        assert_eq!(wrong.len(), 2, "{wrong:?}");
        assert!(wrong[0].contains("blinn_phong") && wrong[1].contains("chain"), "{wrong:?}");
    }

    #[test]
    fn an_import_circle_between_two_files() {
        let integrate = library("height/integrate.rs", "use super::spectrum::PackedSlopes;");
        let spectrum = library("height/spectrum.rs", "use super::integrate::{BLIND, Phase};");
        let mod_rs = library("height/mod.rs", "pub mod integrate;\npub mod spectrum;");
        let found = circles(&[mod_rs, integrate, spectrum]);
        assert_eq!(found, ["height::integrate → height::spectrum → height::integrate"]);
    }

    #[test]
    fn an_import_circle_through_a_folder_in_the_binary() {
        let action = Source::new("app/action.rs", Crate::Binary, "use super::controller::SceneReady;");
        let controller = Source::new("app/controller/mod.rs", Crate::Binary, "mod scene_job;\npub struct SceneReady;");
        let job =
            Source::new("app/controller/scene_job.rs", Crate::Binary, "fn f() { crate::app::action::Action::Reload; }");
        // The job's use is its folder's: the controller uses the action that names it.
        assert_eq!(circles(&[action, controller, job]), ["app::action → app::controller → app::action"]);
    }

    #[test]
    fn no_circle_between_a_folder_and_its_files_or_across_crates() {
        let parent = library("scene/mod.rs", "pub use crate::scene::material::Material;\npub struct Wrap;");
        let child = library("scene/material.rs", "use super::Wrap;");
        let app = Source::new("app/mod.rs", Crate::Binary, "use bumpview::scene::Scene;");
        let scene = library("scene/build.rs", "use crate::app::X;");
        assert!(circles(&[parent, child, app, scene]).is_empty());
    }

    #[test]
    fn a_test_module_in_its_own_file_is_left_out() {
        let parent = library("shading/mod.rs", "#[cfg(test)]\nmod tests;\n");
        let tests = library("shading/tests.rs", "use crate::state::X;");
        let low = library("scene/tests.rs", "use crate::state::X;");
        assert!(violations(&[parent, tests]).is_empty());
        assert_eq!(violations(&[low]).len(), 1);
    }
}

#[path = "layers/technique_rooms.rs"]
mod technique_rooms;

//! The technique rule: a technique enum is its own registry. Only its rooms name one of its
//! variants (`Parallax::Relief`); everywhere else (the report, panel, command line, presets,
//! lessons, bake, check, the renderer) iterates the enum or asks it a capability, so adding a
//! variant touches the files docs/design.md lists under "How to add a technique" and no others.
//! Read as the layers are: code only, test modules left out.

use super::*;

/// Each technique enum and the top-level modules that may name its variants.
const TECHNIQUE_ROOMS: &[(&str, &[&str])] = &[("Parallax", &["frame", "chain", "shading"])];

/// Files that still name a variant outside its rooms, each with why.
const EXCEPTIONS: &[(&str, &str, &str)] = &[(
    "state/mod.rs",
    "Parallax",
    "ViewerState::scene_uploads binds the height maps while any technique is on (`!= Off`); \
     the viewer state's restructuring moves it to `Parallax::shifts`",
)];

/// Every `Enum::Variant` (a variant: an identifier starting upper-case, not all capitals) of
/// [`TECHNIQUE_ROOMS`] in `sources` outside its rooms, one line each.
fn technique_violations(sources: &[Source]) -> Vec<String> {
    let mut wrong = vec![];
    for source in sources {
        let code = without_test_modules(&source.code).0;
        let chars: Vec<char> = code.chars().collect();
        let top = source.module.first().map_or("", String::as_str);
        for &(name, rooms) in TECHNIQUE_ROOMS {
            let in_room = source.krate == Crate::Library && rooms.contains(&top);
            let excepted = EXCEPTIONS.iter().any(|&(file, e, _)| file == source.name && e == name);
            if in_room || excepted {
                continue;
            }
            for variant in variants_named(&chars, name) {
                wrong.push(format!("{}: names {name}::{variant} outside {rooms:?}", source.name));
            }
        }
    }
    wrong
}

/// The variants of enum `name` that `chars` names as `name::Variant`.
fn variants_named(chars: &[char], name: &str) -> Vec<String> {
    let pattern: Vec<char> = format!("{name}::").chars().collect();
    let mut found = vec![];
    for i in 0..chars.len().saturating_sub(pattern.len()) {
        if chars[i..i + pattern.len()] != pattern[..] || ident_before(chars, i) {
            continue;
        }
        let ident: String =
            chars[i + pattern.len()..].iter().take_while(|c| c.is_alphanumeric() || **c == '_').collect();
        let upper_first = ident.chars().next().is_some_and(char::is_uppercase);
        if upper_first && ident.chars().any(char::is_lowercase) {
            found.push(ident);
        }
    }
    found
}

#[test]
fn only_a_techniques_rooms_name_its_variants() {
    let wrong = technique_violations(&the_tree());
    assert!(wrong.is_empty(), "technique variants named outside their rooms:\n{}", wrong.join("\n"));
}

/// Counter-test: a planted match on a variant in the report and in the panel is seen; a
/// capability, an iteration, the default, a comment, a test module and the rooms are not.
#[test]
fn a_variant_named_in_the_report_or_the_panel_is_seen() {
    let report = Source::new(
        "report/uv_chart.rs",
        Crate::Library,
        "fn f(t: Parallax) -> bool { t == Parallax::Relief || matches!(t, Parallax::Steep) }",
    );
    let panel = Source::new("app/panel/parallax.rs", Crate::Binary, "if technique == Parallax::Relief {}");
    let wrong = technique_violations(&[report, panel]);
    assert_eq!(wrong.len(), 3, "{wrong:?}");
    assert!(wrong[0].contains("Parallax::Relief") && wrong[2].contains("app/panel"), "{wrong:?}");
    let fine = Source::new(
        "report/uv_chart.rs",
        Crate::Library,
        "// Parallax::Relief\nfn f() { for t in Parallax::shifting() { t.refines(); } Parallax::default(); \
         SetParallax::Foo; }\n#[cfg(test)]\nmod tests { fn g() { Parallax::Relief; } }",
    );
    let room = Source::new("chain/parallax.rs", Crate::Library, "match t { Parallax::Relief => 1 }");
    assert!(technique_violations(&[fine, room]).is_empty());
}

//! Enum names are what users type: command-line flags, preset files and the README spell
//! them, so they must stay as they are. Each enum derives its names ([`bumpview::names`]);
//! this pins every one, in order (the panel's, `--help`'s and the reports' order).

use bumpview::frame::{BumpSource, DetailBlend, LegacyLook, LightingSpace, Mistake, Parallax, ShadingMode, ViewMode};
use bumpview::height::{Border, Kernel};
use bumpview::lessons::slide::SlideTheme;
use bumpview::names::Named;
use bumpview::scene::{GreenAxis, LightKind, NormalLayout, ShadingModel, SpecularMode};
use bumpview::state::SplitDifference;
use bumpview::tangent::TangentMethod;
use bumpview::texture::MipFilter;

#[test]
fn every_enum_keeps_its_names_in_order() {
    let views = [
        "lit",
        "tangent",
        "bitangent",
        "normal",
        "shading-normal",
        "difference",
        "uv-check",
        "handedness",
        "over-tilt",
        "clearcoat-normal",
    ];
    assert_eq!(ViewMode::names(), views);
    assert_eq!(ShadingMode::names(), ["bump-colour", "bump-only", "colour-only"]);
    assert_eq!(BumpSource::names(), ["normal-map", "height-in-shader"]);
    assert_eq!(SlideTheme::names(), ["dark", "light"]);
    let differences = [
        "bump",
        "view",
        "strength",
        "mode",
        "tangents",
        "convention",
        "bump-source",
        "parallax",
        "mistake",
        "lighting-space",
        "displacement",
        "mip-filter",
        "detail-blend",
        "compression",
    ];
    assert_eq!(SplitDifference::names(), differences);
    let methods = [
        "mikktspace",
        "meshopt",
        "per-face",
        "averaged-uniform",
        "averaged-area",
        "averaged-angle",
        "supplied",
        "analytic",
    ];
    assert_eq!(TangentMethod::names(), methods);
    assert_eq!(Kernel::names(), ["forward", "central", "sobel3", "scharr3", "sobel5", "central4"]);
    assert_eq!(GreenAxis::names(), ["opengl", "directx"]);
    assert_eq!(Border::names(), ["wrap", "clamp"]);
    assert_eq!(ShadingModel::names(), ["blinn-phong", "pbr"]);
    assert_eq!(Parallax::names(), ["off", "offset", "offset-limited", "steep", "occlusion", "relief", "relaxed-cone"]);
    assert_eq!(NormalLayout::names(), ["rgb", "rg", "ag", "xray"]);
    let mistakes = [
        "none",
        "tbn-typo",
        "handedness-ignored",
        "srgb-normal-map",
        "no-renormalization",
        "no-gram-schmidt",
        "green-flipped",
        "half-vector-per-vertex",
        "light-per-vertex",
    ];
    assert_eq!(Mistake::names(), mistakes);
    assert_eq!(LegacyLook::names(), ["off", "dot3", "emboss"]);
    assert_eq!(LightKind::names(), ["point", "directional"]);
    assert_eq!(SpecularMode::names(), ["blinn", "phong", "off"]);
    assert_eq!(LightingSpace::names(), ["world", "tangent", "view"]);
    let mip_filters = ["base-only", "renormalized-box", "toksvig", "lean", "vmf", "geometric-specular-aa"];
    assert_eq!(MipFilter::names(), mip_filters);
    let blends = ["linear", "partial-derivative", "whiteout", "udn", "rnm", "surface-gradient"];
    assert_eq!(DetailBlend::names(), blends);
}

#[test]
fn every_name_reads_back_as_its_value() {
    fn round_trip<T: Named + std::fmt::Debug>() {
        for &value in T::all() {
            assert_eq!(T::from_name(value.name()), Some(value), "{value:?}");
        }
    }
    round_trip::<ViewMode>();
    round_trip::<ShadingMode>();
    round_trip::<BumpSource>();
    round_trip::<SplitDifference>();
    round_trip::<LightKind>();
    round_trip::<SpecularMode>();
    round_trip::<LightingSpace>();
    round_trip::<TangentMethod>();
    round_trip::<Kernel>();
    round_trip::<GreenAxis>();
    round_trip::<Border>();
    round_trip::<ShadingModel>();
    round_trip::<Parallax>();
    round_trip::<NormalLayout>();
    round_trip::<Mistake>();
    round_trip::<LegacyLook>();
    round_trip::<MipFilter>();
    assert_eq!(ShadingMode::from_name("bump-colour"), Some(ShadingMode::BumpTimesColour));
    assert_eq!(TangentMethod::from_name("averaged-area"), Some(TangentMethod::AveragedArea));
}

/// One name per technique: captions, split labels (and so the panel's and the exports'), the
/// command line and the reports call every parallax technique, classic mistake, legacy look,
/// lighting space and mip filter by its [`Named`] name, which each caption line and label contains.
#[test]
fn captions_and_split_labels_name_each_technique_by_its_one_name() {
    use bumpview::frame::{LegacySettings, ShadingSettings};
    use bumpview::render::export::{CaptionScene, caption_lines};
    use bumpview::state::SplitView;

    let scene =
        CaptionScene { convention: "OpenGL (+Y)".into(), tangents: "auto: mikktspace".into(), displacement: None };
    let captioned = |shading: ShadingSettings| caption_lines(&shading, &scene).join("\n");
    let lit = ShadingSettings::default();
    for &technique in &Parallax::all()[1..] {
        let caption = captioned(ShadingSettings {
            parallax: bumpview::frame::ParallaxSettings { technique, ..lit.parallax },
            ..lit
        });
        assert!(caption.contains(&format!("parallax: {}", technique.name())), "{caption}");
        let split =
            SplitView { difference: SplitDifference::Parallax, parallax: [technique; 2], ..SplitView::default() };
        assert_eq!(split.labels()[0], format!("parallax: {}", technique.name()));
    }
    for &mistake in &Mistake::all()[1..] {
        let caption = captioned(ShadingSettings { mistake, ..lit });
        assert!(caption.contains(&format!("mistake: {}: ", mistake.name())), "{caption}");
        let split = SplitView { difference: SplitDifference::Mistake, mistakes: [mistake; 2], ..SplitView::default() };
        assert!(split.labels()[0].starts_with(&format!("{}: ", mistake.name())), "{:?}", split.labels());
    }
    for &look in &LegacyLook::all()[1..] {
        let caption = captioned(ShadingSettings { legacy: LegacySettings { look, cube_map_size: None }, ..lit });
        assert!(caption.contains(&format!("legacy look: {}: ", look.name())), "{caption}");
    }
    for &space in &LightingSpace::all()[1..] {
        let caption = captioned(ShadingSettings { lighting_space: space, ..lit });
        assert!(caption.contains(&format!("lighting space: {}", space.name())), "{caption}");
        let split = SplitView {
            difference: SplitDifference::LightingSpace,
            lighting_spaces: [space; 2],
            ..SplitView::default()
        };
        assert_eq!(split.labels()[0], format!("lighting space: {}", space.name()));
    }
    for &filter in MipFilter::all() {
        let split =
            SplitView { difference: SplitDifference::MipFilter, mip_filters: [filter; 2], ..SplitView::default() };
        assert_eq!(split.labels()[0], format!("mips: {}", filter.name()));
    }
}

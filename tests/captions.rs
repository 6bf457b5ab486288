//! No caption is cut: every line a tile caption can hold, wrapped as `render_grid` draws it,
//! measures (with the font that draws it) no wider than its tile less the margins, at the
//! widths of `--size 640x…`, `--size 1280x…` and the tile widths grid exports use.

use std::collections::BTreeSet;

use bumpview::frame::{
    CUBE_MAP_SIZES, LegacyLook, LegacySettings, LightingSpace, Mistake, Parallax, ParallaxSettings, ShadingMode,
    ShadingSettings, ViewMode,
};
use bumpview::names::Named;
use bumpview::render::export::{CaptionScene, caption_lines, caption_px, wrap_caption};
use bumpview::render::text::text_width;
use bumpview::tangent::TangentMethod;

/// Tile widths, pixels: the tests' small tiles, a third and a half of common slide widths,
/// 640 and 1280 (the issue's), and full HD and 4K tiles.
const WIDTHS: [u32; 12] = [96, 128, 160, 213, 320, 427, 480, 640, 960, 1280, 1920, 3840];

/// Every distinct line a caption can hold: each view in each mode, bump on and off at the
/// strength range's ends, every parallax technique (with layers, steps, shadows and a set
/// depth), every legacy look and cube map, every lighting space and every mistake, with the
/// longest scene facts (two conventions, every tangent method, a level-10 displacement).
fn every_caption_line() -> BTreeSet<String> {
    let methods: Vec<&str> = TangentMethod::names();
    let scene = CaptionScene {
        convention: "OpenGL (+Y), DirectX (−Y)".into(),
        tangents: format!("auto: {}", methods.join(", ")),
        displacement: Some("level 10: 8388608 vertices, 16777216 triangles, 1152.0 MiB".into()),
    };
    let base = ShadingSettings::default();
    let mut variants = Vec::new();
    for &view in ViewMode::all() {
        for &mode in ShadingMode::all() {
            variants.push(ShadingSettings { view, mode, ..base });
        }
    }
    for (bump_enabled, strength) in [(true, -2.0), (false, 4.0), (true, 0.0)] {
        variants.push(ShadingSettings { bump_enabled, strength, ..base });
    }
    for &technique in Parallax::all() {
        for (layers_min, layers_max, shadow_strength, depth_m) in [(8, 32, 0.0, None), (256, 256, 4.0, Some(0.125))] {
            let parallax =
                ParallaxSettings { technique, layers_min, layers_max, shadow_strength, depth_m, ..base.parallax };
            variants.push(ShadingSettings { parallax, ..base });
        }
    }
    for &look in LegacyLook::all() {
        for cube_map_size in CUBE_MAP_SIZES.map(Some).into_iter().chain([None]) {
            variants.push(ShadingSettings { legacy: LegacySettings { look, cube_map_size }, ..base });
        }
    }
    for &lighting_space in LightingSpace::all() {
        variants.push(ShadingSettings { lighting_space, ..base });
    }
    for &mistake in Mistake::all() {
        variants.push(ShadingSettings { mistake, ..base });
    }
    variants.iter().flat_map(|shading| caption_lines(shading, &scene)).collect()
}

#[test]
fn every_wrapped_caption_line_fits_its_tile() {
    let lines = every_caption_line();
    assert!(lines.len() > 40, "{} lines", lines.len());
    for width in WIDTHS {
        let px = caption_px(width);
        let mut widest: f32 = 0.0;
        for line in &lines {
            let wrapped = wrap_caption(std::slice::from_ref(line), width);
            for part in &wrapped {
                let measured = text_width(part, px);
                widest = widest.max(measured);
                // Drawn from half the text size in: the right margin is as wide.
                assert!(measured <= width as f32 - px, "{width} px tile: {part:?} measures {measured:.1} px");
            }
            let kept: String = wrapped.concat().split_whitespace().collect();
            assert_eq!(kept, line.split_whitespace().collect::<String>(), "{width} px: {line:?} lost text");
        }
        println!("{width} px tiles ({px:.1} px text): widest wrapped line {widest:.1} px");
    }
}

/// Without wrapping the mistake lines would be cut at 640 and 1280 pixels (the issue's
/// finding), so the test above measures something.
#[test]
fn unwrapped_mistake_lines_are_wider_than_a_640_pixel_tile() {
    let scene = CaptionScene { convention: "none".into(), tangents: "none".into(), displacement: None };
    let shading = ShadingSettings { mistake: Mistake::NoRenormalization, ..ShadingSettings::default() };
    let line = caption_lines(&shading, &scene).pop().unwrap();
    assert!(line.starts_with("mistake: no-renormalization: "), "{line}");
    for width in [640, 1280] {
        let px = caption_px(width);
        assert!(text_width(&line, px) > width as f32 - px, "{width}: {line}");
        assert!(wrap_caption(std::slice::from_ref(&line), width).len() > 1);
    }
}

//! The split view and the comparison exports on the GPU: each half of a split frame is
//! the full render of its setting, the row export is single renders side by side with a
//! caption strip under them, and split frames hold no NaN.
//!
//! Halves are compared exactly: both pictures come from the same pipelines, uniforms, vertex
//! data and target size (so the same rasterisation and MSAA coverage); the scissor rectangle
//! only decides which pixels each draw may write. A margin of columns next to the divider is
//! left out of this comparison, though the frames match there too (the supersampled test
//! compares every column).

mod common;

use bumpview::frame::ViewMode;
use bumpview::frame::{FrameParams, SplitFrame};
use bumpview::names::Named;
use bumpview::render::capture::{CaptureOptions, render_capture, render_capture_split, render_float_split};
use bumpview::render::export::{
    CAPTION_BACKGROUND, TileGrid, caption, caption_strip_height, render_grid, wrap_caption,
};
use bumpview::state::{Command, SplitDifference, ViewerState};

const SIZE: [u32; 2] = [160, 96];
/// Columns either side of the divider left out of the comparison.
const MARGIN: u32 = 2;

fn split_of(state: &ViewerState) -> SplitFrame {
    state.split_frame().expect("split view on")
}

/// Asserts the split capture's left part equals a full render with `split.left` and its right
/// part one with `split.right`, away from the divider; returns the divider column.
fn assert_halves(renderer: &mut bumpview::render::Renderer, params: &FrameParams, split: &SplitFrame) -> u32 {
    let options = CaptureOptions::plain(SIZE);
    let image = render_capture_split(renderer, &options, params, split).unwrap();
    let left = render_capture(renderer, &options, &FrameParams { shading: split.left, ..*params }).unwrap();
    let right = render_capture(renderer, &options, &FrameParams { shading: split.right, ..*params }).unwrap();
    assert_ne!(left, right, "the two settings must look different for the test to mean anything");
    let divider = split.divider_pixels(SIZE[0]);
    let mut compared = [0u32; 2];
    for y in 0..SIZE[1] {
        for x in 0..SIZE[0] {
            let (expected, side) = if x + MARGIN < divider {
                (&left, 0)
            } else if x >= divider + MARGIN {
                (&right, 1)
            } else {
                continue;
            };
            assert_eq!(image.get_pixel(x, y), expected.get_pixel(x, y), "pixel ({x}, {y}), divider at {divider}");
            compared[side] += 1;
        }
    }
    assert!(compared.iter().all(|&n| n > SIZE[1] * 10), "{compared:?}");
    divider
}

#[test]
fn split_bump_off_on_halves_equal_full_renders() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let mut state = ViewerState::new(&scene);
    state.shading.show_light_marker = false;
    state.apply(Command::ToggleSplit);
    assert_eq!(state.split.difference, SplitDifference::Bump);
    let split = split_of(&state);
    assert!(!split.left.bump_enabled && split.right.bump_enabled);
    assert_eq!(assert_halves(&mut renderer, &state.frame_params(), &split), 80);
}

#[test]
fn split_lit_shading_normal_halves_equal_full_renders_at_any_divider() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let mut state = ViewerState::new(&scene);
    state.apply(Command::SetSplit(true));
    state.apply(Command::SetSplitDifference(SplitDifference::View));
    state.apply(Command::SetSplitDivider(0.3));
    let split = split_of(&state);
    assert_eq!((split.left.view, split.right.view), (ViewMode::Lit, ViewMode::ShadingNormal));
    assert_eq!(state.split.labels(), ["Lit".to_owned(), "Shading normal".to_owned()]);
    assert_eq!(assert_halves(&mut renderer, &state.frame_params(), &split), 48);
}

/// Halves that differ in GPU data: the split capture (right half from the second upload) equals,
/// away from the divider, full renders of scenes uploaded with the left and the right options.
fn assert_halves_with_uploads(difference: SplitDifference, view: ViewMode) {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let mut state = ViewerState::new(&scene);
    state.shading.show_light_marker = false;
    state.shading.view = view;
    state.apply(Command::SetSplit(true));
    state.apply(Command::SetSplitDifference(difference));
    state.apply(Command::SetSplitDivider(0.45));
    let uploads = state.scene_uploads();
    let [left, right] = state.split.scene_options(&state.scene_options);
    assert_eq!((&uploads.main, uploads.split_right.as_ref()), (&left, Some(&right)));
    assert_ne!(left, right);
    renderer.set_scene_uploads(&scene, &uploads);

    let options = CaptureOptions::plain(SIZE);
    let params = state.frame_params();
    let split = split_of(&state);
    assert_eq!(split.left, split.right, "only the GPU data differs");
    let image = render_capture_split(&mut renderer, &options, &params, &split).unwrap();
    let mut full = |options_of_half| {
        renderer.set_scene(&scene, options_of_half);
        render_capture(&mut renderer, &options, &params).unwrap()
    };
    let (left_image, right_image) = (full(left), full(right));
    assert_ne!(left_image, right_image, "{difference:?}: the two sides must look different");
    let divider = split.divider_pixels(SIZE[0]);
    assert_eq!(divider, 72);
    for y in 0..SIZE[1] {
        for x in (0..divider - MARGIN).chain(divider + MARGIN..SIZE[0]) {
            let expected = if x < divider { &left_image } else { &right_image };
            assert_eq!(image.get_pixel(x, y), expected.get_pixel(x, y), "{difference:?}: pixel ({x}, {y})");
        }
    }
    // Turning the split off drops the second upload: the right half is the main scene again.
    state.apply(Command::SetSplit(false));
    assert_eq!(state.scene_uploads().split_right, None);
}

#[test]
fn split_two_tangent_methods_halves_equal_full_renders_with_each() {
    assert_halves_with_uploads(SplitDifference::Tangents, ViewMode::Tangent);
}

#[test]
fn split_opengl_directx_halves_equal_full_renders_with_each() {
    assert_halves_with_uploads(SplitDifference::Convention, ViewMode::Lit);
}

#[test]
fn split_normal_map_height_in_shader_halves_equal_full_renders_with_each() {
    assert_halves_with_uploads(SplitDifference::BumpSource, ViewMode::ShadingNormal);
}

#[test]
fn dropping_the_split_scene_draws_the_right_half_from_the_main_scene() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let mut state = ViewerState::new(&scene);
    state.shading.show_light_marker = false;
    state.apply(Command::SetSplit(true));
    state.apply(Command::SetSplitDifference(SplitDifference::Convention));
    renderer.set_scene_uploads(&scene, &state.scene_uploads());
    let options = CaptureOptions::plain(SIZE);
    let params = state.frame_params();
    let with_second = render_capture_split(&mut renderer, &options, &params, &split_of(&state)).unwrap();
    renderer.set_split_scene(&scene, None);
    let without = render_capture_split(&mut renderer, &options, &params, &split_of(&state)).unwrap();
    let main_only = render_capture(&mut renderer, &options, &params).unwrap();
    assert_ne!(with_second, without);
    assert_eq!(without, main_only, "equal halves from one upload are the full render");
}

/// 2× supersampled split captures of every kind: with the divider at column 80 of the PNG
/// (160 of the 2× frame) every 2×2 block lies in one half, so every column, the divider's
/// included, equals the supersampled full render of its side exactly. Kinds that differ in GPU
/// data draw the right half from the second upload and are compared with full renders of
/// scenes uploaded with each side's options; each kind is shown in a view where its two sides
/// differ (the tangent views for two tangent methods, the shading normal for two bump sources).
#[test]
fn supersampled_split_captures_have_the_divider_on_a_block_boundary() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let options = CaptureOptions { supersample: 2, ..CaptureOptions::plain(SIZE) };
    for &difference in SplitDifference::all() {
        // Only materials with a detail map show the detail blend.
        let scene = match difference {
            SplitDifference::DetailBlend => {
                bumpview::scene::teaching::TeachingScene::DetailWaves.build(bumpview::height::Kernel::default())
            }
            _ => scene.clone(),
        };
        let mut state = ViewerState::new(&scene);
        state.shading.view = match difference {
            SplitDifference::Tangents => ViewMode::Tangent,
            SplitDifference::BumpSource => ViewMode::ShadingNormal,
            _ => ViewMode::Lit,
        };
        state.apply(Command::SetSplit(true));
        state.apply(Command::SetSplitDifference(difference));
        let uploads = state.scene_uploads();
        renderer.set_scene_uploads(&scene, &uploads);
        let split = split_of(&state);
        assert_eq!(split.divider_pixels(SIZE[0]), 80, "{difference:?}");
        let params = state.frame_params();
        let image = render_capture_split(&mut renderer, &options, &params, &split).unwrap();
        let mut full = |scene_options, shading| {
            renderer.set_scene(&scene, scene_options);
            render_capture(&mut renderer, &options, &FrameParams { shading, ..params }).unwrap()
        };
        let left = full(uploads.main.clone(), split.left);
        let right = full(uploads.split_right.clone().unwrap_or(uploads.main), split.right);
        assert_ne!(left, right, "{difference:?}: the two sides must look different for the test to mean anything");
        for y in 0..SIZE[1] {
            for x in 0..SIZE[0] {
                let expected = if x < 80 { &left } else { &right };
                assert_eq!(image.get_pixel(x, y), expected.get_pixel(x, y), "{difference:?}: pixel ({x}, {y})");
            }
        }
    }
}

#[test]
fn row_export_is_single_renders_side_by_side_with_a_caption_strip() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let state = ViewerState::new(&scene);
    let params = state.frame_params();
    let grid = TileGrid::default_row(&state.shading);
    let tiles = &grid.tiles;
    assert_eq!(tiles.len(), 3);
    assert!(!tiles[0].bump_enabled && tiles[1].bump_enabled && tiles[2].view == ViewMode::Tangent);
    let captions: Vec<_> = tiles.iter().map(|s| caption(&renderer, &scene, &state.scene_options, s)).collect();
    assert!(captions[0][1].starts_with("bump off"), "{captions:?}");
    assert_eq!(captions[1][2], "normal map: OpenGL (+Y)");
    assert!(captions[2][3].starts_with("tangents: auto: "), "{captions:?}");
    let tile = [128, 80];
    let options = CaptureOptions::plain(tile);
    let row = render_grid(&mut renderer, &options, &params, &grid, Some(&captions)).unwrap();
    // Each caption wrapped to the tile: the strip holds the most lines one wraps to.
    let lines = captions.iter().map(|c| wrap_caption(c, tile[0]).len()).max().unwrap();
    assert!(lines > 4, "at 128 pixels the tangents line wraps: {lines} lines");
    let strip = caption_strip_height(tile[0], lines);
    assert_eq!(row.dimensions(), (3 * tile[0], tile[1] + strip));
    let plain = render_grid(&mut renderer, &options, &params, &grid, None).unwrap();
    assert_eq!(plain.dimensions(), (3 * tile[0], tile[1]));
    let [r, g, b] = CAPTION_BACKGROUND;
    for (i, shading) in tiles.iter().enumerate() {
        let single = render_capture(&mut renderer, &options, &FrameParams { shading: *shading, ..params }).unwrap();
        let x0 = i as u32 * tile[0];
        for y in 0..tile[1] {
            for x in 0..tile[0] {
                assert_eq!(row.get_pixel(x0 + x, y), single.get_pixel(x, y), "tile {i}, pixel ({x}, {y})");
                assert_eq!(plain.get_pixel(x0 + x, y), single.get_pixel(x, y), "tile {i}, pixel ({x}, {y})");
            }
        }
        // The strip: background with text in it (bright glyph pixels on every line).
        let mut text = 0;
        for y in tile[1]..tile[1] + strip {
            for x in x0..x0 + tile[0] {
                let p = row.get_pixel(x, y).0;
                assert_eq!(p[3], 255);
                if p[..3] != [r, g, b] {
                    text += 1;
                }
            }
        }
        assert!(text > 200, "tile {i}: {text} text pixels in the caption strip");
    }
}

#[test]
fn split_frames_on_a_float_target_hold_no_nan() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let mut state = ViewerState::new(&scene);
    state.apply(Command::SetSplit(true));
    for (difference, views) in [
        (SplitDifference::Bump, [ViewMode::Lit, ViewMode::Lit]),
        (SplitDifference::View, [ViewMode::Lit, ViewMode::ShadingNormal]),
        (SplitDifference::View, [ViewMode::Difference, ViewMode::OverTilt]),
        (SplitDifference::Strength, [ViewMode::Lit, ViewMode::Lit]),
        (SplitDifference::Mode, [ViewMode::Lit, ViewMode::Lit]),
        // Second uploads; the Difference view makes reference frames for both.
        (SplitDifference::Tangents, [ViewMode::Difference; 2]),
        (SplitDifference::Convention, [ViewMode::Lit; 2]),
        (SplitDifference::BumpSource, [ViewMode::Lit; 2]),
    ] {
        state.apply(Command::SetSplitDifference(difference));
        state.apply(Command::SetSplitViews(views));
        if difference.changes_gpu_data() {
            state.apply(Command::SetView(views[0]));
        }
        renderer.set_scene_uploads(&scene, &state.scene_uploads());
        let image = render_float_split(&mut renderer, SIZE, &state.frame_params(), &split_of(&state)).unwrap();
        let bad = image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
        assert_eq!(bad, 0, "{difference:?} {views:?}: {bad} pixels not finite");
    }
}

#[test]
fn grid_export_puts_each_tile_at_its_row_and_column_above_its_caption() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let state = ViewerState::new(&scene);
    let params = state.frame_params();
    let grid = TileGrid::parse("flat,bumped@3;handedness,bump-only", &state.shading).unwrap();
    let captions: Vec<_> = grid.tiles.iter().map(|s| caption(&renderer, &scene, &state.scene_options, s)).collect();
    let tile = [96, 64];
    let options = CaptureOptions::plain(tile);
    let image = render_grid(&mut renderer, &options, &params, &grid, Some(&captions)).unwrap();
    let lines = captions.iter().map(|c| wrap_caption(c, tile[0]).len()).max().unwrap();
    let strip = caption_strip_height(tile[0], lines);
    assert_eq!(image.dimensions(), (2 * tile[0], 2 * (tile[1] + strip)));
    for (i, shading) in grid.tiles.iter().enumerate() {
        let single = render_capture(&mut renderer, &options, &FrameParams { shading: *shading, ..params }).unwrap();
        let (x0, y0) = (i as u32 % 2 * tile[0], i as u32 / 2 * (tile[1] + strip));
        for y in 0..tile[1] {
            for x in 0..tile[0] {
                assert_eq!(image.get_pixel(x0 + x, y0 + y), single.get_pixel(x, y), "tile {i}, pixel ({x}, {y})");
            }
        }
        let strip_pixels = (y0 + tile[1]..y0 + tile[1] + strip).flat_map(|y| (x0..x0 + tile[0]).map(move |x| (x, y)));
        let text = strip_pixels.filter(|&(x, y)| image.get_pixel(x, y).0[..3] != CAPTION_BACKGROUND).count();
        assert!(text > 50, "tile {i}: {text} text pixels in its caption strip");
    }
    assert!(captions[1][1].contains("strength 3.00"), "{:?}", captions[1]);
}

#[test]
fn an_export_too_large_to_hold_is_a_clear_error_before_any_rendering() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let state = ViewerState::new(&scene);
    let grid = TileGrid::parse("flat,bumped", &state.shading).unwrap();
    let options = CaptureOptions::plain([16384, 16384]);
    let frames = renderer.counters().frames_drawn;
    let error = render_grid(&mut renderer, &options, &state.frame_params(), &grid, None).unwrap_err();
    assert!(error.to_string().contains("32768x16384"), "{error}");
    assert_eq!(renderer.counters().frames_drawn, frames);
}

/// A window of the picture drawn alone ([`Renderer::set_window`], how lessons draw their insets)
/// is the same window cut from the whole picture drawn as many times larger: here the
/// 60 × 40 window at (150, 70) of a 320 × 180 picture, drawn 4× (240 × 160), against that
/// window of the 1280 × 720 picture; the GPU-displaced scene, whose tessellation follows the
/// window's view, too.
#[test]
fn a_window_drawn_alone_is_the_window_of_the_magnified_picture() {
    use bumpview::frame::{Displacement, SceneOptions};
    use bumpview::render::PictureWindow;
    use bumpview::render::capture::render_image;
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let params = common::default_params(&scene);
    let window = [150, 70, 60, 40];
    for options in
        [SceneOptions::default(), SceneOptions { displacement: Displacement::on_gpu(3.0), ..Default::default() }]
    {
        renderer.set_scene(&scene, options.clone());
        let whole = render_image(&mut renderer, [1280, 720], &params).unwrap();
        let cut = image::imageops::crop_imm(&whole, 600, 280, 240, 160).to_image();
        renderer.set_window(Some(PictureWindow { picture: [320, 180], window }));
        let alone = render_image(&mut renderer, [240, 160], &params).unwrap();
        renderer.set_window(None);
        let differing =
            cut.pixels().zip(alone.pixels()).filter(|(a, b)| (0..3).any(|c| a[c].abs_diff(b[c]) > 2)).count();
        eprintln!("{}: {differing} of 38400 pixels differ by more than 2 steps", options.displacement.caption());
        // The GPU tessellation follows each frame's view (here cut alike, as its edges measure
        // the same on screen; measured: 1 pixel).
        let allowed = if options.displacement.gpu.is_some() { 100 } else { 0 };
        assert!(differing <= allowed, "{differing}");
    }
}

//! T/B/N glyphs on the GPU: on the wall seen face-on, the red and green pixels lie on the
//! T and B segments projected on the CPU from the same glyph vertices (T = +X, B = +Y, the
//! wall's frame), every projected segment is drawn, and nothing else changes colour that way;
//! glyphs are made only for meshes with tangent frames and hold no NaN.

mod common;

use bumpview::frame::ViewMode;
use bumpview::names::Named;
use bumpview::probe::project_to_pixel;
use bumpview::render::capture::{CaptureOptions, render_capture, render_float};
use bumpview::render::glyphs::{MAX_GLYPHS_PER_MESH, glyph_length, glyph_vertices};
use bumpview::render::pipelines::Pass;
use bumpview::tangent::{self, TangentMethod};
use glam::{Vec2, Vec3};

const SIZE: [u32; 2] = [256, 256];
/// Lift of the glyph base along N, as a fraction of its length (`GLYPH_LIFT` in glyphs.wgsl).
const LIFT: f32 = 0.04;
/// A drawn line may be this many pixels from its projected segment (1 px lines, 4× MSAA).
const TOLERANCE_PX: f32 = 1.5;

/// Glyph colour of a pixel that changed from `before` to `after`: 0 red (T), 1 green (B),
/// 2 otherwise (N, where T and B cross, or unchanged). Over the Normal view's (128, 128, 255)
/// wall a red line raises red and lowers green, a green one the other way round, even where a
/// line covers only part of a pixel.
fn glyph_colour(before: &image::Rgba<u8>, after: &image::Rgba<u8>) -> usize {
    let d = |c: usize| after[c] as i32 - before[c] as i32;
    if d(0) > 30 && d(1) < 0 {
        0
    } else if d(1) > 30 && d(0) < 0 {
        1
    } else {
        2
    }
}

fn changed(before: &image::Rgba<u8>, after: &image::Rgba<u8>) -> bool {
    (0..3).any(|c| before[c].abs_diff(after[c]) > 8)
}

fn distance_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}

#[test]
fn wall_glyphs_are_drawn_where_the_cpu_projects_their_t_and_b_segments() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let mut params = common::close_wall_params(&scene, 1.5);
    params.shading.view = ViewMode::Normal;
    let options = CaptureOptions::plain(SIZE);
    let without = render_capture(&mut renderer, &options, &params).unwrap();
    params.shading.tbn_glyphs = true;
    let with = render_capture(&mut renderer, &options, &params).unwrap();

    // The wall's glyph segments, projected: its frame is T = +X, B = +Y, N = +Z everywhere.
    let wall = &scene.meshes[0];
    assert_eq!(wall.name, "wall");
    let (tangents, _) = tangent::resolve(wall, None);
    let chosen = glyph_vertices(wall, &tangents, MAX_GLYPHS_PER_MESH);
    let length = glyph_length(wall, chosen.len());
    // Segments wholly inside the picture (with `inside`), else all in front of the camera.
    let segments = |direction: Vec3, inside_only: bool| -> Vec<(Vec2, Vec2)> {
        chosen
            .iter()
            .filter_map(|&i| {
                let base = wall.positions[i] + Vec3::Z * (LIFT * length);
                let a = project_to_pixel(&params.camera, SIZE, base)?;
                let b = project_to_pixel(&params.camera, SIZE, base + direction * length)?;
                let inside =
                    |p: Vec2| p.x > 2.0 && p.y > 2.0 && p.x < SIZE[0] as f32 - 2.0 && p.y < SIZE[1] as f32 - 2.0;
                (!inside_only || inside(a) && inside(b)).then_some((a, b))
            })
            .collect()
    };
    let all: Vec<_> = [Vec3::X, Vec3::Y, Vec3::Z].into_iter().flat_map(|d| segments(d, false)).collect();
    let nearest = |x: u32, y: u32, among: &[(Vec2, Vec2)]| {
        let p = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        among.iter().map(|&(a, b)| distance_to_segment(p, a, b)).fold(f32::INFINITY, f32::min)
    };
    let mut changed_pixels = 0;
    for (x, y, pixel) in with.enumerate_pixels() {
        if changed(without.get_pixel(x, y), pixel) {
            changed_pixels += 1;
            let d = nearest(x, y, &all);
            assert!(d <= TOLERANCE_PX, "pixel ({x}, {y}) changed {d:.2} px from every glyph segment");
        }
    }
    assert!(changed_pixels > 0);
    for (colour, direction, name) in [(0, Vec3::X, "T (red)"), (1, Vec3::Y, "B (green)")] {
        let expected = segments(direction, true);
        let anywhere = segments(direction, false);
        assert!(expected.len() >= 4, "{name}: only {} glyphs in view", expected.len());
        let mut marked = 0;
        for (x, y, pixel) in with.enumerate_pixels() {
            if glyph_colour(without.get_pixel(x, y), pixel) == colour {
                marked += 1;
                let d = nearest(x, y, &anywhere);
                assert!(d <= TOLERANCE_PX, "{name}: pixel ({x}, {y}) is {d:.2} px from every {name} segment");
            }
        }
        // Every segment is drawn: a pixel at its midpoint (or a neighbour) has its colour.
        for &(a, b) in &expected {
            let mid = (a + b) * 0.5;
            let near = (-1i32..=1).flat_map(|dy| (-1i32..=1).map(move |dx| (dx, dy))).any(|(dx, dy)| {
                let (x, y) = ((mid.x as i32 + dx) as u32, (mid.y as i32 + dy) as u32);
                glyph_colour(without.get_pixel(x, y), with.get_pixel(x, y)) == colour
            });
            assert!(near, "{name}: segment {a} → {b} not drawn");
        }
        let segment_pixels: f32 = expected.iter().map(|(a, b)| a.distance(*b)).sum();
        assert!(marked as f32 > 0.6 * segment_pixels, "{name}: {marked} pixels for {segment_pixels:.0} px of lines");
    }
}

#[test]
fn glyphs_are_made_only_for_meshes_with_tangent_frames() {
    let mut scene = common::scene();
    for material in &mut scene.materials {
        material.normal_map = None;
        material.height_map = None;
    }
    for mesh in &mut scene.meshes {
        mesh.tangents = None;
    }
    let mut renderer = common::renderer_for(&scene);
    let mut params = common::default_params(&scene);
    params.shading.tbn_glyphs = true;
    let options = CaptureOptions::plain([96, 64]);
    let with = render_capture(&mut renderer, &options, &params).unwrap();
    params.shading.tbn_glyphs = false;
    let without = render_capture(&mut renderer, &options, &params).unwrap();
    assert_eq!(with, without, "no frames, no glyphs");
    assert!(!renderer.built_pipelines().iter().any(|k| matches!(k.pass, Pass::Glyphs { .. })));
}

#[test]
fn glyphs_with_every_tangent_method_hold_no_nan_on_a_float_target() {
    let scene = common::scene();
    let mut renderer = common::renderer_for(&scene);
    let mut params = common::default_params(&scene);
    for &method in TangentMethod::all() {
        let options = bumpview::frame::SceneOptions { tangent_method: Some(method), ..Default::default() };
        renderer.set_scene(&scene, options);
        params.shading.tbn_glyphs = false;
        let without = render_float(&mut renderer, [96, 64], &params).unwrap();
        params.shading.tbn_glyphs = true;
        let image = render_float(&mut renderer, [96, 64], &params).unwrap();
        let bad = image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
        assert_eq!(bad, 0, "{method:?}: {bad} pixels not finite");
        let drawn = image.pixels.iter().zip(&without.pixels).filter(|(a, b)| a != b).count();
        assert!(drawn > 100, "{method:?}: glyphs changed only {drawn} pixels");
    }
    assert!(renderer.built_pipelines().iter().any(|k| matches!(k.pass, Pass::Glyphs { .. })));
}

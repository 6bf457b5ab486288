//! Interactive frames (one sample per pixel) and the adapter's floor, on whatever adapter wgpu
//! finds (lavapipe in CI). Timing is not asserted here: it is measured by the frame benchmark
//! and `bumpview render --frames N`.

mod common;

use bumpview::frame::Msaa;
use bumpview::render::DrawOptions;
use bumpview::render::capture::{IMAGE_FORMAT, draw_offscreen};
use common::*;

const SIZE: [u32; 2] = [160, 100];

/// Pixels from a differing pixel within which an edge must pass (a pixel centre seeing another
/// triangle or nothing): an edge crossing the pixel's square lies within one pixel of a
/// neighbour's centre.
const EDGE_REACH: i64 = 1;

fn frame(renderer: &mut bumpview::render::Renderer, msaa: Msaa) -> Vec<[u8; 4]> {
    let params = default_params(&scene());
    let options = DrawOptions { msaa, ..Default::default() };
    let bytes = draw_offscreen(renderer, SIZE, IMAGE_FORMAT, |r, encoder, target| {
        r.draw(encoder, target, &params, None, options)
    })
    .unwrap();
    bytes.chunks_exact(4).map(|p| p.try_into().unwrap()).collect()
}

/// With one sample a pixel covered by one triangle is shaded exactly as with four (the
/// fragment shader runs once per pixel either way, at its centre); only pixels crossed by a
/// triangle edge — silhouettes, the grid cells of wall and floor, the torus' facets — differ.
#[test]
fn one_sample_frames_differ_from_full_quality_only_along_edges() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let full = frame(&mut renderer, Msaa::X4);
    let interactive = frame(&mut renderer, Msaa::Off);
    let differing = full.iter().zip(&interactive).filter(|(a, b)| a != b).count();
    let share = differing as f64 / full.len() as f64;
    eprintln!("{differing} of {} pixels differ ({:.1}%)", full.len(), 100.0 * share);
    // At 160x100 edges cross about one pixel in twenty (measured on lavapipe: 4.5%); a frame
    // drawn wrong (wrong pipeline, missing geometry, no resolve) differs almost everywhere.
    assert!(share < 0.08, "{:.1}% of pixels differ", 100.0 * share);
    assert!(differing > 0, "4x MSAA smooths some edge");
    // Where they differ: each differing pixel has, within `EDGE_REACH` pixels, a pixel whose
    // centre sees another triangle or nothing (the probe's pick, on the CPU): an edge crosses
    // it. A frame that differs inside triangles fails.
    let probe = bumpview::probe::ProbeScene::new(&scene, &Default::default());
    let camera = default_params(&scene).camera;
    let seen = |x: i64, y: i64| {
        let inside = x >= 0 && y >= 0 && x < SIZE[0] as i64 && y < SIZE[1] as i64;
        inside.then(|| probe.pick(&camera, SIZE, [x as u32, y as u32]).map(|p| (p.instance, p.triangle)))
    };
    let off_edges: Vec<[i64; 2]> = (0..full.len())
        .filter(|&i| full[i] != interactive[i])
        .map(|i| [(i % SIZE[0] as usize) as i64, (i / SIZE[0] as usize) as i64])
        .filter(|&[x, y]| {
            let centre = seen(x, y).flatten();
            let reach = -EDGE_REACH..=EDGE_REACH;
            !reach.clone().any(|dy| reach.clone().any(|dx| seen(x + dx, y + dy).is_some_and(|s| s != centre)))
        })
        .collect();
    println!("{} differing pixels with no edge within {EDGE_REACH} pixels: {off_edges:?}", off_edges.len());
    assert!(off_edges.is_empty(), "pixels differ away from triangle edges: {off_edges:?}");
    let samples: Vec<u32> = renderer.built_pipelines().iter().map(|k| k.samples).collect();
    assert!(samples.contains(&1) && samples.contains(&renderer.sample_count(IMAGE_FORMAT)), "{samples:?}");
}

/// The floor covers every pixel with its one colour, with and without MSAA, and builds its
/// pipeline once per sample count.
#[test]
fn the_floor_is_one_colour_everywhere() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let built = renderer.counters().pipelines_built;
    for msaa in [Msaa::X4, Msaa::Off, Msaa::X4] {
        let bytes =
            draw_offscreen(&mut renderer, SIZE, IMAGE_FORMAT, |r, encoder, target| r.draw_floor(encoder, target, msaa))
                .unwrap();
        // Linear grey 0.5 encodes to sRGB 187.5 of 255, rounded either way.
        let first = [bytes[0], bytes[1], bytes[2], bytes[3]];
        assert!(matches!(first, [187 | 188, g, b, 255] if g == first[0] && b == first[0]), "{first:?}");
        assert!(bytes.chunks_exact(4).all(|p| p == first), "{msaa:?}: not one colour");
    }
    let distinct_counts = if renderer.sample_count(IMAGE_FORMAT) == 1 { 1 } else { 2 };
    assert_eq!(renderer.counters().pipelines_built, built + distinct_counts);
}

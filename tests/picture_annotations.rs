//! What an exported picture carries, as the viewer shows it: the split view's divider and
//! labels, the Difference view's scale with its numbers, the Over-tilt view's key
//! (`render::export::render_picture`).

mod common;

use bumpview::frame::ViewMode;
use bumpview::render::capture::{CaptureOptions, render_capture, render_capture_split};
use bumpview::render::export::render_picture;
use bumpview::shading::difference_color;
use bumpview::state::{Command, ViewerState};
use common::*;

const SIZE: [u32; 2] = [480, 270];

fn is_white(p: &image::Rgba<u8>) -> bool {
    p.0[..3] == [255, 255, 255]
}

/// Text pixels: white blended by glyph coverage over the dark box, bright in every channel.
fn is_text(p: &image::Rgba<u8>) -> bool {
    p.0[..3].iter().all(|&c| c >= 180)
}

/// The pixels `(x, y)` where `a` and `b` differ.
fn differing(a: &image::RgbaImage, b: &image::RgbaImage) -> Vec<(u32, u32)> {
    a.enumerate_pixels().filter(|(x, y, p)| *p != b.get_pixel(*x, *y)).map(|(x, y, _)| (x, y)).collect()
}

#[test]
fn a_rendered_split_has_the_divider_and_both_labels() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let mut state = ViewerState::new(&scene);
    state.apply(Command::SetSplit(true));
    let (split, params) = (state.split_frame().unwrap(), state.frame_params());
    let labels = state.split.labels();
    assert_eq!(labels, ["bump off".to_owned(), "bump on".to_owned()]);
    let options = CaptureOptions::plain(SIZE);
    let plain = render_capture_split(&mut renderer, &options, &params, &split).unwrap();
    let shown = render_picture(&mut renderer, &options, &params, Some((&split, [&labels[0], &labels[1]]))).unwrap();
    let divider = split.divider_pixels(SIZE[0]);
    assert_eq!(divider, 240);
    // The divider: two white columns, the last of the left half and the first of the right.
    for y in 0..SIZE[1] {
        for x in [divider - 1, divider] {
            assert!(is_white(shown.get_pixel(x, y)), "divider pixel ({x}, {y}): {:?}", shown.get_pixel(x, y));
        }
    }
    assert!((0..SIZE[1]).any(|y| !is_white(plain.get_pixel(divider, y))), "the plain capture has no divider");
    // The labels: changed pixels with white text at the top, on each side of the divider,
    // and nothing else changed below them.
    let changed = differing(&plain, &shown);
    let labels_at = |side: std::ops::Range<u32>| {
        let text = changed.iter().filter(|&&(x, y)| side.contains(&x) && is_text(shown.get_pixel(x, y)) && y < 40);
        text.count()
    };
    let (left, right) = (labels_at(0..divider - 1), labels_at(divider + 1..SIZE[0]));
    println!("label text pixels: left {left}, right {right}");
    assert!(left > 20 && right > 20, "white label text pixels: left {left}, right {right}");
    let below = changed.iter().filter(|&&(x, y)| y >= 40 && !(divider - 1..=divider).contains(&x)).count();
    assert_eq!(below, 0, "only the divider changes below the labels");
}

#[test]
fn a_difference_picture_carries_its_scale_and_an_over_tilt_picture_its_key() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let mut params = default_params(&scene);
    params.shading.view = ViewMode::Difference;
    let options = CaptureOptions::plain(SIZE);
    let plain = render_capture(&mut renderer, &options, &params).unwrap();
    let shown = render_picture(&mut renderer, &options, &params, None).unwrap();
    // Every step of the colour scale appears, and the changes keep to the top-right corner.
    let steps: Vec<[u8; 3]> =
        (0..64).map(|i| difference_color((i as f32 + 0.5) / 64.0).map(|c| (c * 255.0).round() as u8)).collect();
    let missing: Vec<_> = steps.iter().filter(|s| !shown.pixels().any(|p| p.0[..3] == s[..])).collect();
    assert!(missing.is_empty(), "scale colours missing: {missing:?}");
    let changed = differing(&plain, &shown);
    assert!(changed.iter().all(|&(x, y)| x >= SIZE[0] / 2 && y < SIZE[1] / 2 + 40), "outside the corner");
    let text = changed.iter().filter(|&&(x, y)| is_text(shown.get_pixel(x, y))).count();
    assert!(text > 30, "the title and numbers: {text} text pixels");

    params.shading.view = ViewMode::OverTilt;
    let plain = render_capture(&mut renderer, &options, &params).unwrap();
    let shown = render_picture(&mut renderer, &options, &params, None).unwrap();
    let red = |image: &image::RgbaImage| image.pixels().filter(|p| p.0[..3] == [255, 0, 0]).count();
    // The swatch: a square of the text size, 12 pixels at 720 high (at least 0.75 of it).
    assert!(red(&shown) >= red(&plain) + 64, "the key's swatch: {} red pixels, {} without", red(&shown), red(&plain));
}

//! `bumpview bake` as a user runs it: PNGs on success (one line per file on stdout, nothing
//! on stderr when it is not a terminal: no progress bar), one line and status 1 for a file
//! that cannot be baked, one line and status 2 for a bad flag or value.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

fn bumpview(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bumpview")).args(args).output().expect("run bumpview")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-bake-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A 64×32 grey ramp with a bump, 8-bit.
fn height_png(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    image::GrayImage::from_fn(64, 32, |x, y| image::Luma([(x * 3 + (y % 7) * 5) as u8])).save(&path).unwrap();
    path
}

#[test]
fn bakes_files_both_ways_and_many_into_a_directory() {
    let dir = temp_dir("ok");
    let (a, b) = (height_png(&dir, "a.png"), height_png(&dir, "b.png"));
    let normal = dir.join("a_n.png");
    let output =
        bumpview(&["bake", text(&a), "--out", text(&normal), "--bits", "16", "--normal-convention", "directx"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(output.stderr.is_empty(), "no progress bar when stderr is not a terminal");
    assert_eq!(String::from_utf8_lossy(&output.stdout).lines().count(), 1);
    let image = image::open(&normal).unwrap();
    assert_eq!((image.width(), image.height(), image.color()), (64, 32, image::ColorType::Rgb16));
    let height = dir.join("back.png");
    let output =
        bumpview(&["bake", "--to-height", text(&normal), "--out", text(&height), "--normal-convention", "directx"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert!(String::from_utf8_lossy(&output.stdout).contains("relief"));
    assert_eq!(image::open(&height).unwrap().color(), image::ColorType::L16);
    let out = dir.join("normals");
    let output = bumpview(&["bake", text(&a), text(&b), "--out", text(&out), "--height-in-alpha", "--strength", "2"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    for name in ["a_normal.png", "b_normal.png"] {
        assert_eq!(image::open(out.join(name)).unwrap().color(), image::ColorType::Rgba8, "{name}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A 64×32 smooth, tiling height map, 16-bit: one sine period across, one cosine period down.
fn smooth_height_png(dir: &Path) -> PathBuf {
    let path = dir.join("smooth.png");
    let tau = std::f32::consts::TAU;
    let h = |x: u32, y: u32| 32768.0 + 12000.0 * (tau * x as f32 / 64.0).sin() + 8000.0 * (tau * y as f32 / 32.0).cos();
    image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_fn(64, 32, |x, y| image::Luma([h(x, y).round() as u16]))
        .save(&path)
        .unwrap();
    path
}

/// A 16-bit normal map's texels decoded (`2·v − 1`).
fn normals(path: &Path) -> Vec<[f32; 3]> {
    let image = image::open(path).unwrap().to_rgb16();
    image.pixels().map(|p| p.0.map(|c| c as f32 / 65535.0 * 2.0 - 1.0)).collect()
}

/// Heights of a 16-bit grey image, less their mean, over their range (max − min).
fn normalised_heights(path: &Path) -> Vec<f32> {
    let values: Vec<f32> = image::open(path).unwrap().to_luma16().pixels().map(|p| p[0] as f32).collect();
    let mean = values.iter().sum::<f32>() / values.len() as f32;
    let (lo, hi) = values.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(l, h), &v| (l.min(v), h.max(v)));
    values.iter().map(|v| (v - mean) / (hi - lo)).collect()
}

/// What the bake writes: `--normal-convention directx` stores the OpenGL map with green
/// inverted (each 16-bit green `65535 − g` within a level, red and blue the same); `--strength
/// 2` doubles every texel's slopes x/z and y/z against `--strength 1` (within 1e-3 of the
/// slope and 2e-4: 16-bit rounding moves a slope by about 3e-5);
/// `--to-height` of the baked map gives the heights back (less their means, over their
/// ranges: within 2e-3 at every texel; measured 4.2e-4).
#[test]
fn baked_content_follows_the_convention_and_strength_and_comes_back() {
    let dir = temp_dir("content");
    let input = smooth_height_png(&dir);
    let bake = |name: &str, extra: &[&str]| {
        let out = dir.join(name);
        let args = [&["bake", text(&input), "--out", text(&out), "--bits", "16"][..], extra].concat();
        let output = bumpview(&args);
        assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        out
    };
    let opengl = normals(&bake("gl.png", &[]));
    let directx = normals(&bake("dx.png", &["--normal-convention", "directx"]));
    let single = normals(&bake("x1.png", &["--strength", "1"]));
    let double = normals(&bake("x2.png", &["--strength", "2"]));
    let level = 2.0 / 65535.0;
    for ((gl, dx), (x1, x2)) in opengl.iter().zip(&directx).zip(single.iter().zip(&double)) {
        assert!((gl[0] - dx[0]).abs() <= level && (gl[2] - dx[2]).abs() <= level, "{gl:?} {dx:?}");
        assert!((gl[1] + dx[1]).abs() <= level, "green not flipped: {gl:?} {dx:?}");
        for c in 0..2 {
            let (slope, doubled) = (x1[c] / x1[2], x2[c] / x2[2]);
            assert!((doubled - 2.0 * slope).abs() < 2e-4 + 1e-3 * slope.abs(), "{c}: {slope} doubled {doubled}");
        }
    }
    let sloped = single.iter().filter(|n| n[0].abs() > 0.01 && n[1].abs() > 0.01).count();
    assert!(sloped > 100, "only {sloped} texels sloped in both directions");
    let back = dir.join("back.png");
    let output = bumpview(&["bake", "--to-height", text(&dir.join("gl.png")), "--out", text(&back)]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let worst = normalised_heights(&back)
        .iter()
        .zip(normalised_heights(&input))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    println!("round trip: worst {worst:.2e} of the range");
    assert!(worst < 2e-3, "round trip off by {worst} of the range");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Each case prints one message on stderr, its first line starting `bumpview:`, and exits 1 (the work
/// failed: not an image, 1×1, a 30000² header, an unwritable output) or 2 (bad flag or value).
#[test]
fn bad_inputs_and_flags_give_one_line_and_their_status() {
    let dir = temp_dir("bad");
    let good = height_png(&dir, "good.png");
    let text_file = dir.join("notes.png");
    std::fs::write(&text_file, "not an image").unwrap();
    let tiny = dir.join("tiny.png");
    image::GrayImage::new(1, 1).save(&tiny).unwrap();
    let huge = dir.join("huge.png");
    // Ten bytes of pixel data, far from the 900 MB declared.
    common::header_only_png(&huge, 30000, png::ColorType::Grayscale, png::BitDepth::Eight);
    let out = dir.join("out.png");
    let unwritable = dir.join("missing").join("out.png");
    let cases: [(Vec<&str>, i32); 9] = [
        (vec!["bake", text(&text_file), "--out", text(&out)], 1),
        (vec!["bake", text(&tiny), "--out", text(&out)], 1),
        (vec!["bake", text(&huge), "--out", text(&out)], 1),
        (vec!["bake", text(&good), "--out", text(&unwritable)], 1),
        (vec!["bake", "--to-height", text(&huge), "--out", text(&out)], 1),
        (vec!["bake", text(&good), "--out", text(&out), "--bits", "12"], 2),
        (vec!["bake", text(&good), "--out", text(&out), "--kernel", "sobel7"], 2),
        (vec!["bake", text(&good), "--out", text(&out), "--height-range", "-1"], 2),
        (vec!["bake", text(&good), "--out", text(&out), "--strength", "2", "--texel-size", "0.01"], 2),
    ];
    for (args, status) in cases {
        let output = bumpview(&args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        let lines: Vec<&str> = stderr.lines().collect();
        assert_eq!(output.status.code(), Some(status), "{args:?}: {stderr}");
        // One message: clap's may go on under its first line (e.g. the possible values).
        let ours = lines.iter().filter(|l| l.starts_with("bumpview:")).count();
        assert!(ours == 1 && lines[0].starts_with("bumpview:"), "{args:?}: {stderr}");
    }
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--max-memory MIB` sets the limit of `--to-height` (one line, status 1, naming the need and
/// the limit, with the flag); at the need the input is admitted and fails only at its missing
/// pixels. Without `--to-height` the flag is a usage error.
#[test]
fn to_height_memory_limit_is_named_and_raisable() {
    let dir = temp_dir("memory");
    let header_only = dir.join("rgb8.png");
    // 4096² RGB 8-bit declared, ten zero bytes of data: needs 176 MiB (tests/bake.rs).
    common::header_only_png(&header_only, 4096, png::ColorType::Rgb, png::BitDepth::Eight);
    let out = dir.join("out.png");
    let run = |extra: &[&str]| {
        let mut args = vec!["bake", text(&header_only), "--out", text(&out)];
        args.extend(extra);
        let output = bumpview(&args);
        (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
    };
    let (status, stderr) = run(&["--to-height", "--max-memory", "175"]);
    assert_eq!(status, Some(1), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("need 176 MiB to integrate, over the limit of 175 MiB (--max-memory raises it)"),
        "{stderr}"
    );
    let (status, stderr) = run(&["--to-height", "--max-memory", "176"]);
    assert!(status == Some(1) && stderr.contains("not a readable PNG image"), "{stderr}");
    let (status, stderr) = run(&["--max-memory", "176"]);
    assert_eq!(status, Some(2), "{stderr}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A 16×16 normal map whose texels alternate, checkerwise, between normals tilted ±0.5 rad
/// about y; and the length of the mean of the two as the viewer decodes them (`2·rgb/255 − 1`,
/// normalised): every level past 0 has this |Na|.
fn checker_normal_png(dir: &Path) -> (PathBuf, f32) {
    let path = dir.join("checker.png");
    let tilted = |sign: f32| {
        let n = glam::Vec3::new(sign * 0.5f32.sin(), 0.0, 0.5f32.cos()) * 0.5 + 0.5;
        n.to_array().map(|c| (c * 255.0).round() as u8)
    };
    image::RgbImage::from_fn(16, 16, |x, y| image::Rgb(tilted(if (x + y) % 2 == 0 { 1.0 } else { -1.0 })))
        .save(&path)
        .unwrap();
    let decoded = |rgb: [u8; 3]| (glam::Vec3::from_array(rgb.map(|c| c as f32 / 255.0)) * 2.0 - 1.0).normalize();
    let length = ((decoded(tilted(1.0)) + decoded(tilted(-1.0))) * 0.5).length();
    (path, length)
}

/// `--mips toksvig` writes every level with Toksvig's gloss s′/s in alpha (the shading
/// layer's formula at the decoded |Na|, to the 8-bit step), `--mips vmf` the widened
/// roughness, `--mips base-only` level 0 alone; LEAN has nothing per level (status 2).
#[test]
fn mips_are_written_one_png_a_level_with_the_methods_alpha() {
    use bumpview::shading::mip_filter::{toksvig_variance, vmf_variance, widened_roughness, widened_shininess};
    use bumpview::texture::MipFilter;
    let dir = temp_dir("mips");
    let (map, length) = checker_normal_png(&dir);
    let out = dir.join("toksvig");
    let output = bumpview(&["bake", text(&map), "--mips", "toksvig", "--shininess", "32", "--out", text(&out)]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(String::from_utf8_lossy(&output.stdout).lines().count(), 5, "16, 8, 4, 2 and 1 texels a side");
    let gloss = widened_shininess(MipFilter::Toksvig, 32.0, 2.0 * toksvig_variance(length)).0 / 32.0;
    for (level, side) in [(0, 16), (1, 8), (4, 1)] {
        let image = image::open(out.join(format!("checker_mip{level}.png"))).unwrap().to_rgba8();
        assert_eq!(image.dimensions(), (side, side));
        let expected = if level == 0 { 255 } else { (gloss * 255.0).round() as u8 };
        assert_eq!(image.get_pixel(0, 0).0[3], expected, "level {level}");
        if level > 0 {
            assert_eq!(&image.get_pixel(0, 0).0[..3], &[128, 128, 255], "the mean of ±x is +z");
        }
    }
    let out = dir.join("vmf");
    let output = bumpview(&["bake", text(&map), "--mips", "vmf", "--roughness", "0.25", "--out", text(&out)]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let roughness = widened_roughness(0.25, vmf_variance(length));
    let alpha = image::open(out.join("checker_mip2.png")).unwrap().to_rgba8().get_pixel(0, 0).0[3];
    assert_eq!(alpha, (roughness * 255.0).round() as u8);
    let out = dir.join("base");
    let output = bumpview(&["bake", text(&map), "--mips", "base-only", "--out", text(&out)]);
    assert!(output.status.success() && out.join("checker_mip0.png").exists() && !out.join("checker_mip1.png").exists());
    let output = bumpview(&["bake", text(&map), "--mips", "lean", "--out", text(&dir.join("lean"))]);
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("--mips lean: "), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

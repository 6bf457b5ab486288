//! `bumpview::bake` through files, against exact references: the sine plane of the report
//! (`h = A·sin(kx)·sin(ky)`, slope 1), whose central-difference normals are known in closed
//! form — the exact slopes times the kernel's gain `sinc(kΔ)` — so a baked texel may differ
//! from them only by the output's rounding; the conventions and depths against each other;
//! the way back (Frankot–Chellappa) against the heights it started from; bad inputs.

mod common;

use std::path::{Path, PathBuf};

use bumpview::bake::image_io::MAX_SIDE;
use bumpview::bake::{
    BakeOptions, DEFAULT_MEMORY_LIMIT, Direction, TexelSize, Units, bake_all, bake_file, plan_outputs, to_height_file,
};
use bumpview::height::rows::Channels;
use bumpview::height::{Border, Kernel};
use bumpview::report::surfaces::SineBumps;
use bumpview::scene::GreenAxis;
use glam::DVec3;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-bake-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The report's sine plane at 32 texels per period, 4 periods (128²), as a 16-bit grey PNG.
fn sine_plane_png(dir: &Path) -> (SineBumps, PathBuf) {
    let bumps = SineBumps::new(32, 4);
    let field = bumps.field().quantized(16);
    let words: Vec<u16> = field.samples.iter().map(|&h| (h * 65535.0).round() as u16).collect();
    let side = bumps.side();
    let path = dir.join("sine.png");
    image::ImageBuffer::<image::Luma<u16>, _>::from_raw(side, side, words).unwrap().save(&path).unwrap();
    (bumps, path)
}

/// The sine plane's units: 2A metres per full range, texels of Δ metres.
fn sine_units(bumps: &SineBumps) -> Units {
    Units::Physical { range_m: 2.0 * bumps.amplitude_m() as f32, texel: TexelSize::Metres(bumps.texel_m() as f32) }
}

/// The central difference's normal at texel `(i, j)` in closed form: the exact slopes times
/// `sinc(kΔ) = sin(kΔ)/(kΔ)`.
fn central_normal(bumps: &SineBumps, i: u32, j: u32) -> DVec3 {
    let (x, y) = bumps.texel_centre(i, j);
    let (dx, dy) = bumps.slope(x, y);
    let k_delta = bumps.wavenumber() * bumps.texel_m();
    let gain = k_delta.sin() / k_delta;
    DVec3::new(-dx * gain, -dy * gain, 1.0).normalize()
}

/// The image's channels as values in 0..1, per texel.
fn channels(path: &Path) -> (u32, Vec<Vec<f64>>) {
    let image = image::open(path).unwrap();
    let count = image.color().channel_count() as usize;
    let values = image.to_rgba32f().pixels().map(|p| p.0[..count].iter().map(|&c| c as f64).collect()).collect();
    (image.width(), values)
}

/// Per texel, the largest component difference between the decoded normal `2c − 1` and the
/// closed-form kernel normal (DirectX green negated back).
fn component_errors(bumps: &SineBumps, path: &Path, green: GreenAxis) -> Vec<f64> {
    let (width, texels) = channels(path);
    texels
        .iter()
        .enumerate()
        .map(|(t, c)| {
            let (i, j) = (t as u32 % width, t as u32 / width);
            let flip = if green == GreenAxis::DirectX { -1.0 } else { 1.0 };
            let decoded = DVec3::new(2.0 * c[0] - 1.0, flip * (2.0 * c[1] - 1.0), 2.0 * c[2] - 1.0);
            (decoded - central_normal(bumps, i, j)).abs().max_element()
        })
        .collect()
}

/// Every texel of the 8-bit bake is within half a step (0.5/127.5 per component) of the
/// central difference's closed-form normal, plus 2e-4 for the 16-bit heights it was baked from
/// and f32 arithmetic.
#[test]
fn the_sine_plane_bakes_to_the_kernels_normals_within_eight_bit_rounding() {
    let dir = temp_dir("sine8");
    let (bumps, input) = sine_plane_png(&dir);
    let output = dir.join("normal.png");
    let options = BakeOptions { units: sine_units(&bumps), ..Default::default() };
    let baked = bake_file(&input, &output, &options).unwrap();
    assert_eq!((baked.width, baked.height), (128, 128));
    let errors = component_errors(&bumps, &output, GreenAxis::OpenGl);
    let worst = errors.iter().copied().fold(0.0, f64::max);
    assert!(worst <= 0.5 / 127.5 + 2e-4, "worst component error {worst}");
    // The same texels against the exact normals differ by the kernel's own error as well.
    let (width, texels) = channels(&output);
    let mean_exact: f64 = texels
        .iter()
        .enumerate()
        .map(|(t, c)| {
            let n = DVec3::new(2.0 * c[0] - 1.0, 2.0 * c[1] - 1.0, 2.0 * c[2] - 1.0).normalize();
            n.angle_between(bumps.normal(t as u32 % width, t as u32 / width)).to_degrees()
        })
        .sum::<f64>()
        / texels.len() as f64;
    // The report: 0.162° for the kernel on float heights, 0.449° with 8-bit heights; 8-bit
    // normals of 16-bit heights fall between.
    assert!((0.15..0.45).contains(&mean_exact), "mean angle to the exact normals {mean_exact}°");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A DirectX bake is the OpenGL bake with green inverted (`255 − g`), red and blue equal, at
/// both depths; reading it as DirectX gives the same normals.
#[test]
fn directx_output_is_opengl_output_with_green_inverted() {
    let dir = temp_dir("directx");
    let (bumps, input) = sine_plane_png(&dir);
    for sixteen_bit in [false, true] {
        let base = BakeOptions { units: sine_units(&bumps), sixteen_bit, ..Default::default() };
        let (gl, dx) = (dir.join("gl.png"), dir.join("dx.png"));
        bake_file(&input, &gl, &base).unwrap();
        bake_file(&input, &dx, &BakeOptions { green: GreenAxis::DirectX, ..base }).unwrap();
        let (gl_image, dx_image) = (image::open(&gl).unwrap().into_rgb16(), image::open(&dx).unwrap().into_rgb16());
        // `into_rgb16` widens 8-bit channels by 257: 255 becomes 65535 too.
        let max = 65535;
        for (a, b) in gl_image.pixels().zip(dx_image.pixels()) {
            assert_eq!((a[0], max - a[1], a[2]), (b[0], b[1], b[2]));
        }
        let (gl_errors, dx_errors) =
            (component_errors(&bumps, &gl, GreenAxis::OpenGl), component_errors(&bumps, &dx, GreenAxis::DirectX));
        assert_eq!(gl_errors.iter().copied().fold(0.0, f64::max), dx_errors.iter().copied().fold(0.0, f64::max));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// 16-bit output rounds to steps 257 times finer than 8-bit (65535 / 255): the RMS component
/// error against the kernel's normals of the stored heights shrinks by that factor, within 10%
/// (the rounding errors are spread evenly over a step, RMS step/√12, on 128² texels).
#[test]
fn sixteen_bit_output_is_finer_by_the_ratio_of_the_steps() {
    let dir = temp_dir("depths");
    let (bumps, input) = sine_plane_png(&dir);
    let stored = bumps.field().quantized(16);
    let rms = |sixteen_bit: bool| {
        let output = dir.join(format!("n{sixteen_bit}.png"));
        bake_file(&input, &output, &BakeOptions { units: sine_units(&bumps), sixteen_bit, ..Default::default() })
            .unwrap();
        let (width, texels) = channels(&output);
        let squares: f64 = texels
            .iter()
            .enumerate()
            .flat_map(|(t, c)| {
                let (i, j) = ((t as u32 % width) as i64, (t as u32 / width) as i64);
                let n = stored.normal(Kernel::CentralDifference, Border::Wrap, i, j).as_dvec3();
                [n.x, n.y, n.z].into_iter().zip(c.clone()).map(|(e, c)| (2.0 * c - 1.0 - e).powi(2))
            })
            .sum();
        (squares / (3 * texels.len()) as f64).sqrt()
    };
    let (eight, sixteen) = (rms(false), rms(true));
    let ratio = eight / sixteen;
    assert!((eight - (2.0 / 255.0) / 12f64.sqrt()).abs() < 0.1 * eight, "8-bit RMS {eight}");
    assert!((257.0 * 0.9..257.0 * 1.1).contains(&ratio), "8-bit RMS {eight}, 16-bit {sixteen}: ratio {ratio}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The heights a file holds, in full ranges (0..1), mean removed.
fn centred_heights(path: &Path) -> Vec<f64> {
    let image = image::open(path).unwrap().into_luma16();
    let values: Vec<f64> = image.pixels().map(|p| p[0] as f64 / 65535.0).collect();
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    values.iter().map(|v| v - mean).collect()
}

/// (RMS, max) difference of two height lists.
fn differences(a: &[f64], b: &[f64]) -> (f64, f64) {
    let squares: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    let max = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    ((squares / a.len() as f64).sqrt(), max)
}

/// Height → 16-bit normals → height with the kernel's own symbol gives back the sine plane's
/// 16-bit heights exactly (every texel's level, up to the mean, which slopes do not fix: the
/// solve's error stays under half a 16-bit step); through 8-bit normals within 3e-3 of the
/// full range (measured RMS 5.1e-4, max 1.2e-3); the spectral symbol (Frankot and
/// Chellappa's `iω`) misses by the kernel's gain, `1 − sinc(kΔ)` = 0.64% of the amplitude
/// (half the range): 3.2e-3.
#[test]
fn to_height_recovers_the_sine_plane() {
    let dir = temp_dir("roundtrip");
    let (bumps, input) = sine_plane_png(&dir);
    let original = centred_heights(&input);
    let trip = |sixteen_bit: bool, spectral: bool| {
        let options = BakeOptions { units: sine_units(&bumps), sixteen_bit, spectral, ..Default::default() };
        let (normal, height) = (dir.join("n.png"), dir.join("h.png"));
        bake_file(&input, &normal, &options).unwrap();
        let baked = to_height_file(&normal, &height, &options).unwrap();
        let (relief, clipped) = baked.relief.unwrap();
        assert!((relief - 1.0).abs() < 0.02 && clipped == 0, "relief {relief} full ranges, {clipped} clipped");
        differences(&centred_heights(&height), &original)
    };
    let (rms, max) = trip(true, false);
    eprintln!("16-bit normals: RMS {rms:.2e} max {max:.2e}");
    assert!(max < 1e-9, "16-bit normals: RMS {rms} max {max}");
    let (rms, max) = trip(false, false);
    eprintln!("8-bit normals: RMS {rms:.2e} max {max:.2e}");
    assert!(max < 3e-3, "8-bit normals: RMS {rms} max {max}");
    let (rms, max) = trip(true, true);
    eprintln!("16-bit normals, spectral: RMS {rms:.2e} max {max:.2e}");
    let k_delta = bumps.wavenumber() * bumps.texel_m();
    let gain_loss = 0.5 * (1.0 - k_delta.sin() / k_delta);
    assert!((max - gain_loss).abs() < 3e-4, "spectral max {max} against the gain loss {gain_loss}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The Rock058 displacement fixture (JPEG, 8-bit, 256², shrunk from ambientCG's 1024²) baked to
/// a 16-bit normal map and back in the same units: the relief comes back within 1e-4 RMS and
/// 3e-4 max of the full range (measured 2.5e-5 and 6.3e-5: under a tenth of an 8-bit step).
#[test]
fn rock058_displacement_round_trips() {
    let base = common::assets();
    let input = common::asset(&base, "textures/ambientCG_Rock058/displacement.jpg");
    let dir = temp_dir("rock");
    let options = BakeOptions { sixteen_bit: true, ..Default::default() };
    let (normal, height) = (dir.join("n.png"), dir.join("h.png"));
    bake_file(&input, &normal, &options).unwrap();
    to_height_file(&normal, &height, &options).unwrap();
    let (rms, max) = differences(&centred_heights(&height), &centred_heights(&input));
    eprintln!("Rock058: RMS {rms:.2e} max {max:.2e} of the full range");
    assert!(rms < 1e-4 && max < 3e-4, "RMS {rms} max {max}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--height-in-alpha` keeps the heights (8-bit: the 16-bit input rounded), a depth map's
/// inverted; two-channel output has blue 0 and the normal's x, y.
#[test]
fn height_in_alpha_and_two_channel_layouts() {
    let dir = temp_dir("layouts");
    let (bumps, input) = sine_plane_png(&dir);
    let heights = centred_heights(&input);
    for depth in [false, true] {
        let output = dir.join("rgba.png");
        let options =
            BakeOptions { units: sine_units(&bumps), channels: Channels::RgbHeight, depth, ..Default::default() };
        bake_file(&input, &output, &options).unwrap();
        let image = image::open(&output).unwrap().into_rgba8();
        let sign = if depth { -1.0 } else { 1.0 };
        let alpha: Vec<f64> = image.pixels().map(|p| sign * p[3] as f64 / 255.0).collect();
        let mean = alpha.iter().sum::<f64>() / alpha.len() as f64;
        let centred: Vec<f64> = alpha.iter().map(|a| a - mean).collect();
        assert!(differences(&centred, &heights).1 < 0.6 / 255.0);
    }
    let two = dir.join("two.png");
    bake_file(
        &input,
        &two,
        &BakeOptions { units: sine_units(&bumps), channels: Channels::TwoChannel, ..Default::default() },
    )
    .unwrap();
    let rgb = dir.join("rgb.png");
    bake_file(&input, &rgb, &BakeOptions { units: sine_units(&bumps), ..Default::default() }).unwrap();
    let (two, rgb) = (image::open(&two).unwrap().into_rgb8(), image::open(&rgb).unwrap().into_rgb8());
    assert!(two.pixels().zip(rgb.pixels()).all(|(a, b)| a[2] == 0 && a[0] == b[0] && a[1] == b[1]));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Each bad input fails with one line naming the file: not an image, a 1×1 image, a header of
/// 30000² texels (refused before its pixels are allocated), an output in a missing folder.
#[test]
fn bad_inputs_fail_with_one_line_naming_the_file() {
    let dir = temp_dir("bad");
    let text = dir.join("notes.png");
    std::fs::write(&text, "not an image").unwrap();
    let tiny = dir.join("tiny.png");
    image::GrayImage::new(1, 1).save(&tiny).unwrap();
    let huge = dir.join("huge.png");
    // Ten bytes of pixel data, far from the 900 MB declared.
    common::header_only_png(&huge, 30000, png::ColorType::Grayscale, png::BitDepth::Eight);
    let (_, good) = sine_plane_png(&dir);
    let unwritable = dir.join("missing-folder").join("out.png");
    let cases = [
        (&text, dir.join("a.png"), "not an image"),
        (&tiny, dir.join("b.png"), "too small"),
        (&huge, dir.join("c.png"), &format!("over the bake's limit of {MAX_SIDE}") as &str),
        (&good, unwritable.clone(), "cannot write"),
    ];
    for (input, output, expected) in cases {
        for to_height in [false, true] {
            let result = if to_height {
                to_height_file(input, &output, &BakeOptions::default())
            } else {
                bake_file(input, &output, &BakeOptions::default())
            };
            let message = result.expect_err("a bad input fails").to_string();
            assert!(message.contains(expected) && !message.contains('\n'), "{message}");
            let named = if output == unwritable { &output } else { input };
            assert!(message.starts_with(&named.display().to_string()), "{message}");
        }
    }
    assert!(!unwritable.parent().unwrap().exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

const MIB: u64 = 1 << 20;

/// `--to-height` refuses an input whose memory need is over the limit from its header, before
/// any pixel is allocated (the pixels are missing: decoding would fail otherwise), in one line
/// naming the file, its size, the need and the limit. The need is the documented formula
/// `max(decoded + max(file, packed), packed + scratch)`, checked at the limit's edge.
#[test]
fn to_height_refuses_inputs_over_the_memory_limit_from_the_header() {
    let dir = temp_dir("memory");
    let out = dir.join("out.png");
    // 4096² RGB 8-bit, wrapping: 3 B decoded + 8 B packed a texel = 11 · 16 MiB = 176 MiB
    // (the solve's 128 MiB + 4 MiB of column scratch is less; the file is under 1 KiB).
    let small = dir.join("rgb8.png");
    common::header_only_png(&small, 4096, png::ColorType::Rgb, png::BitDepth::Eight);
    let with_limit = |mib: u64| BakeOptions { memory_limit: mib * MIB, ..Default::default() };
    let refused = to_height_file(&small, &out, &with_limit(175)).unwrap_err().to_string();
    let expected = "4096x4096 texels (Rgb8, border wrap) need 176 MiB to integrate, over the limit of 175 MiB";
    assert!(refused.starts_with(&small.display().to_string()) && refused.contains(expected), "{refused}");
    assert!(!refused.contains('\n'));
    let admitted = to_height_file(&small, &out, &with_limit(176)).unwrap_err().to_string();
    assert!(admitted.contains("not a readable PNG image"), "{admitted}");
    // 16384² RGB 16-bit, clamped: 6 B decoded + 16 B packed a texel = 22 · 256 MiB = 5632 MiB,
    // over the default 4096 MiB.
    let big = dir.join("rgb16.png");
    common::header_only_png(&big, 16384, png::ColorType::Rgb, png::BitDepth::Sixteen);
    assert_eq!(DEFAULT_MEMORY_LIMIT, 4096 * MIB);
    let clamped = BakeOptions { border: Border::Clamp, ..Default::default() };
    let refused = to_height_file(&big, &out, &clamped).unwrap_err().to_string();
    let expected = "16384x16384 texels (Rgb16, border clamp) need 5632 MiB to integrate, over the limit of 4096 MiB";
    assert!(refused.contains(expected), "{refused}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Several inputs go into a directory, named after each input, baked in parallel; `done`
/// hears of every file.
#[test]
fn many_files_bake_into_a_directory() {
    let dir = temp_dir("many");
    let (_, sine) = sine_plane_png(&dir);
    let other = dir.join("other.png");
    std::fs::copy(&sine, &other).unwrap();
    let inputs = vec![sine.clone(), other.clone()];
    let out = dir.join("normals");
    let outputs = plan_outputs(&inputs, &out, Direction::ToNormal).unwrap();
    assert_eq!(outputs, vec![out.join("sine_normal.png"), out.join("other_normal.png")]);
    let pairs: Vec<_> = inputs.into_iter().zip(outputs.clone()).collect();
    let heard = std::sync::atomic::AtomicUsize::new(0);
    let results = bake_all(&pairs, Direction::ToNormal, &BakeOptions::default(), &|r| {
        assert!(r.is_ok());
        heard.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    });
    assert_eq!(heard.into_inner(), 2);
    assert!(results.iter().all(Result::is_ok) && outputs.iter().all(|o| o.is_file()));
    assert_eq!(
        plan_outputs(std::slice::from_ref(&sine), &dir.join("one.png"), Direction::ToHeight).unwrap(),
        vec![dir.join("one.png")]
    );
    let clash = plan_outputs(&[sine.clone(), dir.join("x").join("sine.png")], &out, Direction::ToNormal);
    assert!(clash.unwrap_err().to_string().contains("another input also writes"));
    std::fs::remove_dir_all(&dir).unwrap();
}

//! `bumpview bake` as a user runs it: PNGs on success (one line per file on stdout, nothing
//! on stderr when it is not a terminal: no progress bar), one line and status 1 for a file
//! that cannot be baked, one line and status 2 for a bad flag or value.

use std::path::{Path, PathBuf};
use std::process::Command;

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

/// Each case prints exactly one line on stderr, starting `bumpview:`, and exits 1 (the work
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
    {
        let mut encoder = png::Encoder::new(std::fs::File::create(&huge).unwrap(), 30000, 30000);
        encoder.set_color(png::ColorType::Grayscale);
        let mut writer = encoder.write_header().unwrap();
        // A zlib stream of ten zero bytes in one stored block, far from the 900 MB declared.
        let mut zlib = vec![0x78, 0x01, 0x01, 10, 0, !10, 0xff];
        zlib.extend([0; 10]);
        zlib.extend([0, 10, 0, 1]);
        writer.write_chunk(png::chunk::IDAT, &zlib).unwrap();
    }
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
        assert!(lines.len() == 1 && lines[0].starts_with("bumpview:"), "{args:?}: {stderr}");
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
    {
        // 4096² RGB 8-bit declared, ten zero bytes of data: needs 176 MiB (tests/bake.rs).
        let mut encoder = png::Encoder::new(std::fs::File::create(&header_only).unwrap(), 4096, 4096);
        encoder.set_color(png::ColorType::Rgb);
        let mut writer = encoder.write_header().unwrap();
        let mut zlib = vec![0x78, 0x01, 0x01, 10, 0, !10, 0xff];
        zlib.extend([0; 10]);
        zlib.extend([0, 10, 0, 1]);
        writer.write_chunk(png::chunk::IDAT, &zlib).unwrap();
    }
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
    assert!(status == Some(1) && stderr.contains("not a readable image"), "{stderr}");
    let (status, stderr) = run(&["--max-memory", "176"]);
    assert_eq!(status, Some(2), "{stderr}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

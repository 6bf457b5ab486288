//! The viewer opens a real window under Xvfb, presents frames and shows the bricks.
#![cfg(feature = "ui")]

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Runs the viewer under Xvfb at 1280×800 with `args` for 10 frames and returns the window
/// it captured. Without `xvfb-run` the test fails, saying what to install.
fn run_viewer(test: &str, args: &[&str]) -> image::RgbImage {
    run_viewer_logged(test, args).0
}

/// [`run_viewer`], with what the viewer wrote to stderr.
fn run_viewer_logged(test: &str, args: &[&str]) -> (image::RgbImage, String) {
    let has_xvfb_run = Command::new("sh")
        .args(["-c", "command -v xvfb-run"])
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    assert!(has_xvfb_run, "the window tests need xvfb-run: apt-get install xvfb xauth");
    let capture = std::env::temp_dir().join(format!("bumpview-window-{test}-{}.png", std::process::id()));
    let mut child = Command::new("xvfb-run")
        .args(["-a", "-s", "-screen 0 1280x800x24", env!("CARGO_BIN_EXE_bumpview"), "--exit-after", "10"])
        .args(args)
        .arg("--capture-window")
        .arg(&capture)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start xvfb-run");
    let started = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if started.elapsed() > Duration::from_secs(180) {
            let _ = child.kill();
            panic!("the viewer did not exit after 10 frames within 180 s");
        }
        std::thread::sleep(Duration::from_millis(200));
    };
    let mut stderr = String::new();
    std::io::Read::read_to_string(child.stderr.as_mut().unwrap(), &mut stderr).unwrap();
    assert!(status.success(), "viewer failed: {stderr}");
    let image = image::open(&capture).expect("window capture").to_rgb8();
    std::fs::remove_file(&capture).unwrap();
    (image, stderr)
}

/// The probe marker's yellow pixels (the ring and ticks; nothing else in the window is this yellow).
fn marker_pixels(image: &image::RgbImage) -> Vec<[f32; 2]> {
    image
        .enumerate_pixels()
        .filter(|(_, _, p)| p[0] > 230 && p[1] > 200 && p[2] < 40)
        .map(|(x, y, _)| [x as f32, y as f32])
        .collect()
}

#[test]
fn viewer_opens_presents_frames_and_exits() {
    let image = run_viewer("viewer_opens_presents_frames_and_exits", &[]);
    assert!(image.width() >= 640 && image.height() >= 400, "{}x{}", image.width(), image.height());
    // Not blank: the 3D view shows red-brown bricks over a good part of the window.
    let bricks = image.pixels().filter(|p| p[0] as i32 > p[1] as i32 + 30 && p[0] > 80).count();
    let share = bricks as f64 / (image.width() * image.height()) as f64;
    assert!(share > 0.05, "only {:.1}% brick-coloured pixels", share * 100.0);
    assert!(marker_pixels(&image).is_empty(), "a probe marker without --probe");
}

/// `--probe X,Y` pins the probe as P + click would: its yellow marker (a ring of radius 6
/// points with ticks out to 14) is drawn over the view at that pixel of the view. The view's
/// corner in the window depends on the panel's width, so the test pins two pixels 100, 60
/// apart: each marker is one compact ring (every marker pixel within 15 pixels of its
/// centre) and the centres lie 100, 60 apart (within 1.5 pixels: the ring's antialiasing),
/// which a marker in the wrong place, at swapped coordinates or at a fixed spot fails.
#[test]
fn a_probe_given_on_the_command_line_is_pinned_and_marked() {
    let centre = |test: &str, pixel: &str| {
        let marker = marker_pixels(&run_viewer(test, &["--probe", pixel]));
        assert!(marker.len() > 20, "{pixel}: only {} marker pixels", marker.len());
        let n = marker.len() as f32;
        let c = [marker.iter().map(|p| p[0]).sum::<f32>() / n, marker.iter().map(|p| p[1]).sum::<f32>() / n];
        let spread = marker.iter().map(|p| (p[0] - c[0]).hypot(p[1] - c[1])).fold(0.0, f32::max);
        assert!(spread < 15.0, "{pixel}: marker pixels spread {spread} px from their centre {c:?}");
        c
    };
    let a = centre("probe_a", "330,260");
    let b = centre("probe_b", "430,320");
    let shift = [b[0] - a[0], b[1] - a[1]];
    println!("markers at {a:?} and {b:?}: shift {shift:?}");
    assert!((shift[0] - 100.0).abs() < 1.5 && (shift[1] - 60.0).abs() < 1.5, "markers {a:?} and {b:?}");
    // The view starts at or after the window's corner, so each marker sits at or after its pixel.
    assert!(a[0] >= 329.0 && a[1] >= 259.0, "marker at {a:?} for view pixel 330,260");
}

/// The window's background between two pictures: the share of the lines across `image` at
/// `at` (columns when `vertical`, else rows, right of `from`) in which the pixel is the dark
/// grey background while the pixels 12 away on both sides are not.
fn gap_share(image: &image::RgbImage, at: u32, vertical: bool, from: u32) -> f32 {
    let grey = |x: u32, y: u32| {
        let p = image.get_pixel(x, y);
        p[0] == p[1] && p[1] == p[2] && p[0] < 60
    };
    let (width, height) = image.dimensions();
    let lines: Vec<bool> = if vertical {
        (0..height).map(|y| grey(at, y) && !grey(at - 12, y) && !grey(at + 12, y)).collect()
    } else {
        (from..width).map(|x| grey(x, at) && !grey(x, at - 12) && !grey(x, at + 12)).collect()
    };
    lines.iter().filter(|&&gap| gap).count() as f32 / lines.len() as f32
}

/// A grid lesson opens as its grid — its four tiles with the window's background between
/// them, across and down, where the scene's own view has none — and the card's number is the
/// one `bumpview slides` writes for the lesson.
#[test]
fn a_grid_lesson_shows_as_a_grid_with_the_slides_number() {
    let lesson = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/lessons/parallax-family.toml");
    let (image, stderr) = run_viewer_logged("grid_lesson", &["--lesson", lesson]);
    let claim = stderr
        .lines()
        .find_map(|line| line.strip_prefix("bumpview: lesson parallax-family: "))
        .unwrap_or_else(|| panic!("no measured claim on stderr: {stderr}"));
    let deck = std::env::temp_dir().join(format!("bumpview-window-grid-deck-{}", std::process::id()));
    let slides = Command::new(env!("CARGO_BIN_EXE_bumpview"))
        .args(["slides", "--force", "--lesson", lesson, "--out"])
        .arg(&deck)
        .output()
        .expect("run slides");
    assert!(slides.status.success(), "{}", String::from_utf8_lossy(&slides.stderr));
    let index = std::fs::read_to_string(deck.join("index.md")).unwrap();
    std::fs::remove_dir_all(&deck).unwrap();
    assert!(index.contains(claim), "the card says '{claim}', the slides' index:\n{index}");

    // Right of the panel (a quarter of the window at most), background between pictures across
    // and down: a column over a third of the window's height, a row over a third of the view.
    let (width, height) = image.dimensions();
    let view_left = width / 4;
    let gaps = |image: &image::RgbImage| {
        let column = (view_left..width - 12).map(|x| gap_share(image, x, true, 0)).fold(0.0, f32::max);
        let row = (12..height - 12).map(|y| gap_share(image, y, false, view_left)).fold(0.0, f32::max);
        (column, row)
    };
    let (column, row) = gaps(&image);
    println!("background between pictures: a column over {column:.2} of the height, a row over {row:.2} of the view");
    assert!(column > 0.33 && row > 0.33, "no gaps between tiles: {column}, {row}");
    let (plain, _) = run_viewer_logged("plain_view", &[]);
    let (column, row) = gaps(&plain);
    assert!(column < 0.1 && row < 0.1, "the scene's own view has gaps: {column}, {row}");
}

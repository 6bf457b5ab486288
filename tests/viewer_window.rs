//! The viewer opens a real window under Xvfb, presents frames and shows the bricks.
#![cfg(feature = "ui")]

use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Runs the viewer under Xvfb at 1280×800 with `args` for 10 frames and returns the window
/// it captured. Without `xvfb-run` the test fails, saying what to install.
fn run_viewer(test: &str, args: &[&str]) -> image::RgbImage {
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
    image
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

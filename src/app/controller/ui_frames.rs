//! A measurement, ignored by default: the UI thread's frames while a scene job re-prepares a
//! 1M-triangle scene (the built-in scene with a 1000 × 500 torus). Each simulated frame does
//! what the window's frame does on the UI thread besides the panel: take in what jobs sent
//! (the install included; the upload is the job's, on its worker), apply the frame's actions and, in the "drawing"
//! runs, orbit the camera a little and draw the old scene with 4× MSAA into a 960 × 600
//! texture. Run it with
//! `cargo test --bin bumpview ui_frames -- --ignored --nocapture --test-threads 1`.

use std::sync::Arc;
use std::time::{Duration, Instant};

use bumpview::frame::Msaa;
use bumpview::render::RenderTarget;
use bumpview::render::capture::IMAGE_FORMAT;
use bumpview::render::timing::target_texture;
use bumpview::scene::builtin::{teaching_scene, torus_mesh};
use bumpview::state::{Command, SplitDifference};
use bumpview::tangent::TangentMethod;

use super::Controller;
use super::tests::{settle, start};
use crate::app::action::Action;

/// A frame every 16 ms at most, as with a 60 Hz display.
const FRAME: Duration = Duration::from_millis(16);

/// Milliseconds since `started`.
fn ms(started: Instant) -> f64 {
    started.elapsed().as_secs_f64() * 1e3
}

/// One frame on the UI thread: its own work (taking in what jobs sent, the install included;
/// when drawing, the orbit and recording and submitting the frame) and, when
/// drawing, the wait for lavapipe (a software GPU on the same CPU; a hardware GPU draws 1M
/// triangles in about a millisecond and the window would not wait for it).
struct Frame {
    work_ms: f64,
    gpu_wait_ms: f64,
    installed: bool,
}

/// Runs one frame.
fn frame(controller: &mut Controller, target: &RenderTarget, drawing: bool) -> Frame {
    let started = Instant::now();
    let revision = controller.revision();
    controller.poll_background(Instant::now());
    if drawing {
        controller.apply([Command::OrbitCamera { d_yaw: 0.002, d_pitch: 0.0 }.into()]);
        controller.draw(target, Msaa::X4).expect("draw");
    }
    let work_ms = ms(started);
    let waited = Instant::now();
    if drawing {
        controller.renderer().device().poll(wgpu::PollType::wait_indefinitely()).expect("wait");
    }
    let frame = Frame { work_ms, gpu_wait_ms: ms(waited), installed: controller.revision() != revision };
    std::thread::sleep(FRAME.saturating_sub(started.elapsed()));
    frame
}

/// Applies `commands` (the first frame's work) and runs frames until their scene job is
/// installed.
fn frames_during(
    controller: &mut Controller,
    commands: &[Command],
    target: &RenderTarget,
    drawing: bool,
) -> Vec<Frame> {
    let started = Instant::now();
    controller.apply(commands.iter().map(|&c| Action::from(c)));
    let mut frames = vec![Frame { work_ms: ms(started), gpu_wait_ms: 0.0, installed: false }];
    while !frames.last().is_some_and(|f| f.installed) {
        frames.push(frame(controller, target, drawing));
    }
    frames
}

/// "median / max ms" of `values`, and how many exceed 50 ms.
fn summary(mut values: Vec<f64>) -> String {
    values.sort_by(f64::total_cmp);
    let median = values.get(values.len() / 2).copied().unwrap_or(0.0);
    let over = values.iter().filter(|&&v| v > 50.0).count();
    format!("median {median:.1} / max {:.1} ms, {over} over 50 ms", values.last().copied().unwrap_or(0.0))
}

/// The 1M-triangle scene prepared, the view 960 × 600; per kind of frame (view still, or
/// drawn every frame) a baseline of 30 frames without a job, then each change: the frames while
/// its job ran, the install frame, and the job's stage times.
#[test]
#[ignore = "a measurement: prints the UI thread's frame times while a 1M-triangle scene re-prepares"]
fn ui_frames_while_a_million_triangle_scene_re_prepares() {
    let mut scene = teaching_scene();
    scene.meshes[2] = torus_mesh(1000, 500);
    let (start, renderer) = start(scene);
    let started = Instant::now();
    let mut controller = Controller::new(start, renderer, Arc::new(|| {}));
    println!("start: {:.1} ms on the UI thread", ms(started));
    settle(&mut controller);
    println!("first job: {:?} (ready {:.0} ms after start)", controller.last_job().unwrap(), ms(started));

    let size = [960, 600];
    controller.set_view_size(Some(size));
    let texture = target_texture(controller.renderer().device(), size);
    let view = texture.create_view(&Default::default());
    let target = RenderTarget { view: &view, format: IMAGE_FORMAT, size };
    let per_face = [Command::SetTangentMethod(Some(TangentMethod::PerFace))];
    let automatic = [Command::SetTangentMethod(None)];
    let split = [Command::SetSplit(true), Command::SetSplitDifference(SplitDifference::Tangents)];
    let mikktspace = [Command::SetTangentMethod(Some(TangentMethod::MikkTSpace))];
    let changes: [(&str, &[Command]); 4] = [
        ("tangent method per-face", &per_face),
        ("tangent method automatic (meshopt)", &automatic),
        ("split halves in tangent methods", &split),
        ("tangent method MikkTSpace", &mikktspace),
    ];
    for drawing in [false, true] {
        let kind = if drawing { "drawing every frame" } else { "view still" };
        let baseline: Vec<Frame> = (0..30).map(|_| frame(&mut controller, &target, drawing)).collect();
        println!(
            "{kind}, no job: UI work {}; lavapipe wait {}",
            summary(baseline.iter().map(|f| f.work_ms).collect()),
            summary(baseline.iter().map(|f| f.gpu_wait_ms).collect()),
        );
        for (name, commands) in changes {
            let frames = frames_during(&mut controller, commands, &target, drawing);
            let (install, during) = frames.split_last().expect("frames");
            let job = controller.last_job().unwrap();
            println!(
                "{kind}, {name}: {} frames while the job ran: UI work {}; lavapipe wait {}; \
                 install frame {:.1} ms (install {:.2} ms); job: load {:.0} ms, prepare {:.0} ms, \
                 upload {:.0} ms, measure {:.0} ms",
                during.len(),
                summary(during.iter().map(|f| f.work_ms).collect()),
                summary(during.iter().map(|f| f.gpu_wait_ms).collect()),
                install.work_ms,
                job.install_ms,
                job.load_ms,
                job.prepare_ms,
                job.upload_ms,
                job.measure_ms,
            );
            controller.apply([Command::SetSplit(false).into()]);
            settle(&mut controller);
        }
    }
}

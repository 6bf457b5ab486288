//! A measurement, ignored by default: the UI thread's frames while a scene job re-prepares a
//! 1M-triangle scene (the built-in scene with a 1000 × 500 torus). Each simulated frame does
//! what the window's frame does on the UI thread besides the panel: take in what jobs sent
//! (the install and its upload included), apply the frame's actions and, in the "drawing"
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

/// One frame on the UI thread: its own work and, when drawing, the wait for lavapipe (the
/// software GPU shares the CPU; a hardware GPU draws 1M triangles in about a millisecond).
struct Frame {
    work_ms: f64,
    gpu_wait_ms: f64,
    installed: bool,
}

/// Applies `commands` and runs frames until their scene job is installed, plus one.
fn frames_during(
    controller: &mut Controller,
    commands: &[Command],
    target: &RenderTarget,
    drawing: bool,
) -> Vec<Frame> {
    let started = Instant::now();
    controller.apply(commands.iter().map(|&c| Action::from(c)));
    let mut frames = vec![Frame { work_ms: ms(started), gpu_wait_ms: 0.0, installed: false }];
    let mut after_install = 0;
    while after_install < 2 {
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
        let gpu_wait_ms = ms(waited);
        let installed = controller.revision() != revision;
        if installed || after_install > 0 {
            after_install += 1;
        }
        frames.push(Frame { work_ms, gpu_wait_ms, installed });
        std::thread::sleep(FRAME.saturating_sub(started.elapsed()));
    }
    frames
}

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
    let changes: [(&str, &[Command]); 4] = [
        ("tangent method MikkTSpace", &[Command::SetTangentMethod(Some(TangentMethod::MikkTSpace))]),
        ("tangent method meshopt", &[Command::SetTangentMethod(Some(TangentMethod::Meshopt))]),
        (
            "split halves in tangent methods",
            &[Command::SetSplit(true), Command::SetSplitDifference(SplitDifference::Tangents)],
        ),
        ("split off", &[Command::SetSplit(false)]),
    ];
    for drawing in [false, true] {
        for (name, commands) in changes {
            let frames = frames_during(&mut controller, commands, &target, drawing);
            let install = frames.iter().position(|f| f.installed).expect("installed");
            let before = &frames[..install];
            let max = |frames: &[Frame], f: fn(&Frame) -> f64| frames.iter().map(f).fold(0.0, f64::max);
            let job = controller.last_job().unwrap();
            println!(
                "{name}, {}: {} frames while the job ran, max UI work {:.1} ms (+ max lavapipe wait {:.1} ms); \
                 install frame {:.1} ms (upload {:.1} ms); job: prepare {:.0} ms, measure {:.0} ms",
                if drawing { "drawing every frame" } else { "view still" },
                before.len(),
                max(before, |f| f.work_ms),
                max(before, |f| f.gpu_wait_ms),
                frames[install].work_ms,
                job.upload_ms,
                job.prepare_ms,
                job.measure_ms,
            );
        }
    }
}

//! Start-up (built-in scene with its normal-map generation, then tangents and upload) and
//! offscreen frame time of the built-in scene at 1280×720 on whatever adapter wgpu picks
//! (set WGPU_BACKEND=vulkan for lavapipe), each frame beside the adapter's floor in the same
//! run (clear + one full-screen triangle of one colour, same size, format, depth buffer and
//! MSAA): full quality (4× MSAA) lit, with T/B/N glyphs and as a split view with a second
//! upload (OpenGL │ DirectX); interactive (1 sample) lit at every pixel and at the render
//! scale the viewer settles on. After criterion's figures it prints each frame as a ratio to
//! its floor, both timed alternately (`render::timing`). Run: `cargo bench --bench startup_and_frame`.

use std::num::NonZeroU32;

use bumpview::frame::{FrameParams, FrameQuality, Msaa, ShadingSettings, SplitFrame};
use bumpview::render::timing::{TimedPicture, time_frames};
use bumpview::render::{DrawOptions, Gpu, RenderTarget, Renderer};
use bumpview::scene::builtin::teaching_scene;
use bumpview::state::interactive::InteractiveQuality;
use bumpview::state::{Command, SplitDifference, ViewerState};
use criterion::{Criterion, criterion_group, criterion_main};

const SIZE: [u32; 2] = [1280, 720];
const FORMAT: wgpu::TextureFormat = bumpview::render::capture::IMAGE_FORMAT;

fn startup(c: &mut Criterion) {
    let mut group = c.benchmark_group("startup");
    group.sample_size(10);
    group.bench_function("teaching_scene (brick height field + normal map)", |b| b.iter(teaching_scene));
    let gpu = Gpu::headless().expect("adapter");
    let scene = teaching_scene();
    group.bench_function("Renderer::new + set_scene (MikkTSpace, upload with mips)", |b| {
        b.iter(|| Renderer::from_gpu(&gpu).set_scene(&scene, Default::default()))
    });
    group.finish();
}

/// A frame to time: its parameters, split and quality.
struct Case {
    name: &'static str,
    params: FrameParams,
    split: Option<SplitFrame>,
    quality: FrameQuality,
    /// The quality is the render scale the viewer settles on, settled again before timing.
    settles: bool,
}

impl Case {
    fn picture(&self) -> TimedPicture<'_> {
        TimedPicture { params: &self.params, split: self.split.as_ref(), view_size: SIZE, quality: self.quality }
    }
}

fn frame(c: &mut Criterion) {
    let gpu = Gpu::headless().expect("adapter");
    let scene = teaching_scene();
    let mut renderer = Renderer::from_gpu(&gpu);
    let mut state = ViewerState::new(&scene);
    state.apply(Command::SetSplitDifference(SplitDifference::Convention));
    state.apply(Command::SetSplit(true));
    // The main upload, and the split view's right half (DirectX) as a second one.
    renderer.set_scene_uploads(&scene, &state.scene_uploads());
    let split = state.split_frame().expect("split on");
    let params = state.frame_params();
    let glyphs = FrameParams { shading: ShadingSettings { tbn_glyphs: true, ..params.shading }, ..params };
    let adapter = renderer.adapter_name();
    let interactive = FrameQuality { msaa: Msaa::Off, render_scale: 1.0 };
    let lit = TimedPicture { params: &params, split: None, view_size: SIZE, quality: interactive };
    let mut controller = InteractiveQuality::default();
    let settled = controller.settle(&mut renderer, &lit).expect("frames");
    let cases = [
        Case { name: "lit, full quality (4x MSAA)", params, split: None, quality: FrameQuality::FULL, settles: false },
        Case {
            name: "lit with T/B/N glyphs, full quality",
            params: glyphs,
            split: None,
            quality: FrameQuality::FULL,
            settles: false,
        },
        Case {
            name: "split OpenGL | DirectX (second upload), full quality",
            params,
            split: Some(split),
            quality: FrameQuality::FULL,
            settles: false,
        },
        Case {
            name: "lit, interactive (1 sample, every pixel)",
            params,
            split: None,
            quality: interactive,
            settles: false,
        },
        Case {
            name: "lit, interactive at the settled render scale",
            params,
            split: None,
            quality: settled,
            settles: true,
        },
    ];

    let mut group = c.benchmark_group(format!("frame 1280x720, {adapter}"));
    group.sample_size(20);
    for msaa in [Msaa::X4, Msaa::Off] {
        let target = Target::new(&gpu, SIZE);
        group.bench_function(format!("floor, {msaa:?}"), |b| {
            b.iter(|| target.draw(&gpu, &mut renderer, |r, e, t| r.draw_floor(e, t, msaa).unwrap()))
        });
    }
    for case in &cases {
        let target = Target::new(&gpu, case.quality.render_size(SIZE));
        let options = DrawOptions { msaa: case.quality.msaa, ..Default::default() };
        group.bench_function(case.name, |b| {
            b.iter(|| {
                target.draw(&gpu, &mut renderer, |r, e, t| {
                    r.draw(e, t, &case.params, case.split.as_ref(), options).unwrap()
                })
            })
        });
    }
    group.finish();

    println!(
        "\nEach frame against the adapter's floor at 1280x720 with its MSAA, timed alternately (medians of 30), {adapter}:"
    );
    let frames = NonZeroU32::new(30).expect("not zero");
    for case in &cases {
        // The render scale as the viewer would have it now: the load on a shared machine moves.
        let quality = match case.settles {
            true => controller.settle(&mut renderer, &lit).expect("frames"),
            false => case.quality,
        };
        let timing = time_frames(&mut renderer, &TimedPicture { quality, ..case.picture() }, frames).expect("frames");
        let [w, h] = quality.render_size(SIZE);
        println!("  {}, drawn at {w}x{h}: {timing}", case.name);
    }
}

/// An offscreen target of the benchmark's format.
struct Target {
    view: wgpu::TextureView,
    size: [u32; 2],
}

impl Target {
    fn new(gpu: &Gpu, size: [u32; 2]) -> Target {
        let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("bench target"),
            size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        Target { view: texture.create_view(&Default::default()), size }
    }

    /// Records with `record`, submits and waits for the adapter.
    fn draw(
        &self,
        gpu: &Gpu,
        renderer: &mut Renderer,
        record: impl FnOnce(&mut Renderer, &mut wgpu::CommandEncoder, &RenderTarget),
    ) {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        record(renderer, &mut encoder, &RenderTarget { view: &self.view, format: FORMAT, size: self.size });
        gpu.queue.submit([encoder.finish()]);
        gpu.device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    }
}

criterion_group!(benches, startup, frame);
criterion_main!(benches);

//! Start-up (built-in scene with its normal-map generation, then tangents and upload) and
//! offscreen frame time of the built-in scene at 1280×720 on whatever adapter wgpu picks
//! (set WGPU_BACKEND=vulkan for lavapipe): lit, with T/B/N glyphs, and the split view with a
//! second upload (OpenGL │ DirectX). Run: `cargo bench --bench startup_and_frame`.

use bumpview::render::{Gpu, RenderTarget, Renderer};
use bumpview::scene::builtin::teaching_scene;
use bumpview::state::{Command, SplitDifference, ViewerState};
use criterion::{Criterion, criterion_group, criterion_main};

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

fn frame(c: &mut Criterion) {
    let gpu = Gpu::headless().expect("adapter");
    let scene = teaching_scene();
    let mut renderer = Renderer::from_gpu(&gpu);
    let mut state = ViewerState::new(&scene);
    state.apply(Command::SetSplitDifference(SplitDifference::Convention));
    renderer.set_scene(&scene, Default::default());
    let params = state.frame_params();
    let size = [1280, 720];
    let format = wgpu::TextureFormat::Rgba8UnormSrgb;
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("bench target"),
        size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    let mut group = c.benchmark_group("frame");
    group.sample_size(20);
    let target = RenderTarget { view: &view, format, size };
    let draw = |renderer: &mut Renderer, record: &dyn Fn(&mut Renderer, &mut wgpu::CommandEncoder)| {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        record(renderer, &mut encoder);
        gpu.queue.submit([encoder.finish()]);
        gpu.device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    };
    group.bench_function(format!("1280x720 lit, {}", gpu.adapter_name()), |b| {
        b.iter(|| draw(&mut renderer, &|r, e| r.render(e, &target, &params).unwrap()))
    });
    let glyphs = bumpview::frame::FrameParams {
        shading: bumpview::frame::ShadingSettings { tbn_glyphs: true, ..params.shading },
        ..params
    };
    group.bench_function("1280x720 lit with T/B/N glyphs", |b| {
        b.iter(|| draw(&mut renderer, &|r, e| r.render(e, &target, &glyphs).unwrap()))
    });
    state.apply(Command::SetSplit(true));
    renderer.set_scene_uploads(&scene, &state.scene_uploads());
    let split = state.split_frame().expect("split on");
    group.bench_function("1280x720 split OpenGL | DirectX (second upload)", |b| {
        b.iter(|| draw(&mut renderer, &|r, e| r.render_split(e, &target, &params, &split, Default::default()).unwrap()))
    });
    group.finish();
}

criterion_group!(benches, startup, frame);
criterion_main!(benches);

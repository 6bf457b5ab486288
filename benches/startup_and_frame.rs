//! Start-up (built-in scene with its normal-map generation, then tangents and upload) and
//! offscreen frame time of the built-in scene at 1280×720 on whatever adapter wgpu picks
//! (set WGPU_BACKEND=vulkan for lavapipe). Run: `cargo bench --bench startup_and_frame`.

use bumpview::render::{Gpu, RenderTarget, Renderer};
use bumpview::scene::builtin::teaching_scene;
use bumpview::viewer::ViewerState;
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
    renderer.set_scene(&scene, Default::default());
    let params = ViewerState::new(&scene).frame_params();
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
    group.bench_function(format!("1280x720 lit, {}", gpu.adapter_name()), |b| {
        b.iter(|| {
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            renderer.render(&mut encoder, &RenderTarget { view: &view, format, size }, &params).unwrap();
            gpu.queue.submit([encoder.finish()]);
            gpu.device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
        })
    });
    group.finish();
}

criterion_group!(benches, startup, frame);
criterion_main!(benches);

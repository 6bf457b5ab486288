//! What the device refuses ends in a notice, not a panic: a scene whose geometry is past the
//! device's buffer limit is drawn as nothing, with one line saying why, and the renderer goes
//! on drawing the next scene it is given.

mod common;

use bumpview::render::Renderer;
use bumpview::render::capture::render_image;
use bumpview::render::gpu::Gpu;
use bumpview::scene::builtin::teaching_scene;
use common::*;

/// A renderer on a device that holds buffers of at most 64 KiB: the built-in torus's T/B/N
/// glyphs (134 KiB) and indices (72 KiB) are refused, the wall's and the floor's buffers fit.
fn renderer_with_small_buffers() -> Renderer {
    let gpu =
        Gpu::headless().unwrap_or_else(|e| panic!("GPU tests need an adapter (install mesa-vulkan-drivers): {e}"));
    let limits = wgpu::Limits { max_buffer_size: 64 << 10, ..gpu.adapter.limits() };
    let descriptor = wgpu::DeviceDescriptor { required_limits: limits, ..Default::default() };
    let (device, queue) =
        pollster::block_on(gpu.adapter.request_device(&descriptor)).expect("a device with lower limits");
    Renderer::new(device, queue, gpu.adapter)
}

#[test]
fn geometry_the_device_refuses_is_a_notice_and_an_empty_picture() {
    let scene = teaching_scene();
    let mut renderer = renderer_with_small_buffers();
    renderer.set_scene(&scene, Default::default());
    let notices = renderer.notices();
    let refused = |n: &String| n.contains("geometry could not be uploaded") && n.contains("maximum buffer size");
    assert!(notices.iter().any(refused), "{notices:?}");
    let picture = render_image(&mut renderer, [32, 24], &default_params(&scene)).unwrap();
    let background = picture.get_pixel(0, 0);
    assert!(picture.pixels().all(|p| p == background), "nothing drawn but the background");
    // A scene the device can hold draws after the refused one.
    let mut small = scene.clone();
    small.instances.retain(|i| i.mesh != 2);
    small.meshes.truncate(2);
    renderer.set_scene(&small, Default::default());
    assert!(renderer.notices().iter().all(|n| !n.contains("geometry")), "{:?}", renderer.notices());
    let picture = render_image(&mut renderer, [32, 24], &default_params(&small)).unwrap();
    assert!(picture.pixels().any(|p| p != background), "the wall and the floor drawn");
}

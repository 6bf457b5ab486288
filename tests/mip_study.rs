//! The mip-filter study (report::mip_study) on lavapipe at small size.

use bumpview::render::{Gpu, Renderer};
use bumpview::report::mip_study::{MipPlan, study};

fn renderer() -> Renderer {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("GPU tests need an adapter (install mesa-vulkan-drivers): {e}"));
    Renderer::from_gpu(&gpu)
}

#[test]
fn explore() {
    let mut renderer = renderer();
    let plan = MipPlan { minifications: vec![1, 4, 16, 64], ..MipPlan::quick() };
    let started = std::time::Instant::now();
    let out = study(&mut renderer, &plan, &mut || {}).unwrap();
    for r in &out.rows {
        println!("{r:?}");
    }
    for c in &out.convergence {
        println!("{c:?}");
    }
    println!("{:?}", started.elapsed());
}

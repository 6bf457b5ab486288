//! Cost of a probe pick (brute force over every drawn triangle) and of the readout at the
//! picked point, on the built-in scene and on the third-party meshes (spot, the largest, is
//! the bound the README quotes). The asset meshes are read through `BUMPVIEW_TEST_ASSETS`
//! (../shared/assets); set, a missing file fails the run; unset, only the built-in scene is
//! timed, with a notice. Run: `BUMPVIEW_TEST_ASSETS=../shared/assets cargo bench --bench probe_pick`.

use std::path::PathBuf;

use bumpview::frame::SceneOptions;
use bumpview::load::load_scene;
use bumpview::probe::ProbeScene;
use bumpview::scene::Scene;
use bumpview::scene::builtin::teaching_scene;
use bumpview::state::ViewerState;
use criterion::{Criterion, criterion_group, criterion_main};

const SIZE: [u32; 2] = [256, 256];
const MESHES: [&str; 4] = [
    "obj/spot/spot_triangulated.obj",
    "gltf/NormalTangentMirrorTest/glTF-Binary/NormalTangentMirrorTest.glb",
    "gltf/WaterBottle/glTF/WaterBottle.gltf",
    "gltf/Suzanne/glTF/Suzanne.gltf",
];

/// The built-in scene and, with `BUMPVIEW_TEST_ASSETS` set, each asset mesh.
fn scenes() -> Vec<(String, Scene)> {
    let mut scenes = vec![("built-in scene".to_owned(), teaching_scene())];
    match std::env::var_os("BUMPVIEW_TEST_ASSETS").map(PathBuf::from) {
        Some(base) => scenes.extend(MESHES.iter().map(|relative| {
            let path = base.join(relative);
            assert!(path.is_file(), "BUMPVIEW_TEST_ASSETS is set but {} is missing", path.display());
            (
                relative.rsplit('/').next().unwrap_or(relative).to_owned(),
                load_scene(&path).unwrap_or_else(|e| panic!("{e}")),
            )
        })),
        None => eprintln!("notice: BUMPVIEW_TEST_ASSETS is unset; timing the built-in scene only"),
    }
    scenes
}

fn pick(c: &mut Criterion) {
    let mut group = c.benchmark_group("probe");
    for (name, scene) in scenes() {
        let probe_scene = ProbeScene::new(&scene, &SceneOptions::default());
        let params = ViewerState::new(&scene).frame_params();
        // The pixel nearest the centre of the middle row where the mesh shows.
        let (pixel, point) = (0..SIZE[0] / 2)
            .flat_map(|d| [SIZE[0] / 2 - d, SIZE[0] / 2 + d])
            .find_map(|x| probe_scene.pick(&params.camera, SIZE, [x, SIZE[1] / 2]).map(|p| ([x, SIZE[1] / 2], p)))
            .unwrap_or_else(|| panic!("{name}: nothing on the middle row"));
        let triangles = probe_scene.triangle_count();
        group.bench_function(format!("pick, {name} ({triangles} triangles)"), |b| {
            b.iter(|| probe_scene.pick(&params.camera, SIZE, std::hint::black_box(pixel)))
        });
        group.bench_function(format!("readout, {name}"), |b| {
            b.iter(|| probe_scene.readout(std::hint::black_box(&point), &params, SIZE))
        });
    }
    group.finish();
}

criterion_group!(benches, pick);
criterion_main!(benches);

//! Mutation fuzzing on stable Rust (proptest): the glTF, OBJ and image loaders and the
//! tangent generators get seed files and meshes mutated at random, and must answer with a
//! scene or an error — never a panic, never a loaded scene with non-finite data (supplied
//! tangents included) or an index out of range, never a non-finite frame. Failing inputs are kept by proptest in `tests/fuzz.proptest-regressions`
//! and replayed first on every run.
//!
//! The case count per target is `BUMPVIEW_FUZZ_CASES` (default 256, quick enough for CI);
//! run long with e.g. `BUMPVIEW_FUZZ_CASES=100000 cargo test --release --test fuzz`.

mod common;

use std::path::{Path, PathBuf};

use base64::Engine;
use bumpview::load::{image::decode_texture, load_scene};
use bumpview::names::Named;
use bumpview::scene::{Mesh, Scene, TextureKind};
use bumpview::tangent::{TangentMethod, tangents};
use glam::{Vec2, Vec3};
use proptest::prelude::*;

/// A tiny glTF: one triangle with positions, normals and UVs in a base64 buffer.
fn seed_gltf() -> String {
    let floats: [f32; 24] = [
        0., 0., 0., 1., 0., 0., 0., 1., 0., // positions
        0., 0., 1., 0., 0., 1., 0., 0., 1., // normals
        0., 1., 1., 1., 0., 0., // uvs
    ];
    let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
    let data = base64::engine::general_purpose::STANDARD.encode(&bytes);
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}}}}]}}],
"buffers":[{{"byteLength":96,"uri":"data:application/octet-stream;base64,{data}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":36}},{{"buffer":0,"byteOffset":72,"byteLength":24}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"}},{{"bufferView":2,"componentType":5126,"count":3,"type":"VEC2"}}]}}"#
    )
}

const SEED_OBJ: &str =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1 4/4/1\n";

/// Seeds from the repository's fixtures (tests/fixtures); each must exist.
fn asset_seeds(relative: &[&str]) -> Vec<(String, Vec<u8>)> {
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    relative
        .iter()
        .map(|r| {
            let path = base.join(r);
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
        })
        .collect()
}

fn mesh_seeds() -> Vec<(String, Vec<u8>)> {
    let mut seeds = vec![("seed.gltf".to_owned(), seed_gltf().into_bytes()), ("seed.obj".to_owned(), SEED_OBJ.into())];
    seeds.extend(asset_seeds(&[
        "gltf/Box/glTF-Binary/Box.glb",
        "gltf/BoxTextured/glTF-Binary/BoxTextured.glb",
        "obj/learn-wgpu-cube/cube.obj",
    ]));
    seeds
}

fn image_seeds() -> Vec<Vec<u8>> {
    let image = image::RgbaImage::from_fn(4, 3, |x, y| image::Rgba([x as u8 * 60, y as u8 * 80, 200, 255]));
    let mut png = vec![];
    image.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
    let mut seeds = vec![png];
    seeds.extend(asset_seeds(&["obj/learn-wgpu-cube/cube-normal.png"]).into_iter().map(|(_, b)| b));
    seeds
}

/// One edit of a byte string.
#[derive(Debug, Clone)]
enum Mutation {
    Flip { at: usize, value: u8 },
    Truncate { at: usize },
    Delete { at: usize, len: usize },
    Insert { at: usize, token: &'static str },
}

/// Tokens that trip parsers: numbers at the edge of f32, broken JSON, odd OBJ indices.
const TOKENS: &[&str] = &[
    "nan",
    "-nan",
    "inf",
    "1e39",
    "-1e39",
    "1e-45",
    "0",
    "-1",
    "-999999",
    "4294967295",
    "}",
    "{",
    "\"",
    ",",
    "[",
    "]",
    ":",
    "f 1 2",
    "v",
    "/",
    "\n",
    "\0",
    "null",
    "\"uri\":\"x.bin\"",
    "\"byteOffset\":99999999",
];

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(at, value)| Mutation::Flip { at, value }),
        any::<usize>().prop_map(|at| Mutation::Truncate { at }),
        (any::<usize>(), 1usize..64).prop_map(|(at, len)| Mutation::Delete { at, len }),
        (any::<usize>(), prop::sample::select(TOKENS)).prop_map(|(at, token)| Mutation::Insert { at, token }),
    ]
}

fn mutate(mut bytes: Vec<u8>, mutations: &[Mutation]) -> Vec<u8> {
    for m in mutations {
        let n = bytes.len().max(1);
        match *m {
            Mutation::Flip { at, value } if !bytes.is_empty() => bytes[at % n] = value,
            Mutation::Flip { .. } => {}
            Mutation::Truncate { at } => bytes.truncate(at % n),
            Mutation::Delete { at, len } => {
                let start = at % n;
                bytes.drain(start..(start + len).min(bytes.len()));
            }
            Mutation::Insert { at, token } => {
                let at = at % (bytes.len() + 1);
                bytes.splice(at..at, token.bytes());
            }
        }
    }
    bytes
}

/// A loaded scene is sane ([`common::assert_sane`]: finite positions, normals, UVs and
/// supplied tangents, consistent attribute counts, indices in range).
fn assert_sane(scene: &Scene, path: &Path) {
    common::assert_sane(scene, &path.display().to_string());
}

/// The sanity check can fail: a NaN supplied tangent, an index past the vertices, an
/// infinite UV or a UV count that does not match each make it panic.
#[test]
fn the_sanity_check_rejects_insane_scenes() {
    let mut good = bumpview::scene::builtin::teaching_scene();
    good.meshes[0].tangents = good.meshes[0].analytic_tangents.clone();
    common::assert_sane(&good, "the built-in scene");
    type Spoil = fn(&mut Mesh);
    let breaks: [(&str, Spoil); 4] = [
        ("NaN tangent", |m| m.tangents.as_mut().unwrap()[3].x = f32::NAN),
        ("index out of range", |m| m.indices[5] = m.positions.len() as u32),
        ("infinite UV", |m| m.uvs[2].y = f32::INFINITY),
        ("a UV short", |m| _ = m.uvs.pop()),
    ];
    for (what, spoil) in breaks {
        let mut scene = good.clone();
        spoil(&mut scene.meshes[0]);
        let caught = std::panic::catch_unwind(|| common::assert_sane(&scene, what));
        assert!(caught.is_err(), "{what} passed the sanity check");
    }
}

fn scratch_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-fuzz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

proptest! {
    #![proptest_config(common::fuzz_config())]

    /// glTF, GLB and OBJ: any mutation of a seed loads or fails with an error, no panic.
    #[test]
    fn mesh_loaders_never_panic(seed in any::<prop::sample::Index>(), mutations in prop::collection::vec(mutation(), 1..6)) {
        let seeds = mesh_seeds();
        let (name, bytes) = &seeds[seed.index(seeds.len())];
        let path = scratch_dir().join(name);
        std::fs::write(&path, mutate(bytes.clone(), &mutations)).unwrap();
        if let Ok(scene) = load_scene(&path) {
            assert_sane(&scene, &path);
        }
    }

    /// Images: any mutation of a PNG decodes or fails with an error, no panic.
    #[test]
    fn image_loader_never_panics(seed in any::<prop::sample::Index>(), mutations in prop::collection::vec(mutation(), 1..6)) {
        let seeds = image_seeds();
        let bytes = mutate(seeds[seed.index(seeds.len())].clone(), &mutations);
        if let Ok(texture) = decode_texture(&bytes, Path::new("fuzz.png"), TextureKind::NormalMap) {
            prop_assert_eq!(texture.rgba.len(), (texture.width * texture.height * 4) as usize);
        }
    }

    /// Tangent generators on random small meshes with extreme and non-finite values: every
    /// method returns one finite frame per vertex.
    #[test]
    fn tangent_generators_stay_finite(
        vertices in prop::collection::vec((extreme_vec3(), extreme_vec3(), (extreme_f32(), extreme_f32())), 3..24),
        triangles in prop::collection::vec((any::<prop::sample::Index>(), any::<prop::sample::Index>(), any::<prop::sample::Index>()), 1..24),
    ) {
        let mut mesh = Mesh::empty("fuzz");
        for (p, n, (u, v)) in &vertices {
            mesh.positions.push(*p);
            mesh.normals.push(*n);
            mesh.uvs.push(Vec2::new(*u, *v));
        }
        let count = vertices.len();
        mesh.indices = triangles.iter().flat_map(|(a, b, c)| [a.index(count), b.index(count), c.index(count)].map(|i| i as u32)).collect();
        for method in TangentMethod::all().iter().copied().filter(|m| m.is_generated()) {
            let mesh = if method == TangentMethod::PerFace { mesh.unwelded() } else { mesh.clone() };
            let frames = tangents(&mesh, method).unwrap();
            prop_assert_eq!(frames.len(), mesh.positions.len());
            prop_assert!(frames.iter().all(|t| t.is_finite() && (t.w == 1.0 || t.w == -1.0)), "{:?}: {:?}", method, frames);
        }
    }
}

fn extreme_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -2.0f32..2.0,
        1 => prop::sample::select(vec![0.0, -0.0, 1e-38, -1e-38, 1e38, -1e38, f32::MAX, f32::MIN_POSITIVE, f32::NAN, f32::INFINITY, f32::NEG_INFINITY]),
    ]
}

fn extreme_vec3() -> impl Strategy<Value = Vec3> {
    (extreme_f32(), extreme_f32(), extreme_f32()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

//! Accessor rewiring: glTF files whose primitives point their attributes and indices at
//! accessors of any component type, normalisation, type, count, offset and buffer view
//! (strided or not, inside or past the buffer), dense or sparse, must load sanely or fail with
//! a one-line error — never panic (the `gltf` crate's readers hit `unreachable!` on an index
//! accessor of floats or signed integers, and overflow on a count of 0). Proptest keeps
//! failing cases in `tests/fuzz_accessors.proptest-regressions`; the case count is
//! `BUMPVIEW_FUZZ_CASES` (default 256, about a second).

mod common;

use std::path::PathBuf;

use base64::Engine;
use bumpview::load::load_scene;
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence};

fn config() -> Config {
    let cases = std::env::var("BUMPVIEW_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(256);
    Config {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource("proptest-regressions"))),
        ..Config::default()
    }
}

/// glTF's component types, and two it does not define.
const COMPONENT_TYPES: [u32; 8] = [5120, 5121, 5122, 5123, 5125, 5126, 5124, 0];
const TYPES: [&str; 5] = ["SCALAR", "VEC2", "VEC3", "VEC4", "MAT2"];

#[derive(Debug, Clone)]
struct View {
    offset: u64,
    length: u64,
    stride: Option<u64>,
}

#[derive(Debug, Clone)]
struct Sparse {
    count: u64,
    indices: (usize, u64, u32),
    values: (usize, u64),
}

#[derive(Debug, Clone)]
struct Accessor {
    view: Option<usize>,
    offset: u64,
    component: u32,
    normalized: bool,
    count: u64,
    kind: &'static str,
    sparse: Option<Sparse>,
}

/// Which accessor each attribute and the indices read (`None`: absent), and the mode.
#[derive(Debug, Clone)]
struct Wiring {
    position: usize,
    normal: Option<usize>,
    texcoord: Option<usize>,
    tangent: Option<usize>,
    indices: Option<usize>,
    mode: u32,
}

/// The buffer: 64 floats from 0 to 1 (so positions and UVs read as floats are sane), some
/// bytes overwritten.
fn buffer(flips: &[(usize, u8)]) -> Vec<u8> {
    let mut bytes: Vec<u8> = (0..64).flat_map(|i| (i as f32 / 64.0).to_le_bytes()).collect();
    for &(at, value) in flips {
        let n = bytes.len();
        bytes[at % n] = value;
    }
    bytes
}

fn document(views: &[View], accessors: &[Accessor], wiring: &Wiring, bytes: &[u8]) -> String {
    let data = base64::engine::general_purpose::STANDARD.encode(bytes);
    let views: Vec<String> = views
        .iter()
        .map(|v| {
            let stride = v.stride.map_or(String::new(), |s| format!(r#","byteStride":{s}"#));
            format!(r#"{{"buffer":0,"byteOffset":{},"byteLength":{}{stride}}}"#, v.offset, v.length)
        })
        .collect();
    let accessors: Vec<String> = accessors
        .iter()
        .map(|a| {
            let view = a.view.map_or(String::new(), |v| format!(r#""bufferView":{v},"#));
            let sparse = a.sparse.as_ref().map_or(String::new(), |s| {
                format!(
                    r#","sparse":{{"count":{},"indices":{{"bufferView":{},"byteOffset":{},"componentType":{}}},"values":{{"bufferView":{},"byteOffset":{}}}}}"#,
                    s.count, s.indices.0, s.indices.1, s.indices.2, s.values.0, s.values.1
                )
            });
            format!(
                r#"{{{view}"byteOffset":{},"componentType":{},"normalized":{},"count":{},"type":"{}","min":[0,0,0],"max":[1,1,1]{sparse}}}"#,
                a.offset, a.component, a.normalized, a.count, a.kind
            )
        })
        .collect();
    let mut attributes = vec![format!(r#""POSITION":{}"#, wiring.position)];
    let optional = [("NORMAL", wiring.normal), ("TEXCOORD_0", wiring.texcoord), ("TANGENT", wiring.tangent)];
    attributes.extend(optional.iter().filter_map(|(name, a)| a.map(|a| format!(r#""{name}":{a}"#))));
    let indices = wiring.indices.map_or(String::new(), |i| format!(r#","indices":{i}"#));
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{{}}}{indices},"mode":{}}}]}}],
"buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{data}"}}],
"bufferViews":[{}],"accessors":[{}]}}"#,
        attributes.join(","),
        wiring.mode,
        bytes.len(),
        views.join(","),
        accessors.join(",")
    )
}

fn offset() -> impl Strategy<Value = u64> {
    prop_oneof![4 => (0u64..64).prop_map(|o| o * 4), 2 => 0u64..300, 1 => Just(u64::MAX / 2)]
}

fn view() -> impl Strategy<Value = View> {
    let stride =
        prop::sample::select(vec![None, None, Some(4), Some(8), Some(12), Some(16), Some(24), Some(252), Some(0)]);
    (offset(), prop_oneof![3 => 0u64..260, 1 => Just(u64::MAX / 2)], stride).prop_map(|(offset, length, stride)| View {
        offset,
        length,
        stride,
    })
}

fn count() -> impl Strategy<Value = u64> {
    prop_oneof![8 => 0u64..24, 1 => Just(1u64 << 40), 1 => Just(u64::from(u32::MAX))]
}

fn sparse(views: usize) -> impl Strategy<Value = Sparse> {
    (count(), (0..views, offset(), prop::sample::select(COMPONENT_TYPES.to_vec())), (0..views, offset()))
        .prop_map(|(count, indices, values)| Sparse { count, indices, values })
}

fn accessor(views: usize) -> impl Strategy<Value = Accessor> {
    (
        prop::option::weighted(0.9, 0..views),
        prop_oneof![3 => Just(0u64), 1 => offset()],
        prop::sample::select(COMPONENT_TYPES.to_vec()),
        any::<bool>(),
        count(),
        prop::sample::select(TYPES.to_vec()),
        prop::option::weighted(0.2, sparse(views)),
    )
        .prop_map(|(view, offset, component, normalized, count, kind, sparse)| Accessor {
            view,
            offset,
            component,
            normalized,
            count,
            kind,
            sparse,
        })
}

fn wiring(accessors: usize) -> impl Strategy<Value = Wiring> {
    let some = move || prop::option::of(0..accessors);
    (0..accessors, some(), some(), some(), some(), prop::sample::select(vec![4u32, 4, 5, 6, 0])).prop_map(
        |(position, normal, texcoord, tangent, indices, mode)| Wiring {
            position,
            normal,
            texcoord,
            tangent,
            indices,
            mode,
        },
    )
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-fuzz-accessors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn rewired() -> impl Strategy<Value = (Vec<View>, Vec<Accessor>, Wiring, Vec<(usize, u8)>)> {
    prop::collection::vec(view(), 1..4).prop_flat_map(|views| {
        let n = views.len();
        prop::collection::vec(accessor(n), 1..6).prop_flat_map(move |accessors| {
            let m = accessors.len();
            (
                Just(views.clone()),
                Just(accessors),
                wiring(m),
                prop::collection::vec((any::<usize>(), any::<u8>()), 0..4),
            )
        })
    })
}

proptest! {
    #![proptest_config(config())]

    /// Any rewiring loads a sane scene or fails with one line; nothing panics.
    #[test]
    fn rewired_accessors_load_or_fail_on_one_line((views, accessors, wiring, flips) in rewired()) {
        let path = scratch("rewired.gltf");
        std::fs::write(&path, document(&views, &accessors, &wiring, &buffer(&flips))).unwrap();
        match load_scene(&path) {
            Ok(scene) => common::assert_sane(&scene, &path.display().to_string()),
            Err(e) => prop_assert!(!e.to_string().contains('\n'), "{}", e),
        }
    }
}

/// One triangle: 3 float positions (accessor 0) and indices 0, 1, 2 as accessor 1 of
/// `component` type and type `kind`.
fn triangle_with_indices(component: u32, kind: &'static str, normalized: bool) -> String {
    let positions =
        Accessor { view: Some(0), offset: 0, component: 5126, normalized: false, count: 3, kind: "VEC3", sparse: None };
    let indices = Accessor { view: Some(1), offset: 0, component, normalized, count: 3, kind, sparse: None };
    let mut bytes: Vec<u8> = [0., 0., 0., 1., 0., 0., 0., 1., 0.].iter().flat_map(|f: &f32| f.to_le_bytes()).collect();
    let index_bytes: Vec<u8> = match component {
        5120 | 5121 => vec![0, 1, 2, 0],
        5122 | 5123 => [0u16, 1, 2, 0].iter().flat_map(|i| i.to_le_bytes()).collect(),
        5126 => [0f32, 1., 2.].iter().flat_map(|i| i.to_le_bytes()).collect(),
        _ => [0u32, 1, 2].iter().flat_map(|i| i.to_le_bytes()).collect(),
    };
    let length = index_bytes.len() as u64;
    bytes.extend(index_bytes);
    let views = [View { offset: 0, length: 36, stride: None }, View { offset: 36, length, stride: None }];
    let wiring = Wiring { position: 0, normal: None, texcoord: None, tangent: None, indices: Some(1), mode: 4 };
    document(&views, &[positions, indices], &wiring, &bytes)
}

/// An index accessor of floats, signed bytes or signed shorts (which the `gltf` crate's
/// reader meets with `unreachable!`), of a vector type, or normalised, is refused on one line
/// naming the primitive and the accessor; unsigned bytes, shorts and ints load.
#[test]
fn index_accessors_gltf_forbids_are_refused_naming_primitive_and_accessor() {
    let path = scratch("indices.gltf");
    for (component, kind, normalized, expected) in [
        (
            5126,
            "SCALAR",
            false,
            "mesh #0: index accessor 1 has component type F32, which glTF does not allow for indices",
        ),
        (
            5120,
            "SCALAR",
            false,
            "mesh #0: index accessor 1 has component type I8, which glTF does not allow for indices",
        ),
        (
            5122,
            "SCALAR",
            false,
            "mesh #0: index accessor 1 has component type I16, which glTF does not allow for indices",
        ),
        (
            5121,
            "SCALAR",
            true,
            "mesh #0: index accessor 1 has normalised component type U8, which glTF does not allow for indices",
        ),
        (5125, "VEC3", false, "mesh #0: index accessor 1 has 3 components per element, 1 expected"),
    ] {
        std::fs::write(&path, triangle_with_indices(component, kind, normalized)).unwrap();
        let message = load_scene(&path).map(|_| ()).unwrap_err().to_string();
        assert_eq!(message, format!("{}: {expected}", path.display()));
    }
    for component in [5121, 5123, 5125] {
        std::fs::write(&path, triangle_with_indices(component, "SCALAR", false)).unwrap();
        let scene = load_scene(&path).unwrap_or_else(|e| panic!("{component}: {e}"));
        assert_eq!(scene.meshes[0].indices, [0, 1, 2], "{component}");
    }
}

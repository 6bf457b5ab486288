//! Accessor rewiring: glTF files whose primitives point their attributes and indices at
//! accessors of any component type, normalisation, type, count, offset and buffer view
//! (strided or not, inside or past the buffer), dense or sparse — random documents, and a
//! valid triangle with a few such edits — must load sanely or fail with a one-line error — never panic (the `gltf` crate's readers hit `unreachable!` on an index
//! accessor of floats or signed integers, and overflow on a count of 0). Proptest keeps
//! failing cases in `tests/fuzz_accessors.proptest-regressions`; the case count is
//! `BUMPVIEW_FUZZ_CASES` (default 256, about a second).

mod common;

use std::path::PathBuf;

use base64::Engine;
use bumpview::load::load_scene;
use proptest::prelude::*;

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

/// A random document: views, accessors, what the primitive reads, and bytes to overwrite.
type Document = (Vec<View>, Vec<Accessor>, Wiring, Vec<(usize, u8)>);

fn rewired() -> impl Strategy<Value = Document> {
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

/// A valid triangle, one accessor per buffer view: POSITION (0), NORMAL (1), TEXCOORD_0 (2),
/// indices as unsigned shorts (3), TANGENT (4), and two scalar accessors no primitive reads,
/// floats 0, 1, 2 (5) and signed bytes 0, 1, 2 (6): rewiring indices to these is what made the
/// `gltf` crate's index reader panic.
fn valid_triangle() -> (Vec<View>, Vec<Accessor>, Wiring, Vec<u8>) {
    let floats = |values: &[f32]| values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>();
    let parts: [(Vec<u8>, u32, &'static str); 7] = [
        (floats(&[0., 0., 0., 1., 0., 0., 0., 1., 0.]), 5126, "VEC3"),
        (floats(&[0., 0., 1., 0., 0., 1., 0., 0., 1.]), 5126, "VEC3"),
        (floats(&[0., 1., 1., 1., 0., 0.]), 5126, "VEC2"),
        (vec![0, 0, 1, 0, 2, 0, 0, 0], 5123, "SCALAR"),
        (floats(&[1., 0., 0., 1., 1., 0., 0., 1., 1., 0., 0., 1.]), 5126, "VEC4"),
        (floats(&[0., 1., 2.]), 5126, "SCALAR"),
        (vec![0, 1, 2, 0], 5120, "SCALAR"),
    ];
    let (mut views, mut accessors, mut bytes) = (vec![], vec![], vec![]);
    for (i, (data, component, kind)) in parts.into_iter().enumerate() {
        views.push(View { offset: bytes.len() as u64, length: data.len() as u64, stride: None });
        accessors.push(Accessor {
            view: Some(i),
            offset: 0,
            component,
            normalized: false,
            count: 3,
            kind,
            sparse: None,
        });
        bytes.extend(data);
    }
    let wiring =
        Wiring { position: 0, normal: Some(1), texcoord: Some(2), tangent: Some(4), indices: Some(3), mode: 4 };
    (views, accessors, wiring, bytes)
}

/// One change to a document: an accessor's fields, a view's, or what a role reads.
#[derive(Debug, Clone)]
enum Edit {
    ComponentType(prop::sample::Index, u32),
    Normalized(prop::sample::Index, bool),
    Count(prop::sample::Index, u64),
    Offset(prop::sample::Index, u64),
    Kind(prop::sample::Index, &'static str),
    View(prop::sample::Index, Option<prop::sample::Index>),
    Sparse(prop::sample::Index, Sparse),
    Stride(prop::sample::Index, Option<u64>),
    ViewOffset(prop::sample::Index, u64),
    ViewLength(prop::sample::Index, u64),
    /// Role 0 POSITION, 1 NORMAL, 2 TEXCOORD_0, 3 TANGENT, 4 indices.
    Rewire(usize, Option<prop::sample::Index>),
    Mode(u32),
}

fn edit() -> impl Strategy<Value = Edit> {
    let at = any::<prop::sample::Index>;
    let strides = vec![None, Some(0), Some(4), Some(8), Some(12), Some(16), Some(252)];
    prop_oneof![
        1 => (at(), prop::sample::select(COMPONENT_TYPES.to_vec())).prop_map(|(a, c)| Edit::ComponentType(a, c)),
        1 => (at(), any::<bool>()).prop_map(|(a, n)| Edit::Normalized(a, n)),
        1 => (at(), count()).prop_map(|(a, c)| Edit::Count(a, c)),
        1 => (at(), offset()).prop_map(|(a, o)| Edit::Offset(a, o)),
        1 => (at(), prop::sample::select(TYPES.to_vec())).prop_map(|(a, k)| Edit::Kind(a, k)),
        1 => (at(), prop::option::of(at())).prop_map(|(a, v)| Edit::View(a, v)),
        1 => (at(), sparse(7)).prop_map(|(a, s)| Edit::Sparse(a, s)),
        1 => (at(), prop::sample::select(strides)).prop_map(|(v, s)| Edit::Stride(v, s)),
        1 => (at(), offset()).prop_map(|(v, o)| Edit::ViewOffset(v, o)),
        1 => (at(), prop_oneof![0u64..200, Just(u64::MAX / 2)]).prop_map(|(v, l)| Edit::ViewLength(v, l)),
        3 => (0usize..5, prop::option::weighted(0.9, at())).prop_map(|(r, a)| Edit::Rewire(r, a)),
        1 => prop::sample::select(vec![0u32, 4, 5, 6]).prop_map(Edit::Mode),
    ]
}

fn apply(views: &mut [View], accessors: &mut [Accessor], wiring: &mut Wiring, edit: &Edit) {
    let (n, m) = (accessors.len(), views.len());
    match edit {
        Edit::ComponentType(a, c) => accessors[a.index(n)].component = *c,
        Edit::Normalized(a, b) => accessors[a.index(n)].normalized = *b,
        Edit::Count(a, c) => accessors[a.index(n)].count = *c,
        Edit::Offset(a, o) => accessors[a.index(n)].offset = *o,
        Edit::Kind(a, k) => accessors[a.index(n)].kind = k,
        Edit::View(a, v) => accessors[a.index(n)].view = v.map(|v| v.index(m)),
        Edit::Sparse(a, s) => accessors[a.index(n)].sparse = Some(s.clone()),
        Edit::Stride(v, s) => views[v.index(m)].stride = *s,
        Edit::ViewOffset(v, o) => views[v.index(m)].offset = *o,
        Edit::ViewLength(v, l) => views[v.index(m)].length = *l,
        Edit::Rewire(role, a) => {
            let a = a.as_ref().map(|a| a.index(n));
            match role {
                0 => wiring.position = a.unwrap_or(0),
                1 => wiring.normal = a,
                2 => wiring.texcoord = a,
                3 => wiring.tangent = a,
                _ => wiring.indices = a,
            }
        }
        Edit::Mode(mode) => wiring.mode = *mode,
    }
}

proptest! {
    #![proptest_config(common::fuzz_config())]

    /// A valid triangle with a few accessors, views or roles changed (an attribute or the
    /// indices pointed at another accessor, a component type, count, offset, stride or
    /// sparse block changed) loads a sane scene or fails with one line; nothing panics.
    #[test]
    fn edited_accessors_of_a_valid_triangle_load_or_fail_on_one_line(edits in prop::collection::vec(edit(), 1..4)) {
        let (mut views, mut accessors, mut wiring, bytes) = valid_triangle();
        for edit in &edits {
            apply(&mut views, &mut accessors, &mut wiring, edit);
        }
        let path = scratch("edited.gltf");
        std::fs::write(&path, document(&views, &accessors, &wiring, &bytes)).unwrap();
        match load_scene(&path) {
            Ok(scene) => common::assert_sane(&scene, &path.display().to_string()),
            Err(e) => prop_assert!(!e.to_string().contains('\n'), "{}", e),
        }
    }

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

/// A sparse accessor without a bufferView is `count` zeros under its sparse values: 2^40 of
/// them (4 TiB once read as floats) are refused from the JSON, before anything is allocated.
#[test]
fn a_sparse_accessor_without_a_view_is_bounded() {
    let path = scratch("sparse.gltf");
    let positions = Accessor {
        view: None,
        offset: 0,
        component: 5126,
        normalized: false,
        count: 1 << 40,
        kind: "VEC3",
        sparse: Some(Sparse { count: 1, indices: (1, 0, 5121), values: (0, 0) }),
    };
    let mut bytes: Vec<u8> = [0f32, 1., 0.].iter().flat_map(|f| f.to_le_bytes()).collect();
    bytes.extend([0, 0, 0, 0]);
    let views = [View { offset: 0, length: 12, stride: None }, View { offset: 12, length: 1, stride: None }];
    let wiring = Wiring { position: 0, normal: None, texcoord: None, tangent: None, indices: None, mode: 4 };
    std::fs::write(&path, document(&views, &[positions], &wiring, &bytes)).unwrap();
    let message = load_scene(&path).map(|_| ()).unwrap_err().to_string();
    let problem = "has 1099511627776 elements and no bufferView: more than the 1024 MiB a buffer may hold once read";
    assert_eq!(message, format!("{}: mesh #0: accessor 0 (Positions) {problem}", path.display()));
}

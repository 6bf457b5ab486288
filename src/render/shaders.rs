//! The WGSL sources, split by pass, and the shader modules assembled from them: each module is
//! the concatenation of its files (WGSL declarations may come in any order), embedded at build
//! time. The mesh pass is assembled twice, once per stage interface: its entry points are
//! written once over `Varyings`, which `mesh_varyings.wgsl` makes the plain `VertexOutput` and
//! `mesh_varyings_per_vertex.wgsl` the same plus the per-vertex light direction and half
//! vector ([`MESH_PER_VERTEX`]); and twice more for LEAN's pipelines, with LEAN's texture
//! bound ([`MESH_LEAN`], [`MESH_LEAN_PER_VERTEX`]).

/// One shader module: its label and its files (name, text) in order.
#[derive(Debug, Clone, Copy)]
pub struct Wgsl {
    pub label: &'static str,
    pub files: &'static [(&'static str, &'static str)],
}

/// Put before every module: texture samples under non-uniform control flow (the mesh pass's
/// `textureSample` calls inside view and material branches) are accepted, as naga accepts them.
/// Browsers' WebGPU compilers (Chromium's Tint) refuse such a module without it; the shaders'
/// own fix is to sample before branching or with explicit gradients.
pub const DIRECTIVES: &str = "diagnostic(off, derivative_uniformity);\n";

impl Wgsl {
    /// The module's source: [`DIRECTIVES`], then its files one after the other.
    pub fn source(&self) -> String {
        std::iter::once(DIRECTIVES).chain(self.files.iter().map(|(_, text)| *text)).collect()
    }
}

/// `("NAME", the text of shaders/NAME)`.
macro_rules! wgsl_file {
    ($name:literal) => {
        ($name, include_str!(concat!("../../shaders/", $name)))
    };
}

/// The Frame uniform (group 0), shared by every pass but the floor.
const FRAME: (&str, &str) = wgsl_file!("frame.wgsl");
/// The object uniform, the material's textures (group 1), the vertex transform and the
/// helpers every pass drawing a mesh shares.
const MESH_COMMON: [(&str, &str); 2] = [wgsl_file!("object.wgsl"), wgsl_file!("common.wgsl")];

/// The mesh pass's files followed by `$varyings`, its stage interface.
macro_rules! mesh_files {
    ($varyings:literal) => {
        mesh_files!($varyings, "lean_unbound.wgsl")
    };
    ($varyings:literal, $lean:literal) => {
        &[
            FRAME,
            MESH_COMMON[0],
            MESH_COMMON[1],
            wgsl_file!("normal_map.wgsl"),
            wgsl_file!("detail.wgsl"),
            wgsl_file!("mip_filter.wgsl"),
            wgsl_file!($lean),
            wgsl_file!("surface_color.wgsl"),
            wgsl_file!("pbr.wgsl"),
            wgsl_file!("parallax.wgsl"),
            wgsl_file!("mistakes.wgsl"),
            wgsl_file!("legacy.wgsl"),
            wgsl_file!("lights.wgsl"),
            wgsl_file!("mesh.wgsl"),
            wgsl_file!($varyings),
        ]
    };
}

/// The mesh pass: every mesh variant, view and shading model (mesh.wgsl's entry points).
pub const MESH: Wgsl = Wgsl { label: "mesh", files: mesh_files!("mesh_varyings.wgsl") };
/// The mesh pass with the per-vertex vectors between its stages: the same entry points, for the
/// legacy looks and the per-vertex mistakes.
pub const MESH_PER_VERTEX: Wgsl =
    Wgsl { label: "mesh (per-vertex vectors)", files: mesh_files!("mesh_varyings_per_vertex.wgsl") };
/// The mesh pass of LEAN's pipelines: LEAN's texture bound in group 2 (lean.wgsl).
pub const MESH_LEAN: Wgsl = Wgsl { label: "mesh (LEAN)", files: mesh_files!("mesh_varyings.wgsl", "lean.wgsl") };
/// LEAN's mesh pass with the per-vertex vectors, for the legacy looks and the per-vertex
/// mistakes.
pub const MESH_LEAN_PER_VERTEX: Wgsl =
    Wgsl { label: "mesh (LEAN, per-vertex vectors)", files: mesh_files!("mesh_varyings_per_vertex.wgsl", "lean.wgsl") };
/// The Difference view of a mesh with frames against its reference frames.
pub const DIFFERENCE: Wgsl =
    Wgsl { label: "difference", files: &[FRAME, MESH_COMMON[0], MESH_COMMON[1], wgsl_file!("difference.wgsl")] };
/// The wireframe overlay.
pub const WIREFRAME: Wgsl =
    Wgsl { label: "wireframe", files: &[FRAME, MESH_COMMON[0], MESH_COMMON[1], wgsl_file!("wireframe.wgsl")] };
/// The T/B/N glyphs.
pub const GLYPHS: Wgsl =
    Wgsl { label: "glyphs", files: &[FRAME, MESH_COMMON[0], MESH_COMMON[1], wgsl_file!("glyphs.wgsl")] };
/// The light markers.
pub const MARKER: Wgsl = Wgsl { label: "marker", files: &[FRAME, wgsl_file!("marker.wgsl")] };
/// The adapter's floor ([`super::floor`]).
pub const FLOOR: Wgsl = Wgsl { label: "floor", files: &[wgsl_file!("floor.wgsl")] };

/// GPU displacement's compute pass ([`super::tessellation`]): common.wgsl's helpers, its own
/// bindings in group 2 (the frame's and the object's, declared before it, unused).
pub const DISPLACE: Wgsl =
    Wgsl { label: "displace", files: &[FRAME, MESH_COMMON[0], MESH_COMMON[1], wgsl_file!("displace.wgsl")] };

/// Every module, with the entry points the pipelines name in it.
pub const ALL: [(Wgsl, &[&str]); 10] = [
    (MESH, &MESH_ENTRY_POINTS),
    (MESH_PER_VERTEX, &MESH_ENTRY_POINTS),
    (MESH_LEAN, &MESH_ENTRY_POINTS),
    (MESH_LEAN_PER_VERTEX, &MESH_ENTRY_POINTS),
    (DIFFERENCE, &["vs_difference", "fs_difference"]),
    (WIREFRAME, &["vs_wireframe", "fs_wireframe"]),
    (GLYPHS, &["vs_glyph", "fs_glyph"]),
    (MARKER, &["vs_marker", "fs_marker"]),
    (FLOOR, &["vs_floor", "fs_floor"]),
    (DISPLACE, &["cs_vertices", "cs_triangles"]),
];

/// The mesh pass's entry points, the same in each of its modules.
const MESH_ENTRY_POINTS: [&str; 7] =
    ["vs_plain", "vs_tangent", "fs_plain", "fs_tangent", "fs_normal_mapped", "fs_object_space", "fs_height_bump"];

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use wgpu::naga;

    use super::*;

    fn parse(wgsl: &Wgsl) -> naga::Module {
        let source = wgsl.source();
        naga::front::wgsl::parse_str(&source)
            .unwrap_or_else(|e| panic!("{}: {}", wgsl.label, e.emit_to_string(&source)))
    }

    /// Every module parses and validates with naga, no GPU needed, and has exactly the entry
    /// points the pipelines name; every file under shaders/ is part of a module, so each is
    /// validated (a file no module includes fails here).
    #[test]
    fn every_wgsl_file_validates_in_a_module_with_its_entry_points() {
        let mut included = BTreeSet::new();
        for (wgsl, entry_points) in ALL {
            let module = parse(&wgsl);
            let source = wgsl.source();
            naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
                .validate(&module)
                .unwrap_or_else(|e| panic!("{}: {}", wgsl.label, e.emit_to_string(&source)));
            let names: BTreeSet<&str> = module.entry_points.iter().map(|e| e.name.as_str()).collect();
            assert_eq!(names, entry_points.iter().copied().collect(), "{}", wgsl.label);
            included.extend(wgsl.files.iter().map(|(name, _)| name.to_string()));
        }
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let on_disk: BTreeSet<String> = std::fs::read_dir(&dir)
            .expect("shaders/ is readable")
            .map(|entry| entry.expect("a directory entry").file_name().to_string_lossy().into_owned())
            .filter(|name| name.ends_with(".wgsl"))
            .collect();
        assert_eq!(included, on_disk, "the files of the modules against shaders/");
    }

    /// The mesh pass's pipeline constants, each declared once (in the file of its step), so the
    /// pipelines can set them; every module of the mesh pass has the same.
    #[test]
    fn the_mesh_pass_has_the_pipeline_constants() {
        let overrides = |wgsl: &Wgsl| -> BTreeSet<String> {
            parse(wgsl).overrides.iter().filter_map(|(_, o)| o.name.clone()).collect()
        };
        let expected = [
            "DETAIL_BLEND",
            "LEGACY",
            "LIGHTING_SPACE",
            "MATERIAL_FEATURES",
            "MIP_FILTER",
            "MISTAKE",
            "PARALLAX",
            "PARALLAX_SHADOWS",
            "SHADING_MODEL",
            "TARGET_ENCODES_SRGB",
            "VIEW",
        ];
        assert_eq!(overrides(&MESH), expected.iter().map(|s| s.to_string()).collect());
        assert_eq!(overrides(&MESH_PER_VERTEX), overrides(&MESH));
        assert_eq!(overrides(&MESH_LEAN), overrides(&MESH));
        assert_eq!(overrides(&MESH_LEAN_PER_VERTEX), overrides(&MESH));
        for wgsl in [DIFFERENCE, WIREFRAME, GLYPHS] {
            assert_eq!(overrides(&wgsl), BTreeSet::from(["TARGET_ENCODES_SRGB".to_string()]), "{}", wgsl.label);
        }
    }

    /// Only the per-vertex interface passes the light direction and half vector on: the plain
    /// mesh pass's vertex stages write locations 0–3 alone.
    #[test]
    fn only_the_per_vertex_interface_has_the_per_vertex_vectors() {
        let locations = |wgsl: &Wgsl| -> BTreeSet<u32> {
            let module = parse(wgsl);
            let entry = module.entry_points.iter().find(|e| e.name == "vs_plain").expect("vs_plain");
            let result = entry.function.result.as_ref().expect("vs_plain returns its varyings");
            let naga::TypeInner::Struct { members, .. } = &module.types[result.ty].inner else {
                panic!("{}: the varyings are a struct", wgsl.label)
            };
            members
                .iter()
                .filter_map(|m| match m.binding {
                    Some(naga::Binding::Location { location, .. }) => Some(location),
                    _ => None,
                })
                .collect()
        };
        assert_eq!(locations(&MESH), BTreeSet::from([0, 1, 2, 3]));
        assert_eq!(locations(&MESH_PER_VERTEX), BTreeSet::from([0, 1, 2, 3, 4, 5]));
    }
}

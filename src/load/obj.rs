//! Wavefront OBJ (+ MTL, read by the `mtl` module) → [`Scene`].
//!
//! Read here rather than with the `tobj` crate: tobj only fan-triangulates (quads here are
//! split along their shorter diagonal), keeps MTL map options such as `-bm` inside the file
//! name, and reports errors without the line. One [`Mesh`] per material used, vertices shared
//! where a face corner repeats the same `v/vt/vn`. OBJ's `v` runs up the image (origin
//! bottom-left): it is stored as `1 − v` (crate conventions). Corners without `vn` get the
//! area-weighted mean normal of the faces around their position.

use std::collections::HashMap;
use std::path::Path;

use glam::{Mat4, Vec2, Vec3};

use super::budget::{Budget, INDEX_BYTES, VERTEX_BYTES};
use super::mesh_ops::{check, triangulate};
use super::mtl;
use crate::error::LoadError;
use crate::math::normalize_or;
use crate::scene::{Instance, Mesh, Scene};

/// A face corner: indices (from 0) into positions, texture coordinates and normals.
type Corner = (usize, Option<usize>, Option<usize>);

/// Bytes a triangle takes while loading, charged to the load's [`Budget`]: three corners as
/// read (40 bytes each) and as mesh vertices and indices ([`VERTEX_BYTES`], [`INDEX_BYTES`]).
const TRIANGLE_BYTES: u64 = 3 * (40 + VERTEX_BYTES + INDEX_BYTES);

/// The file's contents before meshes are built.
#[derive(Default)]
struct ObjData {
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    normals: Vec<Vec3>,
    /// Triangles by material name (`None`: no `usemtl`), in order of first use.
    groups: Vec<(Option<String>, Vec<[Corner; 3]>)>,
    libraries: Vec<String>,
}

/// Loads an `.obj` file and the `.mtl` libraries it names. The camera and light are left
/// to the caller.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    let bytes = super::read_file(path, crate::read::FileKind::Mesh, "OBJ")?;
    let text = String::from_utf8_lossy(&bytes);
    let data = parse(&text, path)?;
    if data.groups.iter().all(|(_, t)| t.is_empty()) {
        return Err(LoadError::new(path, "the OBJ file has no faces (empty or points and lines only)"));
    }
    let mut scene = super::empty_scene();
    let base = path.parent().unwrap_or(Path::new("."));
    let mut materials = mtl::load_libraries(&data.libraries, base, path, &mut scene)?;
    let smooth = position_normals(&data);
    for (material_name, triangles) in data.groups.iter().filter(|(_, t)| !t.is_empty()) {
        let material = mtl::material_index(material_name.as_deref(), &mut materials, &mut scene);
        let name = material_name.clone().unwrap_or_else(|| "obj".into());
        let mesh = build_mesh(&data, triangles, &smooth, &name);
        check(&mesh, path)?;
        scene.meshes.push(mesh);
        scene.instances.push(Instance { mesh: scene.meshes.len() - 1, material, transform: Mat4::IDENTITY });
    }
    Ok(scene)
}

/// Reads the statements this loader uses; others (`o`, `g`, `s`, `l`, `p`...) are skipped.
fn parse(text: &str, path: &Path) -> Result<ObjData, LoadError> {
    let mut data = ObjData::default();
    let mut current = 0;
    // `usemtl` name → index in `data.groups`.
    let mut group_of: HashMap<String, usize> = HashMap::new();
    let mut budget = Budget::for_input(text.len() as u64);
    for (number, line) in text.lines().enumerate() {
        let at = |problem: String| LoadError::new(path, format!("line {}: {problem}", number + 1));
        let line = line.split('#').next().unwrap_or("").trim();
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or("");
        let numbers = |words: std::str::SplitWhitespace| -> Result<Vec<f32>, LoadError> {
            words.map(|w| w.parse::<f32>().map_err(|_| at(format!("{w:?} is not a number")))).collect()
        };
        match keyword {
            "v" | "vn" | "vt" => {
                let values = numbers(words)?;
                let needed = if keyword == "vt" { 1 } else { 3 };
                if values.len() < needed {
                    return Err(at(format!("{keyword} needs {needed} numbers, has {}", values.len())));
                }
                match keyword {
                    "v" => data.positions.push(Vec3::new(values[0], values[1], values[2])),
                    "vn" => data.normals.push(normalize_or(Vec3::new(values[0], values[1], values[2]), Vec3::Z)),
                    _ => data.uvs.push(Vec2::new(values[0], 1.0 - values.get(1).copied().unwrap_or(0.0))),
                }
            }
            "f" => {
                let corners = words.map(|w| corner(w, &data)).collect::<Result<Vec<_>, _>>().map_err(at)?;
                if data.groups.is_empty() {
                    data.groups.push((None, vec![]));
                }
                let triangles = corners.len().saturating_sub(2) as u64;
                budget.charge(triangles * TRIANGLE_BYTES).map_err(|over| at(format!("the faces so far {over}")))?;
                let positions: Vec<Vec3> = corners.iter().map(|c| data.positions[c.0]).collect();
                let triangles = triangulate(&positions).into_iter().map(|t| t.map(|k| corners[k]));
                data.groups[current].1.extend(triangles);
            }
            "usemtl" => {
                let name = line["usemtl".len()..].trim();
                current = match group_of.get(name) {
                    Some(&i) => i,
                    None => {
                        data.groups.push((Some(name.to_owned()), vec![]));
                        group_of.insert(name.to_owned(), data.groups.len() - 1);
                        data.groups.len() - 1
                    }
                };
            }
            "mtllib" => data.libraries.push(line["mtllib".len()..].trim().to_owned()),
            _ => {}
        }
    }
    Ok(data)
}

/// One `v`, `v/vt`, `v//vn` or `v/vt/vn` corner; indices from 1, negative ones counted back
/// from the last element read so far.
fn corner(word: &str, data: &ObjData) -> Result<Corner, String> {
    let resolve = |text: &str, count: usize, what: &str| -> Result<usize, String> {
        let index: i64 = text.parse().map_err(|_| format!("face corner {word:?}: {text:?} is not an index"))?;
        let resolved = if index < 0 { count as i64 + index } else { index - 1 };
        usize::try_from(resolved)
            .ok()
            .filter(|&i| i < count)
            .ok_or_else(|| format!("face corner {word:?}: {what} index {index} is out of range ({count} so far)"))
    };
    let mut parts = word.split('/');
    let position = resolve(parts.next().unwrap_or(""), data.positions.len(), "position")?;
    let optional = |part: Option<&str>, count, what| part.filter(|p| !p.is_empty()).map(|p| resolve(p, count, what));
    let uv = optional(parts.next(), data.uvs.len(), "texture coordinate").transpose()?;
    let normal = optional(parts.next(), data.normals.len(), "normal").transpose()?;
    Ok((position, uv, normal))
}

/// Per OBJ position: the area-weighted mean normal of the faces that use it.
fn position_normals(data: &ObjData) -> Vec<Vec3> {
    let mut sums = vec![Vec3::ZERO; data.positions.len()];
    for [a, b, c] in data.groups.iter().flat_map(|(_, t)| t) {
        let [pa, pb, pc] = [a.0, b.0, c.0].map(|i| data.positions[i]);
        let face = (pb - pa).cross(pc - pa);
        [a.0, b.0, c.0].into_iter().for_each(|i| sums[i] += face);
    }
    sums.into_iter().map(|n| normalize_or(n, Vec3::Z)).collect()
}

/// A mesh of `triangles`, one vertex per distinct corner. UVs are dropped when some corner
/// has none (the mesh is then drawn untextured).
fn build_mesh(data: &ObjData, triangles: &[[Corner; 3]], smooth: &[Vec3], name: &str) -> Mesh {
    let mut mesh = Mesh::empty(name);
    let mut vertices: HashMap<Corner, u32> = HashMap::new();
    let all_uvs = triangles.iter().flatten().all(|c| c.1.is_some());
    for &corner in triangles.iter().flatten() {
        let next = mesh.positions.len() as u32;
        let index = *vertices.entry(corner).or_insert(next);
        if index == next {
            let (p, uv, n) = corner;
            mesh.positions.push(data.positions[p]);
            mesh.normals.push(n.map_or(smooth[p], |n| data.normals[n]));
            if all_uvs {
                mesh.uvs.push(uv.map_or(Vec2::ZERO, |t| data.uvs[t]));
            }
        }
        mesh.indices.push(index);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_split_v_flips_and_missing_normals_are_smoothed() {
        let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n";
        let data = parse(text, Path::new("quad.obj")).unwrap();
        let mesh = build_mesh(&data, &data.groups[0].1, &position_normals(&data), "quad");
        assert_eq!((mesh.positions.len(), mesh.indices.len()), (4, 6));
        // OBJ's v = 0 is the bottom of the image: stored as 1 (v down).
        assert_eq!(mesh.uvs[0], Vec2::new(0.0, 1.0));
        assert!(mesh.normals.iter().all(|&n| n == Vec3::Z));
        let error = parse("v 0 0 0\nf 1 2 x\n", Path::new("bad.obj")).err().unwrap().to_string();
        assert!(error.contains("bad.obj") && error.contains("line 2"), "{error}");
    }
}

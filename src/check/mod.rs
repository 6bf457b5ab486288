//! `bumpview check`: what in a mesh file will make bump mapping go wrong, per mesh and
//! material — degenerate and mirrored UV triangles, UV seams, supplied tangents that are not
//! unit or orthogonal or disagree on `w` inside a triangle, and normal-map sanity with the
//! map's likely green-channel convention ([`green`]) in every normal slot ([`maps`]), and how
//! much its averaged normals shorten per mip level ([`mip_shortening`]).

pub mod green;
pub mod green_cells;
pub mod maps;
pub mod mip_shortening;
pub mod normal_map;
pub mod votes_picture;

use std::collections::HashMap;
use std::fmt::Write;

use glam::{Vec2, Vec3};

use crate::error::LoadWarning;
use crate::scene::{Material, Mesh, Scene, ShadingModel};
use crate::tangent::face_frame;
pub use green::{GreenConvention, Undetermined};
pub use maps::{MapFindings, NEGATIVE_Z_WARN_SHARE, NON_UNIT_WARN_SHARE, NormalSlot, check_normal_maps};
pub use normal_map::{NormalMapFindings, check_normal_map, layout_evidence};

/// How serious a finding is; decides the exit status (0 clean, 1 warnings, 2 errors).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Severity {
    Clean,
    Warning,
    Error,
}

impl Severity {
    pub fn exit_code(self) -> u8 {
        self as u8
    }
}

/// Counts about one mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshFindings {
    pub name: String,
    pub triangles: usize,
    pub vertices: usize,
    /// Triangles whose UVs (relatively) have no area: no tangent frame of their own.
    pub degenerate_uv: usize,
    /// Triangles whose UV winding is opposite to their winding in space (`w = −1` there).
    pub mirrored: usize,
    /// Positions that carry two or more different UVs: vertices split by a UV seam.
    pub seam_positions: usize,
    pub tangents: Option<TangentFindings>,
}

/// Counts about the tangents a mesh supplies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TangentFindings {
    /// `|T|` more than 1e-3 from 1.
    pub non_unit: usize,
    /// `|T̂·N|` above 0.01 (about 0.6°): Gram-Schmidt will change them.
    pub non_orthogonal: usize,
    /// Triangles whose corners disagree on the sign of `w`.
    pub mixed_w_triangles: usize,
}

/// The exponent the highlight of `material` has: its own, or for metallic-roughness
/// Beckmann's `2/α² − 2` with `α = roughness²` (Walter et al. 2007), at most 10⁴.
pub fn material_exponent(material: &Material) -> f32 {
    match material.shading_model {
        ShadingModel::BlinnPhong => material.shininess,
        ShadingModel::MetallicRoughness => crate::shading::pbr::roughness_exponent(material.roughness).min(1e4),
    }
}

/// Everything `check` found in one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckReport {
    pub meshes: Vec<MeshFindings>,
    pub normal_maps: Vec<MapFindings>,
    /// What the loader could not read or honour ([`Scene::warnings`]).
    pub load_warnings: Vec<LoadWarning>,
}

/// A position snapped to a grid of `cell` metres, for finding positions shared by several
/// vertices (parametric seams are equal only up to rounding).
fn position_key(p: Vec3, cell: f32) -> [i64; 3] {
    (p / cell).round().to_array().map(|c| c as i64)
}

/// Counts the findings of one mesh.
pub fn check_mesh(mesh: &Mesh) -> MeshFindings {
    let uv = |i: u32| mesh.uvs.get(i as usize).copied().unwrap_or(Vec2::ZERO);
    let (mut degenerate_uv, mut mirrored) = (0, 0);
    for triangle in mesh.indices.chunks_exact(3) {
        let p = [0, 1, 2].map(|k| mesh.positions[triangle[k] as usize]);
        let uvs = [0, 1, 2].map(|k| uv(triangle[k]));
        match face_frame(p, uvs) {
            None => degenerate_uv += 1,
            Some((t, b)) => {
                let face_normal = (p[1] - p[0]).cross(p[2] - p[0]);
                if face_normal.cross(t).dot(b) < 0.0 {
                    mirrored += 1;
                }
            }
        }
    }
    // Positions closer than a millionth of the mesh's size count as one.
    let (min, max) =
        mesh.positions.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let cell = ((max - min).length() * 1e-6).max(f32::MIN_POSITIVE);
    let mut uvs_at: HashMap<[i64; 3], Vec<[u32; 2]>> = HashMap::new();
    for (p, t) in mesh.positions.iter().zip(&mesh.uvs) {
        let entry = uvs_at.entry(position_key(*p, cell)).or_default();
        let key = t.to_array().map(f32::to_bits);
        if !entry.contains(&key) {
            entry.push(key);
        }
    }
    let tangents = mesh.tangents.as_ref().map(|tangents| {
        let non_unit = tangents.iter().filter(|t| (t.truncate().length() - 1.0).abs() > 1e-3).count();
        let non_orthogonal = tangents
            .iter()
            .zip(&mesh.normals)
            .filter(|(t, n)| t.truncate().normalize_or_zero().dot(n.normalize_or_zero()).abs() > 0.01)
            .count();
        let w_sign = |i: u32| tangents.get(i as usize).is_some_and(|t| t.w < 0.0);
        let mixed_w_triangles = mesh
            .indices
            .chunks_exact(3)
            .filter(|t| w_sign(t[0]) != w_sign(t[1]) || w_sign(t[0]) != w_sign(t[2]))
            .count();
        TangentFindings { non_unit, non_orthogonal, mixed_w_triangles }
    });
    MeshFindings {
        name: mesh.name.clone(),
        triangles: mesh.indices.len() / 3,
        vertices: mesh.positions.len(),
        degenerate_uv,
        mirrored,
        seam_positions: uvs_at.values().filter(|uvs| uvs.len() > 1).count(),
        tangents,
    }
}

/// Checks every mesh of `scene` and every normal map its materials use.
pub fn check_scene(scene: &Scene) -> CheckReport {
    let meshes = scene.meshes.iter().map(check_mesh).collect();
    let normal_maps = check_normal_maps(scene);
    CheckReport { meshes, normal_maps, load_warnings: scene.warnings.clone() }
}

impl CheckReport {
    /// The errors, one line each: textures the scene opened without.
    pub fn errors(&self) -> Vec<String> {
        let unreadable = self.load_warnings.iter().filter(|w| matches!(w, LoadWarning::UnreadableTexture { .. }));
        unreadable.map(ToString::to_string).collect()
    }

    /// The warnings, one line each.
    pub fn warnings(&self) -> Vec<String> {
        let unreadable = |w: &&LoadWarning| matches!(w, LoadWarning::UnreadableTexture { .. });
        let mut warnings: Vec<String> =
            self.load_warnings.iter().filter(|w| !unreadable(w)).map(ToString::to_string).collect();
        for mesh in &self.meshes {
            if mesh.degenerate_uv > 0 {
                warnings.push(format!("mesh {:?}: {} triangles with degenerate UVs", mesh.name, mesh.degenerate_uv));
            }
            if let Some(t) = mesh.tangents
                && t.non_unit + t.non_orthogonal + t.mixed_w_triangles > 0
            {
                warnings.push(format!(
                    "mesh {:?}: supplied tangents: {} non-unit, {} not orthogonal to the normal, {} triangles with mixed w",
                    mesh.name, t.non_unit, t.non_orthogonal, t.mixed_w_triangles
                ));
            }
        }
        self.normal_maps.iter().for_each(|map| warnings.extend(map.warnings()));
        warnings
    }

    pub fn severity(&self) -> Severity {
        if !self.errors().is_empty() {
            Severity::Error
        } else if !self.warnings().is_empty() {
            Severity::Warning
        } else {
            Severity::Clean
        }
    }

    /// The human-readable report.
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        for m in &self.meshes {
            let _ = writeln!(
                out,
                "  mesh {:?}: {} triangles, {} vertices; {} degenerate-UV, {} mirrored triangles; {} UV-seam positions",
                m.name, m.triangles, m.vertices, m.degenerate_uv, m.mirrored, m.seam_positions
            );
            let _ = match m.tangents {
                Some(t) => writeln!(
                    out,
                    "    tangents supplied: {} non-unit, {} non-orthogonal, {} triangles with mixed w",
                    t.non_unit, t.non_orthogonal, t.mixed_w_triangles
                ),
                None => writeln!(out, "    tangents: none supplied (generated with MikkTSpace when needed)"),
            };
        }
        self.normal_maps.iter().for_each(|map| map.write_text(&mut out));
        for error in self.errors() {
            let _ = writeln!(out, "  error: {error}");
        }
        for warning in self.warnings() {
            let _ = writeln!(out, "  warning: {warning}");
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::teaching_scene;

    #[test]
    fn the_built_in_scene_is_clean() {
        let report = check_scene(&teaching_scene());
        assert_eq!(report.severity(), Severity::Clean, "{}", report.to_text());
        assert_eq!(report.meshes.len(), 3);
        let torus = &report.meshes[2];
        assert_eq!((torus.degenerate_uv, torus.mirrored), (0, 0));
        assert!(torus.seam_positions > 0, "the torus has UV seams");
        assert_eq!(report.normal_maps[0].findings.convention.map(|c| c.0), Some(GreenConvention::OpenGl));
    }

    #[test]
    fn mirrored_and_degenerate_triangles_and_bad_tangents_are_counted() {
        let mut mesh = crate::scene::builtin::wall_mesh();
        // Mirror u on the first triangle's copy and collapse the second's UVs.
        let n = mesh.positions.len() as u32;
        for (k, uv) in [(0, Vec2::new(1.0, 1.0)), (1, Vec2::new(0.0, 1.0)), (2, Vec2::new(0.0, 0.0))] {
            mesh.positions.push(mesh.positions[mesh.indices[k] as usize]);
            mesh.normals.push(Vec3::Z);
            mesh.uvs.push(uv);
        }
        for _ in 0..3 {
            mesh.positions.push(Vec3::new(9.0, 9.0, 0.0) + mesh.positions.len() as f32 * Vec3::X);
            mesh.normals.push(Vec3::Z);
            mesh.uvs.push(Vec2::splat(0.5));
        }
        mesh.indices.extend([n, n + 1, n + 2, n + 3, n + 4, n + 5]);
        let mut tangents = vec![glam::Vec4::new(1.0, 0.0, 0.0, 1.0); mesh.positions.len()];
        tangents[mesh.indices[1] as usize] = glam::Vec4::new(2.0, 0.0, 0.0, -1.0);
        tangents[mesh.indices[3] as usize] = glam::Vec4::new(0.6, 0.0, 0.8, 1.0);
        mesh.tangents = Some(tangents);
        let findings = check_mesh(&mesh);
        assert_eq!((findings.mirrored, findings.degenerate_uv), (1, 1));
        let t = findings.tangents.unwrap();
        assert_eq!(t.non_unit, 1);
        assert_eq!(t.non_orthogonal, 1);
        assert!(t.mixed_w_triangles >= 1);
    }

    /// The bricks' averaged normals shorten but stay under the warning; a map of texels
    /// tilted ±0.5 rad checkerwise (|Na| = cos 0.5 = 0.878 from level 1 on; 0.876 as level 1 is
    /// averaged from its 8-bit texels) is warned about, with the level, the length and Toksvig's exponent.
    #[test]
    fn a_map_whose_mips_over_sharpen_the_highlight_is_warned_about() {
        let report = check_scene(&teaching_scene());
        let bricks = &report.normal_maps[0].mips;
        assert!(bricks.len() > 4 && bricks[4].mean_length < 0.99, "{bricks:?}");
        assert!(report.to_text().contains("    mips: mean |Na| per level 1.000 "), "{}", report.to_text());
        let mut scene = teaching_scene();
        let map =
            std::sync::Arc::make_mut(&mut scene.textures[scene.materials[0].normal_map.as_ref().unwrap().texture]);
        let width = map.width as usize;
        for (i, texel) in map.rgba.chunks_exact_mut(4).enumerate() {
            let sign = if (i % width + i / width) % 2 == 0 { 1.0f32 } else { -1.0 };
            let x = (127.5 + 127.5 * sign * 0.5f32.sin()).round() as u8;
            texel.copy_from_slice(&[x, 128, (127.5 + 127.5 * 0.5f32.cos()).round() as u8, 255]);
        }
        let warnings = check_scene(&scene).warnings();
        let expected = "from mip level 1 (256×256) its averaged normals are 0.876 long: a re-normalised chain \
                        draws the highlight with exponent 32 where the bumps it averages spread it to 5.8";
        assert!(warnings.iter().any(|w| w.contains(expected)), "{warnings:?}");
    }

    /// A share of texels pointing into the surface too small to print (it would read 0.00%)
    /// is no warning; from 0.01% on it is.
    #[test]
    fn texels_below_the_surface_warn_from_the_printed_share_on() {
        let with_inward = |count: usize| {
            let mut scene = teaching_scene();
            let texture = scene.materials[0].normal_map.as_ref().unwrap().texture;
            let map = std::sync::Arc::make_mut(&mut scene.textures[texture]);
            for texel in map.rgba.chunks_exact_mut(4).take(count) {
                texel.copy_from_slice(&[128, 128, 60, 255]);
            }
            let share = count as f32 / (map.width * map.height) as f32;
            (share, check_scene(&scene).warnings())
        };
        let (share, warnings) = with_inward(1);
        assert!(share < NEGATIVE_Z_WARN_SHARE, "{share}");
        assert!(warnings.is_empty(), "{warnings:?}");
        let (share, warnings) = with_inward(100);
        assert!(share >= NEGATIVE_Z_WARN_SHARE, "{share}");
        assert!(warnings.iter().any(|w| w.contains("0.04% of texels point into the surface")), "{warnings:?}");
    }
}

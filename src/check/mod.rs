//! `bumpview check`: what in a mesh file will make bump mapping go wrong, per mesh and
//! material — degenerate and mirrored UV triangles, UV seams, supplied tangents that are not
//! unit or orthogonal or disagree on `w` inside a triangle, and normal-map sanity with the
//! map's likely green-channel convention ([`normal_map`]), and how much its averaged normals
//! shorten per mip level ([`mip_shortening`]).

pub mod mip_shortening;
pub mod normal_map;

use std::collections::HashMap;
use std::fmt::Write;

use glam::{Vec2, Vec3};

use crate::error::LoadWarning;
use crate::names::Named;
use crate::scene::{Material, Mesh, NormalLayout, Scene, ShadingModel};
use crate::tangent::face_frame;
use mip_shortening::{LevelShortening, first_over_sharp, mip_shortening};
pub use normal_map::{GreenConvention, NormalMapFindings, check_normal_map, layout_evidence};

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

/// One normal map as a material uses it.
#[derive(Debug, Clone, PartialEq)]
pub struct MapFindings {
    pub material: String,
    pub texture: String,
    pub findings: NormalMapFindings,
    /// The channel layout the map is drawn with (the material's, as loaded), and why.
    pub layout: NormalLayout,
    pub layout_reason: String,
    /// The material's Blinn-Phong exponent (metallic-roughness: Beckmann's `2/α² − 2`).
    pub shininess: f32,
    /// Per mip level, how short the averaged normals get ([`mip_shortening`]); empty unless
    /// the map is read as RGB.
    pub mips: Vec<LevelShortening>,
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

/// Warn about texels that decode more than 10% off unit length when more than this share of
/// a normal map's texels do.
pub const NON_UNIT_WARN_SHARE: f32 = 0.05;
/// Warn about texels with `z < 0` (pointing into the surface) from this share on: 0.01%, the
/// smallest share the report prints as non-zero.
pub const NEGATIVE_Z_WARN_SHARE: f32 = 1e-4;
/// Warn that green looks DirectX above this confidence of the curl test.
pub const DIRECTX_WARN_CONFIDENCE: f32 = 0.5;

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
    let normal_maps = scene
        .materials
        .iter()
        .filter_map(|m| m.normal_map.as_ref().map(|map| (m, map)))
        .filter_map(|(material, map)| {
            let texture = scene.textures.get(map.texture)?;
            let findings = check_normal_map(texture);
            let layout = map.convention.layout;
            let evidence = layout_evidence(findings.suggested_layout);
            let layout_reason = match (layout, map.correction.and_then(|c| scene.textures.get(c))) {
                (NormalLayout::Xray, Some(correction)) => {
                    format!("X-Ray pair: {:?} with the correction {:?} beside it", texture.name, correction.name)
                }
                (NormalLayout::Xray, None) => format!("X-Ray bump {:?} without a bump# correction", texture.name),
                (layout, _) if layout == findings.suggested_layout => format!("as loaded, and {evidence}"),
                _ => format!("as loaded, although {evidence}"),
            };
            let shininess = material_exponent(material);
            let mips = if layout == NormalLayout::Rgb { mip_shortening(texture, shininess) } else { vec![] };
            Some(MapFindings {
                material: material.name.clone(),
                texture: texture.name.clone(),
                findings,
                layout,
                layout_reason,
                shininess,
                mips,
            })
        })
        .collect();
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
        for map in &self.normal_maps {
            let f = &map.findings;
            let name = format!("material {:?}, normal map {:?}", map.material, map.texture);
            if map.layout != f.suggested_layout && map.layout != NormalLayout::Xray {
                let (suggested, evidence) = (f.suggested_layout.name(), layout_evidence(f.suggested_layout));
                warnings.push(format!("{name}: {evidence}, which suggests --normal-layout {suggested}"));
            }
            // The texel statistics read red, green, blue as x, y, z.
            if map.layout != NormalLayout::Rgb {
                continue;
            }
            if f.non_unit_share > NON_UNIT_WARN_SHARE {
                warnings
                    .push(format!("{name}: {:.1}% of texels decode far from unit length", f.non_unit_share * 100.0));
            }
            if f.negative_z_share >= NEGATIVE_Z_WARN_SHARE {
                warnings.push(format!(
                    "{name}: {:.2}% of texels point into the surface (z < 0)",
                    f.negative_z_share * 100.0
                ));
            }
            if f.looks_srgb {
                warnings.push(format!("{name}: looks sRGB-encoded (flat texels near 188 instead of 128)"));
            }
            if let Some((GreenConvention::DirectX, confidence)) = f.convention
                && confidence > DIRECTX_WARN_CONFIDENCE
            {
                warnings.push(format!("{name}: green looks DirectX (−Y), confidence {confidence:.2}"));
            }
            if let Some(l) = first_over_sharp(&map.mips) {
                warnings.push(format!(
                    "{name}: from mip level {} ({}×{}) its averaged normals are {:.3} long: a re-normalised chain \
                     draws the highlight with exponent {:.0} where the bumps it averages spread it to {:.1} \
                     (Toksvig, {:.2}×, below {}×); --mip-filter toksvig or vmf widens it",
                    l.level,
                    l.width,
                    l.height,
                    l.mean_length,
                    map.shininess,
                    l.exponent_ratio * map.shininess,
                    l.exponent_ratio,
                    mip_shortening::WARN_EXPONENT_RATIO
                ));
            }
        }
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
        for map in &self.normal_maps {
            let f = &map.findings;
            let convention = match f.convention {
                Some((GreenConvention::OpenGl, c)) => format!("OpenGL (+Y), confidence {c:.2}"),
                Some((GreenConvention::DirectX, c)) => format!("DirectX (−Y), confidence {c:.2}"),
                None => "undetermined (too flat)".to_owned(),
            };
            let _ = writeln!(
                out,
                "  material {:?}, normal map {:?}: {:.1}% non-unit, {:.2}% z < 0, {}; green: {convention}",
                map.material,
                map.texture,
                f.non_unit_share * 100.0,
                f.negative_z_share * 100.0,
                if f.looks_srgb { "looks sRGB-encoded" } else { "linear" },
            );
            let _ = writeln!(out, "    layout: {} ({})", map.layout.name(), map.layout_reason);
            if !map.mips.is_empty() {
                let lengths: Vec<String> = map.mips.iter().map(|l| format!("{:.3}", l.mean_length)).collect();
                let ratios: Vec<String> = map.mips.iter().map(|l| format!("{:.2}", l.exponent_ratio)).collect();
                let _ = writeln!(out, "    mips: mean |Na| per level {}", lengths.join(" "));
                let _ = writeln!(
                    out,
                    "    Toksvig exponent over the material's {:.0} per level (1: a re-normalised chain is right) {}",
                    map.shininess,
                    ratios.join(" ")
                );
            }
        }
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
        let map = &mut scene.textures[scene.materials[0].normal_map.as_ref().unwrap().texture];
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
            let map = &mut scene.textures[texture];
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

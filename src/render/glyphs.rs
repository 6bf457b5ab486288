//! T/B/N glyphs: three short lines at chosen vertices of a mesh with tangent frames, drawn
//! red (T), green (B) and blue (N). The frame at a glyph is the one the shader shades with
//! (T orthonormalised against N, `B = w·(N × T)`), computed in the vertex shader from the
//! vertex's own normal and tangent, so the glyphs show exactly the frames in use (the front
//! face's: on the back of a double-sided material the shading flips N and B, the glyphs not).
//!
//! Dense meshes are thinned: at most [`MAX_GLYPHS_PER_MESH`] vertices carry a glyph, one per
//! cell of a uniform grid over the mesh (model space), so glyphs are spread evenly and do not
//! overlap. Glyph length scales with the spacing of the chosen vertices.

use std::collections::HashMap;

use bytemuck::{Pod, Zeroable};
use glam::{Vec3, Vec4};

use crate::scene::Mesh;

/// At most this many vertices of one mesh carry a glyph.
pub const MAX_GLYPHS_PER_MESH: usize = 600;

/// A glyph's length as a fraction of the mean spacing of the glyph vertices.
const LENGTH_PER_SPACING: f32 = 0.4;

/// Which line of a glyph a vertex belongs to (`GlyphVertex::glyph[0]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GlyphAxis {
    Tangent = 0,
    Bitangent = 1,
    Normal = 2,
}

/// One end of a glyph line, laid out as the glyph vertex buffer (`vs_glyph` in glyphs.wgsl).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub struct GlyphVertex {
    /// The surface point, model space, metres.
    pub position: [f32; 3],
    /// The vertex normal, model space.
    pub normal: [f32; 3],
    /// The vertex tangent, model space, `w` = handedness.
    pub tangent: [f32; 4],
    /// `[axis, end, length]`: [`GlyphAxis`] as a number, 0 at the surface point and 1 at the
    /// tip, and the line's length in model-space metres.
    pub glyph: [f32; 3],
}

/// The line list of `mesh`'s glyphs (two vertices per line, three lines per glyph) with
/// `tangents` (one per vertex). Vertices with non-finite data are skipped.
pub fn glyph_lines(mesh: &Mesh, tangents: &[Vec4], max: usize) -> Vec<GlyphVertex> {
    let chosen = glyph_vertices(mesh, tangents, max);
    let length = glyph_length(mesh, chosen.len());
    let mut lines = Vec::with_capacity(chosen.len() * 6);
    for i in chosen {
        for axis in [GlyphAxis::Tangent, GlyphAxis::Bitangent, GlyphAxis::Normal] {
            for end in [0.0, 1.0] {
                lines.push(GlyphVertex {
                    position: mesh.positions[i].to_array(),
                    normal: mesh.normals[i].to_array(),
                    tangent: tangents[i].to_array(),
                    glyph: [axis as u32 as f32, end, length],
                });
            }
        }
    }
    lines
}

/// The vertices that carry a glyph, ascending: every usable one (finite position, non-zero
/// normal and tangent) when there are at most `max`, else the first usable vertex of each
/// occupied cell of a grid whose cell grows until at most `max` cells are occupied.
pub fn glyph_vertices(mesh: &Mesh, tangents: &[Vec4], max: usize) -> Vec<usize> {
    let usable = |i: &usize| {
        let (p, n, t) = (mesh.positions[*i], mesh.normals.get(*i), tangents.get(*i));
        p.is_finite()
            && n.is_some_and(|n| n.is_finite() && n.length_squared() > 0.0)
            && t.is_some_and(|t| t.is_finite() && t.truncate().length_squared() > 0.0)
    };
    let candidates: Vec<usize> = (0..mesh.positions.len()).filter(usable).collect();
    if candidates.len() <= max || max == 0 {
        return if max == 0 { vec![] } else { candidates };
    }
    let (low, high) = bounds(mesh, &candidates);
    let extent = (high - low).max_element();
    if !(extent.is_finite() && extent > 0.0) {
        return candidates.into_iter().take(1).collect();
    }
    // A surface spread over the box holds about (area / cell²) cells; start below and grow.
    let mut cell = (surface_area(mesh) / max as f32).sqrt().clamp(extent * 1e-6, extent);
    if !cell.is_finite() || cell <= 0.0 {
        cell = extent / (max as f32).sqrt();
    }
    loop {
        let mut first_in_cell: HashMap<[i64; 3], usize> = HashMap::new();
        for &i in &candidates {
            let key = ((mesh.positions[i] - low) / cell).floor().as_i64vec3().to_array();
            first_in_cell.entry(key).or_insert(i);
        }
        if first_in_cell.len() <= max {
            let mut chosen: Vec<usize> = first_in_cell.into_values().collect();
            chosen.sort_unstable();
            return chosen;
        }
        cell *= 1.25;
    }
}

/// Glyph length for `count` glyphs on `mesh`: 0.4 of the spacing they would
/// have spread evenly over its surface (model-space metres); a mesh without area falls back on
/// its size.
pub fn glyph_length(mesh: &Mesh, count: usize) -> f32 {
    let spacing = (surface_area(mesh) / count.max(1) as f32).sqrt();
    if spacing.is_finite() && spacing > 0.0 {
        return LENGTH_PER_SPACING * spacing;
    }
    let all: Vec<usize> = (0..mesh.positions.len()).filter(|&i| mesh.positions[i].is_finite()).collect();
    let (low, high) = bounds(mesh, &all);
    let size = (high - low).length();
    if size.is_finite() && size > 0.0 { 0.05 * size } else { 0.01 }
}

fn bounds(mesh: &Mesh, vertices: &[usize]) -> (Vec3, Vec3) {
    vertices.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(low, high), &i| {
        (low.min(mesh.positions[i]), high.max(mesh.positions[i]))
    })
}

/// The summed area of the mesh's triangles with finite corners, square metres (model space).
fn surface_area(mesh: &Mesh) -> f32 {
    mesh.indices
        .chunks_exact(3)
        .filter_map(|t| {
            let [a, b, c] = [0, 1, 2].map(|k| mesh.positions.get(t[k] as usize).copied());
            let (a, b, c) = (a?, b?, c?);
            let area = 0.5 * (b - a).cross(c - a).length();
            area.is_finite().then_some(area)
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::torus_mesh;
    use crate::tangent::{self, TangentMethod};

    /// A 1 m square in the XY plane facing +Z, two triangles.
    fn quad() -> Mesh {
        Mesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
            normals: vec![Vec3::Z; 4],
            uvs: vec![glam::Vec2::ZERO; 4],
            indices: vec![0, 1, 2, 0, 2, 3],
            ..Mesh::empty("quad")
        }
    }

    #[test]
    fn dense_meshes_are_thinned_to_at_most_the_limit_and_spread_over_the_surface() {
        let mesh = torus_mesh(96, 32);
        let (tangents, _) = tangent::resolve(&mesh, Some(TangentMethod::MikkTSpace));
        assert!(mesh.positions.len() > 2000, "the test needs a dense mesh: {}", mesh.positions.len());
        for max in [50, 400, 1500] {
            let chosen = glyph_vertices(&mesh, &tangents, max);
            assert!(chosen.len() <= max && chosen.len() * 3 >= max, "{max}: {} glyphs", chosen.len());
            // Spread: no two chosen vertices much closer than the glyph length.
            let length = glyph_length(&mesh, chosen.len());
            let closest = chosen
                .iter()
                .enumerate()
                .flat_map(|(k, &i)| chosen[k + 1..].iter().map(move |&j| (i, j)))
                .map(|(i, j)| mesh.positions[i].distance(mesh.positions[j]))
                .fold(f32::INFINITY, f32::min);
            assert!(closest > 0.25 * length, "{max}: closest pair {closest} m, glyph length {length} m");
        }
    }

    #[test]
    fn small_meshes_get_a_glyph_at_every_vertex_with_three_lines_each() {
        let mesh = quad();
        let tangents = vec![Vec4::new(1.0, 0.0, 0.0, 1.0); mesh.positions.len()];
        let lines = glyph_lines(&mesh, &tangents, MAX_GLYPHS_PER_MESH);
        assert_eq!(lines.len(), mesh.positions.len() * 6);
        // A 1 m² quad with four glyphs: spacing 0.5 m, length 0.2 m.
        assert!(lines.iter().all(|v| (v.glyph[2] - 0.2).abs() < 1e-6), "{:?}", lines[0].glyph);
        let axes: Vec<f32> = lines[..6].iter().map(|v| v.glyph[0]).collect();
        assert_eq!(axes, [0.0, 0.0, 1.0, 1.0, 2.0, 2.0]);
    }

    #[test]
    fn non_finite_or_zero_frames_and_degenerate_meshes_give_no_nan() {
        let mut mesh = quad();
        let mut tangents = vec![Vec4::new(1.0, 0.0, 0.0, 1.0); mesh.positions.len()];
        mesh.positions[0] = Vec3::NAN;
        mesh.normals[1] = Vec3::ZERO;
        tangents[2] = Vec4::new(f32::INFINITY, 0.0, 0.0, 1.0);
        assert_eq!(glyph_vertices(&mesh, &tangents, 10), vec![3]);
        let point = Mesh { positions: vec![Vec3::ONE; 4], ..quad() };
        let tangents = vec![Vec4::new(1.0, 0.0, 0.0, 1.0); 4];
        let lines = glyph_lines(&point, &tangents, 2);
        assert!(!lines.is_empty() && lines.len() <= 12);
        assert!(lines.iter().all(|v| v.glyph[2].is_finite() && v.glyph[2] > 0.0));
        assert!(glyph_vertices(&mesh, &tangents, 0).is_empty());
    }
}

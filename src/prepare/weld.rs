//! Welding displaced surfaces along the edges where they meet, so a displaced scene has no
//! cracks. Two surfaces that share an edge (the built-in wall and floor along their seam, the
//! faces of a hard-edged box) each move their copy of an edge vertex along their own normal;
//! apart, they open a gap the background shows through, as wide as the depth. Here every
//! vertex on a base triangle's edge is keyed by its exact undisplaced position, and where one
//! position carries several normals (or several lifts) all its copies move to one common
//! point `v` with `v · N̂ᵢ = liftᵢ` for each distinct normal: the corner where the displaced
//! surfaces (offset planes) meet, so the surfaces stay joined at every depth.
//!
//! Welding was chosen over the two alternatives: skirts (strips from the displaced edge back
//! to the base edge) add triangles, and standing fins where a UV seam splits vertices; and
//! extending the surfaces under each other changes the scene (its silhouette, what parallax
//! draws) and needs to know which surface is in front. A weld adds nothing, keeps the
//! triangle count, and is exact: copies of a vertex get bit-identical positions. The cost is
//! one stretched row of sub-triangles along a crease (as tall as the depth), which is where
//! the relief of both surfaces would meet in a solid carved on both faces.

use std::collections::HashMap;

use glam::{Mat3, Vec3};

/// A vertex on an edge of a base triangle: where it was before displacement, its unit
/// normal and how far it moved along it (metres, ≤ 0: `(h − 1) · depth`).
#[derive(Debug, Clone, Copy)]
pub struct EdgeVertex {
    /// Index into the displaced mesh's vertices.
    pub index: u32,
    pub base: Vec3,
    pub unit: Vec3,
    pub lift: f32,
}

/// Normals closer than this (cosine) are one normal.
const SAME_NORMAL: f32 = 0.999_999;

/// Moves the copies of every shared edge vertex of `meshes` (each a displaced mesh's
/// positions and its edge vertices, all in one space) to their common point.
pub fn weld(meshes: &mut [(&mut Vec<Vec3>, Vec<EdgeVertex>)]) {
    let mut by_position: HashMap<[u32; 3], Vec<(usize, EdgeVertex)>> = HashMap::new();
    for (mesh, (_, edges)) in meshes.iter().enumerate() {
        for edge in edges {
            // `+ 0.0` makes −0 and +0 one key.
            by_position.entry(edge.base.to_array().map(|c| (c + 0.0).to_bits())).or_default().push((mesh, *edge));
        }
    }
    for copies in by_position.values() {
        let first = copies[0].1;
        if copies.iter().all(|(_, c)| c.unit == first.unit && c.lift == first.lift) {
            continue; // one surface's own vertex: already in one place
        }
        let point = first.base + common_offset(copies.iter().map(|(_, c)| (c.unit, c.lift)));
        for (mesh, copy) in copies {
            meshes[*mesh].0[copy.index as usize] = point;
        }
    }
}

/// The offset `v` with `v · N̂ᵢ = liftᵢ` for each distinct unit normal (lifts of one normal
/// averaged): the least-norm solution in the normals' span, limited to four times the largest
/// lift where the surfaces fold almost flat onto each other (their corner runs off to
/// infinity). Copies of one normal give `lift · N̂`.
pub fn common_offset(contributions: impl Iterator<Item = (Vec3, f32)>) -> Vec3 {
    let mut normals: Vec<(Vec3, f32, f32)> = vec![]; // normal, summed lift, count
    for (unit, lift) in contributions {
        match normals.iter_mut().find(|(n, _, _)| n.dot(unit) > SAME_NORMAL) {
            Some((_, sum, count)) => {
                *sum += lift;
                *count += 1.0;
            }
            None => normals.push((unit, lift, 1.0)),
        }
    }
    let planes: Vec<(Vec3, f32)> = normals.iter().map(|&(n, sum, count)| (n, sum / count)).collect();
    let largest = planes.iter().map(|p| p.1.abs()).fold(0.0, f32::max);
    if largest == 0.0 {
        return Vec3::ZERO;
    }
    let offset = solve(&planes);
    if offset.is_finite() && offset.length() <= 4.0 * largest { offset } else { offset.clamp_length_max(4.0 * largest) }
}

/// Least-norm `v` with `v · nᵢ = tᵢ`: `v = Σ aᵢ nᵢ` with the Gram system `G a = t`, for up to
/// three independent normals (dependent ones are dropped, first kept).
fn solve(planes: &[(Vec3, f32)]) -> Vec3 {
    let mut basis: Vec<(Vec3, f32)> = vec![];
    for &(n, t) in planes {
        let mut candidate = basis.clone();
        candidate.push((n, t));
        if candidate.len() <= 3 && gram(&candidate).determinant() > 1e-6 {
            basis = candidate;
        }
    }
    let padded = |k: usize| basis.get(k).copied().unwrap_or((Vec3::ZERO, 0.0));
    let (g, t) = (gram(&basis), Vec3::new(padded(0).1, padded(1).1, padded(2).1));
    let a = g.inverse() * t;
    (0..basis.len()).map(|k| basis[k].0 * a[k]).sum()
}

/// The Gram matrix `nᵢ · nⱼ` of up to three normals, padded with the identity.
fn gram(planes: &[(Vec3, f32)]) -> Mat3 {
    let mut cols = [Vec3::X, Vec3::Y, Vec3::Z];
    for (i, col) in cols.iter_mut().enumerate().take(planes.len()) {
        for j in 0..planes.len() {
            col[j] = planes[i].0.dot(planes[j].0);
        }
    }
    Mat3::from_cols(cols[0], cols[1], cols[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_perpendicular_faces_meet_at_their_offset_corner() {
        let v = common_offset([(Vec3::Z, -0.03), (Vec3::Y, -0.02)].into_iter());
        assert!((v - Vec3::new(0.0, -0.02, -0.03)).length() < 1e-7, "{v}");
        let box_corner = common_offset([(Vec3::X, -0.01), (Vec3::Y, -0.01), (Vec3::Z, -0.01)].into_iter());
        assert!((box_corner - Vec3::splat(-0.01)).length() < 1e-7, "{box_corner}");
    }

    #[test]
    fn one_normal_averages_its_lifts_and_nearly_folded_faces_stay_bounded() {
        let v = common_offset([(Vec3::Z, -0.02), (Vec3::Z, -0.04)].into_iter());
        assert!((v - Vec3::new(0.0, 0.0, -0.03)).length() < 1e-7, "{v}");
        let folded = common_offset([(Vec3::Y, -0.01), (Vec3::new(0.0, -1.0, 1e-4).normalize(), -0.01)].into_iter());
        assert!(folded.is_finite() && folded.length() <= 0.04 + 1e-6, "{folded}");
        assert_eq!(common_offset([(Vec3::Y, 0.0), (Vec3::Z, 0.0)].into_iter()), Vec3::ZERO);
    }
}

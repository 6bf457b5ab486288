//! Stiff and extreme cases for tangent frames, each a small mesh with the exact frame where
//! one exists: the stability table of the report, and the meshes tests/stiff_tangents.rs uses.

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::surfaces::{Region, uv_sphere};
use crate::names::Named;
use crate::scene::Mesh;
use crate::tangent::{TangentMethod, angle_degrees, tangents};

/// A `cells × cells` grid on the unit square in the XY plane facing +Z; `uv` maps a position
/// to its texture coordinates (v down the image).
pub fn grid(cells: u32, uv: impl Fn(Vec3) -> Vec2) -> Mesh {
    let mut mesh = Mesh::empty("grid");
    for j in 0..=cells {
        for i in 0..=cells {
            let p = Vec3::new(i as f32 / cells as f32, j as f32 / cells as f32, 0.0);
            mesh.positions.push(p);
            mesh.normals.push(Vec3::Z);
            mesh.uvs.push(uv(p));
        }
    }
    let stride = cells + 1;
    for j in 0..cells {
        for i in 0..cells {
            let a = j * stride + i;
            mesh.indices.extend([a, a + 1, a + stride + 1, a, a + stride + 1, a + stride]);
        }
    }
    mesh.analytic_tangents = Some(vec![Vec4::new(1.0, 0.0, 0.0, 1.0); mesh.positions.len()]);
    mesh
}

/// UVs with u along +X and the image's up along +Y.
pub fn plain_uv(p: Vec3) -> Vec2 {
    Vec2::new(p.x, 1.0 - p.y)
}

/// `b` appended to `a` (indices shifted).
pub fn merged(mut a: Mesh, b: &Mesh) -> Mesh {
    let offset = a.positions.len() as u32;
    a.positions.extend(&b.positions);
    a.normals.extend(&b.normals);
    a.uvs.extend(&b.uvs);
    a.indices.extend(b.indices.iter().map(|i| i + offset));
    if let (Some(frames), Some(more)) = (a.analytic_tangents.as_mut(), b.analytic_tangents.as_ref()) {
        frames.extend(more);
    }
    a
}

/// A 1×1 square whose right half has u mirrored (vertices split at x = 0.5): the exact frame
/// is T = +X, w = +1 on the left and T = −X, w = −1 on the right; B is +Y on both.
pub fn mirrored_halves() -> Mesh {
    let mut left = grid(2, |p| Vec2::new(p.x * 0.5, 1.0 - p.y));
    left.positions.iter_mut().for_each(|p| p.x *= 0.5);
    let mut right = grid(2, |p| Vec2::new(0.5 - p.x * 0.5, 1.0 - p.y));
    right.positions.iter_mut().for_each(|p| p.x = 0.5 + p.x * 0.5);
    right.analytic_tangents = Some(vec![Vec4::new(-1.0, 0.0, 0.0, -1.0); right.positions.len()]);
    merged(left, &right)
}

/// Two overlapping copies of a 3×3 grid at the same positions, the second with u mirrored:
/// the exact frame is T = +X, w = +1 on the first copy and T = −X, w = −1 on the second, so a
/// method that merged coincident vertices would mix them.
pub fn duplicate_positions() -> Mesh {
    let a = grid(3, plain_uv);
    let mut b = grid(3, |p| Vec2::new(1.0 - p.x, 1.0 - p.y));
    b.analytic_tangents = Some(vec![Vec4::new(-1.0, 0.0, 0.0, -1.0); b.positions.len()]);
    merged(a, &b)
}

/// The vertices of [`non_finite_grid`] given a NaN position, an infinite UV and a NaN normal.
pub const NON_FINITE_VERTICES: [usize; 3] = [9, 24, 40];

/// A 6×6 grid (exact frame +X, w = +1) with a NaN position at vertex 9, an infinite UV at 24
/// and a NaN normal at 40 ([`NON_FINITE_VERTICES`]).
pub fn non_finite_grid() -> Mesh {
    let mut mesh = grid(6, plain_uv);
    let [position, uv, normal] = NON_FINITE_VERTICES;
    mesh.positions[position] = Vec3::new(f32::NAN, 0.0, 0.0);
    mesh.uvs[uv] = Vec2::new(f32::INFINITY, 0.0);
    mesh.normals[normal] = Vec3::NAN;
    mesh
}

/// Per vertex of `mesh`: whether no triangle using it also uses one of `bad` (the vertices
/// whose frames a method may answer with any valid fallback).
pub fn away_from(mesh: &Mesh, bad: &[usize]) -> Vec<bool> {
    let mut away = vec![true; mesh.positions.len()];
    for triangle in mesh.indices.chunks_exact(3) {
        if triangle.iter().any(|&v| bad.contains(&(v as usize))) {
            triangle.iter().for_each(|&v| away[v as usize] = false);
        }
    }
    away
}

/// One stiff case: a mesh, and where its `analytic_tangents` are the exact answer.
pub struct StiffCase {
    pub name: &'static str,
    pub mesh: Mesh,
    /// Per vertex: the analytic frame there is exact and the methods are held to it. All
    /// false where no frame exists (degenerate UVs: only validity counts). False at a UV
    /// sphere's poles (every u meets there) and seams (each copy of a seam vertex sees the
    /// faces on one side only, so every method is off by about half a cell), at the corners
    /// of a zero-area triangle, and in the triangles that touch non-finite data.
    pub exact: Vec<bool>,
    /// Degrees the surface turns across one cell (0 on a plane): a flat per-face frame is
    /// the direction of its chord, so it may be off the exact frame by half of this.
    pub cell_turn_deg: f32,
}

impl StiffCase {
    /// Whether any vertex has an exact frame.
    pub fn has_reference(&self) -> bool {
        self.exact.contains(&true)
    }

    /// The largest error (degrees) `method` may show against the exact frame at the
    /// [`StiffCase::exact`] vertices. On a plane every method is exact to float rounding
    /// (1e-3° is about 2e-5 rad, far above f32 rounding of unit vectors). On the curved
    /// cases, smooth methods within 1° (the loosest, area weighting, measures 0.82° on the
    /// 32×16 sphere: its north and south faces differ in area, so their tilts do not cancel;
    /// MikkTSpace, uniform and angle weighting 1e-5°); per-face frames within half a cell.
    pub fn tolerance_deg(&self, method: TangentMethod) -> f32 {
        match (self.cell_turn_deg > 0.0, method) {
            (false, _) => 1e-3,
            (true, TangentMethod::PerFace) => 0.5 * self.cell_turn_deg,
            (true, _) => 1.0,
        }
    }
}

/// The cases of the stability table.
pub fn cases() -> Vec<StiffCase> {
    let flat = |name, exact: Vec<bool>, mesh: Mesh| StiffCase { name, exact, mesh, cell_turn_deg: 0.0 };
    let exact_nowhere = |name, mesh: Mesh| flat(name, vec![false; mesh.positions.len()], mesh);
    let exact_everywhere = |name, mesh: Mesh| flat(name, vec![true; mesh.positions.len()], mesh);
    let (segments, rings) = (32, 16);
    let sphere = |name, scale: f32| {
        let reference = uv_sphere(segments, rings);
        let mut mesh = reference.mesh;
        let m = Mat4::from_scale(Vec3::splat(scale));
        mesh.positions.iter_mut().for_each(|p| *p = m.transform_point3(*p));
        let exact = reference.regions.iter().map(|&r| r == Region::Interior).collect();
        StiffCase { name, mesh, exact, cell_turn_deg: 360.0 / segments as f32 }
    };
    let zero_area = {
        let mut mesh = grid(2, plain_uv);
        let n = mesh.positions.len() as u32;
        for uv in [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)] {
            mesh.positions.push(Vec3::new(0.5, 0.5, 0.0));
            mesh.normals.push(Vec3::Z);
            mesh.uvs.push(uv);
            mesh.analytic_tangents.as_mut().expect("grid has frames").push(Vec4::new(1.0, 0.0, 0.0, 1.0));
        }
        mesh.indices.extend([n, n + 1, n + 2]);
        mesh
    };
    let zero_area_exact = (0..zero_area.positions.len()).map(|v| v + 3 < zero_area.positions.len()).collect();
    let non_finite = non_finite_grid();
    let non_finite_exact = away_from(&non_finite, &NON_FINITE_VERTICES);
    vec![
        exact_nowhere("zero-area UV triangles", grid(4, |_| Vec2::splat(0.3))),
        exact_nowhere("collinear UVs", grid(4, |p| Vec2::splat(p.x + p.y))),
        exact_everywhere("mirrored UVs", mirrored_halves()),
        sphere("UV sphere poles (32×16)", 1.0),
        exact_everywhere("duplicate positions", duplicate_positions()),
        flat("zero area in space, not in UV", zero_area_exact, zero_area),
        sphere("scaled by 1e-6", 1e-6),
        sphere("scaled by 1e6", 1e6),
        flat("NaN / Inf in position, UV, normal", non_finite_exact, non_finite),
    ]
}

/// One row of the stability table.
#[derive(Debug, Clone, PartialEq)]
pub struct StabilityRow {
    pub case: &'static str,
    pub method: &'static str,
    /// Frames with a NaN or infinite component.
    pub non_finite: usize,
    /// Frames that are not unit or not orthogonal to their normal (beyond 1e-4).
    pub invalid: usize,
    /// Largest angle between T (and B) and the exact frame over the case's
    /// [`StiffCase::exact`] vertices, degrees; `None` where no exact frame exists.
    pub max_error_deg: Option<f32>,
}

/// Every generated method on every case.
pub fn stability_rows() -> Vec<StabilityRow> {
    let mut rows = vec![];
    for case in cases() {
        for method in TangentMethod::all().iter().copied().filter(|m| m.is_generated()) {
            // Per-face frames are drawn on the unwelded mesh: its vertex k is the case's vertex indices[k].
            let (mesh, exact_at) = if method == TangentMethod::PerFace {
                (case.mesh.unwelded(), case.mesh.indices.iter().map(|&v| case.exact[v as usize]).collect())
            } else {
                (case.mesh.clone(), case.exact.clone())
            };
            let frames = tangents(&mesh, method).expect("generated methods always answer");
            let non_finite = frames.iter().filter(|t| !t.is_finite()).count();
            let invalid = frames
                .iter()
                .zip(&mesh.normals)
                .filter(|(t, n)| {
                    let n = n.normalize_or(Vec3::Z);
                    (t.truncate().length() - 1.0).abs() > 1e-4 || t.truncate().dot(n).abs() > 1e-4
                })
                .count();
            let max_error_deg = case.has_reference().then(|| {
                let exact = mesh.analytic_tangents.as_ref().expect("reference cases carry frames");
                frames
                    .iter()
                    .zip(exact)
                    .zip(&mesh.normals)
                    .zip(&exact_at)
                    .filter(|(_, held)| **held)
                    .map(|(((t, e), n), _)| {
                        let b = |f: &Vec4| f.w.signum() * n.cross(f.truncate());
                        angle_degrees(t.truncate(), e.truncate()).max(angle_degrees(b(t), b(e)))
                    })
                    .fold(0.0f32, |worst, a| if a.is_nan() { f32::INFINITY } else { worst.max(a) })
            });
            rows.push(StabilityRow { case: case.name, method: method.name(), non_finite, invalid, max_error_deg });
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every row: no non-finite and no invalid frame; where an exact frame exists, every
    /// method within its tolerance of it ([`StiffCase::tolerance_deg`]).
    #[test]
    fn every_case_gives_valid_frames_and_the_exact_one_where_it_exists() {
        let rows = stability_rows();
        let cases = cases();
        assert_eq!(rows.len(), cases.len() * 5, "every generated method on every case");
        for r in &rows {
            assert_eq!((r.non_finite, r.invalid), (0, 0), "{r:?}");
            let case = cases.iter().find(|c| c.name == r.case).expect("a row names its case");
            let method =
                TangentMethod::all().iter().copied().find(|m| m.name() == r.method).expect("a row names its method");
            match r.max_error_deg {
                Some(error) => assert!(error < case.tolerance_deg(method), "{r:?}"),
                None => assert!(!case.has_reference(), "{r:?}"),
            }
        }
        // Seven cases have an exact frame, each at most of its vertices.
        let with_reference: Vec<_> = cases.iter().filter(|c| c.has_reference()).collect();
        assert_eq!(with_reference.len(), 7);
        for case in with_reference {
            let held = case.exact.iter().filter(|&&e| e).count();
            assert!(2 * held > case.mesh.positions.len(), "{}: {held} vertices held", case.name);
        }
    }
}

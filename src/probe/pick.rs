//! Rays through pixels against the drawn triangles, and the 2×2 pixel quad around a point
//! (screen-space derivatives as the rasteriser takes them).

use glam::{Mat4, Vec2, Vec3};

use crate::scene::{Mesh, OrbitCamera};

/// A surface point's triangle seen in a view: what the rasteriser's 2×2 pixel quad around it
/// interpolates over.
pub struct Quad<'a> {
    pub camera: &'a OrbitCamera,
    pub size: [u32; 2],
    /// The triangle's corners, world space.
    pub triangle: [Vec3; 3],
    /// The point, world space.
    pub position: Vec3,
}

impl Quad<'_> {
    /// Barycentric coordinates (unbounded: helper pixels lie off the triangle) and position
    /// where the ray through the centre of pixel `(x, y)` meets the triangle's plane.
    fn on_plane(&self, x: i64, y: i64) -> Option<(Vec3, Vec3)> {
        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let (origin, dir) = self.camera.ray_through_pixel(centre, Vec2::new(self.size[0] as f32, self.size[1] as f32));
        meet_plane(origin, dir, self.triangle).map(|(t, barycentric)| (barycentric, origin + dir * t))
    }

    /// Fine screen-space derivatives of `value(barycentric, position)` at the point's pixel, as
    /// lavapipe takes them: differences across its 2×2 quad along the pixel's own row
    /// (`d/dx`) and column (`d/dy`). `None` where the view sees the plane edge-on.
    pub fn derivatives<T: std::ops::Sub<Output = T> + Copy>(&self, value: impl Fn(Vec3, Vec3) -> T) -> Option<(T, T)> {
        let pixel = project_to_pixel(self.camera, self.size, self.position)?;
        let (x, y) = (pixel.x.floor() as i64, pixel.y.floor() as i64);
        let (x0, y0) = (x & !1, y & !1);
        let at = |x, y| self.on_plane(x, y).map(|(b, p)| value(b, p));
        Some((at(x0 + 1, y)? - at(x0, y)?, at(x, y0 + 1)? - at(x, y0)?))
    }
}

/// Where a world-space point appears in a `size` view: pixels from the top-left (`None` behind
/// the eye).
pub fn project_to_pixel(camera: &OrbitCamera, size: [u32; 2], world: Vec3) -> Option<Vec2> {
    let clip = camera.view_projection(size[0] as f32 / size[1] as f32) * world.extend(1.0);
    (clip.w > 0.0).then(|| {
        let ndc = clip.truncate() / clip.w;
        Vec2::new((ndc.x + 1.0) * 0.5 * size[0] as f32, (1.0 - ndc.y) * 0.5 * size[1] as f32)
    })
}

/// A triangle's corners in world space, or `None` when an index is out of range or a position
/// is not finite (the renderer drops such triangles).
pub fn corner_positions(mesh: &Mesh, corners: &[u32], model: &Mat4) -> Option<[Vec3; 3]> {
    let mut p = [Vec3::ZERO; 3];
    for (out, &i) in p.iter_mut().zip(corners) {
        let position = mesh.positions.get(i as usize).filter(|p| p.is_finite())?;
        *out = model.transform_point3(*position);
    }
    Some(p)
}

/// Möller–Trumbore, both faces: the distance along `dir` (unit) and the barycentric weights
/// of the hit inside the triangle, in front of `origin`.
pub fn intersect(origin: Vec3, dir: Vec3, p: [Vec3; 3]) -> Option<(f32, Vec3)> {
    let (t, barycentric) = meet_plane(origin, dir, p)?;
    let [_, u, v] = barycentric.to_array();
    let inside = (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0;
    (inside && t > 0.0).then_some((t, barycentric))
}

/// Where the ray meets the plane of triangle `p` (either side, behind `origin` too): the
/// signed distance along `dir` and the barycentric weights, unbounded off the triangle.
/// `None` for a ray parallel to the plane.
fn meet_plane(origin: Vec3, dir: Vec3, p: [Vec3; 3]) -> Option<(f32, Vec3)> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let h = dir.cross(e2);
    let a = e1.dot(h);
    if a.is_nan() || a.abs() < 1e-12 {
        return None;
    }
    let f = 1.0 / a;
    let s = origin - p[0];
    let q = s.cross(e1);
    let (u, v, t) = (f * s.dot(h), f * dir.dot(q), f * e2.dot(q));
    let barycentric = Vec3::new(1.0 - u - v, u, v);
    (t.is_finite() && barycentric.is_finite()).then_some((t, barycentric))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_hits_a_triangle_with_its_barycentrics_and_misses_beside_it() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let (t, b) = intersect(Vec3::new(0.25, 0.25, 2.0), -Vec3::Z, p).unwrap();
        assert!((t - 2.0).abs() < 1e-6 && (b - Vec3::new(0.5, 0.25, 0.25)).length() < 1e-6, "{t} {b}");
        assert!(intersect(Vec3::new(0.75, 0.75, 2.0), -Vec3::Z, p).is_none());
        assert!(intersect(Vec3::new(0.25, 0.25, 2.0), Vec3::Z, p).is_none(), "behind the origin");
    }
}

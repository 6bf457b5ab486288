//! Reference surfaces with exact answers: a UV sphere and the built-in torus with their
//! analytic tangent frames, and a plane of sine bumps with its analytic normal.
//!
//! Every mesh vertex is put in a [`Region`], so that errors at seams, poles and saddles are
//! reported apart from the smooth interior.

use std::f64::consts::{PI, TAU};

use glam::{DVec3, Vec2, Vec3, Vec4};

use crate::height::HeightField;
use crate::scene::Mesh;
use crate::scene::builtin::torus_mesh;

/// Sphere vertices this close to a pole (degrees of latitude from it) count as [`Region::Pole`],
/// as do the first and last ring of vertices at any resolution.
pub const POLE_DEGREES: f64 = 5.0;

/// Where on a surface a vertex or texel lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Region {
    /// Every vertex (or texel).
    All,
    /// Away from seams and poles (on the torus: the outer half of the tube, `cos t ≥ 0`).
    Interior,
    /// The torus's inner half of the tube (`cos t < 0`, negative Gaussian curvature), off seams.
    Saddle,
    /// On a UV seam: a duplicated column (u = 0 and its twin) or row of vertices.
    Seam,
    /// Near a sphere pole (see [`POLE_DEGREES`]).
    Pole,
    /// Height-field texels within two texels of the edge, where a clamped border changes taps.
    Border,
}

impl Region {
    pub fn name(self) -> &'static str {
        match self {
            Region::All => "all",
            Region::Interior => "interior",
            Region::Saddle => "saddle",
            Region::Seam => "seam",
            Region::Pole => "pole",
            Region::Border => "border",
        }
    }
}

/// A test mesh with its exact frame in `analytic_tangents` and one region per vertex
/// (besides [`Region::All`]).
pub struct Reference {
    pub mesh: Mesh,
    pub regions: Vec<Region>,
}

/// The UV sphere of radius 1 m about the origin, `segments` around and `rings` from pole to
/// pole: `P = (sinθ cosφ, cosθ, −sinθ sinφ)` with `u = φ/2π`, `v = θ/π` (v down the image,
/// so the north pole, +Y, is the image's top). Normals are exact and outward; the analytic
/// frame is `T = ∂P/∂φ / |∂P/∂φ| = (−sinφ, 0, −cosφ)`, `w = +1`, so `B = cross(N, T)` points
/// towards the north pole, up the image. The seam column (u = 0 and u = 1) is duplicated;
/// each pole has one vertex per segment at the segment's middle `u`, with the frame of that
/// meridian. Triangles are counter-clockwise seen from outside.
pub fn uv_sphere(segments: u32, rings: u32) -> Reference {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let mut mesh = Mesh::empty(&format!("sphere {segments}x{rings}"));
    let mut analytic = vec![];
    let mut regions = vec![];
    let pole_radians = POLE_DEGREES.to_radians();
    // Row j holds `segments` vertices at a pole, else `segments + 1`.
    let mut row_start = vec![];
    for j in 0..=rings {
        row_start.push(mesh.positions.len() as u32);
        let at_pole = j == 0 || j == rings;
        let theta = PI * j as f64 / rings as f64;
        let (columns, offset) = if at_pole { (segments, 0.5) } else { (segments + 1, 0.0) };
        for i in 0..columns {
            let u = (i as f64 + offset) / segments as f64;
            let phi = TAU * u;
            let (sin_t, cos_t) = theta.sin_cos();
            let (sin_p, cos_p) = phi.sin_cos();
            let n = Vec3::new((sin_t * cos_p) as f32, cos_t as f32, (-sin_t * sin_p) as f32);
            mesh.positions.push(n);
            mesh.normals.push(n);
            mesh.uvs.push(Vec2::new(u as f32, (j as f64 / rings as f64) as f32));
            analytic.push(Vec4::new(-sin_p as f32, 0.0, -cos_p as f32, 1.0));
            let near_pole = j <= 1 || j + 1 >= rings || theta.min(PI - theta) < pole_radians;
            regions.push(if near_pole {
                Region::Pole
            } else if i == 0 || i == segments {
                Region::Seam
            } else {
                Region::Interior
            });
        }
    }
    for j in 0..rings {
        let (top, bottom) = (row_start[j as usize], row_start[j as usize + 1]);
        for i in 0..segments {
            // bottom-left → bottom-right is +T and bottom-left → top-left is +B: counter-clockwise.
            let (bl, br) = if j + 1 == rings { (bottom + i, bottom + i) } else { (bottom + i, bottom + i + 1) };
            let (tl, tr) = if j == 0 { (top + i, top + i) } else { (top + i, top + i + 1) };
            if j > 0 {
                mesh.indices.extend([bl, tr, tl]);
            }
            if j + 1 < rings {
                mesh.indices.extend([bl, br, tr]);
            }
        }
    }
    mesh.analytic_tangents = Some(analytic);
    Reference { mesh, regions }
}

/// The built-in torus ([`torus_mesh`]) with `segments` around the ring and `sides` around the
/// tube. Its seams are the duplicated first/last column (u = 0 and u = 3, the texture repeats
/// three times around) and the duplicated first/last row (around the tube).
pub fn torus(segments: u32, sides: u32) -> Reference {
    let mesh = torus_mesh(segments, sides);
    let mut regions = vec![];
    for j in 0..=sides {
        let t = TAU * j as f64 / sides as f64;
        for i in 0..=segments {
            regions.push(if i == 0 || i == segments || j == 0 || j == sides {
                Region::Seam
            } else if t.cos() < 0.0 {
                Region::Saddle
            } else {
                Region::Interior
            });
        }
    }
    Reference { mesh, regions }
}

/// The height field `h = A·sin(kx)·sin(ky)`, `k = 2π/λ`, with `A = 1/k` so that its maximum
/// slope `|∇h|` is 1. `x` runs right and `y` up the image, in metres; texel `(i, row j)` is
/// sampled at its centre `x = (i + ½)Δ`, `y = −(j + ½)Δ` (`Δ` = texel size), so a
/// kernel's normal at a texel is compared with the exact normal at that same point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SineBumps {
    /// Period λ in metres.
    pub period_m: f64,
    /// Texels per period (λ/Δ).
    pub texels_per_period: u32,
    /// Periods across the (square) field.
    pub periods: u32,
}

impl SineBumps {
    pub fn new(texels_per_period: u32, periods: u32) -> SineBumps {
        SineBumps { period_m: 1.0, texels_per_period: texels_per_period.max(2), periods: periods.max(1) }
    }

    /// Wavenumber `k = 2π/λ`, radians per metre.
    pub fn wavenumber(&self) -> f64 {
        TAU / self.period_m
    }

    /// Amplitude `A = 1/k`, metres.
    pub fn amplitude_m(&self) -> f64 {
        1.0 / self.wavenumber()
    }

    /// Texel size `Δ`, metres.
    pub fn texel_m(&self) -> f64 {
        self.period_m / self.texels_per_period as f64
    }

    /// Texels along each side.
    pub fn side(&self) -> u32 {
        self.texels_per_period * self.periods
    }

    /// Height in metres at `(x, y)` (metres, y up the image).
    pub fn height_m(&self, x: f64, y: f64) -> f64 {
        let k = self.wavenumber();
        self.amplitude_m() * (k * x).sin() * (k * y).sin()
    }

    /// Exact slopes `(∂h/∂x, ∂h/∂y)` at `(x, y)`, metres per metre.
    pub fn slope(&self, x: f64, y: f64) -> (f64, f64) {
        let k = self.wavenumber();
        let a = self.amplitude_m() * k;
        let ((sx, cx), (sy, cy)) = ((k * x).sin_cos(), (k * y).sin_cos());
        (a * cx * sy, a * sx * cy)
    }

    /// The point `(x, y)` in metres where texel `(i, row j)` is sampled: its centre.
    pub fn texel_centre(&self, i: u32, j: u32) -> (f64, f64) {
        let d = self.texel_m();
        ((i as f64 + 0.5) * d, -(j as f64 + 0.5) * d)
    }

    /// Exact tangent-space unit normal `normalize(−∂h/∂x, −∂h/∂y, 1)` at texel `(i, j)`.
    pub fn normal(&self, i: u32, j: u32) -> DVec3 {
        let (x, y) = self.texel_centre(i, j);
        let (dx, dy) = self.slope(x, y);
        DVec3::new(-dx, -dy, 1.0).normalize()
    }

    /// The field with float samples: `sample = (h + A) / 2A`, so `range_m = 2A`.
    pub fn field(&self) -> HeightField {
        let side = self.side();
        let a = self.amplitude_m();
        let samples = (0..side)
            .flat_map(|j| (0..side).map(move |i| (i, j)))
            .map(|(i, j)| {
                let (x, y) = self.texel_centre(i, j);
                ((self.height_m(x, y) + a) / (2.0 * a)) as f32
            })
            .collect();
        HeightField {
            width: side,
            height: side,
            samples,
            range_m: (2.0 * a) as f32,
            texel_size_m: self.texel_m() as f32,
        }
    }

    /// The region of texel `(i, j)`: [`Region::Border`] within two texels of an edge, else
    /// [`Region::Interior`].
    pub fn region(&self, i: u32, j: u32) -> Region {
        let last = self.side() - 1;
        if i.min(j) < 2 || i.max(j) + 2 > last { Region::Border } else { Region::Interior }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tangent::bitangent;

    #[test]
    fn sphere_frame_follows_u_and_points_b_to_the_north_pole() {
        let sphere = uv_sphere(16, 8);
        let mesh = &sphere.mesh;
        let frames = mesh.analytic_tangents.as_ref().unwrap();
        for tri in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| tri[k] as usize);
            let face = (mesh.positions[b] - mesh.positions[a]).cross(mesh.positions[c] - mesh.positions[a]);
            assert!(face.length() > 1e-6, "no degenerate triangles");
            assert!(face.dot(mesh.normals[a] + mesh.normals[b] + mesh.normals[c]) > 0.0, "counter-clockwise outside");
        }
        // Row 3 starts after the pole row (16) and rows 1, 2 (17 each).
        let stride = 17;
        for i in 0..16 {
            let v = 16 + 2 * stride + i;
            let (n, t) = (mesh.normals[v], frames[v]);
            assert!((n.length() - 1.0).abs() < 1e-6 && (mesh.positions[v] - n).length() < 1e-6);
            let along_u = mesh.positions[v + 1] - mesh.positions[v];
            assert!(t.truncate().dot(along_u.normalize()) > 0.95, "T along +u");
            let b = bitangent(n, t);
            assert!(b.dot((Vec3::Y - mesh.positions[v]).normalize()) > 0.5, "B towards the north pole");
            assert!(mesh.uvs[v - stride].y < mesh.uvs[v].y, "north is up the image (smaller v)");
            assert!(b.dot((mesh.positions[v - stride] - mesh.positions[v]).normalize()) > 0.97, "B up the meridian");
        }
    }

    #[test]
    fn sphere_regions() {
        let sphere = uv_sphere(64, 32);
        let count = |r| sphere.regions.iter().filter(|&&x| x == r).count();
        // Poles: the pole rows (64 each) and rings 1 and 31 (65 each), all within 5° at 32 rings.
        assert_eq!(count(Region::Pole), 2 * 64 + 2 * 65);
        assert_eq!(count(Region::Seam), 2 * 29);
        assert_eq!(sphere.regions.len(), sphere.mesh.positions.len());
    }

    #[test]
    fn sine_bumps_have_unit_maximum_slope_and_fill_the_sample_range() {
        let bumps = SineBumps::new(32, 1);
        let (dx, _) = bumps.slope(0.0, bumps.period_m / 4.0);
        assert!((dx - 1.0).abs() < 1e-12);
        let field = bumps.field();
        let (lo, hi) = field.samples.iter().fold((1.0f32, 0.0f32), |(lo, hi), &s| (lo.min(s), hi.max(s)));
        assert!(lo >= 0.0 && hi <= 1.0 && hi - lo > 0.95, "{lo} {hi}");
    }
}

//! The detail-blend study: every [`DetailBlend`] method against the two exact answers, on
//! height fields whose slopes are known in closed form.
//!
//! The base is a height field `h_b` with slope `g_b = ∇h_b`; the detail a sine pair
//! `h_d(x, y) = (s / k)·(sin(k·x) + sin(k·y))` of strength `s` (slopes `s·cos(k·x)`,
//! `s·cos(k·y)`, at most `s`). Each is a tangent-space normal map, `normalize(−∇h, 1)`. The two
//! references ([`added_heights`], [`rotated_detail`]) answer two questions: (a) the detail
//! height added to the base height, whose normal is `normalize(−(g_b + g_d), 1)`; (b) the
//! detail height raised along the base surface's normal, in the base's own frame turned onto
//! it (the shortest arc from +Z to the base normal), whose normal is that rotation of the
//! detail's. Methods run in `f32` as the shader does; references in `f64`.

use glam::{DQuat, DVec2, DVec3};

use crate::names::Named;
use crate::scene::DetailBlend;
use crate::shading::detail_blend::blend;

/// A tangent-space normal from a height field's slope `g = (∂h/∂x, ∂h/∂y)` (unitless).
pub fn normal_of_slope(g: DVec2) -> DVec3 {
    DVec3::new(-g.x, -g.y, 1.0).normalize()
}

/// Reference (a): the normal of `h_b + h_d`, slopes `g_b + g_d`.
pub fn added_heights(base_slope: DVec2, detail_slope: DVec2) -> DVec3 {
    normal_of_slope(base_slope + detail_slope)
}

/// Reference (b): the detail's normal turned by the shortest arc that takes +Z to the base
/// normal — the detail laid along the base surface in the base's own frame.
pub fn rotated_detail(base_slope: DVec2, detail_slope: DVec2) -> DVec3 {
    let base = normal_of_slope(base_slope);
    DQuat::from_rotation_arc(DVec3::Z, base) * normal_of_slope(detail_slope)
}

/// The angle between two unit vectors in degrees, accurate near 0 (`atan2(|a×b|, a·b)`).
pub fn angle_deg(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

/// `method` on the normals of `base_slope` and `detail_slope`, as the shader computes it (f32).
pub fn blended(method: DetailBlend, base_slope: DVec2, detail_slope: DVec2) -> DVec3 {
    let b = normal_of_slope(base_slope).as_vec3();
    let d = normal_of_slope(detail_slope).as_vec3();
    blend(method, b, d).as_dvec3()
}

/// The lit value of a normal under the study's light: `0.8·max(n·L, 0) + 0.2·max(n·H, 0)^32`
/// (L at 45° elevation, the view along +Z).
pub fn lit(n: DVec3) -> f64 {
    let light = DVec3::new(0.5, 0.5, std::f64::consts::FRAC_1_SQRT_2).normalize();
    let half = (light + DVec3::Z).normalize();
    0.8 * n.dot(light).max(0.0) + 0.2 * n.dot(half).max(0.0).powi(32)
}

/// One method's errors at one base tilt and strength.
#[derive(Debug, Clone, PartialEq)]
pub struct DetailRow {
    pub method: &'static str,
    /// The base normal's tilt from +Z, degrees.
    pub tilt_deg: f64,
    /// The detail's strength (its steepest slope).
    pub strength: f64,
    /// Mean, 95th percentile and largest angle against reference (a) and (b), degrees.
    pub added: [f64; 3],
    pub rotated: [f64; 3],
    /// RMSE of [`lit`] against each reference's.
    pub lit_rmse: [f64; 2],
}

/// The study's grid: base tilts (degrees), detail strengths, detail phases per axis and
/// base azimuths.
#[derive(Debug, Clone, PartialEq)]
pub struct DetailPlan {
    pub tilts_deg: Vec<f64>,
    pub strengths: Vec<f64>,
    pub phases: u32,
    pub azimuths: u32,
}

impl DetailPlan {
    /// What `bumpview report` measures: tilts 0–60° by 10°, strengths 0.25, 0.5, 1, 2, 32×32
    /// phases, 8 azimuths.
    pub fn full() -> DetailPlan {
        DetailPlan {
            tilts_deg: (0..=6).map(|i| f64::from(i) * 10.0).collect(),
            strengths: vec![0.25, 0.5, 1.0, 2.0],
            phases: 32,
            azimuths: 8,
        }
    }
}

/// `(mean, p95, max)` of `values`.
fn summary(mut values: Vec<f64>) -> [f64; 3] {
    values.sort_by(f64::total_cmp);
    let n = values.len().max(1);
    let mean = values.iter().sum::<f64>() / n as f64;
    let p95 = values.get(((n - 1) as f64 * 0.95).round() as usize).copied().unwrap_or(0.0);
    [mean, p95, values.last().copied().unwrap_or(0.0)]
}

/// The base slopes (a plane tilted `tilt_deg` at `azimuths` azimuths) and the detail slopes
/// (the sine pair of `strength` at `phases × phases` points of a period).
pub fn samples(tilt_deg: f64, strength: f64, plan: &DetailPlan) -> Vec<(DVec2, DVec2)> {
    let tan = tilt_deg.to_radians().tan();
    let step = std::f64::consts::TAU / f64::from(plan.phases);
    let mut out = vec![];
    for a in 0..plan.azimuths {
        let azimuth = std::f64::consts::TAU * (f64::from(a) + 0.5) / f64::from(plan.azimuths);
        let base = DVec2::new(azimuth.cos(), azimuth.sin()) * tan;
        for i in 0..plan.phases {
            for j in 0..plan.phases {
                let detail = DVec2::new((f64::from(i) * step).cos(), (f64::from(j) * step).cos()) * strength;
                out.push((base, detail));
            }
        }
    }
    out
}

/// One method's row over `points` (base slope, detail slope).
pub fn row(method: DetailBlend, tilt_deg: f64, strength: f64, points: &[(DVec2, DVec2)]) -> DetailRow {
    let (mut added, mut rotated, mut lit_sq) = (vec![], vec![], [0.0; 2]);
    for &(b, d) in points {
        let n = blended(method, b, d);
        let (ra, rb) = (added_heights(b, d), rotated_detail(b, d));
        added.push(angle_deg(n, ra));
        rotated.push(angle_deg(n, rb));
        lit_sq[0] += (lit(n) - lit(ra)).powi(2);
        lit_sq[1] += (lit(n) - lit(rb)).powi(2);
    }
    let count = points.len().max(1) as f64;
    DetailRow {
        method: method.name(),
        tilt_deg,
        strength,
        added: summary(added),
        rotated: summary(rotated),
        lit_rmse: lit_sq.map(|s| (s / count).sqrt()),
    }
}

/// Every method at every tilt and strength of `plan`.
pub fn study(plan: &DetailPlan) -> Vec<DetailRow> {
    let mut rows = vec![];
    for &tilt in &plan.tilts_deg {
        for &strength in &plan.strengths {
            let points = samples(tilt, strength, plan);
            rows.extend(DetailBlend::all().iter().map(|&m| row(m, tilt, strength, &points)));
        }
    }
    rows
}

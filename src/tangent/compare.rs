//! Angular error of tangent frames against a reference frame, per vertex and summarised.

use glam::{Vec3, Vec4};

use super::bitangent;

/// Angles in degrees between two frames at each vertex: `tangent[i]` between the `T`s,
/// `bitangent[i]` between the `B = w · cross(N, T)`s (so a wrong `w` shows as 180°).
#[derive(Debug, Clone, PartialEq)]
pub struct FrameAngles {
    pub tangent: Vec<f32>,
    pub bitangent: Vec<f32>,
}

/// The angle between two directions in degrees, as `atan2(|a × b|, a · b)` in f64: exact
/// down to rounding even for tiny angles, unlike `acos` of an f32 dot product, which cannot
/// tell angles below about 0.02° from zero. 0 when either vector is zero.
pub fn angle_degrees(a: Vec3, b: Vec3) -> f32 {
    let (a, b) = (a.as_dvec3(), b.as_dvec3());
    a.cross(b).length().atan2(a.dot(b)).to_degrees() as f32
}

/// Compares `frames` with `reference` at each vertex with unit normal `normals[i]`.
pub fn frame_angles(normals: &[Vec3], frames: &[Vec4], reference: &[Vec4]) -> FrameAngles {
    let angle = angle_degrees;
    let mut angles = FrameAngles { tangent: vec![], bitangent: vec![] };
    for ((&n, &f), &r) in normals.iter().zip(frames).zip(reference) {
        angles.tangent.push(angle(f.truncate(), r.truncate()));
        angles.bitangent.push(angle(bitangent(n, f), bitangent(n, r)));
    }
    angles
}

/// Mean, root-mean-square and maximum of a set of angles (degrees).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AngleStats {
    pub mean: f32,
    pub rms: f32,
    pub max: f32,
    pub count: usize,
}

impl AngleStats {
    /// Statistics of `angles`; all zero for an empty set. Non-finite angles count as 180°.
    pub fn of(angles: impl IntoIterator<Item = f32>) -> AngleStats {
        let (mut sum, mut sum_squares, mut max, mut count) = (0.0f64, 0.0f64, 0.0f32, 0usize);
        for a in angles {
            let a = if a.is_finite() { a } else { 180.0 };
            sum += a as f64;
            sum_squares += (a as f64) * (a as f64);
            max = max.max(a);
            count += 1;
        }
        if count == 0 {
            return AngleStats::default();
        }
        let n = count as f64;
        AngleStats { mean: (sum / n) as f32, rms: (sum_squares / n).sqrt() as f32, max, count }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flipped_handedness_is_a_half_turn_of_the_bitangent() {
        let n = [Vec3::Z];
        let angles = frame_angles(&n, &[Vec4::new(1.0, 0.0, 0.0, -1.0)], &[Vec4::new(1.0, 0.0, 0.0, 1.0)]);
        assert!(angles.tangent[0].abs() < 1e-4 && (angles.bitangent[0] - 180.0).abs() < 1e-3);
    }

    #[test]
    fn tiny_angles_are_resolved() {
        let tiny = 1e-5f32.to_radians();
        let a = angle_degrees(Vec3::X, Vec3::new(tiny.cos(), tiny.sin(), 0.0));
        assert!((a - 1e-5).abs() < 1e-8, "{a}");
    }

    #[test]
    fn stats_of_known_angles() {
        let s = AngleStats::of([3.0, 4.0, f32::NAN]);
        assert_eq!(s.count, 3);
        assert!((s.max - 180.0).abs() < 1e-6 && (s.mean - 187.0 / 3.0).abs() < 1e-4);
        assert_eq!(AngleStats::of([]), AngleStats::default());
    }
}

/// One tangent method timed on one mesh and compared with the reference frame.
#[derive(Debug, Clone, PartialEq)]
pub struct MethodMeasurement {
    /// The method that made the frames (a fallback when the chosen one had nothing to offer).
    pub method: super::TangentMethod,
    /// Analytic where the mesh has it, else MikkTSpace.
    pub reference: super::TangentMethod,
    /// Wall-clock time of one run of the method, seconds (the best of three).
    pub seconds: f64,
    pub tangent: AngleStats,
    pub bitangent: AngleStats,
}

/// Runs `choice` on `mesh` (see [`super::resolve`]) three times, keeps the fastest time,
/// and compares its frames with [`super::reference`] on the same geometry.
pub fn measure(mesh: &crate::scene::Mesh, choice: Option<super::TangentMethod>) -> MethodMeasurement {
    let geometry = if choice == Some(super::TangentMethod::PerFace) { mesh.unwelded() } else { mesh.clone() };
    let mut best = f64::INFINITY;
    let mut result = None;
    for _ in 0..3 {
        let start = web_time::Instant::now();
        let frames = super::resolve(&geometry, choice);
        best = best.min(start.elapsed().as_secs_f64());
        result = Some(frames);
    }
    let (frames, method) = result.expect("ran three times");
    let (reference, reference_method) = super::reference(&geometry);
    let angles = frame_angles(&geometry.normals, &frames, &reference);
    MethodMeasurement {
        method,
        reference: reference_method,
        seconds: best,
        tangent: AngleStats::of(angles.tangent),
        bitangent: AngleStats::of(angles.bitangent),
    }
}

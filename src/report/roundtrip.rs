//! Two comparisons beside the error tables: heights → normals → heights on the sine plane
//! (the Frankot–Chellappa solve of `bumpview bake --to-height`), and meshoptimizer's
//! MikkTSpace-compatible frames against bevy_mikktspace's on the reference surfaces.

use glam::Vec3;

use super::surfaces::{Reference, SineBumps};
use super::timing::{Repeats, median_seconds};
use crate::bake::slopes_of;
use crate::height::derivative::Derivative;
use crate::height::integrate::integrate;
use crate::height::{Border, Kernel, rows};
use crate::tangent::{AngleStats, TangentMethod, frame_angles, tangents};

/// One round trip: the sine plane's central-difference normals, stored at `bits` (none:
/// float), integrated back with `derivative`; height errors in full ranges, mean removed.
#[derive(Debug, Clone, PartialEq)]
pub struct RoundTrip {
    /// `float`, `16-bit` or `8-bit` normals.
    pub normals: &'static str,
    pub derivative: Derivative,
    pub rms: f64,
    pub max: f64,
    /// Median seconds of the solve (slopes from normals, then the integration).
    pub seconds: f64,
    pub texels: usize,
}

/// A unit normal's components stored with `bits` bits (`round(levels · (0.5·c + 0.5))`) and
/// decoded again (`2·c − 1`, normalised).
fn stored(n: Vec3, bits: Option<u32>) -> [f32; 3] {
    let Some(bits) = bits else { return n.to_array() };
    let levels = ((1u32 << bits) - 1) as f32;
    let q = n.map(|c| ((0.5 * c + 0.5) * levels).round() / levels * 2.0 - 1.0);
    q.normalize().to_array()
}

/// The round trips on `bumps` (float heights, wrapped): float, 16-bit and 8-bit normals, each
/// integrated with the central difference's own symbol and with the spectral `iω`.
pub fn round_trips(bumps: &SineBumps, repeats: Repeats) -> Vec<RoundTrip> {
    let field = bumps.field();
    let grid = field.grid();
    let normals = rows::normals(&grid, Kernel::CentralDifference, Border::Wrap);
    let mean = |v: &[f32]| v.iter().map(|&x| x as f64).sum::<f64>() / v.len() as f64;
    let original_mean = mean(&field.samples);
    let mut trips = vec![];
    for (label, bits) in [("float", None), ("16-bit", Some(16)), ("8-bit", Some(8))] {
        let stored: Vec<[f32; 3]> = normals.iter().map(|&n| stored(n, bits)).collect();
        for derivative in [Derivative::Kernel(Kernel::CentralDifference), Derivative::Spectral] {
            let (seconds, heights) = median_seconds(repeats, || {
                let slopes = slopes_of(&stored, grid.width, grid.height, grid.slope_scale);
                integrate(&slopes, derivative, Border::Wrap)
            });
            let recovered_mean = mean(&heights);
            let errors: Vec<f64> = heights
                .iter()
                .zip(&field.samples)
                .map(|(&h, &s)| (h as f64 - recovered_mean) - (s as f64 - original_mean))
                .collect();
            let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
            let max = errors.iter().fold(0.0f64, |m, e| m.max(e.abs()));
            trips.push(RoundTrip { normals: label, derivative, rms, max, seconds, texels: heights.len() });
        }
    }
    trips
}

/// meshoptimizer's frames against MikkTSpace's on one reference surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Agreement {
    /// The surface as the tables name it, e.g. `sphere 256x128`.
    pub surface: String,
    pub tangent: AngleStats,
    pub bitangent: AngleStats,
}

/// [`TangentMethod::Meshopt`] against [`TangentMethod::MikkTSpace`] on `reference`.
pub fn agreement(surface: String, reference: &Reference) -> Agreement {
    let mesh = &reference.mesh;
    let ours = tangents(mesh, TangentMethod::Meshopt).expect("generated");
    let mikk = tangents(mesh, TangentMethod::MikkTSpace).expect("generated");
    let angles = frame_angles(&mesh.normals, &ours, &mikk);
    Agreement { surface, tangent: AngleStats::of(angles.tangent), bitangent: AngleStats::of(angles.bitangent) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (0.48, 0.6, 0.64) is unit; `0.5·c + 0.5` = (0.74, 0.8, 0.82) lies at (188.7, 204, 209.1)
    /// of 255 levels and (48 495.9, 52 428, 53 738.7) of 65 535, none near a half: stored, it
    /// decodes from the levels rounded by hand, so rounding to 10 or 12 bits fails.
    #[test]
    fn storing_rounds_to_the_levels() {
        let n = Vec3::new(0.48, 0.6, 0.64);
        assert_eq!(stored(n, None), n.to_array());
        let decoded = |levels: [f32; 3], of: f32| (Vec3::from_array(levels) / of * 2.0 - 1.0).normalize();
        for (bits, levels, of) in [(8, [189.0, 204.0, 209.0], 255.0), (16, [48496.0, 52428.0, 53739.0], 65535.0)] {
            let expected = decoded(levels, of);
            let got = Vec3::from_array(stored(n, Some(bits)));
            assert!((got - expected).abs().max_element() < 1e-6, "{bits} bits: {got} against {expected}");
        }
    }
}

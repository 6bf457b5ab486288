//! DOT3's normalization cube map (Cg tutorial 8.1.3) against exact normalisation, per face
//! size: directions spread evenly over the sphere (a Fibonacci lattice) looked up as the
//! shader does ([`crate::chain::legacy::cube_map_lookup`], bilinear within a face, 8-bit
//! texels, not re-normalised). The error that matters for 8-bit colour is the one in `N·L`:
//! at most `|L_cube − L̂|` for a unit `N` (reached with `N` along the difference), counted in
//! steps of 1/255.

use glam::Vec3;

use crate::chain::legacy::{cube_face, cube_map, cube_map_lookup};
use crate::frame::CUBE_MAP_SIZES;

/// The errors of one face size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CubeMapRow {
    pub size: u32,
    /// Angle between the looked-up vector and the exact direction, degrees.
    pub mean_deg: f32,
    pub max_deg: f32,
    /// `| |L_cube| − 1 |` at most: the length the bilinear mix of unit texels loses.
    pub max_length_error: f32,
    /// `|L_cube − L̂|` at most and at the 99.9th percentile, in steps of 1/255: the largest
    /// change of `N·L`.
    pub max_steps: f32,
    pub p999_steps: f32,
    /// The same at most, away from the faces' edges (where the bilinear lookup has four
    /// texels of its face; within half a texel of an edge it is clamped to the edge texels,
    /// where hardware with seamless cube filtering would blend in the next face).
    pub interior_max_steps: f32,
}

/// `count` unit directions evenly over the sphere (the Fibonacci lattice).
pub fn fibonacci_directions(count: usize) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / count as f32;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f32;
            Vec3::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// One row per face size of [`CUBE_MAP_SIZES`] over `count` directions.
pub fn cube_map_rows(count: usize) -> Vec<CubeMapRow> {
    let directions = fibonacci_directions(count);
    CUBE_MAP_SIZES
        .iter()
        .map(|&size| {
            let texels = cube_map(size);
            let mut steps = Vec::with_capacity(directions.len());
            let (mut sum_deg, mut max_deg, mut max_length_error, mut interior) = (0.0f64, 0.0f32, 0.0f32, 0.0f32);
            for &d in &directions {
                let looked_up = cube_map_lookup(&texels, size, d);
                let texel = (cube_face(d).1 + 1.0) * 0.5 * size as f32 - 0.5;
                if texel.min_element() >= 0.0 && texel.max_element() <= (size - 1) as f32 {
                    interior = interior.max((looked_up - d).length() * 255.0);
                }
                let angle = looked_up.angle_between(d).to_degrees();
                sum_deg += f64::from(angle);
                max_deg = max_deg.max(angle);
                max_length_error = max_length_error.max((looked_up.length() - 1.0).abs());
                steps.push((looked_up - d).length() * 255.0);
            }
            steps.sort_by(f32::total_cmp);
            CubeMapRow {
                size,
                mean_deg: (sum_deg / directions.len().max(1) as f64) as f32,
                max_deg,
                max_length_error,
                max_steps: steps.last().copied().unwrap_or(0.0),
                p999_steps: steps[((steps.len() - 1) as f32 * 0.999) as usize],
                interior_max_steps: interior,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The error falls with the face size; the lattice is unit and covers both poles.
    #[test]
    fn larger_faces_err_less() {
        let directions = fibonacci_directions(1000);
        assert!(directions.iter().all(|d| (d.length() - 1.0).abs() < 1e-5));
        let rows = cube_map_rows(super::super::CUBE_MAP_DIRECTIONS);
        for r in &rows {
            println!(
                "{0}x{0}: mean {1:.3}°, max {2:.3}°, length {3:.4}, N·L 99.9% {4:.2} steps, max {5:.2}, interior max {6:.2}",
                r.size, r.mean_deg, r.max_deg, r.max_length_error, r.p999_steps, r.max_steps, r.interior_max_steps
            );
        }
        assert!(rows.windows(2).all(|w| w[1].max_deg < w[0].max_deg), "{rows:?}");
    }
}

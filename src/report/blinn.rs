//! Blinn's 1978 bump approximation against the exact normal of a displaced sphere, on the
//! CPU. A sphere of radius `R` displaced along its normal by `F(θ, φ)` is `P' = (R + F) n`;
//! its exact normal is `P'_θ × P'_φ` with `P'_u = (1 + F/R) P_u + F_u n`. Blinn ("Simulation of
//! wrinkled surfaces", 1978) drops the `F · ∂n/∂u` terms: `N' = (P_θ + F_θ n) × (P_φ + F_φ n)`
//! (his `N + (F_u (N × P_v) − F_v (N × P_u)) / |N|`). The two differ by the factor
//! `1 + F/R` on the tangents, so the error grows with `h/R`.

use glam::DVec3;

/// One line of the table: the bump's height over the radius and the normals' difference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlinnRow {
    /// Largest height over the sphere's radius.
    pub h_over_r: f64,
    /// Mean tilt of the exact normal from the sphere's, degrees.
    pub mean_tilt_deg: f64,
    /// Mean and largest angle between Blinn's and the exact normal, degrees.
    pub mean_error_deg: f64,
    pub max_error_deg: f64,
}

/// Bumps per half turn of the pattern `F = h · ½ (1 + sin(kφ) sin(kθ))`.
pub const BUMPS_K: f64 = 8.0;
/// The `h/R` the table lists.
pub const H_OVER_R: [f64; 5] = [0.001, 0.01, 0.03, 0.1, 0.3];

/// The table: for each `h/R` of [`H_OVER_R`], Blinn's normal against the exact one at
/// `samples × 2·samples` points of the sphere away from the poles (θ in 0.1π..0.9π, where
/// the parameterisation is regular).
pub fn blinn_rows(samples: u32) -> Vec<BlinnRow> {
    H_OVER_R.iter().map(|&h| row(h, samples)).collect()
}

fn row(h: f64, samples: u32) -> BlinnRow {
    let radius = 1.0;
    let (mut tilt, mut error, mut max_error, mut count) = (0.0, 0.0, 0.0f64, 0.0);
    for i in 0..samples {
        let theta = std::f64::consts::PI * (0.1 + 0.8 * (i as f64 + 0.5) / samples as f64);
        for j in 0..2 * samples {
            let phi = std::f64::consts::PI * (j as f64 + 0.5) / samples as f64;
            let (st, ct, sp, cp) = (theta.sin(), theta.cos(), phi.sin(), phi.cos());
            let n = DVec3::new(st * cp, st * sp, ct);
            let p_theta = radius * DVec3::new(ct * cp, ct * sp, -st);
            let p_phi = radius * DVec3::new(-st * sp, st * cp, 0.0);
            let f = h * radius * 0.5 * (1.0 + (BUMPS_K * phi).sin() * (BUMPS_K * theta).sin());
            let f_theta = h * radius * 0.5 * BUMPS_K * (BUMPS_K * phi).sin() * (BUMPS_K * theta).cos();
            let f_phi = h * radius * 0.5 * BUMPS_K * (BUMPS_K * phi).cos() * (BUMPS_K * theta).sin();
            let scale = 1.0 + f / radius;
            let exact = (p_theta * scale + n * f_theta).cross(p_phi * scale + n * f_phi).normalize();
            let blinn = (p_theta + n * f_theta).cross(p_phi + n * f_phi).normalize();
            let angle = |a: DVec3, b: DVec3| a.dot(b).clamp(-1.0, 1.0).acos().to_degrees();
            let e = angle(exact, blinn);
            tilt += angle(exact, n);
            error += e;
            max_error = max_error.max(e);
            count += 1.0;
        }
    }
    BlinnRow { h_over_r: h, mean_tilt_deg: tilt / count, mean_error_deg: error / count, max_error_deg: max_error }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// For small bumps the error is about the tilt times `h/R` (the tangents' factor
    /// `1 + F/R`, F about h/2 on average): it grows with `h/R`, and vanishes with it.
    #[test]
    fn the_error_grows_with_h_over_r() {
        let rows = blinn_rows(64);
        for pair in rows.windows(2) {
            assert!(pair[1].mean_error_deg > pair[0].mean_error_deg, "{rows:?}");
        }
        let small = rows[0];
        let expected = small.mean_tilt_deg * small.h_over_r * 0.5;
        assert!((small.mean_error_deg / expected - 1.0).abs() < 0.5, "{small:?}, about {expected}");
    }
}

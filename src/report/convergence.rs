//! Convergence: how fast the error falls as the resolution grows (fitted orders), and whether
//! the parallax study's displacement reference has converged (one test for the full and the
//! quick run).

use super::measure::{Row, Study, Vector};
use super::parallax::{DISPLACEMENT, ImageError, ParallaxRow};
use super::surfaces::Region;

/// The displacement reference's test: its picture at the convergence angle differs from the
/// picture one level coarser by at most this RMSE (linear RGB, 1 % of the range). Each level
/// halves the tessellation's edge and the step between levels falls about as fast as the
/// error does (level 8, 9 → 10 on the wall at 70°: 0.0116, 0.0057), so a reference that passes
/// is about one step, under 1 %, from the converged picture.
pub const REFERENCE_STEP_RMSE: f64 = 0.01;

/// A specimen's reference level and how far the picture one level below it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceStep {
    pub level: u32,
    /// The level below against the reference, at the convergence angle.
    pub below: ImageError,
}

impl ReferenceStep {
    /// Whether the reference passes the test ([`REFERENCE_STEP_RMSE`]).
    pub fn converged(&self) -> bool {
        self.below.rmse <= REFERENCE_STEP_RMSE
    }
}

/// The step of `specimen`'s reference at `angle_deg`: `None` where the study did not draw the
/// level below it there.
pub fn reference_step(rows: &[ParallaxRow], specimen: &str, angle_deg: f32) -> Option<ReferenceStep> {
    let displaced =
        |r: &&ParallaxRow| r.specimen == specimen && r.angle_deg == angle_deg && r.technique == DISPLACEMENT;
    let level = rows.iter().filter(displaced).filter_map(|r| r.level).max()?;
    let below_level = level.checked_sub(1)?;
    let below = rows.iter().filter(displaced).find(|r| r.level == Some(below_level))?;
    Some(ReferenceStep { level, below: below.error })
}

/// Mean errors at or below this many degrees are rounding noise of f32 frames and samples,
/// not truncation error, and are left out of the fits.
pub const NOISE_FLOOR_DEGREES: f64 = 1e-4;

/// The fitted order of one method on one surface and region for one vector.
#[derive(Debug, Clone, PartialEq)]
pub struct Order {
    pub study: Study,
    pub method: &'static str,
    pub surface: String,
    pub region: Region,
    pub vector: Vector,
    /// `p` in `mean error ∝ resolution^−p`; `None` with fewer than two usable points.
    pub order: Option<f64>,
    /// Resolutions whose mean error was above [`NOISE_FLOOR_DEGREES`] and so entered the fit.
    pub points: usize,
}

/// `−slope` of the least-squares line through `(ln resolution, ln error)`, using only the
/// points with `error > floor`; `None` with fewer than two such points.
pub fn fitted_order(points: &[(f64, f64)], floor: f64) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points.iter().filter(|&&(_, e)| e > floor).map(|&(r, e)| (r.ln(), e.ln())).collect();
    if logs.len() < 2 {
        return None;
    }
    let n = logs.len() as f64;
    let (mean_x, mean_y) = logs.iter().fold((0.0, 0.0), |(x, y), &(a, b)| (x + a / n, y + b / n));
    let sxx: f64 = logs.iter().map(|&(x, _)| (x - mean_x).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|&(x, y)| (x - mean_x) * (y - mean_y)).sum();
    (sxx > 0.0).then(|| -sxy / sxx)
}

/// Orders of the mean error for every (method, surface, region, vector) measured at two or
/// more resolutions, in the order the rows first name them.
pub fn orders(rows: &[Row]) -> Vec<Order> {
    let mut result: Vec<Order> = vec![];
    for row in rows {
        for &(vector, _) in &row.errors {
            let same = |r: &&Row| r.method == row.method && r.surface == row.surface && r.region == row.region;
            if result.iter().any(|o| {
                o.method == row.method && o.surface == row.surface && o.region == row.region && o.vector == vector
            }) {
                continue;
            }
            let points: Vec<(f64, f64)> = rows
                .iter()
                .filter(same)
                .filter_map(|r| r.error(vector).map(|s| (r.resolution as f64, s.mean as f64)))
                .collect();
            if points.len() < 2 {
                continue;
            }
            result.push(Order {
                study: row.study,
                method: row.method,
                surface: row.surface.clone(),
                region: row.region,
                vector,
                order: fitted_order(&points, NOISE_FLOOR_DEGREES),
                points: points.iter().filter(|&&(_, e)| e > NOISE_FLOOR_DEGREES).count(),
            });
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    fn displaced(level: u32, rmse: f64) -> ParallaxRow {
        ParallaxRow {
            specimen: "wall".into(),
            angle_deg: 70.0,
            technique: DISPLACEMENT,
            layers: None,
            level: Some(level),
            error: ImageError { rmse, off_share: 0.5 },
            frame_ms: 1.0,
        }
    }

    #[test]
    fn the_reference_step_is_the_level_below_against_the_reference() {
        let rows = [displaced(10, 0.0), displaced(8, 0.0116), displaced(9, 0.0057)];
        let step = reference_step(&rows, "wall", 70.0).expect("a step");
        assert_eq!(step.level, 10);
        assert_eq!(step.below.rmse, 0.0057);
        assert!(step.converged());
        let coarse = [displaced(7, 0.0), displaced(6, 0.0290)];
        assert!(!reference_step(&coarse, "wall", 70.0).expect("a step").converged());
        assert_eq!(reference_step(&rows, "wall", 0.0), None);
        assert_eq!(reference_step(&rows[..1], "wall", 70.0), None);
    }

    #[test]
    fn power_laws_give_their_exponent() {
        let points: Vec<(f64, f64)> = [8.0, 16.0, 32.0, 64.0].iter().map(|&r: &f64| (r, 3.0 * r.powf(-2.0))).collect();
        assert!((fitted_order(&points, 0.0).unwrap() - 2.0).abs() < 1e-12);
        // Points under the floor are left out; one point is not enough.
        assert!((fitted_order(&points, 1e-3).unwrap() - 2.0).abs() < 1e-12);
        assert_eq!(fitted_order(&points, 0.02), None);
    }
}

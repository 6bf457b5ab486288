//! `{uv_error}` in a lesson's claim: for each side, the mean distance in texels between the
//! UV its parallax technique reads and the UV of the view ray's exact first intersection with
//! the height field ([`crate::report::uv_error`], the measure of the UV-error study in
//! docs/parallax.md), on the built-in wall's bricks seen from the lesson's
//! `uv_error_angle_deg` at the lesson's relief depth, over a [`GRID`]² grid of the tile,
//! measured once when the lesson is read. It depends on the technique's
//! settings and the angle only, not on the picture: the texture-space error a parallax lesson
//! is about, free of shading.

use std::sync::LazyLock;

use super::Lesson;
use crate::error::PresetError;
use crate::frame::ParallaxSettings;
use crate::report::uv_error::{Relief, mean_uv_error};

/// Points per side of the grid the error is averaged over (48² rays).
pub const GRID: u32 = 48;
/// The steepest angle a claim may be measured at, degrees from the wall's normal.
pub const MAX_ANGLE_DEG: f32 = 85.0;

/// The wall's relief with and without its cone map (made once, on first use).
static WALL: LazyLock<Relief> = LazyLock::new(|| Relief::wall_with_cones(false));
static WALL_WITH_CONES: LazyLock<Relief> = LazyLock::new(|| Relief::wall_with_cones(true));

/// Each side's parallax settings, as its picture is drawn.
fn side_parallax(lesson: &Lesson) -> Result<Vec<ParallaxSettings>, PresetError> {
    lesson.sides.iter().map(|side| Ok(side.preset.shading_of(side.half)?.parallax)).collect()
}

/// "LABEL: X.XX texels" for each side drawn with `settings`, joined by "; ", seen from
/// `angle_deg`.
fn uv_error_text(lesson: &Lesson, settings: &[ParallaxSettings], angle_deg: f32) -> String {
    let texts: Vec<String> = lesson
        .sides
        .iter()
        .zip(settings)
        .map(|(side, parallax)| {
            let wall: &Relief = if parallax.technique.reads_cones() { &WALL_WITH_CONES } else { &WALL };
            // The lesson's depth where it sets one, as its picture has it.
            let relief = Relief { depth_m: parallax.depth_m.unwrap_or(wall.depth_m), ..wall.clone() };
            format!("{}: {:.2} texels", side.label, mean_uv_error(&relief, angle_deg, parallax, GRID))
        })
        .collect();
    texts.join("; ")
}

/// What `lesson`'s claim says for `{uv_error}` at its file's `uv_error_angle_deg`
/// ([`uv_error_text`]), `None` without one. The two come together, the angle within
/// 0..=[`MAX_ANGLE_DEG`] and every side's settings read.
pub fn measured(lesson: &Lesson, angle_deg: Option<f32>) -> Result<Option<String>, String> {
    let says = lesson.claim.contains("{uv_error}");
    match angle_deg {
        None if says => Err("the claim says {uv_error}: give uv_error_angle_deg, the angle it is measured at".into()),
        None => Ok(None),
        Some(_) if !says => Err("uv_error_angle_deg is given: the claim says {uv_error} where the errors go".into()),
        Some(angle) if !(0.0..=MAX_ANGLE_DEG).contains(&angle) => {
            Err(format!("uv_error_angle_deg = {angle}: an angle from 0 to {MAX_ANGLE_DEG} degrees"))
        }
        Some(angle) => Ok(Some(uv_error_text(lesson, &side_parallax(lesson).map_err(|e| e.0)?, angle))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::Parallax;
    use crate::report::parallax::settings;
    use crate::report::uv_error::{grid, uv_error};

    fn lesson(extra: &str, claim: &str) -> Result<Lesson, String> {
        let text = format!(
            "title = \"t\"\ncaption = \"c\"\nclaim = \"{claim}\"\n{extra}\n[preset.shading]\nparallax_layers = [8, 8]\n\
             [[tiles]]\nlabel = \"steep\"\npreset.shading.parallax = \"steep\"\n\
             [[tiles]]\nlabel = \"occlusion\"\npreset.shading.parallax = \"occlusion\"\n"
        );
        Lesson::parse("uv", &text).map_err(|e| e.message)
    }

    /// The claim's numbers are the UV-error study's own measure for the same settings, and
    /// occlusion's interpolation lands nearer the exact hit than steep's last layer.
    #[test]
    fn the_claim_holds_the_studys_errors_for_each_side() {
        let lesson = lesson("uv_error_angle_deg = 70.0", "{uv_error}; {changed}").unwrap();
        let claim = lesson.claim_with(12.0);
        let wall = Relief::wall_with_cones(false);
        let points = grid(GRID);
        let hits: Vec<_> = points.iter().map(|&uv| wall.exact(uv, 70.0)).collect();
        let [steep, occlusion] = [Parallax::Steep, Parallax::Occlusion]
            .map(|technique| uv_error(&wall, &points, &hits, 70.0, (technique, Some(8))).mean);
        assert_eq!(claim, format!("steep: {steep:.2} texels; occlusion: {occlusion:.2} texels; 12.0 %"));
        assert!(occlusion < steep, "{claim}");
        // The same errors, summed in another order.
        assert!((mean_uv_error(&wall, 70.0, &settings(Parallax::Steep, Some(8)), GRID) - steep).abs() < 1e-12);
    }

    #[test]
    fn the_angle_and_the_placeholder_come_together_and_the_angle_is_checked() {
        let e = lesson("", "{uv_error} {changed}").unwrap_err();
        assert!(e.contains("give uv_error_angle_deg"), "{e}");
        let e = lesson("uv_error_angle_deg = 70.0", "{changed}").unwrap_err();
        assert!(e.contains("the claim says {uv_error}"), "{e}");
        let e = lesson("uv_error_angle_deg = 89.5", "{uv_error} {changed}").unwrap_err();
        assert!(e.contains("from 0 to 85"), "{e}");
    }
}

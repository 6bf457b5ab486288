//! Facts about a scene the panel shows, made by the scene job ([`super::scene_job`]) once per
//! scene (`check`) and per tangent method (the method's timing and errors), never per frame.

use bumpview::check::{CheckReport, check_scene};
use bumpview::scene::Scene;
use bumpview::tangent::{MethodMeasurement, TangentMethod, measure};

/// What the panel shows about the current scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneFacts {
    /// Per mesh: the chosen tangent method timed and compared with the reference.
    pub measurements: Vec<(String, MethodMeasurement)>,
    /// The tangent method `measurements` are of (`None`: the automatic choice).
    measured: Option<TangentMethod>,
    /// What `bumpview check` finds in the scene.
    pub check: CheckReport,
    /// `check`'s warnings, one line each.
    pub check_warnings: Vec<String>,
}

impl SceneFacts {
    /// The facts of `scene` with `method`'s measurements; from `held` (the same scene's facts)
    /// what is still true: its check always, its measurements when they are of `method`.
    pub fn renewed(held: Option<&SceneFacts>, scene: &Scene, method: Option<TangentMethod>) -> SceneFacts {
        let measurements = match held.filter(|held| held.measured == method) {
            Some(held) => held.measurements.clone(),
            None => scene.meshes.iter().map(|mesh| (mesh.name.clone(), measure(mesh, method))).collect(),
        };
        let check = held.map_or_else(|| check_scene(scene), |held| held.check.clone());
        SceneFacts { measurements, measured: method, check_warnings: check.warnings(), check }
    }
}

#[cfg(test)]
mod tests {
    use bumpview::scene::builtin::teaching_scene;

    use super::*;

    /// Held facts keep their check and, for the same method, their measurements (times
    /// included, so nothing was measured again); another method is measured anew.
    #[test]
    fn held_facts_are_reused_where_still_true() {
        let scene = teaching_scene();
        let first = SceneFacts::renewed(None, &scene, Some(TangentMethod::PerFace));
        assert_eq!(first.measurements.len(), scene.meshes.len());
        assert_eq!(first.check, check_scene(&scene));
        let mut held = first.clone();
        held.check.meshes.clear();
        let same = SceneFacts::renewed(Some(&held), &scene, Some(TangentMethod::PerFace));
        assert_eq!(same, held, "nothing re-made for the same method");
        let other = SceneFacts::renewed(Some(&held), &scene, None);
        assert_eq!(other.check, held.check, "the check is kept");
        assert_ne!(other.measurements[0].1.method, TangentMethod::PerFace, "measured again");
    }
}

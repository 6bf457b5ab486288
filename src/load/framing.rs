//! The first view of a loaded scene: a camera that frames its bounds, a light above and in
//! front, and an ambient term.

use glam::Vec3;

use crate::scene::{Light, OrbitCamera, Scene};

/// Vertical field of view of a loaded scene's camera, radians (as the built-in scene's).
const FOV_Y: f32 = 50.0 * std::f32::consts::PI / 180.0;
/// Camera elevation above the target, radians (about 14°): from the front and a little above,
/// so that a model lying flat is not seen edge-on.
const PITCH: f32 = 0.25;
/// Extra room around the bounding sphere, as a factor on the camera distance.
const MARGIN: f32 = 1.1;
/// Linear RGB ambient, as the built-in scene's.
const AMBIENT: f32 = 0.08;

/// World-space axis-aligned bounds `(min, max)` of every instance's vertices, metres;
/// `None` when there is no finite vertex.
pub fn bounds(scene: &Scene) -> Option<(Vec3, Vec3)> {
    let mut points = scene.instances.iter().flat_map(|instance| {
        scene.meshes[instance.mesh].positions.iter().map(|&p| instance.transform.transform_point3(p))
    });
    let first = points.find(|p| p.is_finite())?;
    Some(points.filter(|p| p.is_finite()).fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
}

/// Sets the default camera to look at the bounds' centre from the front (+Z, as glTF sample
/// models face) and about 14° above, far enough that the bounding sphere fits the vertical
/// field of view (and the horizontal one for a view at least as wide as tall); the default
/// light sits above, in front and to the left, about two radii out; and an ambient term.
pub fn frame_scene(scene: &mut Scene) {
    let (lo, hi) = bounds(scene).unwrap_or((Vec3::splat(-1.0), Vec3::splat(1.0)));
    let center = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1e-3);
    let distance = MARGIN * radius / (FOV_Y * 0.5).sin();
    scene.default_camera = OrbitCamera { target: center, yaw: 0.0, pitch: PITCH, distance, fov_y: FOV_Y };
    scene.default_light = Light { position: center + radius * Vec3::new(-0.8, 1.2, 1.6), color: Vec3::ONE };
    scene.ambient = Vec3::splat(AMBIENT);
}

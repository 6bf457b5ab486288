//! The first view of a loaded scene: a camera that frames its bounds, a light above and in
//! front, and an ambient term.

use glam::Vec3;

use crate::scene::{Light, OrbitCamera, Scene};

/// Vertical field of view of a loaded scene's camera, radians (as the built-in scene's).
const FOV_Y: f32 = 50.0 * std::f32::consts::PI / 180.0;
/// Camera elevation above the target, radians (about 14°): from the front and a little above,
/// so that a model lying flat is not seen edge-on.
const PITCH: f32 = 0.25;
/// Share of the view's half-height the model may reach above or below the centre: it fills
/// about two thirds of the view's height.
const HEIGHT_FILL: f32 = 2.0 / 3.0;
/// Share of the half-width it may reach in a square view (wider views leave more room).
const WIDTH_FILL: f32 = 0.9;
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
/// models face) and about 14° above, as close as it can while every vertex stays within
/// [`HEIGHT_FILL`] of the view's half-height and [`WIDTH_FILL`] of a square view's half-width
/// (the vertices as drawn, node transforms applied: the model fills about two thirds of the
/// view's height whatever its units); the default light sits above, in front and to the
/// left, about two radii out; and an ambient term.
pub fn frame_scene(scene: &mut Scene) {
    let (lo, hi) = bounds(scene).unwrap_or((Vec3::splat(-1.0), Vec3::splat(1.0)));
    let center = (lo + hi) * 0.5;
    let radius = ((hi - lo).length() * 0.5).max(1e-3);
    let mut camera = OrbitCamera { target: center, yaw: 0.0, pitch: PITCH, distance: 1.0, fov_y: FOV_Y };
    let (right, up) = camera.right_up();
    let back = (camera.eye() - center).normalize();
    let tan = (FOV_Y * 0.5).tan();
    // A vertex at (x, y, z) in the camera's axes around the centre is seen at depth D − z, at
    // NDC y / ((D − z)·tan): the smallest D that keeps |NDC| within the fills.
    let needed = |p: Vec3| {
        let d = p - center;
        let (x, y, z) = (d.dot(right), d.dot(up), d.dot(back));
        z + (y.abs() / (HEIGHT_FILL * tan)).max(x.abs() / (WIDTH_FILL * tan))
    };
    let points = scene.instances.iter().flat_map(|instance| {
        scene.meshes[instance.mesh].positions.iter().map(|&p| instance.transform.transform_point3(p))
    });
    let distance = points.filter(|p| p.is_finite()).map(needed).fold(radius * 0.1, f32::max);
    camera.distance = distance;
    scene.default_camera = camera;
    scene.default_light = Light::point(center + radius * Vec3::new(-0.8, 1.2, 1.6), Vec3::ONE);
    scene.ambient = Vec3::splat(AMBIENT);
}

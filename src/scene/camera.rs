//! Orbit camera: yaw and pitch around a target point, at a distance (world space, metres).

use glam::camera::rh::{proj::directx, view::look_at_mat4};
use glam::{Mat4, Vec2, Vec3};

/// Looks at `target` from `distance` metres. `yaw` turns about +Y (0 looks along −Z, from
/// +Z), `pitch` lifts the eye above the target; both in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitCamera {
    pub target: Vec3,
    pub yaw: f32,
    pub pitch: f32,
    pub distance: f32,
    /// Vertical field of view, radians.
    pub fov_y: f32,
}

/// Pitch stays inside ±89° so the view never flips over the pole.
const PITCH_LIMIT: f32 = 89.0 * std::f32::consts::PI / 180.0;
/// The camera's distance range from its target, metres (zoom and typed distances are clamped).
pub const MIN_DISTANCE: f32 = 0.05;
pub const MAX_DISTANCE: f32 = 500.0;
const NEAR_PLANE: f32 = 0.01;
const FAR_PLANE: f32 = 1000.0;

impl OrbitCamera {
    /// Eye position in world space.
    pub fn eye(&self) -> Vec3 {
        let (sin_yaw, cos_yaw) = self.yaw.sin_cos();
        let (sin_pitch, cos_pitch) = self.pitch.sin_cos();
        self.target + self.distance * Vec3::new(sin_yaw * cos_pitch, sin_pitch, cos_yaw * cos_pitch)
    }

    pub fn view(&self) -> Mat4 {
        look_at_mat4(self.eye(), self.target, Vec3::Y)
    }

    /// The rotation part of [`Self::view`]: world → view space directions.
    pub fn view_rotation(&self) -> glam::Mat3 {
        glam::Mat3::from_mat4(self.view())
    }

    /// Right-handed perspective projection with wgpu's NDC: depth 0..1, Y up.
    pub fn projection(&self, aspect: f32) -> Mat4 {
        directx::perspective(self.fov_y, aspect.max(1e-6), NEAR_PLANE, FAR_PLANE)
    }

    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.projection(aspect) * self.view()
    }

    /// Rotates by the given yaw and pitch increments (radians), pitch clamped to ±89°.
    pub fn orbit(&mut self, d_yaw: f32, d_pitch: f32) {
        self.yaw = (self.yaw + d_yaw).rem_euclid(std::f32::consts::TAU);
        self.pitch = (self.pitch + d_pitch).clamp(-PITCH_LIMIT, PITCH_LIMIT);
    }

    /// Points the camera: `yaw` and `pitch` in radians, kept as [`Self::orbit`] keeps them
    /// (yaw wrapped to 0..2π, pitch clamped to ±89°), `distance` in metres clamped to the
    /// bounds [`Self::zoom`] keeps. Non-finite values leave the camera as it was.
    pub fn point(&mut self, yaw: f32, pitch: f32, distance: f32) {
        if [yaw, pitch, distance].iter().all(|v| v.is_finite()) {
            self.yaw = yaw;
            self.pitch = 0.0;
            self.orbit(0.0, pitch);
            self.distance = distance.clamp(MIN_DISTANCE, MAX_DISTANCE);
        }
    }

    /// Multiplies the distance by `factor` (> 1 moves away), within sane bounds.
    pub fn zoom(&mut self, factor: f32) {
        if factor.is_finite() && factor > 0.0 {
            self.distance = (self.distance * factor).clamp(MIN_DISTANCE, MAX_DISTANCE);
        }
    }

    /// Camera right and up unit vectors in world space.
    pub fn right_up(&self) -> (Vec3, Vec3) {
        let view = self.view();
        (view.row(0).truncate(), view.row(1).truncate())
    }

    /// World-space metres per pixel at `depth` metres in front of the eye, for a viewport
    /// `viewport_height` pixels tall.
    pub fn metres_per_pixel(&self, depth: f32, viewport_height: f32) -> f32 {
        2.0 * depth * (self.fov_y * 0.5).tan() / viewport_height.max(1.0)
    }

    /// Moves the target (and with it the eye) by a screen-space drag in pixels.
    pub fn pan(&mut self, drag_pixels: Vec2, viewport_height: f32) {
        let (right, up) = self.right_up();
        let scale = self.metres_per_pixel(self.distance, viewport_height);
        self.target += (-drag_pixels.x * right + drag_pixels.y * up) * scale;
    }

    /// The world-space ray through a pixel centre: `(origin, unit direction)`.
    /// `pixel` is in pixels from the top-left of a `size` viewport.
    pub fn ray_through_pixel(&self, pixel: Vec2, size: Vec2) -> (Vec3, Vec3) {
        let ndc = Vec2::new(2.0 * pixel.x / size.x - 1.0, 1.0 - 2.0 * pixel.y / size.y);
        let inverse = self.view_projection(size.x / size.y).inverse();
        let near = inverse.project_point3(ndc.extend(0.0));
        let far = inverse.project_point3(ndc.extend(1.0));
        (near, (far - near).normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_ray_points_at_the_target() {
        let camera = OrbitCamera { target: Vec3::new(0.0, 1.0, 0.0), yaw: 0.3, pitch: 0.2, distance: 4.0, fov_y: 0.8 };
        let (origin, dir) = camera.ray_through_pixel(Vec2::new(50.0, 40.0), Vec2::new(100.0, 80.0));
        let to_target = (camera.target - origin).normalize();
        assert!(dir.dot(to_target) > 0.999_999, "{dir} vs {to_target}");
    }

    #[test]
    fn pitch_is_clamped_and_zoom_ignores_nonsense() {
        let mut camera = OrbitCamera { target: Vec3::ZERO, yaw: 0.0, pitch: 0.0, distance: 2.0, fov_y: 0.8 };
        camera.orbit(0.0, 10.0);
        assert!(camera.pitch < std::f32::consts::FRAC_PI_2);
        camera.zoom(f32::NAN);
        camera.zoom(0.0);
        assert_eq!(camera.distance, 2.0);
    }

    #[test]
    fn pointing_keeps_the_orbit_bounds() {
        let mut camera = OrbitCamera { target: Vec3::ZERO, yaw: 0.0, pitch: 0.0, distance: 2.0, fov_y: 0.8 };
        camera.point(-0.5, 2.0, 1e6);
        assert_eq!(camera.yaw, (-0.5f32).rem_euclid(std::f32::consts::TAU));
        assert_eq!((camera.pitch, camera.distance), (PITCH_LIMIT, MAX_DISTANCE));
        camera.point(0.25, -0.3, 0.0);
        assert_eq!((camera.yaw, camera.pitch, camera.distance), (0.25, -0.3, MIN_DISTANCE));
        camera.point(f32::NAN, 0.0, 3.0);
        assert_eq!(camera.distance, MIN_DISTANCE, "a non-finite value changes nothing");
    }
}

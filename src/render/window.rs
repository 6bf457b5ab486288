//! Drawing a part of a picture alone, magnified to fill the frame: how lessons draw their
//! insets without drawing each side many times larger first.

use glam::{Mat4, Vec4};

use super::Renderer;
use crate::scene::OrbitCamera;

/// A part of a picture: `window` (`[x, y, width, height]`, pixels from the top left) of a
/// picture `picture` pixels large.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PictureWindow {
    pub picture: [u32; 2],
    pub window: [u32; 4],
}

impl Renderer {
    /// Draws only `window` of the pictures from now on (`None`: the whole picture again): each
    /// frame, whatever its size, shows that part of the picture the camera would show, magnified
    /// to fill it. Lessons draw their insets so, drawing only what they show.
    pub fn set_window(&mut self, window: Option<PictureWindow>) {
        self.window = window;
    }

    /// The view-projection (world → clip space) of a frame `size` pixels large: the camera's,
    /// or with a window set, the camera's over the whole picture, cropped to the window.
    pub(super) fn view_projection(&self, camera: &OrbitCamera, size: [u32; 2]) -> Mat4 {
        let Some(window) = self.window else { return camera.view_projection(size[0] as f32 / size[1] as f32) };
        let [width, height] = window.picture.map(|c| c.max(1) as f32);
        let [x, y, w, h] = window.window.map(|c| c as f32);
        // Window → NDC: x from x..x + w to −1..1, y (down in pixels) from y..y + h to 1..−1.
        let (sx, sy) = (width / w.max(1.0), height / h.max(1.0));
        let (cx, cy) = ((2.0 * x + w) / width - 1.0, 1.0 - (2.0 * y + h) / height);
        let crop = Mat4::from_cols(
            Vec4::new(sx, 0.0, 0.0, 0.0),
            Vec4::new(0.0, sy, 0.0, 0.0),
            Vec4::Z,
            Vec4::new(-cx * sx, -cy * sy, 0.0, 1.0),
        );
        crop * camera.view_projection(width / height)
    }
}

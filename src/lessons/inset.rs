//! A lesson's magnified inset: for a point that is small by nature (a kernel's half texel, a
//! half vector interpolated across a triangle), the window of the picture where the sides
//! differ most, drawn again magnified from each side. A split lesson's insets are half its
//! picture's width and height, stacked beside it; a grid's are its tiles' size, one under each.
//!
//! Every size and window here is in pixels of the side's picture as the slide shows it.

use image::RgbaImage;

use super::Lesson;
use super::visibility::{VISIBLE_DELTA_E, delta_e_2000, lab};

/// The magnifications a lesson's `inset = { zoom = N }` may ask for.
pub const ZOOMS: std::ops::RangeInclusive<u32> = 2..=8;

/// The windows magnified from each side, and the magnified pictures, one per side (each drawn
/// as its window alone, [`crate::render::Renderer::set_window`]).
#[derive(Debug, Clone)]
pub struct Inset {
    /// The window `[x, y, width, height]` in the side's picture.
    pub window: [u32; 4],
    /// Each side's window, magnified to [`inset_size`].
    pub sides: Vec<RgbaImage>,
}

/// The size of each inset picture for a lesson whose pictures are `picture` pixels: half of
/// it each way beside a split's picture, a grid's tile size under each tile.
pub fn inset_size(lesson: &Lesson, picture: [u32; 2]) -> [u32; 2] {
    if lesson.split { picture.map(|c| (c / 2).max(1)) } else { picture }
}

/// The window an inset of `size` shows at `zoom`: `size / zoom` (rounded up), at most `picture`.
pub fn window_size(size: [u32; 2], zoom: u32, picture: [u32; 2]) -> [u32; 2] {
    [0, 1].map(|i| size[i].div_ceil(zoom.max(1)).clamp(1, picture[i].max(1)))
}

/// The window of `size` in which the neighbouring `sides` (pictures of one size) differ
/// visibly ([`VISIBLE_DELTA_E`]) in the most pixels, counting for each window the pair that
/// differs least there, as the lesson's number does: `[x, y, width, height]`, the first best.
pub fn most_different_window(sides: &[RgbaImage], size: [u32; 2]) -> [u32; 4] {
    let Some(first) = sides.first() else { return [0, 0, size[0], size[1]] };
    let (width, height) = first.dimensions();
    let [w, h] = [size[0].min(width), size[1].min(height)];
    let tables: Vec<Vec<u32>> = sides.windows(2).map(|pair| summed_visible(&pair[0], &pair[1])).collect();
    let stride = width as usize + 1;
    let count = |table: &[u32], x: u32, y: u32| {
        let at = |x: u32, y: u32| table[y as usize * stride + x as usize];
        at(x + w, y + h) + at(x, y) - at(x + w, y) - at(x, y + h)
    };
    let mut best = ([0, 0], 0);
    for y in 0..=height - h {
        for x in 0..=width - w {
            let least = tables.iter().map(|t| count(t, x, y)).min().unwrap_or(0);
            if least > best.1 {
                best = ([x, y], least);
            }
        }
    }
    [best.0[0], best.0[1], w, h]
}

/// The summed-area table (`(width + 1) × (height + 1)`, row-major) of the pixels at which `a`
/// and `b` differ visibly.
fn summed_visible(a: &RgbaImage, b: &RgbaImage) -> Vec<u32> {
    let (width, height) = a.dimensions();
    let stride = width as usize + 1;
    let mut table = vec![0u32; stride * (height as usize + 1)];
    for y in 0..height {
        let mut row = 0;
        for x in 0..width {
            let (p, q) = (a.get_pixel(x, y).0, b.get_pixel(x, y).0);
            let seen =
                p != q && delta_e_2000(lab([p[0], p[1], p[2]]), lab([q[0], q[1], q[2]])) >= f64::from(VISIBLE_DELTA_E);
            row += u32::from(seen);
            let i = (y as usize + 1) * stride + x as usize + 1;
            table[i] = table[i - stride] + row;
        }
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgba;

    #[test]
    fn the_window_is_where_the_weakest_pair_differs_most() {
        let grey = RgbaImage::from_pixel(40, 20, Rgba([90, 90, 90, 255]));
        let paint = |image: &mut RgbaImage, x0: u32, y0: u32| {
            (x0..x0 + 6).for_each(|x| (y0..y0 + 4).for_each(|y| image.put_pixel(x, y, Rgba([220, 40, 40, 255]))));
        };
        let (mut b, mut c) = (grey.clone(), grey.clone());
        // a → b differs at (4, 2) and (30, 12); b → c at (30, 12) only (and c keeps b's first patch).
        paint(&mut b, 4, 2);
        paint(&mut b, 30, 12);
        paint(&mut c, 4, 2);
        let window = most_different_window(&[grey, b, c], [8, 6]);
        assert_eq!(window, [28, 10, 8, 6]);
    }

    #[test]
    fn sizes_follow_the_zoom_and_stay_inside_the_picture() {
        assert_eq!(window_size([300, 169], 4, [603, 339]), [75, 43]);
        assert_eq!(window_size([300, 169], 4, [50, 30]), [50, 30]);
    }
}

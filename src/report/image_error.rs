//! How far a picture is from a reference: the RMSE of the linear RGB channels (sRGB pixels
//! decoded) and the share of pixels whose largest channel differs by more than [`OFF_BY`].

use crate::math::srgb_to_linear;

/// Largest channel difference, in 8-bit steps, beyond which a pixel counts as off.
pub const OFF_BY: u8 = 5;

/// How far a picture is from the reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageError {
    /// RMSE over the linear RGB channels of every pixel.
    pub rmse: f64,
    /// Share (0..1) of pixels with a channel off by more than [`OFF_BY`] / 255.
    pub off_share: f64,
}

/// The error of `image` against `reference` (same size, sRGB-encoded RGBA) over the pixels
/// `mask` holds (row by row; `None`: all).
pub fn image_error(image: &image::RgbaImage, reference: &image::RgbaImage, mask: Option<&[bool]>) -> ImageError {
    assert_eq!(image.dimensions(), reference.dimensions(), "compared pictures differ in size");
    let mut squares = 0.0f64;
    let (mut off, mut pixels) = (0usize, 0usize);
    for (index, (a, b)) in image.pixels().zip(reference.pixels()).enumerate() {
        if mask.is_some_and(|m| !m.get(index).copied().unwrap_or(false)) {
            continue;
        }
        pixels += 1;
        let mut largest = 0u8;
        for c in 0..3 {
            let (x, y) = (srgb_to_linear(a[c] as f32 / 255.0), srgb_to_linear(b[c] as f32 / 255.0));
            squares += ((x - y) as f64).powi(2);
            largest = largest.max(a[c].abs_diff(b[c]));
        }
        off += usize::from(largest > OFF_BY);
    }
    let pixels = pixels.max(1);
    ImageError { rmse: (squares / (3 * pixels) as f64).sqrt(), off_share: off as f64 / pixels as f64 }
}

//! Normal maps back to height maps (`bumpview bake --to-height`) in bounded, predictable memory.
//!
//! The steps and what each holds:
//! 1. the file is read and decoded: file bytes + decoded pixels (1 to 16 bytes a texel: grey
//!    8-bit to RGBA 32-bit float);
//! 2. the slopes are written straight from the pixels into the packed field of the solve
//!    ([`PackedSlopes`]: 8 bytes a texel, 16 with `--border clamp`), then the pixels dropped;
//! 3. the solve runs in place with a small column scratch ([`spectrum::scratch_bytes`]) and the
//!    heights are written to the PNG from the same buffer, band by band.
//!
//! The peak is therefore [`to_height_need`]: `max(decoded + max(file, packed), packed +
//! scratch)`, plus the program and a few MiB of output bands. An input whose need exceeds the
//! limit ([`BakeOptions::memory_limit`]) is refused from its header, before its pixels are
//! allocated.

use std::path::Path;

use image::DynamicImage;
use rustfft::num_complex::Complex32;

use super::image_io::{Header, PngLayout, read_image_admitted, write_png};
use super::{BakeError, BakeOptions, Baked};
use crate::atomic::write_atomically;
use crate::height::Border;
use crate::height::derivative::Derivative;
use crate::height::integrate::Slopes;
use crate::height::rows::Channels;
use crate::height::spectrum::{self, PackedSlopes};
use crate::names::Named;
use crate::scene::GreenAxis;

/// The default of [`BakeOptions::memory_limit`]: 4 GiB, room for a 16384² 16-bit RGB normal
/// map with a wrapping border (3.5 GiB), not for a clamped one (5.5 GiB).
pub const DEFAULT_MEMORY_LIMIT: u64 = 4 << 30;

const MIB: u64 = 1 << 20;

/// Peak bytes `bake --to-height` allocates for an input of `header` with `border` (see the
/// module docs for the steps).
pub fn to_height_need(header: &Header, border: Border) -> u64 {
    let (width, height) = (header.width as usize, header.height as usize);
    let packed = PackedSlopes::bytes(width, height, border);
    let reading = header.decoded_bytes + header.file_bytes.max(packed);
    reading.max(packed + spectrum::scratch_bytes(height, border))
}

/// Refuses `header` when its [`to_height_need`] exceeds `limit` bytes: one line naming the
/// size, the need and the limit (in MiB, rounded up).
fn admit(path: &Path, header: &Header, border: Border, limit: u64) -> Result<(), BakeError> {
    let need = to_height_need(header, border);
    if need <= limit {
        return Ok(());
    }
    Err(BakeError::new(
        path,
        format!(
            "{}x{} texels ({:?}, border {}) need {} MiB to integrate, over the limit of {} MiB (--max-memory raises it)",
            header.width,
            header.height,
            header.color,
            border.name(),
            need.div_ceil(MIB),
            limit.div_ceil(MIB),
        ),
    ))
}

/// Normals pointing this close to the surface or below (`z` under this) are read with this
/// `z`: slopes of at most 100.
const MIN_NORMAL_Z: f32 = 0.01;

/// The slope `(∂h/∂x, ∂h/∂y_up)` of a unit normal in full ranges per texel (slope ÷
/// `slope_scale`).
fn slope_of([x, y, z]: [f32; 3], slope_scale: f32) -> (f32, f32) {
    let z = z.max(MIN_NORMAL_Z);
    (-x / z / slope_scale, -y / z / slope_scale)
}

/// The slopes of unit normals in full ranges per texel (slope ÷ `slope_scale`).
pub fn slopes_of(normals: &[[f32; 3]], width: usize, height: usize, slope_scale: f32) -> Slopes {
    let (dx, dy_up) = normals.iter().map(|&n| slope_of(n, slope_scale)).unzip();
    Slopes { width, height, dx, dy_up }
}

/// How a texel's colour becomes a slope.
#[derive(Clone, Copy)]
struct Decode {
    /// −1 for DirectX (green inverted).
    green: f32,
    two_channel: bool,
    slope_scale: f32,
}

impl Decode {
    /// `normalize(2·c − 1)` of RGB in 0..1, green flipped for DirectX, `z` rebuilt as
    /// `sqrt(max(0, 1 − x² − y²))` for two-channel maps; +Z when degenerate.
    fn normal(self, rgb: [f32; 3]) -> [f32; 3] {
        let [x, y, z] = rgb.map(|c| 2.0 * c - 1.0);
        let y = self.green * y;
        let z = if self.two_channel { (1.0 - x * x - y * y).max(0.0).sqrt() } else { z };
        let length = (x * x + y * y + z * z).sqrt();
        if length > 1e-6 && length.is_finite() { [x / length, y / length, z / length] } else { [0.0, 0.0, 1.0] }
    }

    /// Row `y` of `samples` (`channels` per texel, `unit` mapping a sample to 0..1; grey read as
    /// `r = g = b`) as packed slopes `p + i·q` into `out`.
    fn row<T: Copy>(self, samples: &[T], channels: usize, unit: impl Fn(T) -> f32, y: usize, out: &mut [Complex32]) {
        let row = &samples[y * out.len() * channels..][..out.len() * channels];
        for (out, texel) in out.iter_mut().zip(row.chunks_exact(channels)) {
            let rgb = if channels < 3 { [unit(texel[0]); 3] } else { [unit(texel[0]), unit(texel[1]), unit(texel[2])] };
            let (p, q) = slope_of(self.normal(rgb), self.slope_scale);
            *out = Complex32::new(p, q);
        }
    }
}

/// Writes the slopes of every texel of `image` into `packed`, rows in parallel.
fn fill(packed: &mut PackedSlopes, image: &DynamicImage, decode: Decode) {
    let channels = image.color().channel_count() as usize;
    match image {
        DynamicImage::ImageLuma8(b) => packed.fill(|y, out| decode.row(b, channels, unit8, y, out)),
        DynamicImage::ImageLumaA8(b) => packed.fill(|y, out| decode.row(b, channels, unit8, y, out)),
        DynamicImage::ImageRgb8(b) => packed.fill(|y, out| decode.row(b, channels, unit8, y, out)),
        DynamicImage::ImageRgba8(b) => packed.fill(|y, out| decode.row(b, channels, unit8, y, out)),
        DynamicImage::ImageLuma16(b) => packed.fill(|y, out| decode.row(b, channels, unit16, y, out)),
        DynamicImage::ImageLumaA16(b) => packed.fill(|y, out| decode.row(b, channels, unit16, y, out)),
        DynamicImage::ImageRgb16(b) => packed.fill(|y, out| decode.row(b, channels, unit16, y, out)),
        DynamicImage::ImageRgba16(b) => packed.fill(|y, out| decode.row(b, channels, unit16, y, out)),
        DynamicImage::ImageRgb32F(b) => packed.fill(|y, out| decode.row(b, channels, |v| v, y, out)),
        DynamicImage::ImageRgba32F(b) => packed.fill(|y, out| decode.row(b, channels, |v| v, y, out)),
        // Any layout added later: through a float copy.
        other => {
            let rgb = other.to_rgb32f();
            packed.fill(|y, out| decode.row(&rgb, 3, |v| v, y, out))
        }
    }
}

fn unit8(v: u8) -> f32 {
    v as f32 / 255.0
}

fn unit16(v: u16) -> f32 {
    v as f32 / 65535.0
}

/// Integrates the normal map `input` into the 16-bit grey height map PNG `output`: heights in
/// the options' units (a full range of `range_m` metres, or `1/strength`-per-texel slopes),
/// the lowest point at 0 (white = high; black = high with `depth`), clipped at the full range.
/// Refused before decoding when its [`to_height_need`] is over [`BakeOptions::memory_limit`].
pub fn to_height_file(input: &Path, output: &Path, options: &BakeOptions) -> Result<Baked, BakeError> {
    let image = read_image_admitted(input, |header| admit(input, header, options.border, options.memory_limit))?;
    let (width, height) = (image.width(), image.height());
    let mut packed = PackedSlopes::try_new(width as usize, height as usize, options.border)
        .map_err(|e| BakeError::new(input, format!("cannot allocate the solve: {e}")))?;
    let decode = Decode {
        green: if options.green == GreenAxis::DirectX { -1.0 } else { 1.0 },
        two_channel: options.channels == Channels::TwoChannel,
        slope_scale: options.units.slope_scale(width),
    };
    fill(&mut packed, &image, decode);
    drop(image);
    let derivative = if options.spectral { Derivative::Spectral } else { Derivative::Kernel(options.kernel) };
    let heights = packed.solve(derivative);
    let rows = 0..heights.height();
    let lowest = rows.clone().flat_map(|y| heights.row(y)).fold(f32::INFINITY, f32::min);
    let highest = rows.clone().flat_map(|y| heights.row(y)).fold(f32::NEG_INFINITY, f32::max);
    let clipped = rows.flat_map(|y| heights.row(y)).filter(|&h| h - lowest > 1.0).count();
    let layout = PngLayout { width, height, color: png::ColorType::Grayscale, sixteen_bit: true };
    write_atomically(output, |out| {
        write_png(out, layout, |rows, bytes| {
            let band = rows.flat_map(|y| heights.row(y));
            for (out, h) in bytes.chunks_exact_mut(2).zip(band) {
                let sample = (h - lowest).clamp(0.0, 1.0);
                let sample = if options.depth { 1.0 - sample } else { sample };
                out.copy_from_slice(&((sample * 65535.0).round() as u16).to_be_bytes());
            }
        })
    })
    .map_err(|e| BakeError::new(output, format!("cannot write: {e}")))?;
    let relief = Some((highest - lowest, clipped));
    Ok(Baked { input: input.to_owned(), output: output.to_owned(), width, height, relief })
}

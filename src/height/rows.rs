//! The height→normal kernels over whole images: rows in parallel (rayon), each row's
//! derivatives as one pass per kernel tap over contiguous `f32` rows, so the compiler
//! vectorises them.
//!
//! A [`HeightGrid`] borrows samples as they were decoded (8-bit, 16-bit or float) and converts
//! one band of rows at a time to `f32`, so baking a large 8-bit map never holds a float copy
//! of it. Every texel's normal is the one [`super::HeightField::normal`] computes, by the same
//! taps in the same order (bit for bit on float samples; see the tests).

use std::ops::Range;

use glam::Vec3;
use rayon::prelude::*;

use super::{Border, Kernel, Tap};

/// Columns of padding on each side of a loaded row: the widest kernel reaches two texels.
const PAD: usize = 2;

/// Squared normal lengths at or above this are treated as degenerate (as
/// [`crate::math::normalize_or`] does): the normal falls back to +Z.
const MAX_LENGTH_SQUARED: f32 = 1e30;

/// Height samples as stored, rows top to bottom; `U8` and `U16` span 0..1 over their levels.
#[derive(Debug, Clone, Copy)]
pub enum Samples<'a> {
    U8(&'a [u8]),
    U16(&'a [u16]),
    F32(&'a [f32]),
}

impl Samples<'_> {
    fn len(&self) -> usize {
        match self {
            Samples::U8(s) => s.len(),
            Samples::U16(s) => s.len(),
            Samples::F32(s) => s.len(),
        }
    }

    /// The largest sample value: 255, 65535 or 1.
    fn levels(&self) -> f32 {
        match self {
            Samples::U8(_) => 255.0,
            Samples::U16(_) => 65535.0,
            Samples::F32(_) => 1.0,
        }
    }

    /// Sample `i` in 0..1.
    pub fn unit(&self, i: usize) -> f32 {
        match self {
            Samples::U8(s) => s[i] as f32 / 255.0,
            Samples::U16(s) => s[i] as f32 / 65535.0,
            Samples::F32(s) => s[i],
        }
    }

    /// Samples `start..start + out.len()` as stored values (not scaled to 0..1) into `out`.
    fn load(&self, start: usize, out: &mut [f32]) {
        let end = start + out.len();
        match self {
            Samples::U8(s) => out.iter_mut().zip(&s[start..end]).for_each(|(o, &v)| *o = v as f32),
            Samples::U16(s) => out.iter_mut().zip(&s[start..end]).for_each(|(o, &v)| *o = v as f32),
            Samples::F32(s) => out.copy_from_slice(&s[start..end]),
        }
    }
}

/// A height image to differentiate: `width × height` samples and their world scale.
#[derive(Debug, Clone, Copy)]
pub struct HeightGrid<'a> {
    pub width: usize,
    pub height: usize,
    pub samples: Samples<'a>,
    /// World slope (metres per metre) of a rise of one full sample range (0 → 1) over one
    /// texel: `range_m / texel_size_m`.
    pub slope_scale: f32,
    /// The samples are depths (white = deep): height `h = 1 − sample`.
    pub depth: bool,
}

impl HeightGrid<'_> {
    /// Slope per stored sample step: [`Self::slope_scale`] over the sample's levels.
    fn step_scale(&self) -> f32 {
        let sign = if self.depth { -1.0 } else { 1.0 };
        sign * self.slope_scale / self.samples.levels()
    }

    /// Stored row `y` (wrapped or clamped into the image) with [`PAD`] columns of border on
    /// each side, into `out` (`width + 2·PAD` values).
    fn load_row(&self, y: i64, border: Border, out: &mut [f32]) {
        let (w, h) = (self.width as i64, self.height as i64);
        let y = match border {
            Border::Wrap => y.rem_euclid(h),
            Border::Clamp => y.clamp(0, h - 1),
        } as usize;
        let start = y * self.width;
        self.samples.load(start, &mut out[PAD..PAD + self.width]);
        for p in 0..PAD as i64 {
            let (left, right) = match border {
                Border::Wrap => ((-1 - p).rem_euclid(w), (w + p).rem_euclid(w)),
                Border::Clamp => (0, w - 1),
            };
            out[PAD - 1 - p as usize] = out[PAD + left as usize];
            out[PAD + self.width + p as usize] = out[PAD + right as usize];
        }
    }
}

/// How far (rows or columns) a kernel's taps reach from the centre texel.
fn reach(taps: &[Tap]) -> usize {
    taps.iter().map(|t| t.along.unsigned_abs().max(t.across.unsigned_abs())).max().unwrap_or(0) as usize
}

/// One output row's unit normals, tangent space, `y` up the image: three planes.
pub struct NormalRow<'a> {
    pub x: &'a [f32],
    pub y: &'a [f32],
    pub z: &'a [f32],
    /// The row's samples as stored (0..levels; depths for a depth map).
    pub stored: &'a [f32],
    /// The largest stored value: 255, 65535 or 1.
    pub levels: f32,
    /// The samples are depths: height `h = 1 − stored / levels`.
    pub depth: bool,
}

impl NormalRow<'_> {
    /// The height (white = high) in 0..1 of a stored sample of this row.
    pub fn height(&self, stored: f32) -> f32 {
        let h = stored / self.levels;
        if self.depth { 1.0 - h } else { h }
    }
}

/// Per-thread buffers of one band of rows.
struct Scratch {
    /// `rows + 2·reach` padded rows of stored sample values.
    band: Vec<f32>,
    dx: Vec<f32>,
    dy: Vec<f32>,
    nx: Vec<f32>,
    ny: Vec<f32>,
    nz: Vec<f32>,
}

/// Rows per parallel task among `count` rows: enough tasks to balance the threads, few
/// enough that the halo of re-read rows stays small.
fn band_rows(count: usize) -> usize {
    (count / (rayon::current_num_threads() * 8)).clamp(4, 64)
}

/// `out[x] = Σ weight · row_t[x + offset_t]` over `(weight, row, offset)` terms, one
/// vectorisable pass per term (the first assigns, the rest add, in order).
fn weighted_sum<'a>(out: &mut [f32], terms: impl Iterator<Item = (f32, &'a [f32])>) {
    for (k, (weight, row)) in terms.enumerate() {
        let row = &row[..out.len()];
        if k == 0 {
            out.iter_mut().zip(row).for_each(|(d, &v)| *d = weight * v);
        } else {
            out.iter_mut().zip(row).for_each(|(d, &v)| *d += weight * v);
        }
    }
}

/// Computes the unit normals `normalize(−∂h/∂x, −∂h/∂y_up, 1)` by `kernel` of image rows
/// `rows` and hands each row to `write` with its slice of `out` (`row_len` items per image
/// row, `out` holding exactly `rows`). Rows run in parallel bands. Non-finite or huge slopes
/// give +Z (never NaN).
pub fn for_each_normal_row<T: Send>(
    grid: &HeightGrid,
    kernel: Kernel,
    border: Border,
    rows: Range<usize>,
    out: &mut [T],
    row_len: usize,
    write: impl Fn(NormalRow, &mut [T]) + Sync,
) {
    assert_eq!(grid.samples.len(), grid.width * grid.height, "samples must fill the grid");
    assert!(rows.end <= grid.height, "rows {rows:?} of an image {} rows high", grid.height);
    assert_eq!(out.len(), row_len * rows.len(), "output must hold every row");
    if grid.width == 0 || rows.is_empty() {
        return;
    }
    let start = rows.start;
    let rows = band_rows(rows.len());
    out.par_chunks_mut(row_len * rows).enumerate().for_each_init(
        || Scratch {
            band: vec![],
            dx: vec![0.0; grid.width],
            dy: vec![0.0; grid.width],
            nx: vec![0.0; grid.width],
            ny: vec![0.0; grid.width],
            nz: vec![0.0; grid.width],
        },
        |scratch, (band, out)| {
            let first = start + band * rows;
            let rows = first..first + out.len() / row_len;
            band_normals(grid, kernel, border, rows, scratch, |row, r| write(row, &mut out[r * row_len..][..row_len]));
        },
    );
}

/// The normals of image rows `rows`, in order, each handed to `write` with its index in the band.
fn band_normals(
    grid: &HeightGrid,
    kernel: Kernel,
    border: Border,
    rows: Range<usize>,
    s: &mut Scratch,
    mut write: impl FnMut(NormalRow, usize),
) {
    let taps = kernel.taps();
    let reach = reach(taps);
    let padded = grid.width + 2 * PAD;
    let scale = grid.step_scale();
    s.band.resize((rows.len() + 2 * reach) * padded, 0.0);
    for (k, row) in s.band.chunks_exact_mut(padded).enumerate() {
        grid.load_row(rows.start as i64 + k as i64 - reach as i64, border, row);
    }
    for r in 0..rows.len() {
        // Band row of image row `rows.start + r + offset`, offset in −reach..=reach.
        let band = &s.band;
        let band_row = |offset: i64| {
            let k = ((r + reach) as i64 + offset) as usize;
            &band[k * padded..(k + 1) * padded]
        };
        let column = |offset: i64| (PAD as i64 + offset) as usize;
        // ∂/∂x: `along` columns right, `across` rows down.
        weighted_sum(&mut s.dx, taps.iter().map(|t| (t.weight, &band_row(t.across)[column(t.along)..])));
        // ∂/∂y_up: `along` rows up (towards smaller rows), `across` columns right.
        weighted_sum(&mut s.dy, taps.iter().map(|t| (t.weight, &band_row(-t.along)[column(t.across)..])));
        for x in 0..grid.width {
            let (gx, gy) = (-(s.dx[x] * scale), -(s.dy[x] * scale));
            let length_squared = gx * gx + gy * gy + 1.0;
            let finite = length_squared < MAX_LENGTH_SQUARED;
            let length = length_squared.sqrt();
            s.nx[x] = if finite { gx / length } else { 0.0 };
            s.ny[x] = if finite { gy / length } else { 0.0 };
            s.nz[x] = if finite { 1.0 / length } else { 1.0 };
        }
        let stored = &band_row(0)[PAD..PAD + grid.width];
        let levels = grid.samples.levels();
        write(NormalRow { x: &s.nx, y: &s.ny, z: &s.nz, stored, levels, depth: grid.depth }, r);
    }
}

/// Every texel's unit normal by `kernel`, rows top to bottom.
pub fn normals(grid: &HeightGrid, kernel: Kernel, border: Border) -> Vec<Vec3> {
    let mut out = vec![Vec3::ZERO; grid.width * grid.height];
    for_each_normal_row(grid, kernel, border, 0..grid.height, &mut out, grid.width, |row, out| {
        for (((o, &x), &y), &z) in out.iter_mut().zip(row.x).zip(row.y).zip(row.z) {
            *o = Vec3::new(x, y, z);
        }
    });
    out
}

/// What a normal-map image holds per texel.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Channels {
    /// RGB = the normal.
    #[default]
    Rgb,
    /// RGB = the normal, A = the height (white = high; a depth map's samples inverted).
    RgbHeight,
    /// R, G = the normal's x, y; B = 0 (z is rebuilt as `sqrt(1 − x² − y²)` on reading).
    /// PNG has no red-green colour type, and blue 0 compresses to almost nothing.
    TwoChannel,
}

impl Channels {
    pub fn count(self) -> usize {
        match self {
            Channels::Rgb | Channels::TwoChannel => 3,
            Channels::RgbHeight => 4,
        }
    }
}

/// How normals are stored as image bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MapFormat {
    /// 8 or 16 bits per channel; 16-bit channels are big-endian (as PNG stores them).
    pub sixteen_bit: bool,
    pub channels: Channels,
    /// DirectX convention: green is `−y` (points down the image), stored as the OpenGL byte
    /// inverted.
    pub green_down: bool,
}

impl MapFormat {
    /// Bytes per texel.
    pub fn texel_bytes(self) -> usize {
        self.channels.count() * if self.sixteen_bit { 2 } else { 1 }
    }
}

/// `round(255 · (0.5·c + 0.5))` for `c` in −1..1 (saturating outside).
pub(super) fn unorm8(c: f32) -> u8 {
    (c * 127.5 + 128.0) as u8
}

/// `round(65535 · (0.5·c + 0.5))` for `c` in −1..1 (saturating outside), big-endian bytes.
fn unorm16(c: f32) -> [u8; 2] {
    ((c * 32767.5 + 32768.0) as u16).to_be_bytes()
}

/// The normal map of `grid` by `kernel`, encoded as `format` says: rows top to bottom,
/// `width · format.texel_bytes()` bytes per row, each channel `round(levels · (0.5·c + 0.5))`.
pub fn encode_normal_map(grid: &HeightGrid, kernel: Kernel, border: Border, format: MapFormat) -> Vec<u8> {
    let texel = format.texel_bytes();
    let mut out = vec![0u8; grid.width * grid.height * texel];
    for_each_normal_row(grid, kernel, border, 0..grid.height, &mut out, grid.width * texel, |row, out| {
        encode_row(&row, format, out)
    });
    out
}

/// One row of normals as `format` bytes into `out`. DirectX green is the OpenGL byte
/// inverted (`255 − g`, `65535 − g`), as an "invert green" step makes it, so converting a map
/// between the conventions is exact.
pub fn encode_row(row: &NormalRow, format: MapFormat, out: &mut [u8]) {
    let green8 = |y: f32| if format.green_down { 255 - unorm8(y) } else { unorm8(y) };
    let green16 = |y: f32| {
        let g = u16::from_be_bytes(unorm16(y));
        (if format.green_down { u16::MAX - g } else { g }).to_be_bytes()
    };
    let texels = row.x.iter().zip(row.y).zip(row.z).zip(row.stored);
    let height = |stored: f32| 2.0 * row.height(stored) - 1.0;
    match (format.sixteen_bit, format.channels) {
        (false, Channels::Rgb) => {
            for (o, (((&x, &y), &z), _)) in out.chunks_exact_mut(3).zip(texels) {
                o.copy_from_slice(&[unorm8(x), green8(y), unorm8(z)]);
            }
        }
        (false, Channels::TwoChannel) => {
            for (o, (((&x, &y), _), _)) in out.chunks_exact_mut(3).zip(texels) {
                o.copy_from_slice(&[unorm8(x), green8(y), 0]);
            }
        }
        (false, Channels::RgbHeight) => {
            for (o, (((&x, &y), &z), &h)) in out.chunks_exact_mut(4).zip(texels) {
                o.copy_from_slice(&[unorm8(x), green8(y), unorm8(z), unorm8(height(h))]);
            }
        }
        (true, channels) => {
            let texel = channels.count() * 2;
            for (o, (((&x, &y), &z), &h)) in out.chunks_exact_mut(texel).zip(texels) {
                let z = if channels == Channels::TwoChannel { -1.0 } else { z };
                let ([x0, x1], [y0, y1], [z0, z1]) = (unorm16(x), green16(y), unorm16(z));
                o[..6].copy_from_slice(&[x0, x1, y0, y1, z0, z1]);
                if channels == Channels::RgbHeight {
                    o[6..].copy_from_slice(&unorm16(height(h)));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::height::HeightField;
    use crate::names::Named;

    fn bumpy(width: u32, height: u32) -> HeightField {
        let samples = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| 0.5 + 0.3 * (x as f32 * 0.7).sin() * (y as f32 * 0.45).cos() + 0.01 * ((x * y) % 7) as f32)
            .collect();
        HeightField { width, height, samples, range_m: 0.05, texel_size_m: 0.01 }
    }

    /// Every kernel and border, on odd sizes (one band, many bands, a field narrower than a
    /// kernel's reach): bit for bit the per-texel reference.
    #[test]
    fn rows_equal_the_per_texel_normals_exactly() {
        for (w, h) in [(37, 23), (5, 300), (1, 3), (2, 2)] {
            let field = bumpy(w, h);
            for &kernel in Kernel::all() {
                for border in [Border::Wrap, Border::Clamp] {
                    let fast = normals(&field.grid(), kernel, border);
                    for (i, n) in fast.iter().enumerate() {
                        let (x, y) = ((i % w as usize) as i64, (i / w as usize) as i64);
                        assert_eq!(*n, field.normal(kernel, border, x, y), "{kernel:?} {border:?} {w}x{h} at {x},{y}");
                    }
                }
            }
        }
    }

    /// 8- and 16-bit samples give the normals of the same field with float samples `v / levels`
    /// (up to f32 rounding of the scale).
    #[test]
    fn integer_samples_are_scaled_by_their_levels() {
        let bytes: Vec<u8> = (0..64u32).map(|i| ((i * 37) % 256) as u8).collect();
        let words: Vec<u16> = bytes.iter().map(|&b| b as u16 * 257).collect();
        let floats: Vec<f32> = bytes.iter().map(|&b| b as f32 / 255.0).collect();
        let grid = |samples| HeightGrid { width: 8, height: 8, samples, slope_scale: 3.0, depth: false };
        let reference = normals(&grid(Samples::F32(&floats)), Kernel::Sobel3, Border::Wrap);
        for samples in [Samples::U8(&bytes), Samples::U16(&words)] {
            for (a, b) in normals(&grid(samples), Kernel::Sobel3, Border::Wrap).iter().zip(&reference) {
                assert!(a.angle_between(*b) < 1e-5, "{a} {b}");
            }
        }
    }

    #[test]
    fn huge_slopes_fall_back_to_plus_z() {
        let samples = [0.0f32, 1.0, 0.0, 1.0];
        let grid = HeightGrid { width: 2, height: 2, samples: Samples::F32(&samples), slope_scale: 1e30, depth: false };
        assert!(normals(&grid, Kernel::ForwardDifference, Border::Clamp).iter().all(|&n| n == Vec3::Z));
    }

    #[test]
    fn encodings_hold_the_same_normals() {
        let field = bumpy(9, 7);
        let grid = field.grid();
        let reference = normals(&grid, Kernel::CentralDifference, Border::Wrap);
        let eight = MapFormat { sixteen_bit: false, channels: Channels::Rgb, green_down: false };
        let sixteen = MapFormat { sixteen_bit: true, channels: Channels::RgbHeight, green_down: true };
        let a = encode_normal_map(&grid, Kernel::CentralDifference, Border::Wrap, eight);
        let b = encode_normal_map(&grid, Kernel::CentralDifference, Border::Wrap, sixteen);
        for (i, n) in reference.iter().enumerate() {
            let texel8 = &a[3 * i..3 * i + 3];
            let expected8 = n.to_array().map(|c| ((c * 0.5 + 0.5).clamp(0.0, 1.0) * 255.0).round() as u8);
            for c in 0..3 {
                assert!(texel8[c].abs_diff(expected8[c]) <= 1, "{texel8:?} {expected8:?}");
            }
            let word = |c: usize| u16::from_be_bytes([b[8 * i + 2 * c], b[8 * i + 2 * c + 1]]) as f32 / 65535.0;
            let decoded = Vec3::new(word(0), 1.0 - word(1), word(2)) * 2.0 - 1.0;
            assert!((decoded - *n).abs().max_element() <= 1.0 / 65535.0 + 1e-6, "{decoded} {n}");
            assert!((word(3) - field.samples[i]).abs() <= 0.5 / 65535.0 + 1e-7);
        }
    }
}

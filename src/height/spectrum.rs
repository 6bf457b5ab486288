//! The in-place Fourier solve behind [`super::integrate`]: one buffer of complex texels, no
//! transposes, no second field.
//!
//! Memory: the two real slope fields share one complex transform (`z = p + i·q`, 8 bytes a
//! texel). Real-to-complex transforms (the `realfft` crate) of `p` and `q` would hold the same
//! two half spectra, `2 × (width/2 + 1) × height` complex values, and do the same work, so they
//! would add a dependency for nothing; the packing trick keeps rustfft alone. Rows are
//! transformed in place; columns are transformed, solved and transformed back in batches of
//! [`BATCH`] frequency pairs `(kx, −kx)` copied out to a small scratch, so the whole solve holds
//! [`PackedSlopes::bytes`] plus [`scratch_bytes`].
//!
//! A clamped field is solved on its even extension (see [`super::integrate`]) without storing
//! its lower half: mirrored rows are the conjugates of the stored ones (`p + i·q` becomes
//! `p − i·q`), so a mirrored row's spectrum at `kx` is `conj Z(−kx)` of the stored row, filled in
//! when a column is copied out. Only the upper `height` rows of `2·width` texels are kept:
//! 16 bytes a texel of the input.

use std::collections::TryReserveError;
use std::f32::consts::TAU;

use rayon::prelude::*;
use rustfft::num_complex::Complex32;
use rustfft::{Fft, FftPlanner};

use super::Border;
use super::derivative::{BLIND, Derivative, Phase, signed_frequency};

/// Column frequency pairs `(kx, −kx)` solved per batch: at most `2·BATCH` columns in scratch.
const BATCH: usize = 32;

/// Bytes of column scratch for a field `height` texels tall: two copies (spectrum, solution)
/// of `2·BATCH` columns of the column transform's length.
pub fn scratch_bytes(height: usize, border: Border) -> u64 {
    (2 * 2 * BATCH * column_len(height, border) * size_of::<Complex32>()) as u64
}

fn column_len(height: usize, border: Border) -> usize {
    match border {
        Border::Wrap => height,
        Border::Clamp => 2 * height,
    }
}

fn row_len(width: usize, border: Border) -> usize {
    match border {
        Border::Wrap => width,
        Border::Clamp => 2 * width,
    }
}

/// A `width × height` slope field packed for the solve: row `y` holds `p + i·q` (`p` = ∂h/∂x,
/// `q` = ∂h/∂y_up, height units per texel), and for [`Border::Clamp`] its mirror image to the
/// right (`−p + i·q`).
pub struct PackedSlopes {
    width: usize,
    height: usize,
    border: Border,
    data: Vec<Complex32>,
}

impl PackedSlopes {
    /// Bytes the packed field (and later its heights) takes: 8 per texel, 16 with
    /// [`Border::Clamp`].
    pub fn bytes(width: usize, height: usize, border: Border) -> u64 {
        (row_len(width, border) * height * size_of::<Complex32>()) as u64
    }

    /// A zero field (aborts when memory runs out, as any `Vec` does).
    pub fn new(width: usize, height: usize, border: Border) -> PackedSlopes {
        let data = vec![Complex32::ZERO; row_len(width, border) * height];
        PackedSlopes { width, height, border, data }
    }

    /// A zero field, or the allocator's refusal.
    pub fn try_new(width: usize, height: usize, border: Border) -> Result<PackedSlopes, TryReserveError> {
        let len = row_len(width, border) * height;
        let mut data = Vec::new();
        data.try_reserve_exact(len)?;
        data.resize(len, Complex32::ZERO);
        Ok(PackedSlopes { width, height, border, data })
    }

    /// Fills every row, rows in parallel: `row(y, out)` writes `p + i·q` of row `y`'s `width`
    /// texels into `out`.
    pub fn fill(&mut self, row: impl Fn(usize, &mut [Complex32]) + Sync) {
        let (width, border) = (self.width, self.border);
        let stride = row_len(width, border);
        self.data.par_chunks_mut(stride.max(1)).enumerate().for_each(|(y, out)| {
            let (stored, mirror) = out.split_at_mut(width);
            row(y, stored);
            // The mirror image runs right to left with ∂/∂x negated.
            for (m, s) in mirror.iter_mut().zip(stored.iter().rev()) {
                *m = Complex32::new(-s.re, s.im);
            }
        });
    }

    /// The least-squares heights of the packed slopes by `derivative`, in place.
    pub fn solve(mut self, derivative: Derivative) -> Heights {
        let (width, height, border) = (self.width, self.height, self.border);
        let (n_x, n_y) = (row_len(width, border), column_len(height, border));
        if width == 0 || height == 0 {
            return Heights { width, height, row_len: n_x, scale: 0.0, offset: 0.0, data: self.data };
        }
        let mut planner = FftPlanner::new();
        fft_rows(&mut self.data, &*planner.plan_fft_forward(n_x));
        let columns = Columns {
            n_x,
            n_y,
            rows: height,
            mirrored: border == Border::Clamp,
            forward: planner.plan_fft_forward(n_y),
            inverse: planner.plan_fft_inverse(n_y),
        };
        columns.solve(&mut self.data, derivative);
        fft_rows(&mut self.data, &*planner.plan_fft_inverse(n_x));
        let mut heights =
            Heights { width, height, row_len: n_x, scale: 1.0 / (n_x * n_y) as f32, offset: 0.0, data: self.data };
        if border == Border::Clamp {
            // The cropped quarter's mean is not the extension's (0): remove it.
            let sum: f64 = (0..height).into_par_iter().map(|y| heights.row(y).map(f64::from).sum::<f64>()).sum();
            heights.offset = (sum / (width * height) as f64) as f32;
        }
        heights
    }
}

/// The column stage: forward transform, Frankot–Chellappa division, inverse transform.
struct Columns {
    n_x: usize,
    n_y: usize,
    /// Stored rows (`n_y / 2` when mirrored).
    rows: usize,
    mirrored: bool,
    forward: std::sync::Arc<dyn Fft<f32>>,
    inverse: std::sync::Arc<dyn Fft<f32>>,
}

impl Columns {
    fn solve(&self, data: &mut [Complex32], derivative: Derivative) {
        let (n_x, n_y) = (self.n_x, self.n_y);
        let phases_y: Vec<Phase> =
            (0..n_y).map(|k| Phase::new(TAU * signed_frequency(k, n_y) as f32 / n_y as f32)).collect();
        let (mut spectrum, mut solved) = (vec![], vec![]);
        for start in (0..=n_x / 2).step_by(BATCH) {
            // Each column with its mirror `−kx` (the solve reads both), and where that is.
            let (mut columns, mut mirror_slot) = (vec![], vec![]);
            for kx in start..(start + BATCH).min(n_x / 2 + 1) {
                let mirror = (n_x - kx) % n_x;
                let slot = columns.len();
                columns.push(kx);
                if mirror == kx {
                    mirror_slot.push(slot);
                } else {
                    columns.push(mirror);
                    mirror_slot.extend([slot + 1, slot]);
                }
            }
            spectrum.resize(columns.len() * n_y, Complex32::ZERO);
            solved.resize(columns.len() * n_y, Complex32::ZERO);
            let data_ref = &*data;
            spectrum.par_chunks_mut(n_y).zip(&columns).zip(&mirror_slot).for_each(|((out, &kx), &mirror)| {
                for (y, value) in out[..self.rows].iter_mut().enumerate() {
                    *value = data_ref[y * n_x + kx];
                }
                if self.mirrored {
                    // Mirrored row 2h−1−y: conj Z(−kx) of stored row y.
                    let mirror_kx = columns[mirror];
                    for y in 0..self.rows {
                        out[n_y - 1 - y] = data_ref[y * n_x + mirror_kx].conj();
                    }
                }
            });
            fft_rows(&mut spectrum, &*self.forward);
            solved.par_chunks_mut(n_y).enumerate().for_each(|(slot, out)| {
                let phase_x = Phase::new(TAU * signed_frequency(columns[slot], n_x) as f32 / n_x as f32);
                let own = &spectrum[slot * n_y..][..n_y];
                let mirror = &spectrum[mirror_slot[slot] * n_y..][..n_y];
                for (ky, (out, phase_y)) in out.iter_mut().zip(&phases_y).enumerate() {
                    // Z = P + iQ; P = (Z(k) + conj Z(−k)) / 2, Q = (Z(k) − conj Z(−k)) / 2i.
                    let (a, b) = (own[ky], mirror[(n_y - ky) % n_y].conj());
                    let p = (a + b) * 0.5;
                    let q = (a - b) * Complex32::new(0.0, -0.5);
                    let (dx, dy) = derivative.symbols(&phase_x, phase_y);
                    let denominator = dx.norm_sqr() + dy.norm_sqr();
                    *out = if denominator > BLIND {
                        (dx.conj() * p + dy.conj() * q) / denominator
                    } else {
                        Complex32::ZERO
                    };
                }
            });
            fft_rows(&mut solved, &*self.inverse);
            data.par_chunks_mut(n_x).enumerate().for_each(|(y, row)| {
                for (slot, &kx) in columns.iter().enumerate() {
                    row[kx] = solved[slot * n_y + y];
                }
            });
        }
    }
}

/// Heights solved in place: `width × height`, rows top to bottom, height units, mean 0.
pub struct Heights {
    width: usize,
    height: usize,
    row_len: usize,
    /// The inverse transform's `1 / (n_x · n_y)`.
    scale: f32,
    /// Subtracted from every height (the mean of a cropped extension).
    offset: f32,
    data: Vec<Complex32>,
}

impl Heights {
    pub fn width(&self) -> usize {
        self.width
    }

    pub fn height(&self) -> usize {
        self.height
    }

    /// Row `y`'s heights, left to right.
    pub fn row(&self, y: usize) -> impl ExactSizeIterator<Item = f32> + '_ {
        self.data[y * self.row_len..][..self.width].iter().map(|c| c.re * self.scale - self.offset)
    }

    /// All heights, rows top to bottom (a second buffer of 4 bytes a texel).
    pub fn to_vec(&self) -> Vec<f32> {
        (0..self.height).flat_map(|y| self.row(y)).collect()
    }
}

/// Transforms every row (`fft.len()` values) of `data` in place, rows in parallel.
fn fft_rows(data: &mut [Complex32], fft: &dyn Fft<f32>) {
    let scratch_len = fft.get_inplace_scratch_len();
    data.par_chunks_mut(fft.len() * 16)
        .for_each_init(|| vec![Complex32::ZERO; scratch_len], |scratch, rows| fft.process_with_scratch(rows, scratch));
}

//! The evidence [`super::green`] weighs: a normal map's slope field in octaves, each octave cut
//! into cells, and per cell its two curl residuals, how strongly it bends and how much of it a
//! height field explains.
//!
//! Slopes are `p = −n.x/n.z`, `q = −n.y/n.z` (OpenGL reading, `y_up` towards the top row), in
//! height per map texel; `a = ∂p/∂y_up`, `b = ∂q/∂x` are per texel of their octave. The
//! residual of the OpenGL reading is `a − b`, of the DirectX reading `a + b`.

use glam::Vec3;

/// Fewest texels across and down a cell spans at its octave (and the map needs).
pub const MIN_SIDE: u32 = 8;
/// Slopes steeper than this (about 84°) are clamped.
const MAX_SLOPE: f32 = 10.0;
/// Mean `|ab|` that 8-bit rounding of the texels leaves at octaves 0, 1, 2 …, relative to
/// octave 0's: white rounding noise (one level of uniform dither on a smooth map) put through
/// the same blur and halving measures 3.7·10⁻⁷, 1.9·10⁻⁷, 5.9·10⁻⁸, 1.5·10⁻⁸, 3.8·10⁻⁹, …; each
/// further octave a quarter of the one before (its derivatives, per texel of the octave, halve).
const QUANTISATION_LEVEL: [f32; 5] = [1.0, 0.52, 0.16, 0.041, 0.0105];

/// The quantisation noise's mean `|ab|` at `octave` relative to octave 0's.
pub fn quantisation_level(octave: usize) -> f32 {
    let last = QUANTISATION_LEVEL.len() - 1;
    QUANTISATION_LEVEL[octave.min(last)] * 0.25f32.powi(octave.saturating_sub(last) as i32)
}

/// One cell of one octave.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cell {
    pub octave: usize,
    /// `(E_dx − E_gl) / (E_dx + E_gl)` in −1..1 (positive: OpenGL).
    pub vote: f32,
    /// Mean `|ab|` per texel of the octave.
    pub strength: f32,
    /// How much of the cell's slope derivatives a height field explains under the better
    /// reading, `1 − 2·min(E_gl, E_dx) / E_slope` in 0..1 (`E_slope`: the energy of all four
    /// derivatives of `p` and `q`): 1 for relief, about 0 for detail that is no gradient under
    /// either reading (noise, or printed detail shifting both slopes alike), whose residual
    /// energies are both about half `E_slope`.
    pub quality: f32,
    /// The map area the cell covers, in tiles (`tile_size²` texels).
    pub area: f32,
    /// Its first column and row of tiles (the tile holding its top-left texel) and the columns
    /// and rows of tiles it spans, at least 1.
    pub tiles: [u32; 4],
}

/// Per-cell sums: `Σab`, `Σ(a² + b²)`, `Σ|ab|`, `Σ((∂p/∂x)² + (∂q/∂y)²)`, texels.
#[derive(Default, Clone, Copy)]
struct Sums {
    cross: f64,
    mixed: f64,
    magnitude: f64,
    pure: f64,
    texels: f64,
}

/// The cells of every octave of the unit normals `normal_at(i)` of a `width × height` map
/// (both at least [`MIN_SIDE`]) with tiles of `tile` texels, and octave 0's `Σ(a² + b²)` and
/// `Σ((∂p/∂x)² + (∂q/∂y)²)`. Octave `k` is the slopes halved `k` times; it counts while its
/// shorter side has [`MIN_SIDE`] texels, in cells of `max(tile, MIN_SIDE·2^k)` map texels (the
/// map's remainder joins the last row and column).
pub fn octave_cells(normal_at: impl Fn(usize) -> Vec3, width: u32, height: u32, tile: u32) -> (Vec<Cell>, f64, f64) {
    let (w, h) = (width as usize, height as usize);
    let mut level = (blurred_slopes(normal_at, w, h), w, h);
    let (mut cells, mut mixed_total, mut pure_total) = (Vec::new(), 0.0, 0.0);
    for octave in 0.. {
        let (slopes, lw, lh) = &level;
        if (*lw).min(*lh) < MIN_SIDE as usize {
            break;
        }
        let side = (tile as usize).max((MIN_SIDE as usize) << octave);
        let grid = ((w / side).max(1), (h / side).max(1));
        let (sums, mixed, pure) = octave_sums((slopes, *lw, *lh), octave, side, grid);
        if octave == 0 {
            (mixed_total, pure_total) = (mixed, pure);
        }
        let tile_area = (tile * tile) as f64;
        for (i, s) in sums.iter().enumerate() {
            let (column, row) = (i % grid.0, i / grid.0);
            let span = |start: usize, last: bool, size: usize| {
                let end = if last { size } else { start + side };
                [(start / tile as usize) as u32, ((end - start).div_ceil(tile as usize)).max(1) as u32]
            };
            let [c0, cs] = span(column * side, column + 1 == grid.0, w);
            let [r0, rs] = span(row * side, row + 1 == grid.1, h);
            let mut cell = cell_of(s, octave, (s.texels * (1u64 << (2 * octave)) as f64 / tile_area) as f32);
            cell.tiles = [c0, r0, cs, rs];
            cells.push(cell);
        }
        level = halved(slopes, *lw, *lh);
    }
    (cells, mixed_total, pure_total)
}

/// One cell's vote, strength and quality from its sums.
fn cell_of(s: &Sums, octave: usize, area: f32) -> Cell {
    if s.texels == 0.0 || s.mixed <= 0.0 {
        return Cell { octave, area, ..Cell::default() };
    }
    let residual = (s.mixed - 2.0 * s.cross.abs()).max(0.0);
    Cell {
        octave,
        vote: (2.0 * s.cross / s.mixed).clamp(-1.0, 1.0) as f32,
        strength: (s.magnitude / s.texels) as f32,
        quality: (1.0 - 2.0 * residual / (s.mixed + s.pure)).clamp(0.0, 1.0) as f32,
        area,
        tiles: [0, 0, 1, 1],
    }
}

/// Sums one octave's derivatives into its `grid` of cells of `side` map texels: `slopes` is
/// `w × h`, each texel `2^octave` map texels across. Returns the sums and the octave's
/// `Σ(a² + b²)` and `Σ((∂p/∂x)² + (∂q/∂y)²)`.
fn octave_sums(
    (slopes, w, h): (&[[f32; 2]], usize, usize),
    octave: usize,
    side: usize,
    (columns, rows): (usize, usize),
) -> (Vec<Sums>, f64, f64) {
    let mut sums = vec![Sums::default(); columns * rows];
    let (mut mixed_total, mut pure_total) = (0.0f64, 0.0f64);
    for y in 1..h - 1 {
        let row = ((y << octave) / side).min(rows - 1);
        for x in 1..w - 1 {
            let at = |x: usize, y: usize| slopes[y * w + x];
            // y_up runs towards smaller rows.
            let a = ((at(x, y - 1)[0] - at(x, y + 1)[0]) * 0.5) as f64;
            let b = ((at(x + 1, y)[1] - at(x - 1, y)[1]) * 0.5) as f64;
            let dp_dx = ((at(x + 1, y)[0] - at(x - 1, y)[0]) * 0.5) as f64;
            let dq_dy = ((at(x, y - 1)[1] - at(x, y + 1)[1]) * 0.5) as f64;
            let s = &mut sums[row * columns + ((x << octave) / side).min(columns - 1)];
            let pure = dp_dx * dp_dx + dq_dy * dq_dy;
            s.cross += a * b;
            s.mixed += a * a + b * b;
            s.magnitude += (a * b).abs();
            s.pure += pure;
            s.texels += 1.0;
            mixed_total += a * a + b * b;
            pure_total += pure;
        }
    }
    (sums, mixed_total, pure_total)
}

/// The OpenGL slopes `(p, q)` of the unit normals `normal_at(i)` of texel `i` (`width ×
/// height`, rows from the top), clamped to ±[`MAX_SLOPE`], blurred by a 3×3 binomial (edges
/// clamped), which removes a 2-texel pattern and halves the derivatives of a 4-texel one. The
/// field is the only full-size buffer: 8 bytes a texel, blurred in place with a row or two of
/// scratch.
fn blurred_slopes(normal_at: impl Fn(usize) -> Vec3, width: usize, height: usize) -> Vec<[f32; 2]> {
    let slope = |n: Vec3| {
        let z = n.z.max(1.0 / MAX_SLOPE);
        [(-n.x / z).clamp(-MAX_SLOPE, MAX_SLOPE), (-n.y / z).clamp(-MAX_SLOPE, MAX_SLOPE)]
    };
    let mut field: Vec<[f32; 2]> = (0..width * height).map(|i| slope(normal_at(i))).collect();
    let blend = |l: [f32; 2], c: [f32; 2], r: [f32; 2]| [0, 1].map(|k| 0.25 * l[k] + 0.5 * c[k] + 0.25 * r[k]);
    // Along x, row by row from a copy of the row.
    let mut row = vec![[0.0f32; 2]; width];
    for y in 0..height {
        row.copy_from_slice(&field[y * width..(y + 1) * width]);
        for x in 0..width {
            field[y * width + x] = blend(row[x.saturating_sub(1)], row[x], row[(x + 1).min(width - 1)]);
        }
    }
    // Along y, top to bottom: the row above as it was before its own blur, the row below not
    // yet blurred.
    let mut above = field[..width].to_vec();
    for y in 0..height {
        row.copy_from_slice(&field[y * width..(y + 1) * width]);
        let below = (y + 1).min(height - 1) * width;
        for x in 0..width {
            let under = if y + 1 < height { field[below + x] } else { row[x] };
            field[y * width + x] = blend(above[x], row[x], under);
        }
        above.copy_from_slice(&row);
    }
    field
}

/// The slopes at half the size, filtered by `[1 3 3 1]/8` along each axis (edges clamped),
/// which passes nothing at the finer octave's Nyquist limit.
fn halved(slopes: &[[f32; 2]], w: usize, h: usize) -> (Vec<[f32; 2]>, usize, usize) {
    const TAPS: [f32; 4] = [0.125, 0.375, 0.375, 0.125];
    let (hw, hh) = (w / 2, h / 2);
    let mut out = vec![[0.0; 2]; hw * hh];
    for y in 0..hh {
        for x in 0..hw {
            for (j, ty) in TAPS.iter().enumerate() {
                let sy = (2 * y + j).saturating_sub(1).min(h - 1);
                for (i, tx) in TAPS.iter().enumerate() {
                    let s = slopes[sy * w + (2 * x + i).saturating_sub(1).min(w - 1)];
                    (0..2).for_each(|k| out[y * hw + x][k] += ty * tx * s[k]);
                }
            }
        }
    }
    (out, hw, hh)
}

//! Which way a tangent-space normal map's green points, from tiles that each cast a bounded
//! vote.
//!
//! A normal map is the gradient of a height field: with decoded `n`, the slopes are
//! `p = ∂h/∂x = −n.x/n.z` and `q = ∂h/∂y_up = −n.y/n.z` (OpenGL reading, `y_up` towards the
//! top row), and a gradient field has zero curl, `a − b = 0` with `a = ∂p/∂y_up` and
//! `b = ∂q/∂x`. Read with the wrong green, `q` changes sign and the residual becomes `a + b`.
//! Per tile the energies `E_gl = Σ(a − b)²` and `E_dx = Σ(a + b)²` differ by `4·Σab`, so the
//! tile votes `v = (E_dx − E_gl) / (E_dx + E_gl)` in −1..1 (positive: OpenGL). The slopes are
//! blurred by a 3×3 binomial first, which removes a 2-texel pattern and halves the derivatives
//! of a 4-texel one, so content at the Nyquist limit carries little.
//!
//! Each tile votes in octaves: the slopes, halved in size again and again (`[1 3 3 1]/8` per
//! axis), vote at every octave whose texels a tile spans at least [`MIN_SIDE`] of. A filter
//! commutes with the derivatives, so a height field's slopes are curl-free in every octave, and
//! each octave is a test of its own. Pooled as energies, the finest octave would win: the
//! derivatives weigh a feature by its frequency squared, and that is where printed detail,
//! grain and compression live. So the tile's vote is its octaves' votes averaged by their
//! weights, and the tile weighs as its best-evidenced octave.
//!
//! No tile weighs more than 1: its weight rises from 0 at [`WEIGHT_FLOOR`] to 1 at
//! [`WEIGHT_FULL`] of mean `|ab|`, so a strong fine pattern on a few tiles is outvoted by the
//! rest of the map. The map's score is the weighted mean vote `m`; its standard error counts
//! both the spread between tiles and [`VOTE_SPREAD`], the spread one tile's vote has on its
//! own, `se² = (Σw²(v − m)² + σ²·Σw²) / (Σw)²`. With a flat prior on the map's true mean
//! vote, the chance that its sign is the one measured is `Φ(|m| / se)`: that is the reported
//! confidence. Below [`DECIDED_CONFIDENCE`] the convention is undetermined, with its reason.

use glam::Vec3;

/// Which way green points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GreenConvention {
    /// +Y (green) up the image: OpenGL, glTF, Blender.
    OpenGl,
    /// +Y down the image: DirectX, Unreal.
    DirectX,
}

/// Why the green convention could not be told.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Undetermined {
    /// Fewer than [`MIN_SIDE`] texels across or down: no derivatives to compare.
    TooFewTexels,
    /// The relief is below the 8-bit quantisation's noise: nothing bends.
    TooFlat,
    /// The relief bends along one image axis only (ribs along x or y): the mixed derivatives
    /// the test compares are zero under both readings.
    OneDirectional,
    /// There is evidence, but the tiles disagree: the confidence stays below
    /// [`DECIDED_CONFIDENCE`].
    MixedTiles,
}

impl Undetermined {
    /// The reason in words, for the report.
    pub fn reason(self) -> &'static str {
        match self {
            Undetermined::TooFewTexels => "too few texels",
            Undetermined::TooFlat => "too flat",
            Undetermined::OneDirectional => "one-directional relief",
            Undetermined::MixedTiles => "mixed tiles",
        }
    }
}

/// One tile's vote: `vote` in −1..1 (positive: OpenGL), `weight` in 0..1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TileVote {
    pub vote: f32,
    pub weight: f32,
}

/// The tiles' votes over a map, row by row from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct GreenEvidence {
    /// Texels per tile side.
    pub tile_size: u32,
    pub columns: u32,
    pub rows: u32,
    pub tiles: Vec<TileVote>,
    /// The convention and its confidence `Φ(|m| / se)` in 0.5..1, or why there is none.
    pub verdict: Result<(GreenConvention, f32), Undetermined>,
}

/// Fewest texels across and down the test needs.
pub const MIN_SIDE: u32 = 8;
/// Mean `|ab|` per texel, (slope per texel)², at which a tile starts to count: 10× what the
/// 8-bit quantisation of a flat map leaves after the blur (about 2·10⁻⁷).
pub const WEIGHT_FLOOR: f32 = 2e-6;
/// Mean `|ab|` at which a tile counts fully (weight 1): 100× the quantisation's level.
pub const WEIGHT_FULL: f32 = 2e-5;
/// The spread σ one tile's vote has on its own, whatever its neighbours say.
pub const VOTE_SPREAD: f32 = 0.5;
/// Total weight below which a map has too little evidence: one full tile.
pub const MIN_EVIDENCE: f32 = 1.0;
/// The confidence from which a convention is reported; below it, "mixed tiles".
pub const DECIDED_CONFIDENCE: f32 = 0.9;
/// Mixed derivatives below this share of the pure ones (`∂p/∂x`, `∂q/∂y`) mean relief along
/// one axis.
const ONE_DIRECTIONAL_SHARE: f32 = 0.01;

/// Slopes steeper than this (about 84°) are clamped.
const MAX_SLOPE: f32 = 10.0;

/// The tile side for a `width × height` map: a quarter of the shorter side, 8 to 32 texels.
pub fn tile_size(width: u32, height: u32) -> u32 {
    (width.min(height) / 4).clamp(MIN_SIDE, 32)
}

/// The OpenGL slopes `(p, q)` of the unit normals `normal_at(i)` of texel `i` (`width ×
/// height`, rows from the top), clamped to ±[`MAX_SLOPE`], blurred by a 3×3 binomial (edges
/// clamped). The field is the only full-size buffer: 8 bytes a texel, blurred in place with
/// a row or two of scratch.
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

/// Per-tile sums of one map.
#[derive(Default, Clone, Copy)]
struct TileSums {
    /// Σab, Σ(a² + b²), Σ|ab|, texels.
    cross: f64,
    mixed: f64,
    magnitude: f64,
    texels: f64,
}

/// The tiles' votes and the verdict for unit normals `normals` of a `width × height` map.
pub fn green_evidence(normals: &[Vec3], width: u32, height: u32) -> GreenEvidence {
    green_evidence_of(|i| normals[i], width, height)
}

/// [`green_evidence`] of the unit normal `normal_at(i)` of each texel `i`, read as needed
/// (a map's decoded normals are never held: 12 bytes a texel).
pub fn green_evidence_of(normal_at: impl Fn(usize) -> Vec3, width: u32, height: u32) -> GreenEvidence {
    let tile = tile_size(width, height);
    let (columns, rows) = (width.div_ceil(tile), height.div_ceil(tile));
    let undetermined = |tiles, reason| GreenEvidence { tile_size: tile, columns, rows, tiles, verdict: Err(reason) };
    if width < MIN_SIDE || height < MIN_SIDE {
        return undetermined(vec![], Undetermined::TooFewTexels);
    }
    let (w, h) = (width as usize, height as usize);
    let mut level = (blurred_slopes(normal_at, w, h), w, h);
    let mut octaves: Vec<Vec<TileVote>> = Vec::new();
    let (mut mixed_total, mut pure_total) = (0.0f64, 0.0f64);
    // An octave counts while a tile spans at least MIN_SIDE of its texels across.
    for octave in 0.. {
        let (slopes, lw, lh) = &level;
        if tile >> octave < MIN_SIDE || *lw < 3 || *lh < 3 {
            break;
        }
        let mut sums = vec![TileSums::default(); (columns * rows) as usize];
        let (mixed, pure) = add_octave(&mut sums, (slopes, *lw, *lh), 1 << octave, tile as usize, columns as usize);
        if octave == 0 {
            (mixed_total, pure_total) = (mixed, pure);
        }
        octaves.push(sums.iter().map(tile_vote).collect());
        level = halved(slopes, *lw, *lh);
    }
    let tiles: Vec<TileVote> =
        (0..(columns * rows) as usize).map(|i| octaves_vote(octaves.iter().map(|o| o[i]))).collect();
    let total_weight: f32 = tiles.iter().map(|t| t.weight).sum();
    if total_weight < MIN_EVIDENCE {
        let texels = ((w - 2) * (h - 2)) as f64;
        let bends = (pure_total / texels) as f32 > 4.0 * WEIGHT_FULL;
        let one_way = bends && mixed_total < ONE_DIRECTIONAL_SHARE as f64 * pure_total;
        return undetermined(tiles, if one_way { Undetermined::OneDirectional } else { Undetermined::TooFlat });
    }
    let verdict = verdict(&tiles);
    GreenEvidence { tile_size: tile, columns, rows, tiles, verdict }
}

/// Adds one octave's mixed derivatives to the tiles' sums: `slopes` is `w × h`, each texel
/// `scale` map texels across. Returns the octave's `Σ(a² + b²)` and `Σ((∂p/∂x)² + (∂q/∂y)²)`.
fn add_octave(
    sums: &mut [TileSums],
    (slopes, w, h): (&[[f32; 2]], usize, usize),
    scale: usize,
    tile: usize,
    columns: usize,
) -> (f64, f64) {
    let (mut mixed_total, mut pure_total) = (0.0f64, 0.0f64);
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let at = |x: usize, y: usize| slopes[y * w + x];
            // y_up runs towards smaller rows.
            let a = ((at(x, y - 1)[0] - at(x, y + 1)[0]) * 0.5) as f64;
            let b = ((at(x + 1, y)[1] - at(x - 1, y)[1]) * 0.5) as f64;
            let dp_dx = ((at(x + 1, y)[0] - at(x - 1, y)[0]) * 0.5) as f64;
            let dq_dy = ((at(x, y - 1)[1] - at(x, y + 1)[1]) * 0.5) as f64;
            let s = &mut sums[(y * scale / tile) * columns + x * scale / tile];
            s.cross += a * b;
            s.mixed += a * a + b * b;
            s.magnitude += (a * b).abs();
            s.texels += 1.0;
            mixed_total += a * a + b * b;
            pure_total += dp_dx * dp_dx + dq_dy * dq_dy;
        }
    }
    (mixed_total, pure_total)
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

/// A tile's vote over its octaves: their votes' mean weighted by each octave's weight, so every
/// octave with full evidence has an equal say; the tile weighs as its best-evidenced octave.
fn octaves_vote(octaves: impl Iterator<Item = TileVote> + Clone) -> TileVote {
    let weight: f32 = octaves.clone().map(|o| o.weight).sum();
    if weight <= 0.0 {
        return TileVote { vote: 0.0, weight: 0.0 };
    }
    let vote = octaves.clone().map(|o| o.weight * o.vote).sum::<f32>() / weight;
    TileVote { vote, weight: octaves.map(|o| o.weight).fold(0.0, f32::max) }
}

/// A tile's vote from its sums: `2·Σab / Σ(a² + b²)` (= `(E_dx − E_gl) / (E_dx + E_gl)`),
/// weighted by its mean `|ab|` between [`WEIGHT_FLOOR`] and [`WEIGHT_FULL`].
fn tile_vote(s: &TileSums) -> TileVote {
    if s.texels == 0.0 || s.mixed <= 0.0 {
        return TileVote { vote: 0.0, weight: 0.0 };
    }
    let strength = (s.magnitude / s.texels) as f32;
    let weight = ((strength - WEIGHT_FLOOR) / (WEIGHT_FULL - WEIGHT_FLOOR)).clamp(0.0, 1.0);
    TileVote { vote: (2.0 * s.cross / s.mixed).clamp(-1.0, 1.0) as f32, weight }
}

/// The weighted mean vote, its standard error and the confidence `Φ(|m| / se)`.
fn verdict(tiles: &[TileVote]) -> Result<(GreenConvention, f32), Undetermined> {
    let total: f32 = tiles.iter().map(|t| t.weight).sum();
    let mean = tiles.iter().map(|t| t.weight * t.vote).sum::<f32>() / total;
    let spread: f32 = tiles.iter().map(|t| t.weight * t.weight * ((t.vote - mean).powi(2) + VOTE_SPREAD.powi(2))).sum();
    let standard_error = spread.sqrt() / total;
    let confidence = normal_cdf(mean.abs() / standard_error);
    let convention = if mean >= 0.0 { GreenConvention::OpenGl } else { GreenConvention::DirectX };
    if confidence < DECIDED_CONFIDENCE {
        return Err(Undetermined::MixedTiles);
    }
    Ok((convention, confidence))
}

/// The standard normal distribution function Φ (Abramowitz–Stegun 7.1.26 for erf, error
/// below 1.5·10⁻⁷).
pub fn normal_cdf(z: f32) -> f32 {
    let x = (z.abs() / std::f32::consts::SQRT_2) as f64;
    let t = 1.0 / (1.0 + 0.3275911 * x);
    let poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
    let erf = 1.0 - poly * (-x * x).exp();
    let half = 0.5 * erf as f32;
    if z >= 0.0 { 0.5 + half } else { 0.5 - half }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Unit normals of the height field `h(x, y_up)` sampled exactly, OpenGL convention.
    fn normals_of(width: u32, height: u32, slope: impl Fn(f32, f32) -> (f32, f32)) -> Vec<Vec3> {
        (0..height)
            .flat_map(|row| (0..width).map(move |x| (x as f32, (height - 1 - row) as f32)))
            .map(|(x, y)| {
                let (p, q) = slope(x, y);
                Vec3::new(-p, -q, 1.0).normalize()
            })
            .collect()
    }

    fn bumps(x: f32, y: f32) -> (f32, f32) {
        let k = std::f32::consts::TAU / 16.0;
        (0.5 * (k * x).cos() * (k * y).sin(), 0.5 * (k * x).sin() * (k * y).cos())
    }

    #[test]
    fn bumps_read_opengl_and_their_flip_directx_with_a_high_confidence() {
        let normals = normals_of(64, 64, bumps);
        let (convention, confidence) = green_evidence(&normals, 64, 64).verdict.unwrap();
        assert_eq!(convention, GreenConvention::OpenGl);
        assert!(confidence > 0.99, "{confidence}");
        let flipped: Vec<Vec3> = normals.iter().map(|n| Vec3::new(n.x, -n.y, n.z)).collect();
        assert_eq!(green_evidence(&flipped, 64, 64).verdict.unwrap().0, GreenConvention::DirectX);
    }

    /// A strong wrong-way patch on one tile of sixteen does not outvote the rest.
    #[test]
    fn one_strong_patch_does_not_outvote_the_map() {
        let mut normals = normals_of(64, 64, bumps);
        let strong = normals_of(64, 64, |x, y| bumps(x * 4.0, y * 4.0));
        for row in 0..16 {
            for x in 0..16 {
                let n = strong[row * 64 + x] * Vec3::new(4.0, -4.0, 1.0);
                normals[row * 64 + x] = n.normalize();
            }
        }
        assert_eq!(green_evidence(&normals, 64, 64).verdict.unwrap().0, GreenConvention::OpenGl);
    }

    /// Bumps of period 32 under fine printed stripes of period 5 along the diagonal: both
    /// slopes shifted alike, which a DirectX groove would also give. Read at the finest octave
    /// alone the stripes outvote the bumps (DirectX, confidence above 0.99); with each octave
    /// an equal say the bumps carry the map.
    #[test]
    fn fine_printed_stripes_do_not_outvote_the_relief() {
        let stripes = |x: f32, y: f32| {
            let (p, q) = bumps(x / 2.0, y / 2.0);
            let g = 0.3 * (std::f32::consts::TAU * (x - y) / 5.0).cos();
            (p + g, q + g)
        };
        let normals = normals_of(128, 128, stripes);
        let (convention, confidence) = green_evidence(&normals, 128, 128).verdict.unwrap();
        assert_eq!(convention, GreenConvention::OpenGl, "{confidence}");
        let flipped: Vec<Vec3> = normals.iter().map(|n| Vec3::new(n.x, -n.y, n.z)).collect();
        assert_eq!(green_evidence(&flipped, 128, 128).verdict.unwrap().0, GreenConvention::DirectX);
    }

    #[test]
    fn maps_without_evidence_say_why() {
        let flat = vec![Vec3::Z; 64 * 64];
        assert_eq!(green_evidence(&flat, 64, 64).verdict, Err(Undetermined::TooFlat));
        let ribs = normals_of(64, 64, |x, _| (0.8 * (x * 0.4).cos(), 0.0));
        assert_eq!(green_evidence(&ribs, 64, 64).verdict, Err(Undetermined::OneDirectional));
        let row = normals_of(256, 1, bumps);
        assert_eq!(green_evidence(&row, 256, 1).verdict, Err(Undetermined::TooFewTexels));
    }

    #[test]
    fn the_normal_distribution_function_is_right_at_known_points() {
        for (z, phi) in [(0.0, 0.5), (1.0, 0.841345), (-1.0, 0.158655), (1.281552, 0.9), (3.0, 0.998650)] {
            assert!((normal_cdf(z) - phi).abs() < 1e-5, "{z}: {}", normal_cdf(z));
        }
    }
}

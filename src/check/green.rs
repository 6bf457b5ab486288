//! Which way a tangent-space normal map's green points, from cells that each cast a bounded
//! vote.
//!
//! A normal map is the gradient of a height field: with decoded `n`, the slopes are
//! `p = ∂h/∂x = −n.x/n.z` and `q = ∂h/∂y_up = −n.y/n.z` (OpenGL reading, `y_up` towards the
//! top row), and a gradient field has zero curl, `a − b = 0` with `a = ∂p/∂y_up` and
//! `b = ∂q/∂x`. Read with the wrong green, `q` changes sign and the residual becomes `a + b`.
//! Per cell the energies `E_gl = Σ(a − b)²` and `E_dx = Σ(a + b)²` differ by `4·Σab`, so the
//! cell votes `v = (E_dx − E_gl) / (E_dx + E_gl)` in −1..1 (positive: OpenGL).
//!
//! The slopes vote in octaves ([`super::green_cells`]): halved in size again and again, each
//! octave cut into cells of at least [`MIN_SIDE`] of its texels and a tile, down to the last
//! octave [`MIN_SIDE`] texels across. A filter commutes with the derivatives, so relief is
//! curl-free in every octave, and coarse relief gets a say of its own however fine the detail
//! printed over it. A cell weighs
//!
//! * its strength: from 0 at [`WEIGHT_FLOOR`] to 1 at [`WEIGHT_FULL`] of mean `|ab|`, both
//!   scaled to what 8-bit quantisation leaves at its octave;
//! * its quality `Q` in 0..1: how much of its slope derivatives a height field explains under
//!   the better reading. Noise, and detail printed into both slopes alike, is no gradient under
//!   either reading: both residuals are large, `Q` near 0, and it carries little evidence;
//! * its area in tiles, so each octave covers the map once and a cell weighs as its share of it.
//!
//! The map's score is the weighted mean vote `m`. Only a cell's part that is no height field
//! can pull its vote, so its own spread is `σ·(1 − Q)` with σ = [`VOTE_SPREAD`], and the
//! standard error counts that and the spread between cells,
//! `se² = Σw²((v − m)² + σ²(1 − Q)²) / (Σw)²`. With a flat prior on the map's true mean vote,
//! the chance that its sign is the one measured is `Φ(|m| / se)`: that is the reported
//! confidence. Below [`DECIDED_CONFIDENCE`] the convention is undetermined, with its reason.

use glam::Vec3;

pub use super::green_cells::MIN_SIDE;
use super::green_cells::{Cell, octave_cells, quantisation_level};

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
    /// There is evidence, but the cells disagree, or what bends is no height field under
    /// either reading: the confidence stays below [`DECIDED_CONFIDENCE`].
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

/// One tile's vote as the cells over it cast it: `vote` in −1..1 (positive: OpenGL),
/// `weight` in 0..1 (evidence per unit of area).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TileVote {
    pub vote: f32,
    pub weight: f32,
}

/// The votes over a map's tiles, row by row from the top, and the verdict.
#[derive(Debug, Clone, PartialEq)]
pub struct GreenEvidence {
    /// Texels per tile side; the last row and column of tiles take the map's remainder.
    pub tile_size: u32,
    pub columns: u32,
    pub rows: u32,
    pub tiles: Vec<TileVote>,
    /// The convention and its confidence `Φ(|m| / se)` in 0.5..1, or why there is none.
    pub verdict: Result<(GreenConvention, f32), Undetermined>,
}

/// Mean `|ab|` per texel, (slope per texel)², at which an octave-0 cell starts to count: 10×
/// what the 8-bit quantisation of a flat map leaves after the blur (about 2·10⁻⁷). Coarser
/// octaves scale it by their quantisation noise ([`quantisation_level`]).
pub const WEIGHT_FLOOR: f32 = 2e-6;
/// Mean `|ab|` at which an octave-0 cell counts fully: 100× the quantisation's level.
pub const WEIGHT_FULL: f32 = 2e-5;
/// The spread σ a cell's vote has on its own where none of it is a height field.
pub const VOTE_SPREAD: f32 = 0.5;
/// Total weight below which a map has too little evidence: one full tile.
pub const MIN_EVIDENCE: f32 = 1.0;
/// The confidence from which a convention is reported; below it, "mixed tiles".
pub const DECIDED_CONFIDENCE: f32 = 0.9;
/// Mixed derivatives below this share of the pure ones (`∂p/∂x`, `∂q/∂y`) mean relief along
/// one axis.
const ONE_DIRECTIONAL_SHARE: f32 = 0.01;

/// The tile side for a `width × height` map: a quarter of the shorter side, 8 to 32 texels.
pub fn tile_size(width: u32, height: u32) -> u32 {
    (width.min(height) / 4).clamp(MIN_SIDE, 32)
}

/// The votes and the verdict for unit normals `normals` of a `width × height` map.
pub fn green_evidence(normals: &[Vec3], width: u32, height: u32) -> GreenEvidence {
    green_evidence_of(|i| normals[i], width, height)
}

/// [`green_evidence`] of the unit normal `normal_at(i)` of each texel `i`, read as needed
/// (a map's decoded normals are never held: 12 bytes a texel).
pub fn green_evidence_of(normal_at: impl Fn(usize) -> Vec3, width: u32, height: u32) -> GreenEvidence {
    let tile = tile_size(width, height);
    let (columns, rows) = ((width / tile).max(1), (height / tile).max(1));
    let evidence = |tiles, verdict| GreenEvidence { tile_size: tile, columns, rows, tiles, verdict };
    if width < MIN_SIDE || height < MIN_SIDE {
        return evidence(vec![], Err(Undetermined::TooFewTexels));
    }
    let (cells, mixed_total, pure_total) = octave_cells(normal_at, width, height, tile);
    let tiles = tile_votes(&cells, columns, rows);
    // The best octave's strength alone, in tiles: does anything bend?
    let octaves = cells.iter().map(|c| c.octave + 1).max().unwrap_or(0);
    let bending = (0..octaves)
        .map(|k| cells.iter().filter(|c| c.octave == k).map(|c| strength_weight(c) * c.area).sum::<f32>())
        .fold(0.0, f32::max);
    if bending < MIN_EVIDENCE {
        let texels = ((width - 2) * (height - 2)) as f64;
        let bends = (pure_total / texels) as f32 > 4.0 * WEIGHT_FULL;
        let one_way = bends && mixed_total < ONE_DIRECTIONAL_SHARE as f64 * pure_total;
        return evidence(tiles, Err(if one_way { Undetermined::OneDirectional } else { Undetermined::TooFlat }));
    }
    evidence(tiles, verdict(&cells))
}

/// A cell's strength weight in 0..1: its mean `|ab|` between [`WEIGHT_FLOOR`] and
/// [`WEIGHT_FULL`], both scaled to its octave's quantisation noise.
fn strength_weight(cell: &Cell) -> f32 {
    let level = quantisation_level(cell.octave);
    ((cell.strength - WEIGHT_FLOOR * level) / ((WEIGHT_FULL - WEIGHT_FLOOR) * level)).clamp(0.0, 1.0)
}

/// A cell's weight in the verdict: strength × quality × area in tiles.
fn weight(cell: &Cell) -> f32 {
    strength_weight(cell) * cell.quality * cell.area
}

/// Each tile's vote for the picture: the votes of the cells over it, weighted by their
/// strength × quality; its weight the largest of those.
fn tile_votes(cells: &[Cell], columns: u32, rows: u32) -> Vec<TileVote> {
    let mut sums = vec![(0.0f32, 0.0f32, 0.0f32); (columns * rows) as usize];
    for cell in cells {
        let [c0, r0, cs, rs] = cell.tiles;
        let w = strength_weight(cell) * cell.quality;
        for row in r0..(r0 + rs).min(rows) {
            for column in c0..(c0 + cs).min(columns) {
                let s = &mut sums[(row * columns + column) as usize];
                (s.0, s.1, s.2) = (s.0 + w * cell.vote, s.1 + w, s.2.max(w));
            }
        }
    }
    sums.iter()
        .map(|&(vote, total, best)| TileVote { vote: if total > 0.0 { vote / total } else { 0.0 }, weight: best })
        .collect()
}

/// The weighted mean vote, its standard error and the confidence `Φ(|m| / se)`.
fn verdict(cells: &[Cell]) -> Result<(GreenConvention, f32), Undetermined> {
    let total: f32 = cells.iter().map(weight).sum();
    if total < MIN_EVIDENCE {
        return Err(Undetermined::MixedTiles);
    }
    let mean = cells.iter().map(|c| weight(c) * c.vote).sum::<f32>() / total;
    let octaves = cells.iter().map(|c| c.octave + 1).max().unwrap_or(0);
    let mut octave_means = vec![(0.0f32, 0.0f32); octaves];
    for c in cells {
        let m = &mut octave_means[c.octave];
        (m.0, m.1) = (m.0 + weight(c) * c.vote, m.1 + weight(c));
    }
    let octave_mean = |c: &Cell| octave_means[c.octave].0 / octave_means[c.octave].1.max(f32::MIN_POSITIVE);
    let own = |c: &Cell| VOTE_SPREAD * (1.0 - c.quality);
    let spread: f32 =
        cells.iter().map(|c| weight(c).powi(2) * ((c.vote - octave_mean(c)).powi(2) + own(c).powi(2))).sum();
    let standard_error = spread.sqrt() / total;
    let confidence = if standard_error > 0.0 { normal_cdf(mean.abs() / standard_error) } else { 1.0 };
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

    /// Blobs of radius 3 texels with random signs, printed into both slopes alike (as a
    /// darkening of red and green): no gradient under either reading.
    fn printed_blobs(size: u32) -> impl Fn(f32, f32) -> f32 {
        let mut seed = 7u32;
        let mut next = move || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1 << 24) as f32
        };
        let blobs: Vec<(f32, f32, f32)> =
            (0..size * size / 24).map(|_| (next() * size as f32, next() * size as f32, next() - 0.5)).collect();
        move |x, y| blobs.iter().map(|&(bx, by, s)| s * (-((x - bx).powi(2) + (y - by).powi(2)) / 9.0).exp()).sum()
    }

    /// Printed detail is no gradient under either reading, so it carries no evidence: alone it
    /// decides nothing, and over weaker coarse relief the relief decides the map.
    #[test]
    fn printed_detail_is_no_evidence_and_does_not_hide_the_relief() {
        let printed = printed_blobs(128);
        let alone = normals_of(128, 128, |x, y| (0.4 * printed(x, y), 0.4 * printed(x, y)));
        assert_eq!(green_evidence(&alone, 128, 128).verdict, Err(Undetermined::MixedTiles));
        let over_relief = normals_of(128, 128, |x, y| {
            let (p, q) = bumps(x / 4.0, y / 4.0);
            let g = 0.4 * printed(x, y);
            (0.25 * p + g, 0.25 * q + g)
        });
        let (convention, confidence) = green_evidence(&over_relief, 128, 128).verdict.unwrap();
        assert_eq!(convention, GreenConvention::OpenGl, "{confidence}");
        let flipped: Vec<Vec3> = over_relief.iter().map(|n| Vec3::new(n.x, -n.y, n.z)).collect();
        assert_eq!(green_evidence(&flipped, 128, 128).verdict.unwrap().0, GreenConvention::DirectX);
    }

    /// Gentle relief (period 64 texels, slopes within ±0.005: under one 8-bit level) stored in
    /// 8 bits. Against a floor of 10× octave 0's rounding noise at every octave it is too flat;
    /// the rounding noise falls to about a quarter an octave, and the coarse octaves hear it.
    #[test]
    fn gentle_coarse_relief_is_heard_above_each_octaves_rounding_noise() {
        let rounded = |n: Vec3| (((n + 1.0) * 127.5).round() / 127.5 - 1.0).normalize();
        let gentle = normals_of(192, 192, |x, y| {
            let (p, q) = bumps(x / 4.0, y / 4.0);
            (0.01 * p, 0.01 * q)
        });
        let stored: Vec<Vec3> = gentle.into_iter().map(rounded).collect();
        let (convention, confidence) = green_evidence(&stored, 192, 192).verdict.unwrap();
        assert_eq!(convention, GreenConvention::OpenGl, "{confidence}");
        let flipped: Vec<Vec3> = stored.iter().map(|n| Vec3::new(n.x, -n.y, n.z)).collect();
        assert_eq!(green_evidence(&flipped, 192, 192).verdict.unwrap().0, GreenConvention::DirectX);
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

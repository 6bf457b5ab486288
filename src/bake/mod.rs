//! `bumpview bake`: height map files to tangent-space normal map PNGs, and normal maps back to
//! height maps.
//!
//! Forward, a height image is differentiated by one of the [`Kernel`]s the report measures
//! ([`crate::height::rows`]: rows in parallel, 8- and 16-bit samples read as stored) and
//! written as it is computed, band by band, to a PNG ([`image_io`]); the whole normal map is
//! never held in memory. Backward ([`to_height_file`]), a normal map's slopes are integrated in
//! the least-squares sense ([`crate::height::integrate`], Frankot & Chellappa 1988) into a
//! 16-bit height map in the same units. Files are written atomically ([`crate::atomic`]) and
//! many files are baked in parallel ([`bake_all`]).

pub mod image_io;

use std::path::{Path, PathBuf};

use image::DynamicImage;
use rayon::prelude::*;

use crate::atomic::write_atomically;
use crate::height::integrate::{Derivative, Slopes, integrate};
use crate::height::rows::{Channels, HeightGrid, MapFormat, Samples, encode_row, for_each_normal_row};
use crate::height::{Border, Kernel};
use crate::scene::GreenAxis;
use image_io::{PngLayout, read_image, write_png};

/// A file that could not be baked, on one line: the file and the problem.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {problem}", path.display())]
pub struct BakeError {
    pub path: PathBuf,
    pub problem: String,
}

impl BakeError {
    pub fn new(path: &Path, problem: impl Into<String>) -> BakeError {
        BakeError { path: path.to_owned(), problem: problem.into() }
    }
}

/// How big one texel is on the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TexelSize {
    /// Metres per texel.
    Metres(f32),
    /// The texture's width in metres (texel = width / texels across).
    TextureWidth(f32),
}

/// How height samples become slopes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Units {
    /// Physical units: `range_m` metres per full sample range (0 → 1) over texels of `texel`.
    Physical { range_m: f32, texel: TexelSize },
    /// A plain strength: a rise of one full range over one texel is a slope of `strength`
    /// (the physical units with `range_m / texel_size_m = strength`).
    Strength(f32),
}

impl Default for Units {
    /// The viewer's units for a height map: 0.01 m per full range, the texture 1 m wide.
    fn default() -> Units {
        Units::Physical { range_m: 0.01, texel: TexelSize::TextureWidth(1.0) }
    }
}

impl Units {
    /// `range_m / texel_size_m` for an image `width` texels wide: the slope (metres per metre)
    /// of one full range per texel.
    pub fn slope_scale(self, width: u32) -> f32 {
        match self {
            Units::Physical { range_m, texel: TexelSize::Metres(m) } => range_m / m,
            Units::Physical { range_m, texel: TexelSize::TextureWidth(m) } => range_m * width as f32 / m,
            Units::Strength(s) => s,
        }
    }
}

/// Settings shared by both directions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BakeOptions {
    /// The derivative: forward, it makes the slopes; backward, its symbol is inverted
    /// ([`Derivative::Kernel`]) unless [`Self::spectral`].
    pub kernel: Kernel,
    /// Backward only: integrate with the continuous derivative `iω` instead of the kernel's.
    pub spectral: bool,
    pub border: Border,
    pub units: Units,
    /// Height maps store depth (white = deep): read so forward, written so backward.
    pub depth: bool,
    /// The normal map's green convention: written so forward, read so backward.
    pub green: GreenAxis,
    /// Forward: 16 bits per channel instead of 8.
    pub sixteen_bit: bool,
    /// Forward: RGB, RGB + height in alpha, or two channels; backward: two-channel input
    /// (`z` rebuilt) when [`Channels::TwoChannel`].
    pub channels: Channels,
}

impl Default for BakeOptions {
    fn default() -> BakeOptions {
        BakeOptions {
            kernel: Kernel::CentralDifference,
            spectral: false,
            border: Border::Wrap,
            units: Units::default(),
            depth: false,
            green: GreenAxis::OpenGl,
            sixteen_bit: false,
            channels: Channels::Rgb,
        }
    }
}

/// What a bake wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Baked {
    pub input: PathBuf,
    pub output: PathBuf,
    pub width: u32,
    pub height: u32,
    /// Backward only: the relief recovered, in full ranges of the output (1 = the whole
    /// range; above 1 the output is clipped), and how many texels were clipped.
    pub relief: Option<(f32, usize)>,
}

/// Height samples as decoded: 8 or 16 bits, one channel.
enum Decoded {
    Eight(Vec<u8>),
    Sixteen(Vec<u16>),
}

/// One channel of heights from an image: grey as stored, colour by luminance (as the viewer
/// reads height maps), 8 or 16 bits as the file has them.
fn heights_of(image: DynamicImage) -> Decoded {
    match image {
        DynamicImage::ImageLuma8(grey) => Decoded::Eight(grey.into_raw()),
        DynamicImage::ImageLuma16(grey) => Decoded::Sixteen(grey.into_raw()),
        image if image.color().bytes_per_pixel() / image.color().channel_count() == 1 => {
            Decoded::Eight(image.to_luma8().into_raw())
        }
        image => Decoded::Sixteen(image.to_luma16().into_raw()),
    }
}

/// Bakes the height map `input` into the normal map PNG `output`.
pub fn bake_file(input: &Path, output: &Path, options: &BakeOptions) -> Result<Baked, BakeError> {
    let image = read_image(input)?;
    let (width, height) = (image.width(), image.height());
    let decoded = heights_of(image);
    let samples = match &decoded {
        Decoded::Eight(s) => Samples::U8(s),
        Decoded::Sixteen(s) => Samples::U16(s),
    };
    let grid = HeightGrid {
        width: width as usize,
        height: height as usize,
        samples,
        slope_scale: options.units.slope_scale(width),
        depth: options.depth,
    };
    let format = MapFormat {
        sixteen_bit: options.sixteen_bit,
        channels: options.channels,
        green_down: options.green == GreenAxis::DirectX,
    };
    let color = match options.channels {
        Channels::Rgb | Channels::TwoChannel => png::ColorType::Rgb,
        Channels::RgbHeight => png::ColorType::Rgba,
    };
    let layout = PngLayout { width, height, color, sixteen_bit: options.sixteen_bit };
    let row_bytes = width as usize * format.texel_bytes();
    write_atomically(output, |out| {
        write_png(out, layout, |rows, bytes| {
            for_each_normal_row(&grid, options.kernel, options.border, rows, bytes, row_bytes, |row, out| {
                encode_row(&row, format, out)
            })
        })
    })
    .map_err(|e| BakeError::new(output, format!("cannot write: {e}")))?;
    Ok(Baked { input: input.to_owned(), output: output.to_owned(), width, height, relief: None })
}

/// Unit normals of a normal map image as `(x, y, z)` per texel, rows top to bottom: decoded
/// `normalize(2·c − 1)` from 8 or 16 bits, green negated for DirectX, `z` rebuilt as
/// `sqrt(max(0, 1 − x² − y²))` for two-channel maps.
fn normals_of(image: &DynamicImage, green: GreenAxis, two_channel: bool) -> Vec<[f32; 3]> {
    let rgb = image.to_rgb32f();
    let flip = if green == GreenAxis::DirectX { -1.0 } else { 1.0 };
    rgb.pixels()
        .map(|p| {
            let [x, y, z] = p.0.map(|c| 2.0 * c - 1.0);
            let y = flip * y;
            let z = if two_channel { (1.0 - x * x - y * y).max(0.0).sqrt() } else { z };
            let length = (x * x + y * y + z * z).sqrt();
            if length > 1e-6 && length.is_finite() { [x / length, y / length, z / length] } else { [0.0, 0.0, 1.0] }
        })
        .collect()
}

/// Normals pointing this close to the surface or below (`z` under this) are read with this
/// `z`: slopes of at most 100.
const MIN_NORMAL_Z: f32 = 0.01;

/// The slopes of unit normals in full ranges per texel (slope ÷ `slope_scale`).
pub fn slopes_of(normals: &[[f32; 3]], width: usize, height: usize, slope_scale: f32) -> Slopes {
    let (dx, dy_up) = normals
        .iter()
        .map(|&[x, y, z]| {
            let z = z.max(MIN_NORMAL_Z);
            (-x / z / slope_scale, -y / z / slope_scale)
        })
        .unzip();
    Slopes { width, height, dx, dy_up }
}

/// Integrates the normal map `input` into the 16-bit grey height map PNG `output`: heights in
/// the options' units (a full range of `range_m` metres, or `1/strength`-per-texel slopes),
/// the lowest point at 0 (white = high; black = high with `depth`), clipped at the full range.
pub fn to_height_file(input: &Path, output: &Path, options: &BakeOptions) -> Result<Baked, BakeError> {
    let image = read_image(input)?;
    let (width, height) = (image.width(), image.height());
    let normals = normals_of(&image, options.green, options.channels == Channels::TwoChannel);
    drop(image);
    let slopes = slopes_of(&normals, width as usize, height as usize, options.units.slope_scale(width));
    drop(normals);
    let derivative = if options.spectral { Derivative::Spectral } else { Derivative::Kernel(options.kernel) };
    let heights = integrate(&slopes, derivative, options.border);
    let lowest = heights.iter().copied().fold(f32::INFINITY, f32::min);
    let highest = heights.iter().copied().fold(f32::NEG_INFINITY, f32::max);
    let clipped = heights.iter().filter(|&&h| h - lowest > 1.0).count();
    let layout = PngLayout { width, height, color: png::ColorType::Grayscale, sixteen_bit: true };
    write_atomically(output, |out| {
        write_png(out, layout, |rows, bytes| {
            let band = &heights[rows.start * width as usize..rows.end * width as usize];
            for (out, &h) in bytes.chunks_exact_mut(2).zip(band) {
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

/// Which way a bake goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Height map → normal map.
    ToNormal,
    /// Normal map → height map.
    ToHeight,
}

impl Direction {
    /// The suffix of an output named after its input: `rock.png` → `rock_normal.png`.
    pub fn suffix(self) -> &'static str {
        match self {
            Direction::ToNormal => "_normal.png",
            Direction::ToHeight => "_height.png",
        }
    }
}

/// The output path of each input: `out` itself for one input unless `out` is a directory (or
/// ends with a separator); else `out/<input stem><suffix>`, the directory created. Two inputs
/// with one stem, or several inputs and an `out` that is an existing file, are an error.
pub fn plan_outputs(inputs: &[PathBuf], out: &Path, direction: Direction) -> Result<Vec<PathBuf>, BakeError> {
    let ends_with_separator = out.as_os_str().to_string_lossy().ends_with(std::path::MAIN_SEPARATOR);
    let into_directory = inputs.len() > 1 || out.is_dir() || ends_with_separator;
    if !into_directory {
        return Ok(vec![out.to_owned()]);
    }
    if out.is_file() {
        return Err(BakeError::new(out, "is a file: several inputs need an output directory"));
    }
    std::fs::create_dir_all(out).map_err(|e| BakeError::new(out, format!("cannot create the directory: {e}")))?;
    let mut outputs: Vec<PathBuf> = vec![];
    for input in inputs {
        let stem = input.file_stem().map_or("baked".into(), |s| s.to_string_lossy().into_owned());
        let output = out.join(format!("{stem}{}", direction.suffix()));
        if outputs.contains(&output) {
            return Err(BakeError::new(input, format!("another input also writes {}", output.display())));
        }
        outputs.push(output);
    }
    Ok(outputs)
}

/// Bakes every `(input, output)` pair, files in parallel; `done` is called after each file.
/// Returns one result per pair, in order.
pub fn bake_all(
    pairs: &[(PathBuf, PathBuf)],
    direction: Direction,
    options: &BakeOptions,
    done: &(dyn Fn(&Result<Baked, BakeError>) + Sync),
) -> Vec<Result<Baked, BakeError>> {
    pairs
        .par_iter()
        .map(|(input, output)| {
            let result = match direction {
                Direction::ToNormal => bake_file(input, output, options),
                Direction::ToHeight => to_height_file(input, output, options),
            };
            done(&result);
            result
        })
        .collect()
}

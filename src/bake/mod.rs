//! `bumpview bake`: height map files to tangent-space normal map PNGs, and normal maps back to
//! height maps.
//!
//! Forward, a height image is differentiated by one of the [`Kernel`]s the report measures
//! ([`crate::height::rows`]: rows in parallel, 8- and 16-bit samples read as stored) and
//! written as it is computed, band by band, to a PNG ([`image_io`]); the whole normal map is
//! never held in memory. Backward ([`to_height_file`]), a normal map's slopes are integrated in
//! the least-squares sense ([`crate::height::integrate`], Frankot & Chellappa 1988) into a
//! 16-bit height map in the same units, in memory bounded by [`to_height_need`]. Files are
//! written atomically ([`crate::atomic`]); many files are baked in parallel ([`bake_all`]),
//! except backward, where one solve already uses every core and memory is budgeted per file.

pub mod compressed_format;
#[cfg(not(target_arch = "wasm32"))]
pub mod compressed_out;
pub mod cone;
pub mod detail;
pub mod image_io;
#[cfg(not(target_arch = "wasm32"))]
mod ktx2_out;
pub mod mips;
pub mod round_trip;
pub mod to_height;

use std::path::{Path, PathBuf};

use image::DynamicImage;
use rayon::prelude::*;

use crate::atomic::write_atomically;
use crate::height::rows::{Channels, HeightGrid, MapFormat, Samples, encode_row, for_each_normal_row};
use crate::height::{Border, Kernel};
use crate::scene::GreenAxis;
use image_io::{PngLayout, read_image, write_png};
pub use to_height::{DEFAULT_MEMORY_LIMIT, slopes_of, to_height_file, to_height_need};

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
    /// ([`crate::height::derivative::Derivative::Kernel`]) unless [`Self::spectral`].
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
    /// Backward: inputs whose [`to_height_need`] is above this many bytes are refused before
    /// decoding ([`DEFAULT_MEMORY_LIMIT`]).
    pub memory_limit: u64,
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
            memory_limit: DEFAULT_MEMORY_LIMIT,
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

/// Bakes every `(input, output)` pair, files in parallel (one at a time backward: each solve is
/// parallel and the memory budget is per file); `done` is called after each file. Returns one
/// result per pair, in order.
pub fn bake_all(
    pairs: &[(PathBuf, PathBuf)],
    direction: Direction,
    options: &BakeOptions,
    done: &(dyn Fn(&Result<Baked, BakeError>) + Sync),
) -> Vec<Result<Baked, BakeError>> {
    let bake = |(input, output): &(PathBuf, PathBuf)| {
        let result = match direction {
            Direction::ToNormal => bake_file(input, output, options),
            Direction::ToHeight => to_height_file(input, output, options),
        };
        done(&result);
        result
    };
    match direction {
        Direction::ToNormal => pairs.par_iter().map(bake).collect(),
        Direction::ToHeight => pairs.iter().map(bake).collect(),
    }
}

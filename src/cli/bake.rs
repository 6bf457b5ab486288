//! `bumpview bake`: height maps to tangent-space normal map PNGs, or normal maps back to
//! height maps (`--to-height`), many files in parallel ([`bumpview::bake`]); or a normal map's
//! mip chain with a mip-filter method's gloss or roughness (`--mips`, [`bumpview::bake::mips`]);
//! or a height map's relaxed cone map (`--cone-map`, [`bumpview::bake::cone`]).

use std::path::{Path, PathBuf};

use bumpview::atomic::check_outputs;
use bumpview::error::escape_controls;

use bumpview::bake::compressed_out::CompressedFormat;
use bumpview::bake::mips::{level_path, mip_levels, write_levels};
use bumpview::bake::{BakeOptions, Direction, TexelSize, Units, bake_all, plan_outputs};
use bumpview::frame::DetailBlend;
use bumpview::height::rows::Channels;
use bumpview::height::{Border, Kernel};
use bumpview::load::image::load_texture;
use bumpview::scene::DEFAULT_DETAIL_TILING;
use bumpview::scene::GreenAxis;
use bumpview::scene::TextureKind;
use bumpview::shading::mip_filter::baked_alpha;
use bumpview::texture::MipFilter;

use super::{Failure, args, progress};
use args::parse_positive;

#[derive(clap::Args)]
pub struct BakeArgs {
    /// Height maps (PNG, JPEG, TGA or BMP; grey or colour by luminance; 8 or 16 bits), or
    /// normal maps with --to-height or --mips.
    #[arg(required = true, value_name = "FILE")]
    inputs: Vec<PathBuf>,
    /// The output PNG, or a directory (needed for several inputs) that receives
    /// `<input name>_normal.png` (or `_height.png`).
    #[arg(long, value_name = "FILE|DIR")]
    out: PathBuf,
    /// Normal maps → 16-bit height maps: the least-squares integral of their slopes
    /// (Frankot–Chellappa), in the same units.
    #[arg(long)]
    to_height: bool,
    /// Finite-difference kernel [default: central]; with --to-height, the derivative whose
    /// Fourier symbol is inverted.
    #[arg(long, value_parser = args::named::<Kernel>())]
    kernel: Option<Kernel>,
    /// With --to-height: integrate with the continuous derivative iω (Frankot and Chellappa's)
    /// instead of the kernel's symbol.
    #[arg(long, requires = "to_height")]
    spectral: bool,
    /// Metres spanned by the height map's full range [default: 0.01].
    #[arg(long, value_name = "METRES", value_parser = parse_positive)]
    height_range: Option<f32>,
    /// Metres one texel covers on the surface [default: the texture's width / its texels].
    #[arg(long, value_name = "METRES", value_parser = parse_positive, conflicts_with = "texture_width")]
    texel_size: Option<f32>,
    /// The texture's width in metres [default: 1].
    #[arg(long, value_name = "METRES", value_parser = parse_positive)]
    texture_width: Option<f32>,
    /// A plain strength instead of units: a rise of the full range over one texel is a slope
    /// of STRENGTH.
    #[arg(long, value_parser = parse_positive, conflicts_with_all = ["height_range", "texel_size", "texture_width"])]
    strength: Option<f32>,
    /// The height map stores depth (white = deep); with --to-height, write depth.
    #[arg(long)]
    depth_map: bool,
    /// Differences at the image border: wrap (tiling) or clamp [default: wrap].
    #[arg(long, value_parser = args::named::<Border>())]
    border: Option<Border>,
    /// Green convention of the normal map written (or read with --to-height): opengl (+Y up
    /// the image) or directx (green inverted) [default: opengl].
    #[arg(long, value_parser = args::named::<GreenAxis>())]
    normal_convention: Option<GreenAxis>,
    /// Bits per channel of the normal map: 8 or 16 [default: 8].
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(["8", "16"]), conflicts_with = "to_height")]
    bits: Option<String>,
    /// RGB = the normal, A = the height (white = high).
    #[arg(long, conflicts_with_all = ["two_channel", "to_height"])]
    height_in_alpha: bool,
    /// Only the normal's x and y (red, green; blue 0); with --to-height, rebuild z from them.
    #[arg(long)]
    two_channel: bool,
    /// With --to-height: refuse inputs whose integration needs more than MIB mebibytes
    /// (8 bytes a texel, 16 with --border clamp, plus the decoded image) [default: 4096].
    #[arg(long, value_name = "MIB", requires = "to_height", value_parser = clap::value_parser!(u64).range(1..=1 << 24))]
    max_memory: Option<u64>,
    /// Normal maps (RGB) → their mip chains under METHOD, one RGBA PNG per level in the
    /// directory --out (`<name>_mip<k>.png`): RGB the level's mean normal re-normalised, alpha
    /// toksvig: the gloss s′/s for --shininess; vmf: the roughness for --roughness;
    /// renormalized-box: 255; base-only: level 0 alone.
    #[arg(long, value_name = "METHOD", value_parser = args::named::<MipFilter>(), conflicts_with_all = [
        "to_height", "kernel", "spectral", "height_range", "texel_size", "texture_width", "strength", "depth_map",
        "border", "normal_convention", "bits", "height_in_alpha", "two_channel",
    ])]
    mips: Option<MipFilter>,
    /// With --mips toksvig: the Blinn-Phong exponent the gloss is for [default: 32].
    #[arg(long, value_name = "S", requires = "mips", value_parser = parse_positive)]
    shininess: Option<f32>,
    /// With --mips vmf: the level-0 perceptual roughness widened per level [default: 0.5].
    #[arg(long, value_name = "R", requires = "mips", value_parser = parse_positive)]
    roughness: Option<f32>,
    /// A detail normal map (RGB, OpenGL convention) to blend over the one input normal map:
    /// writes the blended map, 16-bit RGB, to --out (see --blend, --detail-tiling,
    /// --detail-strength).
    #[arg(long, value_name = "FILE", conflicts_with_all = [
        "to_height", "kernel", "spectral", "height_range", "texel_size", "texture_width", "strength", "depth_map",
        "border", "normal_convention", "bits", "height_in_alpha", "two_channel", "mips",
    ])]
    detail: Option<PathBuf>,
    /// With --detail: how the two blend: linear, partial-derivative, whiteout, udn, rnm or
    /// surface-gradient [default: rnm].
    #[arg(long, value_name = "METHOD", requires = "detail", value_parser = args::named::<DetailBlend>())]
    blend: Option<DetailBlend>,
    /// With --detail: the detail map's repeats across the base map [default: 8].
    #[arg(long, value_name = "TIMES", requires = "detail", value_parser = parse_positive)]
    detail_tiling: Option<f32>,
    /// With --detail: the detail map's strength, as a normal map's scale [default: 1].
    #[arg(long, value_name = "S", requires = "detail")]
    detail_strength: Option<f32>,
    /// The one input height map's relaxed cone map (Policarpo & Oliveira 2007), the data
    /// `--parallax relaxed-cone` marches with: an 8-bit grey PNG at --out,
    /// `255 · √(ratio / 0.25)` (white = the widest cone); --depth-map reads white as deep.
    #[arg(long, conflicts_with_all = [
        "to_height", "kernel", "spectral", "height_range", "texel_size", "texture_width", "strength",
        "border", "normal_convention", "bits", "height_in_alpha", "two_channel", "mips", "detail",
    ])]
    cone_map: bool,
    /// Write the input image as a GPU texture file instead of baking: dds-bc5 (a two-channel
    /// normal map: red, green), dds-dxt5nm (x in alpha, y in green), dds-bc1, dds-bc7,
    /// ktx2-uastc (Basis Universal UASTC, Zstandard) or ktx2-etc1s (BasisLZ). Its texels are
    /// taken as they are.
    #[arg(long, value_name = "FORMAT", value_parser = args::named::<CompressedFormat>(), conflicts_with_all = [
        "to_height", "kernel", "spectral", "height_range", "texel_size", "texture_width", "strength",
        "border", "normal_convention", "bits", "height_in_alpha", "two_channel", "mips", "detail", "cone_map",
    ])]
    format: Option<CompressedFormat>,
    /// With --format dds-… or ktx2-uastc…: write the normal map's whole mip chain into the file
    /// (each level the re-normalised mean of the one above, as the viewer makes it), which the
    /// viewer then draws as the file's own blocks where the adapter samples BC formats.
    #[arg(long, requires = "format")]
    with_mips: bool,
    /// Replace outputs that exist (without it, an existing output is kept and nothing is
    /// baked). An input is never written over, even with --force.
    #[arg(long)]
    force: bool,
}

impl BakeArgs {
    fn options(&self) -> BakeOptions {
        let defaults = BakeOptions::default();
        let units = match (self.strength, self.texel_size, self.texture_width) {
            (Some(strength), _, _) => Units::Strength(strength),
            (None, texel_size, texture_width) => Units::Physical {
                range_m: self.height_range.unwrap_or(0.01),
                texel: match texel_size {
                    Some(m) => TexelSize::Metres(m),
                    None => TexelSize::TextureWidth(texture_width.unwrap_or(1.0)),
                },
            },
        };
        let channels = if self.height_in_alpha {
            Channels::RgbHeight
        } else if self.two_channel {
            Channels::TwoChannel
        } else {
            Channels::Rgb
        };
        BakeOptions {
            kernel: self.kernel.unwrap_or(defaults.kernel),
            spectral: self.spectral,
            border: self.border.unwrap_or(defaults.border),
            units,
            depth: self.depth_map,
            green: self.normal_convention.unwrap_or(defaults.green),
            sixteen_bit: self.bits.as_deref() == Some("16"),
            channels,
            memory_limit: self.max_memory.map_or(defaults.memory_limit, |mib| mib << 20),
        }
    }
}

/// Bakes every input, files in parallel, with a progress bar on a terminal; one line per
/// file written (stdout) or failed (stderr; a single input's failure is the one line).
/// Fails (exit 1) when any file failed; an output that is an input, or that exists without
/// `--force`, is a bad `--out` (exit 2) found before any file is read.
pub fn run(args: &BakeArgs) -> Result<(), Failure> {
    if let Some(filter) = args.mips {
        return run_mips(args, filter);
    }
    if let Some(format) = args.format {
        return super::bake_compressed::run(&args.inputs, &args.out, format, args.with_mips, args.force);
    }
    if args.cone_map {
        return super::bake_cone::run(&args.inputs, &args.out, args.depth_map, args.force);
    }
    if let Some(detail) = &args.detail {
        let method = args.blend.unwrap_or_default();
        let (tiling, strength) =
            (args.detail_tiling.unwrap_or(DEFAULT_DETAIL_TILING), args.detail_strength.unwrap_or(1.0));
        let blend = super::bake_detail::DetailBake { detail, method, tiling, strength, force: args.force };
        return super::bake_detail::run(&args.inputs, &args.out, &blend);
    }
    let direction = if args.to_height { Direction::ToHeight } else { Direction::ToNormal };
    let outputs = plan_outputs(&args.inputs, &args.out, direction).map_err(|e| Failure::Failed(e.to_string()))?;
    let inputs: Vec<&Path> = args.inputs.iter().map(PathBuf::as_path).collect();
    let planned: Vec<&Path> = outputs.iter().map(PathBuf::as_path).collect();
    check_outputs(&inputs, &planned, args.force).map_err(|e| Failure::BadArguments(e.to_string()))?;
    let pairs: Vec<_> = args.inputs.iter().cloned().zip(outputs).collect();
    let bar = progress::bar(pairs.len() as u64, "bake");
    let results = bake_all(&pairs, direction, &args.options(), &|result| {
        if let Ok(baked) = result {
            bar.set_message(escape_controls(&baked.output.display().to_string()).into_owned());
        }
        bar.inc(1);
    });
    bar.finish_and_clear();
    if let [Err(error)] = &results[..] {
        return Err(Failure::Failed(error.to_string()));
    }
    let mut failed = 0;
    for result in &results {
        match result {
            Ok(baked) => {
                let relief = baked.relief.map_or(String::new(), |(relief, clipped)| {
                    let clipped = if clipped > 0 { format!(", {clipped} texels clipped") } else { String::new() };
                    format!(", relief {relief:.3} of the full range{clipped}")
                });
                let output = baked.output.display().to_string();
                println!("wrote {} ({}x{}{relief})", escape_controls(&output), baked.width, baked.height);
            }
            Err(error) => {
                eprintln!("bumpview: {}", escape_controls(&error.to_string()));
                failed += 1;
            }
        }
    }
    match failed {
        0 => Ok(()),
        n => Err(Failure::Failed(format!("{n} of {} files failed", results.len()))),
    }
}

/// `bake --mips`: every input's chain into the directory `--out`, one line per file written.
/// Every level file of every input is planned from the images' headers and checked against
/// all inputs and each other before the first is written ([`plan_levels`]).
fn run_mips(args: &BakeArgs, filter: MipFilter) -> Result<(), Failure> {
    let name: &str = filter.into();
    let (shininess, roughness) = (args.shininess.unwrap_or(32.0), args.roughness.unwrap_or(0.5));
    let alpha = baked_alpha(filter, shininess, roughness)
        .map_err(|reason| Failure::BadArguments(format!("--mips {name}: {reason}")))?;
    if std::fs::symlink_metadata(&args.out).is_ok() && !args.out.is_dir() {
        let out = args.out.display();
        return Err(Failure::BadArguments(format!(
            "--out {out}: is not a directory: --mips writes one file per level into a directory"
        )));
    }
    let planned = plan_levels(args, filter);
    let inputs: Vec<&Path> = args.inputs.iter().map(PathBuf::as_path).collect();
    let all: Vec<&Path> = planned.iter().flatten().flatten().map(PathBuf::as_path).collect();
    check_outputs(&inputs, &all, args.force).map_err(|e| Failure::BadArguments(e.to_string()))?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| Failure::Failed(format!("{}: cannot create the directory: {e}", args.out.display())))?;
    let mut failed = 0;
    for (input, paths) in args.inputs.iter().zip(&planned) {
        let written = paths.as_ref().ok_or_else(|| unreadable_header(input)).and_then(|paths| {
            let map = load_texture(input, TextureKind::NormalMap).map_err(|e| e.to_string())?;
            let levels = mip_levels(&map, filter.has_mips(), &alpha);
            if levels.len() != paths.len() {
                return Err(format!("{}: changed while baking (its header said another size)", input.display()));
            }
            write_levels(&levels, paths).map_err(|e| e.to_string())?;
            Ok(levels.iter().map(|l| (l.width, l.height)).collect::<Vec<_>>())
        });
        match written {
            Ok(sizes) => {
                for ((width, height), path) in sizes.into_iter().zip(paths.iter().flatten()) {
                    let path = path.display().to_string();
                    println!("wrote {} ({width}x{height}, {name})", escape_controls(&path));
                }
            }
            Err(e) => {
                eprintln!("bumpview: {}", escape_controls(&e));
                failed += 1;
            }
        }
    }
    match failed {
        0 => Ok(()),
        n => Err(Failure::Failed(format!("{n} of {} files failed", args.inputs.len()))),
    }
}

/// The level files `bake --mips` writes for each input (`None` where its header cannot be
/// read; that input then fails alone): as many as the chain down to 1×1 has,
/// `floor(log2(max(width, height))) + 1`, or level 0 alone for a method without mips.
fn plan_levels(args: &BakeArgs, filter: MipFilter) -> Vec<Option<Vec<PathBuf>>> {
    let count =
        |[width, height]: [u32; 2]| if filter.has_mips() { width.max(height).max(1).ilog2() as usize + 1 } else { 1 };
    let plan = |input: &PathBuf| {
        let levels = count(header_size(input)?);
        Some((0..levels).map(|k| level_path(&args.out, input, k)).collect())
    };
    args.inputs.iter().map(plan).collect()
}

/// An image file's size from its header, without decoding its pixels; `None` for anything but
/// a regular file (a FIFO is never opened) or an unreadable header. TGA, which has no
/// signature, by its extension.
fn header_size(path: &Path) -> Option<[u32; 2]> {
    if !std::fs::metadata(path).ok()?.is_file() {
        return None;
    }
    let mut reader = image::ImageReader::open(path).ok()?.with_guessed_format().ok()?;
    if reader.format().is_none() {
        reader.set_format(image::ImageFormat::from_path(path).ok().filter(|&f| f == image::ImageFormat::Tga)?);
    }
    let (width, height) = reader.into_dimensions().ok()?;
    Some([width, height])
}

/// The line for an input whose header could not be read (its load names the problem).
fn unreadable_header(input: &Path) -> String {
    match load_texture(input, TextureKind::NormalMap) {
        Err(e) => e.to_string(),
        Ok(_) => format!("{}: its image header could not be read", input.display()),
    }
}

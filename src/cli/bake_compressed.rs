//! `bumpview bake IMAGE --format dds-bc5|dds-bc7|dds-bc1|dds-dxt5nm|ktx2-uastc|ktx2-etc1s
//! [--with-mips] --out FILE|DIR`: the image (any format the loader reads) written as a GPU
//! texture file, one level or (DDS, UASTC) its whole mip chain
//! ([`bumpview::bake::compressed_out`]). Its RGBA texels are taken as they are (no colour
//! conversion): a normal map stays a normal map.

use std::path::{Path, PathBuf};

use bumpview::atomic::{check_outputs, write_bytes_atomically};
use bumpview::bake::compressed_out::{CompressedFormat, encode, encode_with_mips};
use bumpview::error::escape_controls;
use bumpview::load::image::load_texture;
use bumpview::names::Named;
use bumpview::scene::TextureKind;

use super::Failure;

/// Writes the one input as `format` to `out` (a directory: the input's name with the format's
/// extension in it), with its mip chain where `with_mips`.
pub fn run(
    inputs: &[PathBuf],
    out: &Path,
    format: CompressedFormat,
    with_mips: bool,
    force: bool,
) -> Result<(), Failure> {
    let [input] = inputs else {
        return Err(Failure::BadArguments("--format writes one image's texture file: give one input".into()));
    };
    let output = match out.is_dir() {
        true => out.join(Path::new(input.file_stem().unwrap_or_default()).with_extension(format.extension())),
        false => out.to_owned(),
    };
    check_outputs(&[input.as_path()], &[output.as_path()], force).map_err(|e| Failure::BadArguments(e.to_string()))?;
    let failed = |e: &dyn std::fmt::Display| Failure::Failed(escape_controls(&e.to_string()).into_owned());
    let texture = load_texture(input, TextureKind::Data).map_err(|e| failed(&e))?;
    let write = if with_mips { encode_with_mips } else { encode };
    let bytes = write(&texture.rgba, texture.width, texture.height, format)
        .map_err(|e| failed(&format!("{}: {e}", input.display())))?;
    write_bytes_atomically(&output, &bytes).map_err(|e| failed(&format!("{}: {e}", output.display())))?;
    let path = output.display().to_string();
    println!(
        "wrote {} ({}x{}, {}, {} bytes)",
        escape_controls(&path),
        texture.width,
        texture.height,
        format.name(),
        bytes.len()
    );
    Ok(())
}

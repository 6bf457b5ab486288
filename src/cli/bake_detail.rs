//! `bumpview bake BASE --detail DETAIL --blend METHOD --out FILE`: the two normal maps blended
//! into one 16-bit normal map ([`bumpview::bake::detail`]).

use std::path::{Path, PathBuf};

use bumpview::atomic::check_outputs;
use bumpview::bake::detail::write_normals_16;
use bumpview::error::escape_controls;
use bumpview::frame::DetailBlend;
use bumpview::load::image::load_texture;
use bumpview::names::Named;
use bumpview::scene::TextureKind;
use bumpview::shading::detail_blend::blend_maps;

use super::Failure;

/// What `--detail` blends with.
pub struct DetailBake<'a> {
    pub detail: &'a Path,
    pub method: DetailBlend,
    pub tiling: f32,
    pub strength: f32,
    pub force: bool,
}

/// Blends the one input (the base normal map) with the detail map and writes `out`.
pub fn run(inputs: &[PathBuf], out: &Path, bake: &DetailBake) -> Result<(), Failure> {
    let [input] = inputs else {
        return Err(Failure::BadArguments("--detail blends over one base normal map: give one input".into()));
    };
    if out.is_dir() {
        return Err(Failure::BadArguments(format!("--out {}: --detail writes one PNG file", out.display())));
    }
    check_outputs(&[input.as_path(), bake.detail], &[out], bake.force)
        .map_err(|e| Failure::BadArguments(e.to_string()))?;
    let failed = |e: &dyn std::fmt::Display| Failure::Failed(escape_controls(&e.to_string()).into_owned());
    let base = load_texture(input, TextureKind::NormalMap).map_err(|e| failed(&e))?;
    let detail = load_texture(bake.detail, TextureKind::NormalMap).map_err(|e| failed(&e))?;
    let normals = blend_maps(&base, &detail, bake.tiling, bake.strength, bake.method);
    write_normals_16(out, base.width, &normals).map_err(|e| failed(&e))?;
    let path = out.display().to_string();
    println!(
        "wrote {} ({}x{}, 16-bit, {} blend, detail ×{} at strength {})",
        escape_controls(&path),
        base.width,
        base.height,
        bake.method.name(),
        bake.tiling,
        bake.strength
    );
    Ok(())
}

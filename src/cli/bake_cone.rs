//! `bumpview bake HEIGHT --cone-map --out FILE`: the height map's relaxed cone map, the data
//! relaxed cone stepping marches with ([`bumpview::bake::cone`]).

use std::path::{Path, PathBuf};

use bumpview::atomic::check_outputs;
use bumpview::bake::cone::write_cone_map;
use bumpview::error::escape_controls;
use bumpview::load::image::load_texture;
use bumpview::scene::{HeightMap, TextureKind};

use super::Failure;

/// Builds the one input's cone map (`depth_map`: white is deep) and writes `out`.
pub fn run(inputs: &[PathBuf], out: &Path, depth_map: bool, force: bool) -> Result<(), Failure> {
    let [input] = inputs else {
        return Err(Failure::BadArguments("--cone-map builds one height map's cones: give one input".into()));
    };
    if out.is_dir() {
        return Err(Failure::BadArguments(format!("--out {}: --cone-map writes one PNG file", out.display())));
    }
    check_outputs(&[input.as_path()], &[out], force).map_err(|e| Failure::BadArguments(e.to_string()))?;
    let failed = |e: &dyn std::fmt::Display| Failure::Failed(escape_controls(&e.to_string()).into_owned());
    let heights = load_texture(input, TextureKind::Height).map_err(|e| failed(&e))?;
    let slot = HeightMap { depth: depth_map, ..HeightMap::new(0, 1.0) };
    let stats = write_cone_map(out, &slot.height_field(&heights, 1.0)).map_err(|e| failed(&e))?;
    let path = out.display().to_string();
    println!(
        "wrote {} ({}x{}, relaxed cones: narrowest {:.4}, mean {:.4} UV per depth, built in {:.2} s)",
        escape_controls(&path),
        heights.width,
        heights.height,
        stats.narrowest,
        stats.mean,
        stats.build_s
    );
    Ok(())
}

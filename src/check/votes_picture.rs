//! The tiles' green votes as a picture over the map (`bumpview check --explain`): the map's
//! relief in grey (lit from the upper left under the OpenGL reading), each tile tinted blue
//! where it votes OpenGL and orange where it votes DirectX, the more opaque the stronger its
//! `weight · |vote|`, with a dark line around each tile.

use glam::Vec3;
use image::RgbaImage;

use super::green::GreenEvidence;

/// Tint of an OpenGL vote, sRGB.
const OPENGL_TINT: [f32; 3] = [40.0, 120.0, 255.0];
/// Tint of a DirectX vote, sRGB.
const DIRECTX_TINT: [f32; 3] = [255.0, 120.0, 20.0];
/// The most a tile's tint covers the relief.
const MAX_TINT: f32 = 0.7;

/// The votes of `evidence` over unit `normals` of a `width × height` map.
pub fn votes_picture(normals: &[Vec3], width: u32, height: u32, evidence: &GreenEvidence) -> RgbaImage {
    let light = Vec3::new(-1.0, 1.0, 1.5).normalize();
    let tile = evidence.tile_size.max(1);
    RgbaImage::from_fn(width, height, |x, y| {
        let n = normals.get((y * width + x) as usize).copied().unwrap_or(Vec3::Z);
        let grey = 255.0 * (0.25 + 0.75 * n.dot(light).max(0.0));
        let index =
            (y / tile).min(evidence.rows.max(1) - 1) * evidence.columns + (x / tile).min(evidence.columns.max(1) - 1);
        let Some(vote) = evidence.tiles.get(index as usize) else {
            return image::Rgba([grey as u8, grey as u8, grey as u8, 255]);
        };
        let tint = if vote.vote >= 0.0 { OPENGL_TINT } else { DIRECTX_TINT };
        let cover = MAX_TINT * (vote.weight * vote.vote.abs()).sqrt();
        let edge = (x % tile == 0 && x / tile < evidence.columns) || (y % tile == 0 && y / tile < evidence.rows);
        let rgb = tint.map(|t| {
            let c = grey + cover * (t - grey);
            (if edge { 0.6 * c } else { c }).round() as u8
        });
        image::Rgba([rgb[0], rgb[1], rgb[2], 255])
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::green::{TileVote, Undetermined};

    /// One tile voting OpenGL fully, one DirectX fully, one with no weight.
    #[test]
    fn tiles_are_tinted_by_their_vote() {
        let votes = [(1.0, 1.0), (-1.0, 1.0), (1.0, 0.0)];
        let tiles = votes.map(|(vote, weight)| TileVote { vote, weight }).to_vec();
        let evidence =
            GreenEvidence { tile_size: 8, columns: 3, rows: 1, tiles, verdict: Err(Undetermined::MixedTiles) };
        let picture = votes_picture(&vec![Vec3::Z; 24 * 8], 24, 8, &evidence);
        let [opengl, directx, none] = [4, 12, 20].map(|x| picture.get_pixel(x, 4).0);
        assert!(opengl[2] > opengl[0] + 60, "{opengl:?}");
        assert!(directx[0] > directx[2] + 60, "{directx:?}");
        assert!(none[0] == none[1] && none[1] == none[2], "{none:?}");
        assert!(picture.get_pixel(8, 4).0[0] < directx[0], "tile edges are darker");
    }
}

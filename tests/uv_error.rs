//! The parallax family's UV error against the exact intersection on the built-in wall
//! (`bumpview::report::uv_error`): it falls as the layers grow, it is 0 face-on and at depth
//! 0, and relief at 64 layers is within 0.05 texel at 70°.

use bumpview::frame::Parallax;
use bumpview::report::uv_error::{Relief, cone_channel, grid, study, uv_error};

/// Points per side of the grid the tests measure over (1024 points of the 512² tile).
const N: u32 = 32;

fn error_of(rows: &[bumpview::report::uv_error::UvError], technique: Parallax, layers: u32) -> f64 {
    rows.iter().find(|r| r.technique == technique && r.layers == Some(layers)).map(|r| r.mean).expect("row")
}

/// Every search (steep, occlusion, relief, relaxed cones): the mean UV error at 8 layers is
/// below that at 4, and so on up to 64, at 45° and 70° (a search of more layers brackets the
/// crossing more tightly), or, once under a hundredth of a texel, no farther: relaxed cones
/// reach the relief in fewer steps than they are given and stop there (measured: 0.0019 texel
/// from 16 steps on at 45°, 0.003 from 32 at 70°).
#[test]
fn each_search_gets_closer_as_its_layers_grow() {
    let relief = Relief::wall();
    let layers = [4, 8, 16, 32, 64];
    let rows = study(&relief, &[45.0, 70.0], &layers, N);
    for angle in [45.0, 70.0] {
        let at: Vec<_> = rows.iter().filter(|r| r.angle_deg == angle).copied().collect();
        for technique in Parallax::shifting().filter(|t| t.marches()) {
            let means = layers.map(|n| error_of(&at, technique, n));
            let closer = |w: &[f64]| w[1] < w[0] || (w[1] <= w[0] && w[0] < 0.01);
            assert!(means.windows(2).all(closer), "{technique:?} at {angle}°: {means:?}");
            assert!(means.iter().all(|m| m.is_finite()));
        }
    }
}

/// Face-on, and at depth 0 from every angle, no technique moves the UV and the exact hit is
/// straight below: the error is exactly 0, with no point on the wrong brick.
#[test]
fn face_on_and_depth_zero_have_no_uv_error() {
    let wall = Relief::wall();
    let flat = Relief { depth_m: 0.0, ..Relief::wall() };
    let points = grid(8);
    for (relief, angles) in [(&wall, vec![0.0]), (&flat, vec![0.0, 45.0, 70.0, 85.0])] {
        for angle in angles {
            let hits: Vec<_> = points.iter().map(|&uv| relief.exact(uv, angle)).collect();
            for technique in Parallax::shifting() {
                for layers in [Some(4), Some(64)] {
                    let e = uv_error(relief, &points, &hits, angle, (technique, layers));
                    assert_eq!(
                        (e.mean, e.max, e.wrong_brick),
                        (0.0, 0.0, Some(0.0)),
                        "{technique:?} {angle}° depth {}",
                        relief.depth_m
                    );
                }
            }
        }
    }
}

/// Relief mapping, 64 layers and its 5 bisection steps, at 70°: the bracket is 1/64 of the
/// ≈14-texel path, halved 5 times (≈0.007 texel); every point within 0.05 texel on average
/// and at the 95th percentile.
#[test]
fn relief_at_64_layers_is_within_a_twentieth_of_a_texel_at_70_degrees() {
    let relief = Relief::wall();
    let points = grid(N);
    let hits: Vec<_> = points.iter().map(|&uv| relief.exact(uv, 70.0)).collect();
    let e = uv_error(&relief, &points, &hits, 70.0, (Parallax::Relief, Some(64)));
    assert!(e.mean < 0.05 && e.p95 < 0.05, "{e:?}");
}

/// A wrong brick needs the UV path to read both a brick face and mortar: within one face
/// (or one joint) it is a shift; from a face into a joint, or across a joint onto the next
/// face, it is not.
#[test]
fn a_wrong_brick_spans_a_face_and_a_joint() {
    use bumpview::height::HeightField;
    use glam::DVec2;
    // Twelve texels across: a face (1.0), a joint (0.0), another face, four texels each.
    let samples = [1.0, 0.0, 1.0].iter().flat_map(|&h| [h; 4]).collect();
    let field = HeightField { width: 12, height: 1, samples, range_m: 0.01, texel_size_m: 1.0 / 12.0 };
    let cones = cone_channel(&field);
    let relief = Relief { name: "strip", bricks: true, field, cones, depth_m: 0.01, tile_m: 1.0 };
    let at = |texel: f64| DVec2::new(texel / 12.0, 0.5);
    assert!(!relief.crosses_region(at(0.6), at(2.9)), "within the first face");
    assert!(!relief.crosses_region(at(5.6), at(6.9)), "within the joint");
    assert!(relief.crosses_region(at(2.9), at(6.0)) && relief.crosses_region(at(6.0), at(2.9)), "face and joint");
    assert!(relief.crosses_region(at(1.0), at(10.0)), "across the joint onto the other face");
}

/// Relaxed cone stepping (Policarpo & Oliveira 2007) against the linear searches, as the
/// report's layer table counts them: the fewest of its layer counts (4 to 64; cone steps for
/// the cones) for a mean UV error under half a texel, at 45°, 70° and 80°, on the wall and,
/// with the shared assets, Rock058. The cones never need more than steep on the wall. Also
/// prints each cone map's build time (this profile). Measured: see docs/parallax.md.
#[test]
fn layers_for_half_a_texel() {
    let mut reliefs = vec![Relief::wall()];
    if let Some(assets) = std::env::var_os("BUMPVIEW_TEST_ASSETS") {
        let rock = bumpview::report::parallax::rock(std::path::Path::new(&assets)).expect("Rock058");
        reliefs.extend(Relief::of_specimen("Rock058", &rock));
    }
    let (layers, angles) = ([4, 8, 16, 32, 64], [45.0, 70.0, 80.0]);
    for relief in &reliefs {
        let started = std::time::Instant::now();
        let _ = cone_channel(&relief.field);
        let (w, h) = (relief.field.width, relief.field.height);
        println!("{}: cone map ({w}×{h}) built in {:.2} s", relief.name, started.elapsed().as_secs_f64());
        let rows = study(relief, &angles, &layers, N);
        let needed = |technique: Parallax| {
            angles.map(|angle| {
                let under = rows.iter().filter(|r| r.technique == technique && r.angle_deg == angle && r.mean < 0.5);
                under.min_by_key(|r| r.layers).map(|r| (r.layers, (r.mean * 1000.0).round() / 1000.0))
            })
        };
        for technique in Parallax::shifting() {
            println!("{} {technique:?}: layers for half a texel at {angles:?}: {:?}", relief.name, needed(technique));
        }
        if relief.bricks {
            let count = |n: Option<(Option<u32>, f64)>| n.map_or(u32::MAX, |(l, _)| l.unwrap_or(0));
            let (cones, steep) = (needed(Parallax::RelaxedCone).map(count), needed(Parallax::Steep).map(count));
            assert!(cones.iter().zip(&steep).all(|(c, s)| c <= s), "cones {cones:?}, steep {steep:?}");
        }
    }
}

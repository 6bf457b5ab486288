//! The classic mistakes (`--mistake`): each draws on the GPU as the CPU chain does (the probe)
//! and changes the picture the documented way, measured against the correct picture.

mod common;

use bumpview::frame::{FrameParams, Mistake, SceneOptions};
use bumpview::names::Named;
use bumpview::scene::Scene;
use common::*;
use glam::{Mat4, Vec3, Vec4};

const SIZE: [u32; 2] = [128, 128];

/// Steps of 8 bits the GPU's lit and shading-normal pictures may differ from the probe: on the
/// close wall 3 and 2 (tests/probe.rs); on the torus 10 and 6: its minified, steeply seen
/// bricks leave the probe's mip level estimate off the GPU's at a few pixels (measured up to
/// 7.4 steps lit, 4.3 normal, the same with and without the mistake), as tests/probe.rs allows
/// 6 on the asset meshes.
const WALL: [f32; 2] = [3.0, 2.0];
const CURVED: [f32; 2] = [10.0, 6.0];

/// The probe's shading normals on a grid of pixels under `mistake` (as ViewerState's uploads
/// prepare it: frames without Gram-Schmidt for that mistake), after checking the GPU equals
/// them; `None` where a pixel is left out.
fn shading_normals(scene: &Scene, params: &FrameParams, mistake: Mistake, tolerance: [f32; 2]) -> Vec<Option<Vec3>> {
    let mut params = *params;
    params.shading.mistake = mistake;
    let options =
        SceneOptions { tangents_without_gram_schmidt: mistake == Mistake::NoGramSchmidt, ..Default::default() };
    println!("{}:", mistake.name());
    let readouts = gpu_against_probe(scene, &options, &params, SIZE, 9, tolerance);
    let grid = (4..SIZE[1] - 1).step_by(9).flat_map(|y| (4..SIZE[0] - 1).step_by(9).map(move |x| [x, y]));
    grid.map(|pixel| readouts.iter().find(|(p, _)| *p == pixel).map(|(_, r)| r.chain.shading_normal)).collect()
}

/// Pairs of (correct, mistaken) shading normals where both exist.
fn pairs(scene: &Scene, params: &FrameParams, mistake: Mistake, tolerance: [f32; 2]) -> Vec<(Vec3, Vec3)> {
    let correct = shading_normals(scene, params, Mistake::None, tolerance);
    let wrong = shading_normals(scene, params, mistake, tolerance);
    correct.into_iter().zip(wrong).filter_map(|(a, b)| a.zip(b)).collect()
}

fn median(mut values: Vec<f32>) -> f32 {
    values.sort_by(f32::total_cmp);
    values[values.len() / 2]
}

fn wall_scene() -> (Scene, FrameParams) {
    let scene = scene();
    let params = close_wall_params(&scene, 0.3);
    (scene, params)
}

/// The GLSL practicum's typo on the wall (N = +Z, T = +X, B = +Y): the world y takes
/// `N.z · n_t.z`, so every normal leans up by about 45° (exactly 45° for a flat texel).
#[test]
fn the_tbn_typo_leans_the_wall_up() {
    let (scene, params) = wall_scene();
    let found = pairs(&scene, &params, Mistake::TbnTypo, WALL);
    let lean = median(found.iter().map(|(_, wrong)| wrong.y.atan2(wrong.z).to_degrees()).collect());
    let correct = median(found.iter().map(|(right, _)| right.y.atan2(right.z).to_degrees()).collect());
    println!("median lean towards +Y: {lean:.1}° (correct {correct:.1}°)");
    assert!((lean - 45.0).abs() < 2.0 && correct.abs() < 2.0, "{lean} {correct}");
}

/// Through an sRGB view the flat texel (128, 128, 255) decodes 38.8° off the surface normal,
/// towards −T −B: the median angle to the correct normal on the bricks (mostly flat faces).
#[test]
fn an_srgb_view_tilts_flat_normals_by_39_degrees_towards_minus_t_minus_b() {
    let (scene, params) = wall_scene();
    let found = pairs(&scene, &params, Mistake::SrgbNormalMap, WALL);
    let angle = median(found.iter().map(|(right, wrong)| right.angle_between(*wrong).to_degrees()).collect());
    let towards = median(found.iter().map(|(_, wrong)| wrong.x + wrong.y).collect());
    println!("median tilt {angle:.1}°, median x + y {towards:.3}");
    assert!((angle - 38.8).abs() < 1.0 && towards < -0.8, "{angle} {towards}");
}

/// Green flipped mirrors the relief's lighting across the T-N plane: each shading normal's B
/// (here y) component changes sign, T and N stay.
#[test]
fn green_flipped_mirrors_the_bitangent_component() {
    let (scene, params) = wall_scene();
    let found = pairs(&scene, &params, Mistake::GreenFlipped, WALL);
    let worst = found.iter().map(|(r, w)| (*w - Vec3::new(r.x, -r.y, r.z)).abs().max_element()).fold(0.0, f32::max);
    let moved = found.iter().filter(|(r, _)| r.y.abs() > 0.05).count();
    println!("green flipped: worst {worst:.2e} off the mirrored normal, {moved} of {} pixels sloped in y", found.len());
    assert!(worst < 1e-4 && moved > 10, "{worst} {moved}");
}

/// Handedness ignored changes nothing where w = +1 and mirrors B where w = −1: on the wall
/// drawn through a mirroring transform (x → −x), the mistaken normals have the B component
/// (here y) negated.
#[test]
fn ignored_handedness_flips_only_mirrored_surfaces() {
    let (scene, params) = wall_scene();
    let same = pairs(&scene, &params, Mistake::HandednessIgnored, WALL);
    assert!(same.len() > 100, "only {} pixels compared", same.len());
    assert!(same.iter().all(|(r, w)| (*r - *w).length() < 1e-6));
    let mut mirrored = scene.clone();
    mirrored.instances[0].transform = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
    let found = pairs(&mirrored, &params, Mistake::HandednessIgnored, WALL);
    let worst = found.iter().map(|(r, w)| (*w - Vec3::new(r.x, -r.y, r.z)).abs().max_element()).fold(0.0, f32::max);
    let moved = found.iter().filter(|(r, _)| r.y.abs() > 0.05).count();
    println!("handedness ignored on the mirrored wall: worst {worst:.2e}, {moved} pixels sloped in y");
    assert!(worst < 1e-4 && moved > 10, "{worst} {moved}");
}

/// Without Gram-Schmidt a supplied tangent leaning 30° out of the wall stays leaning: the
/// correct picture ignores the lean (equal to the wall with plain tangents), the mistaken one
/// tips sloped normals towards T's lean (its z grows where the slope along T is positive).
#[test]
fn without_gram_schmidt_a_leaning_tangent_tips_the_bump() {
    let (mut scene, params) = wall_scene();
    let plain = shading_normals(&scene, &params, Mistake::None, WALL);
    let lean = 30f32.to_radians();
    let count = scene.meshes[0].positions.len();
    scene.meshes[0].tangents = Some(vec![Vec4::new(lean.cos(), 0.0, lean.sin(), 1.0); count]);
    let found = pairs(&scene, &params, Mistake::NoGramSchmidt, WALL);
    let correct: Vec<Vec3> = found.iter().map(|p| p.0).collect();
    let expected: Vec<Vec3> = plain.into_iter().flatten().collect();
    assert!(correct.iter().zip(&expected).all(|(a, b)| (*a - *b).length() < 1e-5), "Gram-Schmidt removes the lean");
    // T = (cos 30°, 0, sin 30°): the mistaken normal is T·x + B·y + N·z, normalised.
    let worst = found
        .iter()
        .map(|(r, w)| {
            let t = Vec3::new(lean.cos(), 0.0, lean.sin());
            let b = Vec3::Z.cross(t);
            let expected = (t * r.x + b * r.y + Vec3::Z * r.z).normalize();
            (*w - expected).length()
        })
        .fold(0.0, f32::max);
    let changed = found.iter().filter(|(r, w)| r.angle_between(*w) > 1f32.to_radians()).count();
    println!("no Gram-Schmidt: worst {worst:.2e} off T·x + B·y + N·z, {changed} pixels moved > 1°");
    assert!(worst < 1e-4 && changed > 10, "{worst} {changed}");
}

/// No re-normalisation changes nothing on the flat wall (its interpolated normal is unit) and
/// shortens the torus's normals between vertices. With T and B unit and orthogonal to the
/// interpolated normal N' of length L, the mistaken normal `T·x + B·y + N'·z` has length
/// `sqrt(x² + y² + L²·z²)`: between L and 1 at every pixel, where L comes from the hit's
/// weights and the triangle's vertex normals (computed here from the mesh). Mid-edge L is
/// `cos(half the angle between the two vertex normals)`; the shortest normal seen is within a
/// tenth of the shortening of the widest edge's mid-point (measured: 0.99472 at 140 pixels
/// against 0.99466 for the widest edge, 11.85°).
#[test]
fn no_renormalisation_shortens_normals_only_where_they_bend() {
    let (scene, params) = wall_scene();
    let same = pairs(&scene, &params, Mistake::NoRenormalization, WALL);
    assert!(same.len() > 100, "only {} pixels compared", same.len());
    assert!(same.iter().all(|(r, w)| (*r - *w).length() < 1e-5));
    let mut params = default_params(&scene);
    params.camera.target = bumpview::scene::builtin::TORUS_CENTER;
    params.camera.distance = 1.2;
    params.shading.mistake = Mistake::NoRenormalization;
    let readouts = gpu_against_probe(&scene, &SceneOptions::default(), &params, SIZE, 9, CURVED);
    let torus = scene.meshes.iter().position(|m| m.name == "torus").expect("the built-in torus");
    let normals = &scene.meshes[torus].normals;
    let widest = scene.meshes[torus]
        .indices
        .chunks_exact(3)
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| normals[a as usize].angle_between(normals[b as usize]))
        .fold(0.0f32, f32::max);
    let mid_edge = (widest / 2.0).cos();
    let (mut shortest, mut on_torus) = (1.0f32, 0);
    for (pixel, r) in &readouts {
        let instance = &scene.instances[r.point.instance];
        if instance.mesh != torus {
            continue;
        }
        let corners = &scene.meshes[torus].indices[3 * r.point.triangle..3 * r.point.triangle + 3];
        let weights = r.point.barycentric;
        let interpolated: Vec3 = (0..3).map(|i| normals[corners[i] as usize].normalize() * weights[i]).sum();
        let (length, shown) = (interpolated.length(), r.chain.shading_normal.length());
        assert!(shown >= length - 1e-4 && shown <= 1.0 + 1e-5, "{pixel:?}: |n| {shown}, interpolated {length}");
        shortest = shortest.min(shown);
        on_torus += 1;
    }
    println!(
        "no re-normalisation on the torus: shortest normal {shortest:.5} at {on_torus} pixels; widest edge {:.2}°, mid-edge length {mid_edge:.5}",
        widest.to_degrees()
    );
    assert!(on_torus > 20, "only {on_torus} torus pixels");
    assert!(shortest <= 1.0 - 0.9 * (1.0 - mid_edge), "shortest {shortest}, mid-edge {mid_edge}");
}

/// The readouts on the close wall (the light 0.35 m in front of it, each triangle about as
/// large) for `mistake`, after checking the GPU equals them; every 6 pixels from (4, 4), so
/// (64, 64), next to the wall's vertex at (0, 1.5), is among them.
fn wall_readouts(mistake: Mistake) -> Vec<([u32; 2], bumpview::probe::ProbeReadout)> {
    let (scene, mut params) = wall_scene();
    params.shading.mistake = mistake;
    println!("{}:", mistake.name());
    gpu_against_probe(&scene, &SceneOptions::default(), &params, SIZE, 6, WALL)
}

/// The largest angle (degrees) between the correct and the mistaken vector `of` a readout,
/// next to a vertex (largest barycentric weight above 0.99) and anywhere.
fn turned(mistake: Mistake, of: fn(&bumpview::chain::ChainValues) -> Vec3) -> (f32, f32) {
    let correct = wall_readouts(Mistake::None);
    let wrong = wall_readouts(mistake);
    let (mut near_vertex, mut anywhere, mut near) = (0.0f32, 0.0f32, 0);
    for ((_, right), (_, r)) in correct.iter().zip(&wrong) {
        let angle = of(&right.chain).angle_between(of(&r.chain)).to_degrees();
        anywhere = anywhere.max(angle);
        if r.point.barycentric.max_element() > 0.99 {
            near_vertex = near_vertex.max(angle);
            near += 1;
        }
    }
    println!("{}: turned up to {anywhere:.2}°, {near_vertex:.3}° at {near} pixels next to vertices", mistake.name());
    assert!(near > 0, "no pixel next to a vertex");
    (near_vertex, anywhere)
}

/// The first light's terms (the close wall's only light).
fn first_light(chain: &bumpview::chain::ChainValues) -> bumpview::chain::LightTerms {
    chain.lights[0].expect("the first light is on")
}

/// The light vector normalised per vertex and interpolated points the right way at the
/// vertices and turns away from the light between them.
#[test]
fn the_light_normalised_per_vertex_turns_between_vertices() {
    let (near_vertex, anywhere) = turned(Mistake::LightPerVertex, |c| first_light(c).direction);
    assert!(near_vertex < 0.3 && anywhere > 3.0, "{near_vertex} {anywhere}");
}

/// The half vector per vertex, interpolated, is right at the vertices and turns between them,
/// so the highlight moves and smears (Cg tutorial 8.1.4).
#[test]
fn the_half_vector_per_vertex_turns_between_vertices() {
    let (near_vertex, anywhere) = turned(Mistake::HalfVectorPerVertex, |c| first_light(c).half);
    assert!(near_vertex < 0.3 && anywhere > 3.0, "{near_vertex} {anywhere}");
}

/// The per-vertex mistakes concern the first light that is on (the shader's
/// `frame.lights[0]`): with a second light, that one stays correct, exactly; with the first
/// light switched off, the second is the first that is on and turns instead. The GPU draws
/// each as the probe.
#[test]
fn the_per_vertex_mistakes_turn_only_the_first_light_that_is_on() {
    let (scene, mut params) = wall_scene();
    let mut second = params.lights[0];
    second.position = bumpview::scene::builtin::WALL_Z * Vec3::Z + Vec3::new(-0.15, 1.4, 0.3);
    second.color = Vec3::new(0.4, 0.5, 0.6);
    params.lights.push(second).unwrap();
    let options = SceneOptions::default();
    let readouts = |params: &FrameParams, mistake| {
        let mut params = *params;
        params.shading.mistake = mistake;
        println!("{}:", mistake.name());
        gpu_against_probe(&scene, &options, &params, SIZE, 6, WALL)
    };
    let largest_turn = |a: &[([u32; 2], bumpview::probe::ProbeReadout)], b: &[([u32; 2], _)], light: usize| {
        let pairs = a.iter().zip(b).map(|((_, r), (_, w)): (_, &([u32; 2], bumpview::probe::ProbeReadout))| {
            r.chain.lights[light].unwrap().direction.angle_between(w.chain.lights[light].unwrap().direction)
        });
        pairs.fold(0.0f32, f32::max).to_degrees()
    };
    let correct = readouts(&params, Mistake::None);
    let wrong = readouts(&params, Mistake::LightPerVertex);
    let (first, other) = (largest_turn(&correct, &wrong, 0), largest_turn(&correct, &wrong, 1));
    println!("both on: the first light turned up to {first:.2}°, the second {other:.2}°");
    assert!(first > 3.0 && other == 0.0, "{first} {other}");
    params.lights[0].enabled = false;
    let correct = readouts(&params, Mistake::LightPerVertex);
    let off = correct.iter().all(|(_, r)| r.chain.lights[0].is_none());
    let right = readouts(&params, Mistake::None);
    let turned = largest_turn(&right, &correct, 1);
    println!("the first light off: the second turned up to {turned:.2}°");
    assert!(off && turned > 3.0, "{off} {turned}");
}

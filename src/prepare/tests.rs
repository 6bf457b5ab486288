//! The prepare stage's own tests: tangents only where drawn, textures only where bound, cone
//! maps only where read, mip chains made ahead as on upload, repairs with notices.

use glam::{Vec2, Vec3};

use super::*;
use crate::frame::BumpSource;
use crate::scene::builtin::teaching_scene;

#[test]
fn the_built_in_scene_gets_tangents_only_where_a_normal_map_is_drawn() {
    let scene = teaching_scene();
    let prepared = PreparedScene::new(&scene, &SceneOptions::default());
    for (instance, prepared_instance) in scene.instances.iter().zip(&prepared.instances) {
        let has_map = scene.materials[instance.material].normal_map.is_some();
        assert_eq!(prepared_instance.bump == BumpKind::TangentSpace, has_map);
        assert_eq!(prepared.meshes[instance.mesh].frames.is_some(), prepared_instance.variant.has_tangents());
    }
    let height = SceneOptions { bump_source: BumpSource::HeightInShader, ..Default::default() };
    let prepared = PreparedScene::new(&scene, &height);
    assert!(prepared.meshes.iter().all(|m| m.frames.is_none()), "height in shader needs no tangents");
    assert_eq!(prepared.tangent_frames_generated, 0);
}

#[test]
fn a_material_without_maps_binds_no_bump_texture_and_the_unused_ones_are_not_used() {
    let mut scene = teaching_scene();
    for material in &mut scene.materials {
        material.normal_map = None;
        material.height_map = None;
    }
    let prepared = PreparedScene::new(&scene, &SceneOptions::default());
    assert!(prepared.instances.iter().all(|i| i.variant == Variant::Plain && i.textures.bump.is_none()));
    let bump_textures: Vec<usize> =
        teaching_scene().materials.iter().filter_map(|m| m.normal_map.as_ref().map(|n| n.texture)).collect();
    assert!(!bump_textures.is_empty());
    assert!(bump_textures.iter().all(|&t| !prepared.uses_texture(t)));
}

#[test]
fn mip_chains_made_ahead_equal_those_made_on_upload() {
    let mut prepared = PreparedScene::new(&teaching_scene(), &SceneOptions::default());
    let on_demand: Vec<_> =
        (0..prepared.scene.textures.len()).map(|i| prepared.mip_chain(i).unwrap().into_owned()).collect();
    prepared.precompute_mip_chains();
    for (index, chain) in on_demand.iter().enumerate() {
        assert_eq!(prepared.mip_chains[index].is_some(), prepared.uses_texture(index));
        assert_eq!(prepared.mip_chain(index).unwrap().as_ref(), chain.as_slice());
    }
    assert!(prepared.mip_chains.iter().any(Option::is_some));
}

#[test]
fn height_maps_carry_cone_maps_only_while_relaxed_cones_are_drawn() {
    let scene = teaching_scene();
    let marched = |options: &SceneOptions| {
        let prepared = PreparedScene::new(&scene, options);
        let index = prepared.instances.iter().find_map(|i| i.textures.height).expect("a marched height map");
        let level0 = prepared.mip_chain(index).unwrap()[0].clone();
        (level0, (*scene.textures[index]).clone())
    };
    let (plain, original) = marched(&SceneOptions { parallax: true, ..Default::default() });
    assert_eq!(plain, original, "no cone map for the other techniques");
    let (packed, _) = marched(&SceneOptions { parallax: true, cone_maps: true, ..Default::default() });
    assert!(packed.rgba.chunks_exact(4).any(|t| t[2] != 0), "the cone ratios in blue");
    let same_heights = packed.rgba.chunks_exact(4).zip(original.rgba.chunks_exact(4));
    assert!(same_heights.clone().all(|(p, o)| p[..2] == o[..2] && p[3] == o[3]));
}

#[test]
fn non_finite_vertex_data_is_repaired_with_a_notice() {
    let mut scene = teaching_scene();
    let mesh = &mut scene.meshes[0];
    mesh.positions[mesh.indices[0] as usize] = Vec3::NAN;
    mesh.normals[1] = Vec3::INFINITY;
    mesh.uvs[2] = Vec2::NAN;
    let triangles = mesh.indices.len() / 3;
    let prepared = PreparedScene::new(&scene, &SceneOptions::default());
    let drawn = &prepared.meshes[0].mesh;
    assert!(drawn.indices.len() / 3 < triangles);
    assert!(drawn.indices.iter().all(|&i| drawn.positions[i as usize].is_finite()));
    assert!(drawn.normals.iter().all(|n| n.is_finite()) && drawn.uvs.iter().all(|uv| uv.is_finite()));
    assert!(prepared.notices.iter().any(|n| n.contains("NaN or infinite data")), "{:?}", prepared.notices);
}

#[test]
fn lean_is_drawn_up_to_its_size_limit_and_toksvig_past_it_with_a_notice() {
    let mut scene = teaching_scene();
    let map = scene.materials[0].normal_map.as_ref().unwrap().texture;
    let lean = SceneOptions { mip_filter: MipFilter::Lean, ..Default::default() };
    let prepared = PreparedScene::new(&scene, &lean);
    assert!(prepared.instances.iter().any(|i| i.mip_filter == MipFilter::Lean));
    assert!(prepared.notices.iter().all(|n| !n.contains("LEAN")));
    // Only the size is read to decide: a header's worth of a 8192² map.
    let huge = TextureImage { width: 8192, height: 8192, rgba: vec![], ..(*scene.textures[map]).clone() };
    scene.textures[map] = huge.into();
    let prepared = PreparedScene::new(&scene, &lean);
    let drawn: Vec<MipFilter> =
        prepared.instances.iter().filter(|i| i.textures.bump == Some(map)).map(|i| i.mip_filter).collect();
    assert!(!drawn.is_empty() && drawn.iter().all(|&f| f == MipFilter::Toksvig), "{drawn:?}");
    let refusals: Vec<&String> = prepared.notices.iter().filter(|n| n.contains("LEAN's moments")).collect();
    assert_eq!(refusals.len(), 1, "one notice per map: {:?}", prepared.notices);
    assert!(refusals[0].contains("8192x8192") && refusals[0].contains("682 MiB"), "{}", refusals[0]);
}

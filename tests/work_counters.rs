//! The core counts its work, so a scene provably gets only what it needs.

mod common;

use bumpview::prepare::Variant;
use bumpview::render::capture::render_image;
use bumpview::render::pipelines::Pass;
use common::*;

#[test]
fn scene_without_normal_maps_generates_no_tangents_and_no_tangent_pipeline() {
    let mut scene = scene();
    for material in &mut scene.materials {
        material.normal_map = None;
    }
    for mesh in &mut scene.meshes {
        mesh.tangents = None;
    }
    let mut renderer = renderer_for(&scene);
    render_image(&mut renderer, [64, 48], &default_params(&scene)).unwrap();
    let counters = renderer.counters();
    assert_eq!(counters.tangent_frames_generated, 0);
    assert_eq!(counters.textures_uploaded, 1, "only the colour texture is used");
    let built = renderer.built_pipelines();
    // Something was drawn, with plain mesh pipelines only.
    assert!(built.iter().any(|k| matches!(k.pass, Pass::Mesh { variant: Variant::Plain, .. })), "{built:?}");
    for key in built {
        assert!(matches!(key.pass, Pass::Mesh { variant: Variant::Plain, .. } | Pass::LightMarker), "{key:?}");
    }
}

#[test]
fn built_in_scene_generates_tangents_only_where_missing_and_caches_pipelines() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    // No built-in mesh supplies tangents: MikkTSpace makes them for all three, once.
    assert!(scene.meshes.iter().all(|m| m.tangents.is_none()));
    let generated: usize = scene.meshes.iter().map(|m| m.positions.len()).sum();
    assert_eq!(renderer.counters().tangent_frames_generated, generated as u64);
    assert_eq!(
        renderer.counters().textures_uploaded,
        2,
        "colour and normal map, once each: no height map without parallax"
    );
    let mut parallax = renderer_for(&scene);
    parallax.set_scene(&scene, bumpview::frame::SceneOptions { parallax: true, ..Default::default() });
    assert_eq!(parallax.counters().textures_uploaded, 2 + 3, "a second upload, with the height map for parallax");

    let params = default_params(&scene);
    render_image(&mut renderer, [64, 48], &params).unwrap();
    let after_first = renderer.counters();
    // Double-sided wall/floor and single-sided torus: two normal-mapped variants.
    assert_eq!(after_first.pipelines_built, 2);
    let mut toggled = params;
    toggled.shading.bump_enabled = false;
    toggled.shading.strength = -2.0;
    toggled.shading.mode = bumpview::frame::ShadingMode::BumpOnly;
    toggled.shading.parallax.technique = bumpview::frame::Parallax::Relief;
    render_image(&mut renderer, [64, 48], &toggled).unwrap();
    let after_second = renderer.counters();
    assert_eq!(
        after_second.pipelines_built, after_first.pipelines_built,
        "bump, strength, lit mode and, without a height map bound for it, the parallax technique build nothing"
    );
    assert_eq!(after_second.textures_uploaded, after_first.textures_uploaded);
    assert_eq!(after_second.frames_drawn, 2);
    toggled.shading.view = bumpview::frame::ViewMode::Tangent;
    render_image(&mut renderer, [64, 48], &toggled).unwrap();
    let after_third = renderer.counters();
    assert_eq!(after_third.pipelines_built, after_first.pipelines_built + 2, "the Tangent view's two variants");
    assert_eq!(after_third.textures_uploaded, after_first.textures_uploaded);
}

/// The view and the shading model pick pipeline variants (WGSL pipeline constants). Going
/// through every view with every shading model builds each variant once: back and forth
/// builds nothing more, and every picture drawn again equals its first drawing pixel for
/// pixel. (That the variants draw what the single shader drew before is held by the tests
/// against the CPU references: shading_reference, debug_views, pbr_reference, modes_and_views.)
#[test]
fn view_and_shading_model_variants_are_built_once() {
    use bumpview::frame::ViewMode;
    use bumpview::names::Named;
    use bumpview::scene::ShadingModel;
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let base = default_params(&scene);
    let models = [None, Some(ShadingModel::BlinnPhong), Some(ShadingModel::MetallicRoughness)];
    let settings: Vec<_> = ViewMode::all()
        .iter()
        .flat_map(|&view| models.map(|model| (view, model)))
        .map(|(view, model)| {
            let mut params = base;
            params.shading.view = view;
            params.shading.shading_override = model;
            params
        })
        .collect();
    let before = renderer.counters().pipelines_built;
    let first: Vec<_> = settings.iter().map(|p| render_image(&mut renderer, [64, 48], p).unwrap()).collect();
    let built = renderer.counters().pipelines_built - before;
    // Two instance kinds (double-sided wall and floor, single-sided torus) times: Lit and
    // Over-tilt in Blinn-Phong (the built-in materials' own, so `None` shares it) and in
    // metallic-roughness, and every other view once (Difference by its own pass).
    let unlit_views = ViewMode::all().iter().filter(|v| !v.is_lit()).count() as u64;
    assert_eq!(built, 2 * (2 * 2 + unlit_views));
    assert_eq!(renderer.built_pipelines().len() as u64, renderer.counters().pipelines_built, "none built twice");
    for (params, image) in settings.iter().zip(&first).rev() {
        assert!(render_image(&mut renderer, [64, 48], params).unwrap() == *image, "{:?}", params.shading);
    }
    assert_eq!(renderer.counters().pipelines_built - before, built, "back and forth builds nothing");
}

/// A mesh that brings tangents but whose material has no normal map keeps its tangents for
/// the T/B views (tangent variant) and generates nothing.
#[test]
fn supplied_tangents_without_normal_map_use_the_tangent_variant() {
    let mut scene = scene();
    for material in &mut scene.materials {
        material.normal_map = None;
    }
    // The torus supplies its analytic frame as if a file carried it.
    let torus = scene.meshes.iter_mut().find(|m| m.name == "torus").unwrap();
    torus.tangents = torus.analytic_tangents.clone();
    let mut renderer = renderer_for(&scene);
    let mut params = default_params(&scene);
    params.shading.view = bumpview::frame::ViewMode::Tangent;
    render_image(&mut renderer, [64, 48], &params).unwrap();
    assert_eq!(renderer.counters().tangent_frames_generated, 0);
    let variants: Vec<_> = renderer
        .built_pipelines()
        .into_iter()
        .filter_map(|k| match k.pass {
            Pass::Mesh { variant, .. } => Some(variant),
            Pass::Difference { .. } | Pass::LightMarker | Pass::Wireframe { .. } | Pass::Glyphs { .. } => None,
        })
        .collect();
    assert!(variants.contains(&Variant::Tangent) && variants.contains(&Variant::Plain), "{variants:?}");
    assert!(!variants.contains(&Variant::NormalMapped));
}

/// The Difference view makes reference frames only when it is first shown, once. With the
/// built-in surfaces' analytic frames removed, the reference is MikkTSpace and its frames are
/// counted: none before the view is shown, one per vertex of each mesh with a tangent stream
/// when it first is, none when it is drawn again. (With analytic frames nothing is generated.)
#[test]
fn difference_view_adds_reference_frames_on_first_use_only() {
    let mut without_analytic = scene();
    without_analytic.meshes.iter_mut().for_each(|m| m.analytic_tangents = None);
    let vertices: u64 = without_analytic.meshes.iter().map(|m| m.positions.len() as u64).sum();
    for (scene, reference_frames) in [(without_analytic, vertices), (scene(), 0)] {
        let mut renderer = renderer_for(&scene);
        let generated = renderer.counters().tangent_frames_generated;
        assert_eq!(generated, vertices, "the drawn frames (MikkTSpace for every mesh)");
        let mut params = default_params(&scene);
        render_image(&mut renderer, [64, 48], &params).unwrap();
        assert!(!renderer.built_pipelines().iter().any(|k| matches!(k.pass, Pass::Difference { .. })));
        assert_eq!(renderer.counters().tangent_frames_generated, generated, "not before the view is shown");
        params.shading.view = bumpview::frame::ViewMode::Difference;
        render_image(&mut renderer, [64, 48], &params).unwrap();
        assert!(renderer.built_pipelines().iter().any(|k| matches!(k.pass, Pass::Difference { .. })));
        assert_eq!(renderer.counters().tangent_frames_generated, generated + reference_frames, "on first use");
        render_image(&mut renderer, [64, 48], &params).unwrap();
        assert_eq!(renderer.counters().tangent_frames_generated, generated + reference_frames, "once");
    }
}

/// Bump from the height map in the shader needs no tangents: none are generated, the height
/// map is uploaded and the normal map is not.
#[test]
fn height_in_shader_needs_no_tangents() {
    use bumpview::frame::{BumpSource, SceneOptions};
    let scene = scene();
    let gpu = bumpview::render::Gpu::headless().unwrap();
    let mut renderer = bumpview::render::Renderer::from_gpu(&gpu);
    renderer.set_scene(&scene, SceneOptions { bump_source: BumpSource::HeightInShader, ..Default::default() });
    render_image(&mut renderer, [64, 48], &default_params(&scene)).unwrap();
    assert_eq!(renderer.counters().tangent_frames_generated, 0);
    assert_eq!(renderer.counters().textures_uploaded, 2, "colour and height");
    assert!(
        renderer
            .built_pipelines()
            .iter()
            .all(|k| matches!(k.pass, Pass::Mesh { variant: Variant::HeightBump, .. } | Pass::LightMarker))
    );
}

/// Glyphs add only a line pipeline (no tangents, no textures); a split view that differs in
/// uniforms uploads nothing more, and one that differs in GPU data uploads the scene once more.
#[test]
fn glyphs_and_uniform_splits_upload_nothing_and_gpu_data_splits_upload_once() {
    use bumpview::state::{Command, SplitDifference, ViewerState};
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let mut state = ViewerState::new(&scene);
    render_image(&mut renderer, [64, 48], &state.frame_params()).unwrap();
    let before = renderer.counters();
    state.apply(Command::SetGlyphs(true));
    render_image(&mut renderer, [64, 48], &state.frame_params()).unwrap();
    let after = renderer.counters();
    assert_eq!(
        (after.tangent_frames_generated, after.textures_uploaded),
        (before.tangent_frames_generated, before.textures_uploaded)
    );
    assert_eq!(after.pipelines_built, before.pipelines_built + 1, "one glyph pipeline");

    state.apply(Command::SetSplit(true));
    for difference in [SplitDifference::Bump, SplitDifference::View, SplitDifference::Strength, SplitDifference::Mode] {
        state.apply(Command::SetSplitDifference(difference));
        renderer.set_split_scene(&scene, state.scene_uploads().split_right);
        let split = state.split_frame().unwrap();
        bumpview::render::capture::render_capture_split(
            &mut renderer,
            &bumpview::render::capture::CaptureOptions::plain([64, 48]),
            &state.frame_params(),
            &split,
        )
        .unwrap();
        let counters = renderer.counters();
        assert_eq!(
            (counters.tangent_frames_generated, counters.textures_uploaded),
            (after.tangent_frames_generated, after.textures_uploaded),
            "{difference:?}"
        );
    }
    state.apply(Command::SetSplitDifference(SplitDifference::Convention));
    let uploads = state.scene_uploads();
    renderer.set_split_scene(&scene, uploads.split_right.clone());
    let split = renderer.counters();
    assert_eq!(split.textures_uploaded, 2 * after.textures_uploaded, "the scene's textures once more");
    renderer.set_split_scene(&scene, None);
    assert_eq!(renderer.counters().textures_uploaded, split.textures_uploaded, "dropping uploads nothing");
}

/// With a height map bound for it, the parallax technique picks pipeline variants (the
/// `PARALLAX` constant): each technique builds the scene's two once, going back builds
/// nothing and draws the same pixels.
#[test]
fn parallax_techniques_are_variants_built_once() {
    use bumpview::frame::{Parallax, SceneOptions};
    use bumpview::names::Named;
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    renderer.set_scene(&scene, SceneOptions { parallax: true, ..Default::default() });
    let base = default_params(&scene);
    let settings: Vec<_> = Parallax::all()
        .iter()
        .map(|&technique| {
            let mut params = base;
            params.shading.parallax.technique = technique;
            params
        })
        .collect();
    let before = renderer.counters().pipelines_built;
    let first: Vec<_> = settings.iter().map(|p| render_image(&mut renderer, [64, 48], p).unwrap()).collect();
    let built = renderer.counters().pipelines_built - before;
    assert_eq!(built, 2 * Parallax::all().len() as u64, "double-sided wall and floor, single-sided torus");
    for (params, image) in settings.iter().zip(&first).rev() {
        assert!(render_image(&mut renderer, [64, 48], params).unwrap() == *image, "{:?}", params.shading.parallax);
    }
    assert_eq!(renderer.counters().pipelines_built - before, built, "back and forth builds nothing");
}

/// Mesh pipelines are specialised to the optional textures and lobes their material has (the
/// `MATERIAL_FEATURES` constant), so a pipeline compiles no sample its material lacks: the
/// built-in bricks have none, and a gloss map given to the wall and floor's material gives
/// their pipeline that one feature while the torus's keeps none, with as many pipelines.
#[test]
fn mesh_pipelines_are_specialised_to_the_materials_features() {
    let features = |scene: &bumpview::scene::Scene| {
        let mut renderer = renderer_for(scene);
        render_image(&mut renderer, [64, 48], &default_params(scene)).unwrap();
        let mut features: Vec<_> = renderer
            .built_pipelines()
            .into_iter()
            .filter_map(|k| match k.pass {
                Pass::Mesh { cull_back_faces, features, .. } => Some((cull_back_faces, features)),
                _ => None,
            })
            .collect();
        features.sort();
        features
    };
    assert_eq!(features(&scene()), [(false, 0), (true, 0)], "wall and floor, torus: nothing optional");
    let mut glossy = scene();
    glossy.materials[0].gloss_texture = glossy.materials[0].base_color_texture;
    assert!(glossy.materials[0].gloss_texture.is_some() && glossy.materials[0].double_sided);
    let glossy_features = features(&glossy);
    assert_eq!(glossy_features.len(), 2);
    assert!(!glossy_features[0].0 && glossy_features[0].1 != 0, "wall and floor: the gloss map");
    assert_eq!(glossy_features[1], (true, 0), "the torus: nothing optional");
}

/// A scene uploaded on another thread (a renderer's [`bumpview::render::Uploader`], as a
/// scene job does) is shown by `install`, a swap: nothing is counted before it is installed,
/// its upload counts once when it is, and installing it again or swapping the halves counts
/// nothing; it draws the same pixels as the renderer's own upload of the same options. Made
/// with its reference frames, the Difference view generates none on the UI thread.
#[test]
fn an_upload_made_on_another_thread_installs_as_a_swap_counted_once() {
    use std::sync::Arc;

    use bumpview::frame::{SceneOptions, ViewMode};
    use bumpview::prepare::PreparedScene;
    use bumpview::render::{ReferenceFrames, SceneUpload, Uploader};
    let upload_on_a_thread = |uploader: Uploader, scene: &bumpview::scene::Scene, reference| -> SceneUpload {
        let prepared = Arc::new(PreparedScene::new(scene, &SceneOptions::default()));
        std::thread::spawn(move || uploader.upload(prepared, reference)).join().unwrap()
    };
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let params = default_params(&scene);
    let expected = render_image(&mut renderer, [64, 48], &params).unwrap();
    let first = renderer.held(false).unwrap();
    let before = renderer.counters();
    let upload = upload_on_a_thread(renderer.uploader(), &scene, ReferenceFrames::OnFirstUse);
    assert_eq!(renderer.counters(), before, "nothing counted before it is installed");
    assert_eq!(upload.prepared().options, first.prepared().options);

    renderer.install(first.clone(), Some(upload.clone()));
    let installed = renderer.counters();
    assert_eq!(installed.scenes_uploaded, before.scenes_uploaded + 1);
    assert_eq!(installed.textures_uploaded, 2 * before.textures_uploaded, "colour and normal map once more");
    let vertices: u64 = scene.meshes.iter().map(|m| m.positions.len() as u64).sum();
    assert_eq!(installed.tangent_frames_generated, before.tangent_frames_generated + vertices);
    assert_eq!(renderer.held(true), Some(upload.clone()));
    renderer.install(upload.clone(), Some(first));
    renderer.install(upload.clone(), None);
    assert_eq!(renderer.counters(), installed, "held uploads are not counted again");
    assert_eq!(renderer.held(false), Some(upload));
    assert!(render_image(&mut renderer, [64, 48], &params).unwrap() == expected, "draws as the renderer's own");

    let mut without_analytic = scene.clone();
    without_analytic.meshes.iter_mut().for_each(|m| m.analytic_tangents = None);
    let upload = upload_on_a_thread(renderer.uploader(), &without_analytic, ReferenceFrames::WithUpload);
    let before = renderer.counters();
    renderer.install(upload, None);
    assert_eq!(
        renderer.counters().tangent_frames_generated,
        before.tangent_frames_generated + 2 * vertices,
        "the drawn frames and the reference frames, made on the thread"
    );
    let mut difference = params;
    difference.shading.view = ViewMode::Difference;
    let counted = renderer.counters().tangent_frames_generated;
    render_image(&mut renderer, [64, 48], &difference).unwrap();
    assert_eq!(renderer.counters().tangent_frames_generated, counted, "none made when drawn");
}

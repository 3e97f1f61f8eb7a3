//! `.vox` materials: MATL values read for the palette entries voxels use,
//! bad values warned about by material id and key; on the shared
//! MagicaVoxel files, the ray counts each file's plan implies, and byte
//! identity across backends, thread counts and crops with materials on.
//! Tests that need `../shared/scenes/vox/` skip with a notice without it.
#![cfg(feature = "vox")]

use std::path::PathBuf;

use dot_vox::{Color, DotVoxData, Material as VoxMaterial, Model, Size, Voxel};
mod common;

use common::frames::scalar;
use voxtrace::glam::Vec3;
use voxtrace::{
    render, Camera, CameraSettings, DenseScene, EffectPlan, Framebuffer, Look, MaterialKind,
    OctreeScene, RayStats, Rect, RenderOptions, Scene, SceneMaterials, Target, VoxModel,
    WithMaterials,
};

/// A file with one 4x1x1 model of palette indices 1..=4 and `materials`.
fn file(materials: Vec<VoxMaterial>) -> Vec<u8> {
    let data = DotVoxData {
        version: 150,
        index_map: Vec::new(),
        models: vec![Model {
            size: Size { x: 4, y: 1, z: 1 },
            voxels: (0..4u8)
                .map(|x| Voxel {
                    x,
                    y: 0,
                    z: 0,
                    i: x,
                })
                .collect(),
        }],
        palette: (0..256)
            .map(|i| Color {
                r: i as u8,
                g: 100,
                b: 200,
                a: 255,
            })
            .collect(),
        materials,
        scenes: Vec::new(),
        layers: Vec::new(),
    };
    let mut out = Vec::new();
    data.write_vox(&mut out).unwrap();
    out
}

fn matl(id: u32, pairs: &[(&str, &str)]) -> VoxMaterial {
    VoxMaterial {
        id,
        properties: pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect(),
    }
}

#[test]
fn matl_values_become_materials_for_used_entries_only() {
    let model = VoxModel::from_bytes(&file(vec![
        matl(
            1,
            &[("_type", "_metal"), ("_metal", "0.8"), ("_rough", "0.2")],
        ),
        matl(
            2,
            &[
                ("_type", "_glass"),
                ("_alpha", "0.9"),
                ("_ior", "0.5"),
                ("_rough", "0.1"),
            ],
        ),
        matl(3, &[("_type", "_emit"), ("_emit", "0.5"), ("_flux", "1")]),
        // No voxel uses entry 9: it stays diffuse and calls for nothing.
        matl(9, &[("_type", "_glass"), ("_alpha", "1")]),
    ]))
    .unwrap();
    assert!(model.warnings().is_empty(), "{:?}", model.warnings());
    let m = model.materials();
    assert_eq!(m.get(1).kind(), MaterialKind::Metal);
    assert_eq!((m.get(1).metalness(), m.get(1).roughness()), (0.8, 0.2));
    assert_eq!(m.get(2).kind(), MaterialKind::Glass);
    // MagicaVoxel's _ior is the index minus one.
    assert_eq!((m.get(2).transparency(), m.get(2).ior()), (0.9, 1.5));
    assert_eq!(m.get(3).kind(), MaterialKind::Emissive);
    assert_eq!(m.get(3).emission(), 1.0); // 0.5 x (1 + 1)
    assert_eq!(m.get(4).kind(), MaterialKind::Diffuse);
    assert_eq!(m.get(9).kind(), MaterialKind::Diffuse);
    assert_eq!(model.emitters().len(), 1);
}

#[test]
fn bad_matl_values_warn_naming_the_material_and_key() {
    let model = VoxModel::from_bytes(&file(vec![
        matl(1, &[("_type", "_metal"), ("_metal", "shiny")]),
        matl(2, &[("_type", "_glass"), ("_trans", "1"), ("_ior", "-0.4")]),
        matl(3, &[("_type", "_emit"), ("_emit", "-2")]),
        matl(4, &[("_type", "_glass")]),
    ]))
    .unwrap();
    let w = model.warnings();
    let has = |needles: &[&str]| {
        w.iter()
            .any(|line| needles.iter().all(|n| line.contains(n)))
    };
    assert!(
        has(&["material 1", "_metal", "'shiny'", "not a number"]),
        "{w:?}"
    );
    assert!(has(&["material 2", "_ior", "-0.4", "below 1"]), "{w:?}");
    assert!(has(&["material 3", "_emit", "-2", "negative"]), "{w:?}");
    assert!(has(&["material 4", "_trans", "missing"]), "{w:?}");
    assert!(w.iter().all(|line| !line.contains('\n')));
    // Each falls back to a usable value: the index of refraction to 1.
    assert_eq!(model.materials().get(2).ior(), 1.0);
    assert_eq!(model.materials().get(3).kind(), MaterialKind::Diffuse);
}

#[test]
fn many_bad_matl_values_list_16_and_count_the_rest() {
    // 200 MATL chunks for the 4 used entries (a file may repeat an id),
    // each with one bad value: one line each would be 200 lines.
    let bad: Vec<VoxMaterial> = (0..200)
        .map(|i| matl(1 + i % 4, &[("_type", "_metal"), ("_metal", "shiny")]))
        .collect();
    let model = VoxModel::from_bytes(&file(bad)).unwrap();
    let w = model.warnings();
    assert_eq!(w.len(), 17, "{w:?}");
    assert!(w[..16].iter().all(|line| line.contains("'shiny'")), "{w:?}");
    assert_eq!(w[16], "... and 184 more MATL warnings");
}

/// `../shared/scenes/vox/<name>`, or `None` with a notice.
fn shared(name: &str) -> Option<VoxModel> {
    let path = PathBuf::from("../shared/scenes/vox").join(name);
    if !path.exists() {
        eprintln!("skipping: {} is absent", path.display());
        return None;
    }
    Some(VoxModel::load(&path).unwrap())
}

/// A small three-quarter view of `model`'s bounds.
fn view(model: &VoxModel, width: u32, height: u32) -> Camera {
    let b = model.bounds();
    let (min, max) = (b.min.as_vec3(), b.max.as_vec3());
    let center = (min + max) * 0.5;
    let reach = (max - min).length();
    Camera::new(CameraSettings {
        width,
        height,
        lookfrom: center + Vec3::new(-0.6, 0.55, -0.8) * reach,
        lookat: center,
        ..CameraSettings::default()
    })
    .unwrap()
}

/// The file's sky as the CLI takes it.
fn options_of(model: &VoxModel) -> RenderOptions {
    let mut options = RenderOptions::default();
    options.lighting.sky = model.settings().sky;
    options
}

fn with<'a, S: Scene>(scene: S, model: &'a VoxModel) -> WithMaterials<'a, S> {
    WithMaterials::new(scene, model.materials(), model.emitters())
}

fn rays(stats: RayStats) -> (u64, u64, u64) {
    (
        stats.reflection_rays,
        stats.refraction_rays,
        stats.light_rays,
    )
}

#[test]
fn diffuse_files_trace_no_new_rays_and_study_traces_every_kind() {
    let Some(cop) = shared("chr_riotcop.vox") else {
        return;
    };
    let storage = OctreeScene::build(&cop, cop.bounds()).unwrap();
    let scene = with(&storage, &cop);
    let options = options_of(&cop);
    assert_eq!(EffectPlan::of(&scene, &options).look, Look::Shaded);
    let camera = view(&cop, 48, 32);
    let mut out = vec![0u32; 48 * 32];
    assert_eq!(
        rays(
            render(
                &scene,
                &camera,
                &options,
                Rect::full(&camera),
                Target::Buffer(&mut out),
                None
            )
            .unwrap()
        ),
        (0, 0, 0)
    );

    let Some(study) = shared("study.vox") else {
        return;
    };
    let storage = OctreeScene::build(&study, study.bounds()).unwrap();
    let scene = with(&storage, &study);
    let options = options_of(&study);
    let plan = EffectPlan::of(&scene, &options);
    assert_eq!(plan.look, Look::Path);
    assert!(plan.kinds.glass && plan.kinds.metal && plan.kinds.emissive);
    let camera = view(&study, 96, 54);
    let mut out = vec![0u32; 96 * 54];
    let (reflection, refraction, light) = rays(
        render(
            &scene,
            &camera,
            &options,
            Rect::full(&camera),
            Target::Buffer(&mut out),
            None,
        )
        .unwrap(),
    );
    assert!(
        reflection > 0 && refraction > 0 && light > 0,
        "{reflection} {refraction} {light}"
    );
}

#[test]
fn material_renders_agree_across_backends_threads_and_crops() {
    let pool = voxtrace::rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    for name in ["study.vox", "O1-COLORED.vox", "H1-COLORED.vox"] {
        let Some(model) = shared(name) else { return };
        let options = options_of(&model);
        let camera = view(&model, 64, 40);
        let octree = OctreeScene::build(&model, model.bounds()).unwrap();
        let dense = DenseScene::build(&model, model.bounds()).unwrap();
        let (a, sa) = scalar(&with(&octree, &model), &camera, &options);
        let (b, sb) = scalar(&with(&dense, &model), &camera, &options);
        assert!(a == b, "{name}: backends differ");
        assert_eq!(sa, sb, "{name}: ray counts differ");
        let frame = Framebuffer::new(64, 40).unwrap();
        let scene = with(&octree, &model);
        let st = pool
            .install(|| {
                render(
                    &scene,
                    &camera,
                    &options,
                    Rect::full(&camera),
                    Target::Framebuffer(&frame),
                    None,
                )
            })
            .unwrap();
        assert!(frame.into_pixels() == a, "{name}: 2 threads differ from 1");
        assert_eq!(st, sa);
        let crop = Rect {
            x: 13,
            y: 7,
            width: 29,
            height: 21,
        };
        let mut c = vec![0u32; 29 * 21];
        render(
            &scene,
            &camera,
            &options,
            crop,
            Target::Buffer(&mut c),
            None,
        )
        .unwrap();
        for row in 0..21 {
            let full = &a[(7 + row) * 64 + 13..][..29];
            assert!(
                &c[row * 29..][..29] == full,
                "{name}: crop row {row} differs"
            );
        }
    }
}

#[test]
fn the_light_list_holds_exactly_the_emissive_voxels() {
    let Some(study) = shared("study.vox") else {
        return;
    };
    let table: SceneMaterials<'_> = SceneMaterials {
        table: study.materials(),
        emitters: study.emitters(),
    };
    let b = study.bounds();
    let mut expected: Vec<_> = b
        .iter()
        .filter(|&p| {
            let m = voxtrace::VoxelSource::material(&study, p);
            m != 0 && table.table.get(m).kind() == MaterialKind::Emissive
        })
        .collect();
    expected.sort_by_key(|p| (p.x, p.y, p.z));
    assert!(!expected.is_empty());
    assert_eq!(study.emitters(), &expected[..]);
}

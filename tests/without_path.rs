//! A build without the feature `path` (the firmware's): frames that would
//! be path-traced get the face-shaded look, every material shaded as
//! diffuse, and the effect plan says so. Run with
//! `cargo test -p voxtrace --no-default-features --features alloc --test without_path`
//! (`.ci/run` does, in its bare-metal step); with `path` on there is
//! nothing to test here.
#![cfg(not(feature = "path"))]

use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    render, render_in_rounds, Camera, CameraSettings, DenseScene, EffectPlan, FnSource, Fog, IAabb,
    Lighting, Look, Material, Materials, Palette, PixelSamples, Rect, RenderOptions, Rounds, Scene,
    Target, WithMaterials,
};

/// The 32x24 camera of these frames.
fn camera() -> Camera {
    Camera::new(CameraSettings {
        width: 32,
        height: 24,
        lookfrom: Vec3::new(6.0, 9.0, 14.0),
        ..CameraSettings::default()
    })
    .unwrap()
}

/// The pixels of `scene`'s frame under `options`.
fn frame<S: Scene + Sync>(scene: &S, options: &RenderOptions) -> Vec<u32> {
    let mut pixels = vec![0; 32 * 24];
    render(
        scene,
        &camera(),
        options,
        Rect::full(&camera()),
        Target::Buffer(&mut pixels),
        None,
    )
    .unwrap();
    pixels
}

#[test]
fn metal_glass_and_emitters_are_shaded_as_diffuse_and_the_plan_says_so() {
    let colors = [
        U8Vec3::splat(200),
        U8Vec3::new(220, 180, 90),
        U8Vec3::new(150, 200, 255),
        U8Vec3::new(255, 230, 180),
    ];
    let source = FnSource::new(Palette::new(&colors), |p: IVec3| {
        if p.y == -1 && p.x.abs() < 10 && p.z.abs() < 10 {
            1
        } else if p.y == 0 && (-4..=4).contains(&p.x) && p.z == 0 {
            (2 + p.x.rem_euclid(3)) as u8
        } else {
            0
        }
    });
    let storage = DenseScene::build(&source, IAabb::centered(16)).unwrap();
    let mut materials = Materials::all_diffuse();
    materials.set(2, Material::metal(1.0, 0.1).unwrap());
    materials.set(3, Material::glass(0.9, 1.5, 0.0).unwrap());
    materials.set(4, Material::emissive(3.0).unwrap());
    let lamps = [
        IVec3::new(-3, 0, 0),
        IVec3::new(0, 0, 0),
        IVec3::new(3, 0, 0),
    ];
    let scene = WithMaterials::new(&storage, &materials, &lamps);

    let asked = RenderOptions {
        samples: 2,
        fog: Some(Fog { distance: 40.0 }),
        ..RenderOptions::default()
    };
    let all_diffuse = RenderOptions {
        lighting: Lighting {
            path_trace: true,
            ..Lighting::DEFAULT
        },
        ..asked
    };
    for (scene_materials, options) in [(scene.materials(), asked), (None, all_diffuse)] {
        let plan = EffectPlan::new(&options, scene_materials);
        assert_eq!(plan.look, Look::Shaded);
        assert_eq!(plan.lights, 0);
        let said = plan.to_string();
        assert!(
            said.ends_with("no path tracer (feature path): shaded as diffuse"),
            "{said}"
        );
    }
    // The pixels of the same voxels with no materials at all.
    let shaded = frame(&storage, &asked);
    assert!(frame(&scene, &asked) == shaded);
    assert!(frame(&storage, &all_diffuse) == shaded);

    // A render in rounds is the one pass: one round, every pixel done,
    // and the predicate never asked.
    let plan = EffectPlan::new(&all_diffuse, None);
    assert_eq!(Rounds::of(&plan).most, 1);
    let mut out = vec![0; 32 * 24];
    let mut state = vec![PixelSamples::default(); 32 * 24];
    let done = render_in_rounds(
        &scene,
        &camera(),
        &all_diffuse,
        Rect::full(&camera()),
        Target::Buffer(&mut out),
        &mut state,
        None,
        |_| panic!("asked after the only round"),
    )
    .unwrap();
    assert!(done.complete && done.rounds == 1, "{done:?}");
    assert!(out == shaded && state.iter().all(PixelSamples::is_done));
}

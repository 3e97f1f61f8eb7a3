//! Physics of the path tracer on scenes built here: glass tints what is
//! behind it, a mirror shows what geometry puts in it, an emitter's pixel
//! is its emission and it lights what it sees (not what is occluded), and
//! a white floor under a uniform sky returns exactly sky x albedo. Also:
//! what the effect plan picks, and that all-diffuse scenes keep the
//! face-shaded kernels byte for byte.

mod common;

use common::frames::scalar;
use common::sources::clutter;
use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    render, unpack, Bounces, Camera, CameraSettings, DenseScene, EffectPlan, FnSource, IAabb,
    Lighting, Look, Material, Materials, OctreeScene, Palette, Rect, RenderOptions, Scene, Target,
    VoxelGenerator, WithMaterials,
};

/// Materials of the test scenes: 1 wall/floor, 2 the special voxel, 3 an
/// occluder.
fn palette(colors: &[U8Vec3]) -> Palette {
    Palette::new(colors)
}

/// Path-traced light: a uniform sky of radiance `sky`, no sun, `diffuse`
/// diffuse bounces, `samples` per pixel.
fn lit(sky: f32, diffuse: u8, samples: u16) -> RenderOptions {
    RenderOptions {
        sun: None,
        samples,
        lighting: Lighting {
            sky: Some(Vec3::splat(sky)),
            bounces: Bounces {
                diffuse,
                specular: 5,
            },
            path_trace: true,
            ..Lighting::DEFAULT
        },
        ..RenderOptions::default()
    }
}

fn camera(from: Vec3, at: Vec3, size: u32, fov: f32) -> Camera {
    Camera::new(CameraSettings {
        width: size,
        height: size,
        vertical_fov: fov,
        lookfrom: from,
        lookat: at,
        ..CameraSettings::default()
    })
    .unwrap()
}

/// Renders and unpacks to RGB rows.
fn frame<S: Scene + Sync>(scene: &S, camera: &Camera, options: &RenderOptions) -> Vec<[u8; 3]> {
    let (out, _) = scalar(scene, camera, options);
    out.iter()
        .map(|&p| {
            let [r, g, b, _] = unpack(p);
            [r, g, b]
        })
        .collect()
}

/// The pixel whose ray points most nearly at `point`.
fn pixel_toward(camera: &Camera, point: Vec3) -> (u32, u32) {
    let want = (point - camera.position()).normalize();
    let mut best = (f32::MIN, (0, 0));
    for y in 0..camera.height() {
        for x in 0..camera.width() {
            let d = camera.get_ray(x, y).dir().dot(want);
            if d > best.0 {
                best = (d, (x, y));
            }
        }
    }
    best.1
}

/// The mean of the 3x3 pixels around `(x, y)`.
fn mean_around(pixels: &[[u8; 3]], width: u32, (x, y): (u32, u32)) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for dy in -1i32..=1 {
        for dx in -1i32..=1 {
            let i = (y as i32 + dy) as usize * width as usize + (x as i32 + dx) as usize;
            let [r, g, b] = pixels[i];
            sum += Vec3::new(r as f32, g as f32, b as f32);
        }
    }
    sum / 9.0
}

#[test]
fn a_glass_slab_before_a_red_wall_shows_the_wall_tinted_by_the_glass() {
    let tint = U8Vec3::new(120, 200, 255);
    let colors = [U8Vec3::new(220, 60, 60), tint, U8Vec3::splat(255)];
    let wall = |p: IVec3| p.z == -10 && p.x.abs() < 24 && p.y.abs() < 24;
    let slab = |p: IVec3| (10..12).contains(&p.z) && p.x.abs() < 3 && p.y.abs() < 3;
    // The slab in the glass's tint (2) or in clear white glass (3).
    let scene = move |glass: u8| {
        FnSource::new(palette(&colors), move |p| {
            if wall(p) {
                1
            } else if slab(p) {
                glass
            } else {
                0
            }
        })
    };
    let bounds = IAabb::centered(32);
    let mut materials = Materials::all_diffuse();
    materials.set(2, Material::glass(1.0, 1.5, 0.0).unwrap());
    materials.set(3, Material::glass(1.0, 1.5, 0.0).unwrap());
    let cam = camera(Vec3::new(0.0, 0.0, 30.0), Vec3::ZERO, 33, 8.0);
    let options = lit(1.0, 1, 64);
    let look = |glass: u8| {
        let storage = OctreeScene::build(&scene(glass), bounds).unwrap();
        let pixels = frame(
            &WithMaterials::new(&storage, &materials, &[]),
            &cam,
            &options,
        );
        mean_around(&pixels, 33, (16, 16))
    };
    let (wall_alone, tinted, clear) = (look(0), look(2), look(3));
    // Red through the glass: the wall (220, 60, 60) times the tint
    // (120, 200, 255) / 255 is (104, 47, 60), and the sky reflected adds
    // about 20 to each channel, so red leads blue by about 1.5 at most.
    assert!(
        tinted.x > 1.3 * tinted.y && tinted.x > 1.3 * tinted.z,
        "{tinted}"
    );
    // The clear pane reflects some sky and passes the rest untinted; the
    // tinted one differs from it only in the light it passes, which is the
    // clear pane's times the tint: clear - tinted = wall x T x (1 - tint),
    // with T about 0.92 (Fresnel at normal incidence, two faces).
    // Clear glass: the wall x T plus the sky reflected (about 0.077 of it).
    let through_clear = wall_alone * 0.923 + Vec3::splat(0.077 * 255.0);
    assert!(
        (clear - through_clear).abs().max_element() < 8.0,
        "{clear} against {through_clear}"
    );
    let lost = (clear - tinted) / wall_alone;
    let expected = (Vec3::ONE - tint.as_vec3() / 255.0) * 0.92;
    for c in 0..3 {
        assert!(
            (lost[c] - expected[c]).abs() < 0.06,
            "channel {c}: lost {lost}, expected {expected}"
        );
    }
}

#[test]
fn a_mirror_shows_the_green_voxel_where_its_reflection_is() {
    let colors = [U8Vec3::splat(255), U8Vec3::new(30, 220, 40)];
    let source = FnSource::new(palette(&colors), |p: IVec3| {
        if p.y == -1 && p.x.abs() < 20 && p.z.abs() < 20 {
            1
        } else if p == IVec3::new(0, 3, 0) {
            2
        } else {
            0
        }
    });
    let mut materials = Materials::all_diffuse();
    materials.set(1, Material::metal(1.0, 0.0).unwrap());
    let storage = DenseScene::build(&source, IAabb::centered(24)).unwrap();
    let scene = WithMaterials::new(&storage, &materials, &[]);
    let cam = camera(
        Vec3::new(0.5, 4.0, 14.0),
        Vec3::new(0.5, 0.0, 0.5),
        96,
        40.0,
    );
    let pixels = frame(&scene, &cam, &lit(1.0, 1, 16));
    // The voxel's image in the mirror plane y = 0: its center (0.5, 3.5,
    // 0.5) mirrored to y = -3.5.
    let image = pixel_toward(&cam, Vec3::new(0.5, -3.5, 0.5));
    let direct = pixel_toward(&cam, Vec3::new(0.5, 3.5, 0.5));
    let empty = pixel_toward(&cam, Vec3::new(6.5, -3.5, 0.5));
    let green = |c: Vec3| c.y > c.x + 80.0 && c.y > c.z + 80.0;
    let at_image = mean_around(&pixels, 96, image);
    assert!(green(at_image), "mirror image {at_image}");
    assert!(green(mean_around(&pixels, 96, direct)));
    // Elsewhere the mirror shows the white sky.
    let at_empty = mean_around(&pixels, 96, empty);
    assert!(
        at_empty.min_element() > 240.0,
        "mirror of the sky {at_empty}"
    );
}

#[test]
fn an_emitter_shows_its_emission_and_lights_only_what_it_sees() {
    let colors = [
        U8Vec3::splat(255),
        U8Vec3::new(255, 200, 100),
        U8Vec3::splat(128),
    ];
    let floor = |p: IVec3| p.y == -1 && p.x.abs() < 16 && p.z.abs() < 16;
    let lamp = IVec3::ZERO;
    let occluder = IVec3::new(-2, 0, 0);
    let at = move |p: IVec3, occluded: bool| {
        if floor(p) {
            1
        } else if p == lamp {
            2
        } else if occluded && p == occluder {
            3
        } else {
            0
        }
    };
    let open = FnSource::new(palette(&colors), move |p| at(p, false));
    let blocked = FnSource::new(palette(&colors), move |p| at(p, true));
    // Emission 1 for the lamp's own pixel, 40 to light the floor well.
    let mut materials = Materials::all_diffuse();
    materials.set(2, Material::emissive(1.0).unwrap());
    let mut bright = Materials::all_diffuse();
    bright.set(2, Material::emissive(40.0).unwrap());
    let lights = [lamp];
    // Darkness but for the lamp: a black sky, no sun, direct light only.
    let options = lit(0.0, 0, 64);
    let cam = camera(
        Vec3::new(0.5, 14.0, 9.0),
        Vec3::new(0.5, 0.0, 0.5),
        96,
        45.0,
    );
    let bounds = IAabb::centered(20);
    let open_storage = OctreeScene::build(&open, bounds).unwrap();
    let lamp_frame = frame(
        &WithMaterials::new(&open_storage, &materials, &lights),
        &cam,
        &options,
    );
    let open_frame = frame(
        &WithMaterials::new(&open_storage, &bright, &lights),
        &cam,
        &options,
    );
    let blocked_storage = OctreeScene::build(&blocked, bounds).unwrap();
    let blocked_frame = frame(
        &WithMaterials::new(&blocked_storage, &bright, &lights),
        &cam,
        &options,
    );
    // The lamp's own pixel is exactly its radiance: color x emission 1.
    let (x, y) = pixel_toward(&cam, Vec3::new(0.5, 1.0, 0.5));
    assert_eq!(lamp_frame[(y * 96 + x) as usize], [255, 200, 100]);
    // A floor voxel behind the occluder, seen from above.
    let behind = pixel_toward(&cam, Vec3::new(-2.5, 0.0, 0.5));
    let lit_floor = mean_around(&open_frame, 96, behind);
    let dark_floor = mean_around(&blocked_frame, 96, behind);
    assert!(lit_floor.x > 20.0, "lit floor {lit_floor}");
    assert!(
        dark_floor.x < 0.25 * lit_floor.x,
        "occluded {dark_floor} vs {lit_floor}"
    );
    // Lit in the lamp's color: more red than blue.
    assert!(lit_floor.x > lit_floor.z + 5.0);
}

#[test]
fn a_white_floor_under_a_uniform_sky_returns_sky_times_albedo() {
    // Energy is neither created nor lost: radiance 0.8 on albedo 200/255
    // gives 0.8 x 200 = 160 on every floor pixel, within 1 %.
    let source = FnSource::new(palette(&[U8Vec3::splat(200)]), |p: IVec3| {
        u8::from(p.y == -1 && p.x.abs() < 30 && p.z.abs() < 30)
    });
    let cam = camera(
        Vec3::new(0.0, 6.0, 0.0),
        Vec3::new(0.0, 0.0, 0.01),
        48,
        60.0,
    );
    for spp in [1, 16] {
        let storage = OctreeScene::build(&source, IAabb::centered(32)).unwrap();
        let pixels = frame(&storage, &cam, &lit(0.8, 2, spp));
        for p in pixels {
            for c in p {
                assert!((f32::from(c) - 160.0).abs() <= 1.6, "pixel {p:?} spp {spp}");
            }
        }
    }
}

#[test]
fn all_diffuse_scenes_keep_the_face_shaded_kernels_byte_for_byte() {
    let terrain = VoxelGenerator::new(3);
    let storage = OctreeScene::build(&terrain, IAabb::centered(24)).unwrap();
    let cam = camera(Vec3::splat(20.0), Vec3::ZERO, 40, 60.0);
    let diffuse = Materials::all_diffuse();
    let wrapped = WithMaterials::new(&storage, &diffuse, &[]);
    for options in [
        RenderOptions::default(),
        RenderOptions {
            shadows: true,
            samples: 2,
            ..RenderOptions::default()
        },
    ] {
        assert_eq!(EffectPlan::of(&wrapped, &options).look, Look::Shaded);
        assert_eq!(
            frame(&wrapped, &cam, &options),
            frame(&storage, &cam, &options)
        );
        let mut out = vec![0u32; 1600];
        let stats = render(
            &storage,
            &cam,
            &options,
            Rect::full(&cam),
            Target::Buffer(&mut out),
            None,
        )
        .unwrap();
        assert_eq!(
            (
                stats.reflection_rays,
                stats.refraction_rays,
                stats.light_rays
            ),
            (0, 0, 0)
        );
    }
}

#[test]
fn the_plan_names_what_the_materials_call_for() {
    let mut materials = Materials::all_diffuse();
    let plan = |m: &Materials| {
        EffectPlan::new(
            &RenderOptions::default(),
            Some(voxtrace::SceneMaterials {
                table: m,
                emitters: &[IVec3::ZERO],
            }),
        )
    };
    assert_eq!(plan(&materials).to_string(), "sun");
    materials.set(7, Material::glass(0.9, 1.4, 0.1).unwrap());
    let p = plan(&materials);
    assert_eq!(p.look, Look::Path);
    assert_eq!(
        p.to_string(),
        "sun, sky(gradient), diffuse(2 bounces), glass(5 bounces)"
    );
    materials.set(9, Material::emissive(2.0).unwrap());
    materials.set(10, Material::metal(0.5, 0.3).unwrap());
    assert_eq!(
        plan(&materials).to_string(),
        "sun, sky(gradient), diffuse(2 bounces), metal(5 bounces), glass(5 bounces), emission(1 lights)"
    );
    // A metal without metalness is diffuse, and calls for nothing.
    let mut dull = Materials::all_diffuse();
    dull.set(4, Material::metal(0.0, 0.5).unwrap());
    assert_eq!(plan(&dull).look, Look::Shaded);
}

#[test]
fn materials_refuse_out_of_range_parameters() {
    assert!(Material::glass(1.0, 0.9, 0.0).is_err());
    assert!(Material::glass(1.1, 1.5, 0.0).is_err());
    assert!(Material::glass(1.0, f32::NAN, 0.0).is_err());
    assert!(Material::metal(0.5, -0.1).is_err());
    assert!(Material::emissive(-1.0).is_err());
    assert!(Material::emissive(f32::INFINITY).is_err());
    assert!(Material::emissive(0.0).is_ok());
}

#[test]
fn a_mixed_material_scene_is_the_same_on_both_backends_two_threads_and_a_crop() {
    // Hashed clutter on a floor: glass, rough and mirror metal, lamps and
    // diffuse voxels side by side, so every path kind meets every other.
    let (source, materials) = clutter();
    let bounds = IAabb::centered(12);
    let lights: Vec<IVec3> = bounds
        .iter()
        .filter(|&p| voxtrace::VoxelSource::material(&source, p) == 5)
        .collect();
    let octree = OctreeScene::build(&source, bounds).unwrap();
    let dense = DenseScene::build(&source, bounds).unwrap();
    let cam = camera(
        Vec3::new(16.0, 9.0, 14.0),
        Vec3::new(0.0, -3.0, 0.0),
        48,
        60.0,
    );
    let options = RenderOptions {
        samples: 2,
        ..RenderOptions::default()
    };
    let a = WithMaterials::new(&octree, &materials, &lights);
    let b = WithMaterials::new(&dense, &materials, &lights);
    let pa = frame(&a, &cam, &options);
    assert!(pa == frame(&b, &cam, &options), "backends differ");
    let pool = voxtrace::rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let fb = voxtrace::Framebuffer::new(48, 48).unwrap();
    pool.install(|| {
        voxtrace::render(
            &a,
            &cam,
            &options,
            voxtrace::Rect::full(&cam),
            Target::Framebuffer(&fb),
            None,
        )
    })
    .unwrap();
    let mut single = vec![0u32; 48 * 48];
    let stats = render(
        &a,
        &cam,
        &options,
        Rect::full(&cam),
        Target::Buffer(&mut single),
        None,
    )
    .unwrap();
    assert!(fb.into_pixels() == single, "2 threads differ");
    let crop = voxtrace::Rect {
        x: 5,
        y: 9,
        width: 30,
        height: 17,
    };
    let mut c = vec![0u32; 30 * 17];
    voxtrace::render(&a, &cam, &options, crop, Target::Buffer(&mut c), None).unwrap();
    for row in 0..17 {
        assert!(
            c[row * 30..][..30] == single[(9 + row) * 48 + 5..][..30],
            "crop row {row}"
        );
    }
    assert!(stats.reflection_rays > 0 && stats.refraction_rays > 0 && stats.light_rays > 0);
}

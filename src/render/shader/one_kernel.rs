//! The one kernel per look of builds without `effect-kernels` (every
//! switch on) gives every frame the pixels and ray counts of the kernel
//! compiled for that frame's effects, which the dispatch of a default
//! build picks: the lit look over every set of effects and background, the
//! path tracer over every set of material kinds.

use alloc::vec;
use alloc::vec::Vec;

use glam::{IVec3, U8Vec3, Vec3};

use crate::geom::IAabb;
use crate::material::{Material, Materials};
use crate::render::camera::{Camera, CameraSettings};
use crate::render::options::{Background, Fog, Lighting, Occlusion, RenderOptions};
use crate::render::shader::lit::Lit;
use crate::render::shader::{Job, Kernel, Shader};
use crate::render::stats::{RayStats, Rect};
use crate::render::tiles::render_tiles;
use crate::scene::Scene;
use crate::source::terrain::VoxelGenerator;
use crate::storage::dense::DenseScene;
use crate::storage::octree::OctreeScene;
use crate::voxel::{FnSource, Palette};
use crate::with_materials::WithMaterials;

/// The whole frame with one kernel: its pixels and rays.
struct Frame<'a, S: ?Sized> {
    scene: &'a S,
    camera: &'a Camera,
}

impl<S: Scene + ?Sized> Job for Frame<'_, S> {
    type Output = (Vec<u32>, RayStats);
    fn run<K: Kernel>(self, kernel: &K) -> (Vec<u32>, RayStats) {
        let width = self.camera.width();
        let mut pixels = vec![0; (width * self.camera.height()) as usize];
        let rect = Rect::full(self.camera);
        let (stats, _) = render_tiles(kernel, self.scene, self.camera, rect, None, |x, y, rgba| {
            pixels[(y * width + x) as usize] = rgba;
        });
        (pixels, stats)
    }
}

fn camera(lookfrom: Vec3) -> Camera {
    Camera::new(CameraSettings {
        width: 40,
        height: 30,
        lookfrom,
        ..CameraSettings::default()
    })
    .unwrap()
}

#[test]
fn the_lit_kernel_with_every_switch_on_renders_every_set_of_effects() {
    let scene = OctreeScene::build(&VoxelGenerator::new(3), IAabb::centered(16)).unwrap();
    let camera = camera(Vec3::new(26.0, 30.0, 20.0));
    let backgrounds = [
        Background::Sky,
        Background::Transparent,
        Background::Color(U8Vec3::new(10, 20, 30)),
    ];
    for set in 0..16 {
        for background in backgrounds {
            let options = RenderOptions {
                shadows: set & 1 != 0,
                occlusion: (set & 2 != 0).then_some(Occlusion {
                    rays: 3,
                    distance: 6.0,
                }),
                fog: (set & 4 != 0).then_some(Fog { distance: 50.0 }),
                samples: if set & 8 != 0 { 3 } else { 1 },
                background,
                ..RenderOptions::default()
            };
            let shader = Shader::new(&options, &camera, None);
            let job = || Frame {
                scene: &scene,
                camera: &camera,
            };
            assert!(
                shader.dispatch(job()) == job().run(&Lit::<true, true, true, true, false>(&shader)),
                "effect set {set:04b} on {background:?}"
            );
        }
    }
}

#[cfg(feature = "path")]
#[test]
fn the_path_kernel_with_every_kind_on_renders_every_set_of_kinds() {
    use crate::render::path::Path;

    // A floor (1) under a metal block (2), a glass block (3) and a lamp (4).
    let colors = [
        U8Vec3::splat(200),
        U8Vec3::new(220, 180, 90),
        U8Vec3::new(150, 200, 255),
        U8Vec3::new(255, 230, 180),
    ];
    let source = FnSource::new(Palette::new(&colors), |p: IVec3| {
        let block = |x: i32| (x..x + 3).contains(&p.x) && (0..3).contains(&p.y) && p.z.abs() < 2;
        if p.y == -1 && p.x.abs() < 12 && p.z.abs() < 12 {
            1
        } else if block(-8) {
            2
        } else if block(-2) {
            3
        } else if p == IVec3::new(5, 1, 0) {
            4
        } else {
            0
        }
    });
    let storage = DenseScene::build(&source, IAabb::centered(16)).unwrap();
    let lamps = [IVec3::new(5, 1, 0)];
    let camera = camera(Vec3::new(4.0, 10.0, 16.0));
    let options = RenderOptions {
        samples: 2,
        lighting: Lighting {
            sky: Some(Vec3::splat(0.8)),
            path_trace: true,
            ..Lighting::DEFAULT
        },
        ..RenderOptions::default()
    };
    // A kind the set lacks is still in the table, inert (no metalness,
    // transparency or emission), so the kernel meets it and must act as
    // if it were diffuse; the lamp stays listed either way.
    for set in 0..8 {
        let mut materials = Materials::all_diffuse();
        let on = |bit: u32| if set & bit != 0 { 1.0 } else { 0.0 };
        materials.set(2, Material::metal(on(1), 0.2).unwrap());
        materials.set(3, Material::glass(on(2), 1.5, 0.0).unwrap());
        materials.set(4, Material::emissive(on(4) * 4.0).unwrap());
        let scene = WithMaterials::new(&storage, &materials, &lamps);
        let shader = Shader::new(&options, &camera, scene.materials());
        let setup = shader.path.as_ref().unwrap();
        let job = || Frame {
            scene: &scene,
            camera: &camera,
        };
        let one = job().run(&Path::<true, true, true> {
            camera: &camera,
            setup,
        });
        assert!(shader.dispatch(job()) == one, "kinds {set:03b}");
    }
}

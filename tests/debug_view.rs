//! The seed paper's debug view on tiny scenes: box edges where the walk's
//! boxes meet, voxels black, the sky elsewhere.

use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    render, sky, Camera, CameraSettings, DenseScene, FnSource, IAabb, OctreeScene, Palette, Rect,
    RenderOptions, Scene, Target,
};

fn debug() -> RenderOptions {
    RenderOptions {
        debug: true,
        ..RenderOptions::default()
    }
}

/// One pixel, looking straight down from high above `(x, z)`.
fn pixel_above(scene: &(impl Scene + Sync), x: f32, z: f32) -> (u32, Option<voxtrace::Hit>) {
    let camera = Camera::new(CameraSettings {
        width: 1,
        height: 1,
        vertical_fov: 0.5,
        lookfrom: Vec3::new(x, 40.0, z),
        lookat: Vec3::new(x, -40.0, z),
        cam_up: Vec3::Z,
        ..CameraSettings::default()
    })
    .unwrap();
    let mut pixel = [0];
    render(
        scene,
        &camera,
        &debug(),
        Rect::full(&camera),
        Target::Buffer(&mut pixel),
        None,
    )
    .unwrap();
    (pixel[0], scene.trace(&camera.get_ray(0, 0)))
}

fn rgb(p: u32) -> U8Vec3 {
    let [r, g, b, _] = voxtrace::unpack(p);
    U8Vec3::new(r, g, b)
}

#[test]
fn edges_are_drawn_where_boxes_meet_and_nowhere_else() {
    // An empty 8^3 volume: the octree's root splits into four side-4 cubes
    // under the camera, meeting at x = 0 and z = 0.
    let empty = FnSource::new(Palette::new(&[U8Vec3::ONE]), |_: IVec3| 0);
    let octree = OctreeScene::build(&empty, IAabb::centered(4)).unwrap();
    let down = sky(Vec3::NEG_Y);
    // Over the corner where four cubes meet, and over one cube's edge.
    for (x, z) in [(0.0, 0.0), (0.01, 2.5), (2.5, -0.01), (3.99, 2.5)] {
        let (p, _) = pixel_above(&octree, x, z);
        assert_ne!(rgb(p), down, "no edge at ({x}, {z})");
        assert_ne!(rgb(p), U8Vec3::ZERO);
    }
    // In the middle of a cube's top face: nothing to draw, the sky shows.
    let (p, _) = pixel_above(&octree, 2.5, 1.5);
    assert_eq!(rgb(p), down);
    // Different cubes have different colors: (2.5, -0.01) lies on the edge
    // of the cube at z < 0, (0.01, 2.5) on that of a cube at z > 0.
    let a = rgb(pixel_above(&octree, 2.5, -0.01).0);
    let b = rgb(pixel_above(&octree, -0.01, 2.5).0);
    assert_ne!(a, b);
}

#[test]
fn voxels_are_black_and_the_sky_stays_where_nothing_is_hit() {
    // A floor at y = -4 in a 16^3 volume, seen straight down away from the
    // edges of every box the walk crosses: the floor is black.
    let floor = FnSource::new(Palette::new(&[U8Vec3::new(9, 200, 9)]), |p: IVec3| {
        u8::from(p.y == -4)
    });
    let bounds = IAabb::centered(8);
    let octree = OctreeScene::build(&floor, bounds).unwrap();
    let dense = DenseScene::build(&floor, bounds).unwrap();
    let scenes: [&(dyn Scene + Sync); 2] = [&octree, &dense];
    for scene in scenes {
        // The dense array's boxes are its unit cells: stay off their edges.
        let (p, hit) = pixel_above(&scene, 2.5, 5.5);
        assert!(hit.is_some());
        assert_eq!(rgb(p), U8Vec3::ZERO);
    }
    // Outside the volume nothing is crossed and nothing is hit.
    let (p, hit) = pixel_above(&octree, 20.5, 20.5);
    assert!(hit.is_none());
    assert_eq!(rgb(p), sky(Vec3::NEG_Y));
}

#[test]
fn the_dense_debug_view_draws_unit_cells() {
    let empty = FnSource::new(Palette::new(&[U8Vec3::ONE]), |_: IVec3| 0);
    let dense = DenseScene::build(&empty, IAabb::centered(4)).unwrap();
    // Every integer line is a cell edge; half-way between them is not.
    assert_ne!(rgb(pixel_above(&dense, 1.0, 2.5).0), sky(Vec3::NEG_Y));
    assert_eq!(rgb(pixel_above(&dense, 1.5, 2.5).0), sky(Vec3::NEG_Y));
}

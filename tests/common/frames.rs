//! Cameras and scalar frames the render tests share.

use voxtrace::glam::Vec3;
use voxtrace::{render, Camera, CameraSettings, RayStats, Rect, RenderOptions, Scene, Target};

/// A `width x height` camera at `lookfrom` looking at the origin.
pub fn camera(width: u32, height: u32, lookfrom: Vec3) -> Camera {
    Camera::new(CameraSettings {
        width,
        height,
        lookfrom,
        ..CameraSettings::default()
    })
    .unwrap()
}

/// The scalar render of the whole frame, with its ray counts.
pub fn scalar(
    scene: &(impl Scene + Sync),
    camera: &Camera,
    options: &RenderOptions,
) -> (Vec<u32>, RayStats) {
    let mut pixels = vec![0; (camera.width() * camera.height()) as usize];
    let stats = render(
        scene,
        camera,
        options,
        Rect::full(camera),
        Target::Buffer(&mut pixels),
        None,
    )
    .unwrap();
    (pixels, stats)
}

/// Pixel `(x, y)` of `camera`'s frame rendered alone, a region of one
/// pixel: the reference every larger region, tiling and thread count
/// must agree with, with its rays.
pub fn pixel(
    scene: &(impl Scene + Sync),
    camera: &Camera,
    options: &RenderOptions,
    (x, y): (u32, u32),
) -> (u32, RayStats) {
    let mut out = [0];
    let alone = Rect {
        x,
        y,
        width: 1,
        height: 1,
    };
    let rays = render(
        scene,
        camera,
        options,
        alone,
        Target::Buffer(&mut out),
        None,
    )
    .unwrap();
    (out[0], rays)
}

//! Cameras and scalar frames the render tests share.

use voxtrace::glam::Vec3;
use voxtrace::{render, Camera, CameraSettings, RayStats, RenderOptions, Scene};

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
    scene: &impl Scene,
    camera: &Camera,
    options: &RenderOptions,
) -> (Vec<u32>, RayStats) {
    let mut pixels = vec![0; (camera.width() * camera.height()) as usize];
    let stats = render(scene, camera, options, &mut pixels).unwrap();
    (pixels, stats)
}

//! The automatic `--vox` camera frames the whole model: a solid box the
//! size of the bounds, seen from the framing position, fills part of the
//! image and never touches its border.

use voxtrace::glam::{IVec3, U8Vec3};
use voxtrace::{
    render, Camera, CameraSettings, FnSource, IAabb, OctreeScene, Palette, RenderOptions, FLAT_SKY,
};
use voxtrace_cli::framing;

#[test]
fn framed_boxes_are_in_view_and_clear_of_the_border() {
    let boxes = [
        IAabb::new(IVec3::new(-5, -5, -5), IVec3::new(5, 5, 5)),
        IAabb::new(IVec3::new(0, 0, 0), IVec3::new(120, 16, 40)),
        IAabb::new(IVec3::new(-300, 2, 7), IVec3::new(-290, 90, 12)),
        IAabb::new(IVec3::new(10, -40, -60), IVec3::new(70, -30, 60)),
    ];
    let sky = voxtrace::pack(FLAT_SKY);
    for bounds in boxes {
        for (width, height, fov) in [(64, 36, 60.0), (40, 60, 30.0), (50, 50, 90.0)] {
            let (eye, target) = framing(bounds, fov, width as f32 / height as f32);
            let camera = Camera::new(CameraSettings {
                width,
                height,
                vertical_fov: fov,
                lookfrom: eye,
                lookat: target,
                ..CameraSettings::default()
            })
            .unwrap();
            let solid = FnSource::new(Palette::new(&[U8Vec3::new(200, 10, 10)]), |_: IVec3| 1);
            let scene = OctreeScene::build(&solid, bounds).unwrap();
            let mut pixels = vec![0; (width * height) as usize];
            let stats = render(&scene, &camera, &RenderOptions::flat(), &mut pixels).unwrap();
            let case = format!("{bounds:?} at {width}x{height}, fov {fov}");
            assert!(
                stats.primary_hits > u64::from(width * height) / 50,
                "{case}: too small"
            );
            let w = width as usize;
            for (i, &p) in pixels.iter().enumerate() {
                let (x, y) = (i % w, i / w);
                let border = x == 0 || y == 0 || x == w - 1 || y == height as usize - 1;
                assert!(
                    !border || p == sky,
                    "{case}: the box touches the border at ({x}, {y})"
                );
            }
        }
    }
}

//! The material room: a small path-traced scene the project builds
//! itself, so that what measures path tracing stands without the shared
//! models (`voxtrace-report accuracy`, the denoiser's and the guides'
//! tests). A 21x17x21 box: white floor, ceiling and back wall, a red and a
//! green side wall, open toward +z to a dim uniform sky; a lamp in the
//! ceiling, a mirror on the right wall, a glass pane in front of a yellow
//! block; its materials, and a camera outside its open side.

use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    Camera, CameraSettings, FnSource, IAabb, Lighting, Material, Materials, Palette, RenderOptions,
};

/// Palette index: white, the floor, ceiling and back wall.
pub const WHITE: u8 = 1;
/// Palette index: the left wall.
pub const RED: u8 = 2;
/// Palette index: the right wall.
pub const GREEN: u8 = 3;
/// Palette index: the glass pane.
pub const GLASS: u8 = 4;
/// Palette index: the mirror (metal).
pub const MIRROR: u8 = 5;
/// Palette index: the lamp (emissive).
pub const LAMP: u8 = 6;
/// Palette index: the yellow block behind the glass.
pub const BLOCK: u8 = 7;

/// The palette, index 1 (white) first.
pub const COLORS: [U8Vec3; 7] = [
    U8Vec3::splat(220),
    U8Vec3::new(200, 40, 40),
    U8Vec3::new(40, 180, 60),
    U8Vec3::new(170, 220, 255),
    U8Vec3::splat(230),
    U8Vec3::new(255, 240, 200),
    U8Vec3::new(230, 190, 40),
];

/// The room lies in `IAabb::centered(BOUNDS)`.
pub const BOUNDS: i32 = 12;

/// The room's material at `p` (0: empty).
pub fn room_voxel(p: IVec3) -> u8 {
    let inside = |lo: i32, hi: i32, v: i32| (lo..=hi).contains(&v);
    let (x, y, z) = (p.x, p.y, p.z);
    if !(inside(-10, 10, x) && inside(-8, 8, y) && inside(-10, 10, z)) {
        return 0;
    }
    if y == 8 && inside(-2, 1, x) && inside(-3, 0, z) {
        LAMP
    } else if x == 9 && inside(-6, 4, y) && inside(-8, -2, z) {
        MIRROR
    } else if z == 2 && inside(-7, -1, x) && inside(-7, -1, y) {
        GLASS
    } else if inside(-6, -3, x) && inside(-7, -4, y) && inside(-4, -1, z) {
        BLOCK
    } else if x == -10 {
        RED
    } else if x == 10 {
        GREEN
    } else if y == -8 || y == 8 || z == -10 {
        WHITE
    } else {
        0
    }
}

/// The room as a voxel source.
pub fn source() -> FnSource<fn(IVec3) -> u8> {
    FnSource::new(Palette::new(&COLORS), room_voxel as fn(IVec3) -> u8)
}

/// Glass, a mirror and a lamp; the rest diffuse.
pub fn materials() -> Materials {
    let mut materials = Materials::all_diffuse();
    materials.set(GLASS, Material::glass(0.9, 1.5, 0.0).unwrap());
    materials.set(MIRROR, Material::metal(1.0, 0.05).unwrap());
    materials.set(LAMP, Material::emissive(4.0).unwrap());
    materials
}

/// The lamp's voxels, the emitters next-event estimation samples.
pub fn lamps() -> Vec<IVec3> {
    IAabb::centered(BOUNDS)
        .iter()
        .filter(|&p| room_voxel(p) == LAMP)
        .collect()
}

/// The report's view of the room at `width x height`.
pub fn camera(width: u32, height: u32) -> Camera {
    Camera::new(CameraSettings {
        width,
        height,
        lookfrom: Vec3::new(3.0, 1.0, 30.0),
        lookat: Vec3::new(0.0, -1.0, 0.0),
        vertical_fov: 50.0,
        ..CameraSettings::default()
    })
    .unwrap()
}

/// The report's lighting: no sun, a uniform sky of 0.25, path-traced at
/// `samples` per pixel.
pub fn path_options(samples: u16) -> RenderOptions {
    RenderOptions {
        sun: None,
        samples,
        lighting: Lighting {
            sky: Some(Vec3::splat(0.25)),
            path_trace: true,
            ..Lighting::DEFAULT
        },
        ..RenderOptions::default()
    }
}

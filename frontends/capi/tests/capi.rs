//! The C API called as C calls it: scenes from the terrain, a `.vox`
//! file in memory and a caller's voxels, renders on one thread and many
//! (the same bytes), and every refusal a status with a message.

use std::ptr::{null, null_mut};

use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    render, CameraSettings, DenseScene, FnSource, IAabb, Palette, Rect, RenderOptions, Target,
};
use voxtrace_capi::*;

/// This thread's last error message.
fn last_error() -> String {
    let mut buffer = [0u8; 512];
    let len = unsafe { vt_last_error(buffer.as_mut_ptr().cast(), buffer.len()) };
    String::from_utf8_lossy(&buffer[..len.min(511)]).into_owned()
}

/// The terrain of `size` and `seed` in `backend`.
fn terrain(size: i32, seed: u64, backend: u32) -> *mut VtScene {
    let mut scene = null_mut();
    assert_eq!(
        unsafe { vt_scene_terrain(size, seed, backend, &mut scene) },
        VtStatus::Ok
    );
    assert!(!scene.is_null());
    scene
}

/// The paper's camera for a terrain of size 24 at 64x36.
const VIEW: VtView = VtView {
    width: 64,
    height: 36,
    position: [30.0, 30.0, 30.0],
    lookat: [0.0, 0.0, 0.0],
    fov: 0.0,
    aim: VT_AIM_POSITION,
    orbit: [0.0; 3],
    view: 0,
};

/// `scene` through `view` with `effects` on `threads` threads.
fn frame(
    scene: *const VtScene,
    view: &VtView,
    effects: Option<&VtEffects>,
    threads: u32,
) -> Vec<u8> {
    let mut rgba = vec![0u8; (view.width * view.height * 4) as usize];
    let effects = effects.map_or(null(), |e| e as *const VtEffects);
    let status = unsafe { vt_render(scene, view, effects, threads, rgba.as_mut_ptr(), rgba.len()) };
    assert_eq!(status, VtStatus::Ok, "{}", last_error());
    rgba
}

#[test]
fn every_thread_count_and_backend_gives_the_same_bytes() {
    let effects = VtEffects {
        shadows: 1,
        ao_rays: 4,
        spp: 2,
        ..VtEffects::default()
    };
    let octree = terrain(24, 7, VT_BACKEND_OCTREE);
    let dense = terrain(24, 7, VT_BACKEND_DENSE);
    let one = frame(octree, &VIEW, Some(&effects), 1);
    assert!(
        one.chunks(4).any(|p| p != one[..4].as_ref()),
        "a frame of one color"
    );
    for threads in [0, 2, 3] {
        assert!(
            frame(octree, &VIEW, Some(&effects), threads) == one,
            "{threads} threads"
        );
    }
    assert!(frame(dense, &VIEW, Some(&effects), 1) == one, "dense");
    assert!(
        frame(octree, &VIEW, None, 1) != one,
        "effects changed nothing"
    );
    unsafe {
        vt_scene_free(octree);
        vt_scene_free(dense);
        vt_scene_free(null_mut());
    }
}

#[test]
fn a_callers_voxels_render_as_the_core_renders_them() {
    // An 8x5x6 volume, x fastest: a floor of index 1 and a pillar of 2.
    let (nx, ny, nz) = (8u32, 5u32, 6u32);
    let material = |p: IVec3| -> u8 {
        match (p.x, p.y, p.z) {
            (_, 0, _) => 1,
            (3..=4, _, 2..=3) => 2,
            _ => 0,
        }
    };
    let mut indices = Vec::new();
    for z in 0..nz as i32 {
        for y in 0..ny as i32 {
            for x in 0..nx as i32 {
                indices.push(material(IVec3::new(x, y, z)));
            }
        }
    }
    let mut palette = [0u8; 765];
    palette[..6].copy_from_slice(&[200, 40, 40, 40, 200, 40]);
    let mut scene = null_mut();
    let status = unsafe {
        vt_scene_voxels(
            indices.as_ptr(),
            nx,
            ny,
            nz,
            palette.as_ptr(),
            VT_BACKEND_OCTREE,
            &mut scene,
        )
    };
    assert_eq!(status, VtStatus::Ok, "{}", last_error());
    let view = VtView {
        width: 48,
        height: 32,
        position: [14.0, 11.0, 15.0],
        lookat: [4.0, 1.0, 3.0],
        fov: 40.0,
        aim: VT_AIM_POSITION,
        orbit: [0.0; 3],
        view: 0,
    };
    let got = frame(scene, &view, None, 1);
    unsafe { vt_scene_free(scene) };
    // The same voxels through the core directly.
    let colors = [U8Vec3::new(200, 40, 40), U8Vec3::new(40, 200, 40)];
    let source = FnSource::new(Palette::new(&colors), material);
    let bounds = IAabb::new(IVec3::ZERO, IVec3::new(8, 5, 6));
    let dense = DenseScene::build(&source, bounds).unwrap();
    let settings = CameraSettings {
        width: 48,
        height: 32,
        vertical_fov: 40.0,
        lookfrom: Vec3::new(14.0, 11.0, 15.0),
        lookat: Vec3::new(4.0, 1.0, 3.0),
        ..CameraSettings::default()
    };
    let camera = voxtrace::Camera::new(settings).unwrap();
    let mut pixels = vec![0u32; 48 * 32];
    let region = Rect::full(&camera);
    render(
        &dense,
        &camera,
        &RenderOptions::default(),
        region,
        Target::Buffer(&mut pixels),
        None,
    )
    .unwrap();
    let expected: Vec<u8> = pixels.iter().flat_map(|&p| voxtrace::unpack(p)).collect();
    assert!(got == expected, "the C API's frame is not the core's");
}

#[test]
fn a_null_palette_is_gray_by_index() {
    // One voxel of index 200 filling the view: its lit color is a gray.
    let cells = [200u8; 27];
    let mut scene = null_mut();
    let status = unsafe {
        vt_scene_voxels(
            cells.as_ptr(),
            3,
            3,
            3,
            null(),
            VT_BACKEND_DENSE,
            &mut scene,
        )
    };
    assert_eq!(status, VtStatus::Ok, "{}", last_error());
    let view = VtView {
        width: 8,
        height: 8,
        position: [1.5, 1.5, 9.0],
        lookat: [1.5, 1.5, 1.5],
        fov: 10.0,
        aim: VT_AIM_POSITION,
        orbit: [0.0; 3],
        view: 0,
    };
    let rgba = frame(scene, &view, None, 1);
    unsafe { vt_scene_free(scene) };
    let center = &rgba[(4 * 8 + 4) * 4..][..4];
    assert!(
        center[0] == center[1] && center[1] == center[2] && center[0] > 0,
        "{center:?}"
    );
    assert!(center[0] <= 200, "{center:?}");
}

#[test]
fn a_vox_file_in_memory_renders_and_a_damaged_one_is_refused() {
    let file = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/terrain.vox"
    ))
    .unwrap();
    let mut scene = null_mut();
    let status =
        unsafe { vt_scene_vox(file.as_ptr(), file.len(), 0, VT_BACKEND_OCTREE, &mut scene) };
    assert_eq!(status, VtStatus::Ok, "{}", last_error());
    let view = VtView {
        position: [60.0, 80.0, 60.0],
        lookat: [0.0, 40.0, 0.0],
        ..VIEW
    };
    let rgba = frame(scene, &view, None, 0);
    assert!(rgba.chunks(4).any(|p| p != rgba[..4].as_ref()));
    unsafe { vt_scene_free(scene) };
    for cut in [0, 8, file.len() / 2] {
        let mut scene = null_mut();
        let status = unsafe { vt_scene_vox(file.as_ptr(), cut, 0, VT_BACKEND_OCTREE, &mut scene) };
        assert_eq!(status, VtStatus::BadFile, "cut at {cut}");
        assert!(scene.is_null());
        assert!(!last_error().is_empty());
    }
    let status =
        unsafe { vt_scene_vox(file.as_ptr(), file.len(), 5, VT_BACKEND_OCTREE, &mut scene) };
    assert_eq!(status, VtStatus::BadFile);
    assert!(last_error().contains("frame"), "{}", last_error());
}

#[test]
fn the_default_view_is_the_papers_camera_or_a_models_front() {
    // At size 100 the paper's camera (90, 90, 90) stands in air.
    let scene = terrain(100, 1, VT_BACKEND_OCTREE);
    let mut view = VtView {
        width: 0,
        height: 0,
        position: [0.0; 3],
        lookat: [0.0; 3],
        fov: 0.0,
        aim: VT_AIM_POSITION,
        orbit: [0.0; 3],
        view: 0,
    };
    assert_eq!(
        unsafe { vt_default_view(scene, 64, 36, &mut view) },
        VtStatus::Ok
    );
    let paper = CameraSettings::paper(100);
    assert_eq!(Vec3::from_array(view.position), paper.lookfrom);
    assert_eq!(Vec3::from_array(view.lookat), paper.lookat);
    assert_eq!(
        (view.width, view.height, view.fov),
        (64, 36, paper.vertical_fov)
    );
    assert_eq!(
        unsafe { vt_default_view(scene, 0, 36, &mut view) },
        VtStatus::InvalidArgument
    );
    assert_eq!(
        unsafe { vt_default_view(scene, 64, 36, null_mut()) },
        VtStatus::InvalidArgument
    );
    assert_eq!(
        unsafe { vt_default_view(null(), 64, 36, &mut view) },
        VtStatus::InvalidArgument
    );
    unsafe { vt_scene_free(scene) };
    // A model: from its front half (+z side, yaw 315 to 45), 30 degrees
    // above, through the model lens.
    let file = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../docs/terrain.vox"
    ))
    .unwrap();
    let mut scene = null_mut();
    let status =
        unsafe { vt_scene_vox(file.as_ptr(), file.len(), 0, VT_BACKEND_DENSE, &mut scene) };
    assert_eq!(status, VtStatus::Ok, "{}", last_error());
    assert_eq!(
        unsafe { vt_default_view(scene, 64, 36, &mut view) },
        VtStatus::Ok
    );
    let back = Vec3::from_array(view.position) - Vec3::from_array(view.lookat);
    assert!(back.z > 0.0 && back.z >= back.x.abs() * 0.99, "{back}");
    assert!((back.y / back.length() - 0.5).abs() < 1e-3, "{back}");
    assert_eq!(view.fov, voxtrace_flags::MODEL_FOV);
    assert!(frame(scene, &view, None, 2).chunks(4).any(|p| p[3] == 255));
    unsafe { vt_scene_free(scene) };
}

#[test]
fn every_refusal_is_a_status_and_a_message() {
    let mut scene = null_mut();
    let refused = |status: VtStatus, words: &str| {
        assert_eq!(status, VtStatus::InvalidArgument, "{}", last_error());
        assert!(
            last_error().contains(words),
            "{words:?} not in {:?}",
            last_error()
        );
    };
    refused(
        unsafe { vt_scene_terrain(0, 1, VT_BACKEND_OCTREE, &mut scene) },
        "size 0",
    );
    refused(
        unsafe { vt_scene_terrain(8, 1, VT_BACKEND_OCTREE, null_mut()) },
        "null",
    );
    refused(
        unsafe { vt_scene_vox(null(), 4, 0, VT_BACKEND_OCTREE, &mut scene) },
        "null",
    );
    let cells = [1u8; 8];
    let voxels = |nx, out| unsafe {
        vt_scene_voxels(cells.as_ptr(), nx, 2, 2, null(), VT_BACKEND_DENSE, out)
    };
    refused(voxels(0, &mut scene), "0x2x2");
    refused(voxels(2, null_mut()), "null");
    let scene = terrain(8, 1, VT_BACKEND_OCTREE);
    let mut rgba = vec![0u8; (VIEW.width * VIEW.height * 4) as usize];
    let render = |view: &VtView, effects: *const VtEffects, len: usize, rgba: *mut u8| unsafe {
        vt_render(scene, view, effects, 1, rgba, len)
    };
    refused(
        render(&VIEW, null(), rgba.len() - 1, rgba.as_mut_ptr()),
        "needs 9216",
    );
    refused(render(&VIEW, null(), rgba.len(), null_mut()), "null");
    let nan = VtView {
        position: [f32::NAN, 0.0, 0.0],
        ..VIEW
    };
    assert_eq!(
        render(&nan, null(), rgba.len(), rgba.as_mut_ptr()),
        VtStatus::InvalidArgument
    );
    assert!(!last_error().is_empty());
    let same = VtView {
        position: [0.0; 3],
        ..VIEW
    };
    assert_eq!(
        render(&same, null(), rgba.len(), rgba.as_mut_ptr()),
        VtStatus::InvalidArgument
    );
    let bad_aim = VtView { aim: 5, ..VIEW };
    refused(
        render(&bad_aim, null(), rgba.len(), rgba.as_mut_ptr()),
        "aim 5",
    );
    let bad_view = VtView {
        aim: VT_AIM_VIEW,
        view: 9,
        ..VIEW
    };
    refused(
        render(&bad_view, null(), rgba.len(), rgba.as_mut_ptr()),
        "view 9",
    );
    let bad_quality = VtEffects {
        quality: 9,
        ..VtEffects::default()
    };
    refused(
        render(&VIEW, &bad_quality, rgba.len(), rgba.as_mut_ptr()),
        "quality 9",
    );
    let bad_reach = VtEffects {
        ao_rays: 2,
        ao_distance: -1.0,
        ..VtEffects::default()
    };
    refused(
        render(&VIEW, &bad_reach, rgba.len(), rgba.as_mut_ptr()),
        "ao_distance",
    );
    let status = unsafe { vt_render(null(), &VIEW, null(), 1, rgba.as_mut_ptr(), rgba.len()) };
    refused(status, "null");
    let status = unsafe {
        vt_render(
            scene,
            &VIEW,
            null(),
            VT_MAX_THREADS + 1,
            rgba.as_mut_ptr(),
            rgba.len(),
        )
    };
    refused(status, "at most 256");
    let mut other = null_mut();
    refused(
        unsafe { vt_scene_terrain(8, 1, 7, &mut other) },
        "backend 7",
    );
    assert!(other.is_null());
    // The message is cut to the buffer, NUL-terminated, its length whole.
    let mut small = [0xffu8; 4];
    let len = unsafe { vt_last_error(small.as_mut_ptr().cast(), small.len()) };
    assert!(len > 4);
    assert_eq!(small[3], 0);
    assert_eq!(unsafe { vt_last_error(null_mut(), 0) }, len);
    unsafe { vt_scene_free(scene) };
}

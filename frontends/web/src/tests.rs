//! The module's calls against the library: the frame is the core's render
//! of the camera the message names, on both backends, for the terrain and
//! for the shipped sample model; views, zoom and effects change what they
//! should; bad input is an error code.

use std::sync::Mutex;

use voxtrace::glam::Vec3;
use voxtrace::{
    CameraSettings, IAabb, OctreeScene, Projection, ViewPreset, VoxModel, VoxelGenerator,
    WithMaterials,
};

use super::*;

/// The module has one state: its tests take turns.
static SERIAL: Mutex<()> = Mutex::new(());

/// The sample model the repository ships (written by `--export-vox`).
const SAMPLE: &[u8] = include_bytes!("../../../docs/terrain.vox");

const W: u32 = 48;
const H: u32 = 32;

fn upload(bytes: &[u8]) -> u32 {
    let ptr = vt_upload(bytes.len() as u32);
    assert!(!ptr.is_null());
    // SAFETY: vt_upload returned room for exactly bytes.len() bytes.
    unsafe { std::ptr::copy_nonoverlapping(bytes.as_ptr(), ptr, bytes.len()) };
    vt_load_vox()
}

fn message() -> String {
    state().message.clone()
}

/// Renders and returns the frame and the camera the message names.
fn frame(backend: u32, view: u32, abc: [f32; 3], zoom: f32, effects: u32, ao: u32) -> Vec<u32> {
    let [a, b, c] = abc;
    let code = vt_render(backend, view, a, b, c, zoom, effects, ao, W, H);
    assert_eq!(code, ErrorCode::Ok as u32, "{}", message());
    state().frame.clone()
}

/// The camera of the CLI flags in `flags` (the message's form).
fn parse_camera(flags: &str) -> CameraSettings {
    let words: Vec<&str> = flags.split(' ').collect();
    let value = |flag: &str| {
        let i = words.iter().position(|w| *w == flag)?;
        words.get(i + 1).copied()
    };
    let vec3 = |s: &str| {
        let v: Vec<f32> = s.split(',').map(|n| n.parse().unwrap()).collect();
        Vec3::new(v[0], v[1], v[2])
    };
    CameraSettings {
        width: W,
        height: H,
        lookfrom: vec3(value("--position").unwrap()),
        lookat: vec3(value("--lookat").unwrap()),
        vertical_fov: value("--fov").map_or(voxtrace::DEFAULT_FOV, |f| f.parse().unwrap()),
        projection: match value("--ortho-height") {
            Some(h) => Projection::Orthographic {
                height: h.parse().unwrap(),
            },
            None => Projection::Perspective,
        },
        ..CameraSettings::default()
    }
}

/// The library's render of `scene` through the camera of `flags`.
fn library<S: Scene + Sync>(scene: &S, flags: &str, options: &RenderOptions) -> Vec<u32> {
    let camera = Camera::new(parse_camera(flags)).unwrap();
    let mut pixels = vec![0; (W * H) as usize];
    render(
        scene,
        &camera,
        options,
        Rect::full(&camera),
        Target::Buffer(&mut pixels),
        None,
    )
    .unwrap();
    pixels
}

#[test]
fn a_positioned_terrain_frame_is_the_library_render() {
    let _turn = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    assert_eq!(vt_terrain(3, 0, 20), 0);
    let pixels = frame(1, 0, [30.0, 40.0, 20.0], 1.0, 0, 0);
    assert_eq!(message(), "--position 30,40,20 --lookat 0,0,0 --fov 60");
    let scene = OctreeScene::build(&VoxelGenerator::new(3), IAabb::centered(20)).unwrap();
    let camera = Camera::new(CameraSettings {
        width: W,
        height: H,
        lookfrom: Vec3::new(30.0, 40.0, 20.0),
        ..CameraSettings::default()
    })
    .unwrap();
    let mut expected = vec![0; (W * H) as usize];
    render(
        &scene,
        &camera,
        &RenderOptions::default(),
        Rect::full(&camera),
        Target::Buffer(&mut expected),
        None,
    )
    .unwrap();
    assert!(pixels == expected, "octree");
    assert_eq!(vt_frame_len(), W * H);
    assert!(
        frame(0, 0, [30.0, 40.0, 20.0], 1.0, 0, 0) == expected,
        "dense"
    );
}

#[test]
fn every_view_zoom_and_effect_of_the_sample_is_the_library_render_of_its_camera() {
    let _turn = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    assert_eq!(upload(SAMPLE), 0, "{}", message());
    let model = VoxModel::from_bytes(SAMPLE).unwrap();
    let octree = OctreeScene::build(&model, model.bounds()).unwrap();
    let scene = WithMaterials::new(&octree, model.materials(), model.emitters());
    // In the default model view (an orbit, framed) every effect changes
    // the picture. (A side view of the sample is a wall its shadows do not
    // reach.)
    let mut cameras = Vec::new();
    // An orbit, every preset, then the CLI's default model view.
    let views = [(1, [30.0, 20.0, 0.0])]
        .into_iter()
        .chain((2..=9).map(|v| (v, [0.0; 3])));
    for (view, abc) in views {
        for zoom in [1.0, 2.5] {
            let mut plain = None;
            for (effects, ao) in [(0, 0), (options::SHADOWS, 0), (options::FOG, 0), (0, 4)] {
                let pixels = frame(1, view, abc, zoom, effects, ao);
                let flags = message();
                let seen_from = parse_camera(&flags);
                let bounds = model.bounds();
                let options =
                    options::render_options(effects, ao as u16, bounds, Some(&model), &seen_from);
                assert!(pixels == library(&scene, &flags, &options), "{flags}");
                assert!(
                    frame(0, view, abc, zoom, effects, ao) == pixels,
                    "dense: {flags}"
                );
                match &plain {
                    None => {
                        // Framed, each view differs from every other;
                        // zoomed in, from its framed self.
                        let framed = cameras.iter().filter(|(v, _)| *v == view);
                        let other = if zoom == 1.0 {
                            &cameras[..]
                        } else {
                            &framed.cloned().collect::<Vec<_>>()[..]
                        };
                        assert!(
                            other.iter().all(|(_, p)| *p != pixels),
                            "{flags} repeats a view"
                        );
                        cameras.push((view, pixels.clone()));
                        plain = Some(pixels);
                    }
                    Some(plain) if view == 1 && zoom == 1.0 => {
                        assert!(plain != &pixels, "{flags}: effects {effects}, ao {ao}");
                    }
                    Some(_) => {}
                }
            }
        }
    }
}

#[test]
fn a_model_opens_on_the_clis_measured_default_view_and_a_drag_starts_there() {
    let _turn = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    assert_eq!(upload(SAMPLE), 0, "{}", message());
    let model = VoxModel::from_bytes(SAMPLE).unwrap();
    let octree = OctreeScene::build(&model, model.bounds()).unwrap();
    let subject = Subject::Model(Box::new(model.clone()));
    let stage = subject.stage();
    // The CLI's measured default (`view.rs`): the open side at MODEL_FOV.
    let lens = voxtrace_flags::CameraFlags {
        fov: voxtrace_flags::MODEL_FOV,
        ..voxtrace_flags::CameraFlags::new(W, H, Aim::Default)
    };
    let orbit = voxtrace_flags::open_side(&octree, &lens, &stage);
    let want = voxtrace_flags::resolve(
        &voxtrace_flags::CameraFlags {
            aim: Aim::Orbit(orbit),
            ..lens
        },
        &stage,
    )
    .unwrap();
    let pixels = frame(1, 9, [0.0; 3], 1.0, 0, 0);
    let scene = WithMaterials::new(&octree, model.materials(), model.emitters());
    let mut expected = vec![0; (W * H) as usize];
    let options = options::render_options(0, 0, model.bounds(), Some(&model), &want);
    render(
        &scene,
        &Camera::new(want).unwrap(),
        &options,
        Rect::full(&Camera::new(want).unwrap()),
        Target::Buffer(&mut expected),
        None,
    )
    .unwrap();
    assert!(pixels == expected, "{}", message());
    assert!(message().ends_with("--fov 30"), "{}", message());
    assert_eq!((vt_orbit_yaw(), vt_orbit_pitch()), (orbit.yaw, orbit.pitch));
    // Orbiting from there keeps the lens: the same orbit is the same frame.
    assert!(frame(1, 1, [orbit.yaw, orbit.pitch, 0.0], 1.0, 0, 0) == expected);
}

#[test]
fn top_and_iso_stand_where_their_presets_say_and_zoom_moves_in() {
    let _turn = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    assert_eq!(upload(SAMPLE), 0);
    let top = ViewPreset::ALL
        .iter()
        .position(|&p| p == ViewPreset::Top)
        .unwrap() as u32
        + 2;
    let iso = ViewPreset::ALL
        .iter()
        .position(|&p| p == ViewPreset::Iso)
        .unwrap() as u32
        + 2;
    frame(1, top, [0.0; 3], 1.0, 0, 0);
    let s = parse_camera(&message());
    let d = s.lookfrom - s.lookat;
    assert!(
        d.y > 0.0 && d.x.abs() < 1e-3 * d.y && d.z.abs() < 1e-3 * d.y,
        "{d}"
    );
    assert_eq!(s.projection, Projection::Perspective);
    frame(1, top, [0.0; 3], 2.0, 0, 0);
    let zoomed = parse_camera(&message());
    assert_eq!(zoomed.lookat, s.lookat);
    let ratio = (zoomed.lookfrom - zoomed.lookat).length() / d.length();
    assert!((ratio - 0.5).abs() < 1e-5, "{ratio}");

    frame(1, iso, [0.0; 3], 1.0, 0, 0);
    let s = parse_camera(&message());
    let d = (s.lookfrom - s.lookat).normalize();
    assert!((d - Vec3::splat(1.0 / 3f32.sqrt())).length() < 1e-5, "{d}");
    let Projection::Orthographic { height } = s.projection else {
        panic!("iso is orthographic");
    };
    frame(1, iso, [0.0; 3], 4.0, 0, 0);
    assert_eq!(
        parse_camera(&message()).projection,
        Projection::Orthographic {
            height: height / 4.0
        }
    );
}

#[test]
fn bad_input_is_an_error_code() {
    let _turn = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    assert_eq!(vt_terrain(3, 0, 0), ErrorCode::BadScene as u32);
    assert_eq!(vt_terrain(3, 0, 257), ErrorCode::BadScene as u32);
    assert_eq!(upload(b"not a vox file"), ErrorCode::BadVox as u32);
    let why = message();
    assert!(!why.is_empty() && !why.starts_with("--position"), "{why}");
    assert_eq!(
        upload(&SAMPLE[..SAMPLE.len() / 2]),
        ErrorCode::BadVox as u32
    );
    assert_eq!(vt_terrain(3, 0, 20), 0);
    let render =
        |backend, view, a, zoom, width| vt_render(backend, view, a, 2.0, 3.0, zoom, 0, 0, width, 8);
    assert_eq!(render(2, 0, 1.0, 1.0, 8), ErrorCode::BadScene as u32);
    assert!(message().contains("backend 2"), "{}", message());
    assert_eq!(render(0, 10, 1.0, 1.0, 8), ErrorCode::BadScene as u32);
    assert_eq!(render(0, 0, 0.0, 1.0, 8), 0);
    // On the target, zero size, a zoom that is not a positive number.
    assert_eq!(
        vt_render(0, 0, 0.0, 0.0, 0.0, 1.0, 0, 0, 8, 8),
        ErrorCode::BadCamera as u32
    );
    assert!(message().contains("coincide"), "{}", message());
    assert_eq!(render(0, 0, 1.0, 1.0, 0), ErrorCode::BadCamera as u32);
    assert!(message().contains("width and height"), "{}", message());
    for zoom in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        assert_eq!(render(0, 2, 1.0, zoom, 8), ErrorCode::BadCamera as u32);
        assert!(message().contains("zoom"), "{}", message());
    }
    assert_eq!(
        vt_render(0, 0, 1.0, 2.0, 3.0, 1.0, 0, 70_000, 8, 8),
        ErrorCode::BadScene as u32
    );
}

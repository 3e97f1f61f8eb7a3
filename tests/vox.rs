//! MagicaVoxel scenes: files this test writes itself (with dot_vox's
//! writer) load with every voxel present in its palette color, placed
//! through the scene graph, into both storages identically; bad files are
//! errors, never panics. Real models from `../shared/scenes/vox/` are used
//! where that folder exists.
#![cfg(feature = "vox")]

use std::collections::BTreeSet;

use dot_vox::{Color, DotVoxData, Model, SceneNode, ShapeModel, Size, Voxel};
use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    render, Camera, CameraSettings, DenseScene, Framer, OctreeScene, Projection, Rect,
    RenderOptions, SplitMix64, Target, VoxModel, VoxelSource,
};

fn palette() -> Vec<Color> {
    (0..256)
        .map(|i| Color {
            r: i as u8,
            g: 255 - i as u8,
            b: (i * 7) as u8,
            a: 255,
        })
        .collect()
}

/// An L-shaped model of `size` 4x3x5 (x, y, z in MagicaVoxel's z-up axes),
/// each voxel with its own palette index.
fn l_model() -> Model {
    let mut voxels = Vec::new();
    for z in 0..5u8 {
        voxels.push(Voxel {
            x: 0,
            y: 0,
            z,
            i: 10 + z,
        });
    }
    for x in 1..4u8 {
        voxels.push(Voxel {
            x,
            y: 0,
            z: 0,
            i: 20 + x,
        });
    }
    voxels.push(Voxel {
        x: 3,
        y: 2,
        z: 0,
        i: 99,
    });
    Model {
        size: Size { x: 4, y: 3, z: 5 },
        voxels,
    }
}

fn attrs(pairs: &[(&str, &str)]) -> dot_vox::Dict {
    pairs
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect()
}

/// Root transform -> group -> one transform + shape per instance.
fn scene(models: Vec<Model>, instances: &[(u32, &str, &str)]) -> DotVoxData {
    let mut scenes = vec![
        SceneNode::Transform {
            attributes: attrs(&[]),
            frames: vec![dot_vox::Frame::new(attrs(&[]))],
            child: 1,
            layer_id: u32::MAX,
        },
        SceneNode::Group {
            attributes: attrs(&[]),
            children: (0..instances.len() as u32).map(|k| 2 + 2 * k).collect(),
        },
    ];
    for (k, &(model, t, r)) in instances.iter().enumerate() {
        let mut frame = vec![("_t", t)];
        if !r.is_empty() {
            frame.push(("_r", r));
        }
        scenes.push(SceneNode::Transform {
            attributes: attrs(&[]),
            frames: vec![dot_vox::Frame::new(attrs(&frame))],
            child: 3 + 2 * k as u32,
            layer_id: 0,
        });
        scenes.push(SceneNode::Shape {
            attributes: attrs(&[]),
            models: vec![ShapeModel {
                model_id: model,
                attributes: attrs(&[]),
            }],
        });
    }
    DotVoxData {
        version: 150,
        index_map: Vec::new(),
        models,
        palette: palette(),
        materials: Vec::new(),
        scenes,
        layers: Vec::new(),
    }
}

fn bytes(data: &DotVoxData) -> Vec<u8> {
    let mut out = Vec::new();
    data.write_vox(&mut out).unwrap();
    out
}

/// Solid positions of `model` in its bounds, with materials.
fn solids(model: &VoxModel) -> Vec<(IVec3, u8)> {
    let b = model.bounds();
    b.iter()
        .filter_map(|p| {
            let m = model.material(p);
            (m != 0).then_some((p, m))
        })
        .collect()
}

#[test]
fn every_voxel_of_the_file_is_present_in_its_color() {
    let data = scene(vec![l_model()], &[(0, "0 0 0", "")]);
    let model = VoxModel::from_bytes(&bytes(&data)).unwrap();
    let found = solids(&model);
    assert_eq!(found.len(), 9);
    assert_eq!(model.voxel_count(), 9);
    let materials: BTreeSet<u8> = found.iter().map(|&(_, m)| m).collect();
    let expected: BTreeSet<u8> = l_model().voxels.iter().map(|v| v.i + 1).collect();
    assert_eq!(materials, expected);
    for (_, m) in found {
        // dot_vox's index i is the file's index minus one: palette[i].
        let c = palette()[usize::from(m - 1)];
        assert_eq!(model.palette().color(m), U8Vec3::new(c.r, c.g, c.b));
    }
    // MagicaVoxel's z is up: the L's 5-voxel leg stands along y here.
    assert_eq!(model.bounds().size(), IVec3::new(4, 5, 3));
}

/// Positions relative to their minimum corner, for comparing shapes.
fn shape(points: impl Iterator<Item = IVec3>) -> BTreeSet<(i32, i32, i32)> {
    let points: Vec<IVec3> = points.collect();
    let lo = points.iter().fold(IVec3::MAX, |a, &p| a.min(p));
    points.iter().map(|&p| (p - lo).into()).collect()
}

#[test]
fn instances_land_where_their_transforms_put_them() {
    // Two copies of the L, 20 voxels apart along MagicaVoxel's x, the second
    // turned a quarter about the vertical axis (_r = 0b0010_0001: x -> -y).
    let data = scene(vec![l_model()], &[(0, "0 0 0", ""), (0, "20 0 0", "33")]);
    let model = VoxModel::from_bytes(&bytes(&data)).unwrap();
    let found = solids(&model);
    assert_eq!(found.len(), 18);
    let (left, right): (Vec<_>, Vec<_>) = found.iter().partition(|(p, _)| p.x < 10);
    assert_eq!((left.len(), right.len()), (9, 9));
    // The second copy is the first turned a quarter about y (voxtrace's up):
    // in y-up axes MagicaVoxel's x -> -y becomes x -> +z.
    let turn = |p: IVec3| IVec3::new(-p.z, p.y, p.x);
    let turned = shape(left.iter().map(|(p, _)| turn(*p)));
    assert_eq!(turned, shape(right.iter().map(|(p, _)| *p)));
    // The same voxels keep their materials through the turn.
    let left_materials: BTreeSet<u8> = left.iter().map(|&(_, m)| m).collect();
    let right_materials: BTreeSet<u8> = right.iter().map(|&(_, m)| m).collect();
    assert_eq!(left_materials, right_materials);
}

#[test]
fn both_storages_build_the_same_scene_from_a_model() {
    let data = scene(
        vec![l_model()],
        &[(0, "0 0 0", ""), (0, "7 3 -2", "33"), (0, "-9 5 4", "70")],
    );
    let model = VoxModel::from_bytes(&bytes(&data)).unwrap();
    let bounds = model.bounds();
    let dense = DenseScene::build(&model, bounds).unwrap();
    let octree = OctreeScene::build(&model, bounds).unwrap();
    for p in bounds.iter() {
        assert_eq!(dense.material(p), model.material(p));
        assert_eq!(octree.material(p), model.material(p));
    }
    let camera = Camera::new(CameraSettings {
        width: 64,
        height: 48,
        lookfrom: Vec3::new(14.0, 12.0, 17.0),
        ..CameraSettings::default()
    })
    .unwrap();
    let mut a = vec![0; 64 * 48];
    let mut b = vec![0; 64 * 48];
    let sa = render(
        &dense,
        &camera,
        &RenderOptions::default(),
        Rect::full(&camera),
        Target::Buffer(&mut a),
        None,
    )
    .unwrap();
    render(
        &octree,
        &camera,
        &RenderOptions::default(),
        Rect::full(&camera),
        Target::Buffer(&mut b),
        None,
    )
    .unwrap();
    assert!(sa.primary_hits > 50, "the camera sees the models");
    assert!(a == b);
}

#[test]
fn bad_files_are_errors_not_panics() {
    let good = bytes(&scene(vec![l_model()], &[(0, "0 0 0", "")]));
    for len in 0..good.len() {
        let _ = VoxModel::from_bytes(&good[..len]); // an error or a smaller scene
    }
    let mut wrong_magic = good.clone();
    wrong_magic[0] = b'X';
    assert!(VoxModel::from_bytes(&wrong_magic).is_err());

    let absurd = Model {
        size: Size {
            x: 100_000,
            y: 1,
            z: 1,
        },
        voxels: vec![Voxel {
            x: 0,
            y: 0,
            z: 0,
            i: 1,
        }],
    };
    let err = VoxModel::from_bytes(&bytes(&scene(vec![absurd], &[(0, "0 0 0", "")])));
    assert!(err.unwrap_err().to_string().contains("100000x1x1"));

    let outside = Model {
        size: Size { x: 2, y: 2, z: 2 },
        voxels: vec![Voxel {
            x: 5,
            y: 0,
            z: 0,
            i: 1,
        }],
    };
    let err = VoxModel::from_bytes(&bytes(&scene(vec![outside], &[(0, "0 0 0", "")])));
    assert!(err.unwrap_err().to_string().contains("outside its size"));

    let mut short_palette = scene(vec![l_model()], &[(0, "0 0 0", "")]);
    short_palette.palette.truncate(16);
    let err = VoxModel::from_bytes(&bytes(&short_palette)).unwrap_err();
    assert!(err.to_string().contains("palette index"), "{err}");

    for (t, r) in [("1 2", ""), ("0 0 0", "3"), ("0 0 99999999", "")] {
        let err = VoxModel::from_bytes(&bytes(&scene(vec![l_model()], &[(0, t, r)])));
        assert!(err.is_err(), "_t {t:?} _r {r:?}");
    }
    let mut missing_model = scene(vec![l_model()], &[(0, "0 0 0", "")]);
    missing_model.scenes[3] = SceneNode::Shape {
        attributes: attrs(&[]),
        models: vec![ShapeModel {
            model_id: 7,
            attributes: attrs(&[]),
        }],
    };
    assert!(VoxModel::from_bytes(&bytes(&missing_model)).is_err());
}

#[test]
fn shared_models_load_into_both_storages_identically() {
    let dir = std::path::Path::new("../shared/scenes/vox");
    if !dir.is_dir() {
        println!("skipped: {} is absent (third-party models)", dir.display());
        return;
    }
    for name in [
        "chr_riotcop.vox",
        "test_multiple_model_scene.vox",
        "H1-COLORED.vox",
    ] {
        let model = VoxModel::load(&dir.join(name)).unwrap();
        let bounds = model.bounds();
        let dense = DenseScene::build(&model, bounds).unwrap();
        let octree = OctreeScene::build(&model, bounds).unwrap();
        let mut count = 0;
        for p in bounds.iter() {
            let m = model.material(p);
            count += usize::from(m != 0);
            assert_eq!(octree.material(p), m, "{name} at {p}");
            assert_eq!(dense.material(p), m, "{name} at {p}");
        }
        assert_eq!(count, model.voxel_count(), "{name}");
        assert!(count > 100, "{name}");
    }
}

#[test]
fn boxes_read_from_chunks_equal_voxel_by_voxel_reads() {
    // Instances far apart (memory follows voxels, not the volume between),
    // plus a cluster, read through every kind of box.
    let data = scene(
        vec![l_model()],
        &[
            (0, "0 0 0", ""),
            (0, "3 1 -2", "33"),
            (0, "4000000 -3000000 100", "70"),
        ],
    );
    let model = VoxModel::from_bytes(&bytes(&data)).unwrap();
    assert_eq!(model.voxel_count(), 27);
    assert!(model.bounds().size().max_element() > 3_000_000);
    let mut rng = SplitMix64::new(7);
    let mut next = |n: i32| rng.below(n as u32) as i32;
    for _ in 0..400 {
        let min = IVec3::new(next(24) - 12, next(24) - 12, next(24) - 12);
        let size = IVec3::new(1 + next(20), 1 + next(20), 1 + next(20));
        let region = voxtrace::IAabb::new(min, min + size);
        let mut out = vec![7u8; region.volume().unwrap()];
        model.fill_box(region, &mut out);
        let expected: Vec<u8> = region.iter().map(|p| model.material(p)).collect();
        assert_eq!(out, expected, "{region:?}");
        if model.classify(region) == voxtrace::Region::Empty {
            assert!(expected.iter().all(|&m| m == 0), "{region:?} called empty");
        }
    }
    // Far from every voxel, the whole space between the instances is empty.
    let gap = voxtrace::IAabb::new(IVec3::new(100, -100, 0), IVec3::new(3_000_000, 100, 50));
    assert_eq!(model.classify(gap), voxtrace::Region::Empty);
}

#[test]
fn row_ends_are_the_ends_of_every_row_of_voxels() {
    let mut rng = SplitMix64::new(11);
    let mut next = |n: u32| rng.below(n);
    for _ in 0..20 {
        // A random cloud, placed twice (rows then cross chunks and
        // negative coordinates).
        let size = 1 + next(30) as u8;
        let voxels = (0..1 + next(300))
            .map(|_| Voxel {
                x: next(u32::from(size)) as u8,
                y: next(u32::from(size)) as u8,
                z: next(u32::from(size)) as u8,
                i: 1 + next(200) as u8,
            })
            .collect();
        let model = Model {
            size: Size {
                x: size.into(),
                y: size.into(),
                z: size.into(),
            },
            voxels,
        };
        let offset = format!("{} -{} 3", next(40), next(40));
        let data = scene(vec![model], &[(0, "-5 -9 -2", ""), (0, &offset, "")]);
        let model = VoxModel::from_bytes(&bytes(&data)).unwrap();
        // Brute force: per row (y, z), the least and the greatest x.
        let mut rows = std::collections::BTreeMap::<(i32, i32), (i32, i32)>::new();
        for p in model.positions() {
            let span = rows.entry((p.y, p.z)).or_insert((p.x, p.x));
            *span = (span.0.min(p.x), span.1.max(p.x));
        }
        let expected: BTreeSet<(i32, i32, i32)> = rows
            .iter()
            .flat_map(|(&(y, z), &(lo, hi))| [(lo, y, z), (hi, y, z)])
            .collect();
        let ends = model.row_ends();
        let found: BTreeSet<(i32, i32, i32)> = ends.iter().map(|&p| p.into()).collect();
        assert_eq!(found, expected);
        assert_eq!(ends.len(), found.len(), "an end listed twice");
        // A camera framed on the row ends is the camera framed on every
        // voxel, bit for bit, from any side and either projection.
        for (toward, projection) in [
            (Vec3::new(1.0, 0.5, 2.0), Projection::Perspective),
            (Vec3::new(-3.0, 1.0, -0.5), Projection::Perspective),
            (
                Vec3::new(0.2, -1.0, 0.7),
                Projection::Orthographic { height: 1.0 },
            ),
        ] {
            let base = CameraSettings {
                width: 320,
                height: 200,
                projection,
                ..CameraSettings::default()
            };
            let framed = |voxels: &mut dyn Iterator<Item = IVec3>| {
                let mut framer = Framer::new(base, toward, 0.9).unwrap();
                for p in voxels {
                    framer.add_box(p.as_vec3(), p.as_vec3() + 1.0);
                }
                framer.settings().map(|s| {
                    let camera = [s.lookfrom, s.lookat].map(|v| v.to_array().map(f32::to_bits));
                    (camera, format!("{:?}", s.projection))
                })
            };
            let from_ends = framed(&mut ends.iter().copied());
            assert!(from_ends.is_some());
            assert_eq!(from_ends, framed(&mut model.positions()));
        }
    }
}

/// `model` with every voxel moved by `(dx, 0, 0)` in a wider size and
/// recolored `+ shift`: a distinct frame of an animation.
fn frame_model(dx: u8, shift: u8) -> Model {
    let mut model = l_model();
    model.size.x += u32::from(dx);
    for v in &mut model.voxels {
        v.x += dx;
        v.i += shift;
    }
    model
}

/// A file holding `models` and no scene graph.
fn without_scene_graph(models: Vec<Model>) -> DotVoxData {
    let mut data = scene(models, &[]);
    data.scenes.clear();
    data
}

/// A model's voxels and bounds: what a render of it depends on.
fn content(model: &VoxModel) -> (voxtrace::IAabb, Vec<(IVec3, u8)>) {
    (model.bounds(), solids(model))
}

#[test]
fn an_animation_without_a_scene_graph_shows_one_frame_at_a_time() {
    let frames = [(0, 0), (2, 30), (1, 60)];
    let model = |k: usize| frame_model(frames[k].0, frames[k].1);
    let file = bytes(&without_scene_graph((0..3).map(model).collect()));
    let alone = |k: usize| {
        let still = bytes(&without_scene_graph(vec![model(k)]));
        content(&VoxModel::from_bytes(&still).unwrap())
    };
    let first = VoxModel::from_bytes(&file).unwrap();
    assert_eq!(first.frames(), 3);
    assert_eq!(content(&first), alone(0), "the default is the first frame");
    for k in 0..3 {
        let frame = VoxModel::from_bytes_frame(&file, k as u32).unwrap();
        assert_eq!(content(&frame), alone(k), "frame {k}");
    }
    assert_ne!(alone(0), alone(1));
    let past = VoxModel::from_bytes_frame(&file, 3)
        .unwrap_err()
        .to_string();
    assert!(
        past.contains("3 animation frames (0 to 2), no frame 3"),
        "{past}"
    );
    // A still file has one frame.
    let still = bytes(&without_scene_graph(vec![model(1)]));
    assert_eq!(VoxModel::from_bytes(&still).unwrap().frames(), 1);
}

#[test]
fn scene_graph_keyframes_pick_each_frames_transform_and_shape() {
    // One instance whose transform moves at frame 2 and whose shape shows
    // model 0, then model 1 from frame 1 (MagicaVoxel's `_f` keyframes).
    let models = || vec![frame_model(0, 0), frame_model(1, 40)];
    let mut data = scene(models(), &[(0, "0 0 0", "")]);
    let SceneNode::Transform { frames, .. } = &mut data.scenes[2] else {
        panic!("the instance's transform");
    };
    *frames = vec![
        dot_vox::Frame::new(attrs(&[("_t", "0 0 0")])),
        dot_vox::Frame::new(attrs(&[("_f", "2"), ("_t", "10 0 -3")])),
    ];
    let SceneNode::Shape { models: shapes, .. } = &mut data.scenes[3] else {
        panic!("the instance's shape");
    };
    shapes.push(ShapeModel {
        model_id: 1,
        attributes: attrs(&[("_f", "1")]),
    });
    let file = bytes(&data);
    let still = |model: u32, t: &str| {
        let one = scene(models(), &[(model, t, "")]);
        content(&VoxModel::from_bytes(&bytes(&one)).unwrap())
    };
    assert_eq!(VoxModel::from_bytes(&file).unwrap().frames(), 3);
    let frame = |k| content(&VoxModel::from_bytes_frame(&file, k).unwrap());
    assert_eq!(
        content(&VoxModel::from_bytes(&file).unwrap()),
        still(0, "0 0 0")
    );
    assert_eq!(frame(0), still(0, "0 0 0"));
    assert_eq!(frame(1), still(1, "0 0 0"));
    assert_eq!(frame(2), still(1, "10 0 -3"));
}

//! Structure-aware fuzzing of the `.vox` scene graph: arbitrary graphs of
//! transforms, groups and shapes (repeated and missing children, loops,
//! deep chains, far translations, bad rotations) over a few small models,
//! serialized to `.vox` bytes by the test suite's own writer. Byte-level
//! fuzzing (`vox.rs`) rarely gets past the chunk parser into the walk; this
//! target starts there.
//!
//! Loading must return a scene or an error, never panic, and stay within
//! libFuzzer's `-rss_limit_mb` (the placement and voxel limits). A loaded
//! scene must agree with an octree built from it, voxel for voxel, when
//! small enough to compare everywhere.
#![no_main]

use libfuzzer_sys::arbitrary::{Arbitrary, Result, Unstructured};
use libfuzzer_sys::fuzz_target;
use voxtrace::{OctreeScene, VoxModel, VoxelSource};

#[allow(dead_code)] // the suite's hostile files are not used here
#[path = "../../frontends/cli/tests/common/vox_bytes.rs"]
mod vox_bytes;

/// A scene graph as `.vox` bytes, with a description for reproduction.
#[derive(Debug)]
struct Graph {
    bytes: Vec<u8>,
}

impl<'a> Arbitrary<'a> for Graph {
    fn arbitrary(u: &mut Unstructured<'a>) -> Result<Self> {
        let mut chunks = Vec::new();
        let models = u.int_in_range(1..=3)?;
        for _ in 0..models {
            let size = [
                u.int_in_range(1..=12)?,
                u.int_in_range(1..=12)?,
                u.int_in_range(1..=12)?,
            ];
            let count = u.int_in_range(0..=24)?;
            let mut voxels = Vec::with_capacity(count);
            for _ in 0..count {
                // Mostly inside the model; sometimes not (an error case).
                let inside = u.ratio(15, 16)?;
                let coord = |u: &mut Unstructured<'a>, side: u32| -> Result<u8> {
                    if inside {
                        Ok(u.int_in_range(0..=side as u8 - 1)?)
                    } else {
                        u.arbitrary()
                    }
                };
                voxels.push([
                    coord(u, size[0])?,
                    coord(u, size[1])?,
                    coord(u, size[2])?,
                    u.int_in_range(1..=255)?,
                ]);
            }
            chunks.extend(vox_bytes::model(size, &voxels));
        }
        let nodes: i32 = u.int_in_range(1..=40)?;
        // Node ids mostly within the graph, sometimes missing ones.
        let id = |u: &mut Unstructured<'a>| -> Result<i32> {
            if u.ratio(31, 32)? {
                u.int_in_range(0..=nodes - 1)
            } else {
                u.arbitrary()
            }
        };
        for node in 0..nodes {
            match u.int_in_range(0..=2)? {
                0 => {
                    let t = if u.ratio(3, 4)? {
                        let c = |u: &mut Unstructured<'a>| -> Result<i32> {
                            if u.ratio(15, 16)? {
                                u.int_in_range(-40..=40)
                            } else {
                                u.arbitrary()
                            }
                        };
                        Some(format!("{} {} {}", c(u)?, c(u)?, c(u)?))
                    } else {
                        None
                    };
                    let child = id(u)?;
                    chunks.push(vox_bytes::transform(node, child, t.as_deref()));
                }
                1 => {
                    let fan = u.int_in_range(0..=12)?;
                    let children = (0..fan).map(|_| id(u)).collect::<Result<Vec<_>>>()?;
                    chunks.push(vox_bytes::group(node, &children));
                }
                _ => {
                    let model = if u.ratio(15, 16)? {
                        u.int_in_range(0..=models as i32 - 1)?
                    } else {
                        u.arbitrary()?
                    };
                    chunks.push(vox_bytes::shape(node, model));
                }
            }
        }
        if u.arbitrary()? {
            chunks.push(vox_bytes::palette());
        }
        Ok(Graph {
            bytes: vox_bytes::file(&chunks),
        })
    }
}

fuzz_target!(|graph: Graph| {
    let Ok(model) = VoxModel::from_bytes(&graph.bytes) else {
        return;
    };
    let bounds = model.bounds();
    assert!(!bounds.is_empty());
    assert_eq!(model.material(bounds.min - 1), 0);
    if bounds.volume().is_ok_and(|v| v <= 1 << 16) {
        let octree = OctreeScene::build(&model, bounds).expect("a small scene builds");
        let solid = bounds.iter().filter(|&p| model.material(p) != 0).count();
        assert_eq!(
            solid,
            model.voxel_count(),
            "voxel_count counts the solid voxels"
        );
        for p in bounds.iter() {
            assert_eq!(octree.material(p), model.material(p), "at {p}");
        }
    }
});

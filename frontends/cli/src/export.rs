//! `--export-vox`: a generated scene written as a MagicaVoxel `.vox` file
//! (through dot_vox), so that a model the project owns can ship with it.
//!
//! Only the surface is written: a voxel whose six neighbours are all solid
//! (inside the volume) can never be the first voxel a ray from an empty
//! cell meets, because every walk steps through faces and so enters a
//! solid region through a voxel with an empty neighbour. Renders of the
//! exported file are therefore the renders of the source, from any camera
//! that does not start inside a solid voxel, in far fewer bytes.

use std::io::Write;

use dot_vox::{Color, Dict, DotVoxData, Frame, Model, SceneNode, ShapeModel, Size, Voxel};
use voxtrace::glam::IVec3;
use voxtrace::{IAabb, VoxelGenerator, VoxelSource};

/// MagicaVoxel's largest model side.
const MAX_SIDE: i32 = 256;

/// The box of the terrain of `size` worth exporting: `[-size, size)` across
/// and, vertically, from two voxels under the lowest column top to the
/// highest (the terrain is solid all the way down; a box of
/// `[-size, size)^3` would be solid through for small sizes).
#[must_use]
pub fn terrain_box(terrain: &VoxelGenerator, size: i32) -> IAabb {
    let (mut low, mut high) = (i32::MAX, i32::MIN);
    for z in -size..size {
        for x in -size..size {
            let top = terrain.height(x, z);
            low = low.min(top);
            high = high.max(top);
        }
    }
    IAabb::new(
        IVec3::new(-size, low - 2, -size),
        IVec3::new(size, high + 1, size),
    )
}

/// Writes the voxels of `source` in `bounds` as one `.vox` model, placed by
/// a translation so that voxtrace's loader puts every voxel back where it
/// was (MagicaVoxel's z-up axes turned into voxtrace's y-up ones); returns
/// the number of voxels written.
///
/// # Errors
/// A one-line message for a box with a side past MagicaVoxel's 256 voxels,
/// or a failed write.
pub fn export_vox(
    source: &impl VoxelSource,
    bounds: IAabb,
    out: &mut impl Write,
) -> Result<usize, String> {
    let s = bounds.size();
    if bounds.is_empty() || s.max_element() > MAX_SIDE {
        return Err(format!(
            "--export-vox writes one MagicaVoxel model, 1 to {MAX_SIDE} voxels a side; this one is {}x{}x{} (try a smaller --size)",
            s.x, s.y, s.z
        ));
    }
    // The file's axes: x, then voxtrace's z (depth), then voxtrace's y (up).
    let file_size = IVec3::new(s.x, s.z, s.y);
    let pivot = file_size / 2;
    // The loader puts file voxel l at R (l - pivot) + R t (rounded through
    // voxel centers), R = (x, y, z) -> (x, z, -y); this translation lands
    // the model's corner on `bounds.min`.
    let shift = IVec3::new(
        bounds.min.x + pivot.x,
        bounds.min.y + pivot.z,
        bounds.min.z + file_size.y - pivot.y,
    );
    let t_file = IVec3::new(shift.x, -shift.z, shift.y);
    let solid = |p: IVec3| bounds.contains(p) && source.material(p) != 0;
    let mut voxels = Vec::new();
    for y in bounds.min.y..bounds.max.y {
        for z in bounds.min.z..bounds.max.z {
            for x in bounds.min.x..bounds.max.x {
                let p = IVec3::new(x, y, z);
                let material = source.material(p);
                if material == 0 {
                    continue;
                }
                let buried = [IVec3::X, IVec3::Y, IVec3::Z]
                    .iter()
                    .all(|&d| solid(p + d) && solid(p - d));
                if buried {
                    continue;
                }
                let q = p - shift;
                let local = IVec3::new(q.x + pivot.x, pivot.y - 1 - q.z, q.y + pivot.z);
                voxels.push(Voxel {
                    x: local.x as u8,
                    y: local.y as u8,
                    z: local.z as u8,
                    i: material - 1,
                });
            }
        }
    }
    let palette = source.palette();
    let colors = (1..=255u8)
        .map(|m| palette.color(m))
        .map(|c| Color {
            r: c.x,
            g: c.y,
            b: c.z,
            a: 255,
        })
        .chain([Color {
            r: 0,
            g: 0,
            b: 0,
            a: 255,
        }])
        .collect();
    let count = voxels.len();
    let dict = |pairs: &[(&str, String)]| -> Dict {
        pairs
            .iter()
            .map(|(k, v)| ((*k).to_string(), v.clone()))
            .collect()
    };
    // MagicaVoxel's usual graph: root transform, group, transform, shape.
    let scenes = vec![
        SceneNode::Transform {
            attributes: Dict::default(),
            frames: vec![Frame {
                attributes: Dict::default(),
            }],
            child: 1,
            layer_id: u32::MAX,
        },
        SceneNode::Group {
            attributes: Dict::default(),
            children: vec![2],
        },
        SceneNode::Transform {
            attributes: Dict::default(),
            frames: vec![Frame {
                attributes: dict(&[("_t", format!("{} {} {}", t_file.x, t_file.y, t_file.z))]),
            }],
            child: 3,
            layer_id: 0,
        },
        SceneNode::Shape {
            attributes: Dict::default(),
            models: vec![ShapeModel {
                model_id: 0,
                attributes: Dict::default(),
            }],
        },
    ];
    let data = DotVoxData {
        version: 150,
        index_map: Vec::new(),
        models: vec![Model {
            size: Size {
                x: file_size.x as u32,
                y: file_size.y as u32,
                z: file_size.z as u32,
            },
            voxels,
        }],
        palette: colors,
        materials: Vec::new(),
        scenes,
        layers: Vec::new(),
    };
    data.write_vox(out).map_err(|e| e.to_string())?;
    Ok(count)
}

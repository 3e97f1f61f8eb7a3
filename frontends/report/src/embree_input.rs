//! `voxtrace-report embree-input`: the seeded terrain as the triangle mesh a
//! user would hand Intel Embree (two triangles for every face between a
//! solid voxel and an empty one), the paper camera's primary rays, and the
//! voxel voxtrace's octree hits with each: the inputs of
//! `benches/embree/trace.c`, which traces the same rays through the mesh.
//!
//! Files, little-endian, in `--out-dir`:
//! - `mesh.bin`: `u32` vertex count, `u32` triangle count, the vertices
//!   (`f32` x, y, z), the triangles (`u32` indices), and each triangle's
//!   voxel (`i32` x, y, z).
//! - `rays.bin`: `u32` width, `u32` height, then per pixel, row by row, the
//!   ray's origin and unit direction (`f32` x 6), bit for bit the rays a
//!   frame traces.
//! - `hits.bin`: per pixel the voxel the octree hits (`i32` x, y, z), or
//!   `i32::MIN` three times for a miss.

use std::io::Write;
use std::path::PathBuf;

use voxtrace::glam::IVec3;
use voxtrace::{Camera, CameraSettings, DenseScene, IAabb, OctreeScene, Scene, VoxelGenerator};

/// What `embree-input` writes.
#[derive(Debug, clap::Args)]
pub struct EmbreeInputArgs {
    /// Scene size (the terrain spans -size..size on each axis).
    #[arg(long, default_value_t = 250)]
    size: i32,
    /// Terrain seed.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Image width.
    #[arg(long, default_value_t = 1920)]
    width: u32,
    /// Image height.
    #[arg(long, default_value_t = 1080)]
    height: u32,
    /// Folder for mesh.bin, rays.bin and hits.bin.
    #[arg(long, default_value = "target/embree")]
    out_dir: PathBuf,
}

/// The six face directions, each with the four corners of that face of the
/// unit cube at the origin, counter-clockwise seen from outside.
const FACES: [(IVec3, [[i32; 3]; 4]); 6] = [
    (IVec3::X, [[1, 0, 0], [1, 1, 0], [1, 1, 1], [1, 0, 1]]),
    (IVec3::NEG_X, [[0, 0, 0], [0, 0, 1], [0, 1, 1], [0, 1, 0]]),
    (IVec3::Y, [[0, 1, 0], [0, 1, 1], [1, 1, 1], [1, 1, 0]]),
    (IVec3::NEG_Y, [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]]),
    (IVec3::Z, [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]),
    (IVec3::NEG_Z, [[0, 0, 0], [0, 1, 0], [1, 1, 0], [1, 0, 0]]),
];

/// Writes the three files.
pub fn run(args: &EmbreeInputArgs) -> Result<(), String> {
    std::fs::create_dir_all(&args.out_dir)
        .map_err(|e| format!("cannot create {}: {e}", args.out_dir.display()))?;
    let bounds = IAabb::centered(args.size);
    let terrain = VoxelGenerator::new(args.seed);
    let dense = DenseScene::build_parallel(&terrain, bounds).map_err(|e| e.to_string())?;
    let octree = OctreeScene::build_parallel(&terrain, bounds).map_err(|e| e.to_string())?;

    // Exposed faces: a solid voxel's side whose neighbour is empty.
    let (mut vertices, mut triangles, mut voxels) = (Vec::new(), Vec::new(), Vec::new());
    for z in bounds.min.z..bounds.max.z {
        for y in bounds.min.y..bounds.max.y {
            for x in bounds.min.x..bounds.max.x {
                let pos = IVec3::new(x, y, z);
                if dense.material(pos) == 0 {
                    continue;
                }
                for (normal, corners) in FACES {
                    if dense.material(pos + normal) != 0 {
                        continue;
                    }
                    let first = (vertices.len() / 3) as u32;
                    for c in corners {
                        vertices.extend((pos + IVec3::from_array(c)).as_vec3().to_array());
                    }
                    triangles.extend([first, first + 1, first + 2, first, first + 2, first + 3]);
                    voxels.extend(pos.to_array());
                    voxels.extend(pos.to_array());
                }
            }
        }
    }
    let mut mesh = Vec::new();
    mesh.extend(((vertices.len() / 3) as u32).to_le_bytes());
    mesh.extend(((triangles.len() / 3) as u32).to_le_bytes());
    vertices
        .iter()
        .for_each(|v: &f32| mesh.extend(v.to_le_bytes()));
    triangles.iter().for_each(|i| mesh.extend(i.to_le_bytes()));
    voxels
        .iter()
        .for_each(|i: &i32| mesh.extend(i.to_le_bytes()));
    write(args, "mesh.bin", &mesh)?;

    let camera = Camera::new(CameraSettings {
        width: args.width,
        height: args.height,
        ..CameraSettings::paper(args.size)
    })
    .map_err(|e| e.to_string())?;
    let (mut rays, mut hits) = (Vec::new(), Vec::new());
    rays.extend(args.width.to_le_bytes());
    rays.extend(args.height.to_le_bytes());
    for y in 0..args.height {
        for x in 0..args.width {
            let ray = camera.get_ray(x, y);
            for v in ray
                .origin()
                .to_array()
                .into_iter()
                .chain(ray.dir().to_array())
            {
                rays.extend(v.to_le_bytes());
            }
            let voxel = octree
                .trace(&ray)
                .map_or([i32::MIN; 3], |h| h.pos.to_array());
            voxel.iter().for_each(|i| hits.extend(i.to_le_bytes()));
        }
    }
    write(args, "rays.bin", &rays)?;
    write(args, "hits.bin", &hits)?;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "{} triangles, {} rays in {}",
        triangles.len() / 3,
        args.width * args.height,
        args.out_dir.display()
    );
    Ok(())
}

fn write(args: &EmbreeInputArgs, name: &str, bytes: &[u8]) -> Result<(), String> {
    let path = args.out_dir.join(name);
    std::fs::write(&path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

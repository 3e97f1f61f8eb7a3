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
//!
//! With `--occlusion N`, also the occlusion rays `voxtrace --ao N` traces
//! from those hits (one sample a pixel), made by the core's own
//! [`occlusion_rays`] (not a copy of the recipe), and voxtrace's answers:
//! - `occlusion.bin`: `u32` ray count, `f32` reach (`--ao-distance`),
//!   `u32` rays a hit, `u32` rays that cannot leave their face (counted
//!   open, not written), then per ray, pixel by pixel, row by row, and a
//!   pixel's rays in order, its origin and unit direction (`f32` x 6).
//! - `occlusion_hits.bin`: per ray, whether the octree's walk meets a
//!   voxel within the reach (`u32` 1 or 0: `Scene::trace_with` with
//!   `Reach::within`), then the same ray unbounded (`Reach::ALL`): its hit's
//!   `t` (`f32`, infinity for a miss) and voxel (`i32` x, y, z, `i32::MIN`
//!   three times for a miss).

use std::io::Write;
use std::path::PathBuf;

use voxtrace::glam::IVec3;
use voxtrace::{
    occlusion_rays, Camera, CameraSettings, DenseScene, IAabb, Occlusion, OctreeScene, Reach,
    Scene, VoxelGenerator, WalkMemory,
};

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
    /// Also write the occlusion rays of `voxtrace --ao N` (N rays a hit)
    /// and voxtrace's answers: occlusion.bin and occlusion_hits.bin.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    occlusion: Option<u16>,
    /// Their reach, in voxels (`voxtrace --ao-distance`).
    #[arg(long, default_value_t = Occlusion::DEFAULT_DISTANCE)]
    ao_distance: f32,
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
    let mut occlusion = args.occlusion.map(|n| Secondary::new(n, args.ao_distance));
    for y in 0..args.height {
        for x in 0..args.width {
            let ray = camera.get_ray(x, y);
            put_ray(&mut rays, &ray);
            let hit = octree.trace(&ray);
            let voxel = hit.map_or([i32::MIN; 3], |h| h.pos.to_array());
            voxel.iter().for_each(|i| hits.extend(i.to_le_bytes()));
            if let (Some(secondary), Some(hit)) = (&mut occlusion, hit) {
                secondary.add(&octree, ray, hit, (x, y));
            }
        }
    }
    write(args, "rays.bin", &rays)?;
    write(args, "hits.bin", &hits)?;
    if let Some(secondary) = occlusion {
        let mut header = Vec::new();
        header.extend(secondary.count.to_le_bytes());
        header.extend(args.ao_distance.to_le_bytes());
        header.extend(u32::from(secondary.per_hit).to_le_bytes());
        header.extend(secondary.unsent.to_le_bytes());
        header.extend(&secondary.rays);
        write(args, "occlusion.bin", &header)?;
        write(args, "occlusion_hits.bin", &secondary.answers)?;
        let mut out = std::io::stdout().lock();
        let _ = writeln!(
            out,
            "{} occlusion rays ({} a hit, reach {}), {} that cannot leave their face",
            secondary.count, secondary.per_hit, args.ao_distance, secondary.unsent
        );
    }
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

/// The occlusion rays of the camera rays' hits, as `occlusion.bin` and
/// `occlusion_hits.bin` hold them (the module's docs).
struct Secondary {
    per_hit: u16,
    reach: Reach,
    count: u32,
    unsent: u32,
    rays: Vec<u8>,
    answers: Vec<u8>,
}

impl Secondary {
    fn new(per_hit: u16, distance: f32) -> Self {
        Secondary {
            per_hit,
            reach: Reach::within(distance),
            count: 0,
            unsent: 0,
            rays: Vec::new(),
            answers: Vec::new(),
        }
    }

    /// The occlusion rays of `hit`, of the camera ray `ray` of `pixel` (the
    /// frame's one sample), and the octree's answers for each, each ray
    /// walked alone from an empty memory (the frame's packets and memories
    /// find the same hits: `Scene`'s guarantees).
    fn add<S: Scene>(
        &mut self,
        octree: &S,
        ray: voxtrace::Ray,
        hit: voxtrace::Hit,
        pixel: (u32, u32),
    ) {
        for occlusion in occlusion_rays(ray, hit, pixel, 0, self.per_hit) {
            let Some(occlusion) = occlusion else {
                self.unsent += 1;
                continue;
            };
            self.count += 1;
            put_ray(&mut self.rays, &occlusion);
            let trace = |reach| {
                let memory = &mut WalkMemory::new();
                octree.trace_with(&occlusion, reach, memory, None).hit
            };
            let blocked = trace(self.reach).is_some();
            self.answers.extend(u32::from(blocked).to_le_bytes());
            let far = trace(Reach::ALL);
            let t = far.map_or(f32::INFINITY, |h| h.t);
            self.answers.extend(t.to_le_bytes());
            let voxel = far.map_or([i32::MIN; 3], |h| h.pos.to_array());
            voxel
                .iter()
                .for_each(|i| self.answers.extend(i.to_le_bytes()));
        }
    }
}

/// Appends `ray`'s origin and unit direction (`f32` x 6, little-endian).
fn put_ray(bytes: &mut Vec<u8>, ray: &voxtrace::Ray) {
    let (origin, dir) = (ray.origin().to_array(), ray.dir().to_array());
    for v in origin.into_iter().chain(dir) {
        bytes.extend(v.to_le_bytes());
    }
}

fn write(args: &EmbreeInputArgs, name: &str, bytes: &[u8]) -> Result<(), String> {
    let path = args.out_dir.join(name);
    std::fs::write(&path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use voxtrace::glam::U8Vec3;
    use voxtrace::{
        occlusion_rays, render, shade, unpack, Camera, CameraSettings, Hit, IAabb, Occlusion,
        OctreeScene, Rect, RenderOptions, Scene, Target, Voxel, VoxelGenerator,
    };

    /// The occlusion rays `embree-input --occlusion` writes are the ones a
    /// `--ao 4` frame traces: each pixel of the frame is its hit's face
    /// light dimmed by the share of those rays that meet nothing within
    /// the reach, every pixel exactly.
    #[test]
    fn occlusion_rays_are_the_frames() {
        // The paper camera is above the terrain from size 100 (inside it at
        // smaller sizes).
        let size = 100;
        let octree = OctreeScene::build(&VoxelGenerator::new(1), IAabb::centered(size)).unwrap();
        let camera = Camera::new(CameraSettings {
            width: 96,
            height: 54,
            ..CameraSettings::paper(size)
        })
        .unwrap();
        let ao = Occlusion {
            rays: 4,
            distance: Occlusion::DEFAULT_DISTANCE,
        };
        let options = RenderOptions {
            occlusion: Some(ao),
            ..RenderOptions::default()
        };
        let mut frame = vec![0u32; 96 * 54];
        let region = Rect::full(&camera);
        render(
            &octree,
            &camera,
            &options,
            region,
            Target::Buffer(&mut frame),
            None,
        )
        .unwrap();
        let mut counts = [0usize; 5];
        for y in 0..54 {
            for x in 0..96 {
                let ray = camera.get_ray(x, y);
                let Some(hit) = octree.trace(&ray) else {
                    continue;
                };
                let rays = occlusion_rays(ray, hit, (x, y), 0, ao.rays);
                let open = rays
                    .map(|r| r.is_none_or(|r| octree.trace_within(&r, ao.distance).is_none()))
                    .filter(|&open| open)
                    .count() as u32;
                // The face's light out of 256: the plain look's shade of a
                // white voxel is 255 * light / 256, rounded down.
                let white = Hit {
                    voxel: Voxel {
                        color: U8Vec3::splat(255),
                    },
                    ..hit
                };
                let v = u32::from(shade(Some(&white), &ray, &RenderOptions::default()).x);
                let light = if v == 0 { 0 } else { v + 1 } * open / u32::from(ao.rays);
                let expected = (hit.voxel.color.as_uvec3() * light / 256).to_array();
                let got = unpack(frame[(y * 96 + x) as usize]);
                assert_eq!(got[..3], expected.map(|c| c as u8), "pixel ({x}, {y})");
                counts[open as usize] += 1;
            }
        }
        // Pixels of every count of open rays, 0 to 4.
        assert!(
            counts.iter().all(|&n| n > 10),
            "open rays by pixel: {counts:?}"
        );
    }
}

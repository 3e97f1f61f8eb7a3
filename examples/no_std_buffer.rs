//! Rendering with no allocator: every byte lives in buffers the caller
//! owns, sized by the storages' own size functions, and nothing in voxtrace
//! allocates.
//!
//! ```sh
//! cargo run --example no_std_buffer
//! ```
//!
//! This is the API that works in a `#![no_std]` crate without an allocator
//! (voxtrace with `default-features = false`): `DenseScene::const_len` and
//! `OctreeScene::max_len` size fixed arrays (or `static`s) at compile time,
//! `DenseScene::required_len` and `OctreeScene::required_len` give the exact
//! need at run time, `build_in` builds a storage into the caller's buffers,
//! and `render` writes into a caller's pixel slice. This example runs on the
//! host (it uses `std` only to print), but the calls between the buffers and
//! the checksum are the same on a microcontroller; `frontends/embedded` is
//! such a firmware.

use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{
    render, Camera, CameraSettings, DenseScene, IAabb, Node, OctreeLen, OctreeScene, Rect,
    RenderOptions, Target, VoxelGenerator,
};

/// The volume: a 32^3 box around a hilltop of the seed-7 terrain (the
/// terrain is clipped to it; voxtrace's storages can sit anywhere).
const BOUNDS: IAabb = IAabb::new(IVec3::new(-116, 56, -116), IVec3::new(-84, 88, -84));
const SEED: u64 = 7;
/// Frame size in pixels.
const WIDTH: u32 = 32;
const HEIGHT: u32 = 32;
const PIXELS: usize = (WIDTH * HEIGHT) as usize;

/// One byte per voxel of `BOUNDS`, known at compile time.
const DENSE_LEN: usize = DenseScene::const_len(BOUNDS);
/// Enough nodes and material bytes for any octree over `BOUNDS`.
const OCTREE_LEN: OctreeLen = OctreeScene::max_len(BOUNDS);

/// FNV-1a over the frame's RGBA bytes: one number to compare frames by.
fn checksum(pixels: &[u32]) -> u64 {
    pixels
        .iter()
        .flat_map(|p| p.to_ne_bytes())
        .fold(0xcbf2_9ce4_8422_2325, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
        })
}

fn main() -> Result<(), voxtrace::Error> {
    // The caller's memory: fixed-size arrays, no Vec, no Box.
    let mut dense = [0u8; DENSE_LEN];
    let mut nodes = [Node::EMPTY; OCTREE_LEN.nodes];
    let mut materials = [0u8; OCTREE_LEN.materials];
    let mut frame_dense = [0u32; PIXELS];
    let mut frame_octree = [0u32; PIXELS];

    let terrain = VoxelGenerator::new(SEED);
    let lookat = Vec3::new(-100.0, 66.0, -100.0);
    let camera = Camera::new(CameraSettings {
        width: WIDTH,
        height: HEIGHT,
        lookfrom: lookat + Vec3::new(30.0, 30.0, 22.0),
        lookat,
        ..CameraSettings::default()
    })?;
    let options = RenderOptions::default();

    // The exact need at run time (the octree's depends on the voxels; finding
    // it costs about one build), against the compile-time bound.
    let dense_needed = DenseScene::required_len(BOUNDS)?;
    let octree_needed = OctreeScene::required_len(&terrain, BOUNDS)?;
    println!("dense:  {dense_needed} bytes (array of {DENSE_LEN})");
    println!(
        "octree: {} nodes, {} material bytes (arrays of {} and {})",
        octree_needed.nodes, octree_needed.materials, OCTREE_LEN.nodes, OCTREE_LEN.materials
    );

    // Build into the buffers and render into the fixed frames.
    let scene = DenseScene::build_in(&terrain, BOUNDS, &mut dense)?;
    let stats = render(
        &scene,
        &camera,
        &options,
        Rect::full(&camera),
        Target::Buffer(&mut frame_dense),
        None,
    )?;
    // The octree gets exactly what `required_len` reported: it is enough.
    let scene = OctreeScene::build_in(
        &terrain,
        BOUNDS,
        &mut nodes[..octree_needed.nodes],
        &mut materials[..octree_needed.materials],
    )?;
    render(
        &scene,
        &camera,
        &options,
        Rect::full(&camera),
        Target::Buffer(&mut frame_octree),
        None,
    )?;

    println!(
        "{WIDTH}x{HEIGHT}, {} primary rays, {} hits",
        stats.primary_rays, stats.primary_hits
    );
    println!("checksum dense:  {:016x}", checksum(&frame_dense));
    println!("checksum octree: {:016x}", checksum(&frame_octree));
    // Both storages return the same hit for every ray, so the frames agree.
    assert_eq!(frame_dense, frame_octree);
    Ok(())
}

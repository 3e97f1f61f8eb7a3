//! The bare-metal render logic, run on the host: its frame equals the
//! desktop render of the same scene byte for byte, for both storages.

use voxtrace::{
    render, DenseScene, Node, OctreeScene, Rect, RenderOptions, Target, VoxelGenerator,
};
use voxtrace_embedded::{
    camera, render_demo, Backend, Buffers, BOUNDS, DENSE_LEN, OCTREE_LEN, PIXELS, SEED,
};

fn embedded(backend: Backend) -> Vec<u32> {
    let mut dense = vec![0u8; DENSE_LEN];
    let mut nodes = vec![Node::EMPTY; OCTREE_LEN.nodes];
    let mut materials = vec![0u8; OCTREE_LEN.materials];
    let mut frame = vec![0u32; PIXELS];
    let buffers = Buffers {
        dense: &mut dense,
        nodes: &mut nodes,
        materials: &mut materials,
    };
    let stats = render_demo(backend, buffers, &mut frame).unwrap();
    assert_eq!(stats.primary_rays, PIXELS as u64);
    assert!(
        stats.primary_hits > PIXELS as u64 / 4,
        "the camera sees terrain"
    );
    frame
}

#[test]
fn the_embedded_frame_is_the_desktop_frame() {
    // The desktop way: storages in vectors from the allocating builders.
    let terrain = VoxelGenerator::new(SEED);
    let scene = OctreeScene::build(&terrain, BOUNDS).unwrap();
    let mut desktop = vec![0u32; PIXELS];
    render(
        &scene,
        &camera().unwrap(),
        &RenderOptions::default(),
        Rect::full(&camera().unwrap()),
        Target::Buffer(&mut desktop),
        None,
    )
    .unwrap();
    let dense = DenseScene::build(&terrain, BOUNDS).unwrap();
    let mut desktop_dense = vec![0u32; PIXELS];
    render(
        &dense,
        &camera().unwrap(),
        &RenderOptions::default(),
        Rect::full(&camera().unwrap()),
        Target::Buffer(&mut desktop_dense),
        None,
    )
    .unwrap();
    assert!(desktop == desktop_dense);

    assert!(
        embedded(Backend::Dense) == desktop,
        "dense differs from the desktop"
    );
    assert!(
        embedded(Backend::Octree) == desktop,
        "octree differs from the desktop"
    );
}

#[test]
fn the_static_sizes_hold_what_the_builds_need() {
    let terrain = VoxelGenerator::new(SEED);
    assert_eq!(DENSE_LEN, DenseScene::required_len(BOUNDS).unwrap());
    let used = OctreeScene::required_len(&terrain, BOUNDS).unwrap();
    assert!(used.nodes <= OCTREE_LEN.nodes && used.materials <= OCTREE_LEN.materials);
}

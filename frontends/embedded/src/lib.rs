//! voxtrace without std or an allocator: the demo scene that the firmware
//! (`src/main.rs`) renders on a Cortex-M4F, as a library the host tests call
//! too, so they can check the bytes against the desktop render.
//!
//! Every buffer is the caller's, sized at compile time by the storages' own
//! size functions ([`DENSE_LEN`], [`OCTREE_LEN`]).

#![no_std]
#![deny(missing_docs, unsafe_code)]

use voxtrace::glam::Vec3;
use voxtrace::{
    render, Camera, CameraSettings, DenseScene, Error, IAabb, Node, OctreeLen, OctreeScene,
    RayStats, Rect, RenderOptions, Target, VoxelGenerator,
};

/// Scene extent: the volume is `[-16, 16)^3`, terrain clipped to it.
pub const SIZE: i32 = 16;
/// The volume.
pub const BOUNDS: IAabb = IAabb::centered(SIZE);
/// Terrain seed.
pub const SEED: u64 = 7;
/// Frame width in pixels.
pub const WIDTH: u32 = 64;
/// Frame height in pixels.
pub const HEIGHT: u32 = 64;
/// Pixels in the frame.
pub const PIXELS: usize = (WIDTH * HEIGHT) as usize;
/// Bytes of the dense array over [`BOUNDS`].
pub const DENSE_LEN: usize = DenseScene::const_len(BOUNDS);
/// Nodes and material bytes enough for any octree over [`BOUNDS`].
pub const OCTREE_LEN: OctreeLen = OctreeScene::max_len(BOUNDS);
/// Where the camera stands: above one corner, looking at the origin.
pub const EYE: Vec3 = Vec3::new(30.0, 34.0, 22.0);

/// Which storage to build.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    /// The flat array, in `dense`.
    Dense,
    /// The octree, in `nodes` and `materials`.
    Octree,
}

/// The caller's buffers for both storages.
pub struct Buffers<'a> {
    /// At least [`DENSE_LEN`] bytes.
    pub dense: &'a mut [u8],
    /// At least `OCTREE_LEN.nodes` nodes.
    pub nodes: &'a mut [Node],
    /// At least `OCTREE_LEN.materials` bytes.
    pub materials: &'a mut [u8],
}

/// The demo camera.
pub fn camera() -> Result<Camera, Error> {
    Camera::new(CameraSettings {
        width: WIDTH,
        height: HEIGHT,
        lookfrom: EYE,
        ..CameraSettings::default()
    })
}

/// Builds the demo terrain with `backend` into `buffers` and renders the
/// default look into `frame` (at least [`PIXELS`] pixels). Allocates
/// nothing.
pub fn render_demo(
    backend: Backend,
    buffers: Buffers<'_>,
    frame: &mut [u32],
) -> Result<RayStats, Error> {
    let terrain = VoxelGenerator::new(SEED);
    let camera = camera()?;
    let options = RenderOptions::default();
    match backend {
        Backend::Dense => {
            let scene = DenseScene::build_in(&terrain, BOUNDS, buffers.dense)?;
            render(
                &scene,
                &camera,
                &options,
                Rect::full(&camera),
                Target::Buffer(frame),
                None,
            )
        }
        Backend::Octree => {
            let scene = OctreeScene::build_in(&terrain, BOUNDS, buffers.nodes, buffers.materials)?;
            render(
                &scene,
                &camera,
                &options,
                Rect::full(&camera),
                Target::Buffer(frame),
                None,
            )
        }
    }
}

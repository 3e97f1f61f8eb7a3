//! Building the octree on the rayon pool (feature `rayon`), with exactly
//! the result of the sequential build: the same nodes in the same order.

use glam::IVec3;
use rayon::prelude::*;
use std::vec::Vec;

use crate::error::Error;
use crate::fallible::{try_grow, try_vec};
use crate::geom::IAabb;
use crate::storage::octree::build::{
    octants, push_vec, root_size, shortcut, Builder, Cube, VecSink,
};
use crate::storage::octree::node::{child_offset, BrickMaterials, Node, NodeKind};
use crate::storage::octree::OctreeScene;
use crate::voxel::VoxelSource;

/// Side of the cubes handed to one task. 64^3 voxels are a few milliseconds
/// of work: enough tasks to balance two to sixteen threads on a terrain,
/// few enough that scheduling costs nothing.
const TASK: i32 = 64;

impl OctreeScene<Vec<Node>, Vec<u8>> {
    /// [`OctreeScene::build`] on the current rayon pool; the nodes and
    /// materials are identical, in the same order.
    ///
    /// The cubes of side 64 that the sequential builder would open are built
    /// in parallel, each into its own vectors; they are then appended in the
    /// sequential order, with child indices and material offsets shifted, and
    /// the levels above them are built as `build` would. The parts are freed
    /// as they are appended, so the peak memory is about the final size plus
    /// the largest part.
    pub fn build_parallel<S: VoxelSource + Sync + ?Sized>(
        source: &S,
        bounds: IAabb,
    ) -> Result<Self, Error> {
        bounds.validate()?;
        let size = root_size(&bounds);
        let mut tasks = Vec::new();
        collect_tasks(source, &bounds, bounds.min, size, &mut tasks)?;
        // One slot per task, reserved fallibly: rayon's `collect` would
        // grow the vector with an abort when memory runs out.
        let mut parts: Vec<Result<Part, Error>> = try_vec(tasks.len())?;
        parts.par_extend(tasks.par_iter().map(|&corner| {
            let mut builder = Builder::new(source, bounds, VecSink::default());
            let root = builder.node(corner, size.min(TASK))?;
            Ok((corner, root, builder.sink))
        }));
        let mut parts = parts.into_iter();
        let mut builder = Builder::new(source, bounds, VecSink::default());
        let root = assemble(&mut builder, &mut parts, bounds.min, size)?.unwrap_or(Node::EMPTY);
        if parts.next().is_some() {
            // The replay opened fewer cubes than the first pass: the source
            // called some cube mixed once and decided the second time.
            return Err(inconsistent(IAabb::new(bounds.min, bounds.min + size)));
        }
        Ok(Self::from_sink(
            bounds,
            root,
            size,
            builder.sink,
            source.palette(),
        ))
    }
}

/// A subtree built by one task: its cube's corner, its root and its own
/// nodes and materials.
type Part = (IVec3, Option<Node>, VecSink);

/// The corners of the task cubes, in the order the sequential builder
/// reaches them.
fn collect_tasks<S: VoxelSource + ?Sized>(
    source: &S,
    bounds: &IAabb,
    corner: IVec3,
    size: i32,
    tasks: &mut Vec<IVec3>,
) -> Result<(), Error> {
    if let Cube::Decided(_) = shortcut(source, bounds, corner, size) {
        return Ok(());
    }
    if size <= TASK {
        try_grow(tasks, 1)?;
        tasks.push(corner);
        return Ok(());
    }
    let half = size / 2;
    for i in 0..8 {
        collect_tasks(source, bounds, corner + child_offset(i) * half, half, tasks)?;
    }
    Ok(())
}

/// Replays the sequential recursion above the task cubes, appending each
/// task's part where the sequential builder would have written it.
fn assemble<S: VoxelSource + ?Sized>(
    builder: &mut Builder<'_, S, VecSink>,
    parts: &mut impl Iterator<Item = Result<Part, Error>>,
    corner: IVec3,
    size: i32,
) -> Result<Option<Node>, Error> {
    if let Cube::Decided(node) = shortcut(builder.source, &builder.bounds, corner, size) {
        return Ok(node);
    }
    if size <= TASK {
        // One part per cube collect_tasks opened, in this order; a source
        // whose classify changed its answer makes the replay open more
        // cubes or others.
        let cube = IAabb::new(corner, corner + size);
        let (built_at, root, part) = parts.next().ok_or(inconsistent(cube))??;
        if built_at != corner {
            return Err(inconsistent(cube));
        }
        return append(&mut builder.sink, root, part);
    }
    let children = octants(corner, size, |corner, half| {
        assemble(builder, parts, corner, half)
    })?;
    builder.combine(&children)
}

/// The error for a source that classified `region` two ways.
fn inconsistent(region: IAabb) -> Error {
    Error::InconsistentSource {
        min: region.min.to_array(),
        max: region.max.to_array(),
    }
}

/// Appends a part's nodes and materials to `sink`, shifting the indices they
/// hold by where they land; returns the part's root, shifted the same way.
fn append(sink: &mut VecSink, root: Option<Node>, part: VecSink) -> Result<Option<Node>, Error> {
    let to_u32 = |n: usize| u32::try_from(n).map_err(|_| Error::SizeOverflow);
    let node_shift = to_u32(sink.nodes.len())?;
    let material_shift = to_u32(sink.materials.len())?;
    let shift = |node: Node| -> Result<Node, Error> {
        let add = |index: u32, by: u32| index.checked_add(by).ok_or(Error::SizeOverflow);
        Ok(Node::of(match node.kind() {
            NodeKind::Branch { children, first } => NodeKind::Branch {
                children,
                first: add(first, node_shift)?,
            },
            NodeKind::Brick {
                occupancy,
                materials: BrickMaterials::Packed(offset),
            } => NodeKind::Brick {
                occupancy,
                materials: BrickMaterials::Packed(add(offset, material_shift)?),
            },
            kind => kind,
        }))
    };
    try_grow(&mut sink.nodes, part.nodes.len())?;
    for &node in &part.nodes {
        sink.nodes.push(shift(node)?);
    }
    push_vec(&mut sink.materials, &part.materials)?;
    root.map(shift).transpose()
}

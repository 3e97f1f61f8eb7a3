//! Building an `OctreeScene` from a `VoxelSource`, into caller buffers or
//! into vectors, through one recursive builder and three sinks.
//!
//! The builder asks the source to classify big boxes first (a height field
//! knows its sky is empty), and only fills 16^3 tiles it cannot classify, so
//! it never visits the empty voxels of a large volume one by one. Children
//! are written before their parent, eight siblings contiguously.

use glam::IVec3;

use crate::error::Error;
use crate::geom::IAabb;
use crate::storage::octree::node::{
    brick_bit, child_offset, BrickMaterials, Node, NodeKind, BRICK,
};
use crate::storage::octree::{occupied_box, OctreeLen, OctreeScene};
use crate::voxel::{Region, VoxelSource};

/// Side of the tiles the builder fills from the source in one call.
const TILE: i32 = 16;
const TILE_VOLUME: usize = (TILE * TILE * TILE) as usize;

/// Where built nodes and materials go. Each push returns the index of the
/// first element pushed.
pub(crate) trait Sink {
    fn push_nodes(&mut self, nodes: &[Node]) -> Result<u32, Error>;
    fn push_materials(&mut self, materials: &[u8]) -> Result<u32, Error>;
}

/// Counts without storing: how [`OctreeScene::required_len`] measures.
#[derive(Default)]
struct Counter(OctreeLen);

fn index_u32(i: usize) -> Result<u32, Error> {
    u32::try_from(i).map_err(|_| Error::SizeOverflow)
}

impl Sink for Counter {
    fn push_nodes(&mut self, nodes: &[Node]) -> Result<u32, Error> {
        let first = index_u32(self.0.nodes)?;
        self.0.nodes += nodes.len();
        Ok(first)
    }

    fn push_materials(&mut self, materials: &[u8]) -> Result<u32, Error> {
        let first = index_u32(self.0.materials)?;
        self.0.materials += materials.len();
        Ok(first)
    }
}

/// Writes into caller-provided slices.
struct SliceSink<'a> {
    nodes: &'a mut [Node],
    materials: &'a mut [u8],
    used: OctreeLen,
}

fn write_into<T: Copy>(dst: &mut [T], used: &mut usize, src: &[T]) -> Result<u32, Error> {
    let first = *used;
    let end = first + src.len();
    let actual = dst.len();
    dst.get_mut(first..end)
        .ok_or(Error::BufferTooSmall {
            required: end,
            actual,
        })?
        .copy_from_slice(src);
    *used = end;
    index_u32(first)
}

impl Sink for SliceSink<'_> {
    fn push_nodes(&mut self, nodes: &[Node]) -> Result<u32, Error> {
        write_into(self.nodes, &mut self.used.nodes, nodes)
    }

    fn push_materials(&mut self, materials: &[u8]) -> Result<u32, Error> {
        write_into(self.materials, &mut self.used.materials, materials)
    }
}

/// Grows vectors with fallible reservations.
#[cfg(feature = "alloc")]
#[derive(Default)]
pub(crate) struct VecSink {
    pub(crate) nodes: alloc::vec::Vec<Node>,
    pub(crate) materials: alloc::vec::Vec<u8>,
}

#[cfg(feature = "alloc")]
pub(crate) fn push_vec<T: Copy>(dst: &mut alloc::vec::Vec<T>, src: &[T]) -> Result<u32, Error> {
    let first = index_u32(dst.len())?;
    crate::fallible::try_grow(dst, src.len())?;
    dst.extend_from_slice(src);
    Ok(first)
}

#[cfg(feature = "alloc")]
impl Sink for VecSink {
    fn push_nodes(&mut self, nodes: &[Node]) -> Result<u32, Error> {
        push_vec(&mut self.nodes, nodes)
    }

    fn push_materials(&mut self, materials: &[u8]) -> Result<u32, Error> {
        push_vec(&mut self.materials, materials)
    }
}

/// Side of the root cube: the smallest power of two covering the bounds,
/// at least one brick.
pub(crate) fn root_size(bounds: &IAabb) -> i32 {
    let side = bounds.size().max_element().max(BRICK) as u32;
    side.next_power_of_two() as i32
}

/// What the source says about a cube before any voxel is read.
pub(crate) enum Cube {
    /// Empty (`None`) or one solid material: no need to look inside.
    Decided(Option<Node>),
    /// Mixed or unknown: this part of the cube lies inside the bounds.
    Open(IAabb),
}

/// Asks `source` to classify the cube `[corner, corner + size)` clipped to
/// `bounds`. Every builder descends only into `Open` cubes, so the
/// sequential and parallel builds visit the same cubes.
pub(crate) fn shortcut<S: VoxelSource + ?Sized>(
    source: &S,
    bounds: &IAabb,
    corner: IVec3,
    size: i32,
) -> Cube {
    let cube = IAabb::new(corner, corner + size);
    let region = cube.intersect(bounds);
    if region.is_empty() {
        return Cube::Decided(None);
    }
    match source.classify(region) {
        Region::Empty => Cube::Decided(None),
        Region::Solid(m) if m != 0 && region == cube => {
            Cube::Decided(Some(Node::of(NodeKind::Solid(m))))
        }
        _ => Cube::Open(region),
    }
}

/// The recursive builder, generic over its sink.
pub(crate) struct Builder<'s, S: ?Sized, K> {
    pub(crate) source: &'s S,
    pub(crate) bounds: IAabb,
    pub(crate) sink: K,
    /// One tile of materials, in the layout of the clipped tile box.
    tile: [u8; TILE_VOLUME],
    tile_box: IAabb,
}

impl<'s, S: VoxelSource + ?Sized, K: Sink> Builder<'s, S, K> {
    pub(crate) fn new(source: &'s S, bounds: IAabb, sink: K) -> Self {
        Builder {
            source,
            bounds,
            sink,
            tile: [0; TILE_VOLUME],
            tile_box: IAabb::new(IVec3::ZERO, IVec3::ZERO),
        }
    }

    /// Builds the node for the cube `[corner, corner + size)`; `None` when
    /// it holds no solid voxel.
    pub(crate) fn node(&mut self, corner: IVec3, size: i32) -> Result<Option<Node>, Error> {
        let region = match shortcut(self.source, &self.bounds, corner, size) {
            Cube::Decided(node) => return Ok(node),
            Cube::Open(region) => region,
        };
        if size <= TILE {
            self.tile_box = region;
            let volume = region.volume()?;
            self.source.fill_box(region, &mut self.tile[..volume]);
            return self.tile_node(corner, size);
        }
        let children = octants(corner, size, |corner, half| self.node(corner, half))?;
        self.combine(&children)
    }

    /// Builds the node for a cube inside the current tile.
    fn tile_node(&mut self, corner: IVec3, size: i32) -> Result<Option<Node>, Error> {
        if size == BRICK {
            return self.brick(corner);
        }
        let children = octants(corner, size, |corner, half| self.tile_node(corner, half))?;
        self.combine(&children)
    }

    /// The material at `pos` from the current tile (0 outside the bounds).
    fn tile_material(&self, pos: IVec3) -> u8 {
        if !self.tile_box.contains(pos) {
            return 0;
        }
        let local = (pos - self.tile_box.min).as_uvec3();
        let size = self.tile_box.size().as_uvec3();
        self.tile[(local.x + size.x * (local.y + size.y * local.z)) as usize]
    }

    /// The brick at `corner` from the current tile: its occupancy and its
    /// solid voxels' materials in bit order.
    fn brick(&mut self, corner: IVec3) -> Result<Option<Node>, Error> {
        let mut occupancy = 0u64;
        let mut packed = [0u8; 64];
        let mut count = 0;
        // Bit order is x fastest, then y, then z (`brick_bit`): the loops
        // run in it, so the materials come out packed.
        let mut visit = |bit: u32, m: u8| {
            if m != 0 {
                occupancy |= 1 << bit;
                packed[count] = m;
                count += 1;
            }
        };
        let inside = IAabb::new(corner, corner + BRICK);
        if inside.intersect(&self.tile_box) == inside {
            // The whole brick is in the tile: four rows of four bytes per
            // layer, read in place.
            let size = self.tile_box.size().as_uvec3();
            let (row, layer) = (size.x as usize, (size.x * size.y) as usize);
            let local = (corner - self.tile_box.min).as_uvec3();
            let base = local.x as usize + row * local.y as usize + layer * local.z as usize;
            let mut bit = 0;
            for z in 0..BRICK as usize {
                for y in 0..BRICK as usize {
                    let start = base + layer * z + row * y;
                    for &m in &self.tile[start..start + BRICK as usize] {
                        visit(bit, m);
                        bit += 1;
                    }
                }
            }
        } else {
            // Cut by the bounds: a voxel at a time, outside ones empty.
            for z in 0..BRICK {
                for y in 0..BRICK {
                    for x in 0..BRICK {
                        let local = IVec3::new(x, y, z);
                        visit(brick_bit(local), self.tile_material(corner + local));
                    }
                }
            }
        }
        let solid = &packed[..count];
        let Some(&first) = solid.first() else {
            return Ok(None);
        };
        let uniform = solid.iter().all(|&m| m == first);
        let node = if uniform && occupancy == u64::MAX {
            NodeKind::Solid(first)
        } else if uniform {
            NodeKind::Brick {
                occupancy,
                materials: BrickMaterials::Uniform(first),
            }
        } else {
            NodeKind::Brick {
                occupancy,
                materials: BrickMaterials::Packed(self.sink.push_materials(solid)?),
            }
        };
        Ok(Some(Node::of(node)))
    }

    /// Merges eight children: all empty stays empty, eight equal solids
    /// become one solid, anything else a branch over its stored children.
    pub(crate) fn combine(&mut self, children: &[Option<Node>; 8]) -> Result<Option<Node>, Error> {
        if let Some(NodeKind::Solid(m)) = children[0].map(Node::kind) {
            if children
                .iter()
                .all(|c| *c == Some(Node::of(NodeKind::Solid(m))))
            {
                return Ok(Some(Node::of(NodeKind::Solid(m))));
            }
        }
        let mut mask = 0u8;
        let mut stored = [Node::EMPTY; 8];
        let mut count = 0;
        for (i, child) in children.iter().enumerate() {
            if let Some(node) = child {
                mask |= 1 << i;
                stored[count] = *node;
                count += 1;
            }
        }
        if mask == 0 {
            return Ok(None);
        }
        let first = self.sink.push_nodes(&stored[..count])?;
        Ok(Some(Node::of(NodeKind::Branch {
            children: mask,
            first,
        })))
    }
}

/// Builds the eight children of the cube `[corner, corner + size)` in octant
/// order with `child(child_corner, half_size)`, stopping at the first error.
/// Every builder (sequential, in a tile, parallel assembly) recurses through
/// here, so all of them order the children the same way.
#[inline(always)]
pub(crate) fn octants(
    corner: IVec3,
    size: i32,
    mut child: impl FnMut(IVec3, i32) -> Result<Option<Node>, Error>,
) -> Result<[Option<Node>; 8], Error> {
    let half = size / 2;
    let mut children = [None; 8];
    for (i, slot) in children.iter_mut().enumerate() {
        *slot = child(corner + child_offset(i) * half, half)?;
    }
    Ok(children)
}

/// Runs the builder over `bounds` into `sink`; returns the root and the sink.
fn build_root<S: VoxelSource + ?Sized, K: Sink>(
    source: &S,
    bounds: IAabb,
    sink: K,
) -> Result<(Node, i32, K), Error> {
    bounds.validate()?;
    let size = root_size(&bounds);
    let mut builder = Builder::new(source, bounds, sink);
    let root = builder.node(bounds.min, size)?.unwrap_or(Node::EMPTY);
    Ok((root, size, builder.sink))
}

impl OctreeScene<(), ()> {
    /// Exactly how many nodes and material bytes [`OctreeScene::build_in`]
    /// will use for this source and bounds. Runs the build without storing
    /// anything (so it costs about one build). Allocates nothing.
    pub fn required_len<S: VoxelSource + ?Sized>(
        source: &S,
        bounds: IAabb,
    ) -> Result<OctreeLen, Error> {
        Ok(build_root(source, bounds, Counter::default())?.2 .0)
    }
}

impl<'a> OctreeScene<&'a [Node], &'a [u8]> {
    /// Builds the octree into caller buffers sized by
    /// [`OctreeScene::required_len`]; fails with [`Error::BufferTooSmall`]
    /// if they are shorter. Allocates nothing.
    pub fn build_in<S: VoxelSource + ?Sized>(
        source: &S,
        bounds: IAabb,
        nodes: &'a mut [Node],
        materials: &'a mut [u8],
    ) -> Result<Self, Error> {
        let sink = SliceSink {
            nodes,
            materials,
            used: OctreeLen::default(),
        };
        let (root, root_size, sink) = build_root(source, bounds, sink)?;
        let SliceSink {
            nodes,
            materials,
            used,
        } = sink;
        let nodes = &nodes[..used.nodes];
        Ok(OctreeScene {
            bounds,
            occupied: occupied_box(root, root_size, bounds, nodes),
            root,
            root_size,
            nodes,
            materials: &materials[..used.materials],
            palette: source.palette().clone(),
        })
    }
}

#[cfg(feature = "alloc")]
impl OctreeScene<alloc::vec::Vec<Node>, alloc::vec::Vec<u8>> {
    /// Builds the octree in new vectors, grown with `try_reserve`: running
    /// out of memory is [`Error::OutOfMemory`], never an abort.
    pub fn build<S: VoxelSource + ?Sized>(source: &S, bounds: IAabb) -> Result<Self, Error> {
        let (root, root_size, sink) = build_root(source, bounds, VecSink::default())?;
        Ok(Self::from_sink(
            bounds,
            root,
            root_size,
            sink,
            source.palette(),
        ))
    }

    /// The scene over a finished sink, its vectors trimmed to their length.
    pub(crate) fn from_sink(
        bounds: IAabb,
        root: Node,
        root_size: i32,
        sink: VecSink,
        palette: &crate::voxel::Palette,
    ) -> Self {
        let VecSink {
            mut nodes,
            mut materials,
        } = sink;
        nodes.shrink_to_fit();
        materials.shrink_to_fit();
        OctreeScene {
            bounds,
            occupied: occupied_box(root, root_size, bounds, &nodes),
            root,
            root_size,
            nodes,
            materials,
            palette: palette.clone(),
        }
    }
}

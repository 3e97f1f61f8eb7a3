//! Tracing a packet of rays through an `OctreeScene`: 32 rays from
//! one origin, whose directions share their signs (an 8x4 block of a
//! camera's pixels), taken down the tree together, front to back.
//!
//! The packet goes down the tree depth first, a node's children in the
//! order every one of its rays meets them (octants by index with the
//! down-moving axes flipped), until every lane has left it at its first
//! solid voxel. Branches are taken by the packet's hull: per axis, the
//! earliest near-plane and the latest far-plane crossing of any lane,
//! from the least and the greatest reciprocal direction (one product
//! each, eight children tested at once). In a leaf (a brick, or a solid
//! cube) each lane keeps its own crossing times, computed as the scalar
//! walk computes every crossing, `(plane - origin) * inv_dir`, a child's
//! slabs being its parent's planes on one side and the midplanes on the
//! other; a child enters the lanes that enter it, after the hull has
//! skipped those no lane can.
//!
//! # Why the hits are the scalar walk's, bit for bit
//! The walk is in a cell from the key that enters it (the latest of its
//! near-plane crossings, ties to the higher axis) until the key that
//! leaves it (the earliest far-plane crossing, ties to the lower axis),
//! and visits it exactly when the first comes before the second. A
//! voxel whose latest near crossing is strictly before its earliest far
//! one is visited; one where they are equal is decided here by no rule:
//! its lane goes back to the caller, who walks it alone. Only packets
//! whose origin lies outside the occupied box are taken, so every solid
//! voxel lies strictly ahead on one axis and its entry crossing is
//! positive: the walk's start keys (at or before 0) never decide it. A
//! box is entered by a lane whenever any of its cells is (its near
//! crossings are no later, its far ones no earlier), so no lane skips the
//! box of its hit; and since a ray's cells grow on every axis in flipped
//! coordinates, the octant order meets them in the walk's order: the
//! first solid voxel a lane finds is its hit.

use glam::{BVec3A, BVec4A, Vec3A, Vec4};

use crate::geom::{Face, Ray};
use crate::scene::{Hit, PACKET};
use crate::storage::octree::grid::pow2;
use crate::storage::octree::node::{brick_bit, child_offset, child_rank, Node, NodeKind, GROUP};
use crate::storage::octree::OctreeScene;

/// One quantity on a packet's 32 lanes: eight `Vec4`s (SSE or NEON
/// registers where glam has them, plain floats elsewhere).
type Wide = [Vec4; PACKET / 4];

/// Lanes whose direction has a reciprocal at least this large on some
/// axis go back to the caller: their crossing times could overflow.
const MAX_INV: f32 = 4_294_967_296.0;

/// A packet's shared origin and signs, and its lanes' reciprocals.
struct Packet {
    origin: Vec3A,
    /// The reciprocal direction per axis, per lane.
    inv: [Wide; 3],
    /// The least and the greatest reciprocal per axis over the lanes.
    inv_lo: Vec3A,
    inv_hi: Vec3A,
    /// The axes every lane moves down along.
    down: BVec3A,
    /// The same as bits (`x | y << 1 | z << 2`).
    flip: usize,
    /// The least far crossing of a cube a lane may enter: the caller's
    /// clear distance, and ahead of the origin (the least positive float
    /// when the clear distance is 0).
    floor: f32,
}

impl Packet {
    /// The planes of the cube of side `side` at `corner` that the lanes
    /// enter it by (near) and leave it by (far), per axis.
    #[inline(always)]
    fn slab_planes(&self, corner: Vec3A, side: f32) -> (Vec3A, Vec3A) {
        let (low, high) = (corner, corner + side);
        (
            Vec3A::select(self.down, high, low),
            Vec3A::select(self.down, low, high),
        )
    }

    /// The earliest and the latest time at which any lane crosses each
    /// axis' plane of `planes`: the crossings `(plane - origin) * inv`
    /// of the least and the greatest reciprocal, as rounding keeps the
    /// order of products by one factor.
    #[inline(always)]
    fn spans(&self, planes: Vec3A) -> (Vec3A, Vec3A) {
        let from_origin = planes - self.origin;
        let ahead = from_origin.cmpge(Vec3A::ZERO);
        let (by_lo, by_hi) = (from_origin * self.inv_lo, from_origin * self.inv_hi);
        (
            Vec3A::select(ahead, by_lo, by_hi),
            Vec3A::select(ahead, by_hi, by_lo),
        )
    }
}

/// What the packet's lanes may do in a cube: per axis, the earliest near
/// crossing and the latest far crossing of any lane.
#[derive(Clone, Copy)]
struct Hull {
    near: Vec3A,
    far: Vec3A,
}

/// Bit `i` of `octants` (a bit per octant) at bit `i ^ flip`: the octants
/// in the order of a walk whose axes in `flip` run down.
#[inline(always)]
fn in_flipped_order(octants: u8, flip: usize) -> u8 {
    let mut bits = octants;
    if flip & 1 != 0 {
        bits = (bits & 0x55) << 1 | (bits & 0xaa) >> 1;
    }
    if flip & 2 != 0 {
        bits = (bits & 0x33) << 2 | (bits & 0xcc) >> 2;
    }
    if flip & 4 != 0 {
        bits = bits.rotate_left(4);
    }
    bits
}

/// Lanes `i` of four where bit 0 of `i` is set, and bit 1: the children
/// beyond the midplane of x, and of y, among four of one z half.
const BEYOND_X: BVec4A = BVec4A::new(false, true, false, true);
const BEYOND_Y: BVec4A = BVec4A::new(false, false, true, true);

impl Hull {
    /// The hull of child `i` (its octant with the down-moving axes
    /// flipped: bit `a` set, beyond the midplane of axis `a`), whose
    /// midplanes the lanes cross from `mid_early` to `mid_late`.
    #[inline(always)]
    fn child(self, i: usize, mid_early: Vec3A, mid_late: Vec3A) -> Hull {
        let beyond = BVec3A::new(i & 1 != 0, i & 2 != 0, i & 4 != 0);
        Hull {
            near: Vec3A::select(beyond, mid_early, self.near),
            far: Vec3A::select(beyond, self.far, mid_late),
        }
    }

    /// [`Hull::entered`] for the eight children at once: bit `i` for child
    /// `i` ([`Hull::child`]).
    #[inline(always)]
    fn children_entered(self, mid_early: Vec3A, mid_late: Vec3A, floor: f32) -> u8 {
        let pick = |beyond, (near, mid): (f32, f32)| {
            Vec4::select(beyond, Vec4::splat(mid), Vec4::splat(near))
        };
        let near_xy = pick(BEYOND_X, (self.near.x, mid_early.x))
            .max(pick(BEYOND_Y, (self.near.y, mid_early.y)));
        let far_xy =
            pick(BEYOND_X, (mid_late.x, self.far.x)).min(pick(BEYOND_Y, (mid_late.y, self.far.y)));
        let floor = Vec4::splat(floor);
        let half = |near_z: f32, far_z: f32| {
            let (near, far) = (
                near_xy.max(Vec4::splat(near_z)),
                far_xy.min(Vec4::splat(far_z)),
            );
            (near.cmple(far) & far.cmpge(floor)).bitmask() as u8
        };
        half(self.near.z, mid_late.z) | half(mid_early.z, self.far.z) << 4
    }

    /// Whether some lane may enter the cube at or after `floor`: never
    /// false when a lane's own crossings enter it (each lane's latest near
    /// crossing is no earlier, its earliest far one no later).
    #[inline(always)]
    fn entered(self, floor: f32) -> bool {
        let far = self.far.min_element();
        self.near.max_element() <= far && far >= floor
    }
}

/// The crossing times of a cube's near and far planes per axis, per lane.
#[derive(Clone, Copy)]
struct Slabs<'a> {
    near: [&'a Wide; 3],
    far: [&'a Wide; 3],
}

/// The times at which the lanes cross the plane at `plane` of `axis`.
#[inline(always)]
fn crossings(packet: &Packet, axis: usize, plane: f32) -> Wide {
    let from_origin = Vec4::splat(plane - packet.origin[axis]);
    packet.inv[axis].map(|inv| from_origin * inv)
}

/// The lanes (bits) whose ray may enter the cube of `slabs` at or after
/// the clear distance: those whose latest near crossing is no later than
/// their earliest far one, which is at least `floor` ([`Packet::floor`]).
/// Never leaves out a lane that visits one of the cube's cells.
#[inline(always)]
fn entering(slabs: &Slabs, floor: f32) -> u32 {
    let floor = Vec4::splat(floor);
    let mut lanes = 0;
    for k in 0..PACKET / 4 {
        let (near, far) = latest_and_earliest(slabs, k);
        let enters = near.cmple(far) & far.cmpge(floor);
        lanes |= enters.bitmask() << (4 * k);
    }
    lanes
}

/// Lanes `4k..4k + 4`' latest near crossing and earliest far crossing.
#[inline(always)]
fn latest_and_earliest(slabs: &Slabs, k: usize) -> (Vec4, Vec4) {
    let [n0, n1, n2] = slabs.near;
    let [f0, f1, f2] = slabs.far;
    (n0[k].max(n1[k]).max(n2[k]), f0[k].min(f1[k]).min(f2[k]))
}

/// A voxel's lanes: those that surely visit it (entry strictly before
/// exit, ahead of the origin), those the order of equal keys decides, and
/// for each lane its entry time and whether it enters through a plane of
/// z, and else of y (the latest near crossing, ties to the highest axis:
/// the walk's key).
struct Visits {
    sure: u32,
    tied: u32,
    entry: Wide,
    through_z: u32,
    through_y: u32,
}

/// [`Visits`] of the voxel whose crossings are `slabs`.
#[inline(always)]
fn visiting(slabs: &Slabs) -> Visits {
    let mut visits = Visits {
        sure: 0,
        tied: 0,
        entry: [Vec4::ZERO; PACKET / 4],
        through_z: 0,
        through_y: 0,
    };
    for k in 0..PACKET / 4 {
        let (near, far) = latest_and_earliest(slabs, k);
        let ahead: BVec4A = near.cmpgt(Vec4::ZERO);
        let shift = 4 * k;
        visits.sure |= (near.cmplt(far) & ahead).bitmask() << shift;
        visits.tied |= (near.cmpeq(far) | (near.cmple(far) & !ahead)).bitmask() << shift;
        visits.entry[k] = near;
        visits.through_z |= slabs.near[2][k].cmpeq(near).bitmask() << shift;
        visits.through_y |= slabs.near[1][k].cmpeq(near).bitmask() << shift;
    }
    visits
}

/// The octants (a bit each) for which `is` holds.
#[inline(always)]
fn present(is: impl Fn(usize) -> bool) -> u8 {
    (0..8).fold(0, |bits, octant| bits | u8::from(is(octant)) << octant)
}

/// The set bits of `lanes`, lowest first.
#[inline(always)]
fn bits(mut lanes: u32) -> impl Iterator<Item = usize> {
    core::iter::from_fn(move || {
        let lane = lanes.trailing_zeros() as usize;
        lanes &= lanes.wrapping_sub(1);
        (lane < 32).then_some(lane)
    })
}

/// Lane `lane` of `wide`.
#[inline(always)]
fn lane(wide: &Wide, lane: usize) -> f32 {
    wide[lane / 4][lane % 4]
}

/// What a packet's walk hands back: each lane's hit, and the lanes it
/// could not decide.
struct Found<'h> {
    hits: &'h mut [Option<Hit>; PACKET],
    undecided: u32,
}

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> OctreeScene<N, M> {
    /// [`crate::Scene::trace_packet`] for the octree: the lanes from the
    /// packet's first ray's origin whose direction moves along every axis
    /// with its signs, when that origin lies outside the occupied box.
    pub(super) fn packet(
        &self,
        rays: &[Ray; PACKET],
        clear: f32,
        hits: &mut [Option<Hit>; PACKET],
    ) -> u32 {
        let (lo, hi) = (self.occupied.min.as_vec3a(), self.occupied.max.as_vec3a());
        let (origin, first_dir, _) = rays[0].lanes();
        let outside = (origin.cmplt(lo) | origin.cmpgt(hi)).any();
        if self.occupied.is_empty() || !outside || clear.is_nan() || clear == f32::INFINITY {
            return 0;
        }
        let down = first_dir.cmplt(Vec3A::ZERO);
        let mut inv = [[Vec4::ZERO; PACKET / 4]; 3];
        let (mut inv_lo, mut inv_hi) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY);
        let mut taken = 0u32;
        for (i, ray) in rays.iter().enumerate() {
            let (o, dir, inv_dir) = ray.lanes();
            let moving = dir.cmpne(Vec3A::ZERO) & inv_dir.abs().cmplt(Vec3A::splat(MAX_INV));
            let same = o.to_array().map(f32::to_bits) == origin.to_array().map(f32::to_bits);
            if same && moving.all() && dir.cmplt(Vec3A::ZERO).bitmask() == down.bitmask() {
                taken |= 1 << i;
                inv_lo = inv_lo.min(inv_dir);
                inv_hi = inv_hi.max(inv_dir);
            }
            for (axis, wide) in inv.iter_mut().enumerate() {
                wide[i / 4][i % 4] = inv_dir[axis];
            }
        }
        if taken == 0 {
            return 0;
        }
        let packet = Packet {
            origin,
            inv,
            inv_lo,
            inv_hi,
            down,
            flip: down.bitmask() as usize,
            floor: clear.max(f32::from_bits(1)),
        };
        let mut found = Found { hits, undecided: 0 };
        let (corner, log) = (self.bounds.min.as_vec3a(), self.root_size.trailing_zeros());
        let (near, far) = packet.slab_planes(corner, self.root_size as f32);
        let hull = Hull {
            near: packet.spans(near).0,
            far: packet.spans(far).1,
        };
        let done = if hull.entered(packet.floor) {
            self.node(&packet, self.root, corner, log, hull, taken, &mut found)
        } else {
            0
        };
        // Lanes that entered nothing, or left without a hit, missed.
        for i in 0..PACKET {
            if taken & !done >> i & 1 != 0 {
                found.hits[i] = None;
            }
        }
        taken & !found.undecided
    }

    /// Walks `lanes` through the node `node`, the cube of side 2^log at
    /// `corner`, which the packet may enter (`hull`): returns the lanes
    /// that ended in it (hit, or undecided). Branches are taken by the
    /// packet's hull, leaves by each lane's crossings.
    #[allow(clippy::too_many_arguments)]
    fn node(
        &self,
        packet: &Packet,
        node: Node,
        corner: Vec3A,
        log: u32,
        hull: Hull,
        mut lanes: u32,
        found: &mut Found,
    ) -> u32 {
        let NodeKind::Branch { children, first } = node.kind() else {
            return self.leaf(packet, node, corner, log, hull, lanes, found);
        };
        let nodes = self.nodes.as_ref();
        let half = pow2(log - 1);
        let (mid_early, mid_late) = packet.spans(corner + half);
        // The children in the order the rays meet them (`i`: the octant
        // with the down-moving axes flipped), present and entered.
        let mut order = hull.children_entered(mid_early, mid_late, packet.floor)
            & in_flipped_order(children, packet.flip);
        let mut ended = 0;
        while order != 0 {
            let i = order.trailing_zeros() as usize;
            order &= order - 1;
            let octant = i ^ packet.flip;
            let child = hull.child(i, mid_early, mid_late);
            let at = corner + child_offset(octant).as_vec3a() * half;
            let index = first + child_rank(children, octant as u32);
            let node = nodes[index as usize];
            let done = self.node(packet, node, at, log - 1, child, lanes, found);
            ended |= done;
            lanes &= !done;
            if lanes == 0 {
                break;
            }
        }
        ended
    }

    /// Walks `lanes` through the leaf `node` (a brick or a solid cube, of
    /// side 2^log at `corner`, the packet's hull `hull`) by each lane's
    /// crossings, children the hull misses skipped first.
    #[allow(clippy::too_many_arguments)]
    fn leaf(
        &self,
        packet: &Packet,
        node: Node,
        corner: Vec3A,
        log: u32,
        hull: Hull,
        lanes: u32,
        found: &mut Found,
    ) -> u32 {
        let (near, far) = packet.slab_planes(corner, pow2(log));
        let near = [0, 1, 2].map(|axis| crossings(packet, axis, near[axis]));
        let far = [0, 1, 2].map(|axis| crossings(packet, axis, far[axis]));
        let slabs = &Slabs {
            near: [&near[0], &near[1], &near[2]],
            far: [&far[0], &far[1], &far[2]],
        };
        let lanes = entering(slabs, packet.floor) & lanes;
        if lanes == 0 {
            return 0;
        }
        let cube = (corner, log, hull);
        match node.kind() {
            NodeKind::Branch { .. } => 0,
            NodeKind::Solid(material) => self.solid(packet, cube, slabs, lanes, material, found),
            NodeKind::Brick {
                occupancy,
                materials,
            } => {
                let group_bit = |group: usize| brick_bit(child_offset(group) * 2);
                let groups = present(|group| occupancy & GROUP << group_bit(group) != 0);
                self.children(
                    packet,
                    cube,
                    groups,
                    slabs,
                    lanes,
                    |group, group_cube, slabs, lanes| {
                        let bit = |voxel: usize| group_bit(group) + brick_bit(child_offset(voxel));
                        let voxels = present(|voxel| occupancy >> bit(voxel) & 1 != 0);
                        self.children(
                            packet,
                            group_cube,
                            voxels,
                            slabs,
                            lanes,
                            |voxel, (at, ..), slabs, lanes| {
                                let material =
                                    self.brick_material(occupancy, materials, bit(voxel));
                                self.voxel(packet, at, slabs, lanes, material, found)
                            },
                        )
                    },
                )
            }
        }
    }

    /// Walks `lanes` through a solid cube (`cube`: its corner, log2 of its
    /// side and the packet's hull; `slabs` its crossings), halved down to
    /// the voxel each lane enters first.
    fn solid(
        &self,
        packet: &Packet,
        cube: (Vec3A, u32, Hull),
        slabs: &Slabs,
        lanes: u32,
        material: u8,
        found: &mut Found,
    ) -> u32 {
        if cube.1 == 0 {
            return self.voxel(packet, cube.0, slabs, lanes, material, found);
        }
        self.children(packet, cube, 0xff, slabs, lanes, |_, cube, slabs, lanes| {
            self.solid(packet, cube, slabs, lanes, material, found)
        })
    }

    /// Shows `enter(octant, child, slabs, lanes)` each child of `cube` (its
    /// corner, log2 of its side and the packet's hull; `slabs` its
    /// crossings) that is in `present` (a bit per octant), that the hull
    /// may enter and that some of `lanes` enter, in the order the packet's
    /// rays meet them, until every lane has ended; `enter` returns the
    /// lanes that ended in the child. Returns the lanes that ended.
    #[inline(always)]
    fn children(
        &self,
        packet: &Packet,
        (corner, log, hull): (Vec3A, u32, Hull),
        present: u8,
        slabs: &Slabs,
        mut lanes: u32,
        mut enter: impl FnMut(usize, (Vec3A, u32, Hull), &Slabs, u32) -> u32,
    ) -> u32 {
        let half = pow2(log - 1);
        let (mid_early, mid_late) = packet.spans(corner + half);
        let mut order = hull.children_entered(mid_early, mid_late, packet.floor)
            & in_flipped_order(present, packet.flip);
        if order == 0 {
            return 0;
        }
        let mid = [0, 1, 2].map(|axis| crossings(packet, axis, corner[axis] + half));
        let mut ended = 0;
        while order != 0 {
            let i = order.trailing_zeros() as usize;
            order &= order - 1;
            let octant = i ^ packet.flip;
            let mut child = Slabs {
                near: slabs.near,
                far: slabs.far,
            };
            for (axis, mid) in mid.iter().enumerate() {
                if i >> axis & 1 == 0 {
                    child.far[axis] = mid;
                } else {
                    child.near[axis] = mid;
                }
            }
            let entering = entering(&child, packet.floor) & lanes;
            if entering == 0 {
                continue;
            }
            let at = corner + child_offset(octant).as_vec3a() * half;
            let cube = (at, log - 1, hull.child(i, mid_early, mid_late));
            let done = enter(octant, cube, &child, entering);
            ended |= done;
            lanes &= !done;
            if lanes == 0 {
                break;
            }
        }
        ended
    }

    /// Ends the lanes of `lanes` that visit the solid voxel at `corner`
    /// (crossings `slabs`) with a hit on it, and those that might with no
    /// answer; returns them.
    fn voxel(
        &self,
        packet: &Packet,
        corner: Vec3A,
        slabs: &Slabs,
        lanes: u32,
        material: u8,
        found: &mut Found,
    ) -> u32 {
        let visits = visiting(slabs);
        let (hit, undecided) = (visits.sure & lanes, visits.tied & lanes);
        found.undecided |= undecided;
        // Every lane's hit is on one voxel, through one of three faces.
        let Some(voxel) = self.palette.voxel(material) else {
            for i in bits(hit) {
                found.hits[i] = None;
            }
            return hit | undecided;
        };
        let pos = corner.as_ivec3();
        let faces = [0, 1, 2].map(|axis| Face::entered(axis, packet.flip >> axis & 1 == 0));
        for i in bits(hit) {
            let axis = if visits.through_z >> i & 1 != 0 {
                2
            } else {
                usize::from(visits.through_y >> i & 1 != 0)
            };
            found.hits[i] = Some(Hit {
                pos,
                face: Some(faces[axis]),
                t: lane(&visits.entry, i),
                material,
                voxel,
            });
        }
        hit | undecided
    }
}

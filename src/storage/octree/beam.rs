//! The beam: one conservative walk of the tree per tile of primary rays.
//!
//! Every ray of a tile lies in a frustum from the camera (`Frustum`).
//! Visiting the nodes that may meet that frustum nearest first, the
//! smallest distance a ray of the frustum must go to reach a non-empty box
//! bounds every ray's hit from below: a ray enters a voxel on its boundary,
//! and the voxel lies in the box. That distance is at least the box's from
//! the apex, and at least its gap on an axis over the steepest the
//! frustum's rays run along that axis. The rays
//! then begin their exact walks there (`WalkRay::begin`) and find the same
//! hit as from the camera, without repeating the descent through the empty
//! space the whole tile shares (the idea of Laine & Karras 2010, section 5).
//!
//! Boxes are tested against the frustum's side planes (with a slack for
//! rounding), and a brick by its 2x2x2 groups and then by the solid voxels
//! of each group that passes, so the answer can be early but never late.
//! Voxels rather than groups as the leaves: a group can count a voxel's
//! diagonal before its solid voxels, more along shallow rays (whose axis
//! bound divides the gap by a small component), and the frustum may meet
//! it only where it is empty.

use glam::{IVec3, Vec3};

use crate::frustum::Frustum;
use crate::geom::{gap_length, gap_to_box, IAabb};
use crate::math::floor_cell;
use crate::storage::octree::node::{brick_bit, child_offset, child_rank, Node, NodeKind, GROUP};
use crate::storage::octree::OctreeScene;

/// Levels of the walk: the largest root (side 2^23) has branches at depths
/// 0 to 20 above its side-4 bricks.
const DEPTH: usize = 21;

/// A branch being walked: its children and cube, and the next child (in
/// nearest-first order) to visit.
#[derive(Clone, Copy)]
struct Level {
    children: u8,
    first: u32,
    corner: IVec3,
    next: u32,
}

/// How much earlier than the nearest box's distance rays start: a ray's
/// crossing times are rounded (a few units in the last place), the box
/// distance too; 1e-5 relative is a hundred times that.
const MARGIN: f32 = 1.0 - 1e-5;

impl<N: AsRef<[Node]>, M: AsRef<[u8]>> OctreeScene<N, M> {
    /// A distance before which no ray inside `frustum` hits a voxel (0 when
    /// the apex touches a solid voxel, `+inf` when the frustum meets
    /// none). Allocates nothing; visits nodes nearest first and skips every
    /// box no closer than the best found.
    pub(crate) fn beam_distance(&self, frustum: &Frustum) -> f32 {
        if self.occupied.is_empty() {
            return f32::INFINITY;
        }
        // A camera touching a solid voxel (inside it, or on its surface):
        // the answer is 0, which the walk below would also reach, but only
        // after descending to that voxel for every tile.
        if self.touches_solid(frustum.apex) {
            return 0.0;
        }
        let nodes = self.nodes.as_ref();
        let min = self.bounds.min;
        let root_log = self.root_size.trailing_zeros();
        // Children nearest the apex first: mirror the octant order on the
        // axes the frustum runs down (its normals sum to a vector inside it).
        let inward =
            frustum.normals[0] + frustum.normals[1] + frustum.normals[2] + frustum.normals[3];
        let down = inward.cmplt(Vec3::ZERO);
        let near_first = u32::from(down.x) | u32::from(down.y) << 1 | u32::from(down.z) << 2;
        let mut best = f32::INFINITY;
        let mut levels = [Level {
            children: 0,
            first: 0,
            corner: IVec3::ZERO,
            next: 0,
        }; DEPTH];
        let mut depth = 0;
        // The node to look at, its cube (corner relative to `min`, side
        // 2^log); then the next one comes from the deepest unfinished branch.
        let mut visit = Some((self.root, IVec3::ZERO, root_log));
        loop {
            if let Some((node, corner, log)) = visit.take() {
                if let Some(distance) = self.reach(frustum, min + corner, 1 << log, best) {
                    match node.kind() {
                        NodeKind::Solid(_) => best = distance,
                        NodeKind::Brick { occupancy, .. } => {
                            let corner = min + corner;
                            let reach =
                                self.brick_reach(frustum, corner, occupancy, best, near_first);
                            best = best.min(reach);
                        }
                        NodeKind::Branch { children, first } if depth < DEPTH => {
                            levels[depth] = Level {
                                children,
                                first,
                                corner,
                                next: 0,
                            };
                            depth += 1;
                        }
                        // Deeper than any tree the builder makes: the whole
                        // cube counts as an obstacle.
                        NodeKind::Branch { .. } => best = distance,
                    }
                }
            }
            if best == 0.0 || depth == 0 {
                break;
            }
            let level = &mut levels[depth - 1];
            if level.next == 8 {
                depth -= 1;
                continue;
            }
            let octant = level.next ^ near_first;
            level.next += 1;
            if level.children & (1 << octant) == 0 {
                continue;
            }
            let rank = child_rank(level.children, octant);
            // Always present: the builder's invariant, which the tracer
            // relies on too.
            let Some(&child) = nodes.get((level.first + rank) as usize) else {
                continue;
            };
            let child_log = root_log - depth as u32;
            let offset = child_offset(octant as usize) << child_log;
            visit = Some((child, level.corner + offset, child_log));
        }
        best * MARGIN
    }

    /// Whether a solid voxel touches `point` (holds it, or has it on its
    /// surface). Up to eight cells touch a point: on an axis where it lies
    /// on a plane, the cells on both sides.
    pub(super) fn touches_solid(&self, point: Vec3) -> bool {
        let cell = IVec3::new(
            floor_cell(point.x),
            floor_cell(point.y),
            floor_cell(point.z),
        );
        let on_plane = cell.as_vec3().cmpeq(point);
        let below = IVec3::select(on_plane, IVec3::ONE, IVec3::ZERO);
        (0..8).any(|corner| {
            let pick = child_offset(corner);
            // (Saturating: a saturated coordinate lies outside every volume.)
            let touching = IVec3::new(
                cell.x.saturating_sub(pick.x),
                cell.y.saturating_sub(pick.y),
                cell.z.saturating_sub(pick.z),
            );
            (pick & !below) == IVec3::ZERO && self.material(touching) != 0
        })
    }

    /// The nearest distance at which a ray of the frustum may reach one of
    /// a brick's solid voxels, if closer than `best` (else `best`): the
    /// voxels of each occupied 2x2x2 group that may itself meet the frustum
    /// closer than `best`. Groups and voxels go in the frustum's
    /// nearest-first octant order `near_first`, so that the first voxel
    /// found tends to be the nearest and the rest fail the distance test
    /// before the plane tests.
    fn brick_reach(
        &self,
        frustum: &Frustum,
        corner: IVec3,
        occupancy: u64,
        mut best: f32,
        near_first: u32,
    ) -> f32 {
        for group in 0..8 {
            let local = child_offset((group ^ near_first) as usize) * 2;
            if occupancy & GROUP << brick_bit(local) == 0
                || self.reach(frustum, corner + local, 2, best).is_none()
            {
                continue;
            }
            for voxel in 0..8 {
                let at = local + child_offset((voxel ^ near_first) as usize);
                if occupancy >> brick_bit(at) & 1 == 0 {
                    continue;
                }
                if let Some(d) = self.reach(frustum, corner + at, 1, best) {
                    best = d;
                }
            }
        }
        best
    }

    /// How far along itself a ray of the frustum has gone, at least, when it
    /// reaches the cube `[corner, corner + side)` clipped to the occupied
    /// box, if the cube may meet the frustum and that is closer than `best`:
    /// the distance from the apex to the box, or, when larger, the gap to
    /// the box on one axis over the largest component a ray of the frustum
    /// has on it ([`Frustum::steepest`]). The second bound keeps a wide box
    /// that the frustum meets only far away, such as the solid ground
    /// straight below a camera looking at the horizon, from counting at its
    /// nearest point.
    fn reach(&self, frustum: &Frustum, corner: IVec3, side: i32, best: f32) -> Option<f32> {
        let cube = IAabb::new(corner, corner + side).intersect(&self.occupied);
        if cube.is_empty() {
            return None;
        }
        let (lo, hi) = (cube.min.as_vec3(), cube.max.as_vec3());
        let gap = gap_to_box(frustum.apex, lo, hi);
        // (`Frustum::through` makes `steepest` at least the slack: no 0/0.)
        let along = (gap / frustum.steepest).max_element();
        let distance = gap_length(gap).max(along);
        if distance >= best {
            return None;
        }
        frustum.may_meet_box(lo, hi).then_some(distance)
    }
}

//! A packet's lanes: what the octree's packet walk (`packet.rs`) asks of
//! its 32 rays, on glam's four-lane vectors. The packet's hull (per axis,
//! the earliest near and the latest far crossing of any lane) decides
//! which children the packet may enter; each lane's own crossing times
//! (`Slabs`) decide which lanes enter a leaf's child, and which visit a
//! voxel. Every time is a crossing the scalar walk computes the same way,
//! `(plane - origin) * inv_dir`.

use glam::{BVec3A, BVec4A, Mat4, Vec3A, Vec4};

use crate::geom::Ray;
use crate::scene::{Reach, PACKET};
use crate::storage::octree::packet::origins::{Origins, Wide};

/// Lanes whose direction has a reciprocal at least this large on some
/// axis go back to the caller: their crossing times could overflow.
pub(super) const MAX_INV: f32 = 4_294_967_296.0;

/// A packet's lanes: their origins and reciprocals, and what they share.
pub(super) struct Packet<O> {
    /// Where the lanes start.
    pub(super) origins: O,
    /// The least and the greatest origin per axis over the lanes.
    pub(super) origin_lo: Vec3A,
    pub(super) origin_hi: Vec3A,
    /// The reciprocal direction per axis, per lane.
    pub(super) inv: [Wide; 3],
    /// The least and the greatest reciprocal per axis over the lanes.
    pub(super) inv_lo: Vec3A,
    pub(super) inv_hi: Vec3A,
    /// The axes every lane moves down along.
    pub(super) down: BVec3A,
    /// The same as bits (`x | y << 1 | z << 2`).
    pub(super) flip: usize,
    /// The stretch of the lanes a cube must meet to be entered.
    pub(super) span: Span,
}

impl<O: Origins> Packet<O> {
    /// The packet of the lanes of `rays` it can take, those lanes (a bit
    /// each), and whether every lane of `lanes` starts at the first one's
    /// origin: of the lanes in `lanes`, the rays that move along every
    /// axis, with the first one's signs and reciprocals below
    /// [`MAX_INV`], and from the first one's origin unless
    /// [`Origins::EACH`], traced over `reach`.
    #[inline]
    pub(super) fn of(rays: &[Ray; PACKET], lanes: u32, reach: Reach) -> (Self, u32, bool) {
        let first = (lanes.trailing_zeros() as usize).min(PACKET - 1);
        let (first_origin, first_dir, _) = rays[first].vectors();
        let down = first_dir.cmplt(Vec3A::ZERO);
        let mut origin = [[Vec4::ZERO; PACKET / 4]; 3];
        let mut inv = [[Vec4::ZERO; PACKET / 4]; 3];
        let (mut origin_lo, mut origin_hi) = ([Vec4::INFINITY; 3], [Vec4::NEG_INFINITY; 3]);
        let (mut inv_lo, mut inv_hi) = ([Vec4::INFINITY; 3], [Vec4::NEG_INFINITY; 3]);
        let (mut taken, mut same_origin) = (0u32, 0u32);
        for k in 0..PACKET / 4 {
            // Four rays' origins, directions and reciprocals, per axis.
            let quad = &rays[4 * k..4 * k + 4];
            let per_axis = |part: fn(&Ray) -> Vec3A| {
                let [a, b, c, d] = core::array::from_fn(|j| part(&quad[j]).extend(0.0));
                let rows = Mat4::from_cols(a, b, c, d).transpose();
                [rows.x_axis, rows.y_axis, rows.z_axis]
            };
            let (o, dir, v) = (
                per_axis(|r| r.vectors().0),
                per_axis(|r| r.vectors().1),
                per_axis(|r| r.vectors().2),
            );
            let (mut ok, mut same) = (BVec4A::splat(true), 0xf);
            for axis in 0..3 {
                let moving =
                    dir[axis].cmpne(Vec4::ZERO) & v[axis].abs().cmplt(Vec4::splat(MAX_INV));
                let signs =
                    dir[axis].cmplt(Vec4::ZERO) ^ BVec4A::splat(down.bitmask() >> axis & 1 != 0);
                ok &= moving & !signs;
                // The same bits: equal, and zeros of the same sign.
                let first = first_origin[axis];
                let first_sign = if first.is_sign_negative() { 0xf } else { 0 };
                let equal = o[axis].cmpeq(Vec4::splat(first)).bitmask();
                same &= equal & !(o[axis].is_negative_bitmask() ^ first_sign);
            }
            let asked = lanes >> (4 * k) & 0xf;
            let take = ok.bitmask() & asked & if O::EACH { 0xf } else { same };
            taken |= take << (4 * k);
            same_origin |= same << (4 * k);
            let take = BVec4A::new(take & 1 != 0, take & 2 != 0, take & 4 != 0, take & 8 != 0);
            for axis in 0..3 {
                origin_lo[axis] = origin_lo[axis].min(Vec4::select(take, o[axis], Vec4::INFINITY));
                origin_hi[axis] =
                    origin_hi[axis].max(Vec4::select(take, o[axis], Vec4::NEG_INFINITY));
                inv_lo[axis] = inv_lo[axis].min(Vec4::select(take, v[axis], Vec4::INFINITY));
                inv_hi[axis] = inv_hi[axis].max(Vec4::select(take, v[axis], Vec4::NEG_INFINITY));
                origin[axis][k] = o[axis];
                inv[axis][k] = v[axis];
            }
        }
        let least = |w: [Vec4; 3]| Vec3A::from_array(w.map(Vec4::min_element));
        let most = |w: [Vec4; 3]| Vec3A::from_array(w.map(Vec4::max_element));
        let packet = Self {
            origins: O::of(origin, first_origin),
            origin_lo: least(origin_lo),
            origin_hi: most(origin_hi),
            inv,
            inv_lo: least(inv_lo),
            inv_hi: most(inv_hi),
            down,
            flip: down.bitmask() as usize,
            span: Span {
                floor: reach.clear.max(f32::from_bits(1)),
                ceiling: reach.max,
            },
        };
        (packet, taken, lanes & !same_origin == 0)
    }

    /// The planes of the cube of side `side` at `corner` that the lanes
    /// enter it by (near) and leave it by (far), per axis.
    #[inline(always)]
    pub(super) fn slab_planes(&self, corner: Vec3A, side: f32) -> (Vec3A, Vec3A) {
        let (low, high) = (corner, corner + side);
        (
            Vec3A::select(self.down, high, low),
            Vec3A::select(self.down, low, high),
        )
    }

    /// The earliest and the latest time at which any lane crosses each
    /// axis' plane of `planes`. A lane's crossing `(plane - origin) *
    /// inv` only grows or only shrinks with each factor, and rounding
    /// keeps that order, so the extremes are among the products of the
    /// ends of the two ranges.
    #[inline(always)]
    pub(super) fn spans(&self, planes: Vec3A) -> (Vec3A, Vec3A) {
        if !O::EACH {
            // One origin: the order of one factor, the reciprocals', or
            // its reverse behind the origin.
            let from_origin = planes - self.origin_lo;
            let ahead = from_origin.cmpge(Vec3A::ZERO);
            let (by_lo, by_hi) = (from_origin * self.inv_lo, from_origin * self.inv_hi);
            return (
                Vec3A::select(ahead, by_lo, by_hi),
                Vec3A::select(ahead, by_hi, by_lo),
            );
        }
        let (least, most) = (planes - self.origin_hi, planes - self.origin_lo);
        let (a, b) = (least * self.inv_lo, least * self.inv_hi);
        let (c, d) = (most * self.inv_lo, most * self.inv_hi);
        (a.min(b).min(c.min(d)), a.max(b).max(c.max(d)))
    }
}

/// The stretch of a lane's ray a cube must meet to be entered: a far
/// crossing at least `floor` (the caller's clear distance, and ahead of
/// the origin: the least positive float when that is 0), a near crossing
/// at most `ceiling` (the reach's farthest hit: a voxel entered later is
/// no hit, nor is any voxel behind it).
#[derive(Clone, Copy)]
pub(super) struct Span {
    pub(super) floor: f32,
    pub(super) ceiling: f32,
}

/// What the packet's lanes may do in a cube: per axis, the earliest near
/// crossing and the latest far crossing of any lane.
#[derive(Clone, Copy)]
pub(super) struct Hull {
    pub(super) near: Vec3A,
    pub(super) far: Vec3A,
}

/// Bit `i` of `octants` (a bit per octant) at bit `i ^ flip`: the octants
/// in the order of a walk whose axes in `flip` run down.
#[inline(always)]
pub(super) fn in_flipped_order(octants: u8, flip: usize) -> u8 {
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

/// Per child `i` (bit `a` set: beyond the midplane of axis `a`), the
/// axes it lies beyond: a table, as building the mask from bits costs
/// more than the rest of [`Hull::child`].
const BEYOND: [BVec3A; 8] = {
    let mut masks = [BVec3A::FALSE; 8];
    let mut i = 0;
    while i < 8 {
        masks[i] = BVec3A::new(i & 1 != 0, i & 2 != 0, i & 4 != 0);
        i += 1;
    }
    masks
};

/// Lanes `i` of four where bit 0 of `i` is set, and bit 1: the children
/// beyond the midplane of x, and of y, among four of one z half.
pub(super) const BEYOND_X: BVec4A = BVec4A::new(false, true, false, true);
pub(super) const BEYOND_Y: BVec4A = BVec4A::new(false, false, true, true);

impl Hull {
    /// The hull of child `i` (its octant with the down-moving axes
    /// flipped: bit `a` set, beyond the midplane of axis `a`), whose
    /// midplanes the lanes cross from `mid_early` to `mid_late`.
    #[inline(always)]
    pub(super) fn child(self, i: usize, mid_early: Vec3A, mid_late: Vec3A) -> Hull {
        let beyond = BEYOND[i & 7];
        Hull {
            near: Vec3A::select(beyond, mid_early, self.near),
            far: Vec3A::select(beyond, self.far, mid_late),
        }
    }

    /// [`Hull::entered`] for the eight children at once: bit `i` for child
    /// `i` ([`Hull::child`]).
    #[inline(always)]
    pub(super) fn children_entered(self, mid_early: Vec3A, mid_late: Vec3A, span: Span) -> u8 {
        let pick = |beyond, (near, mid): (f32, f32)| {
            Vec4::select(beyond, Vec4::splat(mid), Vec4::splat(near))
        };
        let near_xy = pick(BEYOND_X, (self.near.x, mid_early.x))
            .max(pick(BEYOND_Y, (self.near.y, mid_early.y)));
        let far_xy =
            pick(BEYOND_X, (mid_late.x, self.far.x)).min(pick(BEYOND_Y, (mid_late.y, self.far.y)));
        let (floor, ceiling) = (Vec4::splat(span.floor), Vec4::splat(span.ceiling));
        let half = |near_z: f32, far_z: f32| {
            let (near, far) = (
                near_xy.max(Vec4::splat(near_z)),
                far_xy.min(Vec4::splat(far_z)),
            );
            (near.cmple(far.min(ceiling)) & far.cmpge(floor)).bitmask() as u8
        };
        half(self.near.z, mid_late.z) | half(mid_early.z, self.far.z) << 4
    }

    /// Whether some lane may enter the cube within `span`: never false
    /// when a lane's own crossings enter it (each lane's latest near
    /// crossing is no earlier, its earliest far one no later).
    #[inline(always)]
    pub(super) fn entered(self, span: Span) -> bool {
        let far = self.far.min_element();
        self.near.max_element() <= far.min(span.ceiling) && far >= span.floor
    }
}

/// The crossing times of a cube's near and far planes per axis, per lane.
#[derive(Clone, Copy)]
pub(super) struct Slabs<'a> {
    pub(super) near: [&'a Wide; 3],
    pub(super) far: [&'a Wide; 3],
}

/// The times at which the lanes cross the plane at `plane` of `axis`.
#[inline(always)]
pub(super) fn crossings<O: Origins>(packet: &Packet<O>, axis: usize, plane: f32) -> Wide {
    packet.origins.crossings(&packet.inv[axis], axis, plane)
}

/// The lanes of `lanes` (bits) whose ray may enter the cube of `slabs`
/// at or after the span's floor: those whose latest near crossing is no
/// later than their earliest far one, which is at least the floor. Never
/// leaves out a lane that visits one of the cube's cells. (The span's
/// ceiling is left to [`visiting`] and the hull: most packets have none.)
/// Only the four-lane groups holding one of `lanes` are computed: a voxel
/// of a far terrain covers few of a packet's pixels.
#[inline(always)]
pub(super) fn entering(slabs: &Slabs, span: Span, lanes: u32) -> u32 {
    let floor = Vec4::splat(span.floor);
    let mut entered = 0;
    for k in quads(lanes) {
        let (near, far) = latest_and_earliest(slabs, k);
        let enters = near.cmple(far) & far.cmpge(floor);
        entered |= enters.bitmask() << (4 * k);
    }
    entered & lanes
}

/// The four-lane groups (`k`: lanes `4k..4k + 4`) holding a lane of
/// `lanes`.
#[inline(always)]
pub(super) fn quads(lanes: u32) -> impl Iterator<Item = usize> {
    let any = lanes | lanes >> 1;
    let any = any | any >> 2;
    bits((0..PACKET / 4).fold(0, |q, k| q | (any >> (4 * k) & 1) << k))
}

/// Lanes `4k..4k + 4`' latest near crossing and earliest far crossing.
#[inline(always)]
pub(super) fn latest_and_earliest(slabs: &Slabs, k: usize) -> (Vec4, Vec4) {
    let [n0, n1, n2] = slabs.near;
    let [f0, f1, f2] = slabs.far;
    (n0[k].max(n1[k]).max(n2[k]), f0[k].min(f1[k]).min(f2[k]))
}

/// A voxel's lanes: those that surely visit it (entry strictly before
/// exit, ahead of the origin), those the order of equal keys decides, and
/// for each lane its entry time and whether it enters through a plane of
/// z, and else of y (the latest near crossing, ties to the highest axis:
/// the walk's key).
pub(super) struct Visits {
    pub(super) sure: u32,
    pub(super) tied: u32,
    pub(super) entry: Wide,
    pub(super) through_z: u32,
    pub(super) through_y: u32,
}

/// [`Visits`] of the voxel whose crossings are `slabs`, for the lanes of
/// `lanes` (the groups of four holding none are left out: their bits
/// clear, their entries 0). A lane entering it after `ceiling` neither
/// visits it nor ties: its hit would be out of reach, as would every
/// voxel's behind it.
#[inline(always)]
pub(super) fn visiting(slabs: &Slabs, lanes: u32, ceiling: f32) -> Visits {
    let mut visits = Visits {
        sure: 0,
        tied: 0,
        entry: [Vec4::ZERO; PACKET / 4],
        through_z: 0,
        through_y: 0,
    };
    let ceiling = Vec4::splat(ceiling);
    for k in quads(lanes) {
        let (near, far) = latest_and_earliest(slabs, k);
        let ahead: BVec4A = near.cmpgt(Vec4::ZERO);
        let within = near.cmple(ceiling);
        let shift = 4 * k;
        visits.sure |= (near.cmplt(far) & ahead & within).bitmask() << shift;
        let tied = near.cmpeq(far) | (near.cmple(far) & !ahead);
        visits.tied |= (tied & within).bitmask() << shift;
        visits.entry[k] = near;
        visits.through_z |= slabs.near[2][k].cmpeq(near).bitmask() << shift;
        visits.through_y |= slabs.near[1][k].cmpeq(near).bitmask() << shift;
    }
    visits
}

/// The octants (a bit each) for which `is` holds.
#[inline(always)]
pub(super) fn present(is: impl Fn(usize) -> bool) -> u8 {
    (0..8).fold(0, |bits, octant| bits | u8::from(is(octant)) << octant)
}

/// The set bits of `lanes`, lowest first.
#[inline(always)]
pub(super) fn bits(mut lanes: u32) -> impl Iterator<Item = usize> {
    core::iter::from_fn(move || {
        let lane = lanes.trailing_zeros() as usize;
        lanes &= lanes.wrapping_sub(1);
        (lane < 32).then_some(lane)
    })
}

/// Lane `lane` of `wide`.
#[inline(always)]
pub(super) fn lane(wide: &Wide, lane: usize) -> f32 {
    wide[lane / 4][lane % 4]
}

//! The lit look's occlusion rays in packets. They scatter over each face's
//! hemisphere, so a block's are gathered by the octant they point into (a
//! packet's lanes share their signs), each octant's bin traced
//! ([`trace_rays`]) whenever it holds a packet, where the block's
//! hits are close enough for their rays to cross the same nodes
//! ([`close`]). The answers are the lone walks', whichever way they were
//! found.

use glam::{IVec3, Vec3A};

use crate::geom::Ray;
use crate::render::shader::trace_rays;
use crate::scene::{Hit, Reach, Scene, WalkMemory, PACKET};

/// Occlusion rays waiting for a packet: rays into one octant, each with
/// the lane whose hit sent it.
#[derive(Clone, Copy)]
pub(super) struct Bin {
    rays: [Ray; PACKET],
    owners: [u8; PACKET],
    len: usize,
}

impl Bin {
    /// A block's bins, one per octant, empty (`filler` stands in the lanes
    /// no ray holds yet).
    #[inline]
    pub(super) fn octants(filler: Ray) -> [Bin; 8] {
        let (rays, owners) = ([filler; PACKET], [0; PACKET]);
        [Bin {
            rays,
            owners,
            len: 0,
        }; 8]
    }

    /// Traces the bin's rays over `reach`, from a copy of `memory`, and
    /// empties it: `open[lane]` counts the rays of `lane` that meet
    /// nothing, `together[lane]` those answered together.
    pub(super) fn trace<'s, S: Scene + ?Sized>(
        &mut self,
        scene: &'s S,
        reach: Reach,
        memory: &WalkMemory<'s>,
        (open, together): (&mut [u32], &mut [u32]),
    ) {
        if self.len == 0 {
            return;
        }
        let (lanes, memory) = (u32::MAX >> (PACKET - self.len), &mut memory.clone());
        let mut hits = [None; PACKET];
        let answered = trace_rays(scene, &self.rays, lanes, reach, memory, &mut hits);
        for (i, (hit, &owner)) in hits.iter().zip(&self.owners).take(self.len).enumerate() {
            open[usize::from(owner)] += u32::from(hit.is_none());
            together[usize::from(owner)] += answered >> i & 1;
        }
        self.len = 0;
    }
}

/// Puts `ray`, of the hit of lane `lane`, in the bin of `bins` for its
/// octant: that bin when it is full, to be traced.
#[inline]
pub(super) fn put(bins: &mut [Bin; 8], ray: Ray, lane: usize) -> Option<&mut Bin> {
    let bin = &mut bins[octant(ray.vectors().1)];
    (bin.rays[bin.len], bin.owners[bin.len]) = (ray, lane as u8);
    bin.len += 1;
    (bin.len == PACKET).then_some(bin)
}

/// The octant `dir` points into: bit `a` set when it moves down along axis
/// `a` (the sign rule of a packet's lanes).
#[inline]
fn octant(dir: Vec3A) -> usize {
    dir.cmplt(Vec3A::ZERO).bitmask() as usize
}

/// Whether the hits of a block lie within `reach` of one another on every
/// axis, so that their occlusion rays cross the same nodes: only then do
/// they pay in packets (benches/README.md).
#[inline]
pub(super) fn close(hits: &[Option<Hit>], reach: f32) -> bool {
    let (mut lo, mut hi) = (IVec3::MAX, IVec3::MIN);
    for hit in hits.iter().flatten() {
        lo = lo.min(hit.pos);
        hi = hi.max(hit.pos);
    }
    // No hit: nothing to trace either way.
    lo.cmpgt(hi).any() || (hi.as_vec3() - lo.as_vec3()).max_element() <= reach
}

//! The lit look's secondary rays in packets: the shadow and occlusion
//! rays of a packet of camera rays' hits, traced together
//! ([`Scene::trace_packet`]) before the hits are shaded. Shadow rays are
//! parallel and start at neighbouring hits: one packet. Occlusion rays
//! scatter over each face's hemisphere, so they are gathered by the
//! octant they point into (a packet's lanes share their signs), each
//! octant's bin traced whenever it holds a packet, where the block's
//! hits are close enough for their rays to cross the same nodes. The
//! lanes a packet leaves are traced alone ([`Scene::trace_lanes`]): the answers are
//! [`Lit::shade_sample`]'s, whichever way they were found.

use glam::{IVec3, Vec3A};

use crate::geom::Ray;
use crate::render::shader::lit::{occlusion_ray, Found, Lit};
use crate::scene::{Hit, Reach, Scene, WalkMemory, PACKET};

/// Occlusion rays waiting for a packet: rays into one octant, each with
/// the lane whose hit sent it.
#[derive(Clone, Copy)]
struct Bin {
    rays: [Ray; PACKET],
    owners: [u8; PACKET],
    len: usize,
}

impl<const SHADOWS: bool, const AO: bool, const FOG: bool, const AA: bool, const EXACT: bool>
    Lit<'_, '_, '_, SHADOWS, AO, FOG, AA, EXACT>
{
    /// What the secondary rays of each lane's hit (`hits[i]`, of the
    /// camera ray `rays[i]` of sample `sample` of pixel `at(i)`) find:
    /// their shadow rays as one packet, their occlusion rays in packets
    /// by octant.
    #[inline]
    pub(super) fn secondary_in_packets<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        (rays, hits): (&[Ray; PACKET], &[Option<Hit>; PACKET]),
        sample: u32,
        at: &impl Fn(usize) -> (u32, u32),
        memory: &mut WalkMemory<'s>,
    ) -> [Found; PACKET] {
        let mut found = [Found::default(); PACKET];
        if self.shadows() {
            let (mut shadows, mut lanes) = (*rays, 0u32);
            for (i, hit) in hits.iter().enumerate() {
                if let Some(shadow) = hit.as_ref().and_then(|hit| self.shadow_ray(&rays[i], hit)) {
                    shadows[i] = shadow;
                    lanes |= 1 << i;
                }
            }
            // From the camera rays' memory (a copy: the next block's
            // camera rays begin from it).
            let mut blockers = [None; PACKET];
            scene.trace_lanes(
                &shadows,
                lanes,
                Reach::ALL,
                &mut memory.clone(),
                &mut blockers,
            );
            for (i, found) in found.iter_mut().enumerate() {
                if lanes >> i & 1 != 0 {
                    found.blocked = Some(blockers[i].is_some());
                }
            }
        }
        let occlusion = self
            .0
            .options
            .occlusion
            .filter(|ao| AO && close(hits, ao.distance));
        if let Some(ao) = occlusion {
            let reach = Reach::within(ao.distance);
            let mut open = [0u32; PACKET];
            let empty = Bin {
                rays: [rays[0]; PACKET],
                owners: [0; PACKET],
                len: 0,
            };
            let mut bins = [empty; 8];
            for (i, (ray, hit)) in rays.iter().zip(hits).enumerate() {
                let Some((hit, entered)) = hit.as_ref().and_then(|h| Some((h, h.face?))) else {
                    continue;
                };
                found[i].open = Some(0);
                let (x, y) = at(i);
                for j in 0..u32::from(ao.rays) {
                    let Some(r) = occlusion_ray(ray, hit, entered, (x, y, sample), j) else {
                        open[i] += 1;
                        continue;
                    };
                    let bin = &mut bins[octant(r.lanes().1)];
                    (bin.rays[bin.len], bin.owners[bin.len]) = (r, i as u8);
                    bin.len += 1;
                    if bin.len == PACKET {
                        trace_bin(scene, bin, reach, memory, &mut open);
                    }
                }
            }
            for bin in &mut bins {
                trace_bin(scene, bin, reach, memory, &mut open);
            }
            for (found, open) in found.iter_mut().zip(open) {
                found.open = found.open.map(|_| open);
            }
        }
        found
    }
}

/// Traces the occlusion rays of `bin` over `reach` ([`Scene::trace_lanes`])
/// and empties it: `open[lane]` counts the rays of `lane` that meet
/// nothing.
fn trace_bin<'s, S: Scene + ?Sized>(
    scene: &'s S,
    bin: &mut Bin,
    reach: Reach,
    memory: &WalkMemory<'s>,
    open: &mut [u32; PACKET],
) {
    if bin.len == 0 {
        return;
    }
    let lanes = u32::MAX >> (PACKET - bin.len);
    let mut hits = [None; PACKET];
    scene.trace_lanes(&bin.rays, lanes, reach, &mut memory.clone(), &mut hits);
    for (hit, &owner) in hits.iter().zip(&bin.owners).take(bin.len) {
        open[usize::from(owner)] += u32::from(hit.is_none());
    }
    bin.len = 0;
}

/// The octant `dir` points into: bit `a` set when it moves down along axis
/// `a` (the sign rule of a packet's lanes).
#[inline]
fn octant(dir: Vec3A) -> usize {
    dir.cmplt(Vec3A::ZERO).bitmask() as usize
}

/// Whether the hits of a block lie within `reach` of one another on every
/// axis, so that their occlusion rays cross the same nodes: only then do
/// they pay in packets. Measured at size 250, `--shadows --ao 4` (reach
/// 8), one thread, on a 2-core AMD EPYC VM (medians of 5 to 7, ms):
/// packets for every block took 133, 344 and 978 at 480x270, 960x540
/// and 1920x1080; within the reach, 108, 285 and 861; within half of it,
/// 108, 319 and 903; no packets, 108, 347 and 1204.
#[inline]
fn close(hits: &[Option<Hit>; PACKET], reach: f32) -> bool {
    let (mut lo, mut hi) = (IVec3::MAX, IVec3::MIN);
    for hit in hits.iter().flatten() {
        lo = lo.min(hit.pos);
        hi = hi.max(hit.pos);
    }
    // No hit: nothing to trace either way.
    lo.cmpgt(hi).any() || (hi.as_vec3() - lo.as_vec3()).max_element() <= reach
}

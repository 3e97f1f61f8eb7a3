//! The lit look's secondary rays in packets: the shadow and occlusion
//! rays of a packet of camera rays' hits, traced together
//! ([`Scene::trace_packet`]) before the hits are shaded. Shadow rays are
//! parallel and start at neighbouring hits: one packet. Occlusion rays
//! scatter over each face's hemisphere, so they are gathered by the
//! octant they point into (a packet's lanes share their signs), each
//! octant's bin traced whenever it holds a packet. Every lane a packet
//! leaves is traced alone, as [`Lit::shade_sample`] would: the answers
//! are the same, bit for bit, whichever way they were found.

use glam::Vec3A;

use crate::geom::Ray;
use crate::render::sampling::pixel_key;
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
    /// camera ray `rays[i]` of pixel `at(i)`) find: their shadow rays as
    /// one packet, their occlusion rays in packets by octant.
    #[inline]
    pub(super) fn secondary_in_packets<'s, S: Scene + ?Sized>(
        &self,
        scene: &'s S,
        (rays, hits): (&[Ray; PACKET], &[Option<Hit>; PACKET]),
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
            let mut blockers = [None; PACKET];
            let answered = scene.trace_packet(&shadows, lanes, Reach::ALL, &mut blockers);
            for (i, found) in found.iter_mut().enumerate() {
                if answered >> i & 1 != 0 {
                    found.blocked = Some(blockers[i].is_some());
                }
            }
        }
        if let (true, Some(ao)) = (AO, self.0.options.occlusion) {
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
                let key = pixel_key(x, y, 1);
                for j in 0..u32::from(ao.rays) {
                    let Some(r) = occlusion_ray(ray, hit, entered, key, j) else {
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

/// Traces the occlusion rays of `bin` as a packet over `reach`, each ray
/// the packet leaves alone, and empties it: `open[lane]` counts the rays
/// of `lane` that meet nothing.
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
    let answered = scene.trace_packet(&bin.rays, lanes, reach, &mut hits);
    for (lane, ray) in bin.rays[..bin.len].iter().enumerate() {
        let blocked = if answered >> lane & 1 != 0 {
            hits[lane].is_some()
        } else {
            let memory = &mut memory.clone();
            scene.trace_with(ray, reach, memory, None).hit.is_some()
        };
        open[usize::from(bin.owners[lane])] += u32::from(!blocked);
    }
    bin.len = 0;
}

/// The octant `dir` points into: bit `a` set when it moves down along axis
/// `a` (the sign rule of a packet's lanes).
#[inline]
fn octant(dir: Vec3A) -> usize {
    dir.cmplt(Vec3A::ZERO).bitmask() as usize
}

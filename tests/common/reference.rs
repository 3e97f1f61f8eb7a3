//! The brute-force reference: for every solid voxel, decide on its own
//! whether the ray visits it, and keep the one visited first.
//!
//! It shares only the definition of the ray with the backends (see the
//! `walk` module docs): plane crossings at `t = (plane - origin) * inv_dir`
//! in `f32`, visited in the order of the key `(t, axis, plane)`, the start
//! cell being the one the ray is in just after `t = 0`. A cell is visited
//! when the last of its entry crossings comes before the first of its exit
//! crossings. No stepping, no jumping, no volume clipping: a different
//! algorithm for the same definition.

use std::cmp::Ordering;

use voxtrace::glam::IVec3;
use voxtrace::{Face, IAabb, Ray};

/// A crossing's key. `t = -inf` is "before everything", `+inf` "never".
#[derive(Clone, Copy, Debug, PartialEq)]
struct Key {
    t: f32,
    axis: usize,
    ordinal: i64,
}

fn cmp(a: &Key, b: &Key) -> Ordering {
    a.t.partial_cmp(&b.t)
        .expect("reference keys are never NaN")
        .then(a.axis.cmp(&b.axis))
        .then(a.ordinal.cmp(&b.ordinal))
}

/// What the reference decides: position, face, distance, material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefHit {
    pub pos: IVec3,
    pub face: Option<Face>,
    pub t: f32,
    pub material: u8,
}

/// Per-axis description of the ray, computed with f64 floor/ceil (the
/// backends use libm's f32 versions).
struct Axis {
    o: f32,
    inv: f32,
    /// +1, -1, or 0 when the ray does not move along the axis.
    step: i64,
    start: i64,
}

fn axes(ray: &Ray) -> [Axis; 3] {
    let (o, d, inv) = (ray.origin(), ray.dir(), ray.inv_dir());
    std::array::from_fn(|a| {
        let moving = d[a] != 0.0 && inv[a].is_finite();
        let step = if !moving {
            0
        } else if d[a] > 0.0 {
            1
        } else {
            -1
        };
        let of = f64::from(o[a]);
        // The cell just after t = 0: below an integer origin when moving down.
        let start = if step < 0 && of.fract() == 0.0 {
            of as i64 - 1
        } else {
            of.floor() as i64
        };
        Axis {
            o: o[a],
            inv: inv[a],
            step,
            start,
        }
    })
}

fn crossing(ax: &Axis, axis: usize, plane: i64, ordinal: i64) -> Key {
    Key {
        t: (plane as f32 - ax.o) * ax.inv,
        axis,
        ordinal,
    }
}

/// Entry and exit keys of coordinate `c` on one axis, or `None` if the ray
/// never is at that coordinate.
fn interval(ax: &Axis, axis: usize, c: i64) -> Option<(Key, Key)> {
    let before = Key {
        t: f32::NEG_INFINITY,
        axis,
        ordinal: 0,
    };
    let never = Key {
        t: f32::INFINITY,
        axis,
        ordinal: 0,
    };
    if ax.step == 0 {
        return (c == ax.start).then_some((before, never));
    }
    let ahead = (c - ax.start) * ax.step;
    if ahead < 0 {
        return None;
    }
    let entry_plane = if ax.step > 0 { c } else { c + 1 };
    let exit_plane = if ax.step > 0 { c + 1 } else { c };
    let entry = if ahead == 0 {
        if entry_plane as f32 == ax.o {
            Key {
                t: 0.0,
                axis,
                ordinal: 0,
            }
        } else {
            before
        }
    } else {
        crossing(ax, axis, entry_plane, ahead)
    };
    Some((entry, crossing(ax, axis, exit_plane, ahead + 1)))
}

/// The first solid voxel of `material` inside `bounds` along `ray`.
pub fn first_hit(ray: &Ray, bounds: IAabb, material: impl Fn(IVec3) -> u8) -> Option<RefHit> {
    let ax = axes(ray);
    let mut best: Option<(Key, RefHit)> = None;
    for pos in bounds.iter() {
        let m = material(pos);
        if m == 0 {
            continue;
        }
        let mut entry: Option<Key> = None;
        let mut exit: Option<Key> = None;
        let mut visited = true;
        for (a, axis) in ax.iter().enumerate() {
            let Some((e, x)) = interval(axis, a, i64::from(pos[a])) else {
                visited = false;
                break;
            };
            entry = Some(match entry {
                Some(k) if cmp(&k, &e) != Ordering::Less => k,
                _ => e,
            });
            exit = Some(match exit {
                Some(k) if cmp(&k, &x) != Ordering::Greater => k,
                _ => x,
            });
        }
        let (Some(entry), Some(exit)) = (entry, exit) else {
            continue;
        };
        if !visited || entry.t == f32::INFINITY || cmp(&entry, &exit) != Ordering::Less {
            continue;
        }
        if best
            .as_ref()
            .is_some_and(|(k, _)| cmp(k, &entry) != Ordering::Greater)
        {
            continue;
        }
        let (face, t) = if entry.t == f32::NEG_INFINITY {
            (None, 0.0)
        } else {
            (
                Some(Face::entered(entry.axis, ax[entry.axis].step > 0)),
                entry.t,
            )
        };
        best = Some((
            entry,
            RefHit {
                pos,
                face,
                t,
                material: m,
            },
        ));
    }
    best.map(|(_, hit)| hit)
}

/// The backends' answer in the reference's shape.
pub fn as_ref_hit(hit: Option<voxtrace::Hit>) -> Option<RefHit> {
    hit.map(|h| RefHit {
        pos: h.pos,
        face: h.face,
        t: h.t,
        material: h.material,
    })
}

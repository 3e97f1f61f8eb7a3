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
            (of as i64).saturating_sub(1)
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
    // Is `c` at or ahead of the start cell? (i128: the start cell of a huge
    // origin saturates at the ends of i64.)
    let ahead = (i128::from(c) - i128::from(ax.start)) * i128::from(ax.step);
    if ahead < 0 {
        return None;
    }
    let entry_plane = if ax.step > 0 { c } else { c + 1 };
    let exit_plane = if ax.step > 0 { c + 1 } else { c };
    // Planes of one axis are crossed in the order of `plane * step`, even
    // when their rounded times are equal.
    let entry = if ahead == 0 {
        if entry_plane as f32 == ax.o {
            Key {
                t: 0.0,
                axis,
                ordinal: entry_plane * ax.step,
            }
        } else {
            before
        }
    } else {
        crossing(ax, axis, entry_plane, entry_plane * ax.step)
    };
    Some((entry, crossing(ax, axis, exit_plane, exit_plane * ax.step)))
}

/// The first solid voxel of `material` inside `bounds` along `ray`.
pub fn first_hit(ray: &Ray, bounds: IAabb, material: impl Fn(IVec3) -> u8) -> Option<RefHit> {
    first_hit_among(ray, bounds.iter().map(|p| (p, material(p))))
}

/// The first voxel along `ray` among `solids` (position, material); entries
/// with material 0 are skipped.
pub fn first_hit_among(ray: &Ray, solids: impl IntoIterator<Item = (IVec3, u8)>) -> Option<RefHit> {
    let ax = axes(ray);
    let mut best: Option<(Key, RefHit)> = None;
    for (pos, m) in solids {
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

/// Entry and exit distances of the unit cube at `pos`, grown by `grow` on
/// every side, along the forward ray, in f64 from the ray's f32 origin and
/// direction; `None` if they miss.
pub fn slab64(ray: &Ray, pos: IVec3, grow: f64) -> Option<(f64, f64)> {
    let (o, d) = (ray.origin(), ray.dir());
    let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
    for a in 0..3 {
        let (o, d) = (f64::from(o[a]), f64::from(d[a]));
        let (p, q) = (f64::from(pos[a]) - grow, f64::from(pos[a]) + 1.0 + grow);
        if p > q {
            return None; // shrunk by more than half a voxel: no interior left
        }
        if d == 0.0 {
            if o < p || o > q {
                return None;
            }
            continue;
        }
        let (t1, t2) = ((p - o) / d, (q - o) / d);
        lo = lo.max(t1.min(t2));
        hi = hi.min(t1.max(t2));
    }
    (lo <= hi).then_some((lo, hi))
}

/// The farthest distance a ray reaches: crossings beyond overflow f32.
const REACH: f64 = f32::MAX as f64;

/// Checks a backend's answer against geometry in f64, independently of the
/// f32 definition: the hit voxel lies on the ray at distance `t` (within
/// `tol`), and no solid voxel is crossed for more than `tol` before it. For a
/// miss, no solid voxel is crossed for more than `tol`. `tol` scales with the
/// magnitudes involved, since f32 inputs carry relative error ~6e-8.
/// Voxels farther than `f32::MAX` are out of reach by definition (a crossing
/// whose distance overflows f32 never happens).
pub fn check_geometry(
    ray: &Ray,
    hit: Option<&voxtrace::Hit>,
    solids: &[(IVec3, u8)],
) -> Result<(), String> {
    let scale = 1.0 + f64::from(ray.origin().abs().max_element());
    let tol = |t: f64| 2e-6 * (scale + t.abs());
    if let Some(h) = hit {
        let t = f64::from(h.t);
        // Grown by the tolerance: a ray that only touches the voxel's
        // boundary may miss it by rounding.
        let Some((glo, ghi)) = slab64(ray, h.pos, tol(t)) else {
            return Err(format!("hit {} is not on the ray", h.pos));
        };
        let entered_late = slab64(ray, h.pos, 0.0).is_some_and(|(lo, _)| t > lo + tol(t));
        if t < glo - tol(t) || t > ghi + tol(t) || entered_late {
            return Err(format!(
                "hit {} at t={t}, but geometry spans [{glo}, {ghi}]",
                h.pos
            ));
        }
        for &(pos, _) in solids {
            // Only the interior counts: a ray in a face plane only touches
            // the voxel, and there the tie rule decides.
            if let Some((lo, hi)) = slab64(ray, pos, -tol(0.0)).filter(|&(lo, _)| lo < REACH) {
                if hi - lo > tol(hi) && lo < t - tol(t) {
                    return Err(format!(
                        "{pos} is crossed in [{lo}, {hi}], before the hit {} at {t}",
                        h.pos
                    ));
                }
            }
        }
    } else {
        for &(pos, _) in solids {
            if let Some((lo, hi)) = slab64(ray, pos, -tol(0.0)).filter(|&(lo, _)| lo < REACH) {
                if hi - lo > tol(hi) {
                    return Err(format!("miss, but {pos} is crossed in [{lo}, {hi}]"));
                }
            }
        }
    }
    Ok(())
}

//! Placing a walk at a later key on three lanes at once: each moving axis'
//! coordinate guessed from the point at the key and kept only when the two
//! key comparisons the stepwise search (`Walk::settle`) would make first
//! both agree with it.
//!
//! Along one axis the crossing times are monotone in the plane coordinate
//! (one subtraction and one multiplication, each rounded monotonically), so
//! at most one coordinate `c` has both "entered before the key" (or is the
//! first coordinate searched) and "not left before the key" (or is the last):
//! the coordinate the stepwise search ends on. A guess that passes both
//! tests is therefore that coordinate, whatever the guess was; a guess that
//! fails either is handed to the stepwise search. Primary rays placed at
//! their tile's clear distance pass on every axis almost always.

use glam::{BVec3A, IVec3, Vec3A};

use crate::storage::walk::{latest, Key, Walk};

/// Lane indices as floats, for the axis part of key comparisons.
const LANE: Vec3A = Vec3A::new(0.0, 1.0, 2.0);

/// `a < b` per lane for keys `(a, lane)` against the one key `(t, axis)`.
#[inline]
fn keys_before(a: Vec3A, key: Key) -> BVec3A {
    let t = Vec3A::splat(key.t);
    a.cmplt(t) | (a.cmpeq(t) & LANE.cmplt(Vec3A::splat(f32::from(key.axis))))
}

/// `select(mask, a, b)` for integer lanes.
#[inline]
fn pick(mask: BVec3A, a: IVec3, b: IVec3) -> IVec3 {
    let mask = mask.bitmask();
    IVec3::new(
        if mask & 1 != 0 { a.x } else { b.x },
        if mask & 2 != 0 { a.y } else { b.y },
        if mask & 4 != 0 { a.z } else { b.z },
    )
}

/// What a placement on three lanes decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Guess {
    /// Placed in the cell the ray is in at the key, with its entry key.
    Placed,
    /// The ray has left the volume by the key.
    Left,
    /// A guess is off (nothing changed): the stepwise search decides.
    Unsure,
}

impl Walk {
    /// What `settle_all` does, decided on three lanes when every moving
    /// axis' guess checks out ([`Guess`]).
    #[inline]
    pub(super) fn place_by_guess(&mut self, key: Key) -> Guess {
        let (origin, inv_dir) = (self.origin, self.inv_dir);
        // Cell coordinates as floats, all on four lanes: exact, since every
        // coordinate below lies within the volume (|c| <= 2^22 + 1) but a
        // saturated start cell, which keeps its order against them.
        let step = self.step.as_vec3a();
        let (up, moving) = (step.cmpgt(Vec3A::ZERO), step.cmpne(Vec3A::ZERO));
        let (lo, hi, start) = (
            self.lo.as_vec3a(),
            self.hi.as_vec3a(),
            self.start.as_vec3a(),
        );
        // The search runs from the start (inside the volume) or the near
        // face to one past the far face, as `settle_all` searches it.
        let near = Vec3A::select(up, lo, hi - 1.0);
        let limit = Vec3A::select(up, hi, lo - 1.0);
        let start_inside = start.cmpge(lo) & start.cmplt(hi);
        let from = Vec3A::select(start_inside, start, near);
        // The cell of the point at the key, clamped into the searched range
        // (a NaN or infinite point clamps to one end): any guess is sound,
        // the tests below decide.
        let point = origin + self.dir * key.t;
        let c = point.floor().max(from.min(limit)).min(from.max(limit));
        // Entry and exit planes of `c`: moving up a cell is entered through
        // its lower plane and left through its upper one.
        let entry_plane = Vec3A::select(up, c, c + 1.0);
        let exit_plane = Vec3A::select(up, c + 1.0, c);
        let start_t = Vec3A::from_array(self.start_keys.map(|k| k.t));
        let entry_t = Vec3A::select(c.cmpeq(start), start_t, (entry_plane - origin) * inv_dir);
        let exit_t = (exit_plane - origin) * inv_dir;
        let at_limit = c.cmpeq(limit);
        let entered = c.cmpeq(from) | keys_before(entry_t, key);
        let not_left = at_limit | !keys_before(exit_t, key);
        if (!(entered & not_left) & moving).any() {
            return Guess::Unsure;
        }
        if (at_limit & moving).any() {
            return Guess::Left;
        }
        // Placed: the cell, its entry key (the latest of the moving axes'
        // entries, ties to the highest axis, as `Key::lt` orders them; a
        // start key off its plane is before everything); an axis that does
        // not move keeps its start.
        self.key = latest(Vec3A::select(moving, entry_t, Vec3A::NEG_INFINITY));
        self.cell = pick(moving, c.as_ivec3(), self.cell);
        Guess::Placed
    }
}

#[cfg(test)]
mod tests {
    use super::Guess;
    use crate::storage::walk::test_rays::Rng;
    use crate::storage::walk::{Key, Walk};

    /// Keys at and after the walk's entry: random times, and the exact
    /// crossing times of planes on every axis (ties with every lane).
    fn later_key(rng: &mut Rng, walk: &Walk) -> Key {
        let t0 = walk.key.t.max(0.0);
        let t = if rng.next() % 2 == 0 {
            rng.range(t0, t0 + 80.0)
        } else {
            let axis = (rng.next() % 3) as usize;
            let plane = walk.cell[axis] + rng.int(-20, 20);
            walk.crossing(axis, plane).t
        };
        Key {
            t,
            axis: (rng.next() % 3) as u8,
        }
    }

    /// The lane placement decides as the stepwise search does: the same
    /// cell and entry key (so the same exit crossings), or the same "left
    /// the volume", whenever it decides at all; and it decides for most
    /// keys.
    #[test]
    fn guesses_agree_with_the_stepwise_search() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        let (mut decided, mut cases) = (0u32, 0u32);
        while cases < 60_000 {
            let bounds = rng.bounds();
            let Some(ray) = rng.ray() else {
                continue;
            };
            let Some(walk) = Walk::start(&ray, &bounds) else {
                continue;
            };
            let key = later_key(&mut rng, &walk);
            if !walk.key.lt(key) || !key.t.is_finite() {
                continue;
            }
            cases += 1;
            let mut guessed = walk.clone();
            let mut searched = walk.clone();
            let expected = searched.settle_stepwise(key);
            let placed = match guessed.place_by_guess(key) {
                Guess::Unsure => continue,
                guess => guess == Guess::Placed,
            };
            decided += 1;
            assert_eq!(placed, expected.is_ok(), "{ray:?} {bounds:?} {key:?}");
            if placed {
                assert_eq!(guessed.cell, searched.cell, "{ray:?} {bounds:?} {key:?}");
                assert_eq!(guessed.key, searched.key, "{ray:?} {bounds:?} {key:?}");
            }
        }
        // Most guesses hold: the fast path is the common path.
        assert!(decided > cases / 2, "{decided} of {cases} decided");
    }
}

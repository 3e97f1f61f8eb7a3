//! Where a walk begins, on [`WalkRay`]: the one route both storages take
//! into the box they walk ([`WalkRay::begin`]). A ray that starts inside
//! begins in its start cell; one from outside in the cell it enters the
//! box by, found by a guess that two crossings per axis confirm, or by
//! [`Walk::start`] itself when they do not; one that may begin at a clear
//! distance past its entry begins there, told by the point ([`Placed`]).
//! Every answer is where single steps from the start are.

use glam::{BVec3A, Vec3A};

use crate::geom::{IAabb, Ray};
use crate::storage::walk::placed::Placed;
use crate::storage::walk::{latest, Key, Walk, WalkRay, EXACT};

/// Lane indices as floats, to turn an axis into a lane mask.
pub(crate) const AXES: Vec3A = Vec3A::new(0.0, 1.0, 2.0);

/// Where the walk of a box begins ([`WalkRay::begin`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum Begin {
    /// In the cell at `cell` (exact floats) of the box, entered by the
    /// crossing `key`: the start cell of a ray that starts inside, else
    /// the cell the ray enters the box by.
    At { cell: Vec3A, key: Key },
    /// Inside the box at the key `(clear, x)`, past its entry: the walk
    /// may begin there, in a box the point says holds its cell.
    Later(Placed),
    /// Nowhere: the ray misses the box, or has left it by the clear
    /// distance.
    Misses,
}

impl WalkRay {
    /// Where the walk of `ray` (this is its walker) through `region`
    /// begins when the ray is known to hit nothing before `clear` (0:
    /// from its start).
    ///
    /// The walk enters the box at the latest of its per-axis entries (a
    /// start key on an axis where the start cell is inside, as
    /// [`Walk::start`] computes it) and misses it when the start is outside
    /// on an axis the ray does not move toward, or the entry is never
    /// reached. Entered before `clear`, and not left by then, it is
    /// [`Begin::Later`]; a point inside the box by its rounding margin
    /// says so without any key (most primary rays at their tile's clear
    /// distance). Else it begins in the cell it enters by: the start
    /// cell, or from outside the box's first layer on the entry axis and,
    /// on every other axis it moves along, the first cell from the start
    /// (or the near side) whose exit crossing does not come before the
    /// entry key. Crossings only grow along an axis, so that cell is
    /// unique; the entry point's cell is the guess, and the crossings
    /// before and after it confirm it, so the point's rounding cannot move
    /// it. A guess they do not confirm, a start inside on the entry axis
    /// (an origin on the box's face) and an origin too far out for exact
    /// cells are left to [`Walk::start`].
    #[inline(always)]
    pub(crate) fn begin(&self, ray: &Ray, region: &IAabb, clear: f32) -> Begin {
        let (lo, hi) = (region.min.as_vec3a(), region.max.as_vec3a());
        let (origin, inv_dir) = (self.origin, self.inv_dir);
        let (up, start) = (self.start.up, self.start.cell_f);
        let later = Key { t: clear, axis: 0 };
        let placed = (clear > 0.0).then(|| Placed::at(origin, self.dir, self.moving, clear));
        if let Some(placed) = placed.filter(|p| p.surely_in(lo, hi)) {
            return Begin::Later(placed);
        }
        // The entry key.
        let inside = start.cmpge(lo) & start.cmplt(hi);
        let toward = (up & start.cmplt(lo)) | (self.start.down & start.cmpge(hi));
        if !(inside | toward).all() {
            return Begin::Misses;
        }
        let near = Vec3A::select(up, lo, hi);
        let crossed = (near - origin) * inv_dir;
        let enters = latest(Vec3A::select(inside, self.start.key_times(), crossed));
        if enters.t == f32::INFINITY {
            return Begin::Misses;
        }
        if let Some(placed) = placed.filter(|_| enters.lt(later)) {
            return if self.exit_of(lo, hi).lt(later) {
                Begin::Misses
            } else {
                Begin::Later(placed)
            };
        }
        if inside.all() {
            return Begin::At {
                cell: start,
                key: enters,
            };
        }
        // From outside: the entry cell, guessed and confirmed.
        let axis = Vec3A::splat(f32::from(enters.axis));
        let on_entry_axis = AXES.cmpeq(axis);
        if !origin.abs().cmplt(Vec3A::splat(EXACT)).all() || (inside & on_entry_axis).any() {
            return WalkRay::begin_by_steps(ray, region);
        }
        // The first cell from the near side, and one past the far one.
        let near = Vec3A::select(up, lo, hi - 1.0);
        let beyond = Vec3A::select(up, hi, lo - 1.0);
        let from = Vec3A::select(inside, start, near);
        let point = (origin + self.dir * enters.t).floor();
        let guess = Vec3A::select(up, point.max(from).min(beyond), point.min(from).max(beyond));
        // Whether each lane's crossing of the exit plane of `cell` comes
        // before `enters`, ties to the lower axis.
        let kt = Vec3A::splat(enters.t);
        let exits_before = |cell: Vec3A| {
            let t = (Vec3A::select(up, cell + 1.0, cell) - origin) * inv_dir;
            t.cmplt(kt) | (t.cmpeq(kt) & AXES.cmplt(axis))
        };
        let after_previous = guess.cmpeq(from) | exits_before(guess - self.step);
        let not_before = guess.cmpeq(beyond) | !exits_before(guess);
        let checked: BVec3A = (after_previous & not_before) | !self.moving | on_entry_axis;
        if !checked.all() {
            return WalkRay::begin_by_steps(ray, region);
        }
        let cell = Vec3A::select(
            on_entry_axis,
            near,
            Vec3A::select(self.moving, guess, start),
        );
        if (cell.cmpge(lo) & cell.cmplt(hi)).all() {
            Begin::At { cell, key: enters }
        } else {
            // Beside the box on an axis: the ray passes it by.
            Begin::Misses
        }
    }

    /// [`WalkRay::begin`] at the entry, by [`Walk::start`]: what decides
    /// where the walker cannot. Kept out of line: few rays come here.
    #[inline(never)]
    fn begin_by_steps(ray: &Ray, region: &IAabb) -> Begin {
        match Walk::start(ray, region) {
            Some(walk) => Begin::At {
                cell: walk.cell().as_vec3a(),
                key: walk.key(),
            },
            None => Begin::Misses,
        }
    }
}

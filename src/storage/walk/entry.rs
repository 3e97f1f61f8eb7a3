//! Where a ray enters a box, on [`Lanes`]: the key the walk's own entry
//! (`Walk::start`) enters by, and, from outside, the cell it settles on,
//! found by a guess that two crossings per axis confirm. The dense walk
//! and the octree both begin there.

use glam::{BVec3A, Vec3A};

use crate::storage::walk::{latest, Key, Lanes, EXACT};

/// Lane indices as floats, to turn an axis into a lane mask.
pub(crate) const AXES: Vec3A = Vec3A::new(0.0, 1.0, 2.0);

/// Where a walk entering a box from outside is when it enters
/// ([`entry_cell`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum EntryCell {
    /// In this cell (exact floats) of the box.
    In(Vec3A),
    /// Nowhere: the ray passes the entry plane beside the box.
    Beside,
    /// Not settled here: a guess did not check out, the start is inside on
    /// the entry axis, or the origin is too far out for exact cells. The
    /// caller asks `Walk::start`.
    Unsure,
}

impl Lanes {
    /// The key at which the walk enters the box `[lo, hi)` (exact floats),
    /// as `Walk::start` computes it: the latest of the per-axis entries, a start key on an
    /// axis where the start cell is inside, and whether it is inside on every
    /// axis (then the start cell is where the walk begins). `None` when the
    /// start is outside on an axis the ray does not move toward; `+inf` when
    /// it never gets in.
    #[inline]
    pub(crate) fn entry_of(&self, lo: Vec3A, hi: Vec3A) -> Option<(Key, bool)> {
        let (origin, inv_dir) = (self.origin, self.inv_dir);
        let (up, down, start_t) = (self.start.up, self.start.down, self.start.key_times());
        let start = self.start.cell_f;
        let inside = start.cmpge(lo) & start.cmplt(hi);
        let toward = (up & start.cmplt(lo)) | (down & start.cmpge(hi));
        if !(inside | toward).all() {
            return None;
        }
        let near = Vec3A::select(up, lo, hi);
        let t = Vec3A::select(inside, start_t, (near - origin) * inv_dir);
        Some((latest(t), inside.all()))
    }

    /// The cell (exact floats) the walk (crossing planes at
    /// `(plane - origin) * inv_dir`) is in when it enters the box `[lo, hi)`
    /// at `enters`, the latest of its per-axis entry keys
    /// ([`Lanes::entry_of`]'s key), from outside. On
    /// the entry axis that is the box's first layer. On every other axis it
    /// moves along, it is the first cell from the start (or the near side on)
    /// whose exit crossing does not come before `enters`: crossings only grow
    /// along an axis, so that cell is unique; the entry point's cell is the
    /// guess, and the crossings before and after it confirm it, so the
    /// point's rounding cannot move it. On an axis the ray does not move
    /// along, the start cell's coordinate.
    ///
    /// [`EntryCell::Beside`] when that cell lies outside the box: the ray then
    /// passes the entry plane beside the box and misses it.
    #[inline]
    pub(crate) fn entry_cell(&self, lo: Vec3A, hi: Vec3A, enters: Key) -> EntryCell {
        let (origin, dir, inv_dir) = (self.origin, self.dir, self.inv_dir);
        let (up, down, start) = (self.start.up, self.start.down, self.start.cell_f);
        if !origin.abs().cmplt(Vec3A::splat(EXACT)).all() {
            return EntryCell::Unsure;
        }
        let moving = up | down;
        let axis = Vec3A::splat(f32::from(enters.axis));
        let on_entry_axis = AXES.cmpeq(axis);
        let inside = start.cmpge(lo) & start.cmplt(hi);
        if (inside & on_entry_axis).any() {
            return EntryCell::Unsure;
        }
        let one = |mask: BVec3A| Vec3A::select(mask, Vec3A::ONE, Vec3A::ZERO);
        let step = one(up) - one(down);
        // The first cell from the near side, and one past the far one.
        let near = Vec3A::select(up, lo, hi - 1.0);
        let beyond = Vec3A::select(up, hi, lo - 1.0);
        let from = Vec3A::select(inside, start, near);
        let point = (origin + dir * enters.t).floor();
        let guess = Vec3A::select(up, point.max(from).min(beyond), point.min(from).max(beyond));
        // Whether each lane's crossing of the exit plane of `cell` comes
        // before `enters`, ties to the lower axis.
        let kt = Vec3A::splat(enters.t);
        let exits_before = |cell: Vec3A| {
            let plane = Vec3A::select(up, cell + 1.0, cell);
            let t = (plane - origin) * inv_dir;
            t.cmplt(kt) | (t.cmpeq(kt) & AXES.cmplt(axis))
        };
        let after_previous = guess.cmpeq(from) | exits_before(guess - step);
        let not_before = guess.cmpeq(beyond) | !exits_before(guess);
        let checked = (after_previous & not_before) | !moving | on_entry_axis;
        if !checked.all() {
            return EntryCell::Unsure;
        }
        let cell = Vec3A::select(on_entry_axis, near, Vec3A::select(moving, guess, start));
        if (cell.cmpge(lo) & cell.cmplt(hi)).all() {
            EntryCell::In(cell)
        } else {
            EntryCell::Beside
        }
    }
}

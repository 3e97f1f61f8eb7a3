//! The `Scene` trait: what the tracer needs from a storage, and the `Hit`
//! every storage returns.

use core::marker::PhantomData;

use glam::IVec3;

use crate::frustum::Frustum;
use crate::geom::{Face, IAabb, Ray};
use crate::material::SceneMaterials;
use crate::voxel::{Palette, Voxel};

/// The first solid voxel along a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The voxel's position.
    pub pos: IVec3,
    /// The face the ray entered through; `None` when the ray starts strictly
    /// inside the voxel (then `t` is 0).
    pub face: Option<Face>,
    /// Distance along the unit direction to the entry point, `>= 0`, never
    /// `-0.0`, computed as one plane crossing `(plane - origin) * inv_dir`.
    pub t: f32,
    /// The voxel's palette index (never 0, which means empty).
    pub material: u8,
    /// The voxel itself.
    pub voxel: Voxel,
}

impl Hit {
    /// The hit on the voxel of palette index `material` at `pos`, or `None`
    /// when the palette has no such entry (every storage builds its hits
    /// here, so they agree on what a material means).
    #[inline]
    pub(crate) fn from_palette(
        palette: &Palette,
        pos: IVec3,
        face: Option<Face>,
        t: f32,
        material: u8,
    ) -> Option<Hit> {
        palette.voxel(material).map(|voxel| Hit {
            pos,
            face,
            t,
            material,
            voxel,
        })
    }
}

/// A hit (or miss) together with the number of walk moves it took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Traced {
    /// The first solid voxel along the ray, if any.
    pub hit: Option<Hit>,
    /// Walk moves (single steps and empty-box jumps) taken; never more than
    /// [`crate::max_steps`] of the scene's bounds.
    pub steps: u32,
}

/// Entries of a [`WalkMemory`]'s path: one per level of the deepest tree
/// a storage of this crate builds.
pub(crate) const MEMORY_PATH: usize = 32;

/// What a storage keeps between the walks of coherent rays (the pixels of
/// a tile, the occlusion rays of neighbouring hits) so that a ray can begin
/// where the previous one already knows its way: for the octree, the path
/// of nodes down to where the last walk ended, and what the last start
/// cell looked up held (rays from one origin start in one cell).
///
/// # Guarantees
/// A memory only ever changes where a walk begins its work, never what it
/// finds: [`Scene::trace_from_with`] and [`Scene::trace_within_with`] give
/// the same hit, bit for bit, with a new memory, a used one, or one another
/// scene wrote (it is tied to the scene that wrote it, which the lifetime
/// keeps alive, and ignored by every other).
#[derive(Clone, Debug)]
pub struct WalkMemory<'s> {
    /// Address of the scene that wrote the memory (0: none yet).
    pub(crate) owner: usize,
    /// Node indices by depth, valid for depths `1..=depth`.
    pub(crate) path: [u32; MEMORY_PATH],
    /// Deepest valid entry of `path`.
    pub(crate) depth: usize,
    /// A position inside the node at `depth`, relative to the tree's corner.
    pub(crate) corner: IVec3,
    /// The answer of the last start-cell lookup: rays from one origin (a
    /// camera's, or one hit point's occlusion rays) share it.
    pub(crate) start: StartSeen,
    scene: PhantomData<&'s ()>,
}

/// What the start cell of a ray held, for the rays that share its origin
/// and the direction class the start rule reads ([`StartSeen::key_of`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct StartSeen {
    /// Address of the scene that answered (0: nothing seen yet).
    pub(crate) owner: usize,
    /// The origin's bits and the direction class.
    pub(crate) key: [u32; 4],
    /// The hit a walk reports when its start cell is solid, `None` when
    /// that cell is empty.
    pub(crate) hit: Option<Hit>,
}

impl StartSeen {
    /// Nothing seen yet.
    const NONE: StartSeen = StartSeen {
        owner: 0,
        key: [0; 4],
        hit: None,
    };

    /// The start cell and its face depend on the origin and, per axis, on
    /// whether the ray moves along it and whether down: the start rule's
    /// whole input. Equal keys, equal start cells.
    #[inline]
    pub(crate) fn key_of(ray: &Ray, class: u32) -> [u32; 4] {
        let o = ray.origin();
        [o.x.to_bits(), o.y.to_bits(), o.z.to_bits(), class]
    }
}

impl WalkMemory<'_> {
    /// A memory that knows nothing yet.
    #[must_use]
    pub fn new() -> Self {
        WalkMemory {
            owner: 0,
            path: [0; MEMORY_PATH],
            depth: 0,
            corner: IVec3::ZERO,
            start: StartSeen::NONE,
            scene: PhantomData,
        }
    }
}

impl Default for WalkMemory<'_> {
    fn default() -> Self {
        Self::new()
    }
}

/// A voxel storage the tracer can shoot rays into.
///
/// # Guarantees
/// Every implementation in this crate returns, for every ray, the hit the
/// shared cell walk defines (see the crate docs): the same voxel, face and
/// `t`, bit for bit, whatever the storage. Tracing never allocates, never
/// panics, and takes at most [`crate::max_steps`] moves.
pub trait Scene {
    /// The volume the scene covers; nothing outside it is ever hit.
    fn bounds(&self) -> IAabb;

    /// The first solid voxel along `ray`, with the walk's move count.
    fn trace_counted(&self, ray: &Ray) -> Traced;

    /// [`Scene::trace_counted`], also showing `visit` every empty box the
    /// walk moves through, nearest first: cells for the dense array, node
    /// cubes for the octree (the debug view draws their edges). When `visit`
    /// returns `false` the walk stops there and reports no hit.
    fn trace_visiting(&self, ray: &Ray, visit: &mut dyn FnMut(IAabb) -> bool) -> Traced;

    /// A distance before which no ray from the frustum's apex inside
    /// `frustum` hits a voxel: every such ray's hit, if any, has `t >=` the
    /// answer.
    /// What lets a tile of primary rays skip the empty space they share.
    /// The default knows nothing and answers 0.
    #[inline]
    fn clear_distance(&self, frustum: &Frustum) -> f32 {
        let _ = frustum;
        0.0
    }

    /// [`Scene::trace_counted`] for a ray known to hit nothing before
    /// `t_start` (from [`Scene::clear_distance`]): the same hit, bit for
    /// bit, but the walk may begin at `t_start` (the move count then counts
    /// only the moves made). The default walks from the start.
    #[inline]
    fn trace_from(&self, ray: &Ray, t_start: f32) -> Traced {
        let _ = t_start;
        self.trace_counted(ray)
    }

    /// [`Scene::trace_from`] for one of a run of coherent rays sharing
    /// `memory` (the pixels of a tile, in order): the same hit, bit for bit;
    /// the storage may begin from what the previous walk left in `memory`,
    /// and leaves there what the next one can use. The default forgets.
    #[inline]
    fn trace_from_with<'s>(
        &'s self,
        ray: &Ray,
        t_start: f32,
        memory: &mut WalkMemory<'s>,
    ) -> Traced {
        let _ = memory;
        self.trace_from(ray, t_start)
    }

    /// The first solid voxel along `ray`.
    #[inline]
    fn trace(&self, ray: &Ray) -> Option<Hit> {
        self.trace_counted(ray).hit
    }

    /// The first solid voxel along `ray` if it is at most `t_max` away:
    /// exactly `trace(ray).filter(|h| h.t <= t_max)`, but the storages of
    /// this crate stop walking once `t_max` is passed (what makes short
    /// occlusion rays cheap).
    #[inline]
    fn trace_within(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.trace(ray).filter(|h| h.t <= t_max)
    }

    /// [`Scene::trace_within`] for one of a run of coherent rays sharing
    /// `memory` (the occlusion rays of neighbouring hits): the same hit, bit
    /// for bit, as [`Scene::trace_from_with`] is for `trace_from`.
    #[inline]
    fn trace_within_with<'s>(
        &'s self,
        ray: &Ray,
        t_max: f32,
        memory: &mut WalkMemory<'s>,
    ) -> Option<Hit> {
        let _ = memory;
        self.trace_within(ray, t_max)
    }

    /// Bytes of voxel storage this scene holds (arrays and palette).
    fn storage_bytes(&self) -> usize;

    /// The scene's materials and emitters; `None` (the default): every
    /// palette entry is diffuse. Storages answer `None`; wrap one in
    /// [`crate::WithMaterials`] to give it materials.
    #[inline]
    fn materials(&self) -> Option<SceneMaterials<'_>> {
        None
    }
}

/// The tracing methods of [`Scene`], every one but `materials`, each
/// answered by the scene `$inner(self)` returns. The one list that
/// wrappers of a scene forward (a reference, [`crate::WithMaterials`]), so
/// that none of them falls back to a trait default that forgets what the
/// wrapped storage knows: its clear distances, its walk memories.
macro_rules! forward_tracing {
    ($inner:path) => {
        #[inline]
        fn bounds(&self) -> $crate::geom::IAabb {
            $inner(self).bounds()
        }

        #[inline]
        fn trace_counted(&self, ray: &$crate::geom::Ray) -> $crate::scene::Traced {
            $inner(self).trace_counted(ray)
        }

        fn trace_visiting(
            &self,
            ray: &$crate::geom::Ray,
            visit: &mut dyn FnMut($crate::geom::IAabb) -> bool,
        ) -> $crate::scene::Traced {
            $inner(self).trace_visiting(ray, visit)
        }

        #[inline]
        fn clear_distance(&self, frustum: &$crate::frustum::Frustum) -> f32 {
            $inner(self).clear_distance(frustum)
        }

        #[inline]
        fn trace_from(&self, ray: &$crate::geom::Ray, t_start: f32) -> $crate::scene::Traced {
            $inner(self).trace_from(ray, t_start)
        }

        #[inline]
        fn trace_from_with<'s>(
            &'s self,
            ray: &$crate::geom::Ray,
            t_start: f32,
            memory: &mut $crate::scene::WalkMemory<'s>,
        ) -> $crate::scene::Traced {
            $inner(self).trace_from_with(ray, t_start, memory)
        }

        #[inline]
        fn trace(&self, ray: &$crate::geom::Ray) -> Option<$crate::scene::Hit> {
            $inner(self).trace(ray)
        }

        #[inline]
        fn trace_within(&self, ray: &$crate::geom::Ray, t_max: f32) -> Option<$crate::scene::Hit> {
            $inner(self).trace_within(ray, t_max)
        }

        #[inline]
        fn trace_within_with<'s>(
            &'s self,
            ray: &$crate::geom::Ray,
            t_max: f32,
            memory: &mut $crate::scene::WalkMemory<'s>,
        ) -> Option<$crate::scene::Hit> {
            $inner(self).trace_within_with(ray, t_max, memory)
        }

        fn storage_bytes(&self) -> usize {
            $inner(self).storage_bytes()
        }
    };
}
pub(crate) use forward_tracing;

/// The scene a reference refers to.
#[inline(always)]
fn referent<'a, S: ?Sized>(scene: &'a &S) -> &'a S {
    scene
}

impl<S: Scene + ?Sized> Scene for &S {
    forward_tracing!(referent);

    fn materials(&self) -> Option<SceneMaterials<'_>> {
        (**self).materials()
    }
}

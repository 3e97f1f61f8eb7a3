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

/// Rays in a packet ([`Scene::trace_packet`], [`Scene::trace_lanes`]):
/// an 8x4 block of a camera's pixels, or rays their hits send on.
pub const PACKET: usize = 32;

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
/// of nodes down to where the last walk ended, and the last solid start
/// cell a walk found (rays from one origin start in one cell).
///
/// # Guarantees
/// A memory only ever changes where a walk begins its work, never what it
/// finds: [`Scene::trace_with`] gives the same hit, bit for bit, with a
/// new memory, a used one, or one another scene wrote (it is tied to the
/// scene that wrote it, which the lifetime keeps alive, and ignored by
/// every other).
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
    /// The last walk that found its start cell solid: the rays that share
    /// its origin and direction class (a camera's inside a voxel) have the
    /// same hit.
    pub(crate) solid_start: Option<SolidStart>,
    scene: PhantomData<&'s ()>,
}

/// A hit in a ray's start cell (at `t = 0`), for the rays that share its
/// origin and the direction class the start rule reads
/// ([`SolidStart::key_of`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SolidStart {
    /// Address of the scene that found it.
    pub(crate) owner: usize,
    /// The origin's bits and the direction class.
    pub(crate) key: [u32; 4],
    /// The hit every walk with this key reports.
    pub(crate) hit: Hit,
}

impl SolidStart {
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
            solid_start: None,
            scene: PhantomData,
        }
    }
}

impl Default for WalkMemory<'_> {
    fn default() -> Self {
        Self::new()
    }
}

/// The stretch of a ray a trace searches, by distance along its unit
/// direction.
///
/// # Guarantees
/// A trace over a reach reports exactly the hit a trace over
/// [`Reach::ALL`] reports when that hit's `t` is at most `max`, and
/// nothing otherwise, provided the ray hits nothing before `clear` (the
/// caller's promise, from [`Scene::clear_distance`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reach {
    /// A distance before which the ray is known to hit nothing: the walk
    /// may begin there (0: from the ray's origin).
    pub clear: f32,
    /// The farthest hit reported; the walk stops once it is past it.
    pub max: f32,
}

impl Reach {
    /// The whole ray.
    pub const ALL: Reach = Reach {
        clear: 0.0,
        max: f32::INFINITY,
    };

    /// The whole ray, known to hit nothing before `clear`.
    #[must_use]
    pub const fn after(clear: f32) -> Reach {
        Reach {
            clear,
            max: f32::INFINITY,
        }
    }

    /// Hits at most `max` away (an occlusion or shadow ray's reach).
    #[must_use]
    pub const fn within(max: f32) -> Reach {
        Reach { clear: 0.0, max }
    }
}

/// What a walk shows each empty box it moves through, nearest first (the
/// debug view draws their edges); when it returns `false` the walk stops
/// there and reports no hit. `None`: nothing is shown, at no cost.
pub type Visit<'v> = Option<&'v mut dyn FnMut(IAabb) -> bool>;

/// A voxel storage the tracer can shoot rays into.
///
/// One method traces, [`Scene::trace_with`]; the others are built on it,
/// so a storage or a wrapper cannot answer two ways.
///
/// # Guarantees
/// Every implementation in this crate returns, for every ray, the hit the
/// shared cell walk defines (see the crate docs): the same voxel, face and
/// `t`, bit for bit, whatever the storage, the reach's `clear` or the
/// memory. Tracing never allocates, never panics, and takes at most
/// [`crate::max_steps`] moves.
pub trait Scene {
    /// The volume the scene covers; nothing outside it is ever hit.
    fn bounds(&self) -> IAabb;

    /// The first solid voxel along `ray` within `reach`, with the walk's
    /// move count (the moves made, from where the walk began).
    ///
    /// `memory` is what the walks of coherent rays share (the pixels of a
    /// tile, in order; the occlusion rays of neighbouring hits): the
    /// storage may begin from what the previous walk left there, and leaves
    /// what the next one can use. `visit`, when given, is shown every empty
    /// box the walk moves through (cells for the dense array, node cubes
    /// for the octree), and then the walk covers the whole volume, not only
    /// the box of the solid voxels.
    fn trace_with<'s>(
        &'s self,
        ray: &Ray,
        reach: Reach,
        memory: &mut WalkMemory<'s>,
        visit: Visit<'_>,
    ) -> Traced;

    /// A distance before which no ray from the frustum's apex inside
    /// `frustum` hits a voxel: every such ray's hit, if any, has `t >=` the
    /// answer.
    /// What lets a tile of primary rays skip the empty space they share
    /// ([`Reach::after`]). The default knows nothing and answers 0.
    #[inline]
    fn clear_distance(&self, frustum: &Frustum) -> f32 {
        let _ = frustum;
        0.0
    }

    /// The hits of the rays of a packet whose bits are set in `lanes`
    /// (a camera's neighbouring pixels, or the shadow or occlusion rays
    /// of neighbouring hits), each traced over `reach`: for every lane
    /// `i` whose bit is set in the answer (only lanes of `lanes`),
    /// `hits[i]` is exactly the hit [`Scene::trace_with`] gives `rays[i]`
    /// over that reach, bit for bit, provided no ray hits anything before
    /// `reach.clear` (the promise of [`Reach`]). Lanes left unset (their
    /// `hits` untouched) are the caller's to trace one by one. What lets
    /// a storage walk coherent rays together; the default answers no
    /// lane.
    #[inline]
    fn trace_packet(
        &self,
        rays: &[Ray; PACKET],
        lanes: u32,
        reach: Reach,
        hits: &mut [Option<Hit>; PACKET],
    ) -> u32 {
        let _ = (rays, lanes, reach, hits);
        0
    }

    /// The hits of the lanes of `rays` whose bits are set in `lanes`,
    /// each over `reach`, into `hits` (other lanes untouched): exactly
    /// what [`Scene::trace_with`] gives each, found in a packet where the
    /// storage can ([`Scene::trace_packet`]), the rest one by one, their
    /// walks beginning from `memory`. A reach clear forever hits nothing:
    /// no ray is traced. Returns the lanes answered without a walk of
    /// their own (by the packet, or by a reach clear forever).
    #[inline]
    fn trace_lanes<'s>(
        &'s self,
        rays: &[Ray; PACKET],
        lanes: u32,
        reach: Reach,
        memory: &mut WalkMemory<'s>,
        hits: &mut [Option<Hit>; PACKET],
    ) -> u32 {
        let mut alone = lanes;
        if reach.clear == f32::INFINITY {
            alone = 0;
            for (i, hit) in hits.iter_mut().enumerate() {
                if lanes >> i & 1 != 0 {
                    *hit = None;
                }
            }
        } else if lanes != 0 {
            alone &= !self.trace_packet(rays, lanes, reach, hits);
        }
        let together = lanes & !alone;
        // The lanes the packet left, lowest first.
        while alone != 0 {
            let i = alone.trailing_zeros() as usize;
            alone &= alone - 1;
            hits[i] = self.trace_with(&rays[i], reach, memory, None).hit;
        }
        together
    }

    /// The solid voxel in `cell`, as the hit of a ray that starts strictly
    /// inside it (no face, `t` 0), or `None` for an empty cell: a point
    /// lookup, for a path that needs to know what lies across a face (a
    /// path through glass). A storage may begin its lookup from `memory`
    /// and leave there the way to `cell`; the default traces a ray from
    /// the cell's center over no distance (exact for every cell within
    /// [`crate::MAX_COORD`]).
    #[inline]
    fn voxel_at<'s>(&'s self, cell: IVec3, memory: &mut WalkMemory<'s>) -> Option<Hit> {
        let center = Ray::new(cell.as_vec3() + 0.5, glam::Vec3::X).ok()?;
        self.trace_with(&center, Reach::within(0.0), memory, None)
            .hit
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

    /// The first solid voxel along `ray`.
    #[inline]
    fn trace(&self, ray: &Ray) -> Option<Hit> {
        self.trace_counted(ray).hit
    }

    /// The first solid voxel along `ray`, with the walk's move count.
    #[inline]
    fn trace_counted(&self, ray: &Ray) -> Traced {
        self.trace_with(ray, Reach::ALL, &mut WalkMemory::new(), None)
    }

    /// The first solid voxel along `ray` if it is at most `t_max` away:
    /// exactly `trace(ray).filter(|h| h.t <= t_max)`, but the walk stops
    /// once `t_max` is passed (what makes short occlusion rays cheap).
    #[inline]
    fn trace_within(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let memory = &mut WalkMemory::new();
        self.trace_with(ray, Reach::within(t_max), memory, None).hit
    }

    /// [`Scene::trace_counted`], also showing `visit` every empty box the
    /// walk moves through ([`Visit`]).
    #[inline]
    fn trace_visiting(&self, ray: &Ray, visit: &mut dyn FnMut(IAabb) -> bool) -> Traced {
        self.trace_with(ray, Reach::ALL, &mut WalkMemory::new(), Some(visit))
    }
}

/// The methods of [`Scene`] a wrapper of a scene forwards (a reference,
/// [`crate::WithMaterials`]): the one tracing method and those with a
/// default, each answered by the scene `$inner(self)` returns, so that no
/// wrapper falls back to a default that forgets what the wrapped storage
/// knows (its clear distances).
macro_rules! forward_tracing {
    ($inner:path) => {
        #[inline]
        fn bounds(&self) -> $crate::geom::IAabb {
            $inner(self).bounds()
        }

        #[inline]
        fn trace_with<'s>(
            &'s self,
            ray: &$crate::geom::Ray,
            reach: $crate::scene::Reach,
            memory: &mut $crate::scene::WalkMemory<'s>,
            visit: $crate::scene::Visit<'_>,
        ) -> $crate::scene::Traced {
            $inner(self).trace_with(ray, reach, memory, visit)
        }

        #[inline]
        fn clear_distance(&self, frustum: &$crate::frustum::Frustum) -> f32 {
            $inner(self).clear_distance(frustum)
        }

        #[inline]
        fn trace_packet(
            &self,
            rays: &[$crate::geom::Ray; $crate::scene::PACKET],
            lanes: u32,
            reach: $crate::scene::Reach,
            hits: &mut [Option<$crate::scene::Hit>; $crate::scene::PACKET],
        ) -> u32 {
            $inner(self).trace_packet(rays, lanes, reach, hits)
        }

        #[inline]
        fn voxel_at<'s>(
            &'s self,
            cell: glam::IVec3,
            memory: &mut $crate::scene::WalkMemory<'s>,
        ) -> Option<$crate::scene::Hit> {
            $inner(self).voxel_at(cell, memory)
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

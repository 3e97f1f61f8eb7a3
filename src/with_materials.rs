//! `WithMaterials`: a storage together with the materials of its palette
//! entries and its light list, as one [`Scene`].

use glam::IVec3;

use crate::frustum::Frustum;
use crate::geom::{IAabb, Ray};
use crate::material::{Materials, SceneMaterials};
use crate::scene::{Hit, Scene, Traced, WalkMemory};

/// `scene`'s voxels with `materials` and the emissive voxels `emitters`:
/// traces exactly as `scene` does (coherent rays' walk memories included:
/// they are handed on, so its walks keep their shared starts), and the
/// renderer shades its hits with their materials. Borrowing, so it allocates nothing and works without
/// `alloc`.
///
/// ```
/// use voxtrace::{IAabb, Material, Materials, OctreeScene, Scene, VoxelGenerator, WithMaterials};
///
/// let storage = OctreeScene::build(&VoxelGenerator::new(1), IAabb::centered(16))?;
/// let mut materials = Materials::all_diffuse();
/// materials.set(3, Material::metal(1.0, 0.1)?);
/// let scene = WithMaterials::new(&storage, &materials, &[]);
/// assert!(scene.materials().is_some());
/// # Ok::<(), voxtrace::Error>(())
/// ```
#[derive(Clone, Copy, Debug)]
pub struct WithMaterials<'a, S> {
    scene: S,
    materials: &'a Materials,
    emitters: &'a [IVec3],
}

impl<'a, S: Scene> WithMaterials<'a, S> {
    /// `scene` shaded with `materials`, sampling `emitters` (the positions of
    /// its emissive voxels; may be empty) as lights.
    pub fn new(scene: S, materials: &'a Materials, emitters: &'a [IVec3]) -> Self {
        WithMaterials {
            scene,
            materials,
            emitters,
        }
    }
}

impl<S: Scene> Scene for WithMaterials<'_, S> {
    #[inline]
    fn bounds(&self) -> IAabb {
        self.scene.bounds()
    }

    #[inline]
    fn trace_counted(&self, ray: &Ray) -> Traced {
        self.scene.trace_counted(ray)
    }

    fn trace_visiting(&self, ray: &Ray, visit: &mut dyn FnMut(IAabb) -> bool) -> Traced {
        self.scene.trace_visiting(ray, visit)
    }

    #[inline]
    fn clear_distance(&self, frustum: &Frustum) -> f32 {
        self.scene.clear_distance(frustum)
    }

    #[inline]
    fn trace_from(&self, ray: &Ray, t_start: f32) -> Traced {
        self.scene.trace_from(ray, t_start)
    }

    #[inline]
    fn trace_from_with<'s>(
        &'s self,
        ray: &Ray,
        t_start: f32,
        memory: &mut WalkMemory<'s>,
    ) -> Traced {
        self.scene.trace_from_with(ray, t_start, memory)
    }

    #[inline]
    fn trace(&self, ray: &Ray) -> Option<Hit> {
        self.scene.trace(ray)
    }

    #[inline]
    fn trace_within(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        self.scene.trace_within(ray, t_max)
    }

    #[inline]
    fn trace_within_with<'s>(
        &'s self,
        ray: &Ray,
        t_max: f32,
        memory: &mut WalkMemory<'s>,
    ) -> Option<Hit> {
        self.scene.trace_within_with(ray, t_max, memory)
    }

    fn storage_bytes(&self) -> usize {
        self.scene.storage_bytes()
    }

    fn materials(&self) -> Option<SceneMaterials<'_>> {
        Some(SceneMaterials {
            table: self.materials,
            emitters: self.emitters,
        })
    }
}

#[cfg(all(test, feature = "alloc"))]
mod tests {
    use glam::Vec3;

    use super::WithMaterials;
    use crate::geom::{IAabb, Ray};
    use crate::material::Materials;
    use crate::scene::{Scene, WalkMemory};
    use crate::source::terrain::VoxelGenerator;
    use crate::storage::octree::OctreeScene;

    /// The wrapper hands coherent rays' memory to its storage (which
    /// claims it), and the hits stay the storage's own.
    #[test]
    fn walks_through_the_wrapper_share_the_storages_memory() {
        let storage = OctreeScene::build(&VoxelGenerator::new(3), IAabb::centered(24)).unwrap();
        let diffuse = Materials::all_diffuse();
        let wrapped = WithMaterials::new(&storage, &diffuse, &[]);
        let owner = &storage as *const OctreeScene<_, _> as usize;
        let origin = Vec3::new(20.0, 22.0, 19.5);
        let (mut from, mut within) = (WalkMemory::new(), WalkMemory::new());
        let mut hits = 0;
        for i in 0..64 {
            let dir = Vec3::new(-1.0 + i as f32 / 100.0, -0.8, -0.9 + i as f32 / 70.0);
            let ray = Ray::new(origin, dir).unwrap();
            let traced = wrapped.trace_from_with(&ray, 0.5, &mut from);
            assert_eq!(traced.hit, storage.trace_from(&ray, 0.5).hit, "{ray:?}");
            let near = wrapped.trace_within_with(&ray, 30.0, &mut within);
            assert_eq!(near, storage.trace_within(&ray, 30.0), "{ray:?}");
            hits += usize::from(traced.hit.is_some());
        }
        assert!(hits > 32, "only {hits} rays hit the terrain");
        assert_eq!(from.owner, owner, "trace_from_with forgot the memory");
        assert_eq!(within.owner, owner, "trace_within_with forgot the memory");
    }
}

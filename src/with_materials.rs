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
/// renderer shades its hits with their materials. Borrowing, so it
/// allocates nothing and works without `alloc`.
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

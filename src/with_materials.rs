//! `WithMaterials`: a storage together with the materials of its palette
//! entries and its light list, as one [`Scene`].

use glam::IVec3;

use crate::material::{Materials, SceneMaterials};
use crate::scene::{forward_tracing, Scene};

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

/// The storage a [`WithMaterials`] wraps.
#[inline(always)]
fn storage<'a, S>(wrapped: &'a WithMaterials<'_, S>) -> &'a S {
    &wrapped.scene
}

impl<S: Scene> Scene for WithMaterials<'_, S> {
    forward_tracing!(storage);

    fn materials(&self) -> Option<SceneMaterials<'_>> {
        Some(SceneMaterials {
            table: self.materials,
            emitters: self.emitters,
        })
    }
}

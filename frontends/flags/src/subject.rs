//! What a frontend shows and the storage it builds of it, written once for
//! the CLI and the web page: the seeded terrain or a `.vox` model
//! ([`Subject`]), what its camera frames ([`Subject::stage`]), and the
//! storage of either kind built from it ([`Built`]), traced with the
//! model's materials as every frontend traces it ([`Built::trace`]).

use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{
    CameraSettings, DenseScene, Error, IAabb, Node, OctreeScene, Scene, SceneMaterials, VoxModel,
    VoxelGenerator, VoxelSource, WithMaterials,
};

use crate::{Boxes, Stage};

/// Which storage holds the voxels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Backend {
    /// Flat array, one byte per voxel, Amanatides & Woo traversal.
    Dense,
    /// Sparse pointer-free octree (alias: sparse).
    #[cfg_attr(feature = "clap", value(alias = "sparse"))]
    Octree,
}

impl Backend {
    /// The name users type: `dense` or `octree`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Backend::Dense => "dense",
            Backend::Octree => "octree",
        }
    }
}

/// What a frontend renders.
pub enum Subject {
    /// The seeded terrain over `[-size, size)^3`.
    Terrain {
        /// The terrain's seed.
        seed: u64,
        /// The extent N (`--size`).
        size: i32,
    },
    /// A `.vox` scene (boxed: its palette alone is 768 bytes).
    Model(Box<VoxModel>),
}

/// A model's materials and light list as the renderer takes them.
#[must_use]
pub fn materials_of(model: &VoxModel) -> SceneMaterials<'_> {
    SceneMaterials {
        table: model.materials(),
        emitters: model.emitters(),
    }
}

impl Subject {
    /// The loaded scene, `None` for the terrain.
    #[must_use]
    pub fn model(&self) -> Option<&VoxModel> {
        match self {
            Subject::Model(model) => Some(model),
            Subject::Terrain { .. } => None,
        }
    }

    /// The box the storage is built over.
    #[must_use]
    pub fn bounds(&self) -> IAabb {
        match self {
            Subject::Terrain { size, .. } => IAabb::centered(*size),
            Subject::Model(model) => model.bounds(),
        }
    }

    /// What the camera flags frame: the terrain's box from the paper's
    /// position, or the model's voxels, each its own box, around its
    /// bounds' center.
    #[must_use]
    pub fn stage(&self) -> Stage<'_> {
        match self {
            Subject::Terrain { size, .. } => Stage {
                boxes: Boxes::Bounds(IAabb::centered(*size)),
                target: Vec3::ZERO,
                default_position: Some(CameraSettings::paper(*size).lookfrom),
            },
            Subject::Model(model) => Stage {
                boxes: Boxes::Model(model),
                target: (model.bounds().min + model.bounds().max).as_vec3() * 0.5,
                default_position: None,
            },
        }
    }

    /// The material at `pos`, to tell a camera inside a voxel.
    #[must_use]
    pub fn material(&self, pos: IVec3) -> u8 {
        match self {
            Subject::Terrain { seed, .. } => VoxelGenerator::new(*seed).material(pos),
            Subject::Model(model) => model.material(pos),
        }
    }

    /// The materials to shade the storage with: the model's, `None` (all
    /// diffuse) for the terrain.
    #[must_use]
    pub fn materials(&self) -> Option<SceneMaterials<'_>> {
        self.model().map(materials_of)
    }

    /// `backend` built over [`Subject::bounds`], in parallel when
    /// `threaded` (and built with the `rayon` feature).
    ///
    /// # Errors
    /// The core's refusal (out of memory, a volume too large).
    pub fn build(&self, backend: Backend, threaded: bool) -> Result<Built, Error> {
        match self {
            Subject::Terrain { seed, size } => Built::build(
                backend,
                &VoxelGenerator::new(*seed),
                IAabb::centered(*size),
                threaded,
            ),
            Subject::Model(model) => {
                Built::build(backend, model.as_ref(), model.bounds(), threaded)
            }
        }
    }
}

/// A storage of either kind.
pub enum Built {
    /// The flat array.
    Dense(DenseScene<Vec<u8>>),
    /// The sparse octree.
    Octree(OctreeScene<Vec<Node>, Vec<u8>>),
}

/// Work on a scene, compiled for each storage and materials
/// ([`Built::trace`]): the hot loop never calls through `dyn`.
pub trait Tracer {
    /// What the work gives.
    type Output;
    /// Does the work on `scene`.
    fn trace<S: Scene + Sync>(self, scene: &S) -> Self::Output;
}

impl Built {
    /// `backend` built from `source` over `bounds`, in parallel when
    /// `threaded` (and built with the `rayon` feature).
    ///
    /// # Errors
    /// The core's refusal (out of memory, a volume too large).
    pub fn build<S: VoxelSource + Sync + ?Sized>(
        backend: Backend,
        source: &S,
        bounds: IAabb,
        threaded: bool,
    ) -> Result<Built, Error> {
        match (backend, threaded && cfg!(feature = "rayon")) {
            #[cfg(feature = "rayon")]
            (Backend::Dense, true) => DenseScene::build_parallel(source, bounds).map(Built::Dense),
            #[cfg(feature = "rayon")]
            (Backend::Octree, true) => {
                OctreeScene::build_parallel(source, bounds).map(Built::Octree)
            }
            (Backend::Dense, _) => DenseScene::build(source, bounds).map(Built::Dense),
            (Backend::Octree, _) => OctreeScene::build(source, bounds).map(Built::Octree),
        }
    }

    /// The storage as the tracer sees it.
    #[must_use]
    pub fn scene(&self) -> &(dyn Scene + Sync) {
        match self {
            Built::Dense(scene) => scene,
            Built::Octree(scene) => scene,
        }
    }

    /// `tracer`'s work on the storage shaded with `materials` (`None`:
    /// all diffuse).
    pub fn trace<T: Tracer>(&self, materials: Option<SceneMaterials<'_>>, tracer: T) -> T::Output {
        match (self, materials) {
            (Built::Dense(scene), None) => tracer.trace(scene),
            (Built::Octree(scene), None) => tracer.trace(scene),
            (Built::Dense(scene), Some(m)) => {
                tracer.trace(&WithMaterials::new(scene, m.table, m.emitters))
            }
            (Built::Octree(scene), Some(m)) => {
                tracer.trace(&WithMaterials::new(scene, m.table, m.emitters))
            }
        }
    }
}

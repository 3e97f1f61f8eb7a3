//! What a render shows: the seeded terrain or a loaded `.vox` scene, and
//! what each stage of the run asks of it (its box, the stage its camera
//! frames, the cameras a file carries, what a tile's hash names, the
//! memory it already holds, the storage built from it).

use std::path::Path;
use std::time::Duration;

use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{CameraSettings, IAabb, SceneMaterials, VoxModel, VoxelGenerator, VoxelSource};
use voxtrace_cli::errors::show_path;
use voxtrace_cli::{Backend, BuiltScene};
use voxtrace_flags::{Boxes, Stage};

use crate::effects::materials_of;
use crate::farm::TileScene;
use crate::vox_camera::FileCameras;

/// What the CLI renders.
pub enum Subject<'a> {
    /// The seeded terrain over `[-size, size)^3`; a `random` seed is
    /// printed once the run has succeeded.
    Terrain {
        /// The terrain's seed.
        seed: u64,
        /// Whether the seed was drawn at random (no `--seed`).
        random: bool,
        /// The extent N (`--size`).
        size: i32,
    },
    /// A `.vox` scene and the file it was loaded from (boxed: its palette
    /// alone is 768 bytes).
    Model {
        /// The `--vox` file, as messages name it.
        path: &'a Path,
        /// The scene.
        model: Box<VoxModel>,
    },
}

/// A seed from the clock and process id: different per run, printed so the
/// render can be reproduced.
fn random_seed() -> u64 {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos() as u64);
    let mut mix = voxtrace::SplitMix64::new(nanos ^ u64::from(std::process::id()) << 32);
    mix.next_u64() >> 1 // keep it readable as a positive i64 too
}

/// The terrain's seed, `--seed` or else one drawn at random, and whether it
/// was drawn (and so must be printed, once the run is known to go ahead).
pub fn terrain_seed(seed: Option<u64>) -> (u64, bool) {
    match seed {
        Some(seed) => (seed, false),
        None => (random_seed(), true),
    }
}

impl<'a> Subject<'a> {
    /// The `vox` file's scene, or else the terrain of `seed` (drawn at
    /// random without one) and `size`.
    ///
    /// # Errors
    /// One line naming the file, when it cannot be loaded.
    pub fn load(vox: Option<&'a Path>, seed: Option<u64>, size: i32) -> Result<Self, String> {
        Ok(match vox {
            Some(path) => Subject::Model {
                path,
                model: Box::new(
                    VoxModel::load(path)
                        .map_err(|e| format!("cannot load --vox {}: {e}", show_path(path)))?,
                ),
            },
            None => {
                let (seed, random) = terrain_seed(seed);
                Subject::Terrain { seed, random, size }
            }
        })
    }

    /// The loaded scene, `None` for the terrain.
    pub fn model(&self) -> Option<&VoxModel> {
        match self {
            Subject::Model { model, .. } => Some(model),
            Subject::Terrain { .. } => None,
        }
    }

    /// The box the storage is built over.
    pub fn bounds(&self) -> IAabb {
        match self {
            Subject::Terrain { size, .. } => IAabb::centered(*size),
            Subject::Model { model, .. } => model.bounds(),
        }
    }

    /// What the camera flags frame: the terrain's box from the paper's
    /// position, or the model's voxels around its center.
    pub fn stage(&self) -> Stage<'_> {
        match self {
            Subject::Terrain { size, .. } => Stage {
                boxes: Boxes::Bounds(IAabb::centered(*size)),
                target: Vec3::ZERO,
                default_position: Some(CameraSettings::paper(*size).lookfrom),
            },
            Subject::Model { model, .. } => Stage {
                boxes: Boxes::Model(model),
                target: (model.bounds().min + model.bounds().max).as_vec3() * 0.5,
                default_position: None,
            },
        }
    }

    /// The cameras `--camera` may pick from (none for the terrain).
    pub fn cameras(&self) -> FileCameras<'_> {
        match self {
            Subject::Model { path, model } => Some((path, model)),
            Subject::Terrain { .. } => None,
        }
    }

    /// What a tile's settings hash names of this scene.
    pub fn tile_scene(&self) -> TileScene<'_> {
        match self {
            Subject::Model { path, .. } => TileScene::Vox(path),
            Subject::Terrain { seed, size, .. } => TileScene::Terrain {
                seed: *seed,
                size: *size,
            },
        }
    }

    /// The loaded model's solid voxels and heap bytes, for the memory
    /// budget (`None` for the terrain, which is generated as it is built).
    pub fn loaded(&self) -> Option<(u64, u128)> {
        self.model()
            .map(|model| (model.voxel_count() as u64, model.heap_bytes() as u128))
    }

    /// The file's MATL values that could not be used as they are, each
    /// prefixed with the file's path.
    pub fn warnings(&self) -> Vec<String> {
        match self {
            Subject::Model { path, model } => model
                .warnings()
                .iter()
                .map(|w| format!("{}: {w}", show_path(path)))
                .collect(),
            Subject::Terrain { .. } => Vec::new(),
        }
    }

    /// The material at `pos`, to tell a camera inside a voxel.
    pub fn material(&self, pos: IVec3) -> u8 {
        match self {
            Subject::Terrain { seed, .. } => VoxelGenerator::new(*seed).material(pos),
            Subject::Model { model, .. } => model.material(pos),
        }
    }

    /// Builds `backend` over [`Subject::bounds`] (in parallel when
    /// `threaded`): the storage, the build's wall time, and the materials to shade it with
    /// (`None`: all diffuse, the terrain).
    ///
    /// # Errors
    /// [`BuiltScene::build_from`]'s one line.
    pub fn build(
        &self,
        backend: Backend,
        threaded: bool,
    ) -> Result<(BuiltScene, Duration, Option<SceneMaterials<'_>>), String> {
        let bounds = self.bounds();
        match self {
            Subject::Terrain { seed, .. } => {
                let terrain = VoxelGenerator::new(*seed);
                let (built, build) = BuiltScene::build_from(backend, &terrain, bounds, threaded)?;
                Ok((built, build, None))
            }
            Subject::Model { model, .. } => {
                let (built, build) =
                    BuiltScene::build_from(backend, model.as_ref(), bounds, threaded)?;
                Ok((built, build, Some(materials_of(model))))
            }
        }
    }
}

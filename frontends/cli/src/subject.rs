//! What a render shows: the shared crate's [`voxtrace_flags::Subject`]
//! (the seeded terrain or a loaded `.vox` scene, framed and built as every
//! frontend does), with what only the CLI asks of it (the file it came
//! from, for messages, `--camera` and a tile's settings; whether its seed was
//! drawn at random; the memory it already holds).

use std::path::Path;
use std::time::Duration;

use voxtrace::{SceneMaterials, VoxModel};
use voxtrace_cli::errors::show_path;
use voxtrace_cli::part::fnv1a64;
use voxtrace_cli::{Backend, BuiltScene};

/// The cameras `--camera` may pick from: the `.vox` file's path and the
/// scene loaded from it; `None` for the terrain.
pub type FileCameras<'a> = Option<(&'a Path, &'a VoxModel)>;

/// What the CLI renders.
pub struct Subject<'a> {
    /// The terrain or the model.
    pub shown: voxtrace_flags::Subject,
    /// The `--vox` file, as messages name it; `None` for the terrain.
    pub path: Option<&'a Path>,
    /// Whether the terrain's seed was drawn at random (no `--seed`): it
    /// is printed once the run has succeeded.
    pub random: bool,
    /// The animation frame shown (`--frame`; 0 for a still and the
    /// terrain).
    pub frame: u32,
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
    pub fn load(
        vox: Option<&'a Path>,
        frame: u32,
        seed: Option<u64>,
        size: i32,
    ) -> Result<Self, String> {
        let Some(path) = vox else {
            let (seed, random) = terrain_seed(seed);
            let shown = voxtrace_flags::Subject::Terrain { seed, size };
            return Ok(Subject {
                shown,
                path: None,
                random,
                frame: 0,
            });
        };
        let model = voxtrace::VoxModel::load_frame(path, frame)
            .map_err(|e| format!("cannot load --vox {}: {e}", show_path(path)))?;
        Ok(Subject {
            shown: voxtrace_flags::Subject::Model(Box::new(model)),
            path: Some(path),
            random: false,
            frame,
        })
    }

    /// The cameras `--camera` may pick from (none for the terrain).
    pub fn cameras(&self) -> FileCameras<'_> {
        self.path.zip(self.shown.model())
    }

    /// What a tile's settings text names of this scene: the terrain's
    /// seed and size, or the hash of the `--vox` file's contents (read
    /// again now, when a tile is rendered).
    ///
    /// # Errors
    /// One line naming the file, when it cannot be read.
    pub fn tile_text(&self) -> Result<String, String> {
        match (&self.shown, self.path) {
            (voxtrace_flags::Subject::Terrain { seed, size }, _) => {
                Ok(format!("terrain seed={seed} size={size}"))
            }
            (_, path) => {
                let path = path.unwrap_or(Path::new(""));
                let bytes = std::fs::read(path)
                    .map_err(|e| format!("cannot load --vox {}: {e}", show_path(path)))?;
                let hash = fnv1a64(&bytes);
                // A still's text as before animation frames were read.
                Ok(match self.shown.model().map_or(1, |m| m.frames()) {
                    1 => format!("vox fnv1a64={hash:016x}"),
                    _ => format!("vox fnv1a64={hash:016x} frame={}", self.frame),
                })
            }
        }
    }

    /// The loaded model's solid voxels and heap bytes, for the memory
    /// budget (`None` for the terrain, which is generated as it is built).
    pub fn loaded(&self) -> Option<(u64, u128)> {
        let model = self.shown.model()?;
        Some((model.voxel_count() as u64, model.heap_bytes() as u128))
    }

    /// The file's MATL values that could not be used as they are, each
    /// prefixed with the file's path.
    pub fn warnings(&self) -> Vec<String> {
        let (Some(path), Some(model)) = (self.path, self.shown.model()) else {
            return Vec::new();
        };
        let path = show_path(path);
        model
            .warnings()
            .iter()
            .map(|w| format!("{path}: {w}"))
            .collect()
    }

    /// Builds `backend` (in parallel when `threaded`): the storage, the
    /// build's wall time, and the materials to shade it with (`None`: all
    /// diffuse, the terrain).
    ///
    /// # Errors
    /// [`BuiltScene::build_from`]'s one line.
    pub fn build(
        &self,
        backend: Backend,
        threaded: bool,
    ) -> Result<(BuiltScene, Duration, Option<SceneMaterials<'_>>), String> {
        let (built, took) = match &self.shown {
            voxtrace_flags::Subject::Terrain { seed, size } => {
                BuiltScene::build(backend, *size, *seed, threaded)?
            }
            voxtrace_flags::Subject::Model(model) => {
                BuiltScene::build_from(backend, model.as_ref(), model.bounds(), threaded)?
            }
        };
        Ok((built, took, self.shown.materials()))
    }
}

//! Build a storage from the seeded terrain, render a region of a frame.
//!
//! One thread count decides both steps: `Some(1)` runs the sequential build
//! and the render into a buffer on the calling thread; anything else runs
//! the parallel build and the render into the atomic framebuffer on a rayon
//! pool (see [`on_threads`]). Both give the same bytes.

use std::time::{Duration, Instant};

use clap::ValueEnum;

use crate::render_job::{Pass, RenderJob, Rendered};
use crate::units::human_bytes;
use voxtrace::rayon::ThreadPoolBuilder;
use voxtrace::{
    Camera, DenseScene, Error, IAabb, Node, OctreeScene, PixelSamples, Rect, RenderOptions,
    RoundsDone, Scene, SceneMaterials, VoxelGenerator, VoxelSource, WithMaterials,
};

/// Which storage holds the voxels.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, ValueEnum)]
pub enum Backend {
    /// Flat array, one byte per voxel, Amanatides & Woo traversal.
    Dense,
    /// Sparse pointer-free octree (alias: sparse).
    #[value(alias = "sparse")]
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

/// Runs `work` with `threads` workers: on the calling thread for `Some(1)`,
/// otherwise inside a new rayon pool of that many threads (`None`: one per
/// core), so that the parallel build and render inside use exactly those.
pub fn on_threads<R: Send>(
    threads: Option<u16>,
    work: impl FnOnce() -> Result<R, String> + Send,
) -> Result<R, String> {
    match threads {
        Some(1) => work(),
        threads => {
            let count = threads.map_or(0, usize::from); // 0: rayon picks all cores
            ThreadPoolBuilder::new()
                .num_threads(count)
                .build()
                .map_err(|e| format!("cannot start {count} worker threads: {e}"))?
                .install(work)
        }
    }
}

/// A storage built from the terrain, either kind.
pub enum BuiltScene {
    /// The flat array.
    Dense(DenseScene<Vec<u8>>),
    /// The sparse octree.
    Octree(OctreeScene<Vec<Node>, Vec<u8>>),
}

impl BuiltScene {
    /// Builds `backend` over the volume `[-size, size)^3` of the terrain of
    /// `seed`, in parallel unless `threaded` is false; returns the scene and
    /// the build's wall time.
    ///
    /// # Errors
    /// A one-line message; for a dense array that cannot be allocated it
    /// names the bytes it needs.
    pub fn build(
        backend: Backend,
        size: i32,
        seed: u64,
        threaded: bool,
    ) -> Result<(BuiltScene, Duration), String> {
        let terrain = VoxelGenerator::new(seed);
        BuiltScene::build_from(backend, &terrain, IAabb::centered(size), threaded)
    }

    /// Builds `backend` from any voxel source over `bounds`, in parallel
    /// unless `threaded` is false; returns the scene and the build's wall
    /// time.
    ///
    /// # Errors
    /// A one-line message; for a dense array that cannot be allocated it
    /// names the bytes it needs.
    pub fn build_from<S: VoxelSource + Sync + ?Sized>(
        backend: Backend,
        source: &S,
        bounds: IAabb,
        threaded: bool,
    ) -> Result<(BuiltScene, Duration), String> {
        let started = Instant::now();
        let describe = |e: Error| match e {
            Error::OutOfMemory { bytes } => format!(
                "cannot build the {} scene: out of memory: could not allocate {}",
                backend.name(),
                human_bytes(bytes as u128)
            ),
            e => format!("cannot build the {} scene: {e}", backend.name()),
        };
        let scene = match backend {
            Backend::Dense => {
                let built = if threaded {
                    DenseScene::build_parallel(source, bounds)
                } else {
                    DenseScene::build(source, bounds)
                };
                BuiltScene::Dense(built.map_err(|e| match e {
                    Error::OutOfMemory { .. } | Error::SizeOverflow => {
                        // Exact even when it overflows usize: one byte per voxel.
                        let size = bounds.size();
                        let bytes: u128 = [size.x, size.y, size.z]
                            .iter()
                            .map(|&s| u128::from(s.unsigned_abs()))
                            .product();
                        format!(
                            "the dense array for this scene needs {} (one per voxel), \
                             more than can be allocated; try --backend octree",
                            human_bytes(bytes)
                        )
                    }
                    e => describe(e),
                })?)
            }
            Backend::Octree => {
                let built = if threaded {
                    OctreeScene::build_parallel(source, bounds)
                } else {
                    OctreeScene::build(source, bounds)
                };
                BuiltScene::Octree(built.map_err(describe)?)
            }
        };
        Ok((scene, started.elapsed()))
    }

    /// The storage as the tracer sees it.
    #[must_use]
    pub fn scene(&self) -> &(dyn Scene + Sync) {
        match self {
            BuiltScene::Dense(scene) => scene,
            BuiltScene::Octree(scene) => scene,
        }
    }

    /// Renders `region` of `camera`'s frame of the storage shaded with
    /// `materials` (a `.vox` file's; `None`: all diffuse): into a buffer on
    /// the calling thread unless `threaded`, else into the atomic
    /// framebuffer on the current rayon pool. `progress` hears of every
    /// finished band's row count.
    ///
    /// # Errors
    /// A one-line message if the region does not fit the frame or its pixels
    /// cannot be allocated.
    pub fn render_with(
        &self,
        materials: Option<SceneMaterials<'_>>,
        camera: &Camera,
        region: Rect,
        options: &RenderOptions,
        threaded: bool,
        progress: &(dyn Fn(u32) + Sync),
    ) -> Result<Rendered, String> {
        let job = RenderJob {
            camera,
            region,
            options,
            threaded,
            progress,
        };
        let (rendered, _) = self.run(materials, &job, Pass::Once)?;
        Ok(rendered)
    }

    /// [`BuiltScene::render_with`], the samples taken in rounds over the
    /// whole region (`voxtrace::render_in_rounds`, threaded or
    /// not): `keep_going(n)`, asked after round `n` while a pixel has
    /// samples left, says whether another round begins. `progress` hears
    /// of the rows of every round. Returns the rounds taken beside the
    /// frame, which is the one-pass frame of `voxtrace::Rounds`'
    /// options after them. With `keep_radiance`, the frame's mean radiance
    /// comes back too (for the denoiser) where it is path-traced.
    ///
    /// # Errors
    /// As [`BuiltScene::render_with`]; also when the pixels' state
    /// between rounds cannot be allocated.
    #[allow(clippy::too_many_arguments)]
    pub fn render_in_rounds(
        &self,
        materials: Option<SceneMaterials<'_>>,
        camera: &Camera,
        region: Rect,
        options: &RenderOptions,
        threaded: bool,
        progress: &(dyn Fn(u32) + Sync),
        keep_going: &mut dyn FnMut(u32) -> bool,
        keep_radiance: bool,
    ) -> Result<(Rendered, RoundsDone), String> {
        let job = RenderJob {
            camera,
            region,
            options,
            threaded,
            progress,
        };
        let pass = Pass::Rounds {
            keep_going,
            keep_radiance,
        };
        let (rendered, done) = self.run(materials, &job, pass)?;
        Ok((
            rendered,
            done.expect("a render in rounds reports its rounds"),
        ))
    }

    /// Runs `job` on the storage shaded with `materials`, monomorphized
    /// per storage and materials: the hot loop never calls through `dyn`.
    fn run(
        &self,
        materials: Option<SceneMaterials<'_>>,
        job: &RenderJob<'_>,
        pass: Pass<'_>,
    ) -> Result<(Rendered, Option<RoundsDone>), String> {
        match (self, materials) {
            (BuiltScene::Dense(scene), None) => job.run(scene, pass),
            (BuiltScene::Octree(scene), None) => job.run(scene, pass),
            (BuiltScene::Dense(scene), Some(m)) => {
                job.run(&WithMaterials::new(scene, m.table, m.emitters), pass)
            }
            (BuiltScene::Octree(scene), Some(m)) => {
                job.run(&WithMaterials::new(scene, m.table, m.emitters), pass)
            }
        }
    }
}

/// The bytes a render in rounds keeps per pixel between rounds, beside
/// the frame ([`BuiltScene::render_in_rounds`]).
pub const ROUND_STATE_BYTES: u64 = std::mem::size_of::<PixelSamples>() as u64;

#[cfg(test)]
mod tests {
    #[test]
    fn a_pixel_keeps_64_bytes_between_rounds() {
        // docs/cli.md says so; the memory check counts them.
        assert_eq!(super::ROUND_STATE_BYTES, 64);
    }
}

//! The `speed` report's constants and measured figures. `speed` (which
//! measures) and `speed_tables` (which writes the tables and charts) both
//! import them; `speed` calls `speed_tables`, never the other way round.

use voxtrace_cli::Backend;

/// The seed paper's scene sizes, and the octree-only sizes past them.
pub(crate) const TABLE_SIZES: [i32; 3] = [50, 100, 250];
pub(crate) const SCALING_SIZES: [i32; 3] = [500, 1024, 2048];
pub(crate) const FULL_HD: (u32, u32) = (1920, 1080);
pub(crate) const UHD_8K: (u32, u32) = (7680, 4320);

/// The seed paper's figures (Ryzen 5 2600, 6 cores / 12 threads), per size:
/// 1080p dense, 1080p octree, 8K dense, 8K octree, in milliseconds.
pub(crate) const PAPER_MS: [(i32, [f64; 4]); 3] = [
    (50, [37.557, 211.86, 261.11, 2523.0]),
    (100, [192.48, 247.86, 3020.3, 3552.6]),
    (250, [811.93, 122.55, 10016.0, 2099.5]),
];
pub(crate) const PAPER_CORES: f64 = 6.0;

/// Where the camera stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum View {
    /// The paper's: `size - 10` on every axis.
    Paper,
    /// Above the terrain, outside the volume.
    Above,
}

impl View {
    pub(crate) fn name(self) -> &'static str {
        match self {
            View::Paper => "paper camera",
            View::Above => "camera above",
        }
    }
}

/// The figures for one storage at one size.
pub(crate) struct Measured {
    pub(crate) size: i32,
    pub(crate) backend: Backend,
    pub(crate) build_ms: f64,
    pub(crate) bytes: u64,
    pub(crate) surface_voxels: u64,
    /// Median render time per (resolution, view).
    pub(crate) renders: Vec<((u32, u32), View, f64)>,
}

impl Measured {
    pub(crate) fn render_ms(&self, resolution: (u32, u32), view: View) -> Option<f64> {
        self.renders
            .iter()
            .find(|(r, v, _)| *r == resolution && *v == view)
            .map(|m| m.2)
    }
}

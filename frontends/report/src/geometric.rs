//! The accuracy report's geometric section: what exactness costs. Traces
//! every primary ray of the paper's camera with voxtrace's exact dense walk
//! and with the textbook float-accumulating walk of [`crate::naive_dda`],
//! times both on one thread over the same rays, and counts the pixels whose
//! hit voxel differs.

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

use voxtrace::{Camera, CameraSettings, DenseScene, IAabb, Ray, Scene, VoxelGenerator};

use crate::measure::{count_of, format_ms, median_ms};
use crate::naive_dda::{HitCell, NaiveGrid};

/// The seed paper's scene sizes, and the ones `--quick` keeps.
pub const SIZES: [i32; 3] = [50, 100, 250];
pub const QUICK_SIZES: [i32; 2] = [50, 100];

/// One scene size's figures.
pub struct GeometricRow {
    pub size: i32,
    pub pixels: usize,
    /// Pixels the exact walk stops at `t = 0`, in the camera's own voxel.
    pub at_camera: usize,
    pub exact_ms: f64,
    pub naive_ms: f64,
    pub diff: Differences,
}

/// How two lists of per-pixel results differ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Differences {
    /// Pixels whose hit voxel differs, a hit against a miss included.
    pub voxel: usize,
    /// Of those, the pixels where one walk hit and the other missed.
    pub hit_vs_miss: usize,
    /// Pixels with the same voxel entered through a different face.
    pub face_only: usize,
}

/// Compares `ours` (the reference) with `theirs`, pixel by pixel.
#[must_use]
pub fn count_differences(ours: &[Option<HitCell>], theirs: &[Option<HitCell>]) -> Differences {
    assert_eq!(
        ours.len(),
        theirs.len(),
        "one result per pixel on each side"
    );
    let mut d = Differences::default();
    for (a, b) in ours.iter().zip(theirs) {
        match (a, b) {
            (Some(a), Some(b)) if a.pos != b.pos => d.voxel += 1,
            (Some(a), Some(b)) if a.face != b.face => d.face_only += 1,
            (Some(_), None) | (None, Some(_)) => {
                d.voxel += 1;
                d.hit_vs_miss += 1;
            }
            _ => {}
        }
    }
    d
}

/// The primary ray through every pixel center, row by row.
#[must_use]
pub fn primary_rays(camera: &Camera) -> Vec<Ray> {
    (0..camera.height())
        .flat_map(|j| (0..camera.width()).map(move |i| camera.get_ray(i, j)))
        .collect()
}

/// The paper's camera for `size` at `width` x `height`.
pub fn paper_camera(size: i32, width: u32, height: u32) -> Result<Camera, String> {
    Camera::new(CameraSettings {
        width,
        height,
        ..CameraSettings::paper(size)
    })
    .map_err(|e| e.to_string())
}

/// Traces `rays` with `trace` into `out` (one slot per ray) and returns the
/// time it took: the loop that is timed, for both walks alike.
fn trace_all(
    rays: &[Ray],
    out: &mut [Option<HitCell>],
    trace: impl Fn(&Ray) -> Option<HitCell>,
) -> Duration {
    let started = Instant::now();
    for (ray, slot) in rays.iter().zip(out.iter_mut()) {
        *slot = trace(black_box(ray));
    }
    let elapsed = started.elapsed();
    black_box(&*out);
    elapsed
}

/// Every ray through voxtrace's exact walk (the `Scene` trait), into `out`;
/// returns the time taken.
pub fn trace_exact(scene: &impl Scene, rays: &[Ray], out: &mut [Option<HitCell>]) -> Duration {
    trace_all(rays, out, |r| scene.trace(r).map(|h| HitCell::from_hit(&h)))
}

/// Every ray through the textbook walk, into `out`; returns the time taken.
pub fn trace_naive(grid: &NaiveGrid, rays: &[Ray], out: &mut [Option<HitCell>]) -> Duration {
    trace_all(rays, out, |r| grid.trace(r))
}

/// Builds both grids of the terrain of `seed` at each size and measures
/// them: single thread, median of `runs` runs after a warm-up, exact and
/// naive alternating so that drift of the machine hits both alike.
pub fn measure(
    seed: u64,
    sizes: &[i32],
    (width, height): (u32, u32),
    runs: usize,
) -> Result<Vec<GeometricRow>, String> {
    let terrain = VoxelGenerator::new(seed);
    let mut rows = Vec::new();
    for &size in sizes {
        let bounds = IAabb::centered(size);
        let dense = DenseScene::build(&terrain, bounds).map_err(|e| e.to_string())?;
        let naive = NaiveGrid::fill_occupied(&terrain, bounds)?;
        let rays = primary_rays(&paper_camera(size, width, height)?);
        let mut exact_hits = vec![None; rays.len()];
        let mut naive_hits = vec![None; rays.len()];
        let (mut exact_times, mut naive_times) = (Vec::new(), Vec::new());
        // One untimed warm-up pair, then `runs` pairs, A B A B.
        for run in 0..=runs.max(1) {
            let exact_time = trace_exact(&dense, &rays, &mut exact_hits);
            let naive_time = trace_naive(&naive, &rays, &mut naive_hits);
            if run > 0 {
                exact_times.push(exact_time);
                naive_times.push(naive_time);
            }
        }
        let exact_ms = median_ms(&mut exact_times);
        let naive_ms = median_ms(&mut naive_times);
        let diff = count_differences(&exact_hits, &naive_hits);
        eprintln!(
            "size {size} {width}x{height}: exact {} naive {} differing {}",
            format_ms(exact_ms),
            format_ms(naive_ms),
            diff.voxel
        );
        let at_camera = rays
            .iter()
            .filter(|r| dense.trace(r).is_some_and(|h| h.t == 0.0))
            .count();
        rows.push(GeometricRow {
            size,
            pixels: rays.len(),
            at_camera,
            exact_ms,
            naive_ms,
            diff,
        });
    }
    Ok(rows)
}

fn percent(count: usize, of: usize) -> String {
    format!("{:.3} %", 100.0 * count as f64 / of.max(1) as f64)
}

/// The section's markdown: a heading, what was measured, one row per size.
#[must_use]
pub fn section(
    rows: &[GeometricRow],
    seed: u64,
    (width, height): (u32, u32),
    runs: usize,
) -> String {
    let mut md = String::new();
    let runs_text = count_of(runs, "run");
    let _ = writeln!(
        md,
        "\n### What exactness costs: the exact walk against a float-accumulating one\n\n\
         Every primary ray of the paper's camera ((size - 10)·(1, 1, 1), {width}x{height}, \
         terrain seed {seed}) traced on one thread over the same rays by voxtrace's dense \
         walk (plane crossings recomputed from the origin, ties to the lowest axis) and by \
         the textbook Amanatides & Woo loop the seed paper uses (`tMax += tDelta` per step, \
         strict `<` between axes, slab-test entry; without the paper's wrap-around), over a \
         byte grid of the same terrain cut to the box around its solid voxels, the one box \
         the exact walk clips itself to. The textbook walk lives in the report \
         (`frontends/report/src/naive_dda.rs`) only; it is no backend. Median of {runs_text} \
         after a warm-up, the two alternating; ratio = exact / naive (above 1: the naive \
         walk is faster). A pixel differs when its hit voxel differs, a hit against a miss \
         included; \"face only\" counts the same voxel entered through another face.\n"
    );
    let _ = writeln!(
        md,
        "| size | pixels | exact walk | naive walk | ratio | pixels differing | of which hit vs miss | face only |\n\
         |---|---|---|---|---|---|---|---|"
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.2} | {} ({}) | {} | {} |",
            r.size,
            r.pixels,
            format_ms(r.exact_ms),
            format_ms(r.naive_ms),
            r.exact_ms / r.naive_ms.max(1e-9),
            r.diff.voxel,
            percent(r.diff.voxel, r.pixels),
            r.diff.hit_vs_miss,
            r.diff.face_only,
        );
    }
    for r in rows.iter().filter(|r| r.at_camera > 0) {
        let _ = writeln!(
            md,
            "\nAt size {}, {} of the {} rays start in a solid voxel (the paper's camera \
             stands inside the terrain) and stop there at once: that row times and \
             compares the start of the walk, not the walk.",
            r.size, r.at_camera, r.pixels
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counting_tells_voxels_misses_and_faces_apart() {
        let cell = |x, face| {
            Some(HitCell {
                pos: voxtrace::glam::IVec3::new(x, 0, 0),
                face,
            })
        };
        let ours = [cell(1, None), cell(2, None), None, cell(4, None), None];
        let theirs = [
            cell(1, None),
            cell(3, None),
            cell(3, None),
            cell(4, Some(voxtrace::Face::PosY)),
            None,
        ];
        assert_eq!(
            count_differences(&ours, &theirs),
            Differences {
                voxel: 2,
                hit_vs_miss: 1,
                face_only: 1
            }
        );
    }

    #[test]
    fn terrain_at_size_50_is_counted_against_the_exact_walk() {
        let size = 50;
        let terrain = VoxelGenerator::new(1);
        let bounds = IAabb::centered(size);
        let dense = DenseScene::build(&terrain, bounds).unwrap();
        let naive = NaiveGrid::fill(&terrain, bounds).unwrap();
        let rays = primary_rays(&paper_camera(size, 96, 54).unwrap());
        let above = Camera::new(CameraSettings {
            width: 96,
            height: 54,
            ..CameraSettings::above(size)
        })
        .unwrap();
        let rays_above = primary_rays(&above);
        assert_eq!(rays.len(), 96 * 54);
        let traced = |walk: &dyn Fn(&mut [Option<HitCell>]) -> Duration| {
            let mut out = vec![None; rays.len()];
            walk(&mut out);
            out
        };
        let exact = traced(&|out| trace_exact(&dense, &rays, out));
        // The exact walk against itself, through the same counting: nothing.
        let again = traced(&|out| trace_exact(&dense, &rays, out));
        assert_eq!(count_differences(&exact, &again), Differences::default());
        // The frame is not all sky, so a walk that misses everything would
        // be counted as differing everywhere it hits.
        let hits = exact.iter().filter(|h| h.is_some()).count();
        assert!(hits > 0);
        let misses = vec![None; rays.len()];
        assert_eq!(count_differences(&exact, &misses).voxel, hits);
        // The naive walk finds the same voxels up to a few drifted or tied
        // pixels, from the paper's camera (here inside solid ground, so the
        // start cell is all there is) and from above (long walks).
        for rays in [&rays, &rays_above] {
            let mut exact = vec![None; rays.len()];
            let mut naive_hits = vec![None; rays.len()];
            trace_exact(&dense, rays, &mut exact);
            trace_naive(&naive, rays, &mut naive_hits);
            let diff = count_differences(&exact, &naive_hits);
            assert!(diff.voxel * 20 < rays.len(), "{diff:?}");
        }
    }
}

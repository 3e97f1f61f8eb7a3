//! The `speed` report's output: the markdown tables in the seed paper's
//! shape and the plot of render time and storage against scene size.

use std::fmt::Write as _;

use plotters::chart::SeriesLabelPosition;
use voxtrace_cli::Backend;

use crate::measure::{count_of, cpu_name, format_bytes, format_ms};
use crate::plot::{Chart, Line, Series};
use crate::speed_data::{
    Measured, View, FULL_HD, PAPER_CORES, PAPER_MS, SCALING_SIZES, TABLE_SIZES, UHD_8K,
};

fn find(measured: &[Measured], size: i32, backend: Backend) -> Option<&Measured> {
    measured
        .iter()
        .find(|m| m.size == size && m.backend == backend)
}

/// `dense / octree`: above 1 the octree is faster.
fn ratio(dense: Option<f64>, octree: Option<f64>) -> String {
    match (dense, octree) {
        (Some(d), Some(o)) if o > 0.0 => format!("{:.2}", d / o),
        _ => "—".to_string(),
    }
}

fn cell(ms: Option<f64>) -> String {
    ms.map_or_else(|| "—".to_string(), format_ms)
}

pub(crate) fn tables(
    measured: &[Measured],
    threads: usize,
    runs: usize,
    seed: u64,
    command: &str,
) -> String {
    let mut md = String::new();
    let runs_text = count_of(runs, "run");
    let threads_text = count_of(threads, "thread");
    let _ = writeln!(
        md,
        "Measured by `{command}` on {} with {threads_text}: seed {seed}, \
         median of {runs_text} after a warm-up, the CLI's build and render path \
         (parallel build, the threaded `render`, frame allocation included).\n",
        cpu_name()
    );
    for view in [View::Paper, View::Above] {
        let _ = writeln!(
            md,
            "{}\n",
            match view {
                View::Paper => "Render time per frame, the paper's camera at (size - 10)·(1, 1, 1); ratio = dense / octree (above 1: the octree is faster):",
                View::Above => "The same with the camera above the terrain, outside the volume:",
            }
        );
        let _ = writeln!(
            md,
            "| size | 1920x1080 dense | 1920x1080 octree | ratio | 7680x4320 dense | 7680x4320 octree | ratio |\n|---|---|---|---|---|---|---|"
        );
        for size in TABLE_SIZES {
            let (Some(dense), Some(octree)) = (
                find(measured, size, Backend::Dense),
                find(measured, size, Backend::Octree),
            ) else {
                continue;
            };
            let mut row = format!("| {size} ");
            for res in [FULL_HD, UHD_8K] {
                let (d, o) = (dense.render_ms(res, view), octree.render_ms(res, view));
                let _ = write!(row, "| {} | {} | {} ", cell(d), cell(o), ratio(d, o));
            }
            let _ = writeln!(md, "{row}|");
        }
        md.push('\n');
    }

    let _ = writeln!(
        md,
        "Per core against the paper (6 cores / 12 threads; here {threads_text}), 1920x1080, the paper's camera: \
         paper ms × 6 / (ms here × {threads}), above 1 means more frames per core here:\n"
    );
    let _ = writeln!(
        md,
        "| size | paper dense | here dense | per core | paper octree | here octree | per core |\n|---|---|---|---|---|---|---|"
    );
    for (size, paper) in PAPER_MS {
        let per_core = |paper_ms: f64, here: Option<f64>| {
            here.map_or_else(
                || "—".to_string(),
                |ms| format!("{:.1}×", paper_ms * PAPER_CORES / (ms * threads as f64)),
            )
        };
        let here =
            |backend| find(measured, size, backend).and_then(|m| m.render_ms(FULL_HD, View::Paper));
        let (d, o) = (here(Backend::Dense), here(Backend::Octree));
        let _ = writeln!(
            md,
            "| {size} | {} | {} | {} | {} | {} | {} |",
            format_ms(paper[0]),
            cell(d),
            per_core(paper[0], d),
            format_ms(paper[1]),
            cell(o),
            per_core(paper[1], o),
        );
    }
    md.push('\n');

    let _ = writeln!(
        md,
        "Storage (`storage_bytes`, as `--stats` prints it) and build time; surface voxels are the solid voxels with a face on empty space or on the volume's boundary:\n"
    );
    let _ = writeln!(
        md,
        "| size | dense bytes | dense build | octree bytes | octree build | surface voxels | octree bytes per surface voxel |\n|---|---|---|---|---|---|---|"
    );
    let sizes: Vec<i32> = {
        let mut s: Vec<i32> = measured.iter().map(|m| m.size).collect();
        s.dedup();
        s
    };
    for &size in &sizes {
        let dense = find(measured, size, Backend::Dense);
        let Some(octree) = find(measured, size, Backend::Octree) else {
            continue;
        };
        let _ = writeln!(
            md,
            "| {size} | {} | {} | {} | {} | {} | {:.2} |",
            dense.map_or_else(|| "—".to_string(), |d| format_bytes(d.bytes)),
            cell(dense.map(|d| d.build_ms)),
            format_bytes(octree.bytes),
            format_ms(octree.build_ms),
            format_bytes(octree.surface_voxels),
            octree.bytes as f64 / octree.surface_voxels.max(1) as f64,
        );
    }
    md.push('\n');

    let scaling: Vec<&Measured> = measured
        .iter()
        .filter(|m| SCALING_SIZES.contains(&m.size))
        .collect();
    if !scaling.is_empty() {
        let _ = writeln!(
            md,
            "The octree alone past the paper's sizes (a volume of (2·size)^3 voxels), 1920x1080:\n"
        );
        let _ = writeln!(
            md,
            "| size | volume | build | bytes | paper camera | camera above |\n|---|---|---|---|---|---|"
        );
        for m in scaling {
            let side = 2 * m.size;
            let _ = writeln!(
                md,
                "| {} | {side}^3 | {} | {} | {} | {} |",
                m.size,
                format_ms(m.build_ms),
                format_bytes(m.bytes),
                cell(m.render_ms(FULL_HD, View::Paper)),
                cell(m.render_ms(FULL_HD, View::Above)),
            );
        }
    }
    md
}

pub(crate) fn charts(measured: &[Measured], threads: usize) -> Vec<Chart> {
    let color = |backend| match backend {
        Backend::Dense => 0,
        Backend::Octree => 1,
    };
    let series = |backend: Backend,
                  name: String,
                  line: Line,
                  value: &dyn Fn(&Measured) -> Option<f64>| Series {
        name,
        color: color(backend),
        line,
        points: measured
            .iter()
            .filter(|m| m.backend == backend)
            .filter_map(|m| value(m).map(|v| (f64::from(m.size), v)))
            .collect(),
    };
    let mut time = Vec::new();
    for backend in [Backend::Dense, Backend::Octree] {
        for (view, label, line) in [
            (View::Paper, "paper camera", Line::Thick),
            (View::Above, "camera above", Line::Thin),
        ] {
            time.push(series(
                backend,
                format!("{} {label}", backend.name()),
                line,
                &|m| m.render_ms(FULL_HD, view),
            ));
        }
    }
    for (column, backend) in [(0, Backend::Dense), (1, Backend::Octree)] {
        time.push(Series {
            name: format!("{}, seed paper (12 threads)", backend.name()),
            color: color(backend),
            points: PAPER_MS
                .iter()
                .map(|(size, ms)| (f64::from(*size), ms[column]))
                .collect(),
            line: Line::Dashed,
        });
    }
    let memory = [Backend::Dense, Backend::Octree]
        .into_iter()
        .map(|backend| {
            series(backend, backend.name().to_string(), Line::Thick, &|m| {
                Some(m.bytes as f64 / 1e6)
            })
        })
        .collect();
    vec![
        Chart {
            title: format!("Render time, 1920x1080, {}", count_of(threads, "thread")),
            x_label: "scene size (volume = (2·size)³)".to_string(),
            y_label: "ms per frame (median)".to_string(),
            series: time,
            legend: SeriesLabelPosition::UpperLeft,
        },
        Chart {
            title: "Storage".to_string(),
            x_label: "scene size (volume = (2·size)³)".to_string(),
            y_label: "MB (storage_bytes / 10⁶)".to_string(),
            series: memory,
            legend: SeriesLabelPosition::UpperLeft,
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_thread_and_one_run_are_singular() {
        let one = tables(&[], 1, 1, 1, "cmd");
        assert!(
            one.contains("with 1 thread:") && one.contains("median of 1 run after"),
            "{one}"
        );
        assert!(one.contains("here 1 thread)"), "{one}");
        assert!(
            !one.contains("1 threads") && !one.contains("1 runs"),
            "{one}"
        );
        let two = tables(&[], 2, 3, 1, "cmd");
        assert!(
            two.contains("with 2 threads:") && two.contains("median of 3 runs after"),
            "{two}"
        );
        assert_eq!(charts(&[], 1)[0].title, "Render time, 1920x1080, 1 thread");
    }
}

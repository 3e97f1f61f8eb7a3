//! `voxtrace-report speed --vs-binary PATH`: this revision's `voxtrace`
//! binary against another one (a baseline revision's, say), row by row of
//! the speed grid.
//!
//! # The design, and why
//! Both sides run the same way: as separate `voxtrace` processes, one build
//! and one frame per process, timed by the binaries themselves (`--stats`
//! prints `build_ms` and `render_ms`), alternating ours and theirs (A B A B)
//! after one untimed warm-up run of each. Timing our side in-process instead
//! (as the rest of the speed report does) would compare a scene built once
//! and rendered repeatedly with warm caches against fresh processes, and the
//! speedup would partly measure that difference. Alternating spreads the
//! drift of a shared machine over both sides alike.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use voxtrace::glam::Vec3;
use voxtrace::CameraSettings;
use voxtrace_cli::Backend;

use crate::measure::{count_of, format_ms};
use crate::speed_data::{Measured, View};

/// Options of the comparison.
#[derive(Debug, clap::Args)]
pub struct VsArgs {
    /// Another `voxtrace` CLI binary to measure beside this revision: adds a
    /// table with a "speedup vs" column (its median / ours). Both binaries
    /// then run as separate processes per grid row (one build and one frame
    /// each, times from their `--stats`), alternating, the same number of
    /// runs as the in-process figures.
    #[arg(long, value_name = "PATH")]
    pub vs_binary: Option<PathBuf>,
    /// This revision's `voxtrace` binary for the comparison [default: the
    /// `voxtrace` beside this report's executable, i.e. from `cargo build
    /// --release -p voxtrace-cli` into the same target folder].
    #[arg(long, value_name = "PATH", requires = "vs_binary")]
    pub binary: Option<PathBuf>,
}

impl VsArgs {
    /// Ours and theirs when a comparison is asked for, both checked to exist
    /// before any measuring.
    pub fn binaries(&self) -> Result<Option<(PathBuf, PathBuf)>, String> {
        let Some(theirs) = &self.vs_binary else {
            return Ok(None);
        };
        let ours = match &self.binary {
            Some(path) => path.clone(),
            None => std::env::current_exe()
                .map_err(|e| format!("cannot find this executable: {e}"))?
                .with_file_name(format!("voxtrace{}", std::env::consts::EXE_SUFFIX)),
        };
        for (flag, path) in [("--binary", &ours), ("--vs-binary", theirs)] {
            if !path.is_file() {
                return Err(format!(
                    "{flag} {} is not a file (build it with `cargo build --release -p voxtrace-cli`)",
                    path.display()
                ));
            }
        }
        Ok(Some((ours, theirs.clone())))
    }
}

/// The times one `voxtrace --stats` process reported.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProcessTimes {
    pub build_ms: f64,
    pub render_ms: f64,
}

/// Reads `build_ms: X` and `render_ms: Y` from a `--stats` stderr; other
/// lines (other keys, notes, progress) are skipped.
pub fn parse_stats(stderr: &str) -> Result<ProcessTimes, String> {
    let value = |key: &str| -> Result<f64, String> {
        let line = stderr
            .lines()
            .find_map(|l| l.trim().strip_prefix(key)?.strip_prefix(':'))
            .ok_or_else(|| format!("no `{key}:` line in the --stats output"))?;
        line.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite() && *v >= 0.0)
            .ok_or_else(|| format!("`{key}: {}` is not a time in ms", line.trim()))
    };
    Ok(ProcessTimes {
        build_ms: value("build_ms")?,
        render_ms: value("render_ms")?,
    })
}

/// The median (the mean of the middle two for an even count); `values`
/// must not be empty.
#[must_use]
pub fn median(values: &mut [f64]) -> f64 {
    assert!(!values.is_empty(), "a median needs values");
    values.sort_unstable_by(f64::total_cmp);
    let mid = values.len() / 2;
    if values.len() % 2 == 1 {
        values[mid]
    } else {
        (values[mid - 1] + values[mid]) / 2.0
    }
}

/// Theirs over ours: above 1, ours is faster.
#[must_use]
pub fn speedup(theirs_ms: f64, ours_ms: f64) -> Option<f64> {
    (ours_ms > 0.0 && theirs_ms.is_finite()).then(|| theirs_ms / ours_ms)
}

/// One grid row measured by both binaries: medians of their `--stats`.
pub struct VsRow {
    pub size: i32,
    pub backend: Backend,
    pub resolution: (u32, u32),
    pub view: View,
    pub ours: ProcessTimes,
    pub theirs: ProcessTimes,
}

/// One frame of the grid, as CLI flags.
struct Frame {
    seed: u64,
    size: i32,
    backend: Backend,
    resolution: (u32, u32),
    position: Vec3,
    threads: usize,
}

fn run_once(binary: &Path, frame: &Frame, out: &Path) -> Result<ProcessTimes, String> {
    let p = frame.position;
    let output = Command::new(binary)
        .args(["--backend", frame.backend.name()])
        .args(["--size", &frame.size.to_string()])
        .args(["--seed", &frame.seed.to_string()])
        .args(["--width", &frame.resolution.0.to_string()])
        .args(["--height", &frame.resolution.1.to_string()])
        .args(["--threads", &frame.threads.to_string()])
        .arg("--stats")
        .args(["--position", &format!("{},{},{}", p.x, p.y, p.z)])
        .arg("--out")
        .arg(out)
        .output()
        .map_err(|e| format!("cannot run {}: {e}", binary.display()))?;
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() {
        return Err(format!(
            "{} failed ({}): {}",
            binary.display(),
            output.status,
            stderr.trim()
        ));
    }
    parse_stats(&stderr).map_err(|e| format!("{}: {e}", binary.display()))
}

/// Every (resolution, view) of every row of `measured`, by both binaries:
/// one warm-up each, then `runs` pairs, ours first in each.
pub fn measure(
    (ours, theirs): (&Path, &Path),
    measured: &[Measured],
    seed: u64,
    threads: usize,
    runs: usize,
) -> Result<Vec<VsRow>, String> {
    let out = std::env::temp_dir().join(format!("voxtrace-report-vs-{}.png", std::process::id()));
    let mut rows = Vec::new();
    for m in measured {
        for &(resolution, view, _) in &m.renders {
            let settings = match view {
                View::Paper => CameraSettings::paper(m.size),
                View::Above => CameraSettings::above(m.size),
            };
            let frame = Frame {
                seed,
                size: m.size,
                backend: m.backend,
                resolution,
                position: settings.lookfrom,
                threads,
            };
            run_once(ours, &frame, &out)?;
            run_once(theirs, &frame, &out)?;
            let (mut a, mut b) = (Vec::new(), Vec::new());
            for _ in 0..runs.max(1) {
                a.push(run_once(ours, &frame, &out)?);
                b.push(run_once(theirs, &frame, &out)?);
            }
            let medians = |times: &[ProcessTimes]| ProcessTimes {
                build_ms: median(&mut times.iter().map(|t| t.build_ms).collect::<Vec<_>>()),
                render_ms: median(&mut times.iter().map(|t| t.render_ms).collect::<Vec<_>>()),
            };
            let row = VsRow {
                size: m.size,
                backend: m.backend,
                resolution,
                view,
                ours: medians(&a),
                theirs: medians(&b),
            };
            eprintln!(
                "size {} {} {}x{} {}: ours {} theirs {}",
                m.size,
                m.backend.name(),
                resolution.0,
                resolution.1,
                view.name(),
                format_ms(row.ours.render_ms),
                format_ms(row.theirs.render_ms)
            );
            rows.push(row);
        }
    }
    let _ = std::fs::remove_file(&out);
    Ok(rows)
}

fn ratio_cell(theirs: f64, ours: f64) -> String {
    speedup(theirs, ours).map_or_else(|| "—".to_string(), |r| format!("{r:.2}×"))
}

/// The comparison's markdown table.
#[must_use]
pub fn table(rows: &[VsRow], theirs: &Path, threads: usize, runs: usize) -> String {
    let mut md = String::new();
    let runs_text = count_of(runs, "run");
    let _ = writeln!(
        md,
        "Against `{}`: both binaries run as separate processes with the same flags \
         (`--backend --size --seed --width --height --threads {threads} --position --stats`), \
         one build and one frame per process, timed by their own `--stats` \
         (`build_ms`, `render_ms`; PNG encoding not included); median of {runs_text} each \
         after one warm-up each, alternating ours and theirs. Speedup vs = their median / \
         ours (above 1: this revision is faster). These process figures are not the \
         in-process figures above.\n",
        theirs.display()
    );
    let _ = writeln!(
        md,
        "| size | backend | resolution | camera | render here | render theirs | speedup vs | build here | build theirs | speedup vs |\n\
         |---|---|---|---|---|---|---|---|---|---|"
    );
    for r in rows {
        let _ = writeln!(
            md,
            "| {} | {} | {}x{} | {} | {} | {} | {} | {} | {} | {} |",
            r.size,
            r.backend.name(),
            r.resolution.0,
            r.resolution.1,
            r.view.name(),
            format_ms(r.ours.render_ms),
            format_ms(r.theirs.render_ms),
            ratio_cell(r.theirs.render_ms, r.ours.render_ms),
            format_ms(r.ours.build_ms),
            format_ms(r.theirs.build_ms),
            ratio_cell(r.theirs.build_ms, r.ours.build_ms),
        );
    }
    md.push('\n');
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_are_read_among_other_lines() {
        let stderr = "seed: 1\nbuild_ms: 12.500\nrender_ms: 301.250\nencode_ms: 9.000\n\
                      primary_rays: 2073600\nstorage_bytes: 108976\n";
        assert_eq!(
            parse_stats(stderr),
            Ok(ProcessTimes {
                build_ms: 12.5,
                render_ms: 301.25
            })
        );
    }

    #[test]
    fn missing_or_bad_stats_are_errors() {
        assert!(parse_stats("build_ms: 1.0\n")
            .unwrap_err()
            .contains("render_ms"));
        assert!(parse_stats("build_ms: 1.0\nrender_ms: fast\n")
            .unwrap_err()
            .contains("fast"));
        assert!(parse_stats("build_ms: -1\nrender_ms: 2\n").is_err());
        // A key that merely starts like one is not it.
        assert!(parse_stats("build_ms: 1\nrender_ms_total: 2\n").is_err());
    }

    #[test]
    fn medians_and_speedups() {
        assert_eq!(median(&mut [5.0, 1.0, 3.0]), 3.0);
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 100.0]), 3.5);
        assert_eq!(median(&mut [2.0]), 2.0);
        assert_eq!(speedup(300.0, 100.0), Some(3.0));
        assert_eq!(speedup(50.0, 100.0), Some(0.5));
        assert_eq!(speedup(50.0, 0.0), None);
        assert_eq!(ratio_cell(300.0, 200.0), "1.50×");
    }
}

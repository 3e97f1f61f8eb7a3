//! Task selection for job arrays: which tile of a grid, or which frames of
//! an animation, one task of a render farm renders.
//!
//! Every scheduler runs the same command N times with a task number (Slurm's
//! `$SLURM_ARRAY_TASK_ID`, Kubernetes' `$JOB_COMPLETION_INDEX`, HTCondor's
//! `$(Process)`), so an index may be given as `env:VAR` and read when the
//! task starts. The arithmetic is one rule for both tiles and frames: `n`
//! items cut into `parts` runs of consecutive items, part `i` being
//! `[i * n / parts, (i + 1) * n / parts)`. The runs cover every item once
//! and differ in length by at most one.

use std::env::VarError;
use std::ops::Range;

use voxtrace::Rect;

/// Part `index` of `n` items cut into `parts` runs (see the module doc).
/// Needs `index < parts`; a run is empty only when `parts > n`.
#[must_use]
pub fn split(n: u32, parts: u32, index: u32) -> Range<u32> {
    debug_assert!(index < parts);
    // u64: `index * n` overflows u32 for large frames and grids.
    let at = |i: u32| (u64::from(i) * u64::from(n) / u64::from(parts)) as u32;
    at(index)..at(index + 1)
}

/// A grid of `columns` by `rows` tiles over a frame, numbered row-major
/// (tile `i` is in row `i / columns`, column `i % columns`).
///
/// # Guarantees
/// `columns` and `rows` are at least 1 and there are at most
/// [`Grid::MAX_TILES`] tiles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Grid {
    columns: u32,
    rows: u32,
}

impl Grid {
    /// The most tiles a grid has: far more tasks than any farm runs for one
    /// frame, and few enough that a stitch's bookkeeping of what a part file
    /// claims stays small.
    pub const MAX_TILES: u32 = 1 << 16;

    /// A grid of `columns x rows` tiles; `None` if either is 0 or there
    /// would be more than [`Grid::MAX_TILES`] tiles.
    #[must_use]
    pub fn new(columns: u32, rows: u32) -> Option<Grid> {
        let count = u64::from(columns) * u64::from(rows);
        let valid = columns > 0 && rows > 0 && count <= u64::from(Grid::MAX_TILES);
        valid.then_some(Grid { columns, rows })
    }

    /// Parses `CxR` (for example `4x4`), as `--tiles` takes it.
    ///
    /// # Errors
    /// A message naming the bad text.
    pub fn parse(text: &str) -> Result<Grid, String> {
        let bad = || format!("expected COLUMNSxROWS such as 4x4, got '{text}'");
        let (c, r) = text.trim().split_once(['x', 'X']).ok_or_else(bad)?;
        let number = |s: &str| s.trim().parse::<u32>().map_err(|_| bad());
        Grid::new(number(c)?, number(r)?).ok_or_else(|| {
            format!(
                "'{text}' must have at least one column and one row, and at most {} tiles",
                Grid::MAX_TILES
            )
        })
    }

    /// Columns.
    #[must_use]
    pub fn columns(self) -> u32 {
        self.columns
    }

    /// Rows.
    #[must_use]
    pub fn rows(self) -> u32 {
        self.rows
    }

    /// Tiles in the grid.
    #[must_use]
    pub fn count(self) -> u32 {
        self.columns * self.rows // at most MAX_TILES: checked in `new`
    }

    /// Checks that every tile of a `width x height` frame has a pixel.
    ///
    /// # Errors
    /// A message naming the grid and the frame.
    pub fn fits(self, width: u32, height: u32) -> Result<(), String> {
        if self.columns > width || self.rows > height {
            return Err(format!(
                "--tiles {self} does not fit the {width}x{height} frame: \
                 at most one column per pixel of width and one row per pixel of height"
            ));
        }
        Ok(())
    }

    /// The rectangle of tile `index` (row-major) of a `width x height`
    /// frame; `None` if `index` is not a tile of the grid. Tiles differ from
    /// each other by at most one pixel in width and in height.
    #[must_use]
    pub fn tile(self, width: u32, height: u32, index: u32) -> Option<Rect> {
        if index >= self.count() {
            return None;
        }
        let xs = split(width, self.columns, index % self.columns);
        let ys = split(height, self.rows, index / self.columns);
        Some(Rect {
            x: xs.start,
            y: ys.start,
            width: xs.end - xs.start,
            height: ys.end - ys.start,
        })
    }
}

impl core::fmt::Display for Grid {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{}x{}", self.columns, self.rows)
    }
}

/// A task index as given on the command line: a number, or the name of an
/// environment variable to read it from when the task runs (`env:VAR`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TaskIndex {
    /// The index itself.
    Number(u32),
    /// `env:VAR`: the index is the value of `VAR`.
    Env(String),
}

impl TaskIndex {
    /// Parses `I` or `env:VAR`.
    ///
    /// # Errors
    /// A message naming the bad text.
    pub fn parse(text: &str) -> Result<TaskIndex, String> {
        if let Some(var) = text.strip_prefix("env:") {
            if var.is_empty() || var.contains('=') || var.contains('\0') {
                return Err(format!("'{text}' names no environment variable"));
            }
            return Ok(TaskIndex::Env(var.to_string()));
        }
        text.trim()
            .parse::<u32>()
            .map(TaskIndex::Number)
            .map_err(|_| format!("expected a whole number or env:VAR, got '{text}'"))
    }

    /// The index, checked to be below `count`; `flag` (for example
    /// `--tile-index`) and `what` (for example `the 4x4 grid's tiles`) name
    /// the setting in errors. `lookup` reads an environment variable
    /// (`std::env::var` in the binary, a map in tests).
    ///
    /// # Errors
    /// A message naming the flag, the bad value and the valid range: the
    /// variable is unset, not UTF-8 or not a number, or the index is out
    /// of range.
    pub fn resolve(
        &self,
        flag: &str,
        count: u32,
        what: &str,
        lookup: impl Fn(&str) -> Result<String, VarError>,
    ) -> Result<u32, String> {
        let range = format!("{what} are 0 to {}", count.saturating_sub(1));
        let (index, given) = match self {
            TaskIndex::Number(n) => (*n, format!("{flag} {n}")),
            TaskIndex::Env(var) => {
                let given = format!("{flag} env:{var}");
                let value = lookup(var).map_err(|e| match e {
                    VarError::NotPresent => format!("{given}: {var} is not set ({range})"),
                    VarError::NotUnicode(_) => {
                        format!("{given}: {var} is not valid UTF-8 ({range})")
                    }
                })?;
                let n = value
                    .trim()
                    .parse::<u32>()
                    .map_err(|_| format!("{given}: {var} is '{value}', not a number ({range})"))?;
                (n, format!("{given} (= {n})"))
            }
        };
        if index >= count {
            return Err(format!("{given} is out of range: {range}"));
        }
        Ok(index)
    }
}

/// The frames task `index` of `tasks` renders out of an animation of
/// `frames` frames: consecutive runs that differ in length by at most one
/// (with as many tasks as frames, one frame each). For `--task-index` with
/// `--frames N`, once the camera's `--frames` exists.
///
/// # Errors
/// A message naming the range when `index` is not below `tasks`, or when
/// there are more tasks than frames (some would render nothing).
pub fn frames_for_task(index: u32, tasks: u32, frames: u32) -> Result<Range<u32>, String> {
    if tasks == 0 || tasks > frames {
        return Err(format!(
            "{tasks} tasks for {frames} frames: use 1 to {frames} tasks"
        ));
    }
    if index >= tasks {
        return Err(format!(
            "--task-index {index} is out of range: the {tasks} tasks are 0 to {}",
            tasks - 1
        ));
    }
    Ok(split(frames, tasks, index))
}

/// `pattern` with every `%t` replaced by `tile`, zero-padded to the digits
/// of the grid's last tile number (tiles 00 to 15 for a 4x4 grid), so that
/// the parts of a frame sort in tile order.
#[must_use]
pub fn tile_name(pattern: &str, tile: u32, count: u32) -> String {
    let digits = count.saturating_sub(1).to_string().len();
    pattern.replace("%t", &format!("{tile:0digits$}"))
}

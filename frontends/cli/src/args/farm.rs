//! The render farm's flags: `--tiles`, `--tile-index`, `--tasks`,
//! `--task-index` (flattened into the render's flags) and `voxtrace
//! stitch`'s own.

use std::path::PathBuf;

use voxtrace_cli::tiles::{Grid, TaskIndex};

/// The flags that make a render one task of a job array.
#[derive(Debug, Clone, clap::Args)]
pub struct TileArgs {
    /// Cut the frame into a grid of COLUMNS x ROWS tiles (for example 4x4)
    /// and render only the tile --tile-index picks; the PNG then carries
    /// its place in the frame for `voxtrace stitch`. `%t` in --out becomes
    /// the tile number.
    #[arg(long, value_name = "CxR", value_parser = Grid::parse, conflicts_with = "region")]
    pub tiles: Option<Grid>,

    /// The tile to render with --tiles, row-major from 0, or env:VAR to read
    /// it from an environment variable (env:SLURM_ARRAY_TASK_ID).
    #[arg(long, value_name = "I|env:VAR", value_parser = TaskIndex::parse)]
    pub tile_index: Option<TaskIndex>,

    /// Split the --frames animation into this many runs of consecutive
    /// frames (differing by at most one frame) and render only the run
    /// --task-index picks: one command line for every task of an array.
    #[arg(long, value_name = "T", requires = "task_index")]
    pub tasks: Option<u32>,

    /// The run of frames to render with --tasks, from 0, or env:VAR
    /// (env:SLURM_ARRAY_TASK_ID).
    #[arg(long, value_name = "I|env:VAR", value_parser = TaskIndex::parse,
          requires = "tasks", conflicts_with = "frame_range")]
    pub task_index: Option<TaskIndex>,
}

/// `voxtrace stitch PART... --out FILE [--allow-partial]`: the flags of
/// the [`Command::Stitch`](super::Command::Stitch) subcommand.
#[derive(Debug, clap::Args)]
pub struct StitchArgs {
    /// The part PNGs, in any order.
    // Both required, but checked by hand: clap would name them on a second
    // line, and an error is one line.
    #[arg(value_name = "PART")]
    pub parts: Vec<PathBuf>,

    /// The stitched PNG, written whole or not at all; `-` writes it to
    /// standard output (not a terminal). It cannot be one of the parts.
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,

    /// Fill missing tiles with a checkerboard (and list them) instead of
    /// refusing: for previews.
    #[arg(long)]
    pub allow_partial: bool,
}

//! The render-farm side of the binary: `--tiles CxR --tile-index I` picks
//! one tile of the frame and writes it as a part that knows where it
//! belongs, and `voxtrace stitch` puts the parts back together.

use std::ffi::OsString;
use std::io::{BufWriter, Write};
use std::os::unix::ffi::OsStringExt;
use std::path::{Path, PathBuf};

use voxtrace::{Camera, RenderOptions};
use voxtrace_cli::atomic::{remove_on_signal, same_file};
use voxtrace_cli::errors::show_path;
use voxtrace_cli::part::{fnv1a64, settings_text, write_part, Placement};
use voxtrace_cli::stitch::{list, stitch};
use voxtrace_cli::tiles::{frames_for_task, tile_name};
use voxtrace_cli::{say, Backend, FrameRange};

use crate::args::{StitchArgs, TileArgs};
use crate::{memory, output};

/// The frames `--tasks T --task-index I` (in `farm`) pick out of an
/// animation of `frames` (`None` without those flags).
///
/// # Errors
/// One line: the flags without `--frames`, more tasks than frames, or an
/// index out of range or unset (naming the range).
pub fn task_frames(farm: &TileArgs, frames: Option<u32>) -> Result<Option<FrameRange>, String> {
    let (Some(tasks), Some(index)) = (farm.tasks, &farm.task_index) else {
        return Ok(None);
    };
    let frames = frames.ok_or("--tasks splits an animation: it needs --frames N")?;
    frames_for_task(0, tasks, frames)?; // the task count first, then the index
    let what = format!("the {tasks} tasks");
    let index = index.resolve("--task-index", tasks, &what, |var| std::env::var(var))?;
    let run = frames_for_task(index, tasks, frames)?;
    // Frames count from 1.
    Ok(Some(FrameRange {
        first: run.start + 1,
        last: run.end,
    }))
}

/// One tile to render: where it belongs, what decides its pixels, and
/// where it goes.
pub struct TileJob {
    /// Its place in the frame.
    pub placement: Placement,
    /// The settings text its hash is taken of.
    pub settings: String,
    /// `--out` with `%t` replaced.
    pub out: PathBuf,
}

/// Checks the farm flags before anything else runs (a random seed is
/// drawn and printed): `--tiles` and `--tile-index` go together, tiles of
/// a `random_terrain` (no `--vox`, no `--seed`) are refused, since every
/// task would draw its own, and a tile is one of a still, not of `frames`.
///
/// # Errors
/// One line naming the fix.
pub fn check_flags(
    farm: &TileArgs,
    random_terrain: bool,
    frames: Option<u32>,
) -> Result<(), String> {
    match (farm.tiles, &farm.tile_index) {
        (None, Some(_)) => return Err("--tile-index needs --tiles CxR".to_string()),
        (Some(grid), None) => {
            return Err(format!(
                "--tiles {grid} needs --tile-index I (0 to {}) or env:VAR",
                grid.count() - 1
            ))
        }
        (Some(grid), Some(_)) if random_terrain => {
            return Err(format!(
                "--tiles {grid} needs --seed N: every task would draw its own random terrain"
            ))
        }
        _ => {}
    }
    if farm.tiles.is_some() && frames.is_some() {
        return Err("--tiles renders one tile of a still: it does not take --frames".into());
    }
    Ok(())
}

/// The tile `farm` asks for, if any, of `camera`'s frame in `backend`
/// with `options`, written to `out` (`%t`: the tile number); `scene` says
/// what its settings text names of the scene (read only for a tile).
/// Called after [`check_flags`]; the output checks that the part's format
/// is PNG.
///
/// # Errors
/// One line: an index out of range or an unset variable (naming the
/// range), a grid finer than the frame, or a `--vox` file that cannot be
/// read.
pub fn select(
    farm: &TileArgs,
    camera: &Camera,
    options: &RenderOptions,
    scene: &dyn Fn() -> Result<String, String>,
    backend: Backend,
    out: &Path,
) -> Result<Option<TileJob>, String> {
    let (Some(grid), Some(index)) = (farm.tiles, &farm.tile_index) else {
        return Ok(None);
    };
    let (width, height) = (camera.width(), camera.height());
    grid.fits(width, height)?;
    let what = format!("the {grid} grid's tiles");
    let tile = index.resolve("--tile-index", grid.count(), &what, |var| {
        std::env::var(var)
    })?;
    let rect = grid
        .tile(width, height, tile)
        .ok_or("the tile index is out of range")?; // resolve checked it

    let subject = scene()?;
    let settings = settings_text(&subject, backend.name(), camera, options);
    let out = tile_path(out, tile, grid.count());
    let placement = Placement {
        frame_width: width,
        frame_height: height,
        grid,
        tile,
        rect,
        frame_number: 0, // a still; the camera's --frames will set it
        hash: fnv1a64(settings.as_bytes()),
    };
    Ok(Some(TileJob {
        placement,
        settings,
        out,
    }))
}

/// `out` with every `%t` replaced by tile `tile` of `count`, as
/// [`tile_name`] numbers it; the rest kept byte for byte, UTF-8 or not.
fn tile_path(out: &Path, tile: u32, count: u32) -> PathBuf {
    let number = tile_name("%t", tile, count);
    let mut bytes = Vec::new();
    let mut rest = out.as_os_str().as_encoded_bytes();
    while let Some(at) = rest.windows(2).position(|w| w == b"%t") {
        bytes.extend_from_slice(&rest[..at]);
        bytes.extend_from_slice(number.as_bytes());
        rest = &rest[at + 2..];
    }
    bytes.extend_from_slice(rest);
    // Unix paths are any bytes (the CLI builds on Unix only).
    PathBuf::from(OsString::from_vec(bytes))
}

/// Writes a rendered tile as a part PNG into `file`.
///
/// # Errors
/// The encoder's message.
pub fn write_tile(out: impl Write, job: &TileJob, pixels: &[u32]) -> Result<(), String> {
    write_part(BufWriter::new(out), &job.placement, &job.settings, pixels)
}

/// `voxtrace stitch`: reads the parts, assembles the frame and writes it
/// whole to `--out` (or standard output), after every refusal.
///
/// # Errors
/// One line naming the problem: a missing `--out` or part, an output that
/// is one of the parts, a part that cannot be read or does not fit.
pub fn run_stitch(args: &StitchArgs) -> Result<(), String> {
    let out = args
        .out
        .as_ref()
        .ok_or("stitch needs --out FILE (voxtrace stitch PART... --out FILE)")?;
    if args.parts.is_empty() {
        return Err("stitch needs at least one PART (voxtrace stitch PART... --out FILE)".into());
    }
    if output::format_of(out, None)? != output::Format::Png {
        return Err(format!("stitch writes PNG, not --out {}", show_path(out)));
    }
    let to_stdout = output::is_stdout(out);
    if to_stdout {
        output::check_stdout()?;
    }
    refuse_a_part_as_out(out, to_stdout, &args.parts)?;
    // Before any output exists: an interrupted stitch then removes its
    // temporary file and leaves --out as it was.
    remove_on_signal()?;
    let failed = |e: String| format!("cannot write --out {}: {e}", show_path(out));
    // Created first, so that a bad --out fails before the parts are read,
    // and as a render creates its own: a terminal is refused alike.
    let file = if to_stdout {
        None
    } else {
        Some(output::create(out)?)
    };
    let frame = stitch(&args.parts, args.allow_partial, memory::available_memory())?;
    // Encoded as a render encodes its frame: the same file.
    let (width, height, pixels) = (frame.width, frame.height, frame.pixels);
    let encode =
        |to: &mut dyn Write| output::write(to, output::Format::Png, width, height, pixels, true);
    match file {
        Some(mut file) => encode(&mut file)
            .and_then(|()| file.commit().map_err(|e| e.to_string()))
            .map_err(failed)?,
        None => output::stdout()
            .map_err(|e| e.to_string())
            .and_then(|mut out| encode(&mut out))
            .map_err(|e| format!("cannot write to standard output: {e}"))?,
    }
    if !frame.missing.is_empty() {
        say!(
            "note: missing tiles of the {} grid drawn as a checkerboard: {}",
            frame.grid,
            list(&frame.missing)
        );
    }
    Ok(())
}

/// Refuses an output that is one of the parts, however either is named
/// (`./t-0.png`, a symlink, a hard link; standard output redirected to
/// it): the stitch would replace its own input. Files are the same when
/// their device and inode are.
fn refuse_a_part_as_out(out: &Path, to_stdout: bool, parts: &[PathBuf]) -> Result<(), String> {
    let target = if to_stdout {
        // What standard output is open on, if it is open.
        output::stdout().and_then(|out| out.metadata()).ok()
    } else {
        std::fs::metadata(out).ok()
    };
    let Some(target) = target else {
        return Ok(()); // a new file is no part
    };
    let shown = if to_stdout {
        "- (standard output)".to_string()
    } else {
        show_path(out)
    };
    for part in parts {
        if std::fs::metadata(part).is_ok_and(|m| same_file(&m, &target)) {
            return Err(format!(
                "--out {shown} is the part {}: the stitch would overwrite its own input",
                show_path(part)
            ));
        }
    }
    Ok(())
}

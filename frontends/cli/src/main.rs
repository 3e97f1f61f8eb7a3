//! `voxtrace`: renders the seeded terrain, or a `.vox` scene, to an image.
//!
//! Exit codes: 0 on success, 2 on bad arguments, unusable input or output, or
//! a scene that does not fit in memory, with one line on stderr naming the
//! problem.

mod args;
mod budget;
mod denoise_flag;
mod effects;
mod farm;
mod job;
mod memory;
mod output;
mod progress;
mod subject;
mod view;

use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{ArgMatches, CommandFactory};
use voxtrace::{Camera, CameraSettings, EffectPlan, Look, Rect, RenderOptions, VoxelGenerator};
use voxtrace_cli::atomic::{exit_with_error, remove_on_signal, AtomicFile};
use voxtrace_cli::errors::{self, escape_controls, show_path};
use voxtrace_cli::say;
use voxtrace_cli::{export_vox, frame_path, terrain_box, turntable, FrameArg, FrameRange};
use voxtrace_flags::Effects;

use args::{Args, Command, GivenFlags, TileArgs};
use budget::Budget;
use effects::{ignored_effects, ignored_flags, unused_in_path};
use farm::TileJob;
use job::{Frame, Job};
use output::Format;
use subject::{terrain_seed, Subject};
use view::camera_settings;

/// The stack of the thread that does the work: what a Linux main thread
/// usually has (`ulimit -s` 8192), whatever limit the process was started
/// with (under `prlimit --stack=49152` the main thread's own would
/// overflow). Reserved address space; only what is touched is memory.
const WORK_STACK: usize = 8 << 20;

/// Runs [`work`] on a thread whose stack is [`WORK_STACK`], and exits as it
/// does. Rayon's workers size their own stacks.
fn main() -> ExitCode {
    let worker = std::thread::Builder::new()
        .name("voxtrace".into())
        .stack_size(WORK_STACK);
    match worker.spawn(work) {
        // A panic ends the process as it would have on this thread.
        Ok(thread) => thread
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
        // Where no such thread can start (a tiny address space), here.
        Err(_) => work(),
    }
}

/// Parses the flags (as given: a path need not be UTF-8), then stitches,
/// exports the terrain or renders; any error is one line on stderr and
/// exit code 2.
fn work() -> ExitCode {
    let argv: Vec<OsString> = std::env::args_os().collect();
    let (args, matches) = match errors::parse::<Args>(&Args::command(), &argv) {
        Ok(parsed) => parsed,
        Err(e) => return errors::clap_failure(e, &argv),
    };
    if let Some(Command::Stitch(stitch)) = &args.command {
        return match farm::run_stitch(stitch) {
            Ok(()) => ExitCode::SUCCESS,
            Err(message) => exit_with_error(&message),
        };
    }
    // Before any output exists: an interrupted run then removes its
    // temporary files and leaves every output file as it was.
    let done = remove_on_signal().and_then(|()| match &args.export_vox {
        Some(path) => export(path, args.seed, args.size, args.stats),
        None => run(&args, &matches),
    });
    match done {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => exit_with_error(&message),
    }
}

/// The render, stage by stage: the subject, every frame's camera, the
/// effects, the crop and the output are resolved and checked before
/// anything is built; then the render, then what the user should know.
/// Apart from `args` itself, only this file reads [`Args`]: every stage
/// takes plain values.
fn run(args: &Args, matches: &ArgMatches) -> Result<(), String> {
    match args.frame {
        Some(FrameArg::All) => every_frame(args, matches),
        Some(FrameArg::One(frame)) => render_one(args, matches, Some(frame), &args.out),
        None => render_one(args, matches, None, &args.out),
    }
}

/// `--frame all`: every animation frame of the file, each rendered as
/// `--frame K` renders it alone, to `--out` with its run of `#` made `K`;
/// every file name is checked before the first frame is rendered.
///
/// # Errors
/// One line: a flag that cannot go with it, an `--out` without `#`, or
/// the first frame that fails.
fn every_frame(args: &Args, matches: &ArgMatches) -> Result<(), String> {
    let farmed = args.farm.tiles.is_some() || args.farm.tasks.is_some();
    if args.frames.is_some() || farmed {
        return Err(
            "--frame all renders the file's own animation, one whole frame a file: \
                    it cannot also take --frames, --tiles or --tasks"
                .into(),
        );
    }
    if output::is_stdout(&args.out) {
        return Err("--frame all writes one file per frame: --out - cannot hold them".into());
    }
    let count = Subject::load(args.vox.as_deref(), 0, args.seed, args.size)?
        .shown
        .model()
        .map_or(1, |model| model.frames());
    let paths: Vec<PathBuf> = (0..count)
        .map(|k| frame_path(&args.out, k))
        .collect::<Result<_, _>>()?;
    // Every file can be written before the first is: a later frame's
    // folder or name fails now, not after earlier frames were written.
    for path in &paths {
        output::check(path)?;
    }
    for (frame, path) in (0..count).zip(&paths) {
        render_one(args, matches, Some(frame), path)?;
    }
    Ok(())
}

/// One frame of the file (`frame`, `None` when `--frame` was not given)
/// or the terrain, to `out`.
fn render_one(
    args: &Args,
    matches: &ArgMatches,
    frame: Option<u32>,
    out: &Path,
) -> Result<(), String> {
    let started = std::time::Instant::now();
    let random_terrain = args.vox.is_none() && args.seed.is_none();
    farm::check_flags(&args.farm, random_terrain, args.frames)?;
    denoise_flag::check(args.denoise, args.farm.tiles.is_some())?;
    if args.time_limit.is_some() && args.farm.tiles.is_some() {
        return Err(
            "--time-limit cannot cut a frame into --tiles: each task would stop after \
             its own rounds; give every task the --spp or --max-spp a --stats run printed"
                .into(),
        );
    }
    let subject = Subject::load(
        args.vox.as_deref(),
        frame.unwrap_or(0),
        args.seed,
        args.size,
    )?;
    let explicit = Args::camera_given(matches);
    let flags = view::measured_default(args.camera_flags(), explicit, &subject, args.max_memory);
    let file = args.camera;
    let settings = camera_settings(file, &flags, &subject.shown.stage(), subject.cameras())?;
    let range = frame_range(args.frames, args.frame_range, &args.farm)?;
    let cameras = turntable_cameras(settings, range, args.frames.unwrap_or(1))?;
    if let Some(frames) = args.frames {
        // A turntable stopped early names the frames it wrote.
        voxtrace_cli::atomic::expect_frames(range, frames);
    }
    let first = &cameras[0].camera;
    let (options, plan) = resolve_effects(&args.effects(), &subject, &settings);
    let scene = || subject.tile_text();
    let tile = farm::select(&args.farm, first, &options, &scene, args.backend, out)?;
    let region = region(tile.as_ref(), args.region, first)?;
    let pattern = out;
    let out = tile.as_ref().map_or(out, |tile| &tile.out);
    let format = output::format_of(out, args.format)?;
    let files = args.frames.map(|_| range);
    let paths = output_paths(out, format, tile.is_some(), pattern, files)?;
    let mut notes = notes(&options, &plan, &args.given(matches), &settings, format);
    notes.extend(low_samples_hint(&options, &plan, args.denoise));
    notes.extend(nothing_to_denoise(&plan, args.denoise));
    notes.extend(camera_inside_note(&cameras, &subject, args.camera));
    notes.extend(animation_note(&subject, frame));
    let (backend, threads, tile) = (args.backend, args.threads, tile.as_ref());
    let job = Job {
        backend,
        threads,
        subject: &subject,
        options: &options,
        region,
        format,
        tile,
        denoise: args.denoise,
        budget: Budget::of(args.time_limit, &plan),
        rounds: (plan.look == voxtrace::Look::Path).then(|| voxtrace::Rounds::of(&plan)),
    };
    job.check_memory(args.max_memory)?;
    let totals = job.render_all(&cameras, out, &paths)?;
    if args.stats {
        job.print_stats(&totals, &plan, &cameras[0].settings, args.up.is_some());
    }
    report(&subject, &notes);
    finished(&paths, region, started.elapsed());
    Ok(())
}

/// On a terminal, where the render went, its size and its time; nothing
/// for a script (standard error not a terminal), as before.
fn finished(paths: &[PathBuf], region: Rect, took: std::time::Duration) {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return;
    }
    let size = format!("{}x{}", region.width, region.height);
    let secs = took.as_secs_f64();
    match paths {
        [one] if output::is_stdout(one) => {
            say!("wrote the {size} frame to standard output in {secs:.1} s");
        }
        [one] => {
            let bytes = std::fs::metadata(one).map_or(0, |m| m.len());
            let bytes = voxtrace_cli::human_bytes(u128::from(bytes));
            say!("wrote {}: {size}, {bytes}, {secs:.1} s", show_path(one));
        }
        many => say!(
            "wrote {} frames of {size}, {} to {}, in {secs:.1} s",
            many.len(),
            show_path(&many[0]),
            show_path(&many[many.len() - 1])
        ),
    }
}

/// The frames to render: the run of `--tasks` (`farm`), else
/// `--frame-range`, else all of `frames` (one for a still), checked
/// against the animation.
///
/// # Errors
/// One line: a bad task split, or a range past the last frame.
fn frame_range(
    frames: Option<u32>,
    asked: Option<FrameRange>,
    farm: &TileArgs,
) -> Result<FrameRange, String> {
    let range = match farm::task_frames(farm, frames)? {
        Some(range) => range,
        None => asked.unwrap_or(FrameRange::all(frames.unwrap_or(1))),
    };
    range.check_within(frames.unwrap_or(1))?;
    Ok(range)
}

/// Every frame's camera in `range` of a turntable of `frames` around
/// `settings`, checked before anything is built.
///
/// # Errors
/// The first camera the core refuses, in one line.
fn turntable_cameras(
    settings: CameraSettings,
    range: FrameRange,
    frames: u32,
) -> Result<Vec<Frame>, String> {
    range
        .frames()
        .map(|k| {
            let settings = turntable(settings, k, frames);
            let camera = Camera::new(settings).map_err(|e| e.to_string())?;
            Ok(Frame { settings, camera })
        })
        .collect()
}

/// The crop of `camera`'s frame to render: the `tile`'s, else `--region`,
/// else the whole frame.
///
/// # Errors
/// One line when the crop does not fit in the frame.
fn region(tile: Option<&TileJob>, asked: Option<Rect>, camera: &Camera) -> Result<Rect, String> {
    let region = match tile {
        Some(tile) => tile.placement.rect,
        None => asked.unwrap_or(Rect::full(camera)),
    };
    region.validate(camera).map_err(|_| {
        format!(
            "--region {},{},{},{} does not fit in the {}x{} frame",
            region.x,
            region.y,
            region.width,
            region.height,
            camera.width(),
            camera.height()
        )
    })?;
    Ok(region)
}

/// The options the `effects` ask for on `subject` seen from `view` (a
/// `.vox` file's light folded in, fog scaled to the view, as every
/// frontend reads them), and the plan of what runs.
fn resolve_effects(
    effects: &Effects,
    subject: &Subject<'_>,
    view: &CameraSettings,
) -> (RenderOptions, EffectPlan) {
    let model = subject.shown.model();
    let options = voxtrace_flags::render_options(effects, subject.shown.bounds(), model, view);
    let plan = EffectPlan::new(&options, subject.shown.materials());
    (options, plan)
}

/// A note for each effect asked for in `options` that the `plan` does not
/// run, then for each flag `given` that changes nothing for the camera
/// `settings` and the output `format`.
fn notes(
    options: &RenderOptions,
    plan: &EffectPlan,
    given: &GivenFlags,
    settings: &CameraSettings,
    format: Format,
) -> Vec<String> {
    let mut notes = ignored_effects(options);
    if plan.look == Look::Path {
        notes.extend(unused_in_path(options));
    } else {
        for (flag, given) in [
            ("--noise-threshold", given.noise_threshold),
            ("--max-spp", given.max_spp),
        ] {
            if given {
                notes.push(format!(
                    "the scene is not path-traced: {flag} changes nothing (--spp sets its samples)"
                ));
            }
        }
    }
    if given.time_limit {
        notes.extend(budget::unused_note(plan));
    }
    notes.extend(ignored_flags(given, settings, format, options));
    notes
}

/// Fewer fixed samples than this leave a path-traced frame visibly grainy.
const GRAINY_BELOW: u16 = 16;

/// A note when `--denoise` is asked of a frame that is not path-traced,
/// whose pixels have no sampling noise.
fn nothing_to_denoise(plan: &EffectPlan, denoise: bool) -> Option<String> {
    (denoise && plan.look != Look::Path).then(|| {
        "--denoise has little to clean here: the frame is not path-traced, so its \
         pixels carry no sampling noise (it was denoised as asked)"
            .into()
    })
}

/// A hint when a path-traced frame takes a fixed, low `--spp` and is not
/// denoised: it will be grainy, and two flags help.
fn low_samples_hint(options: &RenderOptions, plan: &EffectPlan, denoise: bool) -> Option<String> {
    // Without --spp a path-traced frame samples adaptively.
    let fixed = options.adaptive.is_none();
    (plan.look == Look::Path && fixed && options.samples < GRAINY_BELOW && !denoise).then(|| {
        format!(
            "{} samples per pixel leave a path-traced frame grainy: without --spp it samples \
             until the noise is low (--noise-threshold), or --denoise cleans it",
            options.samples
        )
    })
}

/// For a file of several animation frames rendered without `--frame`:
/// which frame this is, and how to render another.
fn animation_note(subject: &Subject, frame: Option<u32>) -> Option<String> {
    let frames = subject.shown.model()?.frames();
    (frames > 1 && frame.is_none()).then(|| {
        format!(
            "the file holds {frames} animation frames; this is frame 0 (--frame N renders frame N, 0 to {}; --frame all renders each to its own file)",
            frames - 1
        )
    })
}

/// A note when a frame's camera starts inside a solid voxel (its rays see
/// only that voxel), saying what moves it: `--position`, or for a file's
/// camera (`file_camera`, which refuses `--position`) another camera or
/// the default view.
fn camera_inside_note(
    cameras: &[Frame],
    subject: &Subject,
    file_camera: Option<u32>,
) -> Option<String> {
    let bounds = subject.shown.bounds();
    let inside = cameras.iter().any(|frame| {
        let cell = frame.settings.lookfrom.floor().as_ivec3();
        bounds.contains(cell) && subject.shown.material(cell) != 0
    });
    let remedy = match file_camera {
        Some(n) => format!(
            "the file's camera {n} sits there: choose another with --camera, or leave it out for the default view"
        ),
        None => "move it with --position".to_string(),
    };
    inside.then(|| {
        format!("the camera starts inside a solid voxel: its rays see only that voxel ({remedy})")
    })
}

/// Checks the output `out` in `format` before the render, so that a bad
/// one fails now, not after it: a `tiled` run's part is PNG, standard
/// output (`-`) takes one still that is not a tile, and is not a
/// terminal. Returns the path of every frame: `out`, or the `pattern`'s
/// for each of the `frames` of an animation (one file each).
///
/// # Errors
/// One line naming the problem.
fn output_paths(
    out: &Path,
    format: Format,
    tiled: bool,
    pattern: &Path,
    frames: Option<FrameRange>,
) -> Result<Vec<PathBuf>, String> {
    if tiled && format != Format::Png {
        return Err(format!(
            "--tiles writes PNG parts (their place in the frame is a PNG text chunk), not --out {}",
            show_path(out)
        ));
    }
    // `%t` names a tile's part: without --tiles it would be written as is.
    let has_tile_number = |p: &Path| {
        p.as_os_str()
            .as_encoded_bytes()
            .windows(2)
            .any(|w| w == b"%t")
    };
    if !tiled && has_tile_number(pattern) {
        return Err(format!(
            "--out {} has %t, the tile number of --tiles parts: without --tiles, name one file",
            show_path(pattern)
        ));
    }
    let to_stdout = output::is_stdout(out);
    if to_stdout && tiled {
        return Err(
            "--tiles writes a part file for `voxtrace stitch`: --out - cannot be one".into(),
        );
    }
    if to_stdout && frames.is_some() {
        return Err("--frames writes one file per frame: --out - cannot hold them".into());
    }
    if to_stdout {
        output::check_stdout()?;
    }
    match frames {
        Some(range) => range.frames().map(|k| frame_path(pattern, k)).collect(),
        None => Ok(vec![out.to_path_buf()]),
    }
}

/// Prints the random seed, the file's warnings and the `notes`, only after
/// a success: an error stays the one line on stderr. Escaped: a path a
/// warning quotes cannot start a line of its own.
fn report(subject: &Subject<'_>, notes: &[String]) {
    if let (voxtrace_flags::Subject::Terrain { seed, .. }, true) = (&subject.shown, subject.random)
    {
        say!("seed: {seed}");
    }
    subject
        .warnings()
        .iter()
        .for_each(|w| say!("warning: {}", escape_controls(w)));
    notes
        .iter()
        .for_each(|note| say!("note: {}", escape_controls(note)));
}

/// `--export-vox`: the terrain of `seed` (random without one) and `size`
/// as a `.vox` file at `path`, with `--stats`' counts when `stats`. The
/// file is written as every output is: whole, or not at all.
fn export(path: &Path, seed: Option<u64>, size: i32, stats: bool) -> Result<(), String> {
    let failed = |e: String| format!("cannot write --export-vox {}: {e}", show_path(path));
    // Before the work: a bad path fails at once.
    let mut file = AtomicFile::create(path).map_err(|e| failed(e.to_string()))?;
    let (seed, random) = terrain_seed(seed);
    let mut bytes = Vec::new();
    let terrain = VoxelGenerator::new(seed);
    let count = export_vox(&terrain, terrain_box(&terrain, size), &mut bytes)?;
    file.write_all(&bytes)
        .and_then(|()| file.commit())
        .map_err(|e| failed(e.to_string()))?;
    // Only now: an error stays the one line on stderr.
    if random {
        say!("seed: {seed}");
    }
    if stats {
        say!("voxels: {count}");
        say!("file_bytes: {}", bytes.len());
    }
    Ok(())
}

//! `voxtrace stitch` under attack: an `--out` that is one of its parts,
//! damaged parts (a pixel altered with its chunk CRC fixed up, an ancillary
//! chunk with a bad CRC, the last `IDAT` dropped, bytes after the zlib
//! stream or after `IEND`), `--out -`, signals, a frame too large for
//! memory and file names with newlines. Each is one `error:` line and exit
//! 2 (130/143 for a signal), or the frame. Forged digests and every bit of
//! a part's image data flipped are in `hostile/stitch_digest.rs`.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::limits::{check_contract, run_limited, tools_present};
use common::parts::{chunks, idat_indices, numbered_part, png_of, Chunk};
use common::run::{assert_refused, fresh_dir, stderr};
#[cfg(unix)]
use common::terminal::Pty;
use voxtrace_cli::part::write_part;
use voxtrace_cli::tiles::Grid;

/// A fresh empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    fresh_dir("stitch", name)
}

/// `voxtrace stitch ARGS` run in `dir`.
fn stitch_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .arg("stitch")
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

const SETTINGS: &str = "voxtrace=test subject=[terrain seed=1 size=30]";

/// Writes tile `tile` of `grid` over a `width x height` frame into `path`,
/// its pixel at (x, y) being `x + 1000 y`.
fn write_tile(path: &Path, grid: Grid, width: u32, height: u32, tile: u32) {
    let part = numbered_part(grid, width, height, tile, SETTINGS);
    let file = std::fs::File::create(path).unwrap();
    write_part(file, &part.placement, &part.settings, &part.pixels).unwrap();
}

/// The two tiles of a 2x1 grid over a 20x10 frame, `t-0.png` and `t-1.png`
/// in `dir`.
fn two_tiles(dir: &Path) -> [PathBuf; 2] {
    let grid = Grid::new(2, 1).unwrap();
    [0, 1].map(|tile| {
        let path = dir.join(format!("t-{tile}.png"));
        write_tile(&path, grid, 20, 10, tile);
        path
    })
}

#[cfg(unix)]
#[test]
fn an_out_that_is_one_of_the_parts_is_refused_however_it_is_spelled() {
    let dir = scratch("out-is-part");
    let parts = two_tiles(&dir);
    let before = std::fs::read(&parts[0]).unwrap();
    std::os::unix::fs::symlink("t-0.png", dir.join("link.png")).unwrap();
    std::fs::create_dir(dir.join("sub")).unwrap();
    for (args, named) in [
        (["t-0.png", "t-1.png", "--out", "t-0.png"], "t-0.png"),
        (["t-0.png", "t-1.png", "--out", "./t-0.png"], "t-0.png"),
        (["t-0.png", "t-1.png", "--out", "sub/../t-1.png"], "t-1.png"),
        // The output through a symlink to a part, and a part through one.
        (["t-0.png", "t-1.png", "--out", "link.png"], "t-0.png"),
        (["link.png", "t-1.png", "--out", "t-0.png"], "link.png"),
    ] {
        let out = stitch_in(&dir, &args);
        assert_refused(&out, &["--out", "is the part", named]);
    }
    assert_eq!(std::fs::read(&parts[0]).unwrap(), before);
    // Hard links are the same file too.
    std::fs::hard_link(&parts[1], dir.join("hard.png")).unwrap();
    assert_refused(
        &stitch_in(&dir, &["t-0.png", "t-1.png", "--out", "hard.png"]),
        &["is the part t-1.png"],
    );
    // A different file of the same name elsewhere is fine.
    let ok = stitch_in(&dir, &["t-0.png", "t-1.png", "--out", "sub/t-0.png"]);
    assert!(ok.status.success(), "{}", stderr(&ok));
}

/// `png` re-encoded with its image data stored uncompressed (so that any
/// byte of it can change and the stream still inflates) and the first
/// pixel's red byte flipped, the IDAT chunk's CRC recomputed: the zlib
/// stream's Adler-32 and the part's digest still tell.
fn flip_a_pixel_byte(png: &[u8]) -> Vec<u8> {
    let decoder = png::Decoder::new(std::io::Cursor::new(png));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    reader.next_frame(&mut pixels).unwrap();
    let info = reader.info().clone();
    let mut stored = Vec::new();
    let mut encoder = png::Encoder::new(&mut stored, info.width, info.height);
    encoder.set_color(info.color_type);
    encoder.set_depth(info.bit_depth);
    encoder.set_compression(png::Compression::NoCompression);
    encoder.set_filter(png::Filter::NoFilter);
    for chunk in &info.uncompressed_latin1_text {
        encoder
            .add_text_chunk(chunk.keyword.clone(), chunk.text.clone())
            .unwrap();
    }
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(&pixels).unwrap();
    // The digest after the image data (the decoder has read the chunks
    // before it only), where voxtrace writes it.
    let digest = common::parts::text_of(png, "voxtrace-digest");
    let digest = png::text_metadata::TEXtChunk::new("voxtrace-digest", digest);
    writer.write_text_chunk(&digest).unwrap();
    writer.finish().unwrap();

    let idat = stored.windows(4).position(|w| w == b"IDAT").unwrap() - 4;
    let len = u32::from_be_bytes(stored[idat..idat + 4].try_into().unwrap()) as usize;
    // zlib header (2), stored block header (5), row 0's filter byte (1).
    stored[idat + 8 + 2 + 5 + 1] ^= 0x40;
    let crc = common::parts::crc32(&stored[idat + 4..idat + 8 + len]);
    stored[idat + 8 + len..idat + 12 + len].copy_from_slice(&crc.to_be_bytes());
    // The tampered file is still a valid PNG to the png crate's default
    // decoder, which skips Adler-32: only the pixel differs.
    let lax = png::Decoder::new(std::io::Cursor::new(&stored));
    let mut reader = lax.read_info().unwrap();
    let mut altered = vec![0; reader.output_buffer_size().unwrap()];
    reader.next_frame(&mut altered).unwrap();
    assert_eq!(altered[0], pixels[0] ^ 0x40);
    assert_eq!(altered[1..], pixels[1..]);
    stored
}

#[test]
fn a_part_whose_image_data_was_altered_is_refused_naming_it() {
    let dir = scratch("adler");
    let parts = two_tiles(&dir);
    let tampered = dir.join("tampered.png");
    std::fs::write(
        &tampered,
        flip_a_pixel_byte(&std::fs::read(&parts[1]).unwrap()),
    )
    .unwrap();
    let out = stitch_in(&dir, &["t-0.png", "tampered.png", "--out", "frame.png"]);
    assert_refused(&out, &["tampered.png", "corrupt"]);
    assert!(!dir.join("frame.png").exists());
}

/// Stitches `t-0.png` with `name` (tile 1), written as `bytes`, in `dir`,
/// and checks that the stitch was refused, naming `name` and each of
/// `needles`, and wrote no frame.
fn refused_as_tile_1(dir: &Path, name: &str, bytes: &[u8], needles: &[&str]) {
    std::fs::write(dir.join(name), bytes).unwrap();
    let out = stitch_in(dir, &["t-0.png", name, "--out", "frame.png"]);
    assert_refused(&out, &[&[name][..], needles].concat());
    assert!(!dir.join("frame.png").exists());
}

#[test]
fn a_part_with_an_ancillary_chunk_whose_crc_is_bad_is_refused() {
    let dir = scratch("ancillary-crc");
    let parts = two_tiles(&dir);
    let good = chunks(&std::fs::read(&parts[1]).unwrap());
    // A chunk the stitch does not read (tIME, the last-modified time)
    // whose CRC does not match: the PNG crate skips such a chunk unless
    // told not to.
    let mut time = Chunk::new(b"tIME", vec![7, 233, 1, 2, 3, 4, 5]);
    time.crc ^= 1;
    let mut with_time = good.clone();
    with_time.insert(1, time);
    refused_as_tile_1(&dir, "time.png", &png_of(&with_time), &["CRC", "tIME"]);
    // And one of the part's own text chunks: a CRC error, not a part that
    // seems to lack the chunk.
    for keyword in ["voxtrace-part", "voxtrace-settings", "voxtrace-digest"] {
        let mut bad = good.clone();
        let chunk = bad
            .iter_mut()
            .find(|c| c.as_text().is_some_and(|(k, _)| k == keyword))
            .unwrap();
        chunk.crc ^= 0x8000_0000;
        refused_as_tile_1(&dir, "text.png", &png_of(&bad), &["CRC", "tEXt"]);
    }
}

#[test]
fn a_part_whose_last_idat_is_dropped_is_refused() {
    let dir = scratch("dropped-idat");
    let parts = two_tiles(&dir);
    let mut chunks = chunks(&std::fs::read(&parts[1]).unwrap());
    let idats = idat_indices(&chunks);
    // The core's encoder ends the stream in an IDAT of its own (the final
    // block and the Adler-32): without it the pixels all decode.
    assert!(idats.len() >= 2, "one IDAT only");
    chunks.remove(*idats.last().unwrap());
    refused_as_tile_1(
        &dir,
        "dropped.png",
        &png_of(&chunks),
        &["zlib stream is cut short"],
    );
}

#[test]
fn a_part_with_bytes_after_its_zlib_stream_or_after_iend_is_refused() {
    let dir = scratch("trailing");
    let parts = two_tiles(&dir);
    let good = std::fs::read(&parts[1]).unwrap();
    // A byte after the zlib stream, inside the last IDAT (its CRC made
    // right): decoders skip it.
    let mut chunks = chunks(&good);
    let last = *idat_indices(&chunks).last().unwrap();
    chunks[last].data.push(0);
    chunks[last].fix_crc();
    refused_as_tile_1(
        &dir,
        "after-stream.png",
        &png_of(&chunks),
        &["after its zlib stream's end"],
    );
    // An IDAT after the stream's end.
    let mut chunks = common::parts::chunks(&good);
    chunks.insert(last + 1, Chunk::new(b"IDAT", vec![0; 4]));
    refused_as_tile_1(
        &dir,
        "extra-idat.png",
        &png_of(&chunks),
        &["after its zlib stream's end"],
    );
    // Bytes after IEND.
    let trailing = [&good[..], b"more"].concat();
    refused_as_tile_1(&dir, "after-iend.png", &trailing, &["after IEND"]);
}

/// The frame of `two_tiles` as a PNG, stitched into a file.
fn stitched_file(dir: &Path) -> Vec<u8> {
    let out = stitch_in(dir, &["t-0.png", "t-1.png", "--out", "file.png"]);
    assert!(out.status.success(), "{}", stderr(&out));
    std::fs::read(dir.join("file.png")).unwrap()
}

#[test]
fn out_dash_writes_the_frame_to_standard_output() {
    let dir = scratch("stdout");
    two_tiles(&dir);
    let out = stitch_in(&dir, &["t-0.png", "t-1.png", "--out", "-"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out.stdout == stitched_file(&dir), "stdout is not the frame");
    assert!(!dir.join("-").exists(), "a file named - was written");
}

#[cfg(unix)]
#[test]
fn out_dash_to_a_full_disk_a_closed_pipe_or_no_stdout_is_one_error_line() {
    let dir = scratch("stdout-fails");
    two_tiles(&dir);
    let run = |stdout: Stdio| {
        Command::new(env!("CARGO_BIN_EXE_voxtrace"))
            .args(["stitch", "t-0.png", "t-1.png", "--out", "-"])
            .current_dir(&dir)
            .stdout(stdout)
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = run(full.into()).wait_with_output().unwrap();
    assert_refused(&out, &["standard output"]);

    // A pipe whose reader has gone: the write fails with EPIPE. (Closed
    // before the child starts: a child that wrote a small frame into the
    // pipe's buffer before a later close would succeed.)
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let out = run(writer.into()).wait_with_output().unwrap();
    assert_refused(&out, &["standard output"]);

    // Closed (`>&-`): Rust's runtime puts /dev/null there, which must not
    // swallow the frame; a redirection to /dev/null is still fine.
    let shell = |redirect: &str| {
        Command::new("sh")
            .arg("-c")
            .arg(format!(
                "exec \"$0\" stitch t-0.png t-1.png --out - {redirect}"
            ))
            .arg(env!("CARGO_BIN_EXE_voxtrace"))
            .current_dir(&dir)
            .output()
            .unwrap()
    };
    if cfg!(target_os = "linux") {
        assert_refused(&shell(">&-"), &["standard output, which is closed"]);
    }
    let null = shell(">/dev/null");
    assert!(null.status.success(), "{}", stderr(&null));
}

#[cfg(unix)]
#[test]
fn out_dash_refuses_a_terminal() {
    let Some(pty) = Pty::open() else {
        eprintln!("skipped: no pseudo-terminal here");
        return;
    };
    let terminal = pty.terminal();
    let dir = scratch("stdout-tty");
    two_tiles(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(["stitch", "t-0.png", "t-1.png", "--out", "-"])
        .current_dir(&dir)
        .stdout(terminal)
        .output()
        .unwrap();
    assert_refused(&out, &["terminal", "--out FILE"]);
}

/// A terminal named by its path (`/dev/tty`, here a pseudo-terminal's
/// `/dev/pts/N`) is refused as a render refuses it: no PNG bytes on it.
#[cfg(unix)]
#[test]
fn out_a_terminal_by_its_path_is_refused() {
    let Some(pty) = Pty::open() else {
        eprintln!("skipped: no pseudo-terminal here");
        return;
    };
    let dir = scratch("path-tty");
    two_tiles(&dir);
    let terminal = pty.path.to_str().unwrap();
    let out = stitch_in(&dir, &["t-0.png", "t-1.png", "--out", terminal]);
    assert_refused(&out, &["terminal", terminal, "--out FILE"]);
}

/// SIGTERM while the stitch waits on a part (a FIFO no one writes): exit
/// 143 with one `error:` line, the old `--out` kept, no temporary file.
#[cfg(unix)]
#[test]
fn a_signal_during_a_stitch_is_one_error_line_and_leaves_no_temporary_file() {
    let dir = scratch("signal");
    two_tiles(&dir);
    let made = Command::new("mkfifo").arg(dir.join("fifo.png")).status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("skipped: mkfifo is not available");
        return;
    }
    std::fs::write(dir.join("frame.png"), b"the old file").unwrap();
    let child = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(["stitch", "t-0.png", "fifo.png", "--out", "frame.png"])
        .current_dir(&dir)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Wait until the signal thread runs (the handler is installed), or
    // give up after a while and signal anyway.
    let task = format!("/proc/{}/task", child.id());
    let started = Instant::now();
    while started.elapsed() < Duration::from_secs(10) {
        let threads = std::fs::read_dir(&task).map_or(0, Iterator::count);
        if threads >= 2 {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(100));
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let out = child.wait_with_output().unwrap();
    let text = stderr(&out);
    assert_eq!(out.status.code(), Some(143), "{text}");
    assert_eq!(text.lines().count(), 1, "{text}");
    assert!(
        text.starts_with("error: ") && text.contains("SIGTERM"),
        "{text}"
    );
    assert_eq!(
        std::fs::read(dir.join("frame.png")).unwrap(),
        b"the old file"
    );
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["fifo.png", "frame.png", "t-0.png", "t-1.png"]);
}

/// A part of a 12000x12000 frame (a 47x47 tile of a 256x256 grid) stitched
/// with `--allow-partial` under a 1 GiB address space: the frame and the
/// encoder's copy do not fit, and the refusal names the bytes instead of
/// an allocation failure aborting the process.
#[test]
fn a_frame_too_large_for_memory_is_refused_naming_the_bytes() {
    if !tools_present() {
        eprintln!("skipped: prlimit or timeout is missing");
        return;
    }
    let dir = scratch("huge");
    let part = dir.join("huge-0.png");
    write_tile(&part, Grid::new(256, 256).unwrap(), 12000, 12000, 0);
    let out = dir.join("frame.png");
    let args: Vec<String> = vec![
        "stitch".into(),
        part.display().to_string(),
        "--allow-partial".into(),
        "--out".into(),
        out.display().to_string(),
    ];
    let ended = run_limited(&args);
    check_contract("stitch of a 12000x12000 frame", &ended).unwrap();
    assert_eq!(ended.code, Some(2), "{}", ended.stderr);
    assert!(
        ended.stderr.contains("12000x12000") && ended.stderr.contains(" bytes)"),
        "{}",
        ended.stderr
    );
    assert!(!out.exists());
}

/// A part named with a newline (and an escape sequence): the refusal is
/// still one line, the characters shown escaped.
#[test]
fn a_part_path_with_a_newline_is_one_error_line() {
    let dir = scratch("newline");
    two_tiles(&dir);
    let out = stitch_in(
        &dir,
        &[
            "t-0.png",
            "absent\nerror: forged\u{1b}[2K.png",
            "--out",
            "f.png",
        ],
    );
    assert_refused(&out, &["absent\\nerror: forged\\u{1b}[2K.png"]);
    std::fs::copy(dir.join("t-1.png"), dir.join("new\nline.png")).unwrap();
    let out = stitch_in(&dir, &["t-1.png", "new\nline.png", "--out", "f.png"]);
    assert_refused(&out, &["duplicate tile 1", "new\\nline.png"]);
}

/// The setting a stitch names when two parts' settings differ
/// (`settings_diff`), from settings texts made here: the flag and both
/// values, the first listed setting of several, one short line for any
/// text.
mod settings_difference {

    use voxtrace_cli::part::settings_text;
    use voxtrace_cli::settings_diff::settings_difference;

    #[derive(Debug)]
    #[allow(dead_code)] // read through Debug
    struct Options {
        flat: bool,
        shadows: bool,
        occlusion: Option<Occlusion>,
    }

    #[derive(Debug)]
    #[allow(dead_code)] // read through Debug
    struct Occlusion {
        rays: u16,
        distance: f32,
    }

    fn text(subject: &str, backend: &str, shadows: bool, ao: Option<(u16, f32)>) -> String {
        let options = Options {
            flat: false,
            shadows,
            occlusion: ao.map(|(rays, distance)| Occlusion { rays, distance }),
        };
        settings_text(subject, backend, &(1.5f32, "camera"), &options)
    }

    #[test]
    fn a_difference_names_the_flag_and_both_values() {
        let base = text("terrain seed=3 size=30", "octree", true, None);
        let diff = |other: &str| settings_difference(&base, other);
        assert_eq!(diff(&base), None);
        assert_eq!(
            diff(&text("terrain seed=3 size=30", "octree", false, None)).unwrap(),
            "--shadows: true against false"
        );
        assert_eq!(
            diff(&text("terrain seed=9 size=30", "octree", true, None)).unwrap(),
            "--seed: 3 against 9"
        );
        assert_eq!(
            diff(&text("terrain seed=3 size=30", "dense", true, None)).unwrap(),
            "--backend: octree against dense"
        );
        assert_eq!(
            diff(&text(
                "terrain seed=3 size=30",
                "octree",
                true,
                Some((4, 8.0))
            ))
            .unwrap(),
            "--ao: None against Some(Occlusion { rays: 4, distance: 8.0 })"
        );
        let a = text("terrain seed=3 size=30", "octree", true, Some((4, 8.0)));
        let b = text("terrain seed=3 size=30", "octree", true, Some((4, 2.5)));
        assert_eq!(
            settings_difference(&a, &b).unwrap(),
            "--ao-distance: 8.0 against 2.5"
        );
        let vox = text("vox fnv1a64=00000000000000ff", "octree", true, None);
        assert!(
            diff(&vox).unwrap().starts_with("the scene"),
            "{:?}",
            diff(&vox)
        );
        let frame = |k| {
            text(
                &format!("vox fnv1a64=00000000000000ff frame={k}"),
                "octree",
                true,
                None,
            )
        };
        assert_eq!(
            settings_difference(&frame(0), &frame(2)).unwrap(),
            "--frame: 0 against 2"
        );
    }

    #[derive(Debug)]
    #[allow(dead_code)] // read through Debug
    struct Camera {
        pixel00: (f32, f32),
        center: (f32, f32),
    }

    #[test]
    fn of_several_differences_the_one_listed_first_is_named() {
        // The position is named before what it derives, though later in
        // the text.
        let camera = |x: f32| Camera {
            pixel00: (x - 1.0, 0.5),
            center: (x, 0.0),
        };
        let text = |x| settings_text("terrain seed=1 size=9", "octree", &camera(x), &());
        let diff = settings_difference(&text(1.0), &text(2.0)).unwrap();
        assert!(
            diff.starts_with("the camera position (--position")
                && diff.ends_with(": (1.0, 0.0) against (2.0, 0.0)"),
            "{diff}"
        );
    }

    #[test]
    fn texts_that_are_not_settings_still_give_one_short_line() {
        let long = "x".repeat(10_000);
        let diff = settings_difference("a=1 b=[2", &long).unwrap();
        assert!(diff.len() < 200 && diff.ends_with("..."), "{diff}");
        assert_eq!(settings_difference("é=1", "é=2").unwrap(), "é: 1 against 2");
        // Nesting deeper than any settings text stops early, not on the stack.
        let nested = |leaf: &str| "A { a: ".repeat(100_000) + leaf + &" }".repeat(100_000);
        let deep = settings_difference(&nested("1"), &nested("2")).unwrap();
        assert!(deep.lines().count() == 1 && deep.len() < 200, "{deep}");
    }
}

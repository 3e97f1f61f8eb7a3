//! End-to-end tests of the `voxtrace` binary: it writes valid PNGs, both
//! backends write identical files, and bad input exits 2 with one line.

mod common;

use std::path::{Path, PathBuf};

use common::run::{scratch_in, voxtrace};

fn scratch(name: &str) -> PathBuf {
    scratch_in("cli", name)
}

/// Decodes a PNG into (width, height, RGBA bytes).
fn decode(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgba);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

fn render(backend: &str, extra: &[&str], name: &str) -> PathBuf {
    let out = scratch(name);
    let mut args = vec![
        "--backend",
        backend,
        "--size",
        "50",
        "--width",
        "320",
        "--height",
        "180",
        "--seed",
        "1",
    ];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--out", out.to_str().unwrap()]);
    let result = voxtrace(&args);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    out
}

#[test]
fn renders_a_valid_png_with_terrain_and_sky() {
    // At size 50 the paper's camera (40, 40, 40) sits inside the terrain for
    // many seeds; look from above instead.
    let out = render("octree", &["--position", "60,90,45"], "valid.png");
    let (w, h, rgba) = decode(&out);
    assert_eq!((w, h), (320, 180));
    let pixels: Vec<&[u8]> = rgba.chunks(4).collect();
    assert!(pixels.iter().all(|p| p[3] == 255));
    // Sky is blue-dominant and light; grass is green-dominant.
    let sky = pixels.iter().filter(|p| p[2] > p[1] && p[2] > 200).count();
    let grass = pixels.iter().filter(|p| p[1] > p[0] && p[1] > p[2]).count();
    assert!(
        sky > 1000 && grass > 10_000,
        "sky {sky}, grass {grass} of {}",
        pixels.len()
    );
}

#[test]
fn dense_and_octree_write_identical_files() {
    for extra in [
        &[][..],
        &["--flat"][..],
        &["--position", "0,120,0.5", "--fov", "100"][..],
    ] {
        let a = std::fs::read(render("dense", extra, "a.png")).unwrap();
        let b = std::fs::read(render("sparse", extra, "b.png")).unwrap();
        assert!(a == b, "backends differ with {extra:?}");
    }
}

#[test]
fn region_is_the_same_pixels_as_the_full_frame() {
    let (_, _, full) = decode(&render("octree", &[], "full.png"));
    let (w, h, crop) = decode(&render("dense", &["--region", "100,40,64,30"], "crop.png"));
    assert_eq!((w, h), (64, 30));
    for row in 0..30usize {
        let start = ((40 + row) * 320 + 100) * 4;
        assert_eq!(
            &crop[row * 64 * 4..(row + 1) * 64 * 4],
            &full[start..start + 64 * 4],
            "row {row}"
        );
    }
}

#[test]
fn every_thread_count_writes_the_same_file() {
    let scalar = std::fs::read(render("octree", &["--threads", "1"], "t1.png")).unwrap();
    for threads in ["2", "3"] {
        let name = format!("t{threads}.png");
        for backend in ["octree", "dense"] {
            let threaded = render(backend, &["--threads", threads], &name);
            assert!(
                std::fs::read(threaded).unwrap() == scalar,
                "{backend} with --threads {threads} differs from --threads 1"
            );
        }
    }
    // A crop on threads equals the scalar crop.
    let crop = ["--region", "7,150,301,30"];
    let a = std::fs::read(render(
        "octree",
        &[&crop[..], &["--threads", "1"]].concat(),
        "c1.png",
    ));
    let b = std::fs::read(render(
        "octree",
        &[&crop[..], &["--threads", "2"]].concat(),
        "c2.png",
    ));
    assert!(a.unwrap() == b.unwrap());
}

#[test]
fn stats_print_every_contract_key() {
    let out = scratch("stats.png");
    let result = voxtrace([
        "--size",
        "20",
        "--width",
        "32",
        "--height",
        "16",
        "--seed",
        "3",
        "--stats",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success());
    let stderr = String::from_utf8(result.stderr).unwrap();
    for key in [
        "build_ms",
        "render_ms",
        "encode_ms",
        "primary_rays",
        "shadow_rays",
        "ao_rays",
        "reflection_rays",
        "refraction_rays",
        "light_rays",
        "rays_in_packets",
        "rays_alone",
        "storage_bytes",
        "mrays_per_s",
    ] {
        let line = stderr
            .lines()
            .find(|l| l.starts_with(&format!("{key}: ")))
            .unwrap_or_else(|| panic!("no {key} in {stderr}"));
        let value = line.split_once(": ").unwrap().1;
        assert!(value.parse::<f64>().is_ok(), "{line}");
    }
    assert!(stderr.contains("primary_rays: 512\n"));
    // The terrain calls for nothing new: the face-shaded look, no new rays.
    assert!(stderr.contains("effects: sun\n"), "{stderr}");
    for key in ["reflection_rays", "refraction_rays", "light_rays"] {
        assert!(stderr.contains(&format!("{key}: 0\n")), "{stderr}");
    }
    // Every ray took one route or the other.
    let count = |key: &str| -> u64 {
        let line = stderr.lines().find(|l| l.starts_with(&format!("{key}: ")));
        line.and_then(|l| l.split_once(": ")?.1.parse().ok())
            .unwrap()
    };
    assert_eq!(count("rays_in_packets") + count("rays_alone"), 512);
}

#[test]
fn missing_seed_is_printed_and_reproduces_the_render() {
    let out = scratch("random.png");
    let result = voxtrace([
        "--size",
        "20",
        "--width",
        "48",
        "--height",
        "27",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(result.status.success());
    let stderr = String::from_utf8(result.stderr).unwrap();
    let seed = stderr
        .lines()
        .find_map(|l| l.strip_prefix("seed: "))
        .expect("seed printed");
    let again = scratch("again.png");
    let result = voxtrace([
        "--size",
        "20",
        "--width",
        "48",
        "--height",
        "27",
        "--seed",
        seed,
        "--out",
        again.to_str().unwrap(),
    ]);
    assert!(result.status.success());
    assert_eq!(std::fs::read(out).unwrap(), std::fs::read(again).unwrap());
}

#[test]
fn bad_input_exits_2_with_one_line_naming_the_value() {
    let unwritable = "/nonexistent-dir/x.png";
    let out = scratch("bad.png");
    let out = out.to_str().unwrap();
    let cases: &[(&[&str], &str)] = &[
        (&["--size", "0"], "0"),
        (&["--size", "abc"], "abc"),
        (&["--width", "0"], "0"),
        (&["--backend", "bvh"], "bvh"),
        (&["--position", "1,2"], "1,2"),
        (&["--position", "1,x,3"], "x"),
        (&["--fov", "180"], "field of view"),
        (&["--position", "5,5,5", "--lookat", "5,5,5"], "coincide"),
        // Straight down renders (a map); only an explicit --up along the
        // view is refused.
        (&["--position", "0,150,0", "--up", "0,1,0"], "parallel"),
        (&["--region", "300,0,64,64"], "300,0,64,64"),
        (&["--threads", "0"], "0"),
        (&["--threads", "-3"], "-3"),
        (&["--spp", "0"], "0"),
        (&["--ao", "0"], "0"),
        (&["--ao", "2", "--ao-distance", "-1"], "-1"),
        (&["--sun", "0,0,0"], "0,0,0"),
        (&["--sun", "up"], "up"),
        (&["--out", unwritable], unwritable),
        (&["--out", "x.webp"], ".webp"),
        (&["--vox", "/nonexistent.vox"], "/nonexistent.vox"),
        // A note-worthy flag does not add a line to an error.
        (
            &["--sun", "none", "--shadows", "--out", unwritable],
            unwritable,
        ),
        (
            &["--size", "4194304", "--backend", "dense"],
            "590295810358705651712 bytes",
        ),
    ];
    for (args, needle) in cases {
        let mut all = vec![
            "--width", "32", "--height", "18", "--seed", "1", "--out", out,
        ];
        all.extend_from_slice(args);
        let result = voxtrace(&all);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(
            stderr.trim_end().lines().count(),
            1,
            "{args:?}: one line, got {stderr}"
        );
        assert!(
            stderr.contains(needle),
            "{args:?}: {stderr} should name {needle}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

/// The one line of a run that must fail with exit 2.
fn refusal(result: &std::process::Output) -> String {
    let stderr = String::from_utf8_lossy(&result.stderr).into_owned();
    assert_eq!(result.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    stderr
}

#[test]
fn errors_say_what_applies_and_print_nothing_before() {
    use std::ffi::OsStr;
    use std::os::unix::ffi::OsStrExt;
    // A random seed is printed after a success only: an error is alone.
    let unwritable = "/nonexistent-dir/terrain.vox";
    let stderr = refusal(&voxtrace(["--export-vox", unwritable, "--size", "8"]));
    assert!(stderr.contains(unwritable), "{stderr}");
    // An index variable holding bytes that are not text is not "unset".
    let out = scratch("tile-%t.png");
    let result = std::process::Command::new(env!("CARGO_BIN_EXE_voxtrace"))
        .args(["--tiles", "2x2", "--tile-index", "env:VOXTRACE_TEST_INDEX"])
        .args(["--seed", "1", "--width", "16", "--height", "9", "--out"])
        .arg(&out)
        .env("VOXTRACE_TEST_INDEX", OsStr::from_bytes(b"\xff1"))
        .output()
        .unwrap();
    let stderr = refusal(&result);
    assert!(
        stderr.contains("VOXTRACE_TEST_INDEX is not valid UTF-8") && stderr.contains("0 to 3"),
        "{stderr}"
    );
    // A .vox model's size is its own: the refusal does not suggest --size.
    let vox = write_vox("refused.vox");
    let out = scratch("refused.png");
    for (frame, remedy) in [("16", "--max-memory"), ("4000", "a smaller frame")] {
        let result = voxtrace([
            "--vox",
            vox.to_str().unwrap(),
            "--max-memory",
            "1K",
            "--width",
            frame,
            "--height",
            frame,
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = refusal(&result);
        assert!(
            stderr.contains(remedy) && !stderr.contains("--size"),
            "{frame}: {stderr}"
        );
    }
}

/// `key: value` lines of `--stats` as numbers.
fn stat(stderr: &str, key: &str) -> u64 {
    common::run::stat(stderr, key).parse().unwrap()
}

fn stats_with(extra: &[&str]) -> String {
    let out = scratch("effects.png");
    let mut args = vec![
        "--size",
        "30",
        "--width",
        "32",
        "--height",
        "16",
        "--seed",
        "3",
        "--position",
        "40,60,30",
        "--stats",
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let result = voxtrace(&args);
    let stderr = String::from_utf8(result.stderr).unwrap();
    assert!(result.status.success(), "{stderr}");
    stderr
}

#[test]
fn each_effect_flag_counts_its_rays_and_only_its_rays() {
    let plain = stats_with(&[]);
    assert_eq!(stat(&plain, "primary_rays"), 512);
    assert_eq!(stat(&plain, "shadow_rays"), 0);
    assert_eq!(stat(&plain, "ao_rays"), 0);

    let shadows = stats_with(&["--shadows"]);
    assert!(stat(&shadows, "shadow_rays") > 0, "{shadows}");
    assert!(stat(&shadows, "shadow_rays") <= 512);
    assert_eq!(stat(&shadows, "ao_rays"), 0);

    let ao = stats_with(&["--ao", "3"]);
    let ao_rays = stat(&ao, "ao_rays");
    assert!(
        ao_rays > 0 && ao_rays % 3 == 0 && ao_rays <= 3 * 512,
        "{ao}"
    );
    assert_eq!(stat(&ao, "shadow_rays"), 0);

    let spp = stats_with(&["--spp", "4"]);
    assert_eq!(stat(&spp, "primary_rays"), 4 * 512);
    assert_eq!(stat(&spp, "shadow_rays") + stat(&spp, "ao_rays"), 0);
}

#[test]
fn shadows_without_a_sun_trace_nothing_and_say_so_once() {
    let stderr = stats_with(&["--sun", "none", "--shadows"]);
    assert_eq!(stat(&stderr, "shadow_rays"), 0);
    let notes: Vec<&str> = stderr.lines().filter(|l| l.starts_with("note:")).collect();
    assert_eq!(notes.len(), 1, "{stderr}");
    assert!(notes[0].contains("no light"), "{stderr}");
    // Effects under --flat are named as ignored, once.
    let stderr = stats_with(&["--flat", "--ao", "2", "--spp", "2"]);
    assert_eq!(stat(&stderr, "ao_rays"), 0);
    assert_eq!(stat(&stderr, "primary_rays"), 512);
    let notes: Vec<&str> = stderr.lines().filter(|l| l.starts_with("note:")).collect();
    assert_eq!(
        notes,
        ["note: --flat draws no effects: ignoring --ao, --spp"]
    );
}

/// With the `image` feature, `--out`'s extension picks the format, and
/// every format carries the PNG's pixels.
#[cfg(feature = "image")]
#[test]
fn other_formats_carry_the_pngs_pixels() {
    let (_, _, png) = decode(&render("octree", &[], "same.png"));
    for ext in ["bmp", "tga", "ppm"] {
        let path = render("octree", &[], &format!("same.{ext}"));
        let image = image::open(&path)
            .unwrap_or_else(|e| panic!("{ext}: {e}"))
            .to_rgba8();
        assert_eq!(image.dimensions(), (320, 180), "{ext}");
        assert!(image.as_raw() == &png, "{ext} pixels differ from the PNG's");
    }
}

/// A small two-instance scene written with dot_vox's own writer.
fn write_vox(name: &str) -> PathBuf {
    use dot_vox::{Color, DotVoxData, Frame, Model, SceneNode, ShapeModel, Size, Voxel};
    let dict = |pairs: &[(&str, &str)]| -> dot_vox::Dict {
        pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect()
    };
    let voxels = (0..6u8)
        .flat_map(|x| {
            (0..4u8).map(move |z| Voxel {
                x,
                y: x % 3,
                z,
                i: 1 + x * 4 + z,
            })
        })
        .collect();
    let mut scenes = vec![
        SceneNode::Transform {
            attributes: dict(&[]),
            frames: vec![Frame::new(dict(&[]))],
            child: 1,
            layer_id: 0,
        },
        SceneNode::Group {
            attributes: dict(&[]),
            children: vec![2, 4],
        },
    ];
    for (t, r) in [("0 0 0", "4"), ("8 -3 2", "33")] {
        scenes.push(SceneNode::Transform {
            attributes: dict(&[]),
            frames: vec![Frame::new(dict(&[("_t", t), ("_r", r)]))],
            child: scenes.len() as u32 + 1,
            layer_id: 0,
        });
        scenes.push(SceneNode::Shape {
            attributes: dict(&[]),
            models: vec![ShapeModel {
                model_id: 0,
                attributes: dict(&[]),
            }],
        });
    }
    let data = DotVoxData {
        version: 150,
        index_map: Vec::new(),
        models: vec![Model {
            size: Size { x: 6, y: 3, z: 4 },
            voxels,
        }],
        palette: (0..=255u8)
            .map(|i| Color {
                r: i,
                g: 200 - i / 2,
                b: 90,
                a: 255,
            })
            .collect(),
        materials: Vec::new(),
        scenes,
        layers: Vec::new(),
    };
    let path = scratch(name);
    let mut file = std::fs::File::create(&path).unwrap();
    data.write_vox(&mut file).unwrap();
    path
}

#[test]
fn vox_scenes_render_identically_with_both_backends() {
    let vox = write_vox("two.vox");
    let mut files = vec![(vox.clone(), "two")];
    let shared = Path::new("../../../shared/scenes/vox/study.vox");
    if shared.exists() {
        files.push((shared.to_path_buf(), "study"));
    } else {
        println!(
            "skipped study.vox: {} is absent (third-party models)",
            shared.display()
        );
    }
    for (path, name) in files {
        let path = path.to_str().unwrap();
        let a = render("dense", &["--vox", path], &format!("{name}-dense.png"));
        let b = render("octree", &["--vox", path], &format!("{name}-octree.png"));
        let (_, _, pixels) = decode(&a);
        assert!(
            std::fs::read(&a).unwrap() == std::fs::read(&b).unwrap(),
            "{name}"
        );
        // The automatic framing puts the model in view: not all sky.
        let first = &pixels[..4];
        assert!(
            pixels.chunks(4).any(|p| p != first),
            "{name}: nothing in view"
        );
    }
}

#[test]
fn bad_vox_files_exit_2_with_one_line() {
    let out = scratch("bad-vox.png");
    let good = std::fs::read(write_vox("good.vox")).unwrap();
    let cases: [(&str, Vec<u8>); 3] = [
        ("garbage.vox", b"this is not a vox file".to_vec()),
        ("truncated.vox", good[..good.len() / 2].to_vec()),
        ("magic.vox", [b"XOV ".as_slice(), &good[4..]].concat()),
    ];
    for (name, bytes) in cases {
        let path = scratch(name);
        std::fs::write(&path, bytes).unwrap();
        let result = voxtrace([
            "--vox",
            path.to_str().unwrap(),
            "--width",
            "16",
            "--height",
            "9",
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&result.stderr);
        assert_eq!(result.status.code(), Some(2), "{name}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{name}: {stderr}");
        assert!(stderr.contains("cannot load --vox"), "{name}: {stderr}");
    }
}

/// A 4x1x1 model whose voxels use palette entries 1 (metal), 2 (glass),
/// 3 (emissive) and 4 (diffuse), with the MATL values `glass` for entry 2.
fn material_vox(name: &str, glass: &[(&str, &str)]) -> PathBuf {
    use dot_vox::{Color, DotVoxData, Material, Model, Size, Voxel};
    let props = |pairs: &[(&str, &str)]| {
        pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect()
    };
    let data = DotVoxData {
        version: 150,
        index_map: Vec::new(),
        models: vec![Model {
            size: Size { x: 4, y: 1, z: 1 },
            voxels: (0..4u8)
                .map(|x| Voxel {
                    x,
                    y: 0,
                    z: 0,
                    i: x,
                })
                .collect(),
        }],
        palette: vec![
            Color {
                r: 200,
                g: 180,
                b: 160,
                a: 255
            };
            256
        ],
        materials: vec![
            Material {
                id: 1,
                properties: props(&[("_type", "_metal"), ("_metal", "1"), ("_rough", "0.2")]),
            },
            Material {
                id: 2,
                properties: props(glass),
            },
            Material {
                id: 3,
                properties: props(&[("_type", "_emit"), ("_emit", "1")]),
            },
        ],
        scenes: Vec::new(),
        layers: Vec::new(),
    };
    let path = scratch(name);
    data.write_vox(&mut std::fs::File::create(&path).unwrap())
        .unwrap();
    path
}

#[test]
fn material_scenes_print_their_plan_and_count_every_new_ray() {
    let vox = material_vox(
        "materials.vox",
        &[("_type", "_glass"), ("_trans", "1"), ("_ior", "0.5")],
    );
    let out = scratch("materials.png");
    let result = voxtrace([
        "--vox",
        vox.to_str().unwrap(),
        "--width",
        "48",
        "--height",
        "32",
        "--spp",
        "4",
        "--stats",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    assert!(
        stderr.contains("effects: sun, sky(gradient), diffuse(2 bounces), metal(5 bounces), glass(5 bounces), emission(1 lights), spp(4)\n"),
        "{stderr}"
    );
    let count = |key: &str| -> u64 {
        let line = stderr
            .lines()
            .find(|l| l.starts_with(&format!("{key}: ")))
            .unwrap();
        line.split_once(": ").unwrap().1.parse().unwrap()
    };
    assert!(
        count("reflection_rays") > 0 && count("refraction_rays") > 0 && count("light_rays") > 0
    );
    assert!(!stderr.contains("warning"), "{stderr}");
    // --bounces 0 leaves direct light only: no bounce rays at all.
    let result = voxtrace([
        "--vox",
        vox.to_str().unwrap(),
        "--width",
        "48",
        "--height",
        "32",
        "--bounces",
        "0",
        "--stats",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    assert!(
        stderr.contains("reflection_rays: 0\n") && stderr.contains("refraction_rays: 0\n"),
        "{stderr}"
    );
    assert!(stderr.contains("diffuse(0 bounces)"), "{stderr}");
}

#[test]
fn bad_matl_values_warn_in_one_line_naming_file_material_and_key() {
    let vox = material_vox(
        "bad-matl.vox",
        &[("_type", "_glass"), ("_trans", "1"), ("_ior", "-0.5")],
    );
    let out = scratch("bad-matl.png");
    let result = voxtrace([
        "--vox",
        vox.to_str().unwrap(),
        "--width",
        "16",
        "--height",
        "9",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    let warning: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning: "))
        .collect();
    assert_eq!(warning.len(), 1, "{stderr}");
    for needle in ["bad-matl.vox", "material 2", "_ior", "-0.5"] {
        assert!(warning[0].contains(needle), "{needle} in {stderr}");
    }
}

/// Errors on one line, shown exactly (the library's `errors`).
mod one_line_errors {
    use clap::CommandFactory;
    use std::ffi::OsString;
    use voxtrace_cli::errors::{escape_controls, one_line, parse, show_path};

    /// A number and a path, as the binary's flags take them.
    #[derive(Debug, clap::Parser)]
    struct Flags {
        #[arg(long)]
        n: Option<i32>,
        #[arg(long)]
        path: Option<std::path::PathBuf>,
    }

    /// The one line `args` end with, or the parsed flags.
    fn line(args: &[OsString]) -> Result<Flags, String> {
        let mut argv = vec![OsString::from("t")];
        argv.extend_from_slice(args);
        parse::<Flags>(&Flags::command(), &argv)
            .map(|(flags, _)| flags)
            .map_err(|e| one_line(e, &argv))
    }

    #[test]
    fn a_refused_value_is_shown_exactly_on_one_line() {
        for args in [["--n=1\x1b\n2"].as_slice(), &["--n", "1\x1b\n2"]] {
            let args: Vec<OsString> = args.iter().map(OsString::from).collect();
            let line = line(&args).unwrap_err();
            assert!(line.starts_with("error: "), "{line}");
            assert!(!line.contains(char::is_control), "{line:?}");
            assert!(line.contains("'1\\u{1b}\\n2'"), "{line}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn bytes_that_are_not_utf8_pass_in_a_path_and_are_named_elsewhere() {
        use std::os::unix::ffi::{OsStrExt, OsStringExt};
        let bytes = |b: &[u8]| OsString::from_vec(b.to_vec());
        let flags = line(&[bytes(b"--path=a\xff")]).unwrap();
        assert_eq!(flags.path.unwrap().as_os_str().as_bytes(), b"a\xff");
        for args in [
            vec![bytes(b"--n=1\xff")],
            vec!["--n".into(), bytes(b"1\xff")],
        ] {
            let line = line(&args).unwrap_err();
            assert!(line.contains("invalid value '1\\xff' for '--n'"), "{line}");
        }
    }

    #[test]
    fn control_characters_are_escaped_and_the_rest_kept() {
        assert_eq!(
            escape_controls("a\nb\tc\r\u{1b}[31m\u{7f}\u{85}é ü/x.png"),
            "a\\nb\\tc\\r\\u{1b}[31m\\u{7f}\\u{85}é ü/x.png"
        );
        assert_eq!(escape_controls("plain"), "plain");
    }

    #[cfg(unix)]
    #[test]
    fn paths_show_bytes_that_are_not_utf8_as_hex() {
        use std::os::unix::ffi::OsStrExt;
        let path = std::path::Path::new(std::ffi::OsStr::from_bytes(b"a\xff\xef\xbf\xbd\n.png"));
        assert_eq!(show_path(path), "a\\xff\u{fffd}\\n.png");
    }
}

/// The library's figures: byte counts, image error, the rounds' state.
mod library_figures {
    use voxtrace::glam::U8Vec3;
    use voxtrace::pack;
    use voxtrace_cli::human_bytes;
    use voxtrace_cli::image_error::{psnr, rmse};

    #[test]
    fn byte_counts_read_short_and_keep_the_exact_figure() {
        assert_eq!(human_bytes(549_755_813_888), "512 GiB (549755813888 bytes)");
        assert_eq!(human_bytes(1536), "1.5 KiB (1536 bytes)");
        assert_eq!(human_bytes(1000), "1000 bytes");
        assert_eq!(human_bytes(8_000_000), "7.6 MiB (8000000 bytes)");
        assert!(human_bytes(u128::MAX).ends_with(&format!("({} bytes)", u128::MAX)));
    }

    #[test]
    fn a_frame_equal_to_its_reference_has_no_error() {
        let frame: Vec<u32> = (0..64u8)
            .map(|i| pack(U8Vec3::new(i, 255 - i, i / 2)))
            .collect();
        assert_eq!(rmse(&frame, &frame), 0.0);
        assert_eq!(psnr(0.0), f64::INFINITY);
    }

    #[test]
    fn the_error_is_the_root_mean_square_of_the_channel_differences() {
        // Every channel of every pixel off by `d`: the error is `d`, whatever
        // the colors; alpha is not a color channel.
        for d in [1u8, 3, 10, 100] {
            let reference: Vec<u32> = (0..50u8)
                .map(|i| pack(U8Vec3::new(i, i + 1, i + 2)))
                .collect();
            let frame: Vec<u32> = (0..50u8)
                .map(|i| pack(U8Vec3::new(i + d, i + 1 + d, i + 2 + d)) & 0x00ff_ffff)
                .collect();
            assert!((rmse(&frame, &reference) - f64::from(d)).abs() < 1e-9);
        }
        // One channel of one pixel in four off by 12: sqrt(144 / 12) per
        // channel mean.
        let reference = vec![pack(U8Vec3::splat(100)); 4];
        let mut frame = reference.clone();
        frame[2] = pack(U8Vec3::new(112, 100, 100));
        let e = rmse(&frame, &reference);
        assert!((e - 12f64.sqrt()).abs() < 1e-12, "{e}");
        assert!((psnr(e) - 20.0 * (255.0 / e).log10()).abs() < 1e-12);
    }

    #[test]
    fn a_pixel_keeps_64_bytes_between_rounds() {
        // docs/cli.md says so; the memory check counts them.
        assert_eq!(voxtrace_cli::ROUND_STATE_BYTES, 64);
    }
}

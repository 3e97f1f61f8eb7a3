//! `--denoise` with the `denoise` feature (Open Image Denoise linked): on
//! the path-traced room the tests build (glass, a mirror, a lamp),
//! denoising a few-sample render brings it closer to a many-sample
//! reference; the binary denoises whole frames and crops, reports its
//! time in `--stats`, and refuses `--tiles` in one line.
//!
//! Needs OIDN at run time: its `lib/` on the library path (docs/denoise.md).

#![cfg(feature = "denoise")]

mod common;

use common::run::{assert_refused, fresh_dir, stderr, voxtrace};
use voxtrace::{unpack, IAabb, Rect, SceneMaterials};
use voxtrace_cli::denoise::denoise;
use voxtrace_cli::guides::render_guides;
use voxtrace_cli::image_error::rmse;
use voxtrace_cli::room;
use voxtrace_cli::{Backend, BuiltScene};

#[test]
fn denoising_brings_a_noisy_path_traced_room_closer_to_its_reference() {
    let (width, height) = (64, 48);
    let source = room::source();
    let bounds = IAabb::centered(room::BOUNDS);
    let (scene, _) = BuiltScene::build_from(Backend::Octree, &source, bounds, true).unwrap();
    let (table, emitters) = (room::materials(), room::lamps());
    let materials = SceneMaterials {
        table: &table,
        emitters: &emitters,
    };
    let camera = room::camera(width, height);
    let full = Rect::full(&camera);
    let render = |samples: u16| {
        let options = room::path_options(samples);
        scene
            .render_with(Some(materials), &camera, full, &options, true, &|_| {})
            .unwrap()
            .pixels
    };
    let reference = render(256);
    for samples in [2, 8] {
        let options = room::path_options(samples);
        // As the binary renders for --denoise: in rounds, keeping the
        // mean radiance the filter reads as high dynamic range color.
        let (rendered, _) = scene
            .render_in_rounds(
                Some(materials),
                &camera,
                full,
                &options,
                true,
                &|_| {},
                &mut |_| true,
                true,
            )
            .unwrap();
        let noisy = rendered.pixels;
        assert!(noisy == render(samples), "rounds wrote other bytes");
        let radiance = rendered.radiance.expect("a path-traced frame's radiance");
        assert_eq!(radiance.len(), 3 * noisy.len());
        assert!(radiance.iter().any(|&c| c > 1.0), "the lamp is above white");
        let guides = render_guides(scene.scene(), &camera, &options, full, true);
        let before = rmse(&noisy, &reference);
        for hdr in [None, Some(radiance.clone())] {
            let mut denoised = noisy.clone();
            let input = if hdr.is_some() { "radiance" } else { "bytes" };
            denoise(&mut denoised, hdr, width, height, &guides).unwrap();
            let after = rmse(&denoised, &reference);
            println!("{samples} spp: rmse {before:.2} noisy, {after:.2} denoised from {input}");
            assert!(
                after < 0.7 * before,
                "{samples} spp, {input}: {after} vs {before}"
            );
            // Alpha is kept: every pixel stays opaque.
            assert!(denoised.iter().all(|&p| unpack(p)[3] == 255));
        }
    }
}

#[test]
fn the_binary_denoises_whole_frames_and_crops_and_refuses_tiles() {
    let dir = fresh_dir("denoise", "runs");
    let base = [
        "--seed",
        "1",
        "--size",
        "20",
        "--bounces",
        "2",
        "--spp",
        "2",
    ];
    let run = |name: &str, extra: &[&str]| {
        let out = dir.join(name);
        let out = out.to_str().unwrap().to_string();
        let mut args: Vec<&str> = base.to_vec();
        args.extend(["--width", "48", "--height", "32", "--out", &out]);
        args.extend(extra);
        let result = voxtrace(&args);
        assert!(result.status.success(), "{name}: {}", stderr(&result));
        (
            voxtrace::read_png(std::path::Path::new(&out)).unwrap(),
            stderr(&result),
        )
    };
    let (plain, _) = run("plain.png", &[]);
    let (denoised, stats) = run("denoised.png", &["--denoise", "--stats"]);
    assert_eq!((denoised.0, denoised.1), (plain.0, plain.1));
    assert_ne!(denoised.2, plain.2, "--denoise changed nothing");
    assert!(
        stats.lines().any(|l| l.starts_with("denoise_ms: ")),
        "{stats}"
    );
    let (crop, _) = run("crop.png", &["--denoise", "--region", "8,4,24,20"]);
    assert_eq!((crop.0, crop.1), (24, 20));
    let out = dir.join("tile.png");
    let tiled = voxtrace([
        "--seed",
        "1",
        "--size",
        "20",
        "--width",
        "48",
        "--height",
        "32",
        "--denoise",
        "--tiles",
        "2x2",
        "--tile-index",
        "0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_refused(
        &tiled,
        &["--denoise needs the whole frame", "--tiles", "seams"],
    );
    assert!(!out.exists(), "a refused run wrote {}", out.display());
}

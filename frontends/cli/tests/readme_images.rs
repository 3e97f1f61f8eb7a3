//! Docs that cannot go stale: every image the README shows under a caption
//! holding the `voxtrace` command that made it is made again by that
//! command, at its size, and must match the committed file byte for byte.
//!
//! Renders at 960x540 with effects are slow unoptimized, so this runs from
//! `.ci/run` in release (`cargo test --release -p voxtrace-cli --test
//! readme_images -- --ignored`). The report plots (`docs/report/`) are
//! measurements of time, not renders, and are not compared.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository root: the README's paths are relative to it.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `(image path, command arguments)` for each README image whose caption
/// (the next non-empty line) quotes a `voxtrace` or `cargo run` command.
fn captioned_images(readme: &str) -> Vec<(String, Vec<String>)> {
    let lines: Vec<&str> = readme.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(image) = line
            .trim()
            .strip_prefix("![")
            .and_then(|rest| rest.split_once("](")?.1.strip_suffix(')'))
        else {
            continue;
        };
        let Some(caption) = lines[i + 1..].iter().find(|l| !l.trim().is_empty()) else {
            continue;
        };
        let Some(command) = caption.split('`').nth(1) else {
            continue;
        };
        let args = if let Some(rest) = command.strip_prefix("cargo run --release --") {
            rest
        } else if let Some(rest) = command.strip_prefix("voxtrace") {
            rest
        } else {
            continue;
        };
        out.push((
            image.to_string(),
            args.split_whitespace().map(String::from).collect(),
        ));
    }
    out
}

#[test]
fn captions_are_found_and_name_their_own_image() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let images = captioned_images(&readme);
    assert!(
        images.iter().any(|(image, _)| image == "docs/render.png"),
        "{images:?}"
    );
    for (image, args) in &images {
        let out = args.iter().position(|a| a == "--out").map(|i| &args[i + 1]);
        assert_eq!(
            out,
            Some(image),
            "the caption of {image} writes another file"
        );
    }
}

#[test]
#[ignore = "renders at full size: .ci/run runs it optimized"]
fn every_readme_image_is_what_its_caption_command_writes() {
    let root = root();
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("readme-images");
    std::fs::create_dir_all(&dir).unwrap();
    let mut stale = Vec::new();
    for (image, mut args) in captioned_images(&readme) {
        // Inputs outside the repository (third-party models) may be absent.
        if let Some(i) = args.iter().position(|a| a == "--vox") {
            if !root.join(&args[i + 1]).exists() {
                println!("skipped {image}: {} is absent", args[i + 1]);
                continue;
            }
        }
        let fresh = dir.join(Path::new(&image).file_name().unwrap());
        let i = args.iter().position(|a| a == "--out").unwrap();
        args[i + 1] = fresh.display().to_string();
        let result = Command::new(env!("CARGO_BIN_EXE_voxtrace"))
            .args(&args)
            .current_dir(&root)
            .output()
            .unwrap();
        assert!(
            result.status.success(),
            "{image}: {}",
            String::from_utf8_lossy(&result.stderr)
        );
        let committed = std::fs::read(root.join(&image)).unwrap();
        if std::fs::read(&fresh).unwrap() != committed {
            stale.push(format!("{image} (fresh render in {})", fresh.display()));
        } else {
            println!("{image}: identical");
        }
    }
    assert!(stale.is_empty(), "stale README images: {stale:?}");
}

//! Docs that cannot go stale: every image the README (or a page of `docs/`)
//! shows under a caption holding the `voxtrace` command that made it is
//! made again by that command, at its size, and must match the committed
//! file byte for byte.
//!
//! Renders at 960x540 with effects are slow unoptimized, so this runs from
//! `.ci/run` in release (`cargo test --release -p voxtrace-cli --test
//! readme_images -- --ignored`). The report plots (`docs/report/`) are
//! measurements of time, not renders, and are not compared.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository root: the commands' paths are relative to it.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The pages that show images: `README.md` and `docs/*.md`, as paths from
/// the root with their text.
fn pages() -> Vec<(String, String)> {
    let root = root();
    let mut names = vec!["README.md".to_string()];
    let mut docs: Vec<String> = std::fs::read_dir(root.join("docs"))
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.ends_with(".md"))
        .map(|name| format!("docs/{name}"))
        .collect();
    docs.sort();
    names.extend(docs);
    names
        .into_iter()
        .map(|name| {
            let text = std::fs::read_to_string(root.join(&name)).unwrap();
            (name, text)
        })
        .collect()
}

/// `(image path from the root, command arguments)` for each captioned
/// image of every page.
fn all_captioned_images() -> Vec<(String, Vec<String>)> {
    let mut all = Vec::new();
    for (page, text) in pages() {
        let folder = Path::new(&page).parent().unwrap();
        for (image, args) in captioned_images(&text) {
            let image = folder.join(image).to_string_lossy().into_owned();
            all.push((image, args));
        }
    }
    all
}

/// `(image path, command arguments)` for each image of a page whose
/// caption (the next non-empty line) quotes a `voxtrace` or `cargo run`
/// command; the image path is the link's, relative to the page.
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
    let images = all_captioned_images();
    for shown in ["docs/render.png", "docs/vox-terrain.png"] {
        assert!(images.iter().any(|(image, _)| image == shown), "{images:?}");
    }
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
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("readme-images");
    std::fs::create_dir_all(&dir).unwrap();
    let mut stale = Vec::new();
    let images = all_captioned_images();
    for (image, mut args) in images {
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
    assert!(stale.is_empty(), "stale images: {stale:?}");
}

/// GitHub's anchor for a heading: lower case, spaces as hyphens, other
/// punctuation dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

#[test]
fn every_relative_link_of_the_pages_resolves() {
    let root = root();
    let mut broken = Vec::new();
    for (page, text) in pages() {
        let folder = root.join(Path::new(&page).parent().unwrap());
        for (_, rest) in text.match_indices("](").map(|(i, _)| text.split_at(i + 2)) {
            let Some(link) = rest.split(')').next() else {
                continue;
            };
            if link.contains("://") || link.starts_with("mailto:") {
                continue;
            }
            let (file, fragment) = link.split_once('#').unwrap_or((link, ""));
            let target = if file.is_empty() {
                root.join(&page)
            } else {
                folder.join(file)
            };
            if !target.exists() {
                broken.push(format!("{page}: {link}"));
                continue;
            }
            if !fragment.is_empty() {
                let headings = std::fs::read_to_string(&target).unwrap_or_default();
                let found = headings
                    .lines()
                    .filter_map(|line| line.strip_prefix('#'))
                    .any(|heading| anchor(heading.trim_start_matches('#')) == fragment);
                if !found {
                    broken.push(format!("{page}: {link} (no such heading)"));
                }
            }
        }
    }
    assert!(broken.is_empty(), "broken links: {broken:?}");
}

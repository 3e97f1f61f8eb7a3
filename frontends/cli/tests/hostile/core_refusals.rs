//! The core's refusals and warnings name their real cause (issue 51, item
//! 11): a camera is refused for the setting at fault (an orthographic
//! height too small or too large, a position and target too far apart),
//! not as "position too far from the origin" or "position and target
//! coincide"; and a MATL value that is not UTF-8 is one warning naming the
//! material and key, the rest of the material still applying.

use std::path::Path;

use super::common::run::{assert_refused, fresh_dir, stat, stderr, voxtrace};
use super::common::vox_bytes::{chunk, file, model, palette};

/// A 32x24 frame of the terrain of seed 1, size 20 (the camera at
/// 10,10,10 looking at the origin unless `flags` say otherwise), to `out`.
fn terrain<'a>(out: &'a str, flags: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "--size", "20", "--seed", "1", "--width", "32", "--height", "24", "--out", out,
    ];
    args.extend_from_slice(flags);
    args
}

#[test]
fn camera_refusals_name_the_setting_at_fault() {
    let dir = fresh_dir("hostile", "core_refusals_camera");
    let out = dir.join("frame.png");
    let out = out.to_str().unwrap();
    // Flags, words the one error line holds, words it must not hold.
    let cases: [(&[&str], &[&str], &[&str]); 8] = [
        // The issue's two: the height, not the position...
        (
            &["--projection", "orthographic", "--ortho-height", "1e-30"],
            &["orthographic height too small"],
            &["too far from the origin"],
        ),
        // ... and a direction that overflows, not one point.
        (
            &[
                "--position",
                "3.4e38,3.4e38,3.4e38",
                "--lookat",
                "-3.4e38,-3.4e38,-3.4e38",
            ],
            &["position and target too far apart", "overflows"],
            &["coincide"],
        ),
        // A height whose image overflows f32.
        (
            &["--projection", "orthographic", "--ortho-height", "3e38"],
            &["orthographic height too large"],
            &["too far from the origin"],
        ),
        // A height fine at the origin, too small a thousand voxels out.
        (
            &[
                "--projection",
                "orthographic",
                "--ortho-height",
                "1e-3",
                "--position",
                "1000,1000,1000",
                "--lookat",
                "0,0,0",
            ],
            &["orthographic height too small for the camera's distance from the origin"],
            &["position too far"],
        ),
        // Refusals that already named their cause still do.
        (
            &["--position", "1e30,1e30,1e30"],
            &["position too far from the origin"],
            &["field of view", "height"],
        ),
        (
            &[
                "--projection",
                "orthographic",
                "--ortho-height",
                "10",
                "--position",
                "1e30,1e30,1e30",
            ],
            &["position too far from the origin"],
            &["height"],
        ),
        (
            &[
                "--projection",
                "orthographic",
                "--position",
                "3.4e38,0,0",
                "--lookat",
                "3.4e38,0,1",
            ],
            &["position too far from the origin", "overflows"],
            &["height"],
        ),
        (
            &["--position", "5,5,5", "--lookat", "5,5,5"],
            &["position and target coincide"],
            &["too far"],
        ),
    ];
    for (flags, present, absent) in cases {
        let run = voxtrace(terrain(out, flags));
        assert_refused(&run, present);
        let text = stderr(&run);
        for word in absent {
            assert!(!text.contains(word), "{flags:?}: {word:?} in {text}");
        }
        assert!(!Path::new(out).exists(), "{flags:?} wrote a frame");
    }
}

/// A MATL chunk `id` whose pairs are raw bytes, as no UTF-8 writer makes.
fn matl(id: u32, pairs: &[(&[u8], &[u8])]) -> Vec<u8> {
    let mut content = id.to_le_bytes().to_vec();
    content.extend((pairs.len() as u32).to_le_bytes());
    for (key, value) in pairs {
        for s in [key, value] {
            content.extend((s.len() as u32).to_le_bytes());
            content.extend(*s);
        }
    }
    chunk(b"MATL", &content, &[])
}

/// A 2x1x1 model of palette entries 1 and 2, material 1 metal with
/// `metal` as its `_metal` value and a roughness of 0.25.
fn metal_scene(metal: &[u8]) -> Vec<u8> {
    let mut chunks = model([2, 1, 1], &[[0, 0, 0, 1], [1, 0, 0, 2]]);
    chunks.push(matl(
        1,
        &[
            (b"_type", b"_metal"),
            (b"_metal", metal),
            (b"_rough", b"0.25"),
        ],
    ));
    chunks.push(palette());
    file(&chunks)
}

#[test]
fn a_matl_value_not_utf8_warns_and_the_rest_of_the_material_applies() {
    let dir = fresh_dir("hostile", "core_refusals_matl");
    // The bad value, and the value the warning says is used instead.
    let frame = |name: &str, metal: &[u8]| {
        let vox = dir.join(format!("{name}.vox"));
        std::fs::write(&vox, metal_scene(metal)).unwrap();
        let png = dir.join(format!("{name}.png"));
        let run = voxtrace([
            "--vox",
            vox.to_str().unwrap(),
            "--width",
            "16",
            "--height",
            "9",
            "--spp",
            "4",
            "--stats",
            "--out",
            png.to_str().unwrap(),
        ]);
        assert!(run.status.success(), "{name}: {}", stderr(&run));
        // `--stats` and the warnings share stderr.
        (std::fs::read(png).unwrap(), stderr(&run))
    };
    let warnings = |text: &str| -> Vec<String> {
        text.lines()
            .filter(|line| line.starts_with("warning:"))
            .map(String::from)
            .collect()
    };
    let (bad, stats) = frame("metal-not-utf8", b"0.\xff\xfe");
    let lines = warnings(&stats);
    assert_eq!(lines.len(), 1, "{stats}");
    for word in [
        "warning: ",
        "metal-not-utf8.vox",
        "material 1",
        "_metal",
        r"'0.\xff\xfe'",
        "not UTF-8",
        "using 1",
    ] {
        assert!(lines[0].contains(word), "{word:?} not in {stats}");
    }
    // The material is kept: metal (its _type), as rough as its _rough
    // says, with the fallback metalness: the frame of `_metal 1` exactly.
    assert!(stat(&stats, "effects").contains("metal"), "{stats}");
    let (fallback, quiet) = frame("metal-1", b"1");
    assert!(warnings(&quiet).is_empty(), "{quiet}");
    assert!(bad == fallback, "the frames differ");
}

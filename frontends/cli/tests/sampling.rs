//! The sampling flags: `--spp`, `--noise-threshold` and `--quality`. A
//! path-traced scene (here `--bounces`, on the repository's own
//! docs/terrain.vox) samples adaptively unless `--spp` is given, the same
//! bytes on one thread and two; on a face-shaded scene `--quality
//! standard` (a model's default) is `--shadows --ao 8 --spp 4` and
//! `--quality final` is `--shadows --ao 16 --spp 16`, explicit flags
//! winning, and `--quality draft` (the terrain's default) one sample; the
//! conflicts and bad values are one-line refusals.

mod common;

use common::run::{assert_refused, render_terrain_model, scratch_in, stat, stderr, voxtrace};

/// The bytes and `--stats` lines of a 64x36 render of the terrain model
/// with `flags`.
fn render(name: &str, flags: &[&str]) -> (Vec<u8>, String) {
    render_terrain_model("sampling", name, flags)
}

#[test]
fn spp_and_noise_threshold_conflict_in_one_line() {
    let out = voxtrace(["--spp", "4", "--noise-threshold", "0.1", "--out", "x.png"]);
    assert_refused(&out, &["--spp", "--noise-threshold"]);
    for bad in ["0", "-0.1", "1.5", "nan", "inf", "much"] {
        let out = voxtrace(["--noise-threshold", bad, "--out", "x.png"]);
        assert_refused(&out, &["--noise-threshold", "is not a noise threshold"]);
    }
    let out = voxtrace(["--quality", "best", "--out", "x.png"]);
    assert_refused(&out, &["--quality", "draft", "standard", "final"]);
}

#[test]
fn the_terrain_keeps_the_draft_look_by_default() {
    // The bytes and `--stats` lines of a small terrain frame with `extra`.
    let terrain = |name: &str, extra: &[&str]| {
        let out = scratch_in("sampling", &format!("{name}.png"));
        let mut args = vec![
            "--seed", "3", "--size", "16", "--width", "48", "--height", "27",
        ];
        args.extend_from_slice(&["--stats", "--out", out.to_str().unwrap()]);
        args.extend_from_slice(extra);
        let run = voxtrace(&args);
        assert!(run.status.success(), "{extra:?}: {}", stderr(&run));
        (std::fs::read(&out).unwrap(), stderr(&run))
    };
    let (default, stats) = terrain("terrain-default", &[]);
    assert_eq!(stat(&stats, "effects"), "sun");
    let (draft, _) = terrain("terrain-draft", &["--quality", "draft"]);
    assert!(default == draft, "the terrain's default is not draft");
    let (standard, stats) = terrain("terrain-standard", &["--quality", "standard"]);
    assert_eq!(stat(&stats, "effects"), "sun, shadows, ao(8 rays), spp(4)");
    assert!(standard != default);
}

#[test]
fn path_traced_scenes_sample_adaptively_unless_spp_is_given() {
    let (adaptive, stats) = render("adaptive-2", &["--bounces", "1", "--threads", "2"]);
    assert!(
        stat(&stats, "effects").contains("adaptive(16-64 spp, threshold 0.005)"),
        "{stats}"
    );
    let spp: f64 = stat(&stats, "samples_per_pixel").parse().unwrap();
    assert!((16.0..=64.0).contains(&spp), "{spp}");
    let (one_thread, _) = render("adaptive-1", &["--bounces", "1", "--threads", "1"]);
    assert!(adaptive == one_thread, "one thread and two differ");

    let (_, stats) = render("uniform", &["--bounces", "1", "--spp", "3"]);
    assert_eq!(stat(&stats, "samples_per_pixel"), "3.00");
    assert!(stat(&stats, "effects").contains("spp(3)"), "{stats}");

    let (_, stats) = render(
        "threshold",
        &[
            "--bounces",
            "1",
            "--noise-threshold",
            "0.5",
            "--quality",
            "final",
        ],
    );
    assert!(
        stat(&stats, "effects").contains("adaptive(32-256 spp, threshold 0.5)"),
        "{stats}"
    );
    // Every pixel is done at its first round at so high a threshold.
    assert_eq!(stat(&stats, "samples_per_pixel"), "32.00");
}

#[test]
fn quality_final_on_a_face_shaded_model_is_shadows_ao_16_spp_16() {
    let (final_look, stats) = render("final", &["--quality", "final"]);
    assert_eq!(stat(&stats, "samples_per_pixel"), "16.00");
    assert_eq!(
        stat(&stats, "effects"),
        "sun, shadows, ao(16 rays), spp(16)"
    );
    let (spelled, _) = render("spelled", &["--shadows", "--ao", "16", "--spp", "16"]);
    assert!(final_look == spelled, "--quality final is not the flags");
    // Explicit flags win.
    let (a, _) = render(
        "final-spp",
        &["--quality", "final", "--spp", "2", "--ao", "3"],
    );
    let (b, _) = render("spelled-spp", &["--shadows", "--ao", "3", "--spp", "2"]);
    assert!(a == b, "explicit --spp and --ao do not win");
    // Standard is a model's default look: shadows, 8 occlusion rays, 4
    // samples.
    let (default, stats) = render("default", &[]);
    assert_eq!(stat(&stats, "effects"), "sun, shadows, ao(8 rays), spp(4)");
    let (standard, _) = render("standard", &["--quality", "standard"]);
    let (spelled, _) = render(
        "spelled-standard",
        &["--shadows", "--ao", "8", "--spp", "4"],
    );
    assert!(
        default == standard && standard == spelled,
        "standard is not the default look"
    );
    // Draft (alias preview) is one sample, and a face-shaded scene
    // ignores a noise threshold, saying so.
    let (preview, _) = render("preview", &["--quality", "preview"]);
    let (draft, stats) = render("draft", &["--quality", "draft", "--noise-threshold", "0.1"]);
    assert!(preview == draft, "preview is not draft");
    assert_eq!(stat(&stats, "samples_per_pixel"), "1.00");
    assert_eq!(stat(&stats, "effects"), "sun");
    assert!(
        stats.contains("not path-traced: --noise-threshold changes nothing"),
        "{stats}"
    );
    // --flat draws no effects: final adds none, and no note about flags
    // never given.
    let (_, stats) = render("flat", &["--quality", "final", "--flat"]);
    assert_eq!(stat(&stats, "effects"), "flat");
    assert!(!stats.contains("ignoring"), "{stats}");
}

#[test]
fn ao_distance_reaches_the_occlusion_of_quality_standard_and_final() {
    // --quality final turns occlusion on in a face-shaded scene: the
    // distance given is its reach, and no note says otherwise.
    let (final_4, stats) = render("final-ao4", &["--quality", "final", "--ao-distance", "4"]);
    assert!(!stats.contains("--ao-distance"), "{stats}");
    let (spelled, _) = render(
        "spelled-ao4",
        &[
            "--shadows",
            "--ao",
            "16",
            "--ao-distance",
            "4",
            "--spp",
            "16",
        ],
    );
    assert!(final_4 == spelled, "final does not reach --ao-distance 4");
    let (final_8, _) = render("final-ao8", &["--quality", "final"]);
    assert!(final_4 != final_8, "--ao-distance 4 changed nothing");
    // A model's default look (standard) reaches it too.
    let (standard_4, stats) = render("standard-ao4", &["--ao-distance", "4"]);
    assert!(!stats.contains("--ao-distance"), "{stats}");
    let flags = ["--shadows", "--ao", "8", "--ao-distance", "4", "--spp", "4"];
    let (spelled, _) = render("spelled-standard-ao4", &flags);
    assert!(
        standard_4 == spelled,
        "standard does not reach --ao-distance 4"
    );
    // Without occlusion the note stays: the draft look, and final on a
    // path-traced scene (its light rays, no occlusion rays).
    let note = "note: --ao-distance has no effect without --ao";
    let (plain, stats) = render("plain-ao4", &["--quality", "draft", "--ao-distance", "4"]);
    assert!(stats.contains(note), "{stats}");
    let (draft, _) = render("plain", &["--quality", "draft"]);
    assert!(plain == draft);
    let (_, stats) = render(
        "path-final-ao4",
        &["--bounces", "1", "--quality", "final", "--ao-distance", "4"],
    );
    assert!(stats.contains(note), "{stats}");
}

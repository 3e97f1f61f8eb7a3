//! `--time-limit`: a path-traced frame's samples in rounds until the
//! budget is spent. Nothing here is timed: a limit too large to reach
//! gives the bytes of no limit; a limit too small for more than the first
//! round still gives a whole image, of one round's samples, and says so;
//! whatever rounds a run took, the flag `--stats` prints gives its bytes
//! again without a clock. Bad values and `--tiles` are refused in one
//! line; looks the limit cannot change get a note.

mod common;

use common::run::{assert_refused, render_terrain_model, stat, voxtrace};

/// The bytes and `--stats` lines of a 64x36 render of the terrain model
/// with `flags`.
fn render(name: &str, flags: &[&str]) -> (Vec<u8>, String) {
    render_terrain_model("time_limit", name, flags)
}

/// The path-traced sampling checked: adaptive (rounds of 16 up to 64), and
/// 40 fixed samples (rounds of 16, 16 and 8).
const SAMPLING: [&[&str]; 2] = [&["--bounces", "1"], &["--bounces", "1", "--spp", "40"]];

/// A day: no render here comes near it.
const HUGE: &str = "86400";

/// A microsecond: no render here finishes a round in it.
const TINY: &str = "0.000001";

#[test]
fn a_limit_never_reached_gives_the_bytes_of_no_limit() {
    for (k, sampling) in SAMPLING.iter().enumerate() {
        let (free, free_stats) = render(&format!("free-{k}"), sampling);
        for threads in ["1", "2"] {
            let mut flags = sampling.to_vec();
            flags.extend(["--time-limit", HUGE, "--threads", threads]);
            let (limited, stats) = render(&format!("huge-{k}-{threads}"), &flags);
            assert!(limited == free, "{flags:?} changed the bytes");
            assert_eq!(stat(&stats, "rounds_complete"), "true", "{stats}");
            assert_eq!(
                stat(&stats, "samples_per_pixel"),
                stat(&free_stats, "samples_per_pixel")
            );
            let rounds: u32 = stat(&stats, "rounds").parse().unwrap();
            let most: u32 = stat(&stats, "rounds_most").parse().unwrap();
            assert!(rounds >= 1 && rounds <= most, "{stats}");
        }
    }
}

#[test]
fn a_tiny_limit_still_takes_one_whole_round_and_says_so() {
    for (k, (sampling, flag)) in SAMPLING.iter().zip(["--max-spp", "--spp"]).enumerate() {
        let mut flags = sampling.to_vec();
        flags.extend(["--time-limit", TINY]);
        let (bytes, stats) = render(&format!("tiny-{k}"), &flags);
        // A whole image: every pixel opaque, of the first round's samples.
        let (width, height, pixels) =
            voxtrace::decode_png(std::io::Cursor::new(&bytes)).expect("a valid PNG");
        assert_eq!((width, height, pixels.len()), (64, 36, 64 * 36));
        assert!(pixels.iter().all(|&p| voxtrace::unpack(p)[3] == 255));
        assert_eq!(stat(&stats, "rounds"), "1", "{stats}");
        assert_eq!(stat(&stats, "rounds_complete"), "false", "{stats}");
        assert_eq!(stat(&stats, "samples_cap"), "16", "{stats}");
        // Every pixel took the first round, and no more.
        assert_eq!(stat(&stats, "samples_per_pixel"), "16.00", "{stats}");
        assert_eq!(stat(&stats, "reproduce"), format!("{flag} 16"));
    }
}

#[test]
fn the_reported_samples_reproduce_the_bytes() {
    // Whatever rounds each limit's run took on this machine, the flag
    // --stats printed makes its frame again without a clock.
    for (k, sampling) in SAMPLING.iter().enumerate() {
        for (j, limit) in [TINY, "0.02", "0.2", HUGE].iter().enumerate() {
            let mut flags = sampling.to_vec();
            flags.extend(["--time-limit", limit]);
            let (limited, stats) = render(&format!("limit-{k}-{j}"), &flags);
            let reproduce = stat(&stats, "reproduce");
            let (flag, n) = reproduce.split_once(' ').unwrap();
            let mut again = sampling.to_vec();
            if flag == "--spp" {
                // --spp N replaces the fixed sample count.
                again.truncate(2);
            }
            again.extend([flag, n, "--threads", "2"]);
            let (reproduced, again_stats) = render(&format!("again-{k}-{j}"), &again);
            assert!(limited == reproduced, "{flags:?} then {again:?} differ");
            assert_eq!(
                stat(&stats, "samples_per_pixel"),
                stat(&again_stats, "samples_per_pixel")
            );
        }
    }
}

#[test]
fn bad_limits_and_tiles_are_refused_in_one_line() {
    for bad in ["0", "-1", "-0.5", "-0", "nan", "inf", "soon", ""] {
        let out = voxtrace(["--time-limit", bad, "--out", "x.png"]);
        assert_refused(&out, &["--time-limit", "is not a time limit"]);
    }
    let out = voxtrace([
        "--time-limit",
        "10",
        "--seed",
        "1",
        "--tiles",
        "2x2",
        "--tile-index",
        "0",
        "--out",
        "x.png",
    ]);
    assert_refused(&out, &["--time-limit", "--tiles", "--max-spp"]);
    let out = voxtrace(["--max-spp", "8", "--spp", "4", "--out", "x.png"]);
    assert_refused(&out, &["--max-spp", "--spp"]);
    for bad in ["0", "4097", "-3", "many"] {
        let out = voxtrace(["--max-spp", bad, "--out", "x.png"]);
        assert_refused(&out, &["--max-spp"]);
    }
}

#[test]
fn a_limit_that_changes_nothing_gets_a_note() {
    // The face-shaded terrain model: one pass.
    let (plain, _) = render("shaded", &[]);
    let (limited, stats) = render("shaded-limit", &["--time-limit", TINY]);
    assert!(plain == limited);
    assert!(
        stats.contains("note: the scene is not path-traced: --time-limit changes nothing"),
        "{stats}"
    );
    assert!(!stats.contains("rounds:"), "{stats}");
    // Few fixed samples are one round.
    let (_, stats) = render(
        "one-round",
        &["--bounces", "1", "--spp", "8", "--time-limit", "5"],
    );
    assert!(
        stats.contains("note: a pixel's 8 samples are one round: --time-limit changes nothing"),
        "{stats}"
    );
    // --max-spp on a face-shaded scene.
    let (_, stats) = render("max-spp-shaded", &["--max-spp", "32"]);
    assert!(
        stats.contains("note: the scene is not path-traced: --max-spp changes nothing"),
        "{stats}"
    );
}

#[test]
fn max_spp_caps_adaptive_sampling() {
    let (_, stats) = render("max-32", &["--bounces", "1", "--max-spp", "32"]);
    assert!(
        stat(&stats, "effects").contains("adaptive(16-32 spp, threshold 0.005)"),
        "{stats}"
    );
    // Below the first round: one round of that many.
    let (low, stats) = render("max-8", &["--bounces", "1", "--max-spp", "8"]);
    assert!(
        stat(&stats, "effects").contains("adaptive(8-8 spp"),
        "{stats}"
    );
    assert_eq!(stat(&stats, "samples_per_pixel"), "8.00");
    let (spp, _) = render("spp-8", &["--bounces", "1", "--spp", "8"]);
    assert!(low == spp, "8 adaptive samples of one round are --spp 8");
}

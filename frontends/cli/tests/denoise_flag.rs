//! `--denoise` in a build without the `denoise` feature: the parser takes
//! the flag, and the run refuses it in one line that says how to get a
//! build with it, before anything is rendered or written.

#![cfg(not(feature = "denoise"))]

mod common;

use common::run::{assert_refused, fresh_dir, voxtrace};

#[test]
fn without_the_feature_denoise_says_how_to_get_it_in_one_line() {
    let dir = fresh_dir("denoise_flag", "out");
    let out = dir.join("render.png");
    for extra in [&[][..], &["--tiles", "2x2", "--tile-index", "0"]] {
        let mut args = vec![
            "--seed", "1", "--size", "10", "--width", "16", "--height", "9",
        ];
        args.extend(["--denoise", "--out", out.to_str().unwrap()]);
        args.extend(extra);
        let refused = voxtrace(&args);
        assert_refused(
            &refused,
            &[
                "--denoise",
                "--features denoise",
                "OIDN_DIR",
                "docs/denoise.md",
            ],
        );
        assert!(!out.exists(), "a refused run wrote {}", out.display());
    }
}

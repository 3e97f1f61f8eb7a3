//! The shared `.vox` files that call for nothing new (only diffuse
//! materials used, no sun, sky or camera settings) render the same pixels
//! as commit b8c9a6d (before materials) with the same flags, an explicit
//! camera, and the sun and quality b8c9a6d rendered every model with
//! given as `--sun` and `--quality draft` (since issue 54 a model without
//! a sun of its own is lit from over the camera's shoulder, and a model's
//! default look has shadows and occlusion; explicit flags keep the
//! bytes). The hashes below are of the pixels b8c9a6d's binary wrote for
//! these commands (built from `git archive b8c9a6d`, compared pixel for
//! pixel with this branch's before they were recorded);
//! `VOXTRACE_BASE_BIN=/path/to/that/voxtrace` compares against a binary
//! directly instead. Skipped with a notice when
//! `../shared/scenes/vox` is absent.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::run::scratch_in;

/// Each file, its camera, and the FNV-1a hash of the RGBA pixels b8c9a6d
/// wrote for the default look and for `--shadows --ao 4 --spp 2`.
const FILES: [(&str, &str, &str, [u64; 2]); 4] = [
    (
        "chr_riotcop.vox",
        "8,2,11",
        "0.5,-4,-0.5",
        [0x69525ad17b152cc8, 0xa0d205e2dd5580dd],
    ),
    (
        "veh_car1.vox",
        "9,5,24",
        "0,-1,0",
        [0x4c101bce12e038da, 0x87c2c830e976ffed],
    ),
    (
        "scene_house6.vox",
        "62,40,113",
        "0,-10,0",
        [0xaed98118fe165698, 0xf387326c525b5581],
    ),
    (
        "scene_store8.vox",
        "42,30,115",
        "-2,-10,0",
        [0xb16196d4cddd118d, 0x9625310746b32f58],
    ),
];

/// The default look and shadows with occlusion. `--fog` is left out: on a
/// model it is scaled to the framed view since issue 38, where b8c9a6d used
/// the terrain's fog distance (`framing.rs` tests the new fog).
const LOOKS: [&[&str]; 2] = [&[], &["--shadows", "--ao", "4", "--spp", "2"]];

fn scratch(name: &str) -> PathBuf {
    scratch_in("diffuse_identity", name)
}

/// The RGBA pixels `binary` writes for `file` with `camera` and `look`.
fn pixels(binary: &Path, file: &Path, camera: (&str, &str), look: &[&str], out: &Path) -> Vec<u8> {
    // This build's flags for b8c9a6d's light and look (b8c9a6d itself
    // has no --quality, and lit every model by that sun).
    let then: &[&str] =
        if std::env::var_os("VOXTRACE_BASE_BIN").as_deref() == Some(binary.as_os_str()) {
            &[]
        } else {
            &["--sun", "0.45,1,-0.3", "--quality", "draft"]
        };
    let result = Command::new(binary)
        .args([
            "--vox",
            file.to_str().unwrap(),
            "--position",
            camera.0,
            "--lookat",
            camera.1,
        ])
        .args(["--width", "160", "--height", "90", "--threads", "2"])
        .args(then)
        .args(look)
        .args(["--out", out.to_str().unwrap()])
        .output()
        .expect("the binary runs");
    assert!(
        result.status.success(),
        "{}: {}",
        binary.display(),
        String::from_utf8_lossy(&result.stderr)
    );
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(out).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    buf
}

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

#[test]
fn diffuse_files_render_the_pixels_of_b8c9a6d() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes/vox");
    if !dir.exists() {
        eprintln!("skipping: {} is absent", dir.display());
        return;
    }
    let current = PathBuf::from(env!("CARGO_BIN_EXE_voxtrace"));
    let base = std::env::var_os("VOXTRACE_BASE_BIN").map(PathBuf::from);
    let mut wrong = Vec::new();
    for (name, position, lookat, hashes) in FILES {
        for (look, want) in LOOKS.iter().zip(hashes) {
            let file = dir.join(name);
            let now = pixels(
                &current,
                &file,
                (position, lookat),
                look,
                &scratch("now.png"),
            );
            let got = fnv1a(&now);
            match &base {
                Some(base) => {
                    let then = pixels(base, &file, (position, lookat), look, &scratch("base.png"));
                    if now != then {
                        wrong.push(format!("{name} {look:?}: differs from {}", base.display()));
                    }
                    println!("{name} {look:?}: {got:#018x}");
                }
                None if got != want => {
                    wrong.push(format!(
                        "{name} {look:?}: hash {got:#018x}, b8c9a6d's {want:#018x}"
                    ));
                }
                None => {}
            }
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

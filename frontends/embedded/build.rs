//! Puts `memory.x` where cortex-m-rt's `link.x` finds it, and links the
//! firmware with `link.x` (only the firmware binary; the library and the
//! host tests link normally).

use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    std::fs::copy("memory.x", out.join("memory.x")).expect("memory.x is readable");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    if std::env::var_os("CARGO_FEATURE_FIRMWARE").is_some() {
        println!("cargo:rustc-link-arg-bins=-Tlink.x");
    }
}

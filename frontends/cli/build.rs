//! With the `denoise` feature and `OIDN_DIR` set, the binaries (and the
//! tests, which run them) record where Open Image Denoise's libraries are
//! (an rpath to `$OIDN_DIR/lib`), so that an installed `voxtrace` finds
//! them in any shell, with no `LD_LIBRARY_PATH`. A system OIDN that
//! `pkg-config` finds is on the loader's own path already.

fn main() {
    println!("cargo:rerun-if-env-changed=OIDN_DIR");
    let denoise = std::env::var_os("CARGO_FEATURE_DENOISE").is_some();
    let elf = std::env::var("CARGO_CFG_TARGET_OS").is_ok_and(|os| os != "macos" && os != "windows");
    if let (true, true, Some(dir)) = (denoise, elf, std::env::var_os("OIDN_DIR")) {
        let lib = std::path::Path::new(&dir).join("lib");
        println!("cargo:rustc-link-arg=-Wl,-rpath,{}", lib.display());
    }
}

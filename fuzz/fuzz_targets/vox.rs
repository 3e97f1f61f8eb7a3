//! Arbitrary bytes into the `.vox` loader: it must return a scene or an
//! error, never panic, and never allocate beyond what its checks allow
//! (libFuzzer's `-rss_limit_mb` catches a huge allocation).
#![no_main]

use libfuzzer_sys::fuzz_target;
use voxtrace::{VoxModel, VoxelSource};

fuzz_target!(|data: &[u8]| {
    if let Ok(model) = VoxModel::from_bytes(data) {
        // A loaded scene is consistent: its voxels are inside its bounds.
        let bounds = model.bounds();
        assert!(!bounds.is_empty());
        assert_eq!(model.material(bounds.min - 1), 0);
    }
});

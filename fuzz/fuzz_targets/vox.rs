//! Arbitrary bytes into the `.vox` loader: it must return a scene or an
//! error, never panic, and never allocate beyond what its checks allow
//! (libFuzzer's `-rss_limit_mb` catches a huge allocation); its light list
//! holds only emissive voxels and its warnings are one line each.
#![no_main]

use libfuzzer_sys::fuzz_target;
use voxtrace::{VoxModel, VoxelSource};

fuzz_target!(|data: &[u8]| {
    if let Ok(model) = VoxModel::from_bytes(data) {
        // A loaded scene is consistent: its voxels are inside its bounds.
        let bounds = model.bounds();
        assert!(!bounds.is_empty());
        assert_eq!(model.material(bounds.min - 1), 0);
        // The light list is exactly emissive voxels, inside the bounds, in
        // sorted order (the same every load).
        let lights = model.emitters();
        for &p in lights {
            assert!(bounds.contains(p));
            let kind = model.materials().get(model.material(p)).kind();
            assert_eq!(kind, voxtrace::MaterialKind::Emissive);
        }
        assert!(lights
            .windows(2)
            .all(|w| (w[0].x, w[0].y, w[0].z) < (w[1].x, w[1].y, w[1].z)));
        assert!(model.warnings().iter().all(|w| !w.contains('\n')));
    }
});

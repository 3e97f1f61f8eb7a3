//! Arbitrary bytes into the `.vox` loader: it must return a scene or an
//! error, never panic, and never allocate beyond what its checks allow
//! (libFuzzer's `-rss_limit_mb` catches a huge allocation); its light list
//! holds only emissive voxels, its warnings are one line each, and its
//! cameras are one per id with usable values.
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
        // Cameras: one per id, sorted, every value usable (finite, a
        // radius of at least 0, a field of view in (0, 180)), and an
        // orientation of unit vectors.
        let cameras = model.cameras();
        assert!(cameras.windows(2).all(|w| w[0].id < w[1].id));
        for c in cameras {
            assert!(c.focus.is_finite() && c.angle.iter().all(|a| a.is_finite()));
            assert!(c.radius >= 0.0 && c.radius.is_finite() && c.frustum > 0.0);
            assert!(c.fov > 0.0 && c.fov < 180.0);
            let (forward, up) = c.orientation();
            assert!((forward.length() - 1.0).abs() < 1e-3 && (up.length() - 1.0).abs() < 1e-3);
        }
    }
});

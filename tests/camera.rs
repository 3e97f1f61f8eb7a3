//! Camera: rays through pixel centers, and degenerate settings rejected.

use voxtrace::glam::Vec3;
use voxtrace::{Camera, CameraSettings, Error};

fn settings() -> CameraSettings {
    CameraSettings {
        width: 64,
        height: 48,
        lookfrom: Vec3::new(3.0, 4.0, 5.0),
        lookat: Vec3::new(-1.0, 0.5, 2.0),
        ..CameraSettings::default()
    }
}

#[test]
fn center_ray_looks_at_the_target_and_corners_span_the_fov() {
    // An odd size has a center pixel.
    let cam = Camera::new(CameraSettings {
        width: 65,
        height: 49,
        ..settings()
    })
    .unwrap();
    let s = settings();
    let forward = (s.lookat - s.lookfrom).normalize();
    let center = cam.get_ray(32, 24);
    assert!(center.dir().dot(forward) > 1.0 - 1e-6);
    assert_eq!(center.origin(), s.lookfrom);
    // Top and bottom pixel centers span the vertical fov minus one pixel.
    let (top, bottom) = (cam.get_ray(32, 0), cam.get_ray(32, 48));
    let angle = top.dir().dot(bottom.dir()).acos().to_degrees();
    let expected = 2.0
        * ((60.0f32 / 2.0).to_radians().tan() * 48.0 / 49.0)
            .atan()
            .to_degrees();
    assert!((angle - expected).abs() < 1e-3, "{angle} vs {expected}");
    // Row 0 is the top of the image: its rays point further up.
    assert!(top.dir().y > bottom.dir().y);
    assert!(
        cam.get_ray(0, 24).dir().dot(forward.cross(Vec3::Y)) < 0.0,
        "column 0 is on the left"
    );
}

#[test]
fn degenerate_settings_are_errors_not_nan_rays() {
    let cases = [
        CameraSettings {
            width: 0,
            ..settings()
        },
        CameraSettings {
            height: 0,
            ..settings()
        },
        CameraSettings {
            vertical_fov: 0.0,
            ..settings()
        },
        CameraSettings {
            vertical_fov: 180.0,
            ..settings()
        },
        CameraSettings {
            vertical_fov: f32::NAN,
            ..settings()
        },
        CameraSettings {
            lookat: settings().lookfrom,
            ..settings()
        },
        CameraSettings {
            cam_up: Vec3::ZERO,
            ..settings()
        },
        // An up vector along the view, asked for explicitly (the default
        // falls back to a map's up instead: tests/views.rs).
        CameraSettings {
            cam_up: settings().lookat - settings().lookfrom,
            up_fallback: false,
            ..settings()
        },
        CameraSettings {
            lookfrom: Vec3::new(f32::INFINITY, 0.0, 0.0),
            ..settings()
        },
        CameraSettings {
            focus_dist: 0.0,
            ..settings()
        },
        CameraSettings {
            focus_dist: -1.0,
            ..settings()
        },
    ];
    for s in cases {
        assert!(
            matches!(Camera::new(s), Err(Error::InvalidCamera { .. })),
            "{s:?}"
        );
    }
}

#[test]
fn extreme_fovs_and_distances_give_finite_unit_rays() {
    for fov in [0.01, 1.0, 90.0, 179.9] {
        for lookfrom in [
            Vec3::new(1e6, 2e6, -3e6),
            Vec3::new(0.0, 1e-30, 1.0),
            Vec3::splat(7.5),
        ] {
            let cam = Camera::new(CameraSettings {
                vertical_fov: fov,
                lookfrom,
                lookat: Vec3::ZERO,
                ..settings()
            })
            .unwrap();
            for (i, j) in [(0, 0), (63, 0), (0, 47), (63, 47), (31, 23)] {
                let d = cam.get_ray(i, j).dir();
                assert!(
                    d.is_finite() && (d.length() - 1.0).abs() < 1e-5,
                    "fov {fov}: {d}"
                );
            }
        }
    }
}

//! Which reason a refused camera gives: the setting at fault, checked
//! against the geometry directly, and that fixing the named setting alone
//! gives a camera (issue 51, item 11).

use glam::Vec3;
use proptest::prelude::*;

use super::refusal::{
    FAR, FAR_APART, FAR_OVERFLOW, FOCUS_TOO_LARGE, FOCUS_TOO_SMALL, ORTHO_TOO_LARGE,
    ORTHO_TOO_MANY_PIXELS, ORTHO_TOO_SMALL, ORTHO_TOO_SMALL_HERE,
};
use super::{Camera, CameraSettings};
use crate::error::Error;
use crate::render::view::Projection;

/// The reason `s` is refused, or `None` for a camera.
fn reason(s: CameraSettings) -> Option<&'static str> {
    match Camera::new(s) {
        Ok(_) => None,
        Err(Error::InvalidCamera { reason }) => Some(reason),
        Err(other) => panic!("not a camera refusal: {other}"),
    }
}

/// A `width` x `height` camera at `from` looking at `at`.
fn camera(width: u32, height: u32, from: Vec3, at: Vec3, projection: Projection) -> CameraSettings {
    CameraSettings {
        width,
        height,
        lookfrom: from,
        lookat: at,
        projection,
        ..CameraSettings::default()
    }
}

fn ortho(height: f32) -> Projection {
    Projection::Orthographic { height }
}

/// The CLI's defaults: 32x24 from the paper's position for a scene of 20.
fn cli(projection: Projection) -> CameraSettings {
    camera(32, 24, Vec3::splat(10.0), Vec3::ZERO, projection)
}

/// Whether `b - a` overflows `f32` on some axis, decided in `f64`: the
/// difference rounds past `f32::MAX` when it is at least halfway from
/// `f32::MAX` to `2^128`.
fn overflows(a: Vec3, b: Vec3) -> bool {
    let limit = 2f64.powi(128) - 2f64.powi(103);
    (0..3).any(|i| (f64::from(b[i]) - f64::from(a[i])).abs() >= limit)
}

#[test]
fn the_issue_cases_name_their_cause() {
    // `--projection orthographic --ortho-height 1e-30`: the height.
    assert_eq!(reason(cli(ortho(1e-30))), Some(ORTHO_TOO_SMALL));
    // `--position 3.4e38,3.4e38,3.4e38 --lookat -3.4e38,...`: apart, not
    // the same point.
    let apart = camera(
        32,
        24,
        Vec3::splat(3.4e38),
        Vec3::splat(-3.4e38),
        Projection::Perspective,
    );
    assert_eq!(reason(apart), Some(FAR_APART));
    assert_eq!(
        reason(camera(
            32,
            24,
            Vec3::ONE,
            Vec3::ONE,
            Projection::Perspective
        )),
        Some("position and target coincide")
    );
    // A far position with an ordinary height or field of view: the position.
    for projection in [Projection::Perspective, ortho(10.0)] {
        let far = camera(32, 24, Vec3::splat(1e30), Vec3::ZERO, projection);
        assert_eq!(reason(far), Some(FAR));
    }
}

#[test]
fn huge_and_tiny_values_name_the_setting_at_fault() {
    // A height whose image width overflows.
    assert_eq!(reason(cli(ortho(3e38))), Some(ORTHO_TOO_LARGE));
    // A height that fits alone but not beside a position near f32::MAX
    // (the position is at fault when it is the larger), and one whose
    // image alone is past what the check's arithmetic holds.
    assert_eq!(reason(cli(ortho(2e38))), Some(ORTHO_TOO_LARGE));
    let edge = camera(
        32,
        32,
        Vec3::new(3e38, 0.0, 0.0),
        Vec3::new(3e38, 0.0, 1.0),
        ortho(1e36),
    );
    assert_eq!(reason(edge), Some(FAR_OVERFLOW));
    // A height fine at the origin but not a thousand voxels out, where a
    // height of one voxel a pixel is fine.
    let out = |height| camera(32, 24, Vec3::splat(1e3), Vec3::ZERO, ortho(height));
    assert_eq!(reason(out(1e-3)), Some(ORTHO_TOO_SMALL_HERE));
    assert_eq!(reason(out(24.0)), None);
    let moved = CameraSettings {
        lookfrom: Vec3::ZERO,
        lookat: Vec3::splat(-1e3),
        ..out(1e-3)
    };
    assert_eq!(reason(moved), None);
    // A height that underflows to a zero step even at the origin.
    let at_origin = camera(32, 24, Vec3::ZERO, Vec3::ONE, ortho(1e-44));
    assert_eq!(reason(at_origin), Some(ORTHO_TOO_SMALL));
    // More pixels across than f32 tells apart, at the origin and any height.
    let wide = camera(1 << 24, 1, Vec3::ZERO, Vec3::Z, ortho(1.0));
    assert_eq!(reason(wide), Some(ORTHO_TOO_MANY_PIXELS));
    // A focus distance lost in the rounding of a near position, and one
    // whose image plane overflows.
    let focus = |focus_dist| CameraSettings {
        focus_dist,
        ..cli(Projection::Perspective)
    };
    assert_eq!(reason(focus(1e-30)), Some(FOCUS_TOO_SMALL));
    assert_eq!(reason(focus(3e38)), Some(FOCUS_TOO_LARGE));
    assert_eq!(reason(focus(1e37)), None);
    // Each vector that is not finite, by name.
    const NAN: Vec3 = Vec3::new(0.0, f32::NAN, 0.0);
    let bad = |f: fn(&mut CameraSettings)| {
        let mut s = cli(Projection::Perspective);
        f(&mut s);
        reason(s)
    };
    assert_eq!(bad(|s| s.lookfrom = NAN), Some("position must be finite"));
    assert_eq!(bad(|s| s.lookat = NAN), Some("target must be finite"));
    assert_eq!(bad(|s| s.cam_up = NAN), Some("up vector must be finite"));
    // Huge and tiny up vectors are directions like any other.
    assert_eq!(bad(|s| s.cam_up = Vec3::new(3e38, 3e38, -3e38)), None);
    assert_eq!(bad(|s| s.cam_up = Vec3::new(1e-45, 0.0, 0.0)), None);
    assert_eq!(bad(|s| s.cam_up = Vec3::ZERO), Some("up vector is zero"));
}

/// Any finite `f32`, from the subnormals to `f32::MAX`, either sign.
fn any_finite() -> impl Strategy<Value = f32> {
    prop_oneof![
        proptest::num::f32::NORMAL | proptest::num::f32::SUBNORMAL | proptest::num::f32::ZERO,
        -1e3f32..1e3,
        Just(f32::MAX),
        Just(-f32::MAX),
    ]
}

fn finite_vec() -> impl Strategy<Value = Vec3> {
    (any_finite(), any_finite(), any_finite()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// `10^e` for `e` in `range`, as `f32` (0 where it underflows).
fn magnitude(range: core::ops::Range<f64>) -> impl Strategy<Value = f32> {
    range.prop_map(|e| 10f64.powf(e) as f32)
}

/// A unit direction, not along an axis more than by chance.
fn direction() -> impl Strategy<Value = Vec3> {
    (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0).prop_filter_map("not a direction", |(x, y, z)| {
        Vec3::new(x, y, z).try_normalize()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// For any finite position and target, "coincide" exactly when they
    /// are the same point and "too far apart" exactly when the direction
    /// between them overflows.
    #[test]
    fn coincide_and_apart_are_what_they_say(
        from in finite_vec(),
        to in finite_vec(),
        same in proptest::bool::weighted(0.1),
    ) {
        let to = if same { from } else { to };
        let got = reason(camera(32, 24, from, to, Projection::Perspective));
        let coincide = got == Some("position and target coincide");
        prop_assert_eq!(coincide, from == to, "{:?}", got);
        prop_assert_eq!(got == Some(FAR_APART), overflows(from, to), "{:?}", got);
    }

    /// An orthographic refusal names what, changed alone, gives a camera:
    /// a height refused as too small is fine at one voxel a pixel, a
    /// position refused as too far is fine at the origin; and the split
    /// between the two is the direct check `step * |position| < 1`.
    #[test]
    fn orthographic_refusals_name_what_fixing_fixes(
        at in direction(),
        distance in magnitude(-3.0..38.5),
        toward in direction(),
        height in magnitude(-46.0..38.5),
        (width, rows) in (1u32..2000, 1u32..2000),
    ) {
        let from = at * distance;
        let s = camera(width, rows, from, from + toward * distance.max(1.0), ortho(height));
        prop_assume!(from.is_finite() && (s.lookat - from).is_finite() && s.lookat != from);
        prop_assume!(height > 0.0);
        let Some(why) = reason(s) else { return Ok(()) };
        let position = f64::from(from.abs().max_element());
        let step = f64::from(height) / f64::from(rows);
        let moved = CameraSettings { lookfrom: Vec3::ZERO, lookat: s.lookat - from, ..s };
        if why == ORTHO_TOO_SMALL {
            // Too small anywhere: about the origin too.
            prop_assert_eq!(reason(moved), Some(ORTHO_TOO_SMALL));
        } else if why == ORTHO_TOO_SMALL_HERE {
            // Too small here, by the split, and a camera at the origin.
            prop_assert!(step * position < 1.01, "{step} at {position}");
            prop_assert_eq!(reason(moved), None);
        }
        if why == ORTHO_TOO_SMALL || why == ORTHO_TOO_SMALL_HERE {
            if position < 1e4 {
                let voxel = CameraSettings { projection: ortho(rows as f32), ..s };
                prop_assert_eq!(reason(voxel), None);
            }
        } else if why == FAR {
            prop_assert!(step * position > 0.99, "{step} at {position}");
            prop_assert!(position > 1.0, "{position}");
            prop_assert_eq!(reason(moved), None);
        } else if why == FAR_OVERFLOW {
            prop_assert!(position > 1e37, "{position}");
            prop_assert_eq!(reason(moved), None);
        } else if why == ORTHO_TOO_LARGE {
            // The height alone (refused about the origin too), or with a
            // position smaller than the image.
            let across = f64::from(height) * (f64::from(width) / f64::from(rows)).max(1.0);
            prop_assert!(across > 1e37, "{across}");
            let alone = reason(moved) == Some(ORTHO_TOO_LARGE);
            prop_assert!(alone || across * 2.0 > position, "{across} at {position}");
        } else {
            prop_assert!(false, "unexpected: {why}");
        }
    }

    /// A perspective camera with the CLI's focus distance is refused only
    /// for its position (never its field of view or image size), and is a
    /// camera at the origin looking the same way.
    #[test]
    fn perspective_refusals_blame_the_position(
        at in direction(),
        distance in magnitude(-3.0..38.5),
        toward in direction(),
        fov in 1e-3f32..179.99,
        (width, rows) in (1u32..4000, 1u32..4000),
    ) {
        let from = at * distance;
        let s = CameraSettings {
            vertical_fov: fov,
            ..camera(width, rows, from, from + toward * distance.max(1.0), Projection::Perspective)
        };
        prop_assume!(from.is_finite() && (s.lookat - from).is_finite() && s.lookat != from);
        let Some(why) = reason(s) else { return Ok(()) };
        prop_assert!(why == FAR || why == FAR_OVERFLOW, "{why}");
        prop_assert!(from.abs().max_element() > 1e6);
        let moved = CameraSettings { lookfrom: Vec3::ZERO, lookat: s.lookat - from, ..s };
        prop_assert_eq!(reason(moved), None);
    }

    /// A focus distance refused as too small is fine at 1 (the position is
    /// not to blame), one refused as too large is refused at the origin too.
    #[test]
    fn focus_refusals_name_the_focus_distance(
        at in direction(),
        distance in magnitude(-3.0..5.0),
        toward in direction(),
        focus in magnitude(-45.0..38.5),
    ) {
        let from = at * distance;
        let s = CameraSettings {
            focus_dist: focus,
            ..camera(64, 36, from, from + toward, Projection::Perspective)
        };
        prop_assume!(focus > 0.0 && s.lookat != from);
        let Some(why) = reason(s) else { return Ok(()) };
        if why == FOCUS_TOO_SMALL {
            prop_assert_eq!(reason(CameraSettings { focus_dist: 1.0, ..s }), None);
        } else if why == FOCUS_TOO_LARGE {
            let moved = CameraSettings { lookfrom: Vec3::ZERO, lookat: toward, ..s };
            prop_assert_eq!(reason(moved), Some(FOCUS_TOO_LARGE));
        } else {
            prop_assert!(false, "unexpected: {why}");
        }
    }
}

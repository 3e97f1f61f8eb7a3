//! The default view of a scene chosen by measurement: of a fixed set of
//! orbits, the one whose small, cheap image sees the most of the scene
//! (a room's open side, a car's flank), framed as any orbit is.

use voxtrace::glam::Vec3;
use voxtrace::{Camera, Orbit, Scene};

use crate::camera::{resolve, Aim, CameraFlags, Stage};

/// The orbits the default view is chosen from, in the order that breaks
/// ties: yaw 0 (the front, `+z`), 45, ... 315 degrees, each 30 degrees
/// above the horizon.
pub const OPEN_SIDE_ORBITS: [Orbit; 8] = {
    let mut orbits = [Orbit {
        yaw: 0.0,
        pitch: 30.0,
        distance: None,
    }; 8];
    let mut k = 0;
    while k < 8 {
        orbits[k].yaw = 45.0 * k as f32;
        k += 1;
    }
    orbits
};

/// The vertical field of view, in degrees, of a model's measured default
/// view: a longer lens than the terrain's 60 degrees, framed from farther
/// back, so a small model does not look wide-angle.
pub const MODEL_FOV: f32 = 30.0;

/// The height in pixels of each measuring image (its width keeps the
/// frame's shape, at most [`PROBE_MAX_WIDTH`]).
const PROBE_HEIGHT: u32 = 54;
/// The widest measuring image.
const PROBE_MAX_WIDTH: u32 = 192;

/// What one orbit sees: distinct palette indices, then distinct voxels
/// (compared in that order, the larger the better).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Seen {
    /// Distinct palette indices (materials) hit.
    pub colors: u32,
    /// Distinct voxels hit.
    pub voxels: u32,
}

/// What `scene` shows through the camera `flags` describe on `stage`,
/// measured on a small image of the same shape (`None`: no camera).
#[must_use]
pub fn seen<S: Scene + ?Sized>(scene: &S, flags: &CameraFlags, stage: &Stage<'_>) -> Option<Seen> {
    let height = PROBE_HEIGHT;
    let aspect = flags.width as f32 / flags.height.max(1) as f32;
    let width = ((height as f32 * aspect).round() as u32).clamp(1, PROBE_MAX_WIDTH);
    let probe = CameraFlags {
        width,
        height,
        ..*flags
    };
    let camera = Camera::new(resolve(&probe, stage).ok()?).ok()?;
    let mut colors = [false; 256];
    let mut voxels = Vec::with_capacity((width * height) as usize);
    for j in 0..height {
        for i in 0..width {
            if let Some(hit) = scene.trace(&camera.get_ray(i, j)) {
                colors[usize::from(hit.material)] = true;
                voxels.push(hit.pos.to_array());
            }
        }
    }
    voxels.sort_unstable();
    voxels.dedup();
    Some(Seen {
        colors: colors.iter().filter(|&&c| c).count() as u32,
        voxels: voxels.len() as u32,
    })
}

/// Whether an orbit at `yaw` degrees looks at the model's front half:
/// yaw 315, 0 or 45, the side MagicaVoxel turns toward the viewer.
#[must_use]
pub fn in_front_half(yaw: f32) -> bool {
    matches!(yaw.rem_euclid(360.0) as u32, 0..=45 | 315..=359)
}

/// Whether `other` shows clearly more of a model than `front`: two more
/// distinct colors or more (a room's furniture seen through its open
/// side, which its walls hide from the front), or one more and a tenth
/// more voxels (an open side also shows the floor inside). One more
/// color alone is not enough: a figure's back (a pack, a cape) often
/// carries a color its face does not.
fn clearly_more(other: Seen, front: Seen) -> bool {
    let more_colors = other.colors > front.colors;
    more_colors && (other.colors >= front.colors + 2 || other.voxels * 10 > front.voxels * 11)
}

/// The orbit of [`OPEN_SIDE_ORBITS`] `scene` is seen from by default:
/// the one of the front half ([`in_front_half`]) that shows the most
/// ([`Seen`]: the most distinct colors, then the most distinct voxels),
/// unless an orbit from another side shows clearly more (a room open
/// toward its back); with `flags`' image shape and lens, the first in
/// their order on a tie, and the front (yaw 0) when none sees anything.
/// Deterministic: the same scene and flags give the same orbit.
#[must_use]
pub fn open_side<S: Scene + ?Sized>(scene: &S, flags: &CameraFlags, stage: &Stage<'_>) -> Orbit {
    // The best of the front half, and of the rest.
    let mut best = [(None, OPEN_SIDE_ORBITS[0]); 2];
    for orbit in OPEN_SIDE_ORBITS {
        let aimed = CameraFlags {
            aim: Aim::Orbit(orbit),
            ..*flags
        };
        let score = seen(scene, &aimed, stage);
        let side = &mut best[usize::from(!in_front_half(orbit.yaw))];
        if score > side.0 {
            *side = (score, orbit);
        }
    }
    match best {
        [(Some(front), front_orbit), (Some(other), other_orbit)] => {
            if clearly_more(other, front) {
                other_orbit
            } else {
                front_orbit
            }
        }
        [(None, _), (Some(_), other_orbit)] => other_orbit,
        [(_, front_orbit), _] => front_orbit,
    }
}

/// The lens the default view (no camera flag: `flags.aim` is
/// [`Aim::Default`]) is measured with on `stage`, or `None` when the
/// flags stay as they are. A model is measured at [`MODEL_FOV`]; the
/// terrain keeps the paper's camera, byte for byte, unless it would start
/// inside a voxel (`inside`) or on its target, and is then measured at
/// the flags' own lens.
#[must_use]
pub fn default_lens(
    flags: CameraFlags,
    stage: &Stage<'_>,
    inside: impl Fn(Vec3) -> bool,
) -> Option<CameraFlags> {
    if flags.aim != Aim::Default {
        return None;
    }
    let fov = match stage.default_position {
        None => MODEL_FOV,
        Some(position) if position != stage.target && !inside(position) => return None,
        Some(_) => flags.fov,
    };
    Some(CameraFlags { fov, ..flags })
}

/// The measured default view through `lens` ([`default_lens`]): the
/// orbit [`open_side`] picks on `scene`, at that lens.
#[must_use]
pub fn measured_view<S: Scene + ?Sized>(
    lens: CameraFlags,
    scene: &S,
    stage: &Stage<'_>,
) -> CameraFlags {
    CameraFlags {
        aim: Aim::Orbit(open_side(scene, &lens, stage)),
        ..lens
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::framing::Boxes;
    use voxtrace::glam::{IVec3, U8Vec3, Vec3};
    use voxtrace::{FnSource, IAabb, OctreeScene, Palette};

    /// A 16x8x16 room with a floor (1), walls (2) on its `-x`, `-z` and
    /// `+z` sides, open toward `+x`, and three pieces of furniture (3, 4,
    /// 5) in its middle, which only a view from the open side sees.
    fn room() -> (impl Scene, IAabb) {
        room_open_toward(90)
    }

    #[test]
    fn the_room_is_seen_from_its_open_side() {
        let (scene, bounds) = room();
        let stage = Stage {
            boxes: Boxes::Bounds(bounds),
            target: Vec3::splat(8.0),
            default_position: None,
        };
        let flags = CameraFlags {
            fov: MODEL_FOV,
            ..CameraFlags::new(960, 540, Aim::Default)
        };
        let orbit = open_side(&scene, &flags, &stage);
        assert!([45.0, 90.0, 135.0].contains(&orbit.yaw), "{orbit:?}");
        let aimed = CameraFlags {
            aim: Aim::Orbit(orbit),
            ..flags
        };
        assert_eq!(seen(&scene, &aimed, &stage).unwrap().colors, 5);
        // From the closed side the furniture is hidden.
        let behind = CameraFlags {
            aim: Aim::Orbit(OPEN_SIDE_ORBITS[6]),
            ..flags
        };
        assert!(seen(&scene, &behind, &stage).unwrap().colors < 5);
        // The same scene and flags, the same orbit.
        assert_eq!(open_side(&scene, &flags, &stage), orbit);
    }

    /// A 16x8x16 room with a floor (1), walls (2) and three pieces of
    /// furniture (3, 4, 5) in its middle, open toward the side at yaw
    /// `open` (0: `+z`, 90: `+x`, 180: `-z`, 270: `-x`; at 90 its walls
    /// stand on `-x`, `-z` and `+z`).
    fn room_open_toward(open: u32) -> (impl Scene, IAabb) {
        let palette = Palette::new(&[U8Vec3::splat(200); 5]);
        // The room open toward `+x`, turned so that side faces `open`.
        let source = FnSource::new(palette, move |p: IVec3| {
            let (x, z) = match open {
                90 => (p.x, p.z),
                0 => (p.z, 15 - p.x),
                270 => (15 - p.x, 15 - p.z),
                _ => (15 - p.z, p.x),
            };
            match (x, p.y, z) {
                (_, 0, _) => 1,
                (0, _, _) | (_, _, 0 | 15) => 2,
                (7..=8, 1, 5..=6) => 3,
                (7..=8, 1, 8..=9) => 4,
                (7..=8, 1, 11..=12) => 5,
                _ => 0,
            }
        });
        let bounds = IAabb::new(IVec3::ZERO, IVec3::new(16, 8, 16));
        (OctreeScene::build(&source, bounds).unwrap(), bounds)
    }

    /// A figure 8 wide, 16 tall, 4 deep: a body (1), a face of two eyes
    /// (2) and a mouth (3) on its front (`+z`), and on its back a pack
    /// painted in three colors (4, 5, 6): one color more than the face,
    /// as many voxels.
    fn figure() -> (impl Scene, IAabb) {
        let palette = Palette::new(&[U8Vec3::splat(200); 6]);
        let source = FnSource::new(palette, |p: IVec3| match (p.x, p.y, p.z) {
            (3 | 8, 12, 7) => 2,
            (4..=7, 10, 7) => 3,
            (3..=8, 4..=9, 4) => 4 + (p.y - 4) as u8 / 2,
            (2..=9, 0..=15, 4..=7) => 1,
            _ => 0,
        });
        let bounds = IAabb::new(IVec3::new(0, 0, 2), IVec3::new(12, 16, 10));
        (OctreeScene::build(&source, bounds).unwrap(), bounds)
    }

    /// The default orbit of `scene` over `bounds` in a 960x540 frame.
    fn default_orbit(scene: &impl Scene, bounds: IAabb) -> (Orbit, CameraFlags, Stage<'static>) {
        let stage = Stage {
            boxes: Boxes::Bounds(bounds),
            target: (bounds.min + bounds.max).as_vec3() / 2.0,
            default_position: None,
        };
        let flags = CameraFlags {
            fov: MODEL_FOV,
            ..CameraFlags::new(960, 540, Aim::Default)
        };
        (open_side(scene, &flags, &stage), flags, stage)
    }

    #[test]
    fn a_figure_is_seen_from_its_front_half_with_its_face() {
        let (scene, bounds) = figure();
        let (orbit, flags, stage) = default_orbit(&scene, bounds);
        assert!(in_front_half(orbit.yaw), "{orbit:?}");
        let seen_from = |yaw: f32| {
            let aim = Aim::Orbit(Orbit { yaw, ..orbit });
            seen(&scene, &CameraFlags { aim, ..flags }, &stage).unwrap()
        };
        // The face in view: the body, the eyes and the mouth.
        assert_eq!(seen_from(orbit.yaw).colors, 3);
        // The back shows one color more (the most seen alone would take
        // it), but not clearly more.
        let back = seen_from(180.0);
        assert_eq!(back.colors, 4, "{back:?}");
        assert!(!clearly_more(back, seen_from(orbit.yaw)));
    }

    #[test]
    fn a_room_is_seen_through_its_open_side_whichever_way_it_opens() {
        for open in [0, 90, 180, 270] {
            let (scene, bounds) = room_open_toward(open);
            let (orbit, flags, stage) = default_orbit(&scene, bounds);
            // Within 45 degrees of the open side, every piece of
            // furniture in view.
            let off = (orbit.yaw - open as f32).rem_euclid(360.0);
            assert!(off <= 45.0 || off >= 315.0, "open {open}: {orbit:?}");
            let aimed = CameraFlags {
                aim: Aim::Orbit(orbit),
                ..flags
            };
            assert_eq!(
                seen(&scene, &aimed, &stage).unwrap().colors,
                5,
                "open {open}"
            );
        }
    }

    #[test]
    fn the_front_half_is_yaw_315_to_45() {
        let front: Vec<f32> = OPEN_SIDE_ORBITS
            .iter()
            .map(|o| o.yaw)
            .filter(|&yaw| in_front_half(yaw))
            .collect();
        assert_eq!(front, [0.0, 45.0, 315.0]);
        assert!(in_front_half(-30.0) && !in_front_half(46.0) && !in_front_half(314.0));
    }

    #[test]
    fn the_orbits_go_around_at_thirty_degrees() {
        let yaws: Vec<f32> = OPEN_SIDE_ORBITS.iter().map(|o| o.yaw).collect();
        assert_eq!(yaws, [0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0]);
        assert!(OPEN_SIDE_ORBITS
            .iter()
            .all(|o| o.pitch == 30.0 && o.distance.is_none()));
    }
}

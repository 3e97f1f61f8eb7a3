//! Packets of rays (`Scene::trace_packet`) give every lane they answer the
//! hit the one-ray walk gives it, bit for bit: on random scenes, for
//! packets of camera pixels, of diverging and axis-parallel directions,
//! from origins on planes and corners, outside the volume and in its
//! empty space, of parallel rays from scattered origins and of lanes left
//! out, over reaches from the nearest hit, ending at a hit, a float short
//! of it, and not a number.
#![cfg(feature = "packets")]

mod common;

use common::rays::{point_in, random_dir, special_dir, Rng};
use common::sources::{speckle, ListSource};
use proptest::prelude::*;
use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{
    Camera, CameraSettings, DenseScene, Hit, IAabb, OctreeScene, Ray, Reach, Scene, VoxelGenerator,
    WalkMemory, PACKET,
};

/// The one-ray walk's hit of `ray` over `reach`.
fn one_by_one(scene: &impl Scene, ray: &Ray, reach: Reach) -> Option<Hit> {
    let memory = &mut WalkMemory::new();
    scene.trace_with(ray, reach, memory, None).hit
}

/// Checks every answered lane of `rays` against the one-ray walk over
/// the whole ray, from the nearest hit of the packet (a clear distance
/// the caller promises), and within reaches that end exactly at a lane's
/// hit, between hits and before any; returns how many lanes were
/// answered.
fn check(scene: &impl Scene, rays: &[Ray; PACKET]) -> Result<u32, TestCaseError> {
    check_lanes(scene, rays, u32::MAX)
}

/// The reaches [`check`] traces each packet over.
const REACHES: u32 = 7;

/// [`check`] of the lanes of `lanes` only: no other lane is answered.
fn check_lanes(scene: &impl Scene, rays: &[Ray; PACKET], lanes: u32) -> Result<u32, TestCaseError> {
    let mut ts: Vec<f32> = rays
        .iter()
        .filter_map(|r| one_by_one(scene, r, Reach::ALL))
        .map(|h| h.t)
        .collect();
    ts.sort_by(f32::total_cmp);
    let nearest = ts.first().copied().unwrap_or(f32::INFINITY);
    let middle = ts.get(ts.len() / 2).copied().unwrap_or(3.0);
    let reaches: [Reach; REACHES as usize] = [
        Reach::ALL,
        Reach::after(nearest.min(1e30)),
        Reach::within(middle),
        Reach::within(middle * 0.75 + 0.1),
        Reach::within(1.5),
        Reach {
            clear: nearest.min(1e30),
            max: middle,
        },
        Reach::within(f32::from_bits(middle.to_bits().saturating_sub(1))),
    ];
    // A reach that is not a number is left to the one-ray walk.
    let nan = Reach::within(f32::NAN);
    prop_assert_eq!(scene.trace_packet(rays, lanes, nan, &mut [None; PACKET]), 0);
    let mut answered = 0;
    for reach in reaches {
        let mut hits = [None; PACKET];
        let answered_lanes = scene.trace_packet(rays, lanes, reach, &mut hits);
        prop_assert_eq!(answered_lanes & !lanes, 0, "lanes not asked for answered");
        for i in 0..PACKET {
            if answered_lanes >> i & 1 != 0 {
                let alone = one_by_one(scene, &rays[i], reach);
                // Equal, and `t` bit for bit (`==` takes -0 for 0).
                let t_bits = |h: &Option<Hit>| h.map(|h| h.t.to_bits());
                prop_assert!(
                    hits[i] == alone && t_bits(&hits[i]) == t_bits(&alone),
                    "lane {} of {:?} over {:?}: {:?} against {:?}",
                    i,
                    rays[i],
                    reach,
                    hits[i],
                    alone
                );
                answered += 1;
            }
        }
    }
    Ok(answered)
}

/// A packet whose lane `i` starts at and goes along `lane(i)`.
fn packet_from(mut lane: impl FnMut(usize) -> (Vec3, Vec3)) -> Option<[Ray; PACKET]> {
    let rays: Vec<Ray> = (0..PACKET)
        .map(|i| {
            let (origin, dir) = lane(i);
            Ray::new(origin, dir)
        })
        .collect::<Result<_, _>>()
        .ok()?;
    rays.try_into().ok()
}

/// Width of a camera's block of pixels in a packet (its height makes
/// [`PACKET`] rays).
const WIDTH: u32 = 8;

/// A camera's block of pixels at `(x, y)`: rows of [`WIDTH`].
fn camera_block(camera: &Camera, x: u32, y: u32) -> [Ray; PACKET] {
    core::array::from_fn(|i| camera.get_ray(x + i as u32 % WIDTH, y + i as u32 / WIDTH))
}

/// A small random scene: speckled blocks in a box near the origin.
fn random_scene(
    seed: u64,
    percent: u64,
    size: IVec3,
    min: IVec3,
) -> OctreeScene<Vec<voxtrace::Node>, Vec<u8>> {
    let bounds = IAabb::new(min, min + size);
    OctreeScene::build(&speckle(seed, percent), bounds).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Diverging packets: random, special (axis-parallel, diagonal, signed
    /// zero) and aimed directions from one origin, on and off the grid,
    /// inside and outside the volume; lanes from other origins and with
    /// components too small to walk; volumes near the origin and millions
    /// of voxels away. Parallel packets from scattered origins (shadow
    /// rays: on half-integer points, just off a voxel's plane, anywhere),
    /// and packets whose every lane has its own origin and direction,
    /// some lanes left out.
    #[test]
    fn packet_lanes_are_the_one_ray_walks_hits(
        seed in any::<u64>(),
        percent in 1u64..60,
        size in (1i32..40, 1i32..40, 1i32..40),
        min in (-20i32..20, -20i32..20, -20i32..20),
        far in any::<bool>(),
        kind in 0u32..8,
    ) {
        let size = IVec3::new(size.0, size.1, size.2);
        let min = IVec3::new(min.0, min.1, min.2) + if far { IVec3::new(3_000_000, -2_500_000, 1_000_000) } else { IVec3::ZERO };
        let scene = random_scene(seed, percent, size, min);
        let dense = DenseScene::build(&speckle(seed, percent), scene.bounds()).unwrap();
        let mut rng = Rng::new(seed);
        let (lo, hi) = (min.as_vec3(), (min + size).as_vec3());
        let mut answered = 0;
        for _ in 0..8 {
            let mut origin = point_in(&mut rng, lo - size.as_vec3(), hi + size.as_vec3());
            if kind == 3 {
                // From outside the volume: the coherent packet a camera sends.
                origin.y = hi.y + 1.0 + rng.range(0.0, 30.0);
            }
            let aim = point_in(&mut rng, lo, hi) - origin;
            let cone = |rng: &mut Rng| aim + random_dir(rng) * 0.05 * aim.length();
            let rays = packet_from(|i| match kind {
                // Lanes that diverge at once: any direction.
                0 => (origin, random_dir(&mut rng)),
                1 => (origin, special_dir(&mut rng)),
                // A narrow cone toward the volume, some lanes exactly on
                // axis-parallel or diagonal directions.
                2 if i % 5 == 0 => (origin, special_dir(&mut rng)),
                // Some lanes from another origin, a rounding away.
                4 if i % 3 == 1 => (origin + Vec3::splat(origin.x.abs().max(1.0) * 1e-6), cone(&mut rng)),
                // Some lanes with a component too small to cross a plane.
                5 if i % 3 == 1 => (origin, Vec3::new(aim.x, 1e-12, aim.z)),
                _ => (origin, cone(&mut rng)),
            });
            // Parallel lanes from scattered origins, or every lane its
            // own origin and direction (the signs shared, so most are
            // taken).
            let signs = random_dir(&mut rng).signum();
            let shared = if rng.below(3) == 0 { special_dir(&mut rng) } else { random_dir(&mut rng) };
            let rays = match kind {
                6 | 7 => packet_from(|_| {
                    let mut at = point_in(&mut rng, lo - size.as_vec3(), hi + size.as_vec3());
                    match rng.below(3) {
                        0 => at = (at * 2.0).round() * 0.5,
                        1 => {
                            let axis = rng.below(3) as usize;
                            let side = if rng.below(2) == 0 { 1.0 } else { -1.0 };
                            at[axis] = at[axis].round() + side / 256.0;
                        }
                        _ => {}
                    }
                    let dir = if kind == 6 { shared } else { random_dir(&mut rng).abs() * signs };
                    (at, dir)
                }),
                _ => rays,
            };
            let Some(rays) = rays else { continue };
            let lanes = if kind == 7 { rng.below(u32::MAX) | 1 } else { u32::MAX };
            answered += check_lanes(&scene, &rays, lanes)?;
            // A storage without packets answers no lane.
            prop_assert_eq!(dense.trace_packet(&rays, u32::MAX, Reach::ALL, &mut [None; PACKET]), 0);
        }
        // Rays from outside toward the solid voxels, and parallel rays
        // from scattered origins, are taken: the check above is not
        // vacuous.
        if (kind == 3 || kind == 6) && !scene.is_empty() {
            prop_assert!(answered > 0);
        }
    }
}

/// Camera blocks over the terrain, from the paper's camera and from
/// orbits that graze the ground: the coherent packets the renderer sends.
/// Most lanes are answered, so the check above is not vacuous.
#[test]
fn camera_blocks_over_the_terrain_are_the_one_ray_walks_hits() {
    let bounds = IAabb::centered(40);
    let scene = OctreeScene::build(&VoxelGenerator::new(1), bounds).unwrap();
    let (mut lanes, mut answered) = (0, 0);
    for (lookfrom, lookat) in [
        (Vec3::new(60.0, 30.0, 60.0), Vec3::ZERO),
        (Vec3::new(-70.0, 8.0, 3.0), Vec3::new(0.0, 2.0, 0.0)),
        (Vec3::new(0.5, 90.0, 0.5), Vec3::new(0.5, 0.0, 0.25)),
        (Vec3::new(41.0, 20.0, -41.0), Vec3::new(-10.0, -5.0, 10.0)),
    ] {
        let camera = Camera::new(CameraSettings {
            width: 64,
            height: 48,
            lookfrom,
            lookat,
            ..CameraSettings::default()
        })
        .unwrap();
        for y in (0..48).step_by(PACKET / WIDTH as usize) {
            for x in (0..64).step_by(WIDTH as usize) {
                answered += check(&scene, &camera_block(&camera, x, y)).unwrap();
                lanes += REACHES * PACKET as u32;
            }
        }
    }
    assert!(
        answered * 10 >= lanes * 9,
        "{answered} of {lanes} lanes answered"
    );
}

/// Camera blocks from inside the occupied box, in its empty space: a
/// camera just above the ground, looking along it. Packets are taken
/// there too (their origin touches no solid voxel), and most lanes are
/// answered.
#[test]
fn camera_blocks_from_the_empty_space_inside_the_terrain_are_the_one_ray_walks_hits() {
    let bounds = IAabb::centered(64);
    let scene = OctreeScene::build(&VoxelGenerator::new(1), bounds).unwrap();
    // The highest solid voxel of a column, if any.
    let top = |x: i32, z: i32| {
        (-64..64)
            .rev()
            .find(|&y| scene.material(IVec3::new(x, y, z)) != 0)
    };
    let highest = (-64..64)
        .flat_map(|x| (-64..64).map(move |z| (x, z)))
        .filter_map(|(x, z)| top(x, z))
        .max()
        .unwrap();
    let (mut lanes, mut answered, mut cameras) = (0, 0, 0);
    // Columns whose ground lies below the highest voxel: a camera just
    // above it is inside the occupied box.
    let low_columns = (-60..60)
        .step_by(9)
        .flat_map(|x| (-60..60).step_by(13).map(move |z| (x, z)))
        .filter_map(|(x, z)| Some((x, z, top(x, z)?)))
        .filter(|&(_, _, ground)| ground + 2 <= highest)
        .step_by(7)
        .take(5);
    for (x, z, ground) in low_columns {
        cameras += 1;
        let lookfrom = Vec3::new(x as f32 + 0.5, ground as f32 + 1.5, z as f32 + 0.5);
        for lookat in [
            Vec3::new(0.0, ground as f32 - 4.0, 0.0),
            lookfrom + Vec3::new(7.0, -1.0, -3.0),
        ] {
            let Ok(camera) = Camera::new(CameraSettings {
                width: 64,
                height: 48,
                lookfrom,
                lookat,
                ..CameraSettings::default()
            }) else {
                continue;
            };
            for y in (0..48).step_by(PACKET / WIDTH as usize) {
                for x in (0..64).step_by(WIDTH as usize) {
                    answered += check(&scene, &camera_block(&camera, x, y)).unwrap();
                    lanes += REACHES * PACKET as u32;
                }
            }
        }
    }
    assert!(cameras >= 3, "{cameras} cameras inside the occupied box");
    assert!(
        answered * 10 >= lanes * 8,
        "{answered} of {lanes} lanes answered"
    );
}

/// Every half-integer origin around tiny scenes (one to four voxels
/// touching by faces, edges and corners), so origins inside solid
/// voxels, on their faces, edges and corners, and in the empty cells
/// between them, with packets toward all eight octants: small-integer
/// slopes (whose crossings tie) and random directions.
#[test]
fn packets_from_every_half_integer_origin_around_tiny_scenes() {
    let scenes: [&[(IVec3, u8)]; 4] = [
        &[(IVec3::ZERO, 1)],
        &[(IVec3::ZERO, 1), (IVec3::X, 2)],
        &[(IVec3::ZERO, 1), (IVec3::new(1, 1, 1), 2)],
        &[
            (IVec3::NEG_ONE, 1),
            (IVec3::ZERO, 2),
            (IVec3::new(-1, 0, -1), 3),
            (IVec3::new(1, -1, 0), 4),
        ],
    ];
    let slopes = [1.0f32, 2.0, 0.5, 3.0, 1.0, 0.25, 4.0, 1.0];
    let mut rng = Rng::new(5);
    let mut answered = 0;
    for list in scenes {
        let source = ListSource::new(list.to_vec());
        let scene = OctreeScene::build(&source, IAabb::centered(3)).unwrap();
        for corner in 0..7 * 7 * 7 {
            let at = IVec3::new(corner % 7, corner / 7 % 7, corner / 49) - 3;
            let origin = at.as_vec3() * 0.5;
            for octant in 0..8 {
                let signs = Vec3::new(
                    if octant & 1 != 0 { -1.0 } else { 1.0 },
                    if octant & 2 != 0 { -1.0 } else { 1.0 },
                    if octant & 4 != 0 { -1.0 } else { 1.0 },
                );
                let rays = packet_from(|i| {
                    let dir = if i < 8 {
                        Vec3::new(slopes[i], slopes[(i * 3 + 1) % 8], slopes[(i * 5 + 2) % 8])
                    } else {
                        random_dir(&mut rng).abs() + Vec3::splat(0.01)
                    };
                    (origin, dir * signs)
                })
                .unwrap();
                answered += check(&scene, &rays).unwrap();
            }
        }
    }
    // Most lanes are answered: the check is not vacuous.
    assert!(
        answered > 4 * 343 * 8 * PACKET as u32,
        "{answered} lanes answered"
    );
}

//! Hard cases stay numerically stable. Every test is named `stability_*`, so
//! `cargo test stability` runs exactly this suite.
//!
//! Each ray goes through both backends (where the volume fits in a dense
//! array), the f32 brute-force reference (exact agreement: voxel, face, `t`
//! bits), the f64 geometric oracle (within rounding), and the step bound.

mod common;

use common::rays::{point_in, random_dir, special_dir, Rng};
use common::reference::{as_ref_hit, check_geometry, first_hit_among};
use common::sources::{solids, speckle, ListSource};
use voxtrace::glam::{IVec3, Vec3};
use voxtrace::{
    max_steps, render, Camera, CameraSettings, DenseScene, Error, Face, Hit, IAabb, Node,
    OctreeScene, Ray, Rect, RenderOptions, Scene, Target, VoxelSource,
};

struct Fixture {
    bounds: IAabb,
    solids: Vec<(IVec3, u8)>,
    dense: Option<DenseScene<Vec<u8>>>,
    octree: OctreeScene<Vec<Node>, Vec<u8>>,
}

impl Fixture {
    fn new<S: VoxelSource>(source: &S, bounds: IAabb, solids: Vec<(IVec3, u8)>) -> Self {
        let dense = (bounds.volume().unwrap() <= 1 << 24)
            .then(|| DenseScene::build(source, bounds).unwrap());
        Self {
            bounds,
            solids,
            dense,
            octree: OctreeScene::build(source, bounds).unwrap(),
        }
    }

    fn speckled(seed: u64, percent: u64, bounds: IAabb) -> Self {
        let source = speckle(seed, percent);
        Self::new(&source, bounds, solids(&source, bounds))
    }

    fn list(list: Vec<(IVec3, u8)>, bounds: IAabb) -> Self {
        let source = ListSource::new(list.clone());
        Self::new(&source, bounds, list)
    }

    /// Traces `ray` everywhere, asserts that all agree, returns the hit.
    fn check(&self, ray: &Ray) -> Option<Hit> {
        let traced = self.octree.trace_counted(ray);
        let bound = max_steps(&self.bounds);
        assert!(
            traced.steps <= bound,
            "octree took {} > {bound} steps: {ray:?}",
            traced.steps
        );
        if let Some(dense) = &self.dense {
            let d = dense.trace_counted(ray);
            assert!(
                d.steps <= bound,
                "dense took {} > {bound} steps: {ray:?}",
                d.steps
            );
            assert_eq!(d.hit, traced.hit, "dense vs octree: {ray:?}");
            assert_eq!(
                d.hit.map(|h| h.t.to_bits()),
                traced.hit.map(|h| h.t.to_bits())
            );
        }
        let expected = first_hit_among(ray, self.solids.iter().copied());
        assert_eq!(
            as_ref_hit(traced.hit),
            expected,
            "octree vs reference: {ray:?}"
        );
        if let Some(h) = traced.hit {
            assert!(h.t.is_finite() && h.t >= 0.0 && h.t.to_bits() != (-0.0f32).to_bits());
            assert!(self.bounds.contains(h.pos));
        }
        check_geometry(ray, traced.hit.as_ref(), &self.solids)
            .unwrap_or_else(|e| panic!("{e}: {ray:?}"));
        traced.hit
    }
}

fn ray(o: impl Into<Vec3>, d: impl Into<Vec3>) -> Ray {
    Ray::new(o.into(), d.into()).unwrap()
}

fn cube(n: i32) -> IAabb {
    IAabb::centered(n)
}

#[test]
fn stability_zero_and_negative_zero_direction_components() {
    let f = Fixture::speckled(1, 30, cube(6));
    let mut rng = Rng::new(1);
    let zeros = [0.0f32, -0.0];
    for _ in 0..400 {
        let o = point_in(&mut rng, Vec3::splat(-7.0), Vec3::splat(7.0));
        let v = random_dir(&mut rng);
        for axis in 0..3 {
            for z in zeros {
                // One zero component.
                let mut d = v;
                d[axis] = z;
                f.check(&ray(o, d));
                // Two zero components: an axis-parallel ray, either sign.
                let mut d = Vec3::splat(z);
                d[axis] = if v[axis] < 0.0 { -1.0 } else { 1.0 };
                let a = f.check(&ray(o, d));
                let mut flipped = d;
                flipped[(axis + 1) % 3] = -z;
                assert_eq!(
                    a,
                    f.check(&ray(o, flipped)),
                    "the sign of a zero never matters"
                );
            }
        }
    }
}

#[test]
fn stability_tie_rule_lowest_axis_enters_first() {
    // A ray through the edge at x = y = 1, moving (+1, +1, 0).
    let from = Vec3::new(0.0, 0.0, 0.5);
    let diagonal = Vec3::new(1.0, 1.0, 0.0);
    let bounds = IAabb::new(IVec3::ZERO, IVec3::splat(3));
    // Only the y-neighbour is solid: it is not entered, the ray goes on to (1, 1).
    let f = Fixture::list(
        vec![(IVec3::new(0, 1, 0), 1), (IVec3::new(1, 1, 0), 2)],
        bounds,
    );
    let hit = f.check(&ray(from, diagonal)).unwrap();
    assert_eq!((hit.pos, hit.face), (IVec3::new(1, 1, 0), Some(Face::NegY)));
    // The x-neighbour is solid: the ray enters it, through its -x face.
    let f = Fixture::list(vec![(IVec3::new(1, 0, 0), 3)], bounds);
    let hit = f.check(&ray(from, diagonal)).unwrap();
    assert_eq!((hit.pos, hit.face), (IVec3::new(1, 0, 0), Some(Face::NegX)));
    assert_eq!(
        hit.t,
        1.0 / std::f32::consts::FRAC_1_SQRT_2,
        "t of the x = 1 crossing"
    );
    // Through a corner, x then y then z: (1,0,0), (1,1,0), (1,1,1).
    let f = Fixture::list(
        vec![(IVec3::new(1, 1, 0), 1), (IVec3::new(0, 1, 1), 2)],
        bounds,
    );
    let hit = f.check(&ray(Vec3::ZERO, Vec3::ONE)).unwrap();
    assert_eq!((hit.pos, hit.face), (IVec3::new(1, 1, 0), Some(Face::NegY)));
}

#[test]
fn stability_rays_through_edges_and_corners() {
    let f = Fixture::speckled(2, 35, cube(5));
    let mut rng = Rng::new(2);
    for _ in 0..6000 {
        let o = point_in(&mut rng, Vec3::splat(-7.0), Vec3::splat(7.0)).round();
        f.check(&ray(o, special_dir(&mut rng)));
    }
}

#[test]
fn stability_grazing_rays_along_faces() {
    // A solid floor at y = 0 (the cells occupy [0, 1) in y).
    let bounds = IAabb::new(IVec3::new(-6, -2, -6), IVec3::new(6, 3, 6));
    let floor: Vec<_> = IAabb::new(IVec3::new(-6, 0, -6), IVec3::new(6, 1, 6))
        .iter()
        .map(|p| (p, 1))
        .collect();
    let f = Fixture::list(floor, bounds);
    for z in [-0.0f32, 0.0] {
        // On the top face plane, moving along it: above the floor, no hit.
        assert_eq!(f.check(&ray((-9.0, 1.0, 0.5), (1.0, z, 0.0))), None);
        assert_eq!(f.check(&ray((-9.0, 1.0, -9.0), (1.0, z, 1.0))), None);
        // On the bottom face plane: the cell above the plane is the floor.
        let hit = f.check(&ray((-9.0, 0.0, 0.5), (1.0, z, 0.0))).unwrap();
        assert_eq!(
            (hit.pos, hit.face),
            (IVec3::new(-6, 0, 0), Some(Face::NegX))
        );
    }
    // Descending from the top plane: the ray is in the floor's row at once
    // (the cell just after t = 0), so it enters the floor from the side.
    let hit = f.check(&ray((-9.0, 1.0, 0.5), (1.0, -1e-3, 0.0))).unwrap();
    assert_eq!(
        (hit.pos, hit.face),
        (IVec3::new(-6, 0, 0), Some(Face::NegX))
    );
    // Descending from above the plane: enters through the top face.
    // (It crosses y = 1 at x = 3.5, clear of any edge.)
    let hit = f.check(&ray((-9.0, 1.5, 0.5), (1.0, -0.04, 0.0))).unwrap();
    assert_eq!((hit.pos, hit.face), (IVec3::new(3, 0, 0), Some(Face::PosY)));
    let mut rng = Rng::new(3);
    for _ in 0..3000 {
        let mut o = point_in(&mut rng, Vec3::splat(-8.0), Vec3::splat(8.0));
        o.y = [0.0, 1.0, -2.0, 3.0][rng.below(4) as usize];
        let mut d = random_dir(&mut rng);
        d.y = [0.0, -0.0, 1e-7, -1e-7][rng.below(4) as usize];
        f.check(&ray(o, d));
    }
}

#[test]
fn stability_origins_on_boundaries_inside_and_outside() {
    let f = Fixture::speckled(4, 25, cube(6));
    let mut rng = Rng::new(4);
    for _ in 0..3000 {
        let d = if rng.below(2) == 0 {
            special_dir(&mut rng)
        } else {
            random_dir(&mut rng)
        };
        // On a voxel boundary plane (or two, or three).
        let mut o = point_in(&mut rng, Vec3::splat(-6.0), Vec3::splat(6.0));
        for a in 0..rng.below(4) as usize {
            o[a] = o[a].round();
        }
        f.check(&ray(o, d));
        // On the volume's boundary.
        let mut o = point_in(&mut rng, Vec3::splat(-6.0), Vec3::splat(6.0));
        o[rng.below(3) as usize] = if rng.below(2) == 0 { -6.0 } else { 6.0 };
        f.check(&ray(o, d));
        // Outside, pointing away: always a miss, in zero steps.
        let mut o = point_in(&mut rng, Vec3::splat(-6.0), Vec3::splat(6.0));
        let a = rng.below(3) as usize;
        o[a] = 6.0 + rng.range(0.0, 5.0);
        let mut away = d;
        away[a] = d[a].abs().max(0.1);
        assert_eq!(f.check(&ray(o, away)), None);
    }
}

#[test]
fn stability_camera_inside_a_solid_voxel_hits_it_at_zero() {
    let bounds = cube(4);
    let f = Fixture::list(
        IAabb::new(IVec3::splat(-1), IVec3::splat(2))
            .iter()
            .map(|p| (p, 2))
            .collect(),
        bounds,
    );
    let mut rng = Rng::new(5);
    for _ in 0..500 {
        let o = Vec3::new(
            rng.range(0.01, 0.99),
            rng.range(0.01, 0.99),
            rng.range(0.01, 0.99),
        );
        let hit = f.check(&ray(o, random_dir(&mut rng))).unwrap();
        assert_eq!((hit.pos, hit.face, hit.t), (IVec3::ZERO, None, 0.0));
    }
    // On the voxel's face, moving in: entered through that face at t = 0.
    let hit = f.check(&ray((1.0, 0.5, 0.5), (-1.0, 0.2, 0.1))).unwrap();
    assert_eq!(
        (hit.pos, hit.face, hit.t),
        (IVec3::ZERO, Some(Face::PosX), 0.0)
    );
    // Rendering from inside: every pixel is that voxel, at half light.
    for scene in [&f.octree as &(dyn Scene + Sync), f.dense.as_ref().unwrap()] {
        let camera = Camera::new(CameraSettings {
            width: 16,
            height: 9,
            lookfrom: Vec3::splat(0.5),
            lookat: Vec3::new(3.0, 1.0, 2.0),
            ..CameraSettings::default()
        })
        .unwrap();
        let mut pixels = vec![0; 16 * 9];
        let stats = render(
            &scene,
            &camera,
            &RenderOptions::default(),
            Rect::full(&camera),
            Target::Buffer(&mut pixels),
            None,
        )
        .unwrap();
        assert_eq!(stats.primary_hits, 16 * 9);
        assert!(pixels.iter().all(|&p| p == pixels[0]));
    }
}

#[test]
fn stability_far_origins_and_extreme_direction_magnitudes() {
    let f = Fixture::speckled(6, 30, cube(8));
    let mut rng = Rng::new(6);
    let mut hits = 0;
    for _ in 0..2000 {
        let target = point_in(&mut rng, Vec3::splat(-8.0), Vec3::splat(8.0));
        let o = random_dir(&mut rng).normalize() * 1e6;
        hits += usize::from(f.check(&ray(o, target - o)).is_some());
        let d = special_dir(&mut rng) + random_dir(&mut rng) * 0.25;
        let o = point_in(&mut rng, Vec3::splat(-10.0), Vec3::splat(10.0));
        for scale in [1e-38f32, 1e-30, 1e-6, 1e6, 1e30, 3e38] {
            if (d * scale).is_finite() && (d * scale).abs().max_element() > 0.0 {
                f.check(&ray(o, d * scale));
            }
        }
        // Subnormal components beside a normal one.
        let mut sub = d;
        sub[rng.below(3) as usize] = f32::from_bits(1 + rng.below(1000));
        f.check(&ray(o, sub));
    }
    assert!(
        hits > 500,
        "far rays aimed at the volume must hit it ({hits})"
    );
}

#[test]
fn stability_non_finite_rays_are_errors_and_huge_origins_miss() {
    for (o, d) in [
        (Vec3::new(f32::NAN, 0.0, 0.0), Vec3::X),
        (Vec3::new(0.0, f32::INFINITY, 0.0), Vec3::X),
        (Vec3::ZERO, Vec3::new(f32::NAN, 1.0, 0.0)),
        (Vec3::ZERO, Vec3::new(0.0, f32::NEG_INFINITY, 0.0)),
        (Vec3::ZERO, Vec3::ZERO),
        (Vec3::ZERO, Vec3::new(-0.0, 0.0, -0.0)),
    ] {
        assert_eq!(Ray::new(o, d), Err(Error::InvalidRay), "{o} {d}");
    }
    let f = Fixture::speckled(7, 30, cube(4));
    for o in [
        Vec3::splat(f32::MAX),
        Vec3::new(-f32::MAX, 0.0, 0.0),
        Vec3::new(3e38, 1.0, -3e38),
    ] {
        for d in [-o, Vec3::X, Vec3::new(-1.0, 1e-20, 0.0)] {
            if let Ok(r) = Ray::new(o, d) {
                // Whatever the answer, it agrees everywhere and is quick.
                f.check(&r);
            }
        }
    }
}

#[test]
fn stability_large_octree_4096_cubed_matches_reference() {
    // [-2048, 2048)^3: a 4096^3 volume, far beyond any dense array here. A
    // walk crosses up to 12288 planes, where accumulated f32 distances drift.
    let bounds = cube(2048);
    let mut rng = Rng::new(8);
    let list: Vec<(IVec3, u8)> = (0..300)
        .map(|i| {
            let p = IVec3::new(
                rng.int(-2048, 2048),
                rng.int(-2048, 2048),
                rng.int(-2048, 2048),
            );
            (p, 1 + (i % 4) as u8)
        })
        .collect();
    let f = Fixture::list(list.clone(), bounds);
    let mut hits = 0;
    for i in 0..1500 {
        let (target, _) = list[i % list.len()];
        let aim = target.as_vec3() + Vec3::new(rng.unit(), rng.unit(), rng.unit());
        let o = match i % 3 {
            0 => Vec3::new(
                -2048.0,
                rng.range(-2048.0, 2048.0),
                rng.range(-2048.0, 2048.0),
            ), // on the boundary
            1 => random_dir(&mut rng).normalize() * 5000.0, // outside
            _ => point_in(&mut rng, Vec3::splat(-2048.0), Vec3::splat(2048.0)), // inside
        };
        hits += usize::from(f.check(&ray(o, aim - o)).is_some());
    }
    assert!(
        hits > 1000,
        "rays aimed at voxels should mostly hit them ({hits})"
    );
}

#[test]
fn stability_rays_leave_through_every_face_without_wrapping() {
    // Everything solid except one tunnel along each axis at the far edges of
    // the flat array: a ray down the tunnel leaves the volume and must miss
    // (an index that wraps into the next row or slice would hit).
    let bounds = IAabb::new(IVec3::ZERO, IVec3::new(8, 7, 6));
    let size = bounds.size();
    for axis in 0..3 {
        for positive in [true, false] {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            let mut lane = IVec3::ZERO;
            lane[u] = size[u] - 1;
            lane[v] = if positive { size[v] - 1 } else { 0 };
            let in_tunnel = |p: IVec3| p[u] == lane[u] && p[v] == lane[v];
            let list: Vec<_> = bounds
                .iter()
                .filter(|p| !in_tunnel(*p))
                .map(|p| (p, 1))
                .collect();
            let f = Fixture::list(list, bounds);
            let mut o = lane.as_vec3() + 0.5;
            o[axis] = if positive {
                0.5
            } else {
                size[axis] as f32 - 0.5
            };
            let mut d = Vec3::ZERO;
            d[axis] = if positive { 1.0 } else { -1.0 };
            assert_eq!(
                f.check(&ray(o, d)),
                None,
                "axis {axis}, positive {positive}"
            );
            // From outside, through the tunnel's mouth.
            o[axis] = if positive {
                -3.0
            } else {
                size[axis] as f32 + 3.0
            };
            assert_eq!(
                f.check(&ray(o, d)),
                None,
                "axis {axis}, positive {positive}, from outside"
            );
        }
    }
}

#[test]
fn stability_camera_inside_the_volume_never_hits_behind() {
    // A wall of voxels behind the camera, nothing in front.
    let bounds = cube(10);
    let wall: Vec<_> = IAabb::new(IVec3::new(-10, -10, -10), IVec3::new(10, 10, -2))
        .iter()
        .map(|p| (p, 1))
        .collect();
    let f = Fixture::list(wall, bounds);
    for lookfrom in [
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(0.0, 0.0, -2.0),
        Vec3::new(0.5, 0.5, -1.5),
    ] {
        let camera = Camera::new(CameraSettings {
            width: 24,
            height: 16,
            vertical_fov: 120.0,
            lookfrom,
            lookat: lookfrom + Vec3::Z,
            ..CameraSettings::default()
        })
        .unwrap();
        for j in 0..16 {
            for i in 0..24 {
                assert_eq!(f.check(&camera.get_ray(i, j)), None, "from {lookfrom}");
            }
        }
    }
}

#[test]
fn stability_degenerate_cameras_and_extreme_fields_of_view() {
    let base = CameraSettings {
        width: 32,
        height: 18,
        lookfrom: Vec3::new(7.5, 9.0, 11.0),
        ..CameraSettings::default()
    };
    for bad in [
        CameraSettings {
            lookat: base.lookfrom,
            ..base
        },
        CameraSettings {
            cam_up: base.lookat - base.lookfrom,
            up_fallback: false,
            ..base
        },
        CameraSettings {
            vertical_fov: 0.0,
            ..base
        },
        CameraSettings {
            vertical_fov: 180.0,
            ..base
        },
        CameraSettings {
            vertical_fov: -10.0,
            ..base
        },
        CameraSettings { width: 0, ..base },
    ] {
        assert!(
            matches!(Camera::new(bad), Err(Error::InvalidCamera { .. })),
            "{bad:?}"
        );
    }
    let f = Fixture::speckled(9, 20, cube(8));
    for fov in [0.01, 179.9] {
        for lookfrom in [
            base.lookfrom,
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1e6, 0.5, -2.0),
        ] {
            let camera = Camera::new(CameraSettings {
                vertical_fov: fov,
                lookfrom,
                lookat: Vec3::new(0.3, -0.2, 0.1),
                ..base
            })
            .unwrap();
            for j in 0..18 {
                for i in 0..32 {
                    f.check(&camera.get_ray(i, j));
                }
            }
        }
    }
}

/// The pixel a hit or miss must produce, rebuilt from the trace alone.
fn expected_pixel(hit: Option<&Hit>, ray: &Ray) -> u32 {
    voxtrace::pack(voxtrace::shade(hit, ray, &RenderOptions::default()))
}

#[test]
fn stability_no_nan_reaches_a_pixel() {
    let f = Fixture::speckled(10, 30, cube(8));
    let scenes: [&(dyn Scene + Sync); 2] = [&f.octree, f.dense.as_ref().unwrap()];
    let cameras = [
        (Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), 179.9), // inside, on corners
        (Vec3::new(8.0, 8.0, 8.0), Vec3::ZERO, 0.01),                // on the volume's corner
        (Vec3::new(1e6, 1e6, 1e6), Vec3::ZERO, 0.01),                // far away
        (Vec3::new(0.5, 40.0, 0.5), Vec3::new(0.5, 0.0, 0.51), 90.0), // nearly straight down
        (Vec3::new(-3e4, 2.0, 0.0), Vec3::new(3e4, 2.0, 1e-3), 1.0), // grazing along a plane
    ];
    for (lookfrom, lookat, fov) in cameras {
        let camera = Camera::new(CameraSettings {
            width: 40,
            height: 30,
            vertical_fov: fov,
            lookfrom,
            lookat,
            ..CameraSettings::default()
        })
        .unwrap();
        for scene in scenes {
            let mut pixels = vec![0; 40 * 30];
            render(
                &scene,
                &camera,
                &RenderOptions::default(),
                Rect::full(&camera),
                Target::Buffer(&mut pixels),
                None,
            )
            .unwrap();
            for (k, &p) in pixels.iter().enumerate() {
                let r = camera.get_ray(k as u32 % 40, k as u32 / 40);
                assert!(r.dir().is_finite() && (r.dir().length() - 1.0).abs() < 1e-5);
                let hit = scene.trace(&r);
                if let Some(h) = &hit {
                    assert!(h.t.is_finite() && h.t >= 0.0);
                }
                assert_eq!(
                    p,
                    expected_pixel(hit.as_ref(), &r),
                    "pixel {k} from {lookfrom}"
                );
                assert_eq!(voxtrace::unpack(p)[3], 255);
            }
        }
    }
    // The sky and shading guard their inputs: a NaN never turns into a color
    // other than the clamped one.
    assert_eq!(
        voxtrace::sky(Vec3::NAN),
        voxtrace::sky(Vec3::new(0.0, 0.0, 1.0))
    );
    assert_eq!(
        voxtrace::sky(Vec3::new(0.0, f32::INFINITY, 0.0)),
        voxtrace::sky(Vec3::Y)
    );
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    /// Coordinates concentrated on the grid: integers, halves, or free.
    fn coord() -> impl Strategy<Value = f32> {
        prop_oneof![
            (-9i32..=9).prop_map(|i| i as f32),
            (-18i32..=18).prop_map(|i| i as f32 * 0.5),
            -9.0f32..9.0,
        ]
    }

    /// Direction components: zeros of both signs, small integers, or free.
    fn component() -> impl Strategy<Value = f32> {
        prop_oneof![
            Just(0.0f32),
            Just(-0.0f32),
            (-3i32..=3).prop_map(|i| i as f32),
            -1.0f32..1.0,
        ]
    }

    fn fixture() -> &'static Fixture {
        static F: std::sync::OnceLock<Fixture> = std::sync::OnceLock::new();
        F.get_or_init(|| {
            Fixture::speckled(
                11,
                30,
                IAabb::new(IVec3::new(-7, -5, -6), IVec3::new(6, 7, 5)),
            )
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]

        #[test]
        fn stability_proptest_backends_match_reference(
            o in (coord(), coord(), coord()),
            d in (component(), component(), component()),
        ) {
            let d = Vec3::new(d.0, d.1, d.2);
            prop_assume!(d.abs().max_element() > 0.0);
            fixture().check(&ray(Vec3::new(o.0, o.1, o.2), d));
        }
    }
}

#[test]
fn stability_far_origin_where_every_crossing_rounds_to_one_t() {
    // Found by the fuzz target: from z = 8.1e34 every z plane of the volume
    // is crossed at the same f32 time. The planes must still be visited in
    // order, so the first solid cell along -z is the hit.
    let f = Fixture::speckled(
        5,
        30,
        IAabb::new(IVec3::new(-9, -6, -7), IVec3::new(8, 9, 6)),
    );
    let r = ray((-0.0, 0.0, 8.112_963_3e34), (7.1e-42, 0.0, -0.5));
    let hit = f
        .check(&r)
        .expect("the column below the origin has solid voxels");
    assert_eq!(hit.face, Some(Face::PosZ));
    let z_column = (-7..6).rev().map(|z| IVec3::new(0, 0, z));
    let first = z_column
        .into_iter()
        .find(|&p| f.solids.iter().any(|s| s.0 == p))
        .unwrap();
    assert_eq!(hit.pos, first);
}

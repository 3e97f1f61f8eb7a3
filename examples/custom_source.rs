//! Your own voxels: implement [`voxtrace::VoxelSource`] for a type of your
//! own (here a sphere resting on a checkerboard floor), build an
//! [`voxtrace::OctreeScene`] from it, render the frame on all cores with
//! [`voxtrace::render`] into a [`voxtrace::Framebuffer`], and write
//! it as a PNG.
//!
//! ```sh
//! cargo run --example custom_source                 # writes custom_source.png
//! cargo run --example custom_source -- out/ball.png
//! ```
//!
//! A source only has to say which material is at a position (`material`)
//! and what the materials look like (`palette`). It may also answer
//! `classify` for whole boxes: a box it knows to be empty (or all one
//! material) is stored as one octree node without visiting its voxels.
//! (`fill_box`, which fills a box voxel by voxel, has a default too.)

use std::path::PathBuf;

use voxtrace::glam::{IVec3, U8Vec3, Vec3};
use voxtrace::{
    render, write_png, Camera, CameraSettings, Framebuffer, IAabb, OctreeScene, Palette, Rect,
    Region, RenderOptions, Target, VoxelSource,
};

/// Materials of the scene's palette (0 is always empty).
const BALL: u8 = 1;
const LIGHT_TILE: u8 = 2;
const DARK_TILE: u8 = 3;

/// A solid ball of voxels above a one-voxel-thick checkerboard floor.
struct BallOnFloor {
    palette: Palette,
    center: IVec3,
    radius: i32,
    floor_y: i32,
    tile: i32,
}

impl BallOnFloor {
    fn new() -> Self {
        BallOnFloor {
            palette: Palette::new(&[
                U8Vec3::new(200, 60, 40),   // BALL
                U8Vec3::new(230, 230, 220), // LIGHT_TILE
                U8Vec3::new(60, 70, 90),    // DARK_TILE
            ]),
            center: IVec3::new(0, -1, 0),
            radius: 8,
            floor_y: -10,
            tile: 4,
        }
    }

    /// Squared distance from the ball's center to the center of voxel `pos`,
    /// in half-voxel units (exact integers: no rounding at the surface).
    fn dist2(&self, pos: IVec3) -> i64 {
        let (p, c) = (pos.to_array(), self.center.to_array());
        (0..3)
            .map(|i| (2 * i64::from(p[i]) + 1 - 2 * i64::from(c[i])).pow(2))
            .sum()
    }

    fn in_ball(&self, pos: IVec3) -> bool {
        self.dist2(pos) <= i64::from(2 * self.radius).pow(2)
    }
}

impl VoxelSource for BallOnFloor {
    fn palette(&self) -> &Palette {
        &self.palette
    }

    fn material(&self, pos: IVec3) -> u8 {
        if pos.y == self.floor_y {
            let checker = pos.x.div_euclid(self.tile) + pos.z.div_euclid(self.tile);
            if checker.rem_euclid(2) == 0 {
                LIGHT_TILE
            } else {
                DARK_TILE
            }
        } else if self.in_ball(pos) {
            BALL
        } else {
            0
        }
    }

    /// Exact answers for boxes away from the floor: empty when even the
    /// box's voxel nearest the ball's center is outside the ball, solid when
    /// even the farthest one is inside. Anything else is `Mixed`, which is
    /// always allowed.
    fn classify(&self, region: IAabb) -> Region {
        if region.is_empty() {
            return Region::Empty;
        }
        if (region.min.y..region.max.y).contains(&self.floor_y) {
            return Region::Mixed;
        }
        let (first, last) = (region.min, region.max - IVec3::ONE);
        let nearest = self.center.clamp(first, last);
        if !self.in_ball(nearest) {
            return Region::Empty;
        }
        // The ball is convex: if all eight corners are inside, so is the box.
        let corners = (0..8).map(|i| {
            IVec3::new(
                if i & 1 == 0 { first.x } else { last.x },
                if i & 2 == 0 { first.y } else { last.y },
                if i & 4 == 0 { first.z } else { last.z },
            )
        });
        if corners.into_iter().all(|c| self.in_ball(c)) {
            Region::Solid(BALL)
        } else {
            Region::Mixed
        }
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from("custom_source.png"), PathBuf::from);

    // The volume is [-16, 16)^3; the source is asked about nothing outside it.
    let source = BallOnFloor::new();
    let scene = OctreeScene::build(&source, IAabb::centered(16))?;
    let len = scene.len();
    println!(
        "octree: {} nodes, {} material bytes",
        len.nodes, len.materials
    );

    let camera = Camera::new(CameraSettings {
        width: 32,
        height: 32,
        lookfrom: Vec3::new(26.0, 14.0, 30.0),
        lookat: Vec3::new(0.0, -4.0, 0.0),
        ..CameraSettings::default()
    })?;
    let options = RenderOptions {
        shadows: true,
        ..RenderOptions::default()
    };
    let frame = Framebuffer::new(camera.width(), camera.height())?;
    let stats = render(
        &scene,
        &camera,
        &options,
        Rect::full(&camera),
        Target::Framebuffer(&frame),
        None,
    )?;
    println!(
        "{} primary rays, {} shadow rays",
        stats.primary_rays, stats.shadow_rays
    );

    write_png(&out, frame.width(), frame.height(), &frame.to_vec())?;
    println!("wrote {}", out.display());
    Ok(())
}

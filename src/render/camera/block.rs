//! A camera's rays for an 8x4 block of pixels, four at a time: the
//! packets the tiles trace ([`crate::Scene::trace_packet`]).

use glam::{Vec2, Vec3A, Vec4};

use crate::geom::Ray;
use crate::math::per_axis;
use crate::render::camera::{block_pixel, Camera};

impl Camera {
    /// The rays through the centers of the 8x4 pixels from `(i, j)`: lane
    /// `k` is pixel `(i + k % 8, j + k / 8)`'s, bit for bit the ray
    /// [`Camera::get_ray`] gives it. `N` is the block's [`crate::PACKET`] lanes
    /// (a multiple of four), given as the caller's array type so that the
    /// rays are made where the caller keeps them.
    #[must_use]
    pub(crate) fn block_rays<const N: usize>(&self, i: u32, j: u32) -> [Ray; N] {
        self.rays_through(
            |k| {
                let (x, y) = block_pixel((i, j), k);
                (x as f32, y as f32)
            },
            |k| {
                let (x, y) = block_pixel((i, j), k);
                self.get_ray(x, y)
            },
        )
    }

    /// The rays of one sample of each of the 8x4 pixels from `corner`:
    /// lane `k`'s through the point `offset(k)` of its pixel
    /// ([`block_pixel`]), bit for bit the ray [`Camera::get_ray_at`] gives
    /// it. `N` as for [`Camera::block_rays`].
    #[must_use]
    pub(crate) fn block_sample_rays<const N: usize>(
        &self,
        corner: (u32, u32),
        offset: impl Fn(usize) -> Vec2,
    ) -> [Ray; N] {
        // `get_ray_at`'s continuous coordinates, and their point's offset
        // from pixel (0, 0)'s center, in its order.
        let at = |k| {
            let (x, y) = block_pixel(corner, k);
            let offset = offset(k);
            (x as f32 + offset.x, y as f32 + offset.y)
        };
        self.rays_through(
            |k| {
                let (x, y) = at(k);
                (x - 0.5, y - 0.5)
            },
            |k| {
                let (x, y) = at(k);
                self.get_ray_at(x, y)
            },
        )
    }

    /// The rays from the camera through the image-plane points
    /// `pixel00 + delta_u * x + delta_v * y` of `(x, y) = point(k)`, lane
    /// by lane; `lone(k)`, the same ray computed alone, where the camera
    /// is orthographic or a lane's direction is unusable. Four rays are
    /// computed at once, with [`Ray::new`]'s operations in its order, so
    /// the divisions and square roots that bound a lone ray's time
    /// overlap.
    #[inline]
    fn rays_through<const N: usize>(
        &self,
        point: impl Fn(usize) -> (f32, f32),
        lone: impl Fn(usize) -> Ray,
    ) -> [Ray; N] {
        let mut rays = [self.forward; N];
        for quad in 0..N / 4 {
            let lanes = &mut rays[quad * 4..][..4];
            if self.orthographic {
                for (lane, ray) in lanes.iter_mut().enumerate() {
                    *ray = lone(quad * 4 + lane);
                }
                continue;
            }
            let points: [(f32, f32); 4] = core::array::from_fn(|lane| point(quad * 4 + lane));
            let x = Vec4::from_array(points.map(|p| p.0));
            let y = Vec4::from_array(points.map(|p| p.1));
            // Per axis: the image-plane point minus the camera's position.
            let to_pixel = per_axis(|axis| {
                let corner = Vec4::splat(self.pixel00[axis]);
                let (du, dv) = (self.delta_u[axis], self.delta_v[axis]);
                corner + Vec4::splat(du) * x + Vec4::splat(dv) * y - Vec4::splat(self.center[axis])
            });
            // `Ray::new`: scaled by the largest component, then by the
            // length (squares summed x, y, z), and the reciprocal.
            let [dx, dy, dz] = to_pixel;
            let largest = dx.abs().max(dy.abs()).max(dz.abs());
            let scaled = per_axis(|axis| to_pixel[axis] / largest);
            let [sx, sy, sz] = scaled;
            let length = (sx * sx + sy * sy + sz * sz).sqrt();
            let dir = per_axis(|axis| scaled[axis] / length);
            let inv = per_axis(|axis| Vec4::ONE / dir[axis]);
            let usable = largest.cmpgt(Vec4::ZERO) & dx.is_finite_mask() & dy.is_finite_mask();
            let usable = (usable & dz.is_finite_mask()).bitmask();
            for (lane, ray) in lanes.iter_mut().enumerate() {
                *ray = if usable >> lane & 1 != 0 {
                    let of = |v: [Vec4; 3]| Vec3A::new(v[0][lane], v[1][lane], v[2][lane]);
                    Ray::from_parts(self.center, of(dir), of(inv))
                } else {
                    // The lone ray's own fallback.
                    lone(quad * 4 + lane)
                };
            }
        }
        rays
    }
}

#[cfg(test)]
mod tests {
    use glam::{Vec2, Vec3};
    use proptest::prelude::*;

    use crate::geom::Ray;
    use crate::render::camera::{block_pixel, Camera, CameraSettings};
    use crate::render::view::Projection;
    use crate::scene::PACKET;

    proptest! {
        /// Every lane of a block is the lone ray of its pixel, bit for bit,
        /// through its center or any point of it, for cameras anywhere, of
        /// any field of view and projection, at any block of the frame (the
        /// centers of the last pixels of the largest frame too).
        #[test]
        fn a_blocks_rays_are_the_lone_rays(
            from in prop::array::uniform3(-3000.0f32..3000.0),
            at in prop::array::uniform3(-50.0f32..50.0),
            fov in 1.0f32..170.0,
            size in (1u32..5000, 1u32..5000),
            block in (any::<u32>(), any::<u32>()),
            offsets in prop::array::uniform32((0.0f32..1.0, 0.0f32..1.0)),
            ortho in prop::option::of(0.5f32..500.0),
        ) {
            let settings = CameraSettings {
                width: size.0,
                height: size.1,
                vertical_fov: fov,
                lookfrom: Vec3::from(from),
                lookat: Vec3::from(at),
                projection: ortho.map_or(Projection::Perspective, |height| {
                    Projection::Orthographic { height }
                }),
                ..CameraSettings::default()
            };
            let Ok(camera) = Camera::new(settings) else {
                return Ok(());
            };
            let bits = |r: &Ray| {
                let (o, d, inv) = r.vectors();
                [o, d, inv].map(|v| v.to_array().map(f32::to_bits))
            };
            let corner = (block.0 % (size.0 + 8), block.1 % (size.1 + 8));
            let last = (u32::MAX - 2, u32::MAX - 1);
            let centers = if block.0 % 7 == 0 { last } else { corner };
            let offset = |k: usize| Vec2::new(offsets[k].0, offsets[k].1);
            let rays = camera.block_rays::<PACKET>(centers.0, centers.1);
            let samples = camera.block_sample_rays::<PACKET>(corner, offset);
            for (k, (ray, sample)) in rays.iter().zip(&samples).enumerate() {
                let (x, y) = block_pixel(centers, k);
                prop_assert_eq!(bits(ray), bits(&camera.get_ray(x, y)), "pixel ({}, {})", x, y);
                let (x, y) = block_pixel(corner, k);
                let lone = camera.get_ray_at(x as f32 + offset(k).x, y as f32 + offset(k).y);
                prop_assert_eq!(bits(sample), bits(&lone), "a point of pixel ({}, {})", x, y);
            }
        }
    }
}

//! Framing: a camera that shows a set of boxes (a model's voxels, a
//! scene's bounds) whole, centered, filling a given share of the frame.
//!
//! The fit is exact for the boxes given, not for a box around them: each
//! edge of the image is a plane through the camera (perspective) or along
//! the view (orthographic), and a plane is pushed out until every box lies
//! on its inner side; the maximum of a linear function over a box is at a
//! corner, so each box costs a few dot products.

use glam::{BVec4A, Vec3, Vec4};

use crate::error::Error;
use crate::math::tan32;
use crate::render::camera::CameraSettings;
use crate::render::view::{basis, unit, Projection};

/// Accumulates what a camera looking along one direction needs to know of
/// the boxes it must show ([`Framer::add_box`]), then places it
/// ([`Framer::settings`]).
#[derive(Clone, Copy, Debug)]
pub struct Framer {
    base: CameraSettings,
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    /// Tangents of the half angles, shrunk by the fill factor.
    tan_h: f32,
    tan_v: f32,
    aspect: f32,
    fill: f32,
    /// The functionals whose maxima the fit needs, as world vectors:
    /// the four perspective side planes (right, left, top, bottom), then
    /// `+-right`, `+-up`, `-+forward`; in lanes, twelve of them (the last
    /// two repeat the first two).
    functionals: Functionals,
    /// Their maxima over the boxes, lane by lane.
    max: [Vec4; 3],
}

/// Twelve vectors, lane by lane: the x, y and z components of four at a
/// time, and the lanes whose component is not negative (where a linear
/// function is largest over a box: its corner that is largest along those
/// axes).
#[derive(Clone, Copy, Debug)]
struct Functionals {
    components: [[Vec4; 3]; 3],
    rising: [[BVec4A; 3]; 3],
}

impl Functionals {
    fn of(vectors: [Vec3; 10]) -> Functionals {
        let lane = |i: usize| vectors[if i < 10 { i } else { i - 10 }];
        let component = |axis: usize| {
            [0, 1, 2].map(|quad| Vec4::from_array([0, 1, 2, 3].map(|k| lane(4 * quad + k)[axis])))
        };
        let components = [component(0), component(1), component(2)];
        let rising = components.map(|quads| quads.map(|c| c.cmpge(Vec4::ZERO)));
        Functionals { components, rising }
    }
}

impl Framer {
    /// A framer for `base`'s image size, field of view, up vector and
    /// projection, looking from the target toward `-toward_camera`
    /// (`toward_camera` points from the scene to the camera, need not be
    /// unit), the boxes filling `fill` (in `(0, 1]`) of the frame's
    /// tighter side.
    ///
    /// Fails with [`Error::InvalidCamera`] for a zero direction, a bad
    /// field of view or image size, an up vector parallel to the view
    /// without the fallback, or a fill outside `(0, 1]`.
    pub fn new(base: CameraSettings, toward_camera: Vec3, fill: f32) -> Result<Framer, Error> {
        let invalid = |reason| Error::InvalidCamera { reason };
        if base.width == 0 || base.height == 0 {
            return Err(invalid("width and height must be at least 1"));
        }
        if !(base.vertical_fov > 0.0 && base.vertical_fov < 180.0) {
            return Err(invalid(
                "vertical field of view must be in (0, 180) degrees",
            ));
        }
        if !(fill > 0.0 && fill <= 1.0) {
            return Err(invalid("the framing's fill must be in (0, 1]"));
        }
        if !toward_camera.is_finite() {
            return Err(invalid("view direction must be finite"));
        }
        if !base.cam_up.is_finite() {
            return Err(invalid("up vector must be finite"));
        }
        let forward = -unit(toward_camera).ok_or(invalid("the view direction is zero"))?;
        let (right, up) = basis(forward, base.cam_up, base.up_fallback)?;
        let aspect = base.width as f32 / base.height as f32;
        let tan_v = tan32(base.vertical_fov.to_radians() / 2.0) * fill;
        let tan_h = tan_v * aspect;
        Ok(Framer {
            base,
            right,
            up,
            forward,
            tan_h,
            tan_v,
            aspect,
            fill,
            functionals: Functionals::of(functionals(right, up, forward, tan_h, tan_v)),
            max: [Vec4::NEG_INFINITY; 3],
        })
    }

    /// Adds the box `[min, max]` (a voxel is `[p, p + 1]`): per
    /// functional, the dot product with the box's corner that is largest
    /// along its rising axes, in `Vec3::dot`'s order, four at a time.
    #[inline]
    pub fn add_box(&mut self, min: Vec3, max: Vec3) {
        let Functionals {
            components: [x, y, z],
            rising,
        } = &self.functionals;
        let corner = |axis: usize, quad: usize| {
            Vec4::select(
                rising[axis][quad],
                Vec4::splat(max[axis]),
                Vec4::splat(min[axis]),
            )
        };
        for (quad, m) in self.max.iter_mut().enumerate() {
            let dot =
                corner(0, quad) * x[quad] + corner(1, quad) * y[quad] + corner(2, quad) * z[quad];
            // (Not `Vec4::max`, whose answer for NaN differs by target: a
            // NaN corner leaves the maximum as it was, and of equal
            // values, -0 and +0, the first stays, on every target.)
            *m = Vec4::select(dot.cmpgt(*m), dot, *m);
        }
    }

    /// The maxima over the boxes added, one per functional.
    fn maxima(&self) -> [f32; 10] {
        let lanes: [[f32; 4]; 3] = self.max.map(|quad| quad.to_array());
        let mut maxima = [0.0; 10];
        for (i, m) in maxima.iter_mut().enumerate() {
            *m = lanes[i / 4][i % 4];
        }
        maxima
    }

    /// Whether any box was added.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.maxima()[8] == f32::NEG_INFINITY
    }

    /// The fitted camera: `base` with the position and target (on the
    /// boxes' middle along the view) that center the boxes, and for an
    /// orthographic `base` the height that fits them. `None` before any box
    /// was added or when the boxes' extent is not finite.
    #[must_use]
    pub fn settings(&self) -> Option<CameraSettings> {
        let maxima = self.maxima();
        if self.is_empty() || !maxima.iter().all(|m| m.is_finite()) {
            return None;
        }
        let [r, l, t, b, a_max, a_min_neg, c_max, c_min_neg, b_min_neg, b_max] = maxima;
        let near = -b_min_neg; // the closest any box comes along the view
        let (a, c, depth, projection) = match self.base.projection {
            Projection::Perspective => {
                // The tight apex for each pair of side planes; the farther
                // back one holds all four.
                let depth_h = -(r + l) / (2.0 * self.tan_h);
                let depth_v = -(t + b) / (2.0 * self.tan_v);
                // Boxes inside all four side planes lie in front of the
                // apex already; the clearance only keeps rounding from
                // putting the camera on the nearest face. (A fixed half
                // voxel shrank small boxes seen through wide fields of view
                // to half the frame.)
                let clearance = 1e-3 * (b_max + b_min_neg).max(1.0);
                let depth = depth_h.min(depth_v).min(near - clearance);
                ((r - l) / 2.0, (t - b) / 2.0, depth, Projection::Perspective)
            }
            Projection::Orthographic { .. } => {
                let height = ((c_max + c_min_neg) / self.fill)
                    .max((a_max + a_min_neg) / self.aspect / self.fill)
                    .max(f32::MIN_POSITIVE);
                let projection = Projection::Orthographic { height };
                (
                    (a_max - a_min_neg) / 2.0,
                    (c_max - c_min_neg) / 2.0,
                    near - 1.0,
                    projection,
                )
            }
        };
        let lookfrom = self.right * a + self.up * c + self.forward * depth;
        // The target straight ahead, as deep as the middle of the boxes.
        let reach = ((near + b_max) / 2.0 - depth).max(1.0);
        let lookat = lookfrom + self.forward * reach;
        let settings = CameraSettings {
            lookfrom,
            lookat,
            projection,
            ..self.base
        };
        (lookfrom.is_finite() && lookat.is_finite()).then_some(settings)
    }

    /// The orthographic height that shows every box with the image's
    /// middle on the line through `point` along the view (for a camera
    /// placed by hand), with the fill factor's margin.
    #[must_use]
    pub fn ortho_height_around(&self, point: Vec3) -> Option<f32> {
        if self.is_empty() {
            return None;
        }
        let [_, _, _, _, a_max, a_min_neg, c_max, c_min_neg, _, _] = self.maxima();
        let (pa, pc) = (point.dot(self.right), point.dot(self.up));
        let half_a = (a_max - pa).max(pa + a_min_neg);
        let half_c = (c_max - pc).max(pc + c_min_neg);
        let height = 2.0 * half_c.max(half_a / self.aspect) / self.fill;
        (height.is_finite() && height > 0.0).then_some(height)
    }
}

/// The functionals whose maxima the fit needs ([`Framer`]'s order), for a
/// camera with basis `right`, `up`, `forward` and half-angle tangents
/// `tan_h`, `tan_v`.
fn functionals(right: Vec3, up: Vec3, forward: Vec3, tan_h: f32, tan_v: f32) -> [Vec3; 10] {
    let (r, u, f) = (right, up, forward);
    [
        r - f * tan_h,
        -r - f * tan_h,
        u - f * tan_v,
        -u - f * tan_v,
        r,
        -r,
        u,
        -u,
        -f,
        f,
    ]
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use proptest::prelude::*;

    use super::{functionals, Framer};
    use crate::render::camera::CameraSettings;

    fn vec3(range: core::ops::Range<f32>) -> impl Strategy<Value = Vec3> {
        prop::array::uniform3(range).prop_map(Vec3::from)
    }

    proptest! {
        /// The maxima kept four lanes at a time are, bit for bit, each
        /// functional's largest dot product with a box's largest corner
        /// along its rising axes (`Vec3::dot`, one functional at a time).
        #[test]
        fn maxima_are_the_scalar_dot_products(
            toward in vec3(-5.0..5.0),
            fov in 1.0f32..170.0,
            size in (1u32..4000, 1u32..4000),
            boxes in prop::collection::vec((vec3(-1e4..1e4), vec3(0.0..300.0)), 1..40),
        ) {
            let base = CameraSettings {
                width: size.0,
                height: size.1,
                vertical_fov: fov,
                ..CameraSettings::default()
            };
            let Ok(mut framer) = Framer::new(base, toward, 0.9) else {
                return Ok(());
            };
            let vectors = functionals(framer.right, framer.up, framer.forward, framer.tan_h, framer.tan_v);
            let mut expected = [f32::NEG_INFINITY; 10];
            for &(min, extent) in &boxes {
                let max = min + extent;
                framer.add_box(min, max);
                for (m, a) in expected.iter_mut().zip(vectors) {
                    let corner = Vec3::select(a.cmpge(Vec3::ZERO), max, min);
                    *m = m.max(corner.dot(a));
                }
            }
            prop_assert_eq!(framer.maxima().map(f32::to_bits), expected.map(f32::to_bits));
        }
    }
}
